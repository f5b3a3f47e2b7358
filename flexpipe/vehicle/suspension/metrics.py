"""Suspension characteristics of a solved pose, in the left-corner convention.

Angles follow SAE/Adams usage for a left wheel (a right corner is mirrored first): camber
> 0 top outboard, toe > 0 toe-in, caster > 0 steer axis top rearward, kingpin inclination
> 0 top inboard, scrub radius > 0 contact patch outboard of the steer axis at the ground,
caster trail > 0 steer axis ahead of the patch.  The contact patch is the point of the wheel
plane at the loaded radius straight below the wheel centre.
"""

from __future__ import annotations

import numpy as np

from flexpipe.vehicle.suspension.kinematics import Linkage, Pose, travel_velocity

MIRROR = np.diag([1.0, -1.0, 1.0])


def _left(lk: Linkage, v):
    return MIRROR @ v if lk.c.side < 0 else np.asarray(v, float)


def angles(spin_axis, lower, upper) -> dict:
    """Camber, toe, caster and KPI (deg) from a left spin axis and steer-axis points."""
    a = spin_axis / np.linalg.norm(spin_axis)
    k = (upper - lower) / np.linalg.norm(upper - lower)
    return {"camber": np.degrees(np.arctan2(-a[2], np.hypot(a[0], a[1]))),
            "toe": np.degrees(np.arctan2(a[0], a[1])),
            "caster": np.degrees(np.arctan2(-k[0], k[2])),
            "kpi": np.degrees(np.arctan2(-k[1], k[2]))}


def contact_patch(wheel_center, spin_axis, radius) -> np.ndarray:
    """Point of the wheel plane at ``radius`` below the wheel centre."""
    a = spin_axis / np.linalg.norm(spin_axis)
    down = np.array([0.0, 0, -1]) - (-a[2]) * a
    return wheel_center + radius * down / np.linalg.norm(down)


def characteristics(lk: Linkage, pose: Pose) -> dict:
    """Geometry of ``pose``: positions (m), angles (deg), lengths (m), left convention."""
    c = lk.c
    w = _left(lk, lk.point(pose, c.knuckle, c.wheel_center)[0])
    a = _left(lk, lk.vector(pose, c.knuckle, c.spin_axis)[0])
    lo = _left(lk, lk.point(pose, *c.steer_axis[0])[0])
    up = _left(lk, lk.point(pose, *c.steer_axis[1])[0])
    out = angles(a, lo, up)
    cp = contact_patch(w, a, c.wheel_radius)
    k = up - lo
    at_ground = lo + k * (cp[2] - lo[2]) / k[2]
    out.update(wheel_center=w, contact_patch=cp, spin_axis=a,
               scrub_radius=cp[1] - at_ground[1], caster_trail=at_ground[0] - cp[0])
    for fe in c.forces:
        if fe.kind in ("spring", "damper") and fe.kind + "_length" not in out:
            p = lk.point(pose, fe.part, fe.point)[0]
            out[fe.kind + "_length"] = float(np.linalg.norm(p - fe.body_point))
    return out


def rates(lk: Linkage, pose: Pose) -> dict:
    """Travel derivatives at a kinematic ``pose``: motion ratios, roll-centre line, paths.

    Returns
    -------
    dict
        ``spring_mr``/``damper_mr`` (-dL/ds), ``patch`` and ``patch_velocity`` (left
        convention, d/ds of the knuckle point at the contact patch), ``ic_y``/``ic_z``
        front-view instant centre (m), ``side_view_angle`` (deg, of the contact-patch
        path: atan(dx/dz), > 0 when the patch moves forward in bump, i.e. the side-view
        swing arm's instant centre lies behind and above it; for forces at the patch
        that is anti-dive at the front but pro-lift at the rear, where anti-lift and
        anti-squat need the patch to move rearward in bump, a negative angle),
        ``wheel_center_velocity``, ``part_dz`` (d z_cm / ds per part).
    """
    c = lk.c
    dx = travel_velocity(lk, pose)
    out = {}
    for fe in c.forces:
        if fe.kind in ("spring", "damper") and fe.kind + "_mr" not in out:
            p, J = lk.point(pose, fe.part, fe.point)
            u = (p - fe.body_point) / np.linalg.norm(p - fe.body_point)
            out[fe.kind + "_mr"] = float(-(u @ (J @ dx)))
    cp0 = lk.contact_patch0()
    p, J = lk.point(pose, c.knuckle, cp0)
    v = _left(lk, J @ dx)
    pl = _left(lk, p)
    wp, Jw = lk.point(pose, c.knuckle, c.wheel_center)
    vw = _left(lk, Jw @ dx)
    # front view: knuckle rotation rate about x and the wheel centre velocity
    omega = dx[6 * lk.idx[c.knuckle] + 3:6 * lk.idx[c.knuckle] + 6]
    if c.side < 0:  # a rotation vector is a pseudo-vector
        omega = -MIRROR @ omega
    wl = _left(lk, wp)
    with np.errstate(divide="ignore", invalid="ignore"):
        ic_y = wl[1] - vw[2] / omega[0]
        ic_z = wl[2] + vw[1] / omega[0]
    out.update(patch=pl, patch_velocity=v, wheel_center_velocity=vw, ic_y=ic_y, ic_z=ic_z,
               side_view_angle=float(np.degrees(np.arctan2(v[0], v[2]))),
               part_dz=np.array([(lk.point(pose, n, lk.cm0[i])[1] @ dx)[2]
                                 for i, n in enumerate(lk.names)]))
    return out


def roll_centre(pl, vl, pr=None, vr=None):
    """Roll centre (y, z) from the contact-patch lines of both sides.

    Each side's line passes through its contact patch perpendicular (front view) to the
    patch velocity, i.e. through the front-view instant centre.  ``pl, vl``: left patch and
    velocity; ``pr, vr``: right ones (default: mirror of the left, symmetric travel).
    """
    if pr is None:
        pr, vr = MIRROR @ pl, MIRROR @ vl
    dl = np.array([-vl[2], vl[1]])
    dr = np.array([-vr[2], vr[1]])
    A = np.column_stack([dl, -dr])
    rhs = np.array([pr[1] - pl[1], pr[2] - pl[2]])
    t = np.linalg.solve(A, rhs)
    return pl[1] + t[0] * dl[0], pl[2] + t[0] * dl[1]
