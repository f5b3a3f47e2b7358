"""Two-node 3D Euler-Bernoulli beam (line cells), 6 DOF per node.

Local axes (MSC Nastran CBAR convention): ``x`` from node 1 to node 2; the orientation
vector ``v`` lies in the local x-y plane, ``z = x cross v``, ``y = z cross x``.  Without
a vector ``v`` is global z, or global y for a beam (nearly) parallel to z.  ``Iz``
resists bending in the local x-y plane (deflection ``v``), ``Iy`` bending in the x-z
plane (deflection ``w``).

Stiffness: exact Euler-Bernoulli (no shear deformation; the section carries no shear
area), axial ``EA``, Saint-Venant torsion ``GJ``.  Mass: consistent - linear for axial
(``rho A``) and torsion (polar mass moment ``rho (Iy + Iz)``), cubic Hermite for bending
(no rotary inertia of bending).  Vectorized over the batch.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem._element import BadElements

TYPE = "line"
DOFS_PER_NODE = 6


def _frames(X, orientation):
    d = X[:, 1] - X[:, 0]
    L = np.linalg.norm(d, axis=1)
    scale = np.abs(X).reshape(len(X), -1).max(axis=1)
    bad = ~(L > 1e-12 * np.maximum(scale, 1e-300))
    if bad.any():
        raise BadElements(np.flatnonzero(bad), "of zero length (coincident end nodes)")
    ex = d / L[:, None]
    v = np.array(orientation, dtype=float, copy=True).reshape(len(X), 3)
    missing = ~np.isfinite(v).all(axis=1)
    if missing.any():
        vz = np.broadcast_to([0.0, 0.0, 1.0], (int(missing.sum()), 3)).copy()
        along_z = np.linalg.norm(np.cross(ex[missing], vz), axis=1) < 1e-3
        vz[along_z] = [0.0, 1.0, 0.0]
        v[missing] = vz
    ez = np.cross(ex, v)
    nz = np.linalg.norm(ez, axis=1)
    vn = np.linalg.norm(v, axis=1)
    bad = ~(nz > 1e-8 * vn)
    if bad.any():
        raise BadElements(np.flatnonzero(bad),
                          "given an orientation vector parallel to the beam axis (or zero); "
                          "give one in the local x-y plane")
    ez /= nz[:, None]
    ey = np.cross(ez, ex)
    return np.stack([ex, ey, ez], axis=1), L


def _hermite(L, EI):
    """Bending stiffness (ne, 4, 4) on ``v1, theta_z1, v2, theta_z2``."""
    one = np.ones_like(L)
    k = np.stack([
        [12 * one, 6 * L, -12 * one, 6 * L],
        [6 * L, 4 * L**2, -6 * L, 2 * L**2],
        [-12 * one, -6 * L, 12 * one, -6 * L],
        [6 * L, 2 * L**2, -6 * L, 4 * L**2],
    ]).transpose(2, 0, 1) * (EI / L**3)[:, None, None]
    return k


def _hermite_mass(L, m):
    """Consistent bending mass (ne, 4, 4) of mass per length ``m``."""
    one = np.ones_like(L)
    return np.stack([
        [156 * one, 22 * L, 54 * one, -13 * L],
        [22 * L, 4 * L**2, 13 * L, -3 * L**2],
        [54 * one, 13 * L, 156 * one, -22 * L],
        [-13 * L, -3 * L**2, -22 * L, 4 * L**2],
    ]).transpose(2, 0, 1) * (m * L / 420)[:, None, None]


def _place(out, block, dofs, sign=None):
    idx = np.asarray(dofs)
    if sign is not None:
        block = block * np.outer(sign, sign)[None]
    out[:, idx[:, None], idx] += block


def matrices(X, *, E, nu, rho, A, Iy, Iz, J, orientation=None, **_):
    """Stiffness and consistent mass of 3D beams, see :mod:`flexpipe.fem._element`."""
    X = np.asarray(X, dtype=float)
    ne = len(X)
    E, nu, rho, A, Iy, Iz, J = (np.broadcast_to(np.asarray(a, dtype=float), (ne,))
                                for a in (E, nu, rho, A, Iy, Iz, J))
    if orientation is None:
        orientation = np.full((ne, 3), np.nan)
    R, L = _frames(X, orientation)
    G = E / (2 * (1 + nu))
    bar = np.array([[1.0, -1.0], [-1.0, 1.0]])
    lin = np.array([[2.0, 1.0], [1.0, 2.0]]) / 6
    K = np.zeros((ne, 12, 12))
    M = np.zeros((ne, 12, 12))
    _place(K, (E * A / L)[:, None, None] * bar, [0, 6])
    _place(K, (G * J / L)[:, None, None] * bar, [3, 9])
    _place(M, (rho * A * L)[:, None, None] * lin, [0, 6])
    _place(M, (rho * (Iy + Iz) * L)[:, None, None] * lin, [3, 9])
    # x-y plane: v, theta_z = dv/dx ; x-z plane: w, theta_y = -dw/dx
    _place(K, _hermite(L, E * Iz), [1, 5, 7, 11])
    _place(K, _hermite(L, E * Iy), [2, 4, 8, 10], sign=[1, -1, 1, -1])
    m_b = _hermite_mass(L, rho * A)
    _place(M, m_b, [1, 5, 7, 11])
    _place(M, m_b, [2, 4, 8, 10], sign=[1, -1, 1, -1])
    K5 = K.reshape(ne, 4, 3, 4, 3)
    M5 = M.reshape(ne, 4, 3, 4, 3)
    Kg = np.einsum("eji,eajbl,elk->eaibk", R, K5, R, optimize=True).reshape(ne, 12, 12)
    Mg = np.einsum("eji,eajbl,elk->eaibk", R, M5, R, optimize=True).reshape(ne, 12, 12)
    return Kg, Mg
