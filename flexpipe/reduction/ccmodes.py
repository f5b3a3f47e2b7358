"""Interface reduction: characteristic constraint modes (Castanier, Tan & Pierre 2001).

A Craig-Bampton basis carries one static constraint mode per boundary DOF; a body loaded at
30 mounts has 90-180 of them, and each becomes a coordinate of the multibody model.  The
characteristic constraint (CC) modes replace them by the eigenvectors of the
Guyan-reduced boundary problem

``K_bb' v = lambda M_bb' v``,  ``K_bb' = Psi_c^T K Psi_c``,  ``M_bb' = Psi_c^T M Psi_c``

(``Psi_c`` the static constraint modes), truncated at a cut-off frequency: the columns
``Psi_c V_keep`` span the low-frequency interface motion, including the six rigid-body
motions of a free body (zero eigenvalues, always kept).

The fixed-interface modes then have to carry the inertia of the body between the mounts;
with the car's cut-off (1.5 x the band) the free-free modes below the band came out 2 %
high on the sample sedan with 30 mounts.  :func:`inertia_vectors` adds, for the low CC
modes, the interior static response to their inertia loads with the boundary held
(``K_ii^-1 (M psi)_i``): the modal-truncation-augmentation idea of Dickens, Nakagawa &
Wittbrodt (1997), applied to the fixed-interface problem, also Nastran's residual vectors
(RESVEC) of the boundary inertia loads.  These vectors vanish on the boundary, so the
static flexibility at the mounts is unchanged.

References: M. P. Castanier, Y.-C. Tan, C. Pierre, "Characteristic constraint modes for
component mode synthesis", AIAA Journal 39(6), 2001, 1182-1187.  J. M. Dickens,
J. M. Nakagawa, M. J. Wittbrodt, "A critique of mode acceleration and modal truncation
augmentation methods for modal response analysis", Computers & Structures 62(6), 1997,
985-998.

What is lost: the truncated CC modes carry the static flexibility of the high-frequency
interface deformation, so static deflections at the mounts are no longer exact (see
tests/test_mounts.py for the measured error against the unreduced model).  That lost
flexibility, ``C_res = sum over deleted CC modes of v v^T / lambda`` (boundary DOF,
m/N and rad/(N m)), is returned so that its diagonal block at each mount can be put in
series with the bushing there (the residual-flexibility idea of MacNeal 1971 applied to
the interface).
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from flexpipe.errors import InputError


def characteristic_constraint_modes(M, K, Psi_c, *, f_max: float):
    """CC modes of the static constraint modes ``Psi_c`` up to ``f_max`` Hz.

    Parameters
    ----------
    M, K : ndarray or scipy.sparse matrix, shape (n, n)
        Mass and stiffness of the model the constraint modes live on.
    Psi_c : ndarray, shape (n, n_b)
        Static constraint modes (the first ``n_b`` Craig-Bampton columns).
    f_max : float
        Keep the CC modes whose Guyan frequency is at most ``f_max`` Hz.

    Returns
    -------
    Psi_cc : ndarray, shape (n, n_cc)
        ``Psi_c @ V_keep``, mass-normalized on ``M``, ascending frequency.
    f_hz : ndarray, shape (n_cc,)
        Their Guyan frequencies (rigid-body ones ~0).
    C_res : ndarray, shape (n_b, n_b)
        Residual flexibility of the deleted CC modes on the boundary DOF.
    """
    if not f_max > 0:  # NaN fails too; inf keeps every CC mode (all static modes)
        raise InputError(f"the interface-reduction cut-off must be a positive frequency in "
                         f"Hz (inf: keep every mode), got {f_max!r}", key="interface_f_max")
    Psi_c = np.asarray(Psi_c, dtype=float)
    Kb = Psi_c.T @ (K @ Psi_c)
    Mb = Psi_c.T @ (M @ Psi_c)
    Kb, Mb = 0.5 * (Kb + Kb.T), 0.5 * (Mb + Mb.T)
    # scale to a unit mass diagonal so that rotations (rad) and translations (m) mix well
    s = 1.0 / np.sqrt(np.maximum(np.diag(Mb), 1e-300))
    lam, V = sla.eigh(Kb * s[:, None] * s[None, :], Mb * s[:, None] * s[None, :])
    f = np.sqrt(np.clip(lam, 0.0, None)) / (2 * np.pi)
    keep = f <= f_max
    keep[:min(6, keep.size)] = True  # the rigid-body motions of a free body
    Vd = V[:, ~keep] * s[:, None]
    C_res = (Vd / lam[~keep]) @ Vd.T
    return Psi_c @ (V[:, keep] * s[:, None]), f[keep], 0.5 * (C_res + C_res.T)


def inertia_vectors(M, Psi, interior, factor):
    """Interior static response to the inertia loads ``M Psi`` with the boundary held.

    Parameters
    ----------
    M : sparse matrix (n, n)
    Psi : ndarray (n, k)
        Boundary-driven shapes (e.g. the low CC modes).
    interior : ndarray of int
        Interior DOF indices.
    factor
        Factorization of ``K_ii`` (``.solve``).

    Returns
    -------
    ndarray (n, k), zero on the boundary DOF.
    """
    X = np.zeros((Psi.shape[0], Psi.shape[1]))
    if Psi.shape[1]:
        X[interior] = factor.solve(np.asarray((M @ Psi)[interior]))
    return X


def reduce_interface(M, K, Psi, b, *, interface_f_max, inertia_f_max=None, factor=None):
    """Interface-reduce a Craig-Bampton basis ``Psi`` (static constraint modes of the
    boundary DOF ``b`` first, then fixed-interface modes).

    Returns
    -------
    Psi_new : ndarray
        ``[CC modes to interface_f_max, fixed-interface modes, inertia vectors of the CC
        modes to inertia_f_max]`` (no inertia vectors when ``inertia_f_max`` or
        ``factor``, the factor of ``K_ii``, is None).
    n_cc, n_inertia : int
    C_res : ndarray (n_b, n_b)
        Residual flexibility of the deleted CC modes.
    """
    Psi_cc, f_cc, C_res = characteristic_constraint_modes(M, K, Psi[:, :b.size],
                                                          f_max=float(interface_f_max))
    parts = [Psi_cc, Psi[:, b.size:]]
    n_inertia = 0
    if inertia_f_max is not None and factor is not None:
        low = Psi_cc[:, f_cc <= inertia_f_max]
        interior = np.setdiff1d(np.arange(K.shape[0]), b)
        parts.append(inertia_vectors(M, low, interior, factor))
        n_inertia = low.shape[1]
    return np.hstack(parts), Psi_cc.shape[1], n_inertia, C_res


__all__ = ["characteristic_constraint_modes", "inertia_vectors", "reduce_interface"]
