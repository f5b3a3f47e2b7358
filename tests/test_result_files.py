"""Result files: the format follows the suffix (A4), ``load_result`` / ``Result.load`` read
every format back (A5), bad output paths are refused up front (A6), a Result is read-only
(A18)."""

from __future__ import annotations

import copy
import dataclasses
import pickle
import warnings
from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.errors import InputError
from flexpipe.vehicle import load_result
from flexpipe.vehicle.result import BodyMotion, Result

ROOT = Path(__file__).resolve().parents[1]

#: names no MATLAB field and no HDF5 dataset can carry as they are, next to ordinary ones,
#: in an order that is not alphabetical
NAMES = ["speed", "hub_fl_z", "acc_driver seat_x", "acc_" + "long_point_name" * 6 + "_x",
         "mount_a/b_x", ".", "", "channel_5", "travel [front] fl", "q,\"x\"\ny", "日本_z"]
SUFFIXES = (".csv", ".h5", ".hdf5", ".mat")
MAGIC = {".csv": b"t [s],", ".h5": b"\x89HDF\r\n\x1a\n", ".hdf5": b"\x89HDF\r\n\x1a\n",
         ".mat": b"MATLAB 5.0 MAT-file"}


def _result(names=NAMES, n=7, status=-1):
    rng = np.random.default_rng(1)
    t = 1000.0 + 0.002 * np.arange(n)
    ch = {name: rng.normal(3500.0, 800.0, n) * 10.0 ** (k % 5 - 2)
          for k, name in enumerate(names)}
    ch["speed"] = np.full(n, np.nan) if "speed" in ch else None
    ch = {k: v for k, v in ch.items() if v is not None}
    motion = BodyMotion(t=t, q=rng.normal(size=(n, 2)) * 1e-6, position=rng.normal(size=(n, 3)),
                        rotation=rng.normal(size=(n, 3, 3)), mode_index=[6, 7])
    return Result(t=t, channels=ch, status=status, message="stopped: tyre lift-off at 1000.01 s",
                  body="flexible", cpu_time=1.25, wall_time=1.5, simulated_time=1000.0125,
                  info={"h": 0.002, "car": "sedan", "static_wheel_load_N": [1.0, 2.0]},
                  motion=motion)


def _save(result, path, **kw):
    with warnings.catch_warnings():  # MAT: names that are not MATLAB fields
        warnings.simplefilter("ignore", UserWarning)
        return result.save(path, **kw)


def _assert_same_channels(loaded, saved, *, rtol):
    assert list(loaded.channels) == list(saved.channels)  # names exact, order kept
    np.testing.assert_allclose(loaded.t, saved.t, rtol=1e-12 if rtol else 0, atol=0)
    for name in saved.channels:
        np.testing.assert_allclose(loaded[name], saved[name], rtol=rtol, atol=0,
                                   equal_nan=True, err_msg=name)


# ------------------------------------------------------------------ A4: suffix -> format
@pytest.mark.parametrize("suffix", SUFFIXES)
def test_format_follows_the_suffix(tmp_path, suffix):
    path = _save(_result(), tmp_path / f"run{suffix}")
    assert path.read_bytes().startswith(MAGIC[suffix])
    upper = _save(_result(), tmp_path / f"RUN{suffix.upper()}")
    assert upper.read_bytes().startswith(MAGIC[suffix])


@pytest.mark.parametrize("suffix, fmt", [(".csv", "csv"), (".h5", "hdf5"), (".hdf5", "h5"),
                                         (".mat", "mat")])
def test_a_format_that_agrees_with_the_suffix_is_accepted(tmp_path, suffix, fmt):
    path = _save(_result(), tmp_path / f"run{suffix}", format=fmt)
    assert path.read_bytes().startswith(MAGIC[suffix])


@pytest.mark.parametrize("name, fmt, says", [
    ("run.mat", "csv", "'.mat' means format 'mat'"),
    ("run.h5", "mat", "'.h5' means format 'hdf5'"),
    ("run.csv", "hdf5", "'.csv' means format 'csv'"),
    ("run.txt", None, "unknown result-file suffix '.txt'"),
    ("run", None, "unknown result-file suffix '(none)'"),
    ("run.xlsx", "csv", "for format 'csv' name it run.csv"),
])
def test_contradiction_or_unknown_suffix_is_refused(tmp_path, name, fmt, says):
    path = tmp_path / name
    with pytest.raises(InputError) as err:
        _result().save(path, format=fmt)
    msg = str(err.value)
    assert str(path) in msg and says in msg
    assert ".csv (csv), .h5 or .hdf5 (hdf5), .mat (mat)" in msg
    assert list(tmp_path.iterdir()) == []  # nothing written, no temporary file left


def test_unknown_format_names_the_valid_ones(tmp_path):
    with pytest.raises(InputError, match="valid: csv, hdf5, mat"):
        _result().save(tmp_path / "run.csv", format="xlsx")


# ------------------------------------------------------------------ A5: reading back
@pytest.mark.parametrize("suffix", SUFFIXES)
def test_round_trip_of_every_channel_and_the_metadata(tmp_path, suffix):
    saved = _result()
    loaded = load_result(_save(saved, tmp_path / f"run{suffix}"))
    assert isinstance(loaded, Result)
    if suffix == ".csv":  # 7 significant digits per channel, 12 for the time
        _assert_same_channels(loaded, saved, rtol=5e-7)
        assert loaded.status == 0 and "CSV" in loaded.message
        assert loaded.body == "unknown" and loaded.motion is None and dict(loaded.info) == {}
        assert np.isnan(loaded.cpu_time) and loaded.simulated_time == saved.t[-1]
        return
    _assert_same_channels(loaded, saved, rtol=0)  # bit for bit
    assert (loaded.status, loaded.message, loaded.body) == (-1, saved.message, "flexible")
    assert (loaded.cpu_time, loaded.wall_time, loaded.simulated_time) == (1.25, 1.5, 1000.0125)
    assert dict(loaded.info) == dict(saved.info)
    for k in ("t", "q", "position", "rotation", "mode_index"):
        np.testing.assert_array_equal(getattr(loaded.motion, k), getattr(saved.motion, k))


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_round_trip_of_a_channel_subset_and_of_no_rows(tmp_path, suffix):
    saved = _result()
    loaded = Result.load(_save(saved, tmp_path / f"sub{suffix}", channels=["mount_a/b_x", ""]))
    assert list(loaded.channels) == ["mount_a/b_x", ""]
    np.testing.assert_allclose(loaded[""], saved[""], rtol=5e-7)
    empty = _result(names=["hub_fl_z"], n=0)
    loaded = Result.load(_save(empty, tmp_path / f"empty{suffix}"))
    assert loaded.t.shape == (0,) and loaded["hub_fl_z"].shape == (0,)


def test_load_result_is_exported():
    assert fp.load_result is load_result
    assert "load_result" in fp.__all__ and "load_result" in dir(fp)


def test_csv_text_under_a_mat_suffix_of_earlier_versions_still_reads(tmp_path):
    saved = _result()
    old = saved.to_csv(tmp_path / "run.mat")  # what Result.save("run.mat") used to write
    _assert_same_channels(fp.load_result(old), saved, rtol=5e-7)


def test_mat_file_lists_every_name_exactly_for_matlab(tmp_path):
    from scipy.io import loadmat

    with pytest.warns(UserWarning, match="channel_names"):
        path = _result().save(tmp_path / "run.mat")
    d = loadmat(path, simplify_cells=True)
    # (scipy reads MATLAB's empty char array, the name "", as an empty numpy array)
    assert [n if isinstance(n, str) else "" for n in d["channel_names"]] == NAMES


@pytest.mark.parametrize("make, says", [
    (lambda p: p, "result file not found"),
    (lambda p: (p.mkdir(), p)[1], "is a folder"),
    (lambda p: (p.write_text("x,y\n1,2\n"), p)[1], "does not start with the time"),
    (lambda p: (p.write_text(""), p)[1], "empty file"),
    (lambda p: (p.write_bytes(b"\xff\xfe\x00garbage"), p)[1], "neither CSV text"),
    (lambda p: (p.write_text("t [s],a [N]\n0,1\n1,x\n"), p)[1], "bad CSV data"),
])
def test_load_refusals_name_the_file(tmp_path, make, says):
    path = make(tmp_path / "r.csv")
    with pytest.raises(InputError, match=says) as err:
        load_result(path)
    assert str(path) in str(err.value)
    with pytest.raises(InputError, match="got None"):
        load_result(None)


def test_hdf5_without_channels_is_refused(tmp_path):
    h5py = pytest.importorskip("h5py")
    path = tmp_path / "other.h5"
    with h5py.File(path, "w") as f:
        f["x"] = np.zeros(3)
    with pytest.raises(InputError, match="without 't' and 'channels'") as err:
        load_result(path)
    assert str(path) in str(err.value)


# ------------------------------------------------------------------ A6: bad output paths
@pytest.mark.parametrize("method", ["save", "to_csv"])
def test_bad_output_paths_are_refused_naming_the_path(tmp_path, method):
    r = _result()
    folder = tmp_path / "out"
    folder.mkdir()
    afile = tmp_path / "afile"
    afile.write_text("keep me")
    save = getattr(r, method)
    with pytest.raises(InputError, match="is an existing folder") as err:
        save(folder)
    assert str(folder) in str(err.value)
    for under in (afile / "r.csv", afile / "sub" / "r.csv"):
        with pytest.raises(InputError, match=f"{afile} is a file, not a folder") as err:
            save(under)
        assert str(under) in str(err.value)
    for bad in (None, 3.5, b"r.csv"):
        with pytest.raises(InputError, match=f"got {bad!r}"):
            save(bad)
    with pytest.raises(InputError, match="empty"):
        save("")
    assert afile.read_text() == "keep me" and list(folder.iterdir()) == []
    assert sorted(p.name for p in tmp_path.iterdir()) == ["afile", "out"]  # no temp files


def test_save_creates_missing_folders_and_replaces_a_file(tmp_path):
    r = _result()
    path = _save(r, tmp_path / "a" / "b" / "run.h5")
    assert Result.load(path).status == -1
    path.write_text("old")
    _save(r, path)
    assert Result.load(path).status == -1


# ------------------------------------------------------------------ A18: read-only Result
def test_result_is_read_only_and_owns_copies():
    t = np.array([0.0, 0.1])
    ch = {"hub_fl_z": np.array([1.0, 2.0])}
    info = {"h": 0.1}
    r = Result(t=t, channels=ch, status=0, message="ok", body="rigid", cpu_time=0.0,
               wall_time=0.0, simulated_time=0.1, info=info)
    with pytest.raises(ValueError, match="read-only"):
        r.t[0] = 99.0
    with pytest.raises(ValueError, match="read-only"):
        r.channels["hub_fl_z"][:] = 0.0
    with pytest.raises(TypeError):
        r.channels["fake"] = np.zeros(3)
    import json

    assert json.loads(json.dumps(r.info)) == {"h": 0.1}  # info: a plain dict, JSON-able
    t[0], ch["hub_fl_z"][0], info["h"] = 5.0, 5.0, 5.0  # the caller's objects stay theirs
    ch["other"] = t
    assert (r.t[0], r["hub_fl_z"][0], r.info["h"], list(r.channels)) == (0.0, 1.0, 0.1,
                                                                         ["hub_fl_z"])
    assert t.flags.writeable and ch["hub_fl_z"].flags.writeable


def test_motion_is_read_only():
    m = _result().motion
    for name in ("t", "q", "position", "rotation", "mode_index"):
        assert not getattr(m, name).flags.writeable, name


def test_a_changed_result_is_built_with_replace_and_pickles(tmp_path):
    r = _result()
    r2 = dataclasses.replace(r, channels={**r.channels, "extra": np.ones(len(r.t))})
    assert "extra" in r2.channels and "extra" not in r.channels
    for other in (pickle.loads(pickle.dumps(r2)), copy.deepcopy(r2)):
        assert list(other.channels) == list(r2.channels) and dict(other.info) == dict(r.info)
        np.testing.assert_array_equal(other.motion.q, r.motion.q)
    _assert_same_channels(Result.load(r2.save(tmp_path / "r.h5")), r2, rtol=0)


def test_channels_of_another_length_are_refused():
    with pytest.raises(InputError, match="'fake' has shape \\(3,\\)"):
        Result(t=[0.0, 0.1], channels={"fake": np.zeros(3)}, status=0, message="", body="rigid",
               cpu_time=0.0, wall_time=0.0, simulated_time=0.1)


# ------------------------------------------------------------------ a real run
@pytest.fixture(scope="module")
def run():
    car = fp.load_car(ROOT / "cars" / "sedan.toml")
    return fp.simulate(car, speed=10.0, t_end=0.02, body="rigid", cache=False)


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_simulated_run_round_trips(run, tmp_path, suffix):
    assert run.status == 0, run.message
    assert not run.t.flags.writeable and not run["hub_fl_z"].flags.writeable
    loaded = fp.load_result(run.save(tmp_path / f"run{suffix}"))
    _assert_same_channels(loaded, run, rtol=5e-7 if suffix == ".csv" else 0)
    if suffix != ".csv":
        assert loaded.message == run.message and loaded.body == "rigid"
        assert loaded.info["h"] == run.info["h"]
        assert (loaded.motion is None) == (run.motion is None)


def test_a_file_with_a_channel_of_another_length_is_refused_naming_it(tmp_path):
    h5py = pytest.importorskip("h5py")
    path = _save(_result(), tmp_path / "run.h5")
    with h5py.File(path, "a") as f:
        f["channels"].create_dataset("short", data=np.zeros(2))
    with pytest.raises(InputError, match="'short' has shape \\(2,\\)") as err:
        load_result(path)
    assert str(path) in str(err.value)
