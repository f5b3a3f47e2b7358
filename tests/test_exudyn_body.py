"""The Exudyn adapter: a FlexBody as ObjectFFRFreducedOrder against the full FE model
(static and dynamic, one interface clamped, the other loaded), conservation of momentum
of a free flexible body, and the rigid twin."""

from __future__ import annotations

import numpy as np
import pytest

exu = pytest.importorskip("exudyn")
import exudyn.itemInterface as eii  # noqa: E402
from test_reduction import PA, PB, spider_model  # noqa: E402

import flexpipe  # noqa: E402
from flexpipe.exu.body import add_flexible_body, add_rigid_twin  # noqa: E402
from flexpipe.fem import Material, assemble  # noqa: E402
from flexpipe.mesh.generate import box  # noqa: E402

STEEL = Material(210e9, 0.3, 7850.0)
L, B, H = 1.0, 0.2, 0.1


@pytest.fixture(scope="module")
def model():
    fe = assemble(box(L, B, H, 16, 3, 2), STEEL)
    itfs = [flexpipe.Interface(PA, radius=0.07, name="a"),
            flexpipe.Interface(PB, radius=0.07, name="b")]
    body = flexpipe.reduce(fe, itfs, method="craig-bampton", n_modes=8)
    K, M, nf = spider_model(fe)
    return fe, body, K, M, nf


def _quiet(ss):
    ss.timeIntegration.verboseMode = 0
    ss.staticSolver.verboseMode = 0
    ss.solution.file.write = False
    ss.show.computationTime = False
    ss.show.statistics = False
    return ss


def _clamped(body, *, force=None, torque=None, damping=False):
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    h = add_flexible_body(mbs, body, gravity=(0, 0, 0), damping=damping)
    ground = mbs.AddObject(eii.ObjectGround())
    mg = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localPosition=list(PA)))
    mbs.AddObject(eii.GenericJoint(markerNumbers=[mg, h.markers["a"]], constrainedAxes=[1] * 6))
    loads = []
    if force is not None:
        loads.append(mbs.AddLoad(eii.LoadForceVector(markerNumber=h.markers["b"],
                                                     loadVector=list(force))))
    if torque is not None:
        mbs.AddLoad(eii.LoadTorqueVector(markerNumber=h.markers["b"], loadVector=list(torque)))
    return SC, mbs, h, loads


def test_static_response_matches_full_fe(model):
    fe, body, K, _, nf = model
    F = np.array([0.0, 20.0, -100.0])
    T = np.array([5.0, 0.0, 0.0])
    SC, mbs, h, _ = _clamped(body, force=F, torque=T)
    mbs.Assemble()
    ss = _quiet(exu.SimulationSettings())
    ss.staticSolver.newton.relativeTolerance = 1e-12
    ss.staticSolver.newton.absoluteTolerance = 1e-16
    ss.linearSolver.solverType = exu.LinearSolverType.EigenDense
    mbs.SolveStatic(ss)
    u = h.interface_position(mbs, "b") - h.interface_position(mbs, "b", reference=True)
    rot = np.asarray(mbs.GetMarkerOutput(h.markers["b"], exu.OutputVariableType.Rotation))
    keep = np.r_[np.arange(nf), nf + 6 + np.arange(6)]
    f = np.zeros(K.shape[0])
    f[nf + 6: nf + 9], f[nf + 9:] = F, T
    x = np.linalg.solve(K[np.ix_(keep, keep)], f[keep])[-6:]
    # Exudyn's FFRF is geometrically nonlinear: differences are O(deflection^2 / L)
    np.testing.assert_allclose(u, x[:3], atol=1e-5 * np.abs(x[:3]).max())
    np.testing.assert_allclose(rot, x[3:], atol=1e-5 * np.abs(x[3:]).max())


def test_dynamic_response_matches_full_fe(model):
    """Half-sine pulse (8 ms, above the first clamped mode's period) at interface b."""
    fe, body, K, M, nf = model
    F0, T_pulse, dt, t_end = 400.0, 8e-3, 5e-5, 0.02

    def force(t):
        return F0 * np.sin(np.pi * t / T_pulse) if t < T_pulse else 0.0

    SC, mbs, h, loads = _clamped(body, force=(0.0, 0.0, 0.0))
    mbs.SetLoadParameter(loads[0], "loadVectorUserFunction",
                         lambda mbs_, t, load: [0.0, 0.0, force(t)])
    mbs.Assemble()
    ss = _quiet(exu.SimulationSettings())
    ss.timeIntegration.numberOfSteps = int(round(t_end / dt))
    ss.timeIntegration.endTime = t_end
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0  # trapezoidal rule
    ss.timeIntegration.newton.relativeTolerance = 1e-10
    z_exu = []

    def record(mbs_, t):
        z_exu.append(mbs_.GetMarkerOutput(h.markers["b"], exu.OutputVariableType.Position)[2])
        return True

    mbs.SetPreStepUserFunction(record)
    mbs.SolveDynamic(ss)
    z_exu = np.array(z_exu) - PB[2]
    # full model, trapezoidal rule (Newmark average acceleration), same step
    keep = np.r_[np.arange(nf), nf + 6 + np.arange(6)]
    Kf, Mf = K[np.ix_(keep, keep)], M[np.ix_(keep, keep)]
    n = len(keep)
    e = np.zeros(n)
    e[-4] = 1.0  # z force at hardpoint b
    A = Kf + 4 / dt**2 * Mf
    Ainv = np.linalg.inv(A)
    x, v, a = np.zeros(n), np.zeros(n), np.zeros(n)
    z_full = [0.0]
    for k in range(1, int(round(t_end / dt)) + 1):
        t = k * dt
        rhs = force(t) * e + Mf @ (4 / dt**2 * x + 4 / dt * v + a)
        x_new = Ainv @ rhs
        a_new = 4 / dt**2 * (x_new - x) - 4 / dt * v - a
        v = v + dt / 2 * (a + a_new)
        x, a = x_new, a_new
        z_full.append(x[-4])
    z_full = np.array(z_full)
    m = min(len(z_full), len(z_exu))
    peak = np.abs(z_full).max()
    assert peak > 1e-6
    # 14 elastic modes against the full model: within 2% of the peak over 20 ms
    np.testing.assert_allclose(z_exu[:m], z_full[:m], atol=0.02 * peak)


def _momenta(mbs, h, body, Mt):
    n = body.n_nodes
    x = np.array([mbs.GetObjectOutputSuperElement(h.object, exu.OutputVariableType.Position, i)
                  for i in range(n)])
    v = np.array([mbs.GetObjectOutputSuperElement(h.object, exu.OutputVariableType.Velocity, i)
                  for i in range(n)])
    Mv = (Mt @ v.ravel()).reshape(n, 3)  # isotropic nodal blocks (solid mesh)
    return Mv.sum(axis=0), np.cross(x, Mv).sum(axis=0)


def _free_run(fe, body, n_steps):
    from flexpipe.flexbody.invariants import translational_block

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    h = add_flexible_body(mbs, body, gravity=(0, 0, 0), damping=False,
                          velocity=(1.0, -0.5, 0.2), angular_velocity=(3.0, 20.0, -8.0))
    # start with some elastic vibration too
    mbs.SetNodeParameter(h.modal_node, "initialCoordinates_t",
                         list(0.05 * np.ones(body.n_elastic)))
    mbs.Assemble()
    Mt = translational_block(fe.M, 3)
    p0, L0 = _momenta(mbs, h, body, Mt)
    ss = _quiet(exu.SimulationSettings())
    ss.timeIntegration.numberOfSteps = n_steps
    ss.timeIntegration.endTime = 0.04
    ss.timeIntegration.generalizedAlpha.spectralRadius = 1.0
    ss.timeIntegration.newton.relativeTolerance = 1e-12
    mbs.SolveDynamic(ss)
    p1, L1 = _momenta(mbs, h, body, Mt)
    assert np.abs(h.modal_coordinates(mbs)).max() > 0  # it did deform
    return (np.linalg.norm(p1 - p0) / np.linalg.norm(p0),
            np.linalg.norm(L1 - L0) / np.linalg.norm(L0))


def test_free_flexible_body_conserves_momentum(model):
    """Drift is the trapezoidal rule's O(dt^2) error: measured 7.5e-7 -> 1.8e-7 (p) and
    7.8e-7 -> 1.9e-7 (L) from 200 to 400 steps over 40 ms at 20 rad/s."""
    fe, body, _, _, _ = model
    dp1, dL1 = _free_run(fe, body, 200)
    dp2, dL2 = _free_run(fe, body, 400)
    assert dp2 < 1e-6 and dL2 < 1e-6
    assert dp1 / dp2 > 3.5 and dL1 / dL2 > 3.5  # converges to exact conservation


def test_rigid_twin_matches_mass_properties_and_motion(model):
    _, body, _, _, _ = model
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    w0 = (2.0, 15.0, -4.0)
    hf = add_flexible_body(mbs, body, gravity=(0, 0, -9.81), angular_velocity=w0, damping=False)
    hr = add_rigid_twin(mbs, body, position=(0, 2.0, 0), gravity=(0, 0, -9.81),
                        angular_velocity=w0, show_surface=False)
    assert mbs.GetObjectParameter(hr.object, "mass") == pytest.approx(body.mass, rel=1e-14)
    J = body.inertia_origin
    np.testing.assert_allclose(mbs.GetObjectParameter(hr.object, "inertia"),
                               [J[0, 0], J[1, 1], J[2, 2], J[1, 2], J[0, 2], J[0, 1]])
    assert set(hr.markers) == set(hf.markers) == {"a", "b"}
    mbs.Assemble()
    ss = _quiet(exu.SimulationSettings())
    ss.timeIntegration.numberOfSteps = 200
    ss.timeIntegration.endTime = 0.2
    mbs.SolveDynamic(ss)
    # a stiff steel bar tumbling at ~15 rad/s: flexible and rigid interface b coincide
    pf = hf.interface_position(mbs, "b")
    pr = hr.interface_position(mbs, "b") - np.array([0, 2.0, 0])
    np.testing.assert_allclose(pf, pr, atol=1e-5)
    # ballistic centre of mass: c + (w0 x c) t + g t^2 / 2 (the origin starts at rest)
    c, t = body.center_of_mass, 0.2
    expected = c + np.cross(w0, c) * t + np.array([0, 0, -9.81]) * t**2 / 2
    Rm = np.asarray(mbs.GetNodeOutput(hr.node, exu.OutputVariableType.RotationMatrix))
    com = np.asarray(mbs.GetNodeOutput(hr.node, exu.OutputVariableType.Position)) + \
        Rm.reshape(3, 3) @ c
    # (200 steps of the default integrator: 2e-5 m of integration error after 0.2 s)
    np.testing.assert_allclose(com - [0, 2.0, 0], expected, atol=1e-4)
