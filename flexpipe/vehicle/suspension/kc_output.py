"""Files of the K&C rig: one CSV per analysis (units in the headers), ``kc_summary.json``
and PNG plots of the characteristics vs wheel travel; all written atomically."""

from __future__ import annotations

import io
import json
from pathlib import Path

import numpy as np

from flexpipe._io import atomic_path, write_text_atomic

#: quantities plotted against wheel travel, one panel each
PANELS = ("camber [deg]", "toe [deg]", "caster [deg]", "kpi [deg]", "scrub radius [mm]",
          "wheel rate [N/m]", "roll centre height [mm]", "bump steer [deg/m]")


def _csv(table) -> str:
    buf = io.StringIO()
    buf.write(",".join(table.columns) + "\n")
    np.savetxt(buf, table.data, delimiter=",", fmt="%.10g")
    return buf.getvalue()


def _figure():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def _save(plt, fig, path):
    with atomic_path(path, suffix=".png") as tmp:
        fig.savefig(tmp, dpi=110, format="png")
    plt.close(fig)


#: panels that belong to a steering axis: left empty for an axle without a rack (the
#: values of a non-steered axle come from a nominal knuckle axis)
STEER_AXIS_PANELS = ("caster [deg]", "kpi [deg]", "scrub radius [mm]")


def _car_text(res, car: str) -> str:
    car = car or getattr(res, "car", "") or ""
    return f"{car}: " if car else ""


def _steered(res, name) -> bool:
    return f"{name}_static_steer" in res.tables


def plot_travel(res, path: Path, *, car: str = "") -> None:
    """Characteristics vs wheel travel, one line per axle (parallel; roll centre also
    for opposite travel).  Caster, KPI and scrub radius are drawn only for steered axles
    (with a rack); the suptitle names ``car`` when given."""
    plt = _figure()
    fig, axs = plt.subplots(2, 4, figsize=(15, 7), constrained_layout=True)
    unsteered = []
    for name in res.summary:
        par = res.tables[f"{name}_parallel_travel"]
        s = par["wheel travel [mm]"]
        steered = _steered(res, name)
        if not steered:
            unsteered.append(name)
        for ax, q in zip(axs.flat, PANELS, strict=True):
            if q in STEER_AXIS_PANELS and not steered:
                ax.plot([], [])  # keep the axle's colour in every panel
                continue
            ax.plot(par[q], s, label=f"{name}")
            if q == "roll centre height [mm]":
                opp = res.tables[f"{name}_opposite_travel"]
                ax.plot(opp[q], opp["wheel travel [mm]"], ls="--", label=f"{name}, opposite")
    for ax, q in zip(axs.flat, PANELS, strict=True):
        note = (f"\n({', '.join(unsteered)}: not steered, not shown)"
                if q in STEER_AXIS_PANELS and unsteered else "")
        ax.set_xlabel(q + note)
        ax.set_ylabel("wheel travel [mm]")
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
    fig.suptitle(f"{_car_text(res, car)}parallel wheel travel (left corner; Adams/Car sign "
                 "conventions)")
    _save(plt, fig, path)


def plot_steer_and_compliance(res, path: Path, *, car: str = "") -> None:
    """Static steer and force-compliance curves, each panel titled; the suptitle names
    ``car`` when given."""
    plt = _figure()
    fig, axs = plt.subplots(1, 3, figsize=(15, 4.8), constrained_layout=True)
    steered = []
    for name in res.summary:
        st = res.tables.get(f"{name}_static_steer")
        if st is not None:
            steered.append(name)
            axs[0].plot(st["steering wheel angle [deg]"], st["steer left [deg]"],
                        label=f"{name} left")
            axs[0].plot(st["steering wheel angle [deg]"], st["steer right [deg]"], ls="--",
                        label=f"{name} right")
        for ax, kind in ((axs[1], "longitudinal"), (axs[2], "lateral")):
            t = res.tables[f"{name}_{kind}_force"]
            ax.plot(t["force [N]"] / 1e3, t["toe [deg]"], label=f"{name} toe")
            ax.plot(t["force [N]"] / 1e3, t["camber [deg]"], ls="--", label=f"{name} camber")
    axs[0].set_title("static steer: road wheel vs steering wheel angle"
                     + (f" ({', '.join(steered)})" if steered else " (no steered axle)"),
                     fontsize=10)
    axs[1].set_title("longitudinal force compliance: toe and camber", fontsize=10)
    axs[2].set_title("lateral force compliance: toe and camber", fontsize=10)
    axs[0].set_xlabel("steering wheel angle [deg]")
    axs[0].set_ylabel("road wheel angle [deg]")
    axs[1].set_xlabel("longitudinal force at the contact patch [kN]")
    axs[2].set_xlabel("lateral force at the contact patch [kN]")
    for ax in axs[1:]:
        ax.set_ylabel("angle [deg]")
    for ax in axs:
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8)
    fig.suptitle(f"{_car_text(res, car)}static steer and force compliance (left corner; "
                 "Adams/Car sign conventions)")
    _save(plt, fig, path)


def write(res, out: Path, *, car: str = "") -> list[Path]:
    """Write every table as CSV, the summary as JSON and the plots; returns the paths.

    ``car``: name shown in the plot titles (default ``res.car`` if set)."""
    out.mkdir(parents=True, exist_ok=True)
    paths = []
    for name, table in res.tables.items():
        p = out / f"{name}.csv"
        write_text_atomic(p, _csv(table))
        paths.append(p)
    p = out / "kc_summary.json"
    write_text_atomic(p, json.dumps(res.summary, indent=2) + "\n")
    paths.append(p)
    plot_travel(res, out / "kc_wheel_travel.png", car=car)
    plot_steer_and_compliance(res, out / "kc_steer_compliance.png", car=car)
    return paths + [out / "kc_wheel_travel.png", out / "kc_steer_compliance.png"]
