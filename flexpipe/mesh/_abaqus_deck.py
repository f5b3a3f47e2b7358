"""Abaqus deck primitives for :mod:`flexpipe.mesh.abaqus`: the lines of a deck with
``*INCLUDE`` files inlined, keyword parameters, the deck's tables as they are read, set
members (lists, set names, ``GENERATE``) and the label namespaces of a part/assembly deck.

Namespaces (Abaqus/CAE decks): a label in the part or in a flat deck is kept; an
``Instance.label`` (``Plate-1.5``) is that part label; a bare label in the assembly or in
the steps of a deck with ``*ASSEMBLY`` is an *assembly-level* node or element (a reference
point, a MASS or connector element), which gets the id ``offset + label``: the offset is
the smallest power of ten above the largest part label (part nodes 1..441 -> assembly node
1 is 1001).  Assembly sets live in their own namespace too: a bare set name there means
the assembly's set (then the part's set of that name, as a fallback), and an assembly set
whose name a part set already has is stored as ``"<assembly name>.<set>"``
(``"Assembly.Set-1"``), the part set keeping its plain name."""

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
        self.couplings = []     # (ref, [(node id or set key, first, last)], file, line)
        self.instances = 0
        self.n1_node: dict[int, int] = {}   # beam element id -> orientation node id
        self.surfaces: dict[str, list] = {}    # NAME -> [(file, line, text, ctx)]
        self.pending = None     # (ref, surface, file, line, radius) of an open *COUPLING
        self.couplings2 = []    # (KINEMATIC|DISTRIBUTING, ref, surface, file, line,
                        #  influence radius or None, dofs)
        self.springs = []       # (elset, rows, file, line)
        self.connectors = []    # (elset, connection types, behavior, file, line)
        self.behaviors: dict[str, dict] = {}
        self.behavior = None
        self.dropped: dict[str, int] = {}
        self.dropped_at: dict[str, tuple] = {}   # keyword -> (file, line) of the first
        # part / assembly namespaces (see the module docstring)
        self.scope = "model"    # model | part | assembly | instance
        self.has_assembly = False
        self.asm_name = "Assembly"
        self.instance_name = None
        self.node_offset = 0    # id of assembly-level node label n: node_offset + n
        self.elem_offset = 0
        self.asm_labels: dict[int, int] = {}   # id -> label of assembly-level nodes
        self.asm_sets: dict[str, dict] = {"NSET": {}, "ELSET": {}}   # NAME -> key
        # *BOUNDARY and *FREQUENCY (model data and steps)
        self.bc_model = []      # (node id or node set key, dofs "123", file, line)
        self.bc_active = None   # constraints in effect in the current step
        self.bc_first = None    # ... at the end of the first step
        self.bc_used = None     # ... in the first *FREQUENCY step (what is applied)
        self.frequency = None   # (n, f_min, f_max, file, line) of that step
        self.step = None        # open step: {"new": bool, "freq": ..., "file", "line"}
        self.steps = 0
        self.done = False       # the frequency step is read: later steps are not used

    def ctx(self, params=None) -> str:
        """Namespace of the labels on the current keyword's lines: ``"asm"`` in the
        assembly and the steps of a part/assembly deck (not with ``INSTANCE=``), else
        ``"plain"``."""
        if not self.has_assembly or self.scope in ("part", "instance") or (
                params and "INSTANCE" in params):
            return "plain"
        return "asm"

    def node_id(self, tok: str, ctx: str):
        """Node id of the label ``tok`` (``12``, ``Part-1-1.12``), or None for a name."""
        return self._label(tok, ctx, self.node_offset)

    def elem_id(self, tok: str, ctx: str):
        """Element id of the label ``tok``, or None for a name."""
        return self._label(tok, ctx, self.elem_offset)

    @staticmethod
    def _label(tok, ctx, offset):
        tok = tok.strip()
        if tok.isdigit():
            return int(tok) + (offset if ctx == "asm" else 0)
        inst, dot, label = tok.rpartition(".")
        if dot and label.isdigit() and inst[:1].isalpha():
            return int(label)          # Instance.label: the part's own label
        return None

    def set_key(self, table: dict, name: str, ctx: str = "plain"):
        """Key of set ``name`` in ``table`` (case-insensitive; ``Instance.name`` allowed);
        in the assembly namespace (``ctx="asm"``) an assembly set comes first."""
        if ctx == "asm" and "." not in name:
            kind = "NSET" if table is self.nsets else "ELSET"
            key = self.asm_sets[kind].get(name.upper())
            if key is not None:
                return key
        for cand in (name, name.split(".")[-1]):
            for k in table:
                if k.upper() == cand.upper():
                    return k
        return None

    def define_set(self, kind: str, name: str) -> str:
        """Key under which the set ``name`` defined here (``*NSET``, ``NSET=``) is stored."""
        table = self.nsets if kind == "NSET" else self.elsets
        if self.has_assembly and self.scope not in ("part", "instance"):   # assembly set
            amap = self.asm_sets[kind]
            if name.upper() not in amap:
                taken = any(k.upper() == name.upper() for k in table)
                amap[name.upper()] = f"{self.asm_name}.{name}" if taken else name
            return amap[name.upper()]
        return self.set_key(table, name) or name

    def node_ref(self, tok: str, ctx: str):
        """A node label as its id (int), else the key of the node set ``tok`` (str, the
        name itself when no set has it yet)."""
        nid = self.node_id(tok, ctx)
        if nid is not None:
            return nid
        return self.set_key(self.nsets, tok, ctx) or tok

    def elset(self, name, ctx: str):
        """Key of the element set ``name`` referred to by a keyword (``ELSET=``)."""
        if name is None:
            return None
        return self.set_key(self.elsets, name, ctx) or name

    def nodes_of(self, ref, what: str, file, line) -> list:
        """Node ids of ``ref`` from :meth:`node_ref` (a node id or a node set key)."""
        if isinstance(ref, int):
            return [ref]
        key = self.set_key(self.nsets, ref)
        if key is None:
            raise MeshError(f"{what} refers to node set '{ref}', which is not defined",
                            file=file, line=line)
        return list(self.nsets[key])


def _members(deck, table, params, lines, what, ctx="plain"):
    out = []
    gen = "GENERATE" in params
    label = deck.node_id if table is deck.nsets else deck.elem_id
    offset = (deck.node_offset if table is deck.nsets else deck.elem_offset) \
        if ctx == "asm" else 0
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
            out.extend(range(a + offset, b + 1 + offset, st))
            continue
        for tok in toks:
            if tok.lstrip("-").isdigit() and not tok.isdigit():
                out.append(int(tok))
                continue
            ident = label(tok, ctx)
            if ident is not None:
                out.append(ident)
                continue
            key = deck.set_key(table, tok, ctx)
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
