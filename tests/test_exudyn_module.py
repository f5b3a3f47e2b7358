"""Exudyn's two compiled modules (``flexpipe.exu.MODULE_ENV``): the fast one flexpipe loads
by default (no range checks, AVX2) must integrate the car exactly as the range-checked one
does, up to rounding; a bad choice is named."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]

RUN = """
import json, sys
import numpy as np
import flexpipe as fp
from flexpipe.scenarios.runner import _straight_road
car = fp.load_car(sys.argv[1])
r = fp.simulate(car, road=_straight_road(), speed=70 / 3.6, t_end=0.4, body=sys.argv[2])
np.savez(sys.argv[3], **{k: v for k, v in r.channels.items() if k.startswith("hub_")})
print(json.dumps({"status": r.status, "module": r.info["exudyn_module"]}))
"""


def _run(choice: str, body: str, out: Path) -> dict:
    env = dict(os.environ, FLEXPIPE_EXUDYN=choice)
    p = subprocess.run([sys.executable, "-c", RUN, str(ROOT / "cars" / "sedan_linkage.toml"),
                        body, str(out)], capture_output=True, text=True, env=env, cwd=ROOT,
                       timeout=600)
    assert p.returncode == 0, p.stderr[-2000:]
    return json.loads(p.stdout.strip().splitlines()[-1])


@pytest.mark.parametrize("body", ["rigid", "flexible"])
def test_fast_module_integrates_as_the_range_checked_one(tmp_path, body):
    checked = _run("checked", body, tmp_path / "checked.npz")
    fast = _run("fast", body, tmp_path / "fast.npz")
    assert checked == {"status": 0, "module": "exudynCPP"}
    if fast["module"] != "exudynCPPfast":
        pytest.skip("this CPU has no AVX2: Exudyn loads its range-checked module either way")
    a, b = np.load(tmp_path / "checked.npz"), np.load(tmp_path / "fast.npz")
    assert sorted(a.files) == sorted(b.files) and len(a.files) >= 12
    for k in a.files:  # rounding only: far below the 5 % step-convergence target
        scale = max(float(np.std(a[k])), 1.0)
        assert np.sqrt(np.mean((a[k] - b[k]) ** 2)) <= 1e-5 * scale, k


def test_a_bad_module_choice_is_named():
    env = dict(os.environ, FLEXPIPE_EXUDYN="quick")
    p = subprocess.run([sys.executable, "-c", "import flexpipe.exu.body"], capture_output=True,
                       text=True, env=env, cwd=ROOT, timeout=300)
    assert p.returncode != 0
    assert "FLEXPIPE_EXUDYN='quick'; valid: fast, checked" in p.stderr


def test_a_choice_that_comes_too_late_is_reported():
    env = dict(os.environ, FLEXPIPE_EXUDYN="checked")
    code = ("import sys; sys.exudynFast = True; import exudyn; import warnings; "
            "warnings.simplefilter('always'); import flexpipe.exu as e; print(e.compiled_module())")
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                       cwd=ROOT, timeout=300)
    assert p.returncode == 0, p.stderr[-2000:]
    if p.stdout.strip().splitlines()[-1] != "exudynCPPfast":
        pytest.skip("this CPU has no AVX2: Exudyn loads its range-checked module either way")
    assert "FLEXPIPE_EXUDYN=checked is not applied" in p.stderr
    assert "set FLEXPIPE_EXUDYN before the first import of exudyn" in p.stderr
