"""Reduction cost and accuracy with every suspension mount an interface (sample sedan).

The trimmed sample body (``cars/sedan.toml`` on ``meshes/sedan_biw.bdf``) is reduced for
a 30 Hz band (Craig-Bampton, fixed-interface modes to 1.5 x 30 Hz, as the car did until
its band cap was raised to 40 Hz, ``flexpipe.vehicle.bodymodel.BAND_CAP_HZ``) with

``corners4``   the four corner hardpoints as 6-DOF spiders (today's car);
``m30x6``      the 30 body-side mounts as 6-DOF interfaces;
``m30x3``      the 30 mounts as 3-DOF (translational) interfaces;
``m30x3_cc<f>`` the same with interface reduction: characteristic constraint modes up to
               ``f`` Hz (Castanier, Tan & Pierre 2001) plus the inertia vectors of those
               up to 3 x 30 Hz;
``..._cb3``    fixed-interface modes to 3 x 30 Hz (``flexpipe.reduce``'s default ratio)
               instead of the car's 1.5 x.

Per case: reduction time, elastic mode count, the largest free-free frequency error below
30 Hz against the unreduced model, and for the 30-mount cases the supported static
flexibility at the mounts against the unreduced model (largest and median relative error
of a mount's 3 x 3 driving-point block; body held 3-2-1 at three lower-arm mounts), also
with each interface's residual compliance added to its block (``..._series``).
Per case also the Exudyn CPU time per simulated second of the body alone hung on four
spring-dampers (``flexpipe.exu.timing.step_cost``: generalized-alpha, h = 2 ms, as the
car), and of the rigid twin.  Ratios are against ``corners4`` measured in the same run.

``python -m bench.bench_mounts`` prints the figures as JSON.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
BAND = 30.0
CB_RATIO = 1.5
CC_CUTS = (200.0, 400.0, 800.0)
#: interfaces carrying the spring-dampers of the time-step cost run
TIMING_SUPPORTS = {
    "corners": ["fl", "fr", "rl", "rr"],
    "mounts": ["front_spring_upper_l", "front_spring_upper_r", "rear_spring_upper_l",
               "rear_spring_upper_r"],
}
SUPPORT = [("front_lower_arm_front_l", (0, 1, 2)), ("rear_lateral_link_inner_l", (1, 2)),
           ("front_lower_arm_front_r", (2,))]


def _mount_interfaces(fe, dofs):
    import flexpipe
    from flexpipe.vehicle.mounts import read_hardpoints

    hp = read_hardpoints(ROOT / "meshes" / "sedan_biw.bdf")
    return [flexpipe.Interface(p, name=n, dofs=dofs) for n, p in hp.items()
            if n.startswith(("front_", "rear_"))]


def _case(fe, itfs, f_full, *, interface_f_max=None, G_full=None, cb_ratio=CB_RATIO,
          timing=None):
    import flexpipe
    from flexpipe.reduction.verify import block_errors, supported_flexibility_reduced

    t = time.perf_counter()
    body = flexpipe.reduce(fe, itfs, f_max=BAND, cb_factor=cb_ratio,
                           interface_f_max=interface_f_max)
    seconds = time.perf_counter() - t
    f = body.frequencies_hz[6:]
    below = f_full[6:] <= BAND
    k = int(below.sum())
    out = {"reduce_s": round(seconds, 2), "elastic_modes": body.n_elastic,
           "constraint_modes": body.meta["n_constraint_modes"],
           "inertia_vectors": body.meta["n_inertia_vectors"],
           "boundary_dof": body.meta["n_boundary_dof"],
           "max_freq_error_below_band": float(np.max(f[:k] / f_full[6:6 + k] - 1))}
    if timing is not None:
        from flexpipe.exu.timing import step_cost

        out["exudyn_cpu_s_per_s"] = round(step_cost(body, timing), 4)
    if G_full is not None:
        G = supported_flexibility_reduced(body, SUPPORT)
        skip = (list(body.interface_names).index(SUPPORT[0][0]),)
        e = block_errors(G, G_full, skip=skip)
        out["static_error_max"] = float(e.max())
        out["static_error_median"] = float(np.median(e))
        if interface_f_max is not None:
            C = np.zeros_like(G)
            for i, itf in enumerate(body.interfaces):
                C[3 * i:3 * i + 3, 3 * i:3 * i + 3] = itf.residual_compliance[:3, :3]
            e = block_errors(G + C, G_full, skip=skip)
            out["static_error_max_series"] = float(e.max())
            out["static_error_median_series"] = float(np.median(e))
    return out


def run() -> dict:
    """Reduce the sample body with 4 and 30 interfaces; return the figures."""
    import warnings

    from flexpipe.reduction.cms import DependentColumnsWarning
    from flexpipe.reduction.verify import full_frequencies, supported_flexibility_full
    from flexpipe.vehicle.bodymodel import body_fe, corner_interfaces
    from flexpipe.vehicle.spec import load_car

    warnings.simplefilter("ignore", DependentColumnsWarning)
    car = load_car(ROOT / "cars" / "sedan.toml")
    fe = body_fe(car)
    res = {"dof": int(fe.n_dof)}
    corners = corner_interfaces(car, fe.nodes)
    res["corners4"] = _case(fe, corners, full_frequencies(fe, corners, 16),
                            timing=TIMING_SUPPORTS["corners"])
    m3 = _mount_interfaces(fe, 3)
    f_full = full_frequencies(fe, m3, 16)  # node mounts: the unreduced body itself
    G_full = supported_flexibility_full(fe, m3, SUPPORT)
    tm = TIMING_SUPPORTS["mounts"]
    res["m30x6"] = _case(fe, _mount_interfaces(fe, 6), f_full, G_full=G_full)
    res["m30x3"] = _case(fe, m3, f_full, G_full=G_full, timing=tm)
    for cut in CC_CUTS:
        res[f"m30x3_cc{cut:g}"] = _case(fe, m3, f_full, interface_f_max=cut, G_full=G_full,
                                        timing=tm)
    res["corners4_cb3"] = _case(fe, corners, full_frequencies(fe, corners, 16), cb_ratio=3.0)
    res["m30x3_cb3"] = _case(fe, m3, f_full, G_full=G_full, cb_ratio=3.0)
    from flexpipe.exu.timing import step_cost
    from flexpipe.reduction import reduce

    body4 = reduce(fe, corners, f_max=BAND, cb_factor=CB_RATIO)
    res["rigid_twin_exudyn_cpu_s_per_s"] = round(
        step_cost(body4, TIMING_SUPPORTS["corners"], rigid=True), 4)
    base = res["corners4"]
    for key, r in res.items():
        if isinstance(r, dict) and key != "corners4":
            r["time_ratio_vs_corners4"] = round(r["reduce_s"] / base["reduce_s"], 2)
            r["mode_ratio_vs_corners4"] = round(r["elastic_modes"] / base["elastic_modes"], 2)
            if "exudyn_cpu_s_per_s" in r:
                r["exudyn_cpu_ratio_vs_corners4"] = round(
                    r["exudyn_cpu_s_per_s"] / base["exudyn_cpu_s_per_s"], 2)
    return res


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    print(json.dumps(run(), indent=2))
