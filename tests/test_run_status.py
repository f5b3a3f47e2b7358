"""Run status and messages (issue 14): what a stopped run reports, plain numbers in
errors, argument checks that used to reach Exudyn."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.errors import InputError, plain_numbers
from tests.badinput.gen_cars import base_text

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path / "cache"))


@pytest.fixture(scope="module")
def preload_car(tmp_path_factory):
    """The sample car with a -1e6 N spring preload at the front-left corner."""
    text = base_text().replace("[corners.fl]\n", "[corners.fl]\nspring_preload_N = -1e6\n", 1)
    path = tmp_path_factory.mktemp("car") / "car.toml"
    path.write_text(text)
    return fp.load_car(path)


def test_divergence_names_the_implausible_preload_and_what_diverged(preload_car):
    r = fp.simulate(preload_car, speed=10.0, t_end=0.2, body="rigid")
    assert r.status == -1
    # the static preload that holds the design position is the corner's wheel load minus
    # its unsprung weight: positive and of the order of a quarter of the car's weight
    assert "corners.fl.spring_preload_N = -1e+06 N" in r.message
    assert str(preload_car.file) in r.message
    assert "last recorded state" in r.message and "_fl" in r.message


def test_summary_compares_only_runs_that_both_completed(preload_car):
    from flexpipe.scenarios.runner import _summary

    car = fp.load_car(ROOT / "cars" / "sedan.toml")
    good = fp.simulate(car, speed=10.0, t_end=0.1, body="rigid")
    bad = fp.simulate(preload_car, speed=10.0, t_end=0.1, body="rigid")
    assert good.status == 0 and bad.status == -1
    both = _summary({}, {"rigid": good, "flexible": good}, path=None, speed=10.0)
    assert both["status"] == 0 and "hub_force_difference_rigid_vs_flexible" in both
    one = _summary({}, {"rigid": good, "flexible": bad}, path=None, speed=10.0)
    assert one["status"] == -1 and one["state"] == "stopped early"
    assert "hub_force_difference_rigid_vs_flexible" not in one
    assert "not computed" in one["hub_force_difference_note"]


def test_hub_force_note_states_the_comparison_start_actually_used():
    """A 0.1 s run is compared from min(0.5 s, 0.25 x 0.1 s) = 0.025 s, and the note says
    so (not 'after the first 0.5 s')."""
    from flexpipe.scenarios.runner import _summary

    car = fp.load_car(ROOT / "cars" / "sedan.toml")
    good = fp.simulate(car, speed=10.0, t_end=0.1, body="rigid")
    note = _summary({}, {"rigid": good, "flexible": good}, path=None,
                    speed=10.0)["hub_force_difference_note"]
    assert "t = 0.025 s" in note and "0.5 s" in note and "0.25" in note
    assert "first 0.5 s" not in note


def test_profile_table_names_the_clock_of_the_fast_module(monkeypatch, capsys):
    """The CPU-time label follows flexpipe.exu.MODULES['fast'], not a copy of its name."""
    import flexpipe.exu
    from flexpipe.cli.run import _print_profile

    monkeypatch.setitem(flexpipe.exu.MODULES, "fast", "exudynRenamed")
    summary = {"exudyn_module": "exudynRenamed",
               "profile_ms_per_step": {"rigid": {"solver": 1.0}}}
    _print_profile(summary)
    assert capsys.readouterr().out.startswith("CPU time per step")


def test_failed_run_keeps_the_old_folder_and_writes_its_own_status(tmp_path, monkeypatch):
    """A run that raises midway (here: its plot, after the rigid body run) leaves the old
    run's files in ``out`` untouched and its own summary (state 'error') with the files of
    the finished runs in ``OUT.failed``; no staging folder is left."""
    import json

    from flexpipe.scenarios.runner import run_pair

    out = tmp_path / "run"
    out.mkdir()
    (out / "summary.json").write_text('{"status": 0}')
    (out / "flexible.csv").write_text("old")

    def broken_plot(*a, **k):
        raise InputError("nonsense plot", key="plot")

    monkeypatch.setattr("flexpipe.vehicle.plots.hub_force", broken_plot)
    with pytest.raises(InputError) as info:
        run_pair(ROOT / "cars" / "sedan.toml", road=None, path=None, speed=10.0, t_end=0.1,
                 out=out, title="t", bodies=("rigid",), plots=("hub_force_fl",),
                 log=lambda *a: None, progress=False)
    assert any("run.failed" in n for n in info.value.__notes__)
    assert (out / "summary.json").read_text() == '{"status": 0}'
    assert (out / "flexible.csv").read_text() == "old"
    failed = tmp_path / "run.failed"
    summary = json.loads((failed / "summary.json").read_text())
    assert summary["state"] == "error" and summary["status"] == 2
    assert "nonsense" in summary["message"]
    assert sorted(p.name for p in failed.iterdir()) == ["rigid.csv", "summary.json"]
    assert not [p for p in tmp_path.iterdir() if p.name.startswith(".")]


@pytest.mark.parametrize("kw, key", [({"bodies": ("rigid", "nonsense")}, "body"),
                                     ({"t_end": 0.0}, "t_end"),
                                     ({"speed": 1000.0 / 3.6}, "speed"),
                                     ({"h": 2.0}, "h"),
                                     ({"t_end": 100.0, "road": ROOT / "roads" / "bump.csv"},
                                      None)])
def test_bad_arguments_raise_before_the_output_folder_is_touched(tmp_path, kw, key):
    """run_pair checks every body's arguments (numbers, body kind, road length) before it
    stages anything: the old run stays, no OUT.failed, no staging folder."""
    from flexpipe.scenarios.runner import run_pair

    out = tmp_path / "run"
    out.mkdir()
    (out / "summary.json").write_text('{"status": 0}')
    args = {"road": None, "path": None, "speed": 10.0, "t_end": 0.1, "out": out,
            "title": "t", "bodies": ("rigid",), "plots": (), "log": lambda *a: None,
            "progress": False, **kw}
    with pytest.raises(InputError) as info:
        run_pair(ROOT / "cars" / "sedan.toml", **args)
    assert info.value.key == key
    assert sorted(p.name for p in tmp_path.iterdir() if p.name != "cache") == ["run"]
    assert [p.name for p in out.iterdir()] == ["summary.json"]
    assert (out / "summary.json").read_text() == '{"status": 0}'


@pytest.mark.parametrize("kw, key", [({"h": 4e-3, "t_end": 2e-3}, "h"),
                                     ({"max_mode_hz": -1.0}, "max_mode_hz"),
                                     ({"max_mode_hz": float("nan")}, "max_mode_hz")])
def test_arguments_checked_before_the_solver(kw, key):
    car = fp.load_car(ROOT / "cars" / "sedan.toml")
    with pytest.raises(InputError) as info:
        fp.simulate(car, speed=10.0, body="flexible", **{"t_end": 0.1, **kw})
    assert info.value.key == key


def test_messages_show_plain_numbers():
    text = f"got {np.float64(0.2)!r}, {np.int64(3)!r} and {[np.float32(1.5)]!r}"
    assert plain_numbers(text) == "got 0.2, 3 and [1.5]"
    assert "np." not in str(InputError(f"radius {np.float64(-0.5)!r}", key="radius"))
