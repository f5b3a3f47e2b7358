"""Exudyn's two-thread mode (``simulate(threads=2)``, :mod:`flexpipe.exu.threads`).

References: the one-thread run (a multi-threaded residual sums the same terms, so the
results agree to rounding), and a system of independent mass points on springs whose
result does not depend on the order of its objects.

Exudyn 1.13's parallel loop over the body and connector terms takes the first *n*
objects of its full list, *n* being the number of objects without a user function, so
an object with a user function among them is counted twice.  flexpipe places its
symbolic force laws after every other object; these tests hold the car to that order
and show what goes wrong without it.
"""

import os
from pathlib import Path

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
import pytest
from exudyn.advancedUtilities import CreateSymbolicUserFunction

import flexpipe as fp
import flexpipe.exu.threads as threads_mod
from flexpipe.errors import InputError
from flexpipe.exu.threads import (
    auto_threads,
    misplaced_user_function,
    solver_threads,
    usable_cores,
)
from flexpipe.roads import iso8608
from flexpipe.vehicle.run_inputs import check_threads
from tests._carfiles import absolute_text

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan_linkage.toml"
two_cores = pytest.mark.skipif(usable_cores() < 2, reason="needs two cores")

# a nonlinear (table) bushing on a body mount, so that a bushing law is queued as well
TABLE = """
[suspension.front.bushings.lower_arm_front.tables.z]
deflection = [-0.004, 0.0, 0.004]
force = [-6000.0, 0.0, 5000.0]
"""


def _springs(order: str, threads: int, *, n: int = 60):
    """z of ``n`` mass points on nonlinear springs to the ground (symbolic laws), the
    laws added after each point (``interleaved``) or after all points (``last``);
    also whether the objects are in the order flexpipe requires."""
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ground = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=mbs.AddObject(eii.ObjectGround())))
    keep, points, markers = [], [], []

    def law(mbs, t, item, u, v, k, d, f0):
        return 1000.0 * u + 2.0 * v + 50.0 * u * u * u

    def spring(m):
        f = CreateSymbolicUserFunction(mbs, law, "springForceUserFunction",
                                       itemTypeName="ObjectConnectorSpringDamper")
        keep.append(f)
        mbs.AddObject(eii.ObjectConnectorSpringDamper(markerNumbers=[ground, m],
                                                      springForceUserFunction=f))
    for i in range(n):
        node = mbs.AddNode(eii.NodePoint(referenceCoordinates=[float(i), 0.0, 0.0],
                                         initialCoordinates=[0.0, 0.0, 0.01 * (1 + i % 7)]))
        m = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=mbs.AddObject(
            eii.MassPoint(nodeNumber=node, mass=1.0 + 0.1 * i))))
        points.append(node)
        markers.append(m)
        if order == "interleaved":
            spring(m)
    if order == "last":
        for m in markers:
            spring(m)
    mbs.Assemble()
    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = 200
    s.timeIntegration.endTime = 0.2
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    s.parallel.numberOfThreads = threads
    exu.SolveDynamic(mbs, s)
    z = np.array([mbs.GetNodeOutput(p, exu.OutputVariableType.Position)[2] for p in points])
    return z, misplaced_user_function(mbs) is None, mbs


@two_cores
def test_symbolic_laws_last_two_threads_equal_one():
    z1, ordered, _ = _springs("last", 1)
    z2, _, _ = _springs("last", 2)
    assert ordered
    np.testing.assert_allclose(z2, z1, rtol=0, atol=1e-12 * np.abs(z1).max())


@two_cores
def test_exudyn_counts_interleaved_laws_wrongly_on_two_threads():
    """Why flexpipe orders its objects.  If this fails, Exudyn's parallel residual no
    longer miscounts (``CSystem::ComputeSystemODE2RHS``), and the order is no longer
    needed for a right result (keep it: it costs nothing)."""
    z_ref, _, _ = _springs("last", 1)
    z1, ordered, mbs = _springs("interleaved", 1)
    z2, _, _ = _springs("interleaved", 2)
    assert not ordered
    n, note = solver_threads(mbs, 2)  # flexpipe would not grant the second thread
    assert n == 1 and "object 2 (ConnectorSpringDamper) has a user function" in note
    assert "object 3 (MassPoint) without one" in note
    np.testing.assert_allclose(z1, z_ref, atol=1e-9)  # the order alone changes nothing
    assert np.abs(z2 - z1).max() > 0.1 * np.abs(z1).max()


@two_cores
@pytest.mark.parametrize("body", ["rigid", "flexible"])
def test_linkage_car_on_two_threads_equals_one(tmp_path, body):
    """The sample linkage car (its spring, damper and stop laws, plus a table bushing at
    a lower-arm mount) over ISO class C: two threads give the one-thread hub forces."""
    path = tmp_path / "car.toml"
    path.write_text(absolute_text(CAR) + TABLE)
    car = fp.load_car(path)
    road = iso8608("C", length=60.0, dx=0.05, seed=1, track_width=1.6)
    kw = dict(road=road, speed=70 / 3.6, t_end=0.4, body=body)
    one = fp.simulate(car, threads=1, **kw)
    two = fp.simulate(car, threads=2, **kw)
    assert one.status == 0 and two.status == 0, (one.message, two.message)
    assert (one.info["threads"], two.info["threads"]) == (1, 2), two.info.get("threads_note")
    for c in ("fl", "fr", "rl", "rr"):
        for ax in "xyz":
            a, b = one[f"hub_{c}_{ax}"], two[f"hub_{c}_{ax}"]
            assert np.abs(b - a).max() <= 1e-6 * max(np.ptp(a), 1.0), f"hub_{c}_{ax}"


@pytest.mark.parametrize("bad", [0, -1, 1.5, True, "two", None])
def test_bad_threads_named(bad):
    with pytest.raises(InputError) as e:
        check_threads(bad)
    assert e.value.key == "threads" and "auto" in str(e.value)


def test_threads_beyond_the_cores_refused():
    with pytest.raises(InputError, match="cores"):
        check_threads(usable_cores() + 1)


def test_auto_threads(monkeypatch):
    assert check_threads("auto") == "auto"  # resolved as the run starts
    assert auto_threads("rigid") == 1  # a rigid car gains nothing on two
    monkeypatch.setattr(threads_mod, "usable_cores", lambda: 2)
    monkeypatch.setattr(threads_mod, "idle_cores", lambda: 1.9)
    assert auto_threads("flexible") == 2 and auto_threads("full") == 2
    monkeypatch.setattr(threads_mod, "idle_cores", lambda: 1.2)  # another job running
    assert auto_threads("flexible") == 1
    monkeypatch.setattr(threads_mod, "usable_cores", lambda: 1)
    monkeypatch.setattr(threads_mod, "idle_cores", lambda: 1.9)
    assert auto_threads("flexible") == 1


def test_idle_cores_sees_a_busy_core():
    """With a busy-looping process on one core the idle cores drop by about one."""
    import multiprocessing as mp

    if usable_cores() < 2 or threads_mod.idle_cores(0.05) is None:
        pytest.skip("needs /proc/stat and two cores")
    stop = mp.Event()
    p = mp.Process(target=_spin, args=(stop,))
    p.start()
    try:
        busy = threads_mod.idle_cores(0.3)
    finally:
        stop.set()
        p.join()
    assert busy <= (os.cpu_count() or 1) - 0.7


def _spin(stop):
    while not stop.is_set():
        pass


def test_cli_threads_not_a_number(tmp_path, capsys):
    from flexpipe.cli import main

    assert main(["run", str(CAR), "--speed", "70", "--t-end", "1", "--threads", "two",
                 "--out", str(tmp_path / "run")]) == 2  # argparse's usage error
    assert "'two': give auto or a whole number of threads" in capsys.readouterr().err
    assert not (tmp_path / "run").exists()


def test_cli_threads_out_of_range(tmp_path, capsys):
    from flexpipe.cli import main

    assert main(["run", str(CAR), "--speed", "70", "--t-end", "1", "--threads", "0",
                 "--out", str(tmp_path / "run")]) == 2
    assert "threads must be 'auto' or a whole number from 1 to" in capsys.readouterr().err
    assert not (tmp_path / "run").exists()


@two_cores
def test_misordered_car_runs_on_one_thread_and_says_why(monkeypatch):
    """A car whose laws sit among the other objects (the order before the fix) is not
    given the second thread: a warning, ``info["threads_note"]``, the one-thread result."""
    import flexpipe.exu.linkage as linkage

    def add_now(self, item, link, *, bushing=None):
        co = self.mbs.AddObject(item)
        self.body_links.append((link[0], co, *link[2:]))
        if bushing is not None:
            self.bushings.append((bushing, co))

    car = fp.load_car(CAR)
    road = iso8608("C", length=60.0, dx=0.05, seed=1, track_width=1.6)
    kw = dict(road=road, speed=70 / 3.6, t_end=0.3, body="rigid")
    ref = fp.simulate(car, threads=1, **kw)
    monkeypatch.setattr(linkage.LinkageModel, "_defer", add_now)
    with pytest.warns(UserWarning, match="one thread instead of 2"):
        r = fp.simulate(car, threads=2, **kw)
    assert r.status == 0 and r.info["threads"] == 1
    assert "precedes object" in r.info["threads_note"]
    np.testing.assert_allclose(r["hub_fl_z"], ref["hub_fl_z"], rtol=0, atol=1e-6)
