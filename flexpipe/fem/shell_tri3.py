"""Three-node flat shell (tri3): CST membrane + DKT Kirchhoff plate.

* **Membrane** - constant strain triangle (linear ``u, v``).
* **Bending** - Discrete Kirchhoff Triangle (Batoz, Bathe & Ho 1980): the section
  rotations are quadratic over the six-node triangle; at the corners they equal the
  nodal rotations, at the mid-sides the Kirchhoff condition holds discretely (tangential
  rotation = slope of the cubic edge deflection, normal rotation linear along the edge).
  The curvatures are linear, so three mid-side points integrate the stiffness exactly.
  Thin-plate (no transverse shear) element.
* **Mass** - linear (lumped-consistent) interpolation of translations and rotations,
  translational ``rho t`` and rotary ``rho t^3 / 12``.
* **Drilling** - see :mod:`flexpipe.fem._shell`.

All operations are vectorized over the batch of elements.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _shell

TYPE = "triangle"
DOFS_PER_NODE = 6

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


def _batch(R, xy, h, E, nu, rho, t):
    """Global (K, M) of elements whose geometry has been checked."""
    x, y = xy[..., 0], xy[..., 1]
    # b_i = y_j - y_k, c_i = x_k - x_j (i, j, k cyclic); grad L_i = (b_i, c_i) / (2 area)
    b = np.roll(y, -1, axis=1) - np.roll(y, -2, axis=1)
    c = np.roll(x, -2, axis=1) - np.roll(x, -1, axis=1)
    two_area = b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0]
    area = 0.5 * two_area
    gradL = np.stack([b, c], axis=-1) / two_area[:, None, None]      # (ne, 3, 2)
    G = E / (2 * (1 + nu))
    # membrane (CST)
    Bm = _shell.membrane_B(gradL)
    Km = np.einsum("eji,ejk,ekl->eil", Bm, _shell.plane_stress(E, nu, t), Bm,
                   optimize=True) * area[:, None, None]
    # bending (DKT): curvature of the quadratic rotation field at 3 mid-side points
    dN6 = np.einsum("gki,eic->egkc", _DT6, gradL)                    # (ne, 3, 6, 2)
    Bq = np.zeros((len(xy), 3, 3, 12))
    Bq[..., 0, 0::2] = dN6[..., 0]
    Bq[..., 1, 1::2] = dN6[..., 1]
    Bq[..., 2, 0::2] = dN6[..., 1]
    Bq[..., 2, 1::2] = dN6[..., 0]
    Bb = np.einsum("egik,ekj->egij", Bq, _dkt_map(xy))
    Db = _shell.bending_rigidity(E, nu, t)
    Kb = np.einsum("egji,ejk,egkl->eil", Bb, Db, Bb, optimize=True) * (area / 3)[:, None, None]
    # drilling about the (constant) in-plane rotation omega = (v,x - u,y) / 2
    omega = np.zeros((len(xy), 6))
    omega[:, 0::2] = -0.5 * gradL[..., 1]
    omega[:, 1::2] = 0.5 * gradL[..., 0]
    k_drill = _shell.DRILL_ALPHA * G * t * area / 3
    K = _shell.combine(Km, Kb, omega, k_drill)
    NN = (area / 12)[:, None, None] * (np.ones((3, 3)) + np.eye(3))
    M = _shell.consistent_mass(NN, rho, t)
    return _shell.to_global(K, R, h), _shell.to_global(M, R, h, isotropic=True)


def matrices(X, *, E, nu, rho, thickness, **_):
    """Stiffness and lumped-consistent mass of tri3 shells (see :mod:`flexpipe.fem._element`)."""
    R, xy, h = _shell.local_frame(np.asarray(X, dtype=float))
    return _shell.in_sub_batches(_batch, (R, xy, h), E, nu, rho, thickness)
