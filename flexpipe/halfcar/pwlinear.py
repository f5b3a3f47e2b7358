"""Exact time response of the piecewise-linear half car (Natsiavas-type integration).

With linear or dual-rate dampers and linear tires (with or without unilateral contact)
the equations are linear between two switches, ``x' = A_b x + G_b u(t) + c_b``, where
the branch ``b`` fixes the damper rates and the tire contact states, and the road
inputs ``u_j(t) = s0 sin(omega t - phi_j)`` are sinusoids (or zero outside the isolated
irregularity).  On such a piece the solution is known in closed form,

``x(t) = x_p(t) + V exp(Lambda (t - t0)) V^-1 (x(t0) - x_p(t0))``,

with ``A_b = V Lambda V^-1`` and the particular solution
``x_p = Im(X e^{i omega t}) - A_b^-1 c_b``, ``X = (i omega I - A_b)^-1 G_b U``.  The
switching functions (damper velocities, total tire loads) are evaluated on a scan grid,
the first sign change is refined to machine precision on the closed form, the branch is
switched and the next piece starts from the exact state.  No time-step error arises,
whatever the stiffness of the model, and kinks are located exactly.

When a wheel has left the road the car is free to pitch about the other tire: ``A_b``
is singular (a Jordan block at zero) and has no eigenvector basis.  Such branches are
propagated with the exponential of the augmented matrix acting on
``z = [x, cos omega t, sin omega t, 1]``, which is exact for any ``A_b``.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg as sla

from flexpipe.errors import SolverError
from flexpipe.halfcar.elements import EVENT_EPS, EVENT_EPS_F

#: scan step of the switching functions, s (>= 10 samples per period of 500 Hz)
SCAN_STEP = 2e-4
#: scan blocks grow from SCAN_FIRST to SCAN_BLOCK points (short pieces stay cheap)
SCAN_FIRST, SCAN_BLOCK = 8, 512
#: eigenvector-matrix condition above which the augmented exponential is used instead
EIGEN_COND_MAX = 1e8


class EventCounts:
    """Law switches located by an integration: total, damper ones, lift-offs per wheel."""

    def __init__(self):
        self.total, self.damper = 0, 0
        self.lift_offs = np.zeros(2, dtype=int)

    def damper_switch(self) -> None:
        """Count a damper-branch switch."""
        self.total += 1
        self.damper += 1

    def contact_change(self, j: int, lost: bool) -> None:
        """Count a loss (``lost``) or recovery of contact of wheel ``j``."""
        self.total += 1
        self.lift_offs[j] += int(lost)


class PiecewiseLinear:
    """Closed-form propagator of one model with piecewise-linear corner laws.

    Parameters
    ----------
    pieces : transient._Pieces
        Model, laws, road and speed.
    """

    def __init__(self, pieces):
        self.P = pieces
        self.m = pieces.m
        self.n = pieces.n
        self.cache: dict = {}
        road = pieces.road
        self.omega = 2.0 * np.pi * pieces.v / road.wavelength_m
        self.phase = 2.0 * np.pi * pieces.lag / road.wavelength_m
        self.s0 = road.amplitude_m

    # ------------------------------------------------------------------ branches
    def branch(self, damper, contact):
        """Matrices of one branch: ``(A, G, c, eigen)``; ``eigen`` is None when unsafe."""
        key = (tuple(int(b) for b in damper), tuple(bool(c) for c in contact))
        if key not in self.cache:
            P, m, n = self.P, self.m, self.n
            A = P.A_linear(np.array(key[0]), np.array(key[1]))
            con = np.array(key[1])
            G = np.zeros((2 * n, 2))
            G[n:] = P.MinvE * np.where(con, m.k_t, 0.0)
            c = np.zeros(2 * n)
            c[n:] = P.MinvE @ np.where(con, 0.0, -P.laws.F0)
            eigen = None
            if con.all():  # both tires hold the car: A is regular
                lam, V = np.linalg.eig(A)
                if np.linalg.cond(V) < EIGEN_COND_MAX:
                    eigen = (lam, V, np.linalg.inv(V), -np.linalg.solve(A, c))
            # a wheel off the road leaves the car free to pitch about the other tire:
            # A is singular (a Jordan block at 0), handled by the augmented exponential
            self.cache[key] = (A, G, c, eigen)
        return self.cache[key]

    def piece(self, damper, contact, active, t0, x0):
        """Exact solution of one piece started from ``x0`` at ``t0``: a callable of t."""
        A, G, c, eigen = self.branch(damper, contact)
        U = self.s0 * np.exp(-1j * self.phase) * np.asarray(active, dtype=float)
        w = self.omega
        if eigen is not None:
            lam, V, Vinv, x_c = eigen
            X = np.linalg.solve(1j * w * np.eye(A.shape[0]) - A, G @ U)
            xi0 = Vinv @ (x0 - (X * np.exp(1j * w * t0)).imag - x_c)

            def states(t):
                t = np.atleast_1d(np.asarray(t, dtype=float))
                hom = (np.exp(np.outer(t - t0, lam)) * xi0) @ V.T
                return hom.real + (X[None, :] * np.exp(1j * w * t)[:, None]).imag + x_c
            return states
        # augmented state z = [x, cos wt, sin wt, 1]: z' = Ahat z, exact for any A
        m2 = A.shape[0]
        Ahat = np.zeros((m2 + 3, m2 + 3))
        Ahat[:m2, :m2] = A
        Ahat[:m2, m2] = G @ U.imag
        Ahat[:m2, m2 + 1] = G @ U.real
        Ahat[:m2, m2 + 2] = c
        Ahat[m2, m2 + 1] = -w
        Ahat[m2 + 1, m2] = w
        z0 = np.r_[x0, np.cos(w * t0), np.sin(w * t0), 1.0]

        def states(t):
            t = np.atleast_1d(np.asarray(t, dtype=float))
            E = sla.expm((t - t0)[:, None, None] * Ahat)
            return (E @ z0)[:, :m2]
        return states

    def switching(self, x, t, damper, contact):
        """Switching functions (rows: events) with the hysteresis of the ODE path."""
        m, n, P = self.m, self.n, self.P
        rows = []
        if P.dual:
            rows.append((x[:, n:] @ m.D) * damper + EVENT_EPS)  # > 0 while the branch holds
        if P.contact:
            d = P.road_s(t) - x[:, :n] @ m.E
            F = P.laws.F0 + m.k_t * d
            sign = np.where(contact, 1.0, -1.0)
            rows.append(sign * F + EVENT_EPS_F)
        if not rows:
            return np.zeros((t.size, 0))
        return np.hstack(rows)

    # ------------------------------------------------------------------ driver
    def run(self, t_eval, t_end, x0, damper, contact, input_breaks, max_events):
        """Integrate to ``t_end``; returns samples, branches and the switches
        (:class:`EventCounts`)."""
        n = self.n
        T, Y, B, C = [], [], [], []
        t0, x = 0.0, np.array(x0, dtype=float)
        damper, contact = damper.copy(), contact.copy()
        breaks = np.sort(np.asarray([b for b in input_breaks if 0.0 < b < t_end]))
        counts = EventCounts()
        while t0 < t_end:
            nxt = breaks[breaks > t0 + 1e-15]
            t_stop = min(t_end, nxt[0]) if nxt.size else t_end
            active = self.P.road_active(0.5 * (t0 + t_stop))
            states = self.piece(damper, contact, active, t0, x)
            t_hit, k_hit = None, None
            a = t0
            block = SCAN_FIRST
            while a < t_stop and t_hit is None:
                grid = np.minimum(a + SCAN_STEP * np.arange(1, block + 1), t_stop)
                block = min(2 * block, SCAN_BLOCK)
                grid = np.unique(grid)
                xs = states(grid)
                g = self.switching(xs, grid, damper, contact)
                if g.shape[1]:
                    neg = g < 0.0
                    if neg.any():
                        i, k = np.argwhere(neg)[np.argmin(np.argwhere(neg)[:, 0])]
                        lo = a if i == 0 else grid[i - 1]
                        t_hit = self._refine(states, lo, grid[i], k, damper, contact)
                        k_hit = k
                a = grid[-1]
            t_piece_end = t_hit if t_hit is not None else t_stop
            sel = (t_eval >= t0) & (t_eval <= t_piece_end)
            if sel.any():
                T.append(t_eval[sel])
                Y.append(states(t_eval[sel]))
                B.append(np.broadcast_to(damper, (int(sel.sum()), 2)).copy())
                C.append(np.broadcast_to(contact, (int(sel.sum()), 2)).copy())
            x = states(t_piece_end)[0]
            t0 = t_piece_end
            if t_hit is not None:
                n_d = 2 if self.P.dual else 0
                if k_hit < n_d:
                    damper[k_hit] = -damper[k_hit]
                    counts.damper_switch()
                else:
                    j = k_hit - n_d
                    counts.contact_change(j, lost=bool(contact[j]))
                    contact[j] = not contact[j]
                if counts.total > max_events:
                    raise SolverError(f"more than {max_events} law switches: chattering?",
                                      time=t0)
        if not T:
            return np.zeros(0), np.zeros((0, 2 * n)), np.zeros((0, 2), int), \
                np.zeros((0, 2), bool), counts
        return (np.concatenate(T), np.concatenate(Y), np.concatenate(B), np.concatenate(C),
                counts)

    def _refine(self, states, lo, hi, k, damper, contact, max_iter=100):
        """Root of switching function ``k`` in ``[lo, hi]`` (Illinois method)."""
        def g(t):
            xs = states(np.array([t]))
            return self.switching(xs, np.array([t]), damper, contact)[0, k]

        fa, fb = g(lo), g(hi)
        if fa <= 0.0:
            return lo
        side = 0
        for _ in range(max_iter):
            c = (lo * fb - hi * fa) / (fb - fa)
            fc = g(c)
            if fc > 0.0:
                lo, fa = c, fc
                if side == 1:
                    fb *= 0.5
                side = 1
            else:
                hi, fb = c, fc
                if side == -1:
                    fa *= 0.5
                side = -1
            if hi - lo <= 4.0 * np.finfo(float).eps * max(abs(hi), 1.0):
                break
        return hi
