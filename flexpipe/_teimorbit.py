"""Line syntax shared by the TeimOrbit files flexpipe reads: tyre property files
(``.tir``, :mod:`flexpipe.tires.tir`) and Adams 2D road data files (``.rdf``,
:mod:`flexpipe.roads.rdf`).

A TeimOrbit file is a list of ``[SECTION]`` headers, ``KEY = value`` entries, ``(SUB_BLOCK)``
headers, ``{col1 col2 ...}`` table headers and rows of numbers; ``$`` and ``!`` start a
comment outside quotes; a value is a number (Fortran ``1.0D+05`` too), a quoted string or a
bare word.
"""

from __future__ import annotations

import re

SECTION_RE = re.compile(r"^\[\s*([A-Za-z0-9_\- ]+?)\s*\]$")
KEY_RE = re.compile(r"^([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.*)$")
TABLE_RE = re.compile(r"^\{(.*)\}$")
SUBBLOCK_RE = re.compile(r"^\(\s*([A-Za-z0-9_]+)\s*\)$")
NUMBER_RE = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eEdD][+-]?\d+)?$")


def strip_comment(text: str) -> str:
    """Remove a ``$`` or ``!`` comment that is not inside quotes."""
    quote = None
    for i, ch in enumerate(text):
        if quote:
            if ch == quote:
                quote = None
        elif ch in "'\"":
            quote = ch
        elif ch in "$!":
            return text[:i]
    return text


def parse_value(raw: str):
    """A value as written: float for a number, else the (unquoted) string."""
    raw = raw.strip()
    if len(raw) >= 2 and raw[0] == raw[-1] and raw[0] in "'\"":
        return raw[1:-1].strip()
    if NUMBER_RE.match(raw):
        return float(raw.replace("d", "e").replace("D", "E"))
    return raw


def number(text: str) -> float:
    """A number token (``NUMBER_RE``), Fortran exponents included."""
    return float(text.replace("d", "e").replace("D", "E"))
