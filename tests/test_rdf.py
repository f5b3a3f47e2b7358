"""Adams 2D road data files (``.rdf``): every road type's heights against its shape in
closed form (written here from the format's definition, not from flexpipe), units,
track assignment, oblique planks, and the reader's errors."""

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from flexpipe.cli import main
from flexpipe.errors import InputError
from flexpipe.roads import load_road, read_csv, read_rdf

ROOT = Path(__file__).resolve().parents[1]


def _rdf(tmp_path, road_type, params, *, length="mm", angle="degrees", extra="", name="r"):
    lines = [f"{k} = {v}" for k, v in params.items()]
    text = (f"[UNITS]\n LENGTH = '{length}'\n ANGLE = '{angle}'\n[MODEL]\n METHOD = '2D'\n"
            f" ROAD_TYPE = '{road_type}'\n[PARAMETERS]\n " + "\n ".join(lines) + "\n" + extra)
    path = tmp_path / f"{name}.rdf"
    path.write_text(text)
    return path


def test_plank_with_bevels_is_the_chamfered_cleat(tmp_path):
    """HEIGHT 15, START 20000, LENGTH 50, BEVEL 5 (mm): vertical sides to 10 mm, 45-degree
    chamfers to 15 mm at 20.005 and 20.045 m."""
    road = read_rdf(_rdf(tmp_path, "plank", {"HEIGHT": 15, "START": 20000, "LENGTH": 50,
                                             "BEVEL_EDGE_LENGTH": 5}))

    def plank(x):  # the chamfered cleat, from its definition
        u = x - 20.0
        if u < 0 or u > 0.05:
            return 0.0
        return min(0.015, 0.010 + min(u, 0.05 - u))

    xs = [19.0, 19.9999, 20.0001, 20.002, 20.005, 20.025, 20.044, 20.0499, 20.0501, 500.0]
    for lateral in (-0.8, 0.0, 0.7):
        got = [road.height(x, lateral) for x in xs]
        np.testing.assert_allclose(got, [plank(x) for x in xs], atol=1e-9)
    assert road.x[0] == 0.0 and road.x[-1] >= 1000.0   # flat to 1 km past the plank


def test_units_metres_and_millimetres_give_one_road(tmp_path):
    mm = read_rdf(_rdf(tmp_path, "plank", {"HEIGHT": 15, "START": 20000, "LENGTH": 50,
                                           "BEVEL_EDGE_LENGTH": 5}, name="mm"))
    m = read_rdf(_rdf(tmp_path, "plank", {"HEIGHT": 0.015, "START": 20, "LENGTH": 0.05,
                                          "BEVEL_EDGE_LENGTH": 0.005}, length="meter",
                      name="m"))
    np.testing.assert_allclose(mm.x, m.x, rtol=0, atol=1e-12)
    np.testing.assert_allclose(mm.left, m.left, rtol=0, atol=1e-15)


def test_rounded_plank_edges_are_quarter_circles(tmp_path):
    """EDGE_ROUNDED = 1: the top corners are arcs of radius BEVEL_EDGE_LENGTH (within
    1.3e-4 of it, the chord error of 48 segments); a groove (HEIGHT < 0) is the mirror."""
    r, h = 0.02, 0.03
    for sign in (1, -1):
        road = read_rdf(_rdf(tmp_path, "cleat", {"HEIGHT": sign * h, "START": 10,
                                                 "LENGTH": 0.2, "BEVEL_EDGE_LENGTH": r,
                                                 "EDGE_ROUNDED": 1}, length="m"))
        u = np.linspace(0.0, r, 400)
        chord = 1.0 - math.cos(math.pi / 192)   # 48 chords per quarter circle
        for x0, xc in ((10.0 + u, 10.0 + r), (10.2 - u, 10.2 - r)):
            z = sign * road.height(x0, 0.0)
            dist = np.hypot(x0 - xc, z - (h - r))   # from the arc's centre
            assert np.all(dist <= r + 1e-12) and np.all(dist >= r * (1.0 - chord) - 1e-12)
        assert road.height(9.9999989, 0.0) == 0.0   # the vertical side below the arc
        assert road.height(10.0, 0.0) == pytest.approx(sign * (h - r), abs=1e-15)
        assert road.height(10.1, 0.0) == pytest.approx(sign * h, abs=1e-12)


def test_pot_hole_depth_and_its_sign(tmp_path):
    road = read_rdf(_rdf(tmp_path, "pot_hole", {"DEPTH": 50, "START": 1000, "LENGTH": 200}))
    np.testing.assert_allclose(road.height(np.array([0.9, 1.01, 1.19, 1.21]), 0.0),
                               [0.0, -0.05, -0.05, 0.0], atol=1e-12)
    with pytest.warns(UserWarning, match=r"DEPTH = -50 < 0 makes a bump 50 mm high"):
        bump = read_rdf(_rdf(tmp_path, "pothole", {"DEPTH": -50, "START": 1000,
                                                   "LENGTH": 200}))
    assert bump.height(1.1, 0.0) == pytest.approx(0.05)


def test_ramp_roof_and_offset(tmp_path):
    ramp = read_rdf(_rdf(tmp_path, "ramp", {"HEIGHT": -0.1, "START": 5, "SLOPE": 0.5,
                                            "OFFSET": 0.02}, length="m"))
    # falls at 1 in 2 from 5 m to 5.2 m, then holds -0.1 (+ the offset) to the end
    np.testing.assert_allclose(ramp.height(np.array([4.0, 5.1, 5.2, 900.0]), 0.3),
                               np.array([0.0, -0.05, -0.1, -0.1]) + 0.02, atol=1e-12)
    roof = read_rdf(_rdf(tmp_path, "roof", {"HEIGHT": 40, "START": 3000, "LENGTH": 400}))
    np.testing.assert_allclose(roof.height(np.array([3.0, 3.1, 3.2, 3.3, 3.4]), 0.0),
                               [0.0, 0.02, 0.04, 0.02, 0.0], atol=1e-12)


def test_sine_against_its_formula(tmp_path):
    """A sine from START over LENGTH (0 beyond); without LENGTH it runs 1 km."""
    a, wl = 0.01, 2.5
    road = read_rdf(_rdf(tmp_path, "sine", {"AMPLITUDE": a, "WAVE_LENGTH": wl, "START": 10,
                                            "LENGTH": 11.0}, length="m"))
    x = np.linspace(10.0, 21.0, 3001)
    np.testing.assert_allclose(road.height(x, 0.0),
                               a * np.sin(2 * np.pi * (x - 10.0) / wl), atol=3.1e-4 * a)
    assert road.height(21.01, 0.0) == 0.0 and road.height(9.99, 0.0) == 0.0
    endless = read_rdf(_rdf(tmp_path, "sine", {"AMPLITUDE": a, "WAVE_LENGTH": wl,
                                               "START": 10}, length="m", name="endless"))
    assert endless.height(10.0 + 998.125, 0.0) == pytest.approx(a, rel=1e-3)


def _crossings(x, z):
    """Upward zero crossings of the sampled z(x) (linear between samples)."""
    i = np.flatnonzero((z[:-1] < 0) & (z[1:] >= 0))
    return x[i] - z[i] * (x[i + 1] - x[i]) / (z[i + 1] - z[i])


@pytest.mark.parametrize("sweep_type", [0, 1])
def test_sine_sweep_wavelengths_and_amplitude(tmp_path, sweep_type):
    """The cycle lengths at the sweep's start and end are the given wavelengths (within
    the change over one cycle); the linear sweep's spatial frequency rises linearly, the
    logarithmic one's cycles shrink by a constant factor; the envelope is linear."""
    s0, s1, wl0, wl1 = 5.0, 105.0, 4.0, 0.5
    road = read_rdf(_rdf(tmp_path, "sine_sweep", {
        "START": s0, "END": s1, "AMPLITUDE_AT_START": 0.02, "AMPLITUDE_AT_END": 0.005,
        "WAVE_LENGTH_AT_START": wl0, "WAVE_LENGTH_AT_END": wl1, "SWEEP_TYPE": sweep_type},
        length="m"))
    x = np.linspace(s0, s1, 400_001)
    z = road.height(x, 0.0)
    c = _crossings(x, z)
    mid = 0.5 * (c[:-1] + c[1:])
    cycle = np.diff(c)
    if sweep_type == 0:   # spatial frequency linear in distance, 1/wl0 .. 1/wl1
        line = np.polyfit(mid, 1.0 / cycle, 1)
        np.testing.assert_allclose(1.0 / cycle, np.polyval(line, mid), rtol=2e-3)
    else:                 # wavelength linear in distance: each cycle shorter by one factor
        line = np.polyfit(mid, cycle, 1)
        np.testing.assert_allclose(cycle, np.polyval(line, mid), rtol=2e-3)
        q = cycle[1:] / cycle[:-1]
        assert np.ptp(q[:-2]) < 2e-3 * q.mean()
    ends = np.polyval(line, [s0, s1])
    expect = [1 / wl0, 1 / wl1] if sweep_type == 0 else [wl0, wl1]
    np.testing.assert_allclose(ends, expect, rtol=3e-3)
    peaks = np.abs(z).max()
    assert peaks == pytest.approx(0.02, rel=0.02)
    assert road.height(s1 + 0.01, 0.0) == 0.0


def test_poly_line_tracks_by_side_and_as_the_same_csv(tmp_path):
    """Each side of the road reads its own track (no blend at a narrower track), and the
    road is the CSV road of the same points."""
    road = load_road(ROOT / "roads" / "poly_line.rdf")
    rows = [(0.0, 0.0, 0.0), (25.0, 0.0, 0.0), (25.3, -0.04, 0.0), (26.3, -0.04, 0.0),
            (26.6, 0.0, 0.0), (200.0, 0.0, 0.0)]
    csv = tmp_path / "road.csv"
    csv.write_text("distance_m,left_m,right_m\n" + "\n".join(",".join(map(str, r))
                                                           for r in rows) + "\n")
    ref = read_csv(csv)
    s = np.linspace(0.0, 199.0, 4001)
    for lateral in (0.55, 0.75, 1.2):
        np.testing.assert_allclose(road.height(s, lateral), ref.left_height(s), atol=1e-15)
        np.testing.assert_allclose(road.height(s, -lateral), ref.right_height(s), atol=1e-15)


@pytest.mark.parametrize("direction", [30.0, -20.0])
def test_oblique_plank_meets_each_track_at_its_own_distance(tmp_path, direction):
    """DIRECTION turns the plank counter-clockwise from the y axis: at lateral y its edge
    is y tan(DIRECTION) earlier.  The 50 %-height crossing of each lateral line lies there
    within the grid's 2 mm x 1 cm resolution."""
    road = read_rdf(_rdf(tmp_path, "plank", {"HEIGHT": 20, "START": 30000, "LENGTH": 300,
                                             "DIRECTION": direction}))
    t = math.tan(math.radians(direction))
    x = np.linspace(29.0, 31.5, 250_001)
    for y in (-0.8, -0.31, 0.0, 0.45, 0.8):
        z = road.height(x, y)
        rise = x[np.argmax(z >= 0.01)]
        fall = x[len(x) - 1 - np.argmax(z[::-1] >= 0.01)]
        tol = 0.002 + 0.01 * abs(t)
        assert rise == pytest.approx(30.0 - y * t, abs=tol)
        assert fall == pytest.approx(30.3 - y * t, abs=tol)
        assert z.max() == pytest.approx(0.02, abs=1e-12)


def test_info_shows_an_rdf_road(capsys):
    assert main(["info", str(ROOT / "roads" / "plank_15mm.rdf")]) == 0
    out = capsys.readouterr().out
    assert "Adams 2D road, plank" in out and "max 15.00" in out


@pytest.mark.parametrize("road_type,params,extra,key,words", [
    ("plank", {"HEIGHT": 15, "START": 1, "LENGHT": 50}, "", "LENGHT", "did you mean LENGTH"),
    ("plank", {"HEIGHT": 15, "START": 1}, "", "PARAMETERS", "needs LENGTH"),
    ("plank", {"HEIGHT": 15, "START": 1, "LENGTH": 50, "BEVEL_EDGE_LENGTH": 30}, "",
     "BEVEL_EDGE_LENGTH", "min(|HEIGHT|, LENGTH / 2)"),
    ("plank", {"HEIGHT": 15, "START": 1, "LENGTH": 50, "MU_FACTOR_CLEAT": 0.5}, "",
     "MU_FACTOR_CLEAT", "LMUX"),
    ("flat", {"ROTATION_ANGLE_XY_PLANE": 90}, "", "ROTATION_ANGLE_XY_PLANE", "0 or 180"),
    ("stochastic_uneven", {}, "", "ROAD_TYPE", "iso8608"),
    ("drum", {}, "", "ROAD_TYPE", "rig"),
    ("plnak", {}, "", "ROAD_TYPE", "did you mean 'plank'"),
    ("roof", {"HEIGHT": 15, "START": 1, "LENGTH": 50, "DIRECTION": 10}, "", "DIRECTION",
     "only a plank or a pot hole"),
    ("sine_sweep", {"START": 1, "END": 2, "AMPLITUDE_AT_START": 1, "AMPLITUDE_AT_END": 1,
                    "WAVE_LENGTH_AT_START": 100, "WAVE_LENGTH_AT_END": 200}, "",
     "WAVE_LENGTH_AT_END", "must not exceed"),
    ("poly_line", {}, "(XZ_DATA)\n{}\n0 0 0\n5 1 1\n4 0 0\n", "XZ_DATA", "must increase"),
    ("poly_line", {}, "", "PARAMETERS", "(XZ_DATA)"),
    ("ramp", {"HEIGHT": 15, "START": 1, "SLOPE": 0}, "", "SLOPE", "must be > 0"),
])
def test_bad_files_name_file_line_and_key(tmp_path, road_type, params, extra, key, words):
    path = _rdf(tmp_path, road_type, params, extra=extra)
    with pytest.raises(InputError) as err, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        read_rdf(path)
    e = err.value
    assert str(path) in str(e) and e.line is not None and e.key == key
    assert words in str(e)


def test_method_and_units_are_required(tmp_path):
    path = tmp_path / "r.rdf"
    path.write_text("[UNITS]\n LENGTH = 'mm'\n[MODEL]\n METHOD = '3D'\n ROAD_TYPE = 'plank'\n")
    with pytest.raises(InputError, match=r"METHOD = '3D' is not read.*\.crg"):
        read_rdf(path)
    path.write_text("[MODEL]\n METHOD = '2D'\n ROAD_TYPE = 'flat'\n")
    with pytest.raises(InputError, match=r"LENGTH is not given"):
        read_rdf(path)


def test_car_meets_the_plank_where_the_file_puts_it():
    """The rigid prismatic sample at 40 km/h over roads/plank_15mm.rdf (START 30000 mm,
    LENGTH 50 mm): each tyre's load peaks while its wheel centre is over the cleat (to
    within one 11 mm output row), the front and rear axles one wheelbase apart.  (The
    point contact's road normal, from the heights +-50 mm around the wheel, lets the load
    rise from 50 mm before the cleat: README, known limits.)"""
    from flexpipe.vehicle import simulate
    from flexpipe.vehicle.spec import load_car

    car = ROOT / "cars" / "sedan.toml"
    res = simulate(car, road=ROOT / "roads" / "plank_15mm.rdf", speed=40 / 3.6, t_end=3.0,
                   body="rigid")
    assert res.status == 0
    centres = {c.name: c.wheel_center for c in load_car(car).corners}
    row = 40 / 3.6 * 1e-3
    for corner in ("fl", "fr", "rl", "rr"):
        fz = np.asarray(res[f"tire_{corner}_Fz"])
        x_wheel = np.asarray(res["x"]) + centres[corner][0] * np.cos(np.asarray(res["yaw"]))
        i = int(np.argmax(fz))
        assert fz[i] - fz[0] > 2000.0
        assert 30.0 - row <= x_wheel[i] <= 30.05 + row, (corner, x_wheel[i])


def test_body_band_of_a_corner_sampled_road_is_that_of_its_shape():
    """The flexible body's band comes from the road's slope spectrum: the rdf roads,
    sampled at their corners only, give the band of the same shape sampled every mm."""
    from flexpipe.roads import Road
    from flexpipe.vehicle.bodymodel import choose_band

    for name in ("plank_15mm.rdf", "poly_line.rdf"):
        road = load_road(ROOT / "roads" / name)
        x = np.arange(road.x[0], road.x[-1], 1e-3)
        dense = Road(x=x, left=road.left_height(x), right=road.right_height(x))
        for v in (5.0, 12.0, 25.0):
            assert choose_band(v, road, hi=1e4) == pytest.approx(
                choose_band(v, dense, hi=1e4), rel=0.02)
