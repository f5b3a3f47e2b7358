"""Floquet multipliers of periodic solutions: monodromy of the variational equations.

Along a periodic solution the variational equation ``dX/dt = A(t) X`` has

``A(t) = [[0, I], [-M^-1 (K_ref + E diag(dg_t/dd) E^T), -M^-1 (C_ref + D diag(dg_d/dv) D^T)]]``,

with the slopes of the corner-law deviations evaluated on the solution.  The period is
split at every kink of the laws (damper velocity reversal, loss or recovery of tire
contact), located to machine precision on the Fourier series of the solution, and
optionally into uniform sub-intervals.  On each piece ``A`` is frozen at the piece's
midpoint and propagated exactly with the matrix exponential, so

* piecewise-linear laws (dual-rate dampers, contact with linear tires) give the exact
  monodromy matrix; their vector field is continuous at the kinks, so no saltation
  (jump) matrix is needed;
* smooth nonlinear slopes (Duffing tires) give the exponential-midpoint (second-order
  Magnus) approximation.

The Floquet multipliers are the eigenvalues of the monodromy matrix; the periodic
solution is asymptotically stable when all of them lie inside the unit circle.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from flexpipe.halfcar.elements import CornerLaws

#: uniform sub-intervals per period when the slopes vary smoothly (Duffing tires)
SMOOTH_SEGMENTS = 64
#: grid used to bracket the kinks before bisection
KINK_GRID = 512


def eval_series(Z: np.ndarray, omega: float, t: np.ndarray) -> np.ndarray:
    """Evaluate ``Re sum_k Z[..., k] exp(i k omega t)`` at times ``t``."""
    k = np.arange(Z.shape[-1])
    return (Z @ np.exp(1j * np.outer(k, omega * np.asarray(t, dtype=float)))).real


def kink_times(laws: CornerLaws, Zy: np.ndarray, Zd: np.ndarray, omega: float,
               *, n_grid: int = KINK_GRID, max_iter: int = 60) -> np.ndarray:
    """Sorted times in ``(0, T)`` where a corner law switches branch.

    Sign changes of the kink functions are bracketed on a grid of ``n_grid`` points
    and refined by the Illinois (modified regula falsi) method to machine precision.

    Parameters
    ----------
    laws : CornerLaws
    Zy, Zd : ndarray, shape (2, H + 1)
        Complex Fourier coefficients of the suspension extensions and tire compressions.
    omega : float
        Fundamental circular frequency, rad/s.
    """
    T = 2.0 * np.pi / omega
    Zv = Zy * (1j * omega * np.arange(Zy.shape[-1]))

    def kinks(t):
        return laws.kink_functions(eval_series(Zv, omega, t), eval_series(Zd, omega, t))

    t = np.linspace(0.0, T, n_grid + 1)
    s = kinks(t)
    if s.shape[0] == 0:
        return np.zeros(0)
    row, j = np.nonzero(np.signbit(s[:, :-1]) != np.signbit(s[:, 1:]))
    if row.size == 0:
        return np.zeros(0)
    a, b = t[j].copy(), t[j + 1].copy()
    fa, fb = s[row, j].copy(), s[row, j + 1].copy()
    idx = np.arange(row.size)
    side = np.zeros(row.size, dtype=int)
    for _ in range(max_iter):
        c = np.where(fb != fa, (a * fb - b * fa) / np.where(fb != fa, fb - fa, 1.0),
                     0.5 * (a + b))
        fc = kinks(c)[row, idx]
        left = np.signbit(fc) == np.signbit(fa)  # root in [c, b]
        # Illinois: halve the stale end's value when the same end is kept twice
        fb = np.where(left & (side == 1), 0.5 * fb, fb)
        fa = np.where(~left & (side == -1), 0.5 * fa, fa)
        side = np.where(left, 1, -1)
        a, fa = np.where(left, c, a), np.where(left, fc, fa)
        b, fb = np.where(left, b, c), np.where(left, fb, fc)
        if np.all((b - a <= 8 * np.finfo(float).eps * T) | (fc == 0.0)):
            break
    return np.sort(np.where(fa == 0.0, a, np.where(fb == 0.0, b, 0.5 * (a + b))))


def _state_matrices(Minv, K_eff, C_eff):
    n = Minv.shape[0]
    A = np.zeros((K_eff.shape[0], 2 * n, 2 * n))
    A[:, :n, n:] = np.eye(n)
    A[:, n:, :n] = -Minv @ K_eff
    A[:, n:, n:] = -Minv @ C_eff
    return A


def monodromy(M, K_ref, C_ref, D, E, laws: CornerLaws, Zy, Zd, omega: float, *,
              n_segments: int | None = None) -> np.ndarray:
    """Monodromy matrix of the variational equations along a periodic solution.

    Parameters
    ----------
    M, K_ref, C_ref : ndarray, shape (n, n)
        Mass and the linear reference stiffness and damping of the laws.
    D, E : ndarray, shape (n, 2)
        Suspension and wheel operators of the model.
    laws : CornerLaws
    Zy, Zd : ndarray, shape (2, H + 1)
        Fourier coefficients of suspension extensions and tire compressions.
    omega : float
        Circular frequency of the solution, rad/s.
    n_segments : int, optional
        Uniform sub-intervals per period (besides the kinks).  Default: 1 when the
        slopes are piecewise constant, :data:`SMOOTH_SEGMENTS` otherwise.

    Returns
    -------
    ndarray, shape (2 n, 2 n)
        ``Phi(T)`` with ``x(T) = Phi x(0)`` for perturbations of the state ``[q, q']``.

    Notes
    -----
    With piecewise-constant slopes each piece is propagated by ``expm(A h)``.  With
    smoothly varying tire slopes the tire part ``N(t)`` of ``A`` (stiffness only, so
    ``N^2 = 0`` and ``expm(N h) = I + N h``) is split off symmetrically (Strang):
    ``expm(A_0 h / 2) (I + N(t_mid) h) expm(A_0 h / 2)``, second order like the
    exponential midpoint rule, with one exponential per distinct step instead of one
    per segment.
    """
    T = 2.0 * np.pi / omega
    if n_segments is None:
        n_segments = 1 if laws.smooth_slopes else SMOOTH_SEGMENTS
    edges = np.union1d(np.linspace(0.0, T, n_segments + 1), kink_times(laws, Zy, Zd, omega))
    h = np.diff(edges)
    keep = h > 1e-13 * T
    h, mid = h[keep], (edges[:-1] + 0.5 * np.diff(edges))[keep]
    Zv = Zy * (1j * omega * np.arange(Zy.shape[-1]))
    _, s_d, _, s_t = laws.deviations(eval_series(Zv, omega, mid), eval_series(Zd, omega, mid))
    Minv = np.linalg.inv(M)
    C_eff = C_ref[None] + np.einsum("ij,jm,kj->mik", D, s_d, D)
    if laws.smooth_slopes:
        K_eff = K_ref[None] + np.einsum("ij,jm,kj->mik", E, s_t, E)
        steps = sla.expm(h[:, None, None] * _state_matrices(Minv, K_eff, C_eff))
    else:
        # one exponential per distinct (damper slopes, step) pair
        key = np.column_stack([s_d.T, np.round(h / T, 12) * T])
        uniq, inv = np.unique(key, axis=0, return_inverse=True)
        C_u = C_ref[None] + np.einsum("ij,mj,kj->mik", D, uniq[:, :2], D)
        A_u = _state_matrices(Minv, np.broadcast_to(K_ref, C_u.shape), C_u)
        half = sla.expm(0.5 * uniq[:, 2, None, None] * A_u)[inv.ravel()]
        n = M.shape[0]
        N_q = -np.einsum("ab,bj,jm,kj->mak", Minv, E, s_t, E)  # (m, n, n): dv/dq block
        mid_step = np.broadcast_to(np.eye(2 * n), (h.size, 2 * n, 2 * n)).copy()
        mid_step[:, n:, :n] += h[:, None, None] * N_q
        steps = half @ mid_step @ half
    Phi = steps[0]
    for S in steps[1:]:
        Phi = S @ Phi
    return Phi


def floquet_multipliers(*args, **kwargs) -> np.ndarray:
    """Eigenvalues of :func:`monodromy` (same arguments), by decreasing modulus."""
    mu = np.linalg.eigvals(monodromy(*args, **kwargs))
    return mu[np.argsort(-np.abs(mu))]
