"""Durability outputs of a scenario run (called by :func:`flexpipe.scenarios.runner.run_pair`)
and the work behind ``flexpipe stress`` and ``flexpipe animate``."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from flexpipe._io import absolute, write_matrix_csv, write_text_atomic
from flexpipe.durability.rundir import MOTION_FILE, RunData, load_run, road_strip

#: time between animation frames written by a scenario run, s
ANIMATION_FRAME_STEP = 0.1

DESCRIPTIONS = {
    "rigid.csv": "channels of the rigid-body run vs time t [s]; unit of every column in "
                 "its header (see flexpipe.vehicle.dynamics for the channel list)",
    "flexible.csv": "channels of the flexible-body run vs time t [s]; units in the header",
    "full.csv": "channels of the full-body run vs time t [s]; units in the header",
    **{f"{b}.h5": f"channels of the {b}-body run (HDF5: t, channels/NAME with a unit "
                  "attribute, motion/ for a flexible body, info)"
       for b in ("rigid", "flexible", "full")},
    **{f"{b}.mat": f"channels of the {b}-body run (MATLAB: t, channels, units, motion, info)"
       for b in ("rigid", "flexible", "full")},
    "hub_force_fl.png": "vertical force on the front-left hub of each run; with a rigid "
                        "and another run, rigid minus the other below",
    "trajectory.png": "driven path of each run",
    "spectra.png": "PSDs (Welch, 2 s segments, after the start-up) of the front-left "
                   "vertical hub force with rigid minus flexible, and of the first body "
                   "point's and the first seat's vertical acceleration with their ISO "
                   "2631-1 Wk weighting",
    "handling.png": "circle paths: understeer angle and steer against lateral acceleration "
                    "with the understeer gradient of each run (summary.json 'handling')",
    "steer_response.png": "open-loop steering inputs: steering-wheel angle, yaw rate and "
                          "lateral acceleration at the centre of mass against time "
                          "(a step steer's ISO 7401 figures: summary.json 'step_steer'; a "
                          "sine with dwell's UN R140 criteria: 'sine_with_dwell')",
    "summary.json": "this file: settings, run status, CPU times, hub-force differences",
    "motion_flexible.npz": "flexible body pose (origin position m, body-to-global rotation) "
                           "and elastic modal coordinates per output step, with the body "
                           "file, its band and a road strip (input of flexpipe stress/animate)",
    "hardpoints.csv": "elastic displacement (m) and rotation (rad) of every interface of "
                      "the flexible body (suspension hardpoints, powertrain and subframe "
                      "mounts), global axes, vs time",
}


def hardpoint_table(body, motion):
    """``(header, data)``: elastic hardpoint displacement and rotation in global axes."""
    header, cols = ["t [s]"], [motion.t]
    for itf in body.interfaces:
        sh = itf.shapes[:, motion.mode_index]                      # (6, m)
        u = motion.q @ sh[:3].T                                    # (n, 3) body axes
        th = motion.q @ sh[3:].T
        ug = np.einsum("nij,nj->ni", motion.rotation, u)
        tg = np.einsum("nij,nj->ni", motion.rotation, th)
        for k, a in enumerate("xyz"):
            header.append(f"hardpoint_{itf.name}_u{a} [m]")
            cols.append(ug[:, k])
        for k, a in enumerate("xyz"):
            header.append(f"hardpoint_{itf.name}_r{a} [rad]")
            cols.append(tg[:, k])
    return header, np.column_stack(cols)


def write_hardpoints(path, body, motion):
    """``hardpoints.csv`` (see :data:`DESCRIPTIONS`)."""
    header, data = hardpoint_table(body, motion)
    write_matrix_csv(path, header, data, rest="%.9g")


def record_files(out, files: dict, *, folder: str) -> None:
    """Describe rewritten outputs in ``OUT/summary.json`` (atomically: temp file + rename).

    The entries of ``file_descriptions`` and ``files`` under ``folder/`` are replaced by
    ``files`` (``{path relative to out: description}``), so that the summary describes
    what ``flexpipe stress`` / ``flexpipe animate`` wrote last.
    """
    path = Path(out) / "summary.json"
    summary = json.loads(path.read_text())
    prefix = folder.rstrip("/") + "/"
    desc = {k: v for k, v in summary.get("file_descriptions", {}).items()
            if not k.startswith(prefix)}
    summary["file_descriptions"] = dict(sorted({**desc, **files}.items()))
    summary["files"] = sorted({f for f in summary.get("files", []) if not f.startswith(prefix)}
                              | set(files))
    write_text_atomic(path, json.dumps(summary, indent=2) + "\n")


def stress_outputs(out, *, top: int = 20, fatigue: bool = True, log=print, run=None,
                   body=None, progress: bool = False, record: bool = True) -> dict:
    """``flexpipe stress OUT_DIR``: modal stress recovery and fatigue into ``OUT_DIR/stress``.

    ``record``: update ``OUT_DIR/summary.json`` with the new file descriptions
    (:func:`record_files`; a scenario run writes its summary itself).
    """
    import time

    from flexpipe.durability.recover import recover_stress
    from flexpipe.durability.report import write_stress_report

    run = load_run(out) if run is None else run
    body = run.body(log=log) if body is None else body
    car = run.car()
    mat = car.body.fatigue if fatigue else None
    t0 = time.perf_counter()
    sr = recover_stress(run.motion, body, fatigue=mat, progress=progress)
    seconds = time.perf_counter() - t0
    title = (f"{car.name}: max von Mises over {run.motion.t[-1]:.1f} s "
             f"({run.summary.get('title', '')})")
    files = write_stress_report(Path(out) / "stress", sr, body, run.channels, top=top,
                                title=title)
    i = int(np.argmax(sr.max_von_mises))
    log(f"stress: {len(sr.element_id)} elements, {len(sr.t)} steps in {seconds:.2f} s; max "
        f"von Mises {sr.max_von_mises[i] / 1e6:.1f} MPa at element {sr.element_id[i]} "
        f"({sr.location[i]}) at t = {sr.time_of_max[i]:.3f} s")
    if sr.damage is not None:
        j = int(np.nanargmax(sr.damage))
        per_km = sr.damage[j] / max(sr.distance_km, 1e-12)
        log(f"fatigue: max damage {sr.damage[j]:.3g} ({per_km:.3g} per km) at element "
            f"{sr.element_id[j]}")
    files = {f"stress/{k}": v for k, v in files.items()}
    if record:
        record_files(out, files, folder="stress")
    return files


def animate_outputs(out, *, dest=None, scale: float = 1.0, every: int = 1,
                    progress: bool = False, log=print, run=None, body=None,
                    record: bool = True, shown=None) -> dict:
    """``flexpipe animate OUT_DIR``: the ParaView animation into ``OUT_DIR/animation``.

    ``dest`` replaces the animation folder as a whole (:func:`write_animation`).
    ``record``: update ``OUT_DIR/summary.json`` when ``dest`` is inside ``OUT_DIR``
    (:func:`record_files`).  ``shown``: the name ``OUT_DIR`` is printed as (the final
    folder of a scenario run that writes into a staging folder).
    """
    from flexpipe.durability.animate import write_animation

    out = Path(out)
    run = load_run(out) if run is None else run
    body = run.body(log=log) if body is None else body
    dest = out / "animation" if dest is None else Path(dest)
    files = write_animation(dest, run, body, scale=scale, every=every, progress=progress)
    inside = dest.resolve().is_relative_to(out.resolve())
    rel = dest.resolve().relative_to(out.resolve()).as_posix() if inside else str(dest)
    printed = Path(shown) / rel if inside and shown is not None else dest
    log(f"animation: {printed}/animation.pvd ({len(range(0, len(run.motion.t), every))} "
        "frames)")
    files = {f"{rel}/{k}": v for k, v in files.items()}
    if record and inside:
        record_files(out, files, folder=rel)
    return files


def scenario_outputs(out, results: dict, *, car, road, title: str = "", log=print,
                     progress: bool = False, final=None) -> dict:
    """Durability outputs of a scenario run (motion, hardpoints, stress, animation).

    ``out`` is the folder written (a staging folder), ``final`` the folder it becomes
    (printed in messages; default ``out``); ``progress`` shows progress bars of the
    stress recovery and the animation frames.

    Returns ``{file: description}`` of every file written (and of the run's own files).
    """

    out = Path(out)
    files = {k: v for k, v in DESCRIPTIONS.items()
             if (out / k).exists() or k == "summary.json"}
    r = results.get("flexible")
    if r is None or r.motion is None or r.motion.n_modes == 0:
        return files
    if r.status != 0:  # stopped early (e.g. diverged): its motion is no load history
        log(f"durability outputs skipped: the flexible run did not complete ({r.message})")
        return files
    band = r.info.get("band_hz")
    from flexpipe.vehicle.linkage_setup import reduce_car_body

    body, info = reduce_car_body(car, f_max=band)
    X, Y, Z = road_strip(road, r.motion.position[:, 0], r.motion.position[:, 1],
                         width=2.0 * float(np.max(np.abs([c.wheel_center[1]
                                                          for c in car.corners]))) + 1.0)
    r.motion.save(out / MOTION_FILE.format(body="flexible"), body_file=np.array(info["path"]),
                  band_hz=np.array(band), road_x=X, road_y=Y, road_z=Z)
    write_hardpoints(out / "hardpoints.csv", body, r.motion)
    files.update({k: DESCRIPTIONS[k] for k in ("motion_flexible.npz", "hardpoints.csv")})
    run = RunData(out, {"car_file": absolute(car.file), "title": title}, r.t, r.channels, r.motion,
                  Path(info["path"]), band, (X, Y, Z))
    if body.stress is not None:
        files.update(stress_outputs(out, log=log, run=run, body=body, progress=progress,
                                    record=False))
    every = max(1, int(round(ANIMATION_FRAME_STEP / r.info["output_step"])))
    files.update(animate_outputs(out, every=every, log=log, run=run, body=body,
                                 progress=progress, record=False,
                                 shown=out if final is None else final))
    return files
