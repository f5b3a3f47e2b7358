"""Kinematics and compliance rig, as Adams/Car's suspension analyses.

Per axle: parallel wheel travel, opposite wheel travel, static steer, and longitudinal and
lateral force compliance at the contact patch.  The body is fixed; wheel travel is the
wheel-centre height change (m) from the design position.  Kinematic quantities come from
the joint/link solution; the wheel rate and the wheel-centre force from compliance solves
with bushings (see :mod:`flexpipe.vehicle.suspension.kinematics`): the ``kinematic wheel
rate`` is spring rate x motion ratio^2, the ``wheel rate`` (summary: ``wheel rate incl.
compliance``) the slope of the wheel-centre force with bushings and the preloaded spring.

The column ``wheel centre vertical force net of unsprung weight [N]`` is the upward force
the rig applies at the wheel centre to hold it at the row's height, with the linkage's
parts and the wheel weightless: the reaction of the spring, bushings and stops.  At the
design position it is the tyre load ``wheel_load_N`` less the weight of the unsprung
parts as it acts at the wheel (virtual work: each part's weight times d z_cm / ds) and
less the small share the deflected bushings carry.

The rig's spring preload is the file's (``free_length_m`` / ``preload_N``) or holds the
design position under the axle's ``wheel_load_N``, a tyre load, with the wheel of
``[corners.<c>]`` on the knuckle (:func:`~flexpipe.vehicle.suspension.statics.rig_corner`);
time runs preload for the static loads of the car's mass distribution instead (``flexpipe
info`` prints both).

The force-compliance analyses start from the rig's static state: wheel centre at the
design height, the spring's preload reacted by the rig, bushings deflected by it, rack
held at its centre.  Their zero-force rows are that state (so toe and camber there differ
from the kinematic design values by the bushings' static deflection), and each patch
force is an increment on it.  The steering rack, shared by both corners, is rigid under
longitudinal forces (the two tie-rod forces cancel on it) and under lateral forces a
spring of half the rack stiffness (both wheels push it the same way) loaded only by the
increment of the tie-rod force: the static tie-rod forces of the two corners are mirror
images and cancel on the rack.

A ``[subframe.<name>]`` carrying some of the axle's mounts (arms, spring seats, rack
housing) rests on its bushings in the compliance analyses: parallel travel and the
longitudinal forces move it in its symmetric motions (x, z, pitch), opposite travel and
the lateral forces in its antisymmetric ones (y, roll, yaw), its half on the left of the
centre plane carrying the left corner (:mod:`flexpipe.vehicle.suspension.carrier`); in
the kinematic ones its bushings are rigid and it stays with the body.  The rig needs the
subframe's bushings in mirror pairs and one subframe per axle.

The summary (:attr:`KCResult.summary`) is evaluated at the design position itself
(travel exactly 0; rates by central differences of :data:`H_DESIGN`), so it does not
depend on the sweep's range or number of points.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from tqdm import tqdm

from flexpipe.vehicle.suspension.carrier import half_carrier
from flexpipe.vehicle.suspension.kinematics import (
    Linkage,
    solve_compliance,
    solve_kinematics,
    travel_velocity,
)
from flexpipe.vehicle.suspension.metrics import MIRROR, characteristics, rates, roll_centre
from flexpipe.vehicle.suspension.model import Axle
from flexpipe.vehicle.suspension.statics import (
    corner_figures,
    rig_corner,
    rig_suspension,
    wheel_rate,
)

#: half-step (m) of the central differences of the summary's rates at the design position
#: (camber gain, bump steer, wheel rate incl. compliance as in
#: :func:`~flexpipe.vehicle.suspension.statics.wheel_rate`)
H_DESIGN = 5e-4
#: column of the parallel-travel table with the rig's vertical force at the wheel centre
WHEEL_CENTRE_FORCE = "wheel centre vertical force net of unsprung weight [N]"


@dataclass
class Table:
    """A result table: ``columns`` (names with units) and ``data`` (rows x columns)."""

    columns: list
    data: np.ndarray

    def __getitem__(self, name: str) -> np.ndarray:
        return self.data[:, self.columns.index(name)]


@dataclass
class KCResult:
    """K&C results: ``tables[<axle>_<analysis>]``, design-position ``summary`` and per
    axle the ``[subframe.<name>]`` its compliance analyses rest on (``subframes``, None
    without)."""

    tables: dict = field(default_factory=dict)
    summary: dict = field(default_factory=dict)
    subframes: dict = field(default_factory=dict)


def _arb_angle(lk: Linkage, pose, arb, phi0=0.0):
    """Arm angle (rad) of the left anti-roll-bar arm about the bar axis (y) and d/ds."""
    b, a0 = arb.bushing, arb.arm_end
    d, J = lk.point(pose, arb.part, arb.drop_link_lower)
    L0 = np.linalg.norm(a0 - arb.drop_link_lower)
    y = np.array([0.0, 1.0, 0.0])
    phi = phi0
    for _ in range(50):
        c, s = np.cos(phi), np.sin(phi)
        r = a0 - b
        a = b + np.array([c * r[0] + s * r[2], r[1], -s * r[0] + c * r[2]])
        g = (a - d) @ (a - d) - L0**2
        dg = 2 * (a - d) @ np.cross(y, a - b)
        step = g / dg
        phi -= step
        if abs(step) < 1e-14:
            break
    v = J @ travel_velocity(lk, pose)
    return phi, (2 * (a - d) @ v) / dg


def parallel_travel(axle: Axle, travel) -> Table:
    """Parallel wheel travel: geometry, motion ratios, wheel rate, roll centre, bump steer."""
    c = rig_corner(axle, axle.left)
    lk, lkc = Linkage(c), Linkage(c, carrier=half_carrier(axle), mode="symmetric")
    rows, pose, cpose = [], None, None
    for s in tqdm(travel, desc=f"{axle.name} parallel travel", leave=False):
        pose = solve_kinematics(lk, s, pose=pose)
        ch, r = characteristics(lk, pose), rates(lk, pose)
        cpose = solve_compliance(lkc, s, pose=cpose)
        rc = roll_centre(r["patch"], r["patch_velocity"])
        spring = c.spring()
        k_kin = spring.rate * r["spring_mr"] ** 2 if spring is not None else np.nan
        rows.append([s * 1e3, ch["camber"], ch["toe"], ch["caster"], ch["kpi"],
                     ch["scrub_radius"] * 1e3, ch["caster_trail"] * 1e3,
                     (ch["wheel_center"][0] - c.wheel_center[0]) * 1e3,
                     (ch["wheel_center"][1] - c.wheel_center[1]) * 1e3,
                     ch.get("spring_length", np.nan) * 1e3, ch.get("damper_length", np.nan) * 1e3,
                     r.get("spring_mr", np.nan), r.get("damper_mr", np.nan), k_kin,
                     cpose.force, rc[1] * 1e3, r["ic_y"] * 1e3, r["ic_z"] * 1e3,
                     r["side_view_angle"]])
    data = np.array(rows)
    cols = ["wheel travel [mm]", "camber [deg]", "toe [deg]", "caster [deg]", "kpi [deg]",
            "scrub radius [mm]", "caster trail [mm]", "wheel center x [mm]",
            "wheel center y [mm]", "spring length [mm]", "damper length [mm]",
            "spring motion ratio [-]", "damper motion ratio [-]",
            "kinematic wheel rate [N/m]", WHEEL_CENTRE_FORCE, "roll centre height [mm]",
            "instant centre y [mm]", "instant centre z [mm]", "side view angle [deg]"]
    s_m = data[:, 0] / 1e3
    extra = np.column_stack([np.gradient(data[:, 14], s_m), np.gradient(data[:, 2], s_m),
                             np.gradient(data[:, 1], s_m)])
    return Table(cols + ["wheel rate [N/m]", "bump steer [deg/m]", "camber gain [deg/m]"],
                 np.column_stack([data, extra]))


def opposite_travel(axle: Axle, travel, parallel: Table) -> Table:
    """Opposite wheel travel (left +s, right -s): roll centre, camber, roll stiffness.

    The roll moment is ``M = (F_l - F_r) t / 2`` (``F`` the vertical wheel-centre forces,
    ``t`` the wheel-centre track) at the roll angle ``atan(2 s / t)``, so the roll
    stiffness is ``dM/droll = (k_l(s) + k_r(-s) + k_bar) t^2 / 4`` per radian, with
    ``k_l(s)`` and ``k_r(-s)`` each wheel's rate at its own travel (the right corner is the
    mirror image of the left, so ``k_r(-s)`` is the left corner's rate at ``-s``, read from
    ``parallel``) and ``k_bar = d(f_l - f_r)/ds`` the anti-roll bar's share: the bar's
    forces on the two wheels, ``f = k_t (phi_own - phi_other) dphi_own/ds``, from its twist
    ``phi_l - phi_r``.  A left-right symmetric axle gives the same roll stiffness at
    ``+s`` and ``-s``; at the design position it is ``(k + 2 k_t (dphi/ds)^2) t^2 / 2``.
    The roll angle is taken as ``2 s / t`` in the derivative (the exact ``atan`` makes the
    stiffness ``1 + (2 s / t)^2`` times larger: 1 % at 80 mm on the sample's 1.6 m
    tracks).  The slopes are :func:`numpy.gradient` of the sweep, as in
    :func:`parallel_travel`; :func:`design_figures` gives the design value by
    derivatives at the design position.

    Parameters
    ----------
    axle : Axle
        The axle.
    travel : array_like
        Left wheel travel (m), symmetric about 0 (the right wheel runs through ``-travel``).
    parallel : Table
        :func:`parallel_travel` of the axle over at least ``travel`` and ``-travel``: its
        ``wheel rate [N/m]`` column is each wheel's rate.

    Returns
    -------
    Table
        Per row: travel, roll angle, camber and toe of both wheels, roll centre, the bar's
        forces on both wheels, its rate per wheel (``k_bar / 2``), both wheels' rates and
        the roll stiffness.
    """
    c = axle.left
    lk = Linkage(c)
    sol = {}
    for s in sorted(set(np.round(np.r_[travel, -np.asarray(travel)], 12))):
        pose = solve_kinematics(lk, s)
        sol[s] = (characteristics(lk, pose), rates(lk, pose),
                  _arb_angle(lk, pose, axle.anti_roll_bar) if axle.anti_roll_bar else (0, 0))
    track = 2 * c.wheel_center[1]
    arb = axle.anti_roll_bar
    rows = []
    for s in travel:
        (chl, rl, (phl, dphl)), (chr_, rr, (phr, dphr)) = sol[round(s, 12)], sol[round(-s, 12)]
        pr, vr = MIRROR @ rr["patch"], MIRROR @ rr["patch_velocity"]
        y, z = roll_centre(rl["patch"], rl["patch_velocity"], pr, vr)
        f_l = arb.torsion_rate * (phl - phr) * dphl if arb is not None else 0.0
        f_r = arb.torsion_rate * (phr - phl) * dphr if arb is not None else 0.0
        rows.append([s * 1e3, np.degrees(np.arctan2(2 * s, track)), chl["camber"],
                     chr_["camber"], chl["toe"], chr_["toe"], z * 1e3, y * 1e3, f_l, f_r])
    data = np.array(rows)
    s_m = data[:, 0] / 1e3
    s_par, k_par = parallel["wheel travel [mm]"] / 1e3, parallel["wheel rate [N/m]"]
    carrier = half_carrier(axle)
    if carrier is not None:   # a subframe rolls and yaws on its bushings here
        lkc, pose, force = Linkage(rig_corner(axle, c), carrier=carrier,
                                   mode="antisymmetric"), None, []
        for s in s_par:
            pose = solve_compliance(lkc, s, pose=pose)
            force.append(pose.force)
        k_par = np.gradient(np.array(force), s_par)
    k_l, k_r = np.interp(s_m, s_par, k_par), np.interp(-s_m, s_par, k_par)
    k_arb = np.gradient(data[:, -2] - data[:, -1], s_m) / 2 if len(s_m) > 1 else \
        np.zeros(len(s_m))
    roll = (k_l + k_r + 2 * k_arb) * track**2 / 4 * np.pi / 180  # N m/deg
    cols = ["wheel travel [mm]", "roll angle [deg]", "camber left [deg]",
            "camber right [deg]", "toe left [deg]", "toe right [deg]",
            "roll centre height [mm]", "roll centre y [mm]", "anti-roll bar force left [N]",
            "anti-roll bar force right [N]", "anti-roll bar wheel rate [N/m]",
            "wheel rate left [N/m]", "wheel rate right [N/m]", "roll stiffness [N m/deg]"]
    return Table(cols, np.column_stack([data, k_arb, k_l, k_r, roll]))


def static_steer(axle: Axle, rack_travel) -> Table:
    """Static steer at design height: road-wheel angles (left turn > 0) vs rack travel."""
    rows = []
    lkl, lkr = Linkage(axle.left), Linkage(axle.right)
    pl = pr = None
    for x in rack_travel:
        pl = solve_kinematics(lkl, 0.0, rack=x, pose=pl)
        pr = solve_kinematics(lkr, 0.0, rack=x, pose=pr)
        cl, cr = characteristics(lkl, pl), characteristics(lkr, pr)
        wheel = np.degrees(axle.rack.wheel_angle_rad(x))
        rows.append([x * 1e3, wheel, -cl["toe"], cr["toe"], cl["caster"], cl["kpi"],
                     cl["scrub_radius"] * 1e3])
    cols = ["rack travel [mm]", "steering wheel angle [deg]", "steer left [deg]",
            "steer right [deg]", "caster left [deg]", "kpi left [deg]",
            "scrub radius left [mm]"]
    return Table(cols, np.array(rows))


class _RackPreloadLinkage(Linkage):
    """A :class:`Linkage` whose rack, when it is an unknown, also carries the constant
    force ``rack_preload`` (N, along the rack axis): the rack spring of a compliance solve
    then reacts only the change of the tie-rod force from the state that preload holds."""

    rack_preload = 0.0

    def forces(self, pose, **kw) -> np.ndarray:
        Q = super().forces(pose, **kw)
        if self.rack_free:
            Q[-1] += self.rack_preload
        return Q


def _rack_reaction(lk: Linkage, pose) -> float:
    """Force (N, along the rack axis) the corner's tie rod puts on the held rack in the
    compliance equilibrium ``pose`` (rack rigid): the generalised force on the rack
    coordinate of the elastic elements and of the constraint forces that balance the
    parts (least squares for the multipliers of the parts' equilibrium)."""
    lk.rack_free = True
    try:
        _, Gm, _ = lk.constraints(pose, compliant=True)
        Q = lk.forces(pose)
    finally:
        lk.rack_free = False
    lam = np.linalg.lstsq(Gm[:, :-1].T, -Q[:-1], rcond=None)[0]
    return float(Q[-1] + Gm[:, -1] @ lam)


def force_compliance(axle: Axle, direction: int, forces) -> Table:
    """Toe, camber and wheel-centre motion under a contact-patch force.

    Parameters
    ----------
    axle : Axle
        The axle; its left corner is solved, as the rig holds it (:func:`rig_corner`).
    direction : int
        0: longitudinal force (+x forward), 1: lateral (+y left); both wheels are pushed
        the same way.
    forces : array_like
        Contact-patch forces (N), added to the rig's static state (wheel centre at the
        design height, spring preload reacted, bushings deflected).

    Returns
    -------
    Table
        Per force: toe, camber, wheel-centre motion from design and rack travel.  Under
        a lateral force with a compliant column the rack is a spring of half the rack
        stiffness loaded by the change of the tie-rod force only (the two corners'
        static tie-rod forces cancel on the rack), so the zero-force row is the same
        static state in both directions.
    """
    c = rig_corner(axle, axle.left)
    lk = _RackPreloadLinkage(c, carrier=half_carrier(axle),
                             mode="symmetric" if direction == 0 else "antisymmetric")
    k_rack = None
    if direction == 1 and axle.rack is not None and axle.rack.axial_stiffness is not None:
        k_rack = axle.rack.axial_stiffness / 2
        # the rack spring starts in equilibrium with the static tie-rod force
        lk.rack_preload = -_rack_reaction(lk, solve_compliance(lk, 0.0))
    rows, pose = [], None
    for f in forces:
        F = np.zeros(3)
        F[direction] = f
        pose = solve_compliance(lk, 0.0, patch_force=F, rack_stiffness=k_rack, pose=pose)
        ch = characteristics(lk, pose)
        w = lk.point(pose, c.knuckle, c.wheel_center)[0] - c.wheel_center
        rows.append([f, ch["toe"], ch["camber"], w[0] * 1e3, w[1] * 1e3, pose.rack * 1e3])
    cols = ["force [N]", "toe [deg]", "camber [deg]", "wheel center dx [mm]",
            "wheel center dy [mm]", "rack travel [mm]"]
    return Table(cols, np.array(rows))


def sweep(travel: float, n: int) -> np.ndarray:
    """The wheel-travel sweep (m): ``n`` evenly spaced points from ``-travel`` to
    ``travel``, exactly antisymmetric (so every point's opposite is in it, and the middle
    point of an odd ``n`` is exactly the design position, travel 0)."""
    s = travel * np.linspace(-1.0, 1.0, n)
    return (s - s[::-1]) / 2


def kc(car, *, out=None, travel: float = 0.08, n: int = 33, rack_travel: float = 0.03,
       force: float = 2000.0, axles=None) -> KCResult:
    """Run the K&C rig on every axle of ``car`` (a car file path, a ``Car`` or a
    ``Suspension``).

    Parameters
    ----------
    car : str, Path, Car or Suspension
        Car file with ``[suspension.*]`` tables, the :class:`~flexpipe.vehicle.spec.Car`
        :func:`~flexpipe.load_car` returns for one, or its parsed suspension; the wheels
        its ``[corners.<c>]`` tables give (``wheel_mass_kg``) hang on the knuckles.
    out : str or Path, optional
        Folder for CSV tables, ``kc_summary.json`` and PNG plots; checked before the
        analysis (it must be a folder or creatable).
    travel : float
        Wheel travel range +- (m), > 0 and at most :data:`TRAVEL_MAX_M`.
    n : int
        Points of the wheel-travel and rack-travel sweeps, >= :data:`N_MIN`, evenly spaced
        over ``-travel .. travel`` (:func:`sweep`; an odd ``n`` includes the design
        position).  The summary does not depend on it (nor on ``travel``): it is
        evaluated at the design position itself.
    rack_travel : float
        Rack travel range +- (m) of the static-steer analysis, > 0 and at most
        :data:`RACK_TRAVEL_MAX_M`.
    force : float
        Contact-patch force range +- (N) of the compliance analyses (9 points), > 0.
    axles : str or list of str, optional
        Axles to run (default all), e.g. ``["front"]``; case-insensitive.

    Returns
    -------
    KCResult

    Raises
    ------
    InputError
        A bad argument, named with what would be valid (before any analysis).
    """
    from flexpipe.vehicle.suspension.kc_args import check_kc_arguments

    given, travel, n, rack_travel, force, wanted = check_kc_arguments(
        car, out=out, travel=travel, n=n, rack_travel=rack_travel, force=force, axles=axles)
    susp = rig_suspension(given)  # the wheels of [corners.<c>] on the knuckles
    res = KCResult()
    s = sweep(travel, n)
    for name, axle in susp.axles.items():
        if wanted is not None and name not in wanted:
            continue
        par = parallel_travel(axle, s)
        res.tables[f"{name}_parallel_travel"] = par
        res.tables[f"{name}_opposite_travel"] = opposite_travel(axle, s, par)
        if axle.rack is not None:
            res.tables[f"{name}_static_steer"] = static_steer(axle, sweep(rack_travel, n))
        fs = sweep(force, 9)
        res.tables[f"{name}_longitudinal_force"] = lon = force_compliance(axle, 0, fs)
        res.tables[f"{name}_lateral_force"] = lat = force_compliance(axle, 1, fs)
        res.summary[name] = _summary(
            axle, lon, lat, wheel_mass=given.wheels.get(axle.left.corner, (0.0,))[0])
        carrier = half_carrier(axle)
        res.subframes[name] = carrier.name if carrier is not None else None
    if out is not None:
        from flexpipe.vehicle.suspension.kc_output import write

        label = Path(car).name if isinstance(car, (str, Path)) else str(
            getattr(car, "name", "") or "")
        write(res, Path(out), car=label)
    return res


def design_figures(axle: Axle, *, h: float = H_DESIGN) -> dict:
    """Kinematic and elastic figures of ``axle``'s left corner at the design position.

    Parameters
    ----------
    axle : Axle
        The axle as on the rig (its wheels on the knuckles, :func:`rig_suspension`).
    h : float
        Half-step (m) of the central differences in wheel travel.

    Returns
    -------
    dict
        Angles and lengths at travel exactly 0; camber gain and bump steer (deg/m) by
        central differences of kinematic solves at +-``h``; roll-centre height, motion
        ratio and side-view angle from the travel derivatives of the joint solution; the
        roll stiffness ``(k + k_bar) t^2 / 2`` (N m/deg), with ``k`` the wheel rate incl.
        compliance (:func:`~flexpipe.vehicle.suspension.statics.wheel_rate`), ``k_bar =
        2 k_t (dphi/ds)^2`` the anti-roll bar's rate per wheel in opposite travel and ``t``
        the wheel-centre track.
    """
    c = rig_corner(axle, axle.left)
    lk = Linkage(c)
    pose = solve_kinematics(lk, 0.0)
    ch, r = characteristics(lk, pose), rates(lk, pose)
    lo, hi = (characteristics(lk, solve_kinematics(lk, x, pose=pose)) for x in (-h, h))
    spring = c.spring()
    k_bar = 0.0
    if axle.anti_roll_bar is not None:
        _, dphi = _arb_angle(lk, pose, axle.anti_roll_bar)
        k_bar = 2 * axle.anti_roll_bar.torsion_rate * dphi**2
    # the rate in opposite travel: with a subframe, it rolls on its bushings
    k = wheel_rate(c, 0.0, h=h, carrier=half_carrier(axle), mode="antisymmetric")
    track = 2 * c.wheel_center[1]
    return {"camber [deg]": ch["camber"], "toe [deg]": ch["toe"], "caster [deg]": ch["caster"],
            "kpi [deg]": ch["kpi"], "scrub radius [mm]": ch["scrub_radius"] * 1e3,
            "camber gain [deg/m]": (hi["camber"] - lo["camber"]) / (2 * h),
            "bump steer [deg/m]": (hi["toe"] - lo["toe"]) / (2 * h),
            "roll centre height [mm]": roll_centre(r["patch"], r["patch_velocity"])[1] * 1e3,
            "spring motion ratio [-]": r.get("spring_mr", np.nan),
            "patch side-view angle [deg]": r["side_view_angle"],
            # > 0 resists pitch: anti-dive at the front (patch forward in bump), anti-lift
            # and, with the drive at the patch, anti-squat at the rear (patch rearward)
            "anti-dive (front) / anti-lift (rear) angle [deg]": (
                r["side_view_angle"] if axle.name == "front" else -r["side_view_angle"]),
            "kinematic wheel rate [N/m]": (spring.rate * r["spring_mr"] ** 2
                                           if spring is not None else np.nan),
            "roll stiffness [N m/deg]": (k + k_bar) * track**2 / 2 * np.pi / 180}


def _summary(axle, lon, lat, *, wheel_mass: float = 0.0) -> dict:
    """Summary of one axle at the design position: :func:`design_figures`, the spring,
    the compliances (slopes of the force tables, which do not depend on the sweeps'
    points) and the on-centre overall steering ratio (steering-wheel angle per mean
    road-wheel angle for rack travel +-:data:`H_DESIGN` about the centre)."""
    c = axle.left
    out = {"template": c.template, **design_figures(axle)}
    if c.spring() is not None:  # at the rig's preload (rig_corner), wheel on the knuckle
        fig = corner_figures(rig_corner(axle, c), carrier=half_carrier(axle))
        if axle.wheel_load is not None:
            out["wheel load [N]"] = axle.wheel_load
        out["wheel mass [kg]"] = wheel_mass
        out["spring preload [N]"] = fig["spring preload [N]"]
        out["wheel rate incl. compliance [N/m]"] = fig["wheel rate incl. compliance [N/m]"]
    f = lon["force [N]"]
    out["longitudinal toe compliance [deg/kN]"] = np.polyfit(f, lon["toe [deg]"], 1)[0] * 1e3
    out["longitudinal wheel centre compliance [mm/kN]"] = np.polyfit(
        f, lon["wheel center dx [mm]"], 1)[0] * 1e3
    out["lateral toe compliance [deg/kN]"] = np.polyfit(f, lat["toe [deg]"], 1)[0] * 1e3
    out["lateral camber compliance [deg/kN]"] = np.polyfit(f, lat["camber [deg]"], 1)[0] * 1e3
    if axle.rack is not None:  # on centre: d(steering-wheel angle) / d(mean road-wheel angle)
        st = static_steer(axle, np.array([-H_DESIGN, H_DESIGN]))
        mean = (st["steer left [deg]"] + st["steer right [deg]"]) / 2
        out["steering ratio [-]"] = float(np.diff(st["steering wheel angle [deg]"])[0]
                                          / np.diff(mean)[0])
    # + 0.0: a zero angle prints as 0, not -0
    return {k: (float(v) + 0.0 if not isinstance(v, str) else v) for k, v in out.items()}
