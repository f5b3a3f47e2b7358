"""Verification of the solid element families tet4, tet10 and hex8 (incompatible modes).

Independent references only:

* quadrature: exact monomial integrals ``a! b! c! / (a + b + c + 3)!``;
* element rank: a free element has exactly the six rigid-body zero-energy modes;
* constant-strain patch tests on distorted patches: a linear displacement field is
  reproduced exactly, with the closed-form strain energy and boundary force resultants;
* Euler-Bernoulli beam theory for a slender bar (free-free ``beta L = 4.7300, 7.8532``,
  cantilever ``beta L = 1.8751``);
* the exact elastodynamic spectrum of a block with sliding walls (zero normal
  displacement, zero shear traction), whose modes are plane shear/pressure waves:
  ``f = c_s |k| / (2 pi)`` with ``k = pi (l/L, m/b, n/h)``;
* convergence rates: frequency error ~ h^(2p) (p = 1 for tet4/hex8, p = 2 for tet10).
"""

from __future__ import annotations

from math import factorial

import numpy as np
import pytest
import scipy.linalg as sla

from flexpipe.fem import Material, assemble, eigenmodes, hex8, tet4, tet10
from flexpipe.fem.quadrature import gauss_hex, gauss_legendre, tet_rule, triangle_rule
from flexpipe.mesh import CellBlock, Mesh
from flexpipe.mesh.generate import add_midside_nodes, box

E, NU, RHO = 210e9, 0.3, 7850.0
STEEL = Material(E, NU, RHO)
LAM = E * NU / ((1 + NU) * (1 - 2 * NU))
MU = E / (2 * (1 + NU))
FAMILY = {"tetra": tet4, "tetra10": tet10, "hexahedron": hex8}
CELLS = tuple(FAMILY)


# ---------------------------------------------------------------------------- quadrature
@pytest.mark.parametrize("order", [1, 2, 3, 5, 7])
def test_tet_rule_integrates_monomials_exactly(order):
    P, w = tet_rule(order)
    assert np.all(w > 0) and np.all(P >= 0) and np.all(P.sum(axis=1) <= 1)
    for a in range(order + 1):
        for b in range(order + 1 - a):
            for c in range(order + 1 - a - b):
                exact = factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3)
                got = np.sum(w * P[:, 0] ** a * P[:, 1] ** b * P[:, 2] ** c)
                assert got == pytest.approx(exact, rel=1e-13)


@pytest.mark.parametrize("order", [1, 2, 5, 8])
def test_triangle_rule_integrates_monomials_exactly(order):
    P, w = triangle_rule(order)
    for a in range(order + 1):
        for b in range(order + 1 - a):
            exact = factorial(a) * factorial(b) / factorial(a + b + 2)
            assert np.sum(w * P[:, 0] ** a * P[:, 1] ** b) == pytest.approx(exact, rel=1e-13)


def test_gauss_rules():
    x, w = gauss_legendre(3)
    assert np.sum(w * x**4) == pytest.approx(2 / 5, rel=1e-14)      # degree 2n - 1 = 5
    assert np.sum(w * x**6) != pytest.approx(2 / 7, rel=1e-6)       # but not degree 6
    P, W = gauss_hex(2)
    assert W.sum() == pytest.approx(8.0)
    assert np.sum(W * P[:, 0] ** 2 * P[:, 1] ** 2 * P[:, 2] ** 2) == pytest.approx(8 / 27)


# ------------------------------------------------------------------------ element level
def _one_element(cell, rng):
    """A distorted, positively oriented element of each family."""
    if cell == "hexahedron":
        X = hex8.XI * 0.5 + rng.uniform(-0.12, 0.12, (8, 3))
    else:
        X = np.array([[0.0, 0, 0], [1, 0.1, 0], [0.2, 0.9, 0.1], [0.1, 0.3, 1.2]])
        X = X + rng.uniform(-0.05, 0.05, X.shape)
        if cell == "tetra10":
            pts, cells = add_midside_nodes(X, np.arange(4)[None])
            X = pts[cells[0]]
    return X[None]


@pytest.mark.parametrize("cell", CELLS)
def test_single_element_has_exactly_six_zero_energy_modes(cell):
    """Rank 3n - 6: rigid-body modes only, no hourglass / spurious mechanisms."""
    X = _one_element(cell, np.random.default_rng(7))
    one = np.ones(1)
    K, M = FAMILY[cell].matrices(X, E=one * E, nu=one * NU, rho=one * RHO)
    lam = np.linalg.eigvalsh(K[0])
    assert np.all(np.abs(lam[:6]) < 1e-10 * lam[-1])
    assert lam[6] > 1e-3 * lam[-1]
    assert np.linalg.eigvalsh(M[0]).min() > 0                       # consistent mass is SPD


# -------------------------------------------------------------------------- patch tests
def _distorted_cube(cell, n=3, amount=0.22, seed=11):
    """Unit cube, n^3 grid cells, interior nodes moved randomly by up to amount * h."""
    base = "tetra" if cell == "tetra10" else cell
    m = box(1.0, 1.0, 1.0, n, n, n, cell=base)
    pts = np.array(m.points)
    inner = np.all((pts > 1e-9) & (pts < 1 - 1e-9), axis=1)
    pts[inner] += amount / n * np.random.default_rng(seed).uniform(-1, 1, (inner.sum(), 3))
    cells = m.blocks[0].cells
    if cell == "tetra10":  # straight edges: mid-edge nodes at the new midpoints
        pts, cells = add_midside_nodes(pts, cells)
    return pts, cells


def _dense_K(pts, cells, stiffness):
    n = 3 * len(pts)
    K = np.zeros((n, n))
    Ke = stiffness(pts[cells])
    dofs = (cells[:, :, None] * 3 + np.arange(3)).reshape(len(cells), -1)
    np.add.at(K, (dofs[:, :, None], dofs[:, None, :]), Ke)
    return K


def _patch_solve(pts, K, A):
    """Prescribe u = A x on the boundary, solve the interior; return u and nodal forces."""
    on_bnd = np.any((pts < 1e-9) | (pts > 1 - 1e-9), axis=1)
    u_exact = pts @ A.T
    fixed = np.flatnonzero(np.repeat(on_bnd, 3))
    free = np.flatnonzero(~np.repeat(on_bnd, 3))
    u = u_exact.ravel().copy()
    u[free] = np.linalg.solve(K[np.ix_(free, free)], -K[np.ix_(free, fixed)] @ u[fixed])
    return u.reshape(-1, 3), u_exact, (K @ u).reshape(-1, 3)


def _strain_of(sigma):
    """Isotropic compliance (closed form), tensor strain."""
    return ((1 + NU) * sigma - NU * np.trace(sigma) * np.eye(3)) / E


SIGMA_UNIAXIAL = np.diag([1e8, 0.0, 0.0])
SIGMA_SHEAR = np.array([[0.0, 4e7, 0.0], [4e7, 0.0, 0.0], [0.0, 0.0, 0.0]])
ROTATION = np.array([[0.0, -1e-4, 2e-4], [1e-4, 0.0, -3e-4], [-2e-4, 3e-4, 0.0]])


def _family_stiffness(cell, **kw):
    def stiffness(X):
        one = np.ones(len(X))
        if cell == "hexahedron":
            return hex8.stiffness(X, one * E, one * NU, **kw)
        return FAMILY[cell].matrices(X, E=one * E, nu=one * NU, rho=one * RHO)[0]
    return stiffness


@pytest.mark.parametrize("cell", CELLS)
def test_constant_strain_patch_test_on_distorted_patch(cell):
    pts, cells = _distorted_cube(cell)
    K = _dense_K(pts, cells, _family_stiffness(cell))
    on_face_x1 = pts[:, 0] > 1 - 1e-9
    for sigma, check in ((SIGMA_UNIAXIAL, (0, 1, 2)), (SIGMA_SHEAR, (1,))):
        eps = _strain_of(sigma)
        A = eps + ROTATION
        u, u_exact, f = _patch_solve(pts, K, A)
        assert np.abs(u - u_exact).max() < 1e-9 * np.abs(u_exact).max()
        # strain energy 1/2 sigma:eps V (V = 1)
        energy = 0.5 * u.ravel() @ K @ u.ravel()
        assert energy == pytest.approx(0.5 * np.sum(sigma * eps), rel=1e-10)
        # resultant of the nodal forces on the face x = 1 equals sigma . e_x * area
        resultant = f[on_face_x1].sum(axis=0)
        for c in check:
            assert resultant[c] == pytest.approx(sigma[c, 0], abs=1e-8 * np.abs(sigma).max())


def test_hex8_patch_test_needs_taylor_correction():
    """Negative control: Wilson's uncorrected modes fail the patch test on distortion."""
    pts, cells = _distorted_cube("hexahedron")
    K = _dense_K(pts, cells, _family_stiffness("hexahedron", taylor=False))
    u, u_exact, _ = _patch_solve(pts, K, _strain_of(SIGMA_UNIAXIAL))
    assert np.abs(u - u_exact).max() > 1e-4 * np.abs(u_exact).max()


def test_patch_through_the_assembler():
    """Same patch test through assemble(): sparse scatter, material resolution, symmetry."""
    pts, cells = _distorted_cube("hexahedron")
    fe = assemble(Mesh(pts, (CellBlock("hexahedron", cells),)), STEEL)
    u, u_exact, _ = _patch_solve(pts, fe.K.toarray(), _strain_of(SIGMA_SHEAR) + ROTATION)
    assert np.abs(u - u_exact).max() < 1e-9 * np.abs(u_exact).max()


# ------------------------------------------------------------------- slender bar, beams
L_BAR, B_BAR, H_BAR = 1.0, 0.04, 0.02   # L/h = 50 (weak axis), L/b = 25 (strong axis)


def _beam_hz(beta_L, I):
    """Euler-Bernoulli natural frequency for the root beta_n L of the frequency equation."""
    A = B_BAR * H_BAR
    return beta_L**2 / (2 * np.pi * L_BAR**2) * np.sqrt(E * I / (RHO * A))


I_WEAK = B_BAR * H_BAR**3 / 12
I_STRONG = H_BAR * B_BAR**3 / 12
BAR_MESH = {"tetra10": (20, 2, 1), "hexahedron": (25, 2, 1)}


@pytest.mark.parametrize("cell", ["tetra10", "hexahedron"])
def test_slender_bar_matches_euler_bernoulli_within_1_percent(cell):
    mesh = box(L_BAR, B_BAR, H_BAR, *BAR_MESH[cell], cell=cell)
    fe = assemble(mesh, STEEL)
    f, _ = eigenmodes(fe, 9)
    assert np.all(f[:6] < 1e-3 * f[6])                         # six rigid-body modes
    free_free = [_beam_hz(4.730040745, I_WEAK), _beam_hz(4.730040745, I_STRONG),
                 _beam_hz(7.853204624, I_WEAK)]
    assert f[6:9] == pytest.approx(free_free, rel=0.01)
    fixed = (mesh.node_sets["xmin"][:, None] * 3 + np.arange(3)).ravel()
    fc, _ = eigenmodes(fe, 2, fixed_dofs=fixed)
    cantilever = [_beam_hz(1.875104069, I_WEAK), _beam_hz(1.875104069, I_STRONG)]
    assert fc == pytest.approx(cantilever, rel=0.01)


def test_plain_trilinear_hex_locks_where_incompatible_modes_do_not():
    """Negative control: without the incompatible modes the same mesh is far too stiff."""
    mesh = box(L_BAR, B_BAR, H_BAR, *BAR_MESH["hexahedron"], cell="hexahedron")
    pts, cells = mesh.points, mesh.blocks[0].cells
    M = assemble(mesh, STEEL).M.toarray()
    ref = _beam_hz(4.730040745, I_WEAK)
    for incompatible, lo, hi in ((False, 1.5, 10.0), (True, 0.99, 1.01)):
        K = _dense_K(pts, cells, _family_stiffness("hexahedron", incompatible=incompatible))
        lam = sla.eigh(K, M, eigvals_only=True, subset_by_index=[6, 6])[0]
        assert lo < np.sqrt(lam) / (2 * np.pi) / ref < hi


# ------------------------------------------------- exact 3D spectrum, convergence rates
def _sliding_box_first_hz(cell, n):
    """Lowest frequency of the block [0,1] x [0,1] x [0,0.25] with sliding walls."""
    mesh = box(1.0, 1.0, 0.25, *n, cell=cell)
    fe = assemble(mesh, STEEL)
    walls = [("xmin", 0), ("xmax", 0), ("ymin", 1), ("ymax", 1), ("zmin", 2), ("zmax", 2)]
    fixed = np.concatenate([mesh.node_sets[s] * 3 + c for s, c in walls])
    f, _ = eigenmodes(fe, 1, fixed_dofs=fixed)
    return f[0]


# lowest exact mode: shear wave k = pi (1, 1, 0), u = (sin x cos y, -cos x sin y, 0) (pi L)
F_SHEAR_EXACT = np.sqrt(MU / RHO) * np.sqrt(2.0) / 2.0
RATE_MESHES = {"tetra": [(8, 8, 2), (16, 16, 4)], "tetra10": [(4, 4, 1), (8, 8, 2)],
               "hexahedron": [(8, 8, 2), (16, 16, 4)]}
ORDER = {"tetra": 1, "tetra10": 2, "hexahedron": 1}


@pytest.mark.parametrize("cell", CELLS)
def test_convergence_rate_against_exact_elastodynamics(cell):
    """Frequency error vs the exact wave solution falls like h^(2p) under refinement."""
    err = [_sliding_box_first_hz(cell, n) / F_SHEAR_EXACT - 1 for n in RATE_MESHES[cell]]
    assert err[0] > err[1] > 0                     # consistent mass + conforming: from above
    rate = np.log2(err[0] / err[1])
    print(f"{cell}: errors {err}, observed order {rate:.2f}")
    assert rate == pytest.approx(2 * ORDER[cell], abs=0.35 * ORDER[cell])
    if cell != "tetra":
        assert err[1] < 0.01


@pytest.mark.slow
@pytest.mark.parametrize("cell,meshes", [
    ("tetra", [(8, 2, 2), (16, 4, 4), (32, 8, 8)]),
    ("tetra10", [(2, 2, 2), (4, 4, 4), (8, 8, 8)]),
    ("hexahedron", [(8, 2, 2), (16, 4, 4), (32, 8, 8)]),
])
def test_bar_bending_frequency_convergence_rate(cell, meshes):
    """Observed order of the first free-free bending frequency of a bar (L/h = 4) from
    three uniformly refined meshes (Richardson): p_obs = log2((f1 - f2) / (f2 - f3))."""
    f = []
    for n in meshes:
        fe = assemble(box(1.0, 0.25, 0.25, *n, cell=cell), STEEL)
        f.append(eigenmodes(fe, 7)[0][6])
    d1, d2 = f[0] - f[1], f[1] - f[2]
    assert d1 > d2 > 0                              # monotone convergence from above
    rate = np.log2(d1 / d2)
    print(f"{cell}: f = {np.round(f, 2)} Hz, observed order {rate:.2f}")
    assert rate == pytest.approx(2 * ORDER[cell], abs=0.4 * ORDER[cell])
