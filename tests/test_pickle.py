"""Standard-pickle round trips of what a process pool or a Dask worker receives: a car, a
road, a prepared body (prepare() output, a reduced FlexBody) and a Result; a run from the
unpickled pieces equals the run from the originals."""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest
from _rigidcar import rigid_sedan

import flexpipe as fp
from flexpipe.mesh.generate import box
from flexpipe.roads import load_road
from flexpipe.vehicle.simulation import prepare

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module", autouse=True)
def _cache(tmp_path_factory):
    mp = pytest.MonkeyPatch()
    mp.setenv("FLEXPIPE_CACHE", str(tmp_path_factory.mktemp("cache")))
    yield
    mp.undo()


def _rt(obj):
    return pickle.loads(pickle.dumps(obj, protocol=pickle.HIGHEST_PROTOCOL))


def test_car_road_prepared_and_result_pickle_and_rerun_identically(tmp_path):
    car_file = rigid_sedan(tmp_path)
    car = fp.load_car(car_file)
    road = load_road(ROOT / "roads" / "iso_c_200m.toml")
    # prepare() takes a car file and a road file like simulate() does
    prep = prepare(car_file, body="rigid", speed=15.0, road=ROOT / "roads" / "iso_c_200m.toml")
    car2, road2, prep2 = _rt(car), _rt(road), _rt(prep)
    assert car2.corner("fl").spring_rate == car.corner("fl").spring_rate
    assert np.array_equal(road2.left, road.left) and road2.track_width == road.track_width
    assert type(prep2["tires"][0].mf.c).__module__ == "flexpipe.tires.pac2002"
    kw = dict(speed=15.0, t_end=0.3, body="rigid")
    a = fp.simulate(car, road=road, prepared=prep, **kw)
    b = fp.simulate(car2, road=road2, prepared=prep2, **kw)
    assert a.status == 0
    for name in a.channels:
        assert np.array_equal(a[name], b[name]), name
    r2 = _rt(a)
    assert r2.status == a.status and r2.message == a.message and r2.info == a.info
    assert all(np.array_equal(r2[n], a[n]) for n in a.channels)


def test_reduced_flexbody_pickles_bit_for_bit():
    bar = box(1.0, 0.1, 0.1, 10, 2, 2, cell="hexahedron")
    fe = fp.assemble(bar, fp.Material(E=210e9, nu=0.3, rho=7850.0))
    ends = [fp.Interface((0.0, 0.05, 0.05), radius=0.08, name="left"),
            fp.Interface((1.0, 0.05, 0.05), radius=0.08, name="right")]
    body = fp.reduce(fe, ends, method="craig-bampton", n_modes=6)
    b2 = _rt(body)
    for name in ("nodes", "modes", "frequencies_hz", "M", "K", "D", "inertia_origin"):
        assert np.array_equal(getattr(b2, name), getattr(body, name)), name
    assert dict(b2.meta) == dict(body.meta) and [i.name for i in b2.interfaces] == ["left",
                                                                                   "right"]
    inv, inv2 = body.invariants.as_dict(), b2.invariants.as_dict()
    assert inv.keys() == inv2.keys()
    assert all(np.array_equal(inv[k], inv2[k]) for k in inv)
