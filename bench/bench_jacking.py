"""Braking pitch of the linkage car: each corner's jacking force against the K&C geometry.

A corner's jacking force in a steady braking run is ``J = dFz - k_w ds``: the change of
its tyre load less what its wheel rate ``k_w`` (the time runs' joints-rigid rate,
:func:`flexpipe.vehicle.suspension.statics.corner_figures`) carries over the change of
travel ``ds``, against a coasting run.  The K&C rig's contact-patch path ``dP/ds`` says
what the patch forces should give by virtual work: ``-(dFx dPx + dFy dPy) / dPz``.  The
sample brakes with 1,500 N m on one axle at a time (rigid body, flat road, from 25 m/s,
means over 1.2-2.5 s): the braked axle shows the anti-dive / anti-lift of its patch path
(``dFx`` term), and the front, whatever axle brakes, the jacking of the lateral tyre
forces its bump steer builds as the body pitches (``dFy`` term).  Then front drive with
the torque reacted on the knuckle (in-wheel motor: the patch path) and on the body
(driveshafts: the longitudinal force reaches the knuckle at the wheel centre, so its
path); the change between the two is what ``tests/test_drive_reaction.py`` checks.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flexpipe.driver import OpenLoopTorque
from flexpipe.vehicle import bodymodel, load_car, simulate
from flexpipe.vehicle.simulation import default_driver
from flexpipe.vehicle.suspension.kinematics import Linkage, solve_kinematics
from flexpipe.vehicle.suspension.metrics import rates
from flexpipe.vehicle.suspension.statics import (
    corner_figures,
    kinematic_corner,
    rig_corner,
    rig_suspension,
)

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan_linkage.toml"
T_END, T_FROM, TORQUE = 2.5, 1.2, -1500.0


def _run(share: float, torque: float, reaction: str = "body") -> dict:
    car = load_car(CAR, overrides={"drive.brake_front_share": share,
                                   "drive.drive_reaction": reaction})
    steer, _ = default_driver(car, bodymodel.rigid_properties(car).mass)
    speed = OpenLoopTorque.from_table([0.0], [torque])  # the total wheel torque, held
    r = simulate(car, speed=25.0, t_end=T_END, body="rigid", driver=(steer, speed))
    if r.status != 0:
        raise RuntimeError(r.message)
    sel = r.t > T_FROM
    return {k: float(r[k][sel].mean()) for k in r.channels}


def run() -> dict:
    """Run the study; returns a flat dict of figures (N)."""
    susp = rig_suspension(load_car(CAR).suspension)
    geo = {}
    for axle, corner in (("front", "fl"), ("rear", "rl")):
        a = susp.axles[axle]
        c = kinematic_corner(rig_corner(a, a.left))
        lk = Linkage(c)
        rt = rates(lk, solve_kinematics(lk, 0.0))
        geo[corner] = (rt["patch_velocity"], corner_figures(c)["wheel rate, joints rigid [N/m]"],
                       rt["wheel_center_velocity"])
    coast = _run(0.65, 0.0)
    out = {}
    for share, tag in ((1.0, "front_braked"), (0.0, "rear_braked")):
        o = _run(share, TORQUE)
        for corner, (v, k_w, _) in geo.items():
            dfz, ds, dfx, dfy = (o[k.format(c=corner)] - coast[k.format(c=corner)]
                                 for k in ("tire_{c}_Fz", "travel_{c}", "tire_{c}_Fx",
                                           "tire_{c}_Fy"))
            jack = dfz - k_w * ds
            jx, jy = -dfx * v[0] / v[2], -dfy * v[1] / v[2]
            key = f"{tag}_{corner}"
            out.update({f"{key}_jacking_N": round(jack, 1), f"{key}_patch_x_N": round(jx, 1),
                        f"{key}_patch_y_N": round(jy, 1), f"{key}_dFy_N": round(dfy, 1)})
            print(f"{tag:12s} {corner}: jacking {jack:7.1f} N; patch path: Fx {jx:7.1f} N, "
                  f"Fy {jy:7.1f} N (dFy {dfy:6.1f} N), sum {jx + jy:7.1f} N", flush=True)
    # front drive (+1,500 N m), reacted on the knuckle (in-wheel motor: the patch path
    # carries dFx) or on the body (driveshafts: the wheel-centre path)
    v, k_w, vc = geo["fl"]
    for reaction in ("knuckle", "body"):
        o = _run(0.65, -TORQUE, reaction)
        dfz, ds, dfx, dfy = (o[k] - coast[k] for k in ("tire_fl_Fz", "travel_fl",
                                                        "tire_fl_Fx", "tire_fl_Fy"))
        jack = dfz - k_w * ds
        jx = -dfx * (v[0] if reaction == "knuckle" else vc[0]) / v[2]
        jy = -dfy * v[1] / v[2]
        key = f"front_driven_{reaction}_fl"
        out.update({f"{key}_jacking_N": round(jack, 1), f"{key}_path_x_N": round(jx, 1),
                    f"{key}_patch_y_N": round(jy, 1), f"{key}_travel_mm": round(ds * 1e3, 2)})
        print(f"front drive, reacted on the {reaction:7s} fl: jacking {jack:7.1f} N; "
              f"{'patch' if reaction == 'knuckle' else 'wheel-centre'} path Fx {jx:7.1f} N, "
              f"patch Fy {jy:7.1f} N, sum {jx + jy:7.1f} N; travel {ds * 1e3:6.2f} mm",
              flush=True)
    out["front_patch_dy_ds"] = round(float(geo["fl"][0][1] / geo["fl"][0][2]), 4)
    out["front_side_view_angle_deg"] = round(float(np.degrees(np.arctan2(*geo["fl"][0][::2]))), 3)
    return out


if __name__ == "__main__":
    run()
