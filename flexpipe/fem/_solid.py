"""Kernels shared by the isotropic solid element families (tet4, tet10, hex8).

For an isotropic material the stiffness coupling node ``a`` (component ``j``) with node
``b`` (component ``k``) is, per integration point with gradients ``g = grad N``,

    K[aj, bk] = sum_q w_q detJ_q (lam g_aj g_bk + mu g_ak g_bj + mu delta_jk g_a . g_b)

which equals ``B^T D B`` without forming the 6 x 3n strain-displacement matrices.  All
functions work on a batch of elements at once.
"""

from __future__ import annotations

import numpy as np


def lame(E, nu):
    """Lame constants ``lam, mu`` (arrays like ``E``)."""
    E = np.asarray(E, dtype=float)
    nu = np.asarray(nu, dtype=float)
    return E * nu / ((1 + nu) * (1 - 2 * nu)), E / (2 * (1 + nu))


def det_inv3(J: np.ndarray):
    """Determinants and inverses of a stack of 3x3 matrices (explicit cofactors)."""
    a, b, c = J[..., 0, 0], J[..., 0, 1], J[..., 0, 2]
    d, e, f = J[..., 1, 0], J[..., 1, 1], J[..., 1, 2]
    g, h, i = J[..., 2, 0], J[..., 2, 1], J[..., 2, 2]
    C = np.empty_like(J)
    C[..., 0, 0] = e * i - f * h
    C[..., 0, 1] = c * h - b * i
    C[..., 0, 2] = b * f - c * e
    C[..., 1, 0] = f * g - d * i
    C[..., 1, 1] = a * i - c * g
    C[..., 1, 2] = c * d - a * f
    C[..., 2, 0] = d * h - e * g
    C[..., 2, 1] = b * g - a * h
    C[..., 2, 2] = a * e - b * d
    det = a * C[..., 0, 0] + b * C[..., 1, 0] + c * C[..., 2, 0]
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = C / det[..., None, None]
    return det, inv


def isotropic_stiffness(G: np.ndarray, wdet: np.ndarray, lam, mu) -> np.ndarray:
    """Element stiffness from shape-function gradients.

    Parameters
    ----------
    G : ndarray, shape (ne, nq, nn, 3)
        Physical gradients of the ``nn`` shape functions at ``nq`` integration points.
    wdet : ndarray, shape (ne, nq)
        Integration weight times Jacobian determinant.
    lam, mu : ndarray, shape (ne,)
        Lame constants.

    Returns
    -------
    ndarray, shape (ne, 3 nn, 3 nn)
        Node-major DOF order.  With one integration point (``nq == 1``) the result is
        symmetric bit for bit.
    """
    ne, nq, nn, _ = G.shape
    Gs = G.reshape(ne, nq, 3 * nn) * np.sqrt(wdet)[:, :, None]
    if nq == 1:  # outer product: bitwise symmetric
        S = Gs[:, 0, :, None] * Gs[:, 0, None, :]
    else:
        S = np.matmul(Gs.transpose(0, 2, 1), Gs)
    S = S.reshape(ne, nn, 3, nn, 3)                       # S[a, j, b, k] = int g_aj g_bk
    dot = S[:, :, 0, :, 0] + S[:, :, 1, :, 1] + S[:, :, 2, :, 2]   # int g_a . g_b
    K = lam[:, None, None, None, None] * S
    K += mu[:, None, None, None, None] * S.transpose(0, 1, 4, 3, 2)
    mdot = mu[:, None, None] * dot
    for j in range(3):
        K[:, :, j, :, j] += mdot
    return K.reshape(ne, 3 * nn, 3 * nn)


def consistent_mass(N: np.ndarray, wdet: np.ndarray, rho) -> np.ndarray:
    """Consistent mass ``rho int N_a N_b`` expanded to 3 components, (ne, 3 nn, 3 nn).

    ``N`` (nq, nn) shape functions at the points, ``wdet`` (ne, nq), ``rho`` (ne,).
    """
    m = np.einsum("qa,qb,eq->eab", N, N, wdet * np.asarray(rho)[:, None], optimize=True)
    return expand3(m)


def expand3(m: np.ndarray) -> np.ndarray:
    """Scalar node matrices (ne, nn, nn) -> (ne, 3 nn, 3 nn) with identity per node pair."""
    ne, nn, _ = m.shape
    M = np.zeros((ne, nn, 3, nn, 3))
    for j in range(3):
        M[:, :, j, :, j] = m
    return M.reshape(ne, 3 * nn, 3 * nn)


def bad_jacobian(det: np.ndarray, X: np.ndarray, rtol: float = 1e-12) -> np.ndarray:
    """Batch positions whose Jacobian determinant (ne, npoints) is not clearly positive."""
    size = np.ptp(X, axis=1).max(axis=1)                   # element diameter scale
    return ~(det > rtol * size[:, None] ** 3).all(axis=1)
