"""Small (dense-path) eigen solves with massless DOF.

Reference: static condensation of the massless DOF is exact for them, so the
eigenvalues of the condensed problem are the true ones.
"""

import numpy as np
import scipy.linalg as sla

from flexpipe.fem.modes import solve_eigen


def test_dense_eigen_with_singular_mass_matches_static_condensation():
    rng = np.random.default_rng(0)
    A = rng.normal(size=(30, 30))
    K = A @ A.T + 30 * np.eye(30)
    M = np.diag(np.r_[np.linspace(1.0, 3.0, 20), np.zeros(10)])
    lam, X = solve_eigen(K, M, 5)
    Kc = K[:20, :20] - K[:20, 20:] @ np.linalg.solve(K[20:, 20:], K[20:, :20])
    ref = sla.eigh(Kc, M[:20, :20], eigvals_only=True)[:5]
    np.testing.assert_allclose(lam, ref, rtol=1e-10)
    np.testing.assert_allclose(X.T @ M @ X, np.eye(5), atol=1e-10)
