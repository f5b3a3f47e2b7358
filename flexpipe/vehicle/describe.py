"""Text summary of a car file: masses, static corner loads, suspension templates, mounts.

Used by ``flexpipe info CAR.toml``.  Every figure is computed from the file (no run): the
rigid mass properties of the trimmed body, the corner masses (for linkage suspensions the
wheel with every part of the linkage, and the conventional unsprung estimate of
:func:`unsprung_estimate`), the static wheel loads of the whole car at rest,
and for linkage suspensions, per axle at the design position, the spring's motion ratio and
kinematic wheel rate (spring rate x motion ratio^2), the spring preload (virtual work) and
the wheel rate including compliance (bushings, preloaded spring) at two loads: the static
tyre load the time runs preload for, and the K&C rig's (``flexpipe kc``: the axle's
``wheel_load_N`` or the spring's ``preload_N`` / ``free_length_m``) where the file gives
one; then every body-side mount with its interface DOF.  The figures are the K&C rig's
(:func:`flexpipe.vehicle.suspension.statics.corner_figures`), so ``info`` and ``kc`` agree
at the same load.
"""

from __future__ import annotations

import math

from flexpipe.errors import SolverError
from flexpipe.vehicle.spec import CORNERS, Car


def _p(v) -> str:
    return "(" + ", ".join(f"{float(c):.4g}" for c in v) + ")"


def car_text(car: Car) -> str:
    """Human-readable summary of a car (see the module docstring).

    Parameters
    ----------
    car : Car
        The car, as :func:`flexpipe.vehicle.spec.load_car` reads it.

    Returns
    -------
    str
        The summary ``flexpipe info CAR.toml`` prints.
    """
    from flexpipe.vehicle import bodymodel
    from flexpipe.vehicle.corners import static_wheel_loads
    from flexpipe.vehicle.run_inputs import default_step

    rb = bodymodel.rigid_properties(car)
    lines = [f"{car.file}: car '{car.name}'"]
    src = (car.body.mesh if car.body.mesh is not None else
           f"ready body file {car.body.body_file} (its own masses)"
           if car.body.body_file is not None else "[body.rigid] mass properties")
    lines.append(f"  body: {src}; {rb.mass:.2f} kg, centre of mass "
                 f"{_p(rb.center_of_mass)} m, "
                 f"{len(car.body.added_masses)} non-structural masses")
    lines += [f"  {seat.describe()}" for seat in car.body.seats]
    unsprung = [c.unsprung_mass for c in car.corners]
    if car.suspension is None:
        lines.append("  unsprung (per corner, kg): " + ", ".join(
            f"{n} {m:.2f}" for n, m in zip(CORNERS, unsprung, strict=True)))
    else:  # a linkage corner's mass is the wheel and every part of its linkage
        links = car.suspension.corners()
        lines.append("  wheel, knuckle and arms/links, whole (per corner, kg): " + ", ".join(
            f"{n} {m:.2f}" for n, m in zip(CORNERS, unsprung, strict=True)))
        lines.append("  unsprung mass estimate (wheel + knuckle + half of each arm/link "
                     "between body and knuckle; per corner, kg): " + ", ".join(
                         f"{c.name} {unsprung_estimate(links[c.name], c.unsprung_mass):.2f}"
                         for c in car.corners))
    if car.suspension is None:
        N = static_wheel_loads(car, rb.mass, rb.center_of_mass)
        lines.append("  suspension: prismatic corners (hardpoint_m, spring/damper along body z); "
                     f"default time step {1e3 * default_step(car):g} ms")
    else:
        from flexpipe.vehicle.linkage_setup import linkage_statics
        from flexpipe.vehicle.suspension.statics import point_masses

        try:
            susp, N = linkage_statics(car, rb)
            lines.append(f"  suspension: linkage templates, time runs in {susp.mode} mode "
                         f"(default time step {1e3 * default_step(car):g} ms)")
            for name, axle in susp.axles.items():
                lines += _axle_lines(car, name, axle, N[CORNERS.index(axle.left.corner)])
        except SolverError as exc:  # name the file: the corner's [suspension.<axle>]
            raise SolverError(f"{car.file}: static suspension figures: {exc}") from None
        dofs = susp.mount_dofs()
        mounts = susp.mounts()
        lines.append(f"  body mounts ({len(mounts)}; interface DOF 3 = forces, 6 = forces "
                     "and moments):")
        for m, p in mounts.items():
            sf = car.carrier_of(m)
            lines.append(f"    {m:<30} {_p(p)} m  " + (f"on {sf.name}" if sf is not None
                                                        else f"dofs {dofs[m]}"))
        from flexpipe.vehicle.linkage_setup import interface_band

        band = interface_band(car)
        lines.append("  flexible body's mounts: " + (
            "every static mode ([body] interface_band_hz = \"all\")" if math.isinf(band) else
            f"characteristic constraint modes to {band:g} Hz ([body] interface_band_hz)"))
    extra = 0.0 if car.suspension is None else sum(m for m, _ in point_masses(susp)) \
        - sum(unsprung)  # rack and anti-roll-bar arms
    W = 9.81 * (rb.mass + sum(unsprung) + extra + car.mounted_mass)
    lines.append("  static wheel loads (N): " + ", ".join(
        f"{n} {v:.1f}" for n, v in zip(CORNERS, N, strict=True))
        + f"; sum {N.sum():.1f} (car weight {W:.1f})")
    tyres = sorted({c.tire.name + ("" if c.tire_pressure is None else
                                   f" at {c.tire_pressure / 1e3:g} kPa") for c in car.corners})
    lines.append(f"  tyres: {', '.join(tyres)}; "
                 f"steering ratio {car.steering.ratio:g} on the {car.steering.axle} axle; "
                 f"{car.drive.layout}-wheel drive, its torque reacted on the "
                 + ("body (driveshafts)" if car.drive.reaction == "body" else
                    "knuckles (in-wheel motors)"))
    for pt in car.mounted_bodies:
        f, _ = pt.frequencies()
        what = ("takes the drive's reaction" if pt.name == "powertrain" else
                f"carries {', '.join(pt.carries)}")
        lines.append(f"  {pt.name} on mounts: {pt.mass:.1f} kg at {_p(pt.center_of_mass)} m "
                     f"({what}); natural frequencies on its mounts, body held: "
                     f"{', '.join(f'{v:.1f}' for v in f)} Hz")
        for m, p, b in zip(pt.mounts, pt.points, pt.bushings, strict=True):
            lines.append(f"    {m:<30} {_p(p)} m  rates {_p(pt.rates(b)[:3])} N/m")
    if car.drive.reaction_mounts:
        lines.append("  drive reaction through the powertrain mounts (a flexible body's "
                     "interfaces; on a rigid body the couple alone):")
        for m, p in zip(car.drive.reaction_mounts, car.drive.reaction_points, strict=True):
            lines.append(f"    {m:<30} {_p(p)} m")
    return "\n".join(lines)


def unsprung_estimate(linkage, corner_mass: float) -> float:
    """The conventional unsprung mass of a linkage corner.

    The wheel and the knuckle count whole, each part joined both to the body side (body
    or steering rack) and to the wheel side (another part) counts half, a part joined to
    the body side only (a rocker, say) not at all, and any other part whole.

    Parameters
    ----------
    linkage : CornerLinkage
        The corner's linkage (:class:`~flexpipe.vehicle.suspension.model.CornerLinkage`).
    corner_mass : float
        The corner's mass (kg): the wheel and every part of the linkage, as the car file
        reader sums them (``CornerSpec.unsprung_mass``).

    Returns
    -------
    float
        The estimate (kg).
    """
    from flexpipe.vehicle.suspension.model import BODY

    body_side = {BODY, "rack"}
    ends = [(j.a, j.b) for j in linkage.joints] + [(k.a, k.b) for k in linkage.links]
    out = corner_mass
    for part in linkage.parts:
        if part.name == linkage.knuckle:
            continue
        others = [b if a == part.name else a for a, b in ends if part.name in (a, b)]
        to_body = any(o in body_side for o in others)
        to_wheel = any(o not in body_side for o in others)
        share = 0.5 if to_body and to_wheel else (0.0 if to_body else 1.0)
        out -= (1.0 - share) * part.mass
    return out


def _axle_lines(car: Car, name: str, axle, load: float) -> list[str]:
    """Lines of one linkage axle: template, parts, rack and bar, then the spring figures
    of its left corner at the time runs' static tyre ``load`` (N) and at the K&C rig's."""
    from flexpipe.vehicle.suspension.statics import corner_figures, rig_corner, rig_suspension

    c = axle.left
    extra = []
    if axle.rack is not None:
        extra.append(f"steering rack ({axle.rack.travel_per_rev * 1e3:.1f} mm/rev)")
    if axle.anti_roll_bar is not None:
        extra.append(f"anti-roll bar {axle.anti_roll_bar.torsion_rate:g} N m/rad")
    out = [f"    {name}: {c.template}, parts {', '.join(p.name for p in c.parts)}"
           + (f"; {'; '.join(extra)}" if extra else "")]
    if c.spring() is None:
        return out
    fig = corner_figures(c)  # preloaded for the static load (linkage_statics)
    out.append(f"      spring {c.spring().rate:g} N/m, motion ratio "
               f"{fig['spring motion ratio [-]']:.4g}; kinematic wheel rate (spring rate x "
               f"motion ratio^2) {fig['kinematic wheel rate [N/m]']:.0f} N/m")

    def at(label, f):
        return (f"      {label}: spring preload {f['spring preload [N]']:.0f} N, wheel rate "
                f"incl. compliance {f['wheel rate incl. compliance [N/m]']:.0f} N/m, "
                f"joints rigid {f['wheel rate, joints rigid [N/m]']:.0f} N/m")

    mode = car.suspension.mode
    out.append(at(f"at the static tyre load {load:.0f} N (time runs, mode {mode}: the "
                  f"{'joints-rigid' if mode == 'kinematic' else 'incl. compliance'} rate)",
                  fig))
    given = car.suspension.axles[name]
    spring = given.left.spring()
    if given.wheel_load is not None or spring.free_length is not None:
        from flexpipe.vehicle.suspension.carrier import half_carrier, with_subframes

        rig = rig_suspension(with_subframes(car.suspension, car.subframes)).axles[name]
        src = (f"wheel_load_N {given.wheel_load:.0f} N" if given.wheel_load is not None
               else "the spring's preload_N / free_length_m")
        out.append(at(f"on the K&C rig, {src} (flexpipe kc)",
                      corner_figures(rig_corner(rig, rig.left), carrier=half_carrier(rig))))
    return out
