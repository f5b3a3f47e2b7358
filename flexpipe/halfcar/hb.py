"""Periodic steady states by harmonic balance (AFT), condensed on the corner channels.

The nonlinear forces act only through four scalar channels ``z = [y_f, y_r, d_f, d_r]``
(suspension extensions, tire compressions).  Per harmonic ``k`` of the fundamental
``omega`` the linear part is exact in the frequency domain,

``Z_k = Z_lin,k + R_k G_k``,  ``R_k = O (K_ref - (k omega)^2 M + i k omega C_ref)^-1 B``,

with ``O = [D^T; -E^T]`` and ``G_k`` the Fourier coefficients of the law deviations
``g``.  Newton's method solves this for the real Fourier coefficients of the channels
whose law is nonlinear; ``G`` and its Jacobian come from the alternating
frequency/time (AFT) scheme on ``N`` samples per period.  The size of the nonlinear
problem is ``n_active (2 H + 1)`` whatever the number of model DOF, so the complete
and the reduced models cost about the same here.  Stability comes from the Floquet
multipliers of :mod:`flexpipe.halfcar.floquet`.

A sweep over speed is a natural-parameter continuation: each point starts from the
secant extrapolation of the two previous solutions; a failed step is retried with
intermediate speeds.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from tqdm import tqdm

from flexpipe.errors import InputError, SolverError
from flexpipe.halfcar._blas import single_threaded_blas
from flexpipe.halfcar.elements import CornerLaws, Nonlinearity
from flexpipe.halfcar.floquet import monodromy
from flexpipe.halfcar.linear import Spectrum, road_amplitudes
from flexpipe.halfcar.model import HalfCarModel

#: output samples per period used to take maxima of the periodic responses
OUTPUT_SAMPLES = 1024


@dataclass(frozen=True)
class PeriodicSolution:
    """A periodic steady state found by harmonic balance.

    Attributes
    ----------
    omega : float
        Fundamental circular frequency, rad/s.
    Z : ndarray, complex, shape (4, H + 1)
        Channel coefficients ``[y_f, y_r, d_f, d_r]``: ``z(t) = Re sum Z_k e^{i k omega t}``.
    acc_A : ndarray, complex, shape (H + 1,)
        Coefficients of the absolute vertical acceleration at point A.
    tire_force : ndarray, complex, shape (2, H + 1)
        Coefficients of the dynamic tire forces (front, rear).
    G : ndarray, complex, shape (4, H + 1)
        Coefficients of the law deviations ``g`` (dampers, tires).
    iterations : int
    residual : float
        Final relative residual.
    multipliers : ndarray or None
        Floquet multipliers, by decreasing modulus.
    """

    omega: float
    Z: np.ndarray
    acc_A: np.ndarray
    tire_force: np.ndarray
    G: np.ndarray
    iterations: int
    residual: float
    multipliers: np.ndarray | None = None

    @property
    def period(self) -> float:
        """Period in s."""
        return 2.0 * np.pi / self.omega

    def sample(self, coeffs, n: int = OUTPUT_SAMPLES) -> np.ndarray:
        """Values of a series at ``n`` equally spaced times over one period."""
        c = np.asarray(coeffs)
        full = np.zeros(c.shape[:-1] + (n // 2 + 1,), dtype=complex)
        full[..., : c.shape[-1]] = c * (n / 2.0)
        full[..., 0] = c[..., 0] * n
        return np.fft.irfft(full, n=n, axis=-1)


class HarmonicBalance:
    """Harmonic-balance solver of one model with given corner laws.

    Parameters
    ----------
    model : HalfCarModel
    nl : Nonlinearity
    harmonics, samples : int, optional
        ``H`` and AFT samples ``N`` (defaults from the parameter file).
    c_ref, k_ref : array_like, shape (2,), optional
        Linear reference rates (see :class:`CornerLaws`).
    amplitude, wavelength : float, optional
        Road amplitude and wavelength (defaults from the parameter file).
    """

    def __init__(self, model: HalfCarModel, nl: Nonlinearity, *, harmonics=None,
                 samples=None, c_ref=None, k_ref=None, amplitude=None, wavelength=None):
        p = model.params
        self.model, self.nl = model, nl
        self.laws = CornerLaws(model, nl, c_ref=c_ref, k_ref=k_ref)
        self.H = H = int(harmonics if harmonics is not None else p.harmonics)
        self.N = N = int(samples if samples is not None else p.time_samples)
        if H < 1 or N < 2 * H + 1:
            raise InputError(f"harmonic balance needs harmonics >= 1 and samples >= 2 H + 1 "
                             f"= {2 * H + 1}; got harmonics = {H}, samples = {N}",
                             key="samples")
        self.amplitude, self.wavelength = amplitude, wavelength
        self.K_ref = model.K + (model.E * (self.laws.k_ref - model.k_t)) @ model.E.T
        self.C_ref = model.damping_matrix(self.laws.c_ref)
        self.O = np.vstack([model.D.T, -model.E.T])
        self.k = np.arange(H + 1)
        theta = 2.0 * np.pi * np.arange(N) / N
        kt = np.outer(theta, self.k[1:])
        self.Gam = np.hstack([np.ones((N, 1)), np.cos(kt), -np.sin(kt)])  # (N, 2H+1)
        self.Gam_dot = np.hstack([np.zeros((N, 1)), -self.k[1:] * np.sin(kt),
                                  -self.k[1:] * np.cos(kt)])  # times omega
        scale = np.r_[1.0 / N, np.full(2 * H, 2.0 / N)]
        self.Proj = scale[:, None] * self.Gam.T  # samples -> real coefficients
        self.active = ([0, 1] if self.laws.damper_active else []) + \
                      ([2, 3] if self.laws.tire_active else [])

    # ------------------------------------------------------------------ packing
    def to_real(self, Zc):
        """Complex coefficients (..., H + 1) -> real ``[a_0, a_1..H, b_1..H]``."""
        return np.concatenate([Zc[..., :1].real, Zc[..., 1:].real, Zc[..., 1:].imag], axis=-1)

    def to_complex(self, U):
        """Inverse of :meth:`to_real`."""
        H = self.H
        Zc = U[..., : H + 1].astype(complex)
        Zc[..., 1:] += 1j * U[..., H + 1:]
        return Zc

    # ------------------------------------------------------------------ linear part
    def _frequency_data(self, omega):
        m, H = self.model, self.H
        kw = self.k * omega
        Zdyn = (self.K_ref[None] - kw[:, None, None] ** 2 * m.M[None]
                + 1j * kw[:, None, None] * self.C_ref[None])
        P = np.linalg.solve(Zdyn, np.broadcast_to(m.B, (H + 1,) + m.B.shape))  # (H+1, n, 4)
        R = self.O @ P  # (H+1, 4, 4)
        ra = np.einsum("i,kij->kj", m.a_A, P)  # (H+1, 4)
        S = road_amplitudes(m, omega, amplitude=self.amplitude,
                            wavelength=self.wavelength)[0]
        F = self.laws.k_ref * S
        Zlin = np.zeros((4, H + 1), dtype=complex)
        Zlin[:, 1] = R[1][:, 2:] @ F + np.r_[0.0, 0.0, S]
        acc_lin = np.zeros(H + 1, dtype=complex)
        acc_lin[1] = -(omega**2) * (ra[1, 2:] @ F)
        return R, ra, Zlin, acc_lin, S

    def _rbig(self, R):
        """Real matrix of ``G -> R G`` on the active channels."""
        H, a = self.H, self.active
        na, L = len(a), 2 * self.H + 1
        Ra = R[:, a][:, :, a]
        out = np.zeros((na, L, na, L))
        c = np.arange(na)[:, None]
        d = np.arange(na)[None, :]
        out[c, 0, d, 0] = Ra[0].real
        k = np.arange(1, H + 1)[:, None, None]
        cc, dd = c[None], d[None]
        out[cc, k, dd, k] = Ra[1:].real
        out[cc, k, dd, H + k] = -Ra[1:].imag
        out[cc, H + k, dd, k] = Ra[1:].imag
        out[cc, H + k, dd, H + k] = Ra[1:].real
        return out.reshape(na * L, na * L)

    # ------------------------------------------------------------------ AFT
    def _deviations(self, U, omega):
        """Real coefficients of g on all 4 channels and the per-sample slopes."""
        y = U[:2] @ self.Gam.T
        v = omega * (U[:2] @ self.Gam_dot.T)
        d = U[2:] @ self.Gam.T
        g_d, s_d, g_t, s_t = self.laws.deviations(v, d)
        G = np.vstack([g_d, g_t]) @ self.Proj.T
        return G, s_d, s_t, y

    def solve(self, omega: float, U0=None, *, tol: float = 1e-10,
              max_iter: int = 40) -> PeriodicSolution:
        """Periodic solution at circular frequency ``omega``.

        Parameters
        ----------
        omega : float
            rad/s.
        U0 : ndarray, shape (4, 2 H + 1), optional
            Initial real channel coefficients (default: the linear reference solution).

        Raises
        ------
        SolverError
            Newton's method does not reach the tolerance.
        """
        R, ra, Zlin, acc_lin, S = self._frequency_data(omega)
        Ulin = self.to_real(Zlin)
        a, L = self.active, 2 * self.H + 1
        U = Ulin.copy() if U0 is None else np.array(U0, dtype=float)
        scale = max(np.abs(Ulin).max(), 1e-300)
        it, res = 0, 0.0
        if a:
            Rbig = self._rbig(R)
            Rc = R[:, :, a]

            def residual(U):
                G, s_d, s_t, _ = self._deviations(U, omega)
                Z = Zlin + np.einsum("kcd,dk->ck", Rc, self.to_complex(G[a]))
                return (U - self.to_real(Z))[a].ravel(), G, s_d, s_t

            r, G, s_d, s_t = residual(U)
            res = np.abs(r).max() / scale
            while res > tol:
                if it >= max_iter:
                    raise SolverError(f"harmonic balance did not converge at "
                                      f"{omega / (2 * np.pi):.4g} Hz in {max_iter} Newton "
                                      f"iterations (relative residual {res:.2e})")
                slopes = np.vstack([s_d, s_t])
                blocks = []
                for c in a:
                    Gam_c = omega * self.Gam_dot if c < 2 else self.Gam
                    blocks.append(self.Proj @ (slopes[c][:, None] * Gam_c))
                J = np.eye(len(a) * L)
                for i, Jc in enumerate(blocks):
                    J[:, i * L:(i + 1) * L] -= Rbig[:, i * L:(i + 1) * L] @ Jc
                dU = np.linalg.solve(J, -r).reshape(len(a), L)
                step = 1.0
                while True:
                    U_try = U.copy()
                    U_try[a] += step * dU
                    r_try, G_try, sd_try, st_try = residual(U_try)
                    res_try = np.abs(r_try).max() / scale
                    if res_try < res or step < 1.0 / 64:
                        break
                    step *= 0.5
                U, r, G, s_d, s_t, res = U_try, r_try, G_try, sd_try, st_try, res_try
                it += 1
        else:
            G = np.zeros((4, L))
        Gc = self.to_complex(G)
        Z = Zlin + np.einsum("kcd,dk->ck", R, Gc)
        acc = acc_lin - (self.k * omega) ** 2 * np.einsum("kd,dk->k", ra, Gc)
        Ft = np.zeros((2, self.H + 1), dtype=complex)
        Ft[:] = self.laws.k_ref[:, None] * Z[2:] + Gc[2:]
        return PeriodicSolution(omega=omega, Z=Z, acc_A=acc, tire_force=Ft, G=Gc,
                                iterations=it, residual=res)

    def state_coefficients(self, sol: PeriodicSolution) -> np.ndarray:
        """Fourier coefficients ``Q`` (n, H + 1) of all coordinates of a solution.

        ``Q_k = H_k (E k_ref S_k + B G_k)``; the state at ``t`` is
        ``q = Re sum Q_k e^{i k omega t}``, ``q' = Re sum i k omega Q_k e^{i k omega t}``.
        """
        m, omega = self.model, sol.omega
        kw = self.k * omega
        Zdyn = (self.K_ref[None] - kw[:, None, None] ** 2 * m.M[None]
                + 1j * kw[:, None, None] * self.C_ref[None])
        S = road_amplitudes(m, omega, amplitude=self.amplitude,
                            wavelength=self.wavelength)[0]
        F = (m.B @ sol.G).T  # (H+1, n)
        F[1] += m.E @ (self.laws.k_ref * S)
        return np.linalg.solve(Zdyn, F[..., None])[..., 0].T

    def with_stability(self, sol: PeriodicSolution, *, n_segments=None) -> PeriodicSolution:
        """Return ``sol`` with its Floquet multipliers."""
        m = self.model
        Phi = monodromy(m.M, self.K_ref, self.C_ref, m.D, m.E, self.laws, sol.Z[:2],
                        sol.Z[2:], sol.omega, n_segments=n_segments)
        mu = np.linalg.eigvals(Phi)
        return PeriodicSolution(**{**sol.__dict__, "multipliers": mu[np.argsort(-np.abs(mu))]})


def sweep(model: HalfCarModel, nl: Nonlinearity, freq_Hz, *, label=None, stability=True,
          progress=False, harmonics=None, samples=None, max_halvings: int = 6) -> Spectrum:
    """Ride spectrum of the periodic steady states along a speed sweep.

    Parameters
    ----------
    model : HalfCarModel
    nl : Nonlinearity
    freq_Hz : array_like
        Forcing frequencies, ascending (speed = frequency * wavelength).
    label : str, optional
    stability : bool
        Compute Floquet multipliers at every point.
    progress : bool
        Show a tqdm progress bar.
    harmonics, samples : int, optional
        Override the parameter file's harmonic-balance resolution.

    Returns
    -------
    Spectrum
    """
    with single_threaded_blas():
        return _sweep(model, nl, freq_Hz, label=label, stability=stability, progress=progress,
                      harmonics=harmonics, samples=samples, max_halvings=max_halvings)


def _sweep(model, nl, freq_Hz, *, label, stability, progress, harmonics, samples,
           max_halvings):
    f = np.asarray(freq_Hz, dtype=float)
    hb = HarmonicBalance(model, nl, harmonics=harmonics, samples=samples)
    out = {k: [] for k in ("acc", "travel", "tire", "mu", "it")}
    hist: list[tuple[float, np.ndarray]] = []

    def predict(omega):
        if not hist:
            return None
        if len(hist) == 1:
            return hist[-1][1]
        (w1, U1), (w2, U2) = hist[-2], hist[-1]
        return U2 + (U2 - U1) * (omega - w2) / (w2 - w1)

    def to_real_all(sol):
        return hb.to_real(sol.Z)

    desc = label or f"{model.variant}, {nl.label}"
    for fi in tqdm(f, desc=desc, disable=not progress, leave=False):
        omega = 2.0 * np.pi * fi
        targets = [omega]
        sol, halvings = None, 0
        while targets:
            w = targets[-1]
            try:
                s = hb.solve(w, predict(w))
            except SolverError:
                if not hist or halvings >= max_halvings:
                    raise
                halvings += 1
                targets.append(0.5 * (hist[-1][0] + w))
                continue
            hist = (hist + [(w, to_real_all(s))])[-2:]
            targets.pop()
            sol = s
        if stability:
            sol = hb.with_stability(sol)
        out["acc"].append(np.abs(sol.sample(sol.acc_A)).max())
        out["travel"].append(np.abs(sol.sample(sol.Z[:2])).max(axis=-1))
        out["tire"].append(np.abs(sol.sample(sol.tire_force)).max(axis=-1))
        out["mu"].append(np.abs(sol.multipliers[0]) if stability else np.nan)
        out["it"].append(sol.iterations)
    mu = np.array(out["mu"])
    lam = model.params.road_wavelength_m if hb.wavelength is None else hb.wavelength
    return Spectrum(
        label=desc, freq_Hz=f, speed_m_per_s=f * lam, acc_A=np.array(out["acc"]),
        travel=np.array(out["travel"]).T, tire_force=np.array(out["tire"]).T,
        floquet_max=mu, stable=mu < 1.0, iterations=np.array(out["it"]),
    )
