"""Abaqus input deck (``.inp``) reader: a small dedicated parser.

Keywords read
-------------
``*NODE`` (``NSET=``), ``*ELEMENT`` (``TYPE=``, ``ELSET=``), ``*NSET``/``*ELSET``
(lists, set names, ``GENERATE``), ``*SOLID SECTION``, ``*SHELL SECTION`` and ``*SHELL
GENERAL SECTION`` (isotropic ``MATERIAL=`` and thickness, or ``COMPOSITE`` plies;
``OFFSET=SPOS|SNEG|<fraction>`` -> the shell offset ``zoffset`` = -OFFSET x thickness,
the Nastran ZOFFS: Abaqus OFFSET is the distance from the mid-surface to the nodes'
reference surface along the normal, so SPOS puts the mid-surface t/2 *below* the nodes;
``DENSITY=`` mass per area, added as PSHELL NSM is; section parameters that do not change M
and K - ``SECTION INTEGRATION``, ``CONTROLS``, ``POISSON``, ... - are accepted, any other
one is an error naming it), ``*BEAM GENERAL SECTION`` (``SECTION=GENERAL``: A, I11, I12,
I22, J; n1; E, G; ``DENSITY=``), ``*BEAM SECTION`` (``SECTION=RECT``, ``CIRC``, ``PIPE``,
``BOX``, ``I``, ``L``; n1), ``*MATERIAL`` with ``*ELASTIC`` (isotropic) and ``*DENSITY``,
``MASS``/``ROTARYI`` elements with ``*MASS``/``*ROTARY INERTIA``, ``*KINEMATIC
COUPLING`` and ``*COUPLING`` + ``*KINEMATIC`` (rigid spiders, like Nastran RBE2),
``*COUPLING`` + ``*DISTRIBUTING`` on a ``*SURFACE, TYPE=NODE`` (= Nastran RBE3, weights
from the surface; ``REF NODE=`` a node or a one-node set, as Abaqus/CAE writes for a
reference point; ``INFLUENCE RADIUS=r``: only the surface nodes within r of the reference
node are coupled), ``SPRING1``/``SPRING2`` with ``*SPRING``, ``CONN3D2`` connectors with
``*CONNECTOR SECTION`` / ``*CONNECTOR BEHAVIOR`` (linear uncoupled elasticity and
damping: Nastran CBUSH), ``*INCLUDE``, and a single ``*PART``/``*INSTANCE`` without
positioning.

Boundary conditions and steps (as a Nastran SOL 103 deck's ``SPC = n`` and EIGRL)
------------------------------------------------------------------------------------
``*BOUNDARY`` in the model data and in the steps (node, node set or ``Instance.label``;
first and last DOF 1-6, or the types ``ENCASTRE``, ``PINNED``, ``XSYMM``, ``YSYMM``,
``ZSYMM``, ``XASYMM``, ``YASYMM``, ``ZASYMM``; ``OP=NEW`` removes the constraints before it)
-> the DOF set ``Mesh.dof_sets["SPC1"]`` named by ``Mesh.solution["spc"]``: the
representation of a Nastran ``SPC = 1`` set, which ``flexpipe modes`` holds fixed and the
.bdf writer writes as SPC1 cards (``Mesh.info["converted"]["*BOUNDARY"]`` says so).  The
constraints used are those in effect in the first step with ``*FREQUENCY`` (else at the end
of the first step, else those of the model data); that step's number of eigenvalues and
frequency range (``EIGENSOLVER=LANCZOS`` / ``AMS``: n, f_min, f_max; ``SUBSPACE``: n, f_max)
-> ``solution["n_modes"]``, ``["f_min"]``, ``["f_max"]``.  A non-zero prescribed value is
held at zero with a warning (the modes of a ``*FREQUENCY`` step do the same);
``TYPE=VELOCITY``/``ACCELERATION``, other parameters, DOF outside 1-6 and ``*MODEL CHANGE``
are errors.  Other keywords of the steps (loads, output requests) and the steps after the
frequency step are not used; they are listed in one warning and in ``Mesh.info["dropped"]``
with the model data's keywords that do not change M or K.

Parts and assembly (Abaqus/CAE decks)
-------------------------------------
Part nodes and elements keep their labels.  Labels in the assembly and in the steps are
in the assembly's own namespace: an assembly-level ``*NODE`` (a CAE reference point,
numbered from 1 like the part's nodes) or element (``MASS`` on a reference point) gets
the id ``offset + label``, the offset being the smallest power of ten above the largest
part label (part nodes 1..441: assembly node 1 is node 1001; ``Mesh.info["converted"]``
says so), and ``Part-1-1.12`` means part node 12.  An assembly set named like a part set
(CAE numbers both ``Set-1``, ...) is a different set: it is stored as ``"Assembly.Set-1"``
(``<assembly name>.<set>``), and a bare set name in the assembly and the steps means the
assembly's set.  See :mod:`flexpipe.mesh._abaqus_deck`.

Helpers in :mod:`flexpipe.mesh._abaqus_extra` (sections, boundary conditions, masses,
couplings, springs, connectors) and :mod:`flexpipe.mesh._abaqus_deck` (lines,
``*INCLUDE``, parameters, sets, namespaces).

Element types: ``C3D4*`` -> tetra, ``C3D10*`` -> tetra10, ``C3D8*`` -> hexahedron,
``C3D6*`` -> wedge, ``C3D5*`` -> pyramid, ``S3*``/``STRI3`` -> triangle, ``S4*`` -> quad,
``B31*``/``B33*`` -> line (Euler-Bernoulli; beam local 1-axis = Abaqus n1 = flexpipe local
y; an optional third beam node gives n1 and is dropped after use).  An element line that
does not end with a comma ends its element: too few nodes is an error, never a silently
shifted connectivity.  Every ``*ELSET`` is a cell set, every ``*NSET`` a node set;
sections are stored under their ``ELSET`` name.  Other element types and constraints
(``*MPC``, ``*TIE``, ``*EQUATION``, ``*TRANSFORM``, ``*NGEN`` ...) and near misses of the
keywords read (``*ELEMNT``) raise :class:`~flexpipe.errors.MeshError`: dropping them
would change the structure.
"""

from __future__ import annotations

from collections import defaultdict
from pathlib import Path

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.mesh._abaqus_blocks import (
    NODES,
    _dup,
    element_block,
    material_block,
    node_block,
)
from flexpipe.mesh._abaqus_deck import _Deck, _Lines, _members, _params, _rows
from flexpipe.mesh._abaqus_extra import (
    _beam_section,
    _composite,
    _connectors,
    _couplings,
    _couplings2,
    _masses,
    _section_props,
    _springs,
    material_records,
)
from flexpipe.mesh._abaqus_extra import values as _values
from flexpipe.mesh._abaqus_steps import (
    BC_SET,
    _boundary,
    _end_step,
    _solution,
    _step_keyword,
    near_miss,
    warn_dropped,
)
from flexpipe.mesh._bulk import parse_real
from flexpipe.mesh.mesh import CellBlock, Mesh
from flexpipe.mesh.nastran import drop_orientation_nodes

UNSUPPORTED_KEYWORDS = ("MPC", "TIE", "EQUATION", "DISTRIBUTING COUPLING", "RIGID BODY",
                        "MEMBRANE SECTION", "TRANSFORM", "SYSTEM", "CONNECTOR PLASTICITY",
                        "NGEN", "NFILL", "NCOPY", "NMAP", "ELGEN", "ELCOPY", "BEAM ADDED INERTIA",
                        "NONSTRUCTURAL MASS")
#: keywords this reader acts on (a near miss of one of these is taken as a typo)
HANDLED_KEYWORDS = ("NODE", "ELEMENT", "NSET", "ELSET", "SOLID SECTION", "SHELL SECTION",
                    "SHELL GENERAL SECTION", "BEAM SECTION", "BEAM GENERAL SECTION",
                    "MATERIAL", "ELASTIC", "DENSITY", "MASS", "ROTARY INERTIA",
                    "KINEMATIC COUPLING", "COUPLING", "DISTRIBUTING", "KINEMATIC", "SURFACE",
                    "SPRING", "PART", "END PART", "ASSEMBLY", "END ASSEMBLY", "INSTANCE",
                    "END INSTANCE", "STEP", "END STEP", "BOUNDARY", "FREQUENCY", "INCLUDE",
                    "CONNECTOR SECTION", "CONNECTOR BEHAVIOR", "CONNECTOR ELASTICITY",
                    "CONNECTOR DAMPING")
#: keywords that do not change M or K (listed in ``Mesh.info["dropped"]``); real keywords
#: that would otherwise look like near misses of the ones read (``*NODAL THICKNESS`` and
#: ``*DISTRIBUTION`` only act through section parameters, which are refused; ``*PLASTIC``
#: does not change the linear M and K)
IGNORED_KEYWORDS = ("HEADING", "PREPRINT", "AMPLITUDE", "INITIAL CONDITIONS", "OUTPUT",
                    "NODE OUTPUT", "ELEMENT OUTPUT", "RESTART", "SURFACE INTERACTION",
                    "NODAL THICKNESS", "SURFACE SECTION", "SURFACE BEHAVIOR", "PLASTIC",
                    "DISTRIBUTION", "DISTRIBUTION TABLE", "CONNECTOR MOTION", "CONNECTOR STOP",
                    "TRANSVERSE SHEAR STIFFNESS")
#: ignored keywords that say nothing about the model: listed in info, not warned
SILENT_KEYWORDS = ("HEADING", "PREPRINT")
#: what a keyword of :data:`IGNORED_KEYWORDS` would do, said in the "not used" warning
IGNORED_NOTES = {
    "CONNECTOR MOTION": "prescribed connector motion, a load/boundary condition of a step; "
                        "the connector keeps its free components",
    "CONNECTOR STOP": "stops limiting the connector's relative motion, a nonlinear contact "
                      "condition; the linear connector has no stops",
    "TRANSVERSE SHEAR STIFFNESS": "the given transverse shear stiffness values are replaced "
                                  "by flexpipe's own (its shells and beams compute them from "
                                  "the section's material and geometry)",
}


def _parse(path: Path) -> _Deck:
    deck = _Deck(path)
    lines = _Lines(path)
    material = None
    while lines.pos < len(lines.items):
        f, ln, text = lines.items[lines.pos]
        lines.pos += 1
        if not text.startswith("*"):
            raise MeshError(f"data line outside a keyword block: '{text[:40]}'", file=f, line=ln)
        kw = text[1:].split(",")[0].strip().upper()
        p = _params(text)
        if deck.pending is not None and kw not in ("DISTRIBUTING", "KINEMATIC"):
            raise MeshError("*COUPLING must be followed by *DISTRIBUTING or *KINEMATIC",
                            file=deck.pending[2], line=deck.pending[3])
        if kw not in ("CONNECTOR ELASTICITY", "CONNECTOR DAMPING", "CONNECTOR STOP"):
            deck.behavior = None            # connector behaviour options end here
        if deck.done:                       # steps after the frequency step are not used
            deck.dropped[kw] = deck.dropped.get(kw, 0) + 1
            deck.dropped_at.setdefault(kw, (f, ln))
            for _ in lines.data():
                pass
            continue
        if deck.step is not None or kw == "STEP":
            _step_keyword(deck, kw, p, lines, f, ln)
            continue
        ctx = deck.ctx(p)
        if kw == "NODE":
            node_block(deck, p, lines, ctx)
        elif kw == "ELEMENT":
            element_block(deck, p, lines, ctx, f, ln)
        elif kw in ("NSET", "ELSET"):
            table = deck.nsets if kw == "NSET" else deck.elsets
            name = p.get(kw)
            if not name:
                raise MeshError(f"*{kw} needs {kw}=name", file=f, line=ln)
            if kw == "NSET" and "ELSET" in p:
                raise MeshError("*NSET with ELSET= is not supported; list the nodes", file=f,
                                line=ln)
            key = deck.define_set(kw, name)
            table.setdefault(key, []).extend(_members(deck, table, p, lines, f"*{kw} {name}",
                                                      ctx))
        elif kw in ("SOLID SECTION", "SHELL SECTION", "SHELL GENERAL SECTION"):
            rows = list(lines.data())
            props = _section_props(kw, p, rows, f, ln)
            mat = None if "composite" in props else p.get("MATERIAL")
            deck.sections.append((deck.elset(p.get("ELSET"), ctx), props, mat, None, f, ln))
        elif kw in ("BEAM GENERAL SECTION", "BEAM SECTION"):
            props, mat, n1 = _beam_section(p, lines, f, ln)
            deck.sections.append((deck.elset(p.get("ELSET"), ctx), props, mat, n1, f, ln))
        elif kw == "MATERIAL":
            material = p.get("NAME", "")
            deck.materials[material.upper()] = {"at": (f, ln, material)}
        elif kw in ("ELASTIC", "DENSITY"):
            material_block(deck, kw, p, lines, material, f, ln)
        elif kw == "MASS":
            rows = _rows(lines, f, ln, "*MASS")
            m = _values(*rows[0], "*MASS", count=1)[0]
            if not (np.isfinite(m) and m >= 0):
                raise MeshError(f"*MASS {m:g}; valid: >= 0", file=rows[0][0], line=rows[0][1])
            deck.masses.append((deck.elset(p.get("ELSET"), ctx), m, f, ln))
        elif kw == "ROTARY INERTIA":
            rows = _rows(lines, f, ln, "*ROTARY INERTIA")
            v = (_values(*rows[0], "*ROTARY INERTIA", count=3) + [0.0] * 3)[:6]
            I = np.array([[v[0], v[3], v[4]], [v[3], v[1], v[5]], [v[4], v[5], v[2]]])
            deck.inertias.append((deck.elset(p.get("ELSET"), ctx), I, f, ln))
        elif kw == "KINEMATIC COUPLING":
            ref = p.get("REF NODE")
            if not ref:
                raise MeshError("*KINEMATIC COUPLING needs REF NODE=<node id or node set>",
                                file=f, line=ln)
            rows = []
            for lf, lln, t in lines.data():
                tok = [x.strip() for x in t.split(",")]
                first = int(tok[1]) if len(tok) > 1 and tok[1] else 1
                last = int(tok[2]) if len(tok) > 2 and tok[2] else (first if len(tok) > 1
                                                                    and tok[1] else 6)
                if not 1 <= first <= last <= 6:
                    raise MeshError(f"*KINEMATIC COUPLING DOF range {first}..{last}; valid: "
                                    "first <= last within 1..6", file=lf, line=lln)
                rows.append((deck.node_ref(tok[0], ctx), first, last, lf, lln))
            deck.couplings.append((deck.node_ref(ref, ctx), rows, f, ln))
        elif kw == "SURFACE":
            name = p.get("NAME", "")
            if p.get("TYPE", "ELEMENT").upper() != "NODE":
                raise MeshError(f"*SURFACE {name}: only TYPE=NODE surfaces are supported "
                                "(for *COUPLING)", file=f, line=ln)
            deck.surfaces[name.upper()] = [(lf, lln, t, ctx) for lf, lln, t in lines.data()]
        elif kw == "COUPLING":
            ref, surf = p.get("REF NODE", ""), p.get("SURFACE", "")
            if not ref or not surf:
                raise MeshError("*COUPLING needs REF NODE=<node id or node set> and "
                                "SURFACE=<name>", file=f, line=ln)
            radius = None
            if p.get("INFLUENCE RADIUS", "") != "":
                radius = parse_real(p["INFLUENCE RADIUS"])
                if radius is None or not (np.isfinite(radius) and radius > 0):
                    raise MeshError(f"*COUPLING INFLUENCE RADIUS={p['INFLUENCE RADIUS']}; "
                                    "valid: a distance > 0", file=f, line=ln)
            deck.pending = (deck.node_ref(ref, ctx), surf, f, ln, radius)
        elif kw in ("DISTRIBUTING", "KINEMATIC") and deck.pending is not None:
            if p.get("WEIGHTING METHOD", "UNIFORM").upper() != "UNIFORM":
                raise MeshError("*DISTRIBUTING: only WEIGHTING METHOD=UNIFORM is supported",
                                file=f, line=ln)
            dofs = ""
            for lf, lln, t in lines.data():
                v = [int(x) for x in _values(lf, lln, t, f"*{kw} DOF range")]
                if not 1 <= v[0] <= 6:
                    raise MeshError(f"*{kw} DOF {v[0]}; valid: 1..6", file=lf, line=lln)
                last = v[1] if len(v) > 1 and v[1] else v[0]
                if not v[0] <= last <= 6:
                    raise MeshError(f"*{kw} DOF range {v[0]}..{last}; valid: within 1..6",
                                    file=lf, line=lln)
                dofs += "".join(str(d) for d in range(v[0], last + 1))
            deck.couplings2.append((kw, *deck.pending, "".join(sorted(set(dofs or "123456")))))
            deck.pending = None
        elif kw == "CONNECTOR SECTION":
            rows = _rows(lines, f, ln, "*CONNECTOR SECTION")
            types = [t.strip().upper() for t in rows[0][2].split(",") if t.strip()]
            if len(rows) > 1:
                raise MeshError("*CONNECTOR SECTION with an orientation line is not supported "
                                "(connector axes are the global axes)", file=rows[1][0],
                                line=rows[1][1])
            deck.connectors.append((deck.elset(p.get("ELSET"), ctx), types,
                                    p.get("BEHAVIOR", "").upper(), f, ln))
        elif kw == "CONNECTOR BEHAVIOR":
            deck.behavior = p.get("NAME", "").upper()
            deck.behaviors.setdefault(deck.behavior, {"K": {}, "B": {}})
        elif kw in ("CONNECTOR ELASTICITY", "CONNECTOR DAMPING"):
            if deck.behavior is None:
                raise MeshError(f"*{kw} outside a *CONNECTOR BEHAVIOR", file=f, line=ln)
            if "NONLINEAR" in p or "RIGID" in p or "COMPONENT" not in p:
                raise MeshError(f"*{kw}: only linear, uncoupled COMPONENT=<1..6> data is "
                                "supported", file=f, line=ln)
            comp = p["COMPONENT"]
            if not comp.isdigit() or not 1 <= int(comp) <= 6:
                raise MeshError(f"*{kw}: COMPONENT={comp}; valid: 1..6", file=f, line=ln)
            rows = _rows(lines, f, ln, f"*{kw}")
            v = _values(*rows[0], f"*{kw}", count=1)[0]
            if not (np.isfinite(v) and v >= 0):
                raise MeshError(f"*{kw} {v:g}; valid: finite and >= 0", file=rows[0][0],
                                line=rows[0][1])
            key = "K" if kw == "CONNECTOR ELASTICITY" else "B"
            deck.behaviors[deck.behavior][key][int(comp)] = v
        elif kw == "SPRING":
            if "ORIENTATION" in p or "NONLINEAR" in p:
                raise MeshError("*SPRING with ORIENTATION= or NONLINEAR is not supported",
                                file=f, line=ln)
            rows = _rows(lines, f, ln, "*SPRING", 2)
            deck.springs.append((deck.elset(p.get("ELSET"), ctx), rows, f, ln))
        elif kw == "BOUNDARY":              # model data: zero-valued constraints
            deck.bc_model += _boundary(deck, p, lines, f, ln)[0]
        elif kw in ("FREQUENCY", "END STEP"):
            raise MeshError(f"*{kw} outside a step (it is history data: after *STEP)",
                            file=f, line=ln)
        elif kw == "PART":
            deck.scope = "part"
        elif kw == "END PART":
            deck.scope = "model"
        elif kw == "ASSEMBLY":
            _enter_assembly(deck, p)
        elif kw == "END ASSEMBLY":
            deck.scope = "model"
        elif kw == "INSTANCE":
            deck.instances += 1
            if deck.instances > 1 or list(lines.data()):
                raise MeshError("several or positioned *INSTANCEs are not supported; write the "
                                "deck flat (Abaqus: input file without parts and assemblies)",
                                file=f, line=ln)
            deck.scope, deck.instance_name = "instance", p.get("NAME")
        elif kw == "END INSTANCE":
            deck.scope = "assembly"
        elif kw in UNSUPPORTED_KEYWORDS or kw in ("DISTRIBUTING", "KINEMATIC"):
            raise MeshError(f"*{kw} is not supported (rigid spiders: *KINEMATIC COUPLING or "
                            "*COUPLING + *KINEMATIC; RBE3-type: *COUPLING + *DISTRIBUTING); "
                            "remove or convert it", file=f, line=ln)
        else:
            if kw not in IGNORED_KEYWORDS:
                near_miss(kw, HANDLED_KEYWORDS, f, ln)
            deck.dropped[kw] = deck.dropped.get(kw, 0) + 1
            deck.dropped_at.setdefault(kw, (f, ln))
            for _ in lines.data():
                pass
    if deck.pending is not None:
        raise MeshError("*COUPLING must be followed by *DISTRIBUTING or *KINEMATIC",
                        file=deck.pending[2], line=deck.pending[3])
    if deck.step is not None:               # a last step without *END STEP
        _end_step(deck)
    return deck


def _enter_assembly(deck: _Deck, p) -> None:
    """``*ASSEMBLY``: labels of assembly-level nodes and elements get ids above the parts'."""
    deck.has_assembly, deck.scope = True, "assembly"
    deck.asm_name = p.get("NAME") or "Assembly"
    eids = [e for t in deck.eids for e in deck.eids[t]]
    deck.node_offset = 10 ** len(str(max(deck.node_ids))) if deck.node_ids else 0
    deck.elem_offset = 10 ** len(str(max(eids))) if eids else 0


def read_abaqus(path) -> Mesh:
    """Read an Abaqus ``.inp`` deck into a :class:`Mesh` (units of the file)."""
    path = Path(path)
    deck = _parse(path)
    if not deck.node_ids:
        raise MeshError("no *NODE data found: not an Abaqus input deck?", file=str(path))
    gid = np.asarray(deck.node_ids, dtype=np.int64)
    _dup(gid, deck.node_where, "node", deck.asm_labels)
    sorter = np.argsort(gid, kind="stable")

    def index(ids, where, what):
        ids = np.asarray(ids, dtype=np.int64)
        pos = np.clip(np.searchsorted(gid, ids.ravel(), sorter=sorter), 0, len(gid) - 1)
        idx = sorter[pos]
        bad = np.flatnonzero(gid[idx] != ids.ravel())
        if bad.size:
            k = int(bad[0])
            w = where(k)
            i = int(ids.ravel()[k])
            if deck.has_assembly and deck.node_offset and i > deck.node_offset:
                label = i - deck.node_offset
                raise MeshError(
                    f"{what} refers to assembly-level node {label} (id {i}), which is not "
                    f"defined: in a deck with *ASSEMBLY a bare node label in the assembly and "
                    f"the steps is an assembly node; write {deck.instance_name or 'Instance'}."
                    f"{label} for node {label} of the part", file=w[0], line=w[1])
            raise MeshError(f"{what} refers to node {i}, which is not defined", file=w[0],
                            line=w[1])
        return idx.reshape(ids.shape)

    all_e = [(e, t, k) for t in deck.eids for k, e in enumerate(deck.eids[t])]
    _dup([a[0] for a in all_e], [deck.ewhere[t][k] for _, t, k in all_e], "element")
    where_e = {e: (t, k) for e, t, k in all_e}
    blocks, bi_of = [], {}
    for t in deck.eids:
        if t == "mass":
            continue
        nn = NODES[t]
        conn = index(deck.conn[t], lambda k, t=t, nn=nn: deck.ewhere[t][k // nn],
                     f"a {t} element")
        bi_of[t] = len(blocks)
        blocks.append([t, conn, np.asarray(deck.eids[t], dtype=np.int64)])

    def cells_of(name, f, ln, what):
        key = deck.set_key(deck.elsets, name or "")
        if key is None:
            raise MeshError(f"{what} refers to ELSET '{name}', which is not defined", file=f,
                            line=ln)
        out = defaultdict(list)
        for e in dict.fromkeys(deck.elsets[key]):   # a set: each element once (masses)
            if e not in where_e:
                raise MeshError(f"ELSET '{key}' lists element {e}, which is not defined",
                                file=f, line=ln)
            out[where_e[e][0]].append(where_e[e][1])
        return key, out

    cell_sets = {}
    for name in deck.elsets:
        _, members = cells_of(name, str(path), None, "set")
        members = {bi_of[t]: np.unique(v) for t, v in members.items() if t in bi_of}
        if members:
            cell_sets[name] = members
    node_sets = {name: index(ids, lambda k: (str(path), None), f"NSET '{name}'")
                 for name, ids in deck.nsets.items()}
    sections, orient, mat_ref = {}, {}, {}
    zoffset = {}
    for elset, props, mat, n1, f, ln in deck.sections:
        key, members = cells_of(elset, f, ln, "section")
        sec = dict(props)
        offset, nsm = sec.pop("offset", 0.0), sec.pop("nsm", 0.0)
        if mat:
            m = deck.materials.get(mat.upper())
            if m is None:
                raise MeshError(f"section refers to material '{mat}', which is not defined",
                                file=f, line=ln)
            if "E" not in m:
                raise MeshError(f"material '{mat}' has no *ELASTIC data", file=f, line=ln)
            sec.update(E=m["E"], nu=m["nu"], rho=m.get("rho", 0.0))
        if "composite" in sec:
            sec = _composite(deck, sec.pop("composite"), f, ln, nsm)
            for t in ("quad", "triangle"):
                for c in members.get(t, []):
                    mat_ref.setdefault(t, {})[c] = (1.0, 0.0, 0.0)   # Abaqus: global X
        elif nsm:                           # DENSITY=: mass per area, as PSHELL NSM
            if "rho" not in sec:
                raise MeshError("section DENSITY= (mass per area) needs MATERIAL= with a "
                                "*DENSITY", file=f, line=ln)
            sec["rho"] = sec["rho"] + nsm / sec["thickness"]
        for t in ("quad", "triangle") if "thickness" in sec else ():
            for c in members.get(t, []):    # OFFSET -> ZOFFS: mid-surface at node + z n
                zoffset.setdefault(t, {})[c] = -offset * sec["thickness"]
        sections[key] = sec
        if n1 is not None and "line" in members:
            orient.update({c: n1 for c in members["line"]})
    masses = _masses(deck, cells_of, index, where_e)
    links = _couplings(deck, index)
    more_links, interp = _couplings2(deck, index)
    spring_k = _springs(deck, cells_of, blocks)
    conn_data = _connectors(deck, cells_of, blocks, np.asarray(deck.coords, dtype=float),
                            index)
    out_blocks, n1_nodes = [], np.zeros(0, dtype=np.int64)
    for t, conn, eids in blocks:
        data = {}
        if t in ("spring", "spring1"):
            data["K"] = spring_k[t]
        if t == "connector":
            data = conn_data
        if any(zoffset.get(t, {}).values()):
            z = np.zeros(len(eids))
            for c, v in zoffset[t].items():
                z[c] = v
            data["zoffset"] = z
        if t in mat_ref:
            ref = np.full((len(eids), 3), np.nan)
            for c, v in mat_ref[t].items():
                ref[c] = v
            data["mat_ref"] = ref
        if t == "line":
            ori = np.full((len(eids), 3), np.nan)
            for c, v in orient.items():
                ori[c] = v
            with_node = [(k, deck.n1_node[e]) for k, e in enumerate(eids.tolist())
                         if e in deck.n1_node]
            if with_node:
                k, nodes = (np.array(v) for v in zip(*with_node, strict=True))
                g = index(nodes, lambda _: (str(path), None), "a beam's n1 node")
                ori[k] = np.asarray(deck.coords)[g] - np.asarray(deck.coords)[conn[k, 0]]
                n1_nodes = g
            data["orientation"] = ori
        out_blocks.append(CellBlock("spring" if t == "connector" else t, conn, eids,
                                    np.zeros(len(eids), np.int64), data))
    dof_sets, solution = _solution(deck, index)
    converted = {}
    if BC_SET in dof_sets:
        rows = dof_sets[BC_SET]
        converted["*BOUNDARY"] = (f"{len(rows)} DOF on {len(np.unique(rows[:, 0]))} nodes -> "
                                  f"DOF set {BC_SET} (held fixed, as a Nastran SPC = 1)")
    if deck.asm_labels:
        converted["assembly-level *NODE"] = (
            f"{len(deck.asm_labels)} node(s), label n -> id {deck.node_offset} + n (e.g. "
            f"{min(deck.asm_labels.values())} -> {min(deck.asm_labels)})")
    mesh = Mesh(points=np.asarray(deck.coords, dtype=float), blocks=tuple(out_blocks),
                node_ids=gid, node_sets=node_sets, cell_sets=cell_sets, point_masses=masses,
                rigid_links=links + more_links, sections=sections, source=str(path),
                interpolations=interp, dof_sets=dof_sets, solution=solution,
                info={"read": {t: len(e) for t, _, e in blocks}, "converted": converted,
                      "dropped": dict(deck.dropped), "materials": material_records(deck)})
    warn_dropped(path, deck, IGNORED_NOTES, SILENT_KEYWORDS)
    return drop_orientation_nodes(mesh, n1_nodes)
