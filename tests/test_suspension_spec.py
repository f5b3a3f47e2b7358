"""Suspension tables of the car file: the sample, and bad input named by file, line, key."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError, ModelError
from flexpipe.vehicle.suspension.kinematics import Linkage, solve_kinematics
from flexpipe.vehicle.suspension.spec import load_suspension
from flexpipe.vehicle.suspension.templates import build

SAMPLE = Path(__file__).resolve().parents[1] / "cars" / "sedan_linkage.toml"

# The body mounts the BIW mesh must carry (left side; right mirrored), as agreed with the
# body engineer: typed here from the task, not from the car file.
MOUNTS = {
    "front_lower_arm_front": (0.200, 0.420, 0.148), "front_lower_arm_rear": (-0.200, 0.470, 0.153),
    "front_upper_arm_front": (-0.100, 0.470, 0.523), "front_upper_arm_rear": (-0.250, 0.510, 0.528),
    "front_spring_upper": (-0.040, 0.520, 0.648), "front_rack_mount": (-0.200, 0.300, 0.298),
    "front_arb_bushing": (-0.150, 0.350, 0.220),
    "rear_upper_arm_front": (-2.690, 0.397, 0.383), "rear_upper_arm_rear": (-2.907, 0.358, 0.363),
    "rear_lateral_link_inner": (-2.714, 0.188, 0.168),
    "rear_trailing_link_front": (-2.027, 0.449, 0.229),
    "rear_tie_rod_inner": (-3.007, 0.170, 0.185), "rear_spring_upper": (-2.569, 0.491, 0.411),
    "rear_damper_upper": (-2.579, 0.478, 0.616), "rear_arb_bushing": (-2.950, 0.350, 0.250),
}


def test_sample_mounts_are_the_agreed_body_points():
    mounts = load_suspension(SAMPLE).mounts()
    expected = {}
    for k, p in MOUNTS.items():
        expected[k + "_l"] = np.array(p)
        expected[k + "_r"] = np.array(p) * [1, -1, 1]
    assert sorted(mounts) == sorted(expected)
    for k, p in expected.items():
        assert np.allclose(mounts[k], p, atol=5e-4), k


def _write(tmp_path, text):
    p = tmp_path / "car.toml"
    p.write_text(text)
    return p


def _sample_with(tmp_path, old, new):
    text = SAMPLE.read_text()
    assert old in text
    return _write(tmp_path, text.replace(old, new, 1))


def _line_of(path, needle):
    return next(i + 1 for i, s in enumerate(path.read_text().splitlines()) if needle in s)


def test_unknown_hardpoint_names_file_line_and_key(tmp_path):
    p = _sample_with(tmp_path, "upper_arm_outer = [-0.040", "upper_arm_outr = [-0.040")
    with pytest.raises(InputError) as e:
        load_suspension(p)
    msg = str(e.value)
    assert str(p) in msg and f"line {_line_of(p, 'upper_arm_outr')}" in msg
    assert "suspension.front.hardpoints_m.upper_arm_outr" in msg and "upper_arm_outer" in msg


def test_missing_hardpoint_is_named(tmp_path):
    p = _sample_with(tmp_path, "tie_rod_outer = [-0.150, 0.770, -0.120]\n", "")
    with pytest.raises(InputError, match=r"missing hardpoint 'tie_rod_outer'.*"):
        load_suspension(p)
    with pytest.raises(InputError, match=str(_line_of(p, "[suspension.front.hardpoints_m]"))):
        load_suspension(p)


def test_linkage_that_does_not_assemble_names_constraint_and_residual(tmp_path):
    p = _sample_with(tmp_path, "universal_axes = [[0.0, 0.0, 1.0], [-0.272, 0.962, 0.0]]",
                     "universal_axes = [[0.0, 0.3, 1.0], [-0.272, 0.962, 0.0]]")
    with pytest.raises(InputError) as e:
        load_suspension(p)
    msg = str(e.value)
    assert f"line {_line_of(p, 'universal_axes = ')}" in msg
    assert "joint 'trailing_link_front' (universal)" in msg
    assert re.search(r"residual 0\.2\d+", msg)  # cos of the angle between the axes


def test_travel_out_of_reach_names_the_failing_constraint():
    from test_suspension_statics import HP

    lk = Linkage(build("double_wishbone", HP, wheel_radius=0.3))
    with pytest.raises(ModelError, match=r"wheel travel 600\.0 mm.*(joint|link|wheel travel)"
                                         r".*residual"):
        solve_kinematics(lk, 0.6)


def test_bad_tables_and_keys(tmp_path):
    p = _sample_with(tmp_path, "deflection_m = [0.0, 0.005, 0.010, 0.020]",
                     "deflection_m = [0.0, 0.010, 0.005, 0.020]")
    with pytest.raises(InputError, match=r"line \d+, key 'suspension.front.bump_stop."
                                         r"deflection_m'.*increase"):
        load_suspension(p)
    p = _sample_with(tmp_path, 'template = "double_wishbone"', 'template = "double_wishbon"')
    with pytest.raises(InputError, match=r"key 'suspension.front.template'.*macpherson"):
        load_suspension(p)
    p = _sample_with(tmp_path, "[suspension.front.bushings.lower_arm_rear]",
                     "[suspension.front.bushings.upper_arm_outer]")
    with pytest.raises(InputError, match=r"bushing at 'upper_arm_outer'.*lower_arm_front"):
        load_suspension(p)
    p = _sample_with(tmp_path, "rate_N_per_m = 111000.0", "rate_N_per_m = 111000.0\nrte = 1")
    with pytest.raises(InputError, match=r"key 'suspension.front.spring.rte'.*unknown"):
        load_suspension(p)


def test_nonlinear_tables_at_a_link_end_bushing_are_refused(tmp_path):
    """At the body end of a two-force link only the bushing's rate along the link acts:
    a table there would be silently ignored, so the file is refused, naming the key."""
    extra = ("[suspension.rear.bushings.lateral_link_inner]\n"
             "stiffness = [5.0e6, 5.0e6, 5.0e6, 100.0, 100.0, 100.0]\n\n"
             "[suspension.rear.bushings.lateral_link_inner.tables.x]\n"
             "deflection = [-0.002, 0.0, 0.002]\nforce = [-9000.0, 0.0, 9000.0]\n\n"
             "[suspension.rear.bushings.trailing_link_front]")
    p = _sample_with(tmp_path, "[suspension.rear.bushings.trailing_link_front]", extra)
    with pytest.raises(InputError, match=r"key 'suspension.rear.bushings.lateral_link_inner'"
                                         r".*nonlinear tables.*'stiffness' only"):
        load_suspension(p)


@pytest.mark.parametrize("old, new, key", [
    ("force_N = [-6680.0, 0.0, 13360.0]", "force_N = [-6680.0, nan, 13360.0]",
     "suspension.front.damper.force_N"),
    ("velocity_m_per_s = [-1.0, 0.0, 1.0]", "velocity_m_per_s = [-1.0, inf, 1.0]",
     "suspension.front.damper.velocity_m_per_s"),
    ("force_N = [0.0, 1000.0, 3500.0, 12000.0]", "force_N = [0.0, 1000.0, -inf, 12000.0]",
     "suspension.front.bump_stop.force_N"),
    ("deflection_m = [0.0, 0.005, 0.010]\nforce_N = [0.0, 2000.0, 8000.0]",
     "deflection_m = [0.0, nan, 0.010]\nforce_N = [0.0, 2000.0, 8000.0]",
     "suspension.front.rebound_stop.deflection_m"),
    ("rate_N_per_m = 111000.0", "rate_N_per_m = 111000.0\ncompression_m = [0.0, 0.1]\n"
     "force_N = [0.0, nan]", "suspension.front.spring.force_N"),
    ("damping = [400.0, 400.0, 60.0, 0.5, 0.5, 0.2]",
     "damping = [400.0, 400.0, 60.0, 0.5, 0.5, 0.2]\n\n"
     "[suspension.front.bushings.lower_arm_rear.tables.z]\n"
     "deflection = [-0.004, 0.0, 0.004]\nforce = [-6000.0, nan, 6000.0]",
     "suspension.front.bushings.lower_arm_rear.tables.z.force"),
])
def test_non_finite_table_entries_are_refused(tmp_path, old, new, key):
    """A nan or inf in a table used to load and then crash the time run inside Exudyn."""
    p = _sample_with(tmp_path, old, new)
    with pytest.raises(InputError) as e:
        load_suspension(p)
    msg = str(e.value)
    assert str(p) in msg and f"key '{key}'" in msg
    assert "must hold finite numbers" in msg.replace(str(p), "")


@pytest.mark.parametrize("old, new, key, words", [
    ("force_N = [-6680.0, 0.0, 13360.0]", "force_N = [6680.0, 0.0, -13360.0]",
     "suspension.front.damper.force_N", ["negative damping", "must not decrease"]),
    ("rate_N_per_m = 111000.0", "rate_N_per_m = 111000.0\ncompression_m = [0.0, 0.05, 0.1]\n"
     "force_N = [0.0, 6000.0, 5000.0]", "suspension.front.spring.force_N",
     ["spring", "must not decrease"]),
    ("force_N = [0.0, 1000.0, 3500.0, 12000.0]", "force_N = [0.0, -1000.0, -3500.0, -12000.0]",
     "suspension.front.bump_stop.force_N", ["must not decrease"]),
    ("deflection_m = [0.0, 0.005, 0.010]\nforce_N = [0.0, 2000.0, 8000.0]",
     "deflection_m = [0.0, 0.005, 0.010]\nforce_N = [-100.0, 2000.0, 8000.0]",
     "suspension.front.rebound_stop.force_N", ["only pushes", ">= 0"]),
    ("damping = [400.0, 400.0, 60.0, 0.5, 0.5, 0.2]",
     "damping = [400.0, 400.0, 60.0, 0.5, 0.5, 0.2]\n\n"
     "[suspension.front.bushings.lower_arm_rear.tables.z]\n"
     "deflection = [-0.004, 0.0, 0.004]\nforce = [6000.0, 0.0, -6000.0]",
     "suspension.front.bushings.lower_arm_rear.tables.z.force", ["stiffness >= 0"]),
    ("damping = [400.0, 400.0, 60.0, 0.5, 0.5, 0.2]", "damping = [400.0, 400.0, -60.0, 0.5, "
     "0.5, 0.2]", "suspension.front.bushings.lower_arm_rear.damping", [">= 0"]),
])
def test_force_tables_with_the_wrong_sign_are_refused(tmp_path, old, new, key, words):
    """A damper whose force falls with velocity (negative damping) used to run to the end;
    springs, stops and bushings must not have negative stiffness either."""
    p = _sample_with(tmp_path, old, new)
    with pytest.raises(InputError) as e:
        load_suspension(p)
    msg = str(e.value)
    assert str(p) in msg and f"key '{key}'" in msg
    for w in words:
        assert w in msg.replace(str(p), "")


def _front_hardpoints_mirrored(text):
    a = text.index("[suspension.front.hardpoints_m]")
    b = text.index("[suspension.front.parts.lower_arm]")
    block = re.sub(r"(=\s*\[[^,]+,\s*)([0-9.]+)", r"\1-\2", text[a:b])
    return text[:a] + block + text[b:]


def test_hardpoints_on_the_wrong_side_are_refused(tmp_path):
    """The file gives the left corner (y > 0); the right one is its mirror image."""
    p = _write(tmp_path, _front_hardpoints_mirrored(SAMPLE.read_text()))
    with pytest.raises(InputError) as e:
        load_suspension(p)
    msg = str(e.value)
    assert str(p) in msg and f"line {_line_of(p, 'wheel_center = [0.000, -0.7979')}" in msg
    assert "key 'suspension.front.hardpoints_m.wheel_center'" in msg
    assert "y > 0 is left" in msg and "negate" in msg.replace(str(p), "")
    p = _sample_with(tmp_path, "lower_arm_rear = [-0.200, 0.470, -0.265]",
                     "lower_arm_rear = [-0.200, -0.470, -0.265]")
    with pytest.raises(InputError, match=r"key 'suspension.front.hardpoints_m.lower_arm_rear'"
                                         r".*y = -0.47 m.*right side.*y >= 0"):
        load_suspension(p)
    # an inner pivot outboard of the wheel centre (y 0.7979)
    p = _sample_with(tmp_path, "tie_rod_inner = [-0.257, 0.170, -0.116]",
                     "tie_rod_inner = [-0.257, 0.850, -0.116]")
    with pytest.raises(InputError, match=r"key 'suspension.rear.hardpoints_m.tie_rod_inner'"
                                         r".*outboard of the wheel centre.*inboard"):
        load_suspension(p)


@pytest.mark.parametrize("old, new, key, words", [
    ("location_m = [0.0, 0.0, 0.418]", "location_m = [0.0, 0.0, 418.0]",
     "suspension.front.location_m", ["wheel centre z = 417.88 m", "millimetres", "0 < z <= 3"]),
    ("location_m = [-2.75, 0.0, 0.3013]", "location_m = [-2750.0, 0.0, 301.3]",
     "suspension.rear.location_m", ["wheel centre x = -2750 m", "millimetres"]),
    ("wheel_center = [0.000, 0.800, 0.000]", "wheel_center = [0.000, 800.0, 0.000]",
     "suspension.rear.hardpoints_m.wheel_center", ["wheel centre y = 800 m", "millimetres"]),
    ("location_m = [0.0, 0.0, 0.418]", "location_m = [0.0, 0.0, 0.0]",
     "suspension.front.hardpoints_m.wheel_center", ["wheel centre z = -0.1197 m",
                                                    "location_m"]),
])
def test_location_in_millimetres_is_named(tmp_path, old, new, key, words):
    """location_m in mm used to load and fail later naming corners.fl.hardpoint_m, a key a
    linkage car does not have."""
    p = _sample_with(tmp_path, old, new)
    with pytest.raises(InputError) as e:
        load_suspension(p)
    msg = str(e.value)
    assert str(p) in msg and f"key '{key}'" in msg and "line " in msg
    for w in words:
        assert w in msg.replace(str(p), "")


def test_off_body_spring_seat_names_the_linkage_key():
    """A linkage car's corner hardpoint is its spring seat: named as the suspension key."""
    from flexpipe.vehicle import load_car
    from flexpipe.vehicle.bodymodel import corner_interfaces

    car = load_car(SAMPLE)
    with pytest.raises(InputError) as e:
        corner_interfaces(car, np.zeros((1, 3)))
    msg = str(e.value)
    assert str(SAMPLE) in msg and "suspension.front.hardpoints_m.spring_upper" in msg
    assert "corners.fl" not in msg


@pytest.mark.parametrize("old, new, key, other", [
    ("upper_arm_rear = [-0.250, 0.510, 0.110]", "upper_arm_rear = [-0.100, 0.470, 0.105]",
     "suspension.front.hardpoints_m.upper_arm_rear", "upper_arm_front"),
    ("tie_rod_outer = [-0.150, 0.770, -0.120]", "tie_rod_outer = [-0.200, 0.420, -0.120]",
     "suspension.front.hardpoints_m.tie_rod_outer", "tie_rod_inner"),
    ("lateral_link_outer = [0.029, 0.692, -0.093]", "lateral_link_outer = [0.036, 0.188, -0.133]",
     "suspension.rear.hardpoints_m.lateral_link_outer", "lateral_link_inner"),
    ("spring_lower = [0.181, 0.419, -0.164]", "spring_lower = [0.181, 0.491, 0.110]",
     "suspension.rear.hardpoints_m.spring_upper", "spring_lower"),
])
def test_coincident_points_of_an_axis_or_member_are_named(tmp_path, old, new, key, other):
    """Two equal pivots of a revolute axis used to give a numpy warning and a NaN residual."""
    p = _sample_with(tmp_path, old, new)
    with pytest.raises(InputError) as e:
        load_suspension(p)
    msg = str(e.value)
    assert str(p) in msg and f"key '{key}'" in msg
    assert other in msg.replace(str(p), "") and "must be distinct" in msg


def test_universal_axes_must_be_finite_and_non_zero(tmp_path):
    p = _sample_with(tmp_path, "universal_axes = [[0.0, 0.0, 1.0], [-0.272, 0.962, 0.0]]",
                     "universal_axes = [[0.0, 0.0, 0.0], [-0.272, nan, 0.0]]")
    with pytest.raises(InputError, match=r"key 'suspension.rear.universal_axes'.*non-zero"):
        load_suspension(p)


@pytest.mark.parametrize("old, new, key, words", [
    ("rate_N_per_m = 111000.0", "rate_N_per_m = 111.0", "suspension.front.spring.rate_N_per_m",
     ["N/mm", "between 1000 and 1e+07 N/m"]),
    ("wheel_mass_kg = 22.0", "wheel_mass_kg = 0.022", "corners.fl.wheel_mass_kg",
     ["tonnes", "between 1 and 2000 kg"]),
])
def test_unit_slips_of_the_linkage_car_are_named(tmp_path, old, new, key, words):
    from flexpipe.vehicle import load_car

    text = SAMPLE.read_text().replace('"../', f'"{SAMPLE.parents[1].as_posix()}/')
    p = _write(tmp_path, text.replace(old, new, 1))
    with pytest.raises(InputError) as e:
        load_car(p)
    msg = str(e.value)
    assert str(p) in msg and f"key '{key}'" in msg and f"line {_line_of(p, new)}" in msg
    for w in words:
        assert w in msg.replace(str(p), "")


def test_unknown_body_mount_is_refused_at_load(tmp_path):
    """It used to be refused only by the flexible run; info, kc and the rigid run took it."""
    from flexpipe.vehicle import load_car

    text = SAMPLE.read_text().replace('"../', f'"{SAMPLE.parents[1].as_posix()}/')
    p = _write(tmp_path, text.replace("[body.fatigue]", "[body.mounts.front_lower_arm_middle_l]"
                                      "\nradius_m = 0.02\n\n[body.fatigue]", 1))
    with pytest.raises(InputError) as e:
        load_car(p)
    msg = str(e.value)
    assert str(p) in msg and "key 'body.mounts.front_lower_arm_middle_l'" in msg
    assert f"line {_line_of(p, '[body.mounts.front_lower_arm_middle_l]')}" in msg
    assert "valid: front_lower_arm_front_l" in msg and "rear_arb_bushing_r" in msg
    with pytest.raises(InputError, match=r"key 'body.mounts.front_lower_arm_middle_l'.*valid"):
        load_suspension(p)  # what flexpipe kc reads


@pytest.mark.parametrize("spring", ["preload_N = 8000.0", "free_length_m = 0.45"])
def test_wheel_load_with_a_given_spring_preload_is_refused(tmp_path, spring):
    """Both would set the K&C rig's preload; the rig used the spring's and kc printed the
    preload of wheel_load_N."""
    p = _sample_with(tmp_path, "rate_N_per_m = 111000.0", f"rate_N_per_m = 111000.0\n{spring}")
    with pytest.raises(InputError) as e:
        load_suspension(p)
    msg = str(e.value).replace(str(p), "<car>")
    assert str(p) in str(e.value) and "key 'suspension.front.wheel_load_N'" in msg
    assert f"line {_line_of(p, 'wheel_load_N = 3800.0')}" in msg
    assert "preload_N / free_length_m" in msg and "give one" in msg


def test_kc_of_a_suspension_only_file_has_no_wheel(tmp_path):
    """A file with [suspension.*] and no [corners.*]: the rig preloads the bare linkage."""
    text = SAMPLE.read_text()
    start, end = text.index("[corners.fl]"), text.index("# ----", text.index("[corners.rr]"))
    p = _write(tmp_path, text[:start] + text[end:])
    from flexpipe.vehicle.suspension.kc import kc
    from flexpipe.vehicle.suspension.statics import spring_preload

    susp = load_suspension(p)
    assert susp.wheels == {}
    assert load_suspension(SAMPLE).wheels["rl"][0] == 22.0
    s = kc(susp, n=3, travel=0.001, axles=["front"]).summary["front"]
    assert s["wheel mass [kg]"] == 0.0
    assert s["spring preload [N]"] == pytest.approx(
        spring_preload(susp.axles["front"].left, 3800.0), rel=1e-12)


def test_mount_dofs_follow_what_passes_a_moment_in_each_mode(tmp_path):
    """A moment passes into the body at a bushing, a revolute or universal joint, the rack
    housing and an anti-roll-bar bearing; in the kinematic mode a bushing is the joint it
    surrounds, so a bushed ball or inline joint there passes a force only (3 DOF)."""
    kin = load_suspension(SAMPLE)
    assert kin.mode == "kinematic"
    comp = load_suspension(_sample_with(tmp_path, 'mode = "kinematic"', 'mode = "compliant"'))
    bushed = {j.mount: j.kind for c in comp.corners().values() for j in c.joints
              if j.mount is not None and j.bushing is not None}
    assert bushed  # the sample bushes ball, inline and universal joints
    for name, kind in bushed.items():
        assert comp.mount_dofs()[name] == 6, name
        assert kin.mount_dofs()[name] == (3 if kind in ("spherical", "inline") else 6), name
    for name in list(kin.rack.mounts) + [n for a in kin.axles.values()
                                         if a.anti_roll_bar is not None
                                         for n, _ in a.anti_roll_bar.mounts]:
        assert kin.mount_dofs()[name] == comp.mount_dofs()[name] == 6, name
    assert {n for n, d in kin.mount_dofs().items() if d == 3} > \
        {n for n, d in comp.mount_dofs().items() if d == 3}


@pytest.mark.parametrize("offset_mm, ok", [(0.0, True), (0.5, True), (50.0, False)])
def test_point_m_away_from_the_hardpoint_is_refused(tmp_path, offset_mm, ok):
    """A ``point_m`` moves the joint in flexible runs only (the rigid run keeps the
    hardpoint), so the rigid-vs-flexible difference would move with a point that has no
    physical meaning: more than 1 mm from the mount's hardpoint (typed above from the
    task, :data:`MOUNTS`) is an error naming the file, line, key and distance."""
    from flexpipe.vehicle import load_car

    x, y, z = MOUNTS["front_lower_arm_front"]
    text = SAMPLE.read_text().replace('"../', f'"{SAMPLE.parents[1].as_posix()}/')
    table = (f"[body.mounts.front_lower_arm_front_l]\npoint_m = [{x + offset_mm * 1e-3!r}, "
             f"{y!r}, {z!r}]\nradius_m = 0.02\n\n[body.fatigue]")
    p = _write(tmp_path, text.replace("[body.fatigue]", table, 1))
    if ok:
        load_car(p)
        return
    with pytest.raises(InputError) as e:
        load_car(p)
    msg = str(e.value)
    assert str(p) in msg and "key 'body.mounts.front_lower_arm_front_l.point_m'" in msg
    assert f"line {_line_of(p, '[body.mounts.front_lower_arm_front_l]')}" in msg
    assert f"is {offset_mm:.1f} mm from the suspension's point" in msg


def test_car_with_one_axle_suspension_is_named(tmp_path):
    """A car file cut after [suspension.front] (found by damaging the sample at random)
    raised a raw KeyError 'rl'; a car needs both axles, a K&C file may give one."""
    from flexpipe.vehicle import load_car

    text = SAMPLE.read_text().replace('"../', f'"{SAMPLE.parents[1].as_posix()}/')
    p = _write(tmp_path, text[:text.index("[suspension.rear]")])
    with pytest.raises(InputError, match=r"key 'suspension\.rear'.*no \[suspension\.rear\]: a "
                                         r"car needs a suspension on both axles \(this file "
                                         r"gives front"):
        load_car(p)
    assert set(load_suspension(p).axles) == {"front"}  # what flexpipe kc reads
