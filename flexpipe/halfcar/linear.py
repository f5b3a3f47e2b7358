"""Closed-form frequency response of the linear half car on a harmonic road.

The road ``s(z) = s0 sin(2 pi z / lambda)`` crossed at speed ``v`` excites the front
tire with ``s_f(t) = s0 sin(omega t)``, ``omega = 2 pi v / lambda``, and the rear one
with the same profile delayed by ``tau = wheelbase / v``.  With complex amplitudes
(``x(t) = Re X e^{i omega t}``) the steady state is

``Q = (K - omega^2 M + i omega C)^-1 E k_t S``,  ``S = -i s0 [1, e^{-i omega tau}]``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexpipe.halfcar.model import HalfCarModel


@dataclass(frozen=True)
class Spectrum:
    """Ride response spectrum over a speed sweep (one model, one set of laws).

    Attributes
    ----------
    label : str
    freq_Hz, speed_m_per_s : ndarray, shape (nf,)
        Forcing frequency and the horizontal speed giving it.
    acc_A : ndarray, shape (nf,)
        Maximum absolute vertical acceleration at point A over a period, m/s^2.
    travel : ndarray, shape (2, nf)
        Maximum absolute suspension deflection (front, rear), m.
    tire_force : ndarray, shape (2, nf)
        Maximum absolute dynamic tire force (front, rear), N.
    floquet_max : ndarray, shape (nf,)
        Largest Floquet multiplier modulus (spectral radius of the monodromy matrix);
        NaN when stability was not computed.
    stable : ndarray of bool, shape (nf,)
        ``floquet_max < 1`` (False where stability was not computed).
    iterations : ndarray of int, shape (nf,)
        Newton iterations per point (0 for the closed form).
    """

    label: str
    freq_Hz: np.ndarray
    speed_m_per_s: np.ndarray
    acc_A: np.ndarray
    travel: np.ndarray
    tire_force: np.ndarray
    floquet_max: np.ndarray
    stable: np.ndarray
    iterations: np.ndarray


def road_amplitudes(model: HalfCarModel, omega, *, amplitude=None, wavelength=None):
    """Complex amplitudes ``S`` (nf, 2) of the front and rear road inputs."""
    p = model.params
    s0 = p.road_amplitude_m if amplitude is None else amplitude
    lam = p.road_wavelength_m if wavelength is None else wavelength
    omega = np.atleast_1d(np.asarray(omega, dtype=float))
    speed = omega * lam / (2.0 * np.pi)
    tau = model.wheelbase_m / speed
    return -1j * s0 * np.stack([np.ones_like(omega), np.exp(-1j * omega * tau)], axis=1)


def frequency_response(model: HalfCarModel, freq_Hz, *, C=None, amplitude=None,
                       wavelength=None) -> np.ndarray:
    """Complex steady-state amplitudes of all coordinates, shape (nf, n)."""
    omega = 2.0 * np.pi * np.atleast_1d(np.asarray(freq_Hz, dtype=float))
    C = model.C if C is None else C
    Z = (model.K[None] - omega[:, None, None] ** 2 * model.M[None]
         + 1j * omega[:, None, None] * C[None])
    S = road_amplitudes(model, omega, amplitude=amplitude, wavelength=wavelength)
    F = (S * model.k_t) @ model.E.T  # (nf, n)
    return np.linalg.solve(Z, F[..., None])[..., 0]


def linear_spectrum(model: HalfCarModel, freq_Hz, *, label=None, amplitude=None,
                    wavelength=None) -> Spectrum:
    """Ride spectrum of the linear model (``zeta`` dampers) from the closed form.

    Every quantity is harmonic, so its maximum over a period is the modulus of its
    complex amplitude.  The solution is asymptotically stable when every eigenvalue of
    the first-order state matrix has a negative real part; ``floquet_max`` holds
    ``exp(max Re(lambda) T)``.
    """
    f = np.atleast_1d(np.asarray(freq_Hz, dtype=float))
    omega = 2.0 * np.pi * f
    p = model.params
    lam = p.road_wavelength_m if wavelength is None else wavelength
    Q = frequency_response(model, f, amplitude=amplitude, wavelength=wavelength)
    S = road_amplitudes(model, omega, amplitude=amplitude, wavelength=wavelength)
    acc = -(omega**2) * (Q @ model.a_A)
    travel = Q @ model.D
    tire = model.k_t * (S - Q @ model.E)
    n = model.n_dof
    A = np.block([[np.zeros((n, n)), np.eye(n)],
                  [-np.linalg.solve(model.M, model.K), -np.linalg.solve(model.M, model.C)]])
    re_max = np.linalg.eigvals(A).real.max()
    return Spectrum(
        label=label or f"{model.variant}, linear",
        freq_Hz=f, speed_m_per_s=f * lam, acc_A=np.abs(acc), travel=np.abs(travel).T,
        tire_force=np.abs(tire).T, floquet_max=np.exp(re_max * 2.0 * np.pi / omega),
        stable=np.full(f.shape, re_max < 0.0), iterations=np.zeros(f.shape, dtype=int),
    )
