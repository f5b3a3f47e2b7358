"""Direct time integration of the half car on a road, event-accurate at law kinks.

Between two kinks of the corner laws (damper velocity reversal, loss or recovery of
tire contact) every law is smooth.  Piecewise-linear laws (linear or dual-rate dampers,
linear tires with or without contact) are propagated in closed form piece by piece
(:mod:`flexpipe.halfcar.pwlinear`, the default).  With Duffing tires the pieces are
integrated by :func:`scipy.integrate.solve_ivp` (Radau IIA with the exact Jacobian by
default) with the branches frozen; each kink is located as a terminal event, the branch
is switched and the integration restarts from the event state.  A tiny hysteresis
(``EVENT_EPS`` in velocity, ``EVENT_EPS_F`` in force, see
:mod:`flexpipe.halfcar.elements`) keeps a system at rest from chattering between
branches.

The road: the front wheel is at ``z = v t``, the rear one at ``z = v t - wheelbase``.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from flexpipe.errors import InputError, SolverError
from flexpipe.halfcar._blas import single_threaded_blas
from flexpipe.halfcar.elements import EVENT_EPS, EVENT_EPS_F, CornerLaws, Nonlinearity
from flexpipe.halfcar.model import HalfCarModel
from flexpipe.halfcar.pwlinear import EventCounts, PiecewiseLinear


@dataclass(frozen=True)
class Road:
    """Vertical road profile ``s(z)``.

    Parameters
    ----------
    amplitude_m, wavelength_m : float
    cycles : int or None
        ``None``: endless harmonic road ``s0 sin(2 pi z / lambda)``; otherwise the
        isolated irregularity ``s0 sin(2 pi z / lambda)`` for ``0 <= z < cycles lambda``
        and a flat road elsewhere.
    """

    amplitude_m: float
    wavelength_m: float
    cycles: int | None = None

    def __post_init__(self):
        if not self.wavelength_m > 0:
            raise InputError(f"road wavelength must be > 0 m, got {self.wavelength_m}",
                             key="wavelength_m")

    def height(self, z):
        """Road height at abscissa ``z`` (m)."""
        z = np.asarray(z, dtype=float)
        s = self.amplitude_m * np.sin(2.0 * np.pi * z / self.wavelength_m)
        if self.cycles is None:
            return s
        return np.where((z >= 0.0) & (z < self.cycles * self.wavelength_m), s, 0.0)


@dataclass(frozen=True)
class Transient:
    """Time history of a direct integration.

    Attributes
    ----------
    t : ndarray, shape (nt,)
    q, qd : ndarray, shape (nt, n)
        Coordinates and velocities.
    acc_A : ndarray, shape (nt,)
        Absolute vertical acceleration at point A, m/s^2.
    travel, tire_force : ndarray, shape (2, nt)
        Suspension extension (m) and dynamic tire force (N), front and rear.
    damper_state : ndarray of int, shape (2, nt)
        +1 rebound (extension) branch, -1 jounce (compression) branch.
    n_events : int
        Number of law switches located (dampers and tire contact).
    cpu_s : float
        Process time spent integrating.
    contact_state : ndarray of bool, shape (2, nt)
        Whether each tire touches the road (always True without unilateral contact).
    n_lift_offs : ndarray of int, shape (2,)
        Number of times each wheel left the road (located events; 0 without contact).
    n_damper_switches : int
        Number of damper-branch switches among ``n_events``.
    static_tire_force : ndarray, shape (2,)
        Static tire loads, N: the total load is ``static_tire_force + tire_force``.
    """

    t: np.ndarray
    q: np.ndarray
    qd: np.ndarray
    acc_A: np.ndarray
    travel: np.ndarray
    tire_force: np.ndarray
    damper_state: np.ndarray
    n_events: int
    cpu_s: float
    contact_state: np.ndarray
    n_lift_offs: np.ndarray
    n_damper_switches: int
    static_tire_force: np.ndarray

    @property
    def tire_load(self) -> np.ndarray:
        """Total tire loads (static + dynamic), N, shape (2, nt); never < 0 with contact."""
        return self.static_tire_force[:, None] + self.tire_force


class _Pieces:
    """Frozen-branch right-hand sides, Jacobians and event functions."""

    def __init__(self, model: HalfCarModel, nl: Nonlinearity, road: Road, speed: float):
        self.m, self.laws, self.road, self.v = model, CornerLaws(model, nl), road, speed
        self.n = n = model.n_dof
        self.Minv = np.linalg.inv(model.M)
        self.lag = np.array([0.0, model.wheelbase_m])
        self.MinvK = self.Minv @ model.K
        self.MinvE = self.Minv @ model.E
        self.duffing = bool(np.any(self.laws.k_t3))
        self.A_cache: dict = {}
        self.dual = nl.damper == "dual_rate"
        self.contact = nl.contact
        self._zero = np.zeros((n, n))

    def road_active(self, t):
        """Whether each wheel is on the sinusoidal part of the road at time ``t``."""
        z = self.v * t - self.lag
        if self.road.cycles is None:
            return np.ones(2, dtype=bool)
        return (z >= 0.0) & (z < self.road.cycles * self.road.wavelength_m)

    def input_breaks(self):
        """Times at which a wheel enters or leaves the isolated irregularity."""
        if self.road.cycles is None:
            return np.zeros(0)
        span = self.road.cycles * self.road.wavelength_m
        return np.concatenate([self.lag / self.v, (self.lag + span) / self.v])

    def damper_c(self, branch):
        return np.where(branch > 0, self.laws.c_plus, self.laws.c_minus)

    def road_s(self, t):
        return self.road.height(self.v * np.asarray(t, dtype=float)[..., None] - self.lag)

    def tire_extra(self, d, contact):
        """Tire force beyond the linear ``k_t d`` kept in K, per branch."""
        k3, F0, kt = self.laws.k_t3, self.laws.F0, self.laws.k_t
        return np.where(contact, k3 * d**3, -F0 - kt * d)

    def A_linear(self, branch, contact):
        key = (tuple(branch), tuple(contact))
        if key not in self.A_cache:
            n, m = self.n, self.m
            C = m.damping_matrix(self.damper_c(branch))
            K = m.K - (m.E * np.where(contact, 0.0, m.k_t)) @ m.E.T
            A = np.zeros((2 * n, 2 * n))
            A[:n, n:] = np.eye(n)
            A[n:, :n] = -self.Minv @ K
            A[n:, n:] = -self.Minv @ C
            self.A_cache[key] = A
        return self.A_cache[key]

    def accel(self, t, q, qd, branch, contact):
        """``q''`` for states as rows (vectorized over times)."""
        m = self.m
        d = self.road_s(t) - q @ m.E
        v = qd @ m.D
        force = (-(q @ m.K.T) - qd @ m.C_body.T
                 - (v * self.damper_c(branch)) @ m.D.T
                 + (m.k_t * self.road_s(t) + self.tire_extra(d, contact)) @ m.E.T)
        return force @ self.Minv.T

    def functions(self, branch, contact):
        n, m = self.n, self.m

        def rhs(t, x):
            q, qd = x[:n], x[n:]
            return np.concatenate([qd, self.accel(t, q, qd, branch, contact)])

        A = self.A_linear(branch, contact)
        if self.duffing:
            def jac(t, x):
                d = self.road_s(t) - x[:n] @ m.E
                slope = np.where(contact, 3.0 * self.laws.k_t3 * d**2, 0.0)
                J = A.copy()
                J[n:, :n] -= (self.MinvE * slope) @ m.E.T
                return J
        else:
            jac = A
        events = []
        for j in range(2):
            if self.dual:
                def ev(t, x, j=j, b=branch[j]):
                    return x[n:] @ m.D[:, j] + b * EVENT_EPS
                ev.terminal, ev.direction = True, -float(branch[j])
                events.append((ev, "damper", j))
            if self.contact:
                def evc(t, x, j=j, c=contact[j]):
                    d = self.road_s(t)[j] - x[:n] @ m.E[:, j]
                    F = self.laws.F0[j] + self.laws.k_t[j] * d + self.laws.k_t3[j] * d**3
                    return F + (EVENT_EPS_F if c else -EVENT_EPS_F)
                evc.terminal, evc.direction = True, (-1.0 if contact[j] else 1.0)
                events.append((evc, "contact", j))
        return rhs, jac, events


def simulate(model: HalfCarModel, nl: Nonlinearity, road: Road, speed_m_per_s: float,
             t_end: float, *, t_eval=None, x0=None, method: str | None = None,
             rtol: float = 1e-8, atol: float = 1e-12, max_events: int = 100_000) -> Transient:
    """Integrate the half car driving over ``road`` at constant speed.

    Parameters
    ----------
    model : HalfCarModel
    nl : Nonlinearity
    road : Road
    speed_m_per_s : float
    t_end : float
        End time, s (the front wheel is at ``z = 0`` at ``t = 0``).
    t_eval : array_like, optional
        Output times (default: 2000 points).
    x0 : array_like, shape (2 n,), optional
        Initial state ``[q, q']`` (default: static equilibrium at rest).
    method : str, optional
        ``"exact"``: closed-form piecewise-linear propagation
        (:mod:`flexpipe.halfcar.pwlinear`; dampers and contact, no Duffing term);
        otherwise a :func:`scipy.integrate.solve_ivp` method (implicit ones get the
        exact Jacobian).  Default: ``"exact"`` when possible, else ``"Radau"``.
    rtol, atol : float
    max_events : int
        Guard against chattering.

    Returns
    -------
    Transient

    Raises
    ------
    SolverError
        Integration failure or more than ``max_events`` law switches.
    """
    if not (speed_m_per_s > 0 and t_end > 0):
        raise InputError(f"speed and t_end must be > 0, got {speed_m_per_s}, {t_end}")
    P = _Pieces(model, nl, road, float(speed_m_per_s))
    n = model.n_dof
    t_eval = np.linspace(0.0, t_end, 2001) if t_eval is None else np.asarray(t_eval, float)
    x = np.zeros(2 * n) if x0 is None else np.array(x0, dtype=float)
    branch = np.ones(2, dtype=int)
    branch[x[n:] @ model.D < 0] = -1
    contact = np.ones(2, dtype=bool)
    if nl.contact:  # a wheel may start off the road
        d0 = P.road_s(0.0) - x[:n] @ model.E
        contact = P.laws.F0 + P.laws.k_t * d0 + P.laws.k_t3 * d0**3 > 0.0
    if method is None:
        method = "Radau" if P.duffing else "exact"
    cpu0 = time.process_time()
    with single_threaded_blas():
        if method == "exact":
            if P.duffing:
                raise InputError("method='exact' needs piecewise-linear laws; Duffing tires "
                                 "need an ODE method such as 'Radau' or 'DOP853'",
                                 key="method")
            t, y, br, ct, counts = PiecewiseLinear(P).run(
                t_eval, t_end, x, branch, contact, P.input_breaks(), max_events)
        else:
            t, y, br, ct, counts = _run_ivp(P, t_eval, t_end, x, branch, contact, method,
                                            rtol, atol, max_events)
    cpu = time.process_time() - cpu0
    # drop duplicates at restart times (keep the later, post-switch sample)
    order = np.argsort(t, kind="stable")
    t, y, br, ct = t[order], y[order], br[order], ct[order]
    last = np.r_[t[1:] != t[:-1], True]
    t, y, br, ct = t[last], y[last], br[last], ct[last]
    q, qd = y[:, :n], y[:, n:]
    acc = np.empty_like(q)
    for b in np.unique(np.column_stack([br, ct]), axis=0):
        sel = np.all(np.column_stack([br, ct]) == b, axis=1)
        acc[sel] = P.accel(t[sel], q[sel], qd[sel], b[:2], b[2:].astype(bool))
    d = P.road_s(t) - q @ model.E
    tire = model.k_t * d + P.tire_extra(d, ct)
    return Transient(t=t, q=q, qd=qd, acc_A=acc @ model.a_A, travel=(q @ model.D).T,
                     tire_force=tire.T, damper_state=br.T, n_events=counts.total, cpu_s=cpu,
                     contact_state=ct.T, n_lift_offs=counts.lift_offs.copy(),
                     n_damper_switches=counts.damper,
                     static_tire_force=np.array(model.static_tire_force, dtype=float))



def _run_ivp(P, t_eval, t_end, x, branch, contact, method, rtol, atol, max_events):
    """Event-driven restarts of :func:`scipy.integrate.solve_ivp` (any law)."""
    n = P.n
    branch, contact = branch.copy(), contact.copy()
    t0, counts = 0.0, EventCounts()
    T, Y, B, Cs = [], [], [], []
    while True:
        rhs, jac, events = P.functions(branch, contact)
        te = t_eval[(t_eval >= t0) & (t_eval <= t_end)]
        kw = {"jac": jac} if method in ("Radau", "BDF") else {}
        sol = solve_ivp(rhs, (t0, t_end), x, method=method, t_eval=te, rtol=rtol,
                        atol=atol, events=[e[0] for e in events] or None, **kw)
        if sol.status < 0:
            raise SolverError(f"time integration failed: {sol.message}", time=t0)
        ts = np.asarray(sol.t, dtype=float).ravel()
        T.append(ts)
        Y.append(np.asarray(sol.y, dtype=float).reshape(2 * n, ts.size).T)
        B.append(np.broadcast_to(branch, (ts.size, 2)).copy())
        Cs.append(np.broadcast_to(contact, (ts.size, 2)).copy())
        if sol.status != 1:
            break
        hits = [(te_[0], k) for k, te_ in enumerate(sol.t_events) if te_.size]
        t_hit, k = min(hits)
        x = sol.y_events[k][0].copy()
        _, kind, j = events[k]
        if kind == "damper":
            branch[j] = -branch[j]
            counts.damper_switch()
        else:
            counts.contact_change(j, lost=bool(contact[j]))
            contact[j] = not contact[j]
        t0 = t_hit
        if counts.total > max_events:
            raise SolverError(f"more than {max_events} law switches: chattering?",
                              time=t0)
    return (np.concatenate(T), np.concatenate(Y), np.concatenate(B), np.concatenate(Cs),
            counts)
