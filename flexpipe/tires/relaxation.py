"""First-order relaxation of tyre slip (transient slip, "single contact point" model).

The standard first-order model (Pacejka, ch. 7) for the relaxed slip ``s'`` is

    sigma * ds'/dt + |Vx| * s' = w

with the relaxation length ``sigma`` (m) and the slip velocity ``w`` (m/s): ``w = -Vsx`` for
the longitudinal slip (``s' -> kappa``) and ``w = Vsy`` for the tangent of the slip angle.
Its steady state is the kinematic slip ``w/|Vx|``.  Written with the slip displacement
``u = sigma s'`` it reads ``du/dt + |Vx| u / sigma = w``: at standstill the tyre acts as a
spring (``s'`` keeps integrating ``w``) instead of the slip being undefined.

For one step of length ``dt`` with ``Vx``, ``w`` and ``sigma`` held constant the exact
solution is

    s'(t+dt) = s' e^(-a) + (w dt / sigma) (1 - e^(-a))/a,    a = |Vx| dt / sigma,

which is unconditionally stable (no overshoot for any ``dt``) and continuous at ``Vx = 0``.
"""

from __future__ import annotations

import numpy as np


def _phi(a):
    """(1 - exp(-a)) / a, with the limit 1 at a = 0 (accurate for small a)."""
    a = np.asarray(a, dtype=float)
    small = a < 1e-6
    safe = np.where(small, 1.0, a)
    return np.where(small, 1.0 - 0.5 * a, -np.expm1(-safe) / safe)


def relax(slip_state, slip_target, vx, sigma, dt):
    """Exact first-order update of a relaxed slip towards a (kinematic) target.

    Solves ``sigma ds'/dt = |vx| (target - s')`` over ``dt`` with constant inputs:
    ``s' + (target - s') (1 - exp(-|vx| dt / sigma))``.

    Parameters
    ----------
    slip_state : float or array
        Relaxed slip at the start of the step (kappa' or tan(alpha')).
    slip_target : float or array
        Kinematic (steady-state) slip.
    vx : float or array
        Longitudinal speed, m/s (its magnitude is used).
    sigma : float or array
        Relaxation length, m (> 0).
    dt : float
        Step, s.

    Returns
    -------
    ndarray or float
        Relaxed slip at the end of the step.  At ``vx = 0`` the state does not change; use
        :func:`relax_slip_velocity` for standstill.
    """
    a = np.abs(vx) * dt / np.asarray(sigma, dtype=float)
    return slip_target + (np.asarray(slip_state, dtype=float) - slip_target) * np.exp(-a)


def relax_slip_velocity(slip_state, slip_velocity, vx, sigma, dt):
    """Exact step of ``sigma ds'/dt + |vx| s' = w`` (slip-velocity form, valid at vx = 0).

    Parameters
    ----------
    slip_state : float or array
        Relaxed slip at the start of the step.
    slip_velocity : float or array
        ``w``: ``-Vsx`` (longitudinal) or ``Vsy`` (lateral), m/s.
    vx : float or array
        Longitudinal contact speed, m/s.
    sigma : float or array
        Relaxation length, m (> 0).
    dt : float
        Step, s.
    """
    sigma = np.asarray(sigma, dtype=float)
    a = np.abs(vx) * dt / sigma
    return (np.asarray(slip_state, dtype=float) * np.exp(-a)
            + np.asarray(slip_velocity, dtype=float) * dt / sigma * _phi(a))
