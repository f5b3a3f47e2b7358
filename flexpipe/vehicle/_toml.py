"""Checked reading of the car TOML file: typed values, ranges, unknown-key detection.

Every error is an :class:`~flexpipe.errors.InputError` naming the file, the line (found by
a light scan of the text, since :mod:`tomllib` keeps no positions), the dotted key and what
would be valid.
"""

from __future__ import annotations

import difflib
import math
import re
import tomllib
from pathlib import Path

import numpy as np

from flexpipe.errors import InputError
from flexpipe.vehicle.limits import INERTIA_TRIANGLE_TOL

_MISSING = object()


def parse(path: Path) -> tuple[dict, list[str]]:
    """Parse ``path``; returns the document and its text lines (for line lookup)."""
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read the car file ({exc.strerror}); give the path of a "
                         "TOML car file such as cars/sedan.toml", file=path) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text ({exc.reason})", file=path,
                         line=raw[: exc.start].count(b"\n") + 1) from None
    try:
        return tomllib.loads(text), text.splitlines()
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        line = int(m.group(1)) if m else (len(text.splitlines()) or 1
                                          if "end of document" in str(exc) else None)
        raise InputError(f"TOML syntax error: {exc}", file=path, line=line) from None
    except RecursionError:
        raise InputError("TOML nested too deeply (arrays or inline tables within each other "
                         "hundreds of levels deep); a car file needs only a few levels",
                         file=path, line=1) from None


class Table:
    """Typed access to one TOML table; :meth:`finish` rejects keys never asked for.

    Parameters
    ----------
    data : dict
        The table.
    name : str
        Dotted name in the file (``"corners.fl"``).
    file : Path
        The car file.
    lines : list of str
        Its text, to report line numbers.
    fallbacks : sequence of (Path, list of str)
        The car files it is based on (``base``, :mod:`flexpipe.vehicle._car_base`), nearest
        first: an error about a key the file itself does not write names the base file
        and line that do.
    """

    def __init__(self, data, name: str, file: Path, lines: list[str], fallbacks=()):
        self.name = name
        self.file = file
        self.lines = lines
        self.fallbacks = tuple(fallbacks)
        if not isinstance(data, dict):
            raise InputError(f"expected a table [{name}], got {type(data).__name__}",
                             file=file, key=name, line=self._line(None))
        self.data = data
        self._known: set[str] = set()

    # ------------------------------------------------------------------ messages
    def _line(self, key: str | None) -> int | None:
        """1-based line of ``key`` inside this table's header, or of the header."""
        parts = self.name.split(".") if self.name else []
        header = None
        item = re.fullmatch(r"(.+)\[(\d+)\]", self.name)  # body.mass[2]: 3rd [[body.mass]]
        count = -1
        for i, text in enumerate(self.lines):
            s = text.strip()
            if not s.startswith("["):
                continue
            name = s.split("#", 1)[0].strip().strip("[] ").replace(" ", "")
            if item is None and name == self.name:
                header = i
                break
            if item is not None and s.startswith("[[") and name == item.group(1):
                count += 1
                if count == int(item.group(2)):
                    header = i
                    break
        start = header if header is not None else 0
        if key is None:
            return None if header is None else header + 1
        pat = re.compile(rf"^\s*\"?{re.escape(key)}\"?\s*=")
        for i in range(start + 1 if header is not None else 0, len(self.lines)):
            s = self.lines[i].strip()
            if header is not None and i > start and s.startswith("["):
                break
            if pat.match(self.lines[i]):
                return i + 1
        if not parts:
            return None
        return None if header is None else header + 1

    def _key_line(self, key: str) -> int | None:
        """1-based line where this table (its own section) writes ``key``, or None."""
        if self.name and self._line(None) is None:
            return None
        line = self._line(key)
        pat = re.compile(rf"^\s*\"?{re.escape(key)}\"?\s*=")
        return line if line is not None and pat.match(self.lines[line - 1]) else None

    def where(self, key: str | None) -> tuple[Path, int | None]:
        """File and line of ``key`` (or of the table): this file's, or a base file's when
        only the base writes the key."""
        if key is not None and self.fallbacks and self._key_line(key) is None:
            for file, lines in self.fallbacks:
                line = Table({}, self.name, file, lines)._key_line(key)
                if line is not None:
                    return file, line
        return self.file, self._line(key)

    def key(self, key: str) -> str:
        """Dotted name of ``key``."""
        return f"{self.name}.{key}" if self.name else key

    def error(self, key: str | None, message: str) -> InputError:
        """An :class:`InputError` about ``key`` (or the table itself)."""
        file, line = self.where(key)
        return InputError(message, file=file, line=line,
                          key=self.key(key) if key else self.name)

    # ------------------------------------------------------------------ access
    def has(self, key: str) -> bool:
        """Whether ``key`` is present (also marks it as a known key)."""
        self._known.add(key)
        return key in self.data

    def raw(self, key: str, default=_MISSING, *, doc: str = ""):
        """Value of ``key`` unconverted; missing required keys raise."""
        self._known.add(key)
        if key not in self.data:
            if default is _MISSING:
                hint = f" ({doc})" if doc else ""
                close = difflib.get_close_matches(key, [k for k in self.data if k != key], n=1)
                if close:
                    hint += f"; found '{close[0]}' - misspelt?"
                raise InputError(f"missing required key '{key}'{hint}", file=self.file,
                                 line=self._line(None), key=self.key(key))
            return default
        return self.data[key]

    def number(self, key: str, default=_MISSING, *, lo=None, hi=None, lo_open=False,
               doc: str = "") -> float:
        """A finite number, range-checked (``lo`` inclusive unless ``lo_open``)."""
        v = self.raw(key, default, doc=doc)
        if v is default and default is not _MISSING:
            return v
        if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
            raise self.error(key, f"expected a finite number, got {v!r}")
        v = float(v)
        if lo is not None and (v < lo or (lo_open and v == lo)):
            rel = ">" if lo_open else ">="
            raise self.error(key, f"must be {rel} {lo:g}, got {v:g}")
        if hi is not None and v > hi:
            raise self.error(key, f"must be <= {hi:g}, got {v:g}")
        return v

    def magnitude(self, key: str, value: float, lo: float, hi: float, *, unit: str,
                  what: str, slips=()) -> float:
        """``value`` of ``key`` when within ``[lo, hi]``, else an error naming the likely
        unit slip.

        Parameters
        ----------
        key : str
            Key of the value (for the message).
        value : float
            The value read, in ``unit``.
        lo, hi : float
            Bounds no road vehicle's value lies outside (the caller justifies them).
        unit : str
            Unit of the key (``"N/m"``).
        what : str
            What the value is (``"a suspension spring rate"``).
        slips : sequence of (factor, str)
            Likely slips: ``value * factor`` within the bounds means the value was given in
            the unit named by the string (``(1e3, "N/mm")``).
        """
        if lo <= value <= hi:
            return value
        hint = ""
        for factor, name in slips:
            if lo <= value * factor <= hi:
                hint = (f"; it looks like {name} ({value:g} {name} = {value * factor:g} "
                        f"{unit}), but the key's unit is {unit}")
                break
        raise self.error(key, f"{value:g} {unit} is no plausible value for {what}: a road "
                              f"vehicle's lies between {lo:g} and {hi:g} {unit}{hint}")

    def string(self, key: str, default=_MISSING, *, choices=None, doc: str = "") -> str:
        """A string, optionally one of ``choices``."""
        v = self.raw(key, default, doc=doc)
        if v is default and default is not _MISSING:
            return v
        if not isinstance(v, str):
            raise self.error(key, f"expected a string, got {v!r}")
        if not v.strip():
            raise self.error(key, "must not be empty"
                             + (f"; valid: {', '.join(map(repr, choices))}" if choices else ""))
        if choices is not None and v not in choices:
            raise self.error(key, f"got {v!r}; valid: {', '.join(map(repr, choices))}")
        return v

    def vector(self, key: str, n: int = 3, default=_MISSING, *, doc: str = "") -> np.ndarray:
        """A list of ``n`` finite numbers."""
        v = self.raw(key, default, doc=doc)
        if v is default and default is not _MISSING:
            return v
        ok = (isinstance(v, list) and len(v) == n and all(
            not isinstance(x, bool) and isinstance(x, int | float) and math.isfinite(x)
            for x in v))
        if not ok:
            raise self.error(key, f"expected a list of {n} finite numbers, got {v!r}")
        return np.array(v, dtype=float)

    def sub(self, key: str, default=_MISSING) -> Table | None:
        """Sub-table ``key`` as a :class:`Table` (``None`` when absent and optional)."""
        v = self.raw(key, default)
        if v is default and default is not _MISSING:
            return v
        return Table(v, self.key(key), self.file, self.lines, self.fallbacks)

    def finish(self) -> None:
        """Raise for keys of this table that no reader asked for (misspellings)."""
        unknown = sorted(set(self.data) - self._known)
        if unknown:
            k = unknown[0]
            close = difflib.get_close_matches(k, sorted(self._known), n=1)
            hint = f" (did you mean '{close[0]}'?)" if close else ""
            if k == "base" and self.name:
                hint = (" (a car variant names its base car file at the top of the file, "
                        "before any [table])")
            raise self.error(k, f"unknown key{hint}; valid keys in [{self.name or 'top level'}]"
                                f": {', '.join(sorted(self._known))}")


def check_principal_moments(t: Table, key: str, J: np.ndarray,
                            tol: float = INERTIA_TRIANGLE_TOL) -> None:
    """Refuse an inertia tensor whose principal moments break the triangle inequality.

    Every rigid body has ``I1 <= I2 + I3`` for its principal moments (``I2 + I3 - I1 = 2 sum
    m x1^2 >= 0``); a flat body meets it with equality.

    Parameters
    ----------
    t : Table
        The table of ``key`` (for the message).
    key : str
        Key of the inertia (``"unsprung_inertia_kg_m2"``).
    J : (3, 3) array
        The tensor read, kg m^2 (positive semi-definite).
    tol : float
        Margin for rounded moments, relative to the largest one
        (:data:`flexpipe.vehicle.limits.INERTIA_TRIANGLE_TOL`).

    Raises
    ------
    InputError
        Naming the largest moment, the sum of the other two and the rule.
    """
    moments = np.sort(np.linalg.eigvalsh(np.asarray(J, dtype=float)))
    if moments[2] <= (moments[0] + moments[1]) + tol * max(moments[2], 0.0):
        return
    raise t.error(key, f"principal moments {', '.join(f'{m:.4g}' for m in moments)} kg m^2 "
                       "are no rigid body's: the largest must not exceed the sum of the "
                       f"other two ({moments[2]:.4g} > {moments[0] + moments[1]:.4g}); a flat "
                       "body has equality (a wheel about its axle: twice the moment about a "
                       "diameter)")
