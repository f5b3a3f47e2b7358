"""Road query cost on a curved OpenCRG road, as a car queries it every step.

Per step the car asks for the height under 4 wheels (plus 4 neighbours each for the road
normal: 20 points) and under the 4 wheels a step ahead.  The peer is pyopencrg's
``RoadEvaluator`` (its fast path for repeated small queries, also remembering the last
``u`` of each point) on the same file, measured in the same run.  Target: flexpipe costs at
most 2x the peer per step, and the heights agree to 1e-9 m.
"""

from __future__ import annotations

import tempfile
import time
from pathlib import Path

import numpy as np

from flexpipe.roads import Road, read_crg, write_crg
from flexpipe.roads.refline import ReferenceLine

N_STEPS = 3000
DT = 2e-3
SPEED = 20.0


def _curved_file(folder: Path) -> Path:
    du = 0.05
    u = du * np.arange(20001)                                    # 1 km
    v = np.linspace(-3.0, 3.0, 61)
    phi = 0.8 * np.sin(u[1:] / 80.0)
    rng = np.random.default_rng(0)
    z = rng.normal(0.0, 0.003, (u.size, v.size))
    road = Road.from_grid(u, v, z, plan=ReferenceLine.from_heading(0.0, du, phi))
    path = folder / "curved_1km.crg"
    write_crg(road, path, fmt="KDBI")
    return path


def _contact_points(road, k):
    """The 20 + 4 query points of step k (wheels at +-1.3 m, +-0.8 m around the car)."""
    s = 5.0 + SPEED * DT * k
    u = s + np.array([1.3, 1.3, -1.3, -1.3])
    v = np.array([0.8, -0.8, 0.8, -0.8])
    x, y = road.plan.uv_to_xy(u, v)
    e = 0.05
    x20 = np.concatenate([x, x + e, x - e, x, x])
    y20 = np.concatenate([y, y, y, y + e, y - e])
    return (x20, y20), (x + SPEED * DT, y)


def run() -> dict:
    """Run the benchmark; returns a flat dict of figures."""
    import pyopencrg

    with tempfile.TemporaryDirectory() as tmp:
        path = _curved_file(Path(tmp))
        road = read_crg(path)
        ev = pyopencrg.read(path).evaluator()
        queries = [_contact_points(road, k) for k in range(N_STEPS)]
        times, heights = {}, {}
        for name, fn in (("flexpipe", road.height_xy), ("pyopencrg", ev.xy_to_z)):
            out = []
            t0 = time.process_time()
            for (a, b), (c, d) in queries:
                out.append(fn(a, b))
                out.append(fn(c, d))
            times[name] = time.process_time() - t0
            heights[name] = np.concatenate(out)
    ratio = times["flexpipe"] / times["pyopencrg"]
    dz = float(np.max(np.abs(heights["flexpipe"] - heights["pyopencrg"])))
    res = {
        "road_steps": N_STEPS,
        "road_flexpipe_us_per_step": 1e6 * times["flexpipe"] / N_STEPS,
        "road_pyopencrg_us_per_step": 1e6 * times["pyopencrg"] / N_STEPS,
        "road_cost_ratio_flexpipe_over_pyopencrg": ratio,
        "road_max_height_difference_m": dz,
        "road_ok": bool(ratio <= 2.0 and dz < 1e-9),
    }
    for k, v in res.items():
        print(f"{k:45s} {v}")
    return res


if __name__ == "__main__":
    run()
