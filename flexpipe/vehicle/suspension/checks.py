"""Checks of a linkage corner's hardpoints that need no kinematics (scale, distance from
the wheel centre, side, distinct points) and of its bushings' rates (:func:`check_bushing`).

Run by :func:`flexpipe.vehicle.suspension.spec.load_suspension` on the left corner as the
car file gives it (after ``location_m``, before mirroring), so that a slip is named by its
key instead of surfacing as a NaN residual or a mount off the body.  Only what is certainly
wrong is refused.
"""

from __future__ import annotations

import numpy as np

from flexpipe.vehicle import limits as lim
from flexpipe.vehicle._toml import Table
from flexpipe.vehicle.suspension.model import BUSHING_DOFS

#: two hardpoints closer than this (m) are one point: arm pivots, link ends and spring
#: seats lie tens to hundreds of millimetres apart and are given to 0.1 mm, so points this
#: close are a copied line, and the axis or member they define is undefined
MIN_SEPARATION_M = 1e-3
#: envelope of a wheel centre in body coordinates (m; origin on the ground, x = 0 at an
#: axle).  z: a wheel centre sits one loaded tyre radius above the ground, 0.2-0.6 m for
#: cars and trucks and about 1 m for the largest agricultural tyres (710/70 R42), so
#: 0 < z <= 3 m.  |y|: half the track, at most 1.3 m for vehicles within the 2.6 m width
#: limit (EU, US), so |y| <= 3 m.  |x|: from the axle at x = 0; the longest rigid road
#: vehicles are about 15 m, so |x| <= 100 m.  A value in millimetres is 1000 times larger.
WHEEL_CENTER_BOX_M = {0: (-100.0, 100.0), 1: (-3.0, 3.0), 2: (0.0, 3.0)}
#: a corner's hardpoints lie within this distance (m) of its wheel centre.  Its longest
#: members are trailing links and arms: the sample's farthest point, the rear trailing
#: link's front pivot, is 0.81 m from its wheel centre, a truck's trailing arm reaches
#: some 1-1.5 m.  A point typed in millimetres lies about 1000 times its distance away
#: (the sample's lower ball joint as [0, 770, -320]: 770 m)
MAX_HARDPOINT_DISTANCE_M = 3.0
#: points carried by the knuckle (the wheel side): y > 0 on a left corner
WHEEL_SIDE = ("wheel_center", "lower_arm_outer", "upper_arm_outer", "tie_rod_outer",
              "strut_lower", "lateral_link_outer", "trailing_link_outer")
#: body-side ends of the arms and links that run across to the knuckle: inboard of the
#: wheel centre (an arm from a pivot outboard of the wheel centre would pass through the
#: wheel to reach the knuckle inside the rim)
INNER_PIVOTS = ("lower_arm_front", "lower_arm_rear", "upper_arm_front", "upper_arm_rear",
                "lateral_link_inner", "tie_rod_inner")
#: pairs of hardpoints that define an axis or a member, per template, with what they define
_COMMON = (("tie_rod_inner", "tie_rod_outer", "the tie rod (a link of zero length)"),
           ("spring_lower", "spring_upper", "the spring's line of action"),
           ("damper_lower", "damper_upper", "the damper's line of action"),
           ("arb_bushing", "arb_arm_end", "the anti-roll bar's arm"),
           ("arb_arm_end", "drop_link_lower", "the anti-roll bar's drop link"))
AXIS_PAIRS = {
    "double_wishbone": (
        ("lower_arm_front", "lower_arm_rear", "the lower arm's pivot axis (revolute joint)"),
        ("upper_arm_front", "upper_arm_rear", "the upper arm's pivot axis (revolute joint)"),
        ("lower_arm_outer", "upper_arm_outer", "the kingpin axis")) + _COMMON,
    "macpherson": (
        ("lower_arm_front", "lower_arm_rear", "the lower arm's pivot axis (revolute joint)"),
        ("strut_lower", "strut_top", "the strut axis"),
        ("lower_arm_outer", "strut_top", "the kingpin axis")) + _COMMON,
    "multi_link": (
        ("upper_arm_front", "upper_arm_rear", "the upper arm's pivot axis (revolute joint)"),
        ("lateral_link_inner", "lateral_link_outer", "the lateral link (a link of zero "
                                                     "length)"),
        ("trailing_link_front", "trailing_link_outer", "the trailing link"),
        ("trailing_link_outer", "upper_arm_outer", "the kingpin axis")) + _COMMON,
}


def _source(name: str, i: int, raw: dict, loc: np.ndarray) -> str:
    """How coordinate ``i`` of hardpoint ``name`` came about, for the message."""
    if loc[i] == 0:
        return f"hardpoints_m.{name}"
    return f"hardpoints_m.{name} {raw[name][i]:g} + location_m {loc[i]:g}"


def check_hardpoints(template: str, hp: dict, raw: dict, loc: np.ndarray, t: Table,
                     hpt: Table) -> None:
    """Refuse hardpoints that are certainly wrong; name the key at fault.

    Parameters
    ----------
    template : str
        Template name (keys of :data:`AXIS_PAIRS`).
    hp : dict
        Left-corner hardpoints in body coordinates (``raw`` + ``loc``), m.
    raw : dict
        The hardpoints as the file gives them, m.
    loc : (3,) array
        ``location_m`` of the axle, m.
    t, hpt : Table
        The axle table ``[suspension.<axle>]`` and its ``hardpoints_m``, for the messages.

    Raises
    ------
    InputError
        A wheel centre outside any road vehicle's envelope (often millimetres), a
        hardpoint far from its wheel centre (:data:`MAX_HARDPOINT_DISTANCE_M`; often
        millimetres), a left corner's point on the right side, an inner pivot outboard of
        the wheel centre, two points that define an axis or member but coincide.
    """
    wc = hp["wheel_center"]
    for i, (lo, hi) in WHEEL_CENTER_BOX_M.items():
        if lo < wc[i] <= hi:
            continue
        axis = "xyz"[i]
        why = (f"wheel centre {axis} = {wc[i]:g} m ({_source('wheel_center', i, raw, loc)}) "
               f"is outside any road vehicle ({lo:g} < {axis} <= {hi:g} m in body "
               "coordinates: z = 0 the ground, x = 0 at an axle)")
        if lo < wc[i] / 1e3 <= hi:
            why += "; the values look like millimetres, but the file's unit is metres"
        elif i == 2 and wc[2] <= 0:
            why += ("; hardpoints given relative to a suspension location need that "
                    "location in location_m")
        # name the key that put it there: the larger of the two contributions
        if abs(loc[i]) > abs(raw["wheel_center"][i]):
            raise t.error("location_m", why)
        raise hpt.error("wheel_center", why)
    _check_distances(hp, raw, loc, hpt)
    right = [k for k, p in hp.items() if p[1] < 0]
    mirrored = (f"; all {len(hp)} hardpoints have y < 0, as the right corner's would: negate "
                "their y") if len(right) == len(hp) else ""
    for name in sorted(hp, key=lambda k: k != "wheel_center"):  # the wheel centre first
        p, wheel = hp[name], name in WHEEL_SIDE
        if p[1] > 0 or (p[1] == 0 and not wheel):
            continue
        where = "on the centre line" if p[1] == 0 else "on the right side"
        raise hpt.error(name, f"y = {p[1]:g} m ({_source(name, 1, raw, loc)}) puts this "
                              f"point of the left corner {where}; the file gives the left "
                              "corner (ISO 8855 body axes: y > 0 is left; the right corner is "
                              f"its mirror image), so '{name}' needs y "
                              f"{'> 0' if wheel else '>= 0'}{mirrored}")
    for name in INNER_PIVOTS:
        if name in hp and hp[name][1] >= wc[1]:
            raise hpt.error(name, f"the body-side pivot '{name}' at y = {hp[name][1]:g} m lies "
                                  f"outboard of the wheel centre (y = {wc[1]:g} m); the body "
                                  "end of an arm or link must be inboard (smaller y) of the "
                                  "wheel it carries")
    for a, b, what in AXIS_PAIRS[template]:
        if a in hp and b in hp and np.linalg.norm(hp[a] - hp[b]) < MIN_SEPARATION_M:
            d = np.linalg.norm(hp[a] - hp[b])
            raise hpt.error(b, f"'{b}' coincides with '{a}' ({d * 1e3:.3g} mm apart): the two "
                               f"define {what}, so they must be distinct points (at least "
                               f"{MIN_SEPARATION_M * 1e3:g} mm apart)")
    if "arb_bushing" in hp and 2 * hp["arb_bushing"][1] < MIN_SEPARATION_M:
        raise hpt.error("arb_bushing", f"y = {hp['arb_bushing'][1]:g} m: the left bar bushing "
                                       "and its mirror image (the right one) coincide, so "
                                       "they define no bar axis; give y > 0")


def _vec(v) -> str:
    return "[" + ", ".join(f"{x:g}" for x in v) + "]"


def _check_distances(hp: dict, raw: dict, loc: np.ndarray, hpt: Table) -> None:
    """Every hardpoint within :data:`MAX_HARDPOINT_DISTANCE_M` of the wheel centre (checked
    for the envelope first), else an error naming the farthest one, its distance and, when
    its values read as millimetres put it near the wheel centre (and some 1000 times
    nearer than as given), the unit slip.  When most points are far and millimetres do not
    explain it, the wheel centre is named instead."""
    wc = hp["wheel_center"]
    dist = {k: float(np.linalg.norm(p - wc)) for k, p in hp.items() if k != "wheel_center"}
    far = sorted((k for k, d in dist.items() if d > MAX_HARDPOINT_DISTANCE_M),
                 key=lambda k: -dist[k])
    if not far:
        return
    as_mm = {k: np.asarray(raw[k]) / 1e3 + loc for k in far}
    d_mm = {k: float(np.linalg.norm(as_mm[k] - wc)) for k in far}
    # millimetres: read so, the point is near the wheel centre and ~1000 times (at least
    # 300 times) nearer than as given; 10 or 100 times is a misplaced decimal point
    mm = {k: d_mm[k] <= MAX_HARDPOINT_DISTANCE_M and dist[k] >= 300 * d_mm[k] for k in far}
    limit = (f"a corner's hardpoints lie within {MAX_HARDPOINT_DISTANCE_M:g} m of its wheel "
             "centre (its longest members, trailing links and arms, reach about 1.5 m)")
    if 2 * len(far) > len(dist) and not all(mm.values()):
        raise hpt.error("wheel_center", f"the wheel centre {_vec(wc)} m is more than "
                                        f"{MAX_HARDPOINT_DISTANCE_M:g} m from {len(far)} of "
                                        f"the corner's {len(dist)} other hardpoints "
                                        f"({', '.join(far)}); {limit}")
    name = far[0]
    where = f"hardpoints_m.{name} = {_vec(raw[name])}" + (
        f" + location_m {_vec(loc)}" if np.any(loc) else "")
    why = (f"'{name}' at {_vec(hp[name])} m ({where}) lies {dist[name]:.4g} m from the wheel "
           f"centre {_vec(wc)} m; {limit}")
    if mm[name]:
        why += (f"; hardpoints are in metres; this looks like millimetres "
                f"({_vec(as_mm[name])} m would be {d_mm[name]:.3g} m from the wheel centre)")
    if len(far) > 1:
        why += f"; also too far: {', '.join(far[1:])}"
    raise hpt.error(name, why)


def check_bushing(t: Table, k: np.ndarray, c: np.ndarray) -> None:
    """Stiffness and damping of a bushing within the bounds of
    :mod:`flexpipe.vehicle.limits` (0 in a direction: free there).

    Parameters
    ----------
    t : Table
        The bushing's table, for the message.
    k, c : (6,) array
        Stiffness and damping, x y z [N/m, N s/m] then rx ry rz [N m/rad, N m s/rad].

    Raises
    ------
    InputError
        Naming the entry, its direction, the valid range and a likely unit slip.
    """
    for key, v, rows in (
            ("stiffness", k, ((lim.BUSHING_STIFFNESS_N_PER_M, "N/m", lim.BUSHING_STIFFNESS_SLIPS),
                              (lim.BUSHING_ROT_STIFFNESS_N_M_PER_RAD, "N m/rad", ()))),
            ("damping", c, ((lim.BUSHING_DAMPING_N_S_PER_M, "N s/m", ()),
                            (lim.BUSHING_ROT_DAMPING_N_M_S_PER_RAD, "N m s/rad", ())))):
        for i, dof in enumerate(BUSHING_DOFS):
            (lo, hi), unit, slips = rows[i // 3]
            if v[i] == 0 or lo <= v[i] <= hi:
                continue
            hint = next((f"; it looks like {name} ({v[i]:g} {name} = {v[i] * f:g} {unit}), "
                         f"but the key's unit is {unit}" for f, name in slips
                         if lo <= v[i] * f <= hi), "")
            valid = f"0 to {hi:g}" if lo == 0 else f"0 (free) or {lo:g} to {hi:g}"
            raise t.error(key, f"entry {i} ({dof}) of '{key}' = {v[i]:g} {unit} is no plausible "
                               f"bushing {key}: valid {valid} {unit} (rubber and hydro "
                               "bushings lie well within; the reasons are in "
                               f"flexpipe/vehicle/limits.py){hint}; got {v.tolist()}")
