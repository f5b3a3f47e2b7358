"""``flexpipe run`` and the scenario runner: outputs, summary content, exit codes."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from flexpipe.cli import main

ROOT = Path(__file__).resolve().parents[1]
SEDAN = ROOT / "cars" / "sedan.toml"


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path / "cache"))


def test_run_writes_csv_plots_and_summary(tmp_path, capsys):
    out = tmp_path / "run"
    code = main(["run", str(SEDAN), "--speed", "36", "--t-end", "0.4", "--body", "rigid",
                 "--path", str(ROOT / "paths" / "slalom_18m.toml"), "--out", str(out)])
    assert code == 0
    names = sorted(p.name for p in out.iterdir())
    assert names == ["hub_force_fl.png", "rigid.csv", "summary.json", "trajectory.png"]
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == 0
    assert summary["simulated_time_s"] == pytest.approx(0.4)
    assert summary["speed_kmh"] == pytest.approx(36.0)
    assert set(summary["cpu_time_s"]) == {"rigid"}
    header = (out / "rigid.csv").read_text().splitlines()[0].split(",")
    speed = np.loadtxt(out / "rigid.csv", delimiter=",", skiprows=1)[:, header.index(
        "speed [m/s]")]
    assert speed[0] == pytest.approx(10.0, rel=1e-4)  # 36 km/h
    assert (out / "hub_force_fl.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "rigid body" in capsys.readouterr().out


@pytest.mark.parametrize("args, words", [
    (["--speed", "50", "--body", "stiff"], ["--body", "rigid, flexible, full"]),
    (["--speed", "50", "--road", "nowhere.crg"], ["nowhere.crg"]),
    (["--speed", "-5"], ["--speed"]),
])
def test_run_reports_bad_input_in_one_line(tmp_path, capsys, args, words):
    out = tmp_path / "bad"
    code = main(["run", str(SEDAN), "--t-end", "0.2", "--out", str(out), *args])
    assert code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("flexpipe run: error:") and "\n" not in err
    for w in words:
        assert w in err
    assert not out.exists() or not any(out.iterdir())  # nothing half-written


def _earlier_run(out: Path) -> dict:
    """A folder holding an earlier successful run; returns its files' bytes."""
    out.mkdir()
    files = {"summary.json": b'{"status": 0, "state": "completed"}\n',
             "rigid.csv": b"t [s],x [m]\n0,0\n", "hub_force_fl.png": b"\x89PNG\r\n\x1a\nold"}
    for name, data in files.items():
        (out / name).write_bytes(data)
    return files


def _files(folder: Path) -> dict:
    return {p.name: p.read_bytes() for p in folder.iterdir()}


@pytest.mark.parametrize("args, words", [
    (["--t-end", "0"], ["--t-end", "(0, 3600] s"]),
    (["--t-end", "nan"], ["--t-end", "(0, 3600] s"]),
    (["--h", "1"], ["--h", "[1e-05, 0.005] s"]),
    (["--h", "0"], ["--h", "[1e-05, 0.005] s"]),
    (["--speed", "5000"], ["--speed", "[0, 288] km/h", "5000"]),
    (["--speed", "-10"], ["--speed", "[0, 288] km/h"]),
    (["--body", "rgid"], ["--body", "rigid, flexible, full"]),
    (["--t-end", "0.0005"], ["--h", "--t-end"]),
    (["--road", str(ROOT / "roads" / "bump.csv"), "--t-end", "100"], ["bump.csv", "30 m"]),
    (["--f-max", "0", "--body", "flexible"], ["--f-max", "(0, 5000] Hz"]),
    (["--f-max", "40"], ["--f-max", "band of the flexible body", "--body rigid"]),
])
def test_bad_run_arguments_leave_the_output_folder_untouched(tmp_path, capsys, args, words):
    """Argument errors are found before any work: an earlier run in --out keeps every
    file, a new --out is not created, no staging or failure folder is left."""
    base = ["run", str(SEDAN), "--body", "rigid", "--speed", "10", "--t-end", "0.2", "-q"]
    old = tmp_path / "old"
    before = _earlier_run(old)
    assert main([*base, "--out", str(old), *args]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("flexpipe run: error:") and "\n" not in err
    for w in words:
        assert w in err, err
    assert _files(old) == before
    new = tmp_path / "new"
    assert main([*base, "--out", str(new), *args]) == 2
    assert sorted(p.name for p in tmp_path.iterdir()) == ["old"]


def test_speed_error_speaks_km_per_h(tmp_path, capsys):
    code = main(["run", str(SEDAN), "--speed", "5000", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code == 2 and "--speed" in err and "km/h" in err and "[0, 288]" in err
    assert "1388" not in err  # not the m/s value of the library


def test_failed_run_keeps_the_previous_results(tmp_path, capsys, monkeypatch):
    """A run that fails after it started leaves --out as it was and its own summary in
    OUT.failed; the next completed run replaces --out and removes OUT.failed."""
    from flexpipe.errors import InputError

    out = tmp_path / "run"
    before = _earlier_run(out)

    def broken_plot(*a, **k):
        raise InputError("the plot broke", key="plot")

    monkeypatch.setattr("flexpipe.vehicle.plots.hub_force", broken_plot)
    argv = ["run", str(SEDAN), "--speed", "20", "--t-end", "0.1", "--body", "rigid",
            "--out", str(out), "-q"]
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert "the plot broke" in err and "run.failed" in err and "\n" not in err
    assert _files(out) == before
    failed = tmp_path / "run.failed"
    summary = json.loads((failed / "summary.json").read_text())
    assert summary["state"] == "error" and "the plot broke" in summary["message"]
    assert sorted(p.name for p in failed.iterdir()) == ["rigid.csv", "summary.json"]
    monkeypatch.undo()
    assert main(argv) == 0
    assert json.loads((out / "summary.json").read_text())["state"] == "completed"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cache", "run"]


def test_run_that_stops_early_keeps_the_previous_results(tmp_path, capsys):
    from tests.badinput.gen_cars import base_text

    car = tmp_path / "car.toml"
    car.write_text(base_text().replace("[corners.fl]\n",
                                       "[corners.fl]\nspring_preload_N = -1e6\n", 1))
    out = tmp_path / "run"
    before = _earlier_run(out)
    code = main(["run", str(car), "--speed", "10", "--t-end", "0.2", "--body", "rigid",
                 "--out", str(out), "-q"])
    assert code == 1
    assert "stopped early" in capsys.readouterr().err
    assert _files(out) == before
    summary = json.loads((tmp_path / "run.failed" / "summary.json").read_text())
    assert summary["state"] == "stopped early" and summary["status"] == -1


def test_run_help_says_what_a_failed_run_leaves(capsys):
    assert main(["run", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "DIR.failed" in text and "before DIR is created or touched" in text


def test_failing_channel_format_keeps_the_run_as_csv(tmp_path, capsys, monkeypatch):
    """An exception in an optional format's writer (here scipy's savemat) never discards
    the finished run: its channels go to CSV, the plots and summary are written, the run
    counts as failed (its folder is OUT.failed, as any failed run's) and the CLI reports
    one line naming the file, the format and where the channels are."""
    def boom(*args, **kwargs):
        raise ValueError("Field names are restricted to 31 characters")

    monkeypatch.setattr("scipy.io.savemat", boom)
    out = tmp_path / "run"
    code = main(["run", str(SEDAN), "--speed", "36", "--t-end", "0.2", "--body", "rigid",
                 "--format", "mat", "--out", str(out), "-q"])
    assert code == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("flexpipe run: error:") and "\n" not in err
    assert "rigid.mat" in err and "'mat'" in err and "31 characters" in err
    assert "rigid.csv" in err and "run.failed" in err
    assert not out.exists()  # a failed run never becomes (or replaces) --out
    failed = tmp_path / "run.failed"
    assert sorted(p.name for p in failed.iterdir()) == ["hub_force_fl.png", "rigid.csv",
                                                        "summary.json"]
    summary = json.loads((failed / "summary.json").read_text())
    assert summary["state"] == "error" and summary["status"] == 2
    assert "rigid.mat" in summary["message"] and "rigid.csv" in summary["message"]
    assert summary["messages"]["rigid"].startswith("reached t_end")  # the run's own results
    assert summary["files"] == ["hub_force_fl.png", "rigid.csv", "summary.json"]
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


def test_unknown_format_is_rejected_before_the_solver(tmp_path):
    from flexpipe.errors import InputError
    from flexpipe.scenarios.runner import run_pair

    with pytest.raises(InputError, match="csv, hdf5, mat") as info:
        run_pair(SEDAN, road=None, path=None, speed=10.0, t_end=0.1, out=tmp_path / "r",
                 title="t", bodies=("rigid",), plots=(), format="xlsx",
                 log=lambda *a: pytest.fail("simulated before checking the format"))
    assert info.value.key == "format"
    assert not (tmp_path / "r").exists()


@pytest.mark.parametrize("car_name", ["sedan.toml", "sedan_linkage.toml"])
def test_summary_static_wheel_loads_sum_to_the_car_weight(tmp_path, car_name):
    """summary.json's static wheel loads are the car's ground reactions at rest (those of
    ``flexpipe info``): they sum to the weight m g of every mass of the car, the rack and
    anti-roll-bar arms of a linkage car included (not the prismatic formula preload +
    m_unsprung g, which misses them)."""
    from flexpipe.vehicle import bodymodel
    from flexpipe.vehicle.corners import GRAVITY
    from flexpipe.vehicle.spec import load_car
    from flexpipe.vehicle.suspension.model import ARB_ARM_MASS, RACK_MASS

    car = load_car(ROOT / "cars" / car_name)
    mass = bodymodel.rigid_properties(car).mass + sum(c.unsprung_mass for c in car.corners)
    if car.suspension is not None:
        n_arb = sum(a.anti_roll_bar is not None for a in car.suspension.axles.values())
        mass += RACK_MASS * (car.suspension.rack is not None) + 2 * n_arb * ARB_ARM_MASS
    out = tmp_path / "run"
    assert main(["run", str(car.file), "--speed", "20", "--t-end", "0.02", "--body", "rigid",
                 "--out", str(out), "-q"]) == 0
    by_corner = json.loads((out / "summary.json").read_text())["static_wheel_load_N"]
    assert list(by_corner) == ["fl", "fr", "rl", "rr"]
    loads = list(by_corner.values())
    assert min(loads) > 0
    assert sum(loads) == pytest.approx(mass * GRAVITY, rel=1e-6)


def test_summary_stores_the_absolute_car_file(tmp_path, monkeypatch):
    """A car given by a relative path is stored absolute in summary.json, so that
    ``flexpipe stress OUT`` / ``animate OUT`` find it from any folder."""
    monkeypatch.chdir(ROOT)
    out = tmp_path / "run"
    assert main(["run", "cars/sedan.toml", "--speed", "20", "--t-end", "0.02", "--body",
                 "rigid", "--out", str(out), "-q"]) == 0
    car_file = json.loads((out / "summary.json").read_text())["car_file"]
    assert Path(car_file).is_absolute() and Path(car_file) == SEDAN


def test_path_keywords_in_help_and_errors(tmp_path, capsys):
    """--help names the path keywords; an unknown bare name is 'no such path file' with
    the file types and the keywords, reported before the output folder is created."""
    assert main(["run", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "'straight'" in text and "'road'" in text
    out = tmp_path / "o"
    assert main(["run", str(SEDAN), "--speed", "30", "--path", "slalom", "--out", str(out),
                 "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("flexpipe run: error: slalom: no such path file") and "\n" not in err
    assert "'straight'" in err and "'road'" in err and ".toml" in err
    assert not out.exists()


# ----------------------------------------------------------------------- --check-step
def _no_simulation(*a, **k):
    raise AssertionError("a run started before the arguments were checked")


@pytest.mark.parametrize("args, words", [
    (["--check-step", "--t-end", "0.3"], ["--t-from 0.5 s (the default)", "--t-end 0.3 s",
                                          "--t-from <= 0.29875 s"]),
    (["--check-step", "--t-end", "1", "--t-from", "1"], ["--t-from 1 s", "<= 0.99875 s"]),
    (["--check-step", "--t-from", "-1"], ["--t-from", "[0, 3600] s"]),
    (["--check-step", "--h", "2e-5"], ["--h", "h/4 = 5e-06 s", "1e-05 s", "4e-05 s"]),
    (["--t-from", "0.2"], ["--t-from", "--check-step", "min(0.5 s, 0.25 x --t-end)"]),
    (["--check-step", "--t-end", "-1"], ["--t-end", "(0, 3600] s"]),
])
def test_check_step_arguments_are_checked_before_any_run(tmp_path, capsys, monkeypatch,
                                                         args, words):
    """The comparison window and the finest step are checked up front, in the options'
    terms, before any run and before the output folder (even a folder of other files,
    which a study refuses like a run)."""
    monkeypatch.setattr("flexpipe.vehicle.simulation.simulate", _no_simulation)
    foreign = tmp_path / "foreign"
    foreign.mkdir()
    (foreign / "notes.txt").write_text("keep")
    assert main(["run", str(SEDAN), "--speed", "70", "--body", "rigid", "--out",
                 str(foreign), "-q", *args]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("flexpipe run: error:") and "\n" not in err
    for w in words:
        assert w in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cache", "foreign"] or \
        sorted(p.name for p in tmp_path.iterdir()) == ["foreign"]
    assert [p.name for p in foreign.iterdir()] == ["notes.txt"]


def test_check_step_library_checks_window_and_steps_before_running(monkeypatch):
    from flexpipe.errors import InputError
    from flexpipe.vehicle.convergence import check_step

    monkeypatch.setattr("flexpipe.vehicle.simulation.simulate", _no_simulation)
    with pytest.raises(InputError, match=r"t_from = 0.5 s .* t_end = 0.3 s") as info:
        check_step(SEDAN, speed=10.0, t_end=0.3, body="rigid")
    assert info.value.key == "t_from"
    with pytest.raises(InputError, match=r"h/4 = 5e-06 s.*1e-05") as info:
        check_step(SEDAN, h=2e-5, speed=10.0, t_end=1.0, body="rigid")
    assert info.value.key == "h"


def test_check_step_table_marks_negligible_fluctuations():
    """A channel whose fluctuation is below the floor (1 N for forces, or 1e-6 of its
    mean) gets its absolute difference and 'n/a' instead of a percentage, and the
    footnote says why; the header line states h, refinements, t_end and t_from; the CSV
    keeps the absolute and relative columns with units and a meaningful flag."""
    import csv
    import io

    from flexpipe.vehicle.convergence import StepCheck

    chk = StepCheck(steps=(1e-3, 5e-4, 2.5e-4), channels=("hub_fl_z", "hub_rl_y", "travel_fl"),
                    rms_diff=np.array([[20.0, 4.27e-6, 1e-5], [5.0, 4.37e-6, 2e-6]]),
                    rel_dynamic=np.array([[0.04, 1.018, 0.01], [0.01, 1.042, 0.002]]),
                    std_ref=np.array([500.0, 4.19e-6, 1e-3]), cpu_time=(1.0, 2.0, 4.0),
                    units=("N", "N", "m"), mean_abs_ref=np.array([3500.0, 3e-6, 0.01]),
                    floor=np.array([1.0, 1.0, 1e-6]), t_from=0.5, t_end=3.0)
    assert chk.meaningful.tolist() == [True, False, True]
    text = chk.table()
    head = text.splitlines()[0]
    for w in ("h = 0.001 s", "refinements 2, 4", "t_end = 3 s", "t_from = 0.5 s"):
        assert w in head, head
    row = next(ln for ln in text.splitlines() if ln.startswith("hub_rl_y"))
    assert row.split()[1] == "N" and "4.27e-06" in row and "n/a" in row
    assert "%" not in row and "n/a: fluctuation 4.19e-06 N below floor 1 N" in row
    row = next(ln for ln in text.splitlines() if ln.startswith("hub_fl_z"))
    assert "(  4.0 %)" in row and "n/a" not in row
    assert next(ln for ln in text.splitlines() if ln.startswith("travel_fl")).split()[1] == "m"
    assert "n/a: the fluctuation is below the floor (1 N, 1e-06 m; or 1e-06" in text
    rows = list(csv.DictReader(io.StringIO(chk.csv_text())))
    assert rows[1]["channel"] == "hub_rl_y" and rows[1]["relative_meaningful [-]"] == "0"
    assert float(rows[1]["rms_diff h=0.001 s [unit column]"]) == pytest.approx(4.27e-6)
    assert float(rows[1]["rel_dynamic h=0.001 s [-]"]) == pytest.approx(1.018)
    assert rows[0]["unit"] == "N" and rows[0]["relative_meaningful [-]"] == "1"
    assert chk.worst() == pytest.approx(0.04)  # the n/a channel is not the worst


def test_check_step_writes_a_run_folder_and_respects_quiet(tmp_path, capsys):
    """--check-step -q: only the table on stdout (no progress bars, no log lines); the
    folder holds step_check.csv (units in the header) and a summary.json describing the
    study; the same command without --check-step then accepts the folder (argument
    errors reported first) and replaces it with its run."""
    out = tmp_path / "study"
    argv = ["run", str(SEDAN), "--speed", "70", "--t-end", "0.3", "--t-from", "0.1",
            "--body", "rigid", "--out", str(out)]
    assert main([*argv, "--check-step", "-q"]) == 0
    cap = capsys.readouterr()
    assert cap.err == ""
    lines = cap.out.splitlines()
    assert lines[0].startswith("step convergence: h = 0.00125 s") and "t_from = 0.1 s" in lines[0]
    assert lines[-1].startswith("CPU s per run") and not any("wrote" in ln for ln in lines)
    assert any(ln.startswith("hub_rl_y") and "n/a" in ln for ln in lines)  # flat road
    assert sorted(p.name for p in out.iterdir()) == ["step_check.csv", "summary.json"]
    header = (out / "step_check.csv").read_text().splitlines()[0]
    assert "std_reference [N]" in header and "rms_diff h=0.00125 s [N]" in header
    summary = json.loads((out / "summary.json").read_text())
    assert summary["scenario"] == "check_step" and summary["state"] == "completed"
    assert summary["t_from_s"] == 0.1 and summary["t_end_s"] == pytest.approx(0.3)
    assert summary["steps_s"] == [1.25e-3, 6.25e-4, 3.125e-4] and summary["refinements"] == [2, 4]
    assert summary["files"] == ["step_check.csv", "summary.json"]
    assert set(summary["file_descriptions"]) == {"step_check.csv", "summary.json"}
    assert summary["channels"]["hub_rl_y"]["relative_meaningful"] is False
    assert summary["channels"]["hub_fl_z"]["unit"] == "N"
    assert Path(summary["car_file"]).is_absolute()
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]
    assert main(["run", str(SEDAN), "--speed", "70", "--t-end", "-1", "--out",
                 str(out)]) == 2
    assert "--t-end" in capsys.readouterr().err
    assert main(["run", str(SEDAN), "--speed", "70", "--t-end", "0.05", "--body", "rigid",
                 "--out", str(out), "-q"]) == 0
    assert json.loads((out / "summary.json").read_text())["scenario"] == "run"


def test_failed_check_step_keeps_the_folder_and_writes_its_summary(tmp_path, capsys,
                                                                   monkeypatch):
    from flexpipe.errors import SolverError

    def diverging(*a, **k):
        raise SolverError("diverged", time=0.1)

    out = tmp_path / "study"
    before = _earlier_run(out)
    monkeypatch.setattr("flexpipe.vehicle.simulation.simulate", diverging)
    assert main(["run", str(SEDAN), "--speed", "70", "--t-end", "1", "--body", "rigid",
                 "--check-step", "--out", str(out), "-q"]) == 2
    err = capsys.readouterr().err.strip()
    assert "diverged" in err and "study.failed" in err and "\n" not in err
    assert _files(out) == before
    summary = json.loads((tmp_path / "study.failed" / "summary.json").read_text())
    assert summary["scenario"] == "check_step" and summary["state"] == "error"
    assert "diverged" in summary["message"]


def test_check_step_summary_names_road_and_path_files_absolutely(tmp_path, capsys,
                                                                 monkeypatch):
    """A road given relative to the working folder is stored by its absolute path (like
    car_file), so the study's summary.json finds it from any folder."""
    from flexpipe.errors import SolverError

    def diverging(*a, **k):
        raise SolverError("diverged", time=0.1)

    monkeypatch.chdir(ROOT)
    monkeypatch.setattr("flexpipe.vehicle.simulation.simulate", diverging)
    out = tmp_path / "study"
    assert main(["run", str(SEDAN), "--speed", "70", "--t-end", "1", "--body", "rigid",
                 "--road", "roads/flat_500m.toml", "--check-step", "--out", str(out),
                 "-q"]) == 2
    capsys.readouterr()
    summary = json.loads((tmp_path / "study.failed" / "summary.json").read_text())
    assert summary["road"] == str(ROOT / "roads" / "flat_500m.toml")
    assert Path(summary["road"]).is_absolute() and summary["path"] is None


def test_check_step_run_that_stops_early_is_reported_like_a_run(tmp_path, capsys,
                                                                 monkeypatch):
    """A refined run that stops before t_end: the study says 'stopped early' (status -1,
    exit 1, like a run), keeps the run that completed and leaves the folder as it was."""
    from types import SimpleNamespace

    import flexpipe.vehicle.simulation as S

    real = S.simulate

    def second_stops(car, *, h, **k):
        if h < 1.25e-3:
            return SimpleNamespace(status=-1, message="stopped at t = 0.1 s: diverged",
                                   info={"h": h})
        return real(car, h=h, **k)

    out = tmp_path / "study"
    before = _earlier_run(out)
    monkeypatch.setattr(S, "simulate", second_stops)
    assert main(["run", str(SEDAN), "--speed", "70", "--t-end", "0.2", "--t-from", "0.1",
                 "--body", "rigid", "--check-step", "--out", str(out), "-q"]) == 1
    err = capsys.readouterr().err.strip()
    assert "stopped early" in err and "h = 0.000625 s" in err and "study.failed" in err
    assert "\n" not in err and _files(out) == before
    summary = json.loads((tmp_path / "study.failed" / "summary.json").read_text())
    assert summary["state"] == "stopped early" and summary["status"] == -1
    assert list(summary["completed_runs"]) == ["h = 0.00125 s"]
    assert "h = 0.000625 s" in summary["message"] and "diverged" in summary["message"]


def test_f_max_reaches_every_flexible_run_and_the_step_study(tmp_path, monkeypatch):
    """``--f-max`` is the band of the flexible body in a run and in --check-step."""
    import flexpipe.vehicle.simulation as S

    seen = []

    def record(*args, **kw):
        seen.append(kw.get("f_max"))
        raise RuntimeError("stop after the first simulate call")

    monkeypatch.setattr(S, "simulate", record)
    for extra in ([], ["--check-step"]):
        with pytest.raises(RuntimeError, match="stop after"):
            main(["run", str(SEDAN), "--speed", "70", "--body", "flexible", "--f-max", "40",
                  "--t-end", "1", "--out", str(tmp_path / f"o{len(extra)}"), "-q", *extra])
    assert seen == [40.0, 40.0]


def test_trajectory_plot_keeps_both_traces_visible_and_names_the_run(tmp_path, monkeypatch):
    """Rigid wide grey solid underneath, flexible dashed red on top; the default title
    names car, car file, speed, road and path."""
    import matplotlib.pyplot as plt

    from flexpipe.driver import slalom
    from flexpipe.vehicle import plots as P

    class R:
        def __init__(self, dy):
            x = np.linspace(0.0, 60.0, 200)
            self.ch = {"x_rear": x, "y_rear": 0.5 * np.sin(x / 9.0) + dy}
            self.info = {"car": "sedan", "car_file": "/x/cars/sedan_linkage.toml",
                         "speed": 60.0 / 3.6, "road": "roads/iso_b.toml"}

        def __getitem__(self, name):
            return self.ch[name]

    figs = []
    close = plt.close
    monkeypatch.setattr(plt, "close", lambda fig=None: (figs.append(fig), close(fig)))
    path = slalom(cone_spacing=18.0, n_cones=3, offset=0.5, lead_in=40.0, lead_out=40.0)
    P.trajectory({"rigid": R(0.0), "flexible": R(0.001)}, path, tmp_path / "t.png")
    ax = figs[-1].axes[0]
    lines = {ln.get_label(): ln for ln in ax.get_lines()}
    rigid, flex = lines["followed (rigid body)"], lines["followed (flexible body)"]
    assert rigid.get_linestyle() == "-" and flex.get_linestyle() == "--"
    assert rigid.get_linewidth() > 2 * flex.get_linewidth()
    assert rigid.get_color() != flex.get_color() and flex.get_zorder() > rigid.get_zorder()
    title = ax.get_title()
    assert "sedan (sedan_linkage.toml)" in title and "60 km/h" in title
    assert "iso_b.toml" in title
    assert (tmp_path / "t.png").read_bytes()[:4] == b"\x89PNG"
