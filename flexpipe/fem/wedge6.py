"""Six-node pentahedron (wedge6, Nastran CPENTA): linear triangle x linear line.

Shape functions ``N = L_i (1 -+ zeta) / 2`` with triangle coordinates
``L = (1 - xi - eta, xi, eta)`` and ``zeta`` in [-1, 1]; node order: triangle G1-G3 at
``zeta = -1``, G4-G6 above them at ``zeta = +1`` (Nastran CPENTA, meshio/VTK wedge).
Isoparametric, so constant strain and rigid motion are reproduced exactly on any shape
(patch test).  Integration: 3-point (degree 2) triangle rule x 2-point Gauss for the
stiffness (exact on prismatic wedges), 6-point triangle x 3-point Gauss for the
consistent mass.  Like the plain hex8 it is stiff in bending; it is meant for the
transition layers and swept meshes of body decks.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _solid
from flexpipe.fem._element import BadElements
from flexpipe.fem.quadrature import gauss_legendre, triangle_rule

TYPE = "wedge"
DOFS_PER_NODE = 3
#: natural coordinates of the nodes (xi, eta, zeta)
XI = np.array([[0, 0, -1], [1, 0, -1], [0, 1, -1], [0, 0, 1], [1, 0, 1], [0, 1, 1]], float)


def shape(P: np.ndarray):
    """N (np, 6) and dN/dxi (np, 6, 3) at natural points P (np, 3)."""
    P = np.atleast_2d(np.asarray(P, dtype=float))
    xi, eta, zeta = P[:, 0], P[:, 1], P[:, 2]
    L = np.stack([1 - xi - eta, xi, eta], axis=1)
    dL = np.array([[-1.0, -1.0], [1.0, 0.0], [0.0, 1.0]])
    lo, hi = (1 - zeta)[:, None] / 2, (1 + zeta)[:, None] / 2
    N = np.hstack([L * lo, L * hi])
    dN = np.zeros((len(P), 6, 3))
    dN[:, :3, :2] = dL[None] * lo[:, :, None]
    dN[:, 3:, :2] = dL[None] * hi[:, :, None]
    dN[:, :3, 2] = -L / 2
    dN[:, 3:, 2] = L / 2
    return N, dN


def rule(tri_order: int, n_line: int):
    """Product rule on the wedge: points (nq, 3), weights (volume 1 = 1/2 x 2)."""
    pt, wt = triangle_rule(tri_order)
    pl, wl = gauss_legendre(n_line)
    P = np.array([[a, b, c] for a, b in pt for c in pl])
    W = np.array([u * v for u in wt for v in wl])
    return P, W


_PK, _WK = rule(2, 2)
_PM, _WM = rule(4, 3)
_NK, _DNK = shape(_PK)
_NM, _DNM = shape(_PM)
_DNC = shape(XI)[1]


def _jacobian(dN, X):
    return _solid.det_inv3(np.einsum("qai,eaj->eqij", dN, X))


def matrices(X, *, E, nu, rho, **_):
    """Stiffness and consistent mass of wedge6 elements, see :mod:`flexpipe.fem._element`."""
    X = np.asarray(X, dtype=float)
    detK, inv = _jacobian(_DNK, X)
    detC, _ = _jacobian(_DNC, X)
    bad = _solid.bad_jacobian(np.hstack([detK, detC]), X)
    if bad.any():
        raise BadElements(np.flatnonzero(bad), "inverted or badly distorted (det J <= 0 at "
                          "a corner or integration point; G4-G6 must lie on the side of "
                          "G1-G3 given by the right-hand rule)")
    G = np.einsum("eqji,qai->eqaj", inv, _DNK)
    lam, mu = _solid.lame(E, nu)
    Ke = _solid.isotropic_stiffness(G, detK * _WK, lam, mu)
    detM, _ = _jacobian(_DNM, X)
    Me = _solid.consistent_mass(_NM, detM * _WM, rho)
    return Ke, Me
