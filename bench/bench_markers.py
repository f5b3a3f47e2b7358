"""Exudyn's cost of a joint on the flexible body, by marker kind.

The linkage car's flexible body (``cars/sedan_linkage.toml``) alone, its mounts joined to
the ground, integrated for a fixed number of steps with one Newton iteration each: the
constraint time per joint and Newton iteration for a spherical joint on the one-point
position marker of a mount and for a generic joint on the rigid (6-DOF) marker of a
mount (three points, :mod:`flexpipe.exu.body`).  The peer is the bare body in the same
run.  Measured 2026-12-01 (46 modes, Exudyn's range-checked module and its constraint
timers): on the former seven-point rigid markers a generic joint cost 0.124 ms per
iteration, 22x a spherical joint (0.0056 ms); on three points 0.058 ms, 10x.  The third
case puts each generic joint on a 6-DOF bracket of the mount
(:func:`flexpipe.exu.brackets.mount_bracket`); its figure includes the bracket's own
constraints.  The cost per joint and Newton iteration is the run's CPU time beyond the
bare body's, per joint and iteration: Exudyn's fast module (flexpipe's default) has no
part timers, and the same measure serves both modules (``exudyn_module`` in the output).
"""

from __future__ import annotations

import time
from pathlib import Path

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

from flexpipe.exu import compiled_module
from flexpipe.exu.body import add_flexible_body
from flexpipe.exu.brackets import mount_bracket
from flexpipe.vehicle import load_car
from flexpipe.vehicle.simulation import prepare

ROOT = Path(__file__).resolve().parents[1]
STEPS = 500


def _run(fb, kind: str, n_joints: int) -> dict:
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    bh = add_flexible_body(mbs, fb, gravity=(0.0, 0.0, 0.0))
    ground = mbs.AddObject(eii.ObjectGround())
    made = 0
    for itf in fb.interfaces:
        if made == n_joints:
            break
        p = [float(v) for v in itf.point]
        if kind == "spherical":
            mg = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground, localPosition=p))
            mbs.AddObject(eii.ObjectJointSpherical(
                markerNumbers=[mg, bh.position_markers[itf.name]]))
        elif itf.name in bh.markers:  # one axis each: never redundant
            mg = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=p))
            axes = [0] * 6
            axes[made % 6] = 1
            mb = bh.markers[itf.name] if kind == "generic" else mount_bracket(
                mbs, bh, fb, itf.name, p0=(0.0, 0.0, 0.0), R0=np.eye(3), v0=(0.0, 0.0, 0.0))
            mbs.AddObject(eii.GenericJoint(markerNumbers=[mg, mb], constrainedAxes=axes))
        else:
            continue
        made += 1
    mbs.Assemble()
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.numberOfSteps, ti.endTime, ti.verboseMode = STEPS, STEPS * 2e-3, 0
    ti.newton.useModifiedNewton = True
    s.linearSolver.solverType = exu.LinearSolverType.EXUdense
    s.solution.file.write = False
    printing = exu.config.printToConsole
    exu.config.printToConsole = False
    try:
        t0 = time.thread_time()
        exu.SolveDynamic(mbs, s, storeSolver=True)
        cpu = time.thread_time() - t0
    finally:
        exu.config.printToConsole = printing
    iters = mbs.sys["dynamicSolver"].it.newtonStepsCount
    return {"joints": made, "ms_per_step": 1e3 * cpu / STEPS, "ms_per_iteration": 1e3 * cpu / iters}


def run() -> dict:
    """Run the benchmark; returns a flat dict of figures."""
    fb = prepare(load_car(ROOT / "cars" / "sedan_linkage.toml"), body="flexible",
                 speed=70 / 3.6)["flexbody"]
    bare = _run(fb, "spherical", 0)
    sph = _run(fb, "spherical", 30)
    gen = _run(fb, "generic", 12)
    brk = _run(fb, "bracket", 12)
    def per_joint(r):  # CPU per Newton iteration beyond the bare body's, per joint
        return (r["ms_per_iteration"] - bare["ms_per_iteration"]) / r["joints"]

    per_sph, per_gen, per_brk = per_joint(sph), per_joint(gen), per_joint(brk)
    out = {
        "exudyn_module": compiled_module(),
        "elastic_modes": fb.n_elastic,
        "bare_body_ms_per_step": round(bare["ms_per_step"], 4),
        "spherical_joints": sph["joints"],
        "spherical_ms_per_joint_iteration": round(per_sph, 5),
        "generic_joints": gen["joints"],
        "generic_ms_per_joint_iteration": round(per_gen, 5),
        "ratio_generic_to_spherical": round(per_gen / per_sph, 2),
        "bracket_ms_per_joint_iteration": round(per_brk, 5),
        "ratio_generic_to_bracket": round(per_gen / per_brk, 2),
    }
    for k, v in out.items():
        print(f"{k:36s} {v}")
    return out


if __name__ == "__main__":
    run()
