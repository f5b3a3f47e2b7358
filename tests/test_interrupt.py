"""Ctrl-C (SIGINT) and SIGTERM during integration, reduction and writing, in a subprocess.

Contract (issue 14): the command stops with exit code 130 / 143, prints one line (no
traceback), never reports the interrupt as a solver failure, and the output folder keeps
the earlier run as a whole (never an old summary beside new data) while the interrupted
run's own ``summary.json`` ("interrupted at t = ...") goes to ``OUT.failed``; no
temporary file is left behind.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SEDAN = ROOT / "cars" / "sedan.toml"
CODE = {signal.SIGINT: 130, signal.SIGTERM: 143}


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    """One cache for the module: the rigid mass properties are computed once."""
    return tmp_path_factory.mktemp("cache")


def _env(cache):
    env = dict(os.environ, FLEXPIPE_CACHE=str(cache), PYTHONUNBUFFERED="1",
               PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    return env


class _Proc:
    """A subprocess whose stdout+stderr are collected by a thread (no pipe deadlock)."""

    def __init__(self, argv, *, env, cwd):
        self.p = subprocess.Popen(argv, env=env, cwd=cwd, stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT, text=True)
        self.text = ""
        self._t = threading.Thread(target=self._read, daemon=True)
        self._t.start()

    def _read(self):
        for chunk in iter(lambda: self.p.stdout.read(1), ""):
            self.text += chunk

    def wait_for(self, needle: str, timeout: float = 240.0):
        t0 = time.monotonic()
        while needle not in self.text:
            if self.p.poll() is not None or time.monotonic() - t0 > timeout:
                self.p.kill()
                pytest.fail(f"never saw {needle!r}; output:\n{self.text[-3000:]}")
            time.sleep(0.05)

    def finish(self, timeout: float = 120.0) -> int:
        try:
            code = self.p.wait(timeout)
        except subprocess.TimeoutExpired:
            self.p.kill()
            pytest.fail(f"did not stop after the signal; output:\n{self.text[-3000:]}")
        self._t.join(5)
        return code


def _old_run(out: Path) -> None:
    out.mkdir()
    (out / "summary.json").write_text(json.dumps({"status": 0, "state": "completed"}))
    (out / "flexible.csv").write_text("t,x\n0,0\n")


def _old_run_kept(out: Path) -> None:
    """The earlier run is still in ``out``, whole and alone."""
    assert sorted(p.name for p in out.iterdir()) == ["flexible.csv", "summary.json"]
    assert json.loads((out / "summary.json").read_text())["state"] == "completed"
    assert (out / "flexible.csv").read_text() == "t,x\n0,0\n"


def _no_temp_left(folder: Path):
    left = [p.name for p in folder.iterdir() if p.name.startswith(".")]
    assert not left, left


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_signal_during_integration(tmp_path, cache, sig):
    out = tmp_path / "run"
    _old_run(out)
    proc = _Proc([sys.executable, "-m", "flexpipe", "run", str(SEDAN), "--speed", "50",
                  "--t-end", "60", "--body", "rigid", "--out", str(out)],
                 env=_env(cache), cwd=tmp_path)
    proc.wait_for("step")  # the tqdm bar of the time integration
    time.sleep(0.5)
    proc.p.send_signal(sig)
    code = proc.finish()
    assert code == CODE[sig], proc.text[-2000:]
    assert "Traceback" not in proc.text
    assert "converge" not in proc.text and "too large step" not in proc.text
    summary = json.loads((tmp_path / "run.failed" / "summary.json").read_text())
    assert summary["state"] == "interrupted" and summary["status"] == CODE[sig]
    assert f"interrupted ({signal.Signals(sig).name}) at t = " in summary["message"]
    t = float(summary["message"].split("at t = ")[1].split()[0])
    assert 0.0 < t < 60.0
    assert "run.failed" in proc.text  # the message says where the summary went
    _old_run_kept(out)  # the old run keeps its data and its summary
    _no_temp_left(tmp_path)


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_signal_during_reduction(tmp_path, sig):
    out = tmp_path / "run"
    cache = tmp_path / "fresh-cache"
    proc = _Proc([sys.executable, "-m", "flexpipe.scenarios", "straight", "--out", str(out),
                  "--t-end", "0.2"], env=_env(cache), cwd=tmp_path)
    proc.wait_for("reducing body")
    time.sleep(1.0)
    proc.p.send_signal(sig)
    code = proc.finish()
    assert code == CODE[sig], proc.text[-2000:]
    assert "Traceback" not in proc.text
    assert not out.exists()  # an interrupted run does not create the output folder
    failed = tmp_path / "run.failed"
    summary = json.loads((failed / "summary.json").read_text())
    assert summary["state"] == "interrupted"
    assert "during the flexible body run" in summary["message"]
    assert sorted(p.name for p in failed.iterdir()) == ["rigid.csv", "summary.json"]
    assert not [p for p in cache.iterdir() if p.name.startswith(".")]  # no temp file
    assert not list(cache.glob("body-*.npz"))  # no half-written cache entry
    _no_temp_left(tmp_path)


_WRITER = """
import os, signal, sys, time
import flexpipe.vehicle.plots as P
real = P.hub_force
def slow_plot(*a, **k):
    os.kill(os.getpid(), signal.{sig})  # the signal arrives while the results are written
    time.sleep(5)
    return real(*a, **k)
P.hub_force = slow_plot
from flexpipe.cli import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_signal_while_writing(tmp_path, cache, sig):
    out = tmp_path / "run"
    _old_run(out)
    script = tmp_path / "writer.py"
    script.write_text(_WRITER.replace("{sig}", signal.Signals(sig).name))
    proc = _Proc([sys.executable, str(script), "run", str(SEDAN), "--speed", "50",
                  "--t-end", "0.2", "--body", "rigid", "--out", str(out), "-q"],
                 env=_env(cache), cwd=tmp_path)
    code = proc.finish()
    assert code == CODE[sig], proc.text[-2000:]
    assert "Traceback" not in proc.text
    failed = tmp_path / "run.failed"
    summary = json.loads((failed / "summary.json").read_text())
    assert summary["state"] == "interrupted"
    assert summary["completed_runs"]["rigid"].startswith("reached t_end")
    assert sorted(p.name for p in failed.iterdir()) == ["rigid.csv", "summary.json"]
    _old_run_kept(out)
    script.unlink()
    _no_temp_left(tmp_path)
