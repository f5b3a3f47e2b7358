"""Generic FE core: assembly, mass, symmetry, eigenmodes, solver backends, bad input.

References are closed forms (rho * V, rigid-body inertia of a block, six rigid-body
modes), an independent dense assembly loop, and dense LAPACK eigenvalues.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
import scipy.sparse as sp

from flexpipe.errors import InputError, MeshError, ModelError
from flexpipe.fem import Material, assemble, eigenmodes
from flexpipe.fem.assemble import FAMILIES
from flexpipe.fem.modes import solve_eigen
from flexpipe.fem.solver import available_backends, factorize
from flexpipe.mesh import CellBlock, Mesh, PointMass, RigidLink
from flexpipe.mesh.generate import box, plate

STEEL = Material(210e9, 0.3, 7850.0)
CELLS = ("tetra", "tetra10", "hexahedron")


def _distorted_box(cell, n=(3, 2, 2), size=(0.6, 0.3, 0.2), amount=0.2, seed=1):
    """Block mesh whose interior nodes are moved randomly (the block shape is unchanged)."""
    if cell == "tetra10":
        from flexpipe.mesh.generate import add_midside_nodes

        m4 = _distorted_box("tetra", n, size, amount, seed)
        pts, cells = add_midside_nodes(m4.points, m4.blocks[0].cells)
        return Mesh(pts, (CellBlock("tetra10", cells),))
    m = box(*size, *n, cell=cell)
    rng = np.random.default_rng(seed)
    on_face = np.zeros(m.n_nodes, dtype=bool)
    for s in m.node_sets.values():
        on_face[s] = True
    h = np.array(size) / np.array(n)
    pts = np.array(m.points)
    inner = ~on_face
    pts[inner] += amount * h * rng.uniform(-1, 1, (inner.sum(), 3))
    return Mesh(pts, m.blocks, node_sets=m.node_sets)


def _rigid_modes(points):
    """Six rigid-body displacement fields (3 translations, 3 small rotations), (3n, 6)."""
    n = len(points)
    R = np.zeros((n, 3, 6))
    R[:, [0, 1, 2], [0, 1, 2]] = 1.0
    x, y, z = points.T
    R[:, 1, 3], R[:, 2, 3] = -z, y      # rotation about x: (0, -z, y)
    R[:, 0, 4], R[:, 2, 4] = z, -x      # about y: (z, 0, -x)
    R[:, 0, 5], R[:, 1, 5] = -y, x      # about z: (-y, x, 0)
    return R.reshape(3 * n, 6)


@pytest.mark.parametrize("cell", CELLS)
def test_total_mass_and_inertia_of_a_block(cell):
    """Consistent mass reproduces rho V and the block's rigid-body inertia exactly."""
    L, b, h = 0.6, 0.3, 0.2
    fe = assemble(_distorted_box(cell), STEEL)
    m = STEEL.rho * L * b * h
    assert fe.total_mass == pytest.approx(m, rel=1e-12)
    R = _rigid_modes(fe.nodes)
    MR = R.T @ (fe.M @ R)
    # rotations about the axes through the origin corner: rho int (y^2 + z^2) dV etc.
    Ixx = m * (b**2 + h**2) / 3
    Iyy = m * (L**2 + h**2) / 3
    Izz = m * (L**2 + b**2) / 3
    assert np.diag(MR)[3:] == pytest.approx([Ixx, Iyy, Izz], rel=1e-12)
    # static moments: translation x against rotation about z = -int rho y dV ... = m * centroid
    cx, cy, cz = L / 2, b / 2, h / 2
    assert MR[0, 5] == pytest.approx(-m * cy, rel=1e-12)
    assert MR[1, 5] == pytest.approx(m * cx, rel=1e-12)
    assert MR[2, 3] == pytest.approx(m * cy, rel=1e-12)
    assert MR[0, 4] == pytest.approx(m * cz, rel=1e-12)


@pytest.mark.parametrize("cell", CELLS)
def test_matrices_symmetric_and_rigid_motion_strain_free(cell):
    fe = assemble(_distorted_box(cell), STEEL)
    for A in (fe.K, fe.M):
        assert abs(A - A.T).max() == 0.0
    R = _rigid_modes(fe.nodes)
    assert np.abs(fe.K @ R).max() < 1e-8 * abs(fe.K).max() * np.abs(R).max()
    # the mass matrix is positive definite: Cholesky-type factorization succeeds
    factorize(fe.M)


def _dense_reference(mesh, material, dpn):
    """Independent assembly: plain loop over elements into a dense matrix."""
    import importlib

    n = mesh.n_nodes * dpn
    K = np.zeros((n, n))
    M = np.zeros((n, n))
    for b in mesh.blocks:
        fam = importlib.import_module(FAMILIES[b.type])
        de = fam.DOFS_PER_NODE
        for cell in b.cells:
            one = np.ones(1)
            Ke, Me = fam.matrices(mesh.points[cell][None], E=one * material.E,
                                  nu=one * material.nu, rho=one * material.rho)
            dofs = (cell[:, None] * dpn + np.arange(de)).ravel()
            K[np.ix_(dofs, dofs)] += Ke[0]
            M[np.ix_(dofs, dofs)] += Me[0]
    for pm in mesh.point_masses:
        M[pm.node * dpn + np.arange(3), pm.node * dpn + np.arange(3)] += pm.mass
    return K, M


@pytest.mark.parametrize("lookup", ["scipy", "numpy"])
@pytest.mark.parametrize("dpn_case", ["solid", "with_rigid_link"])
def test_sparse_assembly_matches_dense_loop(dpn_case, lookup, monkeypatch):
    """Pattern-based scatter == naive dense loop, for mixed tet4 + hex8 blocks, 3 and 6 DOF,
    with SciPy's CSR look-up of the element blocks and with its NumPy fallback."""
    if lookup == "numpy":
        import importlib

        monkeypatch.setattr(importlib.import_module("flexpipe.fem.assemble"),
                            "_csr_sample_offsets", None)
    hexes = box(0.2, 0.1, 0.1, 2, 1, 1, cell="hexahedron")
    tets = box(0.2, 0.1, 0.1, 2, 1, 1, cell="tetra", origin=(0.2, 0.0, 0.0))
    pts = np.vstack([hexes.points, tets.points])
    tcells = tets.blocks[0].cells + hexes.n_nodes
    # merge coincident nodes on the interface x = 0.2
    key = np.round(pts, 12)
    _, first, inv = np.unique(key, axis=0, return_index=True, return_inverse=True)
    pts_u = pts[first]
    blocks = [CellBlock("hexahedron", inv.ravel()[hexes.blocks[0].cells]),
              CellBlock("tetra", inv.ravel()[tcells])]
    links = ()
    masses = (PointMass(node=0, mass=3.0),)
    if dpn_case == "with_rigid_link":
        links = (RigidLink(master=1, slaves=np.array([2])),)
    mesh = Mesh(pts_u, tuple(blocks), point_masses=masses, rigid_links=links)
    fe = assemble(mesh, STEEL)
    Kd, Md = _dense_reference(mesh, STEEL, fe.dofs_per_node)
    scale = np.abs(Kd).max()
    assert np.abs(fe.K.toarray() - Kd).max() < 1e-12 * scale
    assert np.abs(fe.M.toarray() - Md).max() < 1e-12 * np.abs(Md).max()
    assert fe.dofs_per_node == (6 if links else 3)


@pytest.mark.parametrize("cell", CELLS)
def test_free_body_has_six_rigid_modes_and_no_spurious_ones(cell):
    """Six ~0 Hz modes, then the first elastic mode (hourglass check)."""
    L, b, h = 0.6, 0.3, 0.2
    fe = assemble(_distorted_box(cell, n=(4, 2, 2)), STEEL)
    f, Phi = eigenmodes(fe, 8)
    # beam-theory scale of the first bending mode of this stocky block
    I = b * h**3 / 12
    f_beam = 4.7300407**2 / (2 * np.pi * L**2) * np.sqrt(STEEL.E * I / (STEEL.rho * b * h))
    assert np.all(f[:6] < 1e-4 * f_beam)
    assert f[6] > 0.3 * f_beam
    # the six modes span the rigid-body motions: their M-projection onto R is complete
    R = _rigid_modes(fe.nodes)
    C = Phi[:, :6].T @ (fe.M @ R)
    assert np.linalg.svd(C, compute_uv=False).min() > 1e-6 * np.linalg.norm(C)
    # mass normalisation
    assert np.einsum("ij,ij->j", Phi, fe.M @ Phi) == pytest.approx(np.ones(8), rel=1e-8)


def test_eigenmodes_match_dense_lapack_with_fixed_dofs():
    """Sparse shift-invert Lanczos with fixed DOF == dense eigh of the reduced matrices."""
    mesh = box(0.4, 0.05, 0.05, 8, 1, 1, cell="hexahedron")
    fe = assemble(mesh, STEEL)
    fixed = (mesh.node_sets["xmin"][:, None] * 3 + np.arange(3)).ravel()
    f, Phi = eigenmodes(fe, 5, fixed_dofs=fixed)
    free = np.setdiff1d(np.arange(fe.n_dof), fixed)
    lam = sla.eigh(fe.K.toarray()[np.ix_(free, free)], fe.M.toarray()[np.ix_(free, free)],
                   eigvals_only=True, subset_by_index=[0, 4])
    assert f == pytest.approx(np.sqrt(lam) / (2 * np.pi), rel=1e-8)
    assert np.abs(Phi[fixed]).max() == 0.0


def test_fixed_dofs_out_of_range_is_rejected():
    fe = assemble(box(0.2, 0.05, 0.05, 2, 1, 1, cell="hexahedron"), STEEL)
    with pytest.raises(InputError, match=r"fixed_dofs must lie in \[0, 36\)"):
        eigenmodes(fe, 3, fixed_dofs=[0, 36])
    with pytest.raises(InputError, match="positive integer"):
        eigenmodes(fe, 0)


@pytest.mark.skipif("pardiso" not in available_backends(), reason="pypardiso not installed")
def test_solver_backends_agree():
    fe = assemble(box(0.4, 0.1, 0.1, 6, 2, 2, cell="tetra10"), STEEL)
    A = (fe.K + 1e3 * fe.M).tocsr()
    rhs = np.random.default_rng(0).normal(size=(fe.n_dof, 2))
    x_p = factorize(A, backend="pardiso").solve(rhs)
    x_s = factorize(A, backend="superlu").solve(rhs)
    assert np.abs(A @ x_p - rhs).max() < 1e-6 * np.abs(rhs).max()      # cond(A) ~ 1e8
    assert np.abs(x_p - x_s).max() < 1e-6 * np.abs(x_s).max()
    # free body: K - sigma M is ill-conditioned (rigid modes at -sigma); shift-invert must
    # still reproduce dense LAPACK, with and without deflating the rigid-body modes
    # (PARDISO's default iterative refinement made the elastic frequencies 8 % wrong)
    lam = sla.eigh(fe.K.toarray(), fe.M.toarray(), eigvals_only=True, subset_by_index=[6, 9])
    f_ref = np.sqrt(lam) / (2 * np.pi)
    for backend in ("pardiso", "superlu"):
        for deflate in (True, False):
            f, _ = eigenmodes(fe, 10, backend=backend, deflate_rigid=deflate)
            assert f[6:] == pytest.approx(f_ref, rel=1e-7)
            assert np.all(f[:6] < 1e-2)


def test_solve_eigen_dense_path_matches_lapack():
    rng = np.random.default_rng(3)
    A = rng.normal(size=(20, 20))
    K = A @ A.T + 20 * np.eye(20)
    M = np.diag(rng.uniform(1, 2, 20))
    lam, X = solve_eigen(sp.csr_matrix(K), sp.csr_matrix(M), 4)
    assert lam == pytest.approx(sla.eigh(K, M, eigvals_only=True)[:4], rel=1e-12)


@pytest.mark.parametrize("cell", CELLS)
def test_inverted_element_error_names_the_element_id(cell):
    m = box(0.3, 0.1, 0.1, 3, 1, 1, cell=cell)
    cells = np.array(m.blocks[0].cells)
    ids = np.arange(5001, 5001 + len(cells))
    bad = 2
    if cell == "hexahedron":  # mirror the element: swap bottom and top faces
        cells[bad] = cells[bad][[4, 5, 6, 7, 0, 1, 2, 3]]
    else:  # swap two vertices (and, for tet10, the mid-edge nodes that follow them)
        perm = [1, 0, 2, 3] if cell == "tetra" else [1, 0, 2, 3, 4, 6, 5, 8, 7, 9]
        cells[bad] = cells[bad][perm]
    mesh = Mesh(m.points, (CellBlock(cell, cells, ids=ids),), source="bar.bdf")
    with pytest.raises(MeshError, match=rf"bar\.bdf.*1 {cell} element\(s\).*ids \[{ids[bad]}\]"):
        assemble(mesh, STEEL)


def test_disconnected_parts_are_reported_or_allowed():
    a = box(0.2, 0.1, 0.1, 2, 1, 1, cell="hexahedron")
    b = box(0.2, 0.1, 0.1, 2, 1, 1, cell="hexahedron", origin=(0.5, 0.0, 0.0))
    pts = np.vstack([a.points, b.points])
    cells = np.vstack([a.blocks[0].cells, b.blocks[0].cells + a.n_nodes])
    mesh = Mesh(pts, (CellBlock("hexahedron", cells),))
    with pytest.raises(ModelError, match="2 disconnected parts"):
        assemble(mesh, STEEL)
    fe = assemble(mesh, STEEL, allow_disconnected=True)
    f, _ = eigenmodes(fe, 13)
    assert np.all(f[:12] < 1e-2) and f[12] > 100.0     # 2 x 6 rigid-body modes


def test_orphan_node_is_reported_with_its_id():
    m = box(0.2, 0.1, 0.1, 2, 1, 1, cell="tetra")
    pts = np.vstack([m.points, [[5.0, 5.0, 5.0]]])
    ids = np.arange(101, 101 + len(pts))
    mesh = Mesh(pts, m.blocks, node_ids=ids)
    with pytest.raises(MeshError, match=rf"1 node\(s\) belong to no element.*\[{ids[-1]}\]"):
        assemble(mesh, STEEL)


def test_missing_material_is_reported():
    with pytest.raises(MeshError, match="no material"):
        assemble(box(0.2, 0.1, 0.1, 2, 1, 1), None)


def test_rigid_link_and_point_mass_in_a_six_dof_model():
    """Solid bar + RBE2 spider to a 2 kg point mass: mass adds up, 6 rigid modes remain."""
    m = box(0.4, 0.05, 0.05, 8, 1, 1, cell="hexahedron")
    pts = np.vstack([m.points, [[0.45, 0.025, 0.025]]])
    master = len(pts) - 1
    mesh = Mesh(pts, m.blocks, rigid_links=(RigidLink(master, m.node_sets["xmax"]),),
                point_masses=(PointMass(master, 2.0),))
    fe = assemble(mesh, STEEL)
    assert fe.dofs_per_node == 6
    assert fe.total_mass == pytest.approx(STEEL.rho * 0.4 * 0.05**2 + 2.0, rel=1e-12)
    assert fe.Kr.shape[0] == 3 * (m.n_nodes - 4) + 6     # slaves tied, solid rotations dropped
    f, _ = eigenmodes(fe, 7)
    assert np.all(f[:6] < 1e-2) and f[6] > 10.0


@pytest.mark.parametrize("cell", CELLS)
def test_box_generator_orientation_and_sets(cell):
    m = box(2.0, 1.0, 0.5, 4, 2, 3, cell=cell)
    nodes_per_axis = {"tetra": 1, "tetra10": 2, "hexahedron": 1}[cell]
    k = nodes_per_axis
    assert len(m.node_sets["xmin"]) == (2 * k + 1) * (3 * k + 1)
    assert np.allclose(m.points[m.node_sets["xmax"], 0], 2.0)
    # positive orientation == assembly succeeds; volume from the mass
    fe = assemble(m, Material(1e9, 0.3, 1.0))
    assert fe.total_mass == pytest.approx(1.0, rel=1e-12)
    n_cells = 24 * (6 if cell != "hexahedron" else 1)
    assert len(m.blocks[0]) == n_cells


@pytest.mark.parametrize("cell", ["quad", "triangle"])
def test_plate_generator(cell):
    m = plate(2.0, 1.0, 4, 2, cell=cell)
    assert m.n_nodes == 15 and np.all(m.points[:, 2] == 0.0)
    c = m.blocks[0].cells
    P = m.points[c]
    # counter-clockwise seen from +z: positive signed area of every cell (shoelace)
    x, y = P[..., 0], P[..., 1]
    area = 0.5 * np.sum(x * np.roll(y, -1, axis=1) - np.roll(x, -1, axis=1) * y, axis=1)
    assert np.all(area > 0) and area.sum() == pytest.approx(2.0)
    assert sorted(m.node_sets["ymax"].tolist()) == [2, 5, 8, 11, 14]
    with pytest.raises(InputError, match="cell must be"):
        plate(1.0, 1.0, 2, 2, cell="hexahedron")
    with pytest.raises(InputError, match="positive integer"):
        plate(1.0, 1.0, 0, 2)
