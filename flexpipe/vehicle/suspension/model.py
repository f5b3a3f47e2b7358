"""Data model of a suspension linkage: parts, joints, links, bushings, force elements.

Every point is in body coordinates (ISO 8855: x forward, y left, z up) at the design
position, in metres.  The data classes are frozen: a template builds them once from
hardpoints and the kinematics solver and the multibody builder only read them.

``"body"`` as a part name is the car body (fixed in the K&C rig); a connection to it
names the body mount (``front_lower_arm_front_l``) where the flexible body is loaded.
``"rack"`` as a part name is the steering rack (it slides along its axis on the body).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np

from flexpipe._arrays import frozen_arrays

BODY = "body"
RACK = "rack"
JOINT_KINDS = ("spherical", "revolute", "universal", "inline")
FORCE_KINDS = ("spring", "damper", "bump_stop", "rebound_stop")
BUSHING_DOFS = ("x", "y", "z", "rx", "ry", "rz")
#: masses of parts the car file does not describe (kg): the steering rack and each arm of
#: an anti-roll bar (their inertia matters little; their weight enters the static loads)
RACK_MASS = 2.0
ARB_ARM_MASS = 0.5


def _vec(v, n=3) -> np.ndarray:
    a = np.array(v, dtype=float).reshape(n)
    a.setflags(write=False)
    return a


def _unit(v) -> np.ndarray:
    a = np.array(v, dtype=float).reshape(3)
    return _vec(a / np.linalg.norm(a))


@dataclass(frozen=True)
@frozen_arrays
class Part:
    """A rigid part: ``mass`` (kg), centre of mass ``cm`` (m), ``inertia`` about cm (kg m^2)."""

    name: str
    mass: float
    cm: np.ndarray
    inertia: np.ndarray = field(default_factory=lambda: np.zeros((3, 3)))

    def __post_init__(self):
        if not self.mass >= 0:
            raise ValueError(f"part {self.name!r}: mass must be >= 0, got {self.mass}")
        object.__setattr__(self, "cm", _vec(self.cm))
        object.__setattr__(self, "inertia", np.array(self.inertia, float).reshape(3, 3))


@dataclass(frozen=True)
@frozen_arrays
class Bushing:
    """Six-DOF linear bushing in a local frame, optional nonlinear tables.

    Parameters
    ----------
    stiffness : array of 6
        kx, ky, kz (N/m) and krx, kry, krz (N m/rad) along the columns of ``frame``.
    damping : array of 6
        The matching damping (N s/m, N m s/rad); not used by the static rig.
    frame : 3x3 array
        Columns are the bushing axes in body coordinates (default: body axes).
    tables : dict
        Optional ``{dof: (deflection, force)}`` nonlinear force-deflection tables that
        replace the linear rate in that direction (``dof`` in x, y, z, rx, ry, rz).
    """

    stiffness: np.ndarray
    damping: np.ndarray = field(default_factory=lambda: np.zeros(6))
    frame: np.ndarray = field(default_factory=lambda: np.eye(3))
    tables: dict = field(default_factory=dict)

    def __post_init__(self):
        object.__setattr__(self, "stiffness", _vec(self.stiffness, 6))
        object.__setattr__(self, "damping", _vec(self.damping, 6))
        object.__setattr__(self, "frame", np.array(self.frame, float).reshape(3, 3))

    def force(self, d: np.ndarray) -> np.ndarray:
        """Restoring force/torque (6,) in the bushing frame for deflection ``d`` (6,)."""
        f = -self.stiffness * d
        for i, dof in enumerate(BUSHING_DOFS):
            if dof in self.tables:
                x, y = self.tables[dof]
                f[i] = -np.interp(d[i], x, y)
        return f


@dataclass(frozen=True)
@frozen_arrays
class Joint:
    """A joint between part ``a`` and part ``b`` (either may be ``"body"``).

    ``kind``: ``spherical`` (common point), ``revolute`` (common point and common
    ``axis``), ``universal`` (common point; ``axis`` fixed in ``a`` stays perpendicular to
    ``axis_b`` fixed in ``b``, which locks the rotation about their cross product),
    ``inline`` (the point of ``b`` stays on the line through ``point`` along ``axis``
    fixed in ``a``).  ``mount`` names the body mount when a side is the body;
    ``bushing`` replaces the joint by that bushing in compliance analyses.
    """

    name: str
    kind: str
    a: str
    b: str
    point: np.ndarray
    axis: np.ndarray | None = None
    axis_b: np.ndarray | None = None
    mount: str | None = None
    bushing: Bushing | None = None

    def __post_init__(self):
        if self.kind not in JOINT_KINDS:
            raise ValueError(f"joint kind {self.kind!r}; valid: {JOINT_KINDS}")
        if self.kind != "spherical" and self.axis is None:
            raise ValueError(f"joint {self.name!r}: a {self.kind} joint needs an axis")
        if self.kind == "universal" and self.axis_b is None:
            raise ValueError(f"joint {self.name!r}: a universal joint needs axis_b")
        if BODY in (self.a, self.b) and self.mount is None:
            raise ValueError(f"joint {self.name!r} to the body needs a mount name")
        object.__setattr__(self, "point", _vec(self.point))
        for k in ("axis", "axis_b"):
            if getattr(self, k) is not None:
                object.__setattr__(self, k, _unit(getattr(self, k)))


@dataclass(frozen=True)
@frozen_arrays
class Link:
    """Massless two-force link with ball ends ``point_a`` on ``a`` and ``point_b`` on ``b``.

    ``b`` may be ``"body"`` (then ``mount`` names the body mount) or ``"rack"``.
    ``axial_stiffness`` (N/m) makes the link compliant in compliance analyses.
    """

    name: str
    a: str
    point_a: np.ndarray
    b: str
    point_b: np.ndarray
    mount: str | None = None
    axial_stiffness: float | None = None

    def __post_init__(self):
        object.__setattr__(self, "point_a", _vec(self.point_a))
        object.__setattr__(self, "point_b", _vec(self.point_b))

    @property
    def length(self) -> float:
        """Design length (m)."""
        return float(np.linalg.norm(self.point_a - self.point_b))


@dataclass(frozen=True)
@frozen_arrays
class ForceElement:
    """Spring, damper or stop acting along the line from a part point to a body mount.

    Parameters
    ----------
    kind : str
        ``spring``, ``damper``, ``bump_stop`` or ``rebound_stop``.
    part, point : str, array
        Seat on the part (lower seat).
    mount, body_point : str, array
        Seat on the body (upper seat, a body mount).
    rate : float
        Spring rate (N/m); damper: not used.
    free_length : float
        Spring free length (m); force = rate * (free_length - length), compression > 0.
    table : (x, f) arrays
        Spring: optional force (N, compression > 0) vs compression (m) from free length;
        damper: force (N, rebound > 0) vs extension velocity (m/s), both signs (dual
        rate); stops: force (N) vs deflection beyond the clearance (m).
    clearance : float
        Stops: travel from the design length before contact (m).
    body_part : str
        What carries the upper seat: the body, or the subframe part of the K&C rig's
        half-axle model (:mod:`flexpipe.vehicle.suspension.carrier`).
    """

    name: str
    kind: str
    part: str
    point: np.ndarray
    mount: str
    body_point: np.ndarray
    rate: float = 0.0
    free_length: float | None = None
    table: tuple | None = None
    clearance: float = 0.0
    body_part: str = BODY

    def __post_init__(self):
        if self.kind not in FORCE_KINDS:
            raise ValueError(f"force element kind {self.kind!r}; valid: {FORCE_KINDS}")
        object.__setattr__(self, "point", _vec(self.point))
        object.__setattr__(self, "body_point", _vec(self.body_point))

    @cached_property
    def design_length(self) -> float:
        """Length at the design position (m)."""
        return float(np.linalg.norm(self.point - self.body_point))

    def static_force(self, length: float) -> float:
        """Force pushing the seats apart (N) at ``length`` (dampers: 0)."""
        if self.kind == "spring":
            comp = (self.free_length if self.free_length is not None
                    else self.design_length) - length
            if self.table is not None:
                return float(np.interp(comp, *self.table))
            return self.rate * comp
        if self.kind == "bump_stop":
            d = (self.design_length - self.clearance) - length
            return float(np.interp(d, *self.table)) if d > 0 else 0.0
        if self.kind == "rebound_stop":
            d = length - (self.design_length + self.clearance)
            return -float(np.interp(d, *self.table)) if d > 0 else 0.0
        return 0.0

    def damper_force(self, velocity: float) -> float:
        """Damper force (N, resisting) at extension ``velocity`` (m/s), from the table."""
        return float(np.interp(velocity, *self.table)) if self.kind == "damper" else 0.0


@dataclass(frozen=True)
@frozen_arrays
class CornerLinkage:
    """One corner's linkage: parts, joints, links and force elements around a knuckle.

    ``wheel_center`` and ``spin_axis`` (unit, outboard) are fixed in the ``knuckle`` part;
    ``steer_axis`` is a pair of ``(part, point)`` whose line is the kingpin axis (lower
    point first); ``wheel_radius`` (m) places the contact patch below the wheel centre.
    ``spring_part`` carries the spring seat and the anti-roll bar drop link.
    """

    corner: str
    template: str
    side: int
    parts: tuple
    joints: tuple
    links: tuple
    forces: tuple
    knuckle: str
    wheel_center: np.ndarray
    spin_axis: np.ndarray
    wheel_radius: float
    steer_axis: tuple
    spring_part: str
    hardpoints: dict = field(default_factory=dict)

    def __post_init__(self):
        object.__setattr__(self, "wheel_center", _vec(self.wheel_center))
        object.__setattr__(self, "spin_axis", _unit(self.spin_axis))

    def part(self, name: str) -> Part:
        """The part called ``name``."""
        return next(p for p in self.parts if p.name == name)

    @property
    def mounts(self) -> dict:
        """Body mounts ``{name: point}`` this corner loads (joints, links, force elements)."""
        out = {}
        for j in self.joints:
            if BODY in (j.a, j.b):
                out[j.mount] = j.point
        for lk in self.links:
            if lk.b == BODY:
                out[lk.mount] = lk.point_b
        for f in self.forces:
            out.setdefault(f.mount, f.body_point)
        return out

    def spring(self) -> ForceElement | None:
        """The corner's road spring (first ``spring`` element) or None."""
        return next((f for f in self.forces if f.kind == "spring"), None)

    def damper(self) -> ForceElement | None:
        """The corner's damper or None."""
        return next((f for f in self.forces if f.kind == "damper"), None)


@dataclass(frozen=True)
@frozen_arrays
class Rack:
    """Steering rack sliding along ``axis`` (body y) in a housing on body ``mounts``.

    ``travel_per_rev`` is the rack travel per pinion revolution (m); ``ratio`` the overall
    steering ratio (steering-wheel angle / mean road-wheel angle, for reports);
    ``column_stiffness`` (N m/rad) the torsional compliance of column and pinion with the
    steering wheel held: the rack then sees k = column_stiffness (2 pi / travel_per_rev)^2.
    """

    mounts: dict
    travel_per_rev: float
    ratio: float
    column_stiffness: float | None = None
    axis: np.ndarray = field(default_factory=lambda: np.array([0.0, 1.0, 0.0]))

    def __post_init__(self):
        object.__setattr__(self, "axis", _unit(self.axis))

    @property
    def axial_stiffness(self) -> float | None:
        """Rack stiffness against the held steering wheel (N/m), or None (rigid)."""
        if self.column_stiffness is None:
            return None
        return self.column_stiffness * (2 * np.pi / self.travel_per_rev) ** 2

    def wheel_angle_rad(self, rack_travel: float) -> float:
        """Steering-wheel angle (rad, left turn > 0) for ``rack_travel`` (m, toward +y).

        The rack moves to the right (-y) in a left turn: pinion and rack behind the axle,
        as in the sample and in Chrono's sedan."""
        return -2 * np.pi * rack_travel / self.travel_per_rev


@dataclass(frozen=True)
@frozen_arrays
class AntiRollBar:
    """Torsion bar turning in bushings at ``bushing`` (left; right mirrored), arms to
    ``arm_end``, drop links down to ``drop_link_lower`` on the corner's spring part.

    ``torsion_rate`` (N m/rad) is the bar's twist stiffness between the two arms.
    """

    torsion_rate: float
    bushing: np.ndarray
    arm_end: np.ndarray
    drop_link_lower: np.ndarray
    part: str
    mounts: tuple = ()
    bushing_stiffness: Bushing | None = None

    def __post_init__(self):
        for k in ("bushing", "arm_end", "drop_link_lower"):
            object.__setattr__(self, k, _vec(getattr(self, k)))


@dataclass(frozen=True)
@frozen_arrays
class Axle:
    """Both corners of an axle with its optional rack and anti-roll bar; ``subframe`` is
    the car's ``[subframe.<name>]`` (a ``MountedBody``) carrying some of its mounts, which
    the K&C rig's compliance analyses include."""

    name: str
    left: CornerLinkage
    right: CornerLinkage
    rack: Rack | None = None
    anti_roll_bar: AntiRollBar | None = None
    wheel_load: float | None = None
    subframe: object | None = None


def mirror_point(p) -> np.ndarray:
    """``p`` mirrored in the x-z plane (y -> -y)."""
    q = np.array(p, float).copy()
    q[..., 1] *= -1
    return q


def mirror_corner(c: CornerLinkage, corner: str) -> CornerLinkage:
    """The right-hand corner: ``c`` mirrored in y, mounts renamed ``_l`` -> ``_r``."""
    S = np.diag([1.0, -1.0, 1.0])

    def m(name):
        return None if name is None else (name[:-2] + "_r" if name.endswith("_l") else name)

    def pseudo(v):  # axes are reflected like vectors; sign is irrelevant for lines
        return None if v is None else S @ v

    def bush(b):
        if b is None:
            return None
        return replace(b, frame=S @ b.frame @ S)

    parts = tuple(replace(p, cm=S @ p.cm, inertia=S @ p.inertia @ S) for p in c.parts)
    joints = tuple(replace(j, point=S @ j.point, axis=pseudo(j.axis), axis_b=pseudo(j.axis_b),
                           mount=m(j.mount), bushing=bush(j.bushing)) for j in c.joints)
    links = tuple(replace(lk, point_a=S @ lk.point_a, point_b=S @ lk.point_b, mount=m(lk.mount))
                  for lk in c.links)
    forces = tuple(replace(f, point=S @ f.point, body_point=S @ f.body_point, mount=m(f.mount))
                   for f in c.forces)
    steer = tuple((n, S @ p) for n, p in c.steer_axis)
    return replace(c, corner=corner, side=-c.side, parts=parts, joints=joints, links=links,
                   forces=forces, wheel_center=S @ c.wheel_center, spin_axis=S @ c.spin_axis,
                   steer_axis=steer,
                   hardpoints={k: S @ v for k, v in c.hardpoints.items()})
