"""The full car with linkage suspensions: body (rigid or flexible) + :class:`LinkageModel`
+ wheel spin and the implicit tyre coupling of :class:`~flexpipe.exu.car.CarSystem`.

Every body-side mount of the suspension loads the body where it really sits: on the rigid
body through a marker at the mount point, on the flexible body through the mount's
interface.  Where a joint or a bushing needs the mount's frame, it acts on a *bracket*
(:mod:`flexpipe.exu.brackets`), a tiny rigid body held by position markers only: at a
6-DOF interface the bracket turns with the mount (moments load the body there); at a
3-DOF interface its axes are the body frame's (forces load the body at the mount,
moments load it as a whole).  The templates' inline joints (no moment passes) sit on
3-DOF mounts (``Suspension.mount_dofs``): on ``cars/sedan_linkage.toml`` (ISO C,
70 km/h, 3 s) that moved the hub forces by at most 0.7 % (x), 1.3 % (y), 0.05 % (z) of
their fluctuation against 6-DOF mounts and cut the CPU time by 12 %.  The 6-DOF bracket
replaced Exudyn's ``MarkerSuperElementRigid`` (same three marker points): on the same
run the hub forces moved by at most 0.01 % of their fluctuation, and a generic joint on
the bracket costs Exudyn 1.8-1.9x less per Newton iteration than one on the rigid marker
(``bench/bench_markers.py``, Exudyn's range-checked module).  With Exudyn's fast module
the single joints cost the same in that bench, but the car still runs faster on brackets:
Exudyn 0.84-1.04 against 1.09-1.21 ms per step (flexible car, ISO C 70 km/h, 3 s, three
alternating pairs, 2026-12-02).
"""

from __future__ import annotations

import exudyn.itemInterface as eii
import numpy as np
from exudyn.rigidBodyUtilities import GetRigidBodyNode

from flexpipe.errors import InputError
from flexpipe.exu.body import NODE_TYPE, add_flexible_body
from flexpipe.exu.brackets import frame_bracket, mount_bracket
from flexpipe.exu.car import CarState, CarSystem
from flexpipe.exu.linkage import LinkageModel, add_rigid_part


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
                                  prewarp=spec.modal_prewarp,
                                  inertia_coupling=spec.inertia_coupling)
            self.body_node, self.body_obj, self.modal_node = h.node, h.object, h.modal_node
            if spec.modal_q0 is not None:
                mbs.SetNodeParameter(h.modal_node, "initialCoordinates",
                                     [float(v) for v in spec.modal_q0])

            self.frame_marker = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=self.body_node))
            fb = spec.flexbody
            at = dict(p0=p0, R0=R0, v0=v0, q0=spec.modal_q0)

            def mount_marker(name, rigid):
                if rigid and name in h.markers:  # 6-DOF mount: a bracket turning with it
                    key = (name, "mount")
                    if key not in cache:
                        cache[key] = mount_bracket(mbs, h, fb, name, **at)
                    return cache[key]
                table = h.markers if rigid else h.position_markers
                if rigid and name in h.position_markers:  # 3-DOF: axes of the body frame
                    key = (name, "frame")
                    if key not in cache:
                        cache[key] = frame_bracket(mbs, h, fb, name,
                                                   frame_marker=self.frame_marker, **at)
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
            for b in (spec.powertrain, *spec.subframes):
                if b is not None:
                    points.update(zip(b.mounts, b.points, strict=True))

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
        subframes = {sf.name: add_rigid_part(mbs, sf.mass, sf.inertia, sf.center_of_mass,
                                             sf.center_of_mass, p0=p0, R0=R0, v0=v0,
                                             gravity=g)
                     for sf in spec.subframes}
        if subframes:
            mount_marker = _on_subframes(mbs, spec, subframes, mount_marker)
        self.linkage = lk = LinkageModel(mbs, spec.suspension, mount_marker=mount_marker,
                                         p0=p0, R0=R0, v0=v0, gravity=g)
        for sf in spec.subframes:
            lk.add_body_mounts(sf, subframes[sf.name])
        if spec.powertrain is not None:  # the drive's reaction goes to it (_add_wheel)
            self.drive_marker = lk.add_powertrain(spec.powertrain)
        self.wheel_node = list(lk.knuckle_node)
        self.spin_node, self.load_spin, self.tire_elem = [], [], []
        for i in range(4):
            self._add_wheel(self.wheel_node[i], spec, i)
        if spec.chassis == "flexible" and spec.reaction_mounts:
            self._add_reaction_mounts(h, spec.reaction_mounts)
        lk.add_law_connectors()  # after every other object (flexpipe.exu.threads)
        lk.add_mount_sensors(self.body_node)
        order = spec.suspension.corners()
        self.design_wheel = np.array([order[c].wheel_center for c in ("fl", "fr", "rl", "rr")])
        self._finish(spec)
        self.joint = []

    def _add_reaction_mounts(self, h, names) -> None:
        """Force loads at the flexible body's powertrain mounts that pass the drive's
        reaction couple (:class:`~flexpipe.vehicle.reaction_mounts.CoupleSplit`); a rigid
        body takes the couple on its frame, the same load for it."""
        from flexpipe.vehicle.reaction_mounts import CoupleSplit

        missing = [n for n in names if n not in h.position_markers]
        if missing:
            raise InputError(f"the flexible body has no interface for the powertrain mount "
                             f"'{missing[0]}' of [drive] reaction_mounts; reduce the body "
                             "with it (its interfaces: "
                             f"{', '.join(sorted(h.position_markers))})",
                             key="drive.reaction_mounts")
        split = CoupleSplit(tuple(names), np.array([h.interface_points[n] for n in names]))
        loads = [self.mbs.AddLoad(eii.LoadForceVector(markerNumber=h.position_markers[n],
                                                      loadVector=[0.0, 0.0, 0.0]))
                 for n in names]
        self.reaction = (split, loads)

    def state(self, t: float) -> CarState:
        """Current state; ``jounce`` is the wheel-centre travel along the body z axis."""
        (wp, wv, wR, ww, spin, wq, wqt), (body_p, body_R, body_v, body_w) = self._nodes()
        d = wp - body_p
        ez = body_R[:, 2]
        jounce = d @ ez - self.design_wheel[:, 2]
        # rate along the body z axis: (v - v_body - w x d) . ez = (v - v_body) . ez - d . (ez x w)
        w = body_w
        ez_w = np.array([ez[1] * w[2] - ez[2] * w[1], ez[2] * w[0] - ez[0] * w[2],
                         ez[0] * w[1] - ez[1] * w[0]])
        rate = (wv - body_v) @ ez - d @ ez_w
        return CarState(t=t, body_p=body_p, body_R=body_R, body_v=body_v, body_w=body_w,
                        wheel_p=wp, wheel_v=wv, wheel_R=wR, wheel_w=ww, spin_rate=spin,
                        jounce=jounce, jounce_rate=rate, joint_force=None,
                        mount_R=body_R[None].repeat(4, axis=0), wheel_q=wq, wheel_qt=wqt)

    def apply(self, loads, mount_R, st) -> None:
        """Tyre elements, spin torques, rack travel (the springs, dampers and stops need
        nothing: their laws run inside Exudyn)."""
        self._apply_wheels(loads, st)
        if loads.rack_travel is not None:
            self.linkage.set_rack_travel(loads.rack_travel)

    def joint_forces(self):  # the hub force comes from hub_forces for linkage cars
        return np.zeros((4, 3))


def _on_subframes(mbs, spec, subframes, body_marker):
    """``mount_marker`` with the suspension mounts a subframe carries on that subframe's
    rigid body (``subframes``: name -> (node, object)) at their hardpoints, the others on
    the body (``body_marker``)."""
    points = spec.suspension.mounts()
    owner = {n: sf for sf in spec.subframes for n in sf.carries}
    cache = {}

    def mount_marker(name, rigid):
        sf = owner.get(name)
        if sf is None:
            return body_marker(name, rigid)
        key = (name, rigid)
        if key not in cache:
            obj = subframes[sf.name][1]
            local = [float(v) for v in np.asarray(points[name]) - sf.center_of_mass]
            item = (eii.MarkerBodyRigid if rigid else eii.MarkerBodyPosition)(
                bodyNumber=obj, localPosition=local)
            cache[key] = mbs.AddMarker(item)
        return cache[key]

    return mount_marker
