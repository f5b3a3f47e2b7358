"""Linear ride spectra: closed form, harmonic balance and Floquet multipliers."""

import tomllib
from pathlib import Path

import numpy as np
import pytest
import scipy.linalg as sla
from test_halfcar_model import rigid_half_car

from flexpipe.halfcar import build_model
from flexpipe.halfcar.elements import Nonlinearity
from flexpipe.halfcar.hb import HarmonicBalance
from flexpipe.halfcar.linear import linear_spectrum

DATA = Path(__file__).resolve().parents[1] / "cars" / "halfcar_paper.toml"
FREQ = np.linspace(0.5, 25.0, 300)


@pytest.fixture(scope="module")
def spectra():
    return {v: linear_spectrum(build_model(v), FREQ)
            for v in ("complete", "reduced", "truncated", "rigid")}


def _rel_err(a, b):
    return np.max(np.abs(a / b - 1.0))


def test_rigid_closed_form_matches_hand_built_receptance(spectra):
    raw = tomllib.loads(DATA.read_text())
    M, C, K, x_att, c_rear, k_t = rigid_half_car(raw)
    s0 = raw["road"]["amplitude_m"]
    lam = raw["road"]["reference_speed_km_per_h"] / 3.6 / raw["road"]["reference_frequency_Hz"]
    w = 2 * np.pi * FREQ
    tau = (x_att[1] - x_att[0]) / (FREQ * lam)
    acc = []
    for wi, ti in zip(w, tau, strict=True):
        S = -1j * s0 * np.array([1.0, np.exp(-1j * wi * ti)])
        Q = np.linalg.solve(K - wi**2 * M + 1j * wi * C, np.r_[0, 0, k_t * S])
        acc.append(abs(-(wi**2) * (Q[0] + c_rear * Q[1])))
    np.testing.assert_allclose(spectra["rigid"].acc_A, acc, rtol=1e-9)


def test_reduced_within_two_percent_and_truncated_rigid_worse(spectra):
    c = spectra["complete"]
    err = {v: max(_rel_err(spectra[v].acc_A, c.acc_A),
                  _rel_err(spectra[v].travel, c.travel),
                  _rel_err(spectra[v].tire_force, c.tire_force))
           for v in ("reduced", "truncated", "rigid")}
    assert err["reduced"] < 0.02
    assert err["truncated"] > 10 * err["reduced"]
    assert err["rigid"] > 10 * err["truncated"]


def test_harmonic_balance_of_linear_laws_equals_closed_form():
    # the laws are linear, but HB keeps only part of them in the linear reference, so
    # Newton must recover the rest through the AFT loop
    m = build_model("reduced")
    hb = HarmonicBalance(m, Nonlinearity(), c_ref=0.4 * m.c_lin, k_ref=0.6 * m.k_t)
    assert hb.active == [0, 1, 2, 3]
    ref = linear_spectrum(m, [2.0, 10.3, 21.0])
    for i, f in enumerate([2.0, 10.3, 21.0]):
        sol = hb.solve(2 * np.pi * f)
        assert sol.iterations >= 1
        assert abs(sol.acc_A[1]) == pytest.approx(ref.acc_A[i], rel=1e-8)
        np.testing.assert_allclose(np.abs(sol.Z[:2, 1]), ref.travel[:, i], rtol=1e-8)
        np.testing.assert_allclose(np.abs(sol.tire_force[:, 1]), ref.tire_force[:, i],
                                   rtol=1e-8)
        assert np.abs(sol.Z[:, 2:]).max() < 1e-9 * np.abs(sol.Z[:, 1]).max()


@pytest.mark.parametrize("variant", ["reduced", "complete"])
def test_floquet_multipliers_of_linear_solution_are_exp_lambda_T(variant):
    m = build_model(variant)
    hb = HarmonicBalance(m, Nonlinearity(), c_ref=0.5 * m.c_lin, k_ref=0.7 * m.k_t)
    omega = 2 * np.pi * 7.3
    sol = hb.with_stability(hb.solve(omega), n_segments=16)
    n = m.n_dof
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(m.M, m.K), -np.linalg.solve(m.M, m.C)]])
    expected = np.exp(sla.eigvals(A) * 2 * np.pi / omega)
    mu = sol.multipliers
    assert mu.size == 2 * n
    dist = np.abs(expected[:, None] - mu[None, :])
    assert dist.min(axis=1).max() < 1e-6
    assert dist.min(axis=0).max() < 1e-6
    assert np.abs(mu).max() < 1.0


def test_bad_solver_settings_raise_input_error():
    from flexpipe.errors import InputError

    with pytest.raises(InputError, match="samples"):
        HarmonicBalance(build_model("rigid"), Nonlinearity(), harmonics=10, samples=15)
    with pytest.raises(InputError, match="dual_rate"):
        Nonlinearity(damper="bilinear")
