"""Symbolic force laws of the suspension's springs, dampers and stops
(:mod:`flexpipe.exu.force_laws`) against the elements' own NumPy methods
(:meth:`ForceElement.static_force`, :meth:`ForceElement.damper_force`), and a mass on a
symbolic spring-damper against the closed-form damped oscillation.
"""

import math

import numpy as np
import pytest

exu = pytest.importorskip("exudyn")
import exudyn.itemInterface as eii  # noqa: E402

from flexpipe.exu.force_laws import bushing_law, interp, symbolic_law  # noqa: E402
from flexpipe.vehicle.suspension.model import ForceElement  # noqa: E402

A, B = (0.0, 0.6, -0.27), (-0.04, 0.52, 0.23)  # seats: lower (part), upper (body)
L0 = float(np.linalg.norm(np.subtract(A, B)))
ELEMENTS = {
    "spring_rate": ForceElement("s", "spring", "arm", A, "m", B, rate=111e3,
                                free_length=L0 + 0.03),
    "spring_table": ForceElement("s", "spring", "arm", A, "m", B, free_length=L0 + 0.03,
                                 table=(np.array([0.0, 0.02, 0.05, 0.08]),
                                        np.array([0.0, 2e3, 6e3, 15e3]))),
    "damper": ForceElement("d", "damper", "arm", A, "m", B,
                           table=(np.array([-1.0, -0.1, 0.0, 0.1, 1.0]),
                                  np.array([-6680.0, -1200.0, 0.0, 2500.0, 13360.0]))),
    "bump_stop": ForceElement("b", "bump_stop", "arm", A, "m", B, clearance=0.036,
                              table=(np.array([0.0, 0.005, 0.01, 0.02]),
                                     np.array([0.0, 1e3, 3.5e3, 12e3]))),
    "rebound_stop": ForceElement("r", "rebound_stop", "arm", A, "m", B, clearance=0.047,
                                 table=(np.array([0.0, 0.005, 0.01]),
                                        np.array([0.0, 2e3, 8e3]))),
}


@pytest.mark.parametrize("name", sorted(ELEMENTS))
def test_law_equals_the_elements_numpy_force(name):
    f = ELEMENTS[name]
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    law = symbolic_law(mbs, f)
    rng = np.random.default_rng(3)
    us = np.concatenate([np.linspace(-0.12, 0.12, 241), rng.uniform(-0.2, 0.2, 50)])
    vs = np.concatenate([np.linspace(-1.5, 1.5, 241), rng.uniform(-2.0, 2.0, 50)])
    for u, v in zip(us, vs, strict=True):
        got = law.Evaluate(mbs, 0.0, 0, float(u), float(v), 0.0, 0.0, 0.0)
        # Exudyn's connector force is tension > 0: the spring's and the stops' push
        # apart with a minus, the damper's resisting force as it is
        want = f.damper_force(v) if f.kind == "damper" else -f.static_force(L0 + u)
        assert got == pytest.approx(want, rel=1e-12, abs=1e-9), (u, v)


def test_interp_equals_numpy_interp_with_clamping():
    xs, ys = [-1.0, -0.2, 0.0, 0.3, 1.0], [-5.0, -1.0, 0.0, 2.0, 4.0]
    for x in np.linspace(-2.0, 2.0, 81):
        assert interp(float(x), xs, ys) == pytest.approx(np.interp(x, xs, ys), abs=1e-12)


def test_mass_on_symbolic_spring_damper_rings_as_the_closed_form():
    """1 kg on the linear spring (111 kN/m) and a linear damper (zeta 0.05), released
    from 1 mm: the exact damped oscillation (h = 1e-5 s)."""
    k, m = 111e3, 1.0
    c = 2 * 0.05 * math.sqrt(k * m)
    spring = ForceElement("s", "spring", "arm", A, "m", B, rate=k, free_length=L0)
    damper = ForceElement("d", "damper", "arm", A, "m", B,
                          table=(np.array([-10.0, 10.0]), np.array([-10.0 * c, 10.0 * c])))
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    d = np.subtract(A, B) / L0
    node = mbs.AddNode(eii.NodePoint(referenceCoordinates=list(np.add(B, L0 * d)),
                                     initialCoordinates=list(1e-3 * d)))
    mass = mbs.AddObject(eii.MassPoint(nodeNumber=node, mass=m))
    m0 = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground, localPosition=list(B)))
    m1 = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=mass, localPosition=[0, 0, 0]))
    laws = [symbolic_law(mbs, e) for e in (spring, damper)]
    for law in laws:
        mbs.AddObject(eii.ObjectConnectorSpringDamper(
            markerNumbers=[m0, m1], referenceLength=L0, springForceUserFunction=law))
    mbs.Assemble()
    s = exu.SimulationSettings()
    T = 0.01
    s.timeIntegration.numberOfSteps = 1000
    s.timeIntegration.endTime = T
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    mbs.SolveDynamic(s)
    x = float(np.dot(mbs.GetNodeOutput(node, exu.OutputVariableType.Displacement), d))
    wn = math.sqrt(k / m)
    z = c / (2 * math.sqrt(k * m))
    wd = wn * math.sqrt(1 - z * z)
    exact = 1e-3 * math.exp(-z * wn * T) * (math.cos(wd * T) + z / math.sqrt(1 - z * z)
                                           * math.sin(wd * T))
    assert x == pytest.approx(exact, abs=2e-3 * 1e-3)


def _bushing_run(bushing, *, law, load=(0.0, 0.0, 0.0), static=False):
    """A 2 kg rigid body on ``bushing`` (frame turned off the body axes) to the ground:
    free vibration from an initial velocity and spin (dynamic) or the deflection under
    ``load`` (static).  Returns the body's position and rotation."""
    from exudyn.rigidBodyUtilities import GetRigidBodyNode

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    node = mbs.AddNode(GetRigidBodyNode(
        nodeType=exu.NodeType.RotationEulerParameters, position=[0.0, 0.0, 0.0],
        velocity=[0.0 if static else 0.05, 0.0 if static else -0.03,
                  0.0 if static else 0.08],
        rotationMatrix=np.eye(3),
        angularVelocity=[0.0, 0.0, 0.0] if static else [0.5, -0.4, 0.3]))
    body = mbs.AddObject(eii.ObjectRigidBody(mass=2.0, nodeNumber=node,
                                             inertia=[0.02, 0.03, 0.04, 0.0, 0.0, 0.0]))
    at = exu.HT(rotation=np.asarray(bushing.frame), translation=[0.0, 0.0, 0.0])
    m0 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=ground, localHT=at))
    m1 = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=body, localHT=at))
    kw = {"springForceTorqueUserFunction": bushing_law(mbs, bushing)} if law else {}
    mbs.AddObject(eii.ObjectConnectorRigidBodySpringDamper(
        markerNumbers=[m0, m1], stiffness=np.diag(bushing.stiffness),
        damping=np.diag(bushing.damping), **kw))
    mb = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=body, localPosition=[0, 0, 0]))
    mbs.AddLoad(eii.LoadForceVector(markerNumber=mb, loadVector=list(load)))
    mbs.Assemble()
    s = exu.SimulationSettings()
    s.solution.file.write = False
    if static:
        s.staticSolver.verboseMode = 0
        s.staticSolver.newton.relativeTolerance = 1e-12
        mbs.SolveStatic(s)
    else:
        s.timeIntegration.numberOfSteps = 500
        s.timeIntegration.endTime = 0.05
        s.timeIntegration.verboseMode = 0
        mbs.SolveDynamic(s)
    out = exu.OutputVariableType
    return (np.asarray(mbs.GetNodeOutput(node, out.Position)),
            np.asarray(mbs.GetNodeOutput(node, out.RotationMatrix)).reshape(3, 3))


def _frame():
    a, b = math.radians(30.0), math.radians(20.0)
    Rz = np.array([[math.cos(a), -math.sin(a), 0], [math.sin(a), math.cos(a), 0], [0, 0, 1]])
    Rx = np.array([[1, 0, 0], [0, math.cos(b), -math.sin(b)], [0, math.sin(b), math.cos(b)]])
    return Rz @ Rx


def test_bushing_law_with_linear_tables_is_exudyns_own_linear_bushing():
    """Tables that are exactly the linear rates: the symbolic law must reproduce Exudyn's
    own linear bushing (frames, signs, damping, rotations) along a free vibration."""
    from flexpipe.vehicle.suspension.model import BUSHING_DOFS, Bushing

    k = np.array([8e4, 6e4, 1e5, 50.0, 40.0, 30.0])
    c = np.array([40.0, 30.0, 50.0, 0.05, 0.04, 0.03])
    tables = {d: (np.array([-10.0, 10.0]), np.array([-10.0 * k[i], 10.0 * k[i]]))
              for i, d in enumerate(BUSHING_DOFS)}
    lin = Bushing(k, c, _frame())
    tab = Bushing(k, c, _frame(), tables)
    p_ref, R_ref = _bushing_run(lin, law=False)
    p, R = _bushing_run(tab, law=True)
    assert np.abs(p_ref).max() > 1e-4 and np.abs(R_ref - np.eye(3)).max() > 1e-3
    np.testing.assert_allclose(p, p_ref, rtol=0, atol=1e-9)
    np.testing.assert_allclose(R, R_ref, rtol=0, atol=1e-9)


def test_nonlinear_bushing_deflects_as_its_table():
    """A progressive table along the bushing's local z under a static load along that
    axis: the deflection is the table's inverse at the load (closed form)."""
    from flexpipe.vehicle.suspension.model import Bushing

    A = _frame()
    x = np.array([-0.004, -0.002, 0.0, 0.002, 0.004])
    f = np.array([-9000.0, -2500.0, 0.0, 2500.0, 9000.0])
    bu = Bushing([8e6, 8e6, 1e6, 500.0, 500.0, 150.0], np.zeros(6), A, {"z": (x, f)})
    F = 5000.0
    p, _ = _bushing_run(bu, law=True, load=F * A[:, 2], static=True)
    want = np.interp(F, f, x)  # the load is carried by the table along z
    assert float(A[:, 2] @ p) == pytest.approx(want, rel=1e-6)
    assert np.linalg.norm(p - (A[:, 2] @ p) * A[:, 2]) < 1e-9


def test_elements_between_the_same_seats_share_one_summed_law():
    """Spring, damper and stops between the same two seats are one connector whose force
    is the sum of the elements' own NumPy forces; elements on other seats stay apart."""
    from flexpipe.exu.force_laws import seat_groups

    group = [ELEMENTS[k] for k in ("spring_rate", "damper", "bump_stop", "rebound_stop")]
    other = ForceElement("s2", "spring", "arm", (0.0, 0.5, -0.27), "m", B, rate=5e4,
                         free_length=L0)
    assert [len(g) for g in seat_groups(group + [other])] == [4, 1]
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    law = symbolic_law(mbs, *group)
    rng = np.random.default_rng(5)
    for u, v in zip(rng.uniform(-0.1, 0.1, 200), rng.uniform(-1.5, 1.5, 200), strict=True):
        got = law.Evaluate(mbs, 0.0, 0, float(u), float(v), 0.0, 0.0, 0.0)
        want = sum(f.damper_force(v) if f.kind == "damper" else -f.static_force(L0 + u)
                   for f in group)
        assert got == pytest.approx(want, rel=1e-12, abs=1e-9), (u, v)
    with pytest.raises(ValueError, match="share their seats"):
        symbolic_law(mbs, group[0], other)
