"""Checks a freshly read mesh before anything is computed from it.

:func:`validate` raises :class:`~flexpipe.errors.MeshError` naming the file and the
offending node or element ids for

* non-finite coordinates,
* nodes no element, point mass or rigid link references (``prune_unreferenced=True``
  drops them instead),
* cells that use the same node twice,
* tetrahedra and hexahedra with negative or zero volume (inverted node order, collapsed
  elements) and zero-length beams / zero-area shells,

and warns (:class:`MeshWarning`) about distinct nodes at the same position, which
usually means two parts that were meant to be joined are not (the assembler then reports
disconnected parts).  Disconnected parts, missing materials and shells without thickness
are reported by :func:`flexpipe.fem.assemble`, where the properties are known.
"""

from __future__ import annotations

import warnings
from dataclasses import replace

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.mesh.mesh import CellBlock, Mesh, RigidLink

#: tetrahedron corner pairs / faces used by the volume checks (meshio node order)
_HEX_CORNERS = np.array([  # corner, its three edge neighbours (right-handed)
    [0, 1, 3, 4], [1, 2, 0, 5], [2, 3, 1, 6], [3, 0, 2, 7],
    [4, 7, 5, 0], [5, 4, 6, 1], [6, 5, 7, 2], [7, 6, 4, 3],
])


class MeshWarning(UserWarning):
    """Something in a mesh file that is probably, but not certainly, a mistake."""


def _ids(block: CellBlock, idx) -> list[int]:
    return block.ids[np.asarray(idx)[:10]].tolist()


def _where(mesh: Mesh):
    return mesh.source or None


def _check_points(mesh: Mesh) -> None:
    bad = ~np.isfinite(mesh.points).all(axis=1)
    if bad.any():
        idx = np.flatnonzero(bad)
        raise MeshError(
            f"{len(idx)} node(s) have non-finite (NaN or infinite) coordinates, e.g. node "
            f"ids {mesh.node_ids[idx[:10]].tolist()}; fix the coordinates in the file",
            file=_where(mesh))


def referenced(mesh: Mesh) -> np.ndarray:
    """True for nodes an element, point mass or rigid link uses."""
    used = np.zeros(mesh.n_nodes, dtype=bool)
    for b in mesh.blocks:
        used[b.cells.ravel()] = True
    for pm in mesh.point_masses:
        used[pm.node] = True
    for link in mesh.rigid_links:
        used[link.master] = True
        used[np.asarray(link.slaves, dtype=np.int64)] = True
    for it in mesh.interpolations:
        used[it.ref] = True
        used[np.asarray(it.nodes, dtype=np.int64)] = True
    return used


def prune(mesh: Mesh, keep: np.ndarray) -> Mesh:
    """Return ``mesh`` with only the nodes where ``keep`` is True (all references renumbered)."""
    new_of = np.full(mesh.n_nodes, -1, dtype=np.int64)
    new_of[keep] = np.arange(int(keep.sum()))
    blocks = tuple(CellBlock(b.type, new_of[b.cells], b.ids, b.tags, b.data)
                   for b in mesh.blocks)
    node_sets = {k: new_of[v][new_of[v] >= 0] for k, v in mesh.node_sets.items()}
    masses = tuple(replace(pm, node=int(new_of[pm.node])) for pm in mesh.point_masses)
    links = tuple(RigidLink(int(new_of[lk.master]), new_of[np.asarray(lk.slaves)], lk.dofs,
                            lk.id) for lk in mesh.rigid_links)
    interp = tuple(replace(it, ref=int(new_of[it.ref]),
                           nodes=new_of[np.asarray(it.nodes, dtype=np.int64)])
                   for it in mesh.interpolations)
    dof_sets = {}
    for k, v in mesh.dof_sets.items():
        v = np.asarray(v, dtype=np.int64).reshape(-1, 2)
        n = new_of[v[:, 0]]
        dof_sets[k] = np.column_stack([n, v[:, 1]])[n >= 0]
    solution = dict(mesh.solution)
    if "spc_directions" in solution:      # rows (node, group, direction) of flexpipe modes
        d = np.array(solution["spc_directions"], dtype=float)
        n = new_of[d[:, 0].astype(np.int64)]
        d[:, 0] = n
        solution["spc_directions"] = d[n >= 0]
    return replace(mesh, points=mesh.points[keep], node_ids=mesh.node_ids[keep],
                   blocks=blocks, node_sets=node_sets, point_masses=masses, rigid_links=links,
                   interpolations=interp, dof_sets=dof_sets, solution=solution)


def _check_repeated_nodes(mesh: Mesh) -> None:
    for b in mesh.blocks:
        if b.cells.shape[1] < 2 or len(b) == 0:
            continue
        s = np.sort(b.cells, axis=1)
        bad = (s[:, 1:] == s[:, :-1]).any(axis=1)
        if bad.any():
            idx = np.flatnonzero(bad)
            raise MeshError(
                f"{len(idx)} {b.type} element(s) use the same node twice (collapsed "
                f"element), e.g. element ids {_ids(b, idx)}; use the lower-order element "
                "type (e.g. a triangle instead of a collapsed quad)", file=_where(mesh))


def _signed_tet_volume(X: np.ndarray) -> np.ndarray:
    a, b, c = X[:, 1] - X[:, 0], X[:, 2] - X[:, 0], X[:, 3] - X[:, 0]
    return np.einsum("ij,ij->i", a, np.cross(b, c)) / 6.0


def _check_volumes(mesh: Mesh) -> None:
    for b in mesh.blocks:
        if len(b) == 0:
            continue
        X = mesh.points[b.cells]
        h = np.ptp(X, axis=1).max(axis=1)  # element size
        if b.type in ("tetra", "tetra10"):
            v = _signed_tet_volume(X[:, :4]) / np.maximum(h, 1e-300) ** 3
            worst = v
        elif b.type == "hexahedron":
            # corner Jacobians: mixed product of the three edges leaving each corner
            C = X[:, _HEX_CORNERS]                             # (n, 8, 4, 3)
            e = C[:, :, 1:] - C[:, :, :1]                      # (n, 8, 3, 3)
            det = np.einsum("nci,nci->nc", e[:, :, 0], np.cross(e[:, :, 1], e[:, :, 2]))
            worst = det.min(axis=1) / np.maximum(h, 1e-300) ** 3
            v = det.max(axis=1) / np.maximum(h, 1e-300) ** 3
        elif b.type in ("triangle", "quad"):
            a = np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1)
            if b.type == "quad":
                a = a + np.linalg.norm(np.cross(X[:, 2] - X[:, 0], X[:, 3] - X[:, 0]), axis=1)
            bad = ~(a > 1e-10 * np.maximum(h, 1e-300) ** 2)
            if bad.any():
                idx = np.flatnonzero(bad)
                raise MeshError(f"{len(idx)} {b.type} shell element(s) have zero area, e.g. "
                                f"element ids {_ids(b, idx)}; remove or repair them",
                                file=_where(mesh))
            continue
        elif b.type == "line":
            bad = ~(h > 0)
            if bad.any():
                idx = np.flatnonzero(bad)
                raise MeshError(f"{len(idx)} beam element(s) have zero length (both nodes at "
                                f"one point), e.g. element ids {_ids(b, idx)}",
                                file=_where(mesh))
            continue
        else:
            continue
        inverted = v < -1e-10
        if inverted.any():
            idx = np.flatnonzero(inverted)
            raise MeshError(
                f"{len(idx)} {b.type} element(s) are inverted (negative volume: node order "
                f"mirrored), e.g. element ids {_ids(b, idx)}; renumber their nodes "
                "(e.g. swap the 2nd and 3rd corner) or let the mesher reorient them",
                file=_where(mesh))
        flat = ~(worst > 1e-10)
        if flat.any():
            idx = np.flatnonzero(flat)
            raise MeshError(
                f"{len(idx)} {b.type} element(s) have zero volume or are folded (non-positive "
                f"Jacobian at a corner), e.g. element ids {_ids(b, idx)}; remesh or repair them",
                file=_where(mesh))


def _check_coincident(mesh: Mesh) -> None:
    if mesh.n_nodes < 2:
        return
    from scipy.spatial import cKDTree

    size = float(np.ptp(mesh.points, axis=0).max()) or 1.0
    pairs = cKDTree(mesh.points).query_pairs(1e-9 * size, output_type="ndarray")
    if len(pairs) == 0:
        return
    # pairs tied by a rigid link or sharing a point mass are intended
    group = np.full(mesh.n_nodes, -1, dtype=np.int64)
    for k, lk in enumerate(mesh.rigid_links):
        group[np.asarray(lk.slaves, dtype=np.int64)] = k
        group[lk.master] = k
    ga, gb = group[pairs[:, 0]], group[pairs[:, 1]]
    keep = pairs[~((ga == gb) & (ga >= 0))].tolist()
    if not keep:
        return
    ex = ", ".join(f"{int(mesh.node_ids[a])} & {int(mesh.node_ids[b])}" for a, b in keep[:5])
    warnings.warn(MeshWarning(
        f"{mesh.source or 'mesh'}: {len(keep)} pair(s) of distinct nodes share a position "
        f"(node ids {ex}); unless they are meant to be separate, merge them in the mesher - "
        "otherwise the parts they belong to are not connected"), stacklevel=3)


def validate(mesh: Mesh, *, prune_unreferenced: bool = False,
             check_coincident: bool = True) -> Mesh:
    """Check ``mesh`` (see module docstring) and return it, pruned if asked.

    Parameters
    ----------
    mesh : Mesh
    prune_unreferenced : bool
        Drop nodes that nothing references instead of raising.
    check_coincident : bool
        Warn about distinct nodes at the same position.

    Returns
    -------
    Mesh
    """
    _check_points(mesh)
    used = referenced(mesh)
    if not used.all():
        if prune_unreferenced:
            mesh = prune(mesh, used)
        else:
            idx = np.flatnonzero(~used)
            raise MeshError(
                f"{len(idx)} node(s) belong to no element, point mass or rigid link, e.g. node "
                f"ids {mesh.node_ids[idx[:10]].tolist()}; delete them or read the mesh with "
                "prune_unreferenced=True", file=_where(mesh))
    _check_repeated_nodes(mesh)
    _check_volumes(mesh)
    if check_coincident:
        _check_coincident(mesh)
    return mesh


def missing_property_note(mesh: Mesh, block: int, rows) -> str:
    """The reader's note (``Mesh.info["missing_properties"]``, Nastran) on the missing
    property card of cells ``rows`` of block ``block``, followed by ``"; "``; '' if none."""
    notes = mesh.info.get("missing_properties") or {}
    for name, members in mesh.cell_sets.items():
        if name.startswith("PID") and name[3:] in notes and block in members \
                and np.isin(members[block], rows).any():
            return notes[name[3:]]["text"] + "; "
    return ""


__all__ = ["MeshWarning", "missing_property_note", "prune", "referenced", "validate"]
