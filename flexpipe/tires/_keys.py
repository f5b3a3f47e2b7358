"""Known sections, keys and unit dimensions of TeimOrbit tyre property files.

The tables here decide which entries :func:`flexpipe.tires.read_tir` accepts:

* ``STRICT_SECTIONS`` — coefficient sections of ``PAC2002`` / ``MF_05`` files (and the
  ``[PARAMETER]`` section of ``FIALA`` files).  A key that is not listed is a user error (a
  typo such as ``PKY11`` would otherwise silently become a default of zero).  The lists
  contain the PAC2002 / MF-Tyre 5.2 coefficients plus the MF 6.x extensions that
  PAC2002-labelled files in the wild carry (inflation pressure ``PPX*``/``PPY*``/``QPZ*``,
  extra overturning ``QSX4..`` and rolling ``QSY5..`` terms, turn slip); the extensions are
  accepted but not used by the model: ``MF6_ONLY`` lists those that change the forces, and
  a file that gives one of them a value other than its neutral one gets a warning.
* ``MF52_FORMATS`` / ``MF52_FITTYP`` / ``MF6_FITTYP`` / ``MF6_EVALUATED`` — the ``[MODEL]
  PROPERTY_FILE_FORMAT`` and ``FITTYP`` values of Magic Formula 5.2 files and of MF 6.x
  fits (6.1 and 6.2 evaluated by :mod:`flexpipe.tires.mf61`, 6.0 refused).
* ``KNOWN_SECTIONS`` — other sections whose unknown keys only warn.
* ``UNIT_DIMENSIONS`` — exponents ``(length, force, angle, mass, time, pressure)`` of the
  dimensional keys; these are converted to SI according to ``[UNITS]``.  Magic Formula
  coefficients are non-dimensional (radian based) by definition and are never converted.
"""

from __future__ import annotations


def _seq(prefix: str, first: int, last: int) -> list[str]:
    return [f"{prefix}{i}" for i in range(first, last + 1)]


SCALING = [
    "LFZO", "LCX", "LMUX", "LEX", "LKX", "LHX", "LVX", "LGAX", "LCY", "LMUY", "LEY", "LKY",
    "LHY", "LVY", "LGAY", "LTR", "LRES", "LGAZ", "LXAL", "LYKA", "LVYKA", "LS", "LSGKP",
    "LSGAL", "LGYR", "LMX", "LVMX", "LMY", "LCZ", "LIP", "LKG", "LKYC", "LKZC", "LKYG",
    "LMUV", "LMP", "LKXC", "LMPHI",
]
LONGITUDINAL = (
    ["PCX1"] + _seq("PDX", 1, 3) + _seq("PEX", 1, 4) + _seq("PKX", 1, 3) + _seq("PHX", 1, 2)
    + _seq("PVX", 1, 2) + _seq("RBX", 1, 3) + ["RCX1"] + _seq("REX", 1, 2) + ["RHX1"]
    + _seq("PTX", 1, 4) + _seq("PPX", 1, 4)
)
OVERTURNING = _seq("QSX", 1, 14) + ["QPX1", "PPMX1"]
LATERAL = (
    ["PCY1"] + _seq("PDY", 1, 3) + _seq("PEY", 1, 5) + _seq("PKY", 1, 7) + _seq("PHY", 1, 3)
    + _seq("PVY", 1, 4) + _seq("RBY", 1, 4) + ["RCY1"] + _seq("REY", 1, 2) + _seq("RHY", 1, 2)
    + _seq("RVY", 1, 6) + _seq("PTY", 1, 3) + _seq("PPY", 1, 5)
)
ROLLING = _seq("QSY", 1, 8)
ALIGNING = (
    _seq("QBZ", 1, 6) + ["QBZ9", "QBZ10", "QCZ1"] + _seq("QDZ", 1, 4) + _seq("QDZ", 6, 11)
    + _seq("QEZ", 1, 5) + _seq("QHZ", 1, 4) + _seq("SSZ", 1, 4) + ["QTZ1", "MBELT"]
    + _seq("QPZ", 1, 2) + _seq("PPZ", 1, 2)
)
TURNSLIP = (
    _seq("PDXP", 1, 3) + ["PKYP1"] + _seq("PDYP", 1, 4) + _seq("PHYP", 1, 4)
    + _seq("PECP", 1, 2) + ["QDTP1"] + _seq("QCRP", 1, 2) + ["QBRP1"] + _seq("QDRP", 1, 2)
)
FIALA_PARAMETER = [
    "CSLIP", "CALPHA", "CGAMMA", "UMIN", "UMAX", "RELAX_LENGTH_X", "RELAX_LENGTH_Y",
    "ROLLING_RESISTANCE",
]

#: ``[MODEL] PROPERTY_FILE_FORMAT`` values evaluated with the MF 5.2 equations of
#: :mod:`flexpipe.tires.pac2002`: Adams ``PAC2002`` and TNO MF-Tyre 5.x ``MF_05`` files
#: (the same equations and coefficient names; Project Chrono's PAC2002 reader, where the
#: reference files come from, accepts both alike).
MF52_FORMATS = ("PAC2002", "MF_05")
#: ``[MODEL] FITTYP`` of a Magic Formula 5.2 fit (MF-Tyre writes 6 or 21; Adams PAC2002
#: files usually have no FITTYP at all).
MF52_FITTYP = (6, 21)
#: ``[MODEL] FITTYP`` of the Magic Formula 6.x fits (MF-Tyre / MF-Swift 6.x): version.
MF6_FITTYP = {60: "6.0", 61: "6.1", 62: "6.2"}
#: Those evaluated with the MF 6.1 / 6.2 equations (:mod:`flexpipe.tires.mf61`), whatever
#: the file's PROPERTY_FILE_FORMAT ('MF-TYRE', 'USER', 'MF_61', ...).
MF6_EVALUATED = (61, 62)

#: Coefficients of the MF 6.x equations that the MF 5.2 / PAC2002 equations do not have
#: (warned about in an MF 5.2 file only; an MF 6.1 / 6.2 file is evaluated with them):
#: ``(section, key) -> (neutral values, what it changes)``.  A value other than a neutral
#: one would change the forces under MF 6.x but is ignored here, so it warns.  Neutral:
#: the value that gives the MF 5.2 result, plus 0 where 0 is only a placeholder (PKY4 = 0
#: would give no cornering stiffness, QSY7 = 0 a rolling resistance independent of the
#: load; PAC2002 files list them as 0).
MF6_ONLY = {
    ("LATERAL_COEFFICIENTS", "PKY4"): ((2.0, 0.0), "the shape of the cornering "
                                       "stiffness over the load"),
    ("LATERAL_COEFFICIENTS", "PKY5"): ((0.0,), "the camber effect on the load of peak "
                                       "cornering stiffness"),
    ("LATERAL_COEFFICIENTS", "PKY6"): ((0.0,), "the camber stiffness Kygamma"),
    ("LATERAL_COEFFICIENTS", "PKY7"): ((0.0,), "the load dependency of the camber stiffness"),
    ("LATERAL_COEFFICIENTS", "PEY5"): ((0.0,), "the camber effect on the Fy curvature"),
    ("ROLLING_COEFFICIENTS", "QSY5"): ((0.0,), "the camber effect on the rolling resistance"),
    ("ROLLING_COEFFICIENTS", "QSY6"): ((0.0,), "the camber and load effect on the rolling "
                                       "resistance"),
    ("ROLLING_COEFFICIENTS", "QSY7"): ((1.0, 0.0), "the load exponent of the rolling "
                                       "resistance"),
    **{("OVERTURNING_COEFFICIENTS", k): ((0.0,), "the overturning moment Mx")
       for k in _seq("QSX", 4, 14)},
}
#: Inflation-pressure coefficients (MF 6.x and later PAC2002 versions): neutral when 0 or
#: when the file's pressure equals its nominal pressure (``[OPERATING_CONDITIONS]
#: INFLPRES``/``NOMPRES`` or ``[TIRE_CONDITIONS] IP``/``IP_NOM``).
PRESSURE_TERMS = (
    [("LONGITUDINAL_COEFFICIENTS", k) for k in _seq("PPX", 1, 4)]
    + [("LATERAL_COEFFICIENTS", k) for k in _seq("PPY", 1, 5)]
    + [("ALIGNING_COEFFICIENTS", k) for k in ("PPZ1", "PPZ2", "QPZ1", "QPZ2")]
    + [("OVERTURNING_COEFFICIENTS", k) for k in ("PPMX1", "QPX1")]
    + [("ROLLING_COEFFICIENTS", "QSY8")]
)
#: ``(section, actual pressure key, nominal pressure key)`` pairs read for PRESSURE_TERMS.
PRESSURE_PAIRS = (("OPERATING_CONDITIONS", "INFLPRES", "NOMPRES"),
                  ("TIRE_CONDITIONS", "IP", "IP_NOM"))

#: Coefficient sections of a PAC2002 file: unknown keys are errors.
PAC2002_STRICT = {
    "SCALING_COEFFICIENTS": frozenset(SCALING),
    "LONGITUDINAL_COEFFICIENTS": frozenset(LONGITUDINAL),
    "OVERTURNING_COEFFICIENTS": frozenset(OVERTURNING),
    "LATERAL_COEFFICIENTS": frozenset(LATERAL),
    "ROLLING_COEFFICIENTS": frozenset(ROLLING),
    "ALIGNING_COEFFICIENTS": frozenset(ALIGNING),
    "TURNSLIP_COEFFICIENTS": frozenset(TURNSLIP),
}
#: Strict sections of a FIALA file.
FIALA_STRICT = {"PARAMETER": frozenset(FIALA_PARAMETER)}

#: Other sections with a known key list: unknown keys warn.
KNOWN_SECTIONS = {
    "UNITS": frozenset(["LENGTH", "FORCE", "ANGLE", "MASS", "TIME", "PRESSURE"]),
    "DIMENSION": frozenset(
        ["UNLOADED_RADIUS", "WIDTH", "ASPECT_RATIO", "RIM_RADIUS", "RIM_WIDTH",
         "BOTTOMING_RADIUS"]
    ),
    "VERTICAL": frozenset(
        ["VERTICAL_STIFFNESS", "VERTICAL_DAMPING", "BREFF", "DREFF", "FREFF", "FNOMIN",
         "DYNAMIC_STIFFNESS", "DYNAMIC_DAMPING", "Q_RE0", "Q_V1", "Q_V2", "Q_FZ1", "Q_FZ2",
         "Q_FZ3", "Q_FCX", "Q_FCY", "Q_FCY2", "Q_CAM", "Q_CAM1", "Q_CAM2", "Q_CAM3", "Q_FYS1",
         "Q_FYS2", "Q_FYS3", "PFZ1", "BOTTOM_OFFST", "BOTTOM_STIFF", "Q_RA1", "Q_RA2",
         "Q_RB1", "Q_RB2", "Q_A1", "Q_A2", "VERTICAL_STIFFNESS_CUBIC"]
    ),
    "LONG_SLIP_RANGE": frozenset(["KPUMIN", "KPUMAX"]),
    "SLIP_ANGLE_RANGE": frozenset(["ALPMIN", "ALPMAX"]),
    "INCLINATION_ANGLE_RANGE": frozenset(["CAMMIN", "CAMMAX"]),
    "VERTICAL_FORCE_RANGE": frozenset(["FZMIN", "FZMAX"]),
    "TIRE_CONDITIONS": frozenset(["IP", "IP_NOM"]),
    "OPERATING_CONDITIONS": frozenset(["INFLPRES", "NOMPRES"]),
    "INFLATION_PRESSURE_RANGE": frozenset(["PRESMIN", "PRESMAX"]),
}
#: Sections read without any key check (free-form or tables).
FREE_SECTIONS = frozenset(
    ["MDI_HEADER", "MODEL", "SHAPE", "DEFLECTION_LOAD_CURVE", "BOTTOMING_CURVE", "INERTIA",
     "STRUCTURAL", "CONTACT_PATCH", "TYRE_CONDITIONS", "ROAD", "PARAMETER"]
)

#: Keys of the coefficient sections whose value must be a number.
NUMERIC_SECTIONS = frozenset(PAC2002_STRICT) | {"PARAMETER"} | {
    "DIMENSION", "VERTICAL", "LONG_SLIP_RANGE", "SLIP_ANGLE_RANGE", "INCLINATION_ANGLE_RANGE",
    "VERTICAL_FORCE_RANGE",
}

# exponents of (length, force, angle, mass, time, pressure)
_L = (1, 0, 0, 0, 0, 0)
_F = (0, 1, 0, 0, 0, 0)
_A = (0, 0, 1, 0, 0, 0)
_M = (0, 0, 0, 1, 0, 0)
_P = (0, 0, 0, 0, 0, 1)
_F_PER_L = (-1, 1, 0, 0, 0, 0)
_FT_PER_L = (-1, 1, 0, 0, 1, 0)
_V = (1, 0, 0, 0, -1, 0)

#: ``(section, key) -> exponents`` of the dimensional keys converted to SI.
UNIT_DIMENSIONS = {
    ("DIMENSION", "UNLOADED_RADIUS"): _L,
    ("DIMENSION", "WIDTH"): _L,
    ("DIMENSION", "RIM_RADIUS"): _L,
    ("DIMENSION", "RIM_WIDTH"): _L,
    ("DIMENSION", "BOTTOMING_RADIUS"): _L,
    ("VERTICAL", "VERTICAL_STIFFNESS"): _F_PER_L,
    ("VERTICAL", "VERTICAL_DAMPING"): _FT_PER_L,
    ("VERTICAL", "FNOMIN"): _F,
    ("VERTICAL", "DYNAMIC_STIFFNESS"): _F_PER_L,
    ("VERTICAL", "DYNAMIC_DAMPING"): _FT_PER_L,
    ("VERTICAL", "VERTICAL_STIFFNESS_CUBIC"): (-3, 1, 0, 0, 0, 0),
    ("VERTICAL", "BOTTOM_OFFST"): _L,
    ("VERTICAL", "BOTTOM_STIFF"): _F_PER_L,
    ("MODEL", "LONGVL"): _V,
    ("MODEL", "VXLOW"): _V,
    ("SLIP_ANGLE_RANGE", "ALPMIN"): _A,
    ("SLIP_ANGLE_RANGE", "ALPMAX"): _A,
    ("INCLINATION_ANGLE_RANGE", "CAMMIN"): _A,
    ("INCLINATION_ANGLE_RANGE", "CAMMAX"): _A,
    ("VERTICAL_FORCE_RANGE", "FZMIN"): _F,
    ("VERTICAL_FORCE_RANGE", "FZMAX"): _F,
    ("TIRE_CONDITIONS", "IP"): _P,
    ("TIRE_CONDITIONS", "IP_NOM"): _P,
    ("OPERATING_CONDITIONS", "INFLPRES"): _P,
    ("OPERATING_CONDITIONS", "NOMPRES"): _P,
    ("INFLATION_PRESSURE_RANGE", "PRESMIN"): _P,
    ("INFLATION_PRESSURE_RANGE", "PRESMAX"): _P,
    ("ALIGNING_COEFFICIENTS", "MBELT"): _M,
    ("STRUCTURAL", "LONGITUDINAL_STIFFNESS"): _F_PER_L,
    ("STRUCTURAL", "LATERAL_STIFFNESS"): _F_PER_L,
    ("PARAMETER", "CSLIP"): _F,
    ("PARAMETER", "CALPHA"): (0, 1, -1, 0, 0, 0),
    ("PARAMETER", "CGAMMA"): (0, 1, -1, 0, 0, 0),
    ("PARAMETER", "RELAX_LENGTH_X"): _L,
    ("PARAMETER", "RELAX_LENGTH_Y"): _L,
}
#: Column dimensions of known tables (by section); unknown tables are kept unconverted.
TABLE_DIMENSIONS = {
    "DEFLECTION_LOAD_CURVE": (_L, _F),
    "BOTTOMING_CURVE": (_L, _F),
}

#: Recognised unit names (lower case) -> factor to SI, per quantity.
UNIT_FACTORS = {
    "LENGTH": {
        "meter": 1.0, "meters": 1.0, "metre": 1.0, "m": 1.0, "millimeter": 1e-3,
        "millimeters": 1e-3, "millimetre": 1e-3, "mm": 1e-3, "centimeter": 1e-2, "cm": 1e-2,
        "kilometer": 1e3, "km": 1e3, "inch": 0.0254, "inches": 0.0254, "in": 0.0254,
        "foot": 0.3048, "feet": 0.3048, "ft": 0.3048,
    },
    "FORCE": {
        "newton": 1.0, "newtons": 1.0, "n": 1.0, "kilonewton": 1e3, "kn": 1e3,
        "pound_force": 4.4482216152605, "lbf": 4.4482216152605,
        "kpound_force": 4448.2216152605, "kilogram_force": 9.80665, "kgf": 9.80665,
        "dyne": 1e-5,
    },
    "ANGLE": {
        "radian": 1.0, "radians": 1.0, "rad": 1.0, "degree": 0.017453292519943295,
        "degrees": 0.017453292519943295, "deg": 0.017453292519943295,
    },
    "MASS": {
        "kg": 1.0, "kilogram": 1.0, "gram": 1e-3, "g": 1e-3, "tonne": 1e3, "megagram": 1e3,
        "pound_mass": 0.45359237, "lbm": 0.45359237, "kpound_mass": 453.59237,
        "slug": 14.593902937,
    },
    "TIME": {
        "second": 1.0, "seconds": 1.0, "sec": 1.0, "s": 1.0, "millisecond": 1e-3, "ms": 1e-3,
        "minute": 60.0, "min": 60.0, "hour": 3600.0, "hr": 3600.0,
    },
    "PRESSURE": {
        "pascal": 1.0, "pa": 1.0, "kpascal": 1e3, "kpa": 1e3, "kilopascal": 1e3,
        "mpa": 1e6, "megapascal": 1e6, "bar": 1e5, "psi": 6894.757293168, "atm": 101325.0,
        "n/mm**2": 1e6, "n/mm2": 1e6,
    },
}
#: Order of the exponent tuples in UNIT_DIMENSIONS.
UNIT_QUANTITIES = ("LENGTH", "FORCE", "ANGLE", "MASS", "TIME", "PRESSURE")
