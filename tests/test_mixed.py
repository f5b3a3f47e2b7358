"""Mixed models: shells + beams + solids + point masses + rigid links (RBE2) together.

References: rigid-body kinematics (six zero-energy modes, rigid-link constraints satisfied
by rigid motion), the rigid-body mass matrix of the parts computed from their geometry
(plate, slender rod, box, concentrated masses), and the series-spring frequency of an
offset mass carried by a rigid link.
"""

from __future__ import annotations

import numpy as np
import pytest

from flexpipe.errors import ModelError
from flexpipe.fem import BeamSection, Material, assemble, eigenmodes
from flexpipe.mesh.mesh import CellBlock, Mesh, PointMass, RigidLink

E, NU, RHO = 2.1e11, 0.3, 7800.0
STEEL = Material(E, NU, RHO)
T = 0.005


def skew(r):
    return np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])


def rigid_body_mass(m, c, I_c):
    """6x6 mass matrix (translation, rotation about the origin) of a body of mass ``m``,
    centre ``c`` and inertia ``I_c`` about its centre."""
    c = np.asarray(c, float)
    out = np.zeros((6, 6))
    out[:3, :3] = m * np.eye(3)
    out[:3, 3:] = -m * skew(c)
    out[3:, :3] = m * skew(c)
    out[3:, 3:] = np.asarray(I_c) + m * (c @ c * np.eye(3) - np.outer(c, c))
    return out


def rigid_motions(points):
    """(n_nodes * 6, 6) all-DOF rigid motions: u = t + theta x x, rotations = theta."""
    n = len(points)
    R = np.zeros((n, 6, 6))
    R[:, :3, :3] = np.eye(3)
    for k in range(3):
        e = np.zeros(3)
        e[k] = 1.0
        R[:, :3, 3 + k] = np.cross(e, points)
        R[:, 3 + k, 3 + k] = 1.0
    return R.reshape(n * 6, 6)


def grid(nx, ny, a, b, x0=0.0):
    x, y = np.meshgrid(x0 + np.linspace(0, a, nx + 1), np.linspace(0, b, ny + 1), indexing="ij")
    pts = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    idx = np.arange(x.size).reshape(nx + 1, ny + 1)
    quads = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], -1)
    return pts, idx, quads


def two_patches(tied=True):
    """A quad patch and a triangle patch 0.2 m apart, tied by one RBE2."""
    pa, ia, qa = grid(4, 4, 1.0, 1.0)
    pb, ib, qb = grid(4, 4, 1.0, 1.0, x0=1.2)
    qb = qb.reshape(-1, 4) + len(pa)
    tris = np.concatenate([qb[:, [0, 1, 2]], qb[:, [0, 2, 3]]])
    links = ()
    if tied:
        links = (RigidLink(master=int(ia[-1, 2]), slaves=ib[0, :] + len(pa), id=9),)
    return Mesh(np.vstack([pa, pb]), (CellBlock("quad", qa.reshape(-1, 4)),
                                      CellBlock("triangle", tris)), rigid_links=links)


def test_two_shell_patches_tied_by_rbe2_have_six_rigid_modes():
    fe = assemble(two_patches(), STEEL, thickness=T)
    f, _ = eigenmodes(fe, 8)
    assert np.all(f[:6] < 1e-4 * f[6]), f
    assert f[6] > 1.0
    # untied, the two patches are two free bodies: twelve rigid modes
    fe2 = assemble(two_patches(tied=False), STEEL, thickness=T, allow_disconnected=True)
    f2, _ = eigenmodes(fe2, 13)
    assert np.all(f2[:12] < 1e-4 * f2[12]), f2
    with pytest.raises(ModelError, match="disconnected"):
        assemble(two_patches(tied=False), STEEL, thickness=T)


def _kuhn_tets(nodes_of_cube):
    """Six tetrahedra of a cube (corner order as hexahedron), all sharing diagonal 0-6."""
    c = nodes_of_cube
    paths = [(1, 2), (2, 3), (3, 7), (7, 4), (4, 5), (5, 1)]
    tets = []
    for a, b in paths:
        tet = [c[0], c[a], c[b], c[6]]
        tets.append(tet)
    return tets


def mixed_model():
    """1 x 0.6 m plate (left half quads, right half triangles), a beam stiffener along
    y = 0, a 0.2 x 0.2 x 0.1 m tet4 block standing on the plate, point masses and RBE2s."""
    a, b, nx, ny = 1.0, 0.6, 10, 6
    pts, idx, quads = grid(nx, ny, a, b)
    quads_l = quads[: nx // 2].reshape(-1, 4)
    qr = quads[nx // 2:].reshape(-1, 4)
    tris = np.concatenate([qr[:, [0, 1, 2]], qr[:, [0, 2, 3]]])
    beams = np.column_stack([idx[:-1, 0], idx[1:, 0]])
    # solid block on plate nodes x in [0.2, 0.4], y in [0.2, 0.4], z in [0, 0.1]
    points = [p for p in pts]
    node3d = {}
    for i in range(3):
        for j in range(3):
            node3d[(i, j, 0)] = int(idx[2 + i, 2 + j])
            points.append(np.array([0.2 + 0.1 * i, 0.2 + 0.1 * j, 0.1]))
            node3d[(i, j, 1)] = len(points) - 1
    tets = []
    for i in range(2):
        for j in range(2):
            cube = [node3d[(i + di, j + dj, k)] for k in (0, 1)
                    for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1))]
            tets += _kuhn_tets(cube)
    # RBE2 #1: an independent master 0.2 m above the plate, tied to four plate nodes,
    # carrying a point mass with inertia
    points.append(np.array([0.8, 0.3, 0.2]))
    master = len(points) - 1
    slaves = np.array([idx[7, 2], idx[9, 2], idx[9, 4], idx[7, 4]])
    # RBE2 #2: a plate node (master) carries a dangling slave node holding a mass
    points.append(np.array([0.1, 0.5, -0.3]))
    dangling = len(points) - 1
    pms = (
        PointMass(int(idx[-1, -1]), 2.0, inertia=np.diag([0.01, 0.02, 0.03]),
                  offset=np.array([0.0, 0.0, 0.05]), id=1),
        PointMass(master, 3.0, inertia=np.diag([0.05, 0.04, 0.03]), id=2),
        PointMass(dangling, 1.5, id=3),
    )
    links = (RigidLink(master, slaves, id=11),
             RigidLink(int(idx[1, 5]), np.array([dangling]), id=12))
    mesh = Mesh(np.array(points),
                (CellBlock("quad", quads_l), CellBlock("triangle", tris),
                 CellBlock("line", beams), CellBlock("tetra", np.array(tets))),
                point_masses=pms, rigid_links=links)
    sec = BeamSection(A=4e-4, Iy=2e-8, Iz=3e-8, J=1e-8)
    expected = [
        # plate; the shell's rotary inertia rho t^3/12 acts about all three axes
        rigid_body_mass(RHO * a * b * T, [a / 2, b / 2, 0],
                        RHO * a * b * T / 12 * np.diag([b**2 + T**2, a**2 + T**2,
                                                        a**2 + b**2 + T**2])),
        # slender stiffener: m L^2/12 transverse, polar rho (Iy + Iz) L about its axis
        rigid_body_mass(RHO * sec.A * a, [a / 2, 0, 0],
                        np.diag([RHO * (sec.Iy + sec.Iz) * a, RHO * sec.A * a**3 / 12,
                                 RHO * sec.A * a**3 / 12])),
        rigid_body_mass(RHO * 0.2 * 0.2 * 0.1, [0.3, 0.3, 0.05],
                        RHO * 0.004 / 12 * np.diag([0.2**2 + 0.1**2, 0.2**2 + 0.1**2,
                                                    0.2**2 + 0.2**2])),
        rigid_body_mass(2.0, [a, b, 0.05], np.diag([0.01, 0.02, 0.03])),
        rigid_body_mass(3.0, [0.8, 0.3, 0.2], np.diag([0.05, 0.04, 0.03])),
        rigid_body_mass(1.5, [0.1, 0.5, -0.3], np.zeros((3, 3))),
    ]
    return mesh, sec, sum(expected)


def test_mixed_model_rigid_body_mass_matrix_and_modes():
    mesh, sec, M_rb = mixed_model()
    fe = assemble(mesh, STEEL, thickness=T, beam_section=sec)
    R = rigid_motions(mesh.points)
    col = fe.independent_of_dof
    # independent coordinates of the rigid motions; T must reproduce every DOF it keeps
    q = np.zeros((fe.T.shape[1], 6))
    q[col[col >= 0]] = R[col >= 0]
    used = np.asarray(abs(fe.T).sum(axis=1)).ravel() > 0
    np.testing.assert_allclose((fe.T @ q)[used], R[used], atol=1e-12)
    assert fe.total_mass == pytest.approx(M_rb[0, 0], rel=1e-12)
    np.testing.assert_allclose(q.T @ (fe.Mr @ q), M_rb, rtol=0, atol=1e-9 * M_rb.max())
    # rigid motion stores no strain energy; six zero modes, then a clear gap
    assert np.abs(fe.Kr @ q).max() < 1e-6 * abs(fe.Kr).max()
    f, _ = eigenmodes(fe, 8)
    assert np.all(f[:6] < 1e-4 * f[6]), f
    assert f[6] > 1.0


def test_solid_only_nodes_carry_no_rotational_dof():
    mesh, sec, _ = mixed_model()
    fe = assemble(mesh, STEEL, thickness=T, beam_section=sec)
    in_solid = np.unique(mesh.blocks[3].cells)
    in_others = np.unique(np.concatenate([b.cells.ravel() for b in mesh.blocks[:3]]))
    solid_only = np.setdiff1d(in_solid, in_others)
    assert len(solid_only) == 9
    rot = (solid_only[:, None] * 6 + np.arange(3, 6)).ravel()
    assert abs(fe.T[rot]).sum() == 0
    trans = (solid_only[:, None] * 6 + np.arange(3)).ravel()
    assert (fe.independent_of_dof[trans] >= 0).all()


@pytest.mark.parametrize("via", ["rbe2", "offset"])
def test_offset_mass_on_torsion_rod_series_springs(via):
    """Mass m at distance r from the tip of a (nearly) massless clamped rod, carried by an RBE2
    (or as a CONM2 offset): vertical motion of the mass = tip deflection + r x twist, so
    omega^2 = 1 / (m (L^3 / (3 E Iy) + r^2 L / (G J)))."""
    L, n, r, m = 1.0, 12, 0.2, 5.0
    Iy = Iz = 1e-6
    J = 1e-9
    pts = np.column_stack([np.linspace(0, L, n + 1), np.zeros(n + 1), np.zeros(n + 1)])
    cells = np.column_stack([np.arange(n), np.arange(1, n + 1)])
    if via == "rbe2":
        pts = np.vstack([pts, [L, r, 0.0]])
        pms = (PointMass(n + 1, m),)
        links = (RigidLink(n, np.array([n + 1])),)
    else:
        pms = (PointMass(n, m, offset=np.array([0.0, r, 0.0])),)
        links = ()
    mesh = Mesh(pts, (CellBlock("line", cells),), point_masses=pms, rigid_links=links)
    nearly_massless = Material(E, NU, 1e-3)  # rod mass 1e-6 kg vs 5 kg
    fe = assemble(mesh, nearly_massless, beam_section=BeamSection(1e-3, Iy, Iz, J,
                                                          orientation=(0, 1, 0)))
    f, _ = eigenmodes(fe, 1, np.arange(6))
    G = E / (2 * (1 + NU))
    flex = L**3 / (3 * E * Iy) + r**2 * L / (G * J)
    assert f[0] == pytest.approx(np.sqrt(1 / (m * flex)) / (2 * np.pi), rel=1e-6)
