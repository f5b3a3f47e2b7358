"""Three-node flat shell (tri3): Allman membrane with drilling DOF + DKT Kirchhoff plate.

* **Membrane** - Allman's triangle (Allman 1984, in Cook's 1986 form): the quadratic
  displacement field of the six-node triangle whose mid-side values follow from the
  corner displacements and drilling rotations,
  ``u_mid = (u_i + u_j)/2 + (l_ij / 8)(theta_j - theta_i) n_ij``.  It passes the
  constant-strain patch test and is far less stiff in in-plane bending than the constant
  strain triangle (Scordelis-Lo roof 0.97 of the reference at 8 x 8 x 2 triangles, CST
  0.86).
* **Drilling penalty** - ``1/2 sum_a k_d (theta_z,a - omega_a)^2``, ``omega_a`` the
  in-plane rotation of the quadratic field at corner ``a``,
  ``k_d = DRILL_ALPHA G t area / 3``; removes the one spurious mode of the Allman field
  (equal drilling rotations, no displacement).  ``DRILL_ALPHA = 1e-3``: the Allman field
  cannot follow every quadratic field, so a larger penalty stiffens in-plane bending
  (a one-element-wide strip: +16 % frequency at 1e-3, +34 % at 1).
* **Bending** - Discrete Kirchhoff Triangle (Batoz, Bathe & Ho 1980): the section
  rotations are quadratic over the six-node triangle; at the corners they equal the
  nodal rotations, at the mid-sides the Kirchhoff condition holds discretely (tangential
  rotation = slope of the cubic edge deflection, normal rotation linear along the edge).
  The curvatures are linear, so three mid-side points integrate the stiffness exactly.
  Thin-plate (no transverse shear) element.
* **Mass** - linear (lumped-consistent) interpolation of translations and rotations,
  translational ``rho t`` and rotary ``rho t^3 / 12``.

All operations are vectorized over the batch of elements.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _shell

TYPE = "triangle"
DOFS_PER_NODE = 6
#: drilling penalty factor (fraction of ``G t area``)
DRILL_ALPHA = 1e-3

_EDGES = np.array([[0, 1], [1, 2], [2, 0]])  # mid-side nodes 3, 4, 5
# mid-side integration points (area coordinates), weight area / 3 each
_L_G = np.array([[0.5, 0.5, 0.0], [0.0, 0.5, 0.5], [0.5, 0.0, 0.5]])


def _dT6_dL(L):
    """d N_k / d L_i of the 6-node triangle at area coordinates L (np, 3) -> (np, 6, 3)."""
    npt = len(L)
    d = np.zeros((npt, 6, 3))
    for i in range(3):
        d[:, i, i] = 4 * L[:, i] - 1
    for k, (i, j) in enumerate(_EDGES):
        d[:, 3 + k, i] = 4 * L[:, j]
        d[:, 3 + k, j] = 4 * L[:, i]
    return d


_DT6 = _dT6_dL(_L_G)  # (3 points, 6 shape functions, 3 area coordinates)
_DT6_CORNERS = _dT6_dL(np.eye(3))
_CORNER_BETA = np.array([[0.0, 1.0], [-1.0, 0.0]])  # (beta_x, beta_y) = C (theta_x, theta_y)


def _dkt_map(xy):
    """Map A (ne, 12, 9): nodal ``w, theta_x, theta_y`` -> ``beta_x, beta_y`` at 6 nodes."""
    ne = len(xy)
    A = np.zeros((ne, 12, 9))
    for a in range(3):
        A[:, 2 * a:2 * a + 2, 3 * a + 1:3 * a + 3] = _CORNER_BETA
    for k, (i, j) in enumerate(_EDGES):
        d = xy[:, j] - xy[:, i]
        ell = np.linalg.norm(d, axis=1)
        s = d / ell[:, None]
        n = np.stack([s[:, 1], -s[:, 0]], axis=1)
        # beta_mid = -3/(2l) (w_j - w_i) s + P (beta_i + beta_j),  P = -ss/4 + nn/2
        P = -0.25 * np.einsum("ei,ej->eij", s, s) + 0.5 * np.einsum("ei,ej->eij", n, n)
        PC = P @ _CORNER_BETA
        r = slice(2 * (3 + k), 2 * (3 + k) + 2)
        A[:, r, 3 * i] = 1.5 * s / ell[:, None]
        A[:, r, 3 * j] = -1.5 * s / ell[:, None]
        A[:, r, 3 * i + 1:3 * i + 3] = PC
        A[:, r, 3 * j + 1:3 * j + 3] = PC
    return A


def _allman_map(xy):
    """Map (ne, 12, 9): corner ``u, v, theta_z`` -> ``u, v`` at the 6 nodes of the LST.

    Mid-side k of edge i-j: ``u_k = (u_i + u_j)/2 + (y_j - y_i)(theta_j - theta_i)/8``,
    ``v_k = (v_i + v_j)/2 - (x_j - x_i)(theta_j - theta_i)/8`` (Allman 1984, Cook 1986).
    """
    ne = len(xy)
    A = np.zeros((ne, 12, 9))
    for a in range(3):
        A[:, 2 * a, 3 * a] = A[:, 2 * a + 1, 3 * a + 1] = 1.0
    for k, (i, j) in enumerate(_EDGES):
        d = (xy[:, j] - xy[:, i]) / 8.0
        r = 2 * (3 + k)
        A[:, r, 3 * i] = A[:, r, 3 * j] = 0.5
        A[:, r + 1, 3 * i + 1] = A[:, r + 1, 3 * j + 1] = 0.5
        A[:, r, 3 * j + 2], A[:, r, 3 * i + 2] = d[:, 1], -d[:, 1]
        A[:, r + 1, 3 * j + 2], A[:, r + 1, 3 * i + 2] = -d[:, 0], d[:, 0]
    return A


def _batch(R, xy, h, E, nu, rho, t, bend, lam=None):
    """Global (K, M) of elements whose geometry has been checked."""
    x, y = xy[..., 0], xy[..., 1]
    # b_i = y_j - y_k, c_i = x_k - x_j (i, j, k cyclic); grad L_i = (b_i, c_i) / (2 area)
    b = np.roll(y, -1, axis=1) - np.roll(y, -2, axis=1)
    c = np.roll(x, -2, axis=1) - np.roll(x, -1, axis=1)
    two_area = b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0]
    area = 0.5 * two_area
    gradL = np.stack([b, c], axis=-1) / two_area[:, None, None]      # (ne, 3, 2)
    Cm, Db, Gt = _shell.rigidities(E, nu, t, bend, _shell.oriented(lam, R))
    # bending (DKT): curvature of the quadratic rotation field at 3 mid-side points
    dN6 = np.einsum("gki,eic->egkc", _DT6, gradL)                    # (ne, 3, 6, 2)
    Bq = np.zeros((len(xy), 3, 3, 12))
    Bq[..., 0, 0::2] = dN6[..., 0]
    Bq[..., 1, 1::2] = dN6[..., 1]
    Bq[..., 2, 0::2] = dN6[..., 1]
    Bq[..., 2, 1::2] = dN6[..., 0]
    Bb = np.einsum("egik,ekj->egij", Bq, _dkt_map(xy))
    Kb = _shell.btdb(Bb, Db, np.repeat(area[:, None] / 3, 3, 1))
    # membrane (Allman): LST field from corner u, v, theta_z, exact 3-point rule
    Amap = _allman_map(xy)
    Bm = _shell.membrane_B(dN6)                                      # (ne, 3, 3, 12)
    Km = _shell.btdb(Bm, Cm, np.repeat(area[:, None] / 3, 3, 1))
    Km = np.matmul(Amap.transpose(0, 2, 1), np.matmul(Km, Amap))
    # drilling penalty about the in-plane rotation of the quadratic field at the corners
    dNc = np.einsum("cki,eil->eckl", _DT6_CORNERS, gradL)           # (ne, corner, 6, 2)
    omega = np.zeros((len(xy), 3, 12))
    omega[..., 0::2] = -0.5 * dNc[..., 1]
    omega[..., 1::2] = 0.5 * dNc[..., 0]
    omega = np.matmul(omega, Amap)
    k_drill = DRILL_ALPHA * Cm[:, 2, 2] * area / 3
    K = _shell.combine(_shell.add_drilling(Km, omega, k_drill), Kb)
    NN = (area / 12)[:, None, None] * (np.ones((3, 3)) + np.eye(3))
    M = _shell.consistent_mass(NN, rho, t)
    return _shell.to_global(K, R, h), _shell.to_global(M, R, h, isotropic=True)


def matrices(X, *, E, nu, rho, thickness, bending=1.0, zoffset=None, laminate=None, **_):
    """Stiffness and lumped-consistent mass of tri3 shells (see :mod:`flexpipe.fem._element`)."""
    R, xy, h = _shell.local_frame(np.asarray(X, dtype=float))
    return _shell.in_sub_batches(_batch, (R, xy, _shell.offset_heights(h, zoffset)), E, nu,
                                 rho, thickness, bending=bending, laminate=laminate)
