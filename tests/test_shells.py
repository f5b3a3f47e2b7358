"""Verification of the flat shell elements (quad4 = QM6 + MITC4, tri3 = CST + DKT).

References are independent of the code: Kirchhoff plate closed forms, Euler-Bernoulli
beam eigenvalues, published plate tables, patch-test fields and conservation of mass.
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla
from scipy.spatial.transform import Rotation

from flexpipe.errors import MeshError
from flexpipe.fem import Material, assemble, eigenmodes
from flexpipe.mesh.mesh import CellBlock, Mesh

E, NU, RHO, T = 2.0e11, 0.3, 7800.0, 0.01
STEEL = Material(E, NU, RHO)
CELLS = ["quad", "triangle"]


def plate_mesh(a, b, nx, ny, cell="quad", *, distort=0.0, frame=None, seed=0):
    """Structured a x b plate; interior nodes jittered by ``distort`` x spacing; optional
    rigid placement ``frame = (Q, origin)`` into 3D."""
    x, y = np.meshgrid(np.linspace(0, a, nx + 1), np.linspace(0, b, ny + 1), indexing="ij")
    pts = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    if distort:
        rng = np.random.default_rng(seed)
        inner = (x.ravel() > 0) & (x.ravel() < a) & (y.ravel() > 0) & (y.ravel() < b)
        jitter = rng.uniform(-1, 1, (inner.sum(), 2)) * distort * np.array([a / nx, b / ny])
        pts[inner, :2] += jitter
    idx = np.arange(x.size).reshape(nx + 1, ny + 1)
    quads = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], -1).reshape(-1, 4)
    if frame is not None:
        Q, origin = frame
        pts = pts @ Q.T + origin
    if cell == "quad":
        return Mesh(pts, (CellBlock("quad", quads),))
    tris = np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]])
    return Mesh(pts, (CellBlock("triangle", tris),))


def node_dofs(nodes, comps):
    nodes = np.asarray(nodes)
    return (nodes[:, None] * 6 + np.asarray(comps)[None, :]).ravel()


def kirchhoff_ssss(a, b, count):
    """Closed-form SSSS frequencies f_mn = pi/2 ((m/a)^2 + (n/b)^2) sqrt(D / (rho t))."""
    D = E * T**3 / (12 * (1 - NU**2))
    f = [np.pi / 2 * ((m / a) ** 2 + (n / b) ** 2) * np.sqrt(D / (RHO * T))
         for m in range(1, 8) for n in range(1, 8)]
    return np.sort(f)[:count]


def ssss_frequencies(cell, n, count, a=1.0, b=1.0):
    mesh = plate_mesh(a, b, n, n, cell)
    fe = assemble(mesh, STEEL, thickness=T)
    P = mesh.points
    on_x = np.flatnonzero(np.isclose(P[:, 0], 0) | np.isclose(P[:, 0], a))
    on_y = np.flatnonzero(np.isclose(P[:, 1], 0) | np.isclose(P[:, 1], b))
    everyone = np.arange(len(P))
    # hard simple support: w = 0 and zero rotation about the edge normal; in-plane held
    fixed = np.concatenate([node_dofs(everyone, [0, 1, 5]), node_dofs(on_x, [2, 3]),
                            node_dofs(on_y, [2, 4])])
    f, _ = eigenmodes(fe, count, fixed)
    return f


@pytest.mark.parametrize("cell", CELLS)
def test_total_mass_equals_rho_area_thickness(cell):
    Q = Rotation.from_euler("xyz", [0.3, -0.7, 1.1]).as_matrix()
    mesh = plate_mesh(1.2, 0.7, 6, 5, cell, distort=0.3, frame=(Q, np.array([1.0, -2.0, 0.5])))
    fe = assemble(mesh, STEEL, thickness=T)
    assert fe.total_mass == pytest.approx(RHO * 1.2 * 0.7 * T, rel=1e-12)


@pytest.mark.parametrize("cell", CELLS)
def test_ssss_plate_frequencies_within_1_percent(cell):
    f = ssss_frequencies(cell, 32, 6)
    ref = kirchhoff_ssss(1.0, 1.0, 6)
    np.testing.assert_allclose(f, ref, rtol=0.01)


@pytest.mark.parametrize("cell", CELLS)
def test_ssss_convergence_rate_is_second_order(cell):
    ref = kirchhoff_ssss(1.0, 1.0, 1)[0]
    err = np.array([ssss_frequencies(cell, n, 1)[0] / ref - 1 for n in (4, 8, 16)])
    rates = np.log2(err[:-1] / err[1:])
    assert (err > 0).all()  # consistent mass + conforming-like stiffness: from above
    assert ((rates > 1.8) & (rates < 2.4)).all(), (err, rates)
    assert err[-1] < 0.005


# Square plate, nu = 0.3, lambda = omega a^2 sqrt(rho t / D).  Values of Leissa, "The free
# vibration of rectangular plates", J. Sound Vib. 31(3) 257-293 (1973), as tabulated in the
# code_aster validation manual V2.03.001 (SDLS01, after Barton 1951).  They are Ritz upper
# bounds (converged FE lies up to ~0.9 % below), hence the 1 % tolerance.
LAMBDA_CFFF = np.array([3.492, 8.525, 21.43, 27.33, 31.11])
LAMBDA_FFFF = np.array([13.49, 19.79, 24.43, 35.02, 35.02])


def _lambda(f, a=1.0):
    D = E * T**3 / (12 * (1 - NU**2))
    return 2 * np.pi * f * a**2 * np.sqrt(RHO * T / D)


@pytest.mark.parametrize("cell", CELLS)
def test_cantilever_square_plate_against_leissa(cell):
    mesh = plate_mesh(1.0, 1.0, 16, 16, cell)
    fe = assemble(mesh, STEEL, thickness=T)
    clamped = np.flatnonzero(np.isclose(mesh.points[:, 0], 0.0))
    f, _ = eigenmodes(fe, 5, node_dofs(clamped, range(6)))
    np.testing.assert_allclose(_lambda(f), LAMBDA_CFFF, rtol=0.01)


@pytest.mark.parametrize("cell", CELLS)
def test_free_plate_rigid_modes_and_leissa_in_3d_placement(cell):
    """Free plate placed obliquely in space: exactly six zero modes, then the free-plate
    table; also checks the local frames / rotation to global."""
    Q = Rotation.from_euler("zyx", [0.4, 1.0, -0.6]).as_matrix()
    mesh = plate_mesh(1.0, 1.0, 16, 16, cell, frame=(Q, np.array([3.0, -1.0, 2.0])))
    fe = assemble(mesh, STEEL, thickness=T)
    f, _ = eigenmodes(fe, 11)
    first_elastic = f[6]
    assert np.all(f[:6] < 1e-4 * first_elastic)
    np.testing.assert_allclose(_lambda(f[6:]), LAMBDA_FFFF, rtol=0.01)


@pytest.mark.parametrize("cell", CELLS)
def test_narrow_strip_matches_euler_bernoulli(cell):
    """Shell strip (nu = 0, so D b = E I exactly): out-of-plane bending vs beam theory."""
    L, b, t = 1.0, 0.04, 0.004
    mat = Material(E, 0.0, RHO)
    mesh = plate_mesh(L, b, 40, 2, cell)
    fe = assemble(mesh, mat, thickness=t)
    c = np.sqrt(E * b * t**3 / 12 / (RHO * b * t)) / (2 * np.pi * L**2)
    # free-free: first two elastic modes are out-of-plane bending (torsion, in-plane higher)
    f, X = eigenmodes(fe, 8)
    assert np.all(f[:6] < 1e-3 * f[6])
    np.testing.assert_allclose(f[6:8], c * np.array([4.7300, 7.8532]) ** 2, rtol=0.01)
    uz = np.abs(fe.translations(X[:, 6])[:, 2]).max()
    assert uz > 10 * np.abs(fe.translations(X[:, 6])[:, :2]).max()
    clamped = np.flatnonzero(np.isclose(mesh.points[:, 0], 0.0))
    f, _ = eigenmodes(fe, 2, node_dofs(clamped, range(6)))
    np.testing.assert_allclose(f, c * np.array([1.8751, 4.6941]) ** 2, rtol=0.01)


def _patch_solve(fe, prescribed_dofs, values):
    """Solve K u = 0 with ``u[prescribed] = values``; return u (all DOF)."""
    K = fe.K.tocsr()
    n = K.shape[0]
    u = np.zeros(n)
    u[prescribed_dofs] = values
    free = np.setdiff1d(np.arange(n), prescribed_dofs)
    rhs = -K[free][:, prescribed_dofs] @ values
    u[free] = spla.spsolve(K[free][:, free].tocsc(), rhs)
    return u


@pytest.mark.parametrize("cell", CELLS)
def test_membrane_patch_test_distorted_mesh(cell):
    """Linear in-plane field on the boundary -> exact linear field inside, constant strain
    energy 1/2 eps.C.eps t A (mesh jittered by 35 % and placed obliquely in 3D)."""
    Q = Rotation.from_euler("xyz", [0.5, 0.2, -0.9]).as_matrix()
    origin = np.array([0.2, 0.1, -0.3])
    mesh = plate_mesh(1.0, 0.8, 4, 4, cell, distort=0.35, frame=(Q, origin), seed=3)
    fe = assemble(mesh, STEEL, thickness=T)
    e1, e2 = Q[:, 0], Q[:, 1]
    s = (mesh.points - origin) @ np.column_stack([e1, e2])          # in-plane coordinates
    Gu = np.array([[1.0e-3, 0.4e-3], [-0.2e-3, -0.5e-3]])           # du_i / ds_j
    u_loc = s @ Gu.T
    omega = 0.5 * (Gu[1, 0] - Gu[0, 1])
    U = np.zeros((len(s), 6))
    U[:, :3] = u_loc[:, :1] * e1 + u_loc[:, 1:] * e2
    U[:, 3:] = omega * Q[:, 2]
    bd = np.flatnonzero(np.isclose(s[:, 0], 0) | np.isclose(s[:, 0], 1.0)
                        | np.isclose(s[:, 1], 0) | np.isclose(s[:, 1], 0.8))
    pres = node_dofs(bd, range(6))
    u = _patch_solve(fe, pres, U.ravel()[pres])
    np.testing.assert_allclose(u, U.ravel(), atol=1e-13, rtol=0)
    eps = np.array([Gu[0, 0], Gu[1, 1], Gu[0, 1] + Gu[1, 0]])
    C = E / (1 - NU**2) * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    energy = 0.5 * u @ (fe.K @ u)
    assert energy == pytest.approx(0.5 * eps @ C @ eps * T * 1.0 * 0.8, rel=1e-10)


@pytest.mark.parametrize("cell", CELLS)
def test_constant_curvature_bending_patch_test(cell):
    """w = (kx x^2 + ky y^2 + kxy x y) / 2 on the boundary (with its slopes) -> exact
    interior deflections/rotations and strain energy 1/2 k.D.k A (distorted mesh)."""
    Q = Rotation.from_euler("yzx", [0.3, -0.4, 0.8]).as_matrix()
    origin = np.array([-0.5, 0.4, 1.0])
    a, b = 0.6, 0.5
    mesh = plate_mesh(a, b, 4, 4, cell, distort=0.35, frame=(Q, origin), seed=7)
    fe = assemble(mesh, STEEL, thickness=T)
    s = (mesh.points - origin) @ Q[:, :2]
    kx, ky, kxy = 2e-3, -1e-3, 1.5e-3
    x, y = s[:, 0], s[:, 1]
    w = 0.5 * (kx * x**2 + ky * y**2 + kxy * x * y)
    wx, wy = kx * x + 0.5 * kxy * y, ky * y + 0.5 * kxy * x
    # rotation vector of the normal: theta_1 = dw/dy, theta_2 = -dw/dx (local axes)
    U = np.zeros((len(s), 6))
    U[:, :3] = w[:, None] * Q[:, 2]
    U[:, 3:] = wy[:, None] * Q[:, 0] - wx[:, None] * Q[:, 1]
    bd = np.flatnonzero(np.isclose(x, 0) | np.isclose(x, a) | np.isclose(y, 0) | np.isclose(y, b))
    pres = node_dofs(bd, range(6))
    u = _patch_solve(fe, pres, U.ravel()[pres])
    np.testing.assert_allclose(u, U.ravel(), atol=1e-12, rtol=0)
    kappa = np.array([kx, ky, kxy])
    D = E * T**3 / (12 * (1 - NU**2)) * np.array([[1, NU, 0], [NU, 1, 0], [0, 0, (1 - NU) / 2]])
    energy = 0.5 * u @ (fe.K @ u)
    assert energy == pytest.approx(0.5 * kappa @ D @ kappa * a * b, rel=1e-9)


def _hypar_box(n=6, warp=0.08):
    """Closed box of shells whose top is a hyperbolic paraboloid (warped quads)."""
    pts, quads = [], []

    def add_face(grid):
        base = sum(len(p) for p in pts)
        m = grid.shape[0] - 1
        pts.append(grid.reshape(-1, 3))
        idx = base + np.arange((m + 1) ** 2).reshape(m + 1, m + 1)
        quads.append(np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]],
                              -1).reshape(-1, 4))

    u = np.linspace(-0.5, 0.5, n + 1)
    A, B = np.meshgrid(u, u, indexing="ij")
    top = lambda a, b: 0.5 + warp * 4 * a * b  # noqa: E731
    add_face(np.stack([A, B, top(A, B)], -1))
    add_face(np.stack([B, A, -0.5 + 0 * A], -1))
    for sgn in (-1, 1):
        H = (B + 0.5)  # 0..1 along the height
        add_face(np.stack([sgn * 0.5 + 0 * A, A, -0.5 + H * (top(sgn * 0.5, A) + 0.5)], -1))
        add_face(np.stack([A, sgn * 0.5 + 0 * A, -0.5 + H * (top(A, sgn * 0.5) + 0.5)], -1))
    P = np.concatenate(pts)
    C = np.concatenate(quads)
    # merge coincident nodes
    key = np.round(P, 9)
    uniq, inv = np.unique(key, axis=0, return_inverse=True)
    return Mesh(uniq, (CellBlock("quad", inv.ravel()[C]),))


def test_warped_closed_box_has_exactly_six_rigid_modes():
    mesh = _hypar_box()
    pts = mesh.points[mesh.blocks[0].cells]
    n = np.cross(pts[:, 2] - pts[:, 0], pts[:, 3] - pts[:, 1])
    n /= np.linalg.norm(n, axis=1)[:, None]
    h = np.abs(np.einsum("eai,ei->ea", pts - pts.mean(axis=1)[:, None], n)).max()
    assert h > 1e-4  # the top quads really are warped
    fe = assemble(mesh, STEEL, thickness=T)
    f, _ = eigenmodes(fe, 8)
    assert np.all(f[:6] < 1e-4 * f[6]), f
    assert f[6] > 10.0  # no spurious mechanism (a 1 m steel box, 10 mm walls)


def test_reversed_node_order_gives_same_frequencies():
    mesh = plate_mesh(1.0, 0.6, 8, 6, "quad", distort=0.2)
    flipped = Mesh(mesh.points, (CellBlock("quad", mesh.blocks[0].cells[:, ::-1]),))
    f1, _ = eigenmodes(assemble(mesh, STEEL, thickness=T), 10)
    f2, _ = eigenmodes(assemble(flipped, STEEL, thickness=T), 10)
    np.testing.assert_allclose(f1[6:], f2[6:], rtol=1e-5)  # eigensolver round-off


def test_shell_without_thickness_raises():
    mesh = plate_mesh(1.0, 1.0, 2, 2, "quad")
    with pytest.raises(MeshError, match="thickness"):
        assemble(mesh, STEEL)
    with pytest.raises(MeshError, match="thickness"):
        assemble(mesh, STEEL, thickness=0.0)


def test_severely_warped_quad_raises_with_element_id():
    pts = np.array([[0, 0, 0], [1, 0, 0.3], [1, 1, 0], [0, 1, 0.3]], float)
    mesh = Mesh(pts, (CellBlock("quad", [[0, 1, 2, 3]], ids=np.array([77])),))
    with pytest.raises(MeshError, match=r"warped \(out-of-plane.*77"):
        assemble(mesh, STEEL, thickness=T)


@pytest.mark.parametrize("pts", [
    [[0, 0, 0], [1, 0, 0], [0.2, 0.2, 0], [0, 1, 0]],    # re-entrant (non-convex)
    [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]],        # bow-tie
    [[0, 0, 0], [1, 0, 0], [2, 0, 0], [3, 0, 0]],        # collinear
])
def test_degenerate_quads_raise(pts):
    mesh = Mesh(np.array(pts, float), (CellBlock("quad", [[0, 1, 2, 3]]),))
    with pytest.raises(MeshError, match="quad element"):
        assemble(mesh, STEEL, thickness=T)


def test_degenerate_triangle_raises():
    pts = np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0]], float)
    mesh = Mesh(pts, (CellBlock("triangle", [[0, 1, 2]], ids=np.array([5])),))
    with pytest.raises(MeshError, match=r"degenerate.*5"):
        assemble(mesh, STEEL, thickness=T)


def _static(fe, fixed, F):
    K = fe.K.tocsr()
    free = np.setdiff1d(np.arange(fe.n_dof), fixed)
    u = np.zeros(fe.n_dof)
    u[free] = spla.spsolve(K[free][:, free].tocsc(), F[free])
    return u


def _split(quads, cell):
    if cell == "quad":
        return CellBlock("quad", quads)
    return CellBlock("triangle", np.concatenate([quads[:, [0, 1, 2]], quads[:, [0, 2, 3]]]))


def _grid_quads(n1, n2):
    idx = np.arange((n1 + 1) * (n2 + 1)).reshape(n1 + 1, n2 + 1)
    quads = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], -1)
    return idx, quads.reshape(-1, 4)


# MacNeal & Harder, "A proposed standard set of problems to test finite element accuracy",
# Finite Elem. Anal. Des. 1 (1985) 3-20; targets as restated in the Altair OptiStruct
# verification manual (OS-V 0730 roof, OS-V 0700 twisted beam).
SCORDELIS_LO_W = 0.3024
TWISTED_BEAM_U = {1: 0.001754, 2: 0.005424}  # tip load along width at root (y), along z


@pytest.mark.parametrize("cell, n, tol", [("quad", 8, 0.01), ("triangle", 16, 0.02)])
def test_scordelis_lo_roof(cell, n, tol):
    """Curved shell (membrane + bending): quadrant of the roof, R = 25, L = 50, 40 deg,
    t = 0.25, E = 4.32e8, nu = 0, self weight 90 per unit area, rigid end diaphragms."""
    R, half_L, phi0 = 25.0, 25.0, np.deg2rad(40.0)
    x, phi = np.meshgrid(np.linspace(0, half_L, n + 1), np.linspace(0, phi0, n + 1),
                         indexing="ij")
    x, phi = x.ravel(), phi.ravel()
    pts = np.column_stack([x, R * np.sin(phi), R * np.cos(phi)])
    idx, quads = _grid_quads(n, n)
    block = _split(quads, cell)
    fe = assemble(Mesh(pts, (block,)), Material(4.32e8, 0.0, 1.0), thickness=0.25)
    X = pts[block.cells]
    if cell == "quad":
        area = 0.5 * np.linalg.norm(np.cross(X[:, 2] - X[:, 0], X[:, 3] - X[:, 1]), axis=1)
    else:
        area = 0.5 * np.linalg.norm(np.cross(X[:, 1] - X[:, 0], X[:, 2] - X[:, 0]), axis=1)
    assert area.sum() == pytest.approx(R * phi0 * half_L, rel=0.01)
    F = np.zeros(fe.n_dof)
    nn = block.cells.shape[1]
    np.add.at(F, block.cells.ravel() * 6 + 2, -90.0 * np.repeat(area / nn, nn))
    fixed = np.concatenate([
        node_dofs(np.flatnonzero(np.isclose(x, 0)), [0, 4, 5]),        # symmetry x = 0
        node_dofs(np.flatnonzero(np.isclose(phi, 0)), [1, 3, 5]),      # symmetry y = 0
        node_dofs(np.flatnonzero(np.isclose(x, half_L)), [1, 2]),     # diaphragm
    ])
    u = _static(fe, np.unique(fixed), F)
    w_mid_free_edge = -u[6 * idx[0, n] + 2]
    assert w_mid_free_edge == pytest.approx(SCORDELIS_LO_W, rel=tol)


@pytest.mark.parametrize("cell, nl, nw, tol", [("quad", 12, 2, 0.01),
                                               ("triangle", 24, 4, 0.02)])
@pytest.mark.parametrize("direction", [1, 2])
def test_macneal_harder_twisted_beam(cell, nl, nw, tol, direction):
    """90 deg pretwisted strip 12 x 1.1 x 0.32 (E = 29e6, nu = 0.22): every quad is
    warped, so this checks the mean-plane projection with rigid offsets."""
    L, w = 12.0, 1.1
    s, xl = np.meshgrid(np.linspace(-w / 2, w / 2, nw + 1), np.linspace(0, L, nl + 1))
    phi = np.pi / 2 * xl / L
    pts = np.column_stack([xl.ravel(), (s * np.cos(phi)).ravel(), (s * np.sin(phi)).ravel()])
    idx, quads = _grid_quads(nl, nw)
    fe = assemble(Mesh(pts, (_split(quads, cell),)), Material(29e6, 0.22, 1.0),
                  thickness=0.32)
    tip = idx[-1]
    share = np.full(nw + 1, 1.0 / nw)
    share[[0, -1]] *= 0.5
    F = np.zeros(fe.n_dof)
    F[tip * 6 + direction] = share                                 # unit tip load
    u = _static(fe, node_dofs(idx[0], range(6)), F)
    assert u[tip * 6 + direction] @ share == pytest.approx(TWISTED_BEAM_U[direction], rel=tol)


@pytest.mark.parametrize("cell", CELLS)
def test_folded_box_beam_bending_frequency(cell):
    """Square thin-walled tube of shells (folded plates: drilling DOF at the corners,
    in-plane bending of the webs) vs Euler-Bernoulli with the tube's I."""
    L, b, t, nl, ns = 2.0, 0.1, 0.002, 40, 4
    corners = np.array([[-b / 2, -b / 2], [b / 2, -b / 2], [b / 2, b / 2], [-b / 2, b / 2]])
    ring = np.concatenate([corners[k] + np.outer(np.arange(ns) / ns, corners[(k + 1) % 4]
                                                 - corners[k]) for k in range(4)])
    m = len(ring)
    xs = np.linspace(0, L, nl + 1)
    pts = np.column_stack([np.repeat(xs, m), np.tile(ring, (nl + 1, 1))])
    idx = np.arange(len(pts)).reshape(nl + 1, m)
    quads = np.stack([idx[:-1], idx[1:], np.roll(idx[1:], -1, 1), np.roll(idx[:-1], -1, 1)],
                     -1).reshape(-1, 4)
    fe = assemble(Mesh(pts, (_split(quads, cell),)), STEEL, thickness=t)
    f, _ = eigenmodes(fe, 2, node_dofs(idx[0], range(6)))
    I = ((b + t) ** 4 - (b - t) ** 4) / 12
    f_eb = 1.875104**2 / (2 * np.pi * L**2) * np.sqrt(E * I / (RHO * 4 * b * t))
    # shear deformation and rotary inertia of the tube lower it by ~0.5 %
    np.testing.assert_allclose(f, f_eb, rtol=0.01)
