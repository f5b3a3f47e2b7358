"""Checked access to TOML tables (shared by :mod:`flexpipe.roads` and :mod:`flexpipe.driver`).

A :class:`TableReader` hands out typed, range-checked values of one table and, at the end,
rejects keys it was never asked about, so that a misspelt key is an error rather than a
silently ignored default.
"""

from __future__ import annotations

import math
import pathlib
import tomllib

from flexpipe.errors import InputError

_MISSING = object()


def read_toml(path) -> dict:
    """Parse a TOML file, turning syntax errors into :class:`InputError` with the line.

    Parameters
    ----------
    path : str or pathlib.Path
        The file.

    Returns
    -------
    dict
        The parsed document.
    """
    path = pathlib.Path(path)
    try:
        text = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read the file ({exc.strerror})", file=path) from None
    try:
        return tomllib.loads(text.decode("utf-8"))
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text ({exc.reason} at byte {exc.start}); TOML files are "
                         "UTF-8", file=path, line=text[:exc.start].count(b"\n") + 1) from None
    except tomllib.TOMLDecodeError as exc:
        line = getattr(exc, "lineno", None)
        if line is None and "end of document" in str(exc):
            line = text.count(b"\n") + 1  # the file ends where the error is
        raise InputError(f"TOML syntax error: {exc}", file=path, line=line) from None
    except RecursionError:
        raise InputError("TOML nesting too deep to parse (arrays or tables nested thousands "
                         "of levels); a road, path or driver file is a few flat tables",
                         file=path, line=1) from None


class TableReader:
    """Typed access to one TOML table with key checking.

    Parameters
    ----------
    table : dict
        The table.
    file : str or pathlib.Path, optional
        File the table came from (for error messages).
    name : str, optional
        Dotted name of the table in the file, e.g. ``"road"`` (for error messages).
    """

    def __init__(self, table, *, file=None, name: str = ""):
        if not isinstance(table, dict):
            raise InputError(f"expected a table, got {type(table).__name__}", file=file,
                             key=name or None)
        self.table = table
        self.file = file
        self.name = name
        self._used: set[str] = set()

    def _key(self, key: str) -> str:
        return f"{self.name}.{key}" if self.name else key

    def error(self, key: str, message: str) -> InputError:
        """An :class:`InputError` about ``key`` of this table."""
        return InputError(message, file=self.file, key=self._key(key))

    def has(self, key: str) -> bool:
        """Whether ``key`` is present (marks it as known)."""
        self._used.add(key)
        return key in self.table

    def raw(self, key: str, default=_MISSING):
        """The value of ``key`` without conversion."""
        self._used.add(key)
        if key not in self.table:
            if default is _MISSING:
                raise self.error(key, "missing required key")
            return default
        return self.table[key]

    def float(self, key: str, default=_MISSING, *, positive: bool = False,
              nonnegative: bool = False, lo: float | None = None,
              hi: float | None = None) -> float:
        """A finite float, optionally range-checked."""
        value = self.raw(key, default)
        if value is default and default is not _MISSING:
            return value
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise self.error(key, f"expected a number, got {value!r}")
        value = float(value)
        if not math.isfinite(value):
            raise self.error(key, f"expected a finite number, got {value!r}")
        if positive and value <= 0.0:
            raise self.error(key, f"must be > 0, got {value!r}")
        if nonnegative and value < 0.0:
            raise self.error(key, f"must be >= 0, got {value!r}")
        if lo is not None and value < lo:
            raise self.error(key, f"must be >= {lo}, got {value!r}")
        if hi is not None and value > hi:
            raise self.error(key, f"must be <= {hi}, got {value!r}")
        return value

    def int(self, key: str, default=_MISSING, *, lo: int | None = None) -> int:
        """An integer, optionally bounded below."""
        value = self.raw(key, default)
        if value is default and default is not _MISSING:
            return value
        if isinstance(value, bool) or not isinstance(value, int):
            raise self.error(key, f"expected an integer, got {value!r}")
        if lo is not None and value < lo:
            raise self.error(key, f"must be >= {lo}, got {value!r}")
        return int(value)

    def str(self, key: str, default=_MISSING, *, choices=None) -> str:
        """A string, optionally one of ``choices``."""
        value = self.raw(key, default)
        if value is default and default is not _MISSING:
            return value
        if not isinstance(value, str):
            raise self.error(key, f"expected a string, got {value!r}")
        if choices is not None and value not in choices:
            raise self.error(key, f"got {value!r}; valid: {', '.join(map(repr, choices))}")
        return value

    def float_list(self, key: str, default=_MISSING) -> list[float]:
        """A list of finite floats."""
        value = self.raw(key, default)
        if value is default and default is not _MISSING:
            return value
        if not isinstance(value, list) or not value:
            raise self.error(key, "expected a non-empty list of numbers")
        out = []
        for i, item in enumerate(value):
            if isinstance(item, bool) or not isinstance(item, int | float) \
                    or not math.isfinite(item):
                raise self.error(key, f"item {i} is {item!r}; expected a finite number")
            out.append(float(item))
        return out

    def finish(self) -> None:
        """Raise if the table holds keys that were never read."""
        unknown = sorted(set(self.table) - self._used)
        if unknown:
            valid = ", ".join(sorted(self._used)) or "(none)"
            raise self.error(unknown[0], f"unknown key; valid keys here: {valid}")
