"""Kinematics and compliance rig, as Adams/Car's suspension analyses.

Per axle: parallel wheel travel, opposite wheel travel, static steer, and longitudinal and
lateral force compliance at the contact patch.  The body is fixed; wheel travel is the
wheel-centre height change (m) from the design position.  Kinematic quantities come from
the joint/link solution; the wheel rate and the rig force from compliance solves with
bushings (see :mod:`flexpipe.vehicle.suspension.kinematics`): the ``kinematic wheel rate``
is spring rate x motion ratio^2, the ``wheel rate`` (summary: ``wheel rate incl.
compliance``) the slope of the rig force with bushings and the preloaded spring.

The rig's spring preload is the file's (``free_length_m`` / ``preload_N``) or holds the
design position under the axle's ``wheel_load_N``, a tyre load, with the wheel of
``[corners.<c>]`` on the knuckle (:func:`~flexpipe.vehicle.suspension.statics.rig_corner`);
time runs preload for the static loads of the car's mass distribution instead (``flexpipe
info`` prints both).

The steering rack, shared by both corners, enters a single-corner compliance solve as a
spring of half the rack stiffness under lateral forces (both wheels push it the same way)
and as rigid under longitudinal forces (the two tie-rod forces cancel on it).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from tqdm import tqdm

from flexpipe.vehicle.suspension.kinematics import Linkage, solve_compliance, solve_kinematics
from flexpipe.vehicle.suspension.metrics import MIRROR, characteristics, rates, roll_centre
from flexpipe.vehicle.suspension.model import Axle
from flexpipe.vehicle.suspension.statics import corner_figures, rig_corner, rig_suspension


@dataclass
class Table:
    """A result table: ``columns`` (names with units) and ``data`` (rows x columns)."""

    columns: list
    data: np.ndarray

    def __getitem__(self, name: str) -> np.ndarray:
        return self.data[:, self.columns.index(name)]


@dataclass
class KCResult:
    """K&C results: ``tables[<axle>_<analysis>]`` and design-position ``summary``."""

    tables: dict = field(default_factory=dict)
    summary: dict = field(default_factory=dict)


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
    from flexpipe.vehicle.suspension.kinematics import travel_velocity

    v = J @ travel_velocity(lk, pose)
    return phi, (2 * (a - d) @ v) / dg


def parallel_travel(axle: Axle, travel) -> Table:
    """Parallel wheel travel: geometry, motion ratios, wheel rate, roll centre, bump steer."""
    c = rig_corner(axle, axle.left)
    lk, lkc = Linkage(c), Linkage(c)
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
            "kinematic wheel rate [N/m]", "rig force [N]", "roll centre height [mm]",
            "instant centre y [mm]", "instant centre z [mm]", "side view angle [deg]"]
    s_m = data[:, 0] / 1e3
    extra = np.column_stack([np.gradient(data[:, 14], s_m), np.gradient(data[:, 2], s_m),
                             np.gradient(data[:, 1], s_m)])
    return Table(cols + ["wheel rate [N/m]", "bump steer [deg/m]", "camber gain [deg/m]"],
                 np.column_stack([data, extra]))


def opposite_travel(axle: Axle, travel, parallel: Table) -> Table:
    """Opposite wheel travel (left +s, right -s): roll centre, camber, anti-roll bar rate."""
    c = axle.left
    lk = Linkage(c)
    sol = {}
    for s in sorted(set(np.round(np.r_[travel, -np.asarray(travel)], 12))):
        pose = solve_kinematics(lk, s)
        sol[s] = (characteristics(lk, pose), rates(lk, pose),
                  _arb_angle(lk, pose, axle.anti_roll_bar) if axle.anti_roll_bar else (0, 0))
    track = 2 * c.wheel_center[1]
    rows = []
    for s in travel:
        (chl, rl, (phl, dphl)), (chr_, rr, (phr, _)) = sol[round(s, 12)], sol[round(-s, 12)]
        pr, vr = MIRROR @ rr["patch"], MIRROR @ rr["patch_velocity"]
        y, z = roll_centre(rl["patch"], rl["patch_velocity"], pr, vr)
        arb = axle.anti_roll_bar
        f_arb = arb.torsion_rate * (phl - phr) * dphl if arb is not None else 0.0
        rows.append([s * 1e3, np.degrees(np.arctan2(2 * s, track)), chl["camber"],
                     chr_["camber"], chl["toe"], chr_["toe"], z * 1e3, y * 1e3, f_arb])
    data = np.array(rows)
    s_m = data[:, 0] / 1e3
    rate = np.interp(s_m, parallel["wheel travel [mm]"] / 1e3, parallel["wheel rate [N/m]"])
    k_arb = np.gradient(data[:, -1], s_m)
    total = rate + k_arb
    roll = total * track**2 / 2 * np.pi / 180  # N m/deg
    cols = ["wheel travel [mm]", "roll angle [deg]", "camber left [deg]",
            "camber right [deg]", "toe left [deg]", "toe right [deg]",
            "roll centre height [mm]", "roll centre y [mm]", "anti-roll bar force [N]",
            "anti-roll bar wheel rate [N/m]", "wheel rate [N/m]", "roll stiffness [N m/deg]"]
    return Table(cols, np.column_stack([data, k_arb, total, roll]))


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


def force_compliance(axle: Axle, direction: int, forces) -> Table:
    """Toe, camber and wheel-centre motion under a contact-patch force (N, both wheels the
    same way: +x forward, +y left), wheel centre height held."""
    c = rig_corner(axle, axle.left)
    lk = Linkage(c)
    k_rack = None
    if direction == 1 and axle.rack is not None and axle.rack.axial_stiffness is not None:
        k_rack = axle.rack.axial_stiffness / 2
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
        Points per sweep, >= :data:`N_MIN`.
    rack_travel : float
        Rack travel range +- (m) of the static-steer analysis, > 0 and at most
        :data:`RACK_TRAVEL_MAX_M`.
    force : float
        Contact-patch force range +- (N) of the compliance analyses, > 0.
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
    s = np.linspace(-travel, travel, n)
    for name, axle in susp.axles.items():
        if wanted is not None and name not in wanted:
            continue
        par = parallel_travel(axle, s)
        res.tables[f"{name}_parallel_travel"] = par
        res.tables[f"{name}_opposite_travel"] = opp = opposite_travel(axle, s, par)
        if axle.rack is not None:
            res.tables[f"{name}_static_steer"] = static_steer(
                axle, np.linspace(-rack_travel, rack_travel, n))
        fs = np.linspace(-force, force, 9)
        res.tables[f"{name}_longitudinal_force"] = lon = force_compliance(axle, 0, fs)
        res.tables[f"{name}_lateral_force"] = lat = force_compliance(axle, 1, fs)
        res.summary[name] = _summary(axle, par, opp, lon, lat, res.tables.get(
            f"{name}_static_steer"), wheel_mass=given.wheels.get(axle.left.corner, (0.0,))[0])
    if out is not None:
        from flexpipe.vehicle.suspension.kc_output import write

        write(res, Path(out))
    return res


def _summary(axle, par, opp, lon, lat, steer, *, wheel_mass: float = 0.0) -> dict:
    i = int(np.argmin(np.abs(par["wheel travel [mm]"])))
    c = axle.left
    out = {"template": c.template, "camber [deg]": par["camber [deg]"][i],
           "toe [deg]": par["toe [deg]"][i], "caster [deg]": par["caster [deg]"][i],
           "kpi [deg]": par["kpi [deg]"][i], "scrub radius [mm]": par["scrub radius [mm]"][i],
           "camber gain [deg/m]": par["camber gain [deg/m]"][i],
           "bump steer [deg/m]": par["bump steer [deg/m]"][i],
           "roll centre height [mm]": par["roll centre height [mm]"][i],
           "spring motion ratio [-]": par["spring motion ratio [-]"][i],
           "anti-dive/anti-squat angle [deg]": par["side view angle [deg]"][i],
           "kinematic wheel rate [N/m]": par["kinematic wheel rate [N/m]"][i],
           "roll stiffness [N m/deg]": opp["roll stiffness [N m/deg]"][
               int(np.argmin(np.abs(opp["wheel travel [mm]"])))]}
    if c.spring() is not None:  # at the rig's preload (rig_corner), wheel on the knuckle
        fig = corner_figures(rig_corner(axle, c))
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
    if steer is not None:
        mean = (steer["steer left [deg]"] + steer["steer right [deg]"]) / 2
        j = np.abs(steer["rack travel [mm]"]) > 0
        out["steering ratio [-]"] = float(np.median(
            steer["steering wheel angle [deg]"][j] / mean[j]))
    return {k: (float(v) if not isinstance(v, str) else v) for k, v in out.items()}
