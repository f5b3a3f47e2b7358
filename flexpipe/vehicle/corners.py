"""The four corners as arrays: statics (wheel loads, spring preloads, design position) and
the suspension force law, vectorized over the corners (order ``fl, fr, rl, rr``).

Sign convention: ``jounce`` is the travel of the wheel carrier towards the body along the
body z axis from the design position (m, positive in compression); the suspension force
``F`` is what the spring, damper, stops and anti-roll bar push the body up with at the
hardpoint (N) and the wheel carrier down with.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError
from flexpipe.vehicle.spec import CORNERS, Car

GRAVITY = 9.81
#: tolerance between the design wheel-centre height and the tyre's static loaded radius, m
RIDE_HEIGHT_TOL = 0.003


@dataclass(frozen=True)
class CornerArrays:
    """Corner data as (4,) / (4, 3) arrays in CORNERS order."""

    hardpoint: np.ndarray
    wheel_center: np.ndarray
    k: np.ndarray
    c_jounce: np.ndarray
    c_rebound: np.ndarray
    bump_clearance: np.ndarray
    bump_rate: np.ndarray
    rebound_clearance: np.ndarray
    rebound_rate: np.ndarray
    m_unsprung: np.ndarray
    J_unsprung: np.ndarray  # (4, 3, 3)
    radius: np.ndarray
    spin_inertia: np.ndarray
    arb: np.ndarray  # (2,) front, rear anti-roll-bar rates
    preload: np.ndarray  # static spring force at the design position

    @property
    def n(self) -> int:
        """Number of corners (4)."""
        return len(self.k)

    def force(self, jounce, rate, *, anti_roll: bool = True) -> np.ndarray:
        """Suspension force (4,) for jounce (m) and jounce rate (m/s) (without the
        anti-roll bars for ``anti_roll=False``)."""
        jounce = np.asarray(jounce, dtype=float)
        rate = np.asarray(rate, dtype=float)
        F = self.preload + self.k * jounce
        F = F + np.where(rate > 0.0, self.c_jounce, self.c_rebound) * rate
        F = F + self.bump_rate * np.maximum(jounce - self.bump_clearance, 0.0)
        F = F - self.rebound_rate * np.maximum(-jounce - self.rebound_clearance, 0.0)
        if not anti_roll:
            return F
        d_front = jounce[0] - jounce[1]
        d_rear = jounce[2] - jounce[3]
        arb = np.array([self.arb[0] * d_front, -self.arb[0] * d_front,
                        self.arb[1] * d_rear, -self.arb[1] * d_rear])
        return F + arb


    def stiffness(self, jounce) -> np.ndarray:
        """Tangent stiffness (4,) of spring and stops (no anti-roll bar) at ``jounce``, N/m."""
        jounce = np.asarray(jounce, dtype=float)
        return (self.k + self.bump_rate * (jounce > self.bump_clearance)
                + self.rebound_rate * (-jounce > self.rebound_clearance))


def static_wheel_loads(car: Car, body_mass: float, body_cg, *, g: float = GRAVITY,
                       point_masses=None):
    """Vertical ground reactions (4,) of the car at rest on flat ground, N.

    Whole-car equilibrium (vertical force, pitch and roll moments about the wheel
    contacts) plus zero warp (equal diagonal sums ``N_fl + N_rr = N_fr + N_rl``), the
    statically indeterminate fourth condition of a car whose corners are set to the same
    design height.
    """
    W = np.array([c.wheel_center for c in car.corners])
    if point_masses is None:  # unsprung masses at the wheel centres
        point_masses = [(c.unsprung_mass, w) for c, w in zip(car.corners, W, strict=True)]
    m = np.array([pm[0] for pm in point_masses])
    P = np.array([pm[1] for pm in point_masses], dtype=float)
    M = body_mass + m.sum()
    G = (body_mass * np.asarray(body_cg, dtype=float) + (m[:, None] * P).sum(axis=0)) / M
    A = np.vstack([np.ones(4), W[:, 0], W[:, 1], [1.0, -1.0, -1.0, 1.0]])
    b = M * g * np.array([1.0, G[0], G[1], 0.0])
    N = np.linalg.solve(A, b)
    if np.any(N <= 0):
        bad = CORNERS[int(np.argmin(N))]
        raise InputError(f"the car would tip over: static load on corner {bad} is "
                         f"{N.min():.0f} N; the centre of mass {tuple(np.round(G, 3))} m lies "
                         "outside the wheel base", file=car.file, key=f"corners.{bad}")
    return N


def corner_arrays(car: Car, body_mass: float, body_cg, *, tires=None,
                  g: float = GRAVITY) -> CornerArrays:
    """Corner arrays with spring preloads for the design position.

    Parameters
    ----------
    car : Car
    body_mass, body_cg
        Sprung (body) mass (kg) and centre of mass (body coordinates, m).
    tires : sequence of TireModel, optional
        When given, the design wheel-centre heights are checked against the tyres' loaded
        radius under the static wheel loads (ride height consistency).
    """
    cs = car.corners
    N = static_wheel_loads(car, body_mass, body_cg, g=g)
    mu = np.array([c.unsprung_mass for c in cs])
    given = np.array([np.nan if c.spring_preload is None else c.spring_preload for c in cs])
    preload = np.where(np.isnan(given), N - mu * g, given)
    if tires is not None:  # every corner that is off, in one message
        off = []
        for c, tire, Nz in zip(cs, tires, N, strict=True):
            z_static = static_loaded_radius(tire, Nz)
            if abs(c.wheel_center[2] - z_static) > RIDE_HEIGHT_TOL:
                off.append((c, z_static, Nz))
        if off:
            def key(c):   # where the car file gives the design wheel centre
                if car.suspension is None:
                    return f"corners.{c.name}.wheel_center_m"
                axle = "front" if c.name.startswith("f") else "rear"
                return f"suspension.{axle}.hardpoints_m.wheel_center (+ location_m)"

            what = "; ".join(
                f"{key(c)} z = {c.wheel_center[2]:.4f} m, the tyre's "
                f"static loaded radius under the static wheel load {Nz:.0f} N is "
                f"{z_static:.4f} m (tyre {c.tire.name}"
                f"{'' if c.tire_pressure is None else f' at {c.tire_pressure:g} Pa'}): "
                f"set z to {z_static:.4f}" for c, z_static, Nz in off)
            raise InputError(
                f"{what}; the design position must be the ride height at rest (within "
                f"{RIDE_HEIGHT_TOL * 1e3:g} mm)", file=car.file,
                key=key(off[0][0]).split(" ")[0])
    arb = np.array([car.anti_roll_bars.get("front", 0.0), car.anti_roll_bars.get("rear", 0.0)])
    return CornerArrays(
        hardpoint=np.array([c.hardpoint for c in cs]),
        wheel_center=np.array([c.wheel_center for c in cs]),
        k=np.array([c.spring_rate for c in cs]),
        c_jounce=np.array([c.damper_jounce for c in cs]),
        c_rebound=np.array([c.damper_rebound for c in cs]),
        bump_clearance=np.array([c.bump_stop_clearance for c in cs]),
        bump_rate=np.array([c.bump_stop_rate for c in cs]),
        rebound_clearance=np.array([c.rebound_stop_clearance for c in cs]),
        rebound_rate=np.array([c.rebound_stop_rate for c in cs]),
        m_unsprung=mu, J_unsprung=np.array([c.unsprung_inertia for c in cs]),
        radius=np.array([c.wheel_radius for c in cs]),
        spin_inertia=np.array([c.spin_inertia for c in cs]),
        arb=arb, preload=preload)


def static_loaded_radius(tire, load: float) -> float:
    """Wheel-centre height above flat ground of ``tire`` carrying ``load`` N (no camber)."""
    from scipy.optimize import brentq

    R0 = float(tire.unloaded_radius)

    def residual(d):
        return float(tire.vertical.force(d, 0.0)) - load

    hi = 0.02
    while residual(hi) < 0 and hi < R0:
        hi *= 2
    return R0 - brentq(residual, 0.0, min(hi, R0))


def ackermann_angles(delta: float, *, wheelbase: float, track: float, steered) -> np.ndarray:
    """Road-wheel angles (4,) of an Ackermann steering for the bicycle angle ``delta`` (rad):
    the steered wheels' axes meet the rear axle's line at the bicycle's turn centre."""
    out = np.zeros(4)
    if abs(delta) < 1e-9:
        return out
    L, half = wheelbase, 0.5 * track
    tan_d = math.tan(delta)
    left = math.atan(L * tan_d / (L - half * tan_d))
    right = math.atan(L * tan_d / (L + half * tan_d))
    for i, on in enumerate(steered):
        if on:
            out[i] = left if CORNERS[i][1] == "l" else right
    return out


def road_wheel_angles(R_body: np.ndarray, wheel_R: np.ndarray) -> np.ndarray:
    """Road-wheel angles (4,) (rad, positive left): the heading of each wheel's plane in
    the body's x-y plane, from the wheels' rotation matrices ``wheel_R`` (4, 3, 3; column
    1 the spin axis) and the body's ``R_body`` (3, 3).  Steer, toe and compliance steer
    together."""
    s = wheel_R[:, :, 1] @ R_body  # the spin axes in body axes
    return np.arctan2(-s[:, 0], s[:, 1])
