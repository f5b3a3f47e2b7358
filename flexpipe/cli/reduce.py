"""``flexpipe reduce MESH --interfaces spec.toml -o body.npz`` and ``flexpipe info body.npz``.

``reduce`` reads and assembles the mesh, applies the interfaces of the TOML spec (see
:mod:`flexpipe.reduction.spec`), runs the component mode synthesis, checks the result
against the full model (frequencies, MAC) and writes the FlexBody.  ``info`` prints a
body's summary: the reduced-vs-full frequency table, the MAC matrix, the mass properties
of the reduced body against the mesh, and writes the mode shapes as ``.vtu``.

Examples::

    flexpipe reduce meshes/sedan_biw.bdf --interfaces mounts.toml -o out/biw.npz --f-max 60
    flexpipe info out/biw.npz --vtu out/biw_modes.vtu
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from flexpipe.errors import InputError


def add_arguments(p) -> None:
    """Options of ``flexpipe reduce``."""
    p.add_argument("mesh", help="mesh file (.msh .inp .bdf/.nas/.dat .vtu/.vtk)")
    p.add_argument("--interfaces", required=True, metavar="SPEC.toml",
                   help="interface spec: [[interface]] tables with name, point and radius, "
                   "node_set or nodes")
    p.add_argument("-o", "--out", required=True, help="output FlexBody file (.npz)")
    p.add_argument("--method", default="craig-bampton",
                   choices=["craig-bampton", "residual-flexibility", "modal-truncation"])
    g = p.add_mutually_exclusive_group()
    g.add_argument("--n-modes", type=int, help="normal modes to keep (fixed-interface modes "
                   "for Craig-Bampton, elastic free modes otherwise)")
    g.add_argument("--f-max", type=float, help="top of the frequency band in Hz (default 50)")
    p.add_argument("--interface-f-max", type=float, metavar="HZ",
                   help="Craig-Bampton interface reduction: keep the characteristic "
                   "constraint modes up to HZ (for bodies with many interfaces)")
    p.add_argument("--damping", type=float,
                   help="modal damping ratio of every elastic mode (default Adams/Flex: 1%% "
                   "below 100 Hz, 10%% below 1 kHz, critical above)")
    p.add_argument("--material", help="library material: steel, aluminium, magnesium")
    p.add_argument("--E", type=float, help="Young's modulus in Pa")
    p.add_argument("--nu", type=float, help="Poisson's ratio")
    p.add_argument("--rho", type=float, help="density in kg/m^3")
    p.add_argument("--thickness", type=float, help="shell thickness in m where the file has none")
    p.add_argument("--scale", type=float, default=1.0, help="length factor, e.g. 0.001 for mm")
    p.add_argument("--units", help="unit system of a solver deck, e.g. mm-t-s")
    p.add_argument("--no-check", action="store_true",
                   help="skip the full-model eigen-solve (frequency table, MAC)")
    p.add_argument("--stress", default="none", metavar="all|none|SET",
                   help="store stress modes for durability: all elements, none (default) or "
                        "the elements of a named cell set")
    p.add_argument("--vtu", help="also write the mode shapes to this .vtu file")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress messages")


def add_info_arguments(p, *, what: str = "FlexBody file written by flexpipe reduce (.npz)"
                       ) -> None:
    """Options of ``flexpipe info FILE``; ``what`` is the help of the file argument (the
    argument's destination stays ``body``, which :mod:`flexpipe.cli.info` dispatches on)."""
    p.add_argument("body", metavar="FILE", help=what)
    p.add_argument("--vtu", help="write the mode shapes to this .vtu file (FlexBody files)")
    p.add_argument("--mac-size", type=int, default=12,
                   help="rows/columns of MAC printed (FlexBody files)")


def run(args) -> int:
    """Run ``flexpipe reduce``."""
    from flexpipe._io import check_output_file
    from flexpipe.cli.modes import _check_file_materials, _material, _step
    from flexpipe.fem import assemble
    from flexpipe.mesh import read_mesh
    from flexpipe.reduction import reduce
    from flexpipe.reduction.spec import read_interfaces

    out = Path(args.out)
    if out.suffix != ".npz":
        raise InputError("the output FlexBody file must end in .npz", key="-o")
    check_output_file(out, option="-o")  # before the analysis, not after
    if args.vtu:
        _check_vtu(args.vtu)
    material = _material(args)
    path = Path(args.mesh)
    with _step(f"reading {path}", args.quiet):
        mesh = read_mesh(path, args.scale, units=args.units, thickness=args.thickness)
    if material is None:
        _check_file_materials(mesh)
    interfaces = read_interfaces(args.interfaces, node_ids=mesh.node_ids)
    with _step("assembling", args.quiet):
        fe = assemble(mesh, material, progress=not args.quiet)
    with _step(f"reducing ({args.method}, {fe.Kr.shape[0]} DOF, {len(interfaces)} "
               "interfaces)", args.quiet):
        body = reduce(fe, interfaces, method=args.method, n_modes=args.n_modes,
                      f_max=args.f_max, damping=args.damping, check=not args.no_check,
                      stress=args.stress, interface_f_max=args.interface_f_max,
                      log=None if args.quiet else
                      (lambda line: print(f"  {line}", file=sys.stderr, flush=True)))
    body.save(out)
    print(info_text(body, path=out))
    if args.vtu:
        print(f"wrote {write_modes_vtu(body, args.vtu)}")
    print(f"wrote {out}")
    return 0


def run_info(args) -> int:
    """Run ``flexpipe info BODY.npz``."""
    from flexpipe.reduction import load_body

    if args.vtu:
        _check_vtu(args.vtu)
    body = load_body(args.body)
    print(info_text(body, path=args.body, mac_size=args.mac_size))
    if args.vtu:
        print(f"wrote {write_modes_vtu(body, args.vtu)}")
    return 0


#: smallest MAC at which a reduced mode is paired with a full-model mode in ``info``; below
#: it the reduced mode has no counterpart among the full modes computed (the conventional
#: 0.5: at most one other mode can share a shape that well)
MAC_MATCH = 0.5


def _pair(k: int, rigid: bool, mac, r: int):
    """``(full mode index, MAC)`` paired with reduced mode ``k``: the full elastic mode of
    the largest MAC (rigid modes and a missing MAC: the same index, MAC None)."""
    if mac is None or rigid or k >= mac.shape[0] or mac.shape[1] <= r:
        return k, None
    j = r + int(np.argmax(mac[k, r:]))  # pair by shape (MAC), not by index
    return j, float(mac[k, j])


def info_text(body, *, path="", mac_size: int = 12) -> str:
    """Human-readable summary of a FlexBody (what ``flexpipe info`` prints).

    Parameters
    ----------
    body : FlexBody
        The reduced body.
    path : str or Path
        Its file, for the first line.
    mac_size : int
        Rows and columns of the MAC matrix printed.

    Returns
    -------
    str
        Method, nodes, modes and interfaces; the mass properties of the reduced body
        against the mesh; per mode the reduced frequency, the full-model mode of best MAC
        with its frequency and the difference (only when that MAC reaches
        :data:`MAC_MATCH`, else ``no match``), and the modal damping ratio; the MAC matrix.
    """
    from flexpipe.flexbody.invariants import rigid_mass_properties

    meta = body.meta
    lines = [f"{path}: {body.method}, {body.n_nodes} nodes ({meta.get('n_dof', '?')} DOF), "
             f"{body.n_rigid} rigid + {body.n_elastic} elastic modes",
             "  interfaces: " + ", ".join(
                 f"{i.name} ({i.kind}, {i.dofs} DOF, {len(i.nodes)} "
                 f"{'node' if len(i.nodes) == 1 else 'nodes'} at {_p(i.point)})"
                 for i in body.interfaces),
             f"  source mesh sha256 {body.source_hash[:16]}...  flexpipe "
             f"{meta.get('flexpipe_version', '?')}  reduced in {meta.get('total_s', '?')} s"]
    if body.stress is not None:
        kinds = ", ".join(f"{len(b)} {b.cell_type}" for b in body.stress.blocks)
        lines.append(f"  stress modes ({body.stress.selection}): {kinds} elements, "
                     f"{body.stress.nbytes / 1e6:.1f} MB")
    ck = body.checks
    if "rigid_mass_matrix_full" in ck:
        full = rigid_mass_properties(ck["rigid_mass_matrix_full"])
        red = rigid_mass_properties(ck["rigid_mass_matrix_reduced"])
        lines += ["", "  mass properties        reduced body        mesh (full M)     rel. diff"]
        sc = max(np.abs(full[1]).max(), 1e-12)
        sj = max(np.abs(full[2]).max(), 1e-300)
        rows = [("mass [kg]", red[0], full[0], full[0])]
        rows += [(f"com {a} [m]", red[1][i], full[1][i], sc) for i, a in enumerate("xyz")]
        rows += [(f"I{a} [kg m^2]", red[2][i, j], full[2][i, j], sj)
                 for i, j, a in [(0, 0, "xx"), (1, 1, "yy"), (2, 2, "zz"), (0, 1, "xy"),
                                 (0, 2, "xz"), (1, 2, "yz")]]
        for name, r, f, scale in rows:
            lines.append(f"  {name:<18} {r:>18.10g} {f:>18.10g} {abs(r - f) / scale:>12.2e}")
    f_full = ck.get("full_frequencies_hz")
    mac = ck.get("mac")
    lines += [""]
    if mac is not None:
        lines.append(f"  full mode: the full-model mode of largest MAC with the reduced one; "
                     f"'no match' when that MAC is below {MAC_MATCH:g}")
    lines.append("  mode   reduced [Hz]   full mode      full [Hz]    diff [%]    MAC   "
                 "damping ratio [-]")
    r = body.n_rigid
    for k, f in enumerate(body.frequencies_hz):
        rigid = k < r
        j, best = _pair(k, rigid, mac, r)
        kind = "  rigid" if rigid else f"{body.damping_ratio[k]:>8.3f}"
        m = "" if best is None else f"{best:>6.3f}"
        if best is not None and best < MAC_MATCH:
            lines.append(f"  {k + 1:>4} {f:>14.6g} {'no match':>11} {'-':>14} {'-':>11} "
                         f"{m:>6} {kind}")
            continue
        ff = f_full[j] if f_full is not None and j < len(f_full) else None
        diff = "" if ff is None or rigid or ff <= 0 else f"{100 * (f / ff - 1):>10.4f}"
        fs = "-" if ff is None else f"{ff:.6g}"
        jj = "" if ff is None else str(j + 1)
        lines.append(f"  {k + 1:>4} {f:>14.6g} {jj:>11} {fs:>14} {diff:>11} {m:>6} {kind}")
    if f_full is None:
        lines.append("  (no full-model check stored: reduce without --no-check)")
    if mac is not None:
        n = min(mac_size, body.n_elastic, mac.shape[1] - r)
        if n > 0:
            lines += ["", f"  MAC, elastic modes {r + 1}..{r + n} (rows: reduced, "
                      "columns: full model)"]
            lines.append("       " + "".join(f"{r + j + 1:>6}" for j in range(n)))
            for i in range(n):
                lines.append(f"  {r + i + 1:>4} " + "".join(
                    f"{mac[r + i, r + j]:>6.2f}" for j in range(n)))
    return "\n".join(lines)


def _p(x) -> str:
    return "(" + ", ".join(f"{v:.4g}" for v in x) + ")"


def _check_vtu(path) -> None:
    """The ``--vtu`` file, checked before any work: a ``.vtu`` name that can be written."""
    from flexpipe._io import check_output_file

    if Path(path).suffix != ".vtu":
        raise InputError("the mode-shape file must end in .vtu", key="--vtu")
    check_output_file(path, option="--vtu")


def write_modes_vtu(body, path) -> Path:
    """Mode shapes on the body's surface triangles as point data ``mode_07_34.2Hz``."""
    import meshio

    from flexpipe._io import atomic_path

    path = Path(path)
    if path.suffix != ".vtu":
        raise InputError("the mode-shape file must end in .vtu", key="--vtu")
    point_data = {}
    w = len(str(body.n_modes))
    for k, f in enumerate(body.frequencies_hz):
        point_data[f"mode_{k + 1:0{w}d}_{f:.4g}Hz"] = np.ascontiguousarray(body.modes[:, :, k])
    cells = [("triangle", np.asarray(body.triangles))] if len(body.triangles) else \
        [("vertex", np.arange(body.n_nodes)[:, None])]
    m = meshio.Mesh(np.asarray(body.nodes), cells, point_data=point_data,
                    field_data={"frequency_hz": np.asarray(body.frequencies_hz)})
    with atomic_path(path, suffix=".vtu") as tmp:
        meshio.write(tmp, m, file_format="vtu")
    return path
