"""Sweep benchmark: 16 rigid runs of 10 s on a 2-worker local Dask cluster against the same
16 runs one after the other with ``simulate()`` in this process, and a small flexible
sweep on an empty cache that must reduce each distinct body exactly once.

Acceptance targets (issue 12): the sweep at least 1.7x faster than serial on the 2-core
machine; one reduction per distinct body.  ``run()`` prints and returns the figures; the
ratio compares two measurements of this one run (cluster start-up is reported apart: an
existing cluster does not pay it).
"""

from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path

import numpy as np

from flexpipe.scenarios.runner import DEFAULT_CAR

SPEEDS = [40.0, 50.0, 60.0, 70.0, 80.0, 90.0, 100.0, 110.0]  # km/h
CLASSES = ["B", "C"]
T_RUN = 10.0
ROUNDS = 4
ROAD = {"type": "iso8608", "road_class": "C", "length_m": 340.0, "dx_m": 0.05, "seed": 3,
        "track_width_m": 1.5, "fade_m": 5.0}


def _spec(**extra):
    sweep = {"car": str(DEFAULT_CAR), "body": "rigid", "t_end_s": T_RUN}
    sweep.update(extra.pop("sweep", {}))
    return {"sweep": sweep, "road": dict(ROAD), **extra}


def _serial(car, speeds):
    from flexpipe.vehicle import simulate

    results = []
    for v in speeds:  # the sweep's grid order: first parameter outermost
        for cls in CLASSES:
            results.append(simulate(car, road=dict(ROAD, road_class=cls), speed=v / 3.6,
                                    t_end=T_RUN, body="rigid"))
    return results


def run() -> dict:
    """Run the benchmark; returns a flat dict of figures."""
    import logging

    from dask.distributed import Client, LocalCluster

    from flexpipe.sweeps import sweep
    from flexpipe.vehicle import load_car
    from flexpipe.vehicle.simulation import prepare

    out = {"runs": len(SPEEDS) * len(CLASSES), "t_end_s": T_RUN, "workers": 2,
           "cores": os.cpu_count()}
    old = os.environ.get("FLEXPIPE_CACHE")
    with tempfile.TemporaryDirectory() as tmp:
        os.environ["FLEXPIPE_CACHE"] = str(Path(tmp) / "cache")
        try:
            car = load_car(DEFAULT_CAR)
            prepare(car, body="rigid", speed=20.0)  # body mass properties cached for both
            __import__("flexpipe.exu.car")
            t0 = time.perf_counter()
            cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                   host="127.0.0.1", dashboard_address=":0",
                                   silence_logs=logging.ERROR)
            client = Client(cluster)
            warm = ("flexpipe.vehicle.simulation", "flexpipe.exu.car", "flexpipe.sweeps.tasks")
            client.run(lambda: [__import__(m) for m in warm])  # imports, as in this process
            out["cluster_start_s"] = round(time.perf_counter() - t0, 2)
            out["load_average_start"] = round(os.getloadavg()[0], 2)
            try:
                # serial and sweep alternate in ROUNDS batches of 4 runs, so a change of the
                # load from other jobs during the benchmark hits both alike
                serial_s = sweep_s = cpu = sweep_cpu = 0.0
                diff = 0.0
                n_failed = 0
                for i in range(ROUNDS):
                    speeds = SPEEDS[i::ROUNDS]
                    t0 = time.perf_counter()
                    serial = _serial(car, speeds)
                    serial_s += time.perf_counter() - t0
                    cpu += sum(r.cpu_time for r in serial)
                    spec = _spec(parameters={"speed_kmh": speeds, "road.road_class": CLASSES})
                    t0 = time.perf_counter()
                    res = sweep(spec, out=Path(tmp) / f"rigid{i}", scheduler=client,
                                progress=False, plots=False)
                    sweep_s += time.perf_counter() - t0
                    n_failed += res.n_failed
                    sweep_cpu += float(res.table["cpu_s"].sum())
                    diff = max([diff] + [abs(float(np.abs(r.channels["hub_fl_z"]).max()) - p)
                                         for r, p in zip(serial, res.table["hub_fl_z_peak_N"],
                                                         strict=True)])
                out.update(serial_s=round(serial_s, 2), serial_cpu_s=round(cpu, 2),
                           sweep_s=round(sweep_s, 2), sweep_cpu_s=round(sweep_cpu, 2),
                           sweep_failed=n_failed,
                           speedup=round(serial_s / sweep_s, 2),
                           speedup_with_cluster_start=round(
                               serial_s / (sweep_s + out["cluster_start_s"]), 2),
                           max_peak_hub_force_diff_N=diff,
                           load_average_end=round(os.getloadavg()[0], 2))

                # flexible: 2 car variants (body damping) x 2 speeds on an empty cache
                spec = _spec(sweep={"body": "flexible", "t_end_s": 1.0},
                             parameters={"car.body.damping_ratio": [0.02, 0.03],
                                         "speed_kmh": [60.0, 90.0]})
                t0 = time.perf_counter()
                fres = sweep(spec, out=Path(tmp) / "flex", scheduler=client, progress=False,
                             plots=False)
                out["flex_sweep_s"] = round(time.perf_counter() - t0, 2)
                out["flex_runs"] = fres.n_runs
                out["flex_failed"] = fres.n_failed
                out["distinct_bodies"] = len(fres.reductions)
                out["reductions_done"] = fres.n_reduced
                out["body_files_in_cache"] = len(list((Path(tmp) / "cache").glob("body-*.npz")))
            finally:
                client.close()
                cluster.close()
        finally:
            if old is None:
                os.environ.pop("FLEXPIPE_CACHE", None)
            else:
                os.environ["FLEXPIPE_CACHE"] = old
    out["speedup_target"] = 1.7
    out["speedup_ok"] = out["speedup"] >= 1.7
    out["one_reduction_per_body"] = (out["reductions_done"] == out["distinct_bodies"] == 2
                                     == out["body_files_in_cache"])
    for k, v in out.items():
        print(f"{k:32s} {v}")
    assert out["sweep_failed"] == 0 and out["flex_failed"] == 0
    assert out["max_peak_hub_force_diff_N"] <= 1e-9, "sweep differs from serial simulate()"
    assert out["one_reduction_per_body"], "a body was reduced more than once"
    return out


if __name__ == "__main__":
    run()
