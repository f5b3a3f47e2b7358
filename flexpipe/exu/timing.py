"""Time-step cost of a flexible body in Exudyn, for benchmarks of the mode count.

:func:`step_cost` hangs the body (or its rigid twin) on vertical spring-dampers at some of
its interfaces, under gravity, and integrates it with the car's solver (generalized-alpha,
fixed step); it returns the CPU time per simulated second.  The same set-up for every
body makes the ratios between bodies (4 corners vs 30 mounts, interface reduction) the
figure of merit; absolute times depend on the machine.
"""

from __future__ import annotations

import time

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

from flexpipe.errors import InputError
from flexpipe.exu.body import add_flexible_body, add_rigid_twin


def step_cost(body, supports, *, h: float = 2e-3, t_end: float = 1.0, rigid: bool = False,
              stiffness: float = 5e4, damping: float = 3e3) -> float:
    """CPU seconds per simulated second of ``body`` on spring-dampers at ``supports``.

    Parameters
    ----------
    body : FlexBody
    supports : list of str
        Interface names carrying a spring-damper to the ground (all three directions).
    h, t_end : float
        Step and end time, s.
    rigid : bool
        Time the rigid twin instead.
    stiffness, damping : float
        Per support and direction, N/m and N s/m.
    """
    missing = [s for s in supports if s not in body.interface_names]
    if missing:
        raise InputError(f"no interfaces {missing}; valid: {list(body.interface_names)}",
                         key="supports")
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    add = add_rigid_twin if rigid else add_flexible_body
    hnd = add(mbs, body, gravity=(0.0, 0.0, -9.81))
    ground = mbs.AddObject(eii.ObjectGround())
    for name in supports:
        p = body.interface(name).point
        mg = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground, localPosition=list(p)))
        mbs.AddObject(eii.CartesianSpringDamper(
            markerNumbers=[mg, hnd.position_markers[name]], stiffness=[stiffness] * 3,
            damping=[damping] * 3))
    mbs.Assemble()
    ss = exu.SimulationSettings()  # as flexpipe/exu/car.py sets its solver
    ti = ss.timeIntegration
    ti.numberOfSteps = int(round(t_end / h))
    ti.endTime = t_end
    ti.verboseMode = 0
    ti.newton.useModifiedNewton = True
    ti.generalizedAlpha.computeInitialAccelerations = True
    ss.solution.file.write = False
    ss.show.statistics = False
    ss.show.computationTime = False
    ss.linearSolver.solverType = exu.LinearSolverType.EXUdense
    t0 = time.process_time()
    ok = exu.SolveDynamic(mbs, ss, solverType=exu.DynamicSolverType.GeneralizedAlpha)
    cpu = time.process_time() - t0
    if ok is False or not np.isfinite(cpu):
        raise RuntimeError("the timing run did not finish")
    return cpu / t_end


__all__ = ["step_cost"]
