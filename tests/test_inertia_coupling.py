"""Constant inertia coupling (flexpipe.exu.inertia): the mean-axis measure against cosines
computed directly from the FE mass matrix and explicit rigid-body modes, refusal of
non-mean-axis bodies, statics equal to the full floating frame, a free tumbling and
falling body equal to the full floating frame and to ballistic motion, and the linkage
car's hub forces equal to the full floating frame."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

exu = pytest.importorskip("exudyn")
import exudyn.itemInterface as eii  # noqa: E402
import test_exudyn_body  # noqa: E402
from test_exudyn_body import _quiet  # noqa: E402
from test_reduction import PA, PB  # noqa: E402

from flexpipe.errors import InputError  # noqa: E402
from flexpipe.exu.body import add_flexible_body  # noqa: E402
from flexpipe.flexbody.invariants import (  # noqa: E402
    MAX_MEAN_AXIS_COSINE,
    ffrf_invariants,
    mean_axis_cosine,
    translational_block,
)

box_body = test_exudyn_body.model  # fixture: the box body of the adapter tests


def _rigid_modes(nodes, c):
    """(3 n, 6): unit translations and unit rotations about ``c``, node by node."""
    R = np.zeros((len(nodes), 3, 6))
    for k in range(3):
        R[:, k, k] = 1.0
        e = np.eye(3)[k]
        R[:, :, 3 + k] = np.cross(e, nodes - c)
    return R.reshape(-1, 6)


def _mass_and_centre(nodes, Mt):
    """Total mass and centre of mass from the FE (translational) mass matrix."""
    t = np.tile(np.eye(3), (len(nodes), 1))
    m = float(t[:, 0] @ (Mt @ t[:, 0]))
    return m, np.array([t[:, k] @ (Mt @ nodes.ravel()) for k in range(3)]) / m


def _direct_cosine(nodes, Mt, Psi):
    """|cos| in the mass metric between each mode and the rigid subspace, from the FE
    mass matrix: the principal angle between span(mode) and the rigid subspace."""
    R = _rigid_modes(nodes, _mass_and_centre(nodes, Mt)[1])
    L = np.linalg.cholesky(R.T @ (Mt @ R))
    Rn = np.linalg.solve(L, R.T).T  # mass-orthonormal rigid basis
    MPsi = Mt @ Psi
    return np.linalg.norm(Rn.T @ MPsi, axis=0) / np.sqrt(np.einsum("ij,ij->j", Psi, MPsi))


def _fake_body(Psi, nodes, Mt):
    """The attributes :func:`mean_axis_cosine` reads, for modes ``Psi`` (3 n x m)."""
    m, c = _mass_and_centre(nodes, Mt)
    R = _rigid_modes(nodes, c)
    Jc = R[:, 3:].T @ (Mt @ R[:, 3:])
    return SimpleNamespace(invariants=ffrf_invariants(nodes, Mt, Psi), M=np.block(
        [[np.eye(6), np.zeros((6, Psi.shape[1]))],
         [np.zeros((Psi.shape[1], 6)), Psi.T @ (Mt @ Psi)]]), n_rigid=6,
        n_elastic=Psi.shape[1], mass=m, center_of_mass=c, inertia=Jc,
        frequencies_hz=np.zeros(6 + Psi.shape[1]))


def test_mean_axis_cosine_matches_fe_mass_metric(box_body):
    fe, body, *_ = box_body
    nodes = body.nodes
    Mt = translational_block(fe.M, fe.M.shape[0] // len(nodes))
    Psi = body.modes[:, :, body.n_rigid:].reshape(-1, body.n_elastic)
    # the reduced body's free-free modes are mean-axis modes
    cos0, _ = mean_axis_cosine(body)
    assert cos0 < 1e-6
    # modes polluted with rigid motion (translation, rotation about an axis off the
    # centre of mass): the invariant-based measure equals the direct FE one
    rng = np.random.default_rng(3)
    c = _mass_and_centre(nodes, Mt)[1]
    R = _rigid_modes(nodes, c + np.array([0.3, -0.1, 0.05]))
    scale = np.sqrt(np.einsum("ij,ij->j", Psi, Mt @ Psi))
    polluted = Psi + (R @ rng.normal(size=(6, Psi.shape[1]))) * 0.5 * scale / 40.0
    direct = _direct_cosine(nodes, Mt, polluted)
    got, j = mean_axis_cosine(_fake_body(polluted, nodes, Mt))
    assert direct.max() > 10 * MAX_MEAN_AXIS_COSINE
    assert got == pytest.approx(direct.max(), rel=1e-6)
    assert j == int(np.argmax(direct))


def test_constant_coupling_refuses_non_mean_axis_modes(box_body):
    fe, body, *_ = box_body
    nodes = body.nodes
    Mt = translational_block(fe.M, fe.M.shape[0] // len(nodes))
    Psi = body.modes[:, :, body.n_rigid:].reshape(-1, body.n_elastic)
    # every mode polluted with vertical translation, the first one most (the equal
    # pollution of all modes left the worst one to rounding)
    weight = np.full(Psi.shape[1], 0.5)
    weight[0] = 1.0
    polluted = Psi + np.tile([0.0, 0.0, 1.0], len(nodes))[:, None] * 0.05 * weight
    fake = _fake_body(polluted, nodes, Mt)
    from flexpipe.exu.inertia import check_mean_axes

    with pytest.raises(InputError, match="mean axes.*elastic mode 1.*inertia_coupling='full'"):
        check_mean_axes(fake)
    SC = exu.SystemContainer()
    with pytest.raises(InputError, match="inertia_coupling 'partial'; valid: full, constant"):
        add_flexible_body(SC.AddSystem(), body, inertia_coupling="partial")


def test_constant_coupling_statics_equal_full(box_body):
    _, body, *_ = box_body
    tips = []
    for coupling in ("full", "constant"):
        SC = exu.SystemContainer()
        mbs = SC.AddSystem()
        h = add_flexible_body(mbs, body, gravity=(0, 0, 0), damping=False,
                              inertia_coupling=coupling)
        ground = mbs.AddObject(eii.ObjectGround())
        mg = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=list(PA)))
        mbs.AddObject(eii.GenericJoint(markerNumbers=[mg, h.markers["a"]],
                                       constrainedAxes=[1] * 6))
        mbs.AddLoad(eii.LoadForceVector(markerNumber=h.markers["b"],
                                        loadVector=[0.0, 20.0, -100.0]))
        mbs.Assemble()
        mbs.SolveStatic(_quiet(exu.SimulationSettings()))
        tips.append(h.interface_position(mbs, "b") - np.asarray(PB))
    assert np.linalg.norm(tips[0]) > 1e-7
    np.testing.assert_allclose(tips[1], tips[0], rtol=1e-9, atol=1e-12)


def _free(body, coupling, w0, loads, steps=400, t_end=0.2):
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    h = add_flexible_body(mbs, body, gravity=(0, 0, -9.81), angular_velocity=w0,
                          damping=False, inertia_coupling=coupling)
    for name, f in loads.items():
        mbs.AddLoad(eii.LoadForceVector(markerNumber=h.markers[name], loadVector=list(f)))
    mbs.Assemble()
    ss = _quiet(exu.SimulationSettings())
    ss.timeIntegration.numberOfSteps = steps
    ss.timeIntegration.endTime = t_end
    mbs.SolveDynamic(ss)
    return (h.interface_position(mbs, "b"), h.modal_coordinates(mbs),
            np.asarray(mbs.GetNodeOutput(h.node, exu.OutputVariableType.Position)))


def test_constant_coupling_free_body_without_rotation_equals_full(box_body):
    """A free bar accelerated by equal loads at both ends (no torque about its centre of
    mass) and falling: no rotation, so the terms constant coupling leaves out are zero and
    the inertia-relief bending equals the full floating frame's."""
    _, body, *_ = box_body
    loads = {"a": (0.0, 0.0, 300.0), "b": (0.0, 0.0, 300.0)}
    pf, qf, of = _free(body, "full", (0, 0, 0), loads)
    pc, qc, oc = _free(body, "constant", (0, 0, 0), loads)
    assert np.abs(qf).max() > 1e-7  # the loads bend the bar
    np.testing.assert_allclose(qc, qf, atol=1e-6 * np.abs(qf).max())
    np.testing.assert_allclose(pc, pf, atol=1e-8)  # of a 0.12 m fall
    np.testing.assert_allclose(oc, of, atol=1e-8)


def test_constant_coupling_tumbling_body_close_to_full(box_body):
    """The bar tumbling at about 2 rad/s with an end load: the rigid motion as with the
    full floating frame; the elastic coordinates differ by the centrifugal load of the
    rotation on the modes, which constant coupling leaves out (measured 0.25-1.1 % of
    the largest modal coordinate at 0-2.3 rad/s initial rate; vehicle body rates are
    ten times lower, the load goes with their square)."""
    _, body, *_ = box_body
    w0 = (0.5, 2.0, -1.0)
    loads = {"b": (0.0, 0.0, 200.0)}
    pf, qf, of = _free(body, "full", w0, loads)
    pc, qc, oc = _free(body, "constant", w0, loads)
    assert np.abs(qf).max() > 1e-7
    np.testing.assert_allclose(pc, pf, atol=1e-7)
    np.testing.assert_allclose(oc, of, atol=1e-7)
    np.testing.assert_allclose(qc, qf, atol=2e-2 * np.abs(qf).max())


def test_compact_modal_matrices_and_the_mass_matrix_exudyn_assembles(box_body):
    """Diagonal modal matrices go to Exudyn as their non-zero entries only (a dense
    matrix otherwise), and the constant-coupling body's system mass matrix is the FE
    body's own: the rigid mass on the frame's translations and the reduced modal mass
    ``Phi^T M Phi`` on the modal coordinates, computed here from the FE mass matrix."""
    from flexpipe.exu.inertia import compact

    c = compact(np.diag([2.0, 0.0, 5.0])).GetPythonObject()
    assert isinstance(c, dict)
    np.testing.assert_array_equal(c["triplets"], [[0, 0, 2.0], [2, 2, 5.0]])
    full = np.array([[1.0, 0.5], [0.5, 2.0]])
    np.testing.assert_array_equal(compact(full).GetPythonObject(), full)

    fe, body, *_ = box_body
    Phi = body.modes[:, :, body.n_rigid:].reshape(-1, body.n_elastic)
    Mt = translational_block(fe.M, fe.M.shape[0] // len(body.nodes))
    M_modal = Phi.T @ (Mt @ Phi)
    assert np.allclose(M_modal, np.diag(np.diag(M_modal)), atol=1e-9 * M_modal.max())
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    add_flexible_body(mbs, body, gravity=(0, 0, 0), damping=False,
                      inertia_coupling="constant")
    mbs.Assemble()
    solver = exu.MainSolverStatic()
    solver.InitializeSolver(mbs, _quiet(exu.SimulationSettings()))
    solver.ComputeMassMatrix(mbs)
    n = solver.GetODE2size()
    M = solver.GetSystemMassMatrix()[:n, :n]
    m_fe = _mass_and_centre(body.nodes, Mt)[0]
    np.testing.assert_allclose(np.diag(M)[:3], m_fe, rtol=1e-9)
    np.testing.assert_allclose(M[7:, 7:], M_modal, rtol=0, atol=1e-9 * M_modal.max())
