"""Text summary of a car file: masses, static corner loads, suspension templates, mounts.

Used by ``flexpipe info CAR.toml``.  Every figure is computed from the file (no run): the
rigid mass properties of the trimmed body, the static wheel loads of the whole car at rest,
for linkage suspensions the spring preloads (virtual work) and the kinematic wheel rate at
the design position, and every body-side mount with its interface DOF.
"""

from __future__ import annotations

from flexpipe.vehicle.spec import CORNERS, Car


def _p(v) -> str:
    return "(" + ", ".join(f"{float(c):.4g}" for c in v) + ")"


def car_text(car: Car) -> str:
    """Human-readable summary of ``car`` (see module docstring)."""
    from flexpipe.vehicle import bodymodel
    from flexpipe.vehicle.corners import static_wheel_loads

    rb = bodymodel.rigid_properties(car)
    lines = [f"{car.file}: car '{car.name}'"]
    src = car.body.mesh if car.body.mesh is not None else "[body.rigid] mass properties"
    lines.append(f"  body: {src}; {rb.mass:.2f} kg, centre of mass "
                 f"{_p(rb.center_of_mass)} m, "
                 f"{len(car.body.added_masses)} non-structural masses")
    unsprung = [c.unsprung_mass for c in car.corners]
    lines.append("  unsprung (per corner, kg): " + ", ".join(
        f"{n} {m:.2f}" for n, m in zip(CORNERS, unsprung, strict=True)))
    if car.suspension is None:
        N = static_wheel_loads(car, rb.mass, rb.center_of_mass)
        lines.append("  suspension: prismatic corners (hardpoint_m, spring/damper along body z)")
    else:
        from flexpipe.vehicle.linkage_setup import linkage_statics
        from flexpipe.vehicle.suspension.statics import point_masses, wheel_rate

        susp, N = linkage_statics(car, rb)
        lines.append(f"  suspension: linkage templates, time runs in {susp.mode} mode")
        for name, axle in susp.axles.items():
            c = axle.left
            sp = c.spring()
            extra = []
            if axle.rack is not None:
                extra.append(f"steering rack ({axle.rack.travel_per_rev * 1e3:.1f} mm/rev)")
            if axle.anti_roll_bar is not None:
                extra.append(f"anti-roll bar {axle.anti_roll_bar.torsion_rate:g} N m/rad")
            lines.append(f"    {name}: {c.template}, parts {', '.join(p.name for p in c.parts)}"
                         + (f"; {'; '.join(extra)}" if extra else ""))
            if sp is not None:
                pre = sp.static_force(sp.design_length)
                lines.append(f"      spring {sp.rate:g} N/m, preload {pre:.0f} N at the design "
                             f"position; wheel rate {wheel_rate(c):.0f} N/m")
        dofs = susp.mount_dofs()
        mounts = susp.mounts()
        lines.append(f"  body mounts ({len(mounts)}; interface DOF 3 = forces, 6 = forces "
                     "and moments):")
        for m, p in mounts.items():
            lines.append(f"    {m:<30} {_p(p)} m  dofs {dofs[m]}")
    extra = 0.0 if car.suspension is None else sum(m for m, _ in point_masses(susp)) \
        - sum(unsprung)  # rack and anti-roll-bar arms
    W = 9.81 * (rb.mass + sum(unsprung) + extra)
    lines.append("  static wheel loads (N): " + ", ".join(
        f"{n} {v:.1f}" for n, v in zip(CORNERS, N, strict=True))
        + f"; sum {N.sum():.1f} (car weight {W:.1f})")
    lines.append(f"  tyres: {', '.join(sorted({c.tire.name for c in car.corners}))}; "
                 f"steering ratio {car.steering.ratio:g} on the {car.steering.axle} axle; "
                 f"{car.drive.layout}-wheel drive")
    return "\n".join(lines)
