"""Durability benchmark: cost of stress modes, modal stress recovery, fatigue and animation
on the sample sedan over the ``make straight`` run (10 s, 70 km/h, ISO 8608 class C).

Acceptance targets (issue 11): stress recovery for the 10 s straight run under 10 s; body
file with stress modes under 30 MB.  The peer figure is the flexible run's own CPU time,
measured in the same process: ``recovery_to_simulation_cpu`` is the recovery CPU time
over it.  Wall times are also given: the acceptance target is a wall time.
"""

from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path

from flexpipe.scenarios.runner import DEFAULT_CAR, _straight_road
from flexpipe.vehicle import load_car, simulate
from flexpipe.vehicle.simulation import prepare

SPEED = 70.0 / 3.6
T_RUN = 10.0


def run() -> dict:
    """Run the benchmark; returns a flat dict of figures."""
    from flexpipe.durability.recover import recover_stress

    car = load_car(DEFAULT_CAR)
    road = _straight_road()
    out = {"car": car.name, "t_run_s": T_RUN,
           "load_average_1min_at_start": round(os.getloadavg()[0], 2)}
    old = os.environ.get("FLEXPIPE_CACHE")
    with tempfile.TemporaryDirectory() as tmp:
        os.environ["FLEXPIPE_CACHE"] = tmp
        try:
            prep = prepare(car, body="flexible", speed=SPEED, road=road)
            fb = prep["flexbody"]
            size = Path(prep["reduction"]["path"]).stat().st_size
            out.update(elements_with_stress=fb.stress.n_elements, modes=fb.n_elastic,
                       stress_modes_s=fb.meta.get("stress_s"),
                       stress_modes_MB=round(fb.stress.nbytes / 1e6, 2),
                       body_file_MB=round(size / 1e6, 2), body_file_target_MB=30)
            r = simulate(car, road=road, speed=SPEED, t_end=T_RUN, body="flexible",
                         prepared=prep)
            out["steps"] = len(r.t)
            out["simulation_cpu_s"] = round(r.cpu_time, 2)
            t0, c0 = time.perf_counter(), time.process_time()
            sr = recover_stress(r, fb)
            t_rec = time.perf_counter() - t0
            out["recovery_cpu_s"] = round(time.process_time() - c0, 2)
            out.update(recovery_s=round(t_rec, 2), recovery_target_s=10.0,
                       recovery_to_simulation_cpu=round(out["recovery_cpu_s"]
                                                        / max(r.cpu_time, 1e-9), 3),
                       max_von_mises_MPa=round(float(sr.max_von_mises.max()) / 1e6, 2))
            t0 = time.perf_counter()
            sr = recover_stress(r, fb, fatigue=car.body.fatigue)
            out["recovery_with_fatigue_s"] = round(time.perf_counter() - t0, 2)
            import numpy as np

            out["elements_counted_rainflow"] = int(np.isfinite(sr.damage).sum())
            out["max_damage_per_km"] = float(f"{np.nanmax(sr.damage_per_km):.4g}")
        finally:
            if old is None:
                os.environ.pop("FLEXPIPE_CACHE", None)
            else:
                os.environ["FLEXPIPE_CACHE"] = old
    out["load_average_1min_at_end"] = round(os.getloadavg()[0], 2)
    for k, v in out.items():
        print(f"{k:32s} {v}")
    return out


if __name__ == "__main__":
    run()
