"""K&C rig: files written by ``flexpipe kc`` and closed-form checks of its analyses."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.cli import main
from flexpipe.vehicle.suspension.kc import opposite_travel, parallel_travel, static_steer
from flexpipe.vehicle.suspension.kinematics import Linkage, solve_kinematics, travel_velocity
from flexpipe.vehicle.suspension.spec import load_suspension

SAMPLE = Path(__file__).resolve().parents[1] / "cars" / "sedan_linkage.toml"


def test_cli_writes_csv_with_units_json_and_pngs(tmp_path):
    out = tmp_path / "kc"
    assert main(["kc", str(SAMPLE), "-o", str(out), "--points", "3", "--travel", "40"]) == 0
    header = (out / "front_parallel_travel.csv").read_text().splitlines()[0].split(",")
    for col in ("wheel travel [mm]", "camber [deg]", "toe [deg]", "caster [deg]", "kpi [deg]",
                "scrub radius [mm]", "wheel rate [N/m]", "roll centre height [mm]",
                "bump steer [deg/m]"):
        assert col in header
    for name in ("front_opposite_travel", "front_static_steer", "front_lateral_force",
                 "rear_longitudinal_force"):
        assert (out / f"{name}.csv").stat().st_size > 0
    summary = json.loads((out / "kc_summary.json").read_text())
    assert set(summary) == {"front", "rear"}
    for png in ("kc_wheel_travel.png", "kc_steer_compliance.png"):
        assert (out / png).read_bytes()[:4] == b"\x89PNG"


def test_cli_bad_file_exits_2(tmp_path, capsys):
    bad = tmp_path / "car.toml"
    bad.write_text("[suspension.front]\ntemplate = 'twist_beam'\n")
    assert main(["kc", str(bad), "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "line 2" in err and "suspension.front.template" in err and "macpherson" in err


def test_anti_roll_bar_rate_is_torsion_rate_times_arm_ratio_squared():
    """Vertical drop link on a horizontal 0.2 m arm: the bar turns by v_z / 0.2 per metre
    of travel at each wheel, so in opposite travel each wheel sees 2 k_t (v_z / 0.2)^2."""
    axle = load_suspension(SAMPLE).axles["front"]
    arb = axle.anti_roll_bar
    assert np.allclose(arb.arm_end - arb.bushing, [0.2, 0.2, 0.0])  # x arm, y offset only
    assert np.allclose((arb.arm_end - arb.drop_link_lower)[:2], 0)   # vertical drop link
    lk = Linkage(axle.left)
    pose = solve_kinematics(lk, 0.0)
    _, J = lk.point(pose, arb.part, arb.drop_link_lower)
    vz = (J @ travel_velocity(lk, pose))[2]
    s = np.linspace(-0.004, 0.004, 5)
    opp = opposite_travel(axle, s, parallel_travel(axle, s))
    assert opp["anti-roll bar wheel rate [N/m]"][2] == pytest.approx(
        2 * arb.torsion_rate * (vz / 0.2) ** 2, rel=2e-3)


def test_static_steer_is_mirror_symmetric_and_roll_centre_consistent():
    axle = load_suspension(SAMPLE).axles["front"]
    x = np.linspace(-0.02, 0.02, 5)
    st = static_steer(axle, x)
    assert st["steer left [deg]"] == pytest.approx(-st["steer right [deg]"][::-1], abs=1e-9)
    assert st["steer left [deg]"][2] == pytest.approx(0.0, abs=1e-9)
    # a left turn of the steering wheel (> 0) steers both wheels left (> 0)
    j = [0, 1, 3, 4]
    for side in ("left", "right"):
        assert np.all(np.sign(st[f"steer {side} [deg]"][j])
                      == np.sign(st["steering wheel angle [deg]"][j]))
    s = np.linspace(-0.01, 0.01, 3)
    par = parallel_travel(axle, s)
    opp = opposite_travel(axle, s, par)
    # at zero travel opposite and parallel travel have the same roll centre, on the centre line
    assert opp["roll centre height [mm]"][1] == pytest.approx(par["roll centre height [mm]"][1],
                                                              abs=1e-9)
    assert opp["roll centre y [mm]"][1] == pytest.approx(0.0, abs=1e-9)


def test_api_kc_returns_tables():
    res = fp.kc(SAMPLE, n=3, travel=0.02, axles=["rear"])
    assert set(res.summary) == {"rear"}
    assert res.tables["rear_parallel_travel"]["wheel travel [mm]"].tolist() == [-20, 0, 20]


def test_right_corner_compliance_mirrors_the_left():
    """Mirrored bushings and seats: equal wheel rates, and a lateral patch force on the
    right corner gives the toe/camber the mirrored force gives on the left."""
    from flexpipe.vehicle.suspension.kinematics import solve_compliance
    from flexpipe.vehicle.suspension.metrics import characteristics
    from flexpipe.vehicle.suspension.statics import wheel_rate

    for axle in load_suspension(SAMPLE).axles.values():
        assert wheel_rate(axle.right) == pytest.approx(wheel_rate(axle.left), rel=1e-7)
        out = []
        for corner, fy in ((axle.left, 1500.0), (axle.right, -1500.0)):
            lk = Linkage(corner)
            ch = characteristics(lk, solve_compliance(lk, 0.0, patch_force=(300.0, fy, 0.0)))
            out.append((ch["toe"], ch["camber"]))
        assert out[1] == pytest.approx(out[0], abs=1e-9)
