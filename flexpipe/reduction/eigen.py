"""Eigen-solves and factorizations shared by the reduction methods.

Dense LAPACK for small matrices, one sparse factorization reused for every solve for
large ones.  The lowest modes of a large model come from a block Krylov iteration driven
by that factor (:func:`block_krylov_modes`: multi-right-hand-side solves, seeded with the
static modes in Craig-Bampton), with shift-invert ARPACK as the fallback.

Measured on the 61k-DOF tet4 block of ``bench/bench_reduction.py`` (10 fixed-interface
modes): ARPACK needs 43 single-vector solves (0.1-0.17 s each), the block iteration six
12-column solves (0.15-0.25 s each) for the same eigenvalues to 1e-10.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from flexpipe.errors import InputError, ModelError
from flexpipe.fem.solver import factorize
from flexpipe.reduction._threads import dense_single_threaded

#: problems up to this many DOF are solved with dense LAPACK
DENSE_LIMIT = 400
#: residual tolerance of the block Krylov eigensolver (eigenvalue errors ~ tol^2)
KRYLOV_TOL = 1e-5
#: default shift (rad/s)^2 for free structures: below every eigenvalue (rigid modes at 0)
FREE_SIGMA = -(2 * np.pi * 1.0) ** 2


class _DenseFactor:
    """Cholesky factor of a dense SPD matrix with the sparse ``Factor`` interface."""

    backend = "lapack"

    def __init__(self, A):
        self.shape = A.shape
        try:
            self._c = sla.cho_factor(np.asarray(A, dtype=float), lower=True,
                                     check_finite=True)
        except np.linalg.LinAlgError as exc:
            raise ModelError(f"matrix is not positive definite ({exc})") from None

    def solve(self, b):
        return sla.cho_solve(self._c, np.asarray(b, dtype=float))

    def as_operator(self):
        return spla.LinearOperator(self.shape, matvec=self.solve, matmat=self.solve,
                                   dtype=float)


def factor_spd(A, *, backend=None):
    """Factorize a symmetric positive definite matrix (dense or sparse).

    Raises
    ------
    ModelError
        When ``A`` is singular or not positive definite.
    """
    if sp.issparse(A):
        if A.shape[0] <= DENSE_LIMIT:
            return _DenseFactor(A.toarray())
        return factorize(A, backend=backend)
    return _DenseFactor(A)


def lowest_modes(K, M, k, *, sigma=None, factor=None, backend=None, tol=None,
                 return_factor=False, X0=None):
    """Lowest ``k`` eigenpairs of ``K x = lambda M x``, mass-normalized, ascending.

    Parameters
    ----------
    K, M : ndarray or scipy.sparse matrix
    k : int
    sigma : float, optional
        Shift below the lowest eigenvalue; ``None`` means a free structure and uses
        :data:`FREE_SIGMA` (0 is right for a supported structure).
    factor : Factor, optional
        Factor of ``K - sigma M`` if already available.
    tol : float, optional
        Shift-invert residual tolerance of the block Krylov solver (default
        :data:`KRYLOV_TOL`; eigenvalues then agree to ~1e-10).
    return_factor : bool
        Also return the factor of ``K - sigma M`` and sigma.
    X0 : ndarray, optional
        Starting block for the block Krylov solver (e.g. static modes).

    Returns
    -------
    lam : ndarray, shape (k,)
    X : ndarray, shape (n, k)
        ``X^T M X = I``.
    factor, sigma
        Only when ``return_factor``.
    """
    n = K.shape[0]
    if k > n:
        raise InputError(f"asked for {k} modes but the matrix has only {n} DOF")
    if sigma is None:
        sigma = FREE_SIGMA
    if n <= DENSE_LIMIT:
        Kd = K.toarray() if sp.issparse(K) else np.asarray(K, dtype=float)
        Md = M.toarray() if sp.issparse(M) else np.asarray(M, dtype=float)
        try:
            lam, X = sla.eigh(Kd, Md, subset_by_index=[0, k - 1])
        except np.linalg.LinAlgError as exc:
            raise ModelError(f"generalized eigenproblem failed: the mass matrix is not "
                             f"positive definite ({exc})") from None
        if return_factor:
            if factor is None:
                try:
                    factor = _DenseFactor(Kd - sigma * Md)
                except ModelError as exc:
                    raise ModelError(f"K - sigma M is singular at sigma={sigma:.4g}: {exc}; "
                                     "the structure has a mechanism") from None
            return lam, X, factor, sigma
        return lam, X
    Ks = sp.csr_matrix(K)
    Ms = sp.csr_matrix(M)
    if factor is None:
        try:
            factor = factorize((Ks - sigma * Ms).tocsr(), backend=backend)
        except ModelError as exc:
            raise ModelError(
                f"{exc}; K - sigma M cannot be factorized at sigma = {sigma:.4g}: look for "
                "mechanisms, disconnected parts or zero-stiffness DOF"
            ) from None
    try:
        lam, X = block_krylov_modes(Ks, Ms, k, factor=factor, sigma=sigma, X0=X0,
                                    tol=KRYLOV_TOL if tol is None else tol)
    except ModelError:  # no convergence in the allotted subspace: ARPACK, full precision
        ncv = min(n, max(2 * k + 1, k + 20))
        lam, X = spla.eigsh(Ks, k=k, M=Ms, sigma=sigma, which="LM",
                            OPinv=factor.as_operator(), ncv=ncv, tol=0.0)
    order = np.argsort(lam)
    lam, X = lam[order], X[:, order]
    X = X / np.sqrt(np.abs(np.einsum("ij,ij->j", X, Ms @ X)))
    if return_factor:
        return lam, X, factor, sigma
    return lam, X


def modes_up_to(K, M, f_max_hz, *, sigma=None, factor=None, backend=None, tol=None,
                start=12, return_factor=False, X0=None):
    """All eigenpairs with frequency <= ``f_max_hz`` (plus the next one, for gap tests).

    Computes the lowest ``start`` modes and doubles the count until one lies above
    ``f_max_hz`` (or all modes are found).  Returns like :func:`lowest_modes`; the last
    returned pair is the first one above ``f_max_hz`` when it exists.
    """
    if not (np.isfinite(f_max_hz) and f_max_hz > 0):
        raise InputError(f"f_max must be a positive frequency in Hz, got {f_max_hz!r}",
                         key="f_max")
    n = K.shape[0]
    lam_max = (2 * np.pi * f_max_hz) ** 2
    k = min(n, start)
    while True:
        res = lowest_modes(K, M, k, sigma=sigma, factor=factor, backend=backend, tol=tol,
                           return_factor=True, X0=X0)
        lam, X, factor, sigma = res
        if lam[-1] > lam_max or k == n:
            break
        k = min(n, 2 * k)
    count = min(len(lam), int(np.count_nonzero(lam <= lam_max)) + 1)
    lam, X = lam[:count], X[:, :count]
    return (lam, X, factor, sigma) if return_factor else (lam, X)


def _m_orthonormalize(W, M, V=None, MV=None, *, drop=1e-10, lost=1e-8):
    """M-orthonormalize the columns of W (against V first); drop dependent ones.

    Two full passes (project out V twice, then normalise by the eigen-decomposition of the
    Gram matrix): one pass leaves an orthogonality error of about eps times the Gram
    matrix's condition number, which reaches 1e-6 for a block dominated by rigid-body
    modes; the second pass, on a well-conditioned block, brings it to rounding level.
    Columns that lose all but ``lost`` of their M-norm to the projection are noise and
    are dropped before normalising (else they come back as spurious near-null Ritz
    vectors that pass any absolute residual test).
    """
    W = np.array(W, dtype=float, copy=True)
    if V is not None and V.shape[1]:
        before = np.sqrt(np.abs(np.einsum("ij,ij->j", W, M @ W)))
        for _ in range(2):
            W -= V @ (MV.T @ W)
        after = np.sqrt(np.abs(np.einsum("ij,ij->j", W, M @ W)))
        W = W[:, after > lost * np.maximum(before, 1e-300)]
    for rep in range(2):
        if rep and V is not None and V.shape[1]:
            W -= V @ (MV.T @ W)
        MW = M @ W
        G = W.T @ MW
        G = 0.5 * (G + G.T)
        mu, Q = np.linalg.eigh(G)
        keep = mu > (drop if rep == 0 else 0.5) * max(mu.max(initial=0.0), 1e-300)
        T = Q[:, keep] / np.sqrt(mu[keep])
        W, MW = W @ T, MW @ T
    return W, MW


def block_krylov_modes(K, M, k, *, factor, sigma=0.0, X0=None, block=None, tol=KRYLOV_TOL,
                       max_dim=None, seed=0):
    """Lowest ``k`` eigenpairs by block Krylov (block Lanczos with full re-orthogonalization).

    Starting from ``span(X0)``, every step does a Rayleigh-Ritz solve with the exact ``K``
    and ``M`` and one multi-right-hand-side solve ``Z = A X_b``, ``A = (K - sigma M)^-1 M``,
    of the ``block`` lowest Ritz vectors ``X_b``.  ``Z`` serves twice: its columns extend
    the subspace (the next Krylov block) and give the shift-invert residuals
    ``(theta - sigma) |A x - x / (theta - sigma)|_M`` of the ``k`` lowest Ritz pairs (the
    measure ARPACK uses; eigenvalue errors are of order ``tol^2``).  It stops when they
    are all below ``tol``.

    Parameters
    ----------
    K, M : sparse matrices
    k : int
    factor : Factor
        Factor of ``K - sigma M``.
    sigma : float
        The shift of ``factor`` (below the spectrum).
    X0 : ndarray (n, b), optional
        Starting block (e.g. static modes); ``A`` times a random block when omitted.
    block : int, optional
        Ritz vectors expanded per step (default ``k + 2``).
    tol : float
        Residual tolerance.
    max_dim : int, optional
        Largest subspace (default ``width of X0 + 10 (k + 2) + 20``).

    Returns
    -------
    lam : ndarray (k,)
    X : ndarray (n, k), ``X^T M X = I``

    Raises
    ------
    ModelError
        No convergence within ``max_dim`` vectors.
    """
    with dense_single_threaded():
        return _block_krylov(K, M, k, factor=factor, sigma=sigma, X0=X0, block=block, tol=tol,
                             max_dim=max_dim, seed=seed)


def _block_krylov(K, M, k, *, factor, sigma, X0, block, tol, max_dim, seed):
    n = K.shape[0]
    b = min(max(block or k + 2, k), n)
    rng = np.random.default_rng(seed)
    if X0 is None:
        X0 = factor.solve(M @ rng.standard_normal((n, b)))
    W, MW = _m_orthonormalize(np.array(X0, dtype=float), M)
    cap = min(n, max_dim or W.shape[1] + 10 * b + 20)
    cap = max(cap, min(n, W.shape[1]))
    V, MV = (np.empty((n, cap), order="F") for _ in range(2))
    H = np.zeros((cap, cap))  # V^T K V
    d = 0
    res = np.array([np.inf])
    while W.shape[1] and d + W.shape[1] <= cap:
        e = d + W.shape[1]
        V[:, d:e], MV[:, d:e] = W, MW
        H[:e, d:e] = V[:, :e].T @ (K @ W)
        H[d:e, :d] = H[:d, d:e].T
        d = e
        theta, Y = np.linalg.eigh(0.5 * (H[:d, :d] + H[:d, :d].T))
        bb = min(b, d)
        X = V[:, :d] @ Y[:, :bb]  # lowest Ritz vectors
        Z = factor.solve(MV[:, :d] @ Y[:, :bb])  # A X: the next Krylov directions ...
        if d >= k:  # ... and the shift-invert residuals of the k lowest Ritz pairs
            mu = theta[:k] - sigma
            S = Z[:, :k] - X[:, :k] / mu
            res = mu * np.sqrt(np.abs(np.einsum("ij,ij->j", S, M @ S)))
            if res.max() <= tol or d >= n:
                Xk = X[:, :k]
                norm = np.einsum("ij,ij->j", Xk, M @ Xk)
                if np.abs(norm - 1.0).max() > 1e-6:  # lost M-orthogonality: not trusted
                    raise ModelError("block Krylov basis lost its M-orthogonality "
                                     f"(|x|_M - 1 up to {np.abs(norm - 1.0).max():.1e})")
                return theta[:k], Xk
        W, MW = _m_orthonormalize(Z, M, V[:, :d], MV[:, :d])
    raise ModelError(f"block Krylov eigensolver did not converge to tol={tol:g} within "
                     f"{d} vectors (largest residual {res.max():.2e})")
