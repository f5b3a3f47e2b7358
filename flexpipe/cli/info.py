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

A ``.csv`` file is a road or a path by its header (``#`` comment lines before it skipped)
or, without one, by what it can be (:func:`csv_kind`).  A road's track RMS is weighted by
length over the profile the car drives (linear between samples,
:func:`track_statistics`), so non-uniform sampling does not bias it; its reference line
is told as straight along x, placed or curved.  A tyre file is read once; one without
``[DIMENSION] WIDTH`` (which a run does not need) says "width not given".  A mesh's section
properties carry their SI units, and its structural mass and centre of mass come from the
properties it carries (:func:`flexpipe.fem.structural_mass.structural_mass`, no assembly).
"""

from __future__ import annotations

import math
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
         "table, e.g. cars/sedan.toml), a road (.toml with a [road] table, .crg, .rdf, .csv) or "
         "path (.toml with a [path] table, .csv) file, a speed profile (.toml with a "
         "[speed_profile] table, .csv), a driver (.toml with a [steering] table), a tyre "
         "(.tir), or a mesh (.bdf, .inp, .msh, .vtu, ...)")

#: TOML files info does not describe: (tables that tell them, what they are, their use),
#: tried in order.  Any file with a [sweep] table is a sweep, whatever its design (a grid
#: or Latin hypercube has [parameters], a list [[runs]]), but the half-car parameters
#: (cars/halfcar_paper.toml) carry a [sweep] table beside [table1], so [table1] comes first.
_OTHER_TOML = (
    (("table1",), "half-car parameter", "read by flexpipe.halfcar.params.load_params for "
                                        "make paper"),
    (("sweep",), "sweep", "run it with flexpipe sweep FILE"),
)


def toml_kind(doc: dict) -> str:
    """What a parsed TOML file is, from its top-level tables: ``"car"``, ``"road"``,
    ``"path"``, ``"sweep"``, ``"half-car parameter"``, ``"driver"`` or ``""``
    (unknown); a car variant names its ``base`` car file."""
    if "car" in doc or "base" in doc:
        return "car"
    for tables, kind, _ in _OTHER_TOML:
        if all(t in doc for t in tables):
            return kind
    if "road" in doc:  # load_road names any other table beside it
        return "road"
    if "path" in doc:
        return "path"
    if "speed_profile" in doc:
        return "speed profile"
    return "driver" if "steering" in doc else ""


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
        from flexpipe.vehicle._car_base import car_files
        from flexpipe.vehicle.describe import car_text
        from flexpipe.vehicle.mounts import check_mount_node_ids
        from flexpipe.vehicle.spec import load_car

        car = load_car(path)
        check_mount_node_ids(car)  # mount node ids of the mesh, as a flexible run checks
        text = car_text(car)
        bases = car_files(path)[1:]
        if bases:   # a variant: what it builds on
            head, _, rest = text.partition("\n")
            text = f"{head}\n  based on {' <- '.join(str(b) for b in bases)}\n{rest}"
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
    if kind == "speed profile":
        from flexpipe.driver.speed import profile_file_text

        return profile_file_text(path)
    if kind == "driver":  # read by simulate(..., driver=FILE) and flexpipe run --driver
        from flexpipe.driver import read_driver

        steering, speed = read_driver(path)
        speed = speed.describe() if speed is not None else \
            "the car's default PI speed controller (gains from its mass)"
        return f"{path}: driver\n  steering: {steering.describe()}\n  speed: {speed}"
    use = next((u for _, k, u in _OTHER_TOML if k == kind), None)
    what = (f"is a {kind} file, not a car, mesh or body file ({use})" if kind else
            f"is not a car, road or path file: it has no [car], [road] or [path] table "
            f"(top-level keys: {sorted(doc) or 'none'})")
    raise InputError(f"{what}; flexpipe info takes {TAKES}", file=path)


def _spec_line(table: dict) -> str:
    return "  spec: " + ", ".join(f"{k} = {v!r}" for k, v in table.items())


def track_statistics(x, z) -> tuple[float, float]:
    """Mean and RMS about the mean of a road track, weighted by length.

    The profile is the one the car drives: linear between the samples ``(x, z)``, over
    ``x[0] .. x[-1]``.  Every interval counts by its length, so a densely sampled bump
    weighs no more than its length (``np.std`` of the samples would weigh each sample
    equally and over-weight dense regions of a non-uniformly sampled road).

    Parameters
    ----------
    x : array_like, shape (n,)
        Distance of the samples, strictly increasing (m).
    z : array_like, shape (n,)
        Height at the samples (m).

    Returns
    -------
    mean : float
        ``1/L int z dx`` (m), ``L = x[-1] - x[0]``.
    rms : float
        ``sqrt(1/L int (z - mean)^2 dx)`` (m), exact for the piecewise-linear profile.
    """
    import numpy as np

    x = np.asarray(x, dtype=float)
    z = np.asarray(z, dtype=float)
    h = np.diff(x)
    length = float(x[-1] - x[0])
    mean = float(np.sum(h * (z[:-1] + z[1:])) / (2.0 * length))
    d = z - mean  # about the mean first: no cancellation for roads far above z = 0
    a, b = d[:-1], d[1:]
    var = float(np.sum(h * (a * a + a * b + b * b)) / (3.0 * length))
    return mean, math.sqrt(max(var, 0.0))


def _spacing_text(x) -> str:
    """``"uniform, every d m"`` or ``"spacing min .. max m (not uniform)"`` of samples ``x``
    (uniform within the tolerance :class:`~flexpipe.roads.Road` uses)."""
    import numpy as np

    step = np.diff(np.asarray(x, dtype=float))
    d = float((x[-1] - x[0]) / (len(x) - 1))
    if np.all(np.abs(step - d) <= 1e-9 * max(1.0, abs(float(x[-1])))):
        return f"uniform, every {d:.4g} m"
    return f"spacing {step.min():.4g} .. {step.max():.4g} m (not uniform)"


def _reference_line_text(road) -> str:
    """Where a road lies in the plane: along x, or the OpenCRG plan's placement/curve."""
    plan = road.plan
    if plan is None:
        return "straight along x (s = x, lateral = y)"
    scale = max(1.0, abs(float(road.x[-1])), abs(float(road.x[0])))
    start = f"({plan.x[0]:.6g}, {plan.y[0]:.6g}) m"
    if abs(plan.u0) > 1e-9 * scale:  # s of the reference line's first point
        start = f"{start} (s = {plan.u0:.6g} m)"
    if not plan.straight:
        return (f"curved (heading channel): from {start}, heading "
                f"{math.degrees(plan.phi_start):.4g} deg, to ({plan.x[-1]:.6g}, "
                f"{plan.y[-1]:.6g}) m, heading {math.degrees(plan.phi_end):.4g} deg; "
                "--path road follows it")
    along_x = (abs(plan.phi_start) <= 1e-12 and abs(plan.y[0]) <= 1e-9 * scale
               and abs(plan.x[0] - plan.u0) <= 1e-9 * scale)
    if along_x:
        return "straight along x (s = x, lateral = y)"
    return (f"straight, placed at {start}, heading {math.degrees(plan.phi_start):.4g} deg; "
            "--path road follows it")


def road_text(road, *, file=None, table: dict | None = None) -> str:
    """Human-readable summary of a road.

    Parameters
    ----------
    road : Road
        The road (:class:`~flexpipe.roads.Road`).
    file : str or Path, optional
        The file it was read from.
    table : dict, optional
        Its ``[road]`` spec, when it came from a TOML file.

    Returns
    -------
    str
        Length, samples and their spacing, track width, per track the height range and
        the length-weighted RMS about the mean (:func:`track_statistics`), the height
        grid and where the reference line lies.
    """
    lines = [f"{file or road.source or road.name}: road {road.source or road.name}",
             f"  {road.length:.6g} m long "
             f"(x {road.x[0]:.6g} .. {road.x[-1]:.6g} m), {road.x.size} samples, "
             f"{_spacing_text(road.x)}, track width {road.track_width:.4g} m"]
    for side, z in (("left", road.left), ("right", road.right)):
        rms = track_statistics(road.x, z)[1]
        lines.append(f"  {side} track height (mm): min {1e3 * z.min():.2f}, max "
                     f"{1e3 * z.max():.2f}, RMS about the mean {1e3 * rms:.2f} (over the "
                     "length, linear between samples)")
    if road.y is not None:
        lines.append(f"  height grid: {road.y.size} lateral samples, y {road.y[0]:.4g} .. "
                     f"{road.y[-1]:.4g} m")
    lines.append("  reference line: " + _reference_line_text(road))
    if table:
        lines.append(_spec_line(table))
    return "\n".join(lines)


def csv_kind(path) -> str:
    """Whether a ``.csv`` file is a road (``"road"``), a driver path (``"path"``) or a
    speed profile (``"speed profile"``: a header ``time_s`` or ``distance_m``, then
    ``speed_kmh`` or ``speed_mps``).

    Told by the header when the file has one (``#`` comment lines before it are skipped):
    one naming ``x`` and ``y`` (``x_m,y_m``, any unit) is a path, any other a road (whose
    reader names a column it cannot place).  Without a header, by what the file can be:
    three columns, or a first column that does not increase strictly, only one of them;
    two columns that can be both (x increasing, a drivable path) are an error asking for
    a header.
    """
    from flexpipe._io import header_columns, read_numeric_table
    from flexpipe.driver.tracks import PATH_COLUMNS
    from flexpipe.errors import InputError

    table = read_numeric_table(path, kind="road or path",
                               columns="'distance, left, right' (road) or 'x, y' (path)")
    if table.header is not None:
        from flexpipe.driver.speed import BASES, SPEED_KEYS

        names = [h.strip().lower() for h in table.header]
        if len(names) == 2 and names[0] in BASES.values() and names[1] in SPEED_KEYS:
            return "speed profile"
        try:
            cols = header_columns(table.header, names=PATH_COLUMNS, file=path,
                                  line=table.header_line, kind="path")
        except InputError:
            return "road"
        return "path" if {role for role, _ in cols} == {"x", "y"} else "road"
    rows = [values for _, _, values in table.rows]
    if not rows or len(rows[0]) != 2 or any(len(r) != 2 for r in rows):
        return "road"  # (the road reader names what is wrong)
    x = [r[0] for r in rows]
    can_road = all(b > a for a, b in zip(x, x[1:], strict=False))
    try:
        from flexpipe.driver import Path as DPath

        DPath.from_xy(x, [r[1] for r in rows])
        can_path = True
    except InputError:
        can_path = False
    if can_road and can_path:
        raise InputError("two columns without a header: this can be a road (distance, "
                         "height) or a path (x, y); add a header line naming the columns, "
                         "'distance_m,height_m' or 'x_m,y_m'", file=path,
                         line=table.rows[0][0])
    return "path" if can_path else "road"


def csv_text(path) -> str:
    """Summary of a ``.csv`` road profile (``distance_m, left_m, right_m`` or
    ``distance_m, height_m``) or driver path (``x_m, y_m``), told by :func:`csv_kind`."""
    kind = csv_kind(path)
    if kind == "speed profile":
        from flexpipe.driver.speed import profile_file_text

        return profile_file_text(path)
    if kind == "path":
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


#: printed name and meaning of section keys that are not plain quantities
_SECTION_NAMES = {"bending": "bending_ratio", "k1": "k1", "k2": "k2", "theta": "theta"}
#: SI units of the dimensioned section keys, by (length, mass, time) powers
_UNITS = {(1, 0, 0): "m", (2, 0, 0): "m^2", (4, 0, 0): "m^4", (-1, 1, -2): "Pa",
          (-3, 1, 0): "kg/m^3", (0, 1, -2): "N/m", (2, 1, -2): "N m"}
#: the note printed under the sections for each dimensionless key they use
_SECTION_NOTES = {
    "bending": "bending_ratio: plate bending rigidity over that of a solid shell of the "
               "thickness, PSHELL 12I/T^3 x E(MID2)/E(MID1) (1 solid shell, 0 membrane "
               "only)",
    "k1": "k1, k2: transverse-shear area factors of beams, PBAR/PBEAM K1, K2 (0 no shear "
          "flexibility)",
    "theta": "theta: angle of the principal section axes from the beam's y axis (from "
             "PBAR I12)",
}


def _section_value(key: str, value) -> str:
    """``key=value unit`` of one section property (SI; dimensionless values bare)."""
    from flexpipe.mesh.units import SECTION_DIMENSIONS

    name = _SECTION_NAMES.get(key, key)
    v = float(value)
    if key == "theta":
        return f"{name}={math.degrees(v):.4g} deg"
    unit = _UNITS.get(SECTION_DIMENSIONS.get(key))
    return f"{name}={v:g} {unit}" if unit else f"{name}={v:g}"


def _mass_line(mesh) -> str:
    """The structural-mass line of :func:`mesh_text` ('' for a mesh without elements)."""
    import numpy as np

    from flexpipe.fem.structural_mass import structural_mass

    if not any(len(b) for b in mesh.blocks) and not mesh.point_masses:
        return ""
    parts, total, com, missing = structural_mass(mesh)
    size = float(np.ptp(mesh.points, axis=0).max()) if mesh.n_nodes else 1.0
    com = np.where(np.abs(com) < 1e-12 * max(size, 1e-300), 0.0, com)
    split = ", ".join(f"{k} {v:.5g} kg" for k, v in parts.items())
    if missing:
        known = f"; known: {split}" if split else ""
        return (f"  structural mass: unknown, the file gives no mass for "
                f"{'; '.join(missing)} (flexpipe reduce and modes take --material or "
                f"--rho and --thickness){known}")
    if total <= 0:
        return "  structural mass 0 kg (no element or point carries mass)"
    return (f"  structural mass {total:.5g} kg ({split}), centre of mass "
            f"({', '.join(f'{c:.4g}' for c in com)}) m")


def mesh_text(mesh) -> str:
    """Human-readable summary of a mesh.

    Parameters
    ----------
    mesh : Mesh
        The mesh (:class:`~flexpipe.mesh.Mesh`; an empty one included).

    Returns
    -------
    str
        Nodes and bounding box, element blocks, sets, the carried section properties
        with their SI units, the structural mass and centre of mass
        (:func:`structural_mass`), point masses, constraints, the solution set-up and
        what the reader read, converted and dropped.
    """
    from flexpipe.fem.structural_mass import plural as _plural

    def fmt(v):
        return tuple(round(float(c), 4) for c in v)

    box = (f"bounding box {fmt(mesh.points.min(axis=0))} .. {fmt(mesh.points.max(axis=0))} m"
           if mesh.n_nodes else "no bounding box (empty mesh)")
    lines = [f"{mesh.source}: {mesh.n_nodes} nodes, {box}"]
    for b in mesh.blocks:
        lines.append(f"  {b.type:<10} {len(b):>9} {'element' if len(b) == 1 else 'elements'}")
    if mesh.node_sets:
        lines.append("  node sets: " + ", ".join(
            f"{k} ({len(v)})" for k, v in sorted(mesh.node_sets.items())))
    if mesh.cell_sets:
        lines.append("  cell sets: " + ", ".join(sorted(mesh.cell_sets)))
    used = set()
    for name, props in sorted(mesh.sections.items()):
        lines.append(f"  section {name}: " + ", ".join(
            _section_value(k, v) for k, v in props.items()))
        used.update(props)
    lines += [f"    {note}" for key, note in _SECTION_NOTES.items() if key in used]
    if mesh.point_masses:
        total = sum(pm.mass for pm in mesh.point_masses)
        lines.append(f"  {_plural(len(mesh.point_masses), 'point mass', 'point masses')}, "
                     f"{total:.6g} kg in total")
    mass = _mass_line(mesh)
    if mass:
        lines.append(mass)
    if mesh.rigid_links:
        lines.append(f"  {_plural(len(mesh.rigid_links), 'rigid link')} (RBE2)")
    if mesh.interpolations:
        lines.append(f"  {_plural(len(mesh.interpolations), 'interpolation constraint')} "
                     "(RBE3)")
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
    if path.suffix.lower() in (".crg", ".rdf"):
        from flexpipe.roads import load_road

        print(road_text(load_road(path), file=path))
        return 0
    if path.suffix.lower() == ".tir":
        from flexpipe.cli.info_tires import tire_text

        print(tire_text(path))
        return 0
    if path.suffix.lower() == ".csv":
        print(csv_text(path))
        return 0
    from flexpipe.mesh import read_mesh

    print(mesh_text(read_mesh(path, args.scale, units=args.units)))
    return 0
