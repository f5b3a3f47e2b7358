"""The time loop of a car: Exudyn's generalized-alpha with a Python step before each step.

The step (:class:`flexpipe.vehicle.dynamics.CarController`) reads the state, linearizes the
tyres and force elements and sets the loads; Exudyn then integrates one step implicitly.
The spectral radius is the caller's (``flexpipe.vehicle.simulation.SPECTRAL_RADIUS``),
modified Newton (a Jacobian kept until the body has turned by :data:`JACOBIAN_RENEW_DEG`
or Newton stalls), sparse LU (a few hundred coordinates, most of them in small bodies).
:func:`run` returns a :class:`RunOutcome` with the Newton iteration count and, with
``timers=True``, Exudyn's own computation timers (:func:`solver_stats`).
Ctrl-C and SIGTERM stop the run between steps and are re-raised as
:class:`flexpipe._signals.Interrupted` (flexpipe#14).
"""

from __future__ import annotations

import math
import time
import warnings
from typing import NamedTuple

import exudyn as exu

from flexpipe._signals import Interrupted, deferred_interrupts
from flexpipe.exu import MODULES, compiled_module
from flexpipe.exu.threads import solver_threads
from flexpipe.reduction._threads import openblas_single_threaded

#: angle (deg) the car body may turn, from where the kept Newton Jacobian was computed,
#: before the next step computes a new one.  The joints' constraint Jacobians are in
#: global axes and turn with the car, so a kept Jacobian goes stale as the car yaws: the
#: flexible linkage car took 4.65 Newton iterations per step on the slalom with one
#: Jacobian per run and 2.91 with this renewal (76 Jacobians in 10 s), 12.93 -> 10.01 s
#: of CPU (1 deg: 2.73 iterations, 156 Jacobians, 10.27 s; 3 deg: 3.17, 49, 10.07 s;
#: 2026-12-04).  On a straight road the body turns less and keeps its one Jacobian.
#: ``math.inf``: one Jacobian per run while Newton converges (Exudyn's modified Newton).
JACOBIAN_RENEW_DEG = 2.0
#: Exudyn's computation timers reported by :func:`solver_stats` (its names -> ours)
TIMERS = {"reactionForces": "constraint_reaction_forces", "AERHS": "constraint_equations",
          "ODE2RHS": "body_and_force_terms", "massMatrix": "mass_matrix",
          "newtonIncrement": "back_substitution", "jacobianODE2": "jacobian",
          "factorization": "factorization", "writeSolution": "sensors",
          "python": "python_step", "integrationFormula": "integration_formula",
          "total": "total"}


class RunOutcome(NamedTuple):
    """What :func:`run` reports (a tuple: ``completed, t_reached, cpu, ... = run(...)``)."""

    completed: bool
    t_reached: float
    cpu_s: float
    wall_s: float
    message: str
    python_step_cpu_s: float
    stats: dict
    python_step_wall_s: float = 0.0


def solver_stats(mbs, *, timers: bool) -> dict:
    """Newton iterations, Jacobians and steps of the last dynamic solve of ``mbs`` and,
    with ``timers``, Exudyn's computation timers (seconds, names of :data:`TIMERS`)."""
    solver = mbs.sys.get("dynamicSolver")
    if solver is None:
        return {}
    it = solver.it
    out = {"steps": int(it.numberOfSteps), "newton_iterations": int(it.newtonStepsCount),
           "jacobians": int(it.newtonJacobiCount)}
    if timers:
        out["timers_s"] = {ours: float(getattr(solver.timer, name))
                           for name, ours in TIMERS.items()}
    return out


def solver_info(stats: dict, python_s: float, *, cpu_s: float) -> dict:
    """Newton iterations per step and, when timed, Exudyn's timers in ms per step (the
    ``Result.info`` entries of a run from :attr:`RunOutcome.stats`, the Python step's CPU
    seconds ``python_s`` and the run's CPU seconds ``cpu_s``).

    Exudyn's timers measure wall-clock time (on a loaded machine they include the time
    the process waited for a core).  Its fast module (:mod:`flexpipe.exu`) keeps only its
    total timer: the profile is then CPU time throughout, ``python_step`` (flexpipe's own
    timing), ``exudyn`` (the rest of the run) and ``total`` (the run's CPU time; with two
    threads the process's, which includes the second thread spinning while it waits).
    """
    n = stats.get("steps", 0)
    if not n:
        return {}
    out = {"newton_iterations_per_step": round(stats["newton_iterations"] / n, 3),
           "newton_jacobians": stats["jacobians"],  # computed and factorized
           "threads": stats.get("threads", 1)}
    if stats.get("threads_note"):
        out["threads_note"] = stats["threads_note"]
    if "timers_s" in stats:
        timers = stats["timers_s"]
        if compiled_module() == MODULES["fast"]:  # no part timers in that module
            timers = {"python_step": python_s, "exudyn": cpu_s - python_s, "total": cpu_s}
        out["profile_ms_per_step"] = {k: round(1e3 * v / n, 4) for k, v in timers.items()}
    return out


def run(system, step, *, t_end: float, h: float, spectral_radius: float,
        progress=None, jacobian_every_step: bool = False, output_step: float | None = None,
        timers: bool = False, threads: int = 1) -> RunOutcome:
    """Integrate ``system`` (a :class:`~flexpipe.exu.car.CarSystem`) to ``t_end`` with step
    ``h``; ``step(state) -> CarLoads | None`` runs before every step.

    Exudyn's sensors (if any) store a sample every ``output_step`` (default ``h``).

    ``timers``: switch on Exudyn's computation timers (``RunOutcome.stats``).

    ``threads``: Exudyn's threads (:func:`flexpipe.exu.threads.solver_threads` may grant
    fewer; ``stats["threads"]`` is what ran).  With one thread the CPU time is the
    calling thread's (a sweep's other in-process workers are not counted); with more,
    the process's.

    ``step`` returns ``None`` to stop (e.g. divergence).
    """
    mbs = system.mbs
    n_steps = int(round(t_end / h))
    # the state the integration starts from: the initial configuration (a settled start,
    # flexpipe.vehicle.settle, sets only that one; Exudyn copies it to the current one
    # when the solver initializes, after this first step has read the state)
    sd = mbs.systemData
    sd.SetSystemState(sd.GetSystemState(exu.ConfigurationType.Initial),
                      configuration=exu.ConfigurationType.Current)
    st = system.state(0.0)
    loads = step(st)
    if loads is None:
        return RunOutcome(False, 0.0, 0.0, 0.0, "stopped at the initial state", 0.0, {})
    system.apply(loads, st.mount_R, st)
    last = {"t": 0.0, "n": 0, "cpu": 0.0, "wall": 0.0,  # the Python step's CPU and wall s
            "R": None}  # the body's rotation where the kept Jacobian was computed
    renew_cos = None if jacobian_every_step or not math.isfinite(JACOBIAN_RENEW_DEG) else \
        math.cos(math.radians(min(JACOBIAN_RENEW_DEG, 180.0)))

    def prestep(mbs_, t):
        t0 = t - h  # the state is at the start of the step
        if t0 <= 1e-12:  # t = 0: the constraint forces now exist; the first output row
            refresh = getattr(step, "refresh_first_row", None)  # may read them again
            if refresh is not None:
                refresh()
            return True
        c0, w0 = time.thread_time(), time.perf_counter()
        st = system.state(t0)
        if renew_cos is not None:  # the body turned since the kept Jacobian: a new one
            R = st.body_R
            if last["R"] is None:
                last["R"] = R.copy()
            elif 0.5 * (float((R * last["R"]).sum()) - 1.0) < renew_cos:  # cos(angle)
                mbs.sys["dynamicSolver"].conv.jacobianUpdateRequested = True
                last["R"] = R.copy()
        loads = step(st)
        last["t"] = t0
        last["n"] += 1
        if progress is not None and last["n"] % 100 == 0:
            progress(100)
        if loads is None:
            return False
        system.apply(loads, st.mount_R, st)
        last["cpu"] += time.thread_time() - c0
        last["wall"] += time.perf_counter() - w0
        return True

    def guarded(mbs_, t):  # flexpipe#14: Ctrl-C/SIGTERM stop the run, re-raised below
        if sig.signum is not None:
            return False
        try:
            return prestep(mbs_, t)
        except KeyboardInterrupt as exc:
            last["interrupt"] = exc
            return False

    mbs.SetPreStepUserFunction(guarded)
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.numberOfSteps = n_steps
    ti.endTime = t_end
    ti.verboseMode = 0
    ti.generalizedAlpha.spectralRadius = spectral_radius
    ti.generalizedAlpha.computeInitialAccelerations = True
    ti.newton.useModifiedNewton = not jacobian_every_step
    ti.newton.relativeTolerance = system.newton_rtol
    ti.newton.absoluteTolerance = system.newton_atol
    ti.adaptiveStep = True
    s.solution.file.write = False
    s.solution.sensors.writePeriod = float(output_step or h)
    s.solution.file.writeInitialValues = False
    s.show.statistics = False
    s.show.computationTime = bool(timers)  # Exudyn's timers (its printout is switched off)
    # sparse LU: the Newton increments (one back-substitution per iteration with the kept
    # factorization) cost a third of the dense ones on the linkage car (~480
    # coordinates; Exudyn's timer 0.77 -> 0.24 ms per step, flexible); ISO C 70 km/h,
    # 3 s, identical hub forces, two interleaved pairs of runs: Exudyn CPU 5.6-6.3 ->
    # 4.2-4.3 s flexible, 0.9 -> 0.5 s rigid (2026-12-01)
    s.linearSolver.solverType = exu.LinearSolverType.EigenSparse
    threads, threads_note = solver_threads(mbs, int(threads))
    if threads_note:
        warnings.warn(threads_note, stacklevel=2)
    s.parallel.numberOfThreads = threads
    clock = time.thread_time if threads == 1 else time.process_time  # workers' CPU too
    cpu0, wall0 = clock(), time.perf_counter()
    message = ""
    stats: dict = {}
    printing = exu.config.printToConsole
    exu.config.printToConsole = False  # Exudyn's own notices; failures are reported by us
    try:
        # flexpipe#14: signals only set sig.signum; one BLAS thread (the per-step
        # matrices are tiny: more threads only spin against Exudyn for the cores)
        with deferred_interrupts() as sig, openblas_single_threaded():
            ok = bool(exu.SolveDynamic(mbs, s,
                                       solverType=exu.DynamicSolverType.GeneralizedAlpha,
                                       updateInitialValues=False, storeSolver=True))
    except (RuntimeError, ValueError) as exc:  # Exudyn raises on Newton failure
        ok = False
        message = str(exc).strip().splitlines()[-1] if str(exc).strip() else repr(exc)
    finally:
        exu.config.printToConsole = printing
        stats = solver_stats(mbs, timers=timers)
        stats.update(threads=threads, threads_note=threads_note)
    if sig.signum is not None:  # flexpipe#14: an interrupt, not a solver failure
        raise Interrupted(sig.signum, t=last["t"])
    if "interrupt" in last:
        last["interrupt"].t = last["t"]
        raise last["interrupt"]
    cpu = clock() - cpu0
    wall = time.perf_counter() - wall0
    completed = ok and last["t"] >= t_end - 1.5 * h
    if completed:  # the state at t_end: its output row (the steps record their start)
        step(system.state(t_end))
    return RunOutcome(completed, last["t"], cpu, wall, message, last["cpu"], stats,
                      last["wall"])
