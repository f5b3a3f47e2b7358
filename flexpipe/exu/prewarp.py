"""Frequency-matched modal inertia for Exudyn's generalized-alpha step (issue 10).

A lightly damped elastic mode integrated with a fixed step ``h`` rings at a shifted
frequency: generalized-alpha lengthens the period by about ``(omega h)^2 / 12`` and adds
algorithmic damping.  Over the ``1 / (zeta omega)`` decay time of a 2 %-damped body mode
that phase error accumulates, so hub forces fed through the body modes differ from the
converged solution by tens of percent at h = 2 ms even though every mode below 100 Hz is
resolved with ten or more steps per period (measured on a single mode under broadband
forcing: 34 % at 25 Hz, 100 % at 50 Hz; the car: 27 % on ``hub_rl_x``).

The remedy, known as pre-warping, fits the discrete scheme to the continuous model mode by
mode: each elastic coordinate's modal mass ``m`` and damping ``c`` are replaced by the
values ``m'``, ``c'`` for which the generalized-alpha recurrence at step ``h`` and spectral
radius ``rho`` has exactly the eigenvalues ``exp(s h)`` of the continuous mode,
``s = -zeta omega +- i omega sqrt(1 - zeta^2)``.  The modal stiffness is left alone, so the
static flexibility of the body at every mount is exact.  As ``h -> 0`` the corrections
vanish (``m' -> m``, ``c' -> c``): the model converges to the same continuous body, the
step error of the modes is removed.

Critically damped or overdamped modes (the Adams/Flex default above 1 kHz) do not ring and
are left as they are.  Where the match would need ``c' < 0`` only the frequency is
matched, with ``c' = 0``: at h = 2 ms and spectral radius 0.5 a 2 % mode above about
87 Hz, a 10 % mode above about 165 Hz; at the defaults (h = 1.25 ms, spectral radius 0.7)
a 2 % mode above about 242 Hz (302 Hz at 1 ms), while every 10 % mode the step can reach
is matched (:func:`prewarp_modes` on a 1 Hz grid, 2026-12-02 and 2026-12-04); modes whose
frequency the step cannot reach at all (near its Nyquist frequency: from 319 Hz at
1.25 ms, 398 Hz at 1 ms) are left as they are.

The recurrence is Exudyn's generalized-alpha (Arnold and Brüls 2007, the form Exudyn
implements): ``alpha_m = (2 rho - 1) / (rho + 1)``, ``alpha_f = rho / (rho + 1)``,
``gamma = 1/2 - alpha_m + alpha_f``, ``beta = (gamma + 1/2)^2 / 4``.
``tests/test_prewarp.py`` checks it against Exudyn on a one-coordinate system.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import root

__all__ = ["alpha_parameters", "discrete_mode", "prewarp_modes"]


def alpha_parameters(spectral_radius: float):
    """``(alpha_m, alpha_f, gamma, beta)`` of generalized-alpha for ``spectral_radius``."""
    rho = float(spectral_radius)
    if not 0.0 <= rho <= 1.0:
        raise ValueError(f"spectral_radius must be in [0, 1], got {spectral_radius!r}")
    am = (2.0 * rho - 1.0) / (rho + 1.0)
    af = rho / (rho + 1.0)
    gamma = 0.5 - am + af
    return am, af, gamma, 0.25 * (gamma + 0.5) ** 2


def _amplification(omega, zeta, h, rho):
    """Step matrix of ``q'' + 2 zeta omega q' + omega^2 q = 0`` on the state (q, q', q'', a)
    (the mass scales out of the free motion)."""
    am, af, gamma, beta = alpha_parameters(rho)
    k = omega * omega
    c = 2.0 * zeta * omega
    # (1 - am) a1 + am a0 = (1 - af) q''1 + af q''0,  q''1 = -c v1 - k q1,
    # q1 = q + h v + h^2 ((1/2 - beta) a + beta a1),  v1 = v + h ((1 - gamma) a + gamma a1)
    lhs = (1.0 - am) + (1.0 - af) * (c * h * gamma + k * h * h * beta)
    r = np.array([-(1.0 - af) * k, -(1.0 - af) * (c + k * h), af,
                  -(1.0 - af) * (c * h * (1.0 - gamma) + k * h * h * (0.5 - beta)) - am]) / lhs
    q1 = np.array([1.0, h, 0.0, h * h * (0.5 - beta)]) + h * h * beta * r
    v1 = np.array([0.0, 1.0, 0.0, h * (1.0 - gamma)]) + h * gamma * r
    return np.array([q1, v1, -c * v1 - k * q1, r])


def discrete_mode(omega: float, zeta: float, *, h: float, spectral_radius: float):
    """Frequency (rad/s) and damping ratio with which the step rings a mode.

    ``omega`` (rad/s) and ``zeta`` describe the continuous mode; the result is read from
    the principal eigenvalue pair ``exp(s h)`` of the one-step map.
    """
    lam = np.linalg.eigvals(_amplification(float(omega), float(zeta), float(h),
                                           float(spectral_radius)))
    lam = lam[np.abs(lam.imag) > 0] if np.any(np.abs(lam.imag) > 0) else lam
    target = np.exp(1j * omega * np.sqrt(max(1.0 - zeta * zeta, 0.0)) * h)
    s = np.log(lam[np.argmin(np.abs(lam - target))]) / h
    w = abs(s)
    return float(w), float(-s.real / w) if w > 0 else 0.0


def prewarp_modes(omega, zeta, *, h: float, spectral_radius: float):
    """Modal mass factors and damping ratios that make the step ring every mode exactly.

    Parameters
    ----------
    omega : (m,) array_like
        Continuous natural frequencies of the elastic modes, rad/s.
    zeta : (m,) array_like
        Their damping ratios.
    h : float
        Time step, s.
    spectral_radius : float
        Generalized-alpha spectral radius at infinity.

    Returns
    -------
    mass_factor : (m,) ndarray
        ``m' / m``: the step with modal mass ``m'`` (stiffness unchanged) rings at ``omega``.
    zeta_prime : (m,) ndarray
        Damping ratio of the modified mode (``c' = 2 zeta' sqrt(k m')``) with which the
        step's total damping equals ``zeta``.
    matched : (m,) ndarray of int
        2: frequency and damping matched; 1: no match with ``c' >= 0`` exists, the
        frequency is matched with ``c' = 0`` (the step's algorithmic damping, larger than
        ``zeta``, remains); 0: not even the frequency can be reached (the mode is too
        close to the step's Nyquist frequency), ``m`` and ``c`` kept.
    """
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    zeta = np.broadcast_to(np.asarray(zeta, dtype=float), omega.shape)
    if h <= 0:
        raise ValueError(f"h must be > 0, got {h!r}")
    factor = np.ones_like(omega)
    zp = zeta.copy()
    matched = np.zeros(omega.shape, dtype=int)
    for i, (w, z) in enumerate(zip(omega, zeta, strict=True)):
        if w <= 0 or w * h > 2.5 or z >= 1.0:  # beyond reach, or no ringing to match
            continue

        def residual(p, w=w, z=z):
            wd, zd = discrete_mode(w * np.exp(p[0]), p[1], h=h, spectral_radius=spectral_radius)
            return [np.log(wd / w), zd - z]

        sol = root(residual, [0.0, z], method="hybr")
        if not sol.success or sol.x[1] < 0.0 or np.max(np.abs(residual(sol.x))) > 1e-9:
            # no match with c' >= 0: the mode rings at its frequency, undamped but for the
            # step's own damping (at least zeta)
            sol = root(lambda p, w=w: [residual([p[0], 0.0], w=w, z=0.0)[0]], [0.0])
            if not sol.success or abs(residual([sol.x[0], 0.0], w=w, z=0.0)[0]) > 1e-9:
                continue
            sol.x = np.array([sol.x[0], 0.0])
        factor[i] = np.exp(-2.0 * sol.x[0])  # m' = k / omega'^2
        zp[i] = sol.x[1]
        matched[i] = 1 if sol.x[1] == 0.0 else 2
    return factor, zp, matched
