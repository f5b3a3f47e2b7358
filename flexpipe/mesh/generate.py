"""Structured meshes for tests, benchmarks and examples.

``box`` fills a rectangular block ``[0, L] x [0, b] x [0, h]`` with tet4, tet10 or hex8
cells; ``plate`` covers the rectangle ``[0, Lx] x [0, Ly]`` of the plane z = 0 with
quad or triangle shell cells.  All cells are positively oriented (meshio/VTK node
order, positive Jacobian), and the boundary faces/edges are provided as node sets.
"""

from __future__ import annotations

import numpy as np

from flexpipe.errors import InputError
from flexpipe.mesh.mesh import CellBlock, Mesh

# Kuhn (Freudenthal) split of the unit cube into 6 tetrahedra along the diagonal 0-7.
# Cube corners are numbered by bits (i, j, k) -> i + 2 j + 4 k.  The split is the same in
# every cell, so faces shared by neighbouring cells are cut along the same diagonal.
_KUHN = np.array([
    [0, 1, 3, 7], [0, 3, 2, 7], [0, 2, 6, 7], [0, 6, 4, 7], [0, 4, 5, 7], [0, 5, 1, 7],
])
# hexahedron (meshio/VTK order) corners in bit numbering
_HEX = np.array([0, 1, 3, 2, 4, 5, 7, 6])
# tetra10 mid-edge nodes 4..9 sit on these vertex pairs (meshio/VTK/Nastran order)
TET10_EDGES = np.array([[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]])


def _check_counts(**counts):
    for name, n in counts.items():
        if not isinstance(n, (int, np.integer)) or n < 1:
            raise InputError(f"{name} must be a positive integer number of cells, got {n!r}",
                             key=name)


def _check_lengths(**lengths):
    for name, v in lengths.items():
        if not (np.isfinite(v) and v > 0):
            raise InputError(f"{name} must be a positive length in m, got {v!r}", key=name)


def _grid(L, b, h, nx, ny, nz):
    x = np.linspace(0.0, L, nx + 1)
    y = np.linspace(0.0, b, ny + 1)
    z = np.linspace(0.0, h, nz + 1)
    X, Y, Z = np.meshgrid(x, y, z, indexing="ij")
    return np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])


def _corners(nx, ny, nz):
    """Node indices (n_cells, 8) of the grid cells, corners in bit order i + 2j + 4k."""
    i, j, k = np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij")
    base = ((i * (ny + 1) + j) * (nz + 1) + k).ravel()
    off = np.array([
        (di * (ny + 1) + dj) * (nz + 1) + dk
        for dk in (0, 1) for dj in (0, 1) for di in (0, 1)
    ])
    return base[:, None] + off[None, :]


def add_midside_nodes(points: np.ndarray, tets: np.ndarray):
    """Turn tet4 connectivity into straight-edged tet10 (one shared node per edge).

    Returns
    -------
    points : ndarray, shape (n + n_edges, 3)
    cells : ndarray, shape (n_tets, 10)
    """
    tets = np.asarray(tets, dtype=np.int64)
    e = tets[:, TET10_EDGES]                      # (ne, 6, 2)
    e = np.sort(e, axis=2).reshape(-1, 2)
    n = len(points)
    key = e[:, 0] * n + e[:, 1]
    order = np.argsort(key, kind="stable")
    ks = key[order]
    first = np.ones(len(ks), dtype=bool)
    first[1:] = ks[1:] != ks[:-1]
    edge_no = np.cumsum(first) - 1
    mid_of = np.empty(len(key), dtype=np.int64)
    mid_of[order] = edge_no
    ue = e[order[first]]
    mids = 0.5 * (points[ue[:, 0]] + points[ue[:, 1]])
    cells = np.hstack([tets, n + mid_of.reshape(-1, 6)])
    return np.vstack([points, mids]), cells


def _face_sets(points, L, b, h):
    tol = 1e-9 * max(L, b, h)
    x, y, z = points.T
    return {
        "xmin": np.flatnonzero(np.abs(x) <= tol), "xmax": np.flatnonzero(np.abs(x - L) <= tol),
        "ymin": np.flatnonzero(np.abs(y) <= tol), "ymax": np.flatnonzero(np.abs(y - b) <= tol),
        "zmin": np.flatnonzero(np.abs(z) <= tol), "zmax": np.flatnonzero(np.abs(z - h) <= tol),
    }


def box(L: float, b: float, h: float, nx: int, ny: int, nz: int, *,
        cell: str = "tetra", origin=(0.0, 0.0, 0.0)) -> Mesh:
    """Structured solid mesh of the block ``[0, L] x [0, b] x [0, h]`` (shifted by origin).

    Parameters
    ----------
    L, b, h : float
        Edge lengths along x, y, z in m.
    nx, ny, nz : int
        Grid cells along x, y, z.
    cell : {"tetra", "tetra10", "hexahedron"}
        ``tetra``/``tetra10`` split each grid cell into 6 tetrahedra (Kuhn split, conforming);
        ``tetra10`` adds straight mid-edge nodes; ``hexahedron`` keeps the grid cells.
    origin : (3,) array_like
        Position of the corner ``(0, 0, 0)``.

    Returns
    -------
    Mesh
        With node sets ``xmin``, ``xmax``, ``ymin``, ``ymax``, ``zmin``, ``zmax`` (the
        nodes on each face) and the cell set ``solid`` (all cells).
    """
    _check_lengths(L=L, b=b, h=h)
    _check_counts(nx=nx, ny=ny, nz=nz)
    pts = _grid(L, b, h, nx, ny, nz)
    c = _corners(nx, ny, nz)
    if cell == "hexahedron":
        cells = c[:, _HEX]
    elif cell in ("tetra", "tetra10"):
        cells = c[:, _KUHN].reshape(-1, 4)
        if cell == "tetra10":
            pts, cells = add_midside_nodes(pts, cells)
    else:
        raise InputError(f"cell must be 'tetra', 'tetra10' or 'hexahedron', got {cell!r}",
                         key="cell")
    sets = _face_sets(pts, L, b, h)
    pts = pts + np.asarray(origin, dtype=float)
    return Mesh(points=pts, blocks=(CellBlock(cell, cells),), node_sets=sets,
                cell_sets={"solid": {0: np.arange(len(cells))}})


def plate(Lx: float, Ly: float, nx: int, ny: int, *, cell: str = "quad",
          origin=(0.0, 0.0, 0.0)) -> Mesh:
    """Structured flat shell mesh of ``[0, Lx] x [0, Ly]`` in the plane z = 0.

    Parameters
    ----------
    Lx, Ly : float
        Edge lengths along x, y in m.
    nx, ny : int
        Cells along x, y.
    cell : {"quad", "triangle"}
        ``triangle`` splits every quad along its diagonal from (i, j) to (i+1, j+1).
    origin : (3,) array_like
        Position of the corner ``(0, 0, 0)``.

    Returns
    -------
    Mesh
        Cells numbered counter-clockwise seen from +z (normal +z), node sets ``xmin``,
        ``xmax``, ``ymin``, ``ymax`` (edge nodes) and the cell set ``shell``.
    """
    _check_lengths(Lx=Lx, Ly=Ly)
    _check_counts(nx=nx, ny=ny)
    x = np.linspace(0.0, Lx, nx + 1)
    y = np.linspace(0.0, Ly, ny + 1)
    X, Y = np.meshgrid(x, y, indexing="ij")
    pts = np.column_stack([X.ravel(), Y.ravel(), np.zeros(X.size)])
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    n0 = (i * (ny + 1) + j).ravel()
    n1 = n0 + (ny + 1)
    n2 = n1 + 1
    n3 = n0 + 1
    if cell == "quad":
        cells = np.column_stack([n0, n1, n2, n3])
    elif cell == "triangle":
        cells = np.vstack([np.column_stack([n0, n1, n2]),
                           np.column_stack([n0, n2, n3])])
    else:
        raise InputError(f"cell must be 'quad' or 'triangle', got {cell!r}", key="cell")
    tol = 1e-9 * max(Lx, Ly)
    sets = {
        "xmin": np.flatnonzero(np.abs(pts[:, 0]) <= tol),
        "xmax": np.flatnonzero(np.abs(pts[:, 0] - Lx) <= tol),
        "ymin": np.flatnonzero(np.abs(pts[:, 1]) <= tol),
        "ymax": np.flatnonzero(np.abs(pts[:, 1] - Ly) <= tol),
    }
    pts = pts + np.asarray(origin, dtype=float)
    return Mesh(points=pts, blocks=(CellBlock(cell, cells),), node_sets=sets,
                cell_sets={"shell": {0: np.arange(len(cells))}})
