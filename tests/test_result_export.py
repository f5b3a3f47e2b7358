"""Self-describing result files: units in CSV headers, time precision past 1000 s, HDF5
(read back with h5py), MATLAB (read back with scipy.io.loadmat), pandas DataFrame."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.vehicle.export import channel_unit
from flexpipe.vehicle.result import BodyMotion, Result


@pytest.fixture
def result():
    t = 1000.0 + 0.002 * np.arange(6)  # %.6g would print every one as "1000"
    n = len(t)
    motion = BodyMotion(t=t, q=np.arange(2 * n, dtype=float).reshape(n, 2) * 1e-6,
                        position=np.column_stack([t * 19.4, np.zeros(n), np.full(n, 0.3)]),
                        rotation=np.broadcast_to(np.eye(3), (n, 3, 3)), mode_index=[6, 7])
    ch = {"hub_fl_z": 3500.0 + np.arange(n), "speed": np.full(n, 19.4444444),
          "roll": np.linspace(0, 1e-3, n), "acc_driver_floor_z": np.ones(n)}
    return Result(t=t, channels=ch, status=0, message="ok", body="flexible", cpu_time=1.0,
                  wall_time=1.0, simulated_time=1000.01, info={"h": 0.002}, motion=motion)


def test_units_of_channels():
    assert channel_unit("hub_rr_y") == "N"
    assert channel_unit("tire_fl_Fz") == "N"
    assert channel_unit("travel_fl") == "m"
    assert channel_unit("spin_rl") == "rad/s"
    assert channel_unit("acc_driver_floor_x") == "m/s^2"
    assert channel_unit("yaw") == "rad"


def test_csv_header_units_and_time_precision(result, tmp_path):
    path = result.to_csv(tmp_path / "r.csv")
    lines = path.read_text().splitlines()
    assert lines[0] == "t [s],hub_fl_z [N],speed [m/s],roll [rad],acc_driver_floor_z [m/s^2]"
    t = np.loadtxt(path, delimiter=",", skiprows=1)[:, 0]
    np.testing.assert_array_equal(t, result.t)  # exact: 1000.002 stays 1000.002
    assert len(set(t)) == len(t)


def test_hdf5_round_trip(result, tmp_path):
    h5py = pytest.importorskip("h5py")
    path = result.save(tmp_path / "r.h5", format="hdf5")
    with h5py.File(path, "r") as f:
        np.testing.assert_array_equal(f["t"][()], result.t)
        assert f["t"].attrs["unit"] == "s"
        np.testing.assert_array_equal(f["channels/hub_fl_z"][()], result["hub_fl_z"])
        assert f["channels/hub_fl_z"].attrs["unit"] == "N"
        np.testing.assert_array_equal(f["motion/q"][()], result.motion.q)
        np.testing.assert_array_equal(f["motion/mode_index"][()], [6, 7])


def test_mat_round_trip(result, tmp_path):
    from scipy.io import loadmat

    path = result.save(tmp_path / "r.mat", format="mat")
    d = loadmat(path, simplify_cells=True)
    np.testing.assert_array_equal(np.ravel(d["t"]), result.t)
    np.testing.assert_array_equal(np.ravel(d["channels"]["speed"]), result["speed"])
    assert d["units"]["hub_fl_z"] == "N"
    np.testing.assert_array_equal(d["motion"]["position"], result.motion.position)


def test_dataframe(result):
    pytest.importorskip("pandas")
    df = result.to_dataframe()
    assert list(df.columns)[0] == "hub_fl_z [N]"
    assert df.index.name == "t [s]"
    np.testing.assert_array_equal(df["speed [m/s]"].to_numpy(), result["speed"])


def test_bad_format_and_motion_file(result, tmp_path):
    with pytest.raises(InputError, match="csv, hdf5, mat"):
        result.save(tmp_path / "r.x", format="xlsx")
    m = BodyMotion.load(result.motion.save(tmp_path / "m.npz"))
    np.testing.assert_array_equal(m.q, result.motion.q)
    with pytest.raises(ValueError, match="position"):
        BodyMotion(t=[0.0, 1.0], q=np.zeros((2, 1)), position=np.zeros((3, 3)),
                   rotation=np.zeros((2, 3, 3)), mode_index=[6])


# ------------------------------------------------------------- the sample cars' channels
ROOT = Path(__file__).resolve().parents[1]

#: channels that are genuinely dimensionless (unit "-"), with the reason; none so far:
#: every recorded channel is a position, angle, speed, acceleration, force, torque or rate
DIMENSIONLESS: dict = {}


@pytest.fixture(scope="module")
def car_results():
    """Short rigid-body runs of the linkage car and the prismatic car: every channel the
    recorder builds for them (mount forces, hub and tyre forces, points, driver)."""
    import flexpipe as fp

    return {name: fp.simulate(fp.load_car(ROOT / "cars" / f"{name}.toml"), speed=10.0,
                              t_end=0.05, body="rigid", cache=False)
            for name in ("sedan_linkage", "sedan")}


def test_every_channel_of_the_sample_cars_has_a_unit(car_results):
    linkage = car_results["sedan_linkage"]
    assert any(n.startswith("mount_") for n in linkage.channels)  # the per-mount forces
    for name, r in car_results.items():
        assert r.status == 0, r.message
        missing = [n for n in r.channels if channel_unit(n) == "-" and n not in DIMENSIONLESS]
        assert not missing, f"{name}: channels without a unit: {missing}"
    assert channel_unit("mount_rear_trailing_link_front_l_x") == "N"
    assert channel_unit("mount_front_rack_mount_r_z") == "N"


def test_mount_forces_carry_newton_in_csv_and_hdf5(car_results, tmp_path):
    h5py = pytest.importorskip("h5py")
    r = car_results["sedan_linkage"]
    mounts = [n for n in r.channels if n.startswith("mount_")]
    header = r.to_csv(tmp_path / "r.csv").read_text().splitlines()[0].split(",")
    assert all(f"{n} [N]" in header for n in mounts)
    with h5py.File(r.save(tmp_path / "r.h5", format="hdf5"), "r") as f:
        assert {f[f"channels/{n}"].attrs["unit"] for n in mounts} == {"N"}


def test_mat_holds_every_channel_of_the_linkage_car_by_its_full_name(car_results, tmp_path):
    """MATLAB's classic limit on struct field names is 31 characters; mount channels are
    longer (``mount_rear_lateral_link_inner_l_x``, 33).  The file holds every channel."""
    from scipy.io import loadmat

    r = car_results["sedan_linkage"]
    names = list(r.channels)
    assert max(map(len, names)) > 31
    d = loadmat(r.save(tmp_path / "linkage.mat", format="mat"), simplify_cells=True)
    # lossless for any name: cell arrays of names and units, matrix column j = names{j}
    assert list(d["channel_names"]) == names
    assert list(d["channel_units"]) == [channel_unit(n) for n in names]
    assert d["channel_data"].shape == (len(r.t), len(names))
    for j, n in enumerate(names):
        np.testing.assert_array_equal(d["channel_data"][:, j], r[n])
    # and the structs by name (MATLAB 7.6+ reads 63-character field names)
    assert sorted(d["channels"]) == sorted(names)
    for n in names:
        np.testing.assert_array_equal(np.ravel(d["channels"][n]), r[n])
        assert d["units"][n] == channel_unit(n)
    np.testing.assert_array_equal(np.ravel(d["t"]), r.t)


def test_mat_names_matlab_cannot_use_as_fields_are_kept_in_the_cell_array(result, tmp_path):
    from scipy.io import loadmat

    long = "acc_" + "a_very_long_point_name_from_a_quoted_toml_key" * 2 + "_x"  # > 63
    odd = "acc_driver seat_x"  # a quoted TOML key with a space
    result = dataclasses.replace(result, channels={
        **result.channels, long: np.zeros(len(result.t)), odd: np.ones(len(result.t))})
    with pytest.warns(UserWarning, match="channel_names"):
        path = result.save(tmp_path / "r.mat", format="mat")
    d = loadmat(path, simplify_cells=True)
    names = list(d["channel_names"])
    assert long in names and odd in names
    np.testing.assert_array_equal(d["channel_data"][:, names.index(odd)], 1.0)
    assert long not in d["channels"] and "speed" in d["channels"]
