"""The full car with linkage suspensions: body (rigid or flexible) + :class:`LinkageModel`
+ wheel spin and the implicit tyre coupling of :class:`~flexpipe.exu.car.CarSystem`.

Every body-side mount of the suspension loads the body where it really sits: on the rigid
body through a marker at the mount point, on the flexible body through the mount's
interface.  Where a joint or a bushing needs the mount's frame, a 6-DOF interface gives
its rigid marker (the frame turns with the mount's elastic rotation, moments load the
body there); a 3-DOF interface gives a *bracket*: a tiny rigid body held at the mount by
a spherical joint on the interface's position marker, its axes locked to the body frame,
so forces load the body at the mount and moments load it as a whole.  The templates'
inline joints (no moment passes) sit on 3-DOF mounts with brackets
(``Suspension.mount_dofs``): on ``cars/sedan_linkage.toml`` (ISO C, 70 km/h, 3 s) that
moved the hub forces by at most 0.7 % (x), 1.3 % (y), 0.05 % (z) of their fluctuation
against 6-DOF mounts and cut the CPU time by 12 %; a bracket costs Exudyn about a tenth
of a joint on a rigid marker of the flexible body (``bench/bench_markers.py``).
"""

from __future__ import annotations

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
from exudyn.rigidBodyUtilities import GetRigidBodyNode

from flexpipe.errors import InputError
from flexpipe.exu.body import NODE_TYPE, add_flexible_body
from flexpipe.exu.car import CarState, CarSystem
from flexpipe.exu.linkage import LinkageModel
from flexpipe.tires.contact import _cross

OV = exu.OutputVariableType
#: mass and inertia of a mount bracket (numerical only: its motion is fully constrained,
#: no gravity acts on it)
BRACKET_MASS_KG = 1e-4
BRACKET_INERTIA_KGM2 = 1e-9


class LinkageCarSystem(CarSystem):
    """An assembled Exudyn car with linkage suspensions (``spec.suspension``)."""

    def __init__(self, spec):  # noqa: D107 - see class docstring
        p0, R0, v0, g = self._start(spec)
        mbs = self.mbs
        self.modal_node = None
        cache = {}
        if spec.chassis == "flexible":
            h = add_flexible_body(mbs, spec.flexbody, position=p0, rotation=R0, velocity=v0,
                                  angular_velocity=[0.0, 0.0, 0.0], gravity=g,
                                  n_modes=spec.n_modes, name="body",
                                  prewarp=spec.modal_prewarp)
            self.body_node, self.body_obj, self.modal_node = h.node, h.object, h.modal_node
            if spec.modal_q0 is not None:
                mbs.SetNodeParameter(h.modal_node, "initialCoordinates",
                                     [float(v) for v in spec.modal_q0])

            self.frame_marker = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=self.body_node))
            itfs = {i.name: i for i in spec.flexbody.interfaces}
            fb = spec.flexbody

            def bracket(name):
                """Rigid marker at a 3-DOF mount: a bracket body whose point is held at
                the mount (spherical joint on the body's position marker) and whose axes
                are the body frame's (rotation-only joint to the frame node)."""
                itf = itfs[name]
                p = np.asarray(itf.point, float)
                if spec.modal_q0 is not None:  # start where the deflected mount is
                    sel = slice(fb.n_rigid, fb.n_rigid + len(spec.modal_q0))
                    p = p + itf.shapes[:3, sel] @ np.asarray(spec.modal_q0, float)
                node = mbs.AddNode(GetRigidBodyNode(
                    nodeType=NODE_TYPE, position=list(p0 + R0 @ p), velocity=list(v0),
                    rotationMatrix=R0, angularVelocity=[0.0, 0.0, 0.0]))
                obj = mbs.AddObject(eii.ObjectRigidBody(
                    mass=BRACKET_MASS_KG, nodeNumber=node,
                    inertia=[BRACKET_INERTIA_KGM2] * 3 + [0.0] * 3))
                mp = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=obj,
                                                          localPosition=[0.0, 0.0, 0.0]))
                mbs.AddObject(eii.ObjectJointSpherical(
                    markerNumbers=[h.position_markers[name], mp],
                    visualization=eii.VObjectJointSpherical(show=False)))
                mr = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=obj,
                                                       localPosition=[0.0, 0.0, 0.0]))
                mbs.AddObject(eii.GenericJoint(
                    markerNumbers=[self.frame_marker, mr], constrainedAxes=[0, 0, 0, 1, 1, 1],
                    visualization=eii.VGenericJoint(show=False)))
                return mr

            def mount_marker(name, rigid):
                table = h.markers if rigid else h.position_markers
                if rigid and name not in table and name in h.position_markers:
                    key = (name, "bracket")
                    if key not in cache:
                        cache[key] = bracket(name)
                    return cache[key]
                if name not in table:
                    kind = "6-DOF (rigid)" if rigid else "position"
                    raise InputError(f"the flexible body has no {kind} interface for the "
                                     f"suspension mount '{name}'; reduce the body with this "
                                     "mount (dofs = 6 where a joint or bushing needs the "
                                     "mount's frame)", key=name)
                return table[name]
        else:
            J = spec.inertia_origin
            self.body_node = mbs.AddNode(GetRigidBodyNode(
                nodeType=NODE_TYPE, position=list(p0), velocity=list(v0), rotationMatrix=R0,
                angularVelocity=[0.0, 0.0, 0.0]))
            self.body_obj = mbs.AddObject(eii.ObjectRigidBody(
                mass=spec.mass, nodeNumber=self.body_node,
                inertia=[J[0, 0], J[1, 1], J[2, 2], J[1, 2], J[0, 2], J[0, 1]],
                centerOfMass=list(spec.center_of_mass)))
            mb = mbs.AddMarker(eii.MarkerBodyMass(bodyNumber=self.body_obj))
            mbs.AddLoad(eii.LoadMassProportional(markerNumber=mb, loadVector=list(g)))
            points = spec.suspension.mounts()

            def mount_marker(name, rigid):
                key = (name, rigid)
                if key not in cache:
                    loc = [float(v) for v in points[name]]
                    item = (eii.MarkerBodyRigid if rigid else eii.MarkerBodyPosition)(
                        bodyNumber=self.body_obj, localPosition=loc)
                    cache[key] = mbs.AddMarker(item)
                return cache[key]
        if spec.chassis != "flexible":
            self.frame_marker = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=self.body_node))
        self.linkage = lk = LinkageModel(mbs, spec.suspension, mount_marker=mount_marker,
                                         p0=p0, R0=R0, v0=v0, gravity=g)
        self.wheel_node = list(lk.knuckle_node)
        self.spin_node, self.load_spin, self.tire_elem = [], [], []
        for i in range(4):
            self._add_wheel(self.wheel_node[i], spec, i)
        lk.add_mount_sensors(self.body_node)
        order = spec.suspension.corners()
        self.design_wheel = np.array([order[c].wheel_center for c in ("fl", "fr", "rl", "rr")])
        self._finish(spec)
        self.joint = []

    def state(self, t: float) -> CarState:
        """Current state; ``jounce`` is the wheel-centre travel along the body z axis."""
        g = self.mbs.GetNodeOutput
        bn = self.body_node
        body_p = np.asarray(g(bn, OV.Position))
        body_R = np.asarray(g(bn, OV.RotationMatrix)).reshape(3, 3)
        body_v = np.asarray(g(bn, OV.Velocity))
        body_w = np.asarray(g(bn, OV.AngularVelocity))
        wp, wv, wR, ww, spin, wq, wqt = self._wheel_state()
        local = (wp - body_p) @ body_R
        jounce = local[:, 2] - self.design_wheel[:, 2]
        vrel = (wv - body_v - _cross(np.broadcast_to(body_w, wp.shape), wp - body_p)) @ body_R
        return CarState(t=t, body_p=body_p, body_R=body_R, body_v=body_v, body_w=body_w,
                        wheel_p=wp, wheel_v=wv, wheel_R=wR, wheel_w=ww, spin_rate=spin,
                        jounce=jounce, jounce_rate=vrel[:, 2], joint_force=None,
                        mount_R=np.repeat(body_R[None], 4, axis=0), wheel_q=wq, wheel_qt=wqt)

    _h = 2e-3  # step length, set by run()

    def run(self, step, *, t_end: float, h: float, **kw):  # noqa: D102 - as CarSystem.run
        self._h = float(h)
        return super().run(step, t_end=t_end, h=h, **kw)

    def apply(self, loads, mount_R, st) -> None:
        """Tyre elements, spin torques, rack travel; linearize the springs."""
        self._apply_wheels(loads, st)
        if loads.rack_travel is not None:
            self.linkage.set_rack_travel(loads.rack_travel)
        self.linkage.update_forces(self._h)

    def joint_forces(self):  # the hub force comes from hub_forces for linkage cars
        return np.zeros((4, 3))
