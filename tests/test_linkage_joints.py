"""Joints of the Exudyn linkage (:mod:`flexpipe.exu.linkage`) against the geometry of the
joint they stand for (closed form)."""

import numpy as np
import pytest

exu = pytest.importorskip("exudyn")
import exudyn.itemInterface as eii  # noqa: E402


def test_inline_joint_of_two_distances_keeps_the_point_on_the_line():
    """An arm on a spherical joint at its front pivot and the inline joint of
    :meth:`LinkageModel._inline` at its rear pivot, swinging under gravity from a tilted
    start: the rear pivot stays on the body's pivot line and the arm turns about that
    line only (geometry of the revolute pair it stands for)."""
    from exudyn.rigidBodyUtilities import GetRigidBodyNode

    from flexpipe.exu.linkage import LinkageModel
    from flexpipe.vehicle.suspension.model import BODY, Joint

    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    ground = mbs.AddObject(eii.ObjectGround())
    front, rear = np.array([0.2, 0.42, -0.27]), np.array([-0.2, 0.47, -0.265])
    axis = (rear - front) / np.linalg.norm(rear - front)
    cm = np.array([0.0, 0.7, -0.3])
    w0 = 3.0 * axis  # turning about the pivot line
    node = mbs.AddNode(GetRigidBodyNode(nodeType=exu.NodeType.RotationEulerParameters,
                                        position=list(cm), rotationMatrix=np.eye(3),
                                        velocity=list(np.cross(w0, cm - front)),
                                        angularVelocity=list(w0)))
    arm = mbs.AddObject(eii.ObjectRigidBody(mass=1.6, nodeNumber=node,
                                            inertia=[0.015, 0.02, 0.035, 0.0, 0.0, 0.0]))
    mbs.AddLoad(eii.LoadMassProportional(markerNumber=mbs.AddMarker(
        eii.MarkerBodyMass(bodyNumber=arm)), loadVector=[0.0, 0.0, -9.81]))

    class Host:  # what _inline needs of a LinkageModel
        body_links = []

        def __init__(self):
            self.mbs = mbs

        def mount_marker(self, name, rigid):
            assert not rigid  # the inline joint needs no frame on the body
            return mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground,
                                                        localPosition=list(rear)))

        def _marker(self, owner, point, rigid):
            obj, ref = owner
            return mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=obj,
                                                        localPosition=list(point - ref)))

    host = Host()
    mf = [mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground, localPosition=list(front))),
          mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=arm, localPosition=list(front - cm)))]
    mbs.AddObject(eii.ObjectJointSpherical(markerNumbers=mf))
    j = Joint("lower_arm_rear", "inline", BODY, "arm", rear, axis=axis, mount="m")
    LinkageModel._inline(host, j, BODY, (arm, cm))
    assert len(host.body_links) == 2  # both constraints load the body at its mount
    mp = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=arm, localPosition=list(rear - cm)))
    mbs.Assemble()
    s = exu.SimulationSettings()
    s.timeIntegration.numberOfSteps = 2000
    s.timeIntegration.endTime = 1.0
    s.timeIntegration.verboseMode = 0
    s.solution.file.write = False
    mbs.SolveDynamic(s)
    p = np.asarray(mbs.GetMarkerOutput(mp, exu.OutputVariableType.Position))
    off = (p - front) - ((p - front) @ axis) * axis
    assert np.linalg.norm(off) < 1e-8  # on the line
    w = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.AngularVelocity))
    assert np.linalg.norm(w - (w @ axis) * axis) < 1e-6 * np.linalg.norm(w)
    R = np.asarray(mbs.GetNodeOutput(node, exu.OutputVariableType.RotationMatrix)).reshape(3, 3)
    assert np.abs(R - np.eye(3)).max() > 0.1  # it did swing
