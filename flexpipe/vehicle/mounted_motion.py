"""Motion of the powertrain and the subframes on their mounts: output channels.

A body on bushings (:class:`~flexpipe.vehicle.mounted.MountedBody`) moves from its design
position relative to the car body by ``u`` at its centre of mass and turns by ``theta``
(small rotations, body axes).  Each of its bushings then deflects by
``A^T (u + theta x r)`` and turns by ``A^T theta`` (``A`` the bushing's frame, ``r`` the
mount point from the centre of mass), which the run records (``bushing_<mount>_*``); this
module solves those equations for ``(u, theta)`` over all its mounts, in the least-squares
sense, after the run.  On a rigid body the equations agree and the solution is exact; on a
flexible body each mount moves with the body's local deformation and the solution is the
motion relative to the body at the mounts as a whole.

Channels ``<body>_x|y|z`` (m) and ``<body>_rx|ry|rz`` (rad), body axes, where ``<body>``
is ``powertrain`` or ``subframe_<name>``: the engine-motion figures of a mount layout.
"""

from __future__ import annotations

import numpy as np

from flexpipe.vehicle.sensor_rows import BUSHING_AXES
from flexpipe.vehicle.suspension.kinematics import skew

#: suffixes of a mounted body's motion channels
AXES = ("x", "y", "z", "rx", "ry", "rz")


def prefix(body) -> str:
    """Channel prefix of ``body``: ``powertrain`` or ``subframe_<name>``."""
    return body.name.replace(".", "_")


def bodies(car, bushings) -> list:
    """The car's powertrain and subframes whose every mount has a recorded bushing."""
    have = set(bushings)
    return [b for b in (car.powertrain, *car.subframes)
            if b is not None and set(b.mounts) <= have]


def names(car, bushings) -> list[str]:
    """Channel names of :func:`bodies`."""
    return [f"{prefix(b)}_{a}" for b in bodies(car, bushings) for a in AXES]


def solver(body) -> np.ndarray:
    """The (6, 6 n) least-squares map from the stacked bushing deflections of ``body``'s n
    mounts to its motion ``(u, theta)`` at the centre of mass."""
    rows = []
    for p, b in zip(body.points, body.bushings, strict=True):
        A = b.frame
        r = np.asarray(p, float) - body.center_of_mass
        rows.append(np.block([[A.T, -A.T @ skew(r)], [np.zeros((3, 3)), A.T]]))
    return np.linalg.pinv(np.vstack(rows))


def fill(ctrl) -> None:
    """Write the motion channels of every recorded row of the controller ``ctrl`` from its
    bushing deflection channels."""
    rec = ctrl.rec
    for b in bodies(ctrl.car, ctrl.bushings):
        cols = [rec.index[f"bushing_{m}_{a}"] for m in b.mounts for a in BUSHING_AXES]
        motion = rec.data[: rec.rows, cols] @ solver(b).T
        for k, a in enumerate(AXES):
            rec.data[: rec.rows, rec.index[f"{prefix(b)}_{a}"]] = motion[:, k]
