"""The drive torque's reaction through the powertrain mounts.

A car driven through driveshafts reacts the drive torque in the engine, gearbox or motor,
which passes it to the body through its mounts (``[drive] reaction_mounts``).  A rigid
body feels only the couple, wherever it acts; a flexible body deforms under the mount
forces, so the forces go where the mounts sit, not to the body's reference frame.

:class:`CoupleSplit` turns a couple ``tau`` into forces ``f_j`` at the mount points
``p_j``: the least-norm forces with ``sum f_j = 0`` and ``sum (p_j - c) x f_j = tau``
(``c`` the points' centroid).  They are ``f_j = mu x r_j`` with ``r_j = p_j - c`` and
``J mu = tau``, ``J = sum (|r_j|^2 I - r_j r_j^T)``: the forces of a rigid powertrain on
mounts of equal isotropic stiffness, quasi-static (it turns by ``mu / k`` about the
mounts' centroid).  The statics take at least three mounts not on one line (two cannot
pass a couple about the line through them).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from flexpipe.errors import InputError

#: smallest principal value of J relative to its largest: below it the mounts are (nearly)
#: on one line and cannot pass every couple
MIN_SPREAD = 1e-6


@dataclass(frozen=True)
class CoupleSplit:
    """Least-norm forces at mount points statically equivalent to a couple.

    Parameters
    ----------
    names : tuple of str
        The mounts, in the order of ``points``.
    points : ndarray (n, 3)
        Mount points in body coordinates (m).
    """

    names: tuple
    points: np.ndarray

    def __post_init__(self):
        p = np.asarray(self.points, dtype=float)
        if p.ndim != 2 or p.shape[1] != 3 or len(p) != len(self.names):
            raise InputError(f"mount points must be ({len(self.names)}, 3), got "
                             f"{p.shape}", key="drive.reaction_mounts")
        object.__setattr__(self, "points", p)
        r = p - p.mean(axis=0)
        J = (r * r).sum() * np.eye(3) - r.T @ r
        lam = np.linalg.eigvalsh(J)
        if len(p) < 3 or lam[0] <= MIN_SPREAD * max(lam[2], 1e-300):
            raise InputError(
                f"the drive's reaction mounts {', '.join(self.names)} cannot pass a couple "
                "about every axis: give at least three mounts that are not on one line "
                f"(points {np.round(p, 4).tolist()} m)", key="drive.reaction_mounts")
        object.__setattr__(self, "_r", r)
        object.__setattr__(self, "_Jinv", np.linalg.inv(J))

    @property
    def arms(self) -> np.ndarray:
        """Mount points relative to their centroid (n, 3), body coordinates."""
        return self._r

    def forces(self, tau: np.ndarray) -> np.ndarray:
        """Forces (n, 3) at the mounts whose resultant is zero and whose moment is ``tau``
        (all in one frame: body coordinates, or global with ``rotated``)."""
        mu = self._Jinv @ np.asarray(tau, dtype=float)
        return np.cross(mu, self._r)

    def rotated(self, R: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """Global forces (n, 3) for a global couple ``tau`` on a body turned by ``R``
        (body to global)."""
        return self.forces(R.T @ np.asarray(tau, dtype=float)) @ R.T


def read_reaction_mounts(dt, drive, body, suspension):
    """``drive`` (a :class:`~flexpipe.vehicle.spec.DriveSpec`) with ``[drive]
    reaction_mounts`` read from the table ``dt`` and checked: unique names of
    ``[body.mounts]`` tables with a ``point_m`` that are no suspension mounts, at least
    three not on one line, on a linkage car whose drive reacts on the body."""
    from flexpipe.vehicle.mounted import mount_names, mount_points

    key = "reaction_mounts"
    names = mount_names(dt, key)
    if drive.reaction != "body":
        raise dt.error(key, f"drive_reaction = {drive.reaction!r} reacts the drive torque on "
                            "the knuckles (in-wheel motors): powertrain mounts need "
                            "drive_reaction = \"body\" (or remove reaction_mounts)")
    if suspension is None:
        raise dt.error(key, "powertrain mounts need a linkage suspension car ([suspension.*], "
                            "whose body mounts are tied in [body.mounts]); this car has "
                            "prismatic corners: remove reaction_mounts")
    points = mount_points(dt, key, names, body, suspension)
    if len(names) < 3:
        raise dt.error(key, f"{len(names)} mount(s) cannot pass a couple about every axis: "
                            "give at least three, not on one line")
    try:
        split = CoupleSplit(tuple(names), points)
    except InputError as exc:  # the file and line of the key
        raise dt.error(key, exc.message) from None
    return replace(drive, reaction_mounts=split.names, reaction_points=split.points)
