"""Matrix-level component mode synthesis on Euler-Bernoulli beams (closed-form element
matrices written out here, references from full dense eigen-solves and static solves)."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp

from flexpipe.errors import InputError, ModelError
from flexpipe.reduction.cms import (
    DependentColumnsWarning,
    craig_bampton_basis,
    modal_truncation_basis,
    orthonormalize,
    residual_flexibility_basis,
)


def planar_beam(n_el=10, L=3.0, EI=2.0e6, rhoA=100.0):
    """Free-free planar beam, DOF (w, theta) per node, consistent mass."""
    le = L / n_el
    k = EI / le**3 * np.array([[12, 6 * le, -12, 6 * le],
                               [6 * le, 4 * le**2, -6 * le, 2 * le**2],
                               [-12, -6 * le, 12, -6 * le],
                               [6 * le, 2 * le**2, -6 * le, 4 * le**2]])
    m = rhoA * le / 420 * np.array([[156, 22 * le, 54, -13 * le],
                                    [22 * le, 4 * le**2, 13 * le, -3 * le**2],
                                    [54, 13 * le, 156, -22 * le],
                                    [-13 * le, -3 * le**2, -22 * le, 4 * le**2]])
    n = 2 * (n_el + 1)
    K = np.zeros((n, n))
    M = np.zeros((n, n))
    for e in range(n_el):
        s = slice(2 * e, 2 * e + 4)
        K[s, s] += k
        M[s, s] += m
    return M, K


def full_hz(M, K):
    lam = sla.eigh(K, M, eigvals_only=True)
    return np.sqrt(np.clip(lam, 0, None)) / (2 * np.pi)


WF, WR = 2 * 2, 2 * 8  # heave DOF of nodes 2 and 8: the two suspension mounts
WM = 2 * 5  # heave DOF of node 5: a payload (driver seat) load point


def test_half_car_residual_flexibility_has_six_columns_and_ritz_bounds():
    M, K = planar_beam()
    Psi = residual_flexibility_basis(M, K, [WF, WR], n_normal=2)
    assert Psi.shape == (22, 6)  # 2 rigid + 2 normal + 2 residual
    _, omega = orthonormalize(M, K, Psi)
    f_red = omega / (2 * np.pi)
    f_full = full_hz(M, K)
    # two rigid modes (heave and pitch) at zero, relative to the first elastic one
    assert np.all(f_red[:2] < 1e-6 * f_full[2])
    # Rayleigh-Ritz: every reduced frequency bounds the full one of the same index from above
    assert np.all(f_red[2:] >= f_full[2:6] * (1 - 1e-10))
    # kept free-interface modes are exact; the residual modes only stiffen what follows
    np.testing.assert_allclose(f_red[2:4], f_full[2:4], rtol=1e-9)
    # closed form free-free beam: omega_1 = (4.7300 / L)^2 sqrt(EI / rhoA)
    f1 = (4.730041 / 3.0) ** 2 * np.sqrt(2.0e6 / 100.0) / (2 * np.pi)
    assert f_full[2] == pytest.approx(f1, rel=2e-3)


def _spring_supported(K, k_f=2e5, k_r=3e5):
    Kc = K.copy()
    Kc[WF, WF] += k_f
    Kc[WR, WR] += k_r
    return Kc


@pytest.mark.parametrize("method", ["residual-flexibility", "craig-bampton"])
def test_static_deflection_under_boundary_loads_is_exact(method):
    M, K = planar_beam()
    if method == "craig-bampton":
        Psi = craig_bampton_basis(M, K, [WF, WR, WM], 2)
    else:
        Psi = residual_flexibility_basis(M, K, [WF, WR, WM], n_normal=2)
    Kc = _spring_supported(K)  # the body on its suspension springs
    F = np.zeros(22)
    F[WF], F[WR], F[WM] = -3000.0, 1200.0, -800.0
    x_full = np.linalg.solve(Kc, F)
    q = np.linalg.solve(Psi.T @ Kc @ Psi, Psi.T @ F)
    np.testing.assert_allclose(Psi @ q, x_full, rtol=0, atol=1e-10 * np.abs(x_full).max())


def test_residual_flexibility_beats_truncation_at_same_size():
    M, K = planar_beam()
    Kc = _spring_supported(K)
    F = np.zeros(22)
    F[WM] = -1000.0
    x_full = np.linalg.solve(Kc, F)
    errs = {}
    for name, Psi in [("rf", residual_flexibility_basis(M, K, [WF, WR, WM], n_normal=2)),
                      ("mt", modal_truncation_basis(M, K, 7))]:
        q = np.linalg.solve(Psi.T @ Kc @ Psi, Psi.T @ F)
        errs[name] = np.linalg.norm(Psi @ q - x_full) / np.linalg.norm(x_full)
    assert errs["rf"] < 1e-10
    assert errs["mt"] > 1e-4


def test_attachment_modes_are_mass_orthogonal_to_kept_modes():
    M, K = planar_beam()
    Psi = residual_flexibility_basis(M, K, [WF, WR], n_normal=2)
    cross = Psi[:, :4].T @ M @ Psi[:, 4:]
    assert np.abs(cross).max() < 1e-10 * np.abs(Psi[:, 4:].T @ M @ Psi[:, 4:]).max() ** 0.5


def test_sparse_path_matches_dense_reference():
    M, K = planar_beam(n_el=210, L=30.0)  # 422 DOF: sparse Lanczos + sparse factor
    n = K.shape[0]
    Ms, Ks = sp.csr_matrix(M), sp.csr_matrix(K)
    bnd = [2 * 40, 2 * 150]
    f_full = full_hz(M, K)
    for Psi in (residual_flexibility_basis(Ms, Ks, bnd, n_normal=4),
                craig_bampton_basis(Ms, Ks, bnd, 6)):
        _, omega = orthonormalize(Ms, Ks, Psi)
        f = omega / (2 * np.pi)
        # Ritz upper bounds; the dense LAPACK reference carries ~eps * lambda_max / lambda
        # ~ 1e-7 relative error at the lowest modes of this slender beam
        assert np.all(f[2:] >= f_full[2:len(f)] * (1 - 1e-6))
        np.testing.assert_allclose(f[2:5], f_full[2:5], rtol=5e-3)
    Psi = residual_flexibility_basis(Ms, Ks, bnd, n_normal=4)
    F = np.zeros(n)
    F[bnd[0]] = 1.0
    Kc = K.copy()
    Kc[bnd[0], bnd[0]] += 1e6
    Kc[bnd[1], bnd[1]] += 1e6
    x = np.linalg.solve(Kc, F)
    q = np.linalg.solve(Psi.T @ Kc @ Psi, Psi.T @ F)
    np.testing.assert_allclose(Psi @ q, x, atol=1e-8 * np.abs(x).max())


def test_orthonormalize_drops_dependent_columns():
    M, K = planar_beam()
    Psi = modal_truncation_basis(M, K, 4)
    Psi = np.hstack([Psi, Psi[:, 2:3] * 2.0 + Psi[:, 3:4]])
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        P, omega = orthonormalize(M, K, Psi)
    assert P.shape[1] == 4
    assert any(issubclass(w.category, DependentColumnsWarning) for w in rec)
    np.testing.assert_allclose(P.T @ M @ P, np.eye(4), atol=1e-10)
    np.testing.assert_allclose(P.T @ K @ P, np.diag(omega**2), atol=1e-6 * omega.max() ** 2)


def test_bad_input_and_mechanism():
    M, K = planar_beam()
    with pytest.raises(InputError, match="fixed-interface modes requested"):
        craig_bampton_basis(M, K, [WF, WR], 100)
    with pytest.raises(InputError, match="boundary_dofs"):
        craig_bampton_basis(M, K, [99], 1)
    # one support DOF cannot hold a free beam: K_ii singular (pitch mechanism)
    with pytest.raises(ModelError, match="K_ii"):
        craig_bampton_basis(M, K, [WF], 1)
    # four unconnected beams: 8 zero-frequency modes
    M4 = sla.block_diag(*[M] * 4)
    K4 = sla.block_diag(*[K] * 4)
    with pytest.raises(ModelError, match="mechanism|disconnected"):
        residual_flexibility_basis(M4, K4, [WF], n_normal=2)
