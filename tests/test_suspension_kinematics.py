"""K&C kinematics vs an independent loop closure of the same hardpoints.

The reference solutions below parametrise each linkage differently from flexpipe's solver
(6-DOF part poses, Newton on joint equations): the double wishbone by its two arm angles and
the tie-rod ball position, the MacPherson strut by the lower-arm angle and the strut length,
the multi-link by the upper-arm angle and the knuckle's rotation vector; each is closed with
scipy.optimize.least_squares and rotations from scipy.spatial.transform.
"""

from __future__ import annotations

import numpy as np
import pytest
from _suspdata import (
    SEDAN_FRONT,
    SEDAN_REAR,
    SEDAN_REAR_UNIVERSAL,
    chrono_double_wishbone,
    chrono_macpherson,
    chrono_multi_link,
)
from scipy.optimize import least_squares
from scipy.spatial.transform import Rotation

from flexpipe.vehicle.suspension.kinematics import Linkage, solve_kinematics
from flexpipe.vehicle.suspension.metrics import characteristics
from flexpipe.vehicle.suspension.model import mirror_corner
from flexpipe.vehicle.suspension.templates import build

TRAVEL = np.linspace(-0.08, 0.08, 9)


def _hp(d):
    return {k: np.asarray(v, float) for k, v in d.items()}


def _about(axis_a, axis_b, p, angle):
    """``p`` turned by ``angle`` about the line through axis_a and axis_b."""
    u = (axis_b - axis_a) / np.linalg.norm(axis_b - axis_a)
    return axis_a + Rotation.from_rotvec(angle * u).apply(p - axis_a)


def _frame(p0, p1, p2):
    e1 = (p1 - p0) / np.linalg.norm(p1 - p0)
    e2 = p2 - p0 - ((p2 - p0) @ e1) * e1
    e2 /= np.linalg.norm(e2)
    return np.column_stack([e1, e2, np.cross(e1, e2)])


def _reference_angles(spin, lower, upper):
    """Camber/toe/caster (deg) written out independently of flexpipe.metrics."""
    camber = np.degrees(np.arcsin(-spin[2] / np.linalg.norm(spin)))
    toe = np.degrees(np.arctan(spin[0] / spin[1]))
    k = upper - lower
    caster = np.degrees(np.arctan(-k[0] / k[2]))
    return camber, toe, caster


def dw_reference(hp, s):
    """Double wishbone closed by arm angles (a, b) and the tie-rod ball position."""
    LF, LR, LO = hp["lower_arm_front"], hp["lower_arm_rear"], hp["lower_arm_outer"]
    UF, UR, UO = hp["upper_arm_front"], hp["upper_arm_rear"], hp["upper_arm_outer"]
    TI, TO, W0 = hp["tie_rod_inner"], hp["tie_rod_outer"], hp["wheel_center"]
    d_lu, d_lt, d_ut, d_tr = (np.linalg.norm(LO - UO), np.linalg.norm(LO - TO),
                              np.linalg.norm(UO - TO), np.linalg.norm(TO - TI))
    F0 = _frame(LO, UO, TO)

    def pose(x):
        lo, uo, to = _about(LF, LR, LO, x[0]), _about(UF, UR, UO, x[1]), x[2:5]
        R = _frame(lo, uo, to) @ F0.T
        return lo, uo, to, R

    def res(x):
        lo, uo, to, R = pose(x)
        w = lo + R @ (W0 - LO)
        return [np.linalg.norm(lo - uo) - d_lu, np.linalg.norm(lo - to) - d_lt,
                np.linalg.norm(uo - to) - d_ut, np.linalg.norm(to - TI) - d_tr,
                w[2] - W0[2] - s]

    x = least_squares(res, np.r_[0.0, 0.0, TO], xtol=1e-15, ftol=1e-15, gtol=1e-15).x
    lo, uo, to, R = pose(x)
    return lo + R @ (W0 - LO), R @ [0, 1.0, 0], lo, uo


def mp_reference(hp, s):
    """MacPherson closed by the lower-arm angle, the strut length and the tie-rod ball."""
    LF, LR, LO = hp["lower_arm_front"], hp["lower_arm_rear"], hp["lower_arm_outer"]
    T, SL = hp["strut_top"], hp["strut_lower"]
    TI, TO, W0 = hp["tie_rod_inner"], hp["tie_rod_outer"], hp["wheel_center"]
    u = (T - SL) / np.linalg.norm(T - SL)
    d_lt, d_tr = np.linalg.norm(LO - TO), np.linalg.norm(TO - TI)
    d_st = np.linalg.norm(T - TO)

    def pose(x):
        lo, length, to = _about(LF, LR, LO, x[0]), x[1], x[2:5]
        top_local = SL + length * u  # the knuckle point at the strut top
        R = _frame(lo, T, to) @ _frame(LO, top_local, TO).T
        return lo, to, R, top_local

    def res(x):
        lo, to, R, top_local = pose(x)
        w = lo + R @ (W0 - LO)
        return [np.linalg.norm(T - lo) - np.linalg.norm(top_local - LO),
                np.linalg.norm(lo - to) - d_lt,
                np.linalg.norm(to - T) - np.linalg.norm(TO - top_local),
                np.linalg.norm(to - TI) - d_tr, w[2] - W0[2] - s]

    del d_st
    x = least_squares(res, np.r_[0.0, np.linalg.norm(T - SL), TO], xtol=1e-15, ftol=1e-15,
                      gtol=1e-15).x
    lo, to, R, _ = pose(x)
    return lo + R @ (W0 - LO), R @ [0, 1.0, 0], lo, T


def ml_reference(hp, s):
    """Multi-link closed by the upper-arm angle and the knuckle rotation vector."""
    UF, UR, UO = hp["upper_arm_front"], hp["upper_arm_rear"], hp["upper_arm_outer"]
    W0 = hp["wheel_center"]
    dist = [(hp[o], hp[i], np.linalg.norm(hp[o] - hp[i])) for o, i in (
        ("lateral_link_outer", "lateral_link_inner"), ("trailing_link_outer",
                                                       "trailing_link_front"),
        ("tie_rod_outer", "tie_rod_inner"))]

    def place(x, p):
        return _about(UF, UR, UO, x[0]) + Rotation.from_rotvec(x[1:4]).apply(p - UO)

    def res(x):
        return [np.linalg.norm(place(x, o) - i) - d for o, i, d in dist] + [
            place(x, W0)[2] - W0[2] - s]

    x = least_squares(res, np.zeros(4), xtol=1e-15, ftol=1e-15, gtol=1e-15).x
    R = Rotation.from_rotvec(x[1:4])
    return (place(x, W0), R.apply([0, 1.0, 0]), place(x, hp["trailing_link_outer"]),
            place(x, UO))


REFERENCE = {"double_wishbone": dw_reference, "macpherson": mp_reference,
             "multi_link": ml_reference}


def _compare(template, hp, **kw):
    corner = build(template, hp, wheel_radius=0.3, **kw)
    lk = Linkage(corner)
    pose, worst = None, np.zeros(4)
    for s in TRAVEL:
        pose = solve_kinematics(lk, s, pose=pose)
        ch = characteristics(lk, pose)
        w, spin, lo, up = REFERENCE[template](hp, s)
        ref = _reference_angles(spin, lo, up)
        got = (ch["camber"], ch["toe"], ch["caster"])
        worst[:3] = np.maximum(worst[:3], np.abs(np.subtract(got, ref)))
        worst[3] = max(worst[3], np.max(np.abs(ch["wheel_center"] - w)))
    assert worst[:3].max() < 0.01, f"angle error {worst[:3]} deg"
    assert worst[3] < 1e-4, f"wheel centre error {worst[3] * 1e3:.2e} mm"
    return worst


def test_double_wishbone_typed_sedan_front():
    w = _compare("double_wishbone", _hp(SEDAN_FRONT), steered=True)
    assert w[:3].max() < 1e-6 and w[3] < 1e-8  # both converge far below the tolerance


def test_multi_link_typed_sedan_rear():
    _compare("multi_link", _hp(SEDAN_REAR), universal_axes=SEDAN_REAR_UNIVERSAL)


def test_macpherson_typed():
    hp = {"lower_arm_front": (0.22, 0.52, -0.156), "lower_arm_rear": (-0.30, 0.507, -0.137),
          "lower_arm_outer": (-0.0217, 0.9406, -0.1740), "strut_top": (-0.115, 0.785, 0.579),
          "strut_lower": (-0.0740, 0.8533, 0.2485), "tie_rod_inner": (-0.30, 0.52, -0.059),
          "tie_rod_outer": (-0.2374, 0.8950, -0.0161), "spring_upper": (-0.115, 0.785, 0.579),
          "spring_lower": (-0.0740, 0.8533, 0.2485), "damper_upper": (-0.115, 0.785, 0.579),
          "damper_lower": (-0.0740, 0.8533, 0.2485), "wheel_center": (-0.04, 1.10, -0.026)}
    _compare("macpherson", _hp(hp), steered=True)


@pytest.mark.parametrize("template,loader", [
    ("double_wishbone", chrono_double_wishbone), ("macpherson", chrono_macpherson),
    ("multi_link", chrono_multi_link)])
def test_chrono_reference_files(template, loader):
    data = loader()
    if data is None:
        pytest.skip("../shared/reference/vehicle not present")
    kw = {}
    if template == "multi_link":
        data, axes = data
        kw["universal_axes"] = axes
    _compare(template, data, **kw)


def test_right_corner_is_the_mirror_image():
    left = build("double_wishbone", _hp(SEDAN_FRONT), wheel_radius=0.3, steered=True)
    right = mirror_corner(left, "fr")
    for s in (-0.06, 0.05):
        cl = characteristics(Linkage(left), solve_kinematics(Linkage(left), s))
        cr = characteristics(Linkage(right), solve_kinematics(Linkage(right), s))
        for k in ("camber", "toe", "caster", "kpi"):
            assert cr[k] == pytest.approx(cl[k], abs=1e-9)


def test_revolute_joint_equals_spherical_plus_inline_pivot():
    """The templates pivot arms by a spherical + in-line pair; a revolute joint about the
    same line must give the same motion."""
    from dataclasses import replace

    from flexpipe.vehicle.suspension.model import Joint

    left = build("double_wishbone", _hp(SEDAN_FRONT), wheel_radius=0.3, steered=True)
    joints = []
    for j in left.joints:
        if j.kind == "inline":
            continue
        if j.kind == "spherical" and "body" in (j.a, j.b):
            rear = j.name.replace("front", "rear")
            axis = left.hardpoints[rear] - j.point
            j = Joint(j.name, "revolute", j.a, j.b, j.point, axis=axis, mount=j.mount)
        joints.append(j)
    rev = replace(left, joints=tuple(joints))
    for s in (-0.07, 0.03, 0.08):
        a = characteristics(Linkage(left), solve_kinematics(Linkage(left), s))
        b = characteristics(Linkage(rev), solve_kinematics(Linkage(rev), s))
        for k in ("camber", "toe", "caster"):
            assert b[k] == pytest.approx(a[k], abs=1e-9)


def test_sample_car_file_matches_the_independent_closure():
    """The sample car file (Chrono's hardpoints + location_m) gives the same curves as the
    loop closures of the typed, already-placed hardpoints."""
    from pathlib import Path

    from flexpipe.vehicle.suspension.spec import load_suspension

    susp = load_suspension(Path(__file__).resolve().parents[1] / "cars" / "sedan_linkage.toml")
    for axle, hp, ref in (("front", SEDAN_FRONT, dw_reference),
                          ("rear", SEDAN_REAR, ml_reference)):
        lk = Linkage(susp.axles[axle].left)
        for s in (-0.08, 0.0, 0.05):
            ch = characteristics(lk, solve_kinematics(lk, s))
            w, spin, lo, up = ref(_hp(hp), s)
            assert np.allclose((ch["camber"], ch["toe"], ch["caster"]),
                               _reference_angles(spin, lo, up), atol=1e-6)
            assert np.allclose(ch["wheel_center"], w, atol=1e-7)
