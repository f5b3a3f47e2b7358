"""Exudyn adapter for a :class:`~flexpipe.flexbody.FlexBody` (the only module of flexpipe,
with its siblings in :mod:`flexpipe.exu`, that imports exudyn).

:func:`add_flexible_body` builds an ``ObjectFFRFreducedOrder`` (floating frame of
reference: a rigid-body node plus one modal coordinate per elastic mode) with a
``MarkerSuperElementRigid`` at every interface, its inertia either Exudyn's complete
floating-frame terms or, for mean-axis modes, Adams/Flex's constant coupling
(:mod:`flexpipe.exu.inertia`); :func:`add_rigid_twin` builds an
``ObjectRigidBody`` with identical mass, centre of mass and inertia and a
``MarkerBodyRigid`` at every interface hardpoint.  Both return a :class:`BodyHandle`
whose ``markers`` are ready for joints, springs and loads.

Interfaces as 6-DOF markers
---------------------------
Exudyn's FFRF body carries 3 translations per mesh node.  For every interface the
adapter appends four massless *marker points* to the mode basis: the hardpoint and the
corners of an equilateral triangle of circumradius ``arm`` centred on it (in the body's
x-y plane), whose mode-shape rows are the rigid motion of the hardpoint,
``u = u_h + theta_h x d``.  A ``MarkerSuperElementRigid`` on the three corners (equal
weights, centroid on the hardpoint, zero offset) therefore moves exactly like the
hardpoint of the RBE2 spider (or the 6-DOF node) in the reduced model; three
non-collinear points fix a rotation, and Exudyn's cost of such a marker grows with its
point count (``bench/bench_markers.py``: per Newton iteration a generic joint on a
7-point marker cost 22x a spherical joint on the one-point position marker, on the 3
points 10x).  Being
massless, the points do not change the inertia invariants.  A 3-DOF (translational)
interface gets only the hardpoint itself: a ``MarkerSuperElementPosition`` on it moves
with the hardpoint; it has no rigid marker (its rotation is not a boundary DOF of the
reduction, so moments there would not be reproduced).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
from exudyn.rigidBodyUtilities import GetRigidBodyNode

from flexpipe.errors import InputError
from flexpipe.exu.inertia import (
    COUPLINGS,
    add_constant_coupling,
    check_mean_axes,
    dense,
    inertia6,
)
from flexpipe.flexbody.body import FlexBody

#: rotation parameterization of the reference-frame node (works with implicit solvers)
NODE_TYPE = exu.NodeType.RotationEulerParameters
_ANGLES = np.deg2rad([90.0, 210.0, 330.0])
#: unit offsets of a 6-DOF interface's three rotation points (equilateral triangle)
_ARMS = np.column_stack([np.cos(_ANGLES), np.sin(_ANGLES), np.zeros(3)])
#: marker points per 6-DOF interface: the hardpoint and the triangle
_POINTS_6DOF = 1 + len(_ARMS)


@dataclass(frozen=True)
class BodyHandle:
    """Exudyn items of a body added by :func:`add_flexible_body` or :func:`add_rigid_twin`.

    Attributes
    ----------
    kind : {"flexible", "rigid"}
    object : ObjectIndex
        ``ObjectFFRFreducedOrder`` or ``ObjectRigidBody``.
    node : NodeIndex
        Rigid-body node of the reference frame (placed at the mesh-coordinate origin).
    modal_node : NodeIndex or None
        ``NodeGenericODE2`` holding the modal coordinates (flexible bodies only).
    markers : mapping of str to MarkerIndex
        6-DOF interface name -> rigid marker (``MarkerSuperElementRigid`` /
        ``MarkerBodyRigid``) at the hardpoint.
    node_marker : MarkerIndex
        ``MarkerNodeRigid`` on the reference-frame node.
    body_marker : MarkerIndex
        ``MarkerBodyMass`` of the body (gravity and other mass-proportional loads); with
        constant inertia coupling, of the ``ObjectRigidBody`` carrying its inertia.
    gravity_load : LoadIndex or None
    interface_points : mapping of str to ndarray
        Hardpoints in body coordinates.
    mesh_node_count : int
        Number of real mesh nodes (marker points come after them).
    hardpoint_nodes : mapping of str to int
        Interface name -> index of the body's extra mesh point that sits on the hardpoint
        and follows the rigid spider (flexible bodies only), for one-point markers such
        as ``MarkerSuperElementPosition``.
    position_markers : mapping of str to MarkerIndex
        Every interface name -> position marker at the hardpoint
        (``MarkerSuperElementPosition`` / ``MarkerBodyPosition``): forces, spherical joints,
        bushings without moments.
    """

    kind: str
    object: object
    node: object
    modal_node: object
    markers: Mapping[str, object]
    node_marker: object
    body_marker: object
    gravity_load: object = None
    interface_points: Mapping[str, np.ndarray] = field(default_factory=dict)
    mesh_node_count: int = 0
    hardpoint_nodes: Mapping[str, int] = field(default_factory=dict)
    position_markers: Mapping[str, object] = field(default_factory=dict)

    def _marker(self, name):
        if name not in self.position_markers and name not in self.markers:
            raise InputError(f"no interface {name!r}; valid: {sorted(self.position_markers)}",
                             key=name)
        return self.position_markers.get(name, self.markers.get(name))

    def interface_position(self, mbs, name: str, *, reference: bool = False) -> np.ndarray:
        """World position of interface ``name`` (current, or reference configuration)."""
        cfg = exu.ConfigurationType.Reference if reference else exu.ConfigurationType.Current
        return np.asarray(mbs.GetMarkerOutput(self._marker(name),
                                              exu.OutputVariableType.Position,
                                              configuration=cfg))

    def interface_velocity(self, mbs, name: str) -> np.ndarray:
        """World velocity of interface ``name``."""
        return np.asarray(mbs.GetMarkerOutput(self._marker(name),
                                              exu.OutputVariableType.Velocity))

    def modal_coordinates(self, mbs) -> np.ndarray:
        """Current modal coordinates (empty for a rigid twin)."""
        if self.modal_node is None:
            return np.zeros(0)
        return np.asarray(mbs.GetNodeOutput(self.modal_node, exu.OutputVariableType.Coordinates))


def _frame_node(mbs, position, rotation, velocity, angular_velocity, name):
    R = np.eye(3) if rotation is None else np.asarray(rotation, dtype=float)
    if R.shape != (3, 3) or not np.allclose(R @ R.T, np.eye(3), atol=1e-9):
        raise InputError("rotation must be a 3x3 rotation matrix (orthonormal)", key="rotation")
    item = GetRigidBodyNode(nodeType=NODE_TYPE, position=list(map(float, position)),
                            velocity=list(map(float, velocity)), rotationMatrix=R,
                            angularVelocity=list(map(float, angular_velocity)))
    item.name = f"{name}:frame" if name else ""
    return mbs.AddNode(item)


def _check_vec(v, key):
    a = np.asarray(v, dtype=float)
    if a.shape != (3,) or not np.all(np.isfinite(a)):
        raise InputError(f"must be 3 finite numbers, got {v!r}", key=key)
    return a


def marker_points(body: FlexBody, *, arm: float | None = None):
    """Reference positions (p, 3) and elastic mode rows (p, 3, m_e) of the marker points.

    Per 6-DOF interface: the hardpoint, then the three corners of an equilateral
    triangle of circumradius ``arm`` around it in the x-y plane (4 points); per 3-DOF
    interface the hardpoint only.
    """
    if arm is None:
        size = np.ptp(body.nodes, axis=0).max() if body.n_nodes else 1.0
        arm = 0.02 * max(size, 1e-3)
    pos, rows = [], []
    for itf in body.interfaces:
        u = itf.shapes[:3, body.n_rigid:]  # (3, m_e)
        th = itf.shapes[3:, body.n_rigid:]
        d = np.vstack([np.zeros(3), arm * _ARMS]) if itf.dofs == 6 else np.zeros((1, 3))
        pos.append(itf.point + d)
        # u + theta x d for every point and mode: (k, 3, m_e)
        rows.append(u[None] + np.cross(th.T[None, :, :], d[:, None, :]).transpose(0, 2, 1))
    m_e = body.n_elastic
    if not pos:
        return np.zeros((0, 3)), np.zeros((0, 3, m_e))
    return np.vstack(pos), np.concatenate(rows)


def _elastic_selection(body, n_modes):
    if n_modes is None:
        return body.n_elastic
    if not isinstance(n_modes, (int, np.integer)) or not 0 <= n_modes <= body.n_elastic:
        raise InputError(f"n_modes must be an integer in [0, {body.n_elastic}], got {n_modes!r}",
                         key="n_modes")
    return int(n_modes)


def _prewarped(Mr, Kr, Dr, h, spectral_radius):
    """Modal mass and damping fitted to the step (see :mod:`flexpipe.exu.prewarp`)."""
    from flexpipe.exu.prewarp import prewarp_modes

    m, k, c = np.diag(Mr), np.diag(Kr), np.diag(Dr)
    if any(np.count_nonzero(A - np.diag(np.diag(A))) for A in (Mr, Kr, Dr)):
        raise InputError("prewarp needs diagonal modal mass, stiffness and damping matrices",
                         key="prewarp")
    omega = np.sqrt(k / m)
    zeta = c / (2.0 * np.sqrt(k * m))
    factor, zp, _ = prewarp_modes(omega, zeta, h=float(h), spectral_radius=float(spectral_radius))
    m2 = m * factor
    return np.diag(m2), np.diag(2.0 * zp * np.sqrt(k * m2))


def add_flexible_body(mbs, body: FlexBody, *, position=(0.0, 0.0, 0.0), rotation=None,
                      velocity=(0.0, 0.0, 0.0), angular_velocity=(0.0, 0.0, 0.0),
                      gravity=(0.0, 0.0, -9.81), damping=True, n_modes: int | None = None,
                      color=(0.2, 0.6, 0.9, 1.0), name: str = "flexbody",
                      arm: float | None = None, prewarp=None,
                      inertia_coupling: str = "full") -> BodyHandle:
    """Add ``body`` as an Exudyn ``ObjectFFRFreducedOrder`` with interface markers.

    Parameters
    ----------
    mbs : exudyn.MainSystem
    body : FlexBody
    position : (3,) array_like
        World position of the body-coordinate (mesh) origin, m.
    rotation : (3, 3) array_like, optional
        Body-to-world rotation matrix (default identity).
    velocity, angular_velocity : (3,) array_like
        Initial velocity of the origin and angular velocity, world frame.
    gravity : (3,) array_like
        Gravitational acceleration, m/s^2; ``(0, 0, 0)`` for none.
    damping : bool or float
        ``True``: the body's modal damping ``body.D``; ``False``: none; a float: that
        damping ratio for every elastic mode.
    n_modes : int, optional
        Use only the lowest ``n_modes`` elastic modes (default all).
    color : RGBA
    name : str
        Exudyn item name prefix.
    arm : float, optional
        Distance of the marker points from each hardpoint (default 2% of the body size).
    prewarp : (h, spectral_radius), optional
        Fit each elastic mode's modal mass and damping to the generalized-alpha step ``h``
        with that spectral radius so the step rings it at its own frequency and damping
        (:mod:`flexpipe.exu.prewarp`; stiffness, hence statics, unchanged).
    inertia_coupling : {"full", "constant"}
        Inertia of the floating frame, named as Adams/Flex names its options.  ``"full"``:
        Exudyn's complete FFRF mass matrix and quadratic velocity terms (every inertia
        invariant, deformation-dependent).  ``"constant"``: the rigid body's mass, centre
        of mass and inertia plus the constant modal mass, stiffness and damping, with no
        deformation-dependent coupling (invariants 3, 4, 5, 8 and 9 off); the markers
        still follow ``p + A (x + Phi q)``.  Exact to first order in the deformation when
        the elastic modes are orthogonal to the rigid-body motion (mean axes; checked,
        :func:`flexpipe.flexbody.invariants.mean_axis_cosine`); what it leaves out are the
        centrifugal and Coriolis loads of the frame's rotation on the modes and the
        deformation's change of the body's inertia.

    Returns
    -------
    BodyHandle
    """
    if not isinstance(body, FlexBody):
        raise InputError(f"body must be a FlexBody, got {type(body).__name__}")
    position = _check_vec(position, "position")
    g = _check_vec(gravity, "gravity")
    me = _elastic_selection(body, n_modes)
    sel = slice(body.n_rigid, body.n_rigid + me)
    n = body.n_nodes
    Psi = body.modes[:, :, sel]
    mp_pos, mp_rows = marker_points(body, arm=arm)
    basis = np.concatenate([Psi, mp_rows[:, :, :me]]).reshape(-1, me)
    xref = np.vstack([body.nodes, mp_pos]).ravel()
    Mr = body.M[sel, sel]
    Kr = body.K[sel, sel]
    if damping is True:
        Dr = body.D[sel, sel]
    elif damping is False or damping is None:
        Dr = np.zeros((me, me))
    else:
        zeta = float(damping)
        Dr = np.diag(2 * zeta * body.omega[sel])
    if inertia_coupling not in COUPLINGS:
        raise InputError(f"inertia_coupling {inertia_coupling!r}; valid: {', '.join(COUPLINGS)}",
                         key="inertia_coupling")
    if inertia_coupling == "constant":
        check_mean_axes(body, me)
    if prewarp is not None and me:
        Mr, Dr = _prewarped(Mr, Kr, Dr, *prewarp)
    inv = body.invariants
    k3 = slice(0, 3 * me)

    n_frame = _frame_node(mbs, position, rotation, velocity, angular_velocity, name)
    n_modal = mbs.AddNode(eii.NodeGenericODE2(
        name=f"{name}:modal" if name else "", numberOfODE2Coordinates=me,
        referenceCoordinates=[0.0] * me, initialCoordinates=[0.0] * me,
        initialCoordinates_t=[0.0] * me))
    obj = mbs.AddObject(eii.ObjectFFRFreducedOrder(
        name=name, nodeNumbers=[n_frame, n_modal],
        massMatrixReduced=dense(Mr), stiffnessMatrixReduced=dense(Kr),
        dampingMatrixReduced=dense(Dr) if np.any(Dr) else [],
        modeBasis=basis, referencePositions=xref,
        mass=body.mass, inertia=body.inertia_origin, centerOfMass=body.center_of_mass,
        mPsiTildePsi=inv.mPsiTildePsi[k3, :me], mPsiTildePsiTilde=inv.mPsiTildePsiTilde[k3, k3],
        mPhitTPsi=inv.mPhitTPsi[:, :me], mPhitTPsiTilde=inv.mPhitTPsiTilde[:, k3],
        mXRefTildePsi=inv.mXRefTildePsi[:, :me], mXRefTildePsiTilde=inv.mXRefTildePsiTilde[:, k3],
        computeFFRFterms=inertia_coupling == "full",
        visualization=eii.VObjectFFRFreducedOrder(
            triangleMesh=np.asarray(body.triangles, dtype=np.int64), color=list(color),
            showNodes=False)))
    markers, position_markers, first = {}, {}, {}
    start = n
    for itf in body.interfaces:
        first[itf.name] = start
        label = f"{name}:{itf.name}" if name else ""
        if itf.dofs == 6:
            pts = list(range(start + 1, start + _POINTS_6DOF))
            markers[itf.name] = mbs.AddMarker(eii.MarkerSuperElementRigid(
                name=label, bodyNumber=obj, offset=[0.0, 0.0, 0.0],
                meshNodeNumbers=pts, weightingFactors=[1.0 / len(pts)] * len(pts),
                useAlternativeApproach=True, rotationsExponentialMap=2))
        position_markers[itf.name] = mbs.AddMarker(eii.MarkerSuperElementPosition(
            name=f"{label}:position" if label else "", bodyNumber=obj,
            meshNodeNumbers=[start], weightingFactors=[1.0]))
        start += _POINTS_6DOF if itf.dofs == 6 else 1
    m_node = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=n_frame))
    inertia_obj = obj
    if inertia_coupling == "constant":
        inertia_obj = add_constant_coupling(mbs, body, n_frame, n_modal, Mr, Kr, Dr)
    m_body = mbs.AddMarker(eii.MarkerBodyMass(bodyNumber=inertia_obj))
    load = None
    if np.any(g):
        load = mbs.AddLoad(eii.LoadMassProportional(markerNumber=m_body, loadVector=list(g)))
    return BodyHandle(kind="flexible", object=obj, node=n_frame, modal_node=n_modal,
                      markers=markers, node_marker=m_node, body_marker=m_body,
                      gravity_load=load,
                      interface_points={i.name: i.point.copy() for i in body.interfaces},
                      mesh_node_count=n, hardpoint_nodes=first,
                      position_markers=position_markers)


def add_rigid_twin(mbs, body: FlexBody, *, position=(0.0, 0.0, 0.0), rotation=None,
                   velocity=(0.0, 0.0, 0.0), angular_velocity=(0.0, 0.0, 0.0),
                   gravity=(0.0, 0.0, -9.81), color=(0.7, 0.7, 0.7, 1.0),
                   name: str = "rigidbody", show_surface: bool = True) -> BodyHandle:
    """Add the rigid twin of ``body``: same mass, centre of mass and inertia, same markers.

    The reference node sits at the body-coordinate origin (as for
    :func:`add_flexible_body`), so both bodies can be placed with the same arguments.
    """
    if not isinstance(body, FlexBody):
        raise InputError(f"body must be a FlexBody, got {type(body).__name__}")
    position = _check_vec(position, "position")
    g = _check_vec(gravity, "gravity")
    J = body.inertia_origin
    n_frame = _frame_node(mbs, position, rotation, velocity, angular_velocity, name)
    graphics = []
    if show_surface and len(body.triangles):
        import exudyn.graphics as gfx

        graphics = [gfx.FromPointsAndTrigs(body.nodes.tolist(), body.triangles.tolist(),
                                           color=list(color))]
    obj = mbs.AddObject(eii.ObjectRigidBody(
        name=name, nodeNumber=n_frame, mass=body.mass,
        inertia=inertia6(J),
        centerOfMass=list(body.center_of_mass),
        visualization=eii.VObjectRigidBody(graphicsData=graphics)))
    markers = {itf.name: mbs.AddMarker(eii.MarkerBodyRigid(
        name=f"{name}:{itf.name}" if name else "", bodyNumber=obj,
        localPosition=list(itf.point))) for itf in body.interfaces if itf.dofs == 6}
    position_markers = {itf.name: mbs.AddMarker(eii.MarkerBodyPosition(
        name=f"{name}:{itf.name}:position" if name else "", bodyNumber=obj,
        localPosition=list(itf.point))) for itf in body.interfaces}
    m_node = mbs.AddMarker(eii.MarkerNodeRigid(nodeNumber=n_frame))
    m_body = mbs.AddMarker(eii.MarkerBodyMass(bodyNumber=obj))
    load = None
    if np.any(g):
        load = mbs.AddLoad(eii.LoadMassProportional(markerNumber=m_body, loadVector=list(g)))
    return BodyHandle(kind="rigid", object=obj, node=n_frame, modal_node=None, markers=markers,
                      node_marker=m_node, body_marker=m_body, gravity_load=load,
                      interface_points={i.name: i.point.copy() for i in body.interfaces},
                      mesh_node_count=body.n_nodes, position_markers=position_markers)
