"""Nastran bulk data (``.bdf``, ``.nas``, ``.dat``) reader: a small dedicated parser.

Cards read
----------
Grids and systems: ``GRID`` (``CP`` and ``CD`` in any ``CORD1R/1C/1S/2R/2C/2S``, ``PS``).
Elements: ``CTETRA`` (4/10), ``CHEXA`` (8), ``CPENTA`` (6), ``CPYRAM`` (5), ``CQUAD4``,
``CTRIA3`` (``ZOFFS`` and ``THETA``/``MCID`` applied; corner thicknesses ``T1..`` with
``TFLAG`` - blank Ti = the PSHELL T, TFLAG 1 = factors on it - become one thickness per
element, the mean of its corners: cell sets ``PID<n>_T<k>`` whose sections override the
PID's, one warning when corners differ within an element), ``CQUAD8``/``CTRIA6``
(converted: each split into four CQUAD4/CTRIA3 through its mid-side grids - a CQUAD8 gains
a centre grid - conforming with split neighbours; their ``ZOFFS`` applies to each part,
``MCID`` is projected onto each part, ``THETA`` turns the parent's element x axis, which
each part takes as its material axis; second-order CHEXA/CPENTA/CPYRAM become linear on
their corner grids, with a warning), ``CBAR``/``CBEAM`` (orientation ``X`` or ``G0`` in
the ``CD`` system of GA, end offsets ``WA``/``WB`` applied), ``CROD``/``CONROD``,
``CELAS1``/``CELAS2``, ``CBUSH``, ``CONM1``, ``CONM2``, ``RBE2``, ``RBE3``, ``RBAR``.
Properties and materials: see :mod:`flexpipe.mesh._nastran_props` (``PSHELL``,
``PSOLID``, ``PBAR``, ``PBEAM``, ``PBARL``, ``PBEAML``, ``PROD``, ``PELAS``, ``PBUSH``,
``PCOMP``/``PCOMPG`` with ``MAT8``/``MAT1`` plies, ``MAT1``); ``SET1`` lists of grids
become node sets ``"SET<sid>"``.  Constraints and
set-up: see :mod:`flexpipe.mesh._nastran_extra` (``SPC``,
``SPC1``, ``SPCADD``, ``EIGRL``, case control ``SPC``/``METHOD``, ``PARAM WTMASS``,
``PARAM COUPMASS``).

Strictness and tolerance (as Nastran)
-------------------------------------
* A deck cut short is an error naming the file, the line and the card (see
  :mod:`flexpipe.mesh._bulk`: a continuation without its card, a continuation marker
  without its continuation, a last line that stops inside a field), and so is a deck
  with no element card.
* An element whose PID has no property card is read with a warning naming the PID, the
  card kinds expected and the property ids defined (``Mesh.info["missing_properties"]``);
  building the model without a material/thickness for it is the error that names them.
* The MAT1/MAT8 cards the model uses go to ``Mesh.info["materials"]`` for the E / RHO
  unit-consistency check of :func:`flexpipe.mesh.units.check_wave_speeds`.
* GRIDs no element uses are accepted with a warning and left out (their DOF would be
  removed by AUTOSPC).
* Two cards of one kind with the same id (GRID, element, property, material, coordinate
  system, EIGRL) are an error naming both lines.
* Cards this reader does not use are listed in **one** warning at the end (count and
  first line per name) and recorded in ``Mesh.info["dropped"]``; a name that looks like a
  misspelt element/property/material card (``CQAUD4``) is an error; elements this reader
  cannot model (``CQUADR``, ``CGAP``, ``MPC``, ...) raise
  :class:`~flexpipe.errors.MeshError`, because dropping them would change the structure.
* A vectorized fast path parses plain small-field GRID/CQUAD4/CTRIA3 lines (most of a
  body deck); anything it cannot convert exactly is parsed card by card.

Every element gets the cell set ``"PID<n>"`` (``"CONROD<eid>"`` for CONRODs) and
``Mesh.sections`` holds the resolved section and material, in the units of the file (see
:mod:`flexpipe.mesh.units`).
"""

from __future__ import annotations

import warnings
from collections import Counter, defaultdict
from pathlib import Path

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.fem import spring
from flexpipe.mesh import _nastran_extra as extra
from flexpipe.mesh import _nastran_fast as _fast
from flexpipe.mesh import _nastran_props as nprops
from flexpipe.mesh._bulk import FastLines, case_control, read_cards
from flexpipe.mesh._nastran_coords import Systems
from flexpipe.mesh._nastran_deck import (  # noqa: F401 - the card lists are public here
    NOT_STRUCTURAL,
    SUPPORTED,
    UNSUPPORTED_ELEMENTS,
    UNSUPPORTED_PROPERTIES,
    Deck,
    Looked,
    check_unique,
    material_records,
    missing_property,
    require_elements,
)
from flexpipe.mesh._nastran_elements import (
    ELEMENTS,
    cell_arrays,
    conm1,
    conm2,
    element,
    element_thickness,
    line_data,
    rbe2,
    second_order_refs,
    split_second_order,
)
from flexpipe.mesh._nastran_elements import index_of as _index_of
from flexpipe.mesh.mesh import CellBlock, Mesh, PointMass
from flexpipe.mesh.validate import MeshWarning, prune, referenced


def read_nastran(path) -> Mesh:
    """Read a Nastran bulk-data deck into a :class:`Mesh` (units of the file)."""
    path = Path(path)
    deck, fast, control = Deck(), FastLines(), []
    cards = read_cards(path, fast=fast, control=control)   # + case-control lines
    fgrid = _fast.grids(fast.lines["GRID"], [w[2] for w in fast.where["GRID"]])
    fshell = {}
    for name, ct, k in (("CQUAD4", "quad", 4), ("CTRIA3", "triangle", 3)):
        fshell[ct] = _fast.shells(fast.lines[name], [w[2] for w in fast.where[name]], k)
    for name, ok in (("GRID", fgrid is not None), ("CQUAD4", fshell["quad"] is not None),
                     ("CTRIA3", fshell["triangle"] is not None)):
        if not ok and fast.lines[name]:   # not exactly parsable: card by card, with messages
            cards += [fast.card(name, i) for i in range(len(fast.lines[name]))]
            fast.lines[name], fast.where[name] = [], []
    if fgrid is None:
        fgrid = _fast.grids([], [])
    cards.sort(key=lambda c: c.seq)
    for c in cards:
        deck.add(c)
    n_fast_el = {ct: 0 if a is None else len(a["eid"]) for ct, a in fshell.items()}
    if not deck.grids and not len(fgrid["gid"]):
        raise MeshError("no GRID cards found: not a Nastran bulk-data deck?", file=str(path))
    case = case_control(control, path)
    wtmass = 1.0
    if "WTMASS" in deck.params:
        wtmass = deck.params["WTMASS"].real(1, "WTMASS")
        if not (np.isfinite(wtmass) and wtmass > 0):
            raise deck.params["WTMASS"].error(f"WTMASS = {wtmass:g}; valid: > 0")
    read = Counter(c.name for c in cards if c.name not in deck.dropped)
    for name in ("GRID", "CQUAD4", "CTRIA3"):
        read[name] += len(fast.lines[name])
    info = {"read": {k: v for k, v in read.items() if v}, "converted": {},
            "dropped": dict(deck.dropped), "missing_properties": {}}
    mats = Looked(deck.mats)                 # records the materials the model uses

    # ---- grids: ids, positions in basic (CP), displacement systems (CD)
    slow = deck.grids
    ns = len(slow)
    gid = np.concatenate([np.array([c.int(0, "ID") for c in slow], dtype=np.int64),
                          fgrid["gid"]])
    cp = np.concatenate([np.array([c.int(1, "CP", 0) if c.raw(1) else 0 for c in slow],
                                  dtype=np.int64), fgrid["cp"]])
    X = np.concatenate([np.array([[c.real(2 + k, f"X{k + 1}", 0.0) for k in range(3)]
                                  for c in slow]).reshape(-1, 3), fgrid["X"]])
    cd = np.concatenate([np.array([c.int(5, "CD", 0) if c.raw(5) else 0 for c in slow],
                                  dtype=np.int64), fgrid["cd"]])
    has_ps = np.concatenate([np.array([bool(c.raw(6)) for c in slow], dtype=bool),
                             fgrid["has_ps"]])
    order = np.argsort(np.concatenate([np.array([c.seq for c in slow], dtype=np.int64),
                                       fgrid["seq"]]), kind="stable")
    gid, cp, X, cd, has_ps = gid[order], cp[order], X[order], cd[order], has_ps[order]

    def grid_card(k):
        i = int(order[k])
        return slow[i] if i < ns else fast.card("GRID", i - ns)

    grids = _fast.Lazy(grid_card, len(gid))
    check_unique(gid, grids, "GRID")
    sorter = np.argsort(gid, kind="stable")
    deck_gids = gid[sorter]                  # sorted GRID ids (for SPC1 THRU ranges)
    done = cp == 0

    def grid_xyz(g, user, stack):
        i = int(_index_of(gid, sorter, [g], [user], "G")[0])
        if not done[i]:
            X[i] = systems.to_basic(int(cp[i]), X[i], grids[i], stack)[0]
            done[i] = True
        return X[i]

    systems = Systems(deck.coords, grid_xyz)
    for sys_id in np.unique(cp[~done]):
        rows = np.flatnonzero((cp == sys_id) & ~done)
        X[rows] = systems.to_basic(int(sys_id), X[rows], grids[rows[0]])
        done[rows] = True
    frame_cache: dict = {}
    require_elements(deck, fast, cards, path)   # after the GRIDs' own field errors

    def cd_frames(nodes, user):
        nodes = np.asarray(nodes).ravel()
        out = np.broadcast_to(np.eye(3), (len(nodes), 3, 3)).copy()
        if not cd[nodes].any():
            return out
        for k, nd in enumerate(nodes):
            if cd[nd]:
                if nd not in frame_cache:
                    frame_cache[nd] = systems.frames(int(cd[nd]), X[nd:nd + 1], user)[0]
                out[k] = frame_cache[nd]
        return out

    def index(ids, card):
        return _index_of(gid, sorter, ids, [card] * len(ids), "a grid point")

    # ---- element ids unique across every element-like card (fast shells included)
    el_cards = [c for cs in deck.elements.values() for c in cs]
    fast_ids = [a["eid"] for a in fshell.values() if a is not None]
    n_slow = len(el_cards)
    offsets = np.cumsum([n_slow] + [n_fast_el["quad"], n_fast_el["triangle"]])

    def el_card(i):
        if i < n_slow:
            return el_cards[i]
        name, base = ("CQUAD4", offsets[0]) if i < offsets[1] else ("CTRIA3", offsets[1])
        return fast.card(name, i - base)

    check_unique(np.concatenate([np.array([c.int(0, "EID") for c in el_cards],
                                           dtype=np.int64)] + fast_ids),
                  _fast.Lazy(el_card, int(offsets[-1])), "element")

    # ---- cells
    els: dict = defaultdict(list)
    second: dict = {}
    for c in cards:               # file order: blocks appear in the order of the deck
        if c.name in ELEMENTS:
            element(c, els, second)
    if second:
        listing = ", ".join(f"{k} x{v}" for k, v in second.items())
        warnings.warn(MeshWarning(f"{path}: second-order solids converted to their linear "
                                  f"forms on the corner grids (mid-side grids dropped; "
                                  f"curved edges become straight, bending is stiffer): "
                                  f"{listing}"), stacklevel=3)
    for cell_type in list(els):   # grid ids -> node indices
        items = els[cell_type]
        conn = _index_of(gid, sorter, [it[3] for it in items], [it[0] for it in items],
                         "a node")
        els[cell_type] = [(it[0], it[1], it[2], list(row))
                          for it, row in zip(items, conn, strict=True)]
    so_ref = second_order_refs(els, X)   # CQUAD8/CTRIA6 THETA -> material axis
    new_pts, info["converted"] = split_second_order(els, X, int(gid.max()))
    for k, v in second.items():
        info["converted"][k] = f"{v} second-order -> linear (corner grids)"
    if new_pts:
        gid = np.concatenate([gid, [p[0] for p in new_pts]])
        X = np.vstack([X, [p[1] for p in new_pts]])
        cd = np.concatenate([cd, np.zeros(len(new_pts), dtype=np.int64)])
        sorter = np.argsort(gid, kind="stable")
    blocks, cell_sets, sections = [], {}, {}
    g0_nodes: list = []
    for ct in ("quad", "triangle"):
        if fshell[ct] is not None and ct not in els:
            els[ct] = []

    def first_seq(ct):             # blocks in the order their types first appear
        s0 = [els[ct][0][0].seq] if els[ct] else []
        fa = fshell.get(ct)
        return min(s0 + ([int(fa["seq"][0])] if fa is not None else []))

    corner_sets: dict = {}            # (PID, thickness) -> cell set of corner-T shells
    corner_use = [0, 0, None]         # elements with corner T, with unequal corners, first
    for cell_type in sorted(els, key=first_seq):
        items = els[cell_type]
        cols = cell_arrays(cell_type, items, fshell.get(cell_type), fast, gid, sorter)
        eid, pid, conn, zoff, theta, user_of, corners = cols
        data = {}
        if cell_type == "line":
            ori, w, g0, rel = line_data(items, X, conn, cd_frames, gid, sorter)
            data["orientation"] = ori
            if rel.any():
                data["release"] = rel
            g0_nodes += g0
            if np.any(w):
                data["offset_a"], data["offset_b"] = w[:, :3], w[:, 3:]
        else:
            if zoff is not None and np.any(zoff):
                data["zoffset"] = zoff
            if theta is not None and any(theta):
                data["mat_theta"], data["mat_ref"] = nprops.shell_orientation(
                    theta, conn, X, systems, user_of)
                if so_ref:     # split CQUAD8/CTRIA6: the parent's THETA direction
                    for j in np.flatnonzero(np.array([bool(t) for t in theta])):
                        c = user_of(int(j))
                        if c.seq in so_ref:
                            data["mat_theta"][j] = 0.0
                            data["mat_ref"][j] = so_ref[c.seq]
        bi = len(blocks)
        blocks.append(CellBlock(cell_type, conn, eid, np.abs(pid), data))
        for p in np.unique(pid):
            name = f"PID{p}" if p > 0 else f"CONROD{-p}"
            members = np.flatnonzero(pid == p)
            cell_sets.setdefault(name, {})[bi] = members
            user = user_of(int(members[0]))
            if p < 0:
                sections[name] = nprops.conrod_section(user, mats, wtmass)
                continue
            card = deck.props.get(int(p))
            if card is None:   # a warning here; an error when the model is built
                info["missing_properties"].setdefault(str(p), missing_property(
                    int(p), user, cell_type, deck.props))
                continue
            if cell_type not in nprops.KIND.get(card.name, ()):
                raise user.error(f"refers to {card.name} {card.label()} (line {card.line}), "
                                 f"which is not a property of {user.name} elements")
            if card.name in UNSUPPORTED_PROPERTIES:
                raise card.error(f"{card.name} is not supported; give an equivalent PSHELL "
                                 "or pass thickness and material to assemble() for this PID")
            if name not in sections:
                sections[name] = (nprops.composite(card, mats, wtmass)
                                  if card.name in ("PCOMP", "PCOMPG")
                                  else nprops.section(card, mats, wtmass))
            if corners is not None:
                _corner_thickness(int(p), card, sections[name], bi, members, corners,
                                  user_of, wtmass, cell_sets, corner_sets, corner_use, info)

    for name, sec in corner_sets.values():
        sections[name] = sec       # after the PID sections: these override them
    if corner_use[0]:
        sets = [v[0] for v in corner_sets.values()]
        info["converted"]["corner thicknesses"] = (
            f"{corner_use[0]} shell element(s) with T1.. -> the mean per element "
            + (f"(cell sets {', '.join(sets[:4])}{', ...' if len(sets) > 4 else ''})" if sets
               else "(equal to the PSHELL T)"))
    if corner_use[1]:
        u = corner_use[2]
        warnings.warn(MeshWarning(
            f"{path}: {corner_use[1]} shell element(s) have unequal corner thicknesses "
            f"T1.. (e.g. {u.name} {u.label()}, {Path(u.file).name} line {u.line}); "
            "flexpipe's shells have one thickness per element, so each takes the mean of its "
            "corners (Nastran varies it over the element: the mass is the same for triangles "
            "and parallelograms, the bending stiffness of a tapered element differs slightly)"),
            stacklevel=3)

    # ---- springs
    pelas = {}
    for c in deck.props.values():
        if c.name == "PELAS":
            pelas.update(nprops.pelas(c))
    springs2, springs1 = extra.celas(deck.elements.get("CELAS1", [])
                                     + deck.elements.get("CELAS2", []), pelas, index, cd_frames)
    nan = np.full(6, np.nan)
    for sp_ in (springs2, springs1):   # + CBUSH parameters (k6, b6, frame, s) for writing
        n_c = len(sp_[0])
        sp_ += ([nan] * n_c, [nan] * n_c, [np.eye(3)] * n_c, [np.nan] * n_c)
    for c in deck.elements.get("CBUSH", []):
        pidb = c.int(1, "PID", c.int(0, "EID"))
        pc = deck.props.get(pidb)
        if pc is None or pc.name != "PBUSH":
            raise c.error(f"refers to PBUSH {pidb}, which is not defined")
        pb = nprops.pbush(pc)
        if c.raw(9) not in ("", "-1") or any(c.raw(10 + j) for j in range(3)):
            raise c.error("spring offsets OCID/S1-S3 are not supported; leave them blank")
        ga, gb = c.int(2, "GA"), c.int(3, "GB", 0)
        idx = index([ga] + ([gb] if gb else []), c)
        XA = X[idx[0]]
        XB = X[idx[1]] if gb else XA
        orient = None
        if c.is_int(4) and not c.raw(5) and not c.raw(6):
            orient = X[index([c.int(4, "GO")], c)[0]] - XA
        elif any(c.raw(4 + j) for j in range(3)):
            orient = cd_frames(idx[:1], c)[0] @ [c.real(4 + j, "X", 0.0) for j in range(3)]
        R = extra.bush_frame(c, XA, XB, systems, orient)
        s = c.real(8, "S", 0.5)
        if gb:
            Kb = spring.bush(XA[None], XB[None], R[None], pb["K"][None], s)[0]
            Bb = spring.bush(XA[None], XB[None], R[None], pb["B"][None], s)[0]
            target = springs2
        else:
            Kb = spring.grounded_bush(R[None], pb["K"][None])[0]
            Bb = spring.grounded_bush(R[None], pb["B"][None])[0]
            target = springs1
        for lst, v in zip(target, (idx, Kb, c.int(0, "EID"), Bb, pb["K"], pb["B"], R, s),
                          strict=True):
            lst.append(v)
    for cell_type, (cells, Ks, ids, Bs, k6, b6, frames, ss) in (("spring", springs2),
                                                                 ("spring1", springs1)):
        if cells:
            data = {"K": np.array(Ks), "k6": np.array(k6), "b6": np.array(b6),
                    "frame": np.array(frames), "s": np.array(ss, dtype=float)}
            if np.any(Bs):
                data["B"] = np.array(Bs)
            blocks.append(CellBlock(cell_type, np.array(cells), np.array(ids), None, data))
    # ---- masses, rigid elements
    masses = [conm2(c, index, X, systems) for c in deck.elements.get("CONM2", [])]
    masses += [conm1(c, index, X, systems) for c in deck.elements.get("CONM1", [])]
    if wtmass != 1.0:
        masses = [PointMass(m.node, m.mass * wtmass, m.inertia * wtmass, m.offset, m.id,
                            None if m.matrix is None else m.matrix * wtmass) for m in masses]
    links = [rbe2(c, gid, sorter) for c in deck.elements.get("RBE2", [])]
    links += [extra.rbar(c, index) for c in deck.elements.get("RBAR", [])]
    for lk, c in zip(links, deck.elements.get("RBE2", []) + deck.elements.get("RBAR", []),
                     strict=True):
        if not extra.invariant(lk.dofs) and cd[np.asarray(lk.slaves)].any():
            raise c.error(f"components {lk.dofs} at a grid with a CD system: only 123, 456 or "
                          "123456 are supported there")
    interp = [extra.rbe3(c, index, lambda nd: bool(cd[nd]))
              for c in deck.elements.get("RBE3", [])]

    # ---- constraints and solution set-up
    def ids_in(lo, hi):
        return deck_gids[np.searchsorted(deck_gids, lo):np.searchsorted(deck_gids, hi, "right")]

    dof_sets, spc_dirs = extra.spc_sets(deck.spc["SPC"], deck.spc["SPC1"], deck.spc["SPCADD"],
                                        index, lambda nd: bool(cd[nd]), cd_frames, ids_in)
    ps = [(int(k), ch) for k in np.flatnonzero(has_ps) for ch in extra.components(
        grids[k], 6, "PS", allow_zero=True)]
    if ps:
        dof_sets["GRID_PS"] = np.array([(k, int(ch) - 1) for k, ch in ps])
    solution = extra.solution(case, deck, dof_sets, path)
    info["materials"], info["wtmass"] = material_records(mats), wtmass
    if solution.get("spc") in spc_dirs:
        solution["spc_directions"] = spc_dirs[solution["spc"]]

    node_sets = {}
    gid_set = set(gid.tolist()) if deck.sets else set()
    for sid, c in deck.sets.items():        # SET1 of grid ids -> node set "SET<sid>"
        ids, _ = extra.grid_list(c, 1)
        if ids and all(g in gid_set for g in ids):
            node_sets[f"SET{sid}"] = index(ids, c)
            name = extra.set1_name(c)
            if name:  # the comment line "$ SET name" right before the card names the set
                node_sets[name] = node_sets[f"SET{sid}"]
        else:
            info["dropped"][f"SET{sid}"] = "lists ids that are not all GRIDs"
    mesh = Mesh(points=X, blocks=tuple(blocks), node_ids=gid, cell_sets=cell_sets,
                node_sets=node_sets,
                point_masses=tuple(masses), rigid_links=tuple(links), sections=sections,
                source=str(path), interpolations=tuple(interp), dof_sets=dof_sets,
                solution=solution, info=info)
    mesh = drop_orientation_nodes(mesh, np.array(g0_nodes, dtype=np.int64))
    used = referenced(mesh)
    if not used.all():
        ids = mesh.node_ids[~used]
        warnings.warn(MeshWarning(
            f"{path}: {len(ids)} GRID(s) belong to no element, e.g. {ids[:10].tolist()}; "
            "left out (Nastran removes their DOF by AUTOSPC)"), stacklevel=3)
        info["dropped"][f"unreferenced GRID ({len(ids)})"] = ids[:20].tolist()
        mesh = prune(mesh, used)
    if deck.dropped:
        listing = "; ".join(f"{n} x{k} (first at line {deck.first[n].line})"
                            for n, k in sorted(deck.dropped.items()))
        warnings.warn(MeshWarning(f"{path}: cards not used for M and K (loads, output, "
                                  f"other solutions or unknown): {listing}"), stacklevel=3)
    return mesh


def _corner_thickness(p, card, sec, bi, members, corners, user_of, wtmass, cell_sets,
                      corner_sets, corner_use, info) -> None:
    """Shells of PID ``p`` (rows ``members`` of block ``bi``) with corner thicknesses T1..:
    cell sets ``PID<p>_T<k>`` of one mean thickness each (sections after the PID's, which
    they override); a note for the missing-thickness error when the PSHELL T is blank and
    elements give none."""
    given = [j for j in members if corners[j] is not None]
    if card.name != "PSHELL":
        if given:
            u = user_of(int(given[0]))
            warnings.warn(MeshWarning(
                f"{u.file} line {u.line}: {len(given)} element(s) of {card.name} "
                f"{card.label()} give corner thicknesses T1..; ignored: the laminate's plies "
                "set the thickness"), stacklevel=4)
        return
    T = card.real(2, "T", None)
    if given:
        t, varying = element_thickness(members, corners, user_of, T, card)
        corner_use[0] += len(given)
        if varying and corner_use[2] is None:
            corner_use[2] = user_of(int(next(j for j in given if _unequal(corners[j], T))))
        corner_use[1] += varying
        nsm = card.real(7, "NSM", 0.0) * wtmass
        differs = np.isfinite(t) & ((t != T) if T is not None else True)
        for u in np.unique(t[differs]):
            key = (p, float(u))
            if key not in corner_sets:
                new = dict(sec, thickness=float(u))
                if "rho" in sec:
                    new["rho"] = sec["rho"] - (nsm / T if nsm and T else 0.0) + nsm / u
                k = sum(1 for q, _ in corner_sets if q == p) + 1
                corner_sets[key] = (f"PID{p}_T{k}", new)
            name = corner_sets[key][0]
            cell_sets.setdefault(name, {})[bi] = np.asarray(members)[t == u]
    else:
        t = np.full(len(members), np.nan if T is None else T)
    bare = np.flatnonzero(~np.isfinite(t))
    if len(bare) and str(p) not in info["missing_properties"]:
        u = user_of(int(members[bare[0]]))
        n_t = 4 if u.name in ("CQUAD4", "CQUAD8") else 3
        info["missing_properties"][str(p)] = {
            "text": f"PSHELL {p} ({Path(card.file).name} line {card.line}) has T blank and "
                    f"{len(bare)} of its element(s) give no corner thicknesses T1-T{n_t} "
                    f"either (e.g. {u.name} {u.label()}, {Path(u.file).name} line "
                    f"{u.line}; Nastran needs one of them: PSHELL T, or TFLAG and T1..T{n_t} "
                    f"on the {u.name} continuation line)",
            "element": int(u.int(0, "EID")), "line": u.line}


def _unequal(cj, T) -> bool:
    tflag, vals = cj
    v = [(T if tflag == 0 else 1.0) if x is None else x for x in vals]
    return max(v) - min(v) > 1e-12 * max(v)


def drop_orientation_nodes(mesh: Mesh, nodes) -> Mesh:
    """Remove nodes that only orient beams (CBAR G0, Abaqus n1 node): they carry no DOF."""
    nodes = np.asarray(nodes, dtype=np.int64)
    if nodes.size == 0:
        return mesh
    only = np.zeros(mesh.n_nodes, dtype=bool)
    only[nodes] = True
    only &= ~referenced(mesh)
    return prune(mesh, ~only) if only.any() else mesh

