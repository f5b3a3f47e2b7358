"""``flexpipe modes MESH``: natural frequencies and mode shapes of a mesh.

Prints the frequency table and writes ``modes.vtu`` (all modes as point-data vectors,
frequencies as field data) and ``frequencies.csv`` into ``--out`` (default
``out/modes/<mesh stem>/``); ``--per-mode`` adds ``mode_01.vtu`` ... for animation.

A Nastran SOL 103 deck runs as Nastran would: its case-control ``SPC = n`` set (with
``GRID`` ``PS``) is held fixed and its ``METHOD`` ``EIGRL`` (number of roots ``ND``,
frequency range ``V1..V2``) chooses the modes, unless ``--fixed`` / ``--n`` are given.
An Abaqus deck likewise: the ``*BOUNDARY`` conditions in effect in its first
``*FREQUENCY`` step are held fixed and that step's number of eigenvalues and frequency
range choose the modes (:mod:`flexpipe.mesh.abaqus`).
The mass matrix (printed as ``mass: ...``, see :func:`mass_choice`): ``PARAM, COUPMASS``
when the deck gives it (-1: lumped, >= 0: consistent); without it, a deck with a ``SOL``
statement gets Nastran's default, lumped mass (``COUPMASS = -1``), when its elements are
shells, linear solids and springs - a deck with CBAR/CBEAM/CROD/CONROD or 10-node CTETRA
keeps the consistent mass and says why (flexpipe's lumped mass of those has no rotary or
torsional inertia, or lumps the mid-side nodes otherwise than Nastran may: add ``PARAM,
COUPMASS, -1`` to use it).  Bulk data without
a ``SOL`` statement (such as the car body decks) and the other mesh formats get the
consistent mass, as ``flexpipe reduce`` always does.

Example::

    flexpipe modes meshes/plate_quad.msh --material steel --thickness 0.002 --n 20
"""

from __future__ import annotations

import sys
import time
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from flexpipe._io import write_text_atomic
from flexpipe.errors import InputError


def add_arguments(p) -> None:
    """Options of ``flexpipe modes``."""
    p.add_argument("mesh", help="mesh file (.msh .inp .bdf/.nas/.dat .vtu/.vtk .stl/.obj/.ply); "
                   "a Nastran deck's SPC set and EIGRL apply (an Abaqus deck's *BOUNDARY and "
                   "*FREQUENCY), and a Nastran deck's mass: PARAM,COUPMASS, "
                   "else lumped (Nastran's default) for a SOL deck of shells/solids, "
                   "consistent otherwise (printed as 'mass: ...')")
    p.add_argument("--material", help="library material: steel, aluminium, magnesium "
                   "(default: the materials the file carries, e.g. Nastran MAT1)")
    p.add_argument("--E", type=float, help="Young's modulus in Pa (overrides --material)")
    p.add_argument("--nu", type=float, help="Poisson's ratio (overrides --material)")
    p.add_argument("--rho", type=float, help="density in kg/m^3 (overrides --material)")
    p.add_argument("--thickness", type=float,
                   help="shell thickness in m for shells the file gives none")
    p.add_argument("--n", type=int, default=None,
                   help="number of modes (default: the deck's EIGRL, else 20)")
    p.add_argument("--fixed", action="append", default=[], metavar="SET",
                   help="node set or cell set whose nodes are clamped (repeatable)")
    p.add_argument("--scale", type=float, default=1.0,
                   help="length factor of the mesh geometry, e.g. 0.001 for mm")
    p.add_argument("--units", help="unit system of a solver deck, e.g. mm-t-s (converts "
                   "lengths, E, rho and masses)")
    p.add_argument("--keep", action="append", default=[], metavar="TYPE",
                   help="Gmsh: keep lower-dimensional cells of this type (e.g. line)")
    p.add_argument("--prune", action="store_true", help="drop nodes no element uses")
    p.add_argument("--allow-disconnected", action="store_true",
                   help="accept several unconnected parts")
    p.add_argument("-o", "--out", help="output folder, created if needed (default "
                   "out/modes/<mesh stem>)")
    p.add_argument("--per-mode", action="store_true", help="also write one .vtu per mode")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress messages")


@contextmanager
def _step(text: str, quiet: bool):
    t0 = time.perf_counter()
    if not quiet:
        print(f"{text} ...", file=sys.stderr, flush=True)
    yield
    if not quiet:
        print(f"  done in {time.perf_counter() - t0:.2f} s", file=sys.stderr, flush=True)


def _material(args):
    """The material of ``--material`` / ``--E --nu --rho``, checked as a MAT1 card is."""
    from dataclasses import replace

    from flexpipe.fem.material import Material, check_plausible

    over = {k: getattr(args, k) for k in ("E", "nu", "rho") if getattr(args, k) is not None}
    if args.material is None and not over:
        return None
    if args.material is not None:
        try:
            base = Material.named(args.material)
        except InputError as exc:
            raise InputError(str(exc), key="--material") from None
        if not over:
            return base
        vals = {"E": base.E, "nu": base.nu, "rho": base.rho, **over}
        keys = tuple(f"--{k}" if k in over else f"--material {base.name} {k}"
                     for k in ("E", "nu", "rho"))
        mat = check_plausible(vals["E"], vals["nu"], vals["rho"], keys=keys, given=set(over))
        return replace(mat, name=base.name)
    if len(over) < 3:
        missing = [f"--{k}" for k in ("E", "nu", "rho") if k not in over]
        raise InputError(f"give --material NAME or all of --E, --nu, --rho (missing "
                         f"{', '.join(missing)})")
    return check_plausible(over["E"], over["nu"], over["rho"], keys=("--E", "--nu", "--rho"))


def _check_file_materials(mesh) -> None:
    from flexpipe.mesh.validate import missing_property_note

    for bi, b in enumerate(mesh.blocks):
        if b.type in ("vertex", "spring", "spring1") or len(b) == 0:
            continue
        covered = np.zeros(len(b), dtype=bool)
        for name, props in mesh.sections.items():
            if all(k in props for k in ("E", "nu", "rho")) and bi in mesh.cell_sets.get(name, {}):
                covered[mesh.cell_sets[name][bi]] = True
        if not covered.all():
            ids = b.ids[~covered][:5].tolist()
            note = missing_property_note(mesh, bi, np.flatnonzero(~covered))
            raise InputError(
                f"{note}{int((~covered).sum())} {b.type} element(s) have no material in the "
                f"file (e.g. ids {ids}); {'define that property or ' if note else ''}give "
                "--material steel|aluminium|magnesium or --E --nu --rho", file=mesh.source)


#: span (largest bounding-box side) of a plausible vehicle part or body, m: outside it
#: ``flexpipe modes`` warns of a unit slip (a 4.4 m body in mm read as m spans 4400 m)
SPAN_RANGE_M = (0.01, 50.0)
_UNITS_HINT = ("check the mesh's units: a mesh in mm needs --scale 0.001 (lengths only; "
               "mesh_scale in a car file) or, for a solver deck in mm-t-s, --units mm-t-s "
               "(mesh_units); and check E, the density and --thickness (m)")


def _eigen_or_hint(eigenmodes, path, mesh, fe, span):
    """``eigenmodes`` turning an ARPACK failure into an :class:`InputError` that names
    the file, the mesh's size and mass, and the units to check."""
    from scipy.sparse.linalg import ArpackError, ArpackNoConvergence

    def solve(*a, **kw):
        try:
            return eigenmodes(*a, **kw)
        except (ArpackNoConvergence, ArpackError) as exc:
            lo, hi = mesh.points.min(axis=0), mesh.points.max(axis=0)
            box = (f"({', '.join(f'{v:.4g}' for v in lo)}) .. "
                   f"({', '.join(f'{v:.4g}' for v in hi)}) m")
            raise InputError(
                f"the eigensolver did not converge ({type(exc).__name__}: "
                f"{str(exc).splitlines()[0][:120]}); the mesh spans {span:.4g} m (bounding "
                f"box {box}) and weighs {fe.total_mass:.4g} kg, so {_UNITS_HINT}",
                file=str(path)) from None
    return solve


def run(args) -> int:
    """Run ``flexpipe modes``."""
    from flexpipe._io import check_output_folder
    from flexpipe.fem import assemble, eigenmodes
    from flexpipe.mesh import read_mesh
    from flexpipe.mesh.vtu import write_modes

    if args.n is not None and args.n < 1:
        raise InputError(f"--n must be a positive number of modes, got {args.n}", key="--n")
    material = _material(args)
    path = Path(args.mesh)
    out = check_output_folder(args.out if args.out else Path("out") / "modes" / path.stem,
                              option="-o")  # before the analysis, not after
    with _step(f"reading {path}", args.quiet):
        mesh = read_mesh(path, args.scale, units=args.units, thickness=args.thickness,
                         keep=tuple(args.keep), prune_unreferenced=args.prune)
    if material is None:
        _check_file_materials(mesh)
    lumped, mass_note = mass_choice(mesh)
    with _step("assembling", args.quiet):
        fe = assemble(mesh, material, allow_disconnected=args.allow_disconnected,
                      progress=not args.quiet, lumped=lumped)
    fixed = None
    sol = dict(mesh.solution)
    if args.fixed:
        nodes = np.unique(np.concatenate([mesh.nodes_of(name) for name in args.fixed]))
        dpn = fe.dofs_per_node
        fixed = (nodes[:, None] * dpn + np.arange(dpn)).ravel()
    else:
        fixed = deck_fixed_dofs(mesh, fe.dofs_per_node)
        if fixed is not None and not args.quiet:
            print(f"deck constraints: {', '.join(deck_sets(mesh))} ({len(fixed)} DOF)",
                  file=sys.stderr)
    n = args.n if args.n is not None else (sol.get("n_modes") or 20)
    f_lo, f_hi = (None, None) if args.n is not None else (sol.get("f_min"), sol.get("f_max"))
    span = float(np.ptp(mesh.points, axis=0).max()) if mesh.n_nodes else 0.0
    if not SPAN_RANGE_M[0] <= span <= SPAN_RANGE_M[1]:
        import warnings

        warnings.warn(f"{path}: the mesh spans {span:.4g} m, outside the {SPAN_RANGE_M[0]:g}-"
                      f"{SPAN_RANGE_M[1]:g} m of a vehicle part or body: {_UNITS_HINT}",
                      UserWarning, stacklevel=2)
    with _step(f"solving for {n} modes ({fe.Kr.shape[0]} DOF)", args.quiet):
        dirs = None if args.fixed else mesh.solution.get("spc_directions")
        solve = _eigen_or_hint(eigenmodes, path, mesh, fe, span)
        freqs, shapes = solve(fe, n, fixed_dofs=fixed, directions=dirs)
        while f_hi is not None and freqs[-1] < f_hi and sol.get("n_modes") is None \
                and len(freqs) < fe.Kr.shape[0] - (0 if fixed is None else len(fixed)) - 1:
            n = min(2 * n, fe.Kr.shape[0] - 1 - (0 if fixed is None else len(fixed)))
            freqs, shapes = solve(fe, n, fixed_dofs=fixed, directions=dirs)
        keep = np.ones(len(freqs), dtype=bool)
        if f_lo is not None:
            keep &= freqs >= f_lo
        if f_hi is not None:
            keep &= freqs <= f_hi
        freqs, shapes = freqs[keep], shapes[:, keep]
    written = write_modes(out / "modes.vtu", mesh, freqs, shapes,
                          per_mode_dir=out if args.per_mode else None)
    csv = "mode,frequency_hz\n" + "".join(f"{k + 1},{f:.10g}\n" for k, f in enumerate(freqs))
    write_text_atomic(out / "frequencies.csv", csv)
    counts = ", ".join(f"{b.type} {len(b)}" for b in mesh.blocks)
    print(f"{path}: {mesh.n_nodes} nodes, {counts}; {fe.Kr.shape[0]} DOF; "
          f"mass {fe.total_mass:.6g} kg" + (f"; fixed: {', '.join(args.fixed)}"
                                             if args.fixed else "")
          + (f"; deck SPC: {', '.join(deck_sets(mesh))}" if fixed is not None
             and not args.fixed else ""))
    print(mass_note)
    print(f"{'mode':>5}  {'frequency [Hz]':>16}")
    for k, f in enumerate(freqs):
        print(f"{k + 1:>5}  {f:>16.6g}")
    print(f"wrote {written[0]} ({len(freqs)} modes) and {out / 'frequencies.csv'}"
          + (f" and {len(written) - 1} per-mode files" if args.per_mode else ""))
    return 0


#: cell types whose lumped mass (flexpipe.fem.lumped: translational row sums, no rotary
#: inertia) is the one Nastran forms for COUPMASS = -1
NASTRAN_LUMPED_TYPES = ("quad", "triangle", "tetra", "hexahedron", "wedge", "pyramid",
                        "spring", "spring1", "vertex")


def mass_choice(mesh) -> tuple[bool, str]:
    """``(lumped, note)``: the mass matrix ``flexpipe modes`` uses for ``mesh`` and the line
    it prints about it (see the module docstring)."""
    sol = mesh.solution
    if sol.get("lumped_mass") is not None:
        lumped = bool(sol["lumped_mass"])
        value = sol.get("coupmass", -1 if lumped else 1)
        return lumped, f"mass: {'lumped' if lumped else 'consistent'} (PARAM,COUPMASS,{value})"
    if sol.get("sol") is not None:
        other = sorted({b.type for b in mesh.blocks if len(b)} - set(NASTRAN_LUMPED_TYPES))
        if not other:
            return True, "mass: lumped (Nastran's default, PARAM,COUPMASS absent)"
        return False, ("mass: consistent (PARAM,COUPMASS absent: Nastran's default is lumped, "
                       f"but for {', '.join(other)} elements flexpipe's lumped mass is not "
                       "Nastran's; PARAM,COUPMASS,-1 in the deck uses it)")
    if "wtmass" in mesh.info:          # Nastran bulk data without executive control
        return False, ("mass: consistent (no SOL statement in the deck; a Nastran run "
                       "would lump it: PARAM,COUPMASS,-1 in the deck does so here)")
    return False, "mass: consistent"


def deck_sets(mesh) -> list[str]:
    """Names of the DOF sets a deck's solution set-up holds fixed (SPC = n, GRID PS)."""
    names = []
    if mesh.solution.get("spc"):
        names.append(mesh.solution["spc"])
    if "GRID_PS" in mesh.dof_sets:
        names.append("GRID_PS")
    return names


def deck_fixed_dofs(mesh, dpn: int):
    """Global DOF held fixed by the deck's case-control SPC set and GRID PS, or None."""
    names = deck_sets(mesh)
    if not names:
        return None if mesh.solution.get("spc_directions") is None else np.zeros(0, np.int64)
    rows = np.vstack([np.asarray(mesh.dof_sets[k]).reshape(-1, 2) for k in names])
    rows = rows[rows[:, 1] < dpn]
    return np.unique(rows[:, 0] * dpn + rows[:, 1])
