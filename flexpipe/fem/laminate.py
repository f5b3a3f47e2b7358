"""Classical lamination theory: membrane (A), coupling (B) and bending (D) rigidities.

A ply of an orthotropic material (Nastran MAT8: ``E1, E2, NU12, G12``; or isotropic
MAT1) has the reduced plane-stress stiffness

``Q = [[E1, nu12 E2, 0], [nu12 E2, E2, 0], [0, 0, G12 (1 - nu12 nu21)]] / (1 - nu12 nu21)``

(``nu21 = nu12 E2 / E1``), turned by its angle ``theta`` (degrees, from the element x
axis towards y) into ``Qbar = T^-1 Q T^-T`` (Voigt xx, yy, xy with engineering shear).
With ply ``k`` between ``z_{k-1}`` and ``z_k`` (measured from the reference plane, the
first ply at the bottom ``z0``):

``A = sum Qbar_k (z_k - z_{k-1})``, ``B = sum Qbar_k (z_k^2 - z_{k-1}^2) / 2``,
``D = sum Qbar_k (z_k^3 - z_{k-1}^3) / 3``.

Transverse shear: ``sum G_k t_k`` of the plies' out-of-plane shear moduli (``G1Z``;
``G12`` when blank), with the shells' shear correction factor 5/6.
"""

from __future__ import annotations

import numpy as np


def ply_q(E1: float, E2: float, nu12: float, G12: float) -> np.ndarray:
    """Reduced plane-stress stiffness (3, 3) of an orthotropic ply in its own axes."""
    nu21 = nu12 * E2 / E1
    d = 1.0 - nu12 * nu21
    return np.array([[E1 / d, nu12 * E2 / d, 0.0], [nu12 * E2 / d, E2 / d, 0.0],
                     [0.0, 0.0, G12]])


def rotate_q(Q: np.ndarray, theta_deg: float) -> np.ndarray:
    """``Qbar``: the ply stiffness in element axes for a ply at ``theta`` degrees."""
    c, s = np.cos(np.radians(theta_deg)), np.sin(np.radians(theta_deg))
    T = np.array([[c * c, s * s, 2 * c * s], [s * s, c * c, -2 * c * s],
                  [-c * s, c * s, c * c - s * s]])        # stress transformation
    Ti = np.linalg.inv(T)
    R = np.diag([1.0, 1.0, 2.0])                         # engineering <-> tensor shear
    return Ti @ Q @ R @ T @ np.linalg.inv(R)


def abd(plies, z0: float | None = None):
    """``A, B, D`` (3 x 3 each) and total thickness of ``plies`` = [(Q, t, theta), ...].

    ``z0``: position of the bottom surface from the reference plane (default ``-T/2``).
    """
    T = float(sum(t for _, t, _ in plies))
    z = -T / 2 if z0 is None else float(z0)
    A, B, D = np.zeros((3, 3)), np.zeros((3, 3)), np.zeros((3, 3))
    for Q, t, theta in plies:
        Qb = rotate_q(Q, theta)
        z1 = z + t
        A += Qb * (z1 - z)
        B += Qb * (z1**2 - z**2) / 2
        D += Qb * (z1**3 - z**3) / 3
        z = z1
    return A, B, D, T


def rotate_batch(C: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Stiffness matrices (n, 3, 3) given in axes turned by ``phi`` (n,) radians from the
    element axes, expressed in element axes (``rotate_q`` for a batch)."""
    c, s = np.cos(phi), np.sin(phi)
    T = np.zeros((len(phi), 3, 3))
    T[:, 0, 0], T[:, 0, 1], T[:, 0, 2] = c * c, s * s, 2 * c * s
    T[:, 1, 0], T[:, 1, 1], T[:, 1, 2] = s * s, c * c, -2 * c * s
    T[:, 2, 0], T[:, 2, 1], T[:, 2, 2] = -c * s, c * s, c * c - s * s
    R = np.diag([1.0, 1.0, 2.0])
    Ri = np.diag([1.0, 1.0, 0.5])
    Ti = np.linalg.inv(T)
    return Ti @ C @ R @ T @ Ri


def section(plies, nsm: float = 0.0) -> dict:
    """Section keys of a symmetric laminate: ``A11..A66``, ``D11..D66``, ``Gt``,
    ``thickness``, mean ``rho`` and an equivalent ``E``, ``nu``.

    ``plies``: [(Q, t, theta_deg, G_transverse, rho), ...] from the bottom up.  Raises
    ValueError for an unsymmetric laminate (``B != 0``).
    """
    A, B, D, T = abd([(Q, t, th) for Q, t, th, _, _ in plies])
    if np.abs(B).max() > 1e-9 * np.abs(A).max() * T:
        raise ValueError("the laminate is not symmetric (coupling matrix B != 0); only "
                         "symmetric laminates are supported")
    out = {"thickness": T}
    iu = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
    for (i, j), name in zip(iu, ("11", "12", "16", "22", "26", "66"), strict=True):
        out["A" + name], out["D" + name] = float(A[i, j]), float(D[i, j])
    out["Gt"] = float(sum(g * t for _, t, _, g, _ in plies))
    out["rho"] = (sum(r * t for _, t, _, _, r in plies) + nsm) / T
    nu = float(min(max(A[0, 1] / A[0, 0], 0.0), 0.49))
    out["E"], out["nu"] = float(A[0, 0] / T * (1 - nu * nu)), nu
    return out
