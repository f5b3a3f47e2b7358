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


def test_failing_channel_format_keeps_the_run_as_csv(tmp_path, capsys, monkeypatch):
    """An exception in an optional format's writer (here scipy's savemat) never discards
    the finished run: its channels go to CSV, the plots and summary are written, and the
    CLI reports one line naming the file, the format and where the channels are."""
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
    assert "rigid.csv" in err
    assert sorted(p.name for p in out.iterdir()) == ["hub_force_fl.png", "rigid.csv",
                                                     "summary.json"]
    summary = json.loads((out / "summary.json").read_text())
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
