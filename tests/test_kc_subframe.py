"""The K&C rig with a subframe on bushings (the half-axle model of
:mod:`flexpipe.vehicle.suspension.carrier`).

References: closed forms of a rigid subframe on springs carrying the whole corner (its
translation, pitch and roll under the rig's loads, from the bushing rates written here),
and the limit of a subframe on very stiff bushings, which must give the rig without one.
"""

from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import ModelError
from flexpipe.vehicle import load_car
from flexpipe.vehicle.mounted import MountedBody
from flexpipe.vehicle.suspension.carrier import half_carrier, with_subframes
from flexpipe.vehicle.suspension.kc import kc
from flexpipe.vehicle.suspension.kinematics import Linkage, rotvec, solve_compliance
from flexpipe.vehicle.suspension.model import Bushing
from flexpipe.vehicle.suspension.statics import rig_corner, rig_suspension
from tests.test_subframe import car_file

ROOT = Path(__file__).resolve().parents[1]
CAR = load_car(ROOT / "cars" / "sedan_linkage.toml")
SUSP = CAR.suspension
FRONT = SUSP.axles["front"]
#: every front mount: the corners, the rack housing, the anti-roll bar's bearings
ALL_FRONT = sorted(set(FRONT.left.mounts) | set(FRONT.right.mounts) | set(FRONT.rack.mounts)
                   | set(dict(FRONT.anti_roll_bar.mounts)))
#: four mounts in one horizontal plane through the subframe's reference point
POINTS = np.array([[0.35, 0.442, 0.2], [0.35, -0.442, 0.2], [-0.5, 0.45, 0.2],
                   [-0.5, -0.45, 0.2]])
HARD, K_SOFT = 1e12, 2e6


def _subframe(k, *, points=POINTS, carries=ALL_FRONT, bushings=None):
    return MountedBody(20.0, np.array([-0.05, 0.0, 0.2]), np.diag([1.5, 0.8, 2.2]),
                       tuple(f"m{i}" for i in range(len(points))), points,
                       bushings or tuple(Bushing(k) for _ in points), name="subframe.front",
                       carries=tuple(carries))


@pytest.fixture(scope="module")
def reference():
    return kc(SUSP, axles=["front"], n=5)


def test_stiff_subframe_is_the_rig_without_one(reference):
    """Bushings of 1e12 N/m and 1e10 N m/rad (which still give way by about 1e-6 mm under
    the rig's 2 kN): every table within 1e-5 of its scale (mm, deg, N) and every summary
    figure within 1e-6 of the rig whose mounts sit on the body."""
    res = kc(with_subframes(SUSP, [_subframe([HARD] * 3 + [1e10] * 3)]), axles=["front"], n=5)
    for name, ref in reference.tables.items():
        got = res.tables[name]
        for col in ref.columns:
            scale = max(1.0, float(np.max(np.abs(ref[col]))))
            np.testing.assert_allclose(got[col], ref[col], rtol=0, atol=1e-5 * scale,
                                       err_msg=f"{name}: {col}")
    for key, value in reference.summary["front"].items():
        if isinstance(value, float):
            assert res.summary["front"][key] == pytest.approx(value, rel=1e-6, abs=1e-9), key


@pytest.mark.parametrize("direction", [0, 1])
def test_soft_subframe_adds_its_translation_to_the_force_compliance(reference, direction):
    """A subframe carrying the whole front axle on bushings soft only along the force
    (2e6 N/m each, four of them): under the rig's force F on both contact patches it
    translates by 2F / (4 k), the corner with it, so the wheel centre moves that much
    more and toe and camber do not change."""
    k = [HARD, HARD, HARD, 1e10, 1e10, 1e10]
    k[direction] = K_SOFT
    res = kc(with_subframes(SUSP, [_subframe(k)]), axles=["front"], n=5)
    name = "front_longitudinal_force" if direction == 0 else "front_lateral_force"
    col = "wheel center dx [mm]" if direction == 0 else "wheel center dy [mm]"
    ref, got = reference.tables[name], res.tables[name]
    F = ref["force [N]"]
    np.testing.assert_allclose(got[col] - ref[col], 2 * F / (4 * K_SOFT) * 1e3, rtol=0,
                               atol=1e-5)   # mm, of up to 0.5 mm
    for angle in ("toe [deg]", "camber [deg]"):
        np.testing.assert_allclose(got[angle], ref[angle], rtol=0, atol=1e-5)


def _unloaded(susp):
    """``susp`` whose front springs are free at the design position (no preload): the rig's
    static state is then unloaded, and the subframe's response linear."""
    from dataclasses import replace

    a = susp.axles["front"]
    free = [replace(c, forces=tuple(replace(f, free_length=None) if f.kind == "spring" else f
                                    for f in c.forces)) for c in (a.left, a.right)]
    return replace(susp, axles={**susp.axles, "front": replace(
        a, left=free[0], right=free[1], wheel_load=None)})


def test_soft_subframe_heave_and_roll_closed_forms():
    """Bushings soft only vertically (kz = 2e6 N/m), in one plane, springs unloaded: the
    subframe under the rig's vertical wheel-centre force F moves there by
    F (1/(2 kz) + e^2 / K_pitch) per wheel in parallel travel (e: wheel centre ahead of the
    mounts' centre, K_pitch = sum kz (x - x_c)^2 of one side) and by 2 y_w^2 / (sum kz y^2)
    in opposite travel (the roll under the axle's couple), and the wheel rate and the roll
    stiffness (its wheel-rate part) fall by that compliance in series, within 1e-4 each
    (measured 2e-8 to 1.2e-6).
    (With the sample's preload the subframe first sags and rolls statically, 0.9 mm and
    3.5 mrad, which moves the same figures by up to 3 %.)"""
    base = _unloaded(SUSP)
    sf = _subframe([1e10, 1e10, K_SOFT, 0.0, 0.0, 0.0])   # 1e12 is beyond the solver's
    # force tolerance in an unloaded rig (1e-7 N against round-off of 1e12 N/m x 1e-16 m)
    susp = rig_suspension(with_subframes(base, [sf]))
    axle = susp.axles["front"]
    c, carrier = rig_corner(axle, axle.left), half_carrier(axle)
    w = c.wheel_center
    side = POINTS[POINTS[:, 1] > 0]
    x_c = side[:, 0].mean()
    heave = 1 / (2 * K_SOFT) + (w[0] - x_c) ** 2 / (K_SOFT * np.sum((side[:, 0] - x_c) ** 2))
    roll = 2 * w[1] ** 2 / (K_SOFT * np.sum(POINTS[:, 1] ** 2))
    for mode, closed in (("symmetric", heave), ("antisymmetric", roll)):
        lk = Linkage(c, carrier=carrier, mode=mode)
        lo, hi = (solve_compliance(lk, s) for s in (-5e-4, 5e-4))
        k = lk.idx["subframe"]
        move = (hi.r[k] - lo.r[k]) + np.cross(rotvec(hi.R[k]) - rotvec(lo.R[k]),
                                              w - carrier.cm)
        assert move[2] / (hi.force - lo.force) == pytest.approx(closed, rel=1e-4), mode
    ref = kc(base, axles=["front"], n=5).summary["front"]
    got = kc(with_subframes(base, [sf]), axles=["front"], n=5).summary["front"]
    key = "wheel rate incl. compliance [N/m]"
    assert 1 / got[key] - 1 / ref[key] == pytest.approx(heave, rel=1e-4)
    to_rate = (2 * w[1]) ** 2 / 2 * np.pi / 180   # roll stiffness (N m/deg) per N/m
    k_bar = ref["roll stiffness [N m/deg]"] / to_rate - ref[key]
    k_roll = got["roll stiffness [N m/deg]"] / to_rate - k_bar
    assert 1 / k_roll - 1 / ref[key] == pytest.approx(roll, rel=1e-4)


def test_subframe_must_be_mirror_symmetric():
    bush = (Bushing([2e6] * 3 + [2e3] * 3), Bushing([3e6] * 3 + [2e3] * 3),
            Bushing([2e6] * 3 + [2e3] * 3), Bushing([2e6] * 3 + [2e3] * 3))
    with pytest.raises(ModelError, match=r"mount 'm0'.*'m1' at its mirror point has other rates"):
        kc(with_subframes(SUSP, [_subframe(None, bushings=bush)]), axles=["front"], n=5)
    points = POINTS.copy()
    points[1, 0] = 0.3
    with pytest.raises(ModelError, match=r"no mount at its mirror point"):
        kc(with_subframes(SUSP, [_subframe([2e6] * 6, points=points)]), axles=["front"], n=5)
    with pytest.raises(ModelError, match=r"one subframe per axle"):
        with_subframes(SUSP, [_subframe([2e6] * 6, carries=ALL_FRONT[:3]),
                              _subframe([2e6] * 6, carries=ALL_FRONT[3:])])


def test_kc_of_a_car_file_includes_its_subframe(tmp_path, reference):
    """``flexpipe kc`` on a car file with the docs' front cradle (lower arms, rack and bar
    on four 2e6 N/m bushings): its lateral and longitudinal compliance grow; a subframe
    carrying no front mount leaves the front axle as it was."""
    res = kc(car_file(tmp_path), axles=["front"], n=5)
    assert res.subframes == {"front": "subframe.front"} and \
        reference.subframes == {"front": None}
    ref, got = reference.summary["front"], res.summary["front"]
    assert got["longitudinal wheel centre compliance [mm/kN]"] > \
        ref["longitudinal wheel centre compliance [mm/kN]"] + 0.05
    lat = res.tables["front_lateral_force"]["wheel center dy [mm]"]
    lat0 = reference.tables["front_lateral_force"]["wheel center dy [mm]"]
    assert np.ptp(lat) > np.ptp(lat0) + 0.1
