"""Sweeps of manoeuvres: the ``driver`` and ``speed_profile`` settings give the runs
serial simulate() calls give (to 1e-12), enter the run identity by their files' contents,
are checked (file and key named) before any run, and an open-loop step steer writes its
ISO 7401 figures as metrics."""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from _rigidcar import rigid_sedan

import flexpipe as fp
from flexpipe.errors import InputError
from flexpipe.sweeps.metrics import SINE_WITH_DWELL_METRICS, STEP_METRICS, run_metrics
from flexpipe.sweeps.spec import load_sweep

ROOT = Path(__file__).resolve().parents[1]
STEP = """[steering]
type = "open_loop"
input = "step"
steering_wheel_deg = {deg}
t_start_s = 0.2
rise_time_s = 0.15
"""
BRAKE = """[speed_profile]
time_s = [0.0, 0.5, 2.0]
speed_kmh = [{v0}, {v0}, 40.0]
"""
T_END, H = 2.5, 0.002


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    """One single-threaded in-process worker: no process start-up."""
    from dask.distributed import Client, LocalCluster

    mp = pytest.MonkeyPatch()
    mp.setenv("FLEXPIPE_CACHE", str(tmp_path_factory.mktemp("cache")))
    cluster = LocalCluster(n_workers=1, threads_per_worker=1, processes=False,
                           dashboard_address=":0", silence_logs=50)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()
    mp.undo()


def _files(folder, *, deg=30.0, v0=60.0):
    (folder / "step.toml").write_text(STEP.format(deg=deg))
    (folder / "brake.toml").write_text(BRAKE.format(v0=v0))
    (folder / "pursuit.toml").write_text((ROOT / "paths" / "driver.toml").read_text())


def _spec_file(folder, car, runs, **sweep) -> Path:
    """A list-design sweep file in ``folder`` (paths relative to it)."""
    base = {"car": car.name, "body": "rigid", "speed_kmh": 60.0, "t_end_s": T_END, "h_s": H,
            "design": "list"} | sweep
    lines = ["[sweep]", *(f"{k} = {json.dumps(v)}" for k, v in base.items())]
    for r in runs:
        lines += ["", "[[runs]]", *(f"{k} = {json.dumps(v)}" for k, v in r.items())]
    path = folder / "study.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


RUNS = [{"driver": "step.toml"},
        {"speed_profile": "brake.toml"},
        {"speed_kmh": 50.0},
        {"driver": "pursuit.toml", "speed_profile": "brake.toml", "body": "rigid"}]


def test_sweep_with_driver_and_profile_equals_serial_simulate_and_reruns_on_change(
        client, tmp_path):
    from flexpipe.vehicle import handling

    car = rigid_sedan(tmp_path)
    _files(tmp_path)
    spec = _spec_file(tmp_path, car, RUNS)
    out = tmp_path / "out"
    res = fp.sweep(spec, out=out, scheduler=client, progress=False, plots=False)
    assert res.n_runs == 4 and res.n_failed == 0, res.table["message"].tolist()
    ch = pd.read_parquet(out / "channels")
    loaded = fp.load_car(car)
    table = res.table.set_index("index")
    serial = {}
    for i, r in enumerate(RUNS):
        speed = str(tmp_path / r["speed_profile"]) if "speed_profile" in r \
            else r.get("speed_kmh", 60.0) / 3.6
        driver = str(tmp_path / r["driver"]) if "driver" in r else None
        ref = fp.simulate(car, speed=speed, t_end=T_END, body="rigid", h=H, driver=driver)
        serial[i] = ref
        row = table.loc[i]
        mine = ch[ch["run"].astype(str) == row["key"]].sort_values("t")
        assert np.abs(mine["t"].to_numpy() - ref.t).max() <= 1e-12
        for name in ref.channels:
            x = ref[name]
            assert np.abs(mine[name].to_numpy() - x).max() <= 1e-12 * max(1.0, np.abs(
                x).max()), (i, name)
        for m, v in run_metrics(ref.t, ref.channels).items():
            assert row[m] == pytest.approx(v, rel=1e-12, abs=1e-12, nan_ok=True), (i, m)
    # the profile was followed (40 km/h at the end), the step turned the car
    assert serial[1]["speed"][-1] * 3.6 == pytest.approx(40.0, abs=2.0)
    assert abs(serial[0]["ay"][-1]) > 1.0 > abs(serial[2]["ay"][-1])
    # the step run's ISO 7401 figures, at the centre of mass, are the metrics
    want = handling.step_response(serial[0], cg=handling.centre_of_mass(serial[0], loaded))
    rec = json.loads((out / "runs" / f"{table.loc[0, 'key']}.json").read_text())
    for column, key in STEP_METRICS.items():
        assert rec[column] == want[key], column
    assert rec["yaw_rate_steady_deg_per_s"] > 0 and rec["ay_at_x_m"] != 0.0
    # other runs keep their metric set: no step figures in their records, NaN in the table
    for i in (1, 2, 3):
        other = json.loads((out / "runs" / f"{table.loc[i, 'key']}.json").read_text())
        assert not set(STEP_METRICS) & set(other)
        assert math.isnan(table.loc[i, "yaw_rate_steady_deg_per_s"])
    assert not set(SINE_WITH_DWELL_METRICS) & set(res.table.columns)
    cols = list(res.table.columns)
    assert cols[:2] == ["driver", "speed_profile"]
    assert cols.index("lateral_error_absmax_m") < cols.index("yaw_rate_steady_deg_per_s") \
        < cols.index("simulated_time_s")
    # unchanged files: every run skipped; a changed driver and profile: those runs again
    assert fp.sweep(spec, out=out, scheduler=client, progress=False,
                    plots=False).n_skipped == 4
    _files(tmp_path, deg=20.0, v0=55.0)
    again = fp.sweep(spec, out=out, scheduler=client, progress=False, plots=False)
    assert again.n_skipped == 1 and again.n_failed == 0
    new = again.table.set_index("index")
    assert new.loc[2, "key"] == table.loc[2, "key"]
    assert all(new.loc[i, "key"] != table.loc[i, "key"] for i in (0, 1, 3))
    assert new.loc[0, "steering_wheel_steady_deg"] == pytest.approx(20.0)


def test_identity_follows_the_contents_of_the_driver_and_profile_files(tmp_path):
    car = rigid_sedan(tmp_path)
    _files(tmp_path)
    spec = _spec_file(tmp_path, car, RUNS)
    keys = [r.key for r in load_sweep(spec).runs()]
    assert len(set(keys)) == 4
    (tmp_path / "step.toml").write_text(STEP.format(deg=30.0) + "# a comment\n")
    k2 = [r.key for r in load_sweep(spec).runs()]
    assert k2[0] != keys[0] and k2[1:] == keys[1:]
    (tmp_path / "brake.toml").write_text(BRAKE.format(v0=61.0))
    k3 = [r.key for r in load_sweep(spec).runs()]
    assert k3[1] != k2[1] and k3[3] != k2[3] and k3[::2] == k2[::2]
    # the same run without driver and profile keeps the key it had before these settings
    runs = load_sweep(spec).runs()
    assert runs[2].driver is None and runs[2].speed_profile is None
    assert runs[1].speed == pytest.approx(61.0 / 3.6)  # the band speed: the profile's top
    assert runs[1].speed_profile == str(tmp_path / "brake.toml")
    # a base driver for every run; "default" gives a run the car's own driver back
    spec = _spec_file(tmp_path, car, [{"speed_kmh": 50.0}, {"driver": "default"}],
                      driver="step.toml")
    a, b = load_sweep(spec).runs()
    assert a.driver == str(tmp_path / "step.toml") and b.driver is None


@pytest.mark.parametrize("runs, sweep, key, words", [
    ([{"speed_kmh": 50.0, "speed_profile": "brake.toml"}], {}, "runs[0].speed_profile",
     ["give one"]),
    ([{"speed_kmh": 50.0}], {"speed_profile": "brake.toml"}, "sweep.speed_profile",
     ["give one"]),
    ([{"speed_kmh": 50.0}, {"speed_profile": "nothere.toml"}], {}, "runs[1].speed_profile",
     ["nothere.toml", "does not exist"]),
    ([{"speed_profile": "bad.toml"}], {}, "runs[0].speed_profile",
     ["bad.toml", "speed_profile.time_s"]),
    ([{"speed_profile": "fast.toml"}], {}, "runs[0].speed_profile", ["fast.toml", "km/h"]),
    ([{"speed_profile": "step.toml"}], {}, "runs[0].speed_profile",
     ["step.toml", "no [speed_profile] table"]),
    ([{"speed_profile": "profile.txt"}], {}, "runs[0].speed_profile", [".txt"]),
    ([{"driver": "nothere.toml"}], {}, "runs[0].driver", ["nothere.toml"]),
    ([{"speed_kmh": 50.0}], {"driver": "baddriver.toml"}, "sweep.driver",
     ["baddriver.toml", "steering.input", "jump"]),
    ([{"driver": 3}], {}, "runs[0].driver", ["expected a file name"]),
])
def test_bad_driver_and_profile_are_named_before_any_run(tmp_path, runs, sweep, key, words):
    car = rigid_sedan(tmp_path)
    _files(tmp_path)
    (tmp_path / "bad.toml").write_text("[speed_profile]\ntime_s = [0.0, 2.0, 1.0]\n"
                                       "speed_kmh = [50.0, 50.0, 40.0]\n")
    (tmp_path / "fast.toml").write_text("[speed_profile]\ntime_s = [0.0, 2.0]\n"
                                        "speed_kmh = [100.0, 300.0]\n")
    (tmp_path / "profile.txt").write_text("time_s, speed_kmh\n0, 50\n")
    (tmp_path / "baddriver.toml").write_text('[steering]\ntype = "open_loop"\n'
                                             'input = "jump"\n')
    spec = _spec_file(tmp_path, car, runs, **sweep)
    out = tmp_path / "out"
    with pytest.raises(InputError) as info:
        fp.sweep(spec, out=out, progress=False)  # raises before it starts any worker
    assert info.value.key == key and Path(info.value.file) == spec
    for w in words:
        assert w in str(info.value), (w, str(info.value))
    assert not out.exists()


def test_grid_of_speeds_and_profiles_is_refused_and_unknown_names_list_the_new_settings(
        tmp_path):
    car = rigid_sedan(tmp_path)
    _files(tmp_path)
    base = {"car": str(car), "body": "rigid", "t_end_s": 1.0}
    with pytest.raises(InputError) as info:
        load_sweep({"sweep": base, "parameters": {"speed_kmh": [40.0],
                                                  "speed_profile": [str(tmp_path / "brake.toml")]}})
    assert info.value.key == "parameters.speed_profile"
    with pytest.raises(InputError) as info:
        load_sweep({"sweep": base, "parameters": {"drivers": ["x.toml"]}})
    assert "driver" in str(info.value) and "speed_profile" in str(info.value)
    # a profile grid: each run's speed from its file, base speed_kmh replaced
    spec = load_sweep({"sweep": base | {"speed_kmh": 80.0}, "parameters": {
        "speed_profile": [str(tmp_path / "brake.toml")],
        "driver": [str(tmp_path / "step.toml"), str(tmp_path / "pursuit.toml")]}})
    assert [r.speed_profile is not None and r.driver is not None for r in spec.runs()] == [
        True, True]


def test_path_too_short_for_a_profile_run_is_named_before_any_run(tmp_path):
    """check_runs passes the profile and driver to check_run: the profile's distance is
    what the path must carry."""
    from flexpipe.sweeps.checks import check_runs

    car = rigid_sedan(tmp_path)
    _files(tmp_path)
    (tmp_path / "short.toml").write_text('[path]\ntype = "straight"\nlength_m = 30.0\n')
    spec = load_sweep(_spec_file(tmp_path, car, [{"speed_kmh": 1.0}, {
        "speed_profile": "brake.toml"}], path="short.toml", t_end_s=2.0))
    runs = spec.runs()
    cars = [fp.load_car(car)] * len(runs)
    with pytest.raises(InputError) as info:
        check_runs(spec, runs, cars)
    msg = str(info.value)
    assert "run 1 (speed_profile = 'brake.toml')" in msg and "speed profile" in msg
    assert Path(info.value.file) == tmp_path / "study.toml"


def test_plot_metrics_of_a_step_sweep_are_valid_only_with_a_step_driver(tmp_path):
    from flexpipe.sweeps.checks import check_plot_metrics

    car = rigid_sedan(tmp_path)
    _files(tmp_path)
    cars = [fp.load_car(car)]
    spec = load_sweep({"sweep": {"car": str(car), "body": "rigid", "t_end_s": 1.0,
                                 "driver": str(tmp_path / "step.toml")},
                       "parameters": {"speed_kmh": [60.0]},
                       "plots": {"metrics": ["yaw_rate_steady_deg_per_s"]}})
    check_plot_metrics(spec, cars)
    spec = load_sweep({"sweep": {"car": str(car), "body": "rigid", "t_end_s": 1.0},
                       "parameters": {"speed_kmh": [60.0]},
                       "plots": {"metrics": ["yaw_rate_steady_deg_per_s"]}})
    with pytest.raises(InputError) as info:
        check_plot_metrics(spec, cars)
    assert info.value.key == "plots.metrics"


def test_metrics_of_an_unsettled_step_are_nan_with_a_note():
    from flexpipe.sweeps.metrics import manoeuvre_metrics

    class R:
        status = 0
        info = {"steering": "open-loop steering: step 30 deg"}
        t = np.linspace(0.0, 2.0, 201)
        channels = {"steering_wheel": np.where(t > 1.0, 0.5, 0.0), "yaw": t ** 3,
                    "ay": t, "roll": 0 * t, "speed": 20.0 + 0 * t}

        def __getitem__(self, k):
            return self.channels[k]

    got, note = manoeuvre_metrics(R())
    assert set(got) == set(STEP_METRICS) and all(math.isnan(v) for v in got.values())
    assert "not settled" in note
    R.info = {"steering": "path follower"}
    assert manoeuvre_metrics(R()) == ({}, "")


@pytest.mark.parametrize("name", sorted(p.name for p in (ROOT / "sweeps").glob(
    "manoeuvres_*.toml")))
def test_shipped_manoeuvre_sweeps_pass_the_checks_and_are_documented(name):
    from flexpipe.sweeps.checks import check_plot_metrics, check_runs

    spec = load_sweep(ROOT / "sweeps" / name)
    runs = spec.runs()
    cars = [fp.load_car(r.car_file, overrides=r.car_overrides) for r in runs]
    check_runs(spec, runs, cars)
    check_plot_metrics(spec, cars, runs)
    assert any(r.driver or r.speed_profile for r in runs)
    docs = (ROOT / "docs" / "sweeps.md").read_text()
    assert f"sweeps/{name}" in docs
    shown = [b for b in re.findall(r"```text\n(.*?)```", docs, re.S) if "[sweep]" in b]
    text = (ROOT / "sweeps" / name).read_text()
    assert any(b in text for b in shown) or name != "manoeuvres_step_steer.toml"
