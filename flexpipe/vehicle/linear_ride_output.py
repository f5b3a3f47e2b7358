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
    for point, val in ride.points.items():
        w = [ride.weighted_rms[ride.outputs.index(f"acc_{point}_{ax}")] for ax in "xyz"]
        lines.append(f"  {point:24s} a_w x {w[0]:.3f}  y {w[1]:.3f}  z {w[2]:.3f}  "
                     f"a_v {val['a_v_m/s^2']:.3f} m/s^2: {val['reaction']}")
    return "\n".join(lines)


def write_ride(ride, out) -> list[Path]:
    """Write ``ride.csv``, ``ride.json``, ``ride_psd.csv`` and ``ride_psd.png`` into
    ``out`` (created if needed); returns their paths."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    paths = [out / "ride.csv", out / "ride.json", out / "ride_psd.csv", out / "ride_psd.png"]
    lines = ["output,rms,unit,iso2631_weighting,weighted_rms_m/s^2"]
    for row in ride.rows():
        w = "" if np.isnan(row["weighted_rms"]) else f"{row['weighted_rms']:.7g}"
        lines.append(f"{row['output']},{row['rms']:.7g},{row['unit']},"
                     f"{row['iso2631_weighting']},{w}")
    write_text_atomic(paths[0], "\n".join(lines) + "\n")
    rows = [{k: (None if isinstance(v, float) and np.isnan(v) else v) for k, v in r.items()}
            for r in ride.rows()]
    doc = {"car": ride.car, "body": ride.body, "speed_m_per_s": ride.speed,
           "road_class": ride.road_class, "track_width_m": ride.track_width, **ride.info,
           "notes": list(NOTES), "outputs": rows, "points": ride.points,
           "dynamic_load_coefficient": ride.dynamic_load}
    write_text_atomic(paths[1], json.dumps(doc, indent=1) + "\n")
    units = ["N^2/Hz" if n.endswith("_Fz") else "(m/s^2)^2/Hz" for n in ride.outputs]
    head = ["f_Hz", "road_m^2/Hz", "coherence"] + [f"{n}_{u}" for n, u in
                                                   zip(ride.outputs, units, strict=True)]
    body = [",".join(f"{v:.7g}" for v in (f, g, c, *s)) for f, g, c, s in
            zip(ride.f_hz, ride.road_psd, ride.coherence, ride.psd, strict=True)]
    write_text_atomic(paths[2], "\n".join([",".join(head), *body]) + "\n")
    _plot(ride, paths[3])
    return paths


def _plot(ride, path) -> None:
    from flexpipe.sweeps.iso2631 import response
    from flexpipe.vehicle.linear_output import _figure, _save

    fig, axes = _figure(2, 1, figsize=(8, 7), sharex=True)
    f = ride.f_hz
    for j, name in enumerate(ride.outputs):
        if name.endswith("_Fz"):
            axes[0].loglog(f, ride.psd[:, j], label=f"{name} (RMS {ride.rms[j]:.0f} N)")
        elif name.endswith("_z"):
            wk = np.abs(response(f, "Wk")) ** 2
            line, = axes[1].loglog(f, ride.psd[:, j],
                                   label=f"{name} (RMS {ride.rms[j]:.2f} m/s^2)")
            axes[1].loglog(f, wk * ride.psd[:, j], ls="--", color=line.get_color(),
                           label=f"  Wk weighted ({ride.weighted_rms[j]:.2f} m/s^2)")
    axes[0].set_ylabel("vertical tyre force PSD (N^2/Hz)")
    axes[1].set_ylabel("vertical floor acceleration\nPSD ((m/s^2)^2/Hz)")
    axes[1].set_xlabel("frequency (Hz)")
    axes[0].set_title(f"{ride.car}, {ride.body} body: ISO 8608 class {ride.road_class}, "
                      f"{ride.speed * 3.6:g} km/h (linear model)")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
        top = max((ln.get_ydata().max() for ln in ax.get_lines()), default=1.0)
        ax.set_ylim(top * 1e-4, top * 3)
    _save(fig, path)
