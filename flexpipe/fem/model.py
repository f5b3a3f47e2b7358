"""The :class:`FEModel` data object: assembled mass and stiffness of one structure."""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np
import scipy.sparse as sp

from flexpipe._arrays import frozen_arrays
from flexpipe.mesh.mesh import Mesh

COMPONENTS = ("ux", "uy", "uz", "rx", "ry", "rz")


@dataclass(frozen=True)
@frozen_arrays
class FEModel:
    """Assembled linear finite-element model.

    DOF numbering is node-major: ``dof = node * dofs_per_node + component`` with
    components ``ux, uy, uz, rx, ry, rz``.

    Attributes
    ----------
    M, K : scipy.sparse.csr_matrix, shape (n_dof, n_dof)
        Symmetric mass and stiffness over all DOF (unused DOF have empty rows).
    nodes : ndarray, shape (n_nodes, 3)
        Node coordinates, m.
    dofs_per_node : int
        3 (solids only) or 6 (any shell, beam or rigid link present).
    T : scipy.sparse.csr_matrix, shape (n_dof, n_indep)
        Map from independent DOF to all DOF, ``u = T @ q``: drops DOF no element
        touches and expresses rigid-link (RBE2) slave DOF through their master.
    mesh : Mesh, optional
        The mesh the model was assembled from.
    C : scipy.sparse.csr_matrix, optional
        Viscous damping of discrete dampers (Nastran CBUSH/PBUSH B), when the mesh has any.
    """

    M: sp.csr_matrix
    K: sp.csr_matrix
    nodes: np.ndarray
    dofs_per_node: int
    T: sp.csr_matrix | None = None
    mesh: Mesh | None = None
    info: dict = field(default_factory=dict)
    C: sp.csr_matrix | None = None

    def __post_init__(self):
        if self.T is None:
            object.__setattr__(self, "T", sp.identity(self.n_dof, format="csr"))

    @property
    def n_dof(self) -> int:
        """Number of DOF before constraints."""
        return self.M.shape[0]

    @property
    def n_nodes(self) -> int:
        """Number of nodes."""
        return len(self.nodes)

    @cached_property
    def Kr(self) -> sp.csr_matrix:
        """Stiffness on the independent DOF, ``T^T K T``."""
        return sp.csr_matrix(self.T.T @ self.K @ self.T)

    @cached_property
    def Mr(self) -> sp.csr_matrix:
        """Mass on the independent DOF, ``T^T M T``."""
        return sp.csr_matrix(self.T.T @ self.M @ self.T)

    @cached_property
    def independent_of_dof(self) -> np.ndarray:
        """For each DOF, the independent DOF it equals one-to-one, or -1 if none."""
        T = sp.csr_matrix(self.T)
        out = np.full(self.n_dof, -1, dtype=np.int64)
        counts = np.diff(T.indptr)
        rows = np.flatnonzero(counts == 1)
        cols = T.indices[T.indptr[rows]]
        vals = T.data[T.indptr[rows]]
        ok = np.isclose(vals, 1.0)
        # a column that is referenced by more than one row is a master: still one-to-one
        out[rows[ok]] = cols[ok]
        return out

    def dof(self, node, component=0) -> np.ndarray:
        """Global DOF index of ``component`` (0..5 or name) at node index ``node``."""
        if isinstance(component, str):
            component = COMPONENTS.index(component)
        if component >= self.dofs_per_node:
            raise ValueError(
                f"component {COMPONENTS[component]} does not exist in a model with "
                f"{self.dofs_per_node} DOF per node"
            )
        return np.asarray(node) * self.dofs_per_node + component

    def expand(self, q: np.ndarray) -> np.ndarray:
        """Expand independent-DOF vectors (n_indep,) or (n_indep, k) to all DOF."""
        return self.T @ q

    def translations(self, u: np.ndarray) -> np.ndarray:
        """Nodal translations (n_nodes, 3) of an all-DOF vector ``u``."""
        return np.asarray(u).reshape(self.n_nodes, self.dofs_per_node)[:, :3]

    @property
    def total_mass(self) -> float:
        """Translational mass: ``r^T M r`` for a unit rigid translation in x."""
        r = np.zeros(self.n_dof)
        r[0::self.dofs_per_node] = 1.0
        return float(r @ (self.M @ r))
