"""The :class:`Mesh` data object: nodes, typed cell blocks, named sets, point masses, links.

Element type names follow meshio: ``vertex``, ``line`` (2-node beam), ``triangle``,
``quad``, ``tetra``, ``tetra10``, ``hexahedron``, ``wedge`` (6-node pentahedron),
``pyramid`` (5 nodes); ``spring`` / ``spring1`` are two-node / grounded springs whose
6-DOF-per-node element matrices the reader computed (see :data:`SPRING_TYPES`).
Node indices in cells are 0-based
positions in :attr:`Mesh.points`; the ids users see in their files are kept in
:attr:`Mesh.node_ids` and :attr:`CellBlock.ids` so that every error names them.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from flexpipe._arrays import readonly

#: nodes per cell for every supported element type
NODES_PER_CELL = {
    "vertex": 1,
    "line": 2,
    "triangle": 3,
    "quad": 4,
    "tetra": 4,
    "tetra10": 10,
    "hexahedron": 8,
    "wedge": 6,
    "pyramid": 5,
    "spring": 2,
    "spring1": 1,
}
SOLID_TYPES = ("tetra", "tetra10", "hexahedron", "wedge", "pyramid")
SHELL_TYPES = ("triangle", "quad")
BEAM_TYPES = ("line",)
#: springs/dampers (Nastran CELAS/CBUSH): element matrices carried in ``block.data``
#: (``"K"``, optional ``"B"``, shape (n, 6 nn, 6 nn), global DOF); ``spring1`` is grounded
SPRING_TYPES = ("spring", "spring1")


@dataclass(frozen=True)
class CellBlock:
    """Cells of one element type.

    Attributes
    ----------
    type : str
        meshio element type name (see :data:`NODES_PER_CELL`).
    cells : ndarray of int, shape (n, nodes_per_cell)
        0-based node indices.
    ids : ndarray of int, shape (n,)
        Element ids as in the source file (1-based counters when the format has none).
    tags : ndarray of int, shape (n,)
        Property id (Nastran PID, Gmsh physical tag, 0 when none).
    data : mapping of str to ndarray
        Per-cell data, e.g. ``"orientation"`` (n, 3) for beams.
    """

    type: str
    cells: np.ndarray
    ids: np.ndarray | None = None
    tags: np.ndarray | None = None
    data: Mapping[str, np.ndarray] = field(default_factory=dict)

    def __post_init__(self):
        if self.type not in NODES_PER_CELL:
            raise ValueError(
                f"unknown element type '{self.type}'; valid: {sorted(NODES_PER_CELL)}"
            )
        cells = np.asarray(self.cells, dtype=np.int64).reshape(-1, NODES_PER_CELL[self.type])
        n = len(cells)
        ids = np.arange(1, n + 1) if self.ids is None else self.ids
        tags = np.zeros(n, dtype=np.int64) if self.tags is None else self.tags
        object.__setattr__(self, "cells", readonly(cells, np.int64))
        object.__setattr__(self, "ids", readonly(ids, np.int64))
        object.__setattr__(self, "tags", readonly(tags, np.int64))
        object.__setattr__(self, "data", MappingProxyType(dict(self.data)))

    def __len__(self) -> int:
        return len(self.cells)


@dataclass(frozen=True)
class PointMass:
    """A concentrated mass (Nastran CONM2) at node index ``node``.

    ``inertia`` is the 3x3 rotary inertia tensor about the mass centre (kg m^2; the
    assembler adds the parallel-axis term for the offset); ``offset`` the position of
    the mass centre relative to the node (m).  ``matrix`` (6 x 6, Nastran CONM1), when
    given, is the complete nodal mass matrix and replaces the other three.
    """

    node: int
    mass: float
    inertia: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))
    offset: np.ndarray = field(default_factory=lambda: np.zeros(3))
    id: int = 0
    matrix: np.ndarray | None = None


@dataclass(frozen=True)
class RigidLink:
    """A rigid spider (Nastran RBE2): ``slaves`` follow ``master`` rigidly in ``dofs``.

    ``dofs`` is a string of Nastran component digits, ``"123456"`` for all six.
    """

    master: int
    slaves: np.ndarray
    dofs: str = "123456"
    id: int = 0


@dataclass(frozen=True)
class Interpolation:
    """An interpolation constraint (Nastran RBE3, Abaqus distributing coupling).

    The ``ref`` node's components ``ref_dofs`` follow the weighted least-squares rigid
    motion of the independent nodes ``nodes`` (components ``node_dofs[k]``, weights
    ``weights[k]``); see :mod:`flexpipe.fem.interpolation`.
    """

    ref: int
    ref_dofs: str
    nodes: np.ndarray
    weights: np.ndarray
    node_dofs: tuple = ()
    id: int = 0


@dataclass(frozen=True)
class Mesh:
    """A finite-element mesh in SI units.

    Attributes
    ----------
    points : ndarray, shape (n_nodes, 3)
        Node coordinates in metres.
    blocks : tuple of CellBlock
        Cells grouped by element type.
    node_ids : ndarray of int, shape (n_nodes,)
        Node ids as in the source file.
    node_sets : mapping of str to ndarray of int
        Named sets of 0-based node indices.
    cell_sets : mapping of str to mapping of int to ndarray of int
        Named cell sets: block index -> cell indices within that block.
    point_masses : tuple of PointMass
    rigid_links : tuple of RigidLink
    sections : mapping of str to mapping
        Properties carried by the file, keyed by cell-set name: ``thickness``,
        ``E``, ``nu``, ``rho``, beam ``A``, ``Iy``, ``Iz``, ``J`` (and optionally shear
        area factors ``k1``, ``k2``, principal-axis angle ``theta``), shell ``bending``
        (PSHELL 12I/T^3 times E2/E).
    source : str
        The file the mesh came from ("" when built in memory).
    interpolations : tuple of Interpolation
        RBE3-type constraints.
    dof_sets : mapping of str to ndarray, shape (k, 2)
        Named sets of (node index, component 0..5), e.g. Nastran SPC sets ``"SPC1"``.
    solution : mapping
        Solution set-up read from the file: ``"spc"`` (name of the DOF set held at zero),
        ``"n_modes"``, ``"f_min"``, ``"f_max"`` (EIGRL), ``"lumped_mass"`` and
        ``"coupmass"`` (PARAM COUPMASS), ``"sol"`` (the executive SOL, e.g. 103).
    info : mapping
        What the reader read, converted and dropped (card/keyword -> count or note).
    """

    points: np.ndarray
    blocks: tuple[CellBlock, ...]
    node_ids: np.ndarray | None = None
    node_sets: Mapping[str, np.ndarray] = field(default_factory=dict)
    cell_sets: Mapping[str, Mapping[int, np.ndarray]] = field(default_factory=dict)
    point_masses: tuple[PointMass, ...] = ()
    rigid_links: tuple[RigidLink, ...] = ()
    sections: Mapping[str, Mapping[str, float]] = field(default_factory=dict)
    source: str = ""
    interpolations: tuple[Interpolation, ...] = ()
    dof_sets: Mapping[str, np.ndarray] = field(default_factory=dict)
    solution: Mapping = field(default_factory=dict)
    info: Mapping = field(default_factory=dict)

    def __post_init__(self):
        pts = np.asarray(self.points, dtype=float)
        if pts.ndim != 2 or pts.shape[1] not in (2, 3):
            raise ValueError(f"points must have shape (n, 3), got {pts.shape}")
        if pts.shape[1] == 2:
            pts = np.column_stack([pts, np.zeros(len(pts))])
        nid = np.arange(1, len(pts) + 1) if self.node_ids is None else self.node_ids
        object.__setattr__(self, "points", readonly(pts, float))
        object.__setattr__(self, "node_ids", readonly(nid, np.int64))
        object.__setattr__(self, "blocks", tuple(self.blocks))
        object.__setattr__(
            self, "node_sets",
            MappingProxyType({k: readonly(v, np.int64) for k, v in dict(self.node_sets).items()}),
        )
        object.__setattr__(
            self, "cell_sets",
            MappingProxyType({
                k: MappingProxyType({int(b): readonly(c, np.int64) for b, c in dict(v).items()})
                for k, v in dict(self.cell_sets).items()
            }),
        )
        object.__setattr__(self, "point_masses", tuple(self.point_masses))
        object.__setattr__(self, "rigid_links", tuple(self.rigid_links))
        object.__setattr__(self, "interpolations", tuple(self.interpolations))
        object.__setattr__(
            self, "dof_sets",
            MappingProxyType({k: readonly(np.reshape(v, (-1, 2)), np.int64)
                              for k, v in dict(self.dof_sets).items()}),
        )
        object.__setattr__(self, "solution", MappingProxyType(dict(self.solution)))
        object.__setattr__(self, "info", MappingProxyType(dict(self.info)))
        object.__setattr__(
            self, "sections",
            MappingProxyType({k: MappingProxyType(dict(v))
                              for k, v in dict(self.sections).items()}),
        )

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.points)

    @property
    def cell_types(self) -> tuple[str, ...]:
        """Element types present, in block order."""
        return tuple(b.type for b in self.blocks)

    def blocks_of(self, *types: str) -> list[tuple[int, CellBlock]]:
        """Return ``(block_index, block)`` pairs whose type is one of ``types``."""
        return [(i, b) for i, b in enumerate(self.blocks) if b.type in types]

    def has_rotations(self) -> bool:
        """True when any element carries rotational DOF (shells, beams)."""
        return any(b.type in SHELL_TYPES + BEAM_TYPES + SPRING_TYPES for b in self.blocks) \
            or bool(self.rigid_links) or bool(self.interpolations)

    def describe_node(self, index: int) -> str:
        """Human-readable name of node ``index`` for messages: its file id and position."""
        x, y, z = self.points[index]
        return f"node {int(self.node_ids[index])} at ({x:.4g}, {y:.4g}, {z:.4g}) m"

    def node_index(self, ids, *, file=None, line=None, key=None) -> np.ndarray:
        """0-based positions in :attr:`points` of the nodes with file ids ``ids``.

        The ids are those of the mesh file (Nastran GRID ids, Gmsh node tags, Abaqus node
        numbers: :attr:`node_ids`); the positions are what :class:`flexpipe.Interface`
        ``nodes=`` and :attr:`node_sets` hold.  ``file``, ``line`` and ``key`` locate the
        ids in the user's input for the error (see :func:`index_of_ids`).

        Raises
        ------
        InputError
            An id that is no node of the mesh: the message gives the valid id range, the
            node count and, for each missing id, the nearest existing ids.
        """
        return index_of_ids(self.node_ids, ids, file=file, line=line, key=key)

    def nodes_of(self, name: str) -> np.ndarray:
        """Node indices of the node set ``name``, or of all cells of the cell set ``name``.

        Raises
        ------
        InputError
            When neither a node set nor a cell set has that name (message lists both).
        """
        if name in self.node_sets:
            return np.asarray(self.node_sets[name])
        if name in self.cell_sets:
            parts = [self.blocks[bi].cells[c].ravel() for bi, c in self.cell_sets[name].items()]
            return np.unique(np.concatenate(parts)) if parts else np.zeros(0, dtype=np.int64)
        from flexpipe.errors import InputError

        raise InputError(
            f"no node set or cell set '{name}'; node sets: {sorted(self.node_sets)}, "
            f"cell sets: {sorted(self.cell_sets)}", file=self.source or None, key=name,
        )

    def scaled(self, factor: float) -> Mesh:
        """Return a copy with all lengths multiplied by ``factor`` (e.g. 1e-3 for mm).

        Coordinates, offsets, shell thickness, beam A (factor^2) and I, J (factor^4) are
        scaled; materials, masses and inertias are not (see :mod:`flexpipe.mesh.units`).
        """
        from flexpipe.mesh.units import UnitSystem, convert

        return convert(self, UnitSystem(length=float(factor)), materials=False)


def _near(sorted_ids: np.ndarray, v: int) -> str:
    """``"99 -> 63"`` or ``"50 -> 48 or 52"``: the existing ids on either side of ``v``."""
    k = int(np.searchsorted(sorted_ids, v))
    near = [str(sorted_ids[j]) for j in (k - 1, k) if 0 <= j < len(sorted_ids)]
    return f"{v} -> {' or '.join(near)}"


def index_of_ids(node_ids, ids, *, file=None, line=None, key=None) -> np.ndarray:
    """0-based positions of the file node ids ``ids`` in ``node_ids`` (``Mesh.node_ids``).

    Parameters
    ----------
    node_ids : array_like of int
        The mesh's node ids, in node order.
    ids : array_like of int
        The ids to find, e.g. as a user copied them from a pre-processor.
    file, line, key : optional
        Where ``ids`` came from, named by the error (:class:`~flexpipe.errors.InputError`).

    Returns
    -------
    ndarray of int64
        Positions, in the order of ``ids``.

    Raises
    ------
    InputError
        ``ids`` not integers, or ids that are no node of the mesh (the message lists the
        first ten, each with its nearest existing ids, and the valid range and count).
    """
    from flexpipe.errors import InputError

    where = dict(file=file, line=line, key=key)
    want = np.asarray(ids)
    if want.dtype == bool or (want.size and not np.issubdtype(want.dtype, np.integer)):
        raise InputError(f"node ids must be integers, got {np.ravel(ids).tolist()[:10]}",
                         **where)
    want = want.astype(np.int64).reshape(-1)
    have = np.asarray(node_ids, dtype=np.int64).reshape(-1)
    order = np.argsort(have, kind="stable")
    srt = have[order]
    k = np.minimum(np.searchsorted(srt, want), max(len(srt) - 1, 0))
    found = (srt[k] == want) if len(srt) else np.zeros(want.shape, dtype=bool)
    if not found.all():
        missing = list(dict.fromkeys(want[~found].tolist()))
        more = f" and {len(missing) - 10} more" if len(missing) > 10 else ""
        if not len(srt):
            raise InputError(f"node ids {missing[:10]}{more} are not in the mesh: it has no "
                             "nodes", **where)
        lo, hi = int(srt[0]), int(srt[-1])
        span = f"{lo}..{hi}" if hi - lo + 1 == len(srt) else f"between {lo} and {hi}, with gaps"
        raise InputError(f"node ids {missing[:10]}{more} are not in the mesh; nearest existing "
                         f"ids: {'; '.join(_near(srt, v) for v in missing[:10])}; valid: the "
                         f"mesh's {len(srt)} node ids, {span}", **where)
    return order[k]
