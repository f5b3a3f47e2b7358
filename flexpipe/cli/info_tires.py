"""``flexpipe info FILE.tir``: a tyre file as flexpipe reads it."""

from __future__ import annotations


def tire_text(path) -> str:
    """Summary of a ``.tir`` file as flexpipe reads it: Magic Formula version (MF 6.x: the
    pressure), size, vertical model, and at FNOMIN the peak friction, slip stiffnesses,
    relaxation lengths and loaded radius (read once: its warnings show once)."""
    import numpy as np

    from flexpipe.tires import read_tir
    from flexpipe.tires.model import tire_from_properties
    from flexpipe.vehicle.corners import static_loaded_radius

    props = read_tir(path)
    tire = tire_from_properties(props)  # what tire_from_file(path) builds, one reading
    mf, fz = tire.mf, props.fnomin
    mux, muy = (float(np.asarray(m)) for m in mf.peak_friction(fz))
    kx, ky = (float(np.asarray(k)) for k in mf.slip_stiffness(fz))
    sk, sa = (float(np.asarray(x)) for x in mf.relaxation_lengths(fz))
    relax = ("no relaxation data" if np.isnan(sk) and np.isnan(sa) else
             f"relaxation lengths {sk * 1e3:.0f} mm (longitudinal), {sa * 1e3:.0f} mm (lateral)")
    width = props.get("DIMENSION", "WIDTH")
    width = ("width not given" if width is None else
             f"width {width * 1e3:.0f} mm" if isinstance(width, float) else
             f"width {width!r} (not a number)")
    version = (f"Magic Formula {props.fittyp / 10:.1f} at {mf.pressure / 1e3:.0f} kPa (NOMPRES "
               f"{mf.nominal_pressure / 1e3:.0f} kPa)" if props.is_mf6 else "Magic Formula 5.2")
    return "\n".join([
        f"{path}: tyre ({props.property_file_format or 'no PROPERTY_FILE_FORMAT'}, "
        f"USE_MODE {props.use_mode}, TYRESIDE {props.tyre_side}); {version}",
        f"  unloaded radius {props.unloaded_radius * 1e3:.1f} mm, {width}; vertical "
        f"stiffness {tire.vertical.k:.4g} N/m, damping {tire.vertical.c:.4g} N s/m",
        f"  at FNOMIN = {fz:.0f} N: peak friction mu_x {mux:.3f}, mu_y {muy:.3f}; slip "
        f"stiffness {kx:.4g} N, cornering stiffness {abs(ky) * np.pi / 180:.4g} N/deg; "
        f"{relax}",
        f"  loaded radius at FNOMIN {static_loaded_radius(tire, fz) * 1e3:.1f} mm",
        *pressure_lines(props)])


def pressure_lines(props) -> list[str]:
    """For an MF 6.x tyre with a pressure range: at FNOMIN and PRESMIN / NOMPRES / PRESMAX,
    the cornering and slip stiffnesses, mu_y and the vertical stiffness (each tyre built
    at that pressure, as a car's ``tire_pressure_Pa`` builds it)."""
    import math

    import numpy as np

    from flexpipe.tires.model import tire_from_properties

    if not props.is_mf6 or props.pressures is None or props.pressure_range is None:
        return []
    p0 = props.pressures[1]
    lo, hi = props.pressure_range
    ps = (lo if lo > 0 else p0, p0, hi if math.isfinite(hi) else p0)
    rows = []
    for p in ps:
        t = tire_from_properties(props, pressure=p)
        kx, ky = (float(np.asarray(k)) for k in t.mf.slip_stiffness(props.fnomin))
        muy = float(np.asarray(t.mf.peak_friction(props.fnomin)[1]))
        rows.append(f"{p / 1e3:.0f} kPa: cornering stiffness {abs(ky) * np.pi / 180:.4g} N/deg, "
                    f"slip stiffness {kx:.4g} N, mu_y {muy:.3f}, vertical stiffness "
                    f"{t.vertical.k:.4g} N/m")
    return ["  at FNOMIN over the pressure range: " + "; ".join(rows)]
