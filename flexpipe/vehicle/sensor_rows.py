"""Output rows made after a run from Exudyn's sensor records.

During a run :class:`flexpipe.vehicle.dynamics.CarController` records the first output row
(t = 0) from Python reads and leaves NaN in the rows after it where Exudyn's own sensors
store the values at every output step: the named points' accelerations and the body motion
(:mod:`flexpipe.exu.output_sensors`), and on a linkage car the per-mount and hub forces
(:mod:`flexpipe.exu.mount_sensors`).  :func:`fill` turns those records into the channels,
vectorized over the rows, once the run is over.  :class:`Recorder` holds the rows.
"""

from __future__ import annotations

import numpy as np

from flexpipe.vehicle.spec import CORNERS


class Recorder:
    """Preallocated channel arrays, filled row by row."""

    def __init__(self, names, n_rows: int):
        self.names = list(names)
        self.index = {n: i for i, n in enumerate(self.names)}
        self.data = np.full((n_rows, len(self.names)), np.nan)
        self.t = np.full(n_rows, np.nan)
        self.rows = 0

    def add(self, t: float, values: np.ndarray) -> None:
        if self.rows == len(self.t):  # more rows than planned (steps the solver cut): grow
            self.t = np.concatenate([self.t, np.full(max(len(self.t), 1), np.nan)])
            self.data = np.vstack([self.data, np.full((len(self.t) - len(self.data),
                                                       self.data.shape[1]), np.nan)])
        self.t[self.rows] = t
        self.data[self.rows] = values
        self.rows += 1

    def channels(self) -> dict:
        return {n: self.data[: self.rows, i].copy() for i, n in enumerate(self.names)}


#: suffixes of a bushing's deflection channels: its outer end's displacement (m) and
#: rotation (rad) relative to the mount, in the bushing's frame
BUSHING_AXES = ("dx", "dy", "dz", "rx", "ry", "rz")


def record_mounts(ctrl, row, k: int, R) -> None:
    """The mount forces (body axes, ``R`` the body's rotation) and bushing deflections of
    the row being recorded, from ``row[k]`` on: read now for the first row or a run
    without sensors, else NaN (filled after the run, :func:`fill`)."""
    if ctrl.rec.rows and ctrl.mount_sensors:
        row[k:] = np.nan
        return
    mf = ctrl.linkage.mount_forces()
    for m in ctrl.mounts:
        row[k:k + 3] = R.T @ mf[m]
        k += 3
    if ctrl.bushings:
        bd = ctrl.linkage.bushing_deflections()
        for m in ctrl.bushings:
            row[k:k + 6] = bd[m]
            k += 6


def fill(ctrl) -> None:
    """Fill the rows after the first of the controller ``ctrl``'s recorder (and its body
    motion) from the sensors of its run, then the mounted bodies' motion
    (:mod:`flexpipe.vehicle.mounted_motion`) of every row from the bushings'."""
    from flexpipe.vehicle import mounted_motion

    if ctrl.rec.rows >= 2:
        if ctrl.output_history is not None:
            _points_and_motion(ctrl)
        if ctrl.mounts and ctrl.mount_sensors:
            _mounts_and_hubs(ctrl)
    if ctrl.bushings:   # the powertrain's and subframes' motion, every row
        mounted_motion.fill(ctrl)


def _points_and_motion(ctrl) -> None:
    """``acc_<point>_<axis>`` (body axes) and the body motion rows."""
    rec = ctrl.rec
    rows = slice(1, rec.rows)
    hist = ctrl.output_history(rec.t[rows])
    if hist is None:
        return
    R = hist["R"]
    for p in ctrl.points:
        a = np.einsum("nji,nj->ni", R, hist["points"][p])  # global -> body axes
        for k, ax in enumerate("xyz"):
            rec.data[rows, rec.index[f"acc_{p}_{ax}"]] = a[:, k]
    if ctrl.body_motion is not None and len(ctrl.motion) == 1:
        ctrl.motion.extend(zip(hist["q"], hist["p"], R, strict=True))


def _mounts_and_hubs(ctrl) -> None:
    """``mount_<m>_<axis>`` (:meth:`flexpipe.exu.linkage.LinkageModel.mount_force_history`)
    and ``hub_<corner>_<axis>``: tyre force + weight - m a + links
    (:meth:`~flexpipe.exu.linkage.LinkageModel.hub_force_history`), body axes."""
    rec = ctrl.rec
    rows = slice(1, rec.rows)
    hist = ctrl.linkage.mount_force_history(rec.t[rows])
    for m in ctrl.mounts:
        for k, ax in enumerate("xyz"):
            rec.data[rows, rec.index[f"mount_{m}_{ax}"]] = hist[m][:, k]
    if ctrl.bushings:
        bd = ctrl.linkage.bushing_history(rec.t[rows])
        for m in ctrl.bushings:
            for k, ax in enumerate(BUSHING_AXES):
                rec.data[rows, rec.index[f"bushing_{m}_{ax}"]] = bd[m][:, k]
    hub_rows = ctrl._hub_rows
    if hub_rows:
        idx = np.array(sorted(hub_rows))
        F = np.array([hub_rows[i][0] for i in idx])
        R = np.array([hub_rows[i][1] for i in idx])
        hub_g = ctrl.linkage.hub_force_history(rec.t[idx], F)
        hub = np.einsum("rnji,rnj->rni", R, hub_g)
        for c, corner in enumerate(CORNERS):
            for k, ax in enumerate("xyz"):
                rec.data[idx, rec.index[f"hub_{corner}_{ax}"]] = hub[:, c, k]


__all__ = ["BUSHING_AXES", "fill", "record_mounts"]
