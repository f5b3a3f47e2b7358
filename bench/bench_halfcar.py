"""Half-car benchmark: nonlinear spectrum sweeps and transients, complete vs reduced.

Acceptance target: a 200-point nonlinear spectrum sweep (harmonic balance with
continuation + Floquet stability at every point) of the reduced model in under 20 s on
2 cores.  ``run()`` prints and returns the figures.
"""

from __future__ import annotations

import time

import numpy as np

from flexpipe.halfcar import build_model
from flexpipe.halfcar.elements import Nonlinearity
from flexpipe.halfcar.hb import sweep
from flexpipe.halfcar.transient import Road, simulate

CASES = {
    "dual_rate": Nonlinearity(damper="dual_rate"),
    "dual_rate_duffing_contact": Nonlinearity(damper="dual_rate", tire="duffing",
                                              contact=True),
}


def _timed(fn):
    w0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w0, time.process_time() - c0


def run() -> dict:
    """Time 200-point sweeps and the 150 km/h transient for the complete and reduced models."""
    res: dict = {}
    models = {v: build_model(v) for v in ("complete", "reduced")}
    p = models["reduced"].params
    f = np.linspace(p.sweep_f_min_Hz, p.sweep_f_max_Hz, 200)
    for case, nl in CASES.items():
        for variant, m in models.items():
            spec, wall, cpu = _timed(lambda m=m, nl=nl: sweep(m, nl, f))
            res[f"sweep200_{case}_{variant}_wall_s"] = wall
            res[f"sweep200_{case}_{variant}_cpu_s"] = cpu
            res[f"sweep200_{case}_{variant}_stable_points"] = int(spec.stable.sum())
        res[f"sweep200_{case}_cpu_ratio_complete_to_reduced"] = (
            res[f"sweep200_{case}_complete_cpu_s"] / res[f"sweep200_{case}_reduced_cpu_s"])
    road = Road(p.road_amplitude_m, p.road_wavelength_m, p.irregularity_cycles)
    v = p.reference_speed_m_per_s
    for variant, m in models.items():  # best of 5: each run takes only tens of ms
        cpu = min(_timed(lambda m=m: simulate(m, CASES["dual_rate"], road, v, 1.5))[2]
                  for _ in range(5))
        res[f"transient_dual_rate_{variant}_cpu_s"] = cpu
    res["transient_cpu_ratio_complete_to_reduced"] = (
        res["transient_dual_rate_complete_cpu_s"] / res["transient_dual_rate_reduced_cpu_s"])
    res["target_reduced_sweep200_under_20s"] = bool(
        max(res[f"sweep200_{c}_reduced_wall_s"] for c in CASES) < 20.0)
    for key, value in res.items():
        print(f"{key:52s} {value:.3f}" if isinstance(value, float) else f"{key:52s} {value}")
    return res


if __name__ == "__main__":
    run()
