"""Assembly: element families vectorized over all cells, scattered once into scipy.sparse.

Material and section data are resolved per cell: explicit arguments first (a single
value, or a mapping from cell-set name to value with an optional ``"default"``), then
the properties the mesh file carried (:attr:`Mesh.sections`, e.g. Nastran PSHELL/MAT1).
"""

from __future__ import annotations

import importlib

import numpy as np
import scipy.sparse as sp
from scipy.sparse.csgraph import connected_components

from flexpipe.errors import InputError, MeshError, ModelError
from flexpipe.fem import interpolation
from flexpipe.fem._element import BadElements
from flexpipe.fem.material import Material
from flexpipe.fem.model import FEModel
from flexpipe.fem.properties import (  # noqa: F401 - BeamSection is re-exported
    BeamSection,
    beam_props,
    material_arrays,
    shell_props,
)
from flexpipe.mesh.mesh import BEAM_TYPES, SHELL_TYPES, Mesh

try:  # private SciPy C++ routine (stable for a decade); a NumPy search replaces it if absent
    from scipy.sparse._sparsetools import csr_sample_offsets as _csr_sample_offsets
except ImportError:  # pragma: no cover - depends on the SciPy version
    _csr_sample_offsets = None

#: element family module for each meshio cell type
FAMILIES = {
    "tetra": "flexpipe.fem.tet4",
    "tetra10": "flexpipe.fem.tet10",
    "hexahedron": "flexpipe.fem.hex8",
    "triangle": "flexpipe.fem.shell_tri3",
    "quad": "flexpipe.fem.shell_quad4",
    "line": "flexpipe.fem.beam3d",
    "wedge": "flexpipe.fem.wedge6",
    "pyramid": "flexpipe.fem.pyramid5",
    "spring": "flexpipe.fem.spring",
    "spring1": "flexpipe.fem.spring",
}
CHUNK = 100_000  # most cells per vectorized batch (bounds peak memory)
BATCH_BYTES = 16 * 2**20  # target size of one batch of element matrices


def _batch_size(nd: int) -> int:
    """Cells per batch so that (ne, nd, nd) float arrays stay near BATCH_BYTES.

    Arrays of that size are recycled by the allocator instead of being mapped afresh
    for every batch, which on a 1M-DOF mesh saves more time than the batching costs.
    """
    return int(max(256, min(CHUNK, BATCH_BYTES // (8 * nd * nd))))


class _Stacked(tuple):
    """A tuple of per-cell arrays that slices element-wise like one array."""

    def __getitem__(self, sl):
        if isinstance(sl, slice):
            return tuple(a[sl] for a in self)
        return tuple.__getitem__(self, sl)


def _family(cell_type: str):
    try:
        return importlib.import_module(FAMILIES[cell_type])
    except KeyError:
        raise InputError(
            f"no finite element for cell type '{cell_type}'; valid: {sorted(FAMILIES)}"
        ) from None

class _Pattern:
    """Sparsity pattern of the assembled matrices, built once from the connectivity.

    The pattern is the set of node pairs sharing an element (plus the diagonal blocks
    of point-mass nodes), each a dense ``dpn x dpn`` block.  The matrices are stored in
    CSR with rows sorted and no duplicates; element matrices are summed straight into
    the CSR data array with ``np.add.at`` at precomputed positions, so no COO triplets,
    sorting or sparse additions are needed per batch.
    """

    def __init__(self, mesh: Mesh, dpn: int):
        n = mesh.n_nodes
        self.n, self.dpn = n, dpn
        parts = []
        for b in mesh.blocks:
            if b.type == "vertex" or len(b) == 0:
                continue
            for start in range(0, len(b), CHUNK):
                c = b.cells[start:start + CHUNK]
                parts.append(_unique_sorted((c[:, :, None] * n + c[:, None, :]).ravel()))
        pm = np.array([p.node for p in mesh.point_masses], dtype=np.int64)
        parts.append(pm * n + pm)
        keys = _unique_sorted(np.concatenate(parts)) if parts else np.zeros(0, np.int64)
        rows = keys // n
        cols = keys - rows * n
        counts = np.bincount(rows, minlength=n)
        start_b = np.concatenate([[0], np.cumsum(counts)])
        nnzb = len(keys)
        self.keys = keys
        self.nnz = nnzb * dpn * dpn
        n_dof = n * dpn
        self.itype = it = np.int32 if max(self.nnz, n_dof) < 2**31 - 1 else np.int64
        # node-level CSR of the block pattern (for the block look-up of element node pairs)
        nt = np.int32 if max(nnzb, n) < 2**31 - 1 else np.int64
        self._node_ptr = start_b.astype(nt)
        self._node_col = cols.astype(nt)
        # data position of entry (i, j) of block p in node row a (int64: fastest np.add.at):
        #   base[p] + i * row_stride[a] + j,  base[p] = dpn^2 start_b[a] + dpn (p - start_b[a])
        first = start_b[rows]
        self.base = dpn * dpn * first + dpn * (np.arange(nnzb) - first)
        self.row_stride = dpn * counts
        del first
        self.indptr = np.concatenate([[0], np.cumsum(np.repeat(dpn * counts, dpn))]).astype(it)
        # every DOF row of node a holds the columns [b * dpn + j for blocks b, j < dpn]
        self.indices = np.empty(self.nnz, dtype=it)
        stride = self.row_stride[rows]
        del rows
        for i in range(dpn):
            at = self.base + i * stride
            for j in range(dpn):
                self.indices[at + j] = cols * dpn + j

    def block_index(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """Index of block (a, b) in the pattern, for node index arrays of equal shape."""
        shape = np.shape(a)
        a = np.ascontiguousarray(a, dtype=self._node_col.dtype).ravel()
        b = np.ascontiguousarray(b, dtype=self._node_col.dtype).ravel()
        if _csr_sample_offsets is not None:
            # binary search within each short CSR row: ~6x faster than a global search
            out = np.empty(a.size, dtype=self._node_col.dtype)
            _csr_sample_offsets(self.n, self.n, self._node_ptr, self._node_col, a.size, a, b,
                                out)
        else:
            out = np.searchsorted(self.keys, a.astype(np.int64) * self.n + b)
        return out.reshape(shape)

    def positions(self, conn: np.ndarray, de: int) -> np.ndarray:
        """Data positions (ne, nn, de, nn, de) of element matrices with ``de`` DOF/node."""
        ne, nn = conn.shape
        p = self.block_index(np.broadcast_to(conn[:, :, None], (ne, nn, nn)),
                             np.broadcast_to(conn[:, None, :], (ne, nn, nn)))
        comp = np.arange(de)
        row = self.row_stride[conn][:, :, None] * comp          # (ne, nn, de)
        pos = np.empty((ne, nn, de, nn, de), dtype=np.int64)
        np.add(self.base[p][:, :, None, :, None] + row[:, :, :, None, None], comp, out=pos)
        return pos

    def add(self, data: np.ndarray, pos: np.ndarray, values: np.ndarray):
        """Sum element matrices (ne, nd, nd) into ``data``."""
        np.add.at(data, pos.ravel(), values.ravel())

    def add_sparse(self, data: np.ndarray, A):
        """Sum a (small) sparse matrix whose node blocks lie in the pattern into ``data``."""
        A = sp.coo_matrix(A)
        if A.nnz == 0:
            return
        r, c = A.row.astype(np.int64), A.col.astype(np.int64)
        a, i = np.divmod(r, self.dpn)
        b, j = np.divmod(c, self.dpn)
        p = self.block_index(a, b)
        np.add.at(data, self.base[p] + i * self.row_stride[a] + j, A.data)

    def matrix(self, data: np.ndarray, *, copy_structure: bool) -> sp.csr_matrix:
        """CSR matrix over all DOF from a data array laid out by this pattern."""
        n_dof = self.n * self.dpn
        idx = self.indices.copy() if copy_structure else self.indices
        ptr = self.indptr.copy() if copy_structure else self.indptr
        A = sp.csr_matrix((data, idx, ptr), shape=(n_dof, n_dof), copy=False)
        A.has_sorted_indices = True
        A.has_canonical_format = True
        return A


def _unique_sorted(k: np.ndarray) -> np.ndarray:
    """Sorted distinct values (sort + mask; faster than np.unique for large int arrays)."""
    k = np.sort(k)
    keep = np.ones(len(k), dtype=bool)
    keep[1:] = k[1:] != k[:-1]
    return k[keep]


def _check_connectivity(mesh: Mesh, *, allow_disconnected: bool):
    n = mesh.n_nodes
    rows, cols = [], []
    for b in mesh.blocks:
        c = b.cells
        for a in range(1, c.shape[1]):
            rows.append(c[:, 0])
            cols.append(c[:, a])
    for link in mesh.rigid_links:
        rows.append(np.full(len(link.slaves), link.master))
        cols.append(np.asarray(link.slaves))
    for it in mesh.interpolations:
        rows.append(np.full(len(it.nodes), it.ref))
        cols.append(np.asarray(it.nodes, dtype=np.int64))
    used = np.zeros(n, dtype=bool)
    for b in mesh.blocks:
        used[b.cells.ravel()] = True
    for link in mesh.rigid_links:
        used[link.master] = True
        used[np.asarray(link.slaves)] = True
    for pm in mesh.point_masses:
        used[pm.node] = True
    for it in mesh.interpolations:
        used[it.ref] = True
        used[np.asarray(it.nodes, dtype=np.int64)] = True
    if not used.all():
        idx = np.flatnonzero(~used)
        raise MeshError(
            f"{len(idx)} node(s) belong to no element, e.g. node ids "
            f"{mesh.node_ids[idx[:10]].tolist()}; delete them or read the mesh with "
            "prune_unreferenced=True", file=mesh.source or None,
        )
    if not rows:
        return
    r = np.concatenate(rows)
    c = np.concatenate(cols)
    G = sp.coo_matrix((np.ones(len(r)), (r, c)), shape=(n, n))
    ncomp, labels = connected_components(G, directed=False)
    if ncomp > 1 and not allow_disconnected:
        sizes = np.bincount(labels)
        parts = ", ".join(
            f"part {k + 1}: {sizes[k]} nodes incl. "
            f"{mesh.describe_node(int(np.argmax(labels == k)))}"
            for k in np.argsort(-sizes)[:5]
        )
        raise ModelError(
            f"{mesh.source or 'mesh'}: the structure falls into {ncomp} disconnected parts "
            f"({parts}); connect them (shared nodes, RBE2, springs): a flexible body (flexpipe "
            "reduce) must be one connected structure; for the modes of separate parts give "
            "flexpipe modes --allow-disconnected (in Python: assemble(..., "
            "allow_disconnected=True))"
        )


def _point_mass_matrix(mesh, dpn, n_dof):
    rows, cols, vals = [], [], []
    for pm in mesh.point_masses:
        base = pm.node * dpn
        m = float(pm.mass)
        if not np.isfinite(m) or m < 0:
            raise MeshError(f"point mass {pm.id} at {mesh.describe_node(pm.node)} has mass "
                            f"{m}; must be >= 0 kg", file=mesh.source or None)
        blk = np.zeros((dpn, dpn))
        blk[:3, :3] = m * np.eye(3)
        if pm.matrix is not None:
            blk = np.asarray(pm.matrix, dtype=float)[:dpn, :dpn]
        elif dpn == 6:
            r = np.asarray(pm.offset, dtype=float)
            S = np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])
            blk[:3, 3:] = -m * S
            blk[3:, :3] = m * S
            blk[3:, 3:] = m * S.T @ S + np.asarray(pm.inertia, dtype=float)
        ii, jj = np.meshgrid(np.arange(dpn) + base, np.arange(dpn) + base, indexing="ij")
        rows.append(ii.ravel())
        cols.append(jj.ravel())
        vals.append(blk.ravel())
    if not rows:
        return sp.csr_matrix((n_dof, n_dof))
    return sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                         shape=(n_dof, n_dof))


def _constraint_map(mesh, dpn, n_dof, K, M):
    """T (n_dof, n_indep): drops untouched DOF, ties RBE2 slave DOF to their master."""
    touched = (np.abs(K.diagonal()) > 0) | (np.abs(M.diagonal()) > 0)
    dependent = np.zeros(n_dof, dtype=bool)
    dep_rows, dep_cols, dep_vals = [], [], []
    masters = set()
    for link in mesh.rigid_links:
        masters.add(int(link.master))
    for link in mesh.rigid_links:
        comps = sorted({int(ch) - 1 for ch in link.dofs if ch in "123456"})
        xm = mesh.points[link.master]
        for s in np.asarray(link.slaves, dtype=np.int64):
            if s == link.master:
                continue
            if int(s) in masters:
                raise ModelError(
                    f"RBE2 {link.id}: slave {mesh.describe_node(int(s))} is itself the master of "
                    "another rigid link; merge the links into one"
                )
            d = mesh.points[s] - xm
            for c in comps:
                g = s * dpn + c
                if dependent[g]:
                    raise ModelError(f"RBE2 {link.id}: {mesh.describe_node(int(s))} component "
                                     f"{c + 1} is already tied by another rigid link")
                dependent[g] = True
                mb = link.master * dpn
                dep_rows.append(g)
                dep_cols.append(mb + c)
                dep_vals.append(1.0)
                if c < 3 and dpn == 6:  # u_s = u_m + theta_m x d
                    cross = np.zeros((3, 3))  # row c of [theta]x d = -S(d) theta
                    S = np.array([[0, -d[2], d[1]], [d[2], 0, -d[0]], [-d[1], d[0], 0]])
                    cross = -S
                    for k in range(3):
                        if cross[c, k] != 0:
                            dep_rows.append(g)
                            dep_cols.append(mb + 3 + k)
                            dep_vals.append(cross[c, k])
            touched[link.master * dpn: link.master * dpn + dpn] = True
    for it in mesh.interpolations:
        ref, cols_i, coef = interpolation.rows(it, mesh.points, mesh.node_ids)
        for j, c in enumerate(ref):
            g = it.ref * dpn + c
            if dependent[g]:
                raise ModelError(f"RBE3 {it.id}: reference {mesh.describe_node(it.ref)} "
                                 f"component {c + 1} is already dependent (another RBE2/RBE3)")
            dependent[g] = True
            nz = coef[j] != 0
            dep_rows.extend([g] * int(nz.sum()))
            dep_cols.extend((cols_i[nz, 0] * dpn + cols_i[nz, 1]).tolist())
            dep_vals.extend(coef[j][nz].tolist())
    indep = np.flatnonzero(touched & ~dependent)
    col_of = np.full(n_dof, -1, dtype=np.int64)
    col_of[indep] = np.arange(len(indep))
    P = sp.csr_matrix((np.ones(len(indep)), (indep, np.arange(len(indep)))),
                      shape=(n_dof, len(indep)))
    if not dep_rows:
        return P
    dc = np.asarray(dep_cols, dtype=np.int64)
    free = ~(dependent[dc] | (col_of[dc] >= 0))
    if free.any():
        bad = int(dc[np.flatnonzero(free)[0]])
        raise ModelError(
            f"a rigid element (RBE2 master or RBE3 independent node) uses "
            f"{mesh.describe_node(bad // dpn)} component {bad % dpn + 1}, which no element "
            "gives stiffness (e.g. a rotation of a solid node); use components it has")
    D = sp.csr_matrix((np.asarray(dep_vals, dtype=float), (np.asarray(dep_rows), dc)),
                      shape=(n_dof, n_dof))
    T = P
    for _ in range(16):  # chains: a dependent DOF expressed through other dependent DOF
        T_new = (P + D @ T).tocsr()
        if (T_new != T).nnz == 0:
            return T_new
        T = T_new
    raise ModelError("rigid elements (RBE2/RBE3) depend on each other in a loop or a chain "
                     "deeper than 16; merge them")


def assemble(mesh: Mesh, material=None, thickness=None, beam_section=None, *,
             allow_disconnected: bool = False, progress: bool = False,
             lumped: bool = False) -> FEModel:
    """Assemble mass and stiffness matrices of a mesh.

    Parameters
    ----------
    mesh : Mesh
    material : Material or mapping, optional
        One material, or ``{cell_set: Material, "default": Material}``; falls back to
        materials carried by the mesh (Nastran MAT1).
    thickness : float or mapping, optional
        Shell thickness in m, likewise per cell set; falls back to PSHELL T.
    beam_section : BeamSection or mapping, optional
        Beam cross-section, likewise per cell set.
    allow_disconnected : bool
        Accept a structure made of several unconnected parts.
    progress : bool
        Show a progress bar over element batches.
    lumped : bool
        Lumped (diagonal, translational) element masses instead of consistent ones, as
        Nastran's default ``PARAM COUPMASS -1`` (see :mod:`flexpipe.fem.lumped`).

    Returns
    -------
    FEModel

    Raises
    ------
    MeshError
        Missing material/thickness/section, inverted or degenerate elements, orphan nodes.
    ModelError
        Disconnected parts, inconsistent rigid links.
    """
    if isinstance(material, str):
        material = Material.named(material)
    _check_connectivity(mesh, allow_disconnected=allow_disconnected)
    dpn = 6 if mesh.has_rotations() else 3
    n_dof = mesh.n_nodes * dpn
    batches = []
    for bi, block in enumerate(mesh.blocks):
        if block.type == "vertex" or len(block) == 0:
            continue
        fam = _family(block.type)
        if getattr(fam, "FROM_DATA", False):  # springs: matrices computed by the reader
            E = nu = rho = np.zeros(len(block))
            props = {k: np.asarray(v) for k, v in block.data.items()}
        else:
            E, nu, rho = material_arrays(mesh, bi, block, material)
        if getattr(fam, "FROM_DATA", False):
            pass
        elif block.type in SHELL_TYPES:
            props = shell_props(mesh, bi, block, thickness)
            if "laminate_rows" in props:   # composite sections (PCOMP): A, D, Gt per cell
                from flexpipe.fem.properties import laminate_arrays

                lam = laminate_arrays(props.pop("laminate_rows"), E, nu, props["thickness"],
                                      props.pop("laminate_ref"), props.pop("laminate_theta"))
                props["laminate"] = _Stacked(lam)
        elif block.type in BEAM_TYPES:
            props = beam_props(mesh, bi, block, beam_section)
        else:
            props = {}
        size = _batch_size(block.cells.shape[1] * fam.DOFS_PER_NODE)
        for start in range(0, len(block), size):
            batches.append((bi, block, fam, E, nu, rho, props, slice(start, start + size)))
    iterator = batches
    if progress and len(batches) > 1:
        from tqdm import tqdm

        iterator = tqdm(batches, desc="assembling", unit="batch")
    pattern = _Pattern(mesh, dpn)
    Kdata = np.zeros(pattern.nnz)
    Mdata = np.zeros(pattern.nnz)
    damped = any("B" in b.data for b in mesh.blocks)
    Cdata = np.zeros(pattern.nnz) if damped else None
    for _bi, block, fam, E, nu, rho, props, sl in iterator:
        conn = block.cells[sl]
        X = mesh.points[conn]
        try:
            Ke, Me = fam.matrices(X, E=E[sl], nu=nu[sl], rho=rho[sl],
                                  **{k: v[sl] for k, v in props.items()})
        except BadElements as exc:
            ids = block.ids[sl][exc.index[:10]].tolist()
            raise MeshError(
                f"{len(exc.index)} {block.type} element(s) are {exc.reason}, e.g. element "
                f"ids {ids}; fix the node order/coordinates of these elements",
                file=mesh.source or None,
            ) from None
        if lumped:
            from flexpipe.fem.lumped import lump

            Me = lump(Me, fam.DOFS_PER_NODE)
        # exact symmetry of the element matrices makes the assembled ones exactly symmetric
        # (both triangles receive the same values in the same order)
        if not getattr(fam, "SYMMETRIC", False):
            Ke = Ke + Ke.transpose(0, 2, 1)
            Ke *= 0.5
            Me = Me + Me.transpose(0, 2, 1)
            Me *= 0.5
        de = fam.DOFS_PER_NODE
        pos = pattern.positions(conn, de)
        pattern.add(Kdata, pos, Ke)
        pattern.add(Mdata, pos, Me)
        if damped and "B" in props:
            pattern.add(Cdata, pos, fam.damping(X, **{k: v[sl] for k, v in props.items()}))
        del Ke, Me, pos
    Mp = _point_mass_matrix(mesh, dpn, n_dof)
    pattern.add_sparse(Mdata, (Mp + Mp.T) * 0.5)
    C = None
    if damped:   # before K takes over (and compresses) the shared index arrays
        C = pattern.matrix(Cdata, copy_structure=True)
        C.eliminate_zeros()
    K = pattern.matrix(Kdata, copy_structure=False)
    M = pattern.matrix(Mdata, copy_structure=True)
    # drop exact zeros (unused rotation entries of solid nodes in a 6-DOF model, couplings
    # that vanish on regular grids): less work for the factorization
    K.eliminate_zeros()
    M.eliminate_zeros()
    try:
        T = _constraint_map(mesh, dpn, n_dof, K, M)
    except ModelError as exc:
        if mesh.source and mesh.source not in str(exc):
            raise ModelError(f"{mesh.source}: {exc}") from None
        raise
    # the property arguments, so that stresses (flexpipe.fem.stress) use the same values
    info = {"material": material, "thickness": thickness, "beam_section": beam_section}
    return FEModel(M=M, K=K, nodes=np.array(mesh.points), dofs_per_node=dpn, T=T, mesh=mesh,
                   C=C, info=info)
