"""``flexpipe info FILE``: summary of a FlexBody (.npz), a car, road or path file (.toml,
a road also .crg) or a mesh file.

For a FlexBody it prints the reduced-vs-full frequency table, the MAC matrix and mass
properties (see :func:`flexpipe.cli.reduce.info_text`) and can write the mode shapes as
.vtu; for a mesh it lists nodes, element blocks, named sets, carried properties, constraints,
the solution set-up of a solver deck, and what the reader read, converted (e.g. CQUAD8
into CQUAD4) and dropped (loads, output requests, unknown cards).  A TOML file is told by
its tables (:func:`toml_kind`): a car (``[car]``) is described by
:func:`flexpipe.vehicle.describe.car_text`, a road (``[road]``) and a path (``[path]``)
by their length, samples and extent; any other TOML file (a sweep, a driver, the
half-car parameters) is a one-line error saying what it is and what ``info`` takes.
"""

from __future__ import annotations

from pathlib import Path


def add_arguments(p) -> None:
    """Options of ``flexpipe info``."""
    from flexpipe.cli.reduce import add_info_arguments

    add_info_arguments(p, what=f"file to describe: {TAKES}")
    p.add_argument("--scale", type=float, default=1.0, help="mesh length scale (mesh files)")
    p.add_argument("--units", help="unit system of a solver deck, e.g. mm-t-s (mesh files; "
                   "converts lengths, E, rho and masses)")


#: what ``flexpipe info`` describes (for --help and errors)
TAKES = ("a reduced body (.npz from flexpipe reduce), a car file (.toml with a [car] "
         "table, e.g. cars/sedan.toml), a road (.toml with a [road] table, .crg, .csv) or "
         "path (.toml with a [path] table, .csv) file, a tyre (.tir), or a mesh (.bdf, "
         ".inp, .msh, .vtu, ...)")

#: TOML files info does not describe: (tables that tell them, what they are, their use),
#: tried in order.  Any file with a [sweep] table is a sweep, whatever its design (a grid
#: or Latin hypercube has [parameters], a list [[runs]]), but the half-car parameters
#: (cars/halfcar_paper.toml) carry a [sweep] table beside [table1], so [table1] comes first.
_OTHER_TOML = (
    (("table1",), "half-car parameter", "read by flexpipe.halfcar.params.load_params for "
                                        "make paper"),
    (("sweep",), "sweep", "run it with flexpipe sweep FILE"),
    (("steering", "speed"), "driver", "read by simulate(..., driver=FILE)"),
)


def toml_kind(doc: dict) -> str:
    """What a parsed TOML file is, from its top-level tables: ``"car"``, ``"road"``,
    ``"path"``, ``"sweep"``, ``"half-car parameter"``, ``"driver"`` or ``""``
    (unknown)."""
    if "car" in doc:
        return "car"
    for tables, kind, _ in _OTHER_TOML:
        if all(t in doc for t in tables):
            return kind
    if "road" in doc:  # load_road names any other table beside it
        return "road"
    if "path" in doc:
        return "path"
    return ""


def toml_text(path) -> str:
    """The summary of a TOML car, road or path file (see :func:`toml_kind`).

    Raises
    ------
    InputError
        Any other TOML file, saying what it is and what ``flexpipe info`` takes.
    """
    from flexpipe.errors import InputError
    from flexpipe.roads._tables import read_toml

    path = Path(path)
    doc = read_toml(path)
    kind = toml_kind(doc)
    if kind == "car":
        from flexpipe.vehicle.describe import car_text
        from flexpipe.vehicle.mounts import check_mount_node_ids
        from flexpipe.vehicle.spec import load_car

        car = load_car(path)
        check_mount_node_ids(car)  # mount node ids of the mesh, as a flexible run checks
        text = car_text(car)
        if car.suspension is None:  # what a run would refuse, as a warning under the text
            import warnings

            from flexpipe.vehicle.run_inputs import _check_ride_height

            try:
                _check_ride_height(car)
            except InputError as exc:
                warnings.warn(f"flexpipe run refuses this car: {exc}", stacklevel=2)
        return text
    if kind == "road":
        from flexpipe.roads import load_road

        return road_text(load_road(path), file=path, table=doc["road"])
    if kind == "path":
        from flexpipe.driver import read_path

        return path_text(read_path(path), file=path, table=doc["path"])
    use = next((u for _, k, u in _OTHER_TOML if k == kind), None)
    what = (f"is a {kind} file, not a car, mesh or body file ({use})" if kind else
            f"is not a car, road or path file: it has no [car], [road] or [path] table "
            f"(top-level keys: {sorted(doc) or 'none'})")
    raise InputError(f"{what}; flexpipe info takes {TAKES}", file=path)


def _spec_line(table: dict) -> str:
    return "  spec: " + ", ".join(f"{k} = {v!r}" for k, v in table.items())


def road_text(road, *, file=None, table: dict | None = None) -> str:
    """Human-readable summary of a :class:`~flexpipe.roads.Road` read from ``file``
    (``table``: its ``[road]`` spec, when it came from a TOML file)."""
    import numpy as np

    lines = [f"{file or road.source or road.name}: road {road.source or road.name}",
             f"  {road.length:.6g} m long "
             f"(x {road.x[0]:.6g} .. {road.x[-1]:.6g} m), {road.x.size} samples every "
             f"{road.dx:.4g} m, track width {road.track_width:.4g} m"]
    for side, z in (("left", road.left), ("right", road.right)):
        lines.append(f"  {side} track height (mm): min {1e3 * z.min():.2f}, max "
                     f"{1e3 * z.max():.2f}, RMS about the mean "
                     f"{1e3 * np.std(z):.2f}")
    if road.y is not None:
        lines.append(f"  height grid: {road.y.size} lateral samples, y {road.y[0]:.4g} .. "
                     f"{road.y[-1]:.4g} m")
    lines.append("  reference line: " + ("curved or placed (OpenCRG plan); --path road "
                                         "follows it" if road.plan is not None else
                                         "straight along x"))
    if table:
        lines.append(_spec_line(table))
    return "\n".join(lines)


def tire_text(path) -> str:
    """Summary of a ``.tir`` tyre file as flexpipe reads it (PAC2002): size, vertical
    model, and at the nominal load FNOMIN the peak friction, slip stiffnesses, relaxation
    lengths and the loaded radius."""
    import numpy as np

    from flexpipe.tires import read_tir, tire_from_file
    from flexpipe.vehicle.corners import static_loaded_radius

    props = read_tir(path)
    tire = tire_from_file(path)
    mf, fz = tire.mf, props.fnomin
    mux, muy = (float(np.asarray(m)) for m in mf.peak_friction(fz))
    kx, ky = (float(np.asarray(k)) for k in mf.slip_stiffness(fz))
    sk, sa = (float(np.asarray(x)) for x in mf.relaxation_lengths(fz))
    relax = ("no relaxation data" if np.isnan(sk) and np.isnan(sa) else
             f"relaxation lengths {sk * 1e3:.0f} mm (longitudinal), {sa * 1e3:.0f} mm "
             "(lateral)")
    return "\n".join([
        f"{path}: tyre ({props.property_file_format}, USE_MODE {props.use_mode}, "
        f"TYRESIDE {props.tyre_side})",
        f"  unloaded radius {props.unloaded_radius * 1e3:.1f} mm, width "
        f"{props.width * 1e3:.0f} mm; vertical stiffness {props.vertical_stiffness:.4g} N/m, "
        f"damping {props.vertical_damping:.4g} N s/m",
        f"  at FNOMIN = {fz:.0f} N: peak friction mu_x {mux:.3f}, mu_y {muy:.3f}; slip "
        f"stiffness {kx:.4g} N, cornering stiffness {abs(ky) * np.pi / 180:.4g} N/deg; "
        f"{relax}",
        f"  loaded radius at FNOMIN {static_loaded_radius(tire, fz) * 1e3:.1f} mm"])


def csv_text(path) -> str:
    """Summary of a ``.csv`` road profile (``distance_m, left_m, right_m`` or
    ``distance_m, height_m``) or driver path (``x_m, y_m``), told by its header."""
    from flexpipe.errors import InputError

    try:
        with open(path, encoding="utf-8", errors="replace") as f:
            header = f.readline()
    except OSError as exc:
        raise InputError(f"cannot read the file ({exc.strerror})", file=path) from None
    columns = [c.strip().lower() for c in header.split(",")]
    if "x_m" in columns and "y_m" in columns:
        from flexpipe.driver import read_path

        return path_text(read_path(path), file=path)
    from flexpipe.roads import load_road

    return road_text(load_road(path), file=path)


def path_text(path, *, file=None, table: dict | None = None) -> str:
    """Human-readable summary of a driver :class:`~flexpipe.driver.Path` read from
    ``file`` (``table``: its ``[path]`` spec)."""
    import numpy as np

    k = float(np.max(np.abs(path.curvature)))
    radius = f"smallest radius {1 / k:.4g} m" if k > 0 else "no curvature"
    lines = [f"{file or path.source or path.name}: path {path.source or path.name}, "
             f"{path.s[-1]:.6g} m long, {path.x.size} points",
             f"  from ({path.x[0]:.4g}, {path.y[0]:.4g}) m to ({path.x[-1]:.4g}, "
             f"{path.y[-1]:.4g}) m; y {path.y.min():.4g} .. {path.y.max():.4g} m; "
             f"heading change {np.degrees(path.heading[-1] - path.heading[0]):.4g} deg; "
             f"{radius}"]
    if table:
        lines.append(_spec_line(table))
    return "\n".join(lines)


def mesh_text(mesh) -> str:
    """Human-readable summary of a :class:`~flexpipe.mesh.Mesh` (an empty one included)."""
    def fmt(v):
        return tuple(round(float(c), 4) for c in v)

    box = (f"bounding box {fmt(mesh.points.min(axis=0))} .. {fmt(mesh.points.max(axis=0))} m"
           if mesh.n_nodes else "no bounding box (empty mesh)")
    lines = [f"{mesh.source}: {mesh.n_nodes} nodes, {box}"]
    for b in mesh.blocks:
        lines.append(f"  {b.type:<10} {len(b):>9} elements")
    if mesh.node_sets:
        lines.append("  node sets: " + ", ".join(
            f"{k} ({len(v)})" for k, v in sorted(mesh.node_sets.items())))
    if mesh.cell_sets:
        lines.append("  cell sets: " + ", ".join(sorted(mesh.cell_sets)))
    for name, props in sorted(mesh.sections.items()):
        lines.append(f"  section {name}: " + ", ".join(f"{k}={v:g}" for k, v in props.items()))
    if mesh.point_masses:
        total = sum(pm.mass for pm in mesh.point_masses)
        lines.append(f"  {len(mesh.point_masses)} point masses, {total:.6g} kg in total")
    if mesh.rigid_links:
        lines.append(f"  {len(mesh.rigid_links)} rigid links (RBE2)")
    if mesh.interpolations:
        lines.append(f"  {len(mesh.interpolations)} interpolation constraints (RBE3)")
    for name, rows in sorted(mesh.dof_sets.items()):
        lines.append(f"  DOF set {name}: {len(rows)} DOF on "
                     f"{len(set(map(int, rows[:, 0])))} nodes")
    if mesh.solution:
        lines.append("  solution set-up: " + ", ".join(
            f"{k}={v}" for k, v in mesh.solution.items() if v is not None))
    labels = {"read": "read", "converted": "converted", "dropped": "not used (dropped)"}
    for key, label in labels.items():
        items = dict(mesh.info.get(key, {}))
        if items:
            lines.append(f"  {label}: " + ", ".join(f"{k} {v}" for k, v in
                                                     sorted(items.items())))
        elif key != "read" and "read" in mesh.info:
            lines.append(f"  {label}: none")
    return "\n".join(lines)


def run(args) -> int:
    """Run ``flexpipe info``."""
    path = Path(args.body)
    if path.suffix == ".npz":
        from flexpipe.cli.reduce import run_info

        return run_info(args)
    if path.suffix.lower() == ".toml":
        print(toml_text(path))
        return 0
    if path.suffix.lower() == ".crg":
        from flexpipe.roads import load_road

        print(road_text(load_road(path), file=path))
        return 0
    if path.suffix.lower() == ".tir":
        print(tire_text(path))
        return 0
    if path.suffix.lower() == ".csv":
        print(csv_text(path))
        return 0
    from flexpipe.mesh import read_mesh

    print(mesh_text(read_mesh(path, args.scale, units=args.units)))
    return 0
