"""Sections, boundary conditions, masses, couplings and springs of the Abaqus reader (see
:mod:`flexpipe.mesh.abaqus`): ``*SOLID SECTION``, ``*SHELL SECTION`` and ``*SHELL GENERAL
SECTION`` parameters (``OFFSET``, ``DENSITY``; the ones that do not change M and K; the
others refused), ``*BOUNDARY`` lines and types, the ``*FREQUENCY`` data line,
``*BEAM SECTION`` shapes (RECT, CIRC, PIPE, BOX, I, L) and
``*BEAM GENERAL SECTION``, MASS/ROTARYI elements, ``*KINEMATIC COUPLING``,
``*COUPLING`` with ``*KINEMATIC`` (rigid links) or ``*DISTRIBUTING`` (RBE3-type
interpolation, uniform weights or the node-based surface's weights), SPRING1/SPRING2
with ``*SPRING`` (global DOF), and the plies of a ``*SHELL SECTION, COMPOSITE`` with
their laminate section (:mod:`flexpipe.fem.laminate`)."""

from __future__ import annotations

import warnings
from collections import defaultdict

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.mesh._bulk import parse_real
from flexpipe.mesh.mesh import PointMass, RigidLink
from flexpipe.mesh.validate import MeshWarning


def values(file, line, text, what, *, count=None):
    vals = [v.strip() for v in text.split(",")]
    while vals and not vals[-1]:
        vals.pop()
    out = []
    for v in vals:
        x = parse_real(v) if v else 0.0
        if x is None:
            raise MeshError(f"{what}: '{v}' is not a number", file=file, line=line)
        out.append(x)
    if count is not None and len(out) < count:
        raise MeshError(f"{what}: expected {count} values, got {len(out)}", file=file, line=line)
    return out


def _shape_section(sec, v, where) -> dict:
    """Abaqus BOX / I / L dimensions -> section (local 1 = flexpipe y, 2 = z)."""
    from flexpipe.fem.sections import principal, standard_section

    try:
        if sec == "BOX":       # a (along 1), b (along 2), t1..t4 (uniform walls only)
            a, b, *t = (v + [0.0] * 6)[:6]
            if max(t) != min(t):
                raise ValueError("only equal wall thicknesses t1 = t2 = t3 = t4 are supported")
            s = standard_section("BOX", [b, a, t[0], t[0]])      # Nastran height = 1-axis
            Iz, Iy, I12 = s["I1"], s["I2"], 0.0
        elif sec == "I":       # l, h (along 2), b1, b2, t1, t2, t3
            _, h, b1, b2, t1, t2, t3 = (v + [0.0] * 7)[:7]
            s = standard_section("I", [h, b1, b2, t3, t1, t2])   # Nastran height = 2-axis
            Iz, Iy, I12 = s["I2"], s["I1"], 0.0
        else:                  # L: a (along 1), b (along 2), t1, t2
            a, b, t1, t2 = (v + [0.0] * 4)[:4]
            s = standard_section("L", [a, b, t1, t2])
            Iz, Iy, I12 = s["I2"], s["I1"], s["I12"]
    except ValueError as exc:
        raise MeshError(f"*BEAM SECTION SECTION={sec}: {exc}", file=where[0],
                        line=where[1]) from None
    Ip1, Ip2, theta = principal(Iz, Iy, I12)
    return {"A": s["A"], "Iz": Ip1, "Iy": Ip2, "J": s["J"], "theta": theta}


def _beam_section(params, lines, f, ln):
    rows = [(lf, lln, t) for lf, lln, t in lines.data()]
    if not rows:
        raise MeshError("beam section without data lines", file=f, line=ln)
    sec = params.get("SECTION", "GENERAL").upper()
    v = values(*rows[0], "beam section dimensions")
    if sec != "GENERAL" and (not v or not all(np.isfinite(x) and x > 0 for x in v[
            1 if sec == "I" else 0:])):
        raise MeshError(f"*BEAM SECTION SECTION={sec}: dimensions {v} must be finite and > 0",
                        file=rows[0][0], line=rows[0][1])
    props, mat = {}, None
    if sec == "GENERAL":
        A, I11, I12, I22, J = (v + [0.0] * 5)[:5]
        if I12:
            warnings.warn(MeshWarning(f"{f} line {ln}: product of inertia I12 ignored"),
                          stacklevel=4)
        props = {"A": A, "Iy": I11, "Iz": I22, "J": J}
        if len(rows) > 2:
            E, G = (values(*rows[2], "beam E, G") + [0.0, 0.0])[:2]
            rho = parse_real(params.get("DENSITY", "0")) or 0.0
            props.update(E=E, nu=E / (2 * G) - 1 if G else 0.3, rho=rho)
    elif sec == "RECT":
        a, b = (v + [0.0, 0.0])[:2]
        lo, hi = min(a, b), max(a, b)
        J = hi * lo**3 * (1 / 3 - 0.21 * lo / hi * (1 - lo**4 / (12 * hi**4)))
        props = {"A": a * b, "Iy": a * b**3 / 12, "Iz": b * a**3 / 12, "J": J}
    elif sec in ("CIRC", "PIPE"):
        r = v[0]
        ri = r - v[1] if sec == "PIPE" else 0.0
        if not 0 <= ri < r:
            raise MeshError(f"*BEAM SECTION PIPE: wall {v[1]} must be smaller than the radius "
                            f"{r}", file=rows[0][0], line=rows[0][1])
        I = np.pi * (r**4 - ri**4) / 4
        props = {"A": np.pi * (r**2 - ri**2), "Iy": I, "Iz": I, "J": 2 * I}
    elif sec in ("I", "L", "BOX"):
        props = _shape_section(sec, v, rows[0])
    else:
        raise MeshError(f"beam SECTION={sec} is not supported; use GENERAL, RECT, CIRC, PIPE, "
                        "BOX, I or L", file=f, line=ln)
    if sec != "GENERAL":
        mat = params.get("MATERIAL")
    n1 = values(*rows[1], "beam n1 direction")[:3] if len(rows) > 1 else None
    return props, mat, n1


def _masses(deck, cells_of, index, where_e):
    """Point masses: MASS and ROTARYI elements on the same node are combined into one."""
    acc: dict[int, list] = {}
    for kind, items in (("mass", deck.masses), ("inertia", deck.inertias)):
        for elset, value, f, ln in items:
            _, members = cells_of(elset, f, ln, f"*{kind.upper()}")
            for k in members.get("mass", []):
                node = int(index([deck.conn["mass"][k][0]], lambda _, f=f, ln=ln: (f, ln),
                                 "*MASS")[0])
                entry = acc.setdefault(node, [0.0, np.zeros((3, 3)), deck.eids["mass"][k]])
                if kind == "mass":
                    entry[0] += float(value)
                else:
                    entry[1] = entry[1] + value
    return tuple(PointMass(node, m, I, id=eid) for node, (m, I, eid) in acc.items())


def ref_node(deck, ref, index, what, f, ln) -> int:
    """Node index of a REF NODE= (a node label, or a node set holding one node, as
    Abaqus/CAE writes for a reference point)."""
    ids = deck.nodes_of(ref, what, f, ln)
    if len(ids) != 1:
        raise MeshError(f"{what}={ref}: the node set holds {len(ids)} nodes; valid: one node",
                        file=f, line=ln)
    return int(index(ids, lambda _, f=f, ln=ln: (f, ln), what)[0])


def _couplings(deck, index):
    links = []
    for ref, rows, f, ln in deck.couplings:
        master = ref_node(deck, ref, index, "*KINEMATIC COUPLING REF NODE", f, ln)
        by_dofs = defaultdict(list)
        for tok, first, last, lf, lln in rows:
            nodes = deck.nodes_of(tok, "*KINEMATIC COUPLING", lf, lln)
            dofs = "".join(str(d) for d in range(first, last + 1))
            by_dofs[dofs].extend(nodes)
        node_dofs = defaultdict(str)
        for dofs, nodes in by_dofs.items():
            for n in nodes:
                node_dofs[n] = "".join(sorted(set(node_dofs[n] + dofs)))
        groups = defaultdict(list)
        for n, dofs in node_dofs.items():
            groups[dofs].append(n)
        for dofs, nodes in groups.items():
            slaves = index(nodes, lambda _, f=f, ln=ln: (f, ln), "*KINEMATIC COUPLING")
            links.append(RigidLink(master, slaves, dofs, 0))
    return tuple(links)


def _surface_nodes(deck, name, f, ln, index):
    rows = deck.surfaces.get(name.upper())
    if rows is None:
        raise MeshError(f"*COUPLING refers to SURFACE '{name}', which is not defined (as "
                        "*SURFACE, TYPE=NODE before it)", file=f, line=ln)
    ids, weights = [], []
    for lf, lln, t, ctx in rows:
        tok = [x.strip() for x in t.split(",")]
        w = parse_real(tok[1]) if len(tok) > 1 and tok[1] else 1.0
        if w is None or not (np.isfinite(w) and w > 0):
            raise MeshError(f"*SURFACE {name}: weight '{tok[1]}'; valid: > 0", file=lf,
                            line=lln)
        nodes = deck.nodes_of(deck.node_ref(tok[0], ctx), f"*SURFACE {name}", lf, lln)
        ids += list(nodes)
        weights += [w] * len(nodes)
    idx = index(ids, lambda _, f=f, ln=ln: (f, ln), f"*SURFACE {name}")
    return idx, np.array(weights)


def _couplings2(deck, index):
    """*COUPLING + *KINEMATIC (rigid links) and + *DISTRIBUTING (RBE3-type constraints)."""
    from flexpipe.mesh.mesh import Interpolation

    links, interp = [], []
    for kind, ref, surf, f, ln, radius, dofs in deck.couplings2:
        r = ref_node(deck, ref, index, "*COUPLING REF NODE", f, ln)
        nodes, w = _surface_nodes(deck, surf, f, ln, index)
        nodes, first = np.unique(nodes, return_index=True)
        w = w[first]
        if radius is not None:          # INFLUENCE RADIUS: the surface nodes within it
            X = np.asarray(deck.coords, dtype=float)
            near = np.linalg.norm(X[nodes] - X[r], axis=1) <= radius
            if not near.any():
                raise MeshError(f"*COUPLING INFLUENCE RADIUS={radius:g}: none of the "
                                f"{len(nodes)} nodes of SURFACE {surf} is within it of the "
                                "reference node", file=f, line=ln)
            nodes, w = nodes[near], w[near]
        if r in set(nodes.tolist()):
            raise MeshError("*COUPLING: the reference node is also a surface node", file=f,
                            line=ln)
        if kind == "KINEMATIC":
            links.append(RigidLink(r, nodes, dofs, 0))
        else:
            interp.append(Interpolation(r, dofs, nodes, w, ("123",) * len(nodes), 0))
    return tuple(links), tuple(interp)


def _springs(deck, cells_of, blocks):
    """Stiffness matrices of SPRING1/SPRING2 elements from their *SPRING sections."""
    from flexpipe.fem import spring

    out = {}
    for t, _conn, eids in blocks:
        if t in ("spring", "spring1"):
            out[t] = np.full((len(eids),) + ((12, 12) if t == "spring" else (6, 6)), np.nan)
    for elset, rows, f, ln in deck.springs:
        key, members = cells_of(elset, f, ln, "*SPRING")
        if len(rows) < 2:
            raise MeshError("*SPRING needs a DOF line and a stiffness line", file=f, line=ln)
        d = [int(x) for x in values(*rows[0], "*SPRING DOF")]
        k = values(*rows[1], "*SPRING stiffness", count=1)[0]
        if not np.isfinite(k):
            raise MeshError(f"*SPRING stiffness {k}; valid: finite", file=rows[1][0],
                            line=rows[1][1])
        for t in ("spring", "spring1"):
            cells = members.get(t, [])
            if not cells:
                continue
            need = 2 if t == "spring" else 1
            if len(d) < need or not all(1 <= x <= 6 for x in d[:need]):
                raise MeshError(f"*SPRING ELSET={key}: DOF line {d}; valid: {need} DOF in 1..6",
                                file=rows[0][0], line=rows[0][1])
            eye = np.broadcast_to(np.eye(3), (1, 3, 3))
            ea = spring.unit_dof(eye, np.array([d[0] - 1]))
            eb = spring.unit_dof(eye, np.array([d[1] - 1])) if need == 2 else None
            out[t][cells] = spring.scalar(np.array([k]), ea, eb)[0]
    for t, K in out.items():
        bad = np.flatnonzero(np.isnan(K).any(axis=(1, 2)))
        if bad.size:
            eids = dict((bt, e) for bt, _, e in blocks)[t]
            raise MeshError(f"{len(bad)} {t.upper()} element(s) have no *SPRING section, e.g. "
                            f"{eids[bad[:10]].tolist()}", file=str(deck.path))
    return out


#: connection types and the components they make available (1-3 translations, 4-6 rotations)
CONNECTION = {"BUSHING": "123456", "CARTESIAN": "123", "CARDAN": "456", "ROTATION": "456",
              "EULER": "456"}


def _connectors(deck, cells_of, blocks, X, index):
    """Block data of CONN3D2 connectors: linear uncoupled elasticity and damping along the
    global axes (BUSHING, or CARTESIAN with CARDAN/ROTATION/EULER), between coincident
    nodes; stored like a Nastran CBUSH (``K``, ``B``, ``k6``, ``b6``, ``frame``, ``s``)."""
    from flexpipe.fem import spring

    conn_block = next((b for b in blocks if b[0] == "connector"), None)
    if conn_block is None:
        return {}
    _, conn, eids = conn_block
    n = len(eids)
    k6 = np.full((n, 6), np.nan)
    b6 = np.zeros((n, 6))
    for elset, types, behavior, f, ln in deck.connectors:
        bad = [t for t in types if t not in CONNECTION]
        if bad or not types:
            raise MeshError(f"*CONNECTOR SECTION connection type {bad or types}; supported: "
                            f"{', '.join(CONNECTION)}", file=f, line=ln)
        avail = "".join(sorted(set("".join(CONNECTION[t] for t in types))))
        beh = deck.behaviors.get(behavior)
        if beh is None:
            raise MeshError(f"*CONNECTOR SECTION refers to BEHAVIOR '{behavior}', which is not "
                            "defined (a *CONNECTOR BEHAVIOR with that NAME)", file=f, line=ln)
        used = set(beh["K"]) | set(beh["B"])
        if any(str(c) not in avail for c in used):
            raise MeshError(f"*CONNECTOR BEHAVIOR {behavior} gives components {sorted(used)}, "
                            f"but {'+'.join(types)} makes only {avail} available", file=f,
                            line=ln)
        _, members = cells_of(elset, f, ln, "*CONNECTOR SECTION")
        cells = members.get("connector", [])
        k6[cells] = [beh["K"].get(c, 0.0) for c in range(1, 7)]
        b6[cells] = [beh["B"].get(c, 0.0) for c in range(1, 7)]
    missing = np.flatnonzero(np.isnan(k6).any(axis=1))
    if missing.size:
        raise MeshError(f"{missing.size} CONN3D2 element(s) have no *CONNECTOR SECTION, e.g. "
                        f"{eids[missing[:10]].tolist()}", file=str(deck.path))
    XA, XB = X[conn[:, 0]], X[conn[:, 1]]
    size = max(float(np.ptp(X, axis=0).max()), 1e-300)
    apart = np.flatnonzero(np.linalg.norm(XB - XA, axis=1) > 1e-9 * size)
    if apart.size:
        raise MeshError(f"{apart.size} CONN3D2 connector(s) join nodes that are apart, e.g. "
                        f"element {int(eids[apart[0]])}; only coincident nodes are supported",
                        file=str(deck.path))
    R = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
    s = np.full(n, 0.5)
    return {"K": spring.bush(XA, XB, R, k6, s), "B": spring.bush(XA, XB, R, b6, s), "k6": k6,
            "b6": b6, "frame": R, "s": s}


def _plies(rows, p, f, ln) -> list:
    """Plies (thickness, material, angle) of a composite *SHELL SECTION."""
    plies = []
    for lf, lln, t in rows:
        tok = [x.strip() for x in t.split(",")]
        if len(tok) < 3 or not tok[2]:
            raise MeshError("*SHELL SECTION, COMPOSITE ply line needs 'thickness, points, "
                            "material[, angle]'", file=lf, line=lln)
        th = parse_real(tok[0])
        ang = parse_real(tok[3]) if len(tok) > 3 and tok[3] else 0.0
        if ang is None:
            raise MeshError(f"ply orientation '{tok[3]}' is not an angle; named *ORIENTATIONs "
                            "are not supported", file=lf, line=lln)
        if th is None or not (np.isfinite(th) and th > 0) or not np.isfinite(ang):
            raise MeshError(f"ply thickness '{tok[0]}'; valid: > 0", file=lf, line=lln)
        plies.append((th, tok[2], ang, lf, lln))
    if not plies:
        raise MeshError("*SHELL SECTION, COMPOSITE has no ply lines", file=f, line=ln)
    if "SYMMETRIC" in p:
        plies = plies + plies[::-1]
    return plies


def _composite(deck, plies, f, ln, nsm: float = 0.0) -> dict:
    """Section of a composite shell by classical lamination (see flexpipe.fem.laminate)."""
    from flexpipe.fem.laminate import ply_q
    from flexpipe.fem.laminate import section as lam_section

    out = []
    for th, name, ang, lf, lln in plies:
        m = deck.materials.get(name.upper())
        if m is None or not ("lamina" in m or "E" in m):
            raise MeshError(f"ply material '{name}' is not defined (with *ELASTIC)", file=lf,
                            line=lln)
        if "lamina" in m:
            E1, E2, nu12, G12, G13, _ = m["lamina"]
            Q, Gz = ply_q(E1, E2, nu12, G12), G13
        else:
            G = m["E"] / (2 * (1 + m["nu"]))
            Q, Gz = ply_q(m["E"], m["E"], m["nu"], G), G
        out.append((Q, th, ang, Gz, m.get("rho", 0.0)))
    try:
        return lam_section(out, nsm)
    except ValueError as exc:
        raise MeshError(f"*SHELL SECTION, COMPOSITE: {exc}", file=f, line=ln) from None


#: section parameters: read, accepted because they do not change M and K of a linear
#: elastic section (integration rule, hourglass controls, thickness-change and thermal
#: options, CAE layup name, material axes of an isotropic section), or refused
_SECTION_READ = {"SOLID SECTION": ("ELSET", "MATERIAL"),
                 "SHELL SECTION": ("ELSET", "MATERIAL", "COMPOSITE", "SYMMETRIC", "OFFSET",
                                   "DENSITY"),
                 "SHELL GENERAL SECTION": ("ELSET", "MATERIAL", "COMPOSITE", "SYMMETRIC",
                                           "OFFSET", "DENSITY")}
_SECTION_HARMLESS = {"SOLID SECTION": ("ORIENTATION", "CONTROLS"),
                     "SHELL SECTION": ("ORIENTATION", "CONTROLS", "SECTION INTEGRATION",
                                       "POISSON", "TEMPERATURE", "THICKNESS MODULUS", "LAYUP"),
                     "SHELL GENERAL SECTION": ("ORIENTATION", "CONTROLS", "POISSON",
                                               "LAYUP")}


def _section_props(kw, p, rows, f, ln) -> dict:
    """Section data of ``*SOLID SECTION``, ``*SHELL SECTION`` or ``*SHELL GENERAL SECTION``
    (isotropic MATERIAL or COMPOSITE): ``thickness``, ``composite`` plies, ``offset``
    (OFFSET, a fraction of the thickness) and ``nsm`` (DENSITY, mass per area).  Other
    parameters are accepted when they do not change M and K, else refused."""
    known = _SECTION_READ[kw] + _SECTION_HARMLESS[kw]
    bad = [k for k in p if k not in known]
    if bad:
        hint = {"NODAL THICKNESS": " (thickness from *NODAL THICKNESS: give the thickness on "
                                   "the data line instead)",
                "SHELL THICKNESS": " (thickness from a distribution: give it on the data "
                                   "line instead)",
                "COMPOSITE": " (layered solids: use homogeneous solid sections)"}.get(bad[0], "")
        raise MeshError(f"*{kw} parameter {bad[0]} is not supported{hint}; valid: "
                        f"{', '.join(_SECTION_READ[kw])} (and, not changing M and K, "
                        f"{', '.join(_SECTION_HARMLESS[kw])})", file=f, line=ln)
    props = {}
    if kw == "SOLID SECTION":
        return props
    composite = "COMPOSITE" in p
    if composite and "ORIENTATION" in p:
        raise MeshError(f"*{kw}, COMPOSITE with ORIENTATION={p['ORIENTATION']} is not "
                        "supported (ply angles are taken from the global X axis projected on "
                        "the shell)", file=f, line=ln)
    if composite and "MATERIAL" in p:
        raise MeshError(f"*{kw}: COMPOSITE and MATERIAL= exclude each other (the plies name "
                        "their materials)", file=f, line=ln)
    if "SYMMETRIC" in p and not composite:
        raise MeshError(f"*{kw}: SYMMETRIC applies to a COMPOSITE section only", file=f,
                        line=ln)
    if kw == "SHELL GENERAL SECTION" and not composite and "MATERIAL" not in p:
        raise MeshError("*SHELL GENERAL SECTION without MATERIAL= or COMPOSITE (stiffness "
                        "matrices on the data lines, or USER) is not supported; give "
                        "MATERIAL=<isotropic material> and the thickness, as *SHELL SECTION",
                        file=f, line=ln)
    if composite:
        props["composite"] = _plies(rows, p, f, ln)
    else:
        if not rows:
            raise MeshError(f"*{kw} needs a data line with the thickness", file=f, line=ln)
        if kw == "SHELL GENERAL SECTION" and len(rows) > 1:
            raise MeshError("*SHELL GENERAL SECTION with MATERIAL= has one data line (the "
                            "thickness)", file=rows[1][0], line=rows[1][1])
        props["thickness"] = values(*rows[0], "shell thickness", count=1)[0]
        if not (np.isfinite(props["thickness"]) and props["thickness"] > 0):
            raise MeshError(f"*{kw} thickness {props['thickness']}; valid: > 0",
                            file=rows[0][0], line=rows[0][1])
    if "OFFSET" in p:
        v = p["OFFSET"].upper()
        off = {"SPOS": 0.5, "SNEG": -0.5}.get(v, parse_real(v) if v else None)
        if off is None or not np.isfinite(off):
            raise MeshError(f"*{kw} OFFSET={p['OFFSET']}; valid: SPOS, SNEG or a number (the "
                            "reference surface's distance from the mid-surface, a fraction "
                            "of the thickness along the normal); distributions are not "
                            "supported", file=f, line=ln)
        if off:
            props["offset"] = off
    if "DENSITY" in p:
        nsm = parse_real(p["DENSITY"]) if p["DENSITY"] else None
        if nsm is None or not (np.isfinite(nsm) and nsm >= 0):
            raise MeshError(f"*{kw} DENSITY={p['DENSITY']}; valid: a mass per unit area >= 0",
                            file=f, line=ln)
        if nsm:
            props["nsm"] = nsm
    return props


def material_records(deck) -> dict:
    """``{"*MATERIAL <name>": (E, RHO, file, line)}`` of the materials the sections use
    (a lamina: E1), file units, for the E / RHO plausibility check
    (:func:`flexpipe.mesh.units.check_wave_speeds`, as the Nastran reader's MAT1 cards)."""
    used = []
    for _, props, mat, *_ in deck.sections:
        used += [mat] if mat else []
        used += [ply[1] for ply in props.get("composite", ())]
    out = {}
    for name in dict.fromkeys(n.upper() for n in used):
        m = deck.materials.get(name, {})
        E = m["lamina"][0] if "lamina" in m else m.get("E")
        f, ln, label = m.get("at", (None, None, name))
        if E and m.get("rho"):
            out[f"*MATERIAL {label}"] = (float(E), float(m["rho"]), f, ln)
    return out
