"""The default time step follows the suspension mode: a linkage suspension in compliant
mode (every bushing as given) rings at 70-350 Hz and takes 0.25 ms, every other car
1.25 ms (``bench/bench_compliant.py``, ``bench/bench_convergence.py``).  Whatever runs
a car without a step (``simulate``, ``check_step``, ``flexpipe run``, a sweep) takes
the same one."""

from __future__ import annotations

from pathlib import Path

import pytest

from flexpipe.vehicle import load_car
from flexpipe.vehicle.run_inputs import COMPLIANT_STEP, DEFAULT_STEP, check_run, default_step

ROOT = Path(__file__).resolve().parents[1]
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"
PRISMATIC = ROOT / "cars" / "sedan.toml"


def _compliant(tmp_path) -> Path:
    text = LINKAGE.read_text().replace('"../', f'"{ROOT.as_posix()}/')
    assert 'mode = "kinematic"' in text
    path = tmp_path / "compliant.toml"
    path.write_text(text.replace('mode = "kinematic"', 'mode = "compliant"', 1))
    return path


def test_the_step_of_each_car(tmp_path):
    assert COMPLIANT_STEP < DEFAULT_STEP
    assert default_step(LINKAGE) == DEFAULT_STEP
    assert default_step(PRISMATIC) == DEFAULT_STEP
    assert default_step(_compliant(tmp_path)) == COMPLIANT_STEP
    car = load_car(LINKAGE, overrides={"suspension.mode": "compliant"})
    assert default_step(car) == COMPLIANT_STEP


def test_a_run_without_a_step_takes_its_cars(tmp_path):
    from flexpipe.vehicle import simulate

    comp = _compliant(tmp_path)
    assert check_run(comp, speed=10.0, t_end=0.01, body="rigid").h == COMPLIANT_STEP
    from flexpipe.vehicle.run_inputs import StepWarning

    with pytest.warns(StepWarning):  # coarser than the mode's default (test below)
        assert check_run(comp, speed=10.0, t_end=0.01, body="rigid", h=1e-3).h == 1e-3
    assert check_run(LINKAGE, speed=10.0, t_end=0.01, body="rigid").h == DEFAULT_STEP
    r = simulate(comp, speed=10.0, t_end=0.01, body="rigid")
    assert r.status == 0 and r.info["h"] == COMPLIANT_STEP and len(r.t) == 41


def test_the_step_check_starts_at_the_cars_step(tmp_path, monkeypatch):
    from flexpipe.vehicle.convergence import check_step_inputs

    comp = _compliant(tmp_path)
    steps = check_step_inputs(comp, refinements=(2, 4), t_from=0.0, speed=10.0,
                              t_end=0.01, body="rigid")
    assert steps == (COMPLIANT_STEP, COMPLIANT_STEP / 2, COMPLIANT_STEP / 4)


def test_the_command_line_checks_with_the_cars_step(tmp_path, capsys):
    """--t-end shorter than the car's step is refused naming that step; a bad car
    file still reaches the run's own checks (its error names the file)."""
    from flexpipe.cli import main

    comp = _compliant(tmp_path)
    argv = ["run", str(comp), "--speed", "30", "--body", "rigid", "--t-end", "0.0002",
            "--out", str(tmp_path / "o"), "-q"]
    assert main(argv) == 2
    assert "--h 0.00025 s is longer than --t-end 0.0002 s" in capsys.readouterr().err
    argv[1] = str(LINKAGE)
    assert main(argv) == 2
    assert "--h 0.00125 s is longer than --t-end 0.0002 s" in capsys.readouterr().err
    argv[1] = str(tmp_path / "missing.toml")
    argv[7] = "1"
    assert main(argv) == 2
    assert "missing.toml" in capsys.readouterr().err


@pytest.mark.parametrize("mode, h", [("compliant", COMPLIANT_STEP),
                                     ("kinematic", DEFAULT_STEP)])
def test_a_sweep_without_h_s_takes_each_runs_car_step(tmp_path, mode, h):
    from flexpipe.sweeps.spec import load_sweep

    spec = {"sweep": {"car": str(LINKAGE), "body": "rigid", "t_end_s": 0.5},
            "parameters": {"car.suspension.mode": [mode],
                           "speed_kmh": [30.0, 50.0]}}
    runs = load_sweep(spec, base_dir=tmp_path).runs()
    assert [r.h for r in runs] == [h, h]
    given = load_sweep({**spec, "sweep": {**spec["sweep"], "h_s": 1e-3}},
                       base_dir=tmp_path).runs()
    assert [r.h for r in given] == [1e-3, 1e-3]


def test_a_compliant_car_at_a_coarser_step_is_warned(tmp_path):
    """Above its mode's default the compliant car's hub forces are not converged (44 % of
    their fluctuation off h/8 at 1.25 ms on the sample): the run says so and names the
    file and key; at or below the default, and in kinematic mode, nothing is said."""
    import warnings

    from flexpipe.vehicle.run_inputs import StepWarning

    comp = _compliant(tmp_path)
    with pytest.warns(StepWarning, match=r"compliant\.toml: \[suspension\] mode = "
                                         r"\"compliant\".*h = 0\.001 s.*--check-step"):
        check_run(comp, speed=10.0, t_end=0.01, body="rigid", h=1e-3)
    with warnings.catch_warnings():
        warnings.simplefilter("error", StepWarning)
        check_run(comp, speed=10.0, t_end=0.01, body="rigid")
        check_run(comp, speed=10.0, t_end=0.01, body="rigid", h=1e-4)
        check_run(LINKAGE, speed=10.0, t_end=0.01, body="rigid", h=2e-3)


def test_flexpipe_info_states_the_cars_step(tmp_path):
    from flexpipe.vehicle.describe import car_text

    assert "time runs in compliant mode (default time step 0.25 ms)" in car_text(
        load_car(_compliant(tmp_path)))
    assert "time runs in kinematic mode (default time step 1.25 ms)" in car_text(
        load_car(LINKAGE))
    assert "prismatic corners" in (t := car_text(load_car(PRISMATIC))) and \
        "default time step 1.25 ms" in t
