"""Component mode synthesis at matrix level: Ritz bases ``Psi`` with ``x ~ Psi q``.

Every function accepts dense ndarrays or scipy.sparse matrices ``M``, ``K`` (symmetric,
same shape) and returns a dense basis ``Psi`` of shape ``(n_dof, n_columns)``.  Small
problems (``n_dof <= DENSE_LIMIT``) are solved with dense LAPACK; large ones with one
sparse factorization reused by every solve (see :mod:`flexpipe.reduction.eigen`).

Bases
-----
:func:`craig_bampton_basis`
    Static constraint modes of the boundary DOF plus fixed-interface normal modes
    (Craig & Bampton 1968).
:func:`residual_flexibility_basis`
    Free-interface normal modes (rigid-body plus elastic) plus one residual-flexibility
    attachment mode per boundary DOF (MacNeal 1971, Rubin 1975, Craig & Chang 1977):
    the static response to a unit load at that DOF carried by the *deleted* elastic
    modes only.  For a free structure the load is first put in self-equilibrium by
    inertia relief.
:func:`modal_truncation_basis`
    The lowest free-free modes only (for comparisons).
:func:`orthonormalize`
    Solves the reduced eigenproblem so that ``Psi^T M Psi = I`` and
    ``Psi^T K Psi = diag(omega^2)``.
"""

from __future__ import annotations

import time
import warnings

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp

from flexpipe.errors import InputError, ModelError
from flexpipe.fem.mechanism import count_zero_modes
from flexpipe.reduction.eigen import DENSE_LIMIT, factor_spd, lowest_modes, modes_up_to

#: a mode is rigid when its frequency is below this fraction of the first elastic one
RIGID_RATIO = 1e-3
#: columns whose mass-normalized Gram eigenvalue falls below this are dropped as dependent
DEPENDENCE_TOL = 1e-10
#: a free body has at most this many rigid-body modes
MAX_RIGID = 6


class DependentColumnsWarning(UserWarning):
    """Columns of a Ritz basis were linearly dependent and have been dropped."""


# ---------------------------------------------------------------------------- helpers
def _as_matrix(A, name):
    if sp.issparse(A):
        A = sp.csr_matrix(A, dtype=float)
    else:
        A = np.asarray(A, dtype=float)
        if A.ndim != 2:
            raise InputError(f"{name} must be a square matrix, got shape {A.shape}")
    if A.shape[0] != A.shape[1]:
        raise InputError(f"{name} must be square, got shape {A.shape}")
    return A


def _check_pair(M, K):
    M = _as_matrix(M, "M")
    K = _as_matrix(K, "K")
    if M.shape != K.shape:
        raise InputError(f"M {M.shape} and K {K.shape} must have the same shape")
    return M, K


def _dense(A):
    return A.toarray() if sp.issparse(A) else np.asarray(A)


def _boundary(boundary_dofs, n):
    b = np.asarray(boundary_dofs, dtype=np.int64).ravel()
    if b.size == 0:
        raise InputError("boundary_dofs is empty; give at least one boundary DOF index")
    if b.min() < 0 or b.max() >= n:
        raise InputError(f"boundary_dofs must lie in [0, {n}); got {b.min()}..{b.max()}")
    if np.unique(b).size != b.size:
        raise InputError(f"boundary_dofs contains duplicates: {b.tolist()[:20]}")
    return b


def _count(value, name, *, minimum=0):
    if not isinstance(value, (int, np.integer)) or value < minimum:
        raise InputError(f"{name} must be an integer >= {minimum}, got {value!r}")
    return int(value)


def detect_rigid_modes(omega, *, ratio: float = RIGID_RATIO, max_rigid: int = MAX_RIGID) -> int:
    """Number of leading rigid-body modes in ascending circular frequencies ``omega``.

    The count ``r`` is the largest one for which every one of the first ``r``
    frequencies lies below ``ratio`` times the frequency of mode ``r`` (the first elastic
    mode).  ``omega`` must hold at least ``r + 1`` values for the test to see the gap.

    Raises
    ------
    ModelError
        When more than ``max_rigid`` zero-frequency modes are found (a mechanism).
    """
    r = count_zero_modes(omega, ratio=ratio)
    if r > max_rigid:
        raise ModelError(
            f"{r} zero-frequency modes found but a free body has at most {max_rigid}: the "
            "structure is a mechanism or has disconnected parts (check connectivity, "
            "hinges, elements with zero stiffness)"
        )
    return r


# ---------------------------------------------------------------------------- bases
def craig_bampton_basis(M, K, boundary_dofs, n_fixed=None, *, f_max=None, backend=None,
                        tol=None):
    """Craig-Bampton basis: constraint modes plus fixed-interface normal modes.

    Parameters
    ----------
    M, K : ndarray or scipy.sparse matrix, shape (n, n)
        Symmetric mass and stiffness.
    boundary_dofs : array_like of int
        Indices of the boundary (interface) DOF, ``n_b`` of them.
    n_fixed : int, optional
        Number of fixed-interface normal modes (may be 0).
    f_max : float, optional
        Instead of ``n_fixed``: keep every fixed-interface mode up to ``f_max`` Hz.
    backend : {"pardiso", "superlu"}, optional
        Sparse factorization backend.
    tol : float, optional
        Residual tolerance of the sparse eigensolver (default
        :data:`flexpipe.reduction.eigen.KRYLOV_TOL`: eigenvalues to ~1e-12).

    Returns
    -------
    Psi : ndarray, shape (n, n_b + n_fixed)
        Columns ``[0, n_b)``: static constraint modes (unit displacement of one
        boundary DOF, others held, interior in static equilibrium); columns
        ``n_b...``: mass-normalized fixed-interface modes, ascending frequency.

    Raises
    ------
    ModelError
        When the interior stiffness ``K_ii`` is singular: the boundary does not hold the
        structure against rigid motion, or part of it is a mechanism/disconnected.
    InputError
        Bad indices or more modes than interior DOF.
    """
    return _craig_bampton(M, K, boundary_dofs, n_fixed, f_max=f_max, backend=backend,
                          tol=tol)[0]


def _select(n, f_max, name):
    if n is None and f_max is None:
        raise InputError(f"give {name} or f_max", key=name)
    if n is not None and f_max is not None:
        raise InputError(f"give {name} or f_max, not both", key=name)
    return None if n is None else _count(n, name)


def _craig_bampton(M, K, boundary_dofs, n_fixed, *, f_max=None, backend=None, tol=None,
                   timings=None, factor_out=None):
    """Craig-Bampton basis and the fixed-interface eigenvalues (stage times into
    ``timings`` when a dict is given; the factor of ``K_ii`` appended to ``factor_out``
    when a list is given)."""
    timings = {} if timings is None else timings
    t0 = time.perf_counter()
    M, K = _check_pair(M, K)
    n = K.shape[0]
    b = _boundary(boundary_dofs, n)
    n_fixed = _select(n_fixed, f_max, "n_fixed")
    interior = np.setdiff1d(np.arange(n), b)
    ni, nb = interior.size, b.size
    if n_fixed is not None and n_fixed > ni:
        raise InputError(f"{n_fixed} fixed-interface modes requested (n_modes) but the model "
                         f"has only {ni} interior DOF ({n} DOF, {nb} on the interfaces); "
                         f"valid: 0..{ni}", key="n_modes")
    if ni == 0:
        Psi = np.zeros((n, nb))
        Psi[b, np.arange(nb)] = 1.0
        return Psi, np.zeros(0)
    if sp.issparse(K):
        Kii = K[interior][:, interior]
        Kib = K[interior][:, b]
        Mii = M[interior][:, interior]
    else:
        Kii = K[np.ix_(interior, interior)]
        Kib = K[np.ix_(interior, b)]
        Mii = M[np.ix_(interior, interior)]
    timings["partition_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    try:
        fac = factor_spd(Kii, backend=backend)
    except ModelError as exc:
        raise ModelError(
            f"interior stiffness K_ii is singular ({exc}): the {nb} boundary DOF do not hold "
            "the structure against rigid-body motion, or part of it is a mechanism or "
            "disconnected"
        ) from None
    timings["factor_s"] = time.perf_counter() - t0
    if factor_out is not None:
        factor_out.append(fac)
    t0 = time.perf_counter()
    static = -fac.solve(_dense(Kib))
    timings["static_s"] = time.perf_counter() - t0
    t0 = time.perf_counter()
    if n_fixed is None:
        lam, Phi = modes_up_to(Kii, Mii, f_max, sigma=0.0, factor=fac, backend=backend, tol=tol,
                               X0=static)
        keep = lam <= (2 * np.pi * f_max) ** 2
        lam, Phi = lam[keep], Phi[:, keep]
    elif n_fixed:
        lam, Phi = lowest_modes(Kii, Mii, n_fixed, sigma=0.0, factor=fac, backend=backend,
                                tol=tol, X0=static)
    else:
        lam, Phi = np.zeros(0), np.zeros((ni, 0))
    timings["eigen_s"] = time.perf_counter() - t0
    Psi = np.zeros((n, nb + Phi.shape[1]))
    Psi[b, np.arange(nb)] = 1.0
    Psi[interior, :nb] = static
    Psi[interior, nb:] = Phi
    return Psi, lam


def _free_modes(M, K, n_modes, *, f_max=None, n_rigid=None, backend=None, tol=None):
    """Lowest free-free eigenpairs: ``n_rigid`` (detected when None) + ``n_modes`` elastic,
    or all up to ``f_max`` Hz.  Returns ``(lam, Phi, n_rigid, lam_next, factor, sigma)``
    with ``lam_next`` the first eigenvalue not kept (None when unknown)."""
    n = K.shape[0]
    if n_modes is None:
        lam, Phi, fac, sigma = modes_up_to(K, M, f_max, backend=backend, tol=tol,
                                           start=max(12, (n_rigid or MAX_RIGID) + 6),
                                           return_factor=True)
        if n_rigid is None:
            n_rigid = detect_rigid_modes(np.sqrt(np.clip(lam, 0, None)))
        n_keep = max(int(np.count_nonzero(lam <= (2 * np.pi * f_max) ** 2)), n_rigid)
    else:
        n_ask = min(n, (n_rigid if n_rigid is not None else MAX_RIGID) + n_modes + 1)
        if n_rigid is not None and n_rigid + n_modes > n:
            raise InputError(f"{n_rigid} rigid + {n_modes} elastic modes exceed the {n} DOF",
                             key="n_modes")
        lam, Phi, fac, sigma = lowest_modes(K, M, n_ask, backend=backend, tol=tol,
                                            return_factor=True)
        if n_rigid is None:
            n_rigid = detect_rigid_modes(np.sqrt(np.clip(lam, 0, None)))
        n_keep = n_rigid + n_modes
        if n_keep > len(lam):
            raise InputError(f"{n_rigid} rigid + {n_modes} elastic modes requested but the "
                             f"model has only {n} DOF", key="n_modes")
    lam_next = lam[n_keep] if len(lam) > n_keep else None
    return lam[:n_keep], Phi[:, :n_keep], n_rigid, lam_next, fac, sigma


def residual_flexibility_basis(M, K, boundary_dofs, n_normal=None, *, f_max=None, n_rigid=None,
                               backend=None, tol=None):
    """Free-interface modes plus residual-flexibility attachment modes.

    Parameters
    ----------
    M, K : ndarray or scipy.sparse matrix, shape (n, n)
        Symmetric mass and stiffness of the *free* (or partly supported) component.
    boundary_dofs : array_like of int
        DOF that carry external loads or connect the component to others; one
        attachment mode is built for each.
    n_normal : int, optional
        Number of elastic free-interface normal modes to keep.
    f_max : float, optional
        Instead of ``n_normal``: keep every free-interface mode up to ``f_max`` Hz.
    n_rigid : int, optional
        Number of rigid-body modes.  Detected when omitted: modes whose frequency lies
        below :data:`RIGID_RATIO` times the first elastic one.
    backend : {"pardiso", "superlu"}, optional
    tol : float, optional
        Eigensolver tolerance (sparse problems).

    Returns
    -------
    Psi : ndarray, shape (n, n_rigid + n_normal + n_b)
        ``[Phi_r, Phi_k, Psi_res]``: mass-normalized rigid-body modes, kept elastic modes
        (ascending), then one residual attachment mode per boundary DOF in the order of
        ``boundary_dofs``.

    Notes
    -----
    With ``F_b`` the unit loads at the boundary DOF, ``P = I - M Phi_r Phi_r^T`` the
    inertia-relief projector and ``G_e`` the elastic flexibility (the inverse of ``K`` on
    the M-orthogonal complement of the rigid-body modes), the attachment modes are

    ``Psi_res = G_e P F_b - Phi_k Omega_k^-2 Phi_k^T F_b = sum_deleted phi phi^T F_b / omega^2``.

    They are computed without forming ``G_e``: with the factor of ``A = K - sigma M``
    (sigma < 0, reused from the eigen-solve) the fixed-point iteration
    ``x <- Q A^-1 (Q^T F_b - sigma M x)``, ``Q = I - Phi_0 Phi_0^T M`` over the kept modes
    ``Phi_0 = [Phi_r, Phi_k]``, converges for every deleted mode with the factor
    ``|sigma| / (omega_j^2 - sigma)``; sigma is re-chosen when that bound is poor.
    """
    return _residual_flexibility(M, K, boundary_dofs, n_normal, f_max=f_max, n_rigid=n_rigid,
                                 backend=backend, tol=tol)[0]


def _residual_flexibility(M, K, boundary_dofs, n_normal, *, f_max=None, n_rigid=None,
                          backend=None, tol=None):
    M, K = _check_pair(M, K)
    n = K.shape[0]
    b = _boundary(boundary_dofs, n)
    n_normal = _select(n_normal, f_max, "n_normal")
    if n_rigid is not None:
        n_rigid = _count(n_rigid, "n_rigid")
    lam, Phi0, n_rigid, lam_next, fac, sigma = _free_modes(
        M, K, n_normal, f_max=f_max, n_rigid=n_rigid, backend=backend, tol=tol)
    if lam_next is None and lam.size > n_rigid:
        lam_next = lam[-1]  # the deleted eigenvalues are at least the last kept one
    F = np.zeros((n, b.size))
    F[b, np.arange(b.size)] = 1.0
    X = _residual_attachment(M, K, F, Phi0, lam_next, fac, sigma, backend=backend)
    return np.hstack([Phi0, X]), lam, n_rigid


def _residual_attachment(M, K, F, Phi0, lam_next, fac, sigma, *, backend=None,
                         max_iter=200, rtol=1e-14):
    """``sum over deleted modes of phi phi^T F / lambda`` (see residual_flexibility_basis)."""
    n = K.shape[0]
    if Phi0.shape[1] >= n:  # nothing is deleted
        return np.zeros_like(F)
    MPhi0 = M @ Phi0

    def project(x):  # M-orthogonal projection onto the deleted-mode subspace
        return x - Phi0 @ (MPhi0.T @ x)

    # the iteration contracts every deleted mode j by |sigma| / (lambda_j - sigma)
    if lam_next is not None and lam_next > 0 and abs(sigma) / (lam_next - sigma) > 0.05:
        sigma = -0.01 * float(lam_next)
        fac = factor_spd(K - sigma * M, backend=backend)
    G = F - MPhi0 @ (Phi0.T @ F)  # Q^T F: self-equilibrated, free of kept-mode content
    x = project(fac.solve(G))
    scale = max(np.abs(x).max(), 1e-300)
    previous = np.inf
    for _ in range(max_iter):
        x_new = project(fac.solve(G - sigma * (M @ x)))
        change = np.abs(x_new - x).max() / scale
        x = x_new
        # stop at the tolerance, or at the round-off floor where the change stalls
        if change < rtol or (change < 1e-8 and change > 0.5 * previous):
            break
        previous = change
    else:
        if change > 1e-6:
            raise ModelError(
                f"residual-flexibility iteration did not converge in {max_iter} steps (last "
                f"relative change {change:.2e}); the structure may be nearly a mechanism"
            )
    return x


def modal_truncation_basis(M, K, n_modes=None, *, f_max=None, backend=None, tol=None):
    """The lowest ``n_modes`` free-free modes (rigid-body modes included), mass-normalized,
    or every mode up to ``f_max`` Hz.

    Returns
    -------
    Psi : ndarray, shape (n, n_modes)
    """
    M, K = _check_pair(M, K)
    n_modes = _select(n_modes, f_max, "n_modes")
    if n_modes is not None:
        if n_modes < 1 or n_modes > K.shape[0]:
            raise InputError(f"n_modes={n_modes} must lie in [1, {K.shape[0]}]", key="n_modes")
        return lowest_modes(K, M, n_modes, backend=backend, tol=tol)[1]
    lam, Phi = modes_up_to(K, M, f_max, backend=backend, tol=tol)
    return Phi[:, lam <= (2 * np.pi * f_max) ** 2]


def orthonormalize(M, K, Psi, *, tol: float = DEPENDENCE_TOL):
    """Orthonormalize a Ritz basis by solving the reduced eigenproblem.

    Parameters
    ----------
    M, K : ndarray or scipy.sparse matrix, shape (n, n)
    Psi : ndarray, shape (n, m)
    tol : float
        Columns are dropped when the reduced mass matrix, scaled to a unit diagonal, has
        eigenvalues below ``tol`` times its largest one (near-dependent columns).

    Returns
    -------
    Psi_orth : ndarray, shape (n, m')
        ``Psi_orth^T M Psi_orth = I``, ``Psi_orth^T K Psi_orth = diag(omega^2)``,
        ``m' <= m`` (a :class:`DependentColumnsWarning` says how many were dropped).
    omega : ndarray, shape (m',)
        Ascending circular frequencies of the reduced model, rad/s (rigid modes ~0).
    """
    M, K = _check_pair(M, K)
    Psi = np.asarray(Psi, dtype=float)
    if Psi.ndim != 2 or Psi.shape[0] != K.shape[0]:
        raise InputError(f"Psi must have shape ({K.shape[0]}, m), got {Psi.shape}")
    Mr = Psi.T @ (M @ Psi)
    Kr = Psi.T @ (K @ Psi)
    Mr = 0.5 * (Mr + Mr.T)
    Kr = 0.5 * (Kr + Kr.T)
    d = np.sqrt(np.abs(np.diag(Mr)))
    zero = d <= 1e-300
    if zero.all():
        raise ModelError("every column of the basis has zero mass; nothing to orthonormalize")
    d[zero] = 1.0
    S = 1.0 / d
    mu, V = np.linalg.eigh(Mr * S[:, None] * S[None, :])
    keep = mu > tol * mu.max()
    dropped = int((~keep).sum())
    if dropped:
        warnings.warn(
            f"orthonormalize: dropped {dropped} of {Psi.shape[1]} basis columns that are "
            f"linearly dependent (relative mass-Gram eigenvalue < {tol:g}); the reduced "
            f"model has {int(keep.sum())} modes",
            DependentColumnsWarning, stacklevel=2,
        )
    Tm = (V[:, keep] / np.sqrt(mu[keep])) * S[:, None]  # Tm^T Mr Tm = I
    Kt = Tm.T @ Kr @ Tm
    lam, W = sla.eigh(0.5 * (Kt + Kt.T))
    T = Tm @ W
    omega = np.sqrt(np.clip(lam, 0.0, None))
    Psi_orth = Psi @ T
    # fix the sign so that the largest-magnitude entry of each mode is positive
    idx = np.abs(Psi_orth).argmax(axis=0)
    sign = np.sign(Psi_orth[idx, np.arange(Psi_orth.shape[1])])
    sign[sign == 0] = 1.0
    return Psi_orth * sign, omega


__all__ = [
    "DENSE_LIMIT",
    "DependentColumnsWarning",
    "craig_bampton_basis",
    "detect_rigid_modes",
    "modal_truncation_basis",
    "orthonormalize",
    "residual_flexibility_basis",
]
