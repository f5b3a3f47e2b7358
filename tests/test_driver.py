"""Paths, path projection, pure-pursuit tracking and the PI speed controller.

References: closed-form geometry (circle projection, the slalom/ISO 3888-1 definitions:
ISO 3888-1 section lengths 15/30/25/25/15/15 m, lane widths 1.1b+0.25, 1.2b+0.25,
1.3b+0.25 m, lane offset 3.5 m), and the steady-state force balance of the point mass
(drive force = rolling resistance + aerodynamic drag).
"""

from __future__ import annotations

import math
import pathlib

import numpy as np
import pytest

from flexpipe.driver import (
    KinematicBicycle,
    Path,
    PurePursuit,
    SpeedPI,
    iso3888_1,
    iso3888_1_lanes,
    read_driver,
    read_path,
    simulate,
    slalom,
    straight,
)
from flexpipe.errors import InputError

REPO = pathlib.Path(__file__).resolve().parents[1]
KMH = 1.0 / 3.6


@pytest.fixture(scope="module")
def driver():
    return read_driver(REPO / "paths" / "driver.toml")


def test_projection_on_a_circle_matches_closed_form():
    r = 50.0
    th = np.linspace(0.0, np.pi, 3001)
    path = Path.from_xy(r * np.sin(th), r * (1.0 - np.cos(th)))    # left turn from the origin
    rng = np.random.default_rng(2)
    phi = rng.uniform(0.05, np.pi - 0.05, 300)
    d = rng.uniform(-3.0, 3.0, 300)               # radial offset, positive outward
    px, py = (r + d) * np.sin(phi), r - (r + d) * np.cos(phi)
    s, lateral = path.project(px, py)
    chord_sag = r * (1.0 - math.cos(0.5 * np.pi / 3000))
    seg = r * np.pi / 3000
    np.testing.assert_allclose(s, r * phi, atol=3.0 / r * seg / 2 + 1e-4)
    np.testing.assert_allclose(lateral, -d, atol=2 * chord_sag + 1e-9)   # outside = right
    # scalar queries (hinted walk) agree with the vectorized search
    order = np.argsort(phi)
    scalar = np.array([path.project(float(px[i]), float(py[i])) for i in order])
    np.testing.assert_allclose(scalar[:, 0], s[order], atol=1e-9)
    np.testing.assert_allclose(scalar[:, 1], lateral[order], atol=1e-9)
    assert np.max(np.abs(path.curvature[5:-5] - 1.0 / r)) < 1e-4


def test_point_at_continues_straight_beyond_the_ends():
    path = straight(10.0, ds=1.0, heading=0.5)
    x, y = path.point_at(14.0)
    assert (x, y) == pytest.approx((14.0 * math.cos(0.5), 14.0 * math.sin(0.5)))
    assert path.project(20.0 * math.cos(0.5), 20.0 * math.sin(0.5))[0] == pytest.approx(20.0)


def test_slalom_passes_cones_alternately():
    spacing, offset = 18.0, 0.8
    path = slalom(cone_spacing=spacing, n_cones=6, offset=offset, lead_in=40.0, lead_out=40.0)
    cones = 40.0 + spacing * np.arange(6)
    y_at = np.interp(cones, path.x, path.y)
    np.testing.assert_allclose(y_at, offset * (-1.0) ** np.arange(6), atol=1e-6)
    assert abs(path.y[0]) < 1e-12 and abs(path.y[-1]) < 1e-12
    # curvature continuous, peak near the steady value offset (pi/spacing)^2
    assert np.max(np.abs(path.curvature)) < 1.1 * offset * (np.pi / spacing) ** 2
    with pytest.raises(InputError, match="lead_in"):
        slalom(cone_spacing=18.0, n_cones=3, offset=1.0, lead_in=10.0, lead_out=40.0)


def test_iso3888_1_geometry_from_the_standard():
    b = 1.8
    lanes = {la["section"]: la for la in iso3888_1_lanes(vehicle_width=b, lead_in=50.0)}
    widths = {1: 1.1 * b + 0.25, 3: 1.2 * b + 0.25, 5: 1.3 * b + 0.25, 6: 1.3 * b + 0.25}
    starts = 50.0 + np.cumsum([0, 15, 30, 25, 25, 15, 15])
    for sec, w in widths.items():
        assert lanes[sec]["y_left"] - lanes[sec]["y_right"] == pytest.approx(w)
        assert lanes[sec]["x_start"] == pytest.approx(starts[sec - 1])
        assert lanes[sec]["x_end"] == pytest.approx(starts[sec])
    assert lanes[3]["y_right"] - lanes[1]["y_right"] == pytest.approx(3.5)
    assert lanes[5]["y_right"] == pytest.approx(lanes[1]["y_right"])
    path = iso3888_1(vehicle_width=b)
    assert path.x[-1] == pytest.approx(50.0 + 125.0 + 50.0)
    for la in lanes.values():      # the centre line runs through the middle of every lane
        m = (path.x >= la["x_start"]) & (path.x <= la["x_end"])
        np.testing.assert_allclose(path.y[m], 0.5 * (la["y_left"] + la["y_right"]), atol=1e-9)


@pytest.mark.parametrize("path_file", ["slalom_18m.toml", "iso3888_1.toml"])
def test_tracking_at_60_kmh_within_0p3_m(driver, path_file):
    steering, speed = driver
    path = read_path(REPO / "paths" / path_file)
    car = KinematicBicycle(wheelbase=steering.wheelbase, rear_to_cg=steering.rear_axle_offset)
    v = 60.0 * KMH
    run = simulate(car, steering.with_path(path), speed, v_target=v,
                   t_end=(path.length - 5.0) / v, dt=0.01)
    assert np.max(np.abs(run["lateral"])) < 0.3
    assert run["s"][-1] > path.length - 10.0
    if path_file == "iso3888_1.toml":        # the car body passes every gate
        for la in iso3888_1_lanes(vehicle_width=1.8, lead_in=50.0):
            m = (run["x"] >= la["x_start"]) & (run["x"] <= la["x_end"])
            assert np.all(run["y"][m] - 0.9 > la["y_right"]) and \
                np.all(run["y"][m] + 0.9 < la["y_left"])


def test_tracking_of_a_harder_slalom(driver):
    steering, speed = driver
    path = slalom(cone_spacing=18.0, n_cones=8, offset=1.0, lead_in=40.0, lead_out=60.0)
    v = 60.0 * KMH
    run = simulate(KinematicBicycle(), steering.with_path(path), speed, v_target=v,
                   t_end=(path.length - 5.0) / v)
    assert np.max(np.abs(run["lateral"])) < 0.3


def test_speed_pi_holds_target_within_1_kmh(driver):
    _, speed = driver
    car = KinematicBicycle()
    steering = PurePursuit(wheelbase=car.wheelbase, rear_axle_offset=car.rear_to_cg)
    target = 60.0 * KMH
    run = simulate(car, steering.with_path(straight(1000.0)), speed, v_target=target,
                   t_end=40.0, v0=40.0 * KMH, dt=0.01)
    late = run["t"] > 25.0
    assert np.max(np.abs(run["v"][late] - target)) < 1.0 * KMH
    # steady state: wheel torque balances rolling resistance and drag
    resist = car.mass * 9.81 * car.rolling_resistance + 0.6 * car.drag_area * target**2
    assert run["torque"][-1] == pytest.approx(resist * car.wheel_radius, rel=0.01)
    # overshoot after the drive-torque saturation stays small (anti-windup)
    start = simulate(car, steering.with_path(straight(1000.0)), speed, v_target=target,
                     t_end=40.0, v0=0.0, dt=0.01)
    assert np.any(start["torque"] == speed.drive_torque_max)
    assert np.max(start["v"]) < target + 1.0 * KMH


def test_speed_pi_brakes_and_antiwindup_logic():
    pi = SpeedPI(kp=100.0, ki=10.0, drive_torque_max=500.0, brake_torque_max=900.0)
    assert pi.torque(10.0, 30.0, 0.1) == -900.0          # saturated braking
    assert pi.integral == 0.0                             # no wind-up into saturation
    assert pi.torque(10.0, 9.0, 0.1) == pytest.approx(100.0 * 1.0 + 10.0 * 0.1)
    pi.reset()
    assert pi.integral == 0.0


def test_path_that_ends_before_the_run(driver):
    steering, speed = driver
    path = straight(100.0)
    with pytest.raises(InputError, match="100.0 m long") as info:
        simulate(KinematicBicycle(), steering.with_path(path), speed, v_target=20.0,
                 t_end=10.0)
    assert "200.0 m" in str(info.value)
    path.require_length(99.0)
    with pytest.raises(InputError, match="needs 120.0 m"):
        path.require_length(100.0, start=20.0, what="the slalom")


@pytest.mark.parametrize(("content", "line", "what"), [
    ("x_m,y_m\n0,0\n1,nan\n", 3, "non-finite"),
    ("0,0\n1,0\n1,0\n", 3, "repeats"),
    ("0,0\n1,0\n1,0,3\n", 3, "columns"),
    ("0,0\n1,0\n0.5,0\n", 3, "turns by 180"),
])
def test_path_csv_bad_input_names_file_and_line(tmp_path, content, line, what):
    f = tmp_path / "bad_path.csv"
    f.write_text(content)
    with pytest.raises(InputError, match=what) as info:
        read_path(f)
    assert "bad_path.csv" in str(info.value) and f"line {line}" in str(info.value)


@pytest.mark.parametrize(("name", "words"), [
    ("slalom", ["no such path file", "'straight'", "'road'", ".csv", ".toml"]),
    ("slalom_18m", ["no such path file", "slalom_18m.toml", "'straight'", "'road'"]),
    ("track.txt", ["unknown path file type '.txt'", "'straight'", "'road'", ".csv"]),
])
def test_path_name_that_is_no_file_lists_the_file_types_and_keywords(tmp_path, monkeypatch,
                                                                     name, words):
    """``--path slalom``: not a file and not a keyword; the error says there is no such
    file (with the sample it probably meant) and lists the file types and the keywords."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "slalom_18m.toml").write_text((REPO / "paths" / "slalom_18m.toml").read_text())
    (tmp_path / "track.txt").write_text("0,0\n1,0\n")
    with pytest.raises(InputError) as info:
        read_path(name)
    assert info.value.file is not None and str(info.value.file) == name
    for w in words:
        assert w in str(info.value), str(info.value)


def test_sample_path_csv_is_the_described_arc():
    path = read_path(REPO / "paths" / "sample_xy.csv")
    # 30 m straight + quarter circle of radius 50 m + 30 m straight (chords shorten the arc)
    assert path.length == pytest.approx(30.0 + 25.0 * np.pi + 30.0, rel=1e-3)
    assert path.heading[-1] - path.heading[0] == pytest.approx(np.pi / 2, abs=0.03)


def test_driver_data_validation(tmp_path):
    f = tmp_path / "drv.toml"
    f.write_text("[steering]\nwheelbase_m = 2.7\nlookahead_gain = 1.0\n"
                 "[speed]\nkp_Nm_s_per_m = 1\nki_Nm_per_m = 1\n"
                 "drive_torque_max_Nm = 1\nbrake_torque_max_Nm = 1\n")
    with pytest.raises(InputError, match="lookahead_gain") as info:
        read_driver(f)
    assert "drv.toml" in str(info.value)
    with pytest.raises(InputError, match="must be > 0"):
        PurePursuit.from_dict({"wheelbase_m": -1.0})
    with pytest.raises(InputError, match="no path"):
        PurePursuit(wheelbase=2.7).steer(0.0, 0.0, 0.0, 10.0)
