"""Where the drive torque is reacted: the body (driveshafts) or the knuckle (in-wheel motors).

References: conservation (the reaction is internal to the car: the tyre loads and the
car's motion cannot depend on where it goes when the wheel carrier cannot rotate
against the body, as on the prismatic corners); virtual work on a linkage corner (the
longitudinal tyre force reaches the knuckle at the contact patch when the wheel's torque
is reacted there, at the wheel centre when a driveshaft takes it: the jacking force
``-dFx dx/ds / (dz_patch/ds)`` uses the patch path or the wheel-centre path of the K&C
rig, a solution of the same hardpoints by another method).
"""

from pathlib import Path

import numpy as np
import pytest

from flexpipe.driver import OpenLoopTorque
from flexpipe.errors import InputError
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
SEDAN = ROOT / "cars" / "sedan.toml"
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"


def _run(path, torque, reaction, *, t_end=2.5):
    car = load_car(path, overrides={"drive.drive_reaction": reaction})
    steer, _ = default_driver(car, bodymodel.rigid_properties(car).mass)
    speed = OpenLoopTorque.from_table([0.0], [torque])  # the total wheel torque, held
    r = simulate(car, speed=15.0, t_end=t_end, body="rigid", driver=(steer, speed),
                 output_step=0.01)
    assert r.status == 0, r.message
    return r


def test_prismatic_corners_do_not_care_where_the_torque_is_reacted():
    a, b = (_run(SEDAN, 1500.0, m, t_end=1.5) for m in ("knuckle", "body"))
    for k in ("hub_fl_x", "hub_fl_z", "hub_rr_x", "tire_fl_Fx", "tire_fl_Fz", "pitch"):
        scale = max(np.abs(a[k]).max(), 1e-9)
        assert np.abs(a[k] - b[k]).max() <= 1e-3 * scale, k  # the solver's tolerance


def test_linkage_corner_takes_the_force_at_the_patch_or_the_wheel_centre():
    susp = rig_suspension(load_car(LINKAGE).suspension)
    axle = susp.axles["front"]
    corner = kinematic_corner(rig_corner(axle, axle.left))
    lk = Linkage(corner)
    rt = rates(lk, solve_kinematics(lk, 0.0))
    v_patch, v_centre = rt["patch_velocity"], rt["wheel_center_velocity"]
    k_w = corner_figures(corner)["wheel rate, joints rigid [N/m]"]
    coast = _run(LINKAGE, 0.0, "body")
    sel = coast.t > 1.2

    def jacking(r):
        dfz = r["tire_fl_Fz"][sel].mean() - coast["tire_fl_Fz"][sel].mean()
        ds = r["travel_fl"][sel].mean() - coast["travel_fl"][sel].mean()
        return dfz - k_w * ds, r["tire_fl_Fx"][sel].mean() - coast["tire_fl_Fx"][sel].mean(), \
            r["tire_fl_Fy"][sel].mean() - coast["tire_fl_Fy"][sel].mean()

    knuckle, body = _run(LINKAGE, 1500.0, "knuckle"), _run(LINKAGE, 1500.0, "body")
    (j_k, fx_k, fy_k), (j_b, fx_b, fy_b) = jacking(knuckle), jacking(body)
    # the tyre loads are the car's, wherever the torque goes (front axle, steady state)
    front = [r["tire_fl_Fz"][sel].mean() + r["tire_fr_Fz"][sel].mean() for r in (knuckle, body)]
    assert front[1] == pytest.approx(front[0], rel=5e-3)
    # what moving the reaction changes: the longitudinal force's lever, patch -> centre
    # path (and the lateral force's, through the bump steer of the other travel)
    predicted = (-fx_b * v_centre[0] - fy_b * v_patch[1]) / v_patch[2] \
        - (-fx_k * v_patch[0] - fy_k * v_patch[1]) / v_patch[2]
    assert abs(predicted) > 50.0  # N: a difference the test can see
    assert j_b - j_k == pytest.approx(predicted, rel=0.15)


def test_bad_reaction_is_named():
    with pytest.raises(InputError, match=r"drive\.drive_reaction.*'body', 'knuckle'|"
                                         r"drive\.drive_reaction.*body, knuckle") as exc:
        load_car(LINKAGE, overrides={"drive.drive_reaction": "hub"})
    assert str(LINKAGE) in str(exc.value)
