"""Brackets of :mod:`flexpipe.exu.brackets` against Exudyn's own rigid marker.

Reference: the same reduced body loaded through Exudyn's ``MarkerSuperElementRigid`` on
the same marker points (an independent implementation of a mount's frame), and the
reduced model's own rotation of the interface (``Interface.shapes``).
"""

from __future__ import annotations

import numpy as np
import pytest

import flexpipe
from flexpipe.fem import Material, assemble
from flexpipe.mesh.generate import box

exu = pytest.importorskip("exudyn")
import exudyn.itemInterface as eii  # noqa: E402

from flexpipe.exu.body import add_flexible_body  # noqa: E402
from flexpipe.exu.brackets import frame_bracket, mount_bracket  # noqa: E402

STEEL = Material(210e9, 0.3, 7850.0)
HELD = {"a": (0.10, 0.0, 0.0), "b": (0.10, 0.40, 0.0), "c": (0.90, 0.0, 0.0)}
END = (1.0, 0.2, 0.05)
F = np.array([300.0, -200.0, 1000.0])
T = np.array([150.0, 400.0, -250.0])


@pytest.fixture(scope="module")
def body():
    fe = assemble(box(1.0, 0.4, 0.1, 20, 8, 2, cell="hexahedron"), STEEL)
    itfs = [flexpipe.Interface(p, name=n, dofs=3) for n, p in HELD.items()]
    itfs.append(flexpipe.Interface(END, radius=0.06, name="end", dofs=6))
    return flexpipe.reduce(fe, itfs, n_modes=10)


def _rotation(deg_z, deg_x):
    cz, sz = np.cos(np.radians(deg_z)), np.sin(np.radians(deg_z))
    cx, sx = np.cos(np.radians(deg_x)), np.sin(np.radians(deg_x))
    Rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1.0]])
    Rx = np.array([[1.0, 0, 0], [0, cx, -sx], [0, sx, cx]])
    return Rz @ Rx


def _solve(body, how, R):
    """Body at rotation R held at a, b, c; force F and torque T (body axes) at 'end'
    through Exudyn's rigid marker ('exudyn'), a bracket ('mount', 'frame') or split
    between the mount's position marker and the frame node ('split'); returns the modal
    coordinates, the world rotation of the marker loaded by the torque and that of the
    body frame."""
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    p0 = np.array([0.3, -0.2, 0.5])
    h = add_flexible_body(mbs, body, position=p0, rotation=R, gravity=(0, 0, 0),
                          damping=False)
    ground = mbs.AddObject(eii.ObjectGround())
    for n, p in HELD.items():
        mg = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground,
                                                  localPosition=list(p0 + R @ np.array(p))))
        mbs.AddObject(eii.SphericalJoint(markerNumbers=[mg, h.position_markers[n]]))
    if how == "exudyn":
        m = mt = h.markers["end"]
    elif how == "mount":
        m = mt = mount_bracket(mbs, h, body, "end", p0=p0, R0=R, v0=(0, 0, 0))
    elif how == "frame":
        m = mt = frame_bracket(mbs, h, body, "end", frame_marker=h.node_marker, p0=p0, R0=R,
                               v0=(0, 0, 0))
    else:  # "split": the force on the mount's position marker, the torque on the frame
        m, mt = h.position_markers["end"], h.node_marker
    mbs.AddLoad(eii.LoadForceVector(markerNumber=m, loadVector=list(R @ F)))
    mbs.AddLoad(eii.LoadTorqueVector(markerNumber=mt, loadVector=list(R @ T)))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.staticSolver.verboseMode = 0
    ss.solution.file.write = False
    ss.staticSolver.newton.relativeTolerance = 1e-12
    ss.staticSolver.newton.absoluteTolerance = 1e-12
    mbs.SolveStatic(ss)
    q = np.asarray(mbs.GetNodeOutput(h.modal_node, exu.OutputVariableType.Coordinates))
    Rm = np.asarray(mbs.GetMarkerOutput(mt, exu.OutputVariableType.RotationMatrix))
    Rf = np.asarray(mbs.GetNodeOutput(h.node, exu.OutputVariableType.RotationMatrix))
    return q, Rm.reshape(3, 3), Rf.reshape(3, 3)


@pytest.mark.parametrize("angles", [(0.0, 0.0), (90.0, 30.0)])
def test_mount_bracket_loads_and_turns_like_exudyns_rigid_marker(body, angles):
    R = _rotation(*angles)
    q_ref, R_ref, _ = _solve(body, "exudyn", R)
    q, Rb, Rf = _solve(body, "mount", R)
    scale = np.abs(q_ref).max()
    assert scale > 0
    # measured 1.1e-5 (terms of second order in the small rotations)
    np.testing.assert_allclose(q, q_ref, rtol=0, atol=1e-4 * scale)
    # the bracket turns with the mount: the body frame's rotation times the interface's
    # elastic rotation from the reduced model
    itf = {i.name: i for i in body.interfaces}["end"]
    theta = itf.shapes[3:, body.n_rigid:] @ q
    assert np.abs(theta).max() > 1e-7  # the torque does turn the mount
    skew = np.array([[0, -theta[2], theta[1]], [theta[2], 0, -theta[0]],
                     [-theta[1], theta[0], 0]])
    # measured 1.8e-5 of the elastic rotation, both
    np.testing.assert_allclose(Rb, Rf @ (np.eye(3) + skew), rtol=0,
                               atol=1e-3 * np.abs(theta).max())
    np.testing.assert_allclose(Rb, R_ref, rtol=0, atol=1e-3 * np.abs(theta).max())


def test_frame_bracket_passes_the_force_and_keeps_the_frame_axes(body):
    """A frame bracket loads the mount with the force and the body frame with the
    moment: the response equals the force on the mount's position marker plus the
    moment on the frame node; its axes stay the frame's."""
    R = _rotation(90.0, 30.0)
    q, Rb, Rf = _solve(body, "frame", R)
    q_ref, _, _ = _solve(body, "split", R)
    # measured 8.9e-6 (terms of second order in the small rotations)
    np.testing.assert_allclose(q, q_ref, rtol=0, atol=1e-4 * np.abs(q_ref).max())
    np.testing.assert_allclose(Rb, Rf, rtol=0, atol=1e-12)


def test_mount_bracket_needs_a_six_dof_interface(body):
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    h = add_flexible_body(mbs, body, gravity=(0, 0, 0))
    with pytest.raises(ValueError, match="'a' is no 6-DOF interface"):
        mount_bracket(mbs, h, body, "a", p0=(0, 0, 0), R0=np.eye(3), v0=(0, 0, 0))
