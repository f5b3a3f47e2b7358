"""Nastran constraints, rigid elements, springs and solution set-up.

* ``SPC``, ``SPC1`` (``THRU``), ``SPCADD`` -> DOF sets ``"SPC<sid>"`` of
  (node index, component); ``GRID`` field ``PS`` -> set ``"GRID_PS"`` (always applied).
  Enforced values ``D`` are irrelevant to normal modes and not kept.  As the QRG says for
  SPC1 (remark 3), grid ids in a ``G1 THRU G2`` range need not exist and those that do
  not are skipped (one warning counts them); a range with no GRID at all, and an
  explicitly listed grid that does not exist, are errors naming the card and line.
* Case control ``SPC = n`` and ``METHOD = m`` (also ``METHOD(STRUCTURE) = m``) with
  ``EIGRL m`` (``V1, V2, ND``) -> ``Mesh.solution`` (``spc``, ``f_min``, ``f_max``,
  ``n_modes``), which ``flexpipe modes`` applies; ``PARAM, COUPMASS`` -> ``lumped_mass``,
  the executive ``SOL`` -> ``sol`` (``flexpipe modes`` takes Nastran's default lumped
  mass for a deck with a SOL statement and no COUPMASS, see
  :func:`flexpipe.cli.modes.mass_choice`).
* ``RBE3`` -> :class:`~flexpipe.mesh.Interpolation` (exact weighted-average constraint,
  :mod:`flexpipe.fem.interpolation`).  ``REFC`` are the dependent components of the
  reference grid; ``UM`` (moving the dependency to other grids) is not supported and
  raises an error.
* ``RBAR`` in its usual form (``CNA = 123456``, ``CNB`` blank) -> an RBE2 link
  ``GA -> GB`` in components ``CMB``.
* ``CELAS1``/``CELAS2`` (scalar springs between grid components, in the grids' ``CD``
  systems) and ``CBUSH``/``PBUSH`` (stiffness and viscous damping ``B``) -> ``spring`` /
  ``spring1`` cells whose matrices :mod:`flexpipe.fem.spring` computes.

Components of grids with a ``CD`` system: scalar springs and SPCs use the ``CD``
directions (an SPC on, say, the radial component of a cylindrical system becomes a
directional constraint, ``Mesh.solution["spc_directions"]``, which ``flexpipe modes``
applies exactly); RBE2/RBAR and RBE3 components must be rotation-invariant there (all of
1-3 or none, all of 4-6 or none), otherwise an error says so.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.fem import spring
from flexpipe.mesh._bulk import Card
from flexpipe.mesh.mesh import Interpolation, RigidLink


def components(card: Card, i: int, name: str, *, allow_zero=False) -> str:
    """Component digits of field ``i`` (e.g. '123'), validated."""
    s = card.raw(i)
    if allow_zero and s in ("", "0"):
        return ""
    if not s or not s.isdigit() or set(s) - set("123456"):
        raise card.error(f"component field {name} = '{s}' must be digits 1-6, e.g. 123456")
    return "".join(sorted(set(s)))


def invariant(comps: str) -> bool:
    """True when a component set means the same in every rectangular frame."""
    t = set(comps) & set("123")
    r = set(comps) & set("456")
    return len(t) in (0, 3) and len(r) in (0, 3)


def grid_list(card: Card, start: int, stop_words=()) -> tuple[list[int], int]:
    """Grid ids from field ``start`` (with ``THRU``) until a non-integer; and the end."""
    out, k = [], start
    while k < len(card.fields):
        s = card.raw(k)
        if s.upper() == "THRU" and out:
            hi = card.int(k + 1, "THRU")
            if hi < out[-1] or hi - out[-1] > 10_000_000:
                raise card.error(f"THRU range {out[-1]} THRU {hi} is empty or huge")
            out.extend(range(out[-1] + 1, hi + 1))
            k += 2
            continue
        if s.upper() in stop_words or (s and not card.is_int(k)):
            break
        if s:
            out.append(int(s))
        k += 1
    return out, k


def grid_ranges(card: Card, start: int) -> tuple[list[int], list[tuple[int, int]]]:
    """Grid ids listed from field ``start`` and the ``G1 THRU G2`` ranges (not expanded):
    ``(explicit ids, [(G1, G2), ...])``.  Ends at the first non-integer field."""
    ids, ranges, k = [], [], start
    while k < len(card.fields):
        s = card.raw(k)
        if s.upper() == "THRU" and ids:
            lo, hi = ids.pop(), card.int(k + 1, "THRU")
            if hi < lo:
                raise card.error(f"THRU range {lo} THRU {hi} is empty; valid: G2 > G1")
            ranges.append((lo, hi))
            k += 2
            continue
        if s and not card.is_int(k):
            break
        if s:
            ids.append(int(s))
        k += 1
    return ids, ranges


def spc1_grids(card: Card, ids_in) -> tuple[list[int], int]:
    """Grid ids of an SPC1 card and the number of range ids skipped.

    ``ids_in(lo, hi)`` -> the GRID ids of the deck in ``lo..hi``.  Ids of a ``THRU``
    range that are not GRIDs are skipped (QRG, SPC1 remark 3); a range holding no GRID is
    an error.  Explicitly listed ids are kept (a missing one is an error later).
    """
    ids, ranges = grid_ranges(card, 2)
    skipped = 0
    for lo, hi in ranges:
        have = ids_in(lo, hi)
        if len(have) == 0:
            raise card.error(f"THRU range {lo} THRU {hi} contains no GRID: none of its "
                             f"{hi - lo + 1} ids is a grid point of the deck")
        skipped += hi - lo + 1 - len(have)
        ids.extend(int(g) for g in have)
    return ids, skipped


def spc_sets(spc: list[Card], spc1: list[Card], spcadd: list[Card], index, cd_of, frames,
             ids_in=None):
    """DOF sets ``{"SPC<sid>": (k, 2)}`` and directional constraints.

    ``index(ids, card)`` -> node indices; ``cd_of(node)`` -> CD id; ``frames(nodes,
    card)`` -> displacement frames; ``ids_in(lo, hi)`` -> the GRID ids in ``lo..hi`` (for
    SPC1 ``THRU`` ranges, whose missing ids are skipped; None: every id must exist).
    Components of a grid with a CD system that are not
    rotation-invariant become directions ``{"SPC<sid>": (m, 5)}`` with rows (node, group
    0 = translation / 1 = rotation, direction x, y, z in basic).
    """
    raw: dict[int, list] = {}
    for c in spc:
        sid = c.int(0, "SID")
        for base in (1, 4):
            if not c.raw(base):
                continue
            g = c.int(base, "G")
            comps = components(c, base + 1, "C", allow_zero=True)
            raw.setdefault(sid, []).append((c, [g], comps))
    skipped = []
    for c in spc1:
        sid = c.int(0, "SID")
        comps = components(c, 1, "C")
        if ids_in is None:
            grids, _ = grid_list(c, 2)
        else:
            grids, n_skip = spc1_grids(c, ids_in)
            if n_skip:
                skipped.append((c, n_skip))
        if not grids:
            raise c.error("lists no grid points")
        raw.setdefault(sid, []).append((c, grids, comps))
    if skipped:
        import warnings

        from flexpipe.mesh.validate import MeshWarning
        first = ", ".join(f"SPC1 {c.label()} ({Path(c.file).name} line {c.line}): {n}"
                          for c, n in skipped[:3])
        warnings.warn(MeshWarning(
            f"{skipped[0][0].file}: SPC1 THRU ranges hold {sum(n for _, n in skipped)} id(s) "
            f"that are not GRIDs; skipped, as Nastran does ({first}"
            + (f", ... {len(skipped)} cards" if len(skipped) > 3 else "") + ")"),
            stacklevel=4)
    sets, dirs = {}, {}
    for sid, items in raw.items():
        rows, drows = [], []
        for c, grids, comps in items:
            if not comps:
                continue
            idx = index(grids, c)
            plain = np.ones(len(idx), dtype=bool)
            for k, nd in enumerate(idx):
                if cd_of(nd) and not invariant(comps):
                    plain[k] = False
                    F = frames([nd], c)[0]
                    for g, part in ((0, "123"), (1, "456")):
                        sub = [int(ch) - 1 for ch in comps if ch in part]
                        if len(sub) == 3:
                            rows.append(np.array([[nd, 3 * g + j] for j in range(3)]))
                        else:
                            drows += [[nd, g, *F[:, j % 3]] for j in sub]
            cc = np.array([int(ch) - 1 for ch in comps])
            idx = idx[plain]
            rows.append(np.column_stack([np.repeat(idx, len(cc)), np.tile(cc, len(idx))]))
        sets[sid] = np.unique(np.vstack(rows), axis=0) if rows else np.zeros((0, 2), np.int64)
        if drows:
            dirs[sid] = np.array(drows, dtype=float)
    for c in spcadd:
        sid = c.int(0, "SID")
        members, _ = grid_list(c, 1)
        missing = [m for m in members if m not in sets]
        if missing:
            raise c.error(f"refers to SPC set(s) {missing}, which no SPC/SPC1 card defines")
        sets[sid] = np.unique(np.vstack([sets[m] for m in members] + [sets.get(sid, np.zeros(
            (0, 2), np.int64))]), axis=0)
        d = [dirs[m] for m in members + [sid] if m in dirs]
        if d:
            dirs[sid] = np.vstack(d)
    return ({f"SPC{sid}": v for sid, v in sets.items()},
            {f"SPC{sid}": v for sid, v in dirs.items()})


def eigrl(card: Card) -> dict:
    """``f_min``, ``f_max``, ``n_modes`` of an EIGRL card (blank = open)."""
    v1, v2 = card.real(1, "V1", None), card.real(2, "V2", None)
    nd = card.int(3, "ND", None)
    if nd is not None and nd < 1:
        raise card.error(f"ND = {nd}; valid: a positive number of roots or blank")
    if v1 is not None and v2 is not None and not v2 > v1:
        raise card.error(f"V2 = {v2:g} must exceed V1 = {v1:g}")
    if v2 is None and nd is None:
        raise card.error("gives neither V2 nor ND: no end to the eigenvalue search")
    return {"f_min": v1, "f_max": v2, "n_modes": nd}


def rbe3(c: Card, index, cd_of) -> Interpolation:
    """An RBE3 card as an :class:`Interpolation`."""
    ref = c.int(2, "REFGRID")
    refc = components(c, 3, "REFC")
    k, nodes, weights, comps = 4, [], [], []
    while k < len(c.fields):
        s = c.raw(k).upper()
        if s in ("UM", "ALPHA", "TREF"):
            if s == "UM":
                raise c.error("UM (dependent DOF moved to other grids) is not supported; "
                              "leave the reference grid dependent (REFC)")
            break
        if not s:
            k += 1
            continue
        w = c.real(k, "WT")
        if not (np.isfinite(w) and w > 0):
            raise c.error(f"weight WT = {w:g}; valid: > 0")
        ci = components(c, k + 1, "C")
        grids, k = grid_list(c, k + 2, ("UM", "ALPHA", "TREF"))
        if not grids:
            raise c.error(f"weight group WT = {w:g} lists no grid points")
        nodes.extend(grids)
        weights.extend([w] * len(grids))
        comps.extend([ci] * len(grids))
    if not nodes:
        raise c.error("has no independent grid points")
    idx = index([ref] + nodes, c)
    if cd_of(idx[0]) and not invariant(refc):
        raise c.error(f"REFC = {refc} at a grid with a CD system: only 123, 456, 123456")
    for nd, ci in zip(idx[1:], comps, strict=True):
        if cd_of(nd) and not invariant(ci):
            raise c.error(f"components {ci} at a grid with a CD system: only 123, 456, 123456")
    if int(idx[0]) in set(idx[1:].tolist()):
        raise c.error("the reference grid is also an independent grid")
    return Interpolation(int(idx[0]), refc, idx[1:], np.array(weights), tuple(comps),
                         c.int(0, "EID"))


def rbar(c: Card, index) -> RigidLink:
    """The usual RBAR (GA independent in all six components) as an RBE2 link."""
    cna = components(c, 3, "CNA", allow_zero=True)
    cnb = components(c, 4, "CNB", allow_zero=True)
    cma = components(c, 5, "CMA", allow_zero=True)
    cmb = components(c, 6, "CMB", allow_zero=True)
    if cna != "123456" or cnb or cma or not cmb:
        raise c.error(f"CNA={cna or 'blank'} CNB={cnb or 'blank'} CMA={cma or 'blank'} "
                      f"CMB={cmb or 'blank'}: only the form CNA = 123456, CNB/CMA blank, "
                      "CMB given is supported (write it as an RBE2)")
    idx = index([c.int(1, "GA"), c.int(2, "GB")], c)
    return RigidLink(int(idx[0]), idx[1:], cmb, c.int(0, "EID"))


def celas(cards: list[Card], pelas: dict, index, frames):
    """CELAS1/CELAS2 cards -> two-node and grounded lists (cells, K, ids, B)."""
    two, one = [[], [], [], []], [[], [], [], []]
    for c in cards:
        if c.name == "CELAS1":
            pid = c.int(1, "PID", c.int(0, "EID"))
            if pid not in pelas:
                raise c.error(f"refers to PELAS {pid}, which is not defined")
            k = pelas[pid]
        else:
            k = c.real(1, "K")
            if not np.isfinite(k):
                raise c.error(f"K = {k}; valid: a finite stiffness")
        g1, g2 = c.int(2, "G1", 0), c.int(4, "G2", 0)
        c1 = components(c, 3, "C1", allow_zero=True)
        c2 = components(c, 5, "C2", allow_zero=True)
        if not g1 and not g2:
            raise c.error("connects no grid point (G1 and G2 blank)")
        if (g1 and len(c1) != 1) or (g2 and len(c2) != 1):
            raise c.error("needs one component digit C1/C2 (1-6) per grid; scalar points "
                          "(SPOINT) are not supported")
        pair = [(g, ch) for g, ch in ((g1, c1), (g2, c2)) if g]
        idx = index([g for g, _ in pair], c)
        e = [spring.unit_dof(frames(idx[j:j + 1], c), np.array([int(pair[j][1]) - 1]))
             for j in range(len(pair))]
        if len(pair) == 2:
            two[0].append(idx)
            two[1].append(spring.scalar(np.array([k]), e[0], e[1])[0])
            two[2].append(c.int(0, "EID"))
            two[3].append(np.zeros((12, 12)))
        else:
            one[0].append(idx)
            one[1].append(spring.scalar(np.array([k]), e[0])[0])
            one[2].append(c.int(0, "EID"))
            one[3].append(np.zeros((6, 6)))
    return two, one


def bush_frame(c: Card, XA, XB, systems, orient) -> np.ndarray:
    """Element axes (rows) of a CBUSH: CID, else x = A->B with orientation ``orient``."""
    cid = c.int(7, "CID", None)
    if cid is not None and cid >= 0:
        return systems.frames(cid, XA[None], c)[0].T
    d = XB - XA
    L = np.linalg.norm(d)
    if orient is None or not L > 0:
        if L > 0:
            raise c.error("needs an orientation vector (X1-X3 or GO) or a CID when GA and GB "
                          "are apart")
        return np.eye(3)
    ex = d / L
    ez = np.cross(ex, orient)
    if not np.linalg.norm(ez) > 1e-8 * np.linalg.norm(orient):
        raise c.error("orientation vector is parallel to GA-GB (or zero)")
    ez /= np.linalg.norm(ez)
    return np.array([ex, np.cross(ez, ex), ez])


def solution(case: dict, deck, dof_sets: dict, path) -> dict:
    """``Mesh.solution`` from the case control (``SPC``, ``METHOD``), the ``EIGRL`` cards
    and ``PARAM, COUPMASS`` of ``deck`` (a :mod:`flexpipe.mesh.nastran` deck)."""
    out: dict = {}
    if "SPC" in case:
        sid, line = case["SPC"]
        if f"SPC{sid}" not in dof_sets:
            raise MeshError(f"case control SPC = {sid}, but no SPC/SPC1/SPCADD card has SID "
                            f"{sid}; defined: {sorted(dof_sets)}", file=str(path), line=line)
        out["spc"] = f"SPC{sid}"
    if "METHOD" in case:
        sid, line = case["METHOD"]
        if sid not in deck.eigrl:
            raise MeshError(f"case control METHOD = {sid}, but no EIGRL card has SID {sid}; "
                            f"defined: {sorted(deck.eigrl)}", file=str(path), line=line)
        out.update(eigrl(deck.eigrl[sid]))
    elif len(deck.eigrl) == 1:
        out.update(eigrl(next(iter(deck.eigrl.values()))))
    if "COUPMASS" in deck.params:
        c = deck.params["COUPMASS"]
        out["lumped_mass"] = c.int(1, "COUPMASS") <= 0
        out["coupmass"] = c.int(1, "COUPMASS")
    if "SOL" in case:
        out["sol"] = case["SOL"][0]
    return out


def set1_name(c: Card) -> str | None:
    """Name given to a SET1 card by a ``$ SET name`` comment on the line before it.

    That line was kept by :func:`~flexpipe.mesh._bulk.read_cards` (``Card.preceding``,
    in the card's own file, INCLUDE files too); the name is read as UTF-8.
    """
    prev = c.preceding.encode("latin-1").decode("utf-8", errors="replace").strip()
    parts = prev.split()
    return parts[2] if prev.startswith("$ SET ") and len(parts) == 3 else None
