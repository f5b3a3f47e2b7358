"""Linear statics of a rigid body on bushings, for the powertrain and subframe tests.

Written here from the textbook (a rigid body on linear springs: ``K u = load`` with ``K``
the sum over the mounts of ``T_j^T K_j T_j``), apart from
:class:`flexpipe.vehicle.mounted.MountedBody`, whose data it reads.
"""

import numpy as np


def mount_forces(body, load: np.ndarray) -> np.ndarray:
    """Forces (n, 3) on the car body at the mounts (body axes) of ``body`` (a
    ``MountedBody``) held by its linear bushings under ``load`` = (force, moment about
    its centre of mass), 6 numbers."""
    K = np.zeros((6, 6))
    blocks = []
    for p, b in zip(body.points, body.bushings, strict=True):
        x, y, z = p - body.center_of_mass
        T = np.eye(6)
        T[:3, 3:] = -np.array([[0, -z, y], [z, 0, -x], [-y, x, 0]])
        Kj = np.zeros((6, 6))
        Kj[:3, :3] = b.frame @ np.diag(b.stiffness[:3]) @ b.frame.T
        Kj[3:, 3:] = b.frame @ np.diag(b.stiffness[3:]) @ b.frame.T
        K += T.T @ Kj @ T
        blocks.append((Kj @ T)[:3])
    u = np.linalg.solve(K, np.asarray(load, dtype=float))
    return np.array([B @ u for B in blocks])
