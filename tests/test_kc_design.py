"""K&C rig: the summary at the design position, roll stiffness in opposite travel, the
zero-force state of the compliance analyses, the wheel-centre force column, the CLI's
options and hardpoints typed in millimetres."""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.cli import main
from flexpipe.errors import InputError
from flexpipe.vehicle.suspension.kc import (
    WHEEL_CENTRE_FORCE,
    force_compliance,
    opposite_travel,
    parallel_travel,
    sweep,
)
from flexpipe.vehicle.suspension.kinematics import (
    G,
    Linkage,
    solve_compliance,
    solve_kinematics,
)
from flexpipe.vehicle.suspension.metrics import rates
from flexpipe.vehicle.suspension.spec import load_suspension
from flexpipe.vehicle.suspension.statics import rig_corner, rig_suspension

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "cars" / "sedan_linkage.toml"


@pytest.fixture(scope="module")
def rig():
    """The sample's suspension as the rig holds it (wheels on the knuckles)."""
    return rig_suspension(load_suspension(SAMPLE))


# ------------------------------------------------------------------ summary at design


def test_summary_is_the_design_position_for_any_number_of_points(tmp_path):
    """``--points 4`` has no point at travel 0 (its middle points are at -26.7 and +26.7
    mm); the summary must still be the design position's, equal to 33 points' and with
    the file's static camber and toe (0 deg in the sample)."""
    out = tmp_path / "kc4"
    assert main(["kc", str(SAMPLE), "-o", str(out), "--points", "4", "--axle", "front"]) == 0
    four = json.loads((out / "kc_summary.json").read_text())
    assert set(four) == {"front"}
    res = fp.kc(SAMPLE, n=33, axles=["front"])
    many = res.summary["front"]
    assert set(four["front"]) == set(many)
    for k, v in many.items():
        if k != "template":
            assert four["front"][k] == pytest.approx(v, rel=1e-9, abs=1e-9), k
    assert four["front"]["camber [deg]"] == pytest.approx(0.0, abs=1e-9)
    assert four["front"]["toe [deg]"] == pytest.approx(0.0, abs=1e-9)
    # the 33-point table has its design row in the middle: the same geometry there, and
    # its central differences (5 mm) agree with the summary's rates (0.5 mm)
    par = res.tables["front_parallel_travel"]
    assert par["wheel travel [mm]"][16] == 0.0
    for col in ("caster [deg]", "kpi [deg]", "scrub radius [mm]", "roll centre height [mm]",
                "spring motion ratio [-]", "kinematic wheel rate [N/m]"):
        assert par[col][16] == pytest.approx(many[col], rel=1e-9), col
    for col in ("camber gain [deg/m]", "bump steer [deg/m]"):
        assert par[col][16] == pytest.approx(many[col], rel=1e-3), col


def test_sweep_is_antisymmetric_and_holds_the_design_position():
    for n in (3, 4, 5, 33):
        s = sweep(0.08, n)
        assert len(s) == n and s[0] == -0.08 and s[-1] == 0.08
        assert np.array_equal(s, -s[::-1])
        assert np.allclose(np.diff(s), 0.16 / (n - 1), rtol=1e-12)
    assert sweep(0.08, 33)[16] == 0.0


# ------------------------------------------------------------------ roll stiffness


@pytest.mark.parametrize("axle", ["front", "rear"])
def test_roll_stiffness_is_symmetric_in_roll(rig, axle):
    """Left +s / right -s and left -s / right +s are mirror images of each other on a
    symmetric axle: the same roll stiffness.  The old rig counted the left wheel's rate
    twice (front 3092.6 vs 1709.5 N m/deg at +-80 mm)."""
    a = rig.axles[axle]
    s = sweep(0.08, 5)
    opp = opposite_travel(a, s, parallel_travel(a, s))
    roll = opp["roll stiffness [N m/deg]"]
    assert roll == pytest.approx(roll[::-1], rel=1e-9)
    # each wheel's rate at its own travel: left at +s is right at -s
    assert opp["wheel rate left [N/m]"] == pytest.approx(opp["wheel rate right [N/m]"][::-1],
                                                          rel=1e-12)
    # the bar's force on the left wheel at +s is the right wheel's at -s; at each state
    # the two forces resist the roll (opposite signs)
    fl, fr = opp["anti-roll bar force left [N]"], opp["anti-roll bar force right [N]"]
    assert fl == pytest.approx(fr[::-1], rel=1e-9, abs=1e-9)
    assert np.all(fl[s > 0] > 0) and np.all(fr[s > 0] < 0)


@pytest.mark.parametrize("axle", ["front", "rear"])
def test_design_roll_stiffness_matches_the_hand_formula(rig, axle):
    """K = (k + 2 k_t (dphi/ds)^2) t^2 / 2 per radian: k the wheel rate with bushings
    (here a 1 mm central difference of compliance solves), the bar arm's rate dphi/ds =
    v_z / r_x (vertical drop link on an arm of length r_x along x; v_z by a finite
    difference of kinematic solves), t the wheel-centre track.  The sample gives 1539 /
    783 N m/deg (front / rear, wheel_load_N 3800 / 3488 N, the car's static loads; 1540 /
    792 at the earlier 4220 / 3060 N, as before the symmetric formula): at the design
    position both wheels' rates are equal."""
    a = rig.axles[axle]
    c = rig_corner(a, a.left)
    arb = a.anti_roll_bar
    r = arb.arm_end - arb.bushing
    assert r[2] == 0 and np.allclose((arb.arm_end - arb.drop_link_lower)[:2], 0)
    lk = Linkage(a.left)
    h = 1e-3
    z = [lk.point(solve_kinematics(lk, x), arb.part, arb.drop_link_lower)[0][2]
         for x in (-h, h)]
    dphi = (z[1] - z[0]) / (2 * h) / r[0]
    lkc = Linkage(c)
    k = (solve_compliance(lkc, h).force - solve_compliance(lkc, -h).force) / (2 * h)
    t = 2 * c.wheel_center[1]
    hand = (k + 2 * arb.torsion_rate * dphi**2) * t**2 / 2 * np.pi / 180
    got = fp.kc(SAMPLE, n=3, travel=0.002, axles=[axle]).summary[axle]
    assert got["roll stiffness [N m/deg]"] == pytest.approx(hand, rel=2e-4)


# ------------------------------------------------------------------ compliance


def test_compliance_analyses_share_their_zero_force_state(rig):
    """Both analyses start from the rig's static state (rack held at its centre): their
    zero-force rows agree.  The old lateral run loaded the half-rack spring with the
    static tie-rod force (rack 0.104 mm, toe -0.016 vs -0.060 deg)."""
    a = rig.axles["front"]
    assert a.rack is not None and a.rack.axial_stiffness is not None
    f = sweep(2000.0, 3)
    lon, lat = force_compliance(a, 0, f), force_compliance(a, 1, f)
    assert lon["force [N]"][1] == lat["force [N]"][1] == 0.0
    for col in lon.columns[1:]:
        assert lat[col][1] == pytest.approx(lon[col][1], abs=1e-7), col
    assert lat["rack travel [mm]"][1] == pytest.approx(0.0, abs=1e-7)
    # the rack moves with the force increment only: +-F move it equally both ways
    rack = lat["rack travel [mm]"]
    assert rack[2] > 0.05 and rack[0] == pytest.approx(-rack[2], rel=1e-3)


# ------------------------------------------------------------------ wheel-centre force


def _rigid(corner):
    """``corner`` with every bushing and compliant link replaced by its joint."""
    return replace(corner, joints=tuple(replace(j, bushing=None) for j in corner.joints),
                   links=tuple(replace(lk, axial_stiffness=None) for lk in corner.links))


@pytest.mark.parametrize("axle", ["front", "rear"])
def test_wheel_centre_force_is_the_tyre_load_net_of_the_unsprung_weight(rig, axle):
    """Virtual work at the design position with rigid joints: the force at the wheel
    centre (parts weightless) is wheel_load_N dz_patch/ds - g sum(m_i dz_i/ds); the rig's
    column with bushings differs by the small share the deflected bushings carry."""
    a = rig.axles[axle]
    c = rig_corner(a, a.left)
    lk = Linkage(c)
    r = rates(lk, solve_kinematics(lk, 0.0))
    masses = np.array([p.mass for p in c.parts])
    net = a.wheel_load * r["patch_velocity"][2] - G * masses @ r["part_dz"]
    assert a.wheel_load - net > 9.81 * 22  # the wheel's weight at least
    assert solve_compliance(Linkage(_rigid(c)), 0.0).force == pytest.approx(net, rel=1e-9)
    par = parallel_travel(a, sweep(0.002, 3))
    assert par[WHEEL_CENTRE_FORCE][1] == pytest.approx(net, rel=0.02)


# ------------------------------------------------------------------ CLI options


@pytest.fixture
def no_analysis(monkeypatch):
    import flexpipe.vehicle.suspension.kc as kc_module

    def boom(*_a, **_k):
        raise AssertionError("the analysis ran before the option checks")

    monkeypatch.setattr(kc_module, "kc", boom)


@pytest.mark.parametrize("argv, message", [
    (["--travel", "600"], "--travel must be in (0, 500] mm, got 600 mm"),
    (["--travel", "0"], "--travel must be in (0, 500] mm, got 0 mm"),
    (["--rack", "600"], "--rack must be in (0, 500] mm, got 600 mm"),
    (["--rack", "0"], "--rack must be in (0, 500] mm, got 0 mm"),
    (["--points", "2"], "--points must be an integer >= 3, got 2"),
    (["--force", "-5"], "--force must be > 0 N, got -5 N"),
    (["--force", "nan"], "--force must be > 0 N, got nan N"),
    (["--axle", "middle"], "--axle must be one of front, rear, both, got 'middle'"),
])
def test_cli_option_errors_name_the_option_its_unit_and_range(tmp_path, capsys, no_analysis,
                                                             argv, message):
    assert main(["kc", str(SAMPLE), "-o", str(tmp_path / "kc"), *argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err == [f"flexpipe kc: error: {message}"]
    assert not (tmp_path / "kc").exists()


def test_cli_help_states_defaults_limits_and_points(capsys):
    assert main(["kc", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    for words in ("default 80", "default 33", "default 30", "default 2000", "default both",
                  "0 < --travel <= 500 mm", "--points >= 3", "0 < --rack <= 500 mm",
                  "--force > 0 N", "evenly spaced", "does not depend on --points"):
        assert words in text, words


def test_cli_axle_option_runs_one_axle(tmp_path):
    out = tmp_path / "kc"
    assert main(["kc", str(SAMPLE), "-o", str(out), "--points", "3", "--travel", "2",
                 "--axle", "Rear"]) == 0
    assert set(json.loads((out / "kc_summary.json").read_text())) == {"rear"}
    assert not (out / "front_parallel_travel.csv").exists()
    header = (out / "rear_parallel_travel.csv").read_text().splitlines()[0].split(",")
    assert WHEEL_CENTRE_FORCE in header and "rig force [N]" not in header


# ------------------------------------------------------------------ millimetres


def _copy(tmp_path, old, new):
    text = SAMPLE.read_text()
    assert old in text
    p = tmp_path / "car.toml"
    p.write_text(text.replace(old, new, 1).replace('"../', f'"{ROOT.as_posix()}/'))
    return p


def test_hardpoint_in_millimetres_is_named_with_its_distance(tmp_path, capsys):
    """The audit's case: the lower ball joint in mm was blamed on 'tie_rod_outer' by the
    mobility check.  Now the point's own key, line, distance and the unit are named."""
    p = _copy(tmp_path, "lower_arm_outer = [0.000, 0.770, -0.320]",
              "lower_arm_outer = [0.0, 770.0, -320.0]")
    with pytest.raises(InputError) as e:
        load_suspension(p)
    err = e.value
    line = next(i + 1 for i, s in enumerate(p.read_text().splitlines())
                if s.startswith("lower_arm_outer = [0.0, 770.0"))
    assert err.key == "suspension.front.hardpoints_m.lower_arm_outer" and err.line == line
    # z = -320 + location_m 0.418; the wheel centre at (0, 0.7979, -0.1197 + 0.418)
    dist = np.linalg.norm(np.array([0.0, 770.0, -319.582]) - [0.0, 0.7979, 0.2983])
    assert f"{dist:.4g} m from the wheel centre" in err.message
    assert "hardpoints are in metres; this looks like millimetres" in err.message
    assert "within 3 m" in err.message
    assert main(["kc", str(p), "-o", str(tmp_path / "kc")]) == 2
    msg = capsys.readouterr().err
    assert "lower_arm_outer" in msg and "mechanism" not in msg and "tie_rod_outer" not in msg


def test_hardpoint_ten_times_too_far_is_not_called_millimetres(tmp_path):
    p = _copy(tmp_path, "lower_arm_outer = [0.000, 0.770, -0.320]",
              "lower_arm_outer = [0.0, 7.70, -0.320]")
    with pytest.raises(InputError) as e:
        load_suspension(p)
    assert e.value.key == "suspension.front.hardpoints_m.lower_arm_outer"
    dist = np.linalg.norm(np.array([0.0, 7.70, -0.320 + 0.418]) - [0.0, 0.7979, 0.2983])
    assert f"{dist:.4g} m from the wheel centre" in e.value.message
    assert "millimetres" not in e.value.message
