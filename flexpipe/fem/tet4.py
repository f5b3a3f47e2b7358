"""Linear tetrahedron (tet4): constant strain, exact one-point integration, consistent mass.

Shape functions ``N = (1 - xi - eta - zeta, xi, eta, zeta)``; the strain is constant, so
the one-point stiffness is exact.  The consistent mass is ``rho V / 20 (1 + delta_ab)``
per node pair and component.  Vectorized over the batch: no Python loop per element.
The element is stiff in bending (shear locking); prefer tet10 for accuracy.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _solid
from flexpipe.fem._element import BadElements

TYPE = "tetra"
DOFS_PER_NODE = 3
#: element matrices are symmetric bit for bit (the assembler need not symmetrize them)
SYMMETRIC = True

_DN = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
_M4 = (np.ones((4, 4)) + np.eye(4)) / 20.0


def strain_displacement(G: np.ndarray) -> np.ndarray:
    """Voigt B matrices (ne, 6, 3 * nn) from shape-function gradients G (ne, nn, 3).

    Voigt order xx, yy, zz, yz, xz, xy with engineering shear strains.
    """
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


def gradients(X: np.ndarray):
    """Volumes (ne,) and shape-function gradients (ne, 4, 3); raises BadElements."""
    X = np.asarray(X, dtype=float)
    J = X[:, 1:, :] - X[:, :1, :]                  # rows d x / d xi_i
    det, inv = _solid.det_inv3(J)
    bad = _solid.bad_jacobian(det[:, None], X)
    if bad.any():
        raise BadElements(np.flatnonzero(bad), "inverted or of zero volume (det J <= 0)")
    G = np.einsum("ai,eji->eaj", _DN, inv)
    return det / 6.0, G


def matrices(X, *, E, nu, rho, **_):
    """Stiffness and consistent mass of tet4 elements, see :mod:`flexpipe.fem._element`."""
    vol, G = gradients(X)
    lam, mu = _solid.lame(E, nu)
    Ke = _solid.isotropic_stiffness(G[:, None], vol[:, None], lam, mu)
    Me = _solid.expand3((np.asarray(rho) * vol)[:, None, None] * _M4)
    return Ke, Me
