"""Helpers shared by the mesh readers and writers."""

from __future__ import annotations

import numpy as np

from flexpipe.mesh.mesh import NODES_PER_CELL, Mesh

#: topological dimension of meshio cell types (supported and not)
DIMENSION = {
    "vertex": 0, "line": 1, "line3": 1, "triangle": 2, "triangle6": 2, "triangle7": 2,
    "quad": 2, "quad8": 2, "quad9": 2, "polygon": 2, "tetra": 3, "tetra10": 3,
    "hexahedron": 3, "hexahedron20": 3, "hexahedron27": 3, "wedge": 3, "wedge15": 3,
    "wedge18": 3, "pyramid": 3, "pyramid13": 3, "pyramid14": 3,
}
SUPPORTED_TYPES = tuple(NODES_PER_CELL)


def dimension(cell_type: str) -> int:
    """Topological dimension of a meshio cell type (from its name when not tabulated)."""
    if cell_type in DIMENSION:
        return DIMENSION[cell_type]
    for prefix, d in (("line", 1), ("triangle", 2), ("quad", 2), ("tetra", 3),
                      ("hexahedron", 3), ("wedge", 3), ("pyramid", 3)):
        if cell_type.startswith(prefix):
            return d
    return -1


def unsupported_type_message(cell_type: str) -> str:
    """Message for a cell type flexpipe has no element for."""
    return (f"element type '{cell_type}' is not supported; supported: "
            f"{', '.join(SUPPORTED_TYPES)} (second-order shells/hexes and wedges/pyramids "
            "are not; remesh with linear shells, tet4/tet10 or hex8)")


def cell_section_index(mesh: Mesh) -> list[np.ndarray]:
    """For each block, the index into ``list(mesh.sections)`` of each cell's section (-1: none).

    A later section overrides an earlier one for cells in both, as in the assembler.
    """
    names = list(mesh.sections)
    out = []
    for bi, b in enumerate(mesh.blocks):
        idx = np.full(len(b), -1, dtype=np.int64)
        for k, name in enumerate(names):
            cells = mesh.cell_sets.get(name, {}).get(bi)
            if cells is not None:
                idx[cells] = k
        out.append(idx)
    return out


def unique_ids(ids: np.ndarray) -> np.ndarray:
    """``ids`` when unique and positive, else 1..n."""
    ids = np.asarray(ids, dtype=np.int64)
    if ids.size and (ids.min() < 1 or len(np.unique(ids)) != len(ids)):
        return np.arange(1, len(ids) + 1, dtype=np.int64)
    return ids


def default_orientation(X: np.ndarray) -> np.ndarray:
    """Beam orientation vectors used when none is given: global z, or y for beams along z."""
    d = X[:, 1] - X[:, 0]
    d = d / np.maximum(np.linalg.norm(d, axis=1, keepdims=True), 1e-300)
    v = np.tile([0.0, 0.0, 1.0], (len(X), 1))
    along_z = np.linalg.norm(np.cross(d, v), axis=1) < 1e-3
    v[along_z] = [0.0, 1.0, 0.0]
    return v
