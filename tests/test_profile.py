"""Profile of a run (``simulate(profile=True)``, ``flexpipe run --profile``).

Exudyn's computation timers split the CPU time of a step; the parts must add up to no
more than Exudyn's total, the Python step as Exudyn times it must match the Python step as
flexpipe times it, and the Newton iterations per step must be a count the solver can make.
"""

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan_linkage.toml"


@pytest.fixture(scope="module")
def profiled(tmp_path_factory):
    from flexpipe.scenarios.runner import run_pair

    out = tmp_path_factory.mktemp("prof") / "run"
    summary = run_pair(CAR, road=None, path=None, speed=15.0, t_end=0.3, out=out,
                       title="profile", bodies=("rigid",), log=lambda *a: None,
                       progress=False, profile=True, plots=())
    return summary, out


def test_profile_parts_add_up_to_exudyns_total(profiled):
    summary, out = profiled
    prof = summary["profile_ms_per_step"]["rigid"]
    parts = {k: v for k, v in prof.items() if k != "total"}
    assert min(parts.values()) >= 0.0
    assert sum(parts.values()) <= prof["total"] * 1.001
    # the constraints and the Python step are the big parts of a linkage car's step
    assert prof["constraint_reaction_forces"] > 0 and prof["python_step"] > 0
    assert json.loads((out / "summary.json").read_text())["profile_ms_per_step"] == \
        summary["profile_ms_per_step"]


def test_profile_python_step_agrees_with_flexpipes_own_timing():
    from flexpipe.scenarios.runner import _straight_road
    from flexpipe.vehicle import simulate

    r = simulate(CAR, road=_straight_road(), speed=15.0, t_end=0.3, body="rigid",
                 profile=True)
    n = round(0.3 / r.info["h"])
    ours = 1e3 * r.info["cpu_python_step_s"] / n
    theirs = r.info["profile_ms_per_step"]["python_step"]
    assert 0.5 * ours < theirs < 2.0 * ours
    assert 1.0 <= r.info["newton_iterations_per_step"] <= 25.0  # Exudyn's limit is 25


def test_unprofiled_run_reports_iterations_only(profiled):
    summary, _ = profiled
    assert 1.0 <= summary["newton_iterations_per_step"]["rigid"] <= 25.0
    from flexpipe.vehicle import simulate

    r = simulate(CAR, speed=0.0, t_end=0.05, body="rigid")
    assert "profile_ms_per_step" not in r.info and r.info["newton_iterations_per_step"] >= 1


def test_cli_profile_prints_the_table(tmp_path):
    proc = subprocess.run(
        [sys.executable, "-m", "flexpipe", "run", str(CAR), "--speed", "30", "--t-end", "0.1",
         "--body", "rigid", "--profile", "--out", str(tmp_path / "o")],
        capture_output=True, text=True, cwd=ROOT, timeout=600)
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert "CPU per step, ms" in proc.stdout and "constraint_reaction_forces" in proc.stdout
    assert "Newton iterations per step" in proc.stdout
