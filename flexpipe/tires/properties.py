"""The contents of a ``.tir`` tyre property file as :func:`flexpipe.tires.read_tir` gives
them: :class:`TireProperties` (sections, tables and line numbers, SI units) with typed
accessors, and :class:`TirTable`."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import numpy as np

from flexpipe.errors import InputError
from flexpipe.tires import _keys


def fittyp_of(sections) -> int | None:
    """``[MODEL] FITTYP`` of raw sections as an integer, or None (absent or not a number)."""
    try:
        return int(float(sections.get("MODEL", {}).get("FITTYP")))
    except (TypeError, ValueError):
        return None


@dataclass(frozen=True)
class TirTable:
    """A ``{...}`` table of a ``.tir`` section.

    Attributes
    ----------
    columns : tuple of str
        Column names from the ``{...}`` header (lower case).
    data : ndarray, shape (n_rows, n_columns)
        Read-only values, converted to SI for known tables.
    line : int
        Line number of the ``{...}`` header.
    row_lines : tuple of int
        Line number of every row.
    """

    columns: tuple[str, ...]
    data: np.ndarray
    line: int
    row_lines: tuple[int, ...] = ()

    def column(self, name: str) -> np.ndarray:
        """Return the column ``name`` (case-insensitive)."""
        try:
            return self.data[:, self.columns.index(name.lower())]
        except ValueError:
            raise InputError(
                f"table has no column '{name}'; columns are {list(self.columns)}", key=name
            ) from None


@dataclass(frozen=True)
class TireProperties:
    """Contents of a ``.tir`` file, with dimensional data in SI units.

    Attributes
    ----------
    path : Path
        File that was read.
    sections : Mapping[str, Mapping[str, float | str]]
        Read-only ``{SECTION: {KEY: value}}``; numbers are floats (SI where dimensional).
    tables : Mapping[str, TirTable]
        Read-only ``{SECTION: table}``.
    lines : Mapping[tuple[str, str], int]
        Line number of every ``(SECTION, KEY)`` and of every ``(SECTION, "")`` header.
    """

    path: Path
    sections: Mapping[str, Mapping[str, float | str]]
    tables: Mapping[str, TirTable]
    lines: Mapping[tuple[str, str], int] = field(repr=False)

    # ------------------------------------------------------------------ generic access
    def has(self, section: str, key: str | None = None) -> bool:
        """True if ``[section]`` (and ``key`` in it, when given) is present."""
        sec = self.sections.get(section.upper())
        return sec is not None and (key is None or key.upper() in sec)

    def section(self, name: str) -> Mapping[str, float | str]:
        """Return ``[name]``; raise :class:`InputError` naming the file if absent."""
        try:
            return self.sections[name.upper()]
        except KeyError:
            raise InputError(
                f"section [{name.upper()}] is missing; sections present: "
                f"{', '.join('[' + s + ']' for s in self.sections)}",
                file=self.path,
            ) from None

    def get(self, section: str, key: str, default=None):
        """Value of ``key`` in ``[section]``, or ``default`` if either is absent."""
        return self.sections.get(section.upper(), {}).get(key.upper(), default)

    def number(self, section: str, key: str, default: float | None = None) -> float:
        """Numeric value of ``key`` in ``[section]``.

        Raises :class:`InputError` naming the file, section and key when the key (or its
        section) is absent and no ``default`` is given, or when the value is not a number.
        """
        sec = self.section(section) if default is None else self.sections.get(
            section.upper(), {})
        value = sec.get(key.upper())
        if value is None:
            if default is not None:
                return float(default)
            raise InputError(f"[{section.upper()}] has no {key.upper()}", file=self.path,
                             key=key.upper())
        if isinstance(value, str):
            raise InputError(f"[{section.upper()}] {key.upper()} must be a number, got "
                             f"'{value}'", file=self.path,
                             line=self.lines.get((section.upper(), key.upper())),
                             key=key.upper())
        return value

    # ------------------------------------------------------------------ typed accessors
    @property
    def property_file_format(self) -> str:
        """``[MODEL] PROPERTY_FILE_FORMAT`` upper case, e.g. ``'PAC2002'``, ``'MF_05'`` or
        ``'FIALA'``."""
        return str(self.get("MODEL", "PROPERTY_FILE_FORMAT", "")).upper()

    @property
    def is_mf52(self) -> bool:
        """True for a Magic Formula 5.2 file (``PROPERTY_FILE_FORMAT`` ``'PAC2002'`` or
        ``'MF_05'``, FITTYP none, 6 or 21), evaluated by :class:`flexpipe.tires.Pac2002Tire`."""
        return self.property_file_format in _keys.MF52_FORMATS and not self.is_mf6

    @property
    def is_mf6(self) -> bool:
        """True for a Magic Formula 6.1 or 6.2 fit (``[MODEL] FITTYP`` 61 or 62, any
        PROPERTY_FILE_FORMAT but 'FIALA'), evaluated by :mod:`flexpipe.tires.mf61`."""
        return (self.property_file_format != "FIALA"
                and self.fittyp in _keys.MF6_EVALUATED)

    @property
    def pressures(self) -> tuple[float, float] | None:
        """``(INFLPRES, NOMPRES)`` of ``[OPERATING_CONDITIONS]`` in Pa, or None when the
        file does not give both."""
        sec = "OPERATING_CONDITIONS"
        if self.get(sec, "INFLPRES") is None or self.get(sec, "NOMPRES") is None:
            return None
        return self.number(sec, "INFLPRES"), self.number(sec, "NOMPRES")

    @property
    def pressure_range(self) -> tuple[float, float] | None:
        """``[INFLATION_PRESSURE_RANGE]`` ``(PRESMIN, PRESMAX)`` in Pa (0 and inf where a
        bound is not given), or None without the section."""
        if not self.has("INFLATION_PRESSURE_RANGE"):
            return None
        return (self.number("INFLATION_PRESSURE_RANGE", "PRESMIN", 0.0),
                self.number("INFLATION_PRESSURE_RANGE", "PRESMAX", math.inf))

    @property
    def use_mode(self) -> int:
        """``[MODEL] USE_MODE`` (default 4): see :mod:`flexpipe.tires` for the meaning."""
        return int(self.get("MODEL", "USE_MODE", 4))

    @property
    def relaxation(self) -> bool:
        """Slip relaxation asked for by USE_MODE: its tens digit is 1 or more (Adams' 1x and
        2x, MF-Tyre's three digits 1xy..9xy alike)."""
        return (abs(self.use_mode) // 10) % 10 >= 1

    @property
    def tyre_side(self) -> str:
        """``[MODEL] TYRESIDE`` upper case (``'LEFT'`` if absent)."""
        return str(self.get("MODEL", "TYRESIDE", "LEFT")).upper()

    @property
    def unloaded_radius(self) -> float:
        """Free tyre radius R0, m."""
        return self.number("DIMENSION", "UNLOADED_RADIUS")

    @property
    def width(self) -> float | None:
        """Nominal section width, m, or None when ``[DIMENSION]`` has no WIDTH (the tyre
        models do not use it; it is descriptive only)."""
        if self.get("DIMENSION", "WIDTH") is None:
            return None
        return self.number("DIMENSION", "WIDTH")

    @property
    def fittyp(self) -> int | None:
        """``[MODEL] FITTYP`` (Magic Formula version number: 6 or 21 = MF 5.2, 61 / 62 =
        MF 6.1 / 6.2), or None (absent, or in a FIALA file not a number)."""
        return fittyp_of(self.sections)

    @property
    def vertical_stiffness(self) -> float:
        """Vertical stiffness, N/m (times the scaling factor LCZ when present)."""
        return self.number("VERTICAL", "VERTICAL_STIFFNESS") * float(
            self.get("SCALING_COEFFICIENTS", "LCZ", 1.0))

    @property
    def vertical_damping(self) -> float:
        """Vertical damping, N s/m (0 if absent)."""
        return self.number("VERTICAL", "VERTICAL_DAMPING", 0.0)

    @property
    def vertical_stiffness_cubic(self) -> float | None:
        """flexpipe extension ``VERTICAL_STIFFNESS_CUBIC`` (Duffing term), N/m^3, or None."""
        v = self.get("VERTICAL", "VERTICAL_STIFFNESS_CUBIC")
        return None if v is None else self.number("VERTICAL", "VERTICAL_STIFFNESS_CUBIC")

    @property
    def fnomin(self) -> float:
        """Nominal wheel load FNOMIN, N."""
        return self.number("VERTICAL", "FNOMIN")

    def coefficients(self, section: str) -> Mapping[str, float]:
        """Read-only numeric coefficients of ``[section]`` (empty mapping if absent)."""
        return self.sections.get(section.upper(), MappingProxyType({}))

    def relaxation_length_longitudinal(self, Fz: float | None = None) -> float | None:
        """Longitudinal relaxation length sigma_kappa, m, at load ``Fz`` (default FNOMIN).

        From ``PTX1..PTX3`` (MF 5.2: ``Fz (PTX1 + PTX2 dfz) exp(-PTX3 dfz) R0/FNOMIN LSGKP``)
        or ``[PARAMETER] RELAX_LENGTH_X``; None if neither is given.
        """
        if self.has("PARAMETER", "RELAX_LENGTH_X"):
            return self.number("PARAMETER", "RELAX_LENGTH_X")
        c, s = self.coefficients("LONGITUDINAL_COEFFICIENTS"), self.coefficients(
            "SCALING_COEFFICIENTS")
        if not c.get("PTX1"):
            return None
        fnom = self.fnomin
        Fz = fnom if Fz is None else Fz
        fz0 = fnom * s.get("LFZO", 1.0)
        dfz = (Fz - fz0) / fz0
        return (Fz * (c["PTX1"] + c.get("PTX2", 0.0) * dfz) * math.exp(-c.get("PTX3", 0.0) * dfz)
                * self.unloaded_radius / fnom * s.get("LSGKP", 1.0))

    def relaxation_length_lateral(self, Fz: float | None = None, gamma: float = 0.0
                                  ) -> float | None:
        """Lateral relaxation length sigma_alpha, m, at load ``Fz`` (default FNOMIN).

        From ``PTY1, PTY2`` (MF 5.2: ``PTY1 sin(2 atan(Fz/(PTY2 Fz0'))) (1 - PKY3|gamma|)
        R0 LFZO LSGAL``) or ``[PARAMETER] RELAX_LENGTH_Y``; None if neither is given.
        """
        if self.has("PARAMETER", "RELAX_LENGTH_Y"):
            return self.number("PARAMETER", "RELAX_LENGTH_Y")
        c, s = self.coefficients("LATERAL_COEFFICIENTS"), self.coefficients(
            "SCALING_COEFFICIENTS")
        if not c.get("PTY1") or not c.get("PTY2"):
            return None
        fnom = self.fnomin
        Fz = fnom if Fz is None else Fz
        lfzo = s.get("LFZO", 1.0)
        return (c["PTY1"] * math.sin(2.0 * math.atan(Fz / (c["PTY2"] * fnom * lfzo)))
                * (1.0 - c.get("PKY3", 0.0) * abs(gamma)) * self.unloaded_radius * lfzo
                * s.get("LSGAL", 1.0))


# ====================================================================== parsing
