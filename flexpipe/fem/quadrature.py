"""Numerical integration rules shared by the element families.

All functions return ``(points, weights)`` as float arrays:

``gauss_legendre(n)``
    n-point Gauss-Legendre rule on [-1, 1] (exact to polynomial degree 2n - 1).
``gauss_hex(n)``
    Tensor product n x n x n on the cube [-1, 1]^3, points (n^3, 3).
``gauss_quad(n)``
    Tensor product n x n on the square [-1, 1]^2, points (n^2, 2).
``tet_rule(order)``
    Symmetric rule on the unit tetrahedron {xi, eta, zeta >= 0, xi + eta + zeta <= 1}
    (volume 1/6), exact to polynomial degree ``order``; points (nq, 3) in the
    coordinates (xi, eta, zeta) = barycentric (L2, L3, L4).  Positive weights only.
``triangle_rule(order)``
    Symmetric rule on the unit triangle {xi, eta >= 0, xi + eta <= 1} (area 1/2),
    points (nq, 2) = barycentric (L2, L3).

The symmetric tetrahedron and triangle rules are the classical ones (centroid; the
4-point rule of degree 2; the 14-point rule of degree 5 with positive weights; the
7-point Radon rule of degree 5 on the triangle); higher orders fall back to Stroud's
conical product of Gauss-Jacobi rules.
"""

from __future__ import annotations

from functools import cache

import numpy as np
from scipy.special import roots_jacobi

from flexpipe.errors import InputError


def _check(order, name):
    if not isinstance(order, (int, np.integer)) or order < 1:
        raise InputError(f"{name} must be a positive integer, got {order!r}", key=name)


@cache
def _gl(n: int):
    x, w = np.polynomial.legendre.leggauss(n)
    x.setflags(write=False)
    w.setflags(write=False)
    return x, w


def gauss_legendre(n: int) -> tuple[np.ndarray, np.ndarray]:
    """n-point Gauss-Legendre points and weights on [-1, 1]."""
    _check(n, "n")
    x, w = _gl(int(n))
    return x.copy(), w.copy()


def gauss_quad(n: int) -> tuple[np.ndarray, np.ndarray]:
    """n x n Gauss points (n^2, 2) and weights on [-1, 1]^2 (xi varies slowest)."""
    x, w = gauss_legendre(n)
    P = np.stack(np.meshgrid(x, x, indexing="ij"), axis=-1).reshape(-1, 2)
    return P, np.outer(w, w).ravel()


def gauss_hex(n: int) -> tuple[np.ndarray, np.ndarray]:
    """n x n x n Gauss points (n^3, 3) and weights on [-1, 1]^3 (xi varies slowest)."""
    x, w = gauss_legendre(n)
    P = np.stack(np.meshgrid(x, x, x, indexing="ij"), axis=-1).reshape(-1, 3)
    return P, np.einsum("i,j,k->ijk", w, w, w).ravel()


def _perms(*bary):
    """Distinct permutations of a barycentric tuple."""
    from itertools import permutations

    return np.array(sorted(set(permutations(bary))))


def _conical_tet(n: int):
    """Stroud conical product rule with n points per direction (degree 2n - 1)."""
    # collapse the cube [0,1]^3 onto the tet: weights (1-u)^2 and (1-u) via Gauss-Jacobi
    a, wa = roots_jacobi(n, 2.0, 0.0)
    b, wb = roots_jacobi(n, 1.0, 0.0)
    c, wc = roots_jacobi(n, 0.0, 0.0)
    u, wu = (a + 1) / 2, wa / 8
    v, wv = (b + 1) / 2, wb / 4
    s, ws = (c + 1) / 2, wc / 2
    U, V, S = np.meshgrid(u, v, s, indexing="ij")
    W = np.einsum("i,j,k->ijk", wu, wv, ws)
    xi = U
    eta = (1 - U) * V
    zeta = (1 - U) * (1 - V) * S
    return np.column_stack([xi.ravel(), eta.ravel(), zeta.ravel()]), W.ravel()


def _conical_tri(n: int):
    a, wa = roots_jacobi(n, 1.0, 0.0)
    c, wc = roots_jacobi(n, 0.0, 0.0)
    u, wu = (a + 1) / 2, wa / 4
    s, ws = (c + 1) / 2, wc / 2
    U, S = np.meshgrid(u, s, indexing="ij")
    return np.column_stack([U.ravel(), ((1 - U) * S).ravel()]), np.outer(wu, ws).ravel()


@cache
def _tet(order: int):
    if order <= 1:
        P, w = np.array([[0.25, 0.25, 0.25]]), np.array([1.0 / 6.0])
    elif order == 2:
        a, b = 0.5854101966249685, 0.1381966011250105  # (5 +- 3 sqrt5) / 20
        L = _perms(a, b, b, b)
        P, w = L[:, 1:], np.full(4, 1.0 / 24.0)
    elif order <= 5:
        # 14-point, degree 5, all weights positive (Walkington / Keast family)
        a1, w1 = 0.09273525031089123, 0.01224884051939366
        a2, w2 = 0.3108859192633006, 0.01878132095300264
        c3, w3 = 0.04550370412564965, 0.007091003462846911
        L = np.vstack([_perms(1 - 3 * a1, a1, a1, a1), _perms(1 - 3 * a2, a2, a2, a2),
                       _perms(c3, c3, 0.5 - c3, 0.5 - c3)])
        P = L[:, 1:]
        w = np.concatenate([np.full(4, w1), np.full(4, w2), np.full(6, w3)])
    else:
        P, w = _conical_tet((order + 2) // 2)
    P.setflags(write=False)
    w.setflags(write=False)
    return P, w


def tet_rule(order: int) -> tuple[np.ndarray, np.ndarray]:
    """Rule on the unit tetrahedron exact to polynomial degree ``order``.

    Returns points (nq, 3) as (xi, eta, zeta) and weights (nq,) summing to 1/6.
    """
    _check(order, "order")
    P, w = _tet(int(order))
    return P.copy(), w.copy()


@cache
def _tri(order: int):
    if order <= 1:
        P, w = np.array([[1 / 3, 1 / 3]]), np.array([0.5])
    elif order == 2:
        L = _perms(2 / 3, 1 / 6, 1 / 6)
        P, w = L[:, 1:], np.full(3, 1 / 6)
    elif order <= 5:
        r = np.sqrt(15.0)
        a, b = (6 - r) / 21, (6 + r) / 21
        L = np.vstack([[[1 / 3, 1 / 3, 1 / 3]], _perms(1 - 2 * a, a, a), _perms(1 - 2 * b, b, b)])
        P = L[:, 1:]
        w = 0.5 * np.concatenate([[9 / 40], np.full(3, (155 - r) / 1200),
                                  np.full(3, (155 + r) / 1200)])
    else:
        P, w = _conical_tri((order + 2) // 2)
    P.setflags(write=False)
    w.setflags(write=False)
    return P, w


def triangle_rule(order: int) -> tuple[np.ndarray, np.ndarray]:
    """Rule on the unit triangle exact to polynomial degree ``order``.

    Returns points (nq, 2) as (xi, eta) and weights (nq,) summing to 1/2.
    """
    _check(order, "order")
    P, w = _tri(int(order))
    return P.copy(), w.copy()
