"""Nastran bulk-data tokenizer: physical lines -> cards with typed field access.

Handles free field (commas), small field (8 characters), large field (16 characters,
``NAME*`` and ``*`` continuation lines), continuation lines (first field blank, ``+`` or
``*``), ``$`` comments, executive/case control before ``BEGIN BULK``, ``ENDDATA`` and
``INCLUDE 'file'`` (relative to the including file; a quoted name may continue over the
following lines up to its closing quote, as MSC/NX Nastran allow).  The bulk data starts
after the ``BEGIN BULK`` line, matched as Nastran's free-format case control does: any case,
any blanks between and before the words, text after them (``begin  bulk``, ``BEGIN BULK
AUXMODEL=1``); a deck with ``CEND`` but no such line is an error (its executive and case
control would otherwise be read as bulk data).  Numbers may use Nastran's implied
exponent (``7.85-9``, ``1.+5``) or ``D`` exponents.

A deck cut short is an error naming the file, the line and the card (:func:`cut_checks`):
a continuation line with no card before it, a continuation marker in field 10 with no
continuation line after it, or - without ``ENDDATA`` - a last line that stops, without a
newline, inside a fixed-format field.
"""

from __future__ import annotations

import bisect
import itertools
import re
from dataclasses import dataclass, field
from pathlib import Path

from flexpipe.errors import MeshError

_IMPLIED_EXP = re.compile(r"^([+-]?(?:\d+\.?\d*|\.\d+))([+-]\d+)$")
_REQUIRED = object()
_SMALL = tuple(slice(8 + 8 * k, 16 + 8 * k) for k in range(8))
_LARGE = tuple(slice(8 + 16 * k, 24 + 16 * k) for k in range(4))


@dataclass
class Card:
    """One bulk-data entry: ``name`` and its data fields (field 2 onward, strings).

    ``preceding`` is the physical line just before the card's first line (kept for SET1
    cards only, whose ``$ SET name`` comment names the set; '' otherwise).
    """

    name: str
    fields: list[str] = field(default_factory=list)
    file: str = ""
    line: int = 0
    seq: int = 0
    preceding: str = ""

    def error(self, message: str) -> MeshError:
        """A :class:`MeshError` located at this card."""
        return MeshError(f"{self.name} {self.label()}: {message}", file=self.file, line=self.line)

    def label(self) -> str:
        """The card's id (its first field) for messages."""
        return self.fields[0] if self.fields and self.fields[0] else "?"

    def raw(self, i: int) -> str:
        """Field ``i`` as a stripped string ('' when blank or absent)."""
        return self.fields[i] if i < len(self.fields) else ""

    def int(self, i: int, name: str, default=_REQUIRED):
        """Integer field ``i`` (0-based data index) called ``name`` in messages."""
        s = self.raw(i)
        if not s:
            if default is _REQUIRED:
                raise self.error(f"field {name} is blank; it needs an integer")
            return default
        try:
            return int(s)
        except ValueError:
            raise self.error(f"field {name} = '{s}' is not an integer") from None

    def real(self, i: int, name: str, default=_REQUIRED):
        """Real field ``i`` (Nastran real syntax accepted)."""
        s = self.raw(i)
        if not s:
            if default is _REQUIRED:
                raise self.error(f"field {name} is blank; it needs a real number")
            return default
        v = parse_real(s)
        if v is None:
            raise self.error(f"field {name} = '{s}' is not a number")
        return v

    def is_int(self, i: int) -> bool:
        """True when field ``i`` holds an integer (e.g. CBAR G0 instead of X1)."""
        s = self.raw(i)
        return bool(s) and (s.lstrip("+-").isdigit())


def parse_real(s: str):
    """Parse a Nastran real (``1.5``, ``1.5E-3``, ``1.5-3``, ``1.5D-3``, ``7``); None if bad."""
    t = s.strip().upper().replace("D", "E")
    try:
        return float(t)
    except ValueError:
        m = _IMPLIED_EXP.match(t)
        if m:
            return float(f"{m.group(1)}E{m.group(2)}")
    return None


def _split(line: str) -> tuple[str, list[str]]:
    """Split one physical line into (first field, data fields)."""
    if "," in line:
        parts = [p.strip() for p in line.split(",")]
        first = parts[0]
        width = 4 if (first.endswith("*") or first.startswith("*")) else 8
        data = parts[1:]
        if len(data) == width + 1 or (len(data) > width and data[-1][:1] in ("+", "*")):
            data = data[:-1]                # trailing continuation marker
        elif len(data) < width:
            data = data + [""] * (width - len(data))
        return first, data
    first = line[:8].strip()
    if first.endswith("*") or first.startswith("*"):
        return first, [line[s].strip() for s in _LARGE]
    return first, [line[s].strip() for s in _SMALL]


def _include_statement(lines: list[str], i: int, s: str, path: Path) -> tuple[str, int]:
    """The whole INCLUDE statement starting on line ``i`` (code ``s``) and the index of its
    last line.  A quoted file name that is not closed on the line continues on the next
    lines (MSC/NX Nastran), each stripped of its leading and trailing blanks, until the
    closing quote."""
    m = re.match(r"^\s*INCLUDE\s+(['\"])", s, flags=re.IGNORECASE)
    if m is None or s.count(m.group(1)) != 1:
        return s, i
    q, parts = m.group(1), [s.rstrip()]
    for j in range(i + 1, len(lines)):
        t = lines[j].split("$", 1)[0].strip()
        parts.append(t)
        if q in t:
            return "".join(parts), j
    raise MeshError(f"INCLUDE: the file name opened with {q} on this line is never closed "
                    f"(no closing {q} up to the end of the file); a name continued on the "
                    f"next lines must end with {q}", file=str(path), line=i + 1)


def _include_target(line: str, path: Path, lineno: int, last: int | None = None) -> Path:
    m = re.match(r"^\s*INCLUDE\s+['\"]?([^'\"]+)['\"]?\s*$", line, flags=re.IGNORECASE)
    if not m:
        raise MeshError("cannot parse INCLUDE statement; write INCLUDE 'file.bdf'",
                        file=str(path), line=lineno)
    target = Path(m.group(1).strip())
    if not target.is_absolute():
        near = path.parent / target
        target = near if near.exists() or not target.exists() else target
    if not target.is_file():
        span = f" (the name continued over lines {lineno}-{last})" if last else ""
        raise MeshError(f"INCLUDE file '{m.group(1)}'{span} not found (looked next to "
                        f"{path.name})", file=str(path), line=lineno)
    return target


#: the case-control line that starts the bulk data: free format, any case, blanks
#: before and between the words, anything after (MSC/NX ``BEGIN BULK [AUXMODEL=..]``)
_BEGIN_BULK = re.compile(r"\s*BEGIN\s+BULK(?![A-Z0-9_])", re.IGNORECASE)
_CEND = re.compile(r"^[ \t]*CEND[ \t]*(?:\$.*)?$", re.IGNORECASE | re.MULTILINE)


def bulk_start(lines: list[str], text: str, path: Path) -> int:
    """Index of the first bulk-data line of a deck: the line after ``BEGIN BULK`` (see the
    module docstring), 0 without one.  A deck with a ``CEND`` line (the end of the
    executive control) but no ``BEGIN BULK`` is an error naming the ``CEND`` line."""
    for i, ln in enumerate(lines):
        s = ln.lstrip()
        if s[:5].upper() == "BEGIN" and _BEGIN_BULK.match(s.split("$", 1)[0]):
            return i + 1
    m = _CEND.search(text)
    if m is not None:
        line = next((i + 1 for i, ln in enumerate(lines)
                     if _CEND.match(ln.split("$", 1)[0])), None)
        raise MeshError("CEND (end of the executive control) but no BEGIN BULK line "
                        "follows: the case control and the bulk data cannot be told apart; "
                        "start the bulk data with a line 'BEGIN BULK'", file=str(path),
                        line=line)
    return 0


#: cards taken by the vectorized fast path when written in plain small-field format
FAST_CARDS = ("GRID", "CQUAD4", "CTRIA3")


class FastLines:
    """Plain small-field lines of the :data:`FAST_CARDS`, kept as text (no Card objects).

    ``lines[name]`` are the raw lines, ``where[name]`` their (file, line, sequence) - the
    sequence number orders them among all cards of the deck.  :meth:`card` builds the
    :class:`Card` of one line when a message needs it.
    """

    def __init__(self):
        self.lines: dict[str, list[str]] = {n: [] for n in FAST_CARDS}
        self.where: dict[str, list[tuple]] = {n: [] for n in FAST_CARDS}

    def card(self, name: str, i: int) -> Card:
        """The Card of fast line ``i`` of ``name``."""
        first, data = _split(self.lines[name][i])
        f, ln, seq = self.where[name][i]
        c = Card(name, data, f, ln, seq)
        while c.fields and not c.fields[-1]:
            c.fields.pop()
        return c


def read_deck_text(path: Path, stack, *, include: str, kind: str) -> str:
    """Text of the deck file ``path`` (Latin-1), included from the files in ``stack``;
    a clear error for an include loop, an unreadable file or binary content."""
    if path.resolve() in stack:
        raise MeshError(f"{include} loop: the file includes itself", file=str(path))
    try:
        text = path.read_text(encoding="latin-1")
    except OSError as exc:
        raise MeshError(f"cannot read file: {exc.strerror or exc}", file=str(path)) from None
    if "\x00" in text[:4096]:
        raise MeshError(f"not {kind} text file (binary content: a NUL byte)",
                        file=str(path), line=text[:text.index("\x00")].count("\n") + 1)
    return text


def _card_of(lines: list[str], i: int) -> str:
    """``"GRID* 20"``: name and id of the card that physical line ``i`` belongs to."""
    for j in range(i, -1, -1):
        s = lines[j].split("$", 1)[0].rstrip().expandtabs(8)
        if s.strip():
            first, data = _split(s)
            if first and first[0] not in "+*":
                return f"{first.upper()} {data[0] if data and data[0] else '?'}"
    return "?"


def _marker(s: str) -> str:
    """The continuation marker of card line ``s`` ('' if none): columns 73-80 of a fixed
    field line, a last free field after the data fields that starts with ``+`` or ``*``."""
    if "," not in s:
        return s[72:80].strip()
    parts = [p.strip() for p in s.split(",")]
    width = 4 if parts[0].endswith("*") or parts[0].startswith("*") else 8
    return parts[-1] if len(parts) > width + 1 and parts[-1][:1] in ("+", "*") else ""


def _mid_field(s: str) -> tuple[int, int, int] | None:
    """``(field number on the line, first and last column)`` when fixed-format line ``s``
    stops inside a field that starts with a blank - its right-justified value is missing
    or cut; None otherwise.  A complete line of a right-justified writer ends at a field
    boundary; a left-justified value starts its field.  A line of only a card name (or
    continuation mark) is cut too: every bulk-data card but ENDDATA has data fields."""
    if "," in s or "\t" in s or "$" in s or not s.strip() \
            or s.lstrip()[:7].upper() == "INCLUDE":
        return None
    if len(s) <= 8:
        return 1, 1, 8
    first = s[:8].strip()
    width = 16 if first.endswith("*") or first.startswith("*") else 8
    k = (len(s) - 8) % width
    if k == 0 or s[len(s) - k] != " ":
        return None
    return 2 + (len(s) - 8) // width, len(s) - k + 1, len(s) - k + width


def _is_continuation(s: str) -> bool:
    """True when card line ``s`` continues the card before it (first field blank, + or *)."""
    first = s.split(",", 1)[0].strip() if "," in s else s.expandtabs(8)[:8].strip()
    return first == "" or first[0] in "+*"


def cut_checks(lines: list[str], start: int, stop: int, *, ended: bool, newline: bool,
               path: Path) -> None:
    """Raise a :class:`MeshError` (file, line, card) if bulk-data lines ``start:stop`` of
    ``path`` look cut short (see the module docstring).

    This reader joins a continuation to the card line right before it, so a field-10
    marker whose next card line is not a continuation means a missing (or misplaced)
    continuation: the card would be read with its last fields blank.
    """
    def code(i):
        return lines[i].split("$", 1)[0].rstrip()

    def marked(ln):            # quick pre-filter: columns 73-80 used, or a last "+.." item
        return len(ln) > 72 or ("," in ln and ln.rsplit(",", 1)[1].lstrip()[:1] in ("+", "*"))

    for i in [i for i in range(start, stop) if marked(lines[i])]:
        m = _marker(code(i).expandtabs(8))
        if not m:
            continue
        j = next((j for j in range(i + 1, stop) if code(j).strip()), None)
        if j is None:
            raise MeshError(
                f"{_card_of(lines, i)}: line {i + 1} ends with the continuation marker '{m}' "
                f"but the {'bulk data' if ended else 'file'} ends there: its continuation "
                "line is missing (the file is cut short?)", file=str(path), line=i + 1)
        if not _is_continuation(code(j)):
            raise MeshError(
                f"{_card_of(lines, i)}: line {i + 1} ends with the continuation marker '{m}' "
                f"but line {j + 1} starts a new card ({_card_of(lines, j)}): its "
                "continuation line is missing or misplaced (it must follow its card "
                "directly)", file=str(path), line=i + 1)
    last = stop - 1
    cut = _mid_field(lines[last]) if last >= start and not ended and not newline else None
    if cut is not None:
        raise MeshError(
            f"{_card_of(lines, last)}: the file ends at column {len(lines[last])} of line "
            f"{last + 1}, inside field {cut[0]} of the line (columns {cut[1]}-{cut[2]}, "
            "right-justified: its value is missing or cut), with no newline and no "
            "ENDDATA: the file is cut short; write it again or restore its end",
            file=str(path), line=last + 1)


def read_cards(path: Path, *, fast: FastLines | None = None, control: list | None = None,
               _stack: tuple = (), _seq: list | None = None) -> list[Card]:
    """All bulk-data cards of ``path`` (INCLUDE files inlined), in file order.

    With ``fast``, plain small-field GRID/CQUAD4/CTRIA3 lines without continuation go
    to ``fast`` as text instead (see :class:`FastLines`).  Every card and fast line gets
    a sequence number (``Card.seq``): file order, the cards of an included file
    following those of the file that includes it.  With ``control`` (a list), the
    executive/case-control lines of ``path`` itself - those before ``BEGIN BULK``, none
    without that line - are appended to it (for :func:`case_control`).
    """
    path = Path(path)
    seq = _seq if _seq is not None else [0]
    text = read_deck_text(path, _stack, include="INCLUDE", kind="a Nastran bulk-data")
    lines = text.splitlines()
    start = bulk_start(lines, text, path)
    if control is not None:
        control.extend(lines[:max(start - 1, 0)])
    base = seq[0]
    seq[0] = base + len(lines) + 1
    fpath = str(path)
    fast_at: list[int] = []
    if fast is not None:       # plain small-field lines of the fast cards, in one pass
        heads = {f"{n:<8}" for n in FAST_CARDS}
        fast_at = [i for i, ln in enumerate(lines) if ln[:8] in heads and "," not in ln
                   and "\t" not in ln and "$" not in ln and i >= start]
    is_fast = bytearray(len(lines))
    for i in fast_at:
        is_fast[i] = 1
    others = [i for i in range(start, len(lines)) if not is_fast[i]] if fast_at else \
        range(start, len(lines))
    cards: list[Card] = []
    current: Card | None = None
    last = -1                    # index of the last card line read card by card
    includes = []
    stop = None                  # index of the ENDDATA line
    skip_to = -1                 # last line of a continued INCLUDE file name
    for i in others:
        if i <= skip_to:
            continue
        if fast_at:              # a fast line since the last card: it is the current card
            p = bisect.bisect_left(fast_at, i) - 1
            if p >= 0 and fast_at[p] > last:
                last, current = fast_at[p], None
        s = lines[i]
        if "$" in s:
            s = s.split("$", 1)[0]
        s = s.rstrip()
        if not s.strip():
            continue
        if "\t" in s:
            s = s.expandtabs(8)
        head = s.lstrip()[:7].upper() if s[0] in "EeIi " else ""
        if head == "ENDDATA":
            for j in fast_at[bisect.bisect_left(fast_at, i):]:
                is_fast[j] = 0
            stop = i
            break
        if head == "INCLUDE":
            current, last = None, -1
            s, skip_to = _include_statement(lines, i, s, path)
            includes.append((i, _include_target(s, path, i + 1, skip_to + 1 if skip_to > i
                                                else None)))
            continue
        first, data = _split(s)
        if first == "" or first[0] in "+*":
            if current is None and last >= 0 and is_fast[last]:   # a fast line continued
                is_fast[last] = 0
                f0, d0 = _split(lines[last])
                current = Card(f0.upper(), d0, fpath, last + 1, base + last)
                cards.append(current)
            if current is None:
                raise MeshError(f"continuation line '{s.strip()[:40]}' has no card before "
                                "it: the file starts inside a card (cut?), or the card's "
                                "first line is missing", file=str(path), line=i + 1)
            current.fields.extend(data)
            continue
        current = Card(first.rstrip("*").upper(), data, fpath, i + 1, base + i)
        if i and current.name == "SET1":      # its "$ SET name" comment, if any
            current.preceding = lines[i - 1]
        last = i
        cards.append(current)
    cut_checks(lines, start, len(lines) if stop is None else stop, ended=stop is not None,
               newline=text.endswith(("\n", "\r")), path=path)
    if fast_at:
        kept = [i for i in fast_at if is_fast[i]]
        code = [lines[i][1] for i in kept]           # R: GRID, Q: CQUAD4, T: CTRIA3
        for name in FAST_CARDS:
            idx = list(itertools.compress(kept, [ch == name[1] for ch in code]))
            fast.lines[name].extend([lines[i] for i in idx])
            fast.where[name].extend(zip(itertools.repeat(fpath), [i + 1 for i in idx],
                                        [base + i for i in idx]))
    for _line, target in includes:
        cards.extend(read_cards(target, fast=fast, _stack=_stack + (path.resolve(),),
                                _seq=seq))
    for c in cards:
        while c.fields and not c.fields[-1]:
            c.fields.pop()
    return cards


_CASE = re.compile(r"^\s*(SPC|METHOD|SOL)\s*(?:\(\s*([A-Za-z]+)\s*\))?\s*=?\s*(\d+)\s*$",
                   re.IGNORECASE)
_CASE_WORD = re.compile(r"^\s*(SPC|METHOD)(?![A-Z0-9_])", re.IGNORECASE)
#: named solutions of the executive SOL statement that compute normal modes
_SOL_NAMES = {"SEMODES": 103, "MODES": 103}


def case_control(lines: list[str], path=None) -> dict:
    """``SOL``, ``SPC`` and ``METHOD`` set ids of the executive/case control section.

    ``lines`` are the lines of the main file before ``BEGIN BULK`` (``read_cards(...,
    control=lines)``; empty when the file has no ``BEGIN BULK`` line).  The first
    occurrence wins (global case control, else the first subcase); each value is ``(set
    id, line number)``.  ``METHOD`` may carry a describer, ``METHOD(STRUCTURE) = n`` or
    ``METHOD(BOTH) = n`` (MSC/NX, HyperMesh/OptiStruct): the structure's method;
    ``METHOD(FLUID)`` is not for the structure and is skipped with a warning, and so is an
    ``SPC``/``METHOD`` line this reader cannot read (e.g. ``SPC = ALL``), naming ``path``
    and the line.  ``SOL SEMODES`` counts as ``SOL 103``.
    """
    out: dict = {}
    where = f"{path}, " if path else ""
    for i, ln in enumerate(lines):
        s = ln.split("$", 1)[0]
        if not s.strip():
            continue
        m = _CASE.match(s)
        if m and m.group(2) is not None:
            word, describer = m.group(1).upper(), m.group(2).upper()
            ok = word == "METHOD" and (describer in ("BOTH", "STRUCTURE")
                                       or (len(describer) >= 4
                                           and "STRUCTURE".startswith(describer)))
            if not ok:
                _case_warning(f"{where}line {i + 1}: case control '{s.strip()}' is ignored: "
                              + ("METHOD(FLUID) selects the fluid's eigenvalue method, not "
                                 "the structure's" if word == "METHOD"
                                 and "FLUID".startswith(describer) else
                                 f"the describer ({m.group(2)}) is not understood")
                              + f"; valid: {word} = n" + (", METHOD(STRUCTURE) = n, "
                                                          "METHOD(BOTH) = n"
                                                          if word == "METHOD" else ""))
                continue
        if m is None:
            t = re.match(r"^\s*SOL\s+(\d+|[A-Za-z]+)", s, re.IGNORECASE)
            if t:
                v = t.group(1).upper()
                if v.isdigit() or v in _SOL_NAMES:
                    out.setdefault("SOL", (int(v) if v.isdigit() else _SOL_NAMES[v], i + 1))
                else:
                    out.setdefault("SOL", (v, i + 1))
                continue
            w = _CASE_WORD.match(s)
            if w and w.group(1).upper() not in out:
                _case_warning(f"{where}line {i + 1}: case control '{s.strip()}' is not "
                              f"understood and ignored; valid: {w.group(1).upper()} = n (a "
                              "set id)" + (", METHOD(STRUCTURE) = n"
                                          if w.group(1).upper() == "METHOD" else ""))
            continue
        out.setdefault(m.group(1).upper(), (int(m.group(3)), i + 1))
    return out


def _case_warning(text: str) -> None:
    import warnings

    from flexpipe.mesh.validate import MeshWarning

    warnings.warn(MeshWarning(text), stacklevel=4)
