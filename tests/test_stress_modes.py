"""Stress modes: element stress operators against closed forms, and modal stress recovery
against a full FE static solve under an inertia-relief interface load case."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse as sp
import scipy.sparse.linalg as spla

import flexpipe as fp
from flexpipe.durability.recover import equivalents
from flexpipe.fem import stress as fs
from flexpipe.flexbody.invariants import rigid_body_vectors
from flexpipe.flexbody.stress import stress_modes
from flexpipe.mesh.generate import box, plate
from flexpipe.reduction.interface import interface_system, resolve_interfaces

STEEL = fp.Material(210e9, 0.3, 7850.0)
E, NU = STEEL.E, STEEL.nu


def _field(X, u_fun, dpn):
    """Element DOF vectors (ne, nn * dpn) of a nodal field u_fun(x) -> (n, dpn)."""
    ne, nn, _ = X.shape
    return u_fun(X.reshape(-1, 3)).reshape(ne, nn * dpn)


@pytest.mark.parametrize("cell", ["quad", "triangle"])
def test_shell_operators_membrane_and_bending_closed_form(cell):
    # a skewed, rotated patch of shells: constant strain and constant curvature fields
    m = plate(0.3, 0.2, 3, 2, cell=cell)
    P = m.points.copy()
    P[:, 0] += 0.15 * P[:, 1]  # distort
    c, s = np.cos(0.4), np.sin(0.4)
    Rz = np.array([[c, -s, 0], [s, c, 0], [0, 0, 1.0]])
    Rx = np.array([[1, 0, 0], [0, np.cos(0.3), -np.sin(0.3)], [0, np.sin(0.3), np.cos(0.3)]])
    Q = Rx @ Rz  # plate plane -> global
    X = (P @ Q.T)[m.blocks[0].cells]
    ne = len(X)
    t = np.full(ne, 0.004)
    S, frames = fs.operators(cell, X, E=np.full(ne, E), nu=np.full(ne, NU), thickness=t)
    ex, ey, kap = 2e-4, -1e-4, 0.05

    def u_fun(x):
        loc = x @ Q  # plate coordinates
        u = np.zeros((len(x), 6))
        disp = np.column_stack([ex * loc[:, 0], ey * loc[:, 1],
                                -0.5 * kap * loc[:, 0] ** 2])
        rot = np.column_stack([np.zeros(len(x)), kap * loc[:, 0], np.zeros(len(x))])
        u[:, :3] = disp @ Q.T
        u[:, 3:] = rot @ Q.T
        return u

    sig = np.einsum("ecd,ed->ec", S, _field(X, u_fun, 6))
    # closed form in plate axes, then into each element frame
    f = E / (1 - NU**2)
    m_plate = np.array([[f * (ex + NU * ey), 0, 0], [0, f * (ey + NU * ex), 0], [0, 0, 0]])
    b_plate = np.array([[f * kap * 0.002, 0, 0], [0, f * NU * kap * 0.002, 0], [0, 0, 0]])
    for k in range(ne):
        A = frames[k] @ Q  # element axes in plate axes (rows)
        for block, ref in ((sig[k, :3], m_plate), (sig[k, 3:], b_plate)):
            T = A @ ref @ A.T
            want = np.array([T[0, 0], T[1, 1], T[0, 1]])
            np.testing.assert_allclose(block, want, atol=1e-9 * f * 2e-4)


@pytest.mark.parametrize("cell", ["tetra", "tetra10", "hexahedron"])
def test_solid_operators_constant_strain(cell):
    m = box(0.2, 0.1, 0.1, 2, 1, 1, cell=cell)
    P = m.points.copy()
    P[:, 0] += 0.1 * P[:, 2]
    X = P[m.blocks[0].cells]
    eps = np.array([[1e-4, 2e-5, -3e-5], [2e-5, -5e-5, 4e-5], [-3e-5, 4e-5, 7e-5]])
    S, _ = fs.operators(cell, X, E=np.full(len(X), E), nu=np.full(len(X), NU))
    sig = np.einsum("ecd,ed->ec", S, _field(X, lambda x: x @ eps.T, 3))
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    T = lam * np.trace(eps) * np.eye(3) + 2 * mu * eps
    want = [T[0, 0], T[1, 1], T[2, 2], T[1, 2], T[0, 2], T[0, 1]]
    np.testing.assert_allclose(sig, np.broadcast_to(want, sig.shape), rtol=1e-9, atol=1e-3)


def test_beam_operator_axial_and_bending():
    # a beam along a skew axis; u = e s, v = kappa s^2 / 2 in its local x-y plane
    d = np.array([1.0, 2.0, 2.0]) / 3.0
    v = np.array([0.0, 0.0, 1.0])
    ez = np.cross(d, v)
    ez /= np.linalg.norm(ez)
    ey = np.cross(ez, d)
    X = np.array([[[0.1, 0.2, 0.3], [0.1, 0.2, 0.3]]]) + np.array([0.0, 0.6])[None, :, None] * d
    A, Iy, Iz = 4e-4, 2e-8, 5e-8
    S, _ = fs.operators("line", X, E=np.array([E]), nu=np.array([NU]), A=np.array([A]),
                        Iy=np.array([Iy]), Iz=np.array([Iz]), J=np.array([1e-8]),
                        orientation=v[None])
    e, kap = 3e-4, 0.02
    s = np.array([0.0, 0.6])
    u = np.zeros((2, 6))
    u[:, :3] = (e * s)[:, None] * d + (0.5 * kap * s**2)[:, None] * ey
    u[:, 3:] = (kap * s)[:, None] * ez  # theta_z = dv/ds
    sig = S[0] @ u.ravel()
    cy = np.sqrt(3 * Iz / A)
    np.testing.assert_allclose(sig, [E * e, E * cy * kap, 0, E * e, E * cy * kap, 0],
                               rtol=1e-9, atol=1e-3)


# ----------------------------------------------------------------------------- MSR
def _inertia_relief_full(fe, itfs, loads):
    """Element stresses of the full FE model (with the interface spiders) under interface
    loads balanced by rigid-body inertia: K u = F - M R a, R^T M u = 0."""
    system = interface_system(fe, resolve_interfaces(fe, itfs))
    n = system.K.shape[0]
    F = np.zeros(n)
    for b, f6 in zip(system.boundary, loads, strict=True):
        F[b] += f6
    Rall = rigid_body_vectors(fe.nodes, fe.dofs_per_node)
    Et = system.E.T.tocsr()
    Rs = spla.spsolve((Et @ system.E).tocsc(), Et @ Rall)
    MR = system.M @ Rs
    a = np.linalg.solve(Rs.T @ MR, Rs.T @ F)
    f_eff = F - MR @ a
    A = sp.bmat([[system.K, sp.csr_matrix(MR)], [sp.csr_matrix(MR.T), None]]).tocsc()
    u = spla.spsolve(A, np.concatenate([f_eff, np.zeros(6)]))[:n]
    u_all = np.asarray(system.E @ u)
    return stress_modes(fe, u_all[:, None], [0])


def _msr(body, loads):
    f = sum(itf.shapes.T @ f6 for itf, f6 in zip(body.interfaces, loads, strict=True))
    e = slice(body.n_rigid, None)
    return f[e] / body.omega[e] ** 2


def _compare_top10(body, ref, q):
    """Relative von Mises error at the 10 highest-stress elements of the reference."""
    errs = []
    for bref, bmsr in zip(ref.blocks, body.stress.blocks, strict=True):
        vm_ref, _ = equivalents(bref.kind, bref.modes)
        vm_msr, _ = equivalents(bmsr.kind, bmsr.modes @ q[:, None])
        errs.append((vm_ref[..., 0], vm_msr[..., 0]))
    ref_all = np.concatenate([r.max(axis=1) for r, _ in errs])
    top = np.argsort(-ref_all)[:10]
    loc_ref = np.concatenate([r for r, _ in errs])  # (ne, nloc)
    loc_msr = np.concatenate([m for _, m in errs])
    crit = loc_ref[top].argmax(axis=1)
    r = loc_ref[top, crit]
    m = loc_msr[top, crit]
    return np.abs(m - r) / r


def test_msr_shell_body_equals_full_static_solve():
    m = plate(1.0, 0.6, 24, 12, cell="quad")
    P = m.points.copy()
    Rc = 0.3  # roll the plate into a curved panel (membrane-bending coupling)
    phi = P[:, 1] / Rc
    P = np.column_stack([P[:, 0], Rc * np.sin(phi), Rc * (1 - np.cos(phi))])
    from dataclasses import replace

    m = replace(m, points=P)
    fe = fp.assemble(m, STEEL, thickness=0.002)
    hp = [(0.0, Rc * np.sin(1.0), Rc * (1 - np.cos(1.0))),
          (1.0, Rc * np.sin(1.0), Rc * (1 - np.cos(1.0)))]
    itfs = [fp.Interface(p, radius=0.06, name=n) for p, n in zip(hp, ("a", "b"), strict=True)]
    body = fp.reduce(fe, itfs, n_modes=40, stress="all")  # 20 modes: 3.6 %, 40: 0.66 %
    loads = [np.array([120.0, 300.0, -500.0, 20.0, -10.0, 15.0]),
             np.array([-80.0, 50.0, 200.0, -5.0, 12.0, 0.0])]
    err = _compare_top10(body, _inertia_relief_full(fe, itfs, loads), _msr(body, loads))
    assert err.max() < 0.01, err


@pytest.mark.parametrize("cell", ["hexahedron", "tetra10"])
def test_msr_solid_body_equals_full_static_solve(cell):
    m = box(1.0, 0.1, 0.1, 20, 2, 2, cell=cell) if cell == "hexahedron" else \
        box(1.0, 0.1, 0.1, 10, 1, 1, cell=cell)
    fe = fp.assemble(m, STEEL)
    itfs = [fp.Interface((0.0, 0.05, 0.05), radius=0.08, name="left"),
            fp.Interface((1.0, 0.05, 0.05), radius=0.08, name="right")]
    body = fp.reduce(fe, itfs, n_modes=40, stress="all")  # hex8 20 modes: 1.0 %, 40: 0.22 %
    loads = [np.array([1e3, 2e3, -5e3, 50.0, -80.0, 120.0]),
             np.array([-4e3, 1e3, 3e3, -20.0, 40.0, 0.0])]
    err = _compare_top10(body, _inertia_relief_full(fe, itfs, loads), _msr(body, loads))
    assert err.max() < 0.01, err


def test_stress_modes_size_switch_and_storage(tmp_path):
    m = plate(0.4, 0.2, 8, 4)
    fe = fp.assemble(m, STEEL, thickness=0.002)
    itfs = [fp.Interface((0.0, 0.1, 0.0), radius=0.05, name="a")]
    full = fp.reduce(fe, itfs, n_modes=4, stress="all")
    assert full.stress.n_elements == 32
    assert fp.reduce(fe, itfs, n_modes=4).stress is None
    assert fp.reduce(fe, itfs, n_modes=4, stress="none").stress is None
    sub = fp.reduce(fe, itfs, n_modes=4, stress="shell")  # the mesh's named cell set
    assert sub.stress.n_elements == 32
    with pytest.raises(fp.InputError, match="no cell set 'roof'"):
        fp.reduce(fe, itfs, n_modes=4, stress="roof")
    back = fp.load_body(full.save(tmp_path / "b.npz"))
    assert back == full
    np.testing.assert_array_equal(back.stress.blocks[0].modes, full.stress.blocks[0].modes)
    assert list(back.stress.mode_index) == list(range(full.n_rigid, full.n_modes))


@pytest.mark.parametrize("cell", ["tetra", "tetra10", "hexahedron"])
def test_solid_nodal_operators_constant_strain(cell):
    m = box(0.2, 0.1, 0.1, 2, 1, 1, cell=cell)
    P = m.points.copy()
    P[:, 0] += 0.1 * P[:, 2]
    X = P[m.blocks[0].cells]
    eps = np.array([[1e-4, 2e-5, -3e-5], [2e-5, -5e-5, 4e-5], [-3e-5, 4e-5, 7e-5]])
    Sn = fs.solid_nodal(cell, X, E=np.full(len(X), E), nu=np.full(len(X), NU))
    sig = np.einsum("eacd,ed->eac", Sn, _field(X, lambda x: x @ eps.T, 3))
    lam, mu = E * NU / ((1 + NU) * (1 - 2 * NU)), E / (2 * (1 + NU))
    T = lam * np.trace(eps) * np.eye(3) + 2 * mu * eps
    want = [T[0, 0], T[1, 1], T[2, 2], T[1, 2], T[0, 2], T[0, 1]]
    np.testing.assert_allclose(sig, np.broadcast_to(want, sig.shape), rtol=1e-9, atol=1e-3)


def test_hex8_nodal_stress_in_pure_bending_equals_beam_theory():
    # one element through the depth: the centroid sees the neutral axis, the nodes the
    # extreme fibres, sigma_xx = -E kappa z' (3D elasticity solution of pure bending)
    L, b, h, kap = 1.0, 0.1, 0.1, 2e-3
    m = box(L, b, h, 10, 1, 1, cell="hexahedron")
    fe = fp.assemble(m, STEEL)
    x, y, z = (m.points - [0.0, b / 2, h / 2]).T
    u = np.column_stack([-kap * x * z, NU * kap * y * z,
                         0.5 * kap * (x**2 + NU * (z**2 - y**2))]).ravel()
    sm = stress_modes(fe, u[:, None], [0])
    blk = sm.blocks[0]
    np.testing.assert_allclose(blk.modes[:, 0, 0], 0.0, atol=1e-6 * E * kap * h)
    zn = m.points[blk.nodes, 2] - h / 2
    np.testing.assert_allclose(blk.nodal[:, 0, 0], -E * kap * zn, rtol=1e-9,
                               atol=1e-9 * E * kap * h)
    np.testing.assert_allclose(blk.nodal[:, 1:, 0], 0.0, atol=1e-8 * E * kap * h)
