"""The step-convergence study of ``flexpipe run ... --check-step`` as a run folder.

:func:`run_step_check` is to :func:`~flexpipe.vehicle.convergence.check_step` what
:func:`~flexpipe.scenarios.runner.run_pair` is to a run: a transaction.  Every argument
(the window ``t_from`` .. ``t_end`` and every refined step included) and the output
folder are checked first; the study writes ``step_check.csv`` and ``summary.json``
(``"scenario": "check_step"``: the step sizes, the window, per channel its unit,
fluctuation, floor and differences, and what every file holds) into a staging folder
that replaces the output folder only when the study completes.  A study that fails or
is interrupted leaves the output folder as it was and puts its own ``summary.json`` in
``OUT.failed``: state ``"stopped early"`` (status -1, like a run) with the runs that
completed when one of its runs stops before ``t_end``, else ``"error"`` or
``"interrupted"``.  The folder is a flexpipe run folder, so a later run or study may replace
it.
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

from flexpipe._io import absolute, write_text_atomic

#: what the study writes (``summary.json["file_descriptions"]``)
DESCRIPTIONS = {
    "step_check.csv": "step-convergence table, one row per channel: the reference run's "
                      "fluctuation (std_reference), per coarse step the RMS difference from "
                      "the reference run (rms_diff, channel unit) and its ratio to the "
                      "fluctuation (rel_dynamic); unit, mean magnitude, floor and "
                      "relative_meaningful (0 where the fluctuation is below the floor and "
                      "rel_dynamic divides by numerical noise)",
    "summary.json": "the study: car, body, road, path, speed, step sizes, window t_from .. "
                    "t_end, CPU time per run, the same per-channel figures, state",
}


def run_step_check(car, *, out, road=None, path=None, speed: float, t_end: float,
                   body: str = "rigid", h: float | None = None, refinements=(2, 4),
                   t_from: float | None = None, cache: bool = True, prewarp: bool = True,
                   inertia_coupling: str = "auto", title: str = "", log=print,
                   progress: bool = True, report=None, f_max: float | None = None,
                   driver=None, threads: int | str = 1):
    """Step-convergence study of one run into the run folder ``out`` (see module notes).

    Parameters
    ----------
    car : Car or path
    out : str or Path
        Output folder: absent, empty or a previous flexpipe run (or study).
    road, path, speed, t_end, body, h, cache, prewarp, inertia_coupling, f_max, driver, threads
        As for :func:`~flexpipe.vehicle.simulation.simulate` (speed in m/s).
    refinements, t_from
        As for :func:`~flexpipe.vehicle.convergence.check_step` (``t_from`` default
        :data:`~flexpipe.vehicle.convergence.DEFAULT_T_FROM`).
    title : str
        One-line description for the summary.
    log : callable
        Progress lines (one per run, the folder written).
    progress : bool
        Progress bar of each run.
    report : callable, optional
        Receives the study's table (:meth:`StepCheck.table`) when it completes, before
        the folder is written (``flexpipe run --check-step`` prints it, also with ``-q``).

    Returns
    -------
    (dict, StepCheck or None)
        The summary written and the study; a study whose run stopped early returns its
        summary (status -1, written to ``OUT.failed``) and None.

    Raises
    ------
    InputError
        A bad argument or output folder, before anything is written; or a failure of the
        study (its summary is then in ``OUT.failed``).
    """
    from flexpipe._io import check_run_folder, commit_directory, failed_folder, stage_directory
    from flexpipe.scenarios.runner import _kept, _remove_stale_failure, _write_failure
    from flexpipe.vehicle.convergence import (
        DEFAULT_T_FROM,
        StoppedEarly,
        check_step,
        check_step_inputs,
    )
    from flexpipe.vehicle.run_inputs import as_car, speed_summary

    t_from = DEFAULT_T_FROM if t_from is None else t_from
    car = as_car(car)
    kw = {"road": road, "path": path, "speed": speed, "t_end": t_end, "body": body,
          "prewarp": prewarp, "inertia_coupling": inertia_coupling, "threads": threads}
    if f_max is not None:
        kw["f_max"] = f_max
    if driver is not None:
        kw["driver"] = driver
    steps = check_step_inputs(car, h=h, refinements=refinements, t_from=t_from, **kw)
    out = check_run_folder(out)  # after the arguments: their errors come first
    stage = stage_directory(out)
    base = {"scenario": "check_step", "title": title, "car": car.name,
            "car_file": absolute(car.file), "body": body,
            "road": _source(road), "path": _source(path),
            **speed_summary(speed), "time_step_s": steps[0]}
    t0 = time.perf_counter()
    try:
        log(f"step convergence of {car.name}, {body} body, {title}: h = "
            + ", ".join(f"{s:g}" for s in steps) + " s")
        chk = check_step(car, h=steps[0], refinements=refinements, t_from=t_from,
                         progress=progress, cache=cache, log=lambda m: log("      " + m), **kw)
        write_text_atomic(stage / "step_check.csv", chk.csv_text())
    except StoppedEarly as exc:  # like a run that stops early: status -1, out unchanged
        summary = {**base, "status": -1, "state": "stopped early",
                   "message": " ".join(str(exc).split()),
                   "completed_runs": {f"h = {r.info['h']:g} s": r.message for r in exc.runs},
                   "files": ["summary.json"],
                   "total_wall_time_s": round(time.perf_counter() - t0, 2)}
        write_text_atomic(stage / "summary.json", json.dumps(summary, indent=2) + "\n")
        failed = commit_directory(stage, failed_folder(out))
        log(f"stopped early; {out} {_kept(out)}; this study's files are in {failed}/")
        return summary, None
    except BaseException as exc:
        _write_failure(stage, base, {}, [], exc, bodies=(body,), t0=t0)
        failed = commit_directory(stage, failed_folder(out))
        exc.add_note(f"{out} {_kept(out)}; this study's summary.json is in {failed}")
        raise
    summary = {**base, "status": 0, "state": "completed",
               "message": f"runs at h = {', '.join(f'{s:g}' for s in steps)} s reached "
                          f"t_end = {t_end:g} s",
               **chk.to_dict(),
               "files": sorted(DESCRIPTIONS), "file_descriptions": dict(DESCRIPTIONS),
               "total_wall_time_s": round(time.perf_counter() - t0, 2)}
    write_text_atomic(stage / "summary.json", json.dumps(summary, indent=2) + "\n")
    if report is not None:
        report(chk.table())
    commit_directory(stage, out)
    _remove_stale_failure(failed_folder(out))
    log(f"wrote {Path(out)}/: {', '.join(summary['files'])}")
    return summary, chk


def _source(value) -> str | None:
    """How summary.json names a road or path: a file by its absolute path (found from any
    working folder, like ``car_file``), anything else (a name, a road object) as text."""
    if value is None:
        return None
    if isinstance(value, str | os.PathLike) and Path(value).is_file():
        return absolute(value)
    return str(value)
