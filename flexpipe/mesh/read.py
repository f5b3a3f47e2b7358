"""``read_mesh``: one entry point for every mesh format flexpipe reads."""

from __future__ import annotations

import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

from flexpipe._args import as_path
from flexpipe.errors import FlexpipeError, InputError, MeshError
from flexpipe.mesh.mesh import SHELL_TYPES, Mesh
from flexpipe.mesh.units import check_wave_speeds, convert, resolve
from flexpipe.mesh.validate import MeshWarning, validate

#: file suffix -> format name
FORMATS = {
    ".msh": "gmsh", ".inp": "abaqus", ".bdf": "nastran", ".nas": "nastran",
    ".dat": "nastran", ".blk": "nastran", ".bulk": "nastran", ".vtu": "vtu", ".vtk": "vtk",
    ".stl": "surface", ".obj": "surface", ".ply": "surface", ".off": "surface",
}
#: name of the cell set that ``read_mesh(..., thickness=t)`` gives the thickness to
DEFAULT_THICKNESS_SET = "default_thickness"


def _read_raw(path: Path, fmt: str, keep) -> Mesh:
    if fmt in ("nastran", "abaqus"):
        return _read_format(path, fmt, keep)
    try:  # third-party parsers underneath: no exception of theirs reaches the caller raw
        return _read_format(path, fmt, keep)
    except FlexpipeError:
        raise
    except (OSError, MemoryError) as exc:
        raise MeshError(f"cannot read the file ({type(exc).__name__}: {exc})",
                        file=str(path)) from None
    except Exception as exc:  # noqa: BLE001 - a corrupt file in any of many ways
        raise MeshError(f"cannot read as a {fmt} file ({type(exc).__name__}: "
                        f"{' '.join(str(exc).split())[:200]}); is the file complete and in "
                        "that format?", file=str(path)) from None


def _read_format(path: Path, fmt: str, keep) -> Mesh:
    if fmt == "gmsh":
        from flexpipe.mesh.meshio_io import read_gmsh

        return read_gmsh(path, keep=keep)
    if fmt in ("vtu", "vtk"):
        from flexpipe.mesh.meshio_io import read_vtk

        return read_vtk(path, fmt)
    if fmt == "nastran":
        from flexpipe.mesh.nastran import read_nastran

        return read_nastran(path)
    if fmt == "abaqus":
        from flexpipe.mesh.abaqus import read_abaqus

        return read_abaqus(path)
    from flexpipe.mesh.surface import read_surface

    return read_surface(path)


def _add_thickness(mesh: Mesh, thickness) -> Mesh:
    try:
        t = float(thickness)
    except (TypeError, ValueError):
        raise InputError(f"thickness must be a positive length in m, got {thickness!r}",
                         key="thickness") from None
    if not (np.isfinite(t) and t > 0):
        raise InputError(f"thickness must be a positive length in m, got {thickness!r}",
                         key="thickness")
    members = {}
    for bi, b in mesh.blocks_of(*SHELL_TYPES):
        covered = np.zeros(len(b), dtype=bool)
        for name, props in mesh.sections.items():
            if "thickness" in props and bi in mesh.cell_sets.get(name, {}):
                covered[mesh.cell_sets[name][bi]] = True
        if (~covered).any():
            members[bi] = np.flatnonzero(~covered)
    if not mesh.blocks_of(*SHELL_TYPES):
        warnings.warn(MeshWarning(f"{mesh.source}: thickness={t} given but the mesh has no "
                                  "shell elements"), stacklevel=3)
    if not members:
        return mesh
    cell_sets = {DEFAULT_THICKNESS_SET: members, **mesh.cell_sets}
    sections = {DEFAULT_THICKNESS_SET: {"thickness": t}, **mesh.sections}
    return replace(mesh, cell_sets=cell_sets, sections=sections)


def read_mesh(path, scale: float = 1.0, *, units: str | None = None, thickness=None,
              keep=(), prune_unreferenced: bool = False, check_coincident: bool = True,
              format: str | None = None) -> Mesh:
    """Read a mesh file into a checked :class:`~flexpipe.mesh.Mesh` in SI units.

    Parameters
    ----------
    path : str or Path
        Gmsh ``.msh`` (v2.2/v4, ASCII/binary), Abaqus ``.inp``, Nastran bulk data
        ``.bdf/.nas/.dat``, VTK ``.vtu/.vtk``, surfaces ``.stl/.obj/.ply/.off``.
    scale : float
        Length factor applied to geometry only - coordinates, offsets, shell thickness,
        beam A (scale^2) and I, J (scale^4) - e.g. ``1e-3`` for a millimetre mesh.  It does
        **not** convert E, rho, masses or inertias: use ``units`` for solver decks.
    units : str, optional
        Unit system of the file, e.g. ``"mm-t-s"`` (E in MPa, rho in t/mm^3, mass in t),
        ``"mm-kg-s"``, ``"SI"``; converts lengths *and* materials, masses and inertias
        (see :mod:`flexpipe.mesh.units`).
    thickness : float, optional
        Shell thickness in m for shell elements whose file gives none (STL/OBJ/PLY
        surfaces, Gmsh/VTK shells); stored as section ``"default_thickness"``.  Not scaled.
    keep : tuple of str
        Gmsh only: lower-dimensional cell types to keep as elements (e.g. ``("line",)``
        for beams in a shell model); see :mod:`flexpipe.mesh.meshio_io`.
    prune_unreferenced : bool
        Drop nodes no element references instead of raising.
    check_coincident : bool
        Warn about distinct nodes at the same position.
    format : str, optional
        Force a format (``gmsh``, ``abaqus``, ``nastran``, ``vtu``, ``vtk``, ``surface``)
        instead of guessing from the suffix.

    Returns
    -------
    Mesh

    Raises
    ------
    MeshError
        Unreadable or corrupt file, unsupported element type, duplicate ids, NaN
        coordinates, unreferenced nodes, inverted or degenerate elements, every material
        the model uses off the solids' E / rho range the same way (a unit slip of the whole
        deck, without ``units``; a single stiff or light dummy material is a warning; see
        :func:`~flexpipe.mesh.units.check_wave_speeds`); the message names the file, the
        line where known, and the node or element id.
    """
    path = as_path(path, "path")
    if not path.is_file():
        raise MeshError("file not found" if not path.exists() else "not a file",
                        file=str(path))
    fmt = format or FORMATS.get(path.suffix.lower())
    if fmt not in set(FORMATS.values()):
        raise MeshError(f"unknown mesh format '{path.suffix or format}'; valid suffixes: "
                        f"{', '.join(sorted(FORMATS))} (or pass format=...)", file=str(path))
    system, materials = resolve(scale, units)
    if isinstance(keep, str):
        keep = (keep,)
    from flexpipe.mesh.mesh import NODES_PER_CELL

    unknown = [k for k in keep if k not in NODES_PER_CELL]
    if unknown:
        raise MeshError(f"keep: unknown cell type(s) {unknown}; valid: "
                        f"{sorted(NODES_PER_CELL)}", file=str(path), key="keep")
    mesh = _read_raw(path, fmt, tuple(keep))
    mesh = convert(mesh, system, materials=materials)
    check_wave_speeds(mesh, system, materials=materials)
    mesh = replace(mesh, source=str(path))
    if thickness is not None:
        mesh = _add_thickness(mesh, thickness)
    return validate(mesh, prune_unreferenced=prune_unreferenced,
                    check_coincident=check_coincident)
