"""Verification of the 3D Euler-Bernoulli beam element and of point masses on beams.

References: Euler-Bernoulli eigenvalues (beta L roots of cos cosh = +-1), rod and shaft
wave solutions, static cantilever formulas, the exact frequency equations of a cantilever
with a tip mass and of a shaft with a tip disk (solved here with a root finder).
"""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla
from scipy.optimize import brentq

from flexpipe.errors import MeshError
from flexpipe.fem import BeamSection, Material, assemble, eigenmodes
from flexpipe.mesh.mesh import CellBlock, Mesh, PointMass

E, NU, RHO = 2.1e11, 0.3, 7800.0
G = E / (2 * (1 + NU))
STEEL = Material(E, NU, RHO)
A, IY, IZ, J = 1.0e-3, 2.0e-8, 8.0e-8, 3.0e-8
# roots of cos(x) cosh(x) = 1 (free-free) and = -1 (clamped-free), textbook values
BL_FREE = np.array([4.730041, 7.853205, 10.995608])
BL_CANT = np.array([1.875104, 4.694091, 7.854757])


def beta_l_free(count):
    """Roots of cos x cosh x = 1, the first three checked against the tabulated ones."""
    roots = np.array([brentq(lambda x: np.cos(x) * np.cosh(x) - 1, (k + 1.25) * np.pi,
                             (k + 1.75) * np.pi) for k in range(count)])
    np.testing.assert_allclose(roots[:3], BL_FREE, rtol=1e-6)
    return roots


def line_mesh(p0, p1, n, *, data=None, point_masses=()):
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    pts = p0 + np.linspace(0, 1, n + 1)[:, None] * (p1 - p0)
    cells = np.column_stack([np.arange(n), np.arange(1, n + 1)])
    return Mesh(pts, (CellBlock("line", cells, data=data or {}),), point_masses=point_masses)


def bending_f(beta_L, L, I):
    return beta_L**2 / (2 * np.pi * L**2) * np.sqrt(E * I / (RHO * A))


def test_free_free_skew_beam_bending_torsion_axial():
    L = 3.0
    d = np.array([1.0, 2.0, -2.0]) / 3.0
    v = np.array([0.0, 0.0, 1.0])
    sec = BeamSection(A, IY, IZ, J, orientation=tuple(v))
    mesh = line_mesh([0.5, -1.0, 2.0], np.array([0.5, -1.0, 2.0]) + L * d, 24)
    fe = assemble(mesh, STEEL, beam_section=sec)
    f, X = eigenmodes(fe, 14)
    assert np.all(f[:6] < 1e-4 * f[6])
    ref = np.concatenate([
        bending_f(beta_l_free(8), L, IY),             # deflection along local z
        bending_f(beta_l_free(8), L, IZ),             # deflection along local y
        np.arange(1, 3) / (2 * L) * np.sqrt(G * J / (RHO * (IY + IZ))),   # torsion
        np.arange(1, 3) / (2 * L) * np.sqrt(E / RHO),                     # axial
    ])
    ref = np.sort(ref)[:8]
    np.testing.assert_allclose(f[6:14], ref, rtol=2e-3)
    # the lowest elastic mode bends about local y: it moves along z = x cross v
    ez = np.cross(d, v) / np.linalg.norm(np.cross(d, v))
    u = fe.translations(X[:, 6])
    assert np.abs(u @ ez).max() > 1e3 * np.abs(u - np.outer(u @ ez, ez)).max()


def test_cantilever_frequencies_and_static_tip_loads():
    L, n = 2.0, 12
    mesh = line_mesh([0, 0, 0], [L, 0, 0], n)
    fe = assemble(mesh, STEEL, beam_section=BeamSection(A, IY, IZ, J,
                                                         orientation=(0.0, 1.0, 0.0)))
    clamp = np.arange(6)
    f, _ = eigenmodes(fe, 5, clamp)
    ref = np.sort(np.concatenate([bending_f(BL_CANT, L, IY), bending_f(BL_CANT, L, IZ)]))[:5]
    np.testing.assert_allclose(f, ref, rtol=2e-3)
    # statics: Euler-Bernoulli Hermite elements are nodally exact
    K = fe.K.tocsr()
    free = np.arange(6, fe.n_dof)
    F = np.zeros(fe.n_dof)
    tip = n * 6
    P, Tq, N = 100.0, 7.0, 5.0e4
    F[tip + 0], F[tip + 1], F[tip + 2], F[tip + 3] = N, P, P, Tq
    u = np.zeros(fe.n_dof)
    u[free] = spla.spsolve(K[free][:, free].tocsc(), F[free])
    assert u[tip + 0] == pytest.approx(N * L / (E * A), rel=1e-9)
    assert u[tip + 1] == pytest.approx(P * L**3 / (3 * E * IZ), rel=1e-9)  # v: about z
    assert u[tip + 2] == pytest.approx(P * L**3 / (3 * E * IY), rel=1e-9)  # w: about y
    assert u[tip + 3] == pytest.approx(Tq * L / (G * J), rel=1e-9)
    assert u[tip + 5] == pytest.approx(P * L**2 / (2 * E * IZ), rel=1e-9)   # dv/dx
    assert u[tip + 4] == pytest.approx(-P * L**2 / (2 * E * IY), rel=1e-9)  # -dw/dx


@pytest.mark.parametrize("v, weak_axis", [((0.0, 1.0, 0.0), 2), ((0.0, 0.0, 1.0), 1),
                                          (None, 1)])
def test_orientation_from_cell_data(v, weak_axis):
    """block.data['orientation'] sets local y; the weak inertia Iy bends along local z."""
    L, n = 1.0, 8
    data = {} if v is None else {"orientation": np.tile(v, (n, 1))}
    mesh = line_mesh([0, 0, 0], [L, 0, 0], n, data=data)
    fe = assemble(mesh, STEEL, beam_section=BeamSection(A, IY, IZ, J))
    f, X = eigenmodes(fe, 1, np.arange(6))
    u = np.abs(fe.translations(X[:, 0]))
    assert u[:, weak_axis].max() > 1e6 * np.delete(u, weak_axis, axis=1).max()
    assert f[0] == pytest.approx(bending_f(BL_CANT[0], L, IY), rel=1e-3)


def test_space_frame_has_exactly_six_rigid_modes_and_its_mass():
    """Edges of a 1 m cube, 3 elements per edge, all members rigidly joined."""
    corners = np.array([[i, j, k] for i in (0, 1) for j in (0, 1) for k in (0, 1)], float)
    edges = [(a, b) for a in range(8) for b in range(a + 1, 8)
             if np.isclose(np.linalg.norm(corners[a] - corners[b]), 1.0)]
    pts, cells = list(corners), []
    for a, b in edges:
        ids = [a]
        for s in (1 / 3, 2 / 3):
            pts.append(corners[a] + s * (corners[b] - corners[a]))
            ids.append(len(pts) - 1)
        ids.append(b)
        cells += [(ids[k], ids[k + 1]) for k in range(3)]
    mesh = Mesh(np.array(pts), (CellBlock("line", np.array(cells)),))
    fe = assemble(mesh, STEEL, beam_section=BeamSection(A, IY, IZ, J))
    assert len(edges) == 12
    assert fe.total_mass == pytest.approx(RHO * A * 12.0, rel=1e-12)
    f, _ = eigenmodes(fe, 8)
    assert np.all(f[:6] < 1e-4 * f[6]), f
    assert f[6] > 1.0


def test_tip_mass_on_cantilever_exact_and_effective_mass():
    L, n = 1.5, 16
    m_beam = RHO * A * L
    mu = 2.0
    mesh = line_mesh([0, 0, 0], [L, 0, 0], n, point_masses=(PointMass(n, mu * m_beam),))
    fe = assemble(mesh, STEEL, beam_section=BeamSection(A, IY, IZ, J,
                                                         orientation=(0.0, 1.0, 0.0)))
    f, _ = eigenmodes(fe, 1, np.arange(6))
    # exact: 1 + cos l cosh l + mu l (cos l sinh l - sin l cosh l) = 0
    def char(lam):
        return (1 + np.cos(lam) * np.cosh(lam)
                + mu * lam * (np.cos(lam) * np.sinh(lam) - np.sin(lam) * np.cosh(lam)))
    lam = brentq(char, 0.1, BL_CANT[0])
    f_exact = lam**2 / (2 * np.pi * L**2) * np.sqrt(E * IY / (RHO * A))
    assert f[0] == pytest.approx(f_exact, rel=1e-3)
    # single-DOF estimate k / (M + 33/140 m_beam), k = 3 E I / L^3 (Rayleigh)
    f_sdof = np.sqrt(3 * E * IY / L**3 / ((mu + 33 / 140) * m_beam)) / (2 * np.pi)
    assert f[0] == pytest.approx(f_sdof, rel=5e-3)


def test_tip_disk_on_torsion_shaft_exact():
    """Shaft with a rotary inertia at its tip: (k L) tan(k L) = rho Ip L / I_disk."""
    L, n = 1.0, 10
    Ip = IY + IZ
    I_disk = 20 * RHO * Ip * L
    inertia = np.diag([I_disk, 0.0, 0.0])
    mesh = line_mesh([0, 0, 0], [L, 0, 0], n,
                     point_masses=(PointMass(n, 0.0, inertia=inertia),))
    fe = assemble(mesh, STEEL, beam_section=BeamSection(A, IY, IZ, J))
    f, X = eigenmodes(fe, 4, np.arange(6))
    # the torsion mode: the one whose rotations are about the shaft axis
    rot = X.reshape(-1, 6, 4)[:, 3:, :]
    k = int(np.argmax(np.abs(rot[:, 0, :]).max(axis=0) / np.abs(rot).max(axis=(0, 1))))
    assert np.abs(rot[:, 0, k]).max() > 1e6 * np.abs(rot[:, 1:, k]).max()
    kL = brentq(lambda x: x * np.tan(x) - RHO * Ip * L / I_disk, 1e-6, np.pi / 2 - 1e-9)
    f_exact = kL / L * np.sqrt(G * J / (RHO * Ip)) / (2 * np.pi)
    assert f[k] == pytest.approx(f_exact, rel=1e-3)


def test_zero_length_beam_raises():
    mesh = Mesh(np.array([[0, 0, 0], [0, 0, 0.0], [1, 0, 0]]),
                (CellBlock("line", [[0, 1], [1, 2]], ids=np.array([41, 42])),))
    with pytest.raises(MeshError, match=r"zero length.*41"):
        assemble(mesh, STEEL, beam_section=BeamSection(A, IY, IZ, J))


def test_orientation_parallel_to_axis_raises():
    mesh = line_mesh([0, 0, 0], [1, 0, 0], 2)
    with pytest.raises(MeshError, match="orientation vector parallel"):
        assemble(mesh, STEEL, beam_section=BeamSection(A, IY, IZ, J, orientation=(2, 0, 0)))


def test_beam_without_section_raises():
    with pytest.raises(MeshError, match="cross-section"):
        assemble(line_mesh([0, 0, 0], [1, 0, 0], 2), STEEL)


def test_rectangle_and_box_sections_bend_about_the_right_axes():
    """BeamSection.rectangle(b, h): width b along local z, height h along local y, so a
    load along local y meets E b h^3 / 12 (checked statically, tip deflection P L^3/3EI)."""
    L, n, b, h, t = 1.0, 4, 0.01, 0.03, 0.002
    mesh = line_mesh([0, 0, 0], [L, 0, 0], n)
    tip = 6 * n
    bb = 2 * b
    for sec, Iy_ref, Iz_ref in [
        (BeamSection.rectangle(b, h, orientation=(0.0, 1.0, 0.0)), h * b**3 / 12, b * h**3 / 12),
        (BeamSection.box(bb, h, t, orientation=(0.0, 1.0, 0.0)),
         (h * bb**3 - (h - 2 * t) * (bb - 2 * t) ** 3) / 12,
         (bb * h**3 - (bb - 2 * t) * (h - 2 * t) ** 3) / 12),
    ]:
        fe = assemble(mesh, STEEL, beam_section=sec)
        K = fe.K.tocsr()
        free = np.arange(6, fe.n_dof)
        F = np.zeros(fe.n_dof)
        F[tip + 1] = F[tip + 2] = 1.0                         # global y = local y, z = z
        u = np.zeros(fe.n_dof)
        u[free] = spla.spsolve(K[free][:, free].tocsc(), F[free])
        assert u[tip + 1] == pytest.approx(L**3 / (3 * E * Iz_ref), rel=1e-9)
        assert u[tip + 2] == pytest.approx(L**3 / (3 * E * Iy_ref), rel=1e-9)


def test_cantilever_frequency_convergence_rate_is_fourth_order():
    """Hermite cubic + consistent mass: eigenvalue error ~ h^(2(p + 1 - m)) = h^4 (p = 3,
    m = 2), from above; measured on the first two bending modes against beta L roots."""
    L = 2.0
    sec = BeamSection(A, IY, IZ, J, orientation=(0.0, 1.0, 0.0))
    # roots of cos x cosh x = -1 to full precision (the table's 7 digits limit at 1e-7)
    roots = np.array([brentq(lambda x: np.cos(x) * np.cosh(x) + 1, a, b, xtol=1e-15)
                      for a, b in ((1.5, 2.5), (4.0, 5.0))])
    np.testing.assert_allclose(roots, BL_CANT[:2], rtol=1e-6)
    err = []
    for n in (3, 6, 12):
        fe = assemble(line_mesh([0, 0, 0], [L, 0, 0], n), STEEL, beam_section=sec)
        f, X = eigenmodes(fe, 6, np.arange(6))
        U = X.reshape(-1, 6, X.shape[1])[:, :3, :]      # nodal translations of each mode
        along_z = np.abs(U[:, 2, :]).max(axis=0) > 0.5 * np.abs(U).max(axis=(0, 1))  # about y
        err.append(f[along_z][:2] / bending_f(roots, L, IY) - 1)
    err = np.array(err)
    assert np.all(err > 0)
    rates = np.log2(err[:-1] / err[1:])
    assert np.all((rates > 3.6) & (rates < 4.4)), (err, rates)
    assert np.all(err[-1] < 3e-5)
