"""Stress modes of a reduced body: the element stresses of every elastic mode.

:func:`stress_modes` evaluates the element stress operators of
:mod:`flexpipe.fem.stress` on the expanded elastic modes, one vectorised batch per cell
block, and keeps them in a :class:`StressModes` stored inside the body's ``.npz``.  Modal
stress recovery is then ``sigma(t) = S q(t)`` (:mod:`flexpipe.durability.recover`).

Size switch (``reduce(..., stress=...)``): ``"all"`` elements, the name of a cell set of
the mesh (only its elements), or ``None`` / ``"none"`` (no stress modes).  Stored, and
held in memory, in single precision (float32): ``n_elements x 6 x n_elastic`` numbers.
A stress mode is rounded to 6e-8 of itself, and a recovered stress ``S q`` (computed in
double precision) to about 1e-7 of the largest modal term, far below the error of the
finite elements; in float64 the sample linkage body's stress modes (6,271 shells and
beams, 75 modes) took 22.6 MB and its body file 35.5 MB, past the 30 MB the durability
issue sets, which single precision keeps it under (``bench/bench_durability.py``).
Solids also store nodal stress modes (averaged over the elements sharing a node); for
shells and beams, nodal averages for plots are derived on demand
(:meth:`StressModes.nodal_average`) rather than stored, which keeps the file small.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp

from flexpipe._arrays import readonly
from flexpipe.errors import InputError

#: element kinds and their component names
from flexpipe.fem.stress import COMPONENTS, KIND

_KEYS = ("ids", "cells", "centroids", "modes", "frames", "nodes", "nodal")


@dataclass(frozen=True, eq=False)
class StressBlock:
    """Stress modes of the selected cells of one mesh block.

    Attributes
    ----------
    cell_type : str
        meshio cell type (``quad``, ``triangle``, ``tetra``, ``tetra10``, ``hexahedron``,
        ``line``).
    ids : ndarray of int (ne,)
        Element ids as in the mesh file.
    cells : ndarray of int (ne, nn)
        Node indices of the cells.
    centroids : ndarray (ne, 3)
        Element centroids, body coordinates, m.
    modes : ndarray (ne, 6, m)
        Stress per unit modal coordinate, Pa (components: :attr:`components`), float32.
    frames : ndarray (ne, 3, 3) or empty
        Shells: rows ``e1, e2, n`` of the element frame the components refer to.
    nodes : ndarray of int (k,)
        Solids: the nodes of the block's cells (empty for shells and beams).
    nodal : ndarray (k, 6, m)
        Solids: stress per unit modal coordinate at those nodes, averaged over the block's
        elements that share the node (global axes), Pa, float32.
    """

    cell_type: str
    ids: np.ndarray
    cells: np.ndarray
    centroids: np.ndarray
    modes: np.ndarray
    frames: np.ndarray
    nodes: np.ndarray = field(default_factory=lambda: np.zeros(0, np.int64))
    nodal: np.ndarray = field(default_factory=lambda: np.zeros((0, 6, 0)))

    def __post_init__(self):
        object.__setattr__(self, "ids", readonly(self.ids, np.int64))
        object.__setattr__(self, "cells", readonly(self.cells, np.int64))
        object.__setattr__(self, "nodes", readonly(self.nodes, np.int64))
        for k in ("centroids", "frames"):
            object.__setattr__(self, k, readonly(getattr(self, k)))
        for k in ("modes", "nodal"):  # single precision: see the module docstring
            object.__setattr__(self, k, readonly(getattr(self, k), np.float32))

    @property
    def kind(self) -> str:
        """``shell``, ``solid`` or ``beam``."""
        return KIND[self.cell_type]

    @property
    def components(self) -> tuple[str, ...]:
        """Names of the six stored components."""
        return COMPONENTS[self.kind]

    def __len__(self) -> int:
        return len(self.ids)


@dataclass(frozen=True, eq=False)
class StressModes:
    """Stress modes of a body: one :class:`StressBlock` per cell block with stresses.

    ``mode_index`` gives the body modes (indices into ``FlexBody.frequencies_hz``) the
    last axis of every block refers to: the elastic modes.
    """

    blocks: tuple
    mode_index: np.ndarray
    selection: str = "all"

    def __post_init__(self):
        object.__setattr__(self, "blocks", tuple(self.blocks))
        object.__setattr__(self, "mode_index", readonly(self.mode_index, np.int64))

    @property
    def n_elements(self) -> int:
        """Number of elements with stress modes."""
        return sum(len(b) for b in self.blocks)

    @property
    def nbytes(self) -> int:
        """Bytes of the stored arrays."""
        return sum(b.modes.nbytes + b.centroids.nbytes + b.cells.nbytes + b.frames.nbytes
                   + b.nodal.nbytes + b.nodes.nbytes for b in self.blocks)

    def nodal_average(self, values, n_nodes: int) -> np.ndarray:
        """Average per-element values onto the nodes of their cells.

        Parameters
        ----------
        values : sequence of ndarray
            One array (ne, ...) per block (e.g. max von Mises).
        n_nodes : int

        Returns
        -------
        ndarray (n_nodes, ...)
            NaN at nodes that belong to no element with stresses.
        """
        rows, cols, ofs = [], [], 0
        for b in self.blocks:
            nn = b.cells.shape[1]
            rows.append(b.cells.ravel())
            cols.append(np.repeat(np.arange(len(b)) + ofs, nn))
            ofs += len(b)
        if not rows:
            return np.full((n_nodes,), np.nan)
        r, c = np.concatenate(rows), np.concatenate(cols)
        A = sp.csr_matrix((np.ones(r.size), (r, c)), shape=(n_nodes, ofs))
        A.sum_duplicates()
        count = np.asarray(A.sum(axis=1)).ravel()
        v = np.concatenate([np.asarray(x, dtype=float) for x in values])
        flat = v.reshape(len(v), -1)
        out = (A @ flat) / np.where(count > 0, count, 1.0)[:, None]
        out[count == 0] = np.nan
        return out.reshape((n_nodes,) + v.shape[1:])

    # --------------------------------------------------------------- storage
    def to_arrays(self) -> tuple[dict, dict]:
        """``(header, arrays)`` for the body ``.npz`` (keys prefixed ``stress.``)."""
        header = {"selection": self.selection,
                  "blocks": [b.cell_type for b in self.blocks]}
        arrays = {"stress.mode_index": self.mode_index}
        for j, b in enumerate(self.blocks):
            for k in _KEYS:
                arrays[f"stress.{j}.{k}"] = getattr(b, k)
        return header, arrays

    @classmethod
    def from_arrays(cls, header: dict, get) -> StressModes:
        """Inverse of :meth:`to_arrays`; ``get(key)`` returns a stored array."""
        blocks = [StressBlock(t, *(get(f"stress.{j}.{k}") for k in _KEYS))
                  for j, t in enumerate(header["blocks"])]
        return cls(tuple(blocks), get("stress.mode_index"), header.get("selection", "all"))


def _selected_cells(mesh, selection):
    """{block index: cell indices} of the selection ("all" or a cell-set name)."""
    if selection == "all":
        return {bi: np.arange(len(b)) for bi, b in enumerate(mesh.blocks)
                if b.type in KIND and len(b)}
    if selection not in mesh.cell_sets:
        raise InputError(f"stress: no cell set {selection!r} in the mesh; valid: 'all', "
                         f"'none' or one of {sorted(mesh.cell_sets)}", file=mesh.source or None,
                         key="stress")
    return {int(bi): np.asarray(c) for bi, c in mesh.cell_sets[selection].items()
            if mesh.blocks[int(bi)].type in KIND and len(c)}


def stress_modes(fe, U_all: np.ndarray, mode_index, *, selection="all",
                 batch: int = 20000) -> StressModes | None:
    """Element stress modes of the all-DOF mode shapes ``U_all`` (n_dof, m).

    Parameters
    ----------
    fe : FEModel
        The assembled model (its mesh and the property arguments in ``fe.info``).
    U_all : ndarray (n_dof, m)
        Mode shapes over all DOF of ``fe`` (translations and rotations).
    mode_index : array_like of int (m,)
        Which body modes the columns are.
    selection : {"all", "none", None} or str
        All elements, none, or the elements of a named cell set.
    batch : int
        Elements per vectorised batch.
    """
    from flexpipe.fem import stress as fs
    from flexpipe.fem.properties import beam_props, material_arrays, shell_props
    from flexpipe.mesh.mesh import BEAM_TYPES, SHELL_TYPES

    if selection is None or str(selection).lower() == "none":
        return None
    mesh = fe.mesh
    if mesh is None:
        raise InputError("stress modes need the FE model's mesh (assemble a Mesh)", key="stress")
    info = fe.info or {}
    dpn = fe.dofs_per_node
    blocks = []
    for bi, cells_idx in sorted(_selected_cells(mesh, str(selection)).items()):
        block = mesh.blocks[bi]
        E, nu, _ = material_arrays(mesh, bi, block, info.get("material"))
        if block.type in SHELL_TYPES:
            props = shell_props(mesh, bi, block, info.get("thickness"))
        elif block.type in BEAM_TYPES:
            props = beam_props(mesh, bi, block, info.get("beam_section"))
        else:
            props = {}
        de = 6 if block.type in SHELL_TYPES + BEAM_TYPES else 3
        solid = block.type not in SHELL_TYPES + BEAM_TYPES
        m = U_all.shape[1]
        if solid:  # nodal stresses: sums and counts over the block's own nodes
            nodes = np.unique(block.cells[cells_idx])
            local = np.full(mesh.n_nodes, -1, dtype=np.int64)
            local[nodes] = np.arange(len(nodes))
            nsum = np.zeros((len(nodes), 6, m))
            ncount = np.zeros(len(nodes))
        parts, frames = [], []
        for s in range(0, len(cells_idx), batch):
            sel = cells_idx[s:s + batch]
            conn = block.cells[sel]
            S, R = fs.operators(block.type, mesh.points[conn], E=E[sel], nu=nu[sel],
                                **{k: v[sel] for k, v in props.items()})
            dofs = (conn[:, :, None] * dpn + np.arange(de)).reshape(len(sel), -1)
            Ue = U_all[dofs]
            parts.append(np.einsum("ecd,edm->ecm", S, Ue, optimize=True))
            if R is not None:
                frames.append(R)
            if solid:
                Sn = fs.solid_nodal(block.type, mesh.points[conn], E=E[sel], nu=nu[sel])
                vals = np.einsum("eacd,edm->eacm", Sn, Ue, optimize=True)
                li = local[conn].ravel()
                np.add.at(nsum, li, vals.reshape(-1, 6, m))
                np.add.at(ncount, li, 1.0)
        conn = block.cells[cells_idx]
        extra = {}
        if solid:
            extra = {"nodes": nodes, "nodal": nsum / ncount[:, None, None]}
        blocks.append(StressBlock(
            block.type, block.ids[cells_idx], conn, mesh.points[conn].mean(axis=1),
            np.concatenate(parts), np.concatenate(frames) if frames else np.zeros((0, 3, 3)),
            **extra))
    return StressModes(tuple(blocks), np.asarray(mode_index), str(selection))
