"""``flexpipe stress`` / ``animate`` on a damaged or stopped run folder: a one-line error
naming the file and what to do (before: tracebacks with exit 1, or a wrong cause)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from flexpipe.cli import main
from flexpipe.durability.rundir import load_run, read_channels

ROOT = Path(__file__).resolve().parents[1]
CAR = str(ROOT / "cars" / "sedan_linkage.toml")


def _summary(folder, **extra):
    doc = {"scenario": "run", "state": "completed", "status": 0, "car_file": CAR,
           "messages": {"flexible": "reached t_end = 0.2 s"}, **extra}
    (folder / "summary.json").write_text(json.dumps(doc))


@pytest.mark.parametrize("command", ["stress", "animate"])
@pytest.mark.parametrize("text", ["", '{"scenario": "run", "sta'])
def test_a_cut_summary_is_a_one_line_error(tmp_path, capsys, command, text):
    run = tmp_path / "run"
    run.mkdir()
    (run / "summary.json").write_text(text)
    assert main([command, str(run)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and len(err.strip().splitlines()) == 1
    assert "summary.json" in err and "not valid JSON" in err and "rerun" in err


@pytest.mark.parametrize("command", ["stress", "animate"])
def test_a_cut_motion_file_is_a_one_line_error(tmp_path, capsys, command):
    run = tmp_path / "run"
    run.mkdir()
    _summary(run)
    np.savez(run / "motion_flexible.npz", t=np.arange(1000.0), q=np.zeros((1000, 30)))
    data = (run / "motion_flexible.npz").read_bytes()
    (run / "motion_flexible.npz").write_bytes(data[: len(data) // 3])
    assert main([command, str(run)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and "motion_flexible.npz" in err
    assert "damaged or cut short" in err


@pytest.mark.parametrize("suffix", ["h5", "mat"])
def test_a_cut_channel_file_names_the_file(tmp_path, suffix):
    from flexpipe.errors import InputError

    path = tmp_path / f"flexible.{suffix}"
    if suffix == "h5":
        import h5py

        with h5py.File(path, "w") as f:
            f["t"] = np.arange(5000.0)
            f.create_group("channels")["x"] = np.arange(5000.0)
    else:
        from scipy.io import savemat

        savemat(path, {"t": np.arange(5000.0), "channels": {"x": np.arange(5000.0)}})
    path.write_bytes(path.read_bytes()[:2000])
    with pytest.raises(InputError, match="damaged or cut short") as info:
        read_channels(tmp_path, "flexible")
    assert f"flexible.{suffix}" in str(info.value)


def test_a_stopped_run_says_why_it_has_no_motion(tmp_path):
    from flexpipe.errors import InputError

    run = tmp_path / "run.failed"
    run.mkdir()
    stop = "simulation stopped at t = 0.5060 s: tyre normal force 4.16e+05 N at corner fl"
    _summary(run, state="stopped early", status=-1, messages={"flexible": stop})
    with pytest.raises(InputError) as info:
        load_run(run)
    text = str(info.value)
    assert "stopped early" in text and stop in text and "this flexpipe version" not in text
