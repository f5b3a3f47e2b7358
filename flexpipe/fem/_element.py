"""Shared helpers of the element families.

Every family module (``tet4``, ``tet10``, ``hex8``, ``shell_tri3``, ``shell_quad4``,
``beam3d``) exposes

``TYPE`` : str
    meshio cell type it handles.
``DOFS_PER_NODE`` : int
    3 for solids, 6 for shells and beams.
``matrices(X, *, E, nu, rho, **props) -> (Ke, Me)``
    ``X`` (ne, nn, 3) node coordinates; ``E, nu, rho`` (ne,) arrays; ``props`` holds
    ``thickness`` (ne,) for shells and ``A, Iy, Iz, J`` (ne,), ``orientation`` (ne, 3)
    for beams.  Returns element stiffness and mass (ne, nd, nd) with element DOF
    ordered node-major (node a, component c -> a * DOFS_PER_NODE + c).

Optionally ``SYMMETRIC = True`` promises element matrices that are symmetric bit for bit;
the assembler then skips its own ``(Ke + Ke^T) / 2`` (the assembled matrices are exactly
symmetric either way).

A family raises :class:`BadElements` for inverted or degenerate elements; the assembler
turns it into a :class:`~flexpipe.errors.MeshError` naming the element ids.
"""

from __future__ import annotations

import numpy as np


class BadElements(Exception):
    """Raised by an element family: ``index`` are positions in the batch passed in."""

    def __init__(self, index, reason: str):
        super().__init__(reason)
        self.index = np.atleast_1d(np.asarray(index, dtype=np.int64))
        self.reason = reason


def isotropic_D(E: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """3D isotropic elasticity matrices (ne, 6, 6), Voigt order xx, yy, zz, yz, xz, xy
    (engineering shear strains)."""
    E = np.asarray(E, dtype=float)
    nu = np.asarray(nu, dtype=float)
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    D = np.zeros(E.shape + (6, 6))
    D[..., :3, :3] = lam[..., None, None]
    D[..., [0, 1, 2], [0, 1, 2]] += 2 * mu[..., None]
    D[..., [3, 4, 5], [3, 4, 5]] = mu[..., None]
    return D
