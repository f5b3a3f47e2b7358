"""Two-node 3D beam (line cells), 6 DOF per node: Euler-Bernoulli or Timoshenko.

Local axes (MSC Nastran CBAR convention): ``x`` from node 1 to node 2; the orientation
vector ``v`` lies in the local x-y plane, ``z = x cross v``, ``y = z cross x``.  Without
a vector ``v`` is global z, or global y for a beam (nearly) parallel to z.  ``Iz``
resists bending in the local x-y plane (deflection ``v``), ``Iy`` bending in the x-z
plane (deflection ``w``).

Stiffness: axial ``EA``, Saint-Venant torsion ``GJ`` and bending.  Without shear area
factors (``k1 = k2 = 0``, the default, as a Nastran PBAR with blank K1/K2) bending is
exact Euler-Bernoulli; with factors it is the exact two-node Timoshenko beam as in
Nastran's CBAR/CBEAM (shear stiffness ``k1 G A`` in plane 1 = x-y with ``Iz``,
``k2 G A`` in plane 2 = x-z with ``Iy``): ``phi = 12 E I / (k G A L^2)``, Przemieniecki
(1968) stiffness.  Mass: consistent - linear for axial (``rho A``) and torsion (polar
mass moment ``rho (Iy + Iz)``); bending by cubic Hermite functions (Euler-Bernoulli, no
rotary inertia) or, for Timoshenko beams, Przemieniecki's consistent translational and
rotary-inertia (``rho I``) matrices with the same ``phi``.  ``theta`` rotates the section
axes about the beam axis (principal axes of a section with ``I12 != 0``): ``y' = cos y +
sin z``.  Vectorized over the batch.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem._element import BadElements

TYPE = "line"
DOFS_PER_NODE = 6


def _frames(X, orientation, theta=None):
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
    if theta is not None and np.any(theta):
        c, s = np.cos(theta)[:, None], np.sin(theta)[:, None]
        ey, ez = c * ey + s * ez, -s * ey + c * ez
    return np.stack([ex, ey, ez], axis=1), L


def _hermite(L, EI, phi=None):
    """Bending stiffness (ne, 4, 4) on ``v1, theta_z1, v2, theta_z2`` (Timoshenko: phi)."""
    one = np.ones_like(L)
    p = np.zeros_like(L) if phi is None else phi
    k = np.stack([
        [12 * one, 6 * L, -12 * one, 6 * L],
        [6 * L, (4 + p) * L**2, -6 * L, (2 - p) * L**2],
        [-12 * one, -6 * L, 12 * one, -6 * L],
        [6 * L, (2 - p) * L**2, -6 * L, (4 + p) * L**2],
    ]).transpose(2, 0, 1) * (EI / ((1 + p) * L**3))[:, None, None]
    return k


def _timoshenko_mass(L, m, rI, p):
    """Consistent bending mass (ne, 4, 4): translation ``m`` per length, rotary ``rI``."""
    one = np.ones_like(L)
    a = np.stack([
        [13 / 35 + 7 * p / 10 + p**2 / 3, (11 / 210 + 11 * p / 120 + p**2 / 24) * L,
         9 / 70 + 3 * p / 10 + p**2 / 6, -(13 / 420 + 3 * p / 40 + p**2 / 24) * L],
        [0 * one, (1 / 105 + p / 60 + p**2 / 120) * L**2,
         (13 / 420 + 3 * p / 40 + p**2 / 24) * L, -(1 / 140 + p / 60 + p**2 / 120) * L**2],
        [0 * one, 0 * one, 13 / 35 + 7 * p / 10 + p**2 / 3,
         -(11 / 210 + 11 * p / 120 + p**2 / 24) * L],
        [0 * one, 0 * one, 0 * one, (1 / 105 + p / 60 + p**2 / 120) * L**2],
    ]).transpose(2, 0, 1) * (m * L / (1 + p) ** 2)[:, None, None]
    q = (1 / 10 - p / 2) * L
    r = np.stack([
        [6 / 5 * one, q, -6 / 5 * one, q],
        [0 * one, (2 / 15 + p / 6 + p**2 / 3) * L**2, -q, (-1 / 30 - p / 6 + p**2 / 6) * L**2],
        [0 * one, 0 * one, 6 / 5 * one, -q],
        [0 * one, 0 * one, 0 * one, (2 / 15 + p / 6 + p**2 / 3) * L**2],
    ]).transpose(2, 0, 1) * (rI / ((1 + p) ** 2 * L))[:, None, None]
    out = a + r
    iu = np.triu_indices(4, 1)
    out[:, iu[1], iu[0]] = out[:, iu[0], iu[1]]
    return out


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


def _phi(E, I, k, G, A, L):
    """Shear parameter ``12 E I / (k G A L^2)`` (0 where ``k`` is 0: Euler-Bernoulli)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        p = 12 * E * I / (k * G * A * L**2)
    return np.where(k > 0, p, 0.0)


def _skew(w):
    S = np.zeros(w.shape[:-1] + (3, 3))
    S[..., 0, 1], S[..., 0, 2], S[..., 1, 2] = -w[..., 2], w[..., 1], -w[..., 0]
    S[..., 1, 0], S[..., 2, 0], S[..., 2, 1] = w[..., 2], -w[..., 1], w[..., 0]
    return S


def _offset(K, wa, wb):
    """``T^T K T`` for rigid end offsets: end motion ``u + theta x w`` of the node's."""
    ne = len(K)
    T = np.broadcast_to(np.eye(12), (ne, 12, 12)).copy()
    T[:, 0:3, 3:6] = -_skew(wa)
    T[:, 6:9, 9:12] = -_skew(wb)
    return np.matmul(T.transpose(0, 2, 1), np.matmul(K, T))


def _release(K, M, mask):
    """Condense released local DOF (pin flags) out of local K and M.

    ``mask`` (ne,) bit ``d`` set: local DOF ``d`` (0-5 end A, 6-11 end B) is released, i.e.
    an internal DOF of the element.  Static condensation ``T = [I; -Krr^-1 Krk]``:
    ``K <- T^T K T`` (exact) and ``M <- T^T M T`` (Guyan); released rows stay zero.
    """
    for m in np.unique(mask[mask > 0]):
        sel = np.flatnonzero(mask == m)
        r = np.array([d for d in range(12) if int(m) >> d & 1])
        k = np.setdiff1d(np.arange(12), r)
        Ks, Ms = K[sel], M[sel]
        Krr = Ks[:, r][:, :, r]
        Krk = Ks[:, r][:, :, k]
        try:
            G = -np.linalg.solve(Krr, Krk)                   # released = G @ kept
        except np.linalg.LinAlgError:
            raise BadElements(sel, "released (pin flags) in components without stiffness "
                              "(e.g. torsion with J = 0)") from None
        T = np.zeros((len(sel), 12, len(k)))
        T[:, k, np.arange(len(k))] = 1.0
        T[:, r, :] = G
        Kc = T.transpose(0, 2, 1) @ Ks @ T
        Mc = T.transpose(0, 2, 1) @ Ms @ T
        Kn, Mn = np.zeros_like(Ks), np.zeros_like(Ms)
        Kn[:, k[:, None], k] = 0.5 * (Kc + Kc.transpose(0, 2, 1))
        Mn[:, k[:, None], k] = 0.5 * (Mc + Mc.transpose(0, 2, 1))
        K[sel], M[sel] = Kn, Mn
    return K, M


def matrices(X, *, E, nu, rho, A, Iy, Iz, J, orientation=None, k1=0.0, k2=0.0, theta=0.0,
             offset_a=None, offset_b=None, release=None, **_):
    """Stiffness and consistent mass of 3D beams, see :mod:`flexpipe.fem._element`.

    ``offset_a``, ``offset_b`` (ne, 3): rigid offsets (Nastran CBAR WA, WB in basic) from
    the nodes to the beam ends; the beam lies between the offset ends.  ``release`` (ne,)
    bit masks of released end DOF in element axes (Nastran pin flags PA, PB), condensed
    out by :func:`_release`.
    """
    X = np.asarray(X, dtype=float)
    offs = offset_a is not None and offset_b is not None and (np.any(offset_a)
                                                              or np.any(offset_b))
    if offs:
        wa = np.asarray(offset_a, dtype=float).reshape(-1, 3)
        wb = np.asarray(offset_b, dtype=float).reshape(-1, 3)
        X = X + np.stack([wa, wb], axis=1)
    ne = len(X)
    E, nu, rho, A, Iy, Iz, J, k1, k2, theta = (
        np.broadcast_to(np.asarray(a, dtype=float), (ne,))
        for a in (E, nu, rho, A, Iy, Iz, J, k1, k2, theta))
    if orientation is None:
        orientation = np.full((ne, 3), np.nan)
    R, L = _frames(X, orientation, theta)
    G = E / (2 * (1 + nu))
    p1, p2 = _phi(E, Iz, k1, G, A, L), _phi(E, Iy, k2, G, A, L)
    bar = np.array([[1.0, -1.0], [-1.0, 1.0]])
    lin = np.array([[2.0, 1.0], [1.0, 2.0]]) / 6
    K = np.zeros((ne, 12, 12))
    M = np.zeros((ne, 12, 12))
    _place(K, (E * A / L)[:, None, None] * bar, [0, 6])
    _place(K, (G * J / L)[:, None, None] * bar, [3, 9])
    _place(M, (rho * A * L)[:, None, None] * lin, [0, 6])
    _place(M, (rho * (Iy + Iz) * L)[:, None, None] * lin, [3, 9])
    # x-y plane: v, theta_z = dv/dx ; x-z plane: w, theta_y = -dw/dx
    _place(K, _hermite(L, E * Iz, p1), [1, 5, 7, 11])
    _place(K, _hermite(L, E * Iy, p2), [2, 4, 8, 10], sign=[1, -1, 1, -1])
    eb = (k1 <= 0) & (k2 <= 0)
    m_b1 = _hermite_mass(L, rho * A)
    rod = (Iy == 0) & (Iz == 0)
    if rod.any():  # rods (CROD): linear translational mass, no rotational terms
        m_b1[rod] = 0.0
        lr = (rho * A * L)[rod] / 6
        m_b1[rod, 0, 0] = m_b1[rod, 2, 2] = 2 * lr
        m_b1[rod, 0, 2] = m_b1[rod, 2, 0] = lr
    m_b2 = m_b1.copy()
    if not eb.all():
        t = ~eb
        m_b1[t] = _timoshenko_mass(L[t], rho[t] * A[t], np.where(k1[t] > 0, rho[t] * Iz[t], 0),
                                   p1[t])
        m_b2[t] = _timoshenko_mass(L[t], rho[t] * A[t], np.where(k2[t] > 0, rho[t] * Iy[t], 0),
                                   p2[t])
    _place(M, m_b1, [1, 5, 7, 11])
    _place(M, m_b2, [2, 4, 8, 10], sign=[1, -1, 1, -1])
    if release is not None and np.any(release):
        K, M = _release(K, M, np.broadcast_to(np.asarray(release, dtype=np.int64), (ne,)))
    K5 = K.reshape(ne, 4, 3, 4, 3)
    M5 = M.reshape(ne, 4, 3, 4, 3)
    Kg = np.einsum("eji,eajbl,elk->eaibk", R, K5, R, optimize=True).reshape(ne, 12, 12)
    Mg = np.einsum("eji,eajbl,elk->eaibk", R, M5, R, optimize=True).reshape(ne, 12, 12)
    if offs:
        Kg, Mg = _offset(Kg, wa, wb), _offset(Mg, wa, wb)
    return Kg, Mg
