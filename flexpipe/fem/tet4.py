"""Linear tetrahedron (tet4): constant strain, exact one-point integration, consistent mass."""

from __future__ import annotations

import numpy as np

from flexpipe.fem._element import BadElements, isotropic_D

TYPE = "tetra"
DOFS_PER_NODE = 3

_DN = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


def strain_displacement(G: np.ndarray) -> np.ndarray:
    """Voigt B matrices (ne, 6, 3 * nn) from shape-function gradients G (ne, nn, 3)."""
    ne, nn, _ = G.shape
    B = np.zeros((ne, 6, 3 * nn))
    gx, gy, gz = G[..., 0], G[..., 1], G[..., 2]
    B[:, 0, 0::3] = gx
    B[:, 1, 1::3] = gy
    B[:, 2, 2::3] = gz
    B[:, 3, 1::3] = gz
    B[:, 3, 2::3] = gy
    B[:, 4, 0::3] = gz
    B[:, 4, 2::3] = gx
    B[:, 5, 0::3] = gy
    B[:, 5, 1::3] = gx
    return B


def matrices(X, *, E, nu, rho, **_):
    """Stiffness and consistent mass of tet4 elements, see :mod:`flexpipe.fem._element`."""
    J = np.einsum("ai,eaj->eij", _DN, X)
    det = np.linalg.det(J)
    scale = np.abs(J).reshape(len(J), -1).max(axis=1) ** 3
    bad = ~(det > 1e-12 * scale)
    if bad.any():
        raise BadElements(np.flatnonzero(bad), "inverted or of zero volume (det J <= 0)")
    vol = det / 6.0
    G = np.einsum("ai,eji->eaj", _DN, np.linalg.inv(J))
    B = strain_displacement(G)
    D = isotropic_D(E, nu)
    Ke = np.einsum("eki,ekl,elj->eij", B, D, B, optimize=True) * vol[:, None, None]
    m = (rho * vol / 20.0)[:, None, None] * (np.ones((4, 4)) + np.eye(4))
    Me = np.einsum("eab,ij->eaibj", m, np.eye(3)).reshape(-1, 12, 12)
    return Ke, Me
