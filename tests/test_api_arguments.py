"""Public Python functions refuse a bad argument with an :class:`InputError` that names
the argument (and what would be valid), before any work; valid arguments, including numpy
scalars, ``pathlib.Path`` and numbers given as strings (as ``simulate`` takes them), work.

One parametrized test per function (the API audit's A7-A10, A14-A17, A19)."""

from __future__ import annotations

import importlib
from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.errors import InputError
from flexpipe.fem import Material, assemble
from flexpipe.mesh.generate import box
from flexpipe.roads import read_crg
from flexpipe.roads.generators import flat, iso8608
from flexpipe.roads.road import Road, read_csv
from flexpipe.tires import MagicFormula, Pac2002Tire, read_tir, tire_from_file
from flexpipe.vehicle.result import Result

REPO = Path(__file__).resolve().parents[1]
LINKAGE = REPO / "cars" / "sedan_linkage.toml"
SEDAN = REPO / "cars" / "sedan.toml"
CRG = REPO / "roads" / "sample_bump.crg"
CSV = REPO / "roads" / "bump.csv"
TIR = REPO / "tires" / "sedan_205_55R16.tir"
MESH = REPO / "meshes" / "plate_quad.msh"
SPRING = "corners.fl.spring_rate_N_per_m"


def _raises(call, *names):
    """``call()`` raises an InputError whose message names every one of ``names``."""
    with pytest.raises(InputError) as info:
        call()
    for name in names:
        assert name in str(info.value), (name, str(info.value))
    return info.value


@pytest.fixture(scope="module")
def bar():
    return assemble(box(1.0, 0.2, 0.1, 4, 2, 2), Material(210e9, 0.3, 7850.0))


def _ends():
    return [fp.Interface((0.0, 0.1, 0.05), radius=0.11, name="a"),
            fp.Interface((1.0, 0.1, 0.05), radius=0.11, name="b")]


@pytest.fixture(scope="module")
def body(bar):
    return fp.reduce(bar, _ends(), n_modes=2)


# ----------------------------------------------------------------------------- A7: kc
@pytest.fixture
def no_analysis(monkeypatch):
    """The rig's first analysis fails the test: the argument checks come before it."""
    import flexpipe.vehicle.suspension.kc as kc_module

    def boom(*_a, **_k):
        raise AssertionError("the analysis ran before the argument checks")

    monkeypatch.setattr(kc_module, "parallel_travel", boom)


@pytest.mark.parametrize("kwargs, names", [
    ({"car": 5}, ("car", "int")),
    ({"car": None}, ("car",)),
    ({"car": "sedan"}, ("sedan",)),                        # not a file: the loader's error
    ({"car": "SEDAN_CAR"}, ("car", "prismatic")),           # a Car without [suspension.*]
    ({"n": 0}, ("n must be an integer >= 3",)),
    ({"n": 1}, ("n must be an integer >= 3",)),
    ({"n": 5.5}, ("n must be an integer", "5.5")),
    ({"n": 5.0}, ("n must be an integer",)),
    ({"n": True}, ("n must be an integer",)),
    ({"travel": "abc"}, ("travel must be a number",)),
    ({"travel": -0.08}, ("travel", "(0, 0.5]")),
    ({"travel": 80.0}, ("travel", "80")),                  # millimetres given as metres
    ({"rack_travel": 0.0}, ("rack_travel",)),
    ({"force": float("nan")}, ("force",)),
    ({"axles": ["middle"]}, ("axles", "front", "rear")),
    ({"axles": []}, ("axles",)),
    ({"axles": [1]}, ("axles",)),
    ({"out": "FILE"}, ("out", "is a file")),
    ({"out": "UNDER_FILE"}, ("out", "is a file")),
    ({"out": 5}, ("out", "file path")),
])
def test_kc_refuses_bad_arguments_before_the_analysis(kwargs, names, tmp_path, no_analysis):
    (tmp_path / "f").write_text("x")
    subs = {"SEDAN_CAR": fp.load_car(SEDAN), "FILE": tmp_path / "f",
            "UNDER_FILE": tmp_path / "f" / "kc"}
    kwargs = {k: subs.get(v, v) if isinstance(v, str) else v for k, v in kwargs.items()}
    car = kwargs.pop("car", LINKAGE)
    _raises(lambda: fp.kc(car, **{"n": 3, **kwargs}), *names)


@pytest.mark.parametrize("car, kwargs", [
    ("CAR", {"axles": ["Front"], "travel": "0.01"}),  # a Car; axle names case-insensitive
    (str(LINKAGE), {"axles": "rear", "n": np.int64(3), "travel": np.float32(0.01)}),
])
def test_kc_takes_a_car_and_lenient_valid_arguments(car, kwargs):
    car = fp.load_car(LINKAGE) if car == "CAR" else car
    res = fp.kc(car, **{"n": 3, **kwargs})
    want = "front" if kwargs["axles"] != "rear" else "rear"
    assert list(res.summary) == [want]
    assert res.tables[f"{want}_parallel_travel"]["wheel travel [mm]"][-1] == pytest.approx(10.0)


# ----------------------------------------------------------------------------- A8/A9: reduce
@pytest.mark.parametrize("kwargs, names", [
    ({"f_max": -100.0}, ("f_max", "-100")),
    ({"f_max": "abc"}, ("f_max must be a number",)),
    ({"f_max": 1000.0, "cb_factor": -1.0}, ("cb_factor", "-1")),
    ({"f_max": 1000.0, "cb_factor": "x"}, ("cb_factor",)),
    ({"n_modes": 2, "tol": "x"}, ("tol must be a number",)),
    ({"n_modes": 2, "tol": -1.0}, ("tol", "-1")),
    ({"n_modes": 2, "tol": 0.0}, ("tol",)),
    ({"n_modes": 2, "interface_f_max": "x"}, ("interface_f_max",)),
    ({"n_modes": 2, "interface_f_max": -5.0}, ("interface_f_max",)),
    ({"n_modes": 2, "damping": "abc"}, ("damping", "ratio")),
    ({"n_modes": 2, "damping": -0.1}, ("damping", ">= 0")),
    ({"n_modes": 2, "damping": [[0.1]]}, ("damping",)),
    ({"n_modes": 2, "backend": "mkl"}, ("backend", "superlu", "'mkl'")),
    ({"n_modes": 6.0}, ("n_modes must be an integer",)),
    ({"n_modes": True}, ("n_modes must be an integer",)),
    ({"n_modes": -1}, ("n_modes",)),
    ({"n_modes": 2, "check": "yes"}, ("check must be True or False",)),
    ({"n_modes": 2, "stress": 5}, ("stress",)),
    ({"n_modes": 2, "log": "x"}, ("log",)),
])
def test_reduce_names_each_bad_argument(bar, kwargs, names, monkeypatch):
    red = importlib.import_module("flexpipe.reduction.reduce")  # not the function

    def boom(*_a, **_k):
        raise AssertionError("the reduction ran before the argument checks")

    monkeypatch.setattr(red, "check_mass", boom)
    err = _raises(lambda: fp.reduce(bar, _ends(), **kwargs), *names)
    if "f_max" in kwargs and kwargs.get("cb_factor") is None:
        assert "-300" not in str(err)  # the user's value, not cb_factor * f_max


@pytest.mark.parametrize("kwargs", [
    {"n_modes": np.int64(2), "tol": 1e-8, "damping": 0.02, "backend": "superlu"},
    {"f_max": "400", "cb_factor": np.float64(2.0), "damping": lambda f: 0.01},
    {"n_modes": 2, "interface_f_max": np.float32(5e3), "check": np.bool_(False)},
])
def test_reduce_accepts_valid_arguments(bar, kwargs):
    body = fp.reduce(bar, _ends(), **kwargs)
    assert body.n_elastic >= 2


# ----------------------------------------------------------------------------- A10: Interface
@pytest.mark.parametrize("args, kwargs, names", [
    (((0, 0, 0),), {"nodes": [1.5]}, ("nodes", "integer", "1.5")),
    (((0, 0, 0),), {"nodes": [1.0]}, ("nodes", "integer")),
    (((0, 0, 0),), {"nodes": np.array([0.0, 2.0])}, ("nodes", "integer")),
    (((0, 0, 0),), {"nodes": [True]}, ("nodes", "integer")),
    (("abc",), {"radius": 0.1}, ("point", "3 finite numbers")),
    ((None,), {"radius": 0.1}, ("point",)),
    (((0, 0, 0),), {"radius": "abc"}, ("radius must be a number",)),
    (((0, 0, 0),), {"radius": -0.1}, ("radius", "> 0")),
    (((0, 0, 0),), {"radius": 0.1, "name": 5}, ("name",)),
    (((0, 0, 0),), {"node_set": 3}, ("node_set",)),
])
def test_interface_refuses_bad_arguments(args, kwargs, names):
    _raises(lambda: fp.Interface(*args, **kwargs), *names)


def test_interface_accepts_integer_nodes_and_numeric_radius():
    assert fp.Interface((0, 0, 0), nodes=np.array([3, 1])).nodes == (3, 1)
    assert fp.Interface((0, 0, 0), nodes=[np.int32(2)]).nodes == (2,)
    assert fp.Interface((0, 0, 0), radius="0.1").radius == 0.1
    assert fp.Interface(np.zeros(3), radius=np.float32(0.25)).radius == 0.25


# ----------------------------------------------------------------------------- A14: file paths
def _save_body(body, path):
    return body.save(path)


PATH_FUNCTIONS = {
    "load_car": (fp.load_car, "path"),
    "load_road": (fp.load_road, "spec"),
    "read_crg": (read_crg, "path"),
    "read_csv": (read_csv, "path"),
    "load_body": (fp.load_body, "path"),
    "tire_from_file": (tire_from_file, "path"),
    "read_mesh": (fp.read_mesh, "path"),
    "kc": (fp.kc, "car"),
    "linear_modes": (fp.linear_modes, "car"),
    "FlexBody.save": (None, "path"),
}


@pytest.mark.parametrize("value", [5, None, 2.5, ["cars/sedan.toml"], b"", ""])
@pytest.mark.parametrize("function", list(PATH_FUNCTIONS))
def test_path_arguments_name_the_argument(function, value, body):
    func, name = PATH_FUNCTIONS[function]
    if function == "FlexBody.save":
        func = body.save
    err = _raises(lambda: func(value), name)
    assert "expected str, bytes or os.PathLike" not in str(err)
    assert type(value).__name__ in str(err) or value == ""


def test_load_car_says_dicts_are_no_car_file():
    _raises(lambda: fp.load_car({}), "path", "dict", "overrides")


def test_valid_paths_still_work(body, tmp_path):
    assert fp.load_car(str(SEDAN)).name and fp.load_car(SEDAN).name
    assert fp.load_body(body.save(tmp_path / "b.npz")).n_modes == body.n_modes
    assert fp.load_road(str(CRG)).track_width == 1.5
    assert len(fp.read_mesh(str(MESH)).points) > 0
    assert tire_from_file(str(TIR)).unloaded_radius > 0


# ----------------------------------------------------------------------------- A15: track_width
@pytest.mark.parametrize("call", [
    lambda tw: fp.load_road(CRG, track_width=tw),
    lambda tw: fp.load_road(CSV, track_width=tw),
    lambda tw: read_crg(CRG, track_width=tw),
    lambda tw: read_csv(CSV, track_width=tw),
    lambda tw: flat(20.0, track_width=tw),
    lambda tw: iso8608("A", 50.0, 0.05, 1, track_width=tw),
    lambda tw: Road.from_grid([0.0, 1.0], [-1.0, 1.0], np.zeros((2, 2)), track_width=tw),
    lambda tw: Road(x=[0.0, 1.0], left=[0.0, 0.0], right=[0.0, 0.0], track_width=tw),
], ids=["load_road_crg", "load_road_csv", "read_crg", "read_csv", "flat", "iso8608",
        "from_grid", "Road"])
@pytest.mark.parametrize("bad", ["wide", -1.5, 0.0, float("inf"), [1.5]])
def test_track_width_is_checked(call, bad):
    _raises(lambda: call(bad), "track_width")


def test_track_width_numeric_string_and_numpy_accepted():
    assert fp.load_road(CRG, track_width="1.6").track_width == 1.6
    assert read_csv(CSV, track_width=np.float32(1.25)).track_width == 1.25


# ----------------------------------------------------------------------------- A16: overrides
@pytest.mark.parametrize("overrides, names", [
    ([(SPRING, 30000.0)], ("overrides", "dict", "list")),
    ("x", ("overrides", "dict")),
    ({SPRING: "stiff"}, (SPRING, "finite number")),
])
def test_load_car_overrides_refused(overrides, names):
    _raises(lambda: fp.load_car(SEDAN, overrides=overrides), *names)


@pytest.mark.parametrize("value", [np.int64(30000), np.int32(30000), np.float64(30000.0),
                                   np.float32(30000.0), 30000])
def test_load_car_overrides_accept_numpy_scalars(value):
    car = fp.load_car(SEDAN, overrides={SPRING: value})
    assert car.corners[0].spring_rate == 30000.0


# ----------------------------------------------------------------------------- A17: tyres
@pytest.mark.parametrize("kwargs, names", [
    ({"use_mode": 99}, ("use_mode", "0", "4", "99")),
    ({"use_mode": -1}, ("use_mode",)),
    ({"use_mode": "x"}, ("use_mode", "integer")),
    ({"use_mode": 3.0}, ("use_mode", "integer")),
    ({"relaxation": "x"}, ("relaxation must be True or False",)),
    ({"relaxation": 1}, ("relaxation must be True or False",)),
    ({"model": "fiala", "relaxation": "yes"}, ("relaxation",)),
    ({"model": "fiala", "use_mode": 3}, ("use_mode", "fiala")),
    ({"relax": True}, ("relax", "relaxation")),
    ({"vertical_law": "cubic"}, ("vertical_law", "duffing")),
    ({"model": ["pac2002"]}, ("model", "fiala")),
    ({"model": "pac"}, ("model",)),
])
def test_tire_from_file_refuses_bad_options(kwargs, names):
    _raises(lambda: tire_from_file(TIR, **kwargs), *names)


def test_tire_builders_check_their_options():
    props = read_tir(TIR)
    _raises(lambda: Pac2002Tire.from_properties(props, relaxation="x"), "relaxation")
    _raises(lambda: MagicFormula.from_properties(props, use_mode=7), "use_mode")


@pytest.mark.parametrize("kwargs", [
    {"use_mode": 3}, {"use_mode": np.int64(4), "relaxation": np.bool_(True)},
    {"relaxation": False, "vertical_law": "linear"}, {"model": "fiala", "relaxation": True},
])
def test_tire_from_file_valid_options(kwargs):
    tire = tire_from_file(TIR, **kwargs)
    if "use_mode" in kwargs:
        assert tire.mf.use_mode == int(kwargs["use_mode"])
    if "relaxation" in kwargs:
        assert tire.relaxation is bool(kwargs["relaxation"])


# ----------------------------------------------------------------------------- A19: Result.save
@pytest.fixture
def result():
    t = 0.001 * np.arange(4)
    ch = {"hub_fl_z": np.arange(4.0), "speed": np.full(4, 10.0)}
    return Result(t=t, channels=ch, status=0, message="ok", body="rigid", cpu_time=1.0,
                  wall_time=1.0, simulated_time=0.003, info={"h": 0.001})


@pytest.mark.parametrize("channels, header", [
    ("hub_fl_z", "t [s],hub_fl_z [N]"),
    (["speed"], "t [s],speed [m/s]"),
    (("hub_fl_z", "speed"), "t [s],hub_fl_z [N],speed [m/s]"),
])
def test_result_save_takes_one_channel_name(result, tmp_path, channels, header):
    path = result.save(tmp_path / "r.csv", channels=channels)
    assert path.read_text().splitlines()[0] == header


def test_result_save_unknown_single_channel(result, tmp_path):
    _raises(lambda: result.save(tmp_path / "r.csv", channels="hub_fl"),
            "channels", "'hub_fl'", "hub_fl_z")
