"""Magic Formula 6.1 / 6.2 (MF-Tyre 6.x fits, ``FITTYP`` 61 / 62): steady-state slip forces.

The equations of the TNO MF-Tyre 6.1 equation manual as Pacejka (*Tire and Vehicle
Dynamics*, 3rd ed., 2012, sec. 4.3.2, eqs. 4.E1-4.E78) gives them, in the variant that
MFeval (the MATLAB toolbox checked against TNO's MF-Tyre, and its Julia port MFeval.jl)
evaluates; axes, signs and inputs as :mod:`flexpipe.tires.pac2002` (TYDEX W-axes).
Turn slip is off (``zeta_i = 1``, as MF-Tyre without turn slip).  What differs from MF 5.2:

* **inflation pressure** ``dpi = (p - NOMPRES)/NOMPRES``: slip stiffness (PPX1, PPX2),
  friction (PPX3, PPX4, PPY3, PPY4), cornering stiffness and its peak load (PPY1, PPY2),
  camber stiffness (PPY5), pneumatic trail (PPZ1), camber torque (PPZ2), overturning
  (PPMX1), rolling resistance ``(p/NOMPRES)^QSY8``; the run's pressure is fixed (the file's
  INFLPRES unless given), so ``dpi`` is a constant of the model;
* slip angle and camber enter as ``alpha* = tan(alpha)`` and ``gamma* = sin(gamma)``;
* cornering stiffness ``PKY1 Fz0' (1 + PPY1 dpi)(1 - PKY3|g*|) sin(PKY4 atan(Fz/Fz0' /
  ((PKY2 + PKY5 g*^2)(1 + PPY2 dpi))))`` and a camber stiffness
  ``Kyg0 = Fz (PKY6 + PKY7 dfz)(1 + PPY5 dpi)`` that shifts the curve horizontally
  (no PHY3), curvature with PEY5, combined-slip camber terms RBX3, RBY4;
* aligning moment: the pneumatic trail acts on the side force at zero camber, residual
  torque with QDZ10, QDZ11 and pressure; overturning moment with QSX4-QSX14, rolling
  resistance with QSY5-QSY8 (``Fz0 (Fz/Fz0)^QSY7``);
* relaxation lengths from the carcass stiffnesses of ``[STRUCTURAL]``:
  ``sigma_kappa = Kxk/Cx``, ``sigma_alpha = Kya/Cy`` with
  ``Cx = LONGITUDINAL_STIFFNESS (1 + PCFX1 dfz + PCFX2 dfz^2)(1 + PCFX3 dpi)`` (Cy alike).

MFeval's own choices kept where the manual and the book differ: the trail's camber terms
``(1 + QBZ4 g + QBZ5|g|)`` and ``(1 + QDZ3 g + QDZ4 g^2)`` in the inclination angle itself,
the residual torque's ``cos(alpha*)``, the combined trail times LFZO, and the reduced load
``Fz (Fz/FZMIN)^2`` (Mx) and ``Fz (Fz/FZMIN)`` (My) below FZMIN.  MF 6.2 has the same force
equations; its loaded-radius and vertical models are replaced by flexpipe's vertical
spring (:mod:`flexpipe.tires.vertical`, stiffness times ``1 + PFZ1 dpi``).
``tests/test_mf61.py`` checks these forces against reference values of an independent
evaluation (``tests/data/mf61_reference.csv``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from flexpipe.tires import _keys
from flexpipe.tires.pac2002 import MagicFormula, SlipForces, _mf, _weight

_EPS_K = 1e-6  # MFeval's epsilon of the cornering stiffness in divisions


def _sgn1(x):
    """Sign with sign(0) = 1 (MFeval's convention where a zero would divide by zero)."""
    return np.where(np.asarray(x) >= 0.0, 1.0, -1.0)


@dataclass(frozen=True)
class MagicFormula61(MagicFormula):
    """MF 6.1 / 6.2 Magic Formula, NumPy broadcasting over all inputs.

    Build with :meth:`from_properties`; attributes as :class:`MagicFormula` plus:

    Attributes
    ----------
    version : int
        61 or 62 (the file's FITTYP).
    pressure, nominal_pressure : float
        Inflation pressure of the run and the fit's NOMPRES, Pa.
    fz_min : float
        FZMIN, N (below it Mx and My take MFeval's reduced load).
    cx0, cy0 : float
        ``[STRUCTURAL]`` LONGITUDINAL_STIFFNESS and LATERAL_STIFFNESS, N/m (nan: none).
    pcfx, pcfy : tuple of float
        PCFX1-3 and PCFY1-3.
    """

    version: int = 61
    pressure: float = 0.0
    nominal_pressure: float = 0.0
    fz_min: float = 0.0
    cx0: float = math.nan
    cy0: float = math.nan
    pcfx: tuple[float, float, float] = (0.0, 0.0, 0.0)
    pcfy: tuple[float, float, float] = (0.0, 0.0, 0.0)

    @classmethod
    def from_properties(cls, props, *, use_mode: int | None = None,
                        pressure: float | None = None) -> MagicFormula61:
        """From an MF 6.1 / 6.2 :class:`TireProperties`; ``pressure`` (Pa) is the run's
        inflation pressure, default the file's INFLPRES (its NOMPRES when it has none)."""
        from flexpipe.errors import InputError

        base = MagicFormula.from_properties(props, use_mode=use_mode)
        lat = props.coefficients("LATERAL_COEFFICIENTS")
        if lat.get("PKY4") == 0.0 and base.use_mode in (2, 3, 4):
            raise InputError("[LATERAL_COEFFICIENTS] PKY4 = 0 gives an MF 6.x tyre no "
                             "cornering stiffness; valid: non-zero (about 1.5-2.5 in fitted "
                             "tyres; 2 is the MF 5.2 shape)", file=props.path, key="PKY4",
                             line=props.lines.get(("LATERAL_COEFFICIENTS", "PKY4")))
        # absent PKY4 / QSY7: the MF 5.2 shape of Ky over the load and My proportional to Fz
        defaults = {k: v for sec, k, v in (("LATERAL_COEFFICIENTS", "PKY4", 2.0),
                                           ("ROLLING_COEFFICIENTS", "QSY7", 1.0))
                    if k not in props.coefficients(sec)}
        if defaults:
            base = replace(base, c=replace(base.c, **defaults))
        pressures = props.pressures
        if pressures is None:
            if any(getattr(base.c, k) for _, k in _keys.PRESSURE_TERMS) or \
                    pressure is not None:
                raise InputError(
                    "an MF 6.x file with inflation-pressure terms (or a pressure given for "
                    "the run) needs [OPERATING_CONDITIONS] INFLPRES and NOMPRES (Pa)",
                    file=props.path, key="OPERATING_CONDITIONS")
            p, p0 = 1.0, 1.0
        else:
            p, p0 = pressures
            p = p if pressure is None else float(pressure)
            lo, hi = props.pressure_range or (0.0, math.inf)
            if not (p > 0.0 and lo <= p <= hi and p0 > 0.0):
                raise InputError(
                    f"inflation pressure {p:g} Pa (NOMPRES {p0:g} Pa) is outside the fit's "
                    f"range; valid: {max(lo, 0.0):g} .. {hi:g} Pa ([INFLATION_PRESSURE_RANGE] "
                    "PRESMIN .. PRESMAX) and NOMPRES > 0",
                    file=props.path, key="pressure" if pressure is not None else "INFLPRES",
                    line=None if pressure is not None else
                    props.lines.get(("OPERATING_CONDITIONS", "INFLPRES")))
        def stiff(key):  # a carcass stiffness; absent or not positive: none given
            v = props.number("STRUCTURAL", key, math.nan)
            return v if v > 0 else math.nan

        fields = {f: getattr(base, f) for f in base.__dataclass_fields__}
        return cls(**fields, version=int(props.fittyp), pressure=p, nominal_pressure=p0,
                   fz_min=props.number("VERTICAL_FORCE_RANGE", "FZMIN", 0.0),
                   cx0=stiff("LONGITUDINAL_STIFFNESS"), cy0=stiff("LATERAL_STIFFNESS"),
                   pcfx=tuple(props.number("STRUCTURAL", f"PCFX{i}", 0.0) for i in (1, 2, 3)),
                   pcfy=tuple(props.number("STRUCTURAL", f"PCFY{i}", 0.0) for i in (1, 2, 3)))

    @property
    def dpi(self) -> float:
        """Normalised pressure change ``(p - NOMPRES)/NOMPRES``."""
        return (self.pressure - self.nominal_pressure) / self.nominal_pressure

    # ------------------------------------------------------------------ building blocks
    def _kx(self, Fz, dfz):
        c, dpi = self.c, self.dpi
        return (Fz * (c.PKX1 + c.PKX2 * dfz) * np.exp(c.PKX3 * dfz)
                * (1.0 + c.PPX1 * dpi + c.PPX2 * dpi * dpi) * c.LKX)

    def _ky(self, Fz, gs):
        c, dpi, fz0 = self.c, self.dpi, self.fz0
        return (c.PKY1 * fz0 * (1.0 + c.PPY1 * dpi) * (1.0 - c.PKY3 * np.abs(gs))
                * np.sin(c.PKY4 * np.arctan(Fz / fz0 / ((c.PKY2 + c.PKY5 * gs * gs)
                                                        * (1.0 + c.PPY2 * dpi)))) * c.LKY)

    def _mux(self, dfz, gamma, lmux):
        c, dpi = self.c, self.dpi
        return ((c.PDX1 + c.PDX2 * dfz) * (1.0 + c.PPX3 * dpi + c.PPX4 * dpi * dpi)
                * (1.0 - c.PDX3 * gamma * gamma) * lmux)

    def _muy(self, dfz, gs, lmuy):
        c, dpi = self.c, self.dpi
        return ((c.PDY1 + c.PDY2 * dfz) * (1.0 + c.PPY3 * dpi + c.PPY4 * dpi * dpi)
                * (1.0 - c.PDY3 * gs * gs) * lmuy)

    def _pure_x(self, kappa, Fz, dfz, gamma, lmux):
        c = self.c
        kx = kappa + (c.PHX1 + c.PHX2 * dfz) * c.LHX
        Cx = c.PCX1 * c.LCX
        Dx = self._mux(dfz, gamma, lmux) * Fz
        Ex = np.minimum((c.PEX1 + c.PEX2 * dfz + c.PEX3 * dfz * dfz)
                        * (1.0 - c.PEX4 * np.sign(kx)) * c.LEX, 1.0)
        Kx = self._kx(Fz, dfz)
        SVx = Fz * (c.PVX1 + c.PVX2 * dfz) * c.LVX * lmux
        return Dx * _mf(Kx / (Cx * Dx), Cx, Ex, kx) + SVx, Kx

    def _pure_y(self, a_s, Fz, dfz, gs, lmuy):
        """Fy0 of ``alpha* = a_s`` and ``gamma* = gs``, with Kya, By, Cy, muy, SHy, SVy."""
        c, dpi = self.c, self.dpi
        Ky = self._ky(Fz, gs)
        Kyg0 = Fz * (c.PKY6 + c.PKY7 * dfz) * (1.0 + c.PPY5 * dpi) * c.LKYC
        SVyg = Fz * (c.PVY3 + c.PVY4 * dfz) * gs * c.LKYC * lmuy
        SHy = (c.PHY1 + c.PHY2 * dfz) * c.LHY + (Kyg0 * gs - SVyg) / (Ky + _EPS_K * _sgn1(Ky))
        SVy = Fz * (c.PVY1 + c.PVY2 * dfz) * c.LVY * lmuy + SVyg
        ay = a_s + SHy
        Cy = c.PCY1 * c.LCY
        muy = self._muy(dfz, gs, lmuy)
        Dy = muy * Fz
        Ey = np.minimum((c.PEY1 + c.PEY2 * dfz)
                        * (1.0 + c.PEY5 * gs * gs - (c.PEY3 + c.PEY4 * gs) * _sgn1(ay))
                        * c.LEY, 1.0)
        By = Ky / (Cy * Dy)
        return Dy * _mf(By, Cy, Ey, ay) + SVy, Ky, By, Cy, muy, SHy, SVy

    def _gyk(self, kappa, a_s, dfz, gs):
        c = self.c
        SHyk = c.RHY1 + c.RHY2 * dfz
        Byk = ((c.RBY1 + c.RBY4 * gs * gs) * np.cos(np.arctan(c.RBY2 * (a_s - c.RBY3)))
               * c.LYKA)
        Eyk = np.minimum(c.REY1 + c.REY2 * dfz, 1.0)
        return _weight(Byk, c.RCY1, Eyk, kappa + SHyk, SHyk)

    # ------------------------------------------------------------------ public API
    # fx0 as MagicFormula's (through this class's _pure_x)
    def fy0(self, alpha, Fz, gamma=0.0, *, mu_scale=1.0):
        """Pure lateral force Fy0(alpha, Fz, gamma), N (W-axes: alpha > 0 gives Fy < 0)."""
        Fz, dfz = self._load(Fz)
        a_s = np.tan(np.clip(alpha, *self.alpha_range))
        gs = np.sin(np.clip(gamma, *self.gamma_range))
        return self._pure_y(a_s, Fz, dfz, gs, self.c.LMUY * mu_scale)[0]

    def slip_stiffness(self, Fz, gamma=0.0):
        """Longitudinal slip stiffness Kx (N) and cornering stiffness Ky (N/rad, < 0) at
        the run's pressure."""
        Fz, dfz = self._load(Fz)
        return self._kx(Fz, dfz), self._ky(Fz, np.sin(gamma))

    def peak_friction(self, Fz, gamma=0.0):
        """Peak friction coefficients (mu_x, mu_y) at the run's pressure."""
        Fz, dfz = self._load(Fz)
        return (self._mux(dfz, gamma, self.c.LMUX),
                self._muy(dfz, np.sin(gamma), self.c.LMUY))

    def relaxation_lengths(self, Fz, gamma=0.0):
        """Relaxation lengths ``(|Kxk/Cx|, |Kya/Cy|)``, m, from ``[STRUCTURAL]`` (nan where
        the file has no carcass stiffness)."""
        Fz, dfz = self._load(Fz)
        dpi = self.dpi
        a1, a2, a3 = self.pcfx
        b1, b2, b3 = self.pcfy
        Cx = self.cx0 * (1.0 + a1 * dfz + a2 * dfz * dfz) * (1.0 + a3 * dpi)
        Cy = self.cy0 * (1.0 + b1 * dfz + b2 * dfz * dfz) * (1.0 + b3 * dpi)
        return (np.abs(self._kx(Fz, dfz) / Cx),
                np.abs(self._ky(Fz, np.sin(gamma)) / Cy))

    def forces(self, kappa, alpha, Fz, gamma=0.0, *, vx=None, mirror=False,
               mu_scale=1.0) -> SlipForces:
        """Steady-state Fx, Fy, Mz, Mx, My for the configured USE_MODE (arguments as
        :meth:`MagicFormula.forces`)."""
        c, mode = self.c, self.use_mode
        Fz_in, Fz, dfz, sgn, kappa, alpha, gamma, zero = self._inputs(kappa, alpha, Fz, gamma,
                                                                      mirror)
        a_s, gs = np.tan(alpha), np.sin(gamma)
        lmux, lmuy = c.LMUX * mu_scale, c.LMUY * mu_scale
        Fx = Fy = Mz = Mx = My = zero
        fnom = self.fnomin
        if mode in (1, 3, 4):
            Fx, Kx = self._pure_x(kappa, Fz, dfz, gamma, lmux)
        if mode in (2, 3, 4):
            Fy0, Ky, By, Cy, muy, SHy, SVy = self._pure_y(a_s, Fz, dfz, gs, lmuy)
            Fy = Fy0
            Fyg0 = self._pure_y(a_s, Fz, dfz, 0.0, lmuy)[0]  # the trail acts on Fy at gamma 0
            combined = mode == 4
            if combined:
                SHxa = c.RHX1
                Bxa = ((c.RBX1 + c.RBX3 * gs * gs) * np.cos(np.arctan(c.RBX2 * kappa))
                       * c.LXAL)
                Exa = np.minimum(c.REX1 + c.REX2 * dfz, 1.0)
                Fx = Fx * _weight(Bxa, c.RCX1, Exa, a_s + SHxa, SHxa)
                DVyk = (muy * Fz * (c.RVY1 + c.RVY2 * dfz + c.RVY3 * gs)
                        * np.cos(np.arctan(c.RVY4 * a_s)))
                SVyk = DVyk * np.sin(c.RVY5 * np.arctan(c.RVY6 * kappa)) * c.LVYKA
                Gyk = self._gyk(kappa, a_s, dfz, gs)
                Fy = Fy0 * Gyk + SVyk
                Fyg0 = Fyg0 * Gyk
            Mz = self._aligning(kappa, alpha, a_s, Fz, dfz, gamma, gs, Fx, Fy, Fyg0, Ky, By,
                                Cy, SHy, SVy, lmuy, Kx if combined else None)
            Fze = (np.where(Fz < self.fz_min, Fz * (Fz / self.fz_min) ** 2, Fz)
                   if self.fz_min > 0.0 else Fz)
            Mx = (self.r0 * Fze * c.LMX
                  * (c.QSX1 * c.LVMX - c.QSX2 * gamma * (1.0 + c.PPMX1 * self.dpi)
                     + c.QSX3 * Fy / fnom
                     + c.QSX4 * np.cos(c.QSX5 * np.arctan((c.QSX6 * Fze / fnom) ** 2))
                     * np.sin(c.QSX7 * gamma + c.QSX8 * np.arctan(c.QSX9 * Fy / fnom))
                     + c.QSX10 * np.arctan(c.QSX11 * Fze / fnom) * gamma)
                  + self.r0 * c.LMX * (Fy * (c.QSX13 + c.QSX14 * np.abs(gamma))
                                       - Fze * c.QSX12 * gamma * np.abs(gamma)))
        if mode in (1, 3, 4):
            v = self.longvl if vx is None else np.asarray(vx, dtype=float)
            vr = v / self.longvl
            Fze = (np.where(Fz < self.fz_min, Fz * Fz / self.fz_min, Fz)
                   if self.fz_min > 0.0 else Fz)
            My = (-self.r0 * fnom * c.LMY
                  * (c.QSY1 + c.QSY2 * Fx / fnom + c.QSY3 * np.abs(vr) + c.QSY4 * vr ** 4
                     + (c.QSY5 + c.QSY6 * Fze / fnom) * gamma * gamma)
                  * (Fze / fnom) ** c.QSY7 * (self.pressure / self.nominal_pressure) ** c.QSY8
                  * np.tanh(v / self.vxlow))
        return self._outputs(Fz_in, sgn, Fx, Fy, Mz, Mx, My)

    def _aligning(self, kappa, alpha, a_s, Fz, dfz, gamma, gs, Fx, Fy, Fyg0, Ky, By, Cy,
                  SHy, SVy, lmuy, Kx):
        """Mz: pure slip (``Kx`` None) or combined, MFeval's form (see module notes)."""
        c, fz0, dpi = self.c, self.fz0, self.dpi
        Kyp = Ky + _EPS_K * _sgn1(Ky)
        ar = a_s + SHy + SVy / Kyp
        at = a_s + c.QHZ1 + c.QHZ2 * dfz + (c.QHZ3 + c.QHZ4 * dfz) * gs
        Bt = ((c.QBZ1 + c.QBZ2 * dfz + c.QBZ3 * dfz * dfz)
              * (1.0 + c.QBZ4 * gamma + c.QBZ5 * np.abs(gamma)) * c.LKY / c.LMUY)
        Ct = c.QCZ1
        Dt = ((c.QDZ1 + c.QDZ2 * dfz) * (1.0 - c.PPZ1 * dpi)
              * (1.0 + c.QDZ3 * gamma + c.QDZ4 * gamma * gamma) * Fz * self.r0 / fz0 * c.LTR)
        Et = np.minimum((c.QEZ1 + c.QEZ2 * dfz + c.QEZ3 * dfz * dfz)
                        * (1.0 + (c.QEZ4 + c.QEZ5 * gs) * (2.0 / np.pi)
                           * np.arctan(Bt * Ct * at)), 1.0)
        Br = c.QBZ9 * c.LKY / c.LMUY + c.QBZ10 * By * Cy
        Dr = (Fz * self.r0 * ((c.QDZ6 + c.QDZ7 * dfz) * c.LRES
                              + ((c.QDZ8 + c.QDZ9 * dfz) * (1.0 + c.PPZ2 * dpi)
                                 + (c.QDZ10 + c.QDZ11 * dfz) * np.abs(gs)) * gs * c.LKZC)
              * lmuy * np.cos(a_s))
        cos_a = np.cos(alpha)
        if Kx is None:   # pure slip
            t = Dt * np.cos(Ct * np.arctan(Bt * at - Et * (Bt * at - np.arctan(Bt * at)))) \
                * cos_a
            return -t * Fyg0 + Dr * np.cos(np.arctan(Br * ar)) * cos_a
        k2 = (Kx / Kyp * kappa) ** 2
        at = np.arctan(np.sqrt(np.tan(at) ** 2 + k2)) * _sgn1(at)
        ar = np.arctan(np.sqrt(np.tan(ar) ** 2 + k2)) * _sgn1(ar)
        t = (Dt * np.cos(Ct * np.arctan(Bt * at - Et * (Bt * at - np.arctan(Bt * at))))
             * cos_a * c.LFZO)
        s = self.r0 * (c.SSZ1 + c.SSZ2 * Fy / self.fnomin + (c.SSZ3 + c.SSZ4 * dfz) * gamma) \
            * c.LS
        return -t * Fyg0 + Dr * np.cos(np.arctan(Br * ar)) + s * Fx

