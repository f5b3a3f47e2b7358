"""Files of a ride analysis (:func:`flexpipe.vehicle.linear_ride.ride_response`):
``ride.csv`` (one row per output: RMS and ISO 2631-1 weighted RMS, units in the
headers), ``ride.json`` (the same with the comfort values per body point, the tyres'
dynamic load coefficients and the road), ``ride_psd.csv`` (every output's PSD) and
``ride_psd.png``; each written to a temporary name and renamed into place."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from flexpipe._io import write_text_atomic
from flexpipe.vehicle.linear import output_unit

#: what the ride figures are (the JSON's and the printout's notes)
NOTES = (
    "the linear model's response: controls fixed, dual-rate dampers at their mean slope",
    "RMS about the linearization state over the road's ISO 8608 band",
    "ISO 2631-1 weighting: Wk vertical, Wd fore-aft and lateral; a_v with factors 1 "
    "(comfort)",
)


def ride_text(ride) -> str:
    """The ride figures as text: road, tyres, body points."""
    lines = [f"ISO 8608 class {ride.road_class} at {ride.speed * 3.6:g} km/h: road RMS "
             f"{ride.info['road_rms_m'] * 1e3:.2f} mm over "
             f"{ride.info['n_band_cycles/m'][0]:g}-{ride.info['n_band_cycles/m'][1]:g} "
             f"cycles/m, tracks {ride.track_width:.3f} m apart, coherence "
             f"{ride.info['coherence_model']}"]
    for j, name in enumerate(ride.outputs):
        if name.endswith("_Fz"):
            corner = name[5:-3]
            load = ride.dynamic_load.get(corner)
            lines.append(f"  {name:24s} RMS {ride.rms[j]:8.1f} N"
                         + (f"   dynamic load coefficient {load:.3f}" if load else ""))
    travel = [(name, ride.rms[j]) for j, name in enumerate(ride.outputs)
              if name.startswith("travel_")]
    if travel:
        lines.append("  suspension travel RMS  " + "  ".join(
            f"{name[7:]} {v * 1e3:.1f} mm" for name, v in travel))
    hubs = sorted({name[4:6] for name in ride.outputs if name.startswith("hub_")},
                  key="fl fr rl rr".split().index)
    for c in hubs:
        j = [ride.outputs.index(f"hub_{c}_{ax}") for ax in "xyz"]
        text = "  ".join(f"{ax} {ride.rms[i]:6.1f}" for ax, i in zip("xyz", j, strict=True))
        if ride.difference_rms is not None:
            text += (f"   {ride.body} - {ride.info['reference_body']}: " + "  ".join(
                f"{ax} {ride.difference_rms[i]:5.1f}" for ax, i in zip("xyz", j, strict=True)))
        lines.append(f"  hub_{c} RMS (N, body axes)  {text}")
    for point, val in ride.points.items():
        w = [ride.weighted_rms[ride.outputs.index(f"acc_{point}_{ax}")] for ax in "xyz"]
        lines.append(f"  {point:24s} a_w x {w[0]:.3f}  y {w[1]:.3f}  z {w[2]:.3f}  "
                     f"a_v {val['a_v_m/s^2']:.3f} m/s^2: {val['reaction']}"
                     + (f"; SEAT {val['SEAT_%']:.1f} %" if "SEAT_%" in val else ""))
    return "\n".join(lines)


def write_ride(ride, out) -> list[Path]:
    """Write ``ride.csv``, ``ride.json``, ``ride_psd.csv`` and ``ride_psd.png`` into
    ``out`` (created if needed); returns their paths."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / "ride.csv", out / "ride.json", out / "ride_psd.csv", out / "ride_psd.png"]
    rows = ride.rows()
    ref = ride.info.get("reference_body")
    lines = ["output,rms,unit,iso2631_weighting,weighted_rms_m/s^2"
             + (f",difference_rms_vs_{ref}" if ref else "")]
    for row in rows:
        w = "" if np.isnan(row["weighted_rms"]) else f"{row['weighted_rms']:.7g}"
        lines.append(f"{row['output']},{row['rms']:.7g},{row['unit']},"
                     f"{row['iso2631_weighting']},{w}"
                     + (f",{row['difference_rms']:.7g}" if ref else ""))
    write_text_atomic(paths[0], "\n".join(lines) + "\n")
    rows = [{k: (None if isinstance(v, float) and np.isnan(v) else v) for k, v in r.items()}
            for r in rows]
    doc = {"car": ride.car, "body": ride.body, "speed_m_per_s": ride.speed,
           "road_class": ride.road_class, "track_width_m": ride.track_width, **ride.info,
           "notes": list(NOTES), "outputs": rows, "points": ride.points,
           "dynamic_load_coefficient": ride.dynamic_load}
    write_text_atomic(paths[1], json.dumps(doc, indent=1) + "\n")
    units = [_squared(output_unit(n)) + "/Hz" for n in ride.outputs]
    head = ["f_Hz", "road_m^2/Hz", "coherence"] + [f"{n}_{u}" for n, u in
                                                   zip(ride.outputs, units, strict=True)]
    columns = [ride.psd]
    if ref:  # the difference from the reference body's outputs
        head += [f"{n}_minus_{ref}_{u}" for n, u in zip(ride.outputs, units, strict=True)]
        columns.append(ride.difference_psd)
    body = [",".join(f"{v:.7g}" for v in (f, g, c, *s)) for f, g, c, s in
            zip(ride.f_hz, ride.road_psd, ride.coherence, np.hstack(columns), strict=True)]
    write_text_atomic(paths[2], "\n".join([",".join(head), *body]) + "\n")
    _plot(ride, paths[3])
    return paths


def _squared(unit: str) -> str:
    """``N`` -> ``N^2``, ``m/s^2`` -> ``(m/s^2)^2``."""
    return f"({unit})^2" if "/" in unit else f"{unit}^2"


def _plot(ride, path) -> None:
    from flexpipe.sweeps.iso2631 import response
    from flexpipe.vehicle.linear_output import _figure, _save

    ref = ride.info.get("reference_body")
    fig, axes = _figure(3 if ref else 2, 1, figsize=(8, 10 if ref else 7), sharex=True)
    f = ride.f_hz
    for j, name in enumerate(ride.outputs):
        if name.endswith("_Fz") or (name.startswith("hub_") and name.endswith("_z")):
            axes[0].loglog(f, ride.psd[:, j], label=f"{name} (RMS {ride.rms[j]:.0f} N)",
                           ls="--" if name.startswith("hub_") else "-")
        elif name.startswith("acc_") and name.endswith("_z"):
            wk = np.abs(response(f, "Wk")) ** 2
            line, = axes[1].loglog(f, ride.psd[:, j],
                                   label=f"{name} (RMS {ride.rms[j]:.2f} m/s^2)")
            axes[1].loglog(f, wk * ride.psd[:, j], ls="--", color=line.get_color(),
                           label=f"  Wk weighted ({ride.weighted_rms[j]:.2f} m/s^2)")
    axes[0].set_ylabel("vertical tyre and hub forces\nPSD (N^2/Hz)")
    axes[1].set_ylabel("vertical floor acceleration\nPSD ((m/s^2)^2/Hz)")
    if ref:
        for j, name in enumerate(ride.outputs):
            if name.startswith(("hub_fl_", "hub_rl_")):
                axes[2].loglog(f, ride.difference_psd[:, j],
                               label=f"{name} (RMS {ride.difference_rms[j]:.1f} N)")
        axes[2].set_ylabel(f"hub forces, {ride.body} minus\n{ref}: PSD (N^2/Hz)")
    axes[-1].set_xlabel("frequency (Hz)")
    axes[0].set_title(f"{ride.car}, {ride.body} body: ISO 8608 class {ride.road_class}, "
                      f"{ride.speed * 3.6:g} km/h (linear model)")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        top = max((ln.get_ydata().max() for ln in ax.get_lines()), default=1.0)
        ax.set_ylim(top * 1e-4, top * 3)
    _save(fig, path)


def speed_table(rides) -> tuple[list, list]:
    """Header (units in the names) and rows of ``ride_vs_speed.csv``: per speed, every
    output's RMS and weighted RMS, each body point's ``a_v``, each tyre's dynamic load
    coefficient and, against a reference body, every output's difference RMS."""
    first = rides[0]
    head = ["speed_km/h"]
    for name in first.outputs:
        head.append(f"{name}_rms_{output_unit(name)}")
    head += [f"{n}_weighted_rms_m/s^2" for n in first.outputs if n.startswith("acc_")]
    head += [f"{p}_a_v_m/s^2" for p in first.points]
    head += [f"tire_{c}_dynamic_load" for c in first.dynamic_load]
    compared = first.difference_rms is not None
    if compared:  # against the reference body on the same road
        head += [f"{name}_difference_rms_{output_unit(name)}" for name in first.outputs]
    rows = []
    for r in rides:
        acc = [j for j, n in enumerate(r.outputs) if n.startswith("acc_")]
        rows.append([r.speed * 3.6, *r.rms, *r.weighted_rms[acc],
                     *(p["a_v_m/s^2"] for p in r.points.values()),
                     *r.dynamic_load.values(), *(r.difference_rms if compared else ())])
    return head, rows


def write_ride_vs_speed(rides, out) -> list[Path]:
    """``ride_vs_speed.csv``, ``.json`` and ``.png`` into ``out``: the ride at each speed
    (:func:`~flexpipe.vehicle.linear_ride.ride_vs_speed`); returns their paths."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / "ride_vs_speed.csv", out / "ride_vs_speed.json", out / "ride_vs_speed.png"]
    head, rows = speed_table(rides)
    write_text_atomic(paths[0], "\n".join([",".join(head)] + [
        ",".join(f"{v:.7g}" for v in row) for row in rows]) + "\n")
    first = rides[0]
    doc = {"car": first.car, "body": first.body, "road_class": first.road_class,
           "track_width_m": first.track_width,
           "coherence_model": first.info["coherence_model"],
           "reference_body": first.info.get("reference_body"), "notes": list(NOTES),
           "speeds": [{"speed_km/h": r.speed * 3.6, "points": r.points,
                       "dynamic_load_coefficient": r.dynamic_load,
                       "road_rms_m": r.info["road_rms_m"],
                       "outputs": [{k: (None if isinstance(v, float) and np.isnan(v) else v)
                                    for k, v in row.items()} for row in r.rows()]}
                      for r in rides]}
    write_text_atomic(paths[1], json.dumps(doc, indent=1) + "\n")
    _plot_speeds(rides, paths[2])
    return paths


def _plot_speeds(rides, path) -> None:
    from flexpipe.sweeps.iso2631 import COMFORT_REACTIONS
    from flexpipe.vehicle.linear_output import _figure, _save

    kmh = [r.speed * 3.6 for r in rides]
    first = rides[0]
    travel = [name for name in first.outputs if name.startswith("travel_")]
    hubs = ([name for name in first.outputs if name.startswith("hub_")]
            if first.difference_rms is not None else [])
    n = 2 + bool(travel) + bool(hubs)
    fig, axes = _figure(n, 1, figsize=(8, 2.4 + 2.4 * n), sharex=True)
    for point in rides[0].points:
        axes[0].plot(kmh, [r.points[point]["a_v_m/s^2"] for r in rides], "o-", label=point)
    top = max(r.points[p]["a_v_m/s^2"] for r in rides for p in r.points) * 1.15
    bands = [(lo, name) for lo, _, name in COMFORT_REACTIONS[1:] if lo < top]
    for lo, _ in bands:
        axes[0].axhline(lo, color="0.6", lw=0.8, ls=":")
    axes[0].set_ylim(0.0, top)
    right = axes[0].twinx()  # ISO 2631-1 Annex C: where each reaction starts
    right.set_ylim(0.0, top)
    right.set_yticks([lo for lo, _ in bands], [name for _, name in bands], fontsize=7)
    axes[0].set_ylabel("ISO 2631-1 comfort value a_v (m/s^2)")
    for corner in rides[0].dynamic_load:
        axes[1].plot(kmh, [r.dynamic_load[corner] for r in rides], "o-",
                     label=f"tyre {corner}")
    axes[1].set_ylabel("dynamic load coefficient\nRMS(Fz) / static Fz (-)")
    for name in travel:
        j = rides[0].outputs.index(name)
        axes[2].plot(kmh, [r.rms[j] * 1e3 for r in rides], "o-", label=name)
    if travel:
        axes[2].set_ylabel("suspension travel RMS (mm)")
    colour = {}
    for name in hubs:  # a colour per corner, a line style per axis
        corner, axis = name[4:-2], name[-1]
        j = first.outputs.index(name)
        axes[-1].plot(kmh, [r.difference_rms[j] for r in rides],
                      marker="o", ls={"x": "-", "y": "--", "z": ":"}[axis],
                      color=colour.setdefault(corner, f"C{len(colour)}"), label=name)
    if hubs:
        axes[-1].set_ylabel(f"hub force difference RMS (N)\n{first.body} - "
                            f"{first.info['reference_body']}")
    axes[-1].set_xlabel("speed (km/h)")
    axes[0].set_title(f"{first.car}, {first.body} body: ISO 8608 class {first.road_class} "
                      "(linear model)")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, ncol=4 if hubs and ax is axes[-1] else 1)
    _save(fig, path)
