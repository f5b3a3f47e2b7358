"""Exudyn multibody of the linkage suspension (:mod:`flexpipe.vehicle.suspension`).

Each corner's parts are rigid bodies (the knuckle carries the wheel; its node sits at the
wheel centre so that the tyre coupling of :mod:`flexpipe.exu.car` applies unchanged).
Joints become Exudyn constraints (``spherical`` -> ``ObjectJointSpherical``; ``inline``,
``revolute`` and ``universal`` -> ``GenericJoint`` in a frame whose axes are the joint's),
massless two-force links ``ObjectConnectorDistance`` (``ObjectConnectorSpringDamper`` when
compliant), bushings ``ObjectConnectorRigidBodySpringDamper`` (6-DOF in the bushing frame,
linear, or with its nonlinear tables as a symbolic law of :mod:`flexpipe.exu.force_laws`).
Springs, dampers and stops act between their real seats through one
``ObjectConnectorSpringDamper`` each whose force law (table, dual-rate damper, stop
contact) is an Exudyn symbolic user function (:mod:`flexpipe.exu.force_laws`), evaluated
in C++ at every Newton iteration: they are solved implicitly, nothing of them runs in
Python during the step.  The steering rack is a rigid body sliding along the body y axis
in its two housing mounts, held by the column stiffness at the travel the driver
commands; an anti-roll bar is two
arms turning in their body bushings, joined by the torsion bar and carried by drop links.

Body side: ``mount_marker(name, rigid)`` returns the body's marker at a mount (a
position marker, or a rigid one where a joint or bushing needs the mount's frame).
"""

from __future__ import annotations

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
from exudyn.rigidBodyUtilities import GetRigidBodyNode

from flexpipe.exu import mount_sensors
from flexpipe.exu.body import NODE_TYPE
from flexpipe.exu.force_laws import bushing_law, seat_groups, symbolic_law
from flexpipe.vehicle.suspension.model import ARB_ARM_MASS, BODY, RACK, RACK_MASS

OV = exu.OutputVariableType
CORNERS = ("fl", "fr", "rl", "rr")
#: mass given to a part the car file leaves massless (kg)
MIN_PART_MASS = 0.2
#: stiffness of a steering column given as rigid (N/m at the rack)
RIGID_RACK = 1e8
_I3 = np.eye(3)  # a joint frame that is its marker's frame


def _frame(z_axis, x_hint=(1.0, 0.0, 0.0)) -> np.ndarray:
    """Rotation matrix whose third column is ``z_axis``."""
    z = np.asarray(z_axis, float)
    z = z / np.linalg.norm(z)
    x = np.asarray(x_hint, float)
    if abs(x @ z) > 0.9:
        x = np.array([0.0, 1.0, 0.0]) if abs(z[1]) < 0.9 else np.array([0.0, 0.0, 1.0])
    x = x - (x @ z) * z
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def _inertia6(J):
    return [J[0, 0], J[1, 1], J[2, 2], J[1, 2], J[0, 2], J[0, 1]]


def add_rigid_part(mbs, mass, J_cm, cm, ref, *, p0, R0, v0, gravity):
    """A rigid body (with its weight) whose node sits at ``ref`` (body coordinates at the
    design position, the body frame at ``p0, R0`` moving at ``v0``); centre of mass ``cm``
    and inertia ``J_cm`` about it.  Returns ``(node, object)``."""
    ref = np.asarray(ref, float)
    d = np.asarray(cm, float) - ref
    J = np.asarray(J_cm, float) + mass * (d @ d * np.eye(3) - np.outer(d, d))
    node = mbs.AddNode(GetRigidBodyNode(
        nodeType=NODE_TYPE, position=list(np.asarray(p0) + np.asarray(R0) @ ref),
        velocity=list(v0), rotationMatrix=np.asarray(R0), angularVelocity=[0.0, 0.0, 0.0]))
    obj = mbs.AddObject(eii.ObjectRigidBody(mass=float(mass), nodeNumber=node,
                                            inertia=_inertia6(J), centerOfMass=list(d)))
    m = mbs.AddMarker(eii.MarkerBodyMass(bodyNumber=obj))
    mbs.AddLoad(eii.LoadMassProportional(markerNumber=m, loadVector=list(gravity)))
    return node, obj


class LinkageModel:
    """The suspension of a car added to an Exudyn system (see module docstring).

    Parameters
    ----------
    mbs : exudyn MainSystem
    suspension : Suspension
        With spring free lengths set for the design position and the wheels (rim and
        tyre) in the knuckles (:func:`flexpipe.vehicle.suspension.statics.with_wheels`).
    mount_marker : callable
        ``mount_marker(name, rigid) -> MarkerIndex`` on the car body.
    p0, R0, v0 : arrays
        Pose of the body frame and the initial velocity (global).
    gravity : array (3,)
    """

    def __init__(self, mbs, suspension, *, mount_marker, p0, R0, v0, gravity):
        self.mbs = mbs
        self.p0, self.R0 = np.asarray(p0, float), np.asarray(R0, float)
        self.v0 = np.asarray(v0, float)
        self.g = np.asarray(gravity, float)
        self.mount_marker = mount_marker
        self.susp = suspension
        #: kinematic mode (Adams/Car): every bushing replaced by its joint, links rigid
        self.kinematic = getattr(suspension, "mode", "compliant") == "kinematic"
        self.corners = suspension.corners()
        self.knuckle_node, self.part_nodes = [], []  # part_nodes: per
        # corner (object, mass, centre of mass in the part's frame)
        self._laws = []  # the force elements' symbolic laws (flexpipe.exu.force_laws)
        #: connectors with a symbolic law, added after every other object
        #: (:meth:`add_law_connectors`): (item, body_links slot, bushings slot or None)
        self._deferred = []
        self.to_other = []  # (corner, connector, sign): links from a corner to rack or bar
        self._pos_markers = {}
        #: body-side connections: (mount, object, kind, body is marker 0, joint frame A)
        self.body_links = []
        #: bushings at body mounts: (mount, connector), deflection channels
        self.bushings = []
        self.rack = None
        for i, cn in enumerate(CORNERS):
            self._corner(i, self.corners[cn])
        for axle in suspension.axles.values():
            if axle.anti_roll_bar is not None:
                self._anti_roll_bar(axle)

    # ------------------------------------------------------------------ helpers
    def _body(self, mass, J_cm, cm, ref):
        """Rigid body with node at ``ref`` (body coordinates at design), cm and inertia."""
        return add_rigid_part(self.mbs, mass, J_cm, cm, ref, p0=self.p0, R0=self.R0,
                              v0=self.v0, gravity=self.g)

    def _marker(self, owner, point, rigid, frame=None):
        """Marker at ``point`` (body coordinates) on ``owner`` = (obj, ref) or 'body'; on a
        part, a rigid one turned by ``frame`` (a joint's or bushing's frame) when given
        (body-side markers get theirs from :meth:`_framed`)."""
        if owner == BODY:
            return self._body_marker(point, rigid)
        obj, ref = owner
        local = list(np.asarray(point, float) - ref)
        if frame is not None:
            return self.mbs.AddMarker(eii.MarkerBodyRigid(
                bodyNumber=obj, localHT=exu.HT(rotation=np.asarray(frame), translation=local)))
        if rigid:
            return self.mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=obj, localPosition=local))
        return self.mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=obj, localPosition=local))

    def _framed(self, m, A):
        """Rigid marker at marker ``m``'s point whose frame is ``m``'s turned by ``A``: a
        joint's or bushing's frame given to its markers, as Exudyn asks since 1.12.244
        (instead of the connector's ``rotationMarker0/1``)."""
        d = self.mbs.GetMarker(m)
        if d["markerType"] != "BodyRigid":
            raise TypeError(f"marker {m} is a {d['markerType']} marker; a body's rigid marker "
                            "is needed for a joint frame")
        HT = np.asarray(d["localHT"], dtype=float)
        return self.mbs.AddMarker(eii.MarkerBodyRigid(
            bodyNumber=d["bodyNumber"], localHT=exu.HT(rotation=HT[:3, :3] @ np.asarray(A),
                                                       translation=HT[:3, 3])))

    def _body_marker(self, point, rigid, mount=None):
        return self.mount_marker(mount, rigid)

    # ------------------------------------------------------------------ corner
    def _corner(self, i, c):
        mbs = self.mbs
        owners = {}
        nodes = []
        for p in c.parts:
            mass, J = p.mass, p.inertia
            ref = np.asarray(c.wheel_center if p.name == c.knuckle else p.cm, float)
            if mass <= 0:
                mass = MIN_PART_MASS
            J = np.array(J, float)
            J += np.eye(3) * max(1e-4, 1e-3 * mass) * (np.trace(J) <= 0)
            node, obj = self._body(mass, J, p.cm, ref)
            owners[p.name] = (obj, ref)
            nodes.append((obj, mass, [float(v) for v in np.asarray(p.cm, float) - ref]))
            if p.name == c.knuckle:
                self.knuckle_node.append(node)
                self.knuckle_obj = getattr(self, "knuckle_obj", []) + [obj]
        self.part_nodes.append(nodes)
        self.owners = getattr(self, "owners", {})
        self.owners[CORNERS[i]] = owners

        def own(name):
            return BODY if name == BODY else owners[name]

        for j in c.joints:
            self._joint(j, own(j.a), own(j.b))
        for lk in c.links:
            b = own(lk.b) if lk.b != RACK else self._rack_owner()
            ma = self._marker(own(lk.a), lk.point_a, False)
            mb = (self.mount_marker(lk.mount, False) if lk.b == BODY
                  else self._marker(b, lk.point_b, False))
            if lk.axial_stiffness is None or self.kinematic:
                co = mbs.AddObject(eii.ObjectConnectorDistance(
                    markerNumbers=[mb, ma], distance=lk.length,
                    visualization=eii.VObjectConnectorDistance(show=False)))
            else:
                co = mbs.AddObject(eii.ObjectConnectorSpringDamper(
                    markerNumbers=[mb, ma], referenceLength=lk.length,
                    stiffness=float(lk.axial_stiffness),
                    visualization=eii.VObjectConnectorSpringDamper(show=False)))
            if lk.b == RACK:
                self.to_other.append((i, co, mb, ma))
            elif lk.b == BODY:
                kind = "distance" if lk.axial_stiffness is None or self.kinematic else "vector"
                self.body_links.append((lk.mount, co, kind, (mb, ma), None))
        for group in seat_groups(c.forces):  # one connector per pair of seats
            f = group[0]
            mb = self.mount_marker(f.mount, False)
            ma = self._marker(own(f.part), f.point, False)
            law = symbolic_law(mbs, *group)  # evaluated by Exudyn in every Newton iteration
            self._laws.append(law)  # keeps the expression tree alive
            self._defer(eii.ObjectConnectorSpringDamper(
                markerNumbers=[mb, ma], referenceLength=f.design_length, stiffness=0.0,
                damping=0.0, force=0.0, springForceUserFunction=law,
                visualization=eii.VObjectConnectorSpringDamper(show=False)),
                (f.mount, None, "vector", (mb, ma), None))

    def _joint(self, j, a, b):
        """Joint ``j`` between owners ``a`` and ``b`` (see module docstring)."""
        mbs = self.mbs
        if j.bushing is not None and not self.kinematic:
            self._body_bushing(j.mount, j.bushing, a if b == BODY else b, j.point)
            return
        if j.kind == "spherical":
            m0 = (self.mount_marker(j.mount, False) if a == BODY
                  else self._marker(a, j.point, False))
            m1 = (self.mount_marker(j.mount, False) if b == BODY
                  else self._marker(b, j.point, False))
            co = mbs.AddObject(eii.ObjectJointSpherical(
                markerNumbers=[m0, m1], visualization=eii.VObjectJointSpherical(show=False)))
            if BODY in (a, b):
                sign = 1.0 if a == BODY else -1.0
                self.body_links.append((j.mount, co, "vector" if sign > 0 else "vector-",
                                        (m0, m1), None))
            return
        if j.kind == "inline":  # the point of b stays on the line along axis fixed in a
            A, axes = _frame(j.axis), [1, 1, 0, 0, 0, 0]
        elif j.kind == "revolute":
            A, axes = _frame(j.axis), [1, 1, 1, 1, 1, 0]
        else:  # universal: axis (in a) stays perpendicular to axis_b (in b)
            ey, ez = np.asarray(j.axis, float), np.asarray(j.axis_b, float)
            ex = np.cross(ey, ez)
            ex /= np.linalg.norm(ex)
            A, axes = np.column_stack([ex, ey, np.cross(ex, ey)]), [1, 1, 1, 1, 0, 0]
        m0, m1 = (self._framed(self.mount_marker(j.mount, True), A) if o == BODY
                  else self._marker(o, j.point, True, frame=A) for o in (a, b))
        co = mbs.AddObject(eii.GenericJoint(markerNumbers=[m0, m1], constrainedAxes=axes,
                                            visualization=eii.VGenericJoint(show=False)))
        if BODY in (a, b):
            self.body_links.append((j.mount, co, "local" if a == BODY else "local-",
                                    (m0, m1), _I3))

    def _body_bushing(self, mount, bu, owner, point) -> None:
        """Bushing ``bu`` from the body's ``mount`` (marker 0) to ``owner`` at ``point``,
        in the bushing's frame; its force counts as the mount's (``body_links``)."""
        mbs = self.mbs
        m0 = self._framed(self.mount_marker(mount, True), bu.frame)
        m1 = self._marker(owner, point, True, frame=bu.frame)
        kw = {}
        if bu.tables:  # nonlinear directions: the bushing's law inside Exudyn
            law = bushing_law(mbs, bu)
            self._laws.append(law)
            kw["springForceTorqueUserFunction"] = law
        item = eii.ObjectConnectorRigidBodySpringDamper(
            markerNumbers=[m0, m1], stiffness=np.diag(bu.stiffness),
            damping=np.diag(bu.damping),
            visualization=eii.VObjectConnectorRigidBodySpringDamper(show=False), **kw)
        link = (mount, None, "local", (m0, m1), _I3)
        if kw:
            self._defer(item, link, bushing=mount)
            return
        co = mbs.AddObject(item)
        self.body_links.append((mount, co, *link[2:]))
        self.bushings.append((mount, co))

    def _defer(self, item, link, *, bushing=None) -> None:
        """Queue connector ``item`` (its force law a symbolic user function) for
        :meth:`add_law_connectors`, keeping its places in ``body_links`` (entry ``link``,
        object index to come) and, for a ``bushing`` at that mount, in ``bushings``."""
        self.body_links.append(link)
        slot_b = None
        if bushing is not None:
            self.bushings.append((bushing, None))
            slot_b = len(self.bushings) - 1
        self._deferred.append((item, len(self.body_links) - 1, slot_b))

    def add_law_connectors(self) -> None:
        """Add the queued connectors whose force law is a symbolic user function; call
        it after every other object of the system.

        Exudyn evaluates such connectors serially after the other objects of a
        multi-threaded residual, but its parallel loop takes the first objects of the
        full list, not those without a user function (``CSystem::ComputeSystemODE2RHS``,
        Exudyn 1.13): an object with a law placed among them is counted twice and the
        last objects without one not at all.  Placed last, they are evaluated once,
        serially, and a two-thread run equals a one-thread one
        (``tests/test_threads.py``).
        """
        for item, slot, slot_b in self._deferred:
            co = self.mbs.AddObject(item)
            mount, _, *rest = self.body_links[slot]
            self.body_links[slot] = (mount, co, *rest)
            if slot_b is not None:
                self.bushings[slot_b] = (self.bushings[slot_b][0], co)
        self._deferred = []

    def bushing_deflections(self) -> dict:
        """Per body-mount bushing: displacement (m) and rotation (rad) of its outer end
        relative to the mount, in the bushing's frame: ``{mount: (6,)}`` (read now)."""
        go = self.mbs.GetObjectOutput
        return {m: np.r_[go(co, OV.DisplacementLocal), go(co, OV.Rotation)]
                for m, co in self.bushings}

    def bushing_history(self, t: np.ndarray):
        """:meth:`bushing_deflections` at the times ``t`` from the sensors
        (:func:`flexpipe.exu.mount_sensors.bushing_history`)."""
        return mount_sensors.bushing_history(self, t)

    # ------------------------------------------------------------------ mounted bodies
    def add_body_mounts(self, b, node_obj) -> None:
        """The bushings of ``b`` (a :class:`flexpipe.vehicle.mounted.MountedBody`: the
        powertrain or a subframe; ``node_obj`` its rigid body) at its body mounts; their
        forces count as those mounts' (``mount_forces``, the sensors)."""
        ref = np.asarray(b.center_of_mass, float)
        for name, p, bu in zip(b.mounts, b.points, b.bushings, strict=True):
            self._body_bushing(name, bu, (node_obj[1], ref), p)

    def add_powertrain(self, pt):
        """The powertrain as a rigid body on its bushings at the body mounts; returns the
        rigid marker at its centre of mass (for the drive's reaction couple)."""
        ref = np.asarray(pt.center_of_mass, float)
        node, obj = self._body(pt.mass, pt.inertia, ref, ref)
        self.add_body_mounts(pt, (node, obj))
        return self.mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=node))

    # ------------------------------------------------------------------ rack, bars
    def _rack_owner(self):
        if self.rack is not None:
            return self.rack["owner"]
        mbs = self.mbs
        rk = self.susp.rack
        names = sorted(rk.mounts)
        pts = np.array([rk.mounts[n] for n in names])
        cm = pts.mean(axis=0)
        J = np.diag([0.1, 1e-3, 0.1])
        node, obj = self._body(RACK_MASS, J, cm, cm)
        owner = (obj, cm)
        left = names[int(np.argmax(pts[:, 1]))]
        right = names[int(np.argmin(pts[:, 1]))]
        for name, axes in ((left, [1, 0, 1, 0, 1, 0]), (right, [1, 0, 1, 0, 0, 0])):
            m0 = self.mount_marker(name, True)
            m1 = self._marker(owner, rk.mounts[name], True)
            co = mbs.AddObject(eii.GenericJoint(markerNumbers=[m0, m1], constrainedAxes=axes,
                                                visualization=eii.VGenericJoint(show=False)))
            self.body_links.append((name, co, "local", (m0, m1), np.eye(3)))
        # column: a spring along the rack from the left mount to a rack point d to the right
        d = 0.2
        pl = np.asarray(rk.mounts[left], float)
        mb = self.mount_marker(left, False)
        mr = self._marker(owner, pl - np.array([0.0, d, 0.0]), False)
        k = rk.axial_stiffness or RIGID_RACK
        col = mbs.AddObject(eii.ObjectConnectorSpringDamper(
            markerNumbers=[mb, mr], referenceLength=d, stiffness=float(k),
            damping=float(2e-3 * k), visualization=eii.VObjectConnectorSpringDamper(show=False)))
        self.body_links.append((left, col, "vector", (mb, mr), None))
        self.rack = {"owner": owner, "node": node, "column": col, "d": d, "rack": rk}
        return owner

    def set_rack_travel(self, s: float) -> None:
        """Rack travel commanded through the column (m, toward +y = left)."""
        if self.rack is not None:
            self.mbs.SetObjectParameter(self.rack["column"], "referenceLength",
                                        float(self.rack["d"] - s))

    def _anti_roll_bar(self, axle):
        mbs = self.mbs
        arb = axle.anti_roll_bar
        mounts = dict(arb.mounts)
        arms = []
        for corner in (axle.left, axle.right):
            S = np.diag([1.0, float(corner.side), 1.0])
            bush, end, low = S @ arb.bushing, S @ arb.arm_end, S @ arb.drop_link_lower
            name = min(mounts, key=lambda n, b=bush: np.linalg.norm(np.asarray(mounts[n]) - b))
            cm = 0.5 * (bush + end)
            node, obj = self._body(ARB_ARM_MASS, np.eye(3) * 1e-3, cm, cm)
            owner = (obj, cm)
            A = _frame((0.0, 1.0, 0.0))
            m0 = self._framed(self.mount_marker(name, True), A)
            m1 = self._marker(owner, bush, True, frame=A)
            co = mbs.AddObject(eii.GenericJoint(markerNumbers=[m0, m1],
                                                constrainedAxes=[1, 1, 1, 1, 1, 0],
                                                visualization=eii.VGenericJoint(show=False)))
            self.body_links.append((name, co, "local", (m0, m1), _I3))
            i = CORNERS.index(corner.corner)
            part = self.owners[corner.corner][arb.part]
            ma = self._marker(part, low, False)
            mb = self._marker(owner, end, False)
            link = mbs.AddObject(eii.ObjectConnectorDistance(
                markerNumbers=[mb, ma], distance=float(np.linalg.norm(end - low)),
                visualization=eii.VObjectConnectorDistance(show=False)))
            self.to_other.append((i, link, mb, ma))
            arms.append((owner, bush))
        A = _frame((0.0, 1.0, 0.0))
        mL = self._marker(arms[0][0], arms[0][1], True, frame=A)
        mR = self._marker(arms[1][0], arms[1][1], True, frame=A)
        mbs.AddObject(eii.ObjectConnectorTorsionalSpringDamper(
            markerNumbers=[mL, mR], stiffness=float(arb.torsion_rate),
            damping=float(1e-3 * arb.torsion_rate),
            visualization=eii.VObjectConnectorTorsionalSpringDamper(show=False)))

    # ------------------------------------------------------------------ per step
    def mount_forces(self) -> dict:
        """Force (global, N) the suspension applies to the body at each mount, summed over
        the joints, links, bushings and force elements there.  Exudyn reports every
        connector's force as the force on its marker 0 (global, or in marker 0's joint
        frame for joints and bushings)."""
        mbs = self.mbs
        go, gm = mbs.GetObjectOutput, mbs.GetMarkerOutput
        out = {}
        for mount, co, kind, (m0, m1), A in self.body_links:
            if kind == "distance":
                d = np.asarray(gm(m1, OV.Position)) - np.asarray(gm(m0, OV.Position))
                F = float(go(co, OV.Force)) * d / np.linalg.norm(d)
            elif kind.startswith("vector"):
                F = np.asarray(go(co, OV.Force), dtype=float)
            else:
                R0 = np.asarray(gm(m0, OV.RotationMatrix), dtype=float).reshape(3, 3)
                F = R0 @ A @ np.asarray(go(co, OV.ForceLocal), dtype=float)
            if kind.endswith("-"):  # the body is marker 1: the opposite force
                F = -F
            out[mount] = out.get(mount, 0.0) + F
        return out

    def add_mount_sensors(self, body_node) -> None:
        """Exudyn sensors for the per-mount forces (:mod:`flexpipe.exu.mount_sensors`),
        after :meth:`add_law_connectors` (the sensors need every connector's index)."""
        if self._deferred:
            raise RuntimeError("add_law_connectors() must come before add_mount_sensors()")
        mount_sensors.add(self, body_node)

    def mount_force_history(self, t: np.ndarray):
        """Per-mount forces (body axes, N) at the times ``t`` from the sensors
        (:func:`flexpipe.exu.mount_sensors.history`)."""
        return mount_sensors.history(self, t)

    def hub_force_history(self, t: np.ndarray, F_tire: np.ndarray):
        """The corners' hub forces (n, 4, 3, global, N) at the times ``t`` from the sensors
        and the tyre forces applied then (:func:`flexpipe.exu.mount_sensors.hub_history`)."""
        return mount_sensors.hub_history(self, t, F_tire)

    def hub_forces(self, F_tire: np.ndarray) -> np.ndarray:
        """Force (4, 3, global) each corner applies to the body through its own mounts:
        tyre force + weight - m a of its parts + the forces of the links to rack and bar."""
        gb = self.mbs.GetObjectOutputBody
        out = np.array(F_tire, dtype=float)
        for i, parts in enumerate(self.part_nodes):
            for obj, m, cm in parts:  # the acceleration of each part's centre of mass
                out[i] += m * (self.g - np.asarray(gb(obj, OV.Acceleration, cm)))
        return out + self.link_forces()

    def corner_momenta(self) -> np.ndarray:
        """(4, 3, global): the sum of ``m v`` over each corner's parts, at their centres
        of mass."""
        gb = self.mbs.GetObjectOutputBody
        out = np.zeros((len(self.part_nodes), 3))
        for i, parts in enumerate(self.part_nodes):
            for obj, m, cm in parts:
                out[i] += m * np.asarray(gb(obj, OV.Velocity, cm))
        return out

    def links_to_other(self) -> list:
        """Per link from a corner to the rack or an anti-roll bar, at the current state:
        (corner, unit vector (global) of the link's pull on the corner per unit of
        tension, its tension (N), the global index of its constraint's multiplier, or
        None for a spring link)."""
        gm = self.mbs.GetMarkerOutput
        out = []
        for i, co, mb, ma in self.to_other:
            d = np.asarray(gm(ma, OV.Position)) - np.asarray(gm(mb, OV.Position))
            ae = list(self.mbs.systemData.GetObjectLTGAE(co))
            out.append((i, -d / np.linalg.norm(d), float(self.mbs.GetObjectOutput(co, OV.Force)),
                        int(ae[0]) if ae else None))
        return out

    def link_forces(self) -> np.ndarray:
        """(4, 3, global): the forces of the links to the rack and the anti-roll bars on
        each corner, at the current state."""
        out = np.zeros((len(self.part_nodes), 3))
        for i, pull, F, _ in self.links_to_other():
            out[i] += F * pull  # tension pulls the corner's end back
        return out
