"""Quadratic tetrahedron (tet10), isoparametric, consistent mass.

Node order (meshio/VTK/Nastran CTETRA): vertices 0-3, then mid-edge nodes on the edges
0-1, 1-2, 0-2, 0-3, 1-3, 2-3.  With barycentric ``L`` the shape functions are
``L_i (2 L_i - 1)`` at vertices and ``4 L_i L_j`` on edges.

Integration: stiffness with the 4-point rule of degree 2 (exact for straight-edged
elements, whose strain is linear); mass with the 14-point rule of degree 5 (exact
``rho int N_a N_b`` for straight edges).  Vectorized over the batch.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _solid
from flexpipe.fem._element import BadElements
from flexpipe.fem.quadrature import tet_rule

TYPE = "tetra10"
DOFS_PER_NODE = 3

EDGES = np.array([[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]])
_DL = np.array([[-1.0, -1.0, -1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
_VERTS = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])


def shape(P: np.ndarray):
    """Shape functions N (np, 10) and derivatives dN/dxi (np, 10, 3) at points P (np, 3)."""
    P = np.atleast_2d(np.asarray(P, dtype=float))
    L = np.column_stack([1.0 - P.sum(axis=1), P])          # (np, 4)
    n = len(P)
    N = np.empty((n, 10))
    dNdL = np.zeros((n, 10, 4))
    N[:, :4] = L * (2 * L - 1)
    dNdL[:, np.arange(4), np.arange(4)] = 4 * L - 1
    p, q = EDGES[:, 0], EDGES[:, 1]
    N[:, 4:] = 4 * L[:, p] * L[:, q]
    dNdL[:, 4 + np.arange(6), p] = 4 * L[:, q]
    dNdL[:, 4 + np.arange(6), q] = 4 * L[:, p]
    return N, dNdL @ _DL


_PK, _WK = tet_rule(2)
_PM, _WM = tet_rule(5)
_NK, _DNK = shape(_PK)
_NM, _DNM = shape(_PM)
_DNV = shape(_VERTS)[1]


def _jacobian(dN, X):
    J = np.einsum("qai,eaj->eqij", dN, X)
    return _solid.det_inv3(J)


def matrices(X, *, E, nu, rho, **_):
    """Stiffness and consistent mass of tet10 elements, see :mod:`flexpipe.fem._element`."""
    X = np.asarray(X, dtype=float)
    detK, invK = _jacobian(_DNK, X)
    detM, _ = _jacobian(_DNM, X)
    detV, _ = _jacobian(_DNV, X)
    bad = _solid.bad_jacobian(np.hstack([detK, detM, detV]), X)
    if bad.any():
        raise BadElements(np.flatnonzero(bad),
                          "inverted, degenerate or too strongly curved (det J <= 0)")
    G = np.einsum("eqji,qai->eqaj", invK, _DNK)
    lam, mu = _solid.lame(E, nu)
    Ke = _solid.isotropic_stiffness(G, detK * _WK, lam, mu)
    Me = _solid.consistent_mass(_NM, detM * _WM, rho)
    return Ke, Me
