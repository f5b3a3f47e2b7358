"""A subframe in the K&C rig: the half-axle model.

The rig solves the left corner of an axle whose two corners are mirror images.  When a
``[subframe.<name>]`` carries some of the axle's mounts, the two corners load the same
rigid subframe, which rests on its bushings.  An analysis that loads both wheels alike
(parallel travel, both contact patches pushed forward) is symmetric about the car's
centre plane, one that pushes both sideways is antisymmetric; a mirror-symmetric subframe
then moves only in the matching half of its degrees of freedom (symmetric: x, z and
pitch; antisymmetric: y, roll and yaw), and its left half, i.e. the bushings on the left
of the centre plane at full and those on it at half their rates, carries the left
corner's loads.  So the left corner with the subframe as one more part, restricted to
those motions, is the whole axle exactly (linear statics; and to the order the rig's
small-rotation bushings hold otherwise).  In the kinematic analyses the bushings are the
joints they surround, so the subframe is held with the body.

:func:`half_carrier` builds that part from an axle, :func:`carried_corner` re-hangs the
corner's carried mounts (joints, links, spring and damper seats, the rack housing) on it;
:class:`~flexpipe.vehicle.suspension.kinematics.Linkage` takes it as ``carrier`` with the
analysis's ``mode``.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from flexpipe._arrays import frozen_arrays
from flexpipe.errors import ModelError
from flexpipe.vehicle.suspension.model import BODY, Axle, CornerLinkage, Part

#: part name of the subframe in the rig's linkage
CARRIER = "subframe"
#: the motions a mirror-symmetric subframe keeps, per analysis (indices into x, y, z,
#: rx, ry, rz)
FREE = {"symmetric": (0, 2, 4), "antisymmetric": (1, 3, 5)}
#: a mount within this distance of the centre plane (m) is on it (half its rates count)
CENTRE_TOL_M = 1e-3


@dataclass(frozen=True)
@frozen_arrays
class Carrier:
    """The left half of a subframe as the rig's part.

    Attributes
    ----------
    name : str
        ``"subframe.<name>"``.
    cm : ndarray (3,)
        Reference point (the subframe's centre of mass, on the centre plane), m.
    points : ndarray (n, 3)
        Its bushings on the corner's side of the centre plane or on it, m.
    bushings : tuple of Bushing
    weights : ndarray (n,)
        1 for a bushing on the corner's side, 0.5 on the centre plane.
    carries : frozenset of str
        The corner's mounts on it.
    rack : bool
        The rack housing is on it.
    """

    name: str
    cm: np.ndarray
    points: np.ndarray
    bushings: tuple
    weights: np.ndarray
    carries: frozenset
    rack: bool


def _mirrored(a, b) -> bool:
    """Whether bushing ``b`` is the mirror image of ``a`` (rates, tables, axes up to sign)."""
    S = np.diag([1.0, -1.0, 1.0])
    same_tables = a.tables.keys() == b.tables.keys() and all(
        np.allclose(a.tables[k][0], b.tables[k][0]) and np.allclose(a.tables[k][1],
                                                                     b.tables[k][1])
        for k in a.tables)
    return (np.allclose(a.stiffness, b.stiffness, rtol=1e-9, atol=0.0) and same_tables
            and np.allclose(np.abs(S @ a.frame @ S), np.abs(b.frame), atol=1e-9))


def half_carrier(axle: Axle) -> Carrier | None:
    """The half of ``axle.subframe`` the rig's left corner rests on, or None.

    Raises
    ------
    ModelError
        The subframe's bushings are not mirror pairs (point mirrored within 1 mm, the
        same rates and tables): the half-axle model needs a symmetric subframe.
    """
    sf = axle.subframe
    if sf is None:
        return None
    corner = axle.left
    rack_mounts = set(axle.rack.mounts) if axle.rack is not None else set()
    carried = frozenset(set(corner.mounts) & set(sf.carries))
    rack = bool(rack_mounts & set(sf.carries))
    if not carried and not rack:
        return None
    side = float(np.sign(corner.wheel_center[1]))
    points, bushings, weights = [], [], []
    for name, p, b in zip(sf.mounts, sf.points, sf.bushings, strict=True):
        mirror = np.asarray(p, float) * [1.0, -1.0, 1.0]
        if abs(p[1]) > CENTRE_TOL_M:
            k = next((i for i, q in enumerate(sf.points)
                      if np.linalg.norm(q - mirror) <= CENTRE_TOL_M), None)
            if k is None or not _mirrored(b, sf.bushings[k]):
                why = ("no mount at its mirror point" if k is None else
                       f"'{sf.mounts[k]}' at its mirror point has other rates or axes")
                raise ModelError(
                    f"[{sf.name}] mount '{name}': {why}; the K&C rig solves one corner of "
                    "a mirror-symmetric axle, so its subframe's bushings must come in "
                    "mirror pairs (y -> -y, the same rates)")
        if p[1] * side < -CENTRE_TOL_M:
            continue
        points.append(p)
        bushings.append(b)
        weights.append(0.5 if abs(p[1]) <= CENTRE_TOL_M else 1.0)
    return Carrier(sf.name, np.array([sf.center_of_mass[0], 0.0, sf.center_of_mass[2]]),
                   np.array(points, float), tuple(bushings), np.array(weights), carried, rack)


def carried_corner(corner: CornerLinkage, carrier: Carrier) -> CornerLinkage:
    """``corner`` with the subframe as a part and its carried mounts hung on it."""
    def owner(name, mount):
        return CARRIER if name == BODY and mount in carrier.carries else name

    joints = tuple(replace(j, a=owner(j.a, j.mount), b=owner(j.b, j.mount))
                   for j in corner.joints)
    links = tuple(replace(lk, b=owner(lk.b, lk.mount)) for lk in corner.links)
    forces = tuple(replace(f, body_part=owner(BODY, f.mount)) for f in corner.forces)
    part = Part(CARRIER, 0.0, carrier.cm)
    return replace(corner, parts=(*corner.parts, part), joints=joints, links=links,
                   forces=forces)


def with_subframes(suspension, subframes):
    """``suspension`` whose axles know the subframe carrying their mounts (one per axle).

    Raises
    ------
    ModelError
        Two subframes carry mounts of one axle.
    """
    axles = {}
    for name, a in suspension.axles.items():
        mounts = set(a.left.mounts) | set(a.right.mounts)
        if a.rack is not None:
            mounts |= set(a.rack.mounts)
        if a.anti_roll_bar is not None:
            mounts |= set(dict(a.anti_roll_bar.mounts))
        on = [sf for sf in subframes if mounts & set(sf.carries)]
        if len(on) > 1:
            raise ModelError(f"the {name} axle's mounts are carried by "
                             f"{' and '.join('[' + sf.name + ']' for sf in on)}; the K&C "
                             "rig takes one subframe per axle")
        axles[name] = replace(a, subframe=on[0] if on else None)
    return replace(suspension, axles=axles)
