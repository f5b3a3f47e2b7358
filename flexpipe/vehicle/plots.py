"""PNG plots of car runs (matplotlib, Agg backend, written atomically)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flexpipe._io import atomic_path

STYLE = {"rigid": dict(color="k", lw=1.2, ls="-"),
         "flexible": dict(color="tab:red", lw=1.0, ls="--"),
         "full": dict(color="tab:blue", lw=0.9, ls=":")}


def _figure(figsize=(9, 4.5)):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt, plt.figure(figsize=figsize)


def _save(plt, fig, path) -> Path:
    path = Path(path)
    with atomic_path(path, suffix=".png") as tmp:
        fig.savefig(tmp, dpi=120, format="png")
    plt.close(fig)
    return path


def hub_force(results: dict, path, *, corner: str = "fl", component: str = "z",
              title: str = "") -> Path:
    """Hub force of one corner for several runs on one plot (paper Fig. 7 / Fig. 9).

    With a ``rigid`` run and others, a lower panel shows each run minus the rigid one,
    so that the effect of body flexibility is visible even where the curves overlap.
    """
    name = f"hub_{corner}_{component}"
    others = [k for k in results if k != "rigid"]
    with_diff = "rigid" in results and bool(others)
    plt, fig = _figure((9, 6) if with_diff else (9, 4.5))
    if with_diff:
        ax, ax_d = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2.2, 1]})
    else:
        ax = fig.add_subplot(111)
    for label, r in results.items():
        ax.plot(r.t, r[name] / 1e3, label=f"{label} body", **STYLE.get(label, {}))
    label_y = (f"{'vertical' if component == 'z' else component} hub force "
               f"{corner.upper()} [kN]")
    ax.set_ylabel(label_y)
    ax.set_title(title or f"Force on the {corner.upper()} wheel hub", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend()
    last = ax
    if with_diff:
        rigid = results["rigid"]
        for label in others:
            r = results[label]
            # rigid minus the other, as summary.json's hub_force_difference states it
            diff = np.interp(r.t, rigid.t, rigid[name]) - r[name]
            ax_d.plot(r.t, diff / 1e3, label=f"rigid - {label}",
                      **{**STYLE.get(label, {}), "ls": "-"})
        ax_d.axhline(0.0, color="k", lw=0.6)
        ax_d.set_ylabel("difference [kN]")
        ax_d.grid(True, alpha=0.3)
        ax_d.legend(loc="upper right")
        last = ax_d
    last.set_xlabel("time [s]")
    fig.tight_layout()
    return _save(plt, fig, path)


#: trajectory styles: the rigid trace wide and grey underneath, the others narrow and
#: dashed / dotted on top, so that each stays visible where they coincide
TRAJECTORY_STYLE = {"rigid": dict(color="0.55", lw=2.6, ls="-", zorder=2),
                    "flexible": dict(color="tab:red", lw=1.2, ls="--", zorder=4),
                    "full": dict(color="tab:blue", lw=1.2, ls=":", zorder=5)}


def run_title(results: dict, path_obj=None) -> str:
    """Car (and its file), speed, road and path of the runs, from their ``info``."""
    info = getattr(next(iter(results.values())), "info", None) or {}
    parts = []
    car = info.get("car")
    if car:
        file = info.get("car_file")
        parts.append(f"{car} ({Path(file).name})" if file else str(car))
    if info.get("speed") is not None:
        parts.append(f"{float(info['speed']) * 3.6:.0f} km/h")
    road = info.get("road")
    parts.append(f"road {Path(str(road)).name}" if road else "flat road")
    if path_obj is not None:
        name = getattr(path_obj, "name", "") or Path(getattr(path_obj, "source", "") or "").name
        if name:
            parts.append(f"path {name}")
    return ", ".join(parts)


def trajectory(results: dict, path_obj, path, *, title: str = "") -> Path:
    """Desired path and the followed rear-axle trajectories (paper Fig. 8).

    The rigid trace is wide and grey, the flexible one dashed red on top (full: dotted
    blue), so that both stay visible where they coincide; the default title names the
    car, speed, road and path (:func:`run_title`).
    """
    plt, fig = _figure((10, 4.3))
    ax = fig.add_subplot(111)
    r0 = next(iter(results.values()))
    x_lo, x_hi = float(np.nanmin(r0["x_rear"])), float(np.nanmax(r0["x_rear"]))
    sel = (path_obj.x >= x_lo - 5) & (path_obj.x <= x_hi + 5)
    ax.plot(path_obj.x[sel], path_obj.y[sel], color="k", lw=0.9, zorder=3,
            label="desired path")
    for label, r in results.items():
        st = TRAJECTORY_STYLE.get(label, dict(lw=1.2, ls="-.", zorder=6))
        ax.plot(r["x_rear"], r["y_rear"], label=f"followed ({label} body)", **st)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    head = "Desired / followed vehicle trajectory (rear-axle centre)"
    ax.set_title(title or f"{head}\n{run_title(results, path_obj)}", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _save(plt, fig, path)
