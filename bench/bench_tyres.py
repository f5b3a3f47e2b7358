"""Cost of the compiled tyre per car step: an MF 6.1 tyre against the MF 5.2 one.

A car step evaluates the four wheels' contact, vertical force, slips, relaxation and Magic
Formula in one compiled call (:func:`flexpipe.tires._fast.wheel_kernel`).  The MF 6.1
sample tyre (``tires/sedan_205_55R16_mf61.tir``, at 190 kPa of 230 so every pressure term
acts) is timed against the MF 5.2 sample in the same run, on the same random wheel
states.  Target: MF 6.1 costs at most 1.2x MF 5.2 per call (its equations have more
terms; the call's fixed cost dominates).
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from flexpipe.tires import SlipState, tire_from_file

ROOT = Path(__file__).resolve().parents[1]
N_CALLS = 20000


def _states(tire, rng, n=4):
    C = np.c_[rng.normal(size=(n, 2)), tire.unloaded_radius * (0.92 + 0.04 * rng.random(n))]
    s = np.c_[0.03 * rng.normal(size=n), np.ones(n), 0.03 * rng.normal(size=n)]
    v = np.c_[rng.uniform(10.0, 30.0, n), rng.normal(size=n), 0.1 * rng.normal(size=n)]
    omega = v[:, 0] / tire.unloaded_radius * (1.0 + 0.05 * rng.normal(size=n))
    return C, s, omega, v, SlipState(0.02 * rng.normal(size=n), 0.02 * rng.normal(size=n))


def _time(tire) -> float:
    rng = np.random.default_rng(3)
    C, s, omega, v, st = _states(tire, rng)
    for _ in range(200):   # compile and warm up
        tire.wheel_forces(C, s, omega, v, road_height=0.0, state=st, dt=1e-3)
    t0 = time.process_time()
    for _ in range(N_CALLS):
        tire.wheel_forces(C, s, omega, v, road_height=0.0, state=st, dt=1e-3)
    return (time.process_time() - t0) / N_CALLS


def run() -> dict:
    """Run the benchmark; returns a flat dict of figures."""
    mf52 = tire_from_file(ROOT / "tires" / "sedan_205_55R16.tir")
    mf61 = tire_from_file(ROOT / "tires" / "sedan_205_55R16_mf61.tir", pressure=190000.0)
    t52, t61 = min(_time(mf52) for _ in range(3)), min(_time(mf61) for _ in range(3))
    res = {
        "tyres_calls": N_CALLS,
        "tyres_mf52_us_per_4_wheel_call": 1e6 * t52,
        "tyres_mf61_us_per_4_wheel_call": 1e6 * t61,
        "tyres_cost_ratio_mf61_over_mf52": t61 / t52,
        "tyres_ok": bool(t61 / t52 <= 1.2),
    }
    for k, val in res.items():
        print(f"{k:45s} {val}")
    return res
