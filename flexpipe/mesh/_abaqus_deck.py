"""Abaqus deck primitives for :mod:`flexpipe.mesh.abaqus`: the lines of a deck with
``*INCLUDE`` files inlined, keyword parameters, the deck's tables as they are read, and
set members (lists, set names, ``GENERATE``)."""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

from flexpipe.errors import MeshError
from flexpipe.mesh._bulk import read_deck_text


class _Lines:
    """Iterator over (file, line number, text) with ``*INCLUDE`` inlined."""

    def __init__(self, path: Path):
        self.items: list[tuple[str, int, str]] = []
        self._load(Path(path), ())
        self.pos = 0

    def _load(self, path: Path, stack):
        text = read_deck_text(path, stack, include="*INCLUDE", kind="an Abaqus input")
        for i, ln in enumerate(text.splitlines()):
            s = ln.strip()
            if not s or s.startswith("**"):
                continue
            if s.upper().startswith("*INCLUDE"):
                params = _params(s)
                name = params.get("INPUT")
                if not name:
                    raise MeshError("*INCLUDE needs INPUT=file", file=str(path), line=i + 1)
                target = Path(name) if Path(name).is_absolute() else path.parent / name
                if not target.is_file():
                    raise MeshError(f"*INCLUDE file '{name}' not found", file=str(path),
                                    line=i + 1)
                self._load(target, stack + (path.resolve(),))
                continue
            self.items.append((str(path), i + 1, s))

    def data(self):
        """Consume and yield the data lines up to the next keyword line."""
        while self.pos < len(self.items) and not self.items[self.pos][2].startswith("*"):
            yield self.items[self.pos]
            self.pos += 1


def _params(line: str) -> dict[str, str]:
    out = {}
    for part in line.split(",")[1:]:
        if not part.strip():
            continue
        k, _, v = part.partition("=")
        out[k.strip().upper()] = v.strip().strip('"')
    return out


class _Deck:
    def __init__(self, path: Path):
        self.path = path
        self.node_ids, self.coords, self.node_where = [], [], []
        self.eids = defaultdict(list)
        self.conn = defaultdict(list)
        self.ewhere = defaultdict(list)
        self.nsets: dict[str, list] = {}
        self.elsets: dict[str, list] = {}
        self.sections = []      # (elset, props, material, n1, file, line)
        self.materials: dict[str, dict] = {}
        self.masses = []        # (elset, mass, file, line)
        self.inertias = []      # (elset, 3x3, file, line)
        self.couplings = []     # (ref node id, [(node or set, first, last)], file, line)
        self.instances = 0
        self.n1_node: dict[int, int] = {}   # beam element id -> orientation node id
        self.surfaces: dict[str, list] = {}
        self.pending = None     # (ref node, surface, file, line) of an open *COUPLING
        self.couplings2 = []    # (KINEMATIC|DISTRIBUTING, ref, surface, file, line, dofs)
        self.springs = []       # (elset, rows, file, line)
        self.connectors = []    # (elset, connection types, behavior, file, line)
        self.behaviors: dict[str, dict] = {}
        self.behavior = None
        self.dropped: dict[str, int] = {}

    def set_key(self, table: dict, name: str):
        """Key of set ``name`` in ``table`` (case-insensitive; ``Instance.name`` allowed)."""
        for cand in (name, name.split(".")[-1]):
            for k in table:
                if k.upper() == cand.upper():
                    return k
        return None


def _members(deck, table, params, lines, what):
    out = []
    gen = "GENERATE" in params
    for f, ln, text in lines.data():
        toks = [t.strip() for t in text.split(",") if t.strip()]
        if gen:
            try:
                a, b, *step = (int(t) for t in toks)
            except ValueError:
                raise MeshError(f"{what} GENERATE: expected 'first, last[, step]' integers, "
                                f"got '{text}'", file=f, line=ln) from None
            st = step[0] if step else 1
            if st < 1 or b < a or (b - a) // st > 10_000_000:
                raise MeshError(f"{what} GENERATE {a}, {b}, {st}: need step >= 1, last >= first "
                                "and at most 10 million members", file=f, line=ln)
            out.extend(range(a, b + 1, st))
            continue
        for tok in toks:
            if tok.lstrip("-").isdigit():
                out.append(int(tok))
                continue
            key = deck.set_key(table, tok)
            if key is None:
                raise MeshError(f"{what} refers to set '{tok}', which is not defined "
                                "(before this line)", file=f, line=ln)
            out.extend(table[key])
    return out


def _rows(lines, f, ln, what, n=1):
    """The data lines of a keyword block; an error naming the keyword when too few."""
    rows = list(lines.data())
    if len(rows) < n:
        raise MeshError(f"{what} needs a data line", file=f, line=ln)
    return rows
