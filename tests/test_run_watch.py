"""Runs that leave what a car can do stop with what, where and when
(:mod:`flexpipe.vehicle.watch`), and a stopped run's files are still whole.

The cars are the sample sedan with one value changed in code (``dataclasses.replace``),
so that the load-time range checks of the car file do not stop them first: the point
here is what a run does when the model diverges anyway.
"""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

import numpy as np
import pytest

from flexpipe.vehicle import load_car, simulate
from flexpipe.vehicle.dynamics import Recorder
from flexpipe.vehicle.simulation import DEFAULT_STEP

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(autouse=True)
def _cache(tmp_path_factory, monkeypatch):
    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path_factory.getbasetemp() / "watch_cache"))


def _sedan(**corner_fl):
    car = load_car(ROOT / "cars" / "sedan.toml")
    if corner_fl:
        corners = list(car.corners)
        corners[0] = dataclasses.replace(corners[0], **corner_fl)
        car = dataclasses.replace(car, corners=tuple(corners) if isinstance(
            car.corners, tuple) else corners)
    return car


def _stiff_bar(car):
    bars = dict(car.anti_roll_bars)
    bars["front"] = dataclasses.replace(bars["front"], rate=1e12) if dataclasses.is_dataclass(
        bars["front"]) else 1e12
    return dataclasses.replace(car, anti_roll_bars=bars)


def test_recorder_keeps_rows_beyond_the_planned_number():
    """The solver may cut steps (adaptive step) and so record more rows than planned: the
    recorder grows instead of dropping the end of the run."""
    rec = Recorder(["a", "b"], 2)
    for k in range(5):
        rec.add(0.1 * k, np.array([k, -k], dtype=float))
    ch = rec.channels()
    assert rec.rows == 5
    np.testing.assert_array_equal(ch["a"], [0, 1, 2, 3, 4])
    np.testing.assert_allclose(rec.t[:5], 0.1 * np.arange(5))


def test_a_wheel_spinning_away_stops_the_run_naming_the_wheel():
    """A spin inertia of 1e-9 kg m^2 (a real wheel: about 1 kg m^2) makes the spin
    coupling diverge; before, the run finished 'completed' with 3e10 rad/s."""
    r = simulate(_sedan(spin_inertia=1e-9), speed=30 / 3.6, t_end=0.3,
                 body="rigid")
    assert r.status == -1
    assert "wheel fl spins at" in r.message and "numerical divergence" in r.message
    assert r.t[-1] < 0.05


@pytest.mark.parametrize("h, symptom", [(1e-3, "the body turns at"),
                                         (DEFAULT_STEP, "suspension travel")])
def test_a_stiff_bar_blowing_up_is_divergence_not_an_overturn(h, symptom):
    """Whichever symptom of the divergence the watch sees first (at 1 ms the body's
    rate, at the default step the wheel's travel), the message calls it divergence and
    names the stiff elements the car file may hold, not an overturn."""
    r = simulate(_stiff_bar(_sedan()), speed=30 / 3.6, t_end=0.3, body="rigid", h=h)
    assert r.status == -1
    assert symptom in r.message and "overturned" not in r.message
    assert "numerical divergence" in r.message and "anti-roll bar" in r.message


def test_a_1_m_road_step_stops_with_the_tyre_force(tmp_path):
    """A 1 m step under the front wheels: the point-contact tyre's force reaches 28 times
    the car's weight, which the run reports instead of finishing 'completed'."""
    from flexpipe.roads import load_road

    f = tmp_path / "step.csv"
    f.write_text("distance_m,left_m,right_m\n0,0,0\n9.999,0,0\n10.0,1.0,1.0\n40,1.0,1.0\n")
    car = _sedan()
    r = simulate(car, road=load_road(f), speed=30 / 3.6, t_end=1.5, body="rigid")
    assert r.status == -1
    assert "tyre normal force" in r.message and "times the car's weight" in r.message
    front_x = float(max(c.wheel_center[0] for c in car.corners))
    # the stop comes when a front wheel meets the step (the body origin starts ~6 m in)
    assert "corner fl" in r.message or "corner fr" in r.message
    assert r.t[-1] < 1.0 and front_x > -1.0


def test_a_diverged_flexible_run_reports_the_stop_not_a_durability_error(tmp_path):
    """Before, the durability step ran on the diverged motion and the run ended in
    'ValueError: arange: cannot compute length' with a traceback."""
    from flexpipe.scenarios.runner import run_pair

    out = tmp_path / "out"
    summary = run_pair(_stiff_bar(_sedan()), road=None, path="straight", speed=30 / 3.6,
                       t_end=0.02, out=out, title="diverging", bodies=("flexible",),
                       log=lambda *a: None, progress=False)
    assert summary["status"] != 0 and summary["state"] == "stopped early"
    assert "the body turns at" in summary["messages"]["flexible"]
    assert summary["durability"].startswith("skipped: the flexible run did not complete")
    failed = Path(str(out) + ".failed")
    on_disk = json.loads((failed / "summary.json").read_text())
    assert on_disk["durability"] == summary["durability"]
    assert not out.exists()


def test_every_corner_off_its_ride_height_is_named_in_one_message():
    """Before, the ride-height check stopped at the first corner, so fixing a car took a
    run per corner."""
    from flexpipe.errors import InputError
    from flexpipe.vehicle.simulation import prepare

    car = _sedan()
    corners = [dataclasses.replace(c, wheel_center=np.asarray(c.wheel_center) + [0, 0, 0.02])
               for c in car.corners]
    car = dataclasses.replace(car, corners=type(car.corners)(corners))
    with pytest.raises(InputError) as info:
        prepare(car, body="rigid", speed=0.0)
    text = str(info.value)
    for name in ("fl", "fr", "rl", "rr"):
        assert f"corners.{name}.wheel_center_m z = " in text
    assert text.count("set z to") == 4 and "sedan.toml" in text


def test_a_car_off_its_ride_height_is_refused_before_the_output_folder(tmp_path, capsys):
    """``flexpipe run --help``: bad files are reported before DIR is created or touched;
    the ride-height check ran inside the run and left DIR.failed behind."""
    from flexpipe.cli import main

    text = (ROOT / "cars" / "sedan.toml").read_text().replace('"../', f'"{ROOT}/')
    old = "wheel_center_m = [0.0, 0.775, 0.2983]"
    assert old in text
    car = tmp_path / "car.toml"
    car.write_text(text.replace(old, "wheel_center_m = [0.0, 0.775, 0.33]"))
    out = tmp_path / "out"
    assert main(["run", str(car), "--speed", "30", "--t-end", "0.05", "--body", "rigid",
                 "--out", str(out), "-q"]) == 2
    err = capsys.readouterr().err
    assert "corners.fl.wheel_center_m z = 0.3300 m" in err and "car.toml" in err
    assert not out.exists() and not Path(str(out) + ".failed").exists()


@pytest.mark.parametrize("t_reached, words", [
    (0.0, "at the first step, so the step is rarely the cause"),
    (0.2, "a too large step h = 0.00125 s"),
])
def test_a_solver_failure_at_the_start_does_not_blame_the_step(monkeypatch, t_reached, words):
    """No step makes a car start that cannot (a locked or free linkage part): a Newton
    failure at the first step points at the model, one later at the step."""
    from flexpipe.exu.car import CarSystem
    from flexpipe.exu.timeloop import RunOutcome

    monkeypatch.setattr(CarSystem, "run", lambda self, step, **kw: RunOutcome(
        False, t_reached, 0.0, 0.0, "SolveDynamic terminated", 0.0, {}))
    r = simulate(_sedan(), speed=30 / 3.6, t_end=0.3, body="rigid", settle=False)
    assert r.status == -1 and words in r.message


@pytest.mark.parametrize("field, index", [("body_p", 1), ("wheel_p", (3, 2)),
                                          ("jounce", 0), ("spin_rate", 2)])
@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_any_non_finite_state_value_stops_the_run(field, index, bad):
    from types import SimpleNamespace

    from flexpipe.vehicle import watch

    st = SimpleNamespace(body_p=np.zeros(3), wheel_p=np.zeros((4, 3)), jounce=np.zeros(4),
                         spin_rate=np.full(4, 50.0), body_w=np.zeros(3))
    assert watch.state_problem(st, 0.0, 0.0) is None
    getattr(st, field)[index] = bad
    assert "non-finite" in watch.state_problem(st, 0.0, 0.0)


def test_the_cached_half_car_cannot_be_changed_by_a_caller():
    """build_model caches one model per variant; before, scaling its K in place doubled
    every later natural frequency of that variant in the process."""
    from flexpipe.halfcar import build_model, natural_frequencies

    f0 = np.array(natural_frequencies("complete")[:4])
    m = build_model("complete", None)
    with pytest.raises(ValueError, match="read-only"):
        m.K[:] *= 4.0
    np.testing.assert_array_equal(natural_frequencies("complete")[:4], f0)


@pytest.mark.parametrize("kwargs, key, words", [
    ({"t_end": 0.02, "h": 0.0015}, "t_end", "use t_end = 0.0195 or 0.021 s"),
    ({"t_end": 0.0105, "h": 0.001}, "t_end", "10.5 steps"),
    ({"t_end": 0.02, "output_step": 0.0015}, "output_step", "whole multiple of the step"),
    ({"t_end": 0.02, "output_step": 1e-4}, "output_step", "whole multiple of the step"),
    ({"t_end": 0.02, "output_step": 0.5}, "output_step", "at most t_end"),
    ({"t_end": 0.02, "driver": (1, 2)}, "driver",
     "(PurePursuit or OpenLoopSteer, SpeedPI, OpenLoopTorque or None)"),
    ({"t_end": 0.02, "initial_rates": "abc"}, "initial_rates", "3 finite numbers"),
])
def test_time_base_and_driver_arguments_are_checked(kwargs, key, words):
    """Before: t_end = 0.02 s at h = 1.5 ms ran 13 steps of 1.54 ms with rows stamped on
    a 1.5 ms grid (second row at 3.8e-5 s); output_step was rounded silently; a bad driver
    or initial_rates raised AttributeError / ValueError from deep inside."""
    from flexpipe.errors import InputError

    with pytest.raises(InputError, match=re.escape(words)) as info:
        simulate(_sedan(), speed=10.0, body="rigid", **kwargs)
    assert info.value.key == key


def test_a_whole_number_of_steps_gives_a_uniform_time_base():
    r = simulate(_sedan(), speed=10.0, t_end=0.021, h=0.0015, body="rigid", settle=False)
    assert r.status == 0
    np.testing.assert_allclose(np.diff(r.t), 0.0015, rtol=1e-9)


@pytest.mark.parametrize("output_step", [None, 0.0025])
def test_the_last_row_is_the_state_at_t_end(output_step):
    """A completed run says "reached t_end"; before, its last row was at t_end - h (each
    step records the state at its start, and the end state was never recorded)."""
    r = simulate(_sedan(), speed=10.0, t_end=0.02, body="rigid", output_step=output_step)
    assert r.status == 0 and r.t[-1] == pytest.approx(0.02, abs=1e-12)
    np.testing.assert_allclose(np.diff(r.t), output_step or DEFAULT_STEP, rtol=1e-9)
    assert np.all(np.isfinite(r["hub_fl_z"])) and np.all(np.isfinite(r["tire_fl_Fz"]))
