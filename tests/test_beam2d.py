"""Planar Euler-Bernoulli beam elements against closed-form beam theory."""

import numpy as np
import pytest
import scipy.linalg as sla

from flexpipe.errors import InputError
from flexpipe.fem.beam2d import assemble_beam, element_matrices, rigid_body_modes, uniform_nodes

# roots of cos(bL) cosh(bL) = 1 (free-free) and = -1 (clamped-free), e.g. Blevins Table 8-1
FREE_FREE = np.array([4.73004074, 7.85320462, 10.9956079, 14.1371655])
CLAMPED_FREE = np.array([1.87510407, 4.69409113, 7.85475744])


def _freqs(beam, fixed=()):
    keep = np.setdiff1d(np.arange(beam.n_dof), fixed)
    K = beam.K.toarray()[np.ix_(keep, keep)]
    M = beam.M.toarray()[np.ix_(keep, keep)]
    return np.sqrt(np.clip(sla.eigh(K, M, eigvals_only=True), 0, None))


def test_free_free_frequencies_converge_to_euler_bernoulli():
    L, EI, mu = 4.0, 3.0e5, 150.0
    beam = assemble_beam(uniform_nodes(L, 40), EI, mu)
    w = _freqs(beam)
    assert np.all(np.abs(w[:2]) < 1e-4 * w[2])  # two rigid-body modes
    exact = FREE_FREE**2 / L**2 * np.sqrt(EI / mu)
    np.testing.assert_allclose(w[2:6], exact, rtol=2e-5)


def test_cantilever_frequencies_and_upper_bound():
    L, EI, mu = 2.0, 1.0e4, 3.0
    exact = CLAMPED_FREE**2 / L**2 * np.sqrt(EI / mu)
    coarse = _freqs(assemble_beam(uniform_nodes(L, 4), EI, mu), fixed=(0, 1))[:3]
    fine = _freqs(assemble_beam(uniform_nodes(L, 32), EI, mu), fixed=(0, 1))[:3]
    np.testing.assert_allclose(fine, exact, rtol=1e-5)
    assert np.all(coarse >= exact * (1 - 1e-12))  # consistent mass: Rayleigh-Ritz bound
    assert np.all(coarse - exact >= fine - exact)


def test_tip_load_deflection_exact_on_stepped_beam():
    # two segments EI1 on [0, a], EI2 on [a, L]; tip load P: unit-load integral
    a, L, EI1, EI2, P = 1.2, 3.0, 2.0e5, 5.0e4, 1000.0
    x = np.r_[np.linspace(0, a, 3), np.linspace(a, L, 5)[1:]]
    EI = np.where(x[:-1] < a - 1e-12, EI1, EI2)
    beam = assemble_beam(x, EI, 10.0)
    free = np.arange(2, beam.n_dof)
    f = np.zeros(beam.n_dof)
    f[beam.w_dof(len(x) - 1)] = P
    u = np.linalg.solve(beam.K.toarray()[np.ix_(free, free)], f[free])
    # delta = int_0^L P (L - s)^2 / EI(s) ds
    exact = P * (((L**3 - (L - a) ** 3) / 3) / EI1 + ((L - a) ** 3 / 3) / EI2)
    assert u[beam.w_dof(len(x) - 1) - 2] == pytest.approx(exact, rel=1e-12)


def test_mass_matrix_rigid_body_inertia_and_stiffness_null_space():
    x = np.array([0.0, 0.5, 1.7, 2.0, 3.1])
    mu = np.array([10.0, 20.0, 5.0, 8.0])
    beam = assemble_beam(x, 1e5, mu)
    Phi = rigid_body_modes(x)
    Mr = Phi.T @ beam.M @ Phi
    h = np.diff(x)
    mass = np.sum(mu * h)
    first = np.sum(mu * (x[1:] ** 2 - x[:-1] ** 2) / 2)
    second = np.sum(mu * (x[1:] ** 3 - x[:-1] ** 3) / 3)
    np.testing.assert_allclose(Mr, [[mass, first], [first, second]], rtol=1e-12)
    assert beam.mass == pytest.approx(mass)
    assert np.abs(beam.K @ Phi).max() < 1e-9 * abs(beam.K).max()


def test_element_matrices_vectorized_and_symmetric():
    h = np.array([0.3, 1.0, 2.5])
    Ke, Me = element_matrices(h, np.array([1.0, 2.0, 3.0]), 4.0)
    assert Ke.shape == Me.shape == (3, 4, 4)
    np.testing.assert_allclose(Ke, np.swapaxes(Ke, 1, 2))
    np.testing.assert_allclose(Me, np.swapaxes(Me, 1, 2))
    # one element alone: 12 EI / h^3 translational stiffness, mass mu h in translation
    np.testing.assert_allclose(Ke[:, 0, 0], 12 * np.array([1.0, 2.0, 3.0]) / h**3)
    ones = np.array([1.0, 0.0, 1.0, 0.0])
    np.testing.assert_allclose(np.einsum("i,eij,j->e", ones, Me, ones), 4.0 * h)


@pytest.mark.parametrize(
    "x, EI, mu",
    [([0.0], 1.0, 1.0), ([0.0, 1.0, 1.0], 1.0, 1.0), ([0.0, 1.0], -1.0, 1.0),
     ([0.0, 1.0, 2.0], [1.0, 0.0], 1.0), ([0.0, 1.0, 2.0], 1.0, [1.0, 2.0, 3.0])],
)
def test_bad_beam_input_raises_input_error(x, EI, mu):
    with pytest.raises(InputError):
        assemble_beam(x, EI, mu)
