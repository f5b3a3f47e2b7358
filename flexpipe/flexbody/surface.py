"""Outer-surface triangles of a mesh (for drawing a FlexBody) and a hash of the mesh."""

from __future__ import annotations

import hashlib

import numpy as np

from flexpipe.mesh.mesh import Mesh

# faces of each solid type as corner-node positions, outward for positive cells (VTK order)
_SOLID_FACES = {
    "tetra": [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    "tetra10": [[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
    "hexahedron": [[0, 3, 2], [0, 2, 1], [4, 5, 6], [4, 6, 7], [0, 1, 5], [0, 5, 4],
                   [1, 2, 6], [1, 6, 5], [2, 3, 7], [2, 7, 6], [3, 0, 4], [3, 4, 7]],
}
# a hexahedron face is two triangles: boundary detection runs on whole quads
_HEX_QUADS = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6],
              [3, 0, 4, 7]]


def _unique_faces(faces: np.ndarray) -> np.ndarray:
    """Mask of faces (rows of node indices) that occur once, ignoring node order."""
    key = np.sort(faces, axis=1)
    _, inv, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
    return counts[inv.ravel()] == 1


# wedge (CPENTA) and pyramid (CPYRAM) faces: triangles and quads, outward (VTK order)
_WEDGE_TRIS, _WEDGE_QUADS = [[0, 2, 1], [3, 4, 5]], [[0, 1, 4, 3], [1, 2, 5, 4], [2, 0, 3, 5]]
_PYRAMID_TRIS, _PYRAMID_QUADS = [[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]], [[0, 3, 2, 1]]


def surface_triangles(mesh: Mesh) -> np.ndarray:
    """Triangles (t, 3) covering the outer surface of solids plus all shell cells.

    Solid faces shared by two cells (of any solid types) are interior and dropped; tet10
    faces use the corner nodes; a quadrilateral solid face is two triangles.  Beams,
    springs and point masses draw nothing.
    """
    solid_tris, solid_quads, shells = [], [], []
    for block in mesh.blocks:
        c = block.cells
        if len(c) == 0:
            continue
        if block.type in ("tetra", "tetra10"):
            solid_tris.append(c[:, np.array(_SOLID_FACES[block.type])].reshape(-1, 3))
        elif block.type == "hexahedron":
            solid_quads.append(c[:, np.array(_HEX_QUADS)].reshape(-1, 4))
        elif block.type == "wedge":
            solid_tris.append(c[:, np.array(_WEDGE_TRIS)].reshape(-1, 3))
            solid_quads.append(c[:, np.array(_WEDGE_QUADS)].reshape(-1, 4))
        elif block.type == "pyramid":
            solid_tris.append(c[:, np.array(_PYRAMID_TRIS)].reshape(-1, 3))
            solid_quads.append(c[:, np.array(_PYRAMID_QUADS)].reshape(-1, 4))
        elif block.type == "triangle":
            shells.append(c)
        elif block.type == "quad":
            shells.append(np.vstack([c[:, [0, 1, 2]], c[:, [0, 2, 3]]]))
    tris = []
    if solid_tris:
        f = np.vstack(solid_tris)
        tris.append(f[_unique_faces(f)])
    if solid_quads:
        q = np.vstack(solid_quads)
        q = q[_unique_faces(q)]
        tris.append(np.vstack([q[:, [0, 1, 2]], q[:, [0, 2, 3]]]))
    tris += shells
    if not tris:
        return np.zeros((0, 3), dtype=np.int64)
    return np.ascontiguousarray(np.vstack(tris), dtype=np.int64)


def mesh_hash(mesh: Mesh) -> str:
    """SHA-256 of the node coordinates and the cells (types and connectivity)."""
    h = hashlib.sha256()
    h.update(np.ascontiguousarray(mesh.points, dtype=np.float64).tobytes())
    for block in mesh.blocks:
        h.update(block.type.encode())
        h.update(np.ascontiguousarray(block.cells, dtype=np.int64).tobytes())
    return h.hexdigest()
