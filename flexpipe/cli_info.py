"""``flexpipe info FILE``: summary of a FlexBody (.npz), a car file (.toml) or a mesh file.

For a FlexBody it prints the reduced-vs-full frequency table, the MAC matrix and mass
properties (see :func:`flexpipe.cli_reduce.info_text`) and can write the mode shapes as
.vtu; for a mesh it lists nodes, element blocks, named sets, carried properties, constraints,
the solution set-up of a solver deck, and what the reader read, converted (e.g. CQUAD8
into CQUAD4) and dropped (loads, output requests, unknown cards).
"""

from __future__ import annotations

from pathlib import Path


def add_arguments(p) -> None:
    """Options of ``flexpipe info``."""
    from flexpipe.cli_reduce import add_info_arguments

    add_info_arguments(p)
    p.add_argument("--scale", type=float, default=1.0, help="mesh length scale (mesh files)")
    p.add_argument("--units", help="unit system of a solver deck, e.g. mm-t-s (mesh files; "
                   "converts lengths, E, rho and masses)")


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
        from flexpipe.cli_reduce import run_info

        return run_info(args)
    if path.suffix.lower() == ".toml":
        from flexpipe.vehicle.describe import car_text
        from flexpipe.vehicle.spec import load_car

        print(car_text(load_car(path)))
        return 0
    from flexpipe.mesh import read_mesh

    print(mesh_text(read_mesh(path, args.scale, units=args.units)))
    return 0
