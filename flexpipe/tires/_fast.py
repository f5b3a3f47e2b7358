"""Compiled (Numba) wheel forces of a Magic Formula tyre: the per-step hot path of a car run.

:meth:`flexpipe.tires.contact.TireModel.wheel_forces` with the PAC2002 model is NumPy code
vectorised over the wheels; for the 4 to 24 rows a car step evaluates, NumPy's per-call
overhead dominates (measured 0.4 ms per call, two calls per step).  This module evaluates
the same equations row by row in one compiled function: contact geometry, vertical force,
effective rolling radius, slips, first-order relaxation (slip-velocity form) and the
PAC2002 Magic Formula (pure and combined slip, aligning, overturning and rolling
resistance moments) or the MF 6.1 / 6.2 one.  It is a transcription of
:mod:`flexpipe.tires.contact`, :mod:`flexpipe.tires.relaxation`,
:mod:`flexpipe.tires.vertical`, :mod:`flexpipe.tires.pac2002` and
:mod:`flexpipe.tires.mf61`, which stay the reference: ``tests/test_tire_fast.py`` checks
both against each other on random inputs for every ``.tir`` file at hand.

Numba is the standard JIT compiler for numerical Python (``cache=True``: compiled once per
machine into ``__pycache__``).  Setting the environment variable ``FLEXPIPE_NO_JIT=1``
makes every tyre use the NumPy code.
"""

from __future__ import annotations

import math
import os

import numpy as np

from flexpipe.tires import _keys

try:  # numba is a dependency; the NumPy path stays usable without it
    from numba import njit
except ImportError:  # pragma: no cover - exercised only without numba
    njit = None

_COEFFS = (_keys.SCALING + _keys.LONGITUDINAL + _keys.LATERAL + _keys.ALIGNING
           + _keys.OVERTURNING + _keys.ROLLING)
_EXTRA = ("fnomin", "fz0", "r0_mf", "use_mode", "kmin", "kmax", "amin", "amax", "gmin",
          "gmax", "fz_max", "longvl", "vxlow_mf", "k", "k2", "k3", "c_vert", "R0", "relax",
          "vxlow", "has_reff", "breff", "dreff", "freff", "mf6", "dpi", "p_ratio", "fz_min",
          "cx0", "cy0", "pcfx1", "pcfx2", "pcfx3", "pcfy1", "pcfy2", "pcfy3")
#: every number the compiled tyre needs, as one record of floats (a NumPy structured
#: dtype: a one-element array of it passes to compiled code at the cost of an array, and
#: its fields read by name there)
PACKED = np.dtype([(name, np.float64) for name in tuple(_COEFFS) + _EXTRA])

KAPPA_STATE_MAX = 1.5  # as flexpipe.tires.contact
TAN_ALPHA_STATE_MAX = 10.0


def check_rows(bad: int, spin_axis) -> None:
    """Raise the NumPy tyre's error for the first bad row ``bad`` the kernel reported
    (-1: none): a zero or non-finite spin axis, else road normal."""
    if bad >= 0:
        from flexpipe.errors import InputError

        s = spin_axis[bad]
        name = "spin_axis" if not np.isfinite(s).all() or not s.any() else "road_normal"
        raise InputError(f"{name} must be non-zero, finite vectors", key=name)


def enabled() -> bool:
    """True when the compiled path is available and not switched off."""
    return njit is not None and os.environ.get("FLEXPIPE_NO_JIT", "") not in ("1", "true")


def pack(tire) -> np.ndarray:
    """The numbers of a :class:`~flexpipe.tires.model.Pac2002Tire`: a one-element array of
    :data:`PACKED`."""
    mf, vert = tire.mf, tire.vertical
    c = mf.c
    have = tire.breff is not None
    extra = dict(
        fnomin=mf.fnomin, fz0=mf.fz0, r0_mf=mf.r0, use_mode=float(mf.use_mode),
        kmin=mf.kappa_range[0], kmax=mf.kappa_range[1], amin=mf.alpha_range[0],
        amax=mf.alpha_range[1], gmin=mf.gamma_range[0], gmax=mf.gamma_range[1],
        fz_max=mf.fz_max, longvl=mf.longvl, vxlow_mf=mf.vxlow, k=vert.k, k2=vert.k2,
        k3=vert.k3,
        c_vert=vert.c, R0=tire.unloaded_radius, relax=float(bool(tire.relaxation)),
        vxlow=tire.vxlow, has_reff=float(have), breff=tire.breff or 0.0,
        dreff=tire.dreff or 0.0, freff=tire.freff or 0.0)
    from flexpipe.tires.mf61 import MagicFormula61

    mf6 = isinstance(mf, MagicFormula61)
    extra.update(mf6=float(mf6), dpi=mf.dpi if mf6 else 0.0,
                 p_ratio=mf.pressure / mf.nominal_pressure if mf6 else 1.0,
                 fz_min=mf.fz_min if mf6 else 0.0, cx0=mf.cx0 if mf6 else np.nan,
                 cy0=mf.cy0 if mf6 else np.nan)
    for i in range(3):
        extra[f"pcfx{i + 1}"] = mf.pcfx[i] if mf6 else 0.0
        extra[f"pcfy{i + 1}"] = mf.pcfy[i] if mf6 else 0.0
    out = np.zeros(1, dtype=PACKED)
    for k in _COEFFS:
        out[k] = float(getattr(c, k))
    for k in _EXTRA:
        out[k] = float(extra[k])
    return out


def _jit(fn):
    return njit(cache=True, error_model="numpy")(fn) if njit is not None else fn


def drop_stale_caches(kernels, *sources) -> None:
    """Empty the disk cache of ``kernels`` written before a file of ``sources`` changed.

    Numba checks a cached kernel against its own source file only, but a kernel that
    calls compiled functions of another file holds their machine code too: after an edit
    or a ``git pull`` of that file alone, it would run the old code.  A cache index older
    than one of ``sources`` is emptied, so the kernel compiles again at its next call.
    """
    if njit is None:
        return
    newest = max(os.path.getmtime(f) for f in sources)
    for k in kernels:
        try:
            index = k._cache._cache_file._index_path
            if os.path.exists(index) and os.path.getmtime(index) < newest:
                k._cache.flush()
        except (AttributeError, OSError):  # another Numba layout, or a read-only cache
            pass


@_jit
def _mf(B, C, E, x):
    Bx = B * x
    return math.sin(C * math.atan(Bx - E * (Bx - math.atan(Bx))))


@_jit
def _cosmf(B, C, E, x):
    Bx = B * x
    return math.cos(C * math.atan(Bx - E * (Bx - math.atan(Bx))))


@_jit
def _sign(x):
    return 1.0 if x > 0.0 else (-1.0 if x < 0.0 else 0.0)


@_jit
def _clip(x, lo, hi):
    return lo if x < lo else (hi if x > hi else x)


@_jit
def _phi(a):
    return 1.0 - 0.5 * a if a < 1e-6 else -math.expm1(-a) / a


@_jit
def _sgn1(x):
    return 1.0 if x >= 0.0 else -1.0


@_jit
def _kx6(q, Fz, dfz):
    return (Fz * (q.PKX1 + q.PKX2 * dfz) * math.exp(q.PKX3 * dfz)
            * (1.0 + q.PPX1 * q.dpi + q.PPX2 * q.dpi * q.dpi) * q.LKX)


@_jit
def _ky6(q, Fz, gs):
    return (q.PKY1 * q.fz0 * (1.0 + q.PPY1 * q.dpi) * (1.0 - q.PKY3 * abs(gs))
            * math.sin(q.PKY4 * math.atan(Fz / q.fz0 / ((q.PKY2 + q.PKY5 * gs * gs)
                                                        * (1.0 + q.PPY2 * q.dpi)))) * q.LKY)


@_jit
def _fy6(q, a_s, Fz, dfz, gs, lmuy):
    """MF 6.x pure Fy0 with Kya, By, Cy, muy, SHy, SVy (see :mod:`flexpipe.tires.mf61`)."""
    Ky = _ky6(q, Fz, gs)
    Kyg0 = Fz * (q.PKY6 + q.PKY7 * dfz) * (1.0 + q.PPY5 * q.dpi) * q.LKYC
    SVyg = Fz * (q.PVY3 + q.PVY4 * dfz) * gs * q.LKYC * lmuy
    SHy = (q.PHY1 + q.PHY2 * dfz) * q.LHY + (Kyg0 * gs - SVyg) / (Ky + 1e-6 * _sgn1(Ky))
    SVy = Fz * (q.PVY1 + q.PVY2 * dfz) * q.LVY * lmuy + SVyg
    ay = a_s + SHy
    Cy = q.PCY1 * q.LCY
    muy = ((q.PDY1 + q.PDY2 * dfz) * (1.0 + q.PPY3 * q.dpi + q.PPY4 * q.dpi * q.dpi)
           * (1.0 - q.PDY3 * gs * gs) * lmuy)
    Ey = min((q.PEY1 + q.PEY2 * dfz) * (1.0 + q.PEY5 * gs * gs - (q.PEY3 + q.PEY4 * gs)
                                        * _sgn1(ay)) * q.LEY, 1.0)
    By = Ky / (Cy * muy * Fz)
    return muy * Fz * _mf(By, Cy, Ey, ay) + SVy, Ky, By, Cy, muy, SHy, SVy


@_jit
def _slip_forces6(q, kappa, alpha, Fz_in, gamma, vx, mirror, mu):
    """MF 6.1 / 6.2 steady-state (Fx, Fy, Mz, Mx, My), W-axes, for one wheel: a
    transcription of :meth:`flexpipe.tires.mf61.MagicFormula61.forces`."""
    fz0, fnom, dpi = q.fz0, q.fnomin, q.dpi
    Fz = _clip(Fz_in, 1e-9 * fnom, q.fz_max)
    dfz = (Fz - fz0) / fz0
    sgn = -1.0 if mirror else 1.0
    kappa = _clip(kappa, q.kmin, q.kmax)
    alpha = _clip(sgn * alpha, q.amin, q.amax)
    gamma = _clip(sgn * gamma, q.gmin, q.gmax)
    a_s, gs = math.tan(alpha), math.sin(gamma)
    lmux, lmuy = q.LMUX * mu, q.LMUY * mu
    mode = int(q.use_mode)
    Fx = Fy = Mz = Mx = My = 0.0
    Kx = 0.0
    if mode == 1 or mode == 3 or mode == 4:
        kx = kappa + (q.PHX1 + q.PHX2 * dfz) * q.LHX
        Cx = q.PCX1 * q.LCX
        Dx = ((q.PDX1 + q.PDX2 * dfz) * (1.0 + q.PPX3 * dpi + q.PPX4 * dpi * dpi)
              * (1.0 - q.PDX3 * gamma * gamma) * lmux * Fz)
        Ex = min((q.PEX1 + q.PEX2 * dfz + q.PEX3 * dfz * dfz)
                 * (1.0 - q.PEX4 * _sign(kx)) * q.LEX, 1.0)
        Kx = _kx6(q, Fz, dfz)
        Fx = Dx * _mf(Kx / (Cx * Dx), Cx, Ex, kx) + Fz * (q.PVX1 + q.PVX2 * dfz) * q.LVX * lmux
    if mode == 2 or mode == 3 or mode == 4:
        Fy0, Ky, By, Cy, muy, SHy, SVy = _fy6(q, a_s, Fz, dfz, gs, lmuy)
        Fyg0 = _fy6(q, a_s, Fz, dfz, 0.0, lmuy)[0]
        Fy = Fy0
        combined = mode == 4
        if combined:
            SHxa = q.RHX1
            Bxa = (q.RBX1 + q.RBX3 * gs * gs) * math.cos(math.atan(q.RBX2 * kappa)) * q.LXAL
            Exa = min(q.REX1 + q.REX2 * dfz, 1.0)
            Fx = Fx * _cosmf(Bxa, q.RCX1, Exa, a_s + SHxa) / _cosmf(Bxa, q.RCX1, Exa, SHxa)
            SHyk = q.RHY1 + q.RHY2 * dfz
            Byk = ((q.RBY1 + q.RBY4 * gs * gs) * math.cos(math.atan(q.RBY2 * (a_s - q.RBY3)))
                   * q.LYKA)
            Eyk = min(q.REY1 + q.REY2 * dfz, 1.0)
            Gyk = _cosmf(Byk, q.RCY1, Eyk, kappa + SHyk) / _cosmf(Byk, q.RCY1, Eyk, SHyk)
            DVyk = (muy * Fz * (q.RVY1 + q.RVY2 * dfz + q.RVY3 * gs)
                    * math.cos(math.atan(q.RVY4 * a_s)))
            Fy = Fy0 * Gyk + DVyk * math.sin(q.RVY5 * math.atan(q.RVY6 * kappa)) * q.LVYKA
            Fyg0 = Fyg0 * Gyk
        # aligning moment
        Kyp = Ky + 1e-6 * _sgn1(Ky)
        ar = a_s + SHy + SVy / Kyp
        at = a_s + q.QHZ1 + q.QHZ2 * dfz + (q.QHZ3 + q.QHZ4 * dfz) * gs
        Bt = ((q.QBZ1 + q.QBZ2 * dfz + q.QBZ3 * dfz * dfz)
              * (1.0 + q.QBZ4 * gamma + q.QBZ5 * abs(gamma)) * q.LKY / q.LMUY)
        Ct = q.QCZ1
        Dt = ((q.QDZ1 + q.QDZ2 * dfz) * (1.0 - q.PPZ1 * dpi)
              * (1.0 + q.QDZ3 * gamma + q.QDZ4 * gamma * gamma) * Fz * q.r0_mf / fz0 * q.LTR)
        Et = min((q.QEZ1 + q.QEZ2 * dfz + q.QEZ3 * dfz * dfz)
                 * (1.0 + (q.QEZ4 + q.QEZ5 * gs) * (2.0 / math.pi) * math.atan(Bt * Ct * at)),
                 1.0)
        Br = q.QBZ9 * q.LKY / q.LMUY + q.QBZ10 * By * Cy
        Dr = (Fz * q.r0_mf * ((q.QDZ6 + q.QDZ7 * dfz) * q.LRES
                              + ((q.QDZ8 + q.QDZ9 * dfz) * (1.0 + q.PPZ2 * dpi)
                                 + (q.QDZ10 + q.QDZ11 * dfz) * abs(gs)) * gs * q.LKZC)
              * lmuy * math.cos(a_s))
        cos_a = math.cos(alpha)
        if combined:
            k2 = (Kx / Kyp * kappa) ** 2
            at = math.atan(math.sqrt(math.tan(at) ** 2 + k2)) * _sgn1(at)
            ar = math.atan(math.sqrt(math.tan(ar) ** 2 + k2)) * _sgn1(ar)
            t = Dt * _cosmf(Bt, Ct, Et, at) * cos_a * q.LFZO
            s = (q.r0_mf * (q.SSZ1 + q.SSZ2 * Fy / fnom + (q.SSZ3 + q.SSZ4 * dfz) * gamma)
                 * q.LS)
            Mz = -t * Fyg0 + Dr * math.cos(math.atan(Br * ar)) + s * Fx
        else:
            t = Dt * _cosmf(Bt, Ct, Et, at) * cos_a
            Mz = -t * Fyg0 + Dr * math.cos(math.atan(Br * ar)) * cos_a
        Fze = Fz * (Fz / q.fz_min) ** 2 if Fz < q.fz_min else Fz
        Mx = (q.r0_mf * Fze * q.LMX
              * (q.QSX1 * q.LVMX - q.QSX2 * gamma * (1.0 + q.PPMX1 * dpi) + q.QSX3 * Fy / fnom
                 + q.QSX4 * math.cos(q.QSX5 * math.atan((q.QSX6 * Fze / fnom) ** 2))
                 * math.sin(q.QSX7 * gamma + q.QSX8 * math.atan(q.QSX9 * Fy / fnom))
                 + q.QSX10 * math.atan(q.QSX11 * Fze / fnom) * gamma)
              + q.r0_mf * q.LMX * (Fy * (q.QSX13 + q.QSX14 * abs(gamma))
                                   - Fze * q.QSX12 * gamma * abs(gamma)))
    if mode == 1 or mode == 3 or mode == 4:
        vr = vx / q.longvl
        Fze = Fz * Fz / q.fz_min if Fz < q.fz_min else Fz
        My = (-q.r0_mf * fnom * q.LMY
              * (q.QSY1 + q.QSY2 * Fx / fnom + q.QSY3 * abs(vr) + q.QSY4 * vr ** 4
                 + (q.QSY5 + q.QSY6 * Fze / fnom) * gamma * gamma)
              * (Fze / fnom) ** q.QSY7 * q.p_ratio ** q.QSY8 * math.tanh(vx / q.vxlow_mf))
    if not Fz_in > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    return Fx, sgn * Fy, sgn * Mz, sgn * Mx, My


@_jit
def slip_forces(q, kappa, alpha, Fz_in, gamma, vx, mirror, mu):
    """PAC2002 steady-state (Fx, Fy, Mz, Mx, My), W-axes, for one wheel (see
    :meth:`flexpipe.tires.pac2002.MagicFormula.forces`); an MF 6.x tyre's by
    :func:`_slip_forces6`."""
    if q.mf6 > 0.0:
        return _slip_forces6(q, kappa, alpha, Fz_in, gamma, vx, mirror, mu)
    fz0 = q.fz0
    Fz = _clip(Fz_in, 1e-9 * q.fnomin, q.fz_max)
    dfz = (Fz - fz0) / fz0
    sgn = -1.0 if mirror else 1.0
    kappa = _clip(kappa, q.kmin, q.kmax)
    alpha = _clip(sgn * alpha, q.amin, q.amax)
    gamma = _clip(sgn * gamma, q.gmin, q.gmax)
    lmux, lmuy = q.LMUX * mu, q.LMUY * mu
    mode = int(q.use_mode)
    Fx = Fy = Mz = Mx = My = 0.0
    Kx = 0.0
    if mode == 1 or mode == 3 or mode == 4:
        SHx = (q.PHX1 + q.PHX2 * dfz) * q.LHX
        kx = kappa + SHx
        gx = gamma * q.LGAX
        Cx = q.PCX1 * q.LCX
        Dx = (q.PDX1 + q.PDX2 * dfz) * (1.0 - q.PDX3 * gx * gx) * lmux * Fz
        Ex = min((q.PEX1 + q.PEX2 * dfz + q.PEX3 * dfz * dfz)
                 * (1.0 - q.PEX4 * _sign(kx)) * q.LEX, 1.0)
        Kx = Fz * (q.PKX1 + q.PKX2 * dfz) * math.exp(q.PKX3 * dfz) * q.LKX
        SVx = Fz * (q.PVX1 + q.PVX2 * dfz) * q.LVX * lmux
        Fx = Dx * _mf(Kx / (Cx * Dx), Cx, Ex, kx) + SVx
    if mode == 2 or mode == 3 or mode == 4:
        gy = gamma * q.LGAY
        SHy = (q.PHY1 + q.PHY2 * dfz) * q.LHY + q.PHY3 * gy
        ay = alpha + SHy
        Cy = q.PCY1 * q.LCY
        muy = (q.PDY1 + q.PDY2 * dfz) * (1.0 - q.PDY3 * gy * gy) * lmuy
        Dy = muy * Fz
        Ey = min((q.PEY1 + q.PEY2 * dfz) * (1.0 - (q.PEY3 + q.PEY4 * gy) * _sign(ay)) * q.LEY,
                 1.0)
        Ky = (q.PKY1 * fz0 * math.sin(2.0 * math.atan(Fz / (q.PKY2 * fz0)))
              * (1.0 - q.PKY3 * abs(gy)) * q.LKY)
        By = Ky / (Cy * Dy)
        SVy = Fz * ((q.PVY1 + q.PVY2 * dfz) * q.LVY + (q.PVY3 + q.PVY4 * dfz) * gy) * lmuy
        Fy0 = Dy * _mf(By, Cy, Ey, ay) + SVy
        Fy = Fyp = Fy0
        combined = mode == 4
        if combined:
            SHxa = q.RHX1
            Bxa = q.RBX1 * math.cos(math.atan(q.RBX2 * kappa)) * q.LXAL
            Exa = min(q.REX1 + q.REX2 * dfz, 1.0)
            Fx = Fx * _cosmf(Bxa, q.RCX1, Exa, alpha + SHxa) / _cosmf(Bxa, q.RCX1, Exa, SHxa)
            SHyk = q.RHY1 + q.RHY2 * dfz
            Byk = q.RBY1 * math.cos(math.atan(q.RBY2 * (alpha - q.RBY3))) * q.LYKA
            Eyk = min(q.REY1 + q.REY2 * dfz, 1.0)
            DVyk = (muy * Fz * (q.RVY1 + q.RVY2 * dfz + q.RVY3 * gamma)
                    * math.cos(math.atan(q.RVY4 * alpha)))
            SVyk = DVyk * math.sin(q.RVY5 * math.atan(q.RVY6 * kappa)) * q.LVYKA
            Fyp = Fy0 * _cosmf(Byk, q.RCY1, Eyk, kappa + SHyk) / _cosmf(Byk, q.RCY1, Eyk, SHyk)
            Fy = Fyp + SVyk
        # aligning moment (kappa, Fx, Kx enter only for combined slip)
        ka = kappa if combined else 0.0
        Fxa = Fx if combined else 0.0
        Kxa = Kx if combined else 0.0
        gz = gamma * q.LGAZ
        SHt = q.QHZ1 + q.QHZ2 * dfz + (q.QHZ3 + q.QHZ4 * dfz) * gz
        at = alpha + SHt
        ar = alpha + SHy + SVy / Ky
        Bt = ((q.QBZ1 + q.QBZ2 * dfz + q.QBZ3 * dfz * dfz)
              * (1.0 + q.QBZ4 * gz + q.QBZ5 * abs(gz)) * q.LKY / q.LMUY)
        Ct = q.QCZ1
        Dt = (Fz * (q.QDZ1 + q.QDZ2 * dfz) * (1.0 + q.QDZ3 * gz + q.QDZ4 * gz * gz)
              * q.r0_mf / fz0 * q.LTR)
        Et = min((q.QEZ1 + q.QEZ2 * dfz + q.QEZ3 * dfz * dfz)
                 * (1.0 + (q.QEZ4 + q.QEZ5 * gz) * (2.0 / math.pi) * math.atan(Bt * Ct * at)),
                 1.0)
        Br = q.QBZ9 * q.LKY / q.LMUY + q.QBZ10 * By * Cy
        Dr = (Fz * ((q.QDZ6 + q.QDZ7 * dfz) * q.LRES + (q.QDZ8 + q.QDZ9 * dfz) * gz) * q.r0_mf
              * lmuy)
        cos_a = math.cos(alpha)
        if ka != 0.0:
            k2 = (Kxa / Ky * ka) ** 2
            at = math.atan(math.sqrt(math.tan(at) ** 2 + k2)) * _sign(at)
            ar = math.atan(math.sqrt(math.tan(ar) ** 2 + k2)) * _sign(ar)
        t = Dt * math.cos(Ct * math.atan(Bt * at - Et * (Bt * at - math.atan(Bt * at)))) * cos_a
        Mzr = Dr * math.cos(math.atan(Br * ar)) * cos_a
        s = (q.SSZ1 + q.SSZ2 * Fy / fz0 + (q.SSZ3 + q.SSZ4 * dfz) * gamma) * q.r0_mf * q.LS
        Mz = -t * Fyp + Mzr + s * Fxa
        Mx = q.r0_mf * Fz * (q.QSX1 * q.LVMX - q.QSX2 * gamma + q.QSX3 * Fy / fz0) * q.LMX
    if mode == 1 or mode == 3 or mode == 4:
        vr = vx / q.longvl
        My = (-q.r0_mf * Fz * (q.QSY1 + q.QSY2 * Fx / fz0 + q.QSY3 * abs(vr) + q.QSY4 * vr ** 4)
              * q.LMY * math.tanh(vx / q.vxlow_mf))
    if not Fz_in > 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    return Fx, sgn * Fy, sgn * Mz, sgn * Mx, My


@_jit
def _relaxation_lengths(q, Fz, gamma):
    Fz = _clip(Fz, 1e-9 * q.fnomin, q.fz_max)
    dfz = (Fz - q.fz0) / q.fz0
    if q.mf6 > 0.0:   # MF 6.x: slip stiffness over carcass stiffness (nan without one)
        Cx = q.cx0 * (1.0 + q.pcfx1 * dfz + q.pcfx2 * dfz * dfz) * (1.0 + q.pcfx3 * q.dpi)
        Cy = q.cy0 * (1.0 + q.pcfy1 * dfz + q.pcfy2 * dfz * dfz) * (1.0 + q.pcfy3 * q.dpi)
        return abs(_kx6(q, Fz, dfz) / Cx), abs(_ky6(q, Fz, math.sin(gamma)) / Cy)
    sk = (Fz * (q.PTX1 + q.PTX2 * dfz) * math.exp(-q.PTX3 * dfz) * q.r0_mf / q.fnomin
          * q.LSGKP) if q.PTX1 != 0.0 else np.nan
    sa = (q.PTY1 * math.sin(2.0 * math.atan(Fz / (q.PTY2 * q.fz0))) * (1.0 - q.PKY3 * abs(gamma))
          * q.r0_mf * q.LFZO * q.LSGAL) if (q.PTY1 != 0.0 and q.PTY2 != 0.0) else np.nan
    return sk, sa


@_jit
def _cross3(a0, a1, a2, b0, b1, b2):
    return a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0


@_jit
def wheel_kernel(qa, C, s_in, n_in, omega, v, w, has_w, road_h, mirror, mu, st_k, st_t,
                 has_state, dt, out):
    """All wheels: fills ``out`` (rows, 32) with F(3), M(3), P(3), frame(9), Fx, Fy, Fz,
    Mx, My, Mz, kappa, alpha, gamma, rho, rho_dot, new kappa', new tan(alpha')
    (see :meth:`flexpipe.tires.contact.TireModel.wheel_forces`).  Returns the index of the
    first row with a zero or non-finite spin axis or road normal, else -1."""
    q = qa[0]
    for i in range(C.shape[0]):
        ns = math.sqrt(s_in[i, 0] ** 2 + s_in[i, 1] ** 2 + s_in[i, 2] ** 2)
        nn = math.sqrt(n_in[i, 0] ** 2 + n_in[i, 1] ** 2 + n_in[i, 2] ** 2)
        if not (ns > 0.0 and nn > 0.0 and math.isfinite(ns) and math.isfinite(nn)):
            return i
        s0, s1, s2 = s_in[i, 0] / ns, s_in[i, 1] / ns, s_in[i, 2] / ns
        n0, n1, n2 = n_in[i, 0] / nn, n_in[i, 1] / nn, n_in[i, 2] / nn
        h = n2 * (C[i, 2] - road_h[i])
        gamma = math.asin(_clip(s0 * n0 + s1 * n1 + s2 * n2, -1.0, 1.0))
        x0, x1, x2 = _cross3(s0, s1, s2, n0, n1, n2)
        cos_g = math.sqrt(x0 * x0 + x1 * x1 + x2 * x2)
        ok = cos_g > 1e-6
        cs = cos_g if ok else 1.0
        x0, x1, x2 = x0 / cs, x1 / cs, x2 / cs
        y0, y1, y2 = _cross3(n0, n1, n2, x0, x1, x2)
        d0, d1, d2 = _cross3(s0, s1, s2, x0, x1, x2)
        Rl = h / cs
        rho = q.R0 - Rl if ok else -1.0
        r0_, r1_, r2_ = Rl * d0, Rl * d1, Rl * d2  # P - C
        rho_dot = -(n0 * v[i, 0] + n1 * v[i, 1] + n2 * v[i, 2]) / cs
        f = q.k * rho + q.k2 * rho * rho + q.k3 * rho ** 3 + q.c_vert * rho_dot
        Fz = max(f, 0.0) if rho > 0.0 else 0.0
        V0, V1, V2 = v[i, 0], v[i, 1], v[i, 2]
        if has_w:
            ws = w[i, 0] * s0 + w[i, 1] * s1 + w[i, 2] * s2
            c0, c1, c2 = _cross3(w[i, 0] - ws * s0, w[i, 1] - ws * s1, w[i, 2] - ws * s2,
                                 r0_, r1_, r2_)
            V0, V1, V2 = V0 + c0, V1 + c1, V2 + c2
        Vcx = V0 * x0 + V1 * x1 + V2 * x2
        Vcy = V0 * y0 + V1 * y1 + V2 * y2
        rp = max(rho, 0.0)
        if q.has_reff > 0.0:
            rho0 = q.fnomin / q.k
            rd = rp / rho0
            Re = q.R0 - rho0 * (q.dreff * math.atan(q.breff * rd) + q.freff * rd)
        else:
            Re = q.R0 - rp / 3.0
        Vsx = Vcx - omega[i] * Re
        vden = max(abs(Vcx), q.vxlow)
        kappa = -Vsx / vden
        tan_a = Vcy / vden
        if q.relax > 0.0 and has_state:
            sk, sa = _relaxation_lengths(q, max(Fz, 1e-3), gamma)
            touch = Fz > 0.0
            if sk > 0.0:
                a = abs(Vcx) * dt / sk
                kn = st_k[i] * math.exp(-a) + (-Vsx) * dt / sk * _phi(a)
                kappa = _clip(kn, -KAPPA_STATE_MAX, KAPPA_STATE_MAX) if touch else 0.0
            if sa > 0.0:
                a = abs(Vcx) * dt / sa
                tn = st_t[i] * math.exp(-a) + Vcy * dt / sa * _phi(a)
                tan_a = _clip(tn, -TAN_ALPHA_STATE_MAX, TAN_ALPHA_STATE_MAX) if touch else 0.0
        alpha = math.atan(tan_a)
        Fx, Fy, Mz, Mx, My = slip_forces(q, kappa, alpha, Fz, gamma, Vcx, mirror[i], mu[i])
        F0 = Fx * x0 + Fy * y0 + Fz * n0
        F1 = Fx * x1 + Fy * y1 + Fz * n1
        F2 = Fx * x2 + Fy * y2 + Fz * n2
        m0, m1, m2 = _cross3(r0_, r1_, r2_, F0, F1, F2)
        o = out[i]
        o[0], o[1], o[2] = F0, F1, F2
        o[3] = m0 + Mx * x0 + My * y0 + Mz * n0
        o[4] = m1 + Mx * x1 + My * y1 + Mz * n1
        o[5] = m2 + Mx * x2 + My * y2 + Mz * n2
        o[6], o[7], o[8] = C[i, 0] + r0_, C[i, 1] + r1_, C[i, 2] + r2_
        o[9], o[10], o[11] = x0, x1, x2
        o[12], o[13], o[14] = y0, y1, y2
        o[15], o[16], o[17] = n0, n1, n2
        o[18], o[19], o[20], o[21], o[22], o[23] = Fx, Fy, Fz, Mx, My, Mz
        o[24], o[25], o[26], o[27], o[28] = kappa, alpha, gamma, rho, rho_dot
        o[29], o[30] = kappa, tan_a
    return -1
