"""Element, mass and rigid-element cards of the Nastran reader (see
:mod:`flexpipe.mesh.nastran`): connectivity and node-count checks, CBAR/CBEAM orientation
and offsets, the CQUAD8/CTRIA6 conversion, per-type cell arrays (card-by-card and
fast-path cells in file order), CONM1/CONM2 and RBE2."""

from __future__ import annotations

import warnings

import numpy as np

from flexpipe.mesh import _nastran_extra as extra
from flexpipe.mesh import _nastran_fast as _fast
from flexpipe.mesh._bulk import Card
from flexpipe.mesh.mesh import PointMass, RigidLink
from flexpipe.mesh.validate import MeshWarning

#: element card -> (meshio type by node count, index of first node field, max nodes)
ELEMENTS = {
    "CTETRA": ({4: "tetra", 10: "tetra10"}, 2, 10),
    "CHEXA": ({8: "hexahedron"}, 2, 20),
    "CPENTA": ({6: "wedge"}, 2, 15),
    "CPYRAM": ({5: "pyramid"}, 2, 13),
    "CQUAD4": ({4: "quad"}, 2, 4),
    "CTRIA3": ({3: "triangle"}, 2, 3),
    "CQUAD8": ({8: "quad8"}, 2, 8),
    "CTRIA6": ({6: "triangle6"}, 2, 6),
    "CBAR": ({2: "line"}, 2, 2),
    "CBEAM": ({2: "line"}, 2, 2),
    "CROD": ({2: "line"}, 2, 2),
    "CONROD": ({2: "line"}, 1, 2),
}


def index_of(grid_ids, sorter, wanted, cards, label):
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


def element(card: Card, els: dict, converted: dict | None = None) -> None:
    """Append one element card to ``els[cell_type]`` = list of (card, eid, pid, grids).

    Second-order CHEXA (20), CPENTA (15) and CPYRAM (13; also with some mid-side grids
    blank) become their linear forms on the corner grids; ``converted[name]`` counts them.
    """
    types, first, nmax = ELEMENTS[card.name]
    eid = card.int(0, "EID")
    if card.name == "CONROD":
        pid = -eid
    else:
        pid = card.int(1, "PID", eid)
    raw = card.fields[first:first + nmax]
    try:  # fast path; on a bad field fall back to the checked parser for its message
        g = [int(x) if x else 0 for x in raw]
    except ValueError:
        g = [card.int(first + k, f"G{k + 1}", 0) for k in range(nmax)]
    g += [0] * (nmax - len(g))
    if card.name in ("CHEXA", "CPENTA", "CPYRAM") and sum(1 for x in g if x) > min(types):
        corners = g[:min(types)]
        if 0 in corners:
            raise card.error(f"{card.name}: a corner grid G1-G{min(types)} is blank")
        if converted is not None:
            converted[card.name] = converted.get(card.name, 0) + 1
        g = corners
    if card.name in ("CTETRA", "CHEXA", "CPENTA", "CPYRAM"):
        g = [x for x in g if x]
    n = len(g)
    if n not in types or 0 in g:
        why = "a blank or zero grid field" if 0 in g else "wrong count"
        raise card.error(f"{card.name} with {n} node(s) ({why}) is not supported; valid: "
                         f"{sorted(types)} node(s)")
    els[types[n]].append((card, eid, pid, g))
    if card.name == "CBEAM" and (card.raw(16) or card.raw(17)):
        warnings.warn(MeshWarning(f"{card.file} line {card.line}: CBEAM {eid} warping grids "
                                  "SA/SB are ignored (no warping DOF)"), stacklevel=4)


#: shell card -> (data indices of the corner thicknesses T1.., index of TFLAG) (QRG)
CORNER_T = {"CQUAD4": (range(10, 14), 9), "CTRIA3": (range(11, 14), 10),
            "CQUAD8": (range(10, 14), 16), "CTRIA6": (range(10, 13), 13)}


#: shell card -> data index of ZOFFS (THETA/MCID is the field before it) (QRG)
ZOFFS_FIELD = {"CQUAD4": 7, "CTRIA3": 6, "CQUAD8": 15, "CTRIA6": 9}


def second_order_refs(els: dict, X: np.ndarray) -> dict:
    """Material x axis of each CQUAD8/CTRIA6 with a THETA angle (``card.seq`` -> vector):
    the parent's element x axis (CQUAD4 / CTRIA3 convention on its corner grids) turned
    by THETA about its normal.  The four sub-shells of the split then take this direction
    (projected onto each), not THETA from their own x axes, which differ from the
    parent's.  Call before :func:`split_second_order` (node indices resolved)."""
    from flexpipe.mesh._bulk import parse_real

    out = {}
    for key, zi in (("quad8", 15), ("triangle6", 9)):
        for c, _eid, _pid, g in els.get(key, []):
            s = c.raw(zi - 1)
            if not s or s.lstrip("+-").isdigit():
                continue                    # blank, or an MCID: projected per sub-shell
            v = parse_real(s)
            if v is None or not np.isfinite(v):
                raise c.error(f"THETA = '{s}' is not a number (or MCID id)")
            P = X[np.asarray(g[:4] if key == "quad8" else g[:3])]
            if key == "quad8":
                e1 = P[1] + P[2] - P[0] - P[3]
                n = np.cross(P[2] - P[0], P[3] - P[1])
            else:
                e1 = P[1] - P[0]
                n = np.cross(P[1] - P[0], P[2] - P[0])
            if not np.linalg.norm(n) > 0:
                continue                    # degenerate: left to the sub-shells' checks
            n = n / np.linalg.norm(n)
            e1 = e1 - (e1 @ n) * n
            if not np.linalg.norm(e1) > 0:
                continue
            e1 = e1 / np.linalg.norm(e1)
            a = np.radians(v)
            out[c.seq] = np.cos(a) * e1 + np.sin(a) * np.cross(n, e1)
    return out


def corner_thickness(card: Card):
    """``(TFLAG, [T1, T2, ...])`` of a shell card that gives corner thicknesses (None for
    a blank Ti), or None when it gives none (blank Ti with TFLAG 0 or 1: the PSHELL T)."""
    cols, fcol = CORNER_T.get(card.name, ((), None))
    if not any(card.raw(k) for k in cols):
        if fcol is not None and card.raw(fcol) not in ("", "0", "1"):
            raise card.error(f"TFLAG = {card.raw(fcol)}; valid: 0, 1 or blank")
        return None
    tflag = card.int(fcol, "TFLAG", 0)
    if tflag not in (0, 1):
        raise card.error(f"TFLAG = {tflag}; valid: 0 (T1.. are thicknesses), 1 (factors on "
                         "the PSHELL T) or blank")
    return tflag, [card.real(k, f"T{j + 1}", None) for j, k in enumerate(cols)]


def element_thickness(rows, corners, user_of, T, prop: Card):
    """Thickness of the shell cells ``rows`` of one PSHELL (``T`` its T, None if blank):
    the mean of the element's corner thicknesses (``corners[row]`` from
    :func:`corner_thickness`) where it gives them, ``T`` elsewhere (NaN if T is blank).
    Returns ``(t, number of elements whose corners differ)``."""
    t = np.full(len(rows), np.nan if T is None else float(T))
    varying = 0
    for k, j in enumerate(rows):
        cj = corners[j]
        if cj is None:
            continue
        tflag, vals = cj
        user = user_of(int(j))
        names = [f"T{i + 1}" for i in range(len(vals))]
        if tflag == 1:
            if T is None:
                raise user.error(f"TFLAG = 1 (T1.. are factors on the PSHELL T) but PSHELL "
                                 f"{prop.label()} (line {prop.line}) has T blank; give the "
                                 "PSHELL T, or the thicknesses with TFLAG blank")
            v = [T * (1.0 if x is None else x) for x in vals]
        else:
            blank = [n for n, x in zip(names, vals, strict=True) if x is None]
            if blank and T is None:
                raise user.error(f"corner thickness {', '.join(blank)} is blank and PSHELL "
                                 f"{prop.label()} (line {prop.line}) has T blank: give every "
                                 f"{names[0]}-{names[-1]} or the PSHELL T")
            v = [T if x is None else x for x in vals]
        v = np.array(v, dtype=float)
        if not np.isfinite(v).all() or (v < 0).any() or not (v > 0).any():
            raise user.error(f"corner thicknesses {names[0]}-{names[-1]} = "
                             f"{', '.join(f'{x:g}' for x in v)}"
                             + (" (times PSHELL T)" if tflag == 1 else "")
                             + "; valid: >= 0 and not all zero")
        t[k] = v.mean()
        if v.max() - v.min() > 1e-12 * v.max():
            varying += 1
    return t, varying


def line_data(items, X, conn, cd_frames, gid, sorter):
    """Orientation vectors, end offsets and pin-flag masks of CBAR/CBEAM/CROD cells."""
    n = len(items)
    ori = np.full((n, 3), np.nan)
    w = np.zeros((n, 6))
    rel = np.zeros(n, dtype=np.int64)
    g0_nodes = []
    for k, (c, _, _, _) in enumerate(items):
        if c.name not in ("CBAR", "CBEAM"):
            continue
        if c.is_int(4) and not c.raw(5) and not c.raw(6):
            gi = int(index_of(gid, sorter, [c.int(4, "G0")], [c], "G0")[0])
            ori[k] = X[gi] - X[conn[k, 0]]
            g0_nodes.append(gi)
        else:
            vals = [c.real(4 + j, f"X{j + 1}", None) for j in range(3)]
            if any(v is not None for v in vals):
                ori[k] = cd_frames(conn[k, :1], c)[0] @ [v or 0.0 for v in vals]
        for end, fld in ((0, 8), (6, 9)):          # pin flags PA, PB: released end DOF
            if c.raw(fld):
                comps = extra.components(c, fld, "PA" if end == 0 else "PB")
                rel[k] |= sum(1 << (end + int(ch) - 1) for ch in comps)
        off = [c.real(10 + j, "W", 0.0) for j in range(6)]
        if any(off):
            if c.raw(7).upper() not in ("", "GGG"):
                raise c.error(f"OFFT = {c.raw(7)} is not supported; only GGG (offsets in "
                              "the grids' displacement systems)")
            w[k, :3] = cd_frames(conn[k, :1], c)[0] @ off[:3]
            w[k, 3:] = cd_frames(conn[k, 1:2], c)[0] @ off[3:]
    return ori, w, g0_nodes, rel


def split_second_order(els: dict, X: np.ndarray, max_gid: int):
    """CQUAD8 -> 4 CQUAD4 (+ centre grid), CTRIA6 -> 4 CTRIA3 through the mid-side grids."""
    converted = {}
    new_pts = []
    next_id = max_gid + 1
    q8 = els.pop("quad8", [])
    for c, eid, pid, g in q8:
        corner_x = [X[i] for i in g[:4]]
        mid_x = [X[i] for i in g[4:]]
        xc = -0.25 * np.sum(corner_x, axis=0) + 0.5 * np.sum(mid_x, axis=0)
        ci = len(X) + len(new_pts)
        new_pts.append((next_id, xc))
        next_id += 1
        a, b, cc, d, ab, bc, cd, da = g
        for sub in ((a, ab, ci, da), (ab, b, bc, ci), (ci, bc, cc, cd), (da, ci, cd, d)):
            els["quad"].append((c, eid, pid, list(sub)))
    t6 = els.pop("triangle6", [])
    for c, eid, pid, g in t6:
        a, b, cc, ab, bc, ca = g
        for sub in ((a, ab, ca), (ab, b, bc), (ca, bc, cc), (ab, bc, ca)):
            els["triangle"].append((c, eid, pid, list(sub)))
    if q8:
        converted["CQUAD8"] = f"{len(q8)} -> {4 * len(q8)} CQUAD4 (+{len(q8)} centre grids)"
    if t6:
        converted["CTRIA6"] = f"{len(t6)} -> {4 * len(t6)} CTRIA3"
    return new_pts, converted


def cell_arrays(cell_type, items, fa, fast, gid, sorter):
    """``eid, pid, conn, zoffs, theta_given, card_of, corners`` of one cell type:
    card-by-card ``items`` (node indices already resolved) and the fast-path arrays ``fa``,
    in file order.  ``theta_given`` holds the THETA/MCID field of shells ('' when blank),
    ``corners`` the :func:`corner_thickness` of each shell (None: none given)."""
    k = len(items)
    corners = None
    if cell_type in ("quad", "triangle"):
        corners = np.empty(k, dtype=object)
        corners[:] = [corner_thickness(it[0]) for it in items]
    eid = np.array([it[1] for it in items], dtype=np.int64)
    pid = np.array([it[2] for it in items], dtype=np.int64)
    conn = np.array([it[3] for it in items], dtype=np.int64)
    zoff = theta = None
    if cell_type in ("quad", "triangle"):
        zi = [ZOFFS_FIELD.get(it[0].name) for it in items]
        zoff = np.array([it[0].real(z, "ZOFFS", 0.0) if z else 0.0
                         for it, z in zip(items, zi, strict=True)])
        theta = np.array([it[0].raw(z - 1) if z else ""
                          for it, z in zip(items, zi, strict=True)], dtype=object)
    if fa is None:
        return eid, pid, conn, zoff, theta, lambda j: items[j][0], corners
    name = "CQUAD4" if cell_type == "quad" else "CTRIA3"
    lazy = _fast.Lazy(lambda j: fast.card(name, j), len(fa["eid"]))
    fconn = index_of(gid, sorter, fa["g"], lazy, "a node")
    seq = np.concatenate([np.array([it[0].seq for it in items], dtype=np.int64), fa["seq"]])
    order = np.argsort(seq, kind="stable")

    def card_of(j):
        i = int(order[j])
        return items[i][0] if i < k else fast.card(name, i - k)

    return (np.concatenate([eid, fa["eid"]])[order], np.concatenate([pid, fa["pid"]])[order],
            np.concatenate([conn.reshape(k, fconn.shape[1]), fconn])[order],  # noqa: E501
            np.concatenate([zoff, fa["zoffs"]])[order],
            np.concatenate([theta, _decoded(fa["theta"])])[order], card_of,
            np.concatenate([corners, np.full(len(fa["eid"]), None, dtype=object)])[order])


def _decoded(col: np.ndarray) -> np.ndarray:
    """Object array of stripped strings of an S8 column ('' for blank fields)."""
    out = np.full(len(col), "", dtype=object)
    for i in np.flatnonzero(col != _fast.BLANK):
        out[i] = col[i].decode("latin-1").strip()
    return out


def conm2(c: Card, index, X, systems) -> PointMass:
    node = int(index([c.int(1, "G")], c)[0])
    cid = c.int(2, "CID", 0)
    m = c.real(3, "M")
    if not (np.isfinite(m) and m >= 0):
        raise c.error(f"mass M = {m:g}; valid: a finite value >= 0")
    off = np.array([c.real(4 + k, f"X{k + 1}", 0.0) for k in range(3)])
    i11, i21, i22, i31, i32, i33 = (c.real(8 + k, "I", 0.0) for k in range(6))
    inertia = np.array([[i11, -i21, -i31], [-i21, i22, -i32], [-i31, -i32, i33]])
    if not np.isfinite(inertia).all() or np.linalg.eigvalsh(inertia).min() < -1e-9 * max(
            abs(inertia).max(), 1e-300):
        raise c.error("inertia I11..I33 is not positive semi-definite (or not finite)")
    if cid == -1:
        off = off - X[node]
    elif cid > 0:
        R = systems.frames(cid, X[node:node + 1], c)[0]
        off, inertia = R @ off, R @ inertia @ R.T
    return PointMass(node, m, inertia, off, c.int(0, "EID"))


def conm1(c: Card, index, X, systems) -> PointMass:
    """CONM1: a symmetric 6 x 6 mass matrix (lower triangle M11, M21, M22, ...)."""
    node = int(index([c.int(1, "G")], c)[0])
    vals = [c.real(3 + k, "Mij", 0.0) for k in range(21)]
    Mm = np.zeros((6, 6))
    Mm[np.tril_indices(6)] = vals
    Mm = Mm + np.tril(Mm, -1).T
    if not np.isfinite(Mm).all() or np.linalg.eigvalsh(Mm).min() < -1e-9 * max(
            abs(Mm).max(), 1e-300):
        raise c.error("mass matrix is not symmetric positive semi-definite (or not finite)")
    cid = c.int(2, "CID", 0)
    if cid:
        R = systems.frames(cid, X[node:node + 1], c)[0]
        T = np.kron(np.eye(2), R)
        Mm = T @ Mm @ T.T
    return PointMass(node, float(Mm[0, 0]), np.zeros((3, 3)), np.zeros(3), c.int(0, "EID"),
                     Mm)


def rbe2(c: Card, gid, sorter) -> RigidLink:
    gn = c.int(1, "GN")
    cm = c.raw(2)
    if not cm or not cm.isdigit() or set(cm) - set("123456"):
        raise c.error(f"component field CM = '{cm}' must be digits 1-6, e.g. 123456")
    slaves, _ = extra.grid_list(c, 3)     # a real (ALPHA) ends the node list
    if not slaves:
        raise c.error("has no dependent grid points GMi")
    idx = index_of(gid, sorter, [gn] + slaves, [c] * (len(slaves) + 1), "a grid point")
    return RigidLink(int(idx[0]), idx[1:], "".join(sorted(set(cm))), c.int(0, "EID"))
