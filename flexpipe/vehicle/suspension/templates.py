"""Suspension templates: the topology is code, every number is data.

A template turns a dict of left-side hardpoints (body coordinates, m, Adams/Car-style
names) into a :class:`~flexpipe.vehicle.suspension.model.CornerLinkage`; the right-hand
corner is its mirror image (:func:`~flexpipe.vehicle.suspension.model.mirror_corner`).
Minimal bodies: a massless two-force member is a :class:`Link`; an arm that carries a
spring seat, a drop link or more than two joints is a :class:`Part`.

Body mounts are called ``<axle>_<hardpoint>_l``; a spring or damper seat that coincides
with another mount shares that mount.
"""

from __future__ import annotations

import numpy as np

from flexpipe.errors import InputError
from flexpipe.vehicle.suspension.model import (
    BODY,
    RACK,
    Bushing,
    CornerLinkage,
    ForceElement,
    Joint,
    Link,
    Part,
)

#: required and optional hardpoints per template
HARDPOINTS = {
    "double_wishbone": (
        ("lower_arm_front", "lower_arm_rear", "lower_arm_outer", "upper_arm_front",
         "upper_arm_rear", "upper_arm_outer", "tie_rod_inner", "tie_rod_outer",
         "spring_upper", "spring_lower", "damper_upper", "damper_lower", "wheel_center"),
        ("arb_bushing", "arb_arm_end", "drop_link_lower")),
    "macpherson": (
        ("lower_arm_front", "lower_arm_rear", "lower_arm_outer", "strut_top", "strut_lower",
         "tie_rod_inner", "tie_rod_outer", "spring_upper", "spring_lower", "damper_upper",
         "damper_lower", "wheel_center"),
        ("arb_bushing", "arb_arm_end", "drop_link_lower")),
    "multi_link": (
        ("upper_arm_front", "upper_arm_rear", "upper_arm_outer", "lateral_link_inner",
         "lateral_link_outer", "trailing_link_front", "trailing_link_outer", "tie_rod_inner",
         "tie_rod_outer", "spring_upper", "spring_lower", "damper_upper", "damper_lower",
         "wheel_center"),
        ("arb_bushing", "arb_arm_end", "drop_link_lower")),
}
#: parts of each template (the first is the knuckle; the spring part carries the seats)
PARTS = {"double_wishbone": ("knuckle", "lower_arm", "upper_arm"),
         "macpherson": ("knuckle", "lower_arm"),
         "multi_link": ("knuckle", "upper_arm", "trailing_link")}
SPRING_PART = {"double_wishbone": "lower_arm", "macpherson": "knuckle",
               "multi_link": "trailing_link"}


def spin_axis(camber_deg: float, toe_deg: float) -> np.ndarray:
    """Left wheel's spin axis (outboard) for camber (top out > 0) and toe (toe-in > 0)."""
    g, t = np.radians(camber_deg), np.radians(toe_deg)
    return np.array([np.sin(t) * np.cos(g), np.cos(t) * np.cos(g), -np.sin(g)])


class _Builder:
    def __init__(self, template, hp, axle, corner, parts, bushings, file):
        self.template, self.axle, self.corner, self.file = template, axle, corner, file
        req, opt = HARDPOINTS[template]
        unknown = sorted(set(hp) - set(req) - set(opt))
        if unknown:
            raise InputError(f"unknown hardpoint '{unknown[0]}' for template {template}; "
                             f"valid: {', '.join(req + opt)}", file=file, key=unknown[0])
        missing = [k for k in req if k not in hp]
        if missing:
            raise InputError(f"missing hardpoint '{missing[0]}' of template {template} "
                             f"(required: {', '.join(req)})", file=file, key=missing[0])
        self.hp = {k: np.asarray(v, float) for k, v in hp.items()}
        self.bushings = dict(bushings or {})
        self.parts_data = dict(parts or {})
        self.mount_points: dict[str, np.ndarray] = {}

    def mount(self, hp_name: str, point=None) -> str:
        p = self.hp[hp_name] if point is None else point
        for name, q in self.mount_points.items():
            if np.linalg.norm(q - p) < 1e-9:
                return name
        name = f"{self.axle}_{hp_name}_l"
        self.mount_points[name] = p
        return name

    def part(self, name: str, points) -> Part:
        d = self.parts_data.pop(name, {})
        cm = d.get("cm", np.mean([self.hp[k] for k in points], axis=0))
        return Part(name, float(d.get("mass", 0.0)), cm, d.get("inertia", np.zeros((3, 3))))

    def body_joint(self, kind, part, hp_name, axis=None, axis_b=None) -> Joint:
        bush = self.bushings.pop(hp_name, None)
        if kind == "inline":  # point of the part on a line fixed in the body
            return Joint(hp_name, kind, BODY, part, self.hp[hp_name], axis=axis,
                         mount=self.mount(hp_name), bushing=bush)
        return Joint(hp_name, kind, part, BODY, self.hp[hp_name], axis=axis, axis_b=axis_b,
                     mount=self.mount(hp_name), bushing=bush)

    def arm_pivot(self, part, front, rear) -> list[Joint]:
        axis = self.hp[rear] - self.hp[front]
        return [self.body_joint("spherical", part, front),
                self.body_joint("inline", part, rear, axis=axis)]

    def link(self, name, a, outer, inner, to) -> Link:
        mount = self.mount(inner) if to == BODY else None
        k = None
        bush = self.bushings.pop(inner, None) if to == BODY else None
        if bush is not None:
            if bush.tables:  # a two-force link: only the bushing's rate along it acts
                raise InputError(f"bushing at '{inner}' has nonlinear tables, but it sits at "
                                 f"the body end of the {name}, where only its linear rate "
                                 "along the link acts; give 'stiffness' only",
                                 file=self.file, key=inner)
            u = self.hp[outer] - self.hp[inner]
            u = bush.frame.T @ (u / np.linalg.norm(u))
            k = float(u @ (bush.stiffness[:3] * u))
        return Link(name, a, self.hp[outer], to, self.hp[inner], mount=mount,
                    axial_stiffness=k)

    def forces(self, part, data) -> list[ForceElement]:
        out = []
        for kind, (lo, up) in (("spring", ("spring_lower", "spring_upper")),
                               ("damper", ("damper_lower", "damper_upper")),
                               ("bump_stop", ("damper_lower", "damper_upper")),
                               ("rebound_stop", ("damper_lower", "damper_upper"))):
            d = (data or {}).get(kind)
            if d is None:
                continue
            mount = self.mount(up)
            out.append(ForceElement(kind, kind, part, self.hp[lo], mount, self.hp[up], **d))
        return out

    def finish(self, **kw) -> CornerLinkage:
        if self.bushings:
            k = sorted(self.bushings)[0]
            raise InputError(f"bushing at '{k}', which is no body-side joint of template "
                             f"{self.template}; valid: {', '.join(self.valid_bushings)}",
                             file=self.file, key=k)
        if self.parts_data:
            k = sorted(self.parts_data)[0]
            raise InputError(f"unknown part '{k}' for template {self.template}; valid: "
                             f"{', '.join(PARTS[self.template])}", file=self.file, key=k)
        return CornerLinkage(corner=self.corner, template=self.template, side=1,
                             hardpoints=self.hp, **kw)


def build(template: str, hardpoints: dict, *, axle: str = "front", corner: str = "fl",
          camber_deg: float = 0.0, toe_deg: float = 0.0, wheel_radius: float,
          parts: dict | None = None, bushings: dict | None = None,
          forces: dict | None = None, steered: bool = False,
          universal_axes: tuple | None = None, file=None) -> CornerLinkage:
    """Build the left corner of ``template`` from ``hardpoints``.

    Parameters
    ----------
    template : str
        ``double_wishbone``, ``macpherson`` or ``multi_link`` (see :data:`HARDPOINTS`).
    hardpoints : dict
        ``{name: (x, y, z)}`` of the left side in body coordinates (m).
    axle, corner : str
        Axle name (mount names ``<axle>_<hardpoint>_l``) and corner name.
    camber_deg, toe_deg : float
        Static camber (top out > 0) and toe (toe-in > 0) that set the spin axis.
    wheel_radius : float
        Loaded radius (m): contact patch below the wheel centre.
    parts : dict
        ``{part: {"mass": kg, "cm": (3,), "inertia": 3x3}}``; absent parts are massless
        with the centroid of their hardpoints as cm.
    bushings : dict
        ``{hardpoint: Bushing}`` at body-side joints; a joint stays rigid where absent.
    forces : dict
        ``{"spring"|"damper"|"bump_stop"|"rebound_stop": ForceElement keyword dict}``.
    steered : bool
        The tie rod's inner end is on the steering rack (else on a body mount).
    universal_axes : tuple of two vectors
        Multi-link: the trailing link's universal joint axes (fixed in the link, fixed in
        the body), Chrono's 'Universal Joint Axis Link/Chassis'; default: the body axis
        horizontal and perpendicular to the link, the link axis vertical.
    """
    if template not in HARDPOINTS:
        raise InputError(f"unknown suspension template {template!r}; valid: "
                         f"{', '.join(HARDPOINTS)}", file=file, key="template")
    b = _Builder(template, hardpoints, axle, corner, parts, bushings, file)
    hp = b.hp
    rack_or_body = RACK if steered else BODY
    joints: list[Joint] = []
    links: list[Link] = []
    if template == "double_wishbone":
        lower = b.part("lower_arm", ("lower_arm_front", "lower_arm_rear", "lower_arm_outer"))
        upper = b.part("upper_arm", ("upper_arm_front", "upper_arm_rear", "upper_arm_outer"))
        knuckle = b.part("knuckle", ("lower_arm_outer", "upper_arm_outer", "wheel_center"))
        joints += b.arm_pivot("lower_arm", "lower_arm_front", "lower_arm_rear")
        joints += b.arm_pivot("upper_arm", "upper_arm_front", "upper_arm_rear")
        joints += [Joint("lower_ball_joint", "spherical", "knuckle", "lower_arm",
                         hp["lower_arm_outer"]),
                   Joint("upper_ball_joint", "spherical", "knuckle", "upper_arm",
                         hp["upper_arm_outer"])]
        steer = (("knuckle", hp["lower_arm_outer"]), ("knuckle", hp["upper_arm_outer"]))
        parts_out = (knuckle, lower, upper)
        b.valid_bushings = ("lower_arm_front", "lower_arm_rear", "upper_arm_front",
                            "upper_arm_rear") + (() if steered else ("tie_rod_inner",))
    elif template == "macpherson":
        lower = b.part("lower_arm", ("lower_arm_front", "lower_arm_rear", "lower_arm_outer"))
        knuckle = b.part("knuckle", ("lower_arm_outer", "strut_lower", "wheel_center"))
        joints += b.arm_pivot("lower_arm", "lower_arm_front", "lower_arm_rear")
        joints += [Joint("lower_ball_joint", "spherical", "knuckle", "lower_arm",
                         hp["lower_arm_outer"]),
                   b.body_joint("inline", "knuckle", "strut_top",
                                axis=hp["strut_top"] - hp["strut_lower"])]
        # the strut top is a point of the body on the strut axis fixed in the knuckle
        j = joints[-1]
        joints[-1] = Joint(j.name, "inline", "knuckle", BODY, j.point, axis=j.axis,
                           mount=j.mount, bushing=j.bushing)
        steer = (("knuckle", hp["lower_arm_outer"]), (BODY, hp["strut_top"]))
        parts_out = (knuckle, lower)
        b.valid_bushings = ("lower_arm_front", "lower_arm_rear", "strut_top") + (
            () if steered else ("tie_rod_inner",))
    else:
        upper = b.part("upper_arm", ("upper_arm_front", "upper_arm_rear", "upper_arm_outer"))
        trailing = b.part("trailing_link", ("trailing_link_front", "trailing_link_outer"))
        knuckle = b.part("knuckle", ("upper_arm_outer", "trailing_link_outer",
                                     "wheel_center"))
        d = hp["trailing_link_outer"] - hp["trailing_link_front"]
        if universal_axes is None:
            ab = np.cross([0.0, 0.0, 1.0], d)
            universal_axes = (np.cross(d, ab), ab)
        ua, ub = (np.asarray(v, float) for v in universal_axes)
        joints += b.arm_pivot("upper_arm", "upper_arm_front", "upper_arm_rear")
        joints += [b.body_joint("universal", "trailing_link", "trailing_link_front",
                                axis=ua, axis_b=ub),
                   Joint("upper_ball_joint", "spherical", "knuckle", "upper_arm",
                         hp["upper_arm_outer"]),
                   Joint("trailing_ball_joint", "spherical", "knuckle", "trailing_link",
                         hp["trailing_link_outer"])]
        links.append(b.link("lateral_link", "knuckle", "lateral_link_outer",
                            "lateral_link_inner", BODY))
        steer = (("knuckle", hp["trailing_link_outer"]), ("knuckle", hp["upper_arm_outer"]))
        parts_out = (knuckle, upper, trailing)
        b.valid_bushings = ("upper_arm_front", "upper_arm_rear", "trailing_link_front",
                            "lateral_link_inner") + (() if steered else ("tie_rod_inner",))
    links.append(b.link("tie_rod", "knuckle", "tie_rod_outer", "tie_rod_inner",
                        rack_or_body))
    forces_out = b.forces(SPRING_PART[template], forces)
    return b.finish(parts=parts_out, joints=tuple(joints), links=tuple(links),
                    forces=tuple(forces_out), knuckle="knuckle",
                    wheel_center=hp["wheel_center"], spin_axis=spin_axis(camber_deg, toe_deg),
                    wheel_radius=float(wheel_radius), steer_axis=steer,
                    spring_part=SPRING_PART[template])


def double_wishbone(hardpoints: dict, **kw) -> CornerLinkage:
    """Double wishbone: lower and upper A-arms, knuckle, tie rod; spring on the lower arm."""
    return build("double_wishbone", hardpoints, **kw)


def macpherson(hardpoints: dict, **kw) -> CornerLinkage:
    """MacPherson strut: lower A-arm, knuckle with the strut (its axis through the strut
    top on the body), tie rod; spring and damper on the strut."""
    return build("macpherson", hardpoints, **kw)


def multi_link(hardpoints: dict, **kw) -> CornerLinkage:
    """Multi-link rear (Chrono's Sedan_MultiLink layout): upper A-arm, lateral link,
    trailing link (universal joint at the body, carries the spring and damper seats),
    toe link."""
    return build("multi_link", hardpoints, **kw)


__all__ = ["HARDPOINTS", "Bushing", "build", "double_wishbone", "macpherson", "multi_link",
           "spin_axis"]
