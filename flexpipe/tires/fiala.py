"""Fiala / brush tyre model with combined slip, the simple alternative to PAC2002.

Brush model with a parabolic pressure distribution (Fiala 1954; Pacejka ch. 3).  With the
normalised slips

    phi_x = C_kappa kappa / (3 mu_x Fz),   phi_y = C_alpha tan(alpha_e) / (3 mu_y Fz),
    phi = sqrt(phi_x^2 + phi_y^2),        tan(alpha_e) = tan(alpha) + (C_gamma/C_alpha) gamma,

the force magnitude (in units of the friction limit) is ``f = 1 - (1 - phi)^3`` for
``phi < 1`` and ``f = 1`` (full sliding) beyond, shared along the slip direction:

    Fx = mu_x Fz f phi_x / phi,     Fy = -mu_y Fz f phi_y / phi.

For pure side slip this is Fiala's ``Fy = -mu Fz (1 - H^3) sgn(alpha)`` with
``H = 1 - C_alpha |tan alpha| / (3 mu Fz)``; the initial slopes are ``C_kappa`` and
``-C_alpha`` and the force saturates at the friction ellipse ``(mu_x Fz, mu_y Fz)``.  The
aligning moment is ``Mz = -t Fy`` with the brush pneumatic trail
``t = a (1 - phi)^3 / (3 - 3 phi + phi^2)`` (``a/3`` at small slip, 0 when sliding) and
``a`` the half contact length ``sqrt(2 R0 rho - rho^2)`` at the static deflection
``rho = Fz / k``.  Friction falls linearly from UMAX to UMIN as the comprehensive slip
``sqrt(kappa^2 + tan^2 alpha)`` goes from 0 to 1 (Adams Fiala convention).  Signs: W-axes
as in :mod:`flexpipe.tires.pac2002`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError
from flexpipe.tires.contact import TireModel
from flexpipe.tires.pac2002 import SlipForces
from flexpipe.tires.vertical import VerticalModel


@dataclass(frozen=True)
class FialaParameters:
    """Parameters of :class:`FialaTire` (SI).

    Parameters
    ----------
    c_slip : float
        Longitudinal slip stiffness C_kappa, N per unit slip (> 0).
    c_alpha : float
        Cornering stiffness C_alpha, N/rad (> 0; the model gives Fy = -C_alpha alpha).
    mu_x, mu_y : float
        Peak friction coefficients (Adams Fiala: both UMAX).
    mu_slide_ratio : float
        UMIN/UMAX: friction at comprehensive slip >= 1 relative to the peak.
    c_gamma : float
        Camber stiffness, N/rad (Fy = -c_gamma gamma at small slip).
    rolling_resistance : float
        Rolling resistance coefficient: My = -coefficient Fz R0 (forward rolling).
    relax_length_x, relax_length_y : float or None
        Relaxation lengths, m.
    """

    c_slip: float
    c_alpha: float
    mu_x: float
    mu_y: float
    mu_slide_ratio: float = 1.0
    c_gamma: float = 0.0
    rolling_resistance: float = 0.0
    relax_length_x: float | None = None
    relax_length_y: float | None = None

    def __post_init__(self):
        for name in ("c_slip", "c_alpha", "mu_x", "mu_y"):
            if not getattr(self, name) > 0:
                raise InputError(f"Fiala {name} must be > 0, got {getattr(self, name)}", key=name)
        if not 0 < self.mu_slide_ratio <= 1:
            raise InputError("Fiala UMIN/UMAX must lie in (0, 1], got "
                             f"{self.mu_slide_ratio}", key="UMIN")


@dataclass(frozen=True)
class FialaTire(TireModel):
    """Fiala/brush tyre with the :class:`TireModel` interface (see module docstring).

    Build with :meth:`from_properties` or directly from :class:`FialaParameters`.
    """

    params: FialaParameters
    vertical: VerticalModel
    unloaded_radius: float
    relaxation: bool = False
    vxlow: float = 1.0
    tyre_side: str = "SYMMETRIC"
    mirror_all: bool = False

    @classmethod
    def from_properties(cls, props, *, relaxation: bool | None = None,
                        vertical_law: str = "auto") -> FialaTire:
        """From a ``FIALA`` file ([PARAMETER] CSLIP, CALPHA, UMIN, UMAX, ...) or a ``PAC2002`` /
        ``MF_05`` file (stiffnesses and peak friction of the Magic Formula at FNOMIN, camber 0)."""
        from flexpipe.tires.pac2002 import MagicFormula

        fmt = props.property_file_format
        if fmt == "FIALA":
            umax = props.number("PARAMETER", "UMAX")
            p = FialaParameters(
                c_slip=props.number("PARAMETER", "CSLIP"),
                c_alpha=props.number("PARAMETER", "CALPHA"), mu_x=umax, mu_y=umax,
                mu_slide_ratio=props.number("PARAMETER", "UMIN", umax) / umax,
                c_gamma=props.number("PARAMETER", "CGAMMA", 0.0),
                rolling_resistance=props.number("PARAMETER", "ROLLING_RESISTANCE", 0.0),
                relax_length_x=props.relaxation_length_longitudinal(),
                relax_length_y=props.relaxation_length_lateral())
        elif props.is_mf52 or props.is_mf6:
            from flexpipe.tires.mf61 import MagicFormula61

            mf = (MagicFormula61 if props.is_mf6 else MagicFormula).from_properties(
                props, use_mode=3)
            fn = props.fnomin
            kx, ky = mf.slip_stiffness(fn)
            mux, muy = mf.peak_friction(fn)
            sk, sa = mf.relaxation_lengths(fn)
            p = FialaParameters(
                c_slip=float(kx), c_alpha=float(abs(ky)), mu_x=float(mux), mu_y=float(muy),
                rolling_resistance=props.number("ROLLING_COEFFICIENTS", "QSY1", 0.0),
                relax_length_x=None if np.isnan(sk) else float(sk),
                relax_length_y=None if np.isnan(sa) else float(sa))
        else:
            raise InputError(f"PROPERTY_FILE_FORMAT '{fmt}' cannot give Fiala parameters; "
                             "valid: 'FIALA', 'PAC2002', 'MF_05', or an MF 6.1 / 6.2 "
                             "fit (FITTYP 61 / 62)", file=props.path,
                             line=props.lines.get(("MODEL", "PROPERTY_FILE_FORMAT")),
                             key="PROPERTY_FILE_FORMAT")
        return cls(
            params=p, vertical=VerticalModel.from_properties(props, law=vertical_law),
            unloaded_radius=props.unloaded_radius,
            relaxation=props.relaxation if relaxation is None else relaxation,
            vxlow=props.number("MODEL", "VXLOW", 1.0) or 1.0,
            tyre_side="SYMMETRIC", mirror_all=False)

    def effective_rolling_radius(self, deflection):
        """``R0 - rho/3`` (radial-tyre approximation), m."""
        return self.unloaded_radius - np.maximum(deflection, 0.0) / 3.0

    def relaxation_lengths(self, Fz, gamma=0.0):
        """Constant (sigma_kappa, sigma_alpha), m; nan where not given."""
        p = self.params
        sk = np.nan if p.relax_length_x is None else p.relax_length_x
        sa = np.nan if p.relax_length_y is None else p.relax_length_y
        shape = np.shape(Fz)
        return np.full(shape, sk), np.full(shape, sa)

    def slip_forces(self, kappa, alpha, Fz, gamma=0.0, *, vx=None, mirror=False,
                    mu_scale=1.0) -> SlipForces:
        """Fx, Fy, Mz, Mx (= 0), My in the W-axes; see the module docstring."""
        p = self.params
        Fz_in = np.asarray(Fz, dtype=float)
        Fz = np.maximum(Fz_in, 1e-9)
        sgn = np.where(mirror, -1.0, 1.0)
        kappa = np.asarray(kappa, dtype=float)
        tan_a = np.tan(sgn * np.asarray(alpha, dtype=float))
        slide = np.minimum(np.hypot(kappa, tan_a), 1.0)
        r = (1.0 - (1.0 - p.mu_slide_ratio) * slide) * mu_scale
        mux, muy = p.mu_x * r, p.mu_y * r
        tan_e = tan_a + (p.c_gamma / p.c_alpha) * sgn * np.asarray(gamma, dtype=float)
        phx = p.c_slip * kappa / (3.0 * mux * Fz)
        phy = p.c_alpha * tan_e / (3.0 * muy * Fz)
        phi = np.hypot(phx, phy)
        stick = phi < 1.0
        f_over_phi = np.where(stick, 3.0 - 3.0 * phi + phi * phi,
                              1.0 / np.where(stick, 1.0, phi))
        Fx = mux * Fz * f_over_phi * phx
        Fy = -muy * Fz * f_over_phi * phy
        rho = Fz / self.vertical.k
        a = np.sqrt(np.maximum(2.0 * self.unloaded_radius * rho - rho * rho, 0.0))
        pc = np.minimum(phi, 1.0)
        trail = a * (1.0 - pc) ** 3 / (3.0 - 3.0 * pc + pc * pc)
        Mz = -trail * Fy
        v = 1.0 if vx is None else np.asarray(vx, dtype=float)
        My = -p.rolling_resistance * Fz * self.unloaded_radius * np.tanh(v / self.vxlow)
        on = Fz_in > 0.0
        zero = np.zeros(np.broadcast(Fx, Fy).shape)
        return SlipForces(Fx=np.where(on, Fx, 0.0), Fy=np.where(on, sgn * Fy, 0.0),
                          Mz=np.where(on, sgn * Mz, 0.0), Mx=zero, My=np.where(on, My, 0.0))
