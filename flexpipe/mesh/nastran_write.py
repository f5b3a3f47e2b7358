"""Nastran bulk-data writer (the cards :mod:`flexpipe.mesh.nastran` reads).

Integers go in small-field (8 character) cards; cards with reals use large field
(16 characters) with up to 13 significant digits, so a round trip changes coordinates by
at most ~1e-13 relative.  Named node/cell sets other than the property ids have no place
in bulk data and are not written.  Also written: CPENTA/CPYRAM, CBAR offsets WA/WB, PBAR
shear factors K1/K2 and I12 (from the principal axes), PSHELL MID2 with 12I/T^3, ZOFFS,
RBE3, CONM1, springs (see :mod:`flexpipe.mesh._nastran_write_extra`), SPC1 sets and the
solution set-up (case control ``SPC``/``METHOD`` with EIGRL).
"""

from __future__ import annotations

import re
import warnings

import numpy as np

from flexpipe.mesh._bulk import parse_real
from flexpipe.mesh._common import cell_section_index, default_orientation, unique_ids
from flexpipe.mesh.mesh import SOLID_TYPES, Mesh
from flexpipe.mesh.validate import MeshWarning

CARD_OF = {"tetra": "CTETRA", "tetra10": "CTETRA", "hexahedron": "CHEXA",
           "triangle": "CTRIA3", "quad": "CQUAD4", "line": "CBAR", "wedge": "CPENTA",
           "pyramid": "CPYRAM"}
_PID = re.compile(r"^PID(\d+)$")


def real16(x: float) -> str:
    """Most precise Nastran real that fits 16 characters (always with a decimal point)."""
    x = float(x)
    if x == 0.0:
        return "0."
    s = repr(x)
    if "e" not in s and len(s) <= 16:
        return s if "." in s else s + "."
    cands = []
    for p in range(15, 0, -1):  # exponent form without the E: 1.2345-3
        m, e = f"{x:.{p}e}".split("e")
        t = f"{m}{int(e):+d}"
        if len(t) <= 16:
            cands.append(t)
            break
    if abs(x) < 1e15:  # fixed point, leading zero dropped: -.0001234567890123
        for p in range(16, 0, -1):
            t = f"{x:.{p}f}".replace("0.", ".", 1) if abs(x) < 1 else f"{x:.{p}f}"
            if len(t) <= 16 and float(t) != 0.0:
                cands.append(t)
                break
    if not cands:
        raise ValueError(f"cannot format {x} in 16 characters")
    return min(cands, key=lambda t: abs(_value(t) - x))


def real8(x: float) -> str:
    """Most precise Nastran real that fits 8 characters (small field).

    Tries fixed point, ``E`` exponents and Nastran's implied exponent (``2.625+10``) and
    keeps the spelling nearest ``x``; raises ``ValueError`` when none is within 1e-3
    relative.
    """
    x = float(x)
    if x == 0:
        return "0."
    best, err = None, np.inf
    cands = [f"{x:.{p}f}" for p in range(0, 8)]
    cands += [f"{x:.{p}E}".replace("E+0", "E+").replace("E-0", "E-") for p in range(0, 6)]
    cands += [f"{x:.{p}E}".replace("E+0", "+").replace("E-0", "-").replace("E", "")
              for p in range(0, 6)]
    for s in cands:
        if "." not in s:
            continue
        if s.startswith("0.") and len(s) > 8:
            s = s[1:]
        if s.startswith("-0.") and len(s) > 8:
            s = "-" + s[2:]
        if len(s) > 8:
            continue
        e = abs(_value(s) - x) / abs(x)
        if e < err:
            best, err = s, e
    if best is None or err > 1e-3:
        raise ValueError(f"cannot write {x!r} in 8 characters")
    return best


def _value(t: str) -> float:
    return parse_real(t)


def _field(v, width):
    if v is None:
        return ""
    if isinstance(v, (int, np.integer)):
        return str(int(v))
    if isinstance(v, str):
        return v
    return real16(v) if width == 16 else real8(v)


def card(name: str, values, *, small: bool = False) -> str:
    """Format one card: small field when every value fits 8 characters, else large field.

    ``small=True`` forces small field, reals through :func:`real8` (at least four
    significant digits; ``ValueError`` for a field that does not fit).
    """
    strs = [_field(v, 8 if small else 16) for v in values]
    if small:
        if any(len(s) > 8 for s in strs):
            raise ValueError(f"a field of {name} is longer than 8 characters: {strs}")
    else:
        small = all(len(s) <= 8 for s in strs) and not any(
            isinstance(v, float) for v in values)
    per, width = (8, 8) if small else (4, 16)
    head = name if small else name + "*"
    lines = []
    for k in range(0, max(len(strs), 1), per):
        chunk = strs[k:k + per]
        lead = head if k == 0 else ("+" if small else "*")
        lines.append(f"{lead:<8}" + "".join(f"{s:>{width}}" for s in chunk))
    return "\n".join(line.rstrip() for line in lines) + "\n"


def _property_ids(mesh: Mesh):
    """PID per cell per block and the section name of each PID."""
    sec_idx = cell_section_index(mesh)
    names = list(mesh.sections)
    used = {int(t) for b in mesh.blocks for t in b.tags if t > 0}
    for n in names:
        m = _PID.match(n)
        if m:
            used.add(int(m.group(1)))
    nxt = max(used, default=0) + 1
    pid_of: dict = {}
    section_of_pid: dict = {}
    kind_of_pid: dict = {}
    out = []
    for b, sidx in zip(mesh.blocks, sec_idx, strict=True):
        pids = np.zeros(len(b), dtype=np.int64)
        kind = "solid" if b.type in SOLID_TYPES else b.type
        kind = "shell" if b.type in ("triangle", "quad") else kind
        for key in {(int(t), int(s)) for t, s in zip(b.tags, sidx, strict=True)}:
            full = (kind,) + key
            if full not in pid_of:
                tag, s = key
                m = _PID.match(names[s]) if s >= 0 else None
                cand = int(m.group(1)) if m else tag
                if cand > 0 and cand not in pid_of.values():
                    pid_of[full] = cand
                else:
                    pid_of[full] = nxt
                    nxt += 1
                section_of_pid[pid_of[full]] = names[s] if s >= 0 else None
                kind_of_pid[pid_of[full]] = kind
            sel = (b.tags == key[0]) & (sidx == key[1])
            pids[sel] = pid_of[full]
        out.append(pids)
    return out, section_of_pid, kind_of_pid


def _theta_degrees(mesh: Mesh, b):
    """Material angle (degrees from the element x axis) of shells that carry one."""
    if b.type not in ("quad", "triangle") or not ("mat_theta" in b.data
                                                  or "mat_ref" in b.data):
        return None
    from flexpipe.fem._shell import local_frame, material_angle

    n = len(b)
    R, _, _ = local_frame(mesh.points[b.cells])
    phi = material_angle(R, np.asarray(b.data.get("mat_ref", np.full((n, 3), np.nan))),
                         np.asarray(b.data.get("mat_theta", np.zeros(n))))
    return np.degrees(phi)


def nastran_text(mesh: Mesh) -> str:
    """Bulk-data text of ``mesh`` (values as stored: SI for a mesh read by flexpipe)."""
    from flexpipe.mesh._nastran_write_extra import header

    head, tail = header(mesh)
    parts = [head + f"$ written by flexpipe from {mesh.source or 'an in-memory mesh'}\n"]
    nid = unique_ids(mesh.node_ids)
    for i, (x, y, z) in enumerate(mesh.points):
        parts.append(card("GRID", [int(nid[i]), None, float(x), float(y), float(z)]))
    blocks = [b for b in mesh.blocks if b.type != "vertex"]
    if len(blocks) < len(mesh.blocks):
        warnings.warn(MeshWarning("vertex cells have no Nastran card and are not written"),
                      stacklevel=3)
    n_cells = sum(len(b) for b in blocks)
    eids = unique_ids(np.concatenate(
        [b.ids for b in blocks]
        + [np.array([pm.id for pm in mesh.point_masses], dtype=np.int64),
           np.array([lk.id for lk in mesh.rigid_links], dtype=np.int64)]))
    pids, section_of_pid, kind_of_pid = _property_ids(mesh)
    start = 0
    for bi, b in enumerate(mesh.blocks):
        if b.type == "vertex":
            continue
        e = eids[start:start + len(b)]
        start += len(b)
        conn = nid[b.cells]
        if b.type == "line":
            ori = np.asarray(b.data.get("orientation", np.full((len(b), 3), np.nan)), float)
            miss = ~np.isfinite(ori).all(axis=1)
            ori[miss] = default_orientation(mesh.points[b.cells[miss]])
            wa = np.asarray(b.data.get("offset_a", np.zeros((len(b), 3))), dtype=float)
            wb = np.asarray(b.data.get("offset_b", np.zeros((len(b), 3))), dtype=float)
            rel = np.asarray(b.data.get("release", np.zeros(len(b))), dtype=np.int64)
            for k in range(len(b)):
                pins = ["".join(str(d + 1) for d in range(6) if int(rel[k]) >> (e + d) & 1)
                        or None for e in (0, 6)]
                off = ([None, *pins, *map(float, wa[k]), *map(float, wb[k])]
                       if np.any(wa[k]) or np.any(wb[k]) or rel[k] else [])
                parts.append(card("CBAR", [int(e[k]), int(pids[bi][k]), *map(int, conn[k]),
                                           *map(float, ori[k]), *off]))
        elif b.type in ("spring", "spring1"):
            from flexpipe.mesh._nastran_write_extra import spring_cards

            parts.extend(spring_cards(b, e, nid, mesh.source))
        else:
            name = CARD_OF[b.type]
            z = np.asarray(b.data.get("zoffset", np.zeros(len(b))), dtype=float)
            th = _theta_degrees(mesh, b)
            for k in range(len(b)):
                t_k = None if th is None or th[k] == 0 else float(th[k])
                zo = [t_k, float(z[k])] if z[k] else ([t_k] if t_k is not None else [])
                parts.append(card(name, [int(e[k]), int(pids[bi][k]), *map(int, conn[k]),
                                         *zo]))
    mids: dict = {}
    for pid in sorted(section_of_pid):
        sec = mesh.sections.get(section_of_pid[pid] or "", {})
        mid = None
        if all(k in sec for k in ("E", "nu", "rho")):
            key = (float(sec["E"]), float(sec["nu"]), float(sec["rho"]))
            mid = mids.setdefault(key, len(mids) + 1)
        kind = kind_of_pid[pid]
        if kind == "solid":
            parts.append(card("PSOLID", [pid, mid]))
        elif kind == "shell":
            if "A11" in sec:
                from flexpipe.errors import InputError

                raise InputError(f"section {section_of_pid[pid]} is a laminate (PCOMP); the "
                                 "writer has no PCOMP card - keep the original deck",
                                 file=mesh.source or None)
            t = sec.get("thickness")
            bend = float(sec.get("bending", 1.0))
            parts.append(card("PSHELL", [pid, mid, None if t is None else float(t),
                                         mid if bend else None,
                                         None if bend in (0.0, 1.0) else bend]))
        elif kind == "line" and all(k in sec for k in ("A", "Iy", "Iz", "J")):
            th = float(sec.get("theta", 0.0))
            c, s_ = np.cos(th), np.sin(th)
            Ip1, Ip2 = float(sec["Iz"]), float(sec["Iy"])
            I1, I2 = Ip1 * c * c + Ip2 * s_ * s_, Ip1 * s_ * s_ + Ip2 * c * c
            I12 = (Ip1 - Ip2) * c * s_
            k1, k2 = float(sec.get("k1", 0.0)), float(sec.get("k2", 0.0))
            shear = ([None] * 10 + [k1 or None, k2 or None, I12 or None]
                     if k1 or k2 or I12 else [])
            parts.append(card("PBAR", [pid, mid, float(sec["A"]), I1, I2, float(sec["J"]),
                                       *shear]))
    for (E, nu, rho), mid in mids.items():
        parts.append(card("MAT1", [mid, E, None, nu, rho]))
    for k, pm in enumerate(mesh.point_masses):
        if pm.matrix is not None:
            Mm = np.asarray(pm.matrix, dtype=float)
            parts.append(card("CONM1", [int(eids[n_cells + k]), int(nid[pm.node]), 0,
                                        *map(float, Mm[np.tril_indices(6)])]))
            continue
        I = np.asarray(pm.inertia, dtype=float)
        parts.append(card("CONM2", [int(eids[n_cells + k]), int(nid[pm.node]), 0,
                                    float(pm.mass), *map(float, pm.offset), None,
                                    float(I[0, 0]), float(-I[1, 0]), float(I[1, 1]),
                                    float(-I[2, 0]), float(-I[2, 1]), float(I[2, 2])]))
    off = n_cells + len(mesh.point_masses)
    for k, lk in enumerate(mesh.rigid_links):
        parts.append(card("RBE2", [int(eids[off + k]), int(nid[lk.master]), lk.dofs,
                                   *map(int, nid[np.asarray(lk.slaves)])]))
    from flexpipe.mesh._nastran_write_extra import constraint_cards

    nxt = int(eids.max(initial=0)) + 1
    parts.extend(constraint_cards(mesh, nid, nxt))
    if any(not re.match(r"^SET\d+$", n) for n in mesh.node_sets) or any(
            not _PID.match(n) for n in mesh.cell_sets):
        warnings.warn(MeshWarning("named node/cell sets are not written to Nastran bulk data "
                                  "(only property ids are)"), stacklevel=3)
    return "".join(parts) + tail
