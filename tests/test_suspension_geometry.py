"""Degenerate suspension geometry is refused at load, for ``run``, ``info`` and ``kc`` alike.

Hardpoints that assemble can still leave the knuckle a mechanism or lock the wheel: an arm
whose ball joint lies on its own pivot axis, a tie rod whose line meets the steering axis,
a universal joint that leaves the trailing link free to spin.  Such files used to run
(20 kN of lateral hub force on a flat road, or "the implicit solver did not converge at
t = 0" blaming the step) and print figures in ``info``; only ``kc`` refused some of them.
Now every command refuses them naming file, line, corner and hardpoint key
(:mod:`flexpipe.vehicle.suspension.mobility`), and the sample car, the project's typed
corners and the Chrono reference corners (../shared/reference/vehicle) pass.
"""

from __future__ import annotations

from pathlib import Path

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

from flexpipe.cli import main
from flexpipe.errors import InputError
from flexpipe.vehicle.suspension.mobility import (
    MIN_LEVER_M,
    MIN_SINGULAR,
    design_jacobian,
    link_lever,
    mobility_problem,
)
from flexpipe.vehicle.suspension.spec import load_suspension
from flexpipe.vehicle.suspension.templates import build

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "cars" / "sedan_linkage.toml"

# the audit's two cases (cars/sedan_linkage.toml with one hardpoint moved)
ARM_ON_AXIS = ("lower_arm_outer = [0.000, 0.770, -0.320]",
               "lower_arm_outer = [0.000, 0.445, -0.2675]")  # midpoint of the arm's pivots
TIE_ROD_ON_KINGPIN = ("tie_rod_outer = [-0.150, 0.770, -0.120]",
                      "tie_rod_outer = [-0.020, 0.7325, -0.1075]")  # midway between the balls

# Chrono's generic MacPherson strut (as in test_suspension_kinematics), 0.35 m up
MACPHERSON = {
    "lower_arm_front": (0.22, 0.52, -0.156), "lower_arm_rear": (-0.30, 0.507, -0.137),
    "lower_arm_outer": (-0.0217, 0.9406, -0.1740), "strut_top": (-0.115, 0.785, 0.579),
    "strut_lower": (-0.0740, 0.8533, 0.2485), "tie_rod_inner": (-0.30, 0.52, -0.059),
    "tie_rod_outer": (-0.2374, 0.8950, -0.0161), "spring_upper": (-0.115, 0.785, 0.579),
    "spring_lower": (-0.0740, 0.8533, 0.2485), "damper_upper": (-0.115, 0.785, 0.579),
    "damper_lower": (-0.0740, 0.8533, 0.2485), "wheel_center": (-0.04, 1.10, -0.026)}


def _write(tmp_path, text, name="car.toml"):
    p = tmp_path / name
    p.write_text(text.replace('"../', f'"{ROOT.as_posix()}/'))  # mesh and tyres found
    return p


def _sample_with(tmp_path, old, new):
    text = SAMPLE.read_text()
    assert old in text
    return _write(tmp_path, text.replace(old, new, 1))


def _macpherson_file(tmp_path, **moved):
    hp = dict(MACPHERSON, **moved)
    rows = "\n".join(f"{k} = [{', '.join(f'{v:.6g}' for v in p)}]" for k, p in hp.items())
    return _write(tmp_path, "[suspension.front]\ntemplate = \"macpherson\"\n"
                            "location_m = [0.0, 0.0, 0.35]\n\n"
                            f"[suspension.front.hardpoints_m]\n{rows}\n", "strut.toml")


def _line_of(path, needle):
    return next(i + 1 for i, s in enumerate(path.read_text().splitlines()) if needle in s)


def _refused(path, key, corner, *words):
    """load_suspension (what kc reads) refuses ``path`` naming file, line, key, corner."""
    with pytest.raises(InputError) as e:
        load_suspension(path)
    msg = str(e.value)
    assert str(path) in msg and f"key '{key}'" in msg and "line " in msg, msg
    assert f"corner {corner}" in msg, msg
    for w in words:
        assert w in msg.replace(str(path), ""), (w, msg)
    return e.value


# ------------------------------------------------------------------ the audit's cases


@pytest.mark.parametrize("old, new, key, words", [
    (*ARM_ON_AXIS, "suspension.front.hardpoints_m.lower_arm_outer",
     ["lower arm's pivot axis", "'lower_arm_front' and 'lower_arm_rear'", "at least 0.2 x"]),
    (*TIE_ROD_ON_KINGPIN, "suspension.front.hardpoints_m.tie_rod_outer",
     ["kingpin", "'lower_arm_outer' and 'upper_arm_outer'", "lever arm of 0.0 mm",
      f"at least {MIN_LEVER_M * 1e3:g} mm"]),
])
def test_audit_cases_are_refused_by_run_info_and_kc(tmp_path, capsys, old, new, key, words):
    """The audit's degenerate wishbone ran to completion (20 kN hub force, wheel locked)
    and the tie rod on the kingpin stopped at t = 0 blaming the step; ``info`` printed a
    385 N/m wheel rate or a compliance solve without file or key."""
    p = _sample_with(tmp_path, old, new)
    err = _refused(p, key, "fl", *words)
    assert err.line == _line_of(p, new.split(" =")[0] + " = ")
    from flexpipe.vehicle import load_car

    with pytest.raises(InputError, match=f"key '{key}'"):  # what run and info read
        load_car(p)
    out = tmp_path / "out"
    for argv in (["info", str(p)], ["kc", str(p), "-o", str(tmp_path / "kc")],
                 ["run", str(p), "--speed", "30", "--t-end", "0.3", "--body", "rigid",
                  "--out", str(out), "-q"]):
        assert main(argv) == 2, argv
        msg = capsys.readouterr().err
        assert str(p) in msg and f"key '{key}'" in msg and "corner fl" in msg, (argv, msg)
        assert "step" not in msg and "did not converge" not in msg
    assert not out.exists()


# ------------------------------------------------------------------ one per template


@pytest.mark.parametrize("moved, key, words", [
    # the lower ball joint on the line of the arm's pivots (their midpoint)
    ({"lower_arm_outer": (-0.04, 0.5135, -0.1465)},
     "suspension.front.hardpoints_m.lower_arm_outer", ["lower arm's pivot axis"]),
    # the tie rod's outer end midway between the lower ball joint and the strut top
    ({"tie_rod_outer": (-0.06835, 0.8628, 0.2025)},
     "suspension.front.hardpoints_m.tie_rod_outer",
     ["kingpin", "'lower_arm_outer' and 'strut_top'", "lever arm of 0.0 mm"]),
])
def test_macpherson_degenerate_geometry_is_named(tmp_path, moved, key, words):
    assert load_suspension(_macpherson_file(tmp_path)).axles["front"]  # as given: accepted
    _refused(_macpherson_file(tmp_path, **moved), key, "fl", *words)


@pytest.mark.parametrize("old, new, key, words", [
    # the upper ball joint at the midpoint of the upper arm's pivots
    ("upper_arm_outer = [0.056, 0.714, 0.151]", "upper_arm_outer = [-0.0485, 0.3775, 0.072]",
     "suspension.rear.hardpoints_m.upper_arm_outer", ["upper arm's pivot axis"]),
    # the toe link's outer end on the knuckle's steer axis (through upper_arm_outer)
    ("tie_rod_outer = [-0.144, 0.712, -0.056]", "tie_rod_outer = [0.0328, 0.7086, -0.056]",
     "suspension.rear.hardpoints_m.tie_rod_outer", ["toe link", "steering axis"]),
    # the lateral link's line through the axis the toe link holds: both hold one motion
    ("lateral_link_outer = [0.029, 0.692, -0.093]",
     "lateral_link_outer = [-0.1725, 0.7829, -0.093]",
     "suspension.rear.hardpoints_m.tie_rod_outer",
     ["'lateral_link_outer'", "hold the same motion"]),
])
def test_multi_link_degenerate_geometry_is_named(tmp_path, old, new, key, words):
    _refused(_sample_with(tmp_path, old, new), key, "rl", *words)


def test_double_wishbone_upper_arm_on_its_axis_is_named(tmp_path):
    p = _sample_with(tmp_path, "upper_arm_outer = [-0.040, 0.695, 0.105]",
                     "upper_arm_outer = [-0.175, 0.490, 0.1075]")
    _refused(p, "suspension.front.hardpoints_m.upper_arm_outer", "fl", "upper arm's pivot")


def test_general_rank_test_names_the_dependent_constraints(tmp_path):
    """A universal joint whose locked rotation is perpendicular to the trailing link leaves
    the link free to spin: no arm or link check sees it, the Jacobian's rank does."""
    p = _sample_with(tmp_path, "universal_axes = [[0.0, 0.0, 1.0], [-0.272, 0.962, 0.0]]",
                     "universal_axes = [[-0.723, 0.265, -0.084], [-0.265, -0.723, 0.0]]")
    _refused(p, "suspension.rear.universal_axes", "rl", "mechanism",
             "joint 'trailing_link_front' (universal)", "trailing_link can still move",
             "'trailing_link_front'", "perpendicular to the trailing link")


def test_a_short_steering_arm_above_the_threshold_is_accepted(tmp_path):
    """The tie rod 30 % of the way from the kingpin to its design point: a 40 mm lever."""
    p = _sample_with(tmp_path, TIE_ROD_ON_KINGPIN[0], "tie_rod_outer = [-0.059, 0.7438, -0.1112]")
    lever = link_lever(load_suspension(p).axles["front"].left, "tie_rod")[0]
    assert 1.5 * MIN_LEVER_M < lever < 3 * MIN_LEVER_M


# ------------------------------------------------------------------ what must pass


def _hp(d):
    return {k: np.asarray(v, float) for k, v in d.items()}


def _reference_corners():
    out = {"sedan front (typed)": build("double_wishbone", _hp(SEDAN_FRONT), wheel_radius=0.3,
                                        steered=True),
           "sedan rear (typed)": build("multi_link", _hp(SEDAN_REAR), wheel_radius=0.3,
                                       universal_axes=SEDAN_REAR_UNIVERSAL),
           "sedan rear, default axes": build("multi_link", _hp(SEDAN_REAR), wheel_radius=0.3),
           "macpherson (typed)": build("macpherson", _hp(MACPHERSON), wheel_radius=0.3)}
    for name in ("Sedan_DoubleWishbone.json", "audi_DoubleWishbone.json"):
        hp = chrono_double_wishbone(name)
        if hp is not None:
            out[name] = build("double_wishbone", hp, wheel_radius=0.3, steered=True)
    if chrono_macpherson() is not None:
        out["MacPhersonStrut.json"] = build("macpherson", chrono_macpherson(),
                                            wheel_radius=0.3, steered=True)
    for name in ("Sedan_MultiLink.json", "audi_MultiLink.json"):
        got = chrono_multi_link(name)
        if got is not None:
            out[name] = build("multi_link", got[0], wheel_radius=0.3, universal_axes=got[1])
    for c in load_suspension(SAMPLE).corners().values():
        out[f"sample {c.corner}"] = c
    return out


def test_sample_typed_and_reference_corners_pass_with_margin():
    corners = _reference_corners()
    assert len(corners) >= 8
    for name, c in corners.items():
        assert mobility_problem(c) is None, name
        s = np.linalg.svd(design_jacobian(c)[0], compute_uv=False)
        assert s[-1] > 10 * MIN_SINGULAR, (name, s[-1])
        for lk in c.links:
            assert link_lever(c, lk.name)[0] > 5 * MIN_LEVER_M, (name, lk.name)
