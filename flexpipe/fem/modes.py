"""Lowest eigenmodes by shift-invert Lanczos on the chosen sparse factorization."""

from __future__ import annotations

import warnings

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from flexpipe.errors import InputError, ModelError
from flexpipe.fem.mechanism import (
    MechanismWarning,
    element_scale_hz,
    extra_directions,
    n_parts,
    zero_mode_warning,
)
from flexpipe.fem.model import FEModel
from flexpipe.fem.solver import factorize

#: default shift (rad/s)^2: below every eigenvalue, so a free structure's K - sigma M is SPD
DEFAULT_SIGMA = -(2 * np.pi * 1.0) ** 2


def _fixed_columns(fe: FEModel, fixed_dofs) -> np.ndarray:
    fixed = np.unique(np.asarray(fixed_dofs, dtype=np.int64).ravel())
    if fixed.size and (fixed.min() < 0 or fixed.max() >= fe.n_dof):
        raise InputError(
            f"fixed_dofs must lie in [0, {fe.n_dof}); got {fixed.min()}..{fixed.max()}"
        )
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


def rigid_body_modes(fe: FEModel) -> np.ndarray:
    """Six rigid-body motions in the independent coordinates of ``fe``, shape (n_indep, 6).

    Columns: translations x, y, z, then small rotations about x, y, z through the node
    centroid (rotational DOF, where present, carry the rotation itself).  Rigid links
    (RBE2) move rigidly too, so every rigid motion lies in the range of ``fe.T``.
    """
    X = fe.nodes - fe.nodes.mean(axis=0)
    dpn = fe.dofs_per_node
    R = np.zeros((fe.n_nodes, dpn, 6))
    R[:, [0, 1, 2], [0, 1, 2]] = 1.0
    x, y, z = X.T
    R[:, 1, 3], R[:, 2, 3] = -z, y
    R[:, 0, 4], R[:, 2, 4] = z, -x
    R[:, 0, 5], R[:, 1, 5] = -y, x
    if dpn == 6:
        R[:, [3, 4, 5], [3, 4, 5]] = 1.0
    R = R.reshape(fe.n_dof, 6)
    col = fe.independent_of_dof
    one = col >= 0
    Rq = np.zeros((fe.T.shape[1], 6))
    Rq[col[one]] = R[one]
    return Rq


def zero_energy_basis(K, M, R, *, rtol: float = 1e-9) -> np.ndarray:
    """M-orthonormal basis of the part of span(R) that K does not strain.

    ``R`` (ndof, r) holds candidate motions (e.g. :func:`rigid_body_modes`); directions
    whose Rayleigh quotient is below ``rtol`` times the typical diagonal ratio
    ``K_ii / M_ii`` count as zero-energy.  Returns an (ndof, r0) array, r0 <= r.
    """
    if R is None or R.shape[1] == 0:
        return np.zeros((K.shape[0], 0))
    H = R.T @ (M @ R)
    s, U = np.linalg.eigh(0.5 * (H + H.T))
    ok = s > 1e-12 * max(s.max(), 0.0)
    if not ok.any():
        return np.zeros((K.shape[0], 0))
    B = R @ (U[:, ok] / np.sqrt(s[ok]))                    # M-orthonormal
    G = B.T @ (K @ B)
    mu, V = np.linalg.eigh(0.5 * (G + G.T))
    dK, dM = K.diagonal(), M.diagonal()
    pos = (dM > 0) & (dK > 0)
    scale = float(np.median(dK[pos] / dM[pos])) if pos.any() else 1.0
    return B @ V[:, mu < rtol * scale]


def solve_eigen(K, M, n: int, *, sigma: float = DEFAULT_SIGMA, backend=None, tol=1e-10,
                rigid=None):
    """Lowest ``n`` eigenpairs of ``K x = lambda M x`` (sparse, symmetric).

    Parameters
    ----------
    K, M : sparse matrices, shape (ndof, ndof)
    n : int
    sigma : float
        Shift of the shift-invert Lanczos iteration, below the lowest eigenvalue.
    backend : str, optional
        Sparse factorization backend.
    tol : float
        ARPACK relative tolerance of the Ritz vectors (0: machine precision).  Eigenvalue
        errors go with its square: 1e-10 gives them to round-off with ~15 % fewer solves
        than 0 (measured on a 154k-DOF solid block, 20 modes).
    rigid : ndarray, shape (ndof, r), optional
        M-orthonormal basis of known zero-energy modes (``K @ rigid ~ 0``, e.g. from
        :func:`zero_energy_basis`).  They are returned first and deflated from the
        Lanczos iteration: with a free structure, ``K - sigma M`` is so ill-conditioned
        (``-sigma`` against the largest eigenvalue) that the amplified rigid-body
        components of each solve otherwise swamp the elastic ones, which costs accuracy
        and iterations.

    Returns
    -------
    lam : ndarray, shape (n,)
        Ascending eigenvalues.
    X : ndarray, shape (ndof, n)
        Eigenvectors with ``X^T M X = I``.
    """
    ndof = K.shape[0]
    if n >= ndof - 1 or ndof < 60:
        # small problem: dense solve
        import scipy.linalg as sla

        Kd = K.toarray() if sp.issparse(K) else np.asarray(K)
        Md = M.toarray() if sp.issparse(M) else np.asarray(M)
        if n > ndof:
            raise InputError(f"asked for {n} modes but the model has only {ndof} free DOF")
        # M may be singular (massless DOF): solve M x = mu (K - sigma M) x, whose
        # B-matrix is positive definite, and map back with lambda = sigma + 1/mu
        A = Kd - sigma * Md
        try:
            mu, X = sla.eigh(Md, A, subset_by_index=[ndof - n, ndof - 1])
        except np.linalg.LinAlgError:
            raise ModelError(
                "K - sigma M is not positive definite: the shift is not below the lowest "
                "eigenvalue, or DOF have neither stiffness nor mass (check materials, "
                "densities and supports)") from None
        lam = sigma + 1.0 / mu[::-1]
        X = X[:, ::-1]
        mm = np.einsum("ij,ij->j", X, Md @ X)
        return lam, X / np.sqrt(np.abs(mm))
    K = sp.csr_matrix(K)
    M = sp.csr_matrix(M)
    R = np.zeros((ndof, 0)) if rigid is None else np.asarray(rigid, dtype=float)
    r = R.shape[1]
    lam_r = np.einsum("ij,ij->j", R, K @ R)
    if n <= r:
        order = np.argsort(lam_r)[:n]
        return lam_r[order], R[:, order]
    A = (K - sigma * M).tocsr()
    try:
        fac = factorize(A, backend=backend)
    except ModelError as exc:
        raise ModelError(
            f"{exc}. The stiffness cannot be factorized even after the shift: look for "
            "zero-stiffness DOF, mechanisms, or elements with zero modulus"
        ) from None
    k = n - r
    if r:
        MR = M @ R

        def op(b):
            x = fac.solve(b)
            return x - R @ (MR.T @ x)        # M-orthogonal projection off span(R)

        OPinv = spla.LinearOperator((ndof, ndof), matvec=op, matmat=op, dtype=float)
    else:
        OPinv = fac.as_operator()
    v0 = np.random.default_rng(12345).uniform(-1.0, 1.0, ndof)
    if r:
        v0 -= R @ (MR.T @ v0)
    ncv = min(ndof - r, max(2 * k + 1, k + 20))
    lam, X = spla.eigsh(K, k=k, M=M, sigma=sigma, which="LM", OPinv=OPinv, ncv=ncv,
                        tol=tol, v0=v0)
    order = np.argsort(lam)
    lam, X = lam[order], X[:, order]
    # normalize to unit modal mass (eigsh already does, up to round-off)
    mm = np.einsum("ij,ij->j", X, M @ X)
    X = X / np.sqrt(np.abs(mm))
    if r:
        lam = np.concatenate([lam_r, lam])
        X = np.hstack([R, X])
        order = np.argsort(lam, kind="stable")
        lam, X = lam[order], X[:, order]
    return lam, X


def _direction_basis(fe: FEModel, keep: np.ndarray, directions) -> sp.csr_matrix:
    """Orthonormal basis Z (len(keep), m) of the kept coordinates in which every
    ``(node, group, d)`` row of ``directions`` has zero displacement (group 0) or
    rotation (group 1) along ``d``."""
    import scipy.linalg as sla

    d = np.asarray(directions, dtype=float).reshape(-1, 5)
    dpn = fe.dofs_per_node
    groups: dict = {}
    for row in d:
        groups.setdefault((int(row[0]), int(row[1])), []).append(row[2:])
    replaced = np.zeros(len(keep), dtype=bool)
    rows, cols, vals = [], [], []
    m = 0
    for (node, g), dirs in groups.items():
        if 3 * g + 3 > dpn:
            raise InputError(f"a rotation constraint at node index {node} in a model without "
                             "rotational DOF")
        c3 = fe.independent_of_dof[node * dpn + 3 * g + np.arange(3)]
        pos = np.searchsorted(keep, c3)
        if (c3 < 0).any() or (pos >= len(keep)).any() or (keep[np.minimum(
                pos, len(keep) - 1)] != c3).any():
            where = fe.mesh.describe_node(node) if fe.mesh else f"node index {node}"
            raise InputError(f"directional constraint at {where}: its DOF are fixed, tied by "
                             "a rigid link or carry no stiffness")
        B = sla.null_space(np.array(dirs), rcond=1e-10)        # (3, r) allowed directions
        replaced[pos] = True
        for j in range(B.shape[1]):
            rows += pos.tolist()
            cols += [m] * 3
            vals += B[:, j].tolist()
            m += 1
    same = np.flatnonzero(~replaced)
    rows += same.tolist()
    cols += list(range(m, m + len(same)))
    vals += [1.0] * len(same)
    return sp.csr_matrix((vals, (rows, cols)), shape=(len(keep), m + len(same)))


def eigenmodes(fe: FEModel, n: int, fixed_dofs=None, *, sigma: float = DEFAULT_SIGMA,
               backend: str | None = None, deflate_rigid: bool = True, directions=None):
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
    deflate_rigid : bool
        Find the rigid-body motions the supports leave free (geometric rigid modes that
        ``K`` does not strain) and deflate them from the Lanczos iteration (see
        :func:`solve_eigen`); they are returned as the first modes.  Zero-energy modes
        that are not rigid-body motions (mechanisms, hourglass modes) are still found
        by the iteration.
    directions : array_like, shape (m, 5), optional
        Directional constraints, rows ``(node index, group, dx, dy, dz)``: the node's
        translation (group 0) or rotation (group 1) along ``d`` is held at zero (e.g. a
        Nastran SPC on a component of a cylindrical displacement system).  Applied exactly,
        by an orthonormal change of the node's coordinates.

    Returns
    -------
    frequencies_hz : ndarray, shape (n,)
        Ascending natural frequencies in Hz (rigid-body modes ~0).
    shapes : ndarray, shape (n_dof, n)
        Mass-normalized mode shapes over all DOF (node-major numbering).

    Warns
    -----
    MechanismWarning
        When more modes lie below :data:`~flexpipe.fem.mechanism.ZERO_RATIO` times the
        first elastic frequency than the supports leave rigid-body motions free (6 for a
        free body): a mechanism.  The message names the file, the count, the nodes the
        extra motion moves most and the likely cause (e.g. ``--thickness``).

    Raises
    ------
    ModelError
        When the model has no mass (:func:`check_mass`).
    """
    if not isinstance(n, (int, np.integer)) or n < 1:
        raise InputError(f"n must be a positive integer, got {n!r}")
    Kr, Mr = fe.Kr, fe.Mr
    check_mass(fe)
    keep = np.arange(Kr.shape[0])
    R = rigid_body_modes(fe) if deflate_rigid else None
    if fixed_dofs is not None and len(np.atleast_1d(fixed_dofs)):
        cols = _fixed_columns(fe, fixed_dofs)
        keep = np.setdiff1d(keep, cols)
        Kr = Kr[keep][:, keep]
        Mr = Mr[keep][:, keep]
        if R is not None and len(cols):
            # rigid motions that leave every fixed DOF at rest
            import scipy.linalg as sla

            R = R @ sla.null_space(R[cols], rcond=1e-10)
    Z = None
    if directions is not None and len(np.atleast_1d(directions)):
        Z = _direction_basis(fe, keep, directions)
        Kr = sp.csr_matrix(Z.T @ Kr @ Z)
        Mr = sp.csr_matrix(Z.T @ Mr @ Z)
    if n > Kr.shape[0]:
        raise InputError(f"asked for {n} modes but the model has only {Kr.shape[0]} free DOF")
    Rk = None if R is None else (R[keep] if Z is None else Z.T @ R[keep])
    rigid = zero_energy_basis(Kr, Mr, Rk) if Rk is not None else None
    lam, X = solve_eigen(Kr, Mr, n, sigma=sigma, backend=backend, rigid=rigid)
    Q = np.zeros((fe.T.shape[1], n))
    Q[keep] = X if Z is None else Z @ X
    shapes = fe.expand(Q)
    freqs = np.sqrt(np.clip(lam, 0.0, None)) / (2 * np.pi)
    supported = Kr.shape[0] < fe.Kr.shape[0] or Z is not None
    n_expected = rigid.shape[1] if rigid is not None else (0 if supported else 6)
    n_expected += 6 * (n_parts(fe) - 1)   # allow_disconnected: each part moves freely

    def extra_motion(r):   # zero modes M-orthogonal to the free rigid-body motions
        C = extra_directions(None if rigid is None else Mr @ rigid, X[:, :r])
        return shapes[:, :r] @ C

    text = zero_mode_warning(fe, freqs, n_expected, supported=supported,
                             extra_motion=extra_motion, scale_hz=element_scale_hz(fe))
    if text:
        warnings.warn(MechanismWarning(text), stacklevel=2)
    return freqs, shapes


def check_mass(fe: FEModel) -> None:
    """Refuse a model without any mass (every density and point mass zero).

    Raises
    ------
    ModelError
        Naming the mesh file and the likely cause (a MAT1 without RHO).
    """
    where = f"{fe.mesh.source}: " if fe.mesh is not None and fe.mesh.source else ""
    if not (fe.Mr.diagonal() > 0).any():
        raise ModelError(f"{where}the model has no mass (every density and point mass is "
                         "zero, e.g. MAT1 without RHO, or --rho 0); give densities to "
                         "compute modes")
