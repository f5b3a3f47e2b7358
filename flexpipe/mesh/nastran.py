"""Nastran bulk data (``.bdf``, ``.nas``, ``.dat``) reader: a small dedicated parser.

Cards read
----------
``GRID`` (``CP`` = 0 or a ``CORD2R`` system), ``CTETRA`` (4 or 10 nodes), ``CHEXA`` (8),
``CQUAD4``, ``CTRIA3``, ``CBAR``/``CBEAM`` (orientation vector ``X1 X2 X3`` or node
``G0``), ``CONM2``, ``RBE2``, ``PSHELL`` (``T``, ``MID1``), ``PSOLID``, ``PBAR``,
``PBEAM`` (end-A values ``A, I1, I2, J``), ``MAT1`` (``E, G, NU, RHO``), ``CORD2R``,
``SET1`` (grid ids, ``THRU`` ranges) as the node set ``"SET<id>"``, also named ``name``
when the line before the card is the comment ``$ SET name``.

GRIDs used only as CBAR/CBEAM ``G0`` orientation nodes are dropped after use.  Every
element gets the cell set ``"PID<n>"`` of its property id, and
``Mesh.sections["PID<n>"]`` holds ``thickness`` (PSHELL T), beam ``A, Iy, Iz, J``
(Nastran ``I1`` bends in the x-y plane of the element and becomes ``Iz``, ``I2`` becomes
``Iy``) and ``E, nu, rho`` of the referenced MAT1, in the units of the file (see
:mod:`flexpipe.mesh.units`).

Not read
--------
Loads, constraints (``SPC``, ``GRID`` PS), case control; ``CD`` displacement systems
(orientation vectors and RBE2 components are taken in the basic system - a warning says
so).  Elements this parser does not know (``CPENTA``, ``CQUAD8``, ``RBE3``, ``CBUSH``, ...)
raise :class:`~flexpipe.errors.MeshError`, because dropping them would silently change
the structure; ``PBARL``/``PBEAML``/``PCOMP`` are skipped with a warning (pass the section
to :func:`~flexpipe.fem.assemble` instead).
"""

from __future__ import annotations

import warnings
from collections import defaultdict
from pathlib import Path

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.mesh._bulk import Card, read_cards
from flexpipe.mesh.mesh import CellBlock, Mesh, PointMass, RigidLink
from flexpipe.mesh.validate import MeshWarning, prune, referenced

SUPPORTED = ("CTETRA (4/10 nodes)", "CHEXA (8)", "CQUAD4", "CTRIA3", "CBAR", "CBEAM",
             "CONM2", "RBE2")
UNSUPPORTED_ELEMENTS = {
    "CPENTA", "CPYRAM", "CQUAD8", "CTRIA6", "CQUADR", "CTRIAR", "CQUAD", "CTRIAX", "CTRIAX6",
    "CQUADX", "CROD", "CONROD", "CTUBE", "CELAS1", "CELAS2", "CELAS3", "CELAS4", "CBUSH",
    "CBUSH1D", "CBEND", "CSHEAR", "CGAP", "CWELD", "CFAST", "CSEAM", "CDAMP1", "CDAMP2",
    "CVISC", "CONM1", "CMASS1", "CMASS2", "RBE1", "RBE3", "RBAR", "RBAR1", "RROD", "RTRPLT",
    "RSPLINE", "MPC", "GENEL", "DMIG",
}
SKIPPED_PROPERTIES = {"PBARL", "PBEAML", "PCOMP", "PCOMPG"}
OTHER_MATERIALS = {"MAT2", "MAT8", "MAT9", "MAT3", "MATS1"}
#: element card -> (meshio type by node count, index of first node field, max nodes)
ELEMENTS = {
    "CTETRA": ({4: "tetra", 10: "tetra10"}, 2, 10),
    "CHEXA": ({8: "hexahedron"}, 2, 20),
    "CQUAD4": ({4: "quad"}, 2, 4),
    "CTRIA3": ({3: "triangle"}, 2, 3),
    "CBAR": ({2: "line"}, 2, 2),
    "CBEAM": ({2: "line"}, 2, 2),
}


class _Elements:
    """Per-type accumulators of element cards."""

    def __init__(self):
        self.eid = defaultdict(list)
        self.pid = defaultdict(list)
        self.nodes = defaultdict(list)
        self.cards = defaultdict(list)
        self.orient = []      # (X1, X2, X3) or None, for line cells
        self.g0 = []          # G0 node id or 0
        self.offsets = []     # (WA, WB) for line cells
        self.zoffs = defaultdict(list)


def _element(card: Card, els: _Elements) -> None:
    types, first, nmax = ELEMENTS[card.name]
    eid = card.int(0, "EID")
    pid = card.int(1, "PID", eid)
    if card.name in ("CBAR", "CBEAM"):
        g = [card.int(2, "GA"), card.int(3, "GB")]
    else:
        raw = card.fields[first:first + nmax]
        try:  # fast path; on a bad field fall back to the checked parser for its message
            g = [int(x) if x else 0 for x in raw]
        except ValueError:
            g = [card.int(first + k, f"G{k + 1}", 0) for k in range(nmax)]
        g += [0] * (nmax - len(g))
        if card.name in ("CTETRA", "CHEXA"):
            g = [x for x in g if x]
    n = len(g)
    if n not in types or 0 in g:
        if card.name == "CHEXA" and n > 8:
            raise card.error(f"CHEXA with {n} nodes (hexahedron20) is not supported; "
                             "use 8-node CHEXA or 10-node CTETRA")
        raise card.error(f"{card.name} with {n} nodes is not supported; valid: "
                         f"{sorted(types)} node(s)")
    cell_type = types[n]
    els.eid[cell_type].append(eid)
    els.pid[cell_type].append(pid)
    els.nodes[cell_type].append(g)
    els.cards[cell_type].append(card)
    if cell_type == "line":
        if card.is_int(4) and not card.raw(5) and not card.raw(6):
            els.g0.append(card.int(4, "G0"))
            els.orient.append(None)
        else:
            els.g0.append(0)
            vals = [card.real(4 + k, f"X{k + 1}", None) for k in range(3)]
            els.orient.append(None if all(v is None for v in vals)
                              else [0.0 if v is None else v for v in vals])
        if card.raw(8) or card.raw(9):
            warnings.warn(MeshWarning(f"{card.file} line {card.line}: {card.name} {eid} pin "
                                      "flags PA/PB are not modelled (ends stay rigid)"),
                          stacklevel=4)
        w = [card.real(10 + k, "W", 0.0) for k in range(6)]
        els.offsets.append(w)
    elif cell_type in ("quad", "triangle"):
        z = card.real(7 if cell_type == "quad" else 6, "ZOFFS", 0.0)
        els.zoffs[cell_type].append(z)
        tcols = range(10, 14) if cell_type == "quad" else range(11, 14)
        if any(card.raw(k) for k in tcols):
            warnings.warn(MeshWarning(f"{card.file} line {card.line}: {card.name} {eid} corner "
                                      "thicknesses T1.. are ignored; the PSHELL T applies"),
                          stacklevel=4)


def _material(card: Card) -> dict:
    E = card.real(1, "E", None)
    G = card.real(2, "G", None)
    nu = card.real(3, "NU", None)
    rho = card.real(4, "RHO", None)
    if E is None and G is not None and nu is not None:
        E = 2.0 * (1.0 + nu) * G
    if nu is None and E is not None and G is not None:
        nu = E / (2.0 * G) - 1.0
    if E is None or nu is None:
        raise card.error("needs E and NU (or two of E, G, NU)")
    if rho is None:
        warnings.warn(MeshWarning(f"{card.file} line {card.line}: MAT1 {card.label()} has no "
                                  "RHO: its elements are massless"), stacklevel=4)
        rho = 0.0
    return {"E": E, "nu": nu, "rho": rho}


def _cord2r(cards: dict[int, Card], cid: int, cache: dict, user: Card):
    """Origin and rotation (columns = local axes in basic) of a CORD2R system."""
    if cid == 0:
        return np.zeros(3), np.eye(3)
    if cid in cache:
        return cache[cid]
    card = cards.get(cid)
    if card is None:
        raise user.error(f"refers to coordinate system {cid}, which is not defined")
    if card.name != "CORD2R":
        raise user.error(f"refers to coordinate system {cid} ({card.name}); only CORD2R "
                         "(rectangular) systems are supported")
    cache[cid] = None  # loop guard
    rid = card.int(1, "RID", 0)
    if rid in cache and cache[rid] is None:
        raise card.error("coordinate systems refer to each other in a loop")
    o, R = _cord2r(cards, rid, cache, card)
    pts = np.array([[card.real(2 + 3 * p + k, "A/B/C", 0.0) for k in range(3)]
                    for p in range(3)])
    A, B, C = o + pts @ R.T
    ez = B - A
    ey = np.cross(ez, C - A)
    if np.linalg.norm(ez) == 0 or np.linalg.norm(ey) == 0:
        raise card.error("points A, B, C are collinear or coincide")
    ez /= np.linalg.norm(ez)
    ey /= np.linalg.norm(ey)
    cache[cid] = (A, np.column_stack([np.cross(ey, ez), ey, ez]))
    return cache[cid]


def _check_unique(ids: np.ndarray, cards: list[Card], what: str) -> None:
    order = np.argsort(ids, kind="stable")
    s = ids[order]
    dup = np.flatnonzero(s[1:] == s[:-1])
    if dup.size:
        a, b = cards[order[dup[0]]], cards[order[dup[0] + 1]]
        raise MeshError(
            f"{what} id {int(s[dup[0]])} is defined twice: {a.name} at {Path(a.file).name} "
            f"line {a.line} and {b.name} at {Path(b.file).name} line {b.line}; ids must be "
            "unique", file=b.file, line=b.line)


def _index_of(grid_ids, sorter, wanted, cards, label):
    """0-based node indices of grid ids ``wanted`` (n, k); error names the card."""
    wanted = np.asarray(wanted, dtype=np.int64)
    pos = np.searchsorted(grid_ids, wanted.ravel(), sorter=sorter)
    pos = np.clip(pos, 0, len(grid_ids) - 1)
    idx = sorter[pos] if len(grid_ids) else pos
    ok = grid_ids[idx] == wanted.ravel() if len(grid_ids) else np.zeros(wanted.size, bool)
    if not ok.all():
        bad = int(np.flatnonzero(~ok)[0])
        card = cards[bad // max(wanted.shape[1], 1)] if wanted.ndim == 2 else cards[bad]
        raise card.error(f"{label} refers to GRID {int(wanted.ravel()[bad])}, which is not "
                         "defined")
    return idx.reshape(wanted.shape)


def read_nastran(path) -> Mesh:
    """Read a Nastran bulk-data deck into a :class:`Mesh` (units of the file)."""
    path = Path(path)
    cards = read_cards(path)
    grids, coords, mats, props = [], {}, {}, {}
    other_mats, conm2, rbe2, set1 = {}, [], [], []
    els = _Elements()
    for c in cards:
        n = c.name
        if n == "GRID":
            grids.append(c)
        elif n in ELEMENTS:
            _element(c, els)
        elif n == "CONM2":
            conm2.append(c)
        elif n == "RBE2":
            rbe2.append(c)
        elif n == "SET1":
            set1.append(c)
        elif n in ("PSHELL", "PSOLID", "PBAR", "PBEAM") or n in SKIPPED_PROPERTIES:
            props[c.int(0, "PID")] = c
        elif n == "MAT1":
            mats[c.int(0, "MID")] = c
        elif n in OTHER_MATERIALS:
            other_mats[c.int(0, "MID")] = c
        elif n.startswith("CORD"):
            coords[c.int(0, "CID")] = c
        elif n in UNSUPPORTED_ELEMENTS:
            raise c.error(f"{n} is not supported; supported element cards: "
                          f"{', '.join(SUPPORTED)}. Remove or convert it")
    if not grids:
        raise MeshError("no GRID cards found: not a Nastran bulk-data deck?", file=str(path))

    # ---- nodes
    gid = np.array([c.int(0, "ID") for c in grids], dtype=np.int64)
    _check_unique(gid, grids, "GRID")
    cp = np.array([c.int(1, "CP", 0) for c in grids], dtype=np.int64)
    X = np.array([[c.real(2 + k, f"X{k + 1}", 0.0) for k in range(3)] for c in grids])
    cache: dict = {}
    for sys_id in np.unique(cp[cp != 0]):
        rows = np.flatnonzero(cp == sys_id)
        o, R = _cord2r(coords, int(sys_id), cache, grids[rows[0]])
        X[rows] = o + X[rows] @ R.T
    if any(c.int(5, "CD", 0) for c in grids):
        warnings.warn(MeshWarning(f"{path}: GRID CD (displacement coordinate systems) are "
                                  "ignored: RBE2 components and CBAR vectors are read in the "
                                  "basic system"), stacklevel=3)
    sorter = np.argsort(gid, kind="stable")

    # ---- element ids unique across elements, masses and rigid links
    all_cards = [c for t in els.cards for c in els.cards[t]] + conm2 + rbe2
    all_ids = np.array([e for t in els.cards for e in els.eid[t]]
                       + [c.int(0, "EID") for c in conm2 + rbe2], dtype=np.int64)
    _check_unique(all_ids, all_cards, "element")

    # ---- cell blocks, PID cell sets, sections
    blocks, cell_sets, sections = [], {}, {}
    g0_nodes = np.zeros(0, dtype=np.int64)
    for cell_type in els.eid:
        eid = np.array(els.eid[cell_type], dtype=np.int64)
        pid = np.array(els.pid[cell_type], dtype=np.int64)
        conn = _index_of(gid, sorter, els.nodes[cell_type], els.cards[cell_type], "a node")
        data = {}
        if cell_type == "line":
            ori = np.array([o if o is not None else [np.nan] * 3 for o in els.orient])
            g0 = np.array(els.g0, dtype=np.int64)
            has = np.flatnonzero(g0 > 0)
            if has.size:
                gi = _index_of(gid, sorter, g0[has], [els.cards["line"][i] for i in has], "G0")
                ori[has] = X[gi] - X[conn[has, 0]]
                g0_nodes = gi
            data["orientation"] = ori
            w = np.array(els.offsets, dtype=float)
            if np.any(w):
                data["offset_a"], data["offset_b"] = w[:, :3], w[:, 3:]
                warnings.warn(MeshWarning(f"{path}: CBAR/CBEAM end offsets WA/WB are stored in "
                                          "block.data but not modelled by the beam element"),
                              stacklevel=3)
        elif cell_type in els.zoffs and np.any(els.zoffs[cell_type]):
            data["zoffset"] = np.array(els.zoffs[cell_type], dtype=float)
            warnings.warn(MeshWarning(f"{path}: shell ZOFFS offsets are stored in block.data "
                                      "but not modelled by the shell elements"), stacklevel=3)
        bi = len(blocks)
        blocks.append(CellBlock(cell_type, conn, eid, pid, data))
        for p in np.unique(pid):
            cell_sets.setdefault(f"PID{p}", {})[bi] = np.flatnonzero(pid == p)
            card = props.get(int(p))
            if card is not None and f"PID{p}" not in sections:
                sec = _section(card, cell_type, mats, other_mats,
                               els.cards[cell_type][int(np.argmax(pid == p))])
                if sec:
                    sections[f"PID{p}"] = sec

    # ---- concentrated masses and rigid links
    masses = []
    for c in conm2:
        node = int(_index_of(gid, sorter, [c.int(1, "G")], [c], "G")[0])
        cid = c.int(2, "CID", 0)
        off = np.array([c.real(4 + k, f"X{k + 1}", 0.0) for k in range(3)])
        i11, i21, i22, i31, i32, i33 = (c.real(8 + k, "I", 0.0) for k in range(6))
        inertia = np.array([[i11, -i21, -i31], [-i21, i22, -i32], [-i31, -i32, i33]])
        if cid == -1:
            off = off - X[node]
        elif cid > 0:
            _, R = _cord2r(coords, cid, cache, c)
            off, inertia = R @ off, R @ inertia @ R.T
        masses.append(PointMass(node, c.real(3, "M"), inertia, off, c.int(0, "EID")))
    links = [_rbe2(c, gid, sorter) for c in rbe2]
    node_sets = _node_sets(set1, gid, sorter)
    mesh = Mesh(points=X, blocks=tuple(blocks), node_ids=gid, cell_sets=cell_sets,
                point_masses=tuple(masses), rigid_links=tuple(links), sections=sections,
                node_sets=node_sets, source=str(path))
    return drop_orientation_nodes(mesh, g0_nodes)


def _node_sets(set1: list, gid, sorter) -> dict:
    """SET1 cards as node sets ``"SET<id>"``, plus the names of ``$ SET name`` comments."""
    out, names, text = {}, {}, {}
    for c in set1:
        sid = c.int(0, "SID")
        ids, k = [], 1
        while k < len(c.fields):
            f = c.raw(k).upper()
            if f == "THRU":
                lo, hi = ids[-1], c.int(k + 1, "THRU end")
                ids.extend(range(lo + 1, hi + 1))
                k += 2
                continue
            if f:
                ids.append(c.int(k, f"ID{k}"))
            k += 1
        idx = _index_of(gid, sorter, ids, [c] * len(ids), "a grid") if ids else []
        out[f"SET{sid}"] = np.asarray(idx, dtype=np.int64)
        if c.file not in text:
            try:
                text[c.file] = Path(c.file).read_text(errors="replace").splitlines()
            except OSError:
                text[c.file] = []
        lines = text[c.file]
        prev = lines[c.line - 2].strip() if 2 <= c.line <= len(lines) + 1 else ""
        if prev.startswith("$ SET ") and len(prev.split()) == 3:
            names[prev.split()[2]] = out[f"SET{sid}"]
    return {**out, **names}


def drop_orientation_nodes(mesh: Mesh, nodes) -> Mesh:
    """Remove nodes that only orient beams (CBAR G0, Abaqus n1 node): they carry no DOF."""
    nodes = np.asarray(nodes, dtype=np.int64)
    if nodes.size == 0:
        return mesh
    only = np.zeros(mesh.n_nodes, dtype=bool)
    only[nodes] = True
    only &= ~referenced(mesh)
    return prune(mesh, ~only) if only.any() else mesh


def _rbe2(c: Card, gid, sorter) -> RigidLink:
    gn = c.int(1, "GN")
    cm = c.raw(2)
    if not cm or not cm.isdigit() or set(cm) - set("123456"):
        raise c.error(f"component field CM = '{cm}' must be digits 1-6, e.g. 123456")
    slaves, k = [], 3
    while k < len(c.fields):
        s = c.raw(k)
        if s.upper() == "THRU" and slaves:
            hi = c.int(k + 1, "GMi THRU")
            slaves.extend(range(slaves[-1] + 1, hi + 1))
            k += 2
            continue
        if s and not c.is_int(k):
            break  # ALPHA (thermal expansion) ends the node list
        if s:
            slaves.append(int(s))
        k += 1
    if not slaves:
        raise c.error("has no dependent grid points GMi")
    idx = _index_of(gid, sorter, [gn] + slaves, [c] * (len(slaves) + 1), "a grid point")
    return RigidLink(int(idx[0]), idx[1:], "".join(sorted(set(cm))), c.int(0, "EID"))


def _section(card: Card, cell_type: str, mats: dict, other_mats: dict, user: Card) -> dict:
    """Section properties of property card ``card`` used by element card ``user``."""
    kind = {"PSHELL": ("triangle", "quad"), "PSOLID": ("tetra", "tetra10", "hexahedron"),
            "PBAR": ("line",), "PBEAM": ("line",), "PBARL": ("line",), "PBEAML": ("line",),
            "PCOMP": ("triangle", "quad"), "PCOMPG": ("triangle", "quad")}[card.name]
    if cell_type not in kind:
        raise user.error(f"refers to {card.name} {card.label()} (line {card.line}), which is "
                         f"not a property of {user.name} elements")
    if card.name in SKIPPED_PROPERTIES:
        warnings.warn(MeshWarning(f"{card.file} line {card.line}: {card.name} {card.label()} is "
                                  "not read; pass the section/thickness to assemble() for cell "
                                  f"set 'PID{card.label()}'"), stacklevel=4)
        return {}
    out = {}
    mid = card.int(1, "MID", None)
    if card.name == "PSHELL":
        t = card.real(2, "T", None)
        if t is not None:
            out["thickness"] = t
        if mid is None:
            mid = card.int(3, "MID2", None)
        ratio = card.real(4, "12I/T**3", 1.0)
        if abs(ratio - 1.0) > 1e-9:
            warnings.warn(MeshWarning(f"{card.file} line {card.line}: PSHELL {card.label()} "
                                      f"bending ratio 12I/T^3 = {ratio} is ignored (1.0 used)"),
                          stacklevel=4)
    elif card.name in ("PBAR", "PBEAM"):
        A, I1, I2 = (card.real(k, n, 0.0) for k, n in ((2, "A"), (3, "I1"), (4, "I2")))
        J = card.real(5 if card.name == "PBAR" else 6, "J", 0.0)
        out.update(A=A, Iz=I1, Iy=I2, J=J)
    if mid is not None:
        if mid in mats:
            out.update(_material(mats[mid]))
        elif mid in other_mats:
            raise card.error(f"material {mid} is {other_mats[mid].name}; only isotropic MAT1 "
                             "is supported")
        else:
            raise card.error(f"refers to material MID {mid}, which has no MAT1 card")
    return out
