"""Profile of a run (``simulate(profile=True)``, ``flexpipe run --profile``).

Exudyn's computation timers (its range-checked module, ``FLEXPIPE_EXUDYN=checked``) split
the wall-clock time of a step; the parts must add up to no more than Exudyn's total, the
Python step as Exudyn times it must match the Python step as flexpipe times it on the same
(wall) clock, and the Newton iterations per step must be a count the solver can make.
With the fast module (the default) only Exudyn's total is timed: the profile is then the
run's CPU time, split into flexpipe's Python step and the rest.  The comparisons hold on a
loaded machine (clocks compared like with like).
"""

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan_linkage.toml"


CHECKED = dict(os.environ, FLEXPIPE_EXUDYN="checked")

PROFILED_RUN = """
import json, sys
from flexpipe.scenarios.runner import _straight_road, run_pair
from flexpipe.vehicle import simulate
car, out = sys.argv[1], sys.argv[2]
summary = run_pair(car, road=None, path=None, speed=15.0, t_end=0.3, out=out, title="profile",
                   bodies=("rigid",), log=lambda *a: None, progress=False, profile=True,
                   plots=())
r = simulate(car, road=_straight_road(), speed=15.0, t_end=0.3, body="rigid", profile=True)
print(json.dumps({"summary": summary, "info": r.info}, default=str))
"""


@pytest.fixture(scope="module")
def profiled(tmp_path_factory):
    """A profiled scenario run and a profiled simulation, in a process of their own on
    Exudyn's range-checked module (the one with the part timers)."""
    out = tmp_path_factory.mktemp("prof") / "run"
    p = subprocess.run([sys.executable, "-c", PROFILED_RUN, str(CAR), str(out)],
                       capture_output=True, text=True, cwd=ROOT, env=CHECKED, timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    got = json.loads(p.stdout.strip().splitlines()[-1])
    assert got["info"]["exudyn_module"] == "exudynCPP"
    return got["summary"], out, got["info"]


def test_profile_parts_add_up_to_exudyns_total(profiled):
    summary, out, _ = profiled
    prof = summary["profile_ms_per_step"]["rigid"]
    parts = {k: v for k, v in prof.items() if k != "total"}
    assert min(parts.values()) >= 0.0
    assert sum(parts.values()) <= prof["total"] * 1.001
    # the constraints and the Python step are the big parts of a linkage car's step
    assert prof["constraint_reaction_forces"] > 0 and prof["python_step"] > 0
    assert json.loads((out / "summary.json").read_text())["profile_ms_per_step"] == \
        summary["profile_ms_per_step"]


def test_profile_python_step_agrees_with_flexpipes_own_timing(profiled):
    info = profiled[2]
    n = round(0.3 / info["h"])
    ours = 1e3 * info["wall_python_step_s"] / n  # Exudyn's timers are wall-clock time
    theirs = info["profile_ms_per_step"]["python_step"]
    assert 0.5 * ours < theirs < 2.0 * ours
    assert info["cpu_python_step_s"] <= info["wall_python_step_s"] * 1.01
    assert 1.0 <= info["newton_iterations_per_step"] <= 25.0  # Exudyn's limit is 25
    # modified Newton: at least the first Jacobian, and far fewer than the Newton steps
    assert 1 <= info["newton_jacobians"] <= info["newton_iterations_per_step"] * n


def test_fast_module_profile_is_the_python_step_and_the_rest():
    from flexpipe.exu import compiled_module
    from flexpipe.vehicle import simulate

    if compiled_module() != "exudynCPPfast":
        pytest.skip("Exudyn's fast module is not loaded (no AVX2, or FLEXPIPE_EXUDYN=checked)")
    r = simulate(CAR, speed=15.0, t_end=0.2, body="rigid", profile=True)
    prof = r.info["profile_ms_per_step"]
    assert set(prof) == {"python_step", "exudyn", "total"}
    n = round(0.2 / r.info["h"])
    assert prof["python_step"] == pytest.approx(1e3 * r.info["cpu_python_step_s"] / n, abs=1e-4)
    assert prof["exudyn"] > 0 and prof["python_step"] + prof["exudyn"] == \
        pytest.approx(prof["total"], abs=2e-4)
    # CPU time throughout: the total is the run's CPU time (not Exudyn's wall-clock timer)
    assert prof["total"] * n * 1e-3 == pytest.approx(r.cpu_time, abs=n * 1e-7)


def test_unprofiled_run_reports_iterations_only(profiled):
    summary, _, _ = profiled
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
    assert "wall-clock time (Exudyn's timers" in proc.stdout  # the checked module's clock
    assert "per step, ms (Exudyn module exudynCPP)" in proc.stdout
    assert "constraint_reaction_forces" in proc.stdout
    assert "Newton iterations per step" in proc.stdout
