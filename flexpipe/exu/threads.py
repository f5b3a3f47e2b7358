"""Exudyn's threads for a car run: how many, and whether the system allows more than one.

With ``parallel.numberOfThreads = 2`` Exudyn evaluates the constraint equations, the
constraint reaction forces and the body and connector terms of each Newton residual on
two threads.  Objects whose force law is a user function (flexpipe's symbolic force laws,
:mod:`flexpipe.exu.force_laws`) are meant to be evaluated serially, after the others;
but Exudyn 1.13's parallel loop over the body and connector terms
(``CSystem::ComputeSystemODE2RHS``) takes the first *n* objects of the full list, *n*
being the number of objects *without* a user function.  A law object among those first
*n* is then counted twice and the last objects without a law not at all: flexpipe's
linkage car, its laws built corner by corner among the other objects, drifted in body
height by 24 m in 2 s (measured 2026-12-01, docs/performance-history.md).  Placing every
law object after all other objects
(:meth:`flexpipe.exu.linkage.LinkageModel.add_law_connectors`) makes the first *n*
objects exactly those without a law; a two-thread run then equals a one-thread one to
rounding (``tests/test_threads.py``).  :func:`solver_threads` checks that order before
it grants a second thread.

Exudyn's worker threads wait by spinning: a two-thread run keeps two cores busy for its
whole length, so it pays only where nothing else wants the second core (a single run, not
a sweep's workers).  Measured gains are in :func:`flexpipe.vehicle.simulation.simulate`'s
``threads`` and the README.
"""

from __future__ import annotations

import os
import time


def usable_cores() -> int:
    """Cores this process may run on (its CPU affinity; ``os.cpu_count()`` elsewhere)."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # not on Linux
        return os.cpu_count() or 1


def idle_cores(seconds: float = 0.2) -> float | None:
    """Cores the whole machine left idle over the next ``seconds`` (``/proc/stat``; this
    process sleeps meanwhile, so its own core counts as idle); None where there is no
    ``/proc/stat``."""
    def sample():
        with open("/proc/stat") as f:
            v = [int(x) for x in f.readline().split()[1:9]]
        return v[3] + v[4], sum(v)  # idle + iowait, all
    try:
        i0, t0 = sample()
        time.sleep(seconds)
        i1, t1 = sample()
    except (OSError, ValueError, IndexError):
        return None
    return (i1 - i0) / max(t1 - t0, 1) * (os.cpu_count() or 1)


def auto_threads(body: str) -> int:
    """``threads="auto"``: 2 for a flexible or full body when this process may use two
    cores and two are idle right now (:func:`idle_cores` at least 1.75; without
    ``/proc/stat``: a 1-minute load average below cores - 1.5), else 1.  A rigid car
    gains nothing on two threads (README, "Two threads")."""
    cores = usable_cores()
    if body not in ("flexible", "full") or cores < 2:
        return 1
    idle = idle_cores()
    if idle is not None:
        return 2 if idle >= 1.75 else 1
    try:
        load = os.getloadavg()[0]
    except OSError:  # no load average either
        return 1
    return 2 if load < cores - 1.5 else 1


def _has_user_function(item: dict) -> bool:
    """An object's parameter dictionary sets a computation user function (Exudyn puts
    ``0`` where none is set; ``V...`` keys are drawing functions)."""
    return any(k.endswith(("UserFunction", "UserFunction_t")) and not k.startswith("V")
               and not isinstance(v, int) for k, v in item.items())


def misplaced_user_function(mbs) -> tuple | None:
    """The first object with a user function that precedes an object without one, and
    that object: ``((index, type), (index, type))``; None when the order is right."""
    law = None
    for i in range(mbs.systemData.NumberOfObjects()):
        item = mbs.GetObject(i)
        if _has_user_function(item):
            law = law or (i, item["objectType"])
        elif law is not None:
            return law, (i, item["objectType"])
    return None


def solver_threads(mbs, requested: int) -> tuple[int, str]:
    """Threads Exudyn may use for ``mbs``: ``requested``, or 1 with the reason when the
    objects are not in the order the module docstring gives (every object with a user
    function after every object without one)."""
    if requested > 1:
        bad = misplaced_user_function(mbs)
        if bad is not None:
            (i, a), (j, b) = bad
            return 1, (f"one thread instead of {requested}: object {i} ({a}) has a user "
                       f"function and precedes object {j} ({b}) without one, which "
                       "Exudyn's multi-threaded residual would count wrongly; add objects "
                       "with user functions last (flexpipe.exu.threads)")
    return requested, ""
