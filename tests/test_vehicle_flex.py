"""Flexible and full body in the car, on a small ladder-frame test car (fast to reduce).

References: the car's weight (statics), the rigid-body mass properties of the frame
computed here from its beam geometry, and the full (unreduced-band) body for the
reduction check; plus the cache behaviour and the hardpoint/mass input errors.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.roads import harmonic
from flexpipe.tires import tire_from_file
from flexpipe.vehicle import bodymodel as bm
from flexpipe.vehicle import compare, load_car, simulate
from flexpipe.vehicle.corners import static_loaded_radius, static_wheel_loads
from flexpipe.vehicle.simulation import prepare
from flexpipe.vehicle.spec import CORNERS

ROOT = Path(__file__).resolve().parents[1]
SEDAN = ROOT / "cars" / "sedan.toml"
TIRE = ROOT / "tires" / "sedan_205_55R16.tir"
RHO, BOX = 7850.0, (0.08, 0.12, 0.003)


def _box(b, h, t):
    bi, hi = b - 2 * t, h - 2 * t
    A = b * h - bi * hi
    return A, (h * b**3 - hi * bi**3) / 12, (b * h**3 - bi * hi**3) / 12, \
        4 * ((b - t) * (h - t)) ** 2 * t / (2 * ((b - t) + (h - t)))


def _frame():
    """Ladder frame (m): rails, cross members and two front towers; nodes and bars."""
    pts, bars, key = [], [], {}

    def node(p):
        k = tuple(np.round(p, 6))
        if k not in key:
            key[k] = len(pts)
            pts.append(np.array(p, dtype=float))
        return key[k]

    def line(a, b, n):
        a, b = np.asarray(a, float), np.asarray(b, float)
        ids = [node(a + (b - a) * i / n) for i in range(n + 1)]
        bars.extend(zip(ids[:-1], ids[1:], strict=True))

    for y in (-0.55, 0.55):
        line((0.6, y, 0.4), (-3.3, y, 0.4), 26)
        line((0.0, y, 0.4), (0.0, y, 0.75), 4)
    for x in (0.6, 0.0, -1.35, -2.7, -3.3):
        line((x, -0.55, 0.4), (x, 0.55, 0.4), 10)
    return np.array(pts), np.array(bars)


def _write_bdf(path: Path):
    X, bars = _frame()
    A, Iy, Iz, J = _box(*BOX)
    lines = ["BEGIN BULK", f"MAT1,1,2.1e11,,0.3,{RHO}", f"PBAR,1,1,{A:.6e},{Iz:.6e},{Iy:.6e},"
             f"{J:.6e}"]
    lines += [f"GRID,{i + 1},,{p[0]:.6f},{p[1]:.6f},{p[2]:.6f}" for i, p in enumerate(X)]
    for e, (a, b) in enumerate(bars, 1):
        v = (1.0, 0.0, 0.0) if abs(X[b, 2] - X[a, 2]) > 1e-9 else (0.0, 0.0, 1.0)
        lines.append(f"CBAR,{e},1,{a + 1},{b + 1},{v[0]},{v[1]},{v[2]}")
    lines.append("ENDDATA")
    path.write_text("\n".join(lines) + "\n")
    L = np.linalg.norm(X[bars[:, 1]] - X[bars[:, 0]], axis=1)
    return RHO * A * L.sum()


def _car_text(mesh: Path, wheel_z=(0.35, 0.35)) -> str:
    """The sedan's corners, steering and drive on the frame body."""
    text = SEDAN.read_text()
    body_end = text.index("# Corners:")
    head = f"""[car]
name = "frame"

[body]
mesh = "{mesh.as_posix()}"
damping_ratio = 0.02
interface_radius_m = 0.08

[body.points]
middle = [-1.35, 0.0, 0.4]

[[body.mass]]
name = "cabin"
mass_kg = 900.0
position_m = [-1.4, 0.0, 0.4]
spread_radius_m = 1.2

[[body.mass]]
name = "engine"
mass_kg = 200.0
position_m = [0.2, 0.0, 0.4]
spread_radius_m = 0.5

"""
    rest = text[body_end:].replace('"../', f'"{ROOT.as_posix()}/')
    rest = rest.replace("hardpoint_m = [0.0, 0.65, 0.85]", "hardpoint_m = [0.0, 0.55, 0.75]")
    rest = rest.replace("hardpoint_m = [0.0, -0.65, 0.85]", "hardpoint_m = [0.0, -0.55, 0.75]")
    rest = rest.replace("hardpoint_m = [-2.75, 0.55, 0.65]", "hardpoint_m = [-2.7, 0.55, 0.4]")
    rest = rest.replace("hardpoint_m = [-2.75, -0.55, 0.65]", "hardpoint_m = [-2.7, -0.55, 0.4]")
    rest = rest.replace("wheel_center_m = [-2.75,", "wheel_center_m = [-2.7,")
    rest = re.sub(r"(wheel_center_m = \[0\.0, -?0\.775, )[0-9.]+\]",
                  lambda m: f"{m.group(1)}{wheel_z[0]:.5f}]", rest)
    rest = re.sub(r"(wheel_center_m = \[-2\.7, -?0\.775, )[0-9.]+\]",
                  lambda m: f"{m.group(1)}{wheel_z[1]:.5f}]", rest)
    return head + rest


@pytest.fixture(scope="module")
def frame_car(tmp_path_factory):
    """The test car, its wheel-centre heights set to the tyre's static loaded radius."""
    d = tmp_path_factory.mktemp("frame")
    mp = pytest.MonkeyPatch()
    mp.setenv("FLEXPIPE_CACHE", str(d / "cache"))
    frame_mass = _write_bdf(d / "frame.bdf")
    path = d / "frame.toml"
    path.write_text(_car_text(d / "frame.bdf"))
    with pytest.raises(InputError, match="static loaded radius"):
        prepare(load_car(path), body="rigid", speed=0.0)  # the placeholder z is off
    car = load_car(path)
    rb = bm.rigid_properties(car)
    N = static_wheel_loads(car, rb.mass, rb.center_of_mass)
    tire = tire_from_file(TIRE)
    z = [static_loaded_radius(tire, N[0]), static_loaded_radius(tire, N[2])]
    path.write_text(_car_text(d / "frame.bdf", z))
    yield load_car(path), frame_mass, d
    mp.undo()


def test_body_mass_is_frame_plus_added_masses(frame_car):
    car, frame_mass, _ = frame_car
    rb = bm.rigid_properties(car)
    assert rb.mass == pytest.approx(frame_mass + 900.0 + 200.0, rel=1e-9)
    # the cabin and engine masses sit where the file puts them: combined centre of mass
    X, bars = _frame()
    mid = 0.5 * (X[bars[:, 0]] + X[bars[:, 1]])
    L = np.linalg.norm(X[bars[:, 1]] - X[bars[:, 0]], axis=1)
    c_frame = (mid * L[:, None]).sum(axis=0) / L.sum()
    c = (frame_mass * c_frame + 900.0 * np.array([-1.4, 0, 0.4])
         + 200.0 * np.array([0.2, 0, 0.4])) / rb.mass
    np.testing.assert_allclose(rb.center_of_mass, c, atol=1e-9)


def test_flexible_car_statics_and_cache(frame_car, monkeypatch):
    car, _, d = frame_car
    prep = prepare(car, body="flexible", speed=0.0)
    assert not prep["reduction"]["cached"]
    assert (Path(prep["reduction"]["path"])).is_file()

    def no_reduction(*a, **k):
        raise AssertionError("the cached body was reduced again")

    # a cache hit does no reduction at all (deterministic, unlike a timing comparison,
    # which a loaded machine made fail: 37 ms reduction vs 314 ms cached load)
    import flexpipe.reduction

    monkeypatch.setattr(flexpipe.reduction, "reduce", no_reduction)
    again = prepare(car, body="flexible", speed=0.0)
    assert again["reduction"]["cached"]
    np.testing.assert_array_equal(again["flexbody"].K, prep["flexbody"].K)
    monkeypatch.undo()
    fb = prep["flexbody"]
    assert sorted(fb.interface_names) == sorted(CORNERS)
    r = simulate(car, speed=0.0, t_end=1.0, body="flexible", prepared=prep)
    assert r.status == 0, r.message
    end = r.t > 0.7
    W = r.info["mass_body_kg"] * 9.81
    hub = sum(r[f"hub_{c}_z"] for c in CORNERS)[end].mean()
    assert hub == pytest.approx(W, rel=0.005)
    assert abs(r["z"][end]).max() < 2e-3


def test_full_against_flexible_hub_force(frame_car):
    """Reduction check in the car: the band-limited body against the 300 Hz body."""
    car, _, _ = frame_car
    road = harmonic(wavelength=1.0, amplitude=0.005, length=200.0, dx=0.05)
    runs = {b: simulate(car, road=road, speed=15.0, t_end=1.0, body=b) for b in
            ("full", "flexible", "rigid")}
    for r in runs.values():
        assert r.status == 0, r.message
    assert runs["full"].info["n_elastic_modes"] > runs["flexible"].info["n_elastic_modes"]
    d = compare(runs["full"], runs["flexible"], ["hub_fl_z"], t_from=0.3)["hub_fl_z"]
    assert d["rel_rms_diff"] < 0.02
    # the flexible frame differs from the rigid one more than from the full body
    dr = compare(runs["full"], runs["rigid"], ["hub_fl_z"], t_from=0.3)["hub_fl_z"]
    assert dr["rms_diff"] > d["rms_diff"]


def test_hardpoint_off_the_body_is_reported(frame_car, tmp_path):
    car, _, d = frame_car
    text = Path(car.file).read_text().replace("hardpoint_m = [-2.7, 0.55, 0.4]",
                                              "hardpoint_m = [-2.7, 0.55, 1.4]")
    path = tmp_path / "off.toml"
    path.write_text(text)
    with pytest.raises(InputError, match=r"corners\.rl\.hardpoint_m.*off the body"):
        bm.rigid_properties(load_car(path), cache=False)


def test_spread_mass_keeps_total_and_centre():
    X, _ = _frame()
    nodes, w = bm.spread_mass(X, 123.0, (-1.0, 0.2, 0.4), 0.6)
    assert w.min() > 0
    assert w.sum() == pytest.approx(123.0, rel=1e-12)
    np.testing.assert_allclose((X[nodes] * w[:, None]).sum(axis=0) / w.sum(), [-1.0, 0.2, 0.4],
                               atol=1e-9)
    with pytest.raises(InputError, match="cannot be spread"):
        bm.spread_mass(X, 10.0, (-1.0, 0.0, 2.5), 0.3)
