"""Nonlinear half car: harmonic balance against direct integration, Floquet, transients."""

import numpy as np
import pytest

from flexpipe.halfcar import build_model
from flexpipe.halfcar.elements import Nonlinearity
from flexpipe.halfcar.floquet import eval_series
from flexpipe.halfcar.hb import HarmonicBalance
from flexpipe.halfcar.linear import frequency_response
from flexpipe.halfcar.transient import Road, simulate

DUAL = Nonlinearity(damper="dual_rate")
LIFT = Nonlinearity(damper="dual_rate", contact=True)


def _road(m, cycles=None):
    p = m.params
    return Road(p.road_amplitude_m, p.road_wavelength_m, cycles)


def _hb_state(hb, sol, t=0.0):
    Q = hb.state_coefficients(sol)
    k = np.arange(Q.shape[1])
    e = np.exp(1j * k * sol.omega * t)
    return np.r_[(Q @ e).real, (Q @ (1j * k * sol.omega * e)).real]


@pytest.mark.parametrize("variant, f", [("reduced", 10.4), ("complete", 20.0)])
def test_dual_rate_periodic_solution_equals_long_time_integration(variant, f):
    m = build_model(variant)
    omega, T = 2 * np.pi * f, 1.0 / f
    sol = HarmonicBalance(m, DUAL).solve(omega)
    t_end = np.ceil(12.0 / T) * T  # from rest; transients decay ~ exp(-1.3 t)
    te = t_end - T + np.linspace(0, T, 257)
    tr = simulate(m, DUAL, _road(m), f * m.params.road_wavelength_m, t_end, t_eval=te)
    assert tr.n_events > 4 * 12.0 / T * 0.9  # both dampers switch twice per period
    y = eval_series(sol.Z[:2], omega, te)
    F = eval_series(sol.tire_force, omega, te)
    a = eval_series(sol.acc_A[None], omega, te)[0]
    assert np.abs(tr.travel - y).max() < 1e-3 * np.abs(y).max()
    assert np.abs(tr.tire_force - F).max() < 2e-3 * np.abs(F).max()
    assert np.abs(tr.acc_A).max() == pytest.approx(np.abs(a).max(), rel=5e-3)


@pytest.mark.parametrize("nl, s0", [(DUAL, None), (LIFT, 0.004)])
def test_floquet_multipliers_match_finite_difference_monodromy(nl, s0):
    m = build_model("reduced")
    f = 10.4
    hb = HarmonicBalance(m, nl, amplitude=s0)
    sol = hb.with_stability(hb.solve(2 * np.pi * f))
    x0 = _hb_state(hb, sol)
    road = Road(s0 or m.params.road_amplitude_m, m.params.road_wavelength_m)
    v, T = f * m.params.road_wavelength_m, 1.0 / f

    def flow(x):
        tr = simulate(m, nl, road, v, T, t_eval=np.array([T]), x0=x)
        return np.r_[tr.q[-1], tr.qd[-1]]

    xT = flow(x0)
    assert np.abs(xT - x0).max() < 1e-3 * np.abs(x0).max()  # HB state is periodic
    n2 = x0.size
    Phi = np.empty((n2, n2))
    for i in range(n2):
        eps = 1e-6 * max(np.abs(x0).max(), 1e-3)
        xi = x0.copy()
        xi[i] += eps
        Phi[:, i] = (flow(xi) - xT) / eps
    mu_fd = np.sort(np.abs(np.linalg.eigvals(Phi)))[::-1]
    mu = np.sort(np.abs(sol.multipliers))[::-1]
    np.testing.assert_allclose(mu[:4], mu_fd[:4], rtol=2e-3, atol=1e-6)
    assert mu[0] < 1.0


def test_tire_lift_off_periodic_solution_equals_long_time_integration():
    m = build_model("reduced")
    s0, f = 0.004, 10.4  # twice the paper amplitude: the rear wheel leaves the road
    omega, T = 2 * np.pi * f, 1.0 / f
    sol = HarmonicBalance(m, LIFT, amplitude=s0, harmonics=48, samples=384).solve(omega)
    F0 = m.static_tire_force[1]
    load = sol.sample(sol.tire_force)[1] + F0  # truncated series: ripples ~ 0.2 % of F0
    assert abs(load.min()) < 0.01 * F0 and (load < 0.01 * F0).mean() > 0.05
    t_end = np.ceil(12.0 / T) * T
    te = t_end - T + np.linspace(0, T, 257)
    tr = simulate(m, LIFT, Road(s0, m.params.road_wavelength_m), f * m.params.road_wavelength_m,
                  t_end, t_eval=te)
    y = eval_series(sol.Z[:2], omega, te)
    F = eval_series(sol.tire_force, omega, te)
    assert np.abs(tr.travel - y).max() < 1e-3 * np.abs(y).max()
    assert np.abs(tr.tire_force - F).max() < 5e-3 * np.abs(F).max()


def test_duffing_lift_off_solution_is_a_periodic_orbit_with_its_floquet_multipliers():
    # Duffing tires and unilateral contact at twice the paper amplitude (the rear wheel
    # leaves the road): the HB state must return onto itself under an independent ODE
    # solver, and finite differences of that flow must give the Floquet multipliers
    m = build_model("reduced")
    nl = Nonlinearity(damper="dual_rate", tire="duffing", contact=True)
    s0, f = 0.004, 10.4
    hb = HarmonicBalance(m, nl, amplitude=s0)
    sol = hb.with_stability(hb.solve(2 * np.pi * f), n_segments=128)
    T = 1.0 / f
    road = Road(s0, m.params.road_wavelength_m)
    x0 = _hb_state(hb, sol)

    def flow(x, te=None):
        te = np.array([T]) if te is None else te
        return simulate(m, nl, road, f * m.params.road_wavelength_m, T, t_eval=te, x0=x,
                        method="DOP853", rtol=1e-11, atol=1e-14)

    te = np.linspace(0, T, 33)
    tr = flow(x0, te)
    F = eval_series(sol.tire_force, sol.omega, te)
    assert (F[1] + m.static_tire_force[1]).min() < 0.01 * m.static_tire_force[1]  # lift-off
    # the clipped (zero-load) stretch carries the Gibbs ripple of H = 24 harmonics
    assert np.abs(tr.tire_force - F).max() < 5e-3 * np.abs(F).max()
    xT = np.r_[tr.q[-1], tr.qd[-1]]
    assert np.abs(xT - x0).max() < 1e-3 * np.abs(x0).max()
    Phi = np.empty((x0.size, x0.size))
    eps = 1e-7 * np.abs(x0).max()
    for i in range(x0.size):
        xi = x0.copy()
        xi[i] += eps
        r = flow(xi)
        Phi[:, i] = (np.r_[r.q[-1], r.qd[-1]] - xT) / eps
    mu_fd = np.sort(np.abs(np.linalg.eigvals(Phi)))[::-1]
    np.testing.assert_allclose(np.sort(np.abs(sol.multipliers))[::-1][:4], mu_fd[:4],
                               rtol=2e-3)


def test_dual_rate_mean_force_balance():
    # at steady state each corner's mean spring + damper force vanishes (the body cannot
    # drift), so the suspension settles by -mean(F_damper) / k_s ("jacking down")
    m = build_model("complete")
    hb = HarmonicBalance(m, DUAL, harmonics=48, samples=512)
    sol = hb.solve(2 * np.pi * 9.0)
    t = np.linspace(0, 1 / 9.0, 4096, endpoint=False)
    y = eval_series(sol.Z[:2], sol.omega, t)
    v = eval_series(sol.Z[:2] * (1j * sol.omega * np.arange(sol.Z.shape[1])), sol.omega, t)
    Fd = np.where(v > 0, m.c_rebound[:, None], m.c_jounce[:, None]) * v
    np.testing.assert_allclose(m.k_s * y.mean(axis=1), -Fd.mean(axis=1), rtol=1e-3)
    assert np.all(y.mean(axis=1) < 0)  # more rebound than jounce damping pulls it down


@pytest.mark.parametrize("nl, s0, t_end", [(DUAL, None, 0.8), (LIFT, 0.004, 0.5)])
def test_exact_piecewise_linear_integration_matches_ode_solver(nl, s0, t_end):
    m = build_model("reduced")
    road = Road(s0 or m.params.road_amplitude_m, m.params.road_wavelength_m,
                m.params.irregularity_cycles)
    v = 150 / 3.6 if s0 is None else 10.4 * m.params.road_wavelength_m
    te = np.linspace(0, t_end, 401)
    ex = simulate(m, nl, road, v, t_end, t_eval=te)
    ode = simulate(m, nl, road, v, t_end, t_eval=te, method="DOP853", rtol=1e-11, atol=1e-14)
    assert ex.n_events == ode.n_events > 20
    assert np.abs(ex.acc_A - ode.acc_A).max() < 1e-6 * np.abs(ode.acc_A).max()
    assert np.abs(ex.tire_force - ode.tire_force).max() < 1e-6 * np.abs(ode.tire_force).max()
    np.testing.assert_array_equal(ex.damper_state, ode.damper_state)
    if nl.contact:  # the rear wheel did leave the road
        assert (ex.tire_force[1] + m.static_tire_force[1]).min() < 1e-6


def test_linear_transient_settles_to_closed_form_response():
    m = build_model("complete")
    f = 20.0
    T = 1 / f
    t_end = np.ceil(12 / T) * T
    te = t_end - T + np.linspace(0, T, 65)
    tr = simulate(m, Nonlinearity(), _road(m), f * m.params.road_wavelength_m, t_end,
                  t_eval=te)
    Q = frequency_response(m, f)[0]
    travel = (np.exp(1j * 2 * np.pi * f * te)[:, None] * (Q @ m.D)).real.T
    assert np.abs(tr.travel - travel).max() < 1e-6 * np.abs(travel).max()
