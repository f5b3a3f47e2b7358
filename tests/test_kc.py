"""K&C rig: files written by ``flexpipe kc`` and closed-form checks of its analyses."""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.cli import main
from flexpipe.vehicle.spec import CORNERS
from flexpipe.vehicle.suspension.kc import (
    WHEEL_CENTRE_FORCE,
    opposite_travel,
    parallel_travel,
    static_steer,
)
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


def _info_figures(text: str) -> dict:
    """``{axle: {"kinematic": N/m, "static": (load, preload, rate), "rig": (...)}}`` from
    the text of ``flexpipe info``."""
    out, axle = {}, None
    num = r"([-\d.e+]+)"
    for line in text.splitlines():
        m = re.match(r"    (front|rear): ", line)
        if m:
            axle = out.setdefault(m.group(1), {})
            continue
        m = re.search(rf"kinematic wheel rate \(spring rate x motion ratio\^2\) {num} N/m",
                      line)
        if m and axle is not None:
            axle["kinematic"] = float(m.group(1))
        m = re.search(rf"(at the static tyre load|on the K&C rig, wheel_load_N) {num} N "
                      rf"\((?:time runs[^)]*|flexpipe kc)\): spring preload {num} N, wheel rate "
                      rf"incl\. compliance {num} N/m", line)
        if m and axle is not None:
            key = "static" if m.group(1).startswith("at") else "rig"
            axle[key] = tuple(float(v) for v in m.group(2, 3, 4))
    return out


def test_info_and_kc_give_the_same_spring_figures_at_the_same_load(capsys):
    """``flexpipe info`` prints the spring preload and wheel rate at the time runs' static
    tyre load and on the K&C rig (``wheel_load_N``); ``flexpipe kc`` at either load gives
    the same.  Independent checks on kc's tables: kinematic wheel rate = k (dL/ds)^2 from
    the spring-length column, the rate incl. compliance = slope of the rig-force column."""
    from flexpipe.vehicle import bodymodel
    from flexpipe.vehicle.linkage_setup import linkage_statics

    assert main(["info", str(SAMPLE)]) == 0
    info = _info_figures(capsys.readouterr().out)
    assert set(info) == {"front", "rear"}
    car = fp.load_car(SAMPLE)
    _, N = linkage_statics(car, bodymodel.rigid_properties(car))
    rig = fp.kc(SAMPLE, n=3, travel=0.001)
    for axle, figs in info.items():
        k = car.suspension.axles[axle].left.spring().rate
        s = rig.summary[axle]
        load, preload, rate = figs["rig"]
        assert load == car.suspension.axles[axle].wheel_load == s["wheel load [N]"]
        assert preload == pytest.approx(s["spring preload [N]"], abs=0.5)
        assert rate == pytest.approx(s["wheel rate incl. compliance [N/m]"], abs=0.5)
        assert figs["kinematic"] == pytest.approx(s["kinematic wheel rate [N/m]"], abs=0.5)
        par = rig.tables[f"{axle}_parallel_travel"]
        ds = np.diff(par["wheel travel [mm]"][[0, 2]])[0]
        dL = np.diff(par["spring length [mm]"][[0, 2]])[0]
        assert figs["kinematic"] == pytest.approx(k * (dL / ds) ** 2, rel=1e-4)
        dF = np.diff(par[WHEEL_CENTRE_FORCE][[0, 2]])[0]
        assert rate == pytest.approx(dF / ds * 1e3, rel=2e-3)
        # kc with its wheel load set to the time runs' static load gives info's figures
        load = N[CORNERS.index(car.suspension.axles[axle].left.corner)]
        assert figs["static"][0] == pytest.approx(load, abs=0.5)
        at_static = fp.kc(load_suspension(SAMPLE, overrides={
            f"suspension.{axle}.wheel_load_N": float(load)}), n=3, travel=0.001,
            axles=[axle]).summary[axle]
        assert figs["static"][1] == pytest.approx(at_static["spring preload [N]"], abs=0.5)
        assert figs["static"][2] == pytest.approx(
            at_static["wheel rate incl. compliance [N/m]"], abs=0.5)


def test_rig_preload_allows_for_the_wheel_weight():
    """The rig's preload for wheel_load_N (a tyre load) is the one the time runs' statics
    give at that load: the wheel of [corners.<c>] hangs on the knuckle in both."""
    from flexpipe.vehicle.suspension.statics import preloaded, spring_preload, with_wheels

    car = fp.load_car(SAMPLE)
    wheels = {c: (22.0, np.diag([0.45, 1.0, 0.45])) for c in car.suspension.corners()}
    loads = {c: car.suspension.axles[a].wheel_load for a in ("front", "rear")
             for c in (a[0] + "l", a[0] + "r")}
    runs = preloaded(with_wheels(car.suspension, wheels), loads)
    rig = fp.kc(SAMPLE, n=3, travel=0.001).summary
    for axle in ("front", "rear"):
        sp = runs.axles[axle].left.spring()
        assert rig[axle]["spring preload [N]"] == pytest.approx(
            sp.static_force(sp.design_length), rel=1e-9)
        assert rig[axle]["wheel mass [kg]"] == 22.0
        # without the wheel the spring would carry its weight too: preload differs by
        # m g dz_wheel/ds / MR, about 22 * 9.81 / 0.52 = 415 N at the front
        bare = spring_preload(car.suspension.axles[axle].left, loads[axle[0] + "l"])
        assert bare - rig[axle]["spring preload [N]"] > 200.0


def test_kc_plots_have_panel_titles_name_the_car_and_skip_steering_axis_of_rear(
        tmp_path, monkeypatch):
    """kc_steer_compliance.png: a title per panel and a suptitle naming the car;
    kc_wheel_travel.png names the car and leaves caster / KPI / scrub of the
    non-steered (multi-link) rear out, saying so."""
    import matplotlib.pyplot as plt

    from flexpipe.vehicle.suspension.kc_output import write

    res = fp.kc(SAMPLE, n=3, travel=0.02)
    figs = []
    close = plt.close
    monkeypatch.setattr(plt, "close", lambda fig=None: (figs.append(fig), close(fig)))
    write(res, tmp_path, car="my sedan")
    travel, steer = figs[-2], figs[-1]
    assert travel._suptitle.get_text().startswith("my sedan: ")
    assert steer._suptitle.get_text().startswith("my sedan: ")
    titles = [ax.get_title() for ax in steer.axes]
    assert all(titles) and "static steer" in titles[0] and "(front)" in titles[0]
    assert "longitudinal" in titles[1] and "lateral" in titles[2]
    by_label = {ax.get_xlabel().split("\n")[0]: ax for ax in travel.axes}
    for q in ("caster [deg]", "kpi [deg]", "scrub radius [mm]"):
        ax = by_label[q]
        assert ax.get_legend_handles_labels()[1] == ["front"]
        assert "rear: not steered" in ax.get_xlabel()
    assert by_label["camber [deg]"].get_legend_handles_labels()[1] == ["front", "rear"]
