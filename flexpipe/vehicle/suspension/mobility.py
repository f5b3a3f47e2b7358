"""Mobility of a corner linkage at its design position: wheel travel and nothing else.

A corner's joints and links must leave the knuckle exactly one degree of freedom (the
wheel travel; the rack is held).  Hardpoints that assemble can still fail that: an arm
whose ball joint lies on its own pivot axis carries nothing (the wheel locks and the arm
spins), a tie rod whose line meets the steering axis holds no steer (the knuckle turns
freely), two links that pass through the same line hold the same motion.  Such a corner
used to run (``flexpipe run``: kilonewtons of hub force on a flat road, or "the implicit
solver did not converge at t = 0" blaming the step) and print figures (``flexpipe info``)
while only ``flexpipe kc`` refused it.

:func:`check_mobility` is run by :func:`flexpipe.vehicle.suspension.spec.load_suspension`
on the left corner as the car file gives it, after the assembly check, so ``run``,
``info`` and ``kc`` refuse the same files with the same message naming file, line,
corner and hardpoint key.  Three tests, the specific ones first:

1. every arm's outer point lies off the arm's pivot axis (:data:`MIN_ARM_OFFSET`);
2. every link on the knuckle (tie rod, toe link, lateral link) has a lever arm about the
   knuckle's rotation it must hold: the steering (kingpin) axis for a tie rod
   (:data:`MIN_LEVER_M`);
3. the general test: the design-position constraint Jacobian of the corner (every joint
   and link on every part, plus the wheel-centre height the K&C rig holds:
   :meth:`flexpipe.vehicle.suspension.kinematics.Linkage.constraints`, the equations the
   kinematics solver and the rig use) is square and must be well conditioned
   (:data:`MIN_SINGULAR`); its nearly dependent constraints are named.
"""

from __future__ import annotations

import numpy as np

from flexpipe.vehicle._toml import Table
from flexpipe.vehicle.suspension.kinematics import Linkage
from flexpipe.vehicle.suspension.model import CornerLinkage

#: arms of each template: front pivot, rear pivot (together the pivot axis), outer point
ARMS = {
    "double_wishbone": (("lower_arm_front", "lower_arm_rear", "lower_arm_outer"),
                        ("upper_arm_front", "upper_arm_rear", "upper_arm_outer")),
    "macpherson": (("lower_arm_front", "lower_arm_rear", "lower_arm_outer"),),
    "multi_link": (("upper_arm_front", "upper_arm_rear", "upper_arm_outer"),),
}
#: an arm's outer point must lie at least this fraction of the arm's length (its longest
#: side, outer point to the farther pivot) off the pivot axis.  The ball joint moves on a
#: circle of that radius: real arms reach out nearly at right angles to their axis
#: (0.88-1.0 in the sample car and Chrono's sedan, MacPherson and Audi corners), 0.2 is an
#: arm within 11.5 deg of its own axis, whose circle (60-80 mm for a 0.3-0.4 m arm) no
#: longer spans the wheel travel; at 0 the arm carries nothing and the wheel locks
MIN_ARM_OFFSET = 0.2
#: the part held to fix the wheel travel when a link's lever is measured: with it held
#: and the link removed, the knuckle has one motion left (for a tie rod: the steer
#: rotation about the kingpin axis)
TRAVEL_PART = {"double_wishbone": "upper_arm", "macpherson": "lower_arm",
               "multi_link": "upper_arm"}
#: a link on the knuckle must change its length by at least this much (m) per radian of
#: the knuckle motion it holds: its lever arm about that axis.  Real steering arms are
#: 100-200 mm (the sample and reference corners: tie rods 132-194 mm, the multi-link's
#: lateral link 141 mm); a 20 mm lever already makes the tie-rod force 7-10 times the
#: usual and the toe stiffness 50-100 times lower; at 0 the steer is free (a mechanism)
MIN_LEVER_M = 0.02
#: smallest singular value of the corner's scaled design-position constraint Jacobian
#: (translations and rotations x L, angle equations x L, L the RMS distance of the
#: corner's hardpoints from their centroid): below it the parts can move 100 times
#: further than the joints open, a mechanism to the solver, with joint loads ~ 1/sigma
#: times the applied ones.  The sample and reference corners have 0.25-0.35; a tie rod
#: with a 20 mm lever or an arm at MIN_ARM_OFFSET still has 0.05-0.12
MIN_SINGULAR = 0.01
#: hardpoint key that places each joint or link that is not named after one
CONSTRAINT_KEYS = {"lower_ball_joint": "lower_arm_outer", "upper_ball_joint": "upper_arm_outer",
                   "trailing_ball_joint": "trailing_link_outer", "tie_rod": "tie_rod_outer",
                   "lateral_link": "lateral_link_outer", "wheel travel": "wheel_center"}
#: the knuckle's rotation each link holds, per template, for the message
_HELD = {"tie_rod": {"double_wishbone": "steering (kingpin) axis, the line through "
                                        "'lower_arm_outer' and 'upper_arm_outer'",
                     "macpherson": "steering (kingpin) axis, the line through "
                                   "'lower_arm_outer' and 'strut_top'",
                     "multi_link": "steering axis (the rotation it has left with the upper "
                                   "arm held and the toe link removed, about an axis "
                                   "through 'upper_arm_outer')"},
         "lateral_link": {"multi_link": "rotation it has left with the upper arm held and "
                                        "the lateral link removed (about an axis through "
                                        "'upper_arm_outer')"}}


def _p(v) -> str:
    return "(" + ", ".join(f"{float(c):.4g}" for c in v) + ")"


def _corner_name(c: CornerLinkage) -> str:
    right = {"fl": "fr", "rl": "rr"}.get(c.corner)
    return f"corner {c.corner}" + (f" (and its mirror image {right})" if right else "")


def constraint_key(name: str) -> str | None:
    """Hardpoint key of constraint ``name`` (``"joint 'upper_ball_joint' (spherical)"``,
    ``"link 'tie_rod'"``, ``"wheel travel"``); None if none places it."""
    inner = name.split("'")[1] if "'" in name else name
    return CONSTRAINT_KEYS.get(inner, inner if " " not in inner else None)


def design_jacobian(corner: CornerLinkage):
    """The corner's constraint Jacobian at the design position, made dimensionless.

    Returns
    -------
    G : (m, 6 n) array
        Rows: :meth:`Linkage.constraints` (joints, links, wheel-centre height); columns:
        each part's translation and rotation x L.  Angle rows (revolute and universal
        axes) are multiplied by L, every other row is a length.
    names : list of str
        Constraint name of each row.
    lk : Linkage
        The compiled linkage (its ``idx`` gives the columns of each part).
    L : float
        RMS distance (m) of the corner's hardpoints from their centroid.
    """
    lk = Linkage(corner)
    _, G, names = lk.constraints(lk.design())
    pts = np.array(list(corner.hardpoints.values()) or [corner.wheel_center])
    L = max(float(np.sqrt(np.mean(np.sum((pts - pts.mean(axis=0)) ** 2, axis=1)))), 1e-3)
    G = G.copy()
    trans = np.zeros(G.shape[1], bool)
    for i in range(lk.n):
        trans[6 * i:6 * i + 3] = True
        G[:, 6 * i + 3:6 * i + 6] /= L
    angle = ~np.any(G[:, trans] != 0, axis=1) & np.any(G != 0, axis=1)
    G[angle] *= L
    return G, names, lk, L


def _arms(c: CornerLinkage):
    hp = c.hardpoints
    for front, rear, outer in ARMS[c.template]:
        a = hp[rear] - hp[front]
        a = a / np.linalg.norm(a)
        r = hp[outer] - hp[front]
        off = float(np.linalg.norm(r - (r @ a) * a))
        length = float(max(np.linalg.norm(r), np.linalg.norm(hp[outer] - hp[rear])))
        if off >= MIN_ARM_OFFSET * length:
            continue
        arm = outer.rsplit("_", 1)[0].replace("_", " ")
        return outer, (f"{_corner_name(c)}: '{outer}' lies {off * 1e3:.1f} mm off the "
                       f"{arm}'s pivot axis (the line through '{front}' and '{rear}'), "
                       f"{off / length:.2f} of the arm's length {length * 1e3:.0f} mm: the "
                       "arm turning about that axis barely moves its ball joint, so it "
                       "cannot carry the knuckle (the wheel locks, the arm spins); the outer "
                       f"point must lie at least {MIN_ARM_OFFSET:g} x the arm's length "
                       f"({MIN_ARM_OFFSET * length * 1e3:.0f} mm) off the axis, as a real "
                       "arm reaches out across it")
    return None


def link_lever(corner: CornerLinkage, link: str):
    """Lever arm (m/rad) of ``link`` about the knuckle motion it holds, at design.

    With the link removed and the arm of :data:`TRAVEL_PART` held, the knuckle has one
    motion left (for a tie rod: the steer rotation about the kingpin axis); the link's
    length changes by the lever arm per radian of it.

    Returns
    -------
    tuple or None
        ``(lever, point, direction)``: lever (m), a point of the knuckle's instantaneous
        axis and its unit direction; None when the rest of the linkage does not leave
        exactly one well-defined motion (the general test names that).
    """
    G, names, lk, L = design_jacobian(corner)
    label = f"link '{link}'"
    if label not in names or corner.template not in TRAVEL_PART:
        return None
    row = G[names.index(label)]
    o = lk.idx[TRAVEL_PART[corner.template]]
    hold = np.zeros((6, G.shape[1]))
    hold[:, 6 * o:6 * o + 6] = np.eye(6)
    keep = [i for i, n in enumerate(names) if n not in (label, "wheel travel")]
    s, vt = np.linalg.svd(np.vstack([G[keep], hold]))[1:]  # more rows than columns
    if s[-1] > 1e-9 * s[0] or s[-2] < MIN_SINGULAR:
        return None
    v = vt[-1]
    k = lk.idx[corner.knuckle]
    w = v[6 * k + 3:6 * k + 6] / L           # rotation, rad per unit of v
    nw = float(np.linalg.norm(w))
    if nw < 1e-12:
        return None
    vel = v[6 * k:6 * k + 3] + np.cross(w, corner.wheel_center - lk.cm0[k])
    point = corner.wheel_center + np.cross(w, vel) / nw**2
    return abs(float(row @ v)) / nw, point, w / nw


def _levers(c: CornerLinkage):
    bad = []
    for lk in c.links:
        if lk.a == c.knuckle and lk.name in _HELD:
            got = link_lever(c, lk.name)
            if got is not None and got[0] < MIN_LEVER_M:
                bad.append((lk.name, *got))
    if not bad:
        return None
    bad.sort(key=lambda b: b[0] != "tie_rod")  # the steering link first
    name, lever, _, axis = bad[0]

    def called(n):  # a multi-link's tie rod is its toe link
        return "toe link" if (n, c.template) == ("tie_rod", "multi_link") else \
            n.replace("_", " ")

    key = CONSTRAINT_KEYS[name]
    inner = key.replace("_outer", "_inner")
    held = _HELD[name].get(c.template, "rotation it holds")
    what = "steer" if name == "tie_rod" else "rotation"
    also = ""
    if len(bad) > 1:  # their lines hold the same motion: either may be the slip
        o = bad[1][0]
        also = (f"; the {called(o)} ('{CONSTRAINT_KEYS[o]}') has a lever of only "
                f"{bad[1][1] * 1e3:.1f} mm about the rotation the knuckle has without it: "
                f"the two hold the same motion, so move '{key}' or '{CONSTRAINT_KEYS[o]}'")
    return key, (f"{_corner_name(c)}: the {called(name)} ('{inner}' -> '{key}') has "
                 f"a lever arm of {lever * 1e3:.1f} mm about the knuckle's {held}, direction "
                 f"{_p(axis)}: its line (nearly) meets that axis, so it does not hold the "
                 f"{what} and the knuckle turns freely (a mechanism); move '{key}' off the "
                 f"axis: the lever must be at least {MIN_LEVER_M * 1e3:g} mm (real steering "
                 f"arms: 100-200 mm){also}")


def _rank(c: CornerLinkage, given: tuple = ()):
    G, names, lk, _ = design_jacobian(c)
    U, s, Vt = np.linalg.svd(G)
    if s[-1] >= MIN_SINGULAR:
        return None
    share: dict[str, float] = {}
    for n, u in zip(names, U[:, -1], strict=True):
        share[n] = share.get(n, 0.0) + float(u * u)
    worst = [n for n, w in sorted(share.items(), key=lambda kv: -kv[1]) if w >= 0.05][:4]
    move = np.linalg.norm(Vt[-1].reshape(lk.n, 6), axis=1)
    parts = [lk.names[i] for i in np.argsort(-move) if move[i] >= 0.2 * move.max()]
    keys = [k for k in dict.fromkeys(constraint_key(n) for n in worst) if k]
    msg = (f"{_corner_name(c)}: the linkage is {'a' if s[-1] < 1e-9 else 'nearly a'} "
           f"mechanism at the design position: with the wheel centre's height held, "
           f"{' and '.join(parts)} can still move while {', '.join(worst)} (nearly "
           f"dependent constraints) barely resist (smallest singular value of the scaled "
           f"constraint Jacobian {s[-1]:.2g}; at least {MIN_SINGULAR:g} is needed, real "
           f"corners have about 0.25-0.35); check the hardpoints "
           f"{', '.join(repr(k) for k in keys)}")
    uni = next((n for n in worst if "(universal)" in n), None)
    if uni is not None:
        msg += ("; a universal joint locks the rotation about the cross product of its two "
                "axes, which must not be perpendicular to the trailing link")
        if "universal_axes" in given:
            return "universal_axes", msg
    return next((k for k in keys if k in c.hardpoints), None), msg


def mobility_problem(corner: CornerLinkage, given: tuple = ()) -> tuple | None:
    """The first of the three tests (module docstring) that ``corner`` fails.

    Parameters
    ----------
    corner : CornerLinkage
        A corner that assembles at the design position.
    given : tuple of str
        Keys of the axle table the file gives (``universal_axes`` is named when given).

    Returns
    -------
    tuple or None
        ``(key, message)``: the hardpoint key (or ``universal_axes``) to name and what is
        wrong with what would be valid; None when the corner passes.
    """
    return _arms(corner) or _levers(corner) or _rank(corner, given)


def check_mobility(corner: CornerLinkage, t: Table, hpt: Table) -> None:
    """Refuse a corner whose linkage is not a one-degree-of-freedom wheel travel.

    Parameters
    ----------
    corner : CornerLinkage
        The left corner as built from the file (it assembles at the design position).
    t, hpt : Table
        The axle table ``[suspension.<axle>]`` and its ``hardpoints_m``, for the messages.

    Raises
    ------
    InputError
        Naming file, line, corner and hardpoint key: an arm's outer point on (or within
        :data:`MIN_ARM_OFFSET` of) its pivot axis; a tie rod, toe link or lateral link
        whose lever about the knuckle rotation it holds is below :data:`MIN_LEVER_M`; any
        other (near) mechanism or locked wheel, with its nearly dependent constraints.
    """
    got = mobility_problem(corner, tuple(t.data))
    if got is None:
        return
    key, msg = got
    if key == "universal_axes":
        raise t.error(key, msg)
    raise hpt.error(key if key in hpt.data else None, msg)


__all__ = ["ARMS", "MIN_ARM_OFFSET", "MIN_LEVER_M", "MIN_SINGULAR", "check_mobility",
           "constraint_key", "design_jacobian", "link_lever", "mobility_problem"]
