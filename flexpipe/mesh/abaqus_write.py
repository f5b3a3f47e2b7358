"""Abaqus ``.inp`` writer (the keywords :mod:`flexpipe.mesh.abaqus` reads).

Nodes, elements (C3D4, C3D10, C3D8, S3, S4, B31), every node and cell set as
``*NSET``/``*ELSET``, sections with their materials, point masses (``MASS``/``ROTARYI``
elements), rigid links (``*KINEMATIC COUPLING``), interpolations (``*DISTRIBUTING``
coupling), and the solution's constraint set and eigenvalue set-up (``*BOUNDARY``, a
``*STEP`` with ``*FREQUENCY``).  Reals are written with 17
significant digits, so a round trip is exact.
"""

from __future__ import annotations

import re
import warnings

import numpy as np

from flexpipe.mesh._common import cell_section_index, default_orientation, unique_ids
from flexpipe.mesh.mesh import Mesh
from flexpipe.mesh.validate import MeshWarning

ELEMENT_OF = {"tetra": "C3D4", "tetra10": "C3D10", "hexahedron": "C3D8", "triangle": "S3",
              "quad": "S4", "line": "B31", "wedge": "C3D6", "pyramid": "C3D5"}
KIND = {"tetra": "solid", "tetra10": "solid", "hexahedron": "solid", "triangle": "shell",
        "quad": "shell", "line": "beam", "wedge": "solid", "pyramid": "solid"}


def _q(name: str) -> str:
    """A set/material name as Abaqus wants it (quoted unless a plain word)."""
    return name if re.fullmatch(r"[A-Za-z_][\w\-]*", name) else f'"{name}"'


def _r(x) -> str:
    return repr(float(x))


def _id_lines(ids, per=16) -> list[str]:
    ids = [str(int(i)) for i in ids]
    return [", ".join(ids[k:k + per]) for k in range(0, len(ids), per)]


def _section_groups(mesh: Mesh, eids_of_block):
    """(elset name, kind, section name, element ids, n1) for every distinct section use."""
    sec_idx = cell_section_index(mesh)
    names = list(mesh.sections)
    groups = []
    for s, name in enumerate(names):
        parts = []
        for bi, b in enumerate(mesh.blocks):
            if b.type not in KIND:
                continue
            cells = np.flatnonzero(sec_idx[bi] == s)
            if cells.size == 0:
                continue
            if b.type == "line":
                ori = np.asarray(b.data.get("orientation", np.full((len(b), 3), np.nan)), float)
                ori = ori[cells]
                miss = ~np.isfinite(ori).all(axis=1)
                ori[miss] = default_orientation(mesh.points[b.cells[cells[miss]]])
                uniq, inv = np.unique(np.round(ori, 15), axis=0, return_inverse=True)
                for k in range(len(uniq)):
                    parts.append(("beam", eids_of_block[bi][cells[inv.ravel() == k]],
                                  ori[inv.ravel() == k][0]))
            else:
                parts.append((KIND[b.type], eids_of_block[bi][cells], None))
        kinds = {}
        for kind, e, n1 in parts:
            kinds.setdefault(kind, []).append((e, n1))
        whole = sum(len(mesh.cell_sets[name].get(bi, ())) for bi in range(len(mesh.blocks)))
        for kind, items in kinds.items():
            for j, (e, n1) in enumerate(items):
                single = len(kinds) == 1 and len(items) == 1 and len(e) == whole
                groups.append((name if single else f"{name}_{kind}{j + 1}", kind, name, e, n1))
    return groups


def _not_written(mesh: Mesh) -> list[str]:
    """Model data the .inp writer cannot carry (written to .bdf only)."""
    lost = set()
    for sec in mesh.sections.values():
        if float(sec.get("bending", 1.0)) != 1.0:
            lost.add("PSHELL bending ratio")
        if sec.get("k1") or sec.get("k2"):
            lost.add("beam shear factors (Timoshenko)")
        if sec.get("theta"):
            lost.add("beam principal-axis angle")
    for b in mesh.blocks:
        for key, what in (("zoffset", "shell offsets ZOFFS"), ("offset_a", "beam offsets"),
                          ("release", "beam pin flags"), ("mat_theta", "material angles")):
            if key in b.data and np.any(np.nan_to_num(b.data[key])):
                lost.add(what)
    return sorted(lost)


def abaqus_text(mesh: Mesh) -> str:
    """Abaqus input text of ``mesh``."""
    lost = _not_written(mesh)
    if lost:
        warnings.warn(MeshWarning(f"not written to .inp (write .bdf to keep them): "
                                  f"{', '.join(lost)}"), stacklevel=3)
    out = ["*HEADING", f"written by flexpipe from {mesh.source or 'an in-memory mesh'}"]
    nid = unique_ids(mesh.node_ids)
    out.append("*NODE")
    out += [f"{int(nid[i])}, {_r(x)}, {_r(y)}, {_r(z)}" for i, (x, y, z) in enumerate(mesh.points)]
    all_ids = unique_ids(np.concatenate([b.ids for b in mesh.blocks] + [np.zeros(0, np.int64)]))
    eids_of_block, start = [], 0
    for b in mesh.blocks:
        eids_of_block.append(all_ids[start:start + len(b)])
        start += len(b)
    for bi, b in enumerate(mesh.blocks):
        if b.type == "vertex":
            warnings.warn(MeshWarning("vertex cells are not written to Abaqus"), stacklevel=3)
            continue
        out.append(f"*ELEMENT, TYPE={ELEMENT_OF[b.type]}")
        conn = nid[b.cells]
        out += [", ".join(str(int(v)) for v in (eids_of_block[bi][k], *conn[k]))
                for k in range(len(b))]
    next_eid = int(all_ids.max(initial=0)) + 1
    for name, idx in mesh.node_sets.items():
        out.append(f"*NSET, NSET={_q(name)}")
        out += _id_lines(nid[idx])
    for name, members in mesh.cell_sets.items():
        ids = np.concatenate([eids_of_block[bi][c] for bi, c in members.items()
                              if mesh.blocks[bi].type != "vertex"] + [np.zeros(0, np.int64)])
        out.append(f"*ELSET, ELSET={_q(name)}")
        out += _id_lines(ids)
    materials = {}
    for elset, kind, name, e, n1 in _section_groups(mesh, eids_of_block):
        sec = mesh.sections[name]
        if elset != name:
            out.append(f"*ELSET, ELSET={_q(elset)}")
            out += _id_lines(e)
        mat = None
        if all(k in sec for k in ("E", "nu", "rho")):
            key = (float(sec["E"]), float(sec["nu"]), float(sec["rho"]))
            mat = materials.setdefault(key, f"MAT{len(materials) + 1}")
        mpar = f", MATERIAL={mat}" if mat else ""
        if kind == "solid":
            out.append(f"*SOLID SECTION, ELSET={_q(elset)}{mpar}")
        elif kind == "shell" and "A11" in sec:
            from flexpipe.errors import InputError

            raise InputError(f"section {name} is a laminate (PCOMP); the .inp writer has no "
                             "composite section - keep the original deck",
                             file=mesh.source or None)
        elif kind == "shell" and "thickness" in sec:
            out.append(f"*SHELL SECTION, ELSET={_q(elset)}{mpar}")
            out.append(_r(sec["thickness"]))
        elif kind == "beam" and all(k in sec for k in ("A", "Iy", "Iz", "J")):
            dens = f", DENSITY={_r(sec['rho'])}" if mat else ""
            out.append(f"*BEAM GENERAL SECTION, ELSET={_q(elset)}, SECTION=GENERAL{dens}")
            out.append(f"{_r(sec['A'])}, {_r(sec['Iy'])}, 0., {_r(sec['Iz'])}, {_r(sec['J'])}")
            out.append(", ".join(_r(v) for v in n1))
            if mat:
                E, nu = float(sec["E"]), float(sec["nu"])
                out.append(f"{_r(E)}, {_r(E / (2 * (1 + nu)))}")
    for (E, nu, rho), name in materials.items():
        out += [f"*MATERIAL, NAME={name}", "*ELASTIC", f"{_r(E)}, {_r(nu)}", "*DENSITY", _r(rho)]
    for pm in mesh.point_masses:
        if pm.matrix is not None:
            from flexpipe.errors import InputError

            raise InputError(f"point mass {pm.id} is a full 6x6 mass matrix (CONM1), which "
                             "Abaqus MASS/ROTARYI elements cannot hold; write .bdf instead")
        if np.any(np.asarray(pm.offset) != 0):
            warnings.warn(MeshWarning(f"point mass {pm.id}: Abaqus MASS elements have no "
                                      "offset; the offset is not written"), stacklevel=3)
        eid = next_eid
        next_eid += 2
        out += [f"*ELEMENT, TYPE=MASS, ELSET=PM{eid}", f"{eid}, {int(nid[pm.node])}",
                f"*MASS, ELSET=PM{eid}", _r(pm.mass)]
        I = np.asarray(pm.inertia, dtype=float)
        if np.any(I):
            out += [f"*ELEMENT, TYPE=ROTARYI, ELSET=PI{eid + 1}",
                    f"{eid + 1}, {int(nid[pm.node])}", f"*ROTARY INERTIA, ELSET=PI{eid + 1}",
                    ", ".join(_r(v) for v in (I[0, 0], I[1, 1], I[2, 2], I[0, 1], I[0, 2],
                                              I[1, 2]))]
    for lk in mesh.rigid_links:
        out.append(f"*KINEMATIC COUPLING, REF NODE={int(nid[lk.master])}")
        runs = _dof_runs(int(c) for c in lk.dofs)
        for s in np.asarray(lk.slaves):
            out += [f"{int(nid[s])}, {a}, {b}" for a, b in runs]
    for k, it in enumerate(mesh.interpolations):       # RBE3: distributing coupling
        if any(c != "123" for c in (it.node_dofs or ("123",))):
            from flexpipe.errors import InputError

            raise InputError(f"RBE3 {it.id} ties independent components other than 123, "
                             "which *DISTRIBUTING coupling cannot express; write .bdf")
        name = f"RBE3_{k + 1}"
        out.append(f"*SURFACE, TYPE=NODE, NAME={name}")
        out += [f"{int(nid[n])}, {_r(w)}" for n, w in zip(np.asarray(it.nodes),
                                                          np.asarray(it.weights), strict=True)]
        out += [f"*COUPLING, REF NODE={int(nid[it.ref])}, SURFACE={name}", "*DISTRIBUTING"]
        out += [f"{c}, {c}" for c in sorted(it.ref_dofs)]
    out += _history(mesh, nid)
    return "\n".join(out) + "\n"


def _dof_runs(comps) -> list[tuple[int, int]]:
    """Runs ``(first, last)`` of consecutive 1-based components."""
    comps = sorted(comps)
    runs, s0 = [], comps[0]
    for a, b in zip(comps, comps[1:] + [None], strict=True):
        if b != a + 1:
            runs.append((s0, a))
            s0 = b
    return runs


def _history(mesh: Mesh, nid) -> list[str]:
    """``*BOUNDARY`` for the constraint set the solution uses (``solution["spc"]``, as
    Nastran's ``SPC =``) and a ``*STEP`` with ``*FREQUENCY`` for its number of modes and
    frequency range (as an EIGRL): what :mod:`flexpipe.mesh._abaqus_steps` reads back as
    the same DOF set and set-up.  What Abaqus cannot hold is named in a warning."""
    sol = mesh.solution
    if sol.get("spc_directions") is not None:
        from flexpipe.errors import InputError

        raise InputError("the mesh carries SPCs in rotated displacement systems (CD), which "
                         "the writer does not reproduce; keep the original deck",
                         file=mesh.source or None)
    out, lost = [], []
    used = sol.get("spc")
    if used is not None and used not in mesh.dof_sets:
        lost.append(f"the constraint set {used!r} the solution names (not in the mesh)")
    unused = sorted(k for k in mesh.dof_sets if k != used)
    if unused:
        lost.append(f"constraint set(s) {', '.join(unused)}, which the solution does not use "
                    "(an .inp holds the one set in effect)")
    if used in mesh.dof_sets and len(mesh.dof_sets[used]):
        by_node: dict = {}
        for n, c in np.asarray(mesh.dof_sets[used], dtype=np.int64).reshape(-1, 2):
            by_node.setdefault(int(n), set()).add(int(c) + 1)
        out.append("*BOUNDARY")
        for n in sorted(by_node):
            out += [f"{int(nid[n])}, {a}, {b}" for a, b in _dof_runs(by_node[n])]
    n, f_min, f_max = (sol.get(k) for k in ("n_modes", "f_min", "f_max"))
    if n is not None or f_max is not None:
        fields = ["" if v is None else (str(int(v)) if k == 0 else _r(v))
                  for k, v in enumerate((n, f_min, f_max))]
        out += ["*STEP, NAME=modes", "*FREQUENCY, EIGENSOLVER=LANCZOS", ", ".join(fields),
                "*END STEP"]
    elif f_min is not None:
        lost.append(f"the lower frequency bound {f_min:g} Hz without a number of modes or an "
                    "upper bound (*FREQUENCY needs one of them)")
    lumped = sol.get("lumped_mass")
    if lumped or (lumped is None and sol.get("sol") is not None):
        lost.append("the lumped mass of the Nastran solution (PARAM,COUPMASS,-1 or its "
                    "default; flexpipe reads an .inp with the consistent mass)")
    if lost:
        warnings.warn(MeshWarning(f"not written to .inp (write .bdf to keep them): "
                                  f"{'; '.join(lost)}"), stacklevel=4)
    return out
