"""A road that does not start at distance 0 is driven on.

Finding: a CSV road from 100 to 130 m with a bump at 110 m was never driven on: the car
started at x = 5.75 m on the held first sample (flat) and the run "completed".  The
default straight path now starts at the road's first sample, so the car starts at the
same run-in as on a road starting at 0 and the run equals the unshifted one; a path that
cannot move (a file, a Path) is refused when the road does not lie under it.
"""

from __future__ import annotations

import math
import pathlib

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.roads import Road, flat, read_csv
from flexpipe.roads.refline import ReferenceLine
from flexpipe.vehicle import simulate
from flexpipe.vehicle.run_inputs import START_MARGIN_M, check_run
from flexpipe.vehicle.spec import load_car

REPO = pathlib.Path(__file__).resolve().parents[1]
CAR = REPO / "cars" / "sedan.toml"
BUMP = REPO / "roads" / "bump.csv"


def _shifted_bump(tmp_path, offset=100.0):
    """roads/bump.csv with every distance + ``offset`` m (written here, line by line)."""
    out = []
    for line in BUMP.read_text().splitlines():
        if line[:1].isdigit():
            d, rest = line.split(",", 1)
            line = f"{float(d) + offset:.3f},{rest}"
        out.append(line)
    path = tmp_path / "bump_at_100.csv"
    path.write_text("\n".join(out) + "\n")
    return path


def test_road_starting_at_100_m_gives_the_run_of_the_road_at_0(tmp_path):
    shifted = _shifted_bump(tmp_path)
    assert read_csv(shifted).x[0] == 100.0
    kw = dict(speed=60 / 3.6, t_end=0.6, body="rigid")
    ref = simulate(CAR, road=BUMP, **kw)
    run = simulate(CAR, road=shifted, **kw)
    assert ref.status == 0 and run.status == 0
    # the car starts at the same run-in from the road's first sample: START_MARGIN_M
    # beyond the rear wheels (body origin at x = 0 on the car), placed there at the design
    # position; row 0 is the state after settling at rest, in which the suspension's
    # side-view geometry has moved the body origin by micrometres (4.5e-6 m)
    start = abs(min(c.wheel_center[0] for c in load_car(CAR).corners)) + START_MARGIN_M
    assert ref["x"][0] == pytest.approx(start, abs=1e-5)
    assert run["x"][0] - 100.0 == pytest.approx(ref["x"][0], abs=1e-9)
    np.testing.assert_allclose(run["x"], ref["x"] + 100.0, atol=1e-6)
    # ... and drives over the 50 mm bump at 110 m as the reference does over the one at 10 m
    for ch in ("hub_fl_z", "tire_fl_Fz", "travel_fl", "z"):
        np.testing.assert_allclose(run[ch], ref[ch], rtol=0,
                                   atol=1e-6 * max(1.0, np.abs(ref[ch]).max()))
    assert np.ptp(run["tire_fl_Fz"]) > 1000.0       # not the flat held first sample


def test_given_path_is_refused_when_the_road_is_not_under_it(tmp_path):
    shifted = _shifted_bump(tmp_path)
    with pytest.raises(InputError) as exc:
        check_run(CAR, road=shifted, path=REPO / "paths" / "sample_xy.csv", speed=60 / 3.6,
                  t_end=0.6, body="rigid")
    msg = str(exc.value)
    start = abs(min(c.wheel_center[0] for c in load_car(CAR).corners)) + START_MARGIN_M
    end = start + 60 / 3.6 * 0.6 + 10.0        # the path's first 30 m run along x
    assert "bump_at_100.csv" in msg and "covers 100 .. 130 m" in msg, msg
    assert f"needs x from 0 to {end:g} m" in msg and "used as given" in msg, msg
    # the same path on the road at 0 is accepted
    check_run(CAR, road=BUMP, path=REPO / "paths" / "sample_xy.csv", speed=30 / 3.6,
              t_end=0.6, body="rigid")


def test_default_path_starts_on_a_placed_road(tmp_path):
    """An OpenCRG-like road placed at (50, 20) heading north: the default straight path
    starts at its first sample along its start heading, and the run is checked against
    the road's u range."""
    n, du = 401, 0.25
    plan = ReferenceLine.from_heading(0.0, du, np.full(n - 1, math.pi / 2), x0=50.0, y0=20.0)
    x = du * np.arange(n)
    road = Road.from_grid(x, np.array([-2.0, 2.0]), np.zeros((n, 2)), plan=plan,
                          name="north")
    a = check_run(CAR, road=road, speed=10.0, t_end=1.0, body="rigid")
    assert a.path.x[0] == pytest.approx(50.0) and a.path.y[0] == pytest.approx(20.0)
    assert a.path.heading[0] == pytest.approx(math.pi / 2)
    px, py = a.path.point_at(a.start)
    u, v = road.to_uv(px, py)
    assert u == pytest.approx(a.start) and v == pytest.approx(0.0, abs=1e-9)
    with pytest.raises(InputError, match=r"covers 0 .. 100 m; 9 s at 36 km/h needs u"):
        check_run(CAR, road=road, speed=10.0, t_end=9.0, body="rigid")


def test_road_at_0_and_no_road_keep_the_path_from_the_origin():
    a = check_run(CAR, road=BUMP, speed=10.0, t_end=1.0, body="rigid")
    length = a.start + 10.0 * 1.0 + 10.0 + 50.0    # run-in, travel, 10 m, 50 m spare
    assert a.path.x[0] == 0.0 and a.path.source == f"straight(length={length:g})"
    b = check_run(CAR, road=None, speed=10.0, t_end=1.0, body="rigid")
    assert b.path.x[0] == 0.0
    with pytest.raises(InputError, match="covers 0 .. 30 m"):
        check_run(CAR, road=flat(30.0), speed=10.0, t_end=3.0, body="rigid")
