"""Abaqus model-data blocks of :func:`flexpipe.mesh.abaqus.read_abaqus`: nodes, elements
and the elastic and density data of a material.

Element types are mapped to meshio cell types (:data:`TYPE_OF`); a node or element label
of the assembly gets the assembly's id offset (``ctx == "asm"``), so that it never collides
with a part's label, and ``Instance.label`` names an instance's node or element.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.mesh._abaqus_deck import _Deck, _rows
from flexpipe.mesh._abaqus_extra import values as _values

_TYPES = {"tetra": ("C3D4", "C3D4H"),
          "tetra10": ("C3D10", "C3D10H", "C3D10M", "C3D10MH", "C3D10I", "C3D10HS"),
          "hexahedron": ("C3D8", "C3D8R", "C3D8I", "C3D8H", "C3D8RH", "C3D8IH"),
          "triangle": ("S3", "S3R", "S3RS", "STRI3"),
          "quad": ("S4", "S4R", "S4RS", "S4R5", "S4RSW"),
          "line": ("B31", "B31H", "B33", "B33H"),
          "wedge": ("C3D6", "C3D6H"),
          "pyramid": ("C3D5", "C3D5H"),
          "spring1": ("SPRING1",),
          "spring": ("SPRING2",),
          "connector": ("CONN3D2",),
          "mass": ("MASS", "ROTARYI")}
TYPE_OF = {a: t for t, names in _TYPES.items() for a in names}
NODES = {"tetra": 4, "tetra10": 10, "hexahedron": 8, "triangle": 3, "quad": 4, "line": 2,
         "wedge": 6, "pyramid": 5, "spring1": 1, "spring": 2, "connector": 2, "mass": 1}


def node_block(deck: _Deck, p, lines, ctx) -> None:
    """``*NODE``: labels, coordinates and the optional ``NSET=``."""
    start = len(deck.node_ids)
    for lf, lln, t in lines.data():
        v = _values(lf, lln, t, "*NODE line", count=3)
        label = v[0]
        if not (np.isfinite(label) and label == int(label) and label >= 0):
            raise MeshError(f"*NODE label '{t.split(',')[0].strip()}'; valid: an "
                            "integer >= 0", file=lf, line=lln)
        nid = int(label) + (deck.node_offset if ctx == "asm" else 0)
        if ctx == "asm":
            deck.asm_labels[nid] = int(label)
        deck.node_ids.append(nid)
        deck.coords.append((v[1:4] + [0.0])[:3])
        deck.node_where.append((lf, lln))
    if "NSET" in p:
        deck.nsets.setdefault(deck.define_set("NSET", p["NSET"]), []).extend(
            deck.node_ids[start:])


def element_block(deck: _Deck, p, lines, ctx, f, ln) -> None:
    """``*ELEMENT``: one type per block, connectivity continued by a trailing comma, the
    optional third node of a beam (its n1 direction) and the optional ``ELSET=``."""
    etype = p.get("TYPE", "").upper()
    if etype not in TYPE_OF:
        raise MeshError(
            f"element type '{etype}' is not supported; supported: "
            f"{', '.join(sorted(TYPE_OF))}", file=f, line=ln)
    t = TYPE_OF[etype]
    buf, first = [], None
    new = []
    noff, eoff = (deck.node_offset, deck.elem_offset) if ctx == "asm" else (0, 0)
    for lf, lln, dt in lines.data():
        buf += [x.strip() for x in dt.split(",") if x.strip()]
        first = first or (lf, lln)
        if dt.rstrip().endswith(",") and len(buf) < NODES[t] + 1 + (t == "line"):
            continue            # a trailing comma continues the element
        try:                    # labels of this namespace (fast path)
            ids = [int(buf[0]) + eoff] + [int(x) + noff for x in buf[1:]]
        except ValueError:      # Instance.label, or not a label
            ids = [deck.elem_id(buf[0], ctx)] + [deck.node_id(x, ctx)
                                                 for x in buf[1:]]
        if None in ids:
            raise MeshError(f"element line '{dt[:60]}' must hold integer ids (or "
                            "Instance.label)", file=lf, line=lln)
        if t == "line" and len(ids) == 4:  # optional third node: the n1 direction
            deck.n1_node[ids[0]] = ids.pop()
        if len(ids) != NODES[t] + 1:
            raise MeshError(f"*ELEMENT TYPE={etype}: element {buf[0]} has "
                            f"{len(ids) - 1} nodes, expected {NODES[t]} (end a line "
                            "with a comma to continue an element)", file=first[0],
                            line=first[1])
        deck.eids[t].append(ids[0])
        deck.conn[t].append(ids[1:])
        deck.ewhere[t].append(first)
        new.append(ids[0])
        buf, first = [], None
    if buf:
        raise MeshError(f"*ELEMENT TYPE={etype}: element {buf[0]} has {len(buf) - 1} "
                        f"nodes, expected {NODES[t]}", file=first[0], line=first[1])
    if "ELSET" in p:
        deck.elsets.setdefault(deck.define_set("ELSET", p["ELSET"]), []).extend(new)


def material_block(deck: _Deck, kw: str, p, lines, material, f, ln) -> None:
    """``*ELASTIC`` (isotropic, or ``TYPE=LAMINA``) and ``*DENSITY`` of ``material``."""
    if kw == "ELASTIC" and p.get("TYPE", "").upper() == "LAMINA":
        rows = _rows(lines, f, ln, "*ELASTIC, TYPE=LAMINA")
        v = _values(*rows[0], "*ELASTIC, TYPE=LAMINA E1, E2, nu12, G12, G13, G23",
                    count=4)
        v = (v + [v[3], v[3]])[:6] if len(v) < 6 else v[:6]
        if not all(np.isfinite(x) and 0 < x < 1e20 for x in (v[0], v[1], v[3], v[4])) \
                or not (np.isfinite(v[2]) and v[2] ** 2 * v[1] / v[0] < 1):
            raise MeshError(f"*ELASTIC, TYPE=LAMINA of material '{material}': {v}; valid: "
                            "E1, E2, G12, G13 > 0 and nu12^2 E2 / E1 < 1",
                            file=rows[0][0], line=rows[0][1])
        deck.materials.setdefault((material or "").upper(), {}).update(lamina=v)
    elif kw == "ELASTIC":
        if p.get("TYPE", "ISOTROPIC").upper() != "ISOTROPIC":
            raise MeshError(f"*ELASTIC TYPE={p['TYPE']} is not supported (ISOTROPIC or "
                            "LAMINA)", file=f, line=ln)
        rows = _rows(lines, f, ln, "*ELASTIC")
        E, nu = _values(*rows[0], "*ELASTIC E, nu", count=2)[:2]
        mname = f"material '{material}'"
        if not (np.isfinite(E) and 0 < E < 1e20):
            raise MeshError(f"*ELASTIC of {mname}: E = {E:g}; valid: 0 < E < 1e20 (file "
                            "units)", file=rows[0][0], line=rows[0][1])
        if not (np.isfinite(nu) and -1 < nu < 0.5):
            raise MeshError(f"*ELASTIC of {mname}: nu = {nu:g}; valid: -1 < nu < 0.5",
                            file=rows[0][0], line=rows[0][1])
        deck.materials.setdefault((material or "").upper(), {}).update(E=E, nu=nu)
    else:
        rows = _rows(lines, f, ln, "*DENSITY")
        rho = _values(*rows[0], "*DENSITY", count=1)[0]
        if not (np.isfinite(rho) and 0 <= rho < 1e20):
            raise MeshError(f"*DENSITY of material '{material}': {rho:g}; valid: >= 0",
                            file=rows[0][0], line=rows[0][1])
        deck.materials.setdefault((material or "").upper(), {}).update(rho=rho)


def _dup(ids, where, what, labels=None):
    ids = np.asarray(ids, dtype=np.int64)
    order = np.argsort(ids, kind="stable")
    d = np.flatnonzero(ids[order][1:] == ids[order][:-1])
    if d.size:
        a, b = where[order[d[0]]], where[order[d[0] + 1]]
        i = int(ids[order[d[0]]])
        name = f"{i} (assembly-level {what} {labels[i]})" if labels and i in labels else i
        raise MeshError(f"{what} {name} is defined twice: "
                        f"{Path(a[0]).name} line {a[1]} and {Path(b[0]).name} line {b[1]}",
                        file=b[0], line=b[1])
