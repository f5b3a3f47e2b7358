"""Lowest eigenmodes by shift-invert Lanczos on the chosen sparse factorization."""

from __future__ import annotations

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from flexpipe.errors import InputError, ModelError
from flexpipe.fem.model import FEModel
from flexpipe.fem.solver import factorize

#: default shift (rad/s)^2: below every eigenvalue, so a free structure's K - sigma M is SPD
DEFAULT_SIGMA = -(2 * np.pi * 1.0) ** 2


def _fixed_columns(fe: FEModel, fixed_dofs) -> np.ndarray:
    fixed = np.unique(np.asarray(fixed_dofs, dtype=np.int64).ravel())
    if fixed.size and (fixed.min() < 0 or fixed.max() >= fe.n_dof):
        raise InputError(f"fixed_dofs must lie in [0, {fe.n_dof}); got {fixed.min()}..{fixed.max()}")
    cols = fe.independent_of_dof[fixed]
    # DOF no element touches have no column: fixing them is a no-op
    untouched = np.asarray(abs(fe.T[fixed]).sum(axis=1)).ravel() == 0
    bad = (cols < 0) & ~untouched
    if bad.any():
        raise InputError(
            f"fixed DOF {fixed[bad][:10].tolist()} are tied by rigid links (RBE2 slaves); "
            "fix the link's master DOF instead"
        )
    return np.unique(cols[cols >= 0])


def solve_eigen(K, M, n: int, *, sigma: float = DEFAULT_SIGMA, backend=None, tol=0.0):
    """Lowest ``n`` eigenpairs of ``K x = lambda M x`` (sparse, symmetric).

    Returns ``(lam, X)`` ascending with ``X^T M X = I``.
    """
    ndof = K.shape[0]
    if n >= ndof - 1 or ndof < 60:
        # small problem: dense solve
        import scipy.linalg as sla

        Kd = K.toarray() if sp.issparse(K) else np.asarray(K)
        Md = M.toarray() if sp.issparse(M) else np.asarray(M)
        if n > ndof:
            raise InputError(f"asked for {n} modes but the model has only {ndof} free DOF")
        lam, X = sla.eigh(Kd, Md, subset_by_index=[0, n - 1])
        return lam, X
    A = (sp.csr_matrix(K) - sigma * sp.csr_matrix(M)).tocsr()
    try:
        fac = factorize(A, backend=backend)
    except ModelError as exc:
        raise ModelError(
            f"{exc}. The stiffness cannot be factorized even after the shift: look for "
            "zero-stiffness DOF, mechanisms, or elements with zero modulus"
        ) from None
    ncv = min(ndof, max(2 * n + 1, n + 20))
    lam, X = spla.eigsh(sp.csr_matrix(K), k=n, M=sp.csr_matrix(M), sigma=sigma, which="LM",
                        OPinv=fac.as_operator(), ncv=ncv, tol=tol)
    order = np.argsort(lam)
    lam, X = lam[order], X[:, order]
    # normalize to unit modal mass (eigsh already does, up to round-off)
    mm = np.einsum("ij,ij->j", X, M @ X)
    X = X / np.sqrt(np.abs(mm))
    return lam, X


def eigenmodes(fe: FEModel, n: int, fixed_dofs=None, *, sigma: float = DEFAULT_SIGMA,
               backend: str | None = None):
    """Lowest ``n`` natural modes of a free or constrained structure.

    Parameters
    ----------
    fe : FEModel
    n : int
        Number of modes.  A free structure's six rigid-body modes come first, at ~0 Hz.
    fixed_dofs : array_like of int, optional
        Global DOF indices (``node * dofs_per_node + component``) held at zero.
    sigma : float, optional
        Shift (rad/s)^2 of the shift-invert Lanczos iteration; must lie below the lowest
        eigenvalue (negative for a free structure).
    backend : {"pardiso", "superlu"}, optional
        Sparse factorization (default: fastest available).

    Returns
    -------
    frequencies_hz : ndarray, shape (n,)
        Ascending natural frequencies in Hz (rigid-body modes ~0).
    shapes : ndarray, shape (n_dof, n)
        Mass-normalized mode shapes over all DOF (node-major numbering).
    """
    if not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError(f"n must be a positive integer, got {n!r}")
    Kr, Mr = fe.Kr, fe.Mr
    keep = np.arange(Kr.shape[0])
    if fixed_dofs is not None and len(np.atleast_1d(fixed_dofs)):
        cols = _fixed_columns(fe, fixed_dofs)
        keep = np.setdiff1d(keep, cols)
        Kr = Kr[keep][:, keep]
        Mr = Mr[keep][:, keep]
    if n > Kr.shape[0]:
        raise InputError(f"asked for {n} modes but the model has only {Kr.shape[0]} free DOF")
    lam, X = solve_eigen(Kr, Mr, n, sigma=sigma, backend=backend)
    Q = np.zeros((fe.T.shape[1], n))
    Q[keep] = X
    shapes = fe.expand(Q)
    freqs = np.sqrt(np.clip(lam, 0.0, None)) / (2 * np.pi)
    return freqs, shapes
