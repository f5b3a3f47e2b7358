"""Exudyn side of the full car: bodies, joints, loads and the time-step loop.

Model (per corner ``fl, fr, rl, rr``)
-------------------------------------
* Chassis: ``ObjectFFRFreducedOrder`` (flexible/full body, via
  :func:`flexpipe.exu.body.add_flexible_body`, started in its static deflection on the
  springs) or ``ObjectRigidBody`` with the same mass properties; a 6-DOF marker at each
  suspension hardpoint.
* Wheel carrier (upright + wheel as one rigid body of the unsprung mass).  Prismatic
  suspension travel along the chassis z axis: a ``GenericJoint`` holds the carrier's
  x, y translation at the hardpoint marker (forces into the flexible structure there),
  a second ``GenericJoint`` holds its orientation relative to the chassis frame (the
  moments take the path of a real suspension's lower arms into the body as a whole, not
  through the strut top).  Steered corners leave the rotation about z free and hold it
  with a torsional spring-damper (the steering compliance) whose offset is the angle.
* Wheel spin: one rotational coordinate (``Node1D`` + ``ObjectRotationalMass1D``) per
  wheel carrying the spin inertia.
* Tyre: the whole contact force is a linear ``ObjectGenericODE2`` on the carrier node and
  the spin coordinate whose damping, stiffness and force are set every step from the
  tyre model's linearization (:mod:`flexpipe.vehicle.tire_coupling`), so the implicit
  integrator balances it at the end of the step; the tyre's own moments (Mx, My, Mz)
  too (their part about the spin axis on the spin coordinate, the rest on the carrier);
  the drive and brake torques are loads held over the step (the driver samples them
  every 10 ms).
* Time integration: Exudyn's generalized-alpha with the spectral radius
  :data:`flexpipe.vehicle.simulation.SPECTRAL_RADIUS` (0.7; ``run``; figures there).
  With the code of an earlier round 0.5 was better at the then 2 ms default (rigid
  linkage car, ISO C 70 km/h, front-left hub force against h/8, RMS in % of the
  fluctuation, x / y: 4.2 / 6.5 at 0.7, 3.7 / 4.5 at 0.5, 4.3 / 5.3 at 0.3); at 1 ms
  (the default until 2026-12-04; now 1.25 ms) 0.7 is the better one (figures at
  ``SPECTRAL_RADIUS``, measured on the 30 Hz body, 2026-12-01); at 2 ms the two have not
  been compared on the present code.
  The flexible body's modal masses and damping are pre-warped to the step and this
  spectral radius (``CarBuild.modal_prewarp``, :mod:`flexpipe.exu.prewarp`): flexible
  linkage car, ISO C 70 km/h, worst corner x / y 26.6 / 12.6 % plain, 8.3 / 6.7 %
  pre-warped (0.3 / 0.7: 9.0 / 7.4, 8.5 / 7.9 %), at Newton tolerance 1e-3.
* Suspension: spring, damper and stops are one implicit ``ObjectConnectorSpringDamper``
  per corner, linearized every step with secant slopes (the anti-roll bars come as loads
  at the travel predicted for the end of the step).  A ``PreStepUserFunction`` reads the
  state once per step and sets all of this.

:class:`flexpipe.exu.linkage_car.LinkageCarSystem` builds the car with linkage
suspensions instead of the prismatic corners and reuses the tyre coupling and time loop.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
from exudyn.rigidBodyUtilities import GetRigidBodyNode

from flexpipe.exu import output_sensors, timeloop
from flexpipe.exu._node_state import NodeReader
from flexpipe.exu._tire_element import element, element_numpy
from flexpipe.exu.body import NODE_TYPE, add_flexible_body
from flexpipe.tires._fast import enabled as jit_enabled
from flexpipe.tires.contact import _cross

OV = exu.OutputVariableType


@dataclass
class CarState:
    """State read from Exudyn at the start of a step (global ISO 8855 frame)."""

    t: float
    body_p: np.ndarray
    body_R: np.ndarray
    body_v: np.ndarray
    body_w: np.ndarray
    wheel_p: np.ndarray
    wheel_v: np.ndarray
    wheel_R: np.ndarray
    wheel_w: np.ndarray
    spin_rate: np.ndarray
    jounce: np.ndarray
    jounce_rate: np.ndarray
    joint_force: np.ndarray | None  # (4, 3) joint force in the hardpoint frame, if read
    mount_R: np.ndarray  # (4, 3, 3) hardpoint marker frames
    wheel_q: np.ndarray = None  # (4, 7) carrier node coordinates (position, EP), displacement
    wheel_qt: np.ndarray = None  # (4, 7) their time derivatives


@dataclass
class CarLoads:
    """Loads for one step."""

    suspension: np.ndarray  # (4,) explicit part, along the chassis z axis at the hardpoint
    damper_c: np.ndarray  # (4,) damping coefficient of the implicit damper for the step
    tire: object  # flexpipe.vehicle.tire_coupling.TireStep: contact force, linearized
    spin_torque: np.ndarray  # (4,) about the spin axis, on the wheel spin coordinate
    steer: np.ndarray  # (4,) steering angle offsets (rad), used on steered corners
    suspension_k: np.ndarray = None  # (4,) tangent stiffness of the suspension connector
    suspension_f0: np.ndarray = None  # (4,) its force at zero travel and rate (linearized)
    rack_travel: float | None = None  # linkage cars: steering rack travel (m, toward +y)
    #: (4,) the drive part of spin_torque whose reaction goes to the body, not the carrier
    #: (driveshafts; None or zeros: every spin torque reacted on the carrier: brakes,
    #: in-wheel motors)
    drive_torque: np.ndarray | None = None


@dataclass
class CarBuild:
    """Everything :func:`build_car` needs (plain data, no Exudyn objects)."""

    chassis: str  # "rigid" or "flexible"
    flexbody: object = None  # FlexBody for "flexible"
    n_modes: int | None = None  # use only the lowest n elastic modes (None: all)
    modal_q0: np.ndarray | None = None  # initial elastic coordinates (static deflection)
    modal_prewarp: tuple | None = None  # (h, spectral radius): modes fitted to the step
    inertia_coupling: str = "full"  # "full" or "constant" (flexpipe.exu.inertia)
    mass: float = 0.0
    center_of_mass: np.ndarray = None
    inertia_origin: np.ndarray = None
    hardpoints: np.ndarray = None  # (4, 3) body coordinates
    wheel_centers: np.ndarray = None  # (4, 3) body coordinates, design position
    m_unsprung: np.ndarray = None
    J_unsprung: np.ndarray = None  # (4, 3, 3)
    spin_inertia: np.ndarray = None
    spring_k: np.ndarray = None  # (4,) suspension spring rate (implicit connector), N/m
    spring_preload: np.ndarray = None  # (4,) spring force at the design position, N
    damper_c: np.ndarray = None  # (4,) initial damping of the implicit connector, N s/m
    steered: np.ndarray = None  # (4,) bool
    steer_stiffness: float = 2.0e4  # N m / rad, steering system at the road wheel
    steer_damping: float = 150.0  # N m s / rad
    position: np.ndarray = field(default_factory=lambda: np.zeros(3))
    rotation: np.ndarray = field(default_factory=lambda: np.eye(3))
    speed: float = 0.0
    body_rates: np.ndarray = field(default_factory=lambda: np.zeros(3))  # vz, wx, wy extra
    spin_rate: np.ndarray = None
    gravity: float = 9.81
    point_nodes: dict = field(default_factory=dict)  # name -> mesh node index
    point_local: dict = field(default_factory=dict)  # name -> body coordinates
    #: powertrain mounts of a flexible body that take the drive's reaction couple (names
    #: of its interfaces; empty: the body frame takes it)
    reaction_mounts: tuple = ()
    #: linkage cars: the powertrain as a rigid body on mounts (it takes the reaction)
    powertrain: object = None
    subframes: tuple = ()  # linkage cars: subframes on mounts carrying suspension mounts
    suspension: object = None  # linkage cars: Suspension with preloaded springs


class CarSystem:
    """An assembled Exudyn car; :meth:`run` integrates it with per-step linearized loads."""

    def _start(self, spec):
        """New Exudyn system; returns the initial pose ``p0, R0``, velocity ``v0`` and
        gravity ``g`` (global).  With every elastic mode switched off the floating frame
        without elastic coordinates is a rigid body with the FE body's own mass properties
        (Exudyn's ObjectFFRFreducedOrder needs at least one modal coordinate)."""
        self.spec = spec
        self.SC = exu.SystemContainer()
        self.mbs = self.SC.AddSystem()
        p0 = np.asarray(spec.position, dtype=float)
        R0 = np.asarray(spec.rotation, dtype=float)
        v0 = R0 @ np.array([spec.speed, 0.0, 0.0])
        g = np.array([0.0, 0.0, -spec.gravity])
        if spec.chassis == "flexible" and spec.n_modes == 0:
            fb = spec.flexbody
            spec.mass, spec.center_of_mass = fb.mass, fb.center_of_mass
            spec.inertia_origin = fb.inertia_origin
            spec.chassis = "rigid"
        return p0, R0, v0, g

    def __init__(self, spec: CarBuild):
        p0, R0, v0, g = self._start(spec)
        mbs = self.mbs
        rates = np.asarray(spec.body_rates, dtype=float)
        vb = v0 + R0 @ np.array([0.0, 0.0, rates[0]])
        wb = R0 @ np.array([rates[1], rates[2], 0.0])
        names = ("fl", "fr", "rl", "rr")
        if spec.chassis == "flexible":
            h = add_flexible_body(mbs, spec.flexbody, position=p0, rotation=R0, velocity=vb,
                                  angular_velocity=wb, gravity=g, n_modes=spec.n_modes,
                                  name="body", prewarp=spec.modal_prewarp,
                                  inertia_coupling=spec.inertia_coupling)
            self.body_node, self.body_obj = h.node, h.object
            mount = [h.markers[n] for n in names]
            self.modal_node = h.modal_node
            if spec.modal_q0 is not None:
                mbs.SetNodeParameter(h.modal_node, "initialCoordinates",
                                     [float(v) for v in spec.modal_q0])
            # loads need only a position: a one-point marker on the hardpoint's point
            load_at = [mbs.AddMarker(eii.MarkerSuperElementPosition(
                bodyNumber=h.object, meshNodeNumbers=[h.hardpoint_nodes[n]],
                weightingFactors=[1.0])) for n in names]
        else:
            J = spec.inertia_origin
            self.body_node = mbs.AddNode(GetRigidBodyNode(
                nodeType=NODE_TYPE, position=list(p0), velocity=list(vb),
                rotationMatrix=R0, angularVelocity=list(wb)))
            self.body_obj = mbs.AddObject(eii.ObjectRigidBody(
                mass=spec.mass, nodeNumber=self.body_node,
                inertia=[J[0, 0], J[1, 1], J[2, 2], J[1, 2], J[0, 2], J[0, 1]],
                centerOfMass=list(spec.center_of_mass)))
            mount = [mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=self.body_obj,
                                                       localPosition=list(hp)))
                     for hp in spec.hardpoints]
            mb = mbs.AddMarker(eii.MarkerBodyMass(bodyNumber=self.body_obj))
            mbs.AddLoad(eii.LoadMassProportional(markerNumber=mb, loadVector=list(g)))
            self.modal_node = None
            load_at = mount
        self.mount = mount
        self.frame_marker = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=self.body_node))
        self.wheel_node, self.wheel_obj, self.joint, self.torsion = [], [], [], []
        self.tire_elem = []
        self.susp_spring = []
        self.spin_node, self.load_body, self.load_carrier = [], [], []
        self.load_spin = []
        self.travel0 = np.zeros(4)
        self.slide_local = np.zeros((4, 3))
        for i in range(4):
            W = spec.wheel_centers[i]
            H = spec.hardpoints[i]
            n_w = mbs.AddNode(GetRigidBodyNode(
                nodeType=NODE_TYPE, position=list(p0 + R0 @ W), velocity=list(v0),
                rotationMatrix=R0, angularVelocity=[0.0, 0.0, 0.0]))
            Jw = spec.J_unsprung[i]
            o_w = mbs.AddObject(eii.ObjectRigidBody(
                mass=float(spec.m_unsprung[i]), nodeNumber=n_w,
                inertia=[Jw[0, 0], Jw[1, 1], Jw[2, 2], Jw[1, 2], Jw[0, 2], Jw[0, 1]],
                centerOfMass=[0.0, 0.0, 0.0]))
            # carrier marker on the travel axis (below the hardpoint, at wheel-centre height)
            m_slide = mbs.AddMarker(eii.MarkerBodyRigid(
                bodyNumber=o_w, localPosition=[H[0] - W[0], H[1] - W[1], 0.0]))
            m_mass = mbs.AddMarker(eii.MarkerBodyMass(bodyNumber=o_w))
            mbs.AddLoad(eii.LoadMassProportional(markerNumber=m_mass, loadVector=list(g)))
            steered = bool(spec.steered[i])
            # forces through the hardpoint: the carrier slides along the mount's z axis
            jnt = mbs.AddObject(eii.GenericJoint(markerNumbers=[mount[i], m_slide],
                                                 constrainedAxes=[1, 1, 0, 0, 0, 0],
                                                 visualization=eii.VGenericJoint(show=False)))
            # moments through the body frame (the lower-arm path of a real suspension):
            # the carrier keeps its orientation relative to the body axes, free to steer
            rot_axes = [0, 0, 0, 1, 1, 0] if steered else [0, 0, 0, 1, 1, 1]
            mbs.AddObject(eii.GenericJoint(markerNumbers=[self.frame_marker, m_slide],
                                           constrainedAxes=rot_axes,
                                           visualization=eii.VGenericJoint(show=False)))
            tsd = None
            if steered:
                # steering compliance about the body z axis, offset = steering angle
                tsd = mbs.AddObject(eii.ObjectConnectorTorsionalSpringDamper(
                    markerNumbers=[self.frame_marker, m_slide], stiffness=spec.steer_stiffness,
                    damping=spec.steer_damping, offset=0.0))
            self._add_wheel(n_w, spec, i)
            # spring (with preload) and damper, implicit; the damping coefficient is set per
            # step (dual rate: jounce or rebound), stops and anti-roll bars come explicitly
            self.susp_spring.append(mbs.AddObject(eii.ObjectConnectorSpringDamper(
                markerNumbers=[load_at[i], m_slide], referenceLength=float(H[2] - W[2]),
                stiffness=float(spec.spring_k[i]), damping=float(spec.damper_c[i]),
                force=-float(spec.spring_preload[i]),
                visualization=eii.VObjectConnectorSpringDamper(show=False))))
            self.load_body.append(mbs.AddLoad(eii.LoadForceVector(
                markerNumber=load_at[i], loadVector=[0.0, 0.0, 0.0], bodyFixed=False)))
            self.load_carrier.append(mbs.AddLoad(eii.LoadForceVector(
                markerNumber=m_slide, loadVector=[0.0, 0.0, 0.0], bodyFixed=True)))
            self.wheel_node.append(n_w)
            self.wheel_obj.append(o_w)
            self.joint.append(jnt)
            self.torsion.append(tsd)
            self.travel0[i] = W[2] - H[2]
            self.slide_local[i] = [H[0] - W[0], H[1] - W[1], 0.0]
        self._finish(spec)

    def _finish(self, spec) -> None:
        """Output points and their sensors; assemble; carrier reference coordinates,
        solver tolerances."""
        mbs = self.mbs
        self.points = {}
        for name, node in spec.point_nodes.items():
            self.points[name] = ("node", int(node)) if spec.chassis == "flexible" else \
                ("local", list(map(float, spec.point_local[name])))
        output_sensors.add(self)
        mbs.Assemble()
        self._reader = NodeReader(mbs, list(self.wheel_node) + [self.body_node],
                                  self.spin_node)
        self.wheel_ref = self._reader.ref[:4]  # carriers' reference coordinates (4, 7)
        #: the tyre element's kernel, chosen once per run as the state reader's
        self._element = element if jit_enabled() else element_numpy
        # Newton's relative tolerance: at 1e-3 the lateral hub forces of the rigid linkage
        # car converged at first order in h (ISO C 100 km/h, worst corner y against
        # 0.125 ms: 1.9 / 0.9 % at 1 / 0.5 ms), at 1e-4 at second order (0.9 / 0.2 %;
        # 4.3 -> 3.5 % at 2 ms against h/8) for 10-17 % more CPU; 1e-6 adds nothing more
        self.newton_rtol = 1e-4
        self.newton_atol = 1e-4

    # ------------------------------------------------------------------ state and loads
    def _nodes(self):
        """Carriers' position, velocity, rotation, angular velocity, spin rate, node
        coordinates and their rates (global, arrays over the wheels), then the body
        frame's position, rotation, velocity and angular velocity: one bulk read
        (:class:`flexpipe.exu._node_state.NodeReader`)."""
        (p, v, R, w, c, ct), spin = self._reader.read()
        return (p[:4], v[:4], R[:4], w[:4], spin, c[:4], ct[:4]), (p[4], R[4], v[4], w[4])

    def state(self, t: float) -> CarState:
        """Read the current state (suspension travel from the marker frames, which is
        much cheaper than the joint outputs of a flexible-body marker)."""
        gm = self.mbs.GetMarkerOutput
        (wp, wv, wR, ww, spin, wq, wqt), (body_p, body_R, body_v, body_w) = self._nodes()
        mp = np.array([gm(m, OV.Position) for m in self.mount])
        mv = np.array([gm(m, OV.Velocity) for m in self.mount])
        mR = np.array([gm(m, OV.RotationMatrix) for m in self.mount]).reshape(4, 3, 3)
        r = np.einsum("nij,nj->ni", wR, self.slide_local)
        ps = wp + r
        vs = wv + _cross(ww, r)
        jounce = np.einsum("ni,ni->n", mR[:, :, 2], ps - mp) - self.travel0
        rate = np.einsum("ni,ni->n", mR[:, :, 2], vs - mv)
        return CarState(
            t=t, body_p=body_p, body_R=body_R, body_v=body_v, body_w=body_w,
            wheel_p=wp, wheel_v=wv, wheel_R=wR, wheel_w=ww, spin_rate=spin,
            jounce=jounce, jounce_rate=rate, joint_force=None, mount_R=mR,
            wheel_q=wq, wheel_qt=wqt)

    # --- durability (feat/durability): pose and elastic modal coordinates for BodyMotion
    def body_motion_sample(self):
        """``(q, p, R)``: elastic modal coordinates (empty for a rigid body), global position
        of the body-frame origin and body-to-global rotation matrix, now."""
        g = self.mbs.GetNodeOutput
        q = np.zeros(0) if self.modal_node is None else \
            np.asarray(g(self.modal_node, OV.Coordinates), dtype=float)
        return (q, np.asarray(g(self.body_node, OV.Position), dtype=float),
                np.asarray(g(self.body_node, OV.RotationMatrix), dtype=float).reshape(3, 3))

    def output_history(self, t: np.ndarray):
        """Named points' accelerations and the body's motion at the output times ``t``
        from Exudyn's sensors (:func:`flexpipe.exu.output_sensors.history`)."""
        return output_sensors.history(self, t)

    def coordinates(self) -> np.ndarray:
        """All second-order coordinates now (displacements from the reference)."""
        return np.array(self.mbs.systemData.GetODE2Coordinates(), dtype=float)

    def set_initial_coordinates(self, q) -> None:
        """Start from the coordinates ``q`` (of a system built from the same car; the
        initial velocities stay as built)."""
        self.mbs.systemData.SetODE2Coordinates(
            [float(v) for v in q], configuration=exu.ConfigurationType.Initial)

    def joint_forces(self) -> np.ndarray:
        """Constraint force of every suspension joint in its hardpoint frame (4, 3)."""
        return np.array([self.mbs.GetObjectOutput(j, OV.ForceLocal) for j in self.joint])

    def wheel_accelerations(self) -> np.ndarray:
        """Global accelerations (4, 3) of the wheel carriers' centres of mass."""
        return np.array([self.mbs.GetNodeOutput(n, OV.Acceleration) for n in self.wheel_node])

    def _point_output(self, variable) -> dict:
        """Exudyn's output ``variable`` (global, (3,)) of every named body point."""
        out = {}
        for name, (kind, where) in self.points.items():
            if kind == "node":
                a = self.mbs.GetObjectOutputSuperElement(self.body_obj, variable, where)
            else:
                a = self.mbs.GetObjectOutputBody(self.body_obj, variable, where)
            out[name] = np.asarray(a, dtype=float)
        return out

    def point_accelerations(self) -> dict:
        """Global acceleration (3,) of every named body point."""
        return self._point_output(OV.Acceleration)

    def point_velocities(self) -> dict:
        """Global velocity (3,) of every named body point."""
        return self._point_output(OV.Velocity)

    def apply(self, loads: CarLoads, mount_R: np.ndarray, st: CarState) -> None:
        """Set the loads for the coming step (``mount_R``: hardpoint frames, for the
        direction of the suspension force on the body; ``st``: the state at its start)."""
        mbs = self.mbs
        setp = mbs.SetLoadParameter
        so = mbs.SetObjectParameter
        self._apply_wheels(loads, st)
        for i in range(4):
            F = float(loads.suspension[i])
            setp(self.load_body[i], "loadVector", (F * mount_R[i][:, 2]).tolist())
            setp(self.load_carrier[i], "loadVector", [0.0, 0.0, -F])
            if self.torsion[i] is not None:
                so(self.torsion[i], "offset", float(loads.steer[i]))
            so(self.susp_spring[i], "damping", float(loads.damper_c[i]))
            if loads.suspension_k is not None:
                so(self.susp_spring[i], "stiffness", float(loads.suspension_k[i]))
                so(self.susp_spring[i], "force", -float(loads.suspension_f0[i]))

    # ------------------------------------------------------------------ wheels
    def _add_wheel(self, n_w, spec, i: int) -> None:
        """Spin coordinate of wheel ``i`` on carrier node ``n_w``, its drive/brake torque
        load and the tyre element: a linear ODE2 element on the carrier node and the spin
        coordinate whose damping, stiffness and force are set every step (the tyre force
        and moments linearized, flexpipe.vehicle.tire_coupling)."""
        mbs = self.mbs
        n_s = mbs.AddNode(eii.Node1D(referenceCoordinates=[0.0], initialCoordinates=[0.0],
                                     initialVelocities=[float(spec.spin_rate[i])]))
        mbs.AddObject(eii.ObjectRotationalMass1D(inertia=float(spec.spin_inertia[i]),
                                                 nodeNumber=n_s))
        m_spin = mbs.AddMarker(eii.MarkerNodeCoordinate(nodeNumber=n_s, coordinate=0))
        self.tire_elem.append(mbs.AddObject(eii.ObjectGenericODE2(
            nodeNumbers=[n_w, n_s], massMatrix=np.zeros((8, 8)),
            stiffnessMatrix=np.zeros((8, 8)), dampingMatrix=np.zeros((8, 8)),
            forceVector=np.zeros(8), visualization=eii.VObjectGenericODE2(show=False))))
        self.load_spin.append(mbs.AddLoad(eii.LoadCoordinate(markerNumber=m_spin, load=0.0)))
        self.spin_node.append(n_s)
        # the spin coordinate is the wheel's absolute rotation about its axis (a bearing
        # passes no moment about it): the reaction of a spin torque is a load of its own,
        # on the carrier (brake caliper, in-wheel motor) or on the body (driveshaft), set
        # each step along the spin axes (set_spin_reactions)
        if i == 0:
            self.load_drive = []
            self.load_drive_body = mbs.AddLoad(eii.LoadTorqueVector(  # or the powertrain
                markerNumber=getattr(self, "drive_marker", self.frame_marker),
                loadVector=[0.0, 0.0, 0.0]))
            #: (CoupleSplit, loads) when powertrain mounts take the couple (add_reaction_mounts)
            self.reaction = None
        m_c = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=n_w))
        self.load_drive.append(mbs.AddLoad(eii.LoadTorqueVector(markerNumber=m_c,
                                                                loadVector=[0.0, 0.0, 0.0])))

    def _apply_wheels(self, loads: CarLoads, st: CarState) -> None:
        """The tyre elements and spin torques for the coming step."""
        so = self.mbs.SetObjectParameter
        D, K, f = self.tire_matrices(loads.tire, st)
        for i, elem in enumerate(self.tire_elem):
            self.mbs.SetLoadParameter(self.load_spin[i], "load", float(loads.spin_torque[i]))
            so(elem, "dampingMatrix", D[i])
            so(elem, "stiffnessMatrix", K[i])
            so(elem, "forceVector", f[i])
        self.set_spin_reactions(loads.spin_torque, loads.drive_torque, st)

    def set_spin_reactions(self, spin_torque, drive_torque, st: CarState) -> None:
        """The reactions of the spin torques (N m per wheel, on the wheels about their
        spin axes) at the state ``st``: the ``drive_torque`` part (or None) on the body
        (its frame or its powertrain mounts: driveshafts), the rest on the carriers (brake
        calipers, in-wheel motors).  Follower loads along the spin axes, set again for
        every step (and, in a linearization, for every perturbed configuration)."""
        setp = self.mbs.SetLoadParameter
        s = st.wheel_R[:, :, 1]
        T = np.asarray(spin_torque, dtype=float)
        Tb = np.zeros(4) if drive_torque is None else np.asarray(drive_torque, dtype=float)
        on_carrier = -(T - Tb)[:, None] * s
        for i in range(4):
            setp(self.load_drive[i], "loadVector", on_carrier[i].tolist())
        tau = -(Tb[:, None] * s).sum(axis=0)  # the couple on the body
        if self.reaction is None:  # on its frame
            setp(self.load_drive_body, "loadVector", tau.tolist())
        else:  # at its powertrain mounts (a flexible body)
            split, mount_loads = self.reaction
            for load, f in zip(mount_loads, split.rotated(st.body_R, tau), strict=True):
                setp(load, "loadVector", f.tolist())

    def tire_matrices(self, ts, st: CarState):
        """Linear ODE2 elements (damping D, stiffness K, force f on each carrier's 7 node
        coordinates and its spin coordinate; arrays over the wheels) that apply the
        linearized tyre force ``F0 + Dv (v_P - v_P,n) + dw (omega - omega_n) + A (z - z_n)``
        at the contact point, plus ``S theta`` for a rotation of the carrier, and the
        tyre's own moment linearized alike (Exudyn's convention: ``D q_t + K q = f``)."""
        ep = self.wheel_ref[:, 3:] + st.wheel_q[:, 3:]
        qt = np.concatenate([st.wheel_qt, st.spin_rate[:, None]], axis=1)
        args = [np.ascontiguousarray(a, dtype=float)
                for a in (ep, ts.r, ts.spin_axis, qt, st.wheel_q, *ts.lin6,
                          self.spec.spin_inertia)]  # J: the spin's gyroscopic moment
        return self._element(*args)

    # ------------------------------------------------------------------ time loop
    def run(self, step, *, t_end: float, h: float, spectral_radius: float,
            progress=None, jacobian_every_step: bool = False, output_step: float | None = None,
            timers: bool = False, threads: int = 1):
        """Integrate to ``t_end`` with step ``h`` (:func:`flexpipe.exu.timeloop.run`)."""
        return timeloop.run(self, step, t_end=t_end, h=h, spectral_radius=spectral_radius,
                            progress=progress, jacobian_every_step=jacobian_every_step,
                            output_step=output_step, timers=timers, threads=threads)
