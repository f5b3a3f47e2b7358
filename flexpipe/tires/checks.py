"""Checks of a ``.tir`` file: key names, units, and physical ranges (values in SI, after the
``[UNITS]`` conversion).

Key names: an unknown key in a PAC2002 / MF_05 coefficient section (or FIALA
``[PARAMETER]``) is an error; elsewhere an unknown key or section warns, unless it is one
edit away from a known one (a typo that would silently fall back to a default), which is an
error.

Magic Formula version: ``[MODEL] FITTYP`` must be 6 or 21 (MF 5.2) or 61 / 62 (MF 6.1 /
6.2) when given; another version is an error (:func:`check_fittyp`).  MF 6.x coefficients
with a non-neutral value in an MF 5.2 file warn, since they are ignored
(:func:`warn_unused_mf6`).

Every value that would make the tyre model divide by zero, return NaN, or give plausible
but wrong forces is rejected with an :class:`~flexpipe.errors.InputError` naming the file,
the line, the key and the valid range:

* radius, nominal load, stiffness and the force range must be positive
  (``UNLOADED_RADIUS``, ``FNOMIN``, ``VERTICAL_STIFFNESS``, ``FZMAX`` > 0; damping and
  ``FZMIN`` >= 0; a given ``RIM_RADIUS`` < ``UNLOADED_RADIUS``; ``FZMIN`` < ``FZMAX``);
  dimensions the models do not use (``WIDTH``, ``BOTTOMING_RADIUS`` ...) are not checked;
* radius, nominal load and vertical stiffness must be those of a road-vehicle tyre
  (0.05-5 m, 10 N-2 MN, 1e3-1e9 N/m): outside, a ``[UNITS]`` entry is usually wrong;
  the reference speed ``LONGVL`` that of a tyre measurement (1-100 m/s; rigs run at
  10-30 m/s, and PAC2002 divides the speed by it);
* input ranges must be ordered and hold zero (``KPUMIN <= 0 <= KPUMAX``, ``KPUMIN <
  KPUMAX``; the same for ``ALPMIN/ALPMAX`` (within +-pi/2) and ``CAMMIN/CAMMAX``), since the
  model clips its inputs to them;
* PAC2002 factors that divide or set a peak (``LFZO``, ``LCZ`` > 0; for the force
  directions the USE_MODE computes: ``LMUX, LCX, LKX, LMUY, LCY, LKY`` > 0 and ``PKY1,
  PKY2`` non-zero);
* PAC2002 coefficients whose sign the physics fixes (ISO/Adams W-axes, see
  :mod:`flexpipe.tires.pac2002`), for the directions the USE_MODE computes: shape factors
  and peak friction ``PCX1, PDX1, PCY1, PDY1`` > 0, longitudinal slip stiffness ``PKX1`` > 0,
  cornering stiffness at the nominal load < 0 (``PKY1 < 0`` with ``PKY2 > 0``), rolling
  resistance ``QSY1`` >= 0, pneumatic trail ``QDZ1`` >= 0 and relaxation lengths at the
  nominal load >= 0 (``PTX1`` >= 0, ``PTY1`` and ``PTY2`` of one sign);
* ``[MODEL] TYRESIDE`` is ``LEFT``, ``RIGHT`` or ``SYMMETRIC`` (any case);
* a ``[DEFLECTION_LOAD_CURVE] {pen fz}`` table needs increasing deflections >= 0 and
  non-decreasing loads >= 0.
"""

from __future__ import annotations

import difflib
import math
import warnings

import numpy as np

from flexpipe.errors import InputError
from flexpipe.tires import _keys

_POSITIVE = {
    "DIMENSION": ("UNLOADED_RADIUS",),
    "VERTICAL": ("FNOMIN", "VERTICAL_STIFFNESS"),
    "VERTICAL_FORCE_RANGE": ("FZMAX",),
    "SCALING_COEFFICIENTS": ("LFZO", "LCZ"),
    "PARAMETER": ("CSLIP", "CALPHA", "UMAX", "UMIN"),
}
_NONNEGATIVE = {
    "VERTICAL": ("VERTICAL_DAMPING",),
    "VERTICAL_FORCE_RANGE": ("FZMIN",),
    "PARAMETER": ("ROLLING_RESISTANCE", "RELAX_LENGTH_X", "RELAX_LENGTH_Y"),
}
_UNITS_HINT = "a tyre outside it usually means a wrong [UNITS] entry"
_PLAUSIBLE = (  # section, key, low, high (SI), why: any road-vehicle tyre, bicycle to mining truck
    ("DIMENSION", "UNLOADED_RADIUS", 0.05, 5.0, "m", _UNITS_HINT),
    ("VERTICAL", "FNOMIN", 10.0, 2e6, "N", _UNITS_HINT),
    ("VERTICAL", "VERTICAL_STIFFNESS", 1e3, 1e9, "N/m", _UNITS_HINT),
    # the reference speed of the measurement: tyre rigs and trailers run at 10-30 m/s (the
    # published files: 16.6-16.7); PAC2002 divides the speed by it (rolling resistance), so
    # 0 has no meaning, and no tyre is measured below walking pace or above 360 km/h
    ("MODEL", "LONGVL", 1.0, 100.0, "m/s", "the reference speed of the tyre measurement, "
     "10-30 m/s on tyre rigs; the model divides the speed by it"),
)
_RANGES = (  # section, low key, high key, default low, default high, absolute limit
    ("LONG_SLIP_RANGE", "KPUMIN", "KPUMAX", -1.5, 1.5, math.inf),
    ("SLIP_ANGLE_RANGE", "ALPMIN", "ALPMAX", -1.5707, 1.5707, math.pi / 2 + 1e-3),
    ("INCLINATION_ANGLE_RANGE", "CAMMIN", "CAMMAX", -0.5, 0.5, math.pi / 2),
)
_MF_LONG = (("SCALING_COEFFICIENTS", ("LMUX", "LCX", "LKX"), True),)
_MF_LAT = (("SCALING_COEFFICIENTS", ("LMUY", "LCY", "LKY"), True),
           ("LATERAL_COEFFICIENTS", ("PKY1", "PKY2"), False))
#: Valid ``[MODEL] TYRESIDE`` values: the side the tyre was measured on (a wheel on the
#: other side gets the mirrored characteristic) or SYMMETRIC (never mirrored).
TYRE_SIDES = ("LEFT", "RIGHT", "SYMMETRIC")
# Coefficients that must be given and be > 0 for the directions the USE_MODE computes, with
# why: in the ISO/Adams W-axes of PAC2002 (x forward, y left, z up) a driving slip kappa > 0
# gives Fx > 0, so the slip stiffness Kx = Fz0' PKX1 LKX at the nominal load is positive;
# C (shape) and D = mu Fz (peak) are positive by the Magic Formula's definition (every
# published fit: C about 1.2-1.8, mu 0.5-1.7).  A zero C or D gives NaN forces, a zero PKX1
# Fx = 0 at any slip.
_MF_POSITIVE = {
    "LONG": (
        ("LONGITUDINAL_COEFFICIENTS", "PCX1", "the Fx shape factor Cx, positive by definition "
         "and about 1.4-1.8 in fitted tyres; it must be non-zero: a zero gives NaN forces"),
        ("LONGITUDINAL_COEFFICIENTS", "PDX1", "the peak friction coefficient mu_x at the "
         "nominal load, about 0.6-1.5 on a dry road; it must be non-zero: a zero gives NaN "
         "forces"),
        ("LONGITUDINAL_COEFFICIENTS", "PKX1", "Kx/Fz, the longitudinal slip stiffness at the "
         "nominal load, about 10-30; in the ISO/Adams W-axes a driving slip kappa > 0 gives "
         "Fx > 0, and a zero gives Fx = 0 at any slip"),
    ),
    "LAT": (
        ("LATERAL_COEFFICIENTS", "PCY1", "the Fy shape factor Cy, positive by definition and "
         "about 1.2-1.6 in fitted tyres; it must be non-zero: a zero gives NaN forces"),
        ("LATERAL_COEFFICIENTS", "PDY1", "the peak friction coefficient mu_y at the nominal "
         "load, about 0.6-1.5 on a dry road; it must be non-zero: a zero gives NaN forces"),
    ),
}


def check_tir(path, fmt: str, use_mode: int, sections, lines, tables) -> None:
    """Raise :class:`InputError` for the first physically invalid value (see module notes)."""

    def fail(sec, key, value, valid):
        raise InputError(f"[{sec}] {key} = {value:g} is out of range; valid: {valid}",
                         file=path, line=lines.get((sec, key)), key=key)

    def value(sec, key):
        v = sections.get(sec, {}).get(key)
        return v if isinstance(v, float) else None

    for sec, keys in _POSITIVE.items():
        for key in keys:
            v = value(sec, key)
            if v is not None and not v > 0.0:
                fail(sec, key, v, "> 0")
    for sec, keys in _NONNEGATIVE.items():
        for key in keys:
            v = value(sec, key)
            if v is not None and not v >= 0.0:
                fail(sec, key, v, ">= 0")
    for sec, key, lo, hi, unit, why in _PLAUSIBLE:
        v = value(sec, key)
        if v is not None and not lo <= v <= hi:
            fail(sec, key, v, f"{lo:g} .. {hi:g} {unit} after the [UNITS] conversion ({why})")
    r0, rim = value("DIMENSION", "UNLOADED_RADIUS"), value("DIMENSION", "RIM_RADIUS")
    if r0 is not None and rim is not None and rim > 0.0 and rim >= r0:
        fail("DIMENSION", "RIM_RADIUS", rim, f"< UNLOADED_RADIUS = {r0:g} m")
    umax, umin = value("PARAMETER", "UMAX"), value("PARAMETER", "UMIN")
    if umax is not None and umin is not None and umin > umax:
        fail("PARAMETER", "UMIN", umin, f"<= UMAX = {umax:g}")
    fzmin, fzmax = value("VERTICAL_FORCE_RANGE", "FZMIN"), value("VERTICAL_FORCE_RANGE", "FZMAX")
    if fzmin is not None and fzmax is not None and fzmin >= fzmax:
        fail("VERTICAL_FORCE_RANGE", "FZMIN", fzmin, f"< FZMAX = {fzmax:g} N")
    for sec, lo_key, hi_key, lo_def, hi_def, limit in _RANGES:
        lo, hi = value(sec, lo_key), value(sec, hi_key)
        lo_v = lo_def if lo is None else lo
        hi_v = hi_def if hi is None else hi
        if lo is not None and not -limit <= lo <= 0.0:
            fail(sec, lo_key, lo, f"in [{-limit:.4g}, 0] (the model clips its input to it)")
        if hi is not None and not 0.0 <= hi <= limit:
            fail(sec, hi_key, hi, f"in [0, {limit:.4g}] (the model clips its input to it)")
        if not lo_v < hi_v:
            fail(sec, lo_key if lo is not None else hi_key, lo_v if lo is not None else hi_v,
                 f"{lo_key} < {hi_key} (got {lo_v:g} and {hi_v:g})")
    _check_tyre_side(path, sections, lines)
    if fmt in _keys.MF52_FORMATS:
        mode = abs(int(use_mode)) % 10
        long_, lat = mode in (1, 3, 4), mode in (2, 3, 4)
        for sec, key, why in (_MF_POSITIVE["LONG"] if long_ else ()) + (
                _MF_POSITIVE["LAT"] if lat else ()):
            v = value(sec, key)
            if v is None:
                raise InputError(f"[{sec}] has no {key}; USE_MODE {use_mode} needs it: {why}",
                                 file=path, line=lines.get((sec, "")), key=key)
            if not v > 0.0:
                fail(sec, key, v, f"> 0 ({why})")
        groups = (_MF_LONG if long_ else ()) + (_MF_LAT if lat else ())
        for sec, keys, positive in groups:
            for key in keys:
                v = value(sec, key)
                if v is None and not positive:
                    raise InputError(f"[{sec}] has no {key}; USE_MODE {use_mode} needs it "
                                     "(a zero would give NaN forces)", file=path,
                                     line=lines.get((sec, "")), key=key)
                if v is not None and (not v > 0.0 if positive else v == 0.0):
                    fail(sec, key, v, "> 0" if positive else "non-zero (a zero gives NaN "
                                                               "forces)")
        _check_mf_signs(path, sections, lines, value, fail, long_=long_, lat=lat)
    table = tables.get("DEFLECTION_LOAD_CURVE")
    if table is not None:
        _check_load_curve(path, table)


def _check_tyre_side(path, sections, lines) -> None:
    """``[MODEL] TYRESIDE`` must be one of :data:`TYRE_SIDES` (a typo such as 'RIGTH' would
    otherwise make an asymmetric tyre silently symmetric)."""
    side = sections.get("MODEL", {}).get("TYRESIDE")
    if side is None or (isinstance(side, str) and side.strip().upper() in TYRE_SIDES):
        return
    shown = f"'{side}'" if isinstance(side, str) else f"{side:g}"
    raise InputError(f"[MODEL] TYRESIDE = {shown} is not valid; valid: "
                     f"{', '.join(repr(s) for s in TYRE_SIDES)} (case-insensitive): the side "
                     "of the vehicle the tyre was measured on, or SYMMETRIC", file=path,
                     line=lines.get(("MODEL", "TYRESIDE")), key="TYRESIDE")


def _check_mf_signs(path, sections, lines, value, fail, *, long_: bool, lat: bool) -> None:
    """Signs of PAC2002 coefficients fixed by the physics in the ISO/Adams W-axes.

    Evaluated at the scaled nominal load Fz0' = FNOMIN LFZO (dfz = 0, no camber), where the
    formulas of :mod:`flexpipe.tires.pac2002` reduce to a product of the coefficients.
    """
    if lat:
        # Ky = PKY1 Fz0' sin(2 atan(Fz/(PKY2 Fz0'))) LKY has the sign of PKY1 PKY2 at every
        # load (LKY > 0 is checked).  In the W-axes a positive slip angle (contact patch
        # moving to +y) gives a negative Fy, so Ky < 0: every PAC2002 fit has PKY1 < 0
        # (about -10 to -25) and PKY2 > 0 (the load ratio at which |Ky| peaks, about 1-4).
        # A wrong sign reverses every side force.
        pky1 = value("LATERAL_COEFFICIENTS", "PKY1")
        pky2 = value("LATERAL_COEFFICIENTS", "PKY2")
        if pky1 and pky2 and pky1 * pky2 > 0.0:
            fz0 = (value("VERTICAL", "FNOMIN") or 0.0) * (
                value("SCALING_COEFFICIENTS", "LFZO") or 1.0)
            ky = pky1 * fz0 * math.sin(2.0 * math.atan(1.0 / pky2)) * (
                value("SCALING_COEFFICIENTS", "LKY") or 1.0)
            key, v = ("PKY1", pky1) if pky2 > 0.0 else ("PKY2", pky2)
            fail("LATERAL_COEFFICIENTS", key, v,
                 "PKY1 < 0 with PKY2 > 0 (got PKY1 = "
                 f"{pky1:g}, PKY2 = {pky2:g}: cornering stiffness Ky = {ky:+.4g} N/rad at the "
                 "nominal load; in the ISO/Adams W-axes of PAC2002 a positive slip angle gives "
                 "a negative Fy, so Ky must be < 0; was the sign flipped or the file fitted in "
                 "another axis system?)")
        # pneumatic trail t = Dt cos(...) with Dt = Fz QDZ1 R0/Fz0' LTR at the nominal load:
        # the trail lies behind the contact centre, so the aligning moment turns the wheel
        # back towards zero slip angle (fits: QDZ1 about 0.05-0.2); < 0 reverses Mz
        v = value("ALIGNING_COEFFICIENTS", "QDZ1")
        if v is not None and v < 0.0:
            fail("ALIGNING_COEFFICIENTS", "QDZ1", v, ">= 0 (peak pneumatic trail / R0 at the "
                 "nominal load, about 0.05-0.2; a negative trail reverses the aligning moment)")
        # sigma_alpha = PTY1 sin(2 atan(Fz/(PTY2 Fz0'))) R0 LFZO LSGAL: a length, >= 0
        pty1 = value("LATERAL_COEFFICIENTS", "PTY1")
        pty2 = value("LATERAL_COEFFICIENTS", "PTY2")
        if pty1 and pty2 and pty1 * pty2 < 0.0:
            key, v = ("PTY1", pty1) if pty1 < 0.0 else ("PTY2", pty2)
            fail("LATERAL_COEFFICIENTS", key, v, "PTY1 and PTY2 of the same sign (PTY1 > 0 "
                 f"with PTY2 > 0, the usual fit, or both < 0; got PTY1 = {pty1:g}, PTY2 = "
                 f"{pty2:g}): the lateral relaxation length PTY1 sin(2 atan(Fz/(PTY2 Fz0))) "
                 "R0 is a length, about 1-3 R0; opposite signs make it negative")
    if long_:
        # rolling resistance My = -R0 Fz (QSY1 + ...) tanh(Vx/VXLOW) opposes the rolling
        # (fits: QSY1 about 0.005-0.02); a negative QSY1 would push the wheel forward
        v = value("ROLLING_COEFFICIENTS", "QSY1")
        if v is not None and v < 0.0:
            fail("ROLLING_COEFFICIENTS", "QSY1", v, ">= 0 (rolling resistance coefficient, "
                 "about 0.005-0.02; a negative value drives the wheel instead of braking it)")
        # sigma_kappa = Fz0' PTX1 R0/FNOMIN LSGKP at the nominal load: a length, >= 0
        # (0 = no relaxation data)
        v = value("LONGITUDINAL_COEFFICIENTS", "PTX1")
        if v is not None and v < 0.0:
            fail("LONGITUDINAL_COEFFICIENTS", "PTX1", v, ">= 0 (longitudinal relaxation "
                 "length / R0 at the nominal load, about 0.5-3; 0 means no relaxation data)")


def _check_load_curve(path, table) -> None:
    cols = table.columns
    if "pen" not in cols or "fz" not in cols:
        raise InputError(f"[DEFLECTION_LOAD_CURVE] table columns are {{{' '.join(cols)}}}; "
                         "expected {pen fz}", file=path, line=table.line)
    pen, fz = table.column("pen"), table.column("fz")
    bad = np.flatnonzero((pen < 0.0) | (fz < 0.0))
    if bad.size:
        i = int(bad[0])
        raise InputError(f"[DEFLECTION_LOAD_CURVE] row {i + 1} (pen {pen[i]:g} m, fz "
                         f"{fz[i]:g} N) is negative; deflection and load must be >= 0",
                         file=path, line=_row_line(table, i))
    for name, a, strict in (("pen", pen, True), ("fz", fz, False)):
        step = np.diff(a)
        wrong = np.flatnonzero(step <= 0.0 if strict else step < 0.0)
        if wrong.size:
            i = int(wrong[0]) + 1
            raise InputError(f"[DEFLECTION_LOAD_CURVE] {name} of row {i + 1} ({a[i]:g}) does "
                             f"not {'increase' if strict else 'stay or increase'} from row "
                             f"{i} ({a[i - 1]:g})", file=path, line=_row_line(table, i))
    if np.count_nonzero(pen > 0.0) < 2:
        raise InputError("[DEFLECTION_LOAD_CURVE] needs at least two rows with pen > 0",
                         file=path, line=table.line)


def _row_line(table, i: int):
    return table.row_lines[i] if i < len(table.row_lines) else table.line


def probe_forces(tire, path) -> None:
    """Raise :class:`InputError` if ``tire`` gives a non-finite force in its normal range.

    Evaluated at loads 0.1-2 x nominal, slips -0.5..0.5, slip angles -0.3..0.3 rad and
    camber -0.05..0.05 rad: catches coefficient combinations the single-key checks cannot.
    """
    fn = getattr(getattr(tire, "mf", None), "fnomin", None) or 4000.0
    Fz = np.array([0.1, 0.5, 1.0, 2.0])[:, None, None, None] * fn
    kappa = np.array([-0.5, -0.05, 0.0, 0.05, 0.5])[None, :, None, None]
    alpha = np.array([-0.3, 0.0, 0.3])[None, None, :, None]
    gamma = np.array([-0.05, 0.0, 0.05])[None, None, None, :]
    with np.errstate(all="ignore"):
        f = tire.slip_forces(kappa, alpha, Fz, gamma)
    for name in ("Fx", "Fy", "Mz", "Mx", "My"):
        a = np.broadcast_to(np.asarray(getattr(f, name), dtype=float),
                            np.broadcast_shapes(Fz.shape, kappa.shape, alpha.shape, gamma.shape))
        bad = np.argwhere(~np.isfinite(a))
        if bad.size:
            i, j, k, m = bad[0]
            raise InputError(
                f"the tyre coefficients give {name} = {a[i, j, k, m]} at Fz = "
                f"{float(Fz[i, 0, 0, 0]):g} N, kappa = {float(kappa[0, j, 0, 0]):g}, alpha = "
                f"{float(alpha[0, 0, k, 0]):g} rad, gamma = {float(gamma[0, 0, 0, m]):g} rad; "
                "check the Magic Formula / Fiala coefficients for zeros or overflow", file=path)


# ---------------------------------------------------------------- warnings
def file_warning(message: str) -> None:
    """Warn (:class:`UserWarning`) about a tyre file, always from this one code location.

    The message names the file (and line), so under Python's default warning filter each
    message is shown once per process: reading or building the same file again (a script
    calling :func:`~flexpipe.tires.read_tir` and then
    :func:`~flexpipe.tires.tire_from_file`, a car with the file on several corners) does
    not repeat it, while a filter ``"always"`` (e.g. :func:`pytest.warns`) still sees every
    read.
    """
    warnings.warn(message, UserWarning, stacklevel=1)


# ---------------------------------------------------------------- Magic Formula version
def check_fittyp(path, sections, lines) -> None:
    """``[MODEL] FITTYP``, when given, must mark a Magic Formula version flexpipe evaluates:
    MF 5.2 (:data:`_keys.MF52_FITTYP`) or MF 6.1 / 6.2 (:data:`_keys.MF6_EVALUATED`).

    Any other version (e.g. MF 6.0, FITTYP 60, whose equations are neither) would give
    plausible but wrong forces, so it is refused rather than read.
    """
    raw = sections.get("MODEL", {}).get("FITTYP")
    if raw is None:
        return
    line = lines.get(("MODEL", "FITTYP"))
    valid = sorted(_keys.MF52_FITTYP + _keys.MF6_EVALUATED)
    supported = ("flexpipe evaluates Magic Formula 5.2 (FITTYP 6 or 21, or no FITTYP as in "
                 "Adams PAC2002 files) and MF 6.1 / 6.2 (FITTYP 61 / 62)")
    try:
        value = float(raw)
    except (TypeError, ValueError):
        value = math.nan
    if not math.isfinite(value) or value != int(value):
        raise InputError(f"[MODEL] FITTYP = '{raw}' is not a Magic Formula version number; "
                         f"{supported}", file=path, line=line, key="FITTYP")
    fittyp = int(value)
    if fittyp in valid:
        return
    what = (f"a Magic Formula {_keys.MF6_FITTYP[fittyp]} fit" if fittyp in _keys.MF6_FITTYP
            else "no Magic Formula version flexpipe knows")
    raise InputError(f"[MODEL] FITTYP = {fittyp} marks {what}; valid: "
                     f"{', '.join(str(v) for v in valid)}: {supported}; evaluating the fit "
                     "with another version's equations would give wrong forces",
                     file=path, line=line, key="FITTYP")


def warn_unused_mf6(path, sections, lines) -> None:
    """One warning listing the MF 6.x coefficients of an MF 5.2 / PAC2002 file that have a
    non-neutral value (:data:`_keys.MF6_ONLY`, and :data:`_keys.PRESSURE_TERMS` when the
    file's inflation pressure differs from its nominal one): they are ignored."""

    def num(sec, key):
        v = sections.get(sec, {}).get(key)
        return v if isinstance(v, float) else None

    found = []
    for (sec, key), (neutral, what) in _keys.MF6_ONLY.items():
        v = num(sec, key)
        if v is not None and v not in neutral:
            shown = " or ".join(f"{n:g}" for n in neutral)
            found.append((lines[(sec, key)], f"[{sec}] {key} = {v:g} (line "
                          f"{lines[(sec, key)]}; {what}; neutral: {shown})"))
    pressure = None
    for sec, key, nom_key in _keys.PRESSURE_PAIRS:
        p, p0 = num(sec, key), num(sec, nom_key)
        if p is not None and p0 is not None and not math.isclose(p, p0, rel_tol=1e-9):
            pressure = (f"{key} = {p:g} Pa differs from {nom_key} = {p0:g} Pa (line "
                        f"{lines[(sec, key)]})")
            break
    if pressure is not None:
        for sec, key in _keys.PRESSURE_TERMS:
            v = num(sec, key)
            if v:
                found.append((lines[(sec, key)], f"[{sec}] {key} = {v:g} (line "
                              f"{lines[(sec, key)]}; inflation pressure term)"))
    if not found:
        return
    found.sort()
    n = len(found)
    text = (f"{path}: {'an MF 6.x coefficient' if n == 1 else f'{n} MF 6.x coefficients'} "
            f"with a non-neutral value {'is' if n == 1 else 'are'} ignored: "
            f"{'; '.join(t for _, t in found)}. flexpipe evaluates the PAC2002 / MF 5.2 "
            f"equations, which have no such term{'' if n == 1 else 's'}, so the forces are "
            "not those an MF 6.x evaluation of this file would give")
    if pressure is not None and any("pressure term" in t for _, t in found):
        text += (f"; the pressure terms would act because {pressure}, but flexpipe gives the "
                 "forces at the nominal pressure")
    file_warning(text)


# ---------------------------------------------------------------- keys and units
def unit_factors(path, units: dict, lines: dict) -> dict[str, float]:
    factors = {}
    for quantity in _keys.UNIT_QUANTITIES:
        name = units.get(quantity)
        if name is None:
            factors[quantity] = 1.0
            continue
        table = _keys.UNIT_FACTORS[quantity]
        key = str(name).strip().lower()
        if key not in table:
            raise InputError(
                f"[UNITS] {quantity} = '{name}' is not a known unit; valid: "
                f"{', '.join(sorted(table))}", file=path, line=lines.get(("UNITS", quantity)),
                key=quantity)
        factors[quantity] = table[key]
    return factors


def scale(exponents, factors) -> float:
    return math.prod(factors[q] ** e for q, e in zip(_keys.UNIT_QUANTITIES, exponents, strict=True)
                     if e)


def check_keys(path, fmt, sections, lines, *, strict_as=None):
    """Unknown sections and keys (see :mod:`flexpipe.tires._keys`); ``strict_as`` checks
    the file as one of that format (an MF 6.x fit as a PAC2002 file: the same keys)."""
    strict = {"PAC2002": _keys.PAC2002_STRICT, "MF_05": _keys.PAC2002_STRICT,
              "FIALA": _keys.FIALA_STRICT}.get(strict_as or fmt, {})
    for name, sec in sections.items():
        allowed = strict.get(name)
        if allowed is None:
            allowed = _keys.KNOWN_SECTIONS.get(name)
            if allowed is None:
                if name not in _keys.FREE_SECTIONS and name not in _keys.PAC2002_STRICT:
                    close = difflib.get_close_matches(name, _ALL_SECTIONS, n=1, cutoff=0.85)
                    if close:   # a misspelt known section would silently drop its data
                        raise InputError(f"unknown section [{name}] (did you mean "
                                         f"[{close[0]}]?)", file=path,
                                         line=lines[(name, "")], key=name)
                    file_warning(f"{path}, line {lines[(name, '')]}: unknown section [{name}]"
                                 " kept but not used")
                continue
            for key in sec:
                if key not in allowed:
                    close = [k for k in sorted(allowed) if _one_edit(key, k)]
                    if close:   # a misspelt known key would silently fall back to a default
                        raise InputError(f"unknown key {key} in [{name}] (did you mean "
                                         f"{close[0]}?)", file=path, line=lines[(name, key)],
                                         key=key)
                    file_warning(f"{path}, line {lines[(name, key)]}: key {key} is not a "
                                 f"known entry of [{name}]; ignored")
            continue
        for key in sec:
            if key not in allowed:
                close = difflib.get_close_matches(key, sorted(allowed), n=3, cutoff=0.6)
                hint = f" (did you mean {' or '.join(close)}?)" if close else ""
                raise InputError(
                    f"unknown key {key} in [{name}] of a {fmt} file{hint}; valid keys: "
                    f"{', '.join(sorted(allowed))}", file=path, line=lines[(name, key)], key=key)


def _one_edit(a: str, b: str) -> bool:
    """True if ``a`` becomes ``b`` by one insertion, deletion, substitution or swap of two
    neighbours -- except a changed digit (``Q_FZ4`` is another coefficient, not a typo)."""
    if a == b or abs(len(a) - len(b)) > 1:
        return False
    if len(a) == len(b):
        diff = [i for i in range(len(a)) if a[i] != b[i]]
        if len(diff) == 1:
            return not (a[diff[0]].isdigit() and b[diff[0]].isdigit())
        return (len(diff) == 2 and diff[1] == diff[0] + 1 and a[diff[0]] == b[diff[1]]
                and a[diff[1]] == b[diff[0]])
    short, long_ = (a, b) if len(a) < len(b) else (b, a)
    return any(long_[:i] + long_[i + 1:] == short for i in range(len(long_)))


_ALL_SECTIONS = sorted(set(_keys.KNOWN_SECTIONS) | set(_keys.FREE_SECTIONS)
                       | set(_keys.PAC2002_STRICT) | set(_keys.FIALA_STRICT))
