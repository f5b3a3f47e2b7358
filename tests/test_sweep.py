"""Sweeps on dask.distributed: results equal serial simulate() runs to 1e-12, reruns skip
finished runs, a failing run is recorded and does not stop the sweep, a worker killed
mid-sweep loses nothing and duplicates nothing, bad dotted keys are named up front."""

from __future__ import annotations

import json
import os
import signal
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pyarrow.parquet as pq
import pytest
from _rigidcar import rigid_sedan

import flexpipe as fp
from flexpipe.errors import InputError
from flexpipe.sweeps.metrics import run_metrics
from flexpipe.sweeps.overrides import apply_overrides

ROOT = Path(__file__).resolve().parents[1]
ROAD = ROOT / "roads" / "iso_c_200m.toml"


@pytest.fixture(scope="module")
def client(tmp_path_factory):
    from dask.distributed import Client, LocalCluster

    mp = pytest.MonkeyPatch()
    mp.setenv("FLEXPIPE_CACHE", str(tmp_path_factory.mktemp("cache")))
    cluster = LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                           host="127.0.0.1", dashboard_address=":0", silence_logs=50)
    c = Client(cluster)
    yield c
    c.close()
    cluster.close()
    mp.undo()


def _spec(car, **sweep):
    base = {"car": str(car), "road": str(ROAD), "body": "rigid", "t_end_s": 0.6}
    base.update(sweep)
    return {"sweep": base}


def test_sweep_equals_serial_simulate_and_resumes(client, tmp_path):
    car = rigid_sedan(tmp_path)
    spec = _spec(car) | {"parameters": {"speed_kmh": [40.0, 70.0],
                                        "car.corners.fl.spring_rate_N_per_m": [30000.0,
                                                                               36000.0]}}
    res = fp.sweep(spec, out=tmp_path / "out", scheduler=client, progress=False)
    assert res.n_runs == 4 and res.n_failed == 0 and list(res.table["status"]) == [0] * 4
    ch = pd.read_parquet(tmp_path / "out" / "channels")
    assert sorted(ch["run"].astype(str).unique()) == sorted(res.table["key"])
    for _, row in res.table.iterrows():
        k = row["car.corners.fl.spring_rate_N_per_m"]
        serial = fp.simulate(fp.load_car(car, overrides={"corners.fl.spring_rate_N_per_m": k}),
                             road=ROAD, speed=row["speed_kmh"] / 3.6, t_end=0.6, body="rigid")
        mine = ch[ch["run"].astype(str) == row["key"]].sort_values("t")
        assert np.abs(mine["t"].to_numpy() - serial.t).max() <= 1e-12
        for name in serial.channels:
            ref = serial[name]
            assert np.abs(mine[name].to_numpy() - ref).max() <= 1e-12 * max(1.0, np.abs(
                ref).max()), name
        for m, v in run_metrics(serial.t, serial.channels).items():
            assert row[m] == pytest.approx(v, rel=1e-12, abs=1e-12), m
    # the stiffer front-left spring is a different car: a different hub force
    assert res.table["hub_fl_z_peak_N"].nunique() == 4
    # the table starts with the swept parameters, key, status... (docs/sweeps.md)
    lead = ["speed_kmh", "car.corners.fl.spring_rate_N_per_m", "key", "status", "message",
            "cpu_s", "wall_s"]
    assert list(res.table.columns[:7]) == lead
    assert list(pd.read_csv(tmp_path / "out" / "metrics.csv", nrows=1).columns[:7]) == lead
    # every channel column carries the unit of the run's own CSV header
    serial.save(tmp_path / "serial.csv")
    header = (tmp_path / "serial.csv").read_text().splitlines()[0].split(",")
    csv_units = dict(h[:-1].split(" [") for h in header)
    files = sorted((tmp_path / "out" / "channels").glob("run=*/part-0.parquet"))
    schema = pq.read_schema(files[0])
    assert {f.name: f.metadata[b"unit"].decode() for f in schema} == csv_units
    assert json.loads(schema.metadata[b"units"]) == csv_units
    assert (csv_units["t"], csv_units["hub_fl_z"], csv_units["travel_fl"]) == ("s", "N", "m")
    again = fp.sweep(spec, out=tmp_path / "out", scheduler=client, progress=False)
    assert again.n_skipped == 4 and again.table.equals(res.table)
    assert (tmp_path / "out" / "metrics.parquet").is_file()


def test_failed_run_is_recorded_and_the_sweep_goes_on(client, tmp_path):
    car = rigid_sedan(tmp_path)
    # a -1e6 N spring preload passes every check before the runs but diverges at once:
    # that run fails on its worker, the other one runs
    spec = _spec(car, design="list") | {"runs": [
        {"speed_kmh": 50.0}, {"speed_kmh": 50.0, "car.corners.fl.spring_preload_N": -1e6}]}
    res = fp.sweep(spec, out=tmp_path / "out", scheduler=client, progress=False)
    t = res.table.set_index("index")
    assert t.loc[0, "status"] == 0
    assert t.loc[1, "status"] < 0 and "spring_preload_N" in t.loc[1, "message"]
    assert res.n_failed == 1


def test_killed_worker_loses_and_duplicates_nothing(client, tmp_path):
    car = rigid_sedan(tmp_path)
    speeds = [30.0, 40.0, 50.0, 60.0, 70.0, 80.0]
    spec = _spec(car, t_end_s=1.5) | {"parameters": {"speed_kmh": speeds}}
    out = tmp_path / "out"
    box = {}
    th = threading.Thread(target=lambda: box.update(
        res=fp.sweep(spec, out=out, scheduler=client, progress=False)))
    th.start()
    killed = None
    deadline = time.time() + 60
    while killed is None and time.time() < deadline and th.is_alive():
        busy = {w: ks for w, ks in client.processing().items()
                if any(str(k).startswith("run-") for k in ks)}
        done = list((out / "runs").glob("*.json")) if (out / "runs").is_dir() else []
        if busy and done:  # one run finished, another is running: kill its worker
            addr = next(iter(busy))
            pid = client.run(os.getpid, workers=[addr])[addr]
            os.kill(pid, signal.SIGKILL)
            killed = addr
        time.sleep(0.05)
    th.join(timeout=120)
    assert killed is not None, "no worker was caught running a task"
    res = box["res"]
    assert sorted(res.table["speed_kmh"]) == speeds  # every run present once
    assert list(res.table["status"]) == [0] * len(speeds)
    assert len(list((out / "runs").glob("*.json"))) == len(speeds)
    assert len(list((out / "channels").glob("run=*/part-0.parquet"))) == len(speeds)


def test_bad_dotted_key_is_named_before_anything_runs(tmp_path):
    car = rigid_sedan(tmp_path)
    spec = _spec(car) | {"parameters": {"car.corners.fx.spring_rate_N_per_m": [1.0]}}
    with pytest.raises(InputError, match=r"corners\.fx.*valid names under \[corners\]: fl, "
                                         r"fr, rl, rr"):
        fp.sweep(spec, out=tmp_path / "out", progress=False)
    spec = _spec(car) | {"parameters": {"car.corners.fl.spring_rate": [1.0]}}
    with pytest.raises(InputError, match="did you mean 'spring_rate_N_per_m'"):
        fp.sweep(spec, out=tmp_path / "out", progress=False)
    spec = _spec(car) | {"parameters": {"wind_kmh": [1.0]}}
    with pytest.raises(InputError, match="unknown parameter 'wind_kmh'"):
        fp.sweep(spec, out=tmp_path / "out", progress=False)
    assert not (tmp_path / "out" / "runs").exists()


def test_overrides_reach_arrays_of_tables_and_leave_the_document_alone():
    doc = {"body": {"mass": [{"name": "driver", "mass_kg": 75.0}]}, "corners": {"fl": {}}}
    new = apply_overrides(doc, {"body.mass.driver.mass_kg": 90.0, "body.mass.0.name": "d",
                                "corners.fl.spring_rate_N_per_m": 1.0})
    assert new["body"]["mass"][0] == {"name": "d", "mass_kg": 90.0}
    assert doc["body"]["mass"][0]["mass_kg"] == 75.0 and doc["corners"]["fl"] == {}
    with pytest.raises(InputError, match="is a table in the file"):
        apply_overrides(doc, {"corners.fl": 3.0})


def test_cli_runs_a_latin_hypercube_spec_file(client, tmp_path, capsys):
    from flexpipe.cli import main

    car = rigid_sedan(tmp_path)
    spec = tmp_path / "lhs.toml"
    spec.write_text(f"""
[sweep]
car = "{car.name}"
road = "{ROAD.as_posix()}"
t_end_s = 0.4
design = "lhs"
samples = 4
seed = 7

[parameters]
speed_kmh = {{min = 40.0, max = 80.0}}
"road.seed" = {{min = 1, max = 4}}
body = ["rigid"]
""")
    code = main(["sweep", str(spec), "--scheduler", client.scheduler.address, "--out",
                 str(tmp_path / "out"), "--no-progress"])
    assert code == 0, capsys.readouterr()
    assert "4 runs (0 already done, 0 failed" in capsys.readouterr().out
    t = pd.read_parquet(tmp_path / "out" / "metrics.parquet")
    # Latin hypercube: one sample in each quarter of the speed range, each seed once
    assert sorted(((t["speed_kmh"] - 40.0) // 10.0).astype(int)) == [0, 1, 2, 3]
    assert sorted(t["road.seed"]) == [1, 2, 3, 4]
    assert (t["status"] == 0).all()
    import dask.dataframe as dd

    rows = len(dd.read_parquet(tmp_path / "out" / "channels").compute())
    from flexpipe.vehicle.simulation import DEFAULT_STEP

    # every run's samples, t = 0 .. t_end, output every step by default
    assert rows == 4 * (round(0.4 / DEFAULT_STEP) + 1)


def test_runs_sharing_a_body_share_one_reduction_key():
    from flexpipe.sweeps import load_sweep
    from flexpipe.sweeps.execute import _cars
    from flexpipe.sweeps.tasks import body_keys, road_of

    spec = load_sweep({"sweep": {"car": str(ROOT / "cars" / "sedan.toml"), "road": str(ROAD),
                                 "body": "flexible", "t_end_s": 1.0},
                       "parameters": {"car.body.damping_ratio": [0.02, 0.03],
                                      "speed_kmh": [60.0, 90.0],
                                      "car.corners.fl.spring_rate_N_per_m": [3e4, 4e4]}})
    runs = spec.runs()
    keys = [body_keys(car, r, road_of(r)) for r, car in zip(runs, _cars(runs), strict=True)]
    # the body depends on its damping (and band), not on the springs or the speed here
    # (both speeds excite the road above the band's cap)
    from flexpipe.vehicle.bodymodel import BAND_CAP_HZ

    assert len(runs) == 8 and len({k[1] for k in keys}) == 2 and len({k[0] for k in keys}) == 2
    assert {k[2] for k in keys} == {BAND_CAP_HZ}


def test_runs_with_another_interface_band_get_their_own_body():
    """A sweep over ``body.interface_band_hz`` of a linkage car reduces one body per
    value (the band changes the body's modes), and a full run keeps every static mode
    whatever the car file says; its key is the reduction cache's."""
    from flexpipe.sweeps import load_sweep
    from flexpipe.sweeps.execute import _cars
    from flexpipe.sweeps.tasks import body_keys, road_of

    car_file = str(ROOT / "cars" / "sedan_linkage.toml")
    spec = load_sweep({"sweep": {"car": car_file, "road": str(ROAD), "body": "flexible",
                                 "t_end_s": 1.0},
                       "parameters": {"car.body.interface_band_hz": [400.0, 800.0, "all"]}})
    runs = spec.runs()
    keys = [body_keys(car, r, road_of(r))[1] for r, car in zip(runs, _cars(runs), strict=True)]
    assert len(set(keys)) == 3
    full = load_sweep({"sweep": {"car": car_file, "road": str(ROAD), "body": "full",
                                 "t_end_s": 1.0},
                       "parameters": {"car.body.interface_band_hz": [400.0, 800.0]}})
    runs = full.runs()
    keys = [body_keys(car, r, road_of(r))[1] for r, car in zip(runs, _cars(runs), strict=True)]
    assert len(set(keys)) == 1

def _spec_file(folder, text: str) -> Path:
    car = rigid_sedan(folder)
    path = Path(folder) / "study.toml"
    path.write_text(f'''[sweep]
car = "{car.name}"
road = "{ROAD.as_posix()}"
body = "rigid"
t_end_s = 0.2
''' + text)
    return path


@pytest.mark.parametrize("text, key, words", [
    # (a) the settle window leaves no samples for the metrics
    ("settle_s = 5.0\n[parameters]\nspeed_kmh = [50.0, 60.0]\n", "sweep.settle_s",
     ["settle_s = 5", "t_end_s = 0.2", "sweep.t_end_s", "at least 4"]),
    ("settle_s = 0.1\n[parameters]\nt_end_s = [0.5, 0.1]\n", "sweep.settle_s",
     ["parameters.t_end_s", "t_end_s = 0.1"]),
    # (b) an unknown metric to plot
    ("[parameters]\nspeed_kmh = [50.0, 60.0]\n[plots]\nmetrics = [\"hub_fl_z_rms_N\", "
     "\"travel_absmax_mm\"]\n", "plots.metrics",
     ["travel_absmax_mm", "did you mean 'travel_absmax_m'", "aw_driver_floor_z_m_per_s2",
      "lateral_error_absmax_m"]),
    # (c) run parameters, in the sweep's own keys and units
    ("h_s = 2.0\n[parameters]\nspeed_kmh = [50.0, 60.0]\n", "sweep.h_s",
     ["[1e-05, 0.005] s", "2.0"]),
    ("[parameters]\nspeed_kmh = [50.0, 400.0]\n", "parameters.speed_kmh",
     ["[0, 288] km/h", "400"]),
    ("[parameters]\nspeed_kmh = [50.0]\n\"road.road_class\" = [\"C\", \"Z\"]\n",
     "parameters.road.road_class", ["run 1", "'Z'", "'A'"]),
    ("[parameters]\nt_end_s = [30.0]\nspeed_kmh = [20.0, 60.0]\n", None,
     ["run 1", "speed_kmh = 60.0", "use a longer road"]),
    # (d) a repeated value of an axis
    ("[parameters]\nspeed_kmh = [50.0, 50.0]\n", "parameters.speed_kmh",
     ["50.0 appears twice"]),
    ("[parameters]\nspeed_kmh = [50, 60.0, 50.0]\n", "parameters.speed_kmh",
     ["appears twice"]),
])
def test_bad_sweep_is_rejected_before_any_run_starts(tmp_path, text, key, words):
    """Every run's settings, the metrics window, the plotted metrics and the sweep axes
    are checked before a run starts: the error names the sweep file and the sweep key,
    and nothing is written."""
    path = _spec_file(tmp_path, text)
    with pytest.raises(InputError) as info:
        fp.sweep(path, out=tmp_path / "out", progress=False)
    msg = str(info.value)
    assert info.value.key == key and info.value.file == path and str(path) in msg
    for w in words:
        assert w in msg, msg
    assert not (tmp_path / "out").exists()


def test_cli_sweep_rejects_an_output_file_before_running(tmp_path, capsys):
    from flexpipe.cli import main

    path = _spec_file(tmp_path, "[parameters]\nspeed_kmh = [50.0, 60.0]\n")
    (tmp_path / "taken").write_text("")
    assert main(["sweep", str(path), "--out", str(tmp_path / "taken"), "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "'--out'" in err and "takes a folder" in err


def test_sample_sweep_passes_the_checks():
    from flexpipe.sweeps import load_sweep
    from flexpipe.sweeps.checks import check_plot_metrics, check_runs
    from flexpipe.sweeps.execute import _cars

    spec = load_sweep(ROOT / "sweeps" / "sample.toml")
    runs = spec.runs()
    cars = _cars(runs)
    check_runs(spec, runs, cars)
    check_plot_metrics(spec, cars)
    assert len(runs) == 18


LINKAGE = ROOT / "cars" / "sedan_linkage.toml"
FRONT_RATE = "car.suspension.front.spring.rate_N_per_m"


def test_a_sweep_over_a_linkage_spring_runs_different_cars(client, tmp_path):
    """Each run's car has its own front spring: the kinematic wheel rate k MR^2 of the K&C
    rig scales with k (MR is geometry), the static load and hence the preload that holds
    the design position do not, so the static spring deflection preload / k does; the time
    runs start at rest (settled on the road) and differ on the road."""
    from flexpipe.sweeps import load_sweep
    from flexpipe.sweeps.execute import _cars
    from flexpipe.vehicle import bodymodel
    from flexpipe.vehicle.linkage_setup import linkage_statics

    rates = [111000.0, 222000.0]
    spec = {"sweep": {"car": str(LINKAGE), "road": str(ROAD), "body": "rigid",
                      "t_end_s": 0.4, "speed_kmh": 60.0},
            "parameters": {FRONT_RATE: rates}}
    runs = load_sweep(spec).runs()
    got = {}
    for run, car in zip(runs, _cars(runs), strict=True):  # the cars the sweep runs
        k = run.params[FRONT_RATE]
        kc = fp.kc(car.suspension, n=3, travel=0.002, axles=["front"]).summary["front"]
        susp, N = linkage_statics(car, bodymodel.rigid_properties(car))
        sp = susp.axles["front"].left.spring()
        assert sp.rate == k
        preload = sp.static_force(sp.design_length)
        assert sp.free_length - sp.design_length == pytest.approx(preload / k, rel=1e-12)
        got[k] = (kc["kinematic wheel rate [N/m]"], kc["spring motion ratio [-]"], preload,
                  N[0], sp.free_length - sp.design_length)
    (w1, mr1, p1, n1, d1), (w2, mr2, p2, n2, d2) = got[rates[0]], got[rates[1]]
    assert mr2 == pytest.approx(mr1, rel=1e-12)
    assert w1 == pytest.approx(rates[0] * mr1**2, rel=1e-9)
    assert w2 / w1 == pytest.approx(2.0, rel=1e-9)
    assert (n2, p2) == pytest.approx((n1, p1), rel=1e-9)
    assert d2 / d1 == pytest.approx(0.5, rel=1e-9)
    res = fp.sweep(spec, out=tmp_path / "out", scheduler=client, progress=False)
    assert res.n_runs == 2 and list(res.table["status"]) == [0, 0], res.table["message"]
    ch = pd.read_parquet(tmp_path / "out" / "channels")
    first = {}
    for _, row in res.table.iterrows():
        mine = ch[ch["run"].astype(str) == row["key"]].sort_values("t")
        # at rest, settled on the road under the wheels (0.7 mm off the design height on
        # this road): the first rows agree to a few micrometres
        tr = mine["travel_fl"].to_numpy()
        assert abs(tr[0]) < 3e-3 and abs(tr[1] - tr[0]) < 1e-5
        first[row[FRONT_RATE]] = mine["hub_fl_z"].to_numpy()
    assert np.abs(first[rates[0]] - first[rates[1]]).max() > 10.0  # N: different cars
    # plumbing (the seat's physics is checked in test_seats.py): the sample's driver seat
    # reaches the channel files as its floor channel through the seat, and the table's
    # SEAT value is the ratio of the two weighted vertical RMS columns
    from flexpipe.vehicle.seats import Seat

    seat = Seat("driver_seat", "driver_floor", 4.0, 0.3)
    for _, row in res.table.iterrows():
        mine = ch[ch["run"].astype(str) == row["key"]].sort_values("t")
        t = mine["t"].to_numpy()
        np.testing.assert_allclose(mine["acc_driver_seat_z"].to_numpy(),
                                   seat.acceleration(t, mine["acc_driver_floor_z"].to_numpy()),
                                   rtol=0, atol=1e-9)
        assert row["seat_driver_seat_SEAT_pct"] == pytest.approx(
            100 * row["aw_driver_seat_z_m_per_s2"] / row["aw_driver_floor_z_m_per_s2"],
            rel=1e-12)


def test_runs_moving_a_suspension_mount_get_their_own_body():
    from flexpipe.sweeps import load_sweep
    from flexpipe.sweeps.execute import _cars
    from flexpipe.sweeps.tasks import body_keys, road_of

    mount = "car.suspension.front.hardpoints_m.upper_arm_front"
    spec = load_sweep({"sweep": {"car": str(LINKAGE), "road": str(ROAD), "body": "flexible",
                                 "t_end_s": 1.0, "speed_kmh": 60.0},
                       "parameters": {mount: [[-0.100, 0.470, 0.105], [-0.080, 0.470, 0.105]],
                                      FRONT_RATE: [111000.0, 120000.0]}})
    runs = spec.runs()
    keys = [body_keys(car, r, road_of(r)) for r, car in zip(runs, _cars(runs), strict=True)]
    # the reduced body has an interface at every mount: one body per mount position, the
    # same for both springs
    assert len(runs) == 4 and len({k[1] for k in keys}) == 2
    assert keys[0][1] == keys[1][1] and keys[0][1] != keys[2][1]


@pytest.mark.parametrize("t_end, h, output_step, settle, n", [
    (0.003, 1e-3, 1e-3, 0.0, 4),  # t = 0 counts: 0, 1, 2, 3 ms
    (0.003, 1e-3, 1e-3, 0.001, 3),
    (0.010, 1e-3, 2e-3, 0.004, 4),  # 4, 6, 8, 10 ms
    (0.010, 1e-3, 2e-3, 0.0041, 3),
    (0.010, 1e-3, 2e-3, 0.0039, 4),
])
def test_settle_window_counts_the_samples_run_metrics_uses(t_end, h, output_step, settle,
                                                           n):
    """The settle check counts the output samples exactly as run_metrics selects them
    (t = 0 included): enough samples pass, one too few is refused naming the key, the
    count and the latest valid settle_s."""
    from flexpipe.sweeps.metrics import MIN_SAMPLES
    from flexpipe.sweeps.spec import _check_window

    dt = output_step
    t = np.arange(int(round(t_end / dt)) + 1) * dt
    assert int((t >= settle - 1e-12).sum()) == n  # run_metrics' own rule
    keys = ("sweep.settle_s", "sweep.t_end_s")
    if n >= MIN_SAMPLES:
        _check_window(settle, t_end, h, output_step, where="s.toml", keys=keys)
        return
    with pytest.raises(InputError) as info:
        _check_window(settle, t_end, h, output_step, where="s.toml", keys=keys)
    msg = str(info.value)
    assert info.value.key == "sweep.settle_s" and "s.toml" in msg
    assert f"leaves {n} output sample" in msg and f"at least {MIN_SAMPLES}" in msg
    latest = (len(t) - MIN_SAMPLES) * dt
    assert f"settle_s <= {latest:.6g} s" in msg


def test_hub_force_std_is_numpys_std_of_the_channel_and_rms_keeps_the_static_load():
    """``hub_<c>_<k>_std_N`` is the fluctuation (numpy's std of the channel after settle);
    ``_rms_N`` is the RMS of the total force: rms**2 = mean**2 + std**2."""
    t = np.arange(0.0, 2.0 + 1e-9, 1e-3)
    rng = np.random.default_rng(3)
    hub = 3500.0 + 500.0 * np.sin(2 * np.pi * 7.0 * t) + 50.0 * rng.standard_normal(t.size)
    ch = {"hub_fl_z": hub, "hub_rr_x": 20.0 * np.cos(2 * np.pi * 3.0 * t)}
    m = run_metrics(t, ch, settle=0.5)
    sel = t >= 0.5 - 1e-12
    assert m["hub_fl_z_std_N"] == pytest.approx(np.std(hub[sel]), rel=1e-12)
    assert m["hub_rr_x_std_N"] == pytest.approx(np.std(ch["hub_rr_x"][sel]), rel=1e-12)
    assert m["hub_fl_z_rms_N"] == pytest.approx(np.sqrt(np.mean(hub[sel] ** 2)), rel=1e-12)
    assert m["hub_fl_z_rms_N"] ** 2 == pytest.approx(np.mean(hub[sel]) ** 2
                                                     + m["hub_fl_z_std_N"] ** 2, rel=1e-12)
    assert 350.0 < m["hub_fl_z_std_N"] < 400.0 < 3500.0 < m["hub_fl_z_rms_N"]
    from flexpipe.sweeps.metrics import metric_names

    assert "hub_fl_z_std_N" in metric_names([])


def test_metrics_table_columns_put_swept_parameters_key_and_status_first():
    from flexpipe.sweeps.metrics import table_columns

    cols = ["av_p_m_per_s2", "aw_p_z_m_per_s2", "cpu_s", "hub_fl_z_rms_N", "hub_fl_z_std_N",
            "index", "key", "message", "road.road_class", "speed_kmh", "status", "task_s",
            "travel_absmax_m", "wall_s", "zzz_unknown"]
    out = table_columns(cols, ["speed_kmh", "road.road_class"])
    assert out[:7] == ["speed_kmh", "road.road_class", "key", "status", "message", "cpu_s",
                       "wall_s"]
    assert out.index("hub_fl_z_std_N") < out.index("hub_fl_z_rms_N") < out.index("aw_p_z_m_per_s2")
    assert sorted(out) == sorted(cols) and out[-1] == "zzz_unknown"


def test_sweep_plots_default_to_the_fluctuation_and_have_title_and_unit_labels(tmp_path,
                                                                               monkeypatch):
    import matplotlib.pyplot as plt

    from flexpipe.sweeps.plots import axis_label, default_metrics, plot_metrics
    from flexpipe.sweeps.spec import load_sweep

    spec = load_sweep(_spec(ROOT / "cars" / "sedan.toml", settle_s=0.2)
                      | {"parameters": {"speed_kmh": [50.0, 80.0]}})
    table = pd.DataFrame({"speed_kmh": [50.0, 80.0], "key": ["a", "b"], "status": [0, 0],
                          "hub_fl_z_std_N": [547.0, 669.0], "hub_fl_z_rms_N": [3585.0, 3530.0],
                          "aw_driver_floor_z_m_per_s2": [0.8, 1.1]})
    assert default_metrics(table) == ["aw_driver_floor_z_m_per_s2", "hub_fl_z_std_N"]
    figs = []
    close = plt.close
    monkeypatch.setattr(plt, "close", lambda fig=None: (figs.append(fig), close(fig)))
    files = plot_metrics(table, spec, tmp_path, metrics=default_metrics(table))
    assert [f.name for f in files] == ["aw_driver_floor_z_m_per_s2__vs__speed_kmh.png",
                                       "hub_fl_z_std_N__vs__speed_kmh.png"]
    ax = figs[-1].axes[0]
    assert ax.get_xlabel() == "speed [km/h]"
    assert ax.get_ylabel() == "hub force FL z, fluctuation (std about the mean) [N]"
    title = ax.get_title()
    assert "sedan" in title and "rigid body" in title and "t_end 0.6 s" in title
    assert "metrics from t = 0.2 s" in title and "road" in title
    assert axis_label("hub_fl_z_rms_N") == "hub force FL z, RMS incl. static load [N]"
    assert axis_label("vdv_driver_floor_z_m_per_s1.75").endswith("[m/s^1.75]")
    assert axis_label("car.corners.fl.spring_rate_N_per_m") == (
        "car.corners.fl.spring_rate [N/m]")
