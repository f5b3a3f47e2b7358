"""PAC2002 (MF-Tyre 5.2) Magic Formula: steady-state slip forces and moments.

Axis system and signs: TYDEX/ISO **W-axes** at the contact point (x forward along the
wheel-plane/road intersection, z up along the road normal, y = z x x to the left), which is
what PAC2002 property files are fitted in:

* longitudinal slip ``kappa = -Vsx/|Vcx|`` is positive when driving, giving Fx > 0;
* slip angle ``tan(alpha) = Vcy/|Vcx|`` is positive when the contact patch moves towards
  +y; it gives **negative** Fy (hence PKY1 < 0 in the files) and a positive (aligning) Mz;
* inclination ``gamma`` is positive when the top of the wheel leans towards -y (the spin
  axis has a positive component along the road normal).

Equations (Pacejka, *Tire and Vehicle Dynamics*, 2nd ed., ch. 4; MF-Tyre 5.2 / Adams
PAC2002 documentation), with ``Fz0' = FNOMIN LFZO`` and ``dfz = (Fz - Fz0')/Fz0'``:
pure slip ``F = D sin(C atan(B x - E (B x - atan(B x)))) + SV`` with ``x = slip + SH``;
combined slip by the cosine weighting functions ``Gxa``, ``Gyk`` and the kappa-induced side
force ``SVyk``; the aligning moment from pneumatic trail and residual torque with
equivalent slip angles.  A road friction factor ``mu_scale`` multiplies LMUX and LMUY.
The curvature factors E are limited to <= 1 as the model requires.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, make_dataclass

import numpy as np

from flexpipe.tires import _keys
from flexpipe.tires.checks import file_warning

_SCALING_DEFAULT_ONE = set(_keys.SCALING)
_COEFF_SECTIONS = ("SCALING_COEFFICIENTS", "LONGITUDINAL_COEFFICIENTS", "LATERAL_COEFFICIENTS",
                   "ALIGNING_COEFFICIENTS", "OVERTURNING_COEFFICIENTS", "ROLLING_COEFFICIENTS")
_ALL = (_keys.SCALING + _keys.LONGITUDINAL + _keys.LATERAL + _keys.ALIGNING
        + _keys.OVERTURNING + _keys.ROLLING)

def checked_use_mode(value) -> int:
    """``value`` as the slip part of USE_MODE, an integer 0-4 (see :mod:`flexpipe.tires`),
    else an :class:`~flexpipe.errors.InputError` naming ``use_mode``."""
    from flexpipe._args import checked_int

    return checked_int(value, "use_mode (the slip part of USE_MODE: 0 Fz only, 1 Fx and My, "
                       "2 Fy, Mx and Mz, 3 all uncombined, 4 all combined)", lo=0, hi=4,
                       key="use_mode")


#: Flat, frozen record of every PAC2002 coefficient (missing ones: scaling 1, others 0).
Pac2002Coefficients = make_dataclass(
    "Pac2002Coefficients",
    [(k, float, 1.0 if k in _SCALING_DEFAULT_ONE else 0.0) for k in _ALL],
    frozen=True, slots=True,
)
# make_dataclass puts the class in module 'types' (Python < 3.12 has no module= argument):
# name its real home so standard pickle finds it (prepare() output crosses process pools).
Pac2002Coefficients.__module__ = __name__


@dataclass(frozen=True)
class SlipForces:
    """Forces and moments at the contact point in the W-axes (N, N m); arrays or floats."""

    Fx: np.ndarray
    Fy: np.ndarray
    Mz: np.ndarray
    Mx: np.ndarray
    My: np.ndarray


def _mf(B, C, E, x):
    """Magic Formula core ``sin(C atan(Bx - E(Bx - atan Bx)))`` without the peak D."""
    Bx = B * x
    return np.sin(C * np.arctan(Bx - E * (Bx - np.arctan(Bx))))


def _weight(B, C, E, x, shift):
    """PAC2002 combined-slip weighting ``G = cos(C atan(B x - ...)) / (same at x = shift)``."""
    def f(u):
        Bu = B * u
        return np.cos(C * np.arctan(Bu - E * (Bu - np.arctan(Bu))))
    return f(x) / f(shift)


@dataclass(frozen=True)
class MagicFormula:
    """PAC2002 Magic Formula evaluated with NumPy broadcasting over all inputs.

    Build with :meth:`from_properties`.  Inputs may be floats or arrays of any common
    broadcast shape (e.g. 4 wheels); outputs have that shape.

    Attributes
    ----------
    c : Pac2002Coefficients
        All coefficients (flat attributes).
    fnomin, r0 : float
        Nominal load FNOMIN (N) and unloaded radius (m).
    use_mode : int
        ``abs(USE_MODE) % 10``: 0 none, 1 Fx/My, 2 Fy/Mx/Mz, 3 uncombined, 4 combined.
    kappa_range, alpha_range, gamma_range : tuple of float
        Inputs are clipped to these (file's *_RANGE sections; defaults wide).
    fz_max : float
        Load used inside the formula is limited to this (FZMAX; default 3 FNOMIN).
    longvl, vxlow : float
        Reference speed (m/s) for rolling resistance, speed below which its sign is smoothed.
    """

    c: object
    fnomin: float
    r0: float
    use_mode: int = 4
    kappa_range: tuple[float, float] = (-1.5, 1.5)
    alpha_range: tuple[float, float] = (-1.5707, 1.5707)
    gamma_range: tuple[float, float] = (-0.5, 0.5)
    fz_max: float = math.inf
    longvl: float = 16.7
    vxlow: float = 1.0

    @classmethod
    def from_properties(cls, props, *, use_mode: int | None = None) -> MagicFormula:
        """Precompute the flat coefficient record from :class:`TireProperties`.

        Parameters
        ----------
        props : TireProperties
            A ``PAC2002`` or ``MF_05`` (MF 5.2) property file.
        use_mode : int, optional
            Override of ``abs(USE_MODE) % 10``, 0-4 (e.g. 3 to switch combined slip off;
            see :mod:`flexpipe.tires`).
        """
        if use_mode is not None:
            use_mode = checked_use_mode(use_mode)
        values = {}
        for sec in _COEFF_SECTIONS:
            for k, v in props.coefficients(sec).items():
                if isinstance(v, float) and k in Pac2002Coefficients.__dataclass_fields__:
                    values[k] = v
        coeffs = Pac2002Coefficients(**values)
        mode = abs(props.use_mode) % 10 if use_mode is None else int(use_mode)
        if mode == 4 and not (coeffs.RBX1 or coeffs.RBY1):
            file_warning(
                f"{props.path}: USE_MODE 4 (combined slip) but the file has no combined-slip "
                "coefficients (RBX1, RBY1 ...): PAC2002 weighting is then 1, i.e. forces are "
                "NOT reduced under combined slip")
        fnom = props.fnomin


        def rng(sec, lo, hi, default):
            return (props.number(sec, lo, default[0]), props.number(sec, hi, default[1]))

        return cls(
            c=coeffs, fnomin=fnom, r0=props.unloaded_radius, use_mode=mode,
            kappa_range=rng("LONG_SLIP_RANGE", "KPUMIN", "KPUMAX", (-1.5, 1.5)),
            alpha_range=rng("SLIP_ANGLE_RANGE", "ALPMIN", "ALPMAX", (-1.5707, 1.5707)),
            gamma_range=rng("INCLINATION_ANGLE_RANGE", "CAMMIN", "CAMMAX", (-0.5, 0.5)),
            fz_max=props.number("VERTICAL_FORCE_RANGE", "FZMAX", 3.0 * fnom),
            longvl=props.number("MODEL", "LONGVL", 16.7),
            vxlow=props.number("MODEL", "VXLOW", 1.0) or 1.0,
        )

    # ------------------------------------------------------------------ building blocks
    @property
    def fz0(self) -> float:
        """Scaled nominal load ``Fz0' = FNOMIN LFZO``, N."""
        return self.fnomin * self.c.LFZO

    def _load(self, Fz):
        Fz = np.clip(np.asarray(Fz, dtype=float), 1e-9 * self.fnomin, self.fz_max)
        return Fz, (Fz - self.fz0) / self.fz0

    def _pure_x(self, kappa, Fz, dfz, gamma, lmux):
        c = self.c
        SHx = (c.PHX1 + c.PHX2 * dfz) * c.LHX
        kx = kappa + SHx
        gx = gamma * c.LGAX
        Cx = c.PCX1 * c.LCX
        Dx = (c.PDX1 + c.PDX2 * dfz) * (1.0 - c.PDX3 * gx * gx) * lmux * Fz
        Ex = np.minimum((c.PEX1 + c.PEX2 * dfz + c.PEX3 * dfz * dfz)
                        * (1.0 - c.PEX4 * np.sign(kx)) * c.LEX, 1.0)
        Kx = Fz * (c.PKX1 + c.PKX2 * dfz) * np.exp(c.PKX3 * dfz) * c.LKX
        SVx = Fz * (c.PVX1 + c.PVX2 * dfz) * c.LVX * lmux
        return Dx * _mf(Kx / (Cx * Dx), Cx, Ex, kx) + SVx, Kx

    def _pure_y(self, alpha, Fz, dfz, gamma, lmuy):
        c = self.c
        fz0 = self.fz0
        gy = gamma * c.LGAY
        SHy = (c.PHY1 + c.PHY2 * dfz) * c.LHY + c.PHY3 * gy
        ay = alpha + SHy
        Cy = c.PCY1 * c.LCY
        muy = (c.PDY1 + c.PDY2 * dfz) * (1.0 - c.PDY3 * gy * gy) * lmuy
        Dy = muy * Fz
        Ey = np.minimum((c.PEY1 + c.PEY2 * dfz)
                        * (1.0 - (c.PEY3 + c.PEY4 * gy) * np.sign(ay)) * c.LEY, 1.0)
        Ky = (c.PKY1 * fz0 * np.sin(2.0 * np.arctan(Fz / (c.PKY2 * fz0)))
              * (1.0 - c.PKY3 * np.abs(gy)) * c.LKY)
        By = Ky / (Cy * Dy)
        SVy = Fz * ((c.PVY1 + c.PVY2 * dfz) * c.LVY + (c.PVY3 + c.PVY4 * dfz) * gy) * lmuy
        return Dy * _mf(By, Cy, Ey, ay) + SVy, Ky, By, Cy, muy, SHy, SVy

    # ------------------------------------------------------------------ public API
    def fx0(self, kappa, Fz, gamma=0.0, *, mu_scale=1.0):
        """Pure longitudinal force Fx0(kappa, Fz, gamma), N (W-axes)."""
        Fz, dfz = self._load(Fz)
        kappa = np.clip(kappa, *self.kappa_range)
        gamma = np.clip(gamma, *self.gamma_range)
        return self._pure_x(kappa, Fz, dfz, gamma, self.c.LMUX * mu_scale)[0]

    def fy0(self, alpha, Fz, gamma=0.0, *, mu_scale=1.0):
        """Pure lateral force Fy0(alpha, Fz, gamma), N (W-axes: alpha > 0 gives Fy < 0)."""
        Fz, dfz = self._load(Fz)
        alpha = np.clip(alpha, *self.alpha_range)
        gamma = np.clip(gamma, *self.gamma_range)
        return self._pure_y(alpha, Fz, dfz, gamma, self.c.LMUY * mu_scale)[0]

    def slip_stiffness(self, Fz, gamma=0.0):
        """Longitudinal slip stiffness Kx (N) and cornering stiffness Ky (N/rad, < 0)."""
        c, fz0 = self.c, self.fz0
        Fz, dfz = self._load(Fz)
        Kx = Fz * (c.PKX1 + c.PKX2 * dfz) * np.exp(c.PKX3 * dfz) * c.LKX
        Ky = (c.PKY1 * fz0 * np.sin(2.0 * np.arctan(Fz / (c.PKY2 * fz0)))
              * (1.0 - c.PKY3 * np.abs(gamma * c.LGAY)) * c.LKY)
        return Kx, Ky

    def peak_friction(self, Fz, gamma=0.0):
        """Peak friction coefficients (mu_x, mu_y) = (Dx/Fz, Dy/Fz)."""
        c = self.c
        Fz, dfz = self._load(Fz)
        gx, gy = gamma * c.LGAX, gamma * c.LGAY
        return ((c.PDX1 + c.PDX2 * dfz) * (1.0 - c.PDX3 * gx * gx) * c.LMUX,
                (c.PDY1 + c.PDY2 * dfz) * (1.0 - c.PDY3 * gy * gy) * c.LMUY)

    def relaxation_lengths(self, Fz, gamma=0.0):
        """Relaxation lengths (sigma_kappa, sigma_alpha), m, MF 5.2 (PTX*, PTY*).

        Missing PTX1 / PTY1 give ``nan`` (no relaxation data).
        """
        c, fz0 = self.c, self.fz0
        Fz, dfz = self._load(Fz)
        sk = (Fz * (c.PTX1 + c.PTX2 * dfz) * np.exp(-c.PTX3 * dfz) * self.r0 / self.fnomin
              * c.LSGKP) if c.PTX1 else np.full_like(Fz, np.nan)
        sa = (c.PTY1 * np.sin(2.0 * np.arctan(Fz / (c.PTY2 * fz0)))
              * (1.0 - c.PKY3 * np.abs(gamma)) * self.r0 * c.LFZO * c.LSGAL
              ) if (c.PTY1 and c.PTY2) else np.full_like(Fz, np.nan)
        return sk, sa

    def forces(self, kappa, alpha, Fz, gamma=0.0, *, vx=None, mirror=False,
               mu_scale=1.0) -> SlipForces:
        """Steady-state Fx, Fy, Mz, Mx, My for the configured USE_MODE.

        Parameters
        ----------
        kappa, alpha, gamma : float or array
            Longitudinal slip (-), slip angle and inclination (rad), W-axes conventions.
        Fz : float or array
            Vertical load, N; where ``Fz <= 0`` every output is 0.
        vx : float or array, optional
            Longitudinal contact speed (m/s) for the rolling resistance sign and speed
            terms; default: rolling forward at LONGVL.
        mirror : bool or array of bool
            Mirror the characteristic (tyre used on the side opposite to TYRESIDE, or a
            negative USE_MODE): Fy, Mz, Mx of the mirrored slip angle and camber change sign.
        mu_scale : float or array
            Road friction factor multiplying LMUX and LMUY.

        Returns
        -------
        SlipForces
        """
        c, mode = self.c, self.use_mode
        Fz_in, Fz, dfz, sgn, kappa, alpha, gamma, zero = self._inputs(kappa, alpha, Fz, gamma,
                                                                      mirror)
        lmux, lmuy = c.LMUX * mu_scale, c.LMUY * mu_scale
        Fx = Fy = Mz = Mx = My = zero
        if mode in (1, 3, 4):
            Fx, Kx = self._pure_x(kappa, Fz, dfz, gamma, lmux)
        if mode in (2, 3, 4):
            Fy0, Ky, By, Cy, muy, SHy, SVy = self._pure_y(alpha, Fz, dfz, gamma, lmuy)
            Fy = Fyp = Fy0
            if mode == 4:
                SHxa = c.RHX1
                Bxa = c.RBX1 * np.cos(np.arctan(c.RBX2 * kappa)) * c.LXAL
                Exa = np.minimum(c.REX1 + c.REX2 * dfz, 1.0)
                Fx = Fx * _weight(Bxa, c.RCX1, Exa, alpha + SHxa, SHxa)
                SHyk = c.RHY1 + c.RHY2 * dfz
                Byk = c.RBY1 * np.cos(np.arctan(c.RBY2 * (alpha - c.RBY3))) * c.LYKA
                Eyk = np.minimum(c.REY1 + c.REY2 * dfz, 1.0)
                DVyk = (muy * Fz * (c.RVY1 + c.RVY2 * dfz + c.RVY3 * gamma)
                        * np.cos(np.arctan(c.RVY4 * alpha)))
                SVyk = DVyk * np.sin(c.RVY5 * np.arctan(c.RVY6 * kappa)) * c.LVYKA
                Fyp = Fy0 * _weight(Byk, c.RCY1, Eyk, kappa + SHyk, SHyk)
                Fy = Fyp + SVyk
            combined = mode == 4
            Mz = self._aligning(kappa if combined else 0.0, alpha, Fz, dfz, gamma,
                                Fx if combined else 0.0, Fy, Fyp, Ky, By, Cy, SHy, SVy, lmuy,
                                Kx if combined else 0.0)
            Mx = self.r0 * Fz * (c.QSX1 * c.LVMX - c.QSX2 * gamma + c.QSX3 * Fy / self.fz0) * c.LMX
        if mode in (1, 3, 4):
            v = self.longvl if vx is None else np.asarray(vx, dtype=float)
            vr = v / self.longvl
            My = (-self.r0 * Fz * (c.QSY1 + c.QSY2 * Fx / self.fz0 + c.QSY3 * np.abs(vr)
                                   + c.QSY4 * vr ** 4) * c.LMY * np.tanh(v / self.vxlow))
        return self._outputs(Fz_in, sgn, Fx, Fy, Mz, Mx, My)

    def _inputs(self, kappa, alpha, Fz, gamma, mirror):
        """Inputs clipped to the file's ranges, the characteristic mirrored where asked:
        ``(Fz_in, Fz, dfz, sign, kappa, alpha, gamma, zeros of the broadcast shape)``."""
        Fz_in = np.asarray(Fz, dtype=float)
        Fz, dfz = self._load(Fz_in)
        sgn = np.where(mirror, -1.0, 1.0)
        kappa = np.clip(kappa, *self.kappa_range)
        alpha = np.clip(sgn * np.asarray(alpha, dtype=float), *self.alpha_range)
        gamma = np.clip(sgn * np.asarray(gamma, dtype=float), *self.gamma_range)
        zero = np.zeros(np.broadcast(kappa, alpha, Fz, gamma, sgn).shape)
        return Fz_in, Fz, dfz, sgn, kappa, alpha, gamma, zero

    @staticmethod
    def _outputs(Fz_in, sgn, Fx, Fy, Mz, Mx, My) -> SlipForces:
        """Zero where the tyre is off the road; Fy, Mz, Mx mirrored back."""
        on = Fz_in > 0.0
        return SlipForces(Fx=np.where(on, Fx, 0.0), Fy=np.where(on, sgn * Fy, 0.0),
                          Mz=np.where(on, sgn * Mz, 0.0), Mx=np.where(on, sgn * Mx, 0.0),
                          My=np.where(on, My, 0.0))

    def _aligning(self, kappa, alpha, Fz, dfz, gamma, Fx, Fy, Fyp, Ky, By, Cy, SHy, SVy, lmuy,
                  Kx):
        c, fz0 = self.c, self.fz0
        gz = gamma * c.LGAZ
        SHt = c.QHZ1 + c.QHZ2 * dfz + (c.QHZ3 + c.QHZ4 * dfz) * gz
        at = alpha + SHt
        ar = alpha + SHy + SVy / Ky
        Bt = ((c.QBZ1 + c.QBZ2 * dfz + c.QBZ3 * dfz * dfz)
              * (1.0 + c.QBZ4 * gz + c.QBZ5 * np.abs(gz)) * c.LKY / c.LMUY)
        Ct = c.QCZ1
        Dt = (Fz * (c.QDZ1 + c.QDZ2 * dfz) * (1.0 + c.QDZ3 * gz + c.QDZ4 * gz * gz)
              * self.r0 / fz0 * c.LTR)
        Et = np.minimum((c.QEZ1 + c.QEZ2 * dfz + c.QEZ3 * dfz * dfz)
                        * (1.0 + (c.QEZ4 + c.QEZ5 * gz) * (2.0 / np.pi) * np.arctan(Bt * Ct * at)),
                        1.0)
        Br = c.QBZ9 * c.LKY / c.LMUY + c.QBZ10 * By * Cy
        Dr = Fz * ((c.QDZ6 + c.QDZ7 * dfz) * c.LRES + (c.QDZ8 + c.QDZ9 * dfz) * gz) * self.r0 * lmuy
        cos_a = np.cos(alpha)
        if np.any(kappa):
            k2 = (Kx / Ky * kappa) ** 2
            at = np.arctan(np.sqrt(np.tan(at) ** 2 + k2)) * np.sign(at)
            ar = np.arctan(np.sqrt(np.tan(ar) ** 2 + k2)) * np.sign(ar)
        t = Dt * np.cos(Ct * np.arctan(Bt * at - Et * (Bt * at - np.arctan(Bt * at)))) * cos_a
        Mzr = Dr * np.cos(np.arctan(Br * ar)) * cos_a
        s = (c.SSZ1 + c.SSZ2 * Fy / fz0 + (c.SSZ3 + c.SSZ4 * dfz) * gamma) * self.r0 * c.LS
        return -t * Fyp + Mzr + s * Fx
