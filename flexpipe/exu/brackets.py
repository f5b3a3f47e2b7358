"""Brackets: tiny rigid bodies that give a flexible-body mount a frame cheaply.

Exudyn's ``MarkerSuperElementRigid`` on an ``ObjectFFRFreducedOrder`` is costly: a
generic joint on it costs ten times a spherical joint on a one-point
``MarkerSuperElementPosition`` (``bench/bench_markers.py``).  A bracket is held to the
body by position markers only, and joints and bushings then act on the bracket's own
rigid marker:

* :func:`mount_bracket` (6-DOF mounts): a spherical joint at the hardpoint and three
  distance constraints to two corners of the interface's marker triangle
  (:func:`flexpipe.exu.body.marker_points`).  The bracket translates and turns with the
  mount (rigid motion of the frame plus the mount's elastic rotation, to first order in
  the elastic rotation, as the rigid marker on the triangle); forces and moments load
  the body at the hardpoint and the two corners.  The triangle moves rigidly with the
  interface (its rows are the interface's translation plus rotation times the arm), so
  three of its points fix the frame and load the modes as four do: a converged run
  (``cars/sedan_linkage.toml``, flexible, ISO C 70 km/h, 3 s, Newton tolerance 1e-8)
  gave every hub and mount channel within 0.001 % of its fluctuation of the bracket
  held at all four points, with 12 position markers fewer on the body; Exudyn's time
  per run fell by about 5 % (8.67 -> 8.26 s on average over five alternating pairs of
  5 s runs, faster in four of them; 2026-12-02).
  ``bench/bench_markers.py`` measures its cost against the rigid marker.
* :func:`frame_bracket` (3-DOF mounts): a spherical joint at the hardpoint and the
  bracket's axes locked to the body frame; forces load the body at the mount, moments
  load it as a whole (a 3-DOF interface has no rotation).

The brackets carry no gravity; their mass and inertia are numerical only (every degree
of freedom is constrained).
"""

from __future__ import annotations

import exudyn.itemInterface as eii
import numpy as np
from exudyn.rigidBodyUtilities import GetRigidBodyNode

from flexpipe.exu.body import NODE_TYPE, marker_points

#: mass and inertia of a bracket (numerical only: its motion is fully constrained)
BRACKET_MASS_KG = 1e-4
BRACKET_INERTIA_KGM2 = 1e-9
_EZ = np.array([0.0, 0.0, 1.0])


def _skew(v):
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def _bracket_body(mbs, point, R, v0):
    node = mbs.AddNode(GetRigidBodyNode(
        nodeType=NODE_TYPE, position=[float(x) for x in point],
        velocity=[float(x) for x in v0], rotationMatrix=R,
        angularVelocity=[0.0, 0.0, 0.0]))
    obj = mbs.AddObject(eii.ObjectRigidBody(
        mass=BRACKET_MASS_KG, nodeNumber=node, inertia=[BRACKET_INERTIA_KGM2] * 3 + [0.0] * 3))
    return obj


def _hold_point(mbs, handle, name, obj):
    """Spherical joint: the bracket's origin on the mount's position marker."""
    mp = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=obj, localPosition=[0.0, 0.0, 0.0]))
    mbs.AddObject(eii.ObjectJointSpherical(
        markerNumbers=[handle.position_markers[name], mp],
        visualization=eii.VObjectJointSpherical(show=False)))


def _elastic(body, q0):
    q = np.zeros(body.n_elastic) if q0 is None else np.asarray(q0, float)
    return q, slice(body.n_rigid, body.n_rigid + len(q))


def frame_bracket(mbs, handle, body, name, *, frame_marker, p0, R0, v0, q0=None):
    """Rigid marker at the 3-DOF mount ``name``: axes of the body frame (see module).

    ``frame_marker`` is a rigid marker on the body's reference-frame node; ``p0``,
    ``R0``, ``v0`` the frame's initial position, rotation and velocity; ``q0`` the
    initial elastic coordinates (the bracket starts at the deflected mount).
    """
    itf = {i.name: i for i in body.interfaces}[name]
    q, sel = _elastic(body, q0)
    p = np.asarray(itf.point, float) + itf.shapes[:3, sel] @ q
    obj = _bracket_body(mbs, np.asarray(p0) + np.asarray(R0) @ p, R0, v0)
    _hold_point(mbs, handle, name, obj)
    mr = mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=obj, localPosition=[0.0, 0.0, 0.0]))
    mbs.AddObject(eii.GenericJoint(markerNumbers=[frame_marker, mr],
                                   constrainedAxes=[0, 0, 0, 1, 1, 1],
                                   visualization=eii.VGenericJoint(show=False)))
    return mr


def mount_bracket(mbs, handle, body, name, *, p0, R0, v0, q0=None, arm=None):
    """Rigid marker at the 6-DOF mount ``name``: follows the mount (see module).

    The three distance constraints run from triangle corners ``c_k`` of the mount's
    marker points to bracket points ``c_k + L n`` (``L`` the triangle's circumradius):
    from ``c_1`` along ``n = t_1``, tangential in the triangle's plane (rotation about
    its normal), and along the normal ``n = e_z``; from ``c_2`` along the normal (the
    two normal distances fix the two in-plane rotations, the corners not being in line
    with the hardpoint).  ``arm`` must be the one the body was added with
    (:func:`flexpipe.exu.body.add_flexible_body`, default ``None``).
    """
    if handle.kind != "flexible" or name not in handle.markers:
        raise ValueError(f"'{name}' is no 6-DOF interface of a flexible body")
    pos, rows = marker_points(body, arm=arm)
    i0 = handle.hardpoint_nodes[name] - handle.mesh_node_count
    q, sel = _elastic(body, q0)
    P = pos[i0:i0 + 4] + rows[i0:i0 + 4, :, :len(q)] @ q
    itf = {i.name: i for i in body.interfaces}[name]
    theta = itf.shapes[3:, sel] @ q  # elastic rotation of the mount at the start
    R0 = np.asarray(R0, float)
    obj = _bracket_body(mbs, np.asarray(p0) + R0 @ P[0], R0 @ (np.eye(3) + _skew(theta)), v0)
    _hold_point(mbs, handle, name, obj)
    d = pos[i0 + 1:i0 + 4] - pos[i0]  # bracket points in its own (reference) frame
    L = float(np.linalg.norm(d[0]))
    t1 = np.cross(_EZ, d[0]) / L
    corner = {}  # one position marker per corner used
    for k, n in ((0, t1), (0, _EZ), (1, _EZ)):
        if k not in corner:
            corner[k] = mbs.AddMarker(eii.MarkerSuperElementPosition(
                bodyNumber=handle.object,
                meshNodeNumbers=[handle.hardpoint_nodes[name] + 1 + k], weightingFactors=[1.0]))
        mk = corner[k]
        ma = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=obj,
                                                  localPosition=[float(x) for x in d[k] + L * n]))
        mbs.AddObject(eii.ObjectConnectorDistance(
            markerNumbers=[mk, ma], distance=L,
            visualization=eii.VObjectConnectorDistance(show=False)))
    return mbs.AddMarker(eii.MarkerBodyRigid(bodyNumber=obj, localPosition=[0.0, 0.0, 0.0]))
