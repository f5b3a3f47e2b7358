"""Nastran cards for springs, RBE3, SPC sets and the solution set-up (writer side).

Springs are written back as the cards they came from: a rank-one matrix on one basic
component per node as ``CELAS2``; a CBUSH (the reader keeps its ``k6``/``b6`` values,
element axes ``frame`` and spring point ``s`` in ``block.data``) as ``CBUSH`` + ``PBUSH``
with a ``CORD2R`` holding its axes.  Anything else has no Nastran card flexpipe writes
and raises :class:`~flexpipe.errors.InputError`.
"""

from __future__ import annotations

import warnings

import numpy as np

from flexpipe.errors import InputError

#: first id of the coordinate systems / properties written for CBUSH springs
BUSH_ID0 = 900_000


def _card(name, values):
    from flexpipe.mesh.nastran_write import card

    return card(name, values)


def _celas(K: np.ndarray, nn: int):
    """(k, [(node slot, component), ...]) when K = k g g^T on basic components, else None."""
    d = np.diag(K)
    nz = np.flatnonzero(d)
    if len(nz) == 0 or len(nz) > nn or len({int(i) // 6 for i in nz}) != len(nz):
        return None
    k = float(d[nz[0]])
    g = np.zeros(len(d))
    g[nz[0]] = 1.0
    if len(nz) == 2:
        g[nz[1]] = np.sign(K[nz[0], nz[1]]) * np.sign(k) if K[nz[0], nz[1]] else 0.0
    if not np.allclose(K, k * np.outer(g, g), rtol=1e-13, atol=1e-13 * abs(k)):
        return None
    return k, [(int(i) // 6, int(i) % 6 + 1, g[i]) for i in nz]


def spring_cards(block, eids, nid, source) -> list[str]:
    """CELAS2 / CBUSH (+ PBUSH, CORD2R) cards of a ``spring`` or ``spring1`` block."""
    out = []
    K = np.asarray(block.data["K"], dtype=float)
    k6 = block.data.get("k6")
    nn = 2 if block.type == "spring" else 1
    for i in range(len(block)):
        eid = int(eids[i])
        nodes = [int(nid[n]) for n in block.cells[i]]
        if k6 is not None and np.isfinite(k6[i]).all():
            cid = pid = BUSH_ID0 + eid
            R = np.asarray(block.data["frame"][i], dtype=float)
            out.append(_card("CORD2R", [cid, 0, 0.0, 0.0, 0.0, *map(float, R[2]),
                                        *map(float, R[0])]))
            out.append(_card("PBUSH", [pid, "K", *map(float, k6[i]), None, "B",
                                       *map(float, block.data["b6"][i])]))
            out.append(_card("CBUSH", [eid, pid, *nodes] + [None] * (2 - nn) + [None] * 3
                             + [cid, float(block.data["s"][i])]))
            continue
        if "B" in block.data and np.any(block.data["B"][i]):
            raise InputError(f"spring {eid} carries damping without CBUSH data; it cannot be "
                             "written as a Nastran card", file=source or None)
        cel = _celas(K[i], nn)
        if cel is None or any(sgn < 0 for _, _, sgn in cel[1][:1]):
            raise InputError(f"spring {eid}: its stiffness matrix is not a scalar spring on "
                             "basic components and not a CBUSH; it cannot be written as a "
                             "Nastran card", file=source or None)
        k, comps = cel
        if len(comps) == 2 and comps[1][2] < 0:
            fields = [nodes[comps[0][0]], comps[0][1], nodes[comps[1][0]], comps[1][1]]
        elif len(comps) == 1:
            fields = [nodes[comps[0][0]], comps[0][1]]
        else:
            raise InputError(f"spring {eid} couples components with equal sign; it cannot be "
                             "written as CELAS2", file=source or None)
        out.append(_card("CELAS2", [eid, float(k), *fields]))
    return out


def constraint_cards(mesh, nid, next_eid: int) -> list[str]:
    """RBE3, SPC1, SET1 (node sets named ``SET<n>``) and EIGRL cards."""
    if mesh.solution.get("spc_directions") is not None:
        raise InputError("the mesh carries SPCs in rotated displacement systems (CD), which "
                         "the writer does not reproduce; keep the original deck",
                         file=mesh.source or None)
    out = []
    for k, it in enumerate(mesh.interpolations):
        groups = {}
        for n, w, c in zip(np.asarray(it.nodes), np.asarray(it.weights, dtype=float),
                           it.node_dofs or ("123",) * len(it.nodes), strict=True):
            groups.setdefault((float(w), c), []).append(int(nid[n]))
        fields = [next_eid + k, None, int(nid[it.ref]), it.ref_dofs]
        for (w, c), nodes in groups.items():
            fields += [w, c, *nodes]
        out.append(_card("RBE3", fields))
    for name, rows in mesh.dof_sets.items():
        if not name.startswith("SPC") or not name[3:].isdigit():
            continue
        rows = np.asarray(rows, dtype=np.int64).reshape(-1, 2)
        by_node: dict = {}
        for n, c in rows:
            by_node.setdefault(int(n), set()).add(int(c) + 1)
        by_comp: dict = {}
        for n, cs in by_node.items():
            by_comp.setdefault("".join(map(str, sorted(cs))), []).append(int(nid[n]))
        for comps, nodes in by_comp.items():
            out.append(_card("SPC1", [int(name[3:]), comps, *sorted(nodes)]))
    for name, nodes in mesh.node_sets.items():
        if name.startswith("SET") and name[3:].isdigit():
            out.append(_card("SET1", [int(name[3:]), *map(int, nid[np.asarray(nodes)])]))
    sol = mesh.solution
    if any(sol.get(k) is not None for k in ("n_modes", "f_min", "f_max")):
        out.append(_card("EIGRL", [1, sol.get("f_min"), sol.get("f_max"),
                                   sol.get("n_modes")]))
    if sol.get("lumped_mass") is not None:      # PARAM, COUPMASS of the source deck
        out.append(_card("PARAM", ["COUPMASS", -1 if sol["lumped_mass"] else 1]))
    return out


def header(mesh) -> tuple[str, str]:
    """Executive/case control before the bulk data and the closing line, or ('', '')."""
    sol = mesh.solution
    lines = []
    spc = str(sol.get("spc") or "")
    if spc.startswith("SPC") and spc[3:].isdigit():  # the sets the bulk data writes
        lines.append(f"SPC = {spc[3:]}")
    elif spc:
        warnings.warn(f"the constraint set {spc!r} has no Nastran SPC id (SPC<n>); it is not "
                      "written", stacklevel=3)
    if any(sol.get(k) is not None for k in ("n_modes", "f_min", "f_max")):
        lines.append("METHOD = 1")
    if not lines and sol.get("sol") is None:
        return "", ""
    return "SOL 103\nCEND\n" + "\n".join(lines) + "\nBEGIN BULK\n", "ENDDATA\n"
