"""A run's output folder as the durability tools read it back.

``make straight`` / :func:`flexpipe.scenarios.runner.run_pair` leave in ``OUT_DIR``:
``summary.json`` (car file, scenario), ``flexible.csv`` (channels, units in the header)
and ``motion_flexible.npz`` (:class:`~flexpipe.vehicle.result.BodyMotion` plus the body
file it refers to, the band it was reduced for and a strip of the road surface).
:func:`load_run` turns them into a :class:`RunData`.
"""

from __future__ import annotations

import json
import zipfile
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flexpipe.errors import InputError

MOTION_FILE = "motion_{body}.npz"


def read_channels(out, body: str = "flexible"):
    """``(t, channels)`` of a run's channel file: ``BODY.csv``, ``BODY.h5`` or ``BODY.mat``
    (read by :func:`flexpipe.vehicle.load_result`; a damaged file is an error naming it)."""
    from flexpipe.vehicle.export import load_result

    out = Path(out)
    for suffix in ("csv", "h5", "mat"):
        path = out / f"{body}.{suffix}"
        if path.is_file():
            try:
                r = load_result(path)
            except InputError:
                raise
            except (OSError, KeyError, ValueError, TypeError, AttributeError) as exc:
                raise InputError(_damaged(exc), file=path) from None
            return np.asarray(r.t), {k: np.asarray(v) for k, v in r.channels.items()}
    raise InputError(f"no {body}.csv, {body}.h5 or {body}.mat", file=out)


def _damaged(exc: BaseException) -> str:
    """The message for a run file that cannot be read (cut short or overwritten)."""
    text = " ".join(str(exc).split()) or type(exc).__name__
    return (f"cannot read the file ({text}): it is damaged or cut short; rerun the "
            "scenario to write it again")


def road_strip(road, x, y, *, width: float = 3.0, ds: float = 0.25):
    """Road surface heights on a strip along the driven track ``(x, y)`` (global).

    Returns ``(X, Y, Z)`` arrays (n_along, n_across) for a ``width``-wide strip.
    """
    x, y = np.asarray(x, float), np.asarray(y, float)
    s = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(x), np.diff(y)))])
    ss = np.arange(s[0] - 3.0, s[-1] + 3.0, ds)
    cx, cy = np.interp(ss, s, x), np.interp(ss, s, y)
    hx, hy = np.gradient(cx), np.gradient(cy)
    nrm = np.hypot(hx, hy)
    nrm[nrm == 0] = 1.0
    nx_, ny_ = -hy / nrm, hx / nrm
    off = np.linspace(-width / 2, width / 2, 13)
    X = cx[:, None] + off[None] * nx_[:, None]
    Y = cy[:, None] + off[None] * ny_[:, None]
    Z = np.asarray(road.height_xy(X.ravel(), Y.ravel()), dtype=float).reshape(X.shape)
    return X, Y, Z


@dataclass
class RunData:
    """What the durability tools need from one run folder."""

    out: Path
    summary: dict
    t: np.ndarray
    channels: dict
    motion: object
    body_file: Path
    band_hz: float | None
    road: tuple | None

    def car(self):
        """The car of the run (from ``summary.json``)."""
        from flexpipe.vehicle.spec import load_car

        return load_car(run_car_file(self.summary, self.out))

    def body(self, *, log=None):
        """The reduced body of the run: its cached file, or reduced again with stresses."""
        from flexpipe.flexbody import load_body

        if self.body_file.is_file():
            body = load_body(self.body_file)
            if body.stress is not None:
                return body
        if self.band_hz is None:
            raise InputError(f"body file {self.body_file} is missing and the run does not "
                             "say its band; rerun the scenario", file=self.out)
        from flexpipe.vehicle.linkage_setup import reduce_car_body

        body, _ = reduce_car_body(self.car(), f_max=self.band_hz, log=log)
        return body


def run_car_file(summary: dict, out) -> Path:
    """The car file a run used: ``summary.json``'s ``car_file``, an absolute path (runs
    of earlier flexpipe versions stored it as given, relative to the folder the run was
    started in; such a path is looked up from the current folder).

    Raises
    ------
    InputError
        The summary names no car file, or the file is no longer there (moved, deleted,
        or a relative path run from another folder), naming the path and the remedy.
    """
    where = Path(out) / "summary.json"
    raw = summary.get("car_file")
    if not raw or raw == "None":
        raise InputError("names no car file ('car_file'): rerun the scenario", file=where,
                         key="car_file")
    path = Path(raw)
    if not path.is_file():
        if path.is_absolute():
            msg = (f"the run's car file {raw} does not exist: it has been moved or deleted "
                   "since the run; put it back or set 'car_file' to its new absolute path")
        else:
            msg = (f"the run's car file {raw} is not in the current folder {Path.cwd()}: the "
                   "path is relative (runs of earlier flexpipe versions stored it so); run "
                   "this command in the folder the run was started in, or set 'car_file' "
                   "to the file's absolute path")
        raise InputError(msg, file=where, key="car_file")
    return path


def _why_no_motion(summary: dict, body: str) -> str:
    """Why a run folder has no recorded motion of ``body``, and what to do."""
    if summary.get("scenario") == "check_step":
        return ("the folder holds a step-convergence study (flexpipe run --check-step: "
                "step_check.csv), not a run; stress recovery and animation need the folder "
                "of a run (flexpipe run without --check-step)")
    if summary.get("state") in ("error", "interrupted"):
        return (f"the run ended with state '{summary['state']}' before writing it "
                f"({summary.get('message', 'see summary.json')}): rerun the scenario")
    if summary.get("state") == "stopped early":
        why = (summary.get("messages") or {}).get(body) or summary.get("durability") or \
            "see summary.json"
        return (f"the {body} run stopped early ({why}), so it has no load history to "
                "recover stresses from or animate: fix what the message names and rerun")
    ran = list(summary.get("messages") or {})
    if ran and body not in ran:
        return (f"the run simulated only the {' and '.join(ran)} body model"
                f"{'s' if len(ran) > 1 else ''} (summary.json 'messages'); stress recovery "
                f"and animation need the {body} body's motion: rerun with --body {body} "
                f"(or --body rigid,{body}, the default of flexpipe run)")
    return (f"the run has no recorded {body} body motion (rerun the scenario with this "
            "flexpipe version)")


def load_run(out, *, body: str = "flexible") -> RunData:
    """Read a run folder (see module docstring)."""
    from flexpipe.vehicle.result import BodyMotion

    out = Path(out)
    if not out.is_dir():
        raise InputError("run folder not found (make straight writes out/straight)", file=out)
    summary_path = out / "summary.json"
    if not summary_path.is_file():
        raise InputError("no summary.json: not a flexpipe run folder", file=out)
    try:
        summary = json.loads(summary_path.read_text(encoding="utf-8"))
    except json.JSONDecodeError as exc:
        raise InputError(f"not valid JSON ({exc.msg} at line {exc.lineno}, column "
                         f"{exc.colno}): the run folder is damaged; rerun the scenario",
                         file=summary_path, line=exc.lineno) from None
    except UnicodeDecodeError as exc:
        raise InputError(_damaged(exc), file=summary_path) from None
    if not isinstance(summary, dict):
        raise InputError("not a flexpipe run summary (a JSON object was expected)",
                         file=summary_path)
    mpath = out / MOTION_FILE.format(body=body)
    if not mpath.is_file():
        raise InputError(f"no {mpath.name}: {_why_no_motion(summary, body)}", file=out)
    run_car_file(summary, out)  # before any work: stress and animate need the car
    try:
        motion = BodyMotion.load(mpath)
        with np.load(mpath, allow_pickle=False) as d:
            body_file = Path(str(d["body_file"])) if "body_file" in d.files else Path()
            band = float(d["band_hz"]) if "band_hz" in d.files else None
            road = (d["road_x"], d["road_y"], d["road_z"]) if "road_x" in d.files else None
    except (OSError, EOFError, KeyError, ValueError, zipfile.BadZipFile) as exc:
        raise InputError(_damaged(exc), file=mpath) from None
    t, ch = read_channels(out, body)
    if len(t) != len(motion.t):
        raise InputError(f"{body}.csv has {len(t)} rows but {mpath.name} {len(motion.t)} "
                         "steps: files from different runs", file=out)
    return RunData(out, summary, t, ch, motion, body_file, band, road)
