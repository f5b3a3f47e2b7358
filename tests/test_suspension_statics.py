"""Closed-form checks of the suspension statics on a parallelogram double wishbone.

Equal, parallel, horizontal arms (lower arm b = 0.5 m, pivot axis along x) and a tie rod of
the same length parallel to them: the knuckle translates on a circle, so camber and toe stay
exactly zero, the wheel centre moves in y by sqrt(b^2 - s^2) - b, and a vertical spring seat
at a = 0.3 m from the pivot axis has the lever-rule motion ratio a / b at design.
"""

from __future__ import annotations

import numpy as np
import pytest

from flexpipe.vehicle.suspension.kinematics import Linkage, solve_compliance, solve_kinematics
from flexpipe.vehicle.suspension.metrics import characteristics, rates, roll_centre
from flexpipe.vehicle.suspension.model import Bushing
from flexpipe.vehicle.suspension.statics import spring_preload, wheel_rate, with_preload
from flexpipe.vehicle.suspension.templates import build

B, A, K = 0.5, 0.3, 40000.0
HP = {"lower_arm_front": (0.2, 0.3, 0.15), "lower_arm_rear": (-0.2, 0.3, 0.15),
      "lower_arm_outer": (0.0, 0.8, 0.15), "upper_arm_front": (0.15, 0.4, 0.55),
      "upper_arm_rear": (-0.15, 0.4, 0.55), "upper_arm_outer": (0.0, 0.9, 0.55),
      "tie_rod_inner": (-0.2, 0.35, 0.35), "tie_rod_outer": (-0.2, 0.85, 0.35),
      "spring_upper": (0.0, 0.6, 0.50), "spring_lower": (0.0, 0.6, 0.15),
      "damper_upper": (0.0, 0.6, 0.50), "damper_lower": (0.0, 0.6, 0.15),
      "wheel_center": (0.0, 0.95, 0.35)}
SPRING = {"spring": {"rate": K}}


def corner(**kw):
    return build("double_wishbone", HP, wheel_radius=0.3, forces=SPRING, **kw)


def test_parallelogram_no_camber_or_toe_change_and_circular_path():
    lk = Linkage(corner())
    pose = None
    for s in np.linspace(-0.08, 0.08, 9):
        pose = solve_kinematics(lk, s, pose=pose)
        ch = characteristics(lk, pose)
        assert abs(ch["toe"]) < 1e-8 and abs(ch["camber"]) < 1e-8
        assert ch["wheel_center"][1] - 0.95 == pytest.approx(np.sqrt(B**2 - s**2) - B,
                                                           abs=1e-10)
        # roll-centre line through the patch perpendicular to its path: z = z_p + y_p tan
        r = rates(lk, pose)
        p = ch["contact_patch"]
        alpha = np.arcsin(s / B)
        assert roll_centre(r["patch"], r["patch_velocity"])[1] == pytest.approx(
            p[2] - p[1] * np.tan(alpha), abs=1e-9)


def test_motion_ratio_is_the_lever_rule():
    lk = Linkage(corner())
    assert rates(lk, solve_kinematics(lk, 0.0))["spring_mr"] == pytest.approx(A / B, abs=1e-12)


def test_wheel_rate_is_spring_rate_times_mr_squared_plus_bushing_torsion():
    assert wheel_rate(corner()) == pytest.approx(K * (A / B) ** 2, rel=1e-6)
    kt = 150.0  # N m/rad about the pivot axis (x), translations very stiff
    bush = Bushing([1e10, 1e10, 1e10, kt, 0.0, 0.0])
    c = corner(bushings={"lower_arm_front": bush, "lower_arm_rear": bush,
                         "upper_arm_front": bush, "upper_arm_rear": bush})
    expected = K * (A / B) ** 2 + 4 * kt / B**2  # four bushings each turn by s / b
    assert wheel_rate(c) == pytest.approx(expected, rel=1e-5)


def test_joints_rigid_wheel_rate_leaves_the_bushings_out():
    """The time runs' kinematic mode: the same bushed corner's rate without the bushing
    torsion, i.e. the lever rule K (a/b)^2 (flexpipe info's "joints rigid" figure)."""
    from flexpipe.vehicle.suspension.statics import corner_figures

    bush = Bushing([1e10, 1e10, 1e10, 150.0, 0.0, 0.0])
    c = corner(bushings={"lower_arm_front": bush, "lower_arm_rear": bush,
                         "upper_arm_front": bush, "upper_arm_rear": bush})
    fig = corner_figures(c)
    assert fig["wheel rate, joints rigid [N/m]"] == pytest.approx(K * (A / B) ** 2, rel=1e-6)
    assert fig["wheel rate incl. compliance [N/m]"] == pytest.approx(
        K * (A / B) ** 2 + 4 * 150.0 / B**2, rel=1e-5)


def test_preload_times_mr_is_wheel_load_minus_part_weights():
    m_knuckle, m_lower, m_upper, g = 12.0, 3.0, 2.0, 9.81
    parts = {"knuckle": {"mass": m_knuckle, "cm": (0.0, 0.9, 0.35)},
             "lower_arm": {"mass": m_lower, "cm": (0.0, 0.5, 0.15)},   # 0.2 m from its axis
             "upper_arm": {"mass": m_upper, "cm": (0.0, 0.65, 0.55)}}  # 0.25 m
    c = corner(parts=parts)
    load = 3500.0
    p = spring_preload(c, load)
    weights = g * (m_knuckle + m_lower * 0.2 / B + m_upper * 0.25 / B)
    assert p * A / B == pytest.approx(load - weights, rel=1e-10)
    # the equilibrium (compliance) solve with that preload and gravity needs the wheel load
    lk = Linkage(with_preload(c, p))
    assert solve_compliance(lk, 0.0, gravity=True).force == pytest.approx(load, rel=1e-8)


def test_macpherson_strut_top_bushing_keeps_the_strut_sliding():
    """A strut-top bushing stiff across the strut and free in rotation must leave the
    wheel rate at the kinematic k MR^2 (the strut still slides in its tube)."""
    hp = {"lower_arm_front": (0.22, 0.52, -0.156), "lower_arm_rear": (-0.30, 0.507, -0.137),
          "lower_arm_outer": (-0.0217, 0.9406, -0.1740), "strut_top": (-0.115, 0.785, 0.579),
          "strut_lower": (-0.0740, 0.8533, 0.2485), "tie_rod_inner": (-0.30, 0.52, -0.059),
          "tie_rod_outer": (-0.2374, 0.8950, -0.0161), "spring_upper": (-0.115, 0.785, 0.579),
          "spring_lower": (-0.0740, 0.8533, 0.2485), "damper_upper": (-0.115, 0.785, 0.579),
          "damper_lower": (-0.0740, 0.8533, 0.2485), "wheel_center": (-0.04, 1.10, -0.026)}
    kw = dict(wheel_radius=0.3, forces={"spring": {"rate": K}})
    rigid = build("macpherson", hp, **kw)
    lk = Linkage(rigid)
    mr = rates(lk, solve_kinematics(lk, 0.0))["spring_mr"]
    assert wheel_rate(rigid) == pytest.approx(K * mr**2, rel=1e-6)
    bush = Bushing([1e10, 1e10, 1e10, 0.0, 0.0, 0.0])
    soft = build("macpherson", hp, bushings={"strut_top": bush}, **kw)
    assert wheel_rate(soft) == pytest.approx(K * mr**2, rel=1e-5)
