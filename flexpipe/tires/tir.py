"""Reader for Adams-style TeimOrbit tyre property files (``.tir``).

Format handled
--------------
* ``$ ...`` comments anywhere on a line, ``! ...`` comments anywhere outside quotes;
* ``[SECTION]`` headers (names are case-insensitive and stored upper case);
* ``KEY = value`` with a number (``1.2``, ``-3.7604e-005``, Fortran ``1.0D+05``), a quoted
  string (``'meter'`` or ``"meter"``) or a bare word (kept as a string);
* tables: a ``{col1 col2 ...}`` header inside a section followed by rows of numbers, e.g.
  ``[DEFLECTION_LOAD_CURVE] {pen fz}`` or ``[SHAPE] {radial width}``; kept as read-only
  arrays in :attr:`TireProperties.tables`;
* ``[MDI_HEADER]`` is descriptive: its ``KEY = value`` entries are kept, any other line is
  skipped; a TeimOrbit comment block (a ``(COMMENTS)`` line, an optional one-column
  ``{comment_string}`` header and ``'quoted'`` rows) is skipped in ``[MDI_HEADER]`` and the
  other free sections (:data:`flexpipe.tires._keys.FREE_SECTIONS`).

Checks (all raise :class:`~flexpipe.errors.InputError` naming the file and line): a line
that is neither a section, key, table header nor table row; a key before the first
section; a duplicate key; a non-numeric or non-finite value in a coefficient section; the
physical ranges of :mod:`flexpipe.tires.checks`; an unknown key in a coefficient section
of a ``PAC2002`` / ``MF_05`` file (or in ``[PARAMETER]`` of a ``FIALA`` file); an unknown
unit name; a key or section name one letter away from a known one; a ``[MODEL] FITTYP``
other than 6 or 21 (MF 5.2) and 61 or 62 (MF 6.1 / 6.2), e.g. MF 6.0's 60 (an MF 6.1 / 6.2
fit is checked as a Magic Formula file whatever its PROPERTY_FILE_FORMAT). Missing required
sections raise naming the file and the section.
Unknown sections, and MF 6.x coefficients with a non-neutral value in an MF 5.2 file (see
:mod:`flexpipe.tires`), are kept and produce a :class:`UserWarning`, shown once per process
and file under the default warning filter (:func:`flexpipe.tires.checks.file_warning`).

Units
-----
Dimensional keys listed in :data:`flexpipe.tires._keys.UNIT_DIMENSIONS` and the columns of
known tables are converted to SI (m, N, rad, kg, s, Pa) from the ``[UNITS]`` section.
Magic Formula coefficients are non-dimensional (radian-based) and are used as written.
"""

from __future__ import annotations

import math
from pathlib import Path
from types import MappingProxyType

import numpy as np

from flexpipe._teimorbit import KEY_RE as _KEY_RE
from flexpipe._teimorbit import NUMBER_RE as _NUMBER_RE
from flexpipe._teimorbit import SECTION_RE as _SECTION_RE
from flexpipe._teimorbit import SUBBLOCK_RE as _SUBBLOCK_RE
from flexpipe._teimorbit import TABLE_RE as _TABLE_RE
from flexpipe._teimorbit import parse_value as _parse_value
from flexpipe._teimorbit import strip_comment as _strip_comment
from flexpipe.errors import InputError
from flexpipe.tires import _keys
from flexpipe.tires.checks import (
    check_fittyp,
    check_keys,
    check_tir,
    file_warning,
    scale,
    unit_factors,
    warn_unused_mf6,
)
from flexpipe.tires.properties import TireProperties, TirTable, fittyp_of

#: USE_MODE values honoured (sign = mirroring, tens = transient behaviour).
VALID_USE_MODES = frozenset(s * (t + u) for s in (1, -1) for t in (0, 10, 20)
                            for u in range(5))
#: An MF 6.1 / 6.2 file may also carry MF-Tyre's three-digit USE_MODE (e.g. 124): its
#: hundreds digit (the contact method) is not used, flexpipe's contact is a single point.
VALID_USE_MODES_MF6 = VALID_USE_MODES | frozenset(
    s * (100 * h + t + u) for s in (1, -1) for h in range(1, 10) for t in range(0, 60, 10)
    for u in range(5))


#: Sections a PAC2002 / MF_05 file needs, by USE_MODE % 10.
def _required_sections(fmt: str, use_mode: int) -> list[str]:
    if fmt == "FIALA":
        return ["MODEL", "DIMENSION", "VERTICAL", "PARAMETER"]
    if fmt not in _keys.MF52_FORMATS and fmt != "MF6":
        return ["MODEL"]
    req = ["MODEL", "DIMENSION", "VERTICAL"]
    mode = abs(use_mode) % 10
    if mode in (1, 3, 4):
        req.append("LONGITUDINAL_COEFFICIENTS")
    if mode in (2, 3, 4):
        req += ["LATERAL_COEFFICIENTS", "ALIGNING_COEFFICIENTS"]
    return req


def read_tir(path) -> TireProperties:
    """Read a TeimOrbit ``.tir`` tyre property file.

    Parameters
    ----------
    path : str or Path
        The ``.tir`` file.

    Returns
    -------
    TireProperties
        Sections (SI where dimensional) and tables.

    Raises
    ------
    InputError
        Unreadable file, malformed or unknown entry (naming file and line), unknown unit,
        invalid USE_MODE, or a missing required section (naming file and section).
    """
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read tyre property file: {exc.strerror}", file=path) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = raw.decode("latin-1")

    sections: dict[str, dict] = {}
    lines: dict[tuple[str, str], int] = {}
    tables: dict[str, tuple[tuple[str, ...], list, int]] = {}
    empty = []      # (section, key, line) of empty entries in free sections
    current = None
    table_open = None
    comments = 0    # in a (COMMENTS) block: 1 right after its header line, 2 in its rows
    for lineno, line in enumerate(text.splitlines(), start=1):
        body = _strip_comment(line).strip()
        if not body:
            continue
        m = _SECTION_RE.match(body)
        if m:
            current = m.group(1).strip().upper().replace(" ", "_")
            sections.setdefault(current, {})
            lines.setdefault((current, ""), lineno)
            table_open = None
            comments = 0
            continue
        if current is None:
            raise InputError(f"entry '{body}' appears before the first [SECTION] header",
                             file=path, line=lineno)
        if comments:   # TeimOrbit comment block: {comment_string} header, 'quoted' rows
            header = _TABLE_RE.match(body)
            if body[0] in "'\"" or (comments == 1 and header
                                     and len(header.group(1).split()) == 1):
                comments = 2
                continue
            comments = 0
        m = _SUBBLOCK_RE.match(body)
        if m and m.group(1).upper() == "COMMENTS":
            if current not in _keys.FREE_SECTIONS:
                raise InputError(
                    f"[{current}] holds a (COMMENTS) block; comment blocks are read (and "
                    "skipped) only in the free sections "
                    f"({', '.join('[' + s + ']' for s in sorted(_keys.FREE_SECTIONS))}): "
                    "move it to [MDI_HEADER] or turn its lines into $ comments",
                    file=path, line=lineno, key="COMMENTS")
            comments = 1
            table_open = None
            continue
        m = _KEY_RE.match(body)
        if current == "MDI_HEADER":
            # descriptive only: keep its well-formed KEY = value entries, skip the rest
            # (free text, tables, repeated keys) instead of parsing it
            if m and _parse_value(m.group(2)) != "" and \
                    m.group(1).upper() not in sections[current]:
                sections[current][m.group(1).upper()] = _parse_value(m.group(2))
                lines[(current, m.group(1).upper())] = lineno
            continue
        if m:
            key, value = m.group(1).upper(), _parse_value(m.group(2))
            table_open = None
            if value == "":
                if current in _keys.FREE_SECTIONS:
                    # MF-Tool writes empty entries (ROAD_INCREMENT =): skipped in an MF 6.x
                    # file, an error in any other (decided once FITTYP is known)
                    empty.append((current, key, lineno))
                    continue
                raise InputError(f"[{current}] {key} has no value", file=path, line=lineno,
                                 key=key)
            if key in sections[current]:
                raise InputError(f"[{current}] {key} is given twice (first on line "
                                 f"{lines[(current, key)]})", file=path, line=lineno, key=key)
            if current in _keys.NUMERIC_SECTIONS and isinstance(value, str):
                raise InputError(f"[{current}] {key} must be a number, got '{m.group(2).strip()}'",
                                 file=path, line=lineno, key=key)
            if isinstance(value, float) and not math.isfinite(value):
                raise InputError(f"[{current}] {key} = {m.group(2).strip()} is not a finite "
                                 "number", file=path, line=lineno, key=key)
            sections[current][key] = value
            lines[(current, key)] = lineno
            if current == "MODEL" and key == "FITTYP":
                # at once: an MF 6.x file should fail on its version, not on a later entry
                # this reader does not know (empty values, MF 6.x-only keys, ...)
                check_fittyp(path, sections, lines)
            continue
        m = _TABLE_RE.match(body)
        if m:
            cols = tuple(c.lower() for c in m.group(1).split())
            if not cols or current in tables:
                why = "an empty table header" if not cols else "a second table in the section"
                raise InputError(f"[{current}] has {why}", file=path, line=lineno)
            tables[current] = (cols, [], lineno, [])
            table_open = current
            continue
        if table_open is not None:
            cols, rows, _, row_lines = tables[table_open]
            parts = body.replace(",", " ").split()
            if len(parts) != len(cols) or not all(_NUMBER_RE.match(p) for p in parts):
                raise InputError(f"[{current}] table row '{body}' must hold {len(cols)} numbers "
                                 f"({' '.join(cols)})", file=path, line=lineno)
            row = [float(p.replace("d", "e").replace("D", "E")) for p in parts]
            if not all(math.isfinite(x) for x in row):
                raise InputError(f"[{current}] table row '{body}' holds a non-finite number",
                                 file=path, line=lineno)
            rows.append(row)
            row_lines.append(lineno)
            continue
        raise InputError(f"cannot parse '{body}' in [{current}]: expected KEY = value, "
                         "a [SECTION] header, a {column ...} table header or a (COMMENTS) "
                         "block", file=path, line=lineno)

    if not sections:
        raise InputError("no [SECTION] found: not a TeimOrbit tyre property file", file=path)
    fmt = str(sections.get("MODEL", {}).get("PROPERTY_FILE_FORMAT", "")).upper()
    # an MF 6.1 / 6.2 fit is checked as a Magic Formula file whatever its format's name
    mf6 = fmt != "FIALA" and fittyp_of(sections) in _keys.MF6_EVALUATED
    kind = "MF6" if mf6 else fmt
    if empty and not mf6:
        sec, key, lineno = empty[0]
        raise InputError(f"[{sec}] {key} has no value", file=path, line=lineno, key=key)
    use_mode = sections.get("MODEL", {}).get("USE_MODE", 4.0)
    valid = VALID_USE_MODES_MF6 if mf6 else VALID_USE_MODES
    if not isinstance(use_mode, float) or use_mode != int(use_mode) or \
            int(use_mode) not in valid:
        more = (", or MF-Tyre's three digits 1xy..9xy with x 0..5, y 0..4 (e.g. 124)"
                if mf6 else "")
        raise InputError(f"[MODEL] USE_MODE = {use_mode!r} is not valid; valid: 0..4, 10..14, "
                         f"20..24 (negative = mirrored){more}", file=path,
                         line=lines.get(("MODEL", "USE_MODE")), key="USE_MODE")
    for name in _required_sections(kind, int(use_mode)):
        if name not in sections:
            raise InputError(f"required section [{name}] is missing for a {fmt or 'tyre'} "
                             f"file with USE_MODE {int(use_mode)}", file=path, key=name)
        if not sections[name] and name not in tables:
            raise InputError(f"required section [{name}] is empty (truncated file?)",
                             file=path, line=lines[(name, "")], key=name)
    if "PROPERTY_FILE_FORMAT" not in sections["MODEL"] and not mf6:
        raise InputError("[MODEL] has no PROPERTY_FILE_FORMAT (e.g. 'PAC2002', 'MF_05' or "
                         "'FIALA')",
                         file=path, line=lines[("MODEL", "")], key="PROPERTY_FILE_FORMAT")
    check_keys(path, fmt, sections, lines, strict_as="PAC2002" if mf6 else None)

    factors = unit_factors(path, sections.get("UNITS", {}), lines)
    if (fmt in _keys.MF52_FORMATS or mf6) and factors["ANGLE"] != 1.0:
        file_warning(f"{path}, line {lines.get(('UNITS', 'ANGLE'))}: [UNITS] ANGLE = "
                     f"'{sections['UNITS']['ANGLE']}' is not radian; the angle ranges are "
                     "converted, but Magic Formula coefficients are still interpreted as "
                     "radian-based (as the Magic Formula defines them)")
    for (sec, key), dims in _keys.UNIT_DIMENSIONS.items():
        value = sections.get(sec, {}).get(key)
        if isinstance(value, float):
            sections[sec][key] = value * scale(dims, factors)

    frozen_tables = {}
    for name, (cols, rows, lineno, row_lines) in tables.items():
        if not rows:
            raise InputError(f"[{name}] table {{{' '.join(cols)}}} has no rows", file=path,
                             line=lineno)
        data = np.array(rows, dtype=float)
        dims = _keys.TABLE_DIMENSIONS.get(name)
        if dims is not None and len(dims) == data.shape[1]:
            data = data * np.array([scale(d, factors) for d in dims])
        data.setflags(write=False)
        frozen_tables[name] = TirTable(cols, data, lineno, tuple(row_lines))
    check_tir(path, "PAC2002" if mf6 else fmt, int(use_mode), sections, lines,
              frozen_tables)
    if fmt in _keys.MF52_FORMATS and not mf6:
        warn_unused_mf6(path, sections, lines)

    return TireProperties(
        path=path,
        sections=MappingProxyType({k: MappingProxyType(v) for k, v in sections.items()}),
        tables=MappingProxyType(frozen_tables),
        lines=MappingProxyType(lines),
    )
