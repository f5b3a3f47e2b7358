"""How much of the body the car keeps: its hub forces against richer bodies.

The linkage car's flexible body is reduced twice over: fixed-interface modes up to 1.5x
the run's band (:func:`flexpipe.vehicle.bodymodel.choose_band`, at most
:data:`~flexpipe.vehicle.bodymodel.BAND_CAP_HZ` = 40 Hz, so 60 Hz on ISO C at 70 km/h),
and, of its 30 mounts' static modes, the characteristic constraint modes up to 400 Hz
(interface reduction, :data:`flexpipe.vehicle.linkage_setup.INTERFACE_F_MAX_HZ`,
``[body] interface_band_hz``; ``"all"`` keeps every static mode: the static flexibility
at every mount exact).  The ``full`` body (``flexpipe run --body full``) keeps every
fixed-interface mode to 250 Hz and every static mode.  This bench runs the flexible
linkage car (``cars/sedan_linkage.toml``, ISO 8608 class C, 70 km/h, 3 s, default step)
with bands of 30, 40 (the default), 45 and 60 Hz, with the default band and the interface
reduced to 800 and 1600 Hz or not at all, and as the full body, and prints for each: the
elastic mode count, the CPU time of the run (one process, one run after the other: a
ratio, not a speed figure) and the worst corner's RMS hub-force difference after 0.5 s
from the full body's, and from the one with every static mode, in percent of that run's
fluctuating part (standard deviation), over all frequencies and band by band
(zero-phase Butterworth filters of the difference).  The first reduction of the full
body takes about 3 minutes (then cached).

Usage: ``python -m bench body_modes`` (or ``python bench/bench_body_modes.py``).
"""

from __future__ import annotations

import dataclasses
import math
import sys
from pathlib import Path

import numpy as np
from scipy.signal import butter, sosfiltfilt

import flexpipe as fp
from flexpipe.scenarios.runner import _straight_road
from flexpipe.vehicle.simulation import prepare

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan_linkage.toml"
#: (tag, band Hz or None for the default, interface band Hz or None for the default)
VARIANTS = (("band30", 30.0, None), ("band40", None, None), ("band45", 45.0, None),
            ("band60", 60.0, None),
            ("if800", None, 800.0), ("if1600", None, 1600.0), ("all", None, math.inf))
FILTERS_HZ = ((0.0, 50.0), (50.0, 150.0), (150.0, 300.0), (300.0, 500.0))
T_END = 3.0
T_FROM = 0.5
SPEED = 70.0 / 3.6


def _hub(r) -> dict:
    return {k: np.asarray(v) for k, v in r.channels.items()
            if k.startswith("hub_") and k.count("_") == 2}


def differences(t, runs: dict, ref: dict) -> dict:
    """Worst channel's RMS difference (percent of ``ref``'s standard deviation after
    :data:`T_FROM`), over all frequencies (``"all"``) and per band of :data:`FILTERS_HZ`."""
    fs = 1.0 / float(np.median(np.diff(t)))
    m = t > T_FROM
    out = {}
    for k, x in ref.items():
        scale = float(np.std(x[m]))
        d = runs[k] - x
        vals = {"all": float(np.sqrt(np.mean(d[m] ** 2)))}
        for lo, hi in FILTERS_HZ:
            sos = (butter(4, hi, "low", fs=fs, output="sos") if lo == 0.0 else
                   butter(4, [lo, hi], "band", fs=fs, output="sos"))
            vals[f"{lo:g}-{hi:g}_hz"] = float(np.sqrt(np.mean(sosfiltfilt(sos, d)[m] ** 2)))
        for name, v in vals.items():
            pct = 100.0 * v / scale
            if pct > out.get(name, (-1.0, ""))[0]:
                out[name] = (pct, k)
    return out


def run() -> dict:
    """Run the benchmark; returns a flat dict of figures."""
    road = _straight_road()
    base = fp.load_car(CAR)
    results = {}
    for tag, f_max, itf in (*VARIANTS, ("full", None, None)):
        body = "full" if tag == "full" else "flexible"
        car = base if itf is None else dataclasses.replace(
            base, body=dataclasses.replace(base.body, interface_band_hz=itf))
        prep = prepare(car, body=body, speed=SPEED, road=road, f_max=f_max)
        r = fp.simulate(car, road=road, speed=SPEED, t_end=T_END, body=body, prepared=prep,
                        f_max=f_max)
        if r.status != 0:
            raise RuntimeError(f"{tag}: {r.message}")
        results[tag] = (r, prep["flexbody"])
    t = np.asarray(results["full"][0].t)
    out = {"t_run_s": T_END, "speed_kmh": 70.0}
    for tag, (r, fb) in results.items():
        out[f"{tag}_elastic_modes"] = int(fb.n_elastic)
        out[f"{tag}_band_hz"] = r.info.get("band_hz")
        out[f"{tag}_highest_mode_hz"] = round(float(fb.frequencies_hz[-1]), 1)
        out[f"{tag}_cpu_s"] = round(r.cpu_time, 2)
        out[f"{tag}_cpu_over_full"] = round(r.cpu_time / results["full"][0].cpu_time, 3)
        for ref in ("full", "all"):
            if tag == ref or (ref == "all" and tag == "full"):
                continue
            for name, (pct, k) in differences(t, _hub(r), _hub(results[ref][0])).items():
                out[f"{tag}_vs_{ref}_{name}_pct"] = round(pct, 2)
                out[f"{tag}_vs_{ref}_{name}_channel"] = k
    for k, v in out.items():
        print(f"{k:40s} {v}")
    return out


if __name__ == "__main__":
    sys.exit(0 if run() else 1)
