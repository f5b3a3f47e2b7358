"""Four-node flat shell (quad4): Allman-type membrane with drilling DOF + MITC4 plate.

* **Membrane** - Allman-type quadrilateral (Cook 1986): the 8-node serendipity field
  whose mid-side displacements follow from the corner displacements and drilling
  rotations, ``u_mid = (u_i + u_j)/2 + (l_ij / 8)(theta_j - theta_i) n_ij``; 3x3 Gauss.
  It reproduces pure in-plane bending of rectangles (no in-plane shear locking), passes
  the constant-strain patch test on distorted meshes, and gives the drilling rotation a
  true membrane stiffness, which keeps non-coplanar (twisted, folded) meshes from
  being over-flexible.
* **Drilling penalty** - ``1/2 sum_a k_d (theta_z,a - omega_a)^2`` with ``omega_a`` the
  in-plane rotation of the membrane field at corner ``a`` and
  ``k_d = DRILL_ALPHA G t area / 4``; it removes the one spurious mode of the Allman field
  (equal drilling rotations, no displacement) and vanishes for every field the element
  reproduces exactly.  ``DRILL_ALPHA = 0.1`` (MacNeal-Harder twisted beam within 0.2 %
  on the 12 x 2 mesh; 1e-3 left it 8 % too flexible).
* **Bending** - bilinear ``w, theta_x, theta_y``; curvatures by 2x2 Gauss.  Transverse
  shear by the MITC4 assumed covariant strains (Bathe & Dvorkin 1985): ``gamma_xi``
  tied at the edge midpoints ``(0, +-1)``, ``gamma_eta`` at ``(+-1, 0)``, which removes
  shear locking for thin plates.  Shear correction factor 5/6.
* **Warping, mass** - see :mod:`flexpipe.fem._shell`; consistent bilinear mass (2x2).

All operations are vectorized over the batch of elements.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _shell
from flexpipe.fem._element import BadElements

TYPE = "quad"
DOFS_PER_NODE = 6
#: drilling penalty factor (fraction of ``G t area``)
DRILL_ALPHA = 0.1

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
_DN_CORNER = _shape(_XI)[1]
# MITC4 tying points: gamma_xi at A (0, 1), C (0, -1); gamma_eta at B (1, 0), D (-1, 0)
_N_T, _DN_T = _shape(np.array([[0.0, 1.0], [0.0, -1.0], [1.0, 0.0], [-1.0, 0.0]]))


def _jacobian(dN, xy):
    """J[e, g, i, j] = d x_j / d xi_i, its determinant and inverse."""
    J = np.matmul(dN.transpose(0, 2, 1)[None], xy[:, None])
    det = J[..., 0, 0] * J[..., 1, 1] - J[..., 0, 1] * J[..., 1, 0]
    inv = np.empty_like(J)
    inv[..., 0, 0] = J[..., 1, 1]
    inv[..., 1, 1] = J[..., 0, 0]
    inv[..., 0, 1] = -J[..., 0, 1]
    inv[..., 1, 0] = -J[..., 1, 0]
    return J, det, inv / det[..., None, None]


_G3 = np.array([-np.sqrt(0.6), 0.0, np.sqrt(0.6)])
_W3 = np.array([5.0, 8.0, 5.0]) / 9.0
_P9 = np.array([[a, b] for a in _G3 for b in _G3])        # 3x3 Gauss points
_W9 = np.array([wa * wb for wa in _W3 for wb in _W3])
_MID = np.array([[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]])  # edges 0-1, 1-2, 2-3, 3-0
_EDGES = np.array([[0, 1], [1, 2], [2, 3], [3, 0]])


def _q8_gradients(p):
    """d N / d xi (np, 8, 2) of the 8-node serendipity quad at natural points p."""
    xi, eta = p[:, 0, None], p[:, 1, None]
    xc, yc = _XI[None, :, 0], _XI[None, :, 1]
    d = np.zeros((len(p), 8, 2))
    d[:, :4, 0] = 0.25 * xc * (1 + eta * yc) * (2 * xi * xc + eta * yc)
    d[:, :4, 1] = 0.25 * yc * (1 + xi * xc) * (xi * xc + 2 * eta * yc)
    xm, ym = _MID[None, :, 0], _MID[None, :, 1]
    along_xi = (xm == 0)[0]                               # mid-sides of edges 0-1, 2-3
    d[:, 4:, 0] = np.where(along_xi, -xi * (1 + eta * ym), 0.5 * xm * (1 - eta**2))
    d[:, 4:, 1] = np.where(along_xi, 0.5 * ym * (1 - xi**2), -eta * (1 + xi * xm))
    return d


_DQ8_G = _q8_gradients(_P9)
_DN_9 = _shape(_P9)[1]
_DQ8_CORNER = _q8_gradients(_XI)


def _allman_map(xy):
    """Map (ne, 16, 12): corner ``u, v, theta_z`` -> ``u, v`` at the 8 serendipity nodes."""
    ne = len(xy)
    A = np.zeros((ne, 16, 12))
    for a in range(4):
        A[:, 2 * a, 3 * a] = A[:, 2 * a + 1, 3 * a + 1] = 1.0
    for k, (i, j) in enumerate(_EDGES):
        d = (xy[:, j] - xy[:, i]) / 8.0
        r = 2 * (4 + k)
        A[:, r, 3 * i] = A[:, r, 3 * j] = 0.5
        A[:, r + 1, 3 * i + 1] = A[:, r + 1, 3 * j + 1] = 0.5
        A[:, r, 3 * j + 2], A[:, r, 3 * i + 2] = d[:, 1], -d[:, 1]
        A[:, r + 1, 3 * j + 2], A[:, r + 1, 3 * i + 2] = -d[:, 0], d[:, 0]
    return A


def _grad(inv, dN):
    """Cartesian gradients (ne, np, nn, 2) from inverse Jacobians and d N / d xi."""
    return np.matmul(dN[None], inv.transpose(0, 1, 3, 2))


def _membrane_allman(xy, C):
    """Allman-type quad membrane (ne, 12, 12) on ``u, v, theta_z`` and its centre rotation."""
    _, det9, inv9 = _jacobian(_DN_9, xy)
    dNdx = _grad(inv9, _DQ8_G)
    Amap = _allman_map(xy)
    K8 = _shell.btdb(_shell.membrane_B(dNdx), C, det9 * _W9)
    Km = np.matmul(Amap.transpose(0, 2, 1), np.matmul(K8, Amap))
    # in-plane rotation (v,x - u,y) / 2 of the field at the four corners
    _, _, invc = _jacobian(_DN_CORNER, xy)
    dNc = _grad(invc, _DQ8_CORNER)                            # (ne, corner, node, 2)
    omega = np.zeros((len(xy), 4, 16))
    omega[..., 0::2] = -0.5 * dNc[..., 1]
    omega[..., 1::2] = 0.5 * dNc[..., 0]
    return Km, np.matmul(omega, Amap)


def _plate(xy, Db, kGt, detG, invG, dNdx):
    """MITC4 bending + assumed transverse shear stiffness (ne, 12, 12)."""
    Bb = _shell.curvature_B(dNdx)                            # (ne, 4, 3, 12)
    Kb = _shell.btdb(Bb, Db, detG)
    # covariant shear strains at the tying points: gamma_i = w,xi_i + beta . x,xi_i
    xt, _, _ = _jacobian(_DN_T, xy)                          # (ne, 4, 2, 2) tangents
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


def _batch(R, xy, h, E, nu, rho, t, bend, lam=None):
    """Global (K, M) of elements whose geometry has been checked."""
    _, detG, invG = _jacobian(_DN_G, xy)
    dNdx = _grad(invG, _DN_G)
    Cm, Db, Gt = _shell.rigidities(E, nu, t, bend, _shell.oriented(lam, R))
    Kp = _plate(xy, Db, _shell.SHEAR_FACTOR * Gt, detG, invG, dNdx)
    Km, omega = _membrane_allman(xy, Cm)
    k_drill = DRILL_ALPHA * Cm[:, 2, 2] * detG.sum(axis=1) / 4
    Km = _shell.add_drilling(Km, omega, k_drill)
    K = _shell.combine(Km, Kp)
    NN = np.einsum("ga,gb,eg->eab", _N_G, _N_G, detG)
    M = _shell.consistent_mass(NN, rho, t)
    return _shell.to_global(K, R, h), _shell.to_global(M, R, h, isotropic=True)


def matrices(X, *, E, nu, rho, thickness, bending=1.0, zoffset=None, laminate=None, **_):
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
    return _shell.in_sub_batches(_batch, (R, xy, _shell.offset_heights(h, zoffset)), E, nu,
                                 rho, thickness, bending=bending, laminate=laminate)
