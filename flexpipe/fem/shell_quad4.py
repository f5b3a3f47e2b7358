"""Four-node flat shell (quad4): QM6 membrane + MITC4 Reissner-Mindlin plate.

* **Membrane** - bilinear displacements enriched with Wilson's incompatible modes
  ``1 - xi^2``, ``1 - eta^2`` in Taylor's form (their derivatives use the centre
  Jacobian, so the constant-strain patch test is passed on distorted meshes); the four
  internal modes are condensed out element by element.  This removes the in-plane
  shear locking of the plain bilinear quad (exact pure in-plane bending of rectangles).
* **Bending** - bilinear ``w, theta_x, theta_y``; curvatures by 2x2 Gauss.  Transverse
  shear by the MITC4 assumed covariant strains (Bathe & Dvorkin 1985): ``gamma_xi``
  tied at the edge midpoints ``(0, +-1)``, ``gamma_eta`` at ``(+-1, 0)``, which removes
  shear locking for thin plates.  Shear correction factor 5/6.
* **Drilling, warping, mass** - see :mod:`flexpipe.fem._shell`.

All operations are vectorized over the batch of elements.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _shell
from flexpipe.fem._element import BadElements

TYPE = "quad"
DOFS_PER_NODE = 6

_XI = np.array([[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]])
_G = _XI / np.sqrt(3.0)  # 2x2 Gauss points, unit weights


def _shape(p):
    """Bilinear N (np, 4) and dN/dxi (np, 4, 2) at natural points p (np, 2)."""
    p = np.atleast_2d(p)
    a = 1 + p[:, None, 0] * _XI[None, :, 0]
    b = 1 + p[:, None, 1] * _XI[None, :, 1]
    N = 0.25 * a * b
    dN = np.stack([0.25 * _XI[None, :, 0] * b, 0.25 * _XI[None, :, 1] * a], axis=-1)
    return N, dN


_N_G, _DN_G = _shape(_G)
_N_C, _DN_C = _shape(np.zeros((1, 2)))
_DN_CORNER = _shape(_XI)[1]
# MITC4 tying points: gamma_xi at A (0, 1), C (0, -1); gamma_eta at B (1, 0), D (-1, 0)
_N_T, _DN_T = _shape(np.array([[0.0, 1.0], [0.0, -1.0], [1.0, 0.0], [-1.0, 0.0]]))


def _jacobian(dN, xy):
    """J[e, g, i, j] = d x_j / d xi_i, its determinant and inverse."""
    J = np.einsum("gai,eaj->egij", dN, xy)
    det = J[..., 0, 0] * J[..., 1, 1] - J[..., 0, 1] * J[..., 1, 0]
    inv = np.empty_like(J)
    inv[..., 0, 0] = J[..., 1, 1]
    inv[..., 1, 1] = J[..., 0, 0]
    inv[..., 0, 1] = -J[..., 0, 1]
    inv[..., 1, 0] = -J[..., 1, 0]
    return J, det, inv / det[..., None, None]


def _membrane(xy, C, detG, invG, dNdx):
    """QM6 membrane stiffness (ne, 8, 8) after condensing the incompatible modes."""
    B = _shell.membrane_B(dNdx)                              # (ne, 4, 3, 8)
    _, det0, inv0 = _jacobian(_DN_C, xy)
    # incompatible modes 1 - xi^2, 1 - eta^2: d/dxi = (-2 xi, 0), (0, -2 eta)
    dP = np.zeros((4, 2, 2))
    dP[:, 0, 0] = -2 * _G[:, 0]
    dP[:, 1, 1] = -2 * _G[:, 1]
    dPdx = np.einsum("eij,gaj->egai", inv0[:, 0], dP)
    dPdx = dPdx * (det0[:, 0][:, None] / detG)[:, :, None, None]
    Bi = _shell.membrane_B(dPdx)                             # (ne, 4, 3, 4)
    Ball = np.concatenate([B, Bi], axis=-1)
    Kall = _shell.btdb(Ball, C, detG)
    Kcc, Kci, Kii = Kall[:, :8, :8], Kall[:, :8, 8:], Kall[:, 8:, 8:]
    return Kcc - Kci @ np.linalg.solve(Kii, Kci.transpose(0, 2, 1))


def _plate(xy, Db, kGt, detG, invG, dNdx):
    """MITC4 bending + assumed transverse shear stiffness (ne, 12, 12)."""
    Bb = _shell.curvature_B(dNdx)                            # (ne, 4, 3, 12)
    Kb = _shell.btdb(Bb, Db, detG)
    # covariant shear strains at the tying points: gamma_i = w,xi_i + beta . x,xi_i
    xt = np.einsum("tai,eaj->etij", _DN_T, xy)               # (ne, 4, 2, 2) tangents
    ne = len(xy)
    row = np.zeros((ne, 4, 2, 12))                           # [tying point, direction]
    row[:, :, :, 0::3] = _DN_T.transpose(0, 2, 1)[None]
    # beta_x = theta_y (DOF 2), beta_y = -theta_x (DOF 1)
    row[:, :, :, 2::3] = xt[..., 0, None] * _N_T[None, :, None, :]
    row[:, :, :, 1::3] = -xt[..., 1, None] * _N_T[None, :, None, :]
    g_xi_A, g_xi_C = row[:, 0, 0], row[:, 1, 0]
    g_eta_B, g_eta_D = row[:, 2, 1], row[:, 3, 1]
    xi, eta = _G[:, 0], _G[:, 1]
    g_xi = (0.5 * (1 + eta))[None, :, None] * g_xi_A[:, None] + \
        (0.5 * (1 - eta))[None, :, None] * g_xi_C[:, None]
    g_eta = (0.5 * (1 + xi))[None, :, None] * g_eta_B[:, None] + \
        (0.5 * (1 - xi))[None, :, None] * g_eta_D[:, None]
    Bs = np.matmul(invG, np.stack([g_xi, g_eta], axis=2))
    Ks = _shell.btdb(Bs, np.broadcast_to(np.eye(2), (ne, 2, 2)), detG * kGt[:, None])
    return Kb + Ks


def _batch(R, xy, h, E, nu, rho, t):
    """Global (K, M) of elements whose geometry has been checked."""
    _, detG, invG = _jacobian(_DN_G, xy)
    dNdx = np.einsum("egij,gaj->egai", invG, _DN_G)
    G = E / (2 * (1 + nu))
    Km = _membrane(xy, _shell.plane_stress(E, nu, t), detG, invG, dNdx)
    Kp = _plate(xy, _shell.bending_rigidity(E, nu, t), _shell.SHEAR_FACTOR * G * t,
                detG, invG, dNdx)
    # drilling: in-plane rotation at the centre, omega = (v,x - u,y) / 2
    _, _, inv0 = _jacobian(_DN_C, xy)
    dN0 = np.einsum("eij,aj->eai", inv0[:, 0], _DN_C[0])
    omega = np.zeros((len(xy), 8))
    omega[:, 0::2] = -0.5 * dN0[..., 1]
    omega[:, 1::2] = 0.5 * dN0[..., 0]
    k_drill = _shell.DRILL_ALPHA * G * t * detG.sum(axis=1) / 4
    K = _shell.combine(Km, Kp, omega, k_drill)
    NN = np.einsum("ga,gb,eg->eab", _N_G, _N_G, detG)
    M = _shell.consistent_mass(NN, rho, t)
    return _shell.to_global(K, R, h), _shell.to_global(M, R, h, isotropic=True)


def matrices(X, *, E, nu, rho, thickness, **_):
    """Stiffness and consistent mass of quad4 shells, see :mod:`flexpipe.fem._element`."""
    X = np.asarray(X, dtype=float)
    R, xy, h = _shell.local_frame(X)
    # corners: det J > 0 everywhere iff the projected quad is convex and not inverted
    _, detC, _ = _jacobian(_DN_CORNER, xy)
    scale = np.einsum("eai,eai->e", xy, xy)
    bad = ~(detC.min(axis=1) > 1e-8 * scale)
    if bad.any():
        raise BadElements(np.flatnonzero(bad),
                          "inverted, non-convex or degenerate (det J <= 0 at a corner)")
    return _shell.in_sub_batches(_batch, (R, xy, h), E, nu, rho, thickness)
