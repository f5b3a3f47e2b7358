"""``write_mesh``: write a :class:`~flexpipe.mesh.Mesh` as Gmsh, Abaqus, Nastran or VTK.

What each format keeps
----------------------
``.msh`` (Gmsh 2.2 ASCII by default, or 4.1; binary optional)
    nodes, elements, cell sets as physical groups (one per element; the first set wins),
    node sets as physical groups of vertex cells.  No sections, masses or links.
``.inp`` (Abaqus)
    everything: sets, sections with materials, point masses (without offsets), rigid
    links as ``*KINEMATIC COUPLING``.
``.bdf``/``.nas``/``.dat`` (Nastran bulk data)
    nodes, elements with property ids, PSHELL/PSOLID/PBAR with MAT1, CONM2, RBE2; no
    named sets.
``.vtu``/``.vtk``
    nodes, elements, node/element ids and property ids as data arrays.

The values are written as stored (SI for a mesh flexpipe read).  Every file is written
atomically: a failure leaves no partial file behind.
"""

from __future__ import annotations

from pathlib import Path

from flexpipe._io import atomic_path
from flexpipe.errors import InputError
from flexpipe.mesh.mesh import Mesh

WRITE_FORMATS = {".msh": "gmsh", ".inp": "abaqus", ".bdf": "nastran", ".nas": "nastran",
                 ".dat": "nastran", ".vtu": "vtu", ".vtk": "vtk"}


def write_mesh(mesh: Mesh, path, *, format: str | None = None, gmsh_version: str = "2.2",
               binary: bool = False) -> Path:
    """Write ``mesh`` to ``path`` in the format given by its suffix (or ``format``).

    Parameters
    ----------
    mesh : Mesh
    path : str or Path
    format : {"gmsh", "abaqus", "nastran", "vtu", "vtk"}, optional
    gmsh_version : {"2.2", "4.1"}
        Gmsh file version.
    binary : bool
        Binary Gmsh file (ASCII by default).

    Returns
    -------
    Path
        The written file.
    """
    path = Path(path)
    fmt = format or WRITE_FORMATS.get(path.suffix.lower())
    if fmt not in set(WRITE_FORMATS.values()):
        raise InputError(f"cannot write format '{path.suffix or format}'; valid suffixes: "
                         f"{', '.join(sorted(WRITE_FORMATS))}", file=str(path))
    if gmsh_version not in ("2.2", "4.1"):
        raise InputError(f"gmsh_version must be '2.2' or '4.1', got {gmsh_version!r}",
                         key="gmsh_version")
    springs = [b.type for b in mesh.blocks if b.type in ("spring", "spring1")]
    if springs and fmt in ("gmsh", "abaqus"):
        raise InputError(f"the mesh has spring elements ({len(springs)} block(s), from "
                         "CELAS/CBUSH or *SPRING), which .msh/.inp output does not carry; "
                         "write a Nastran deck (.bdf) instead", file=str(path))
    lost = [k for k in ("interpolations",) if getattr(mesh, k)]
    if lost and fmt == "gmsh":
        raise InputError("the mesh has RBE3 interpolation constraints, which .msh output "
                         "does not carry; write .bdf instead", file=str(path))
    with atomic_path(path) as tmp:
        if fmt == "gmsh":
            from flexpipe.mesh.meshio_io import write_gmsh

            write_gmsh(mesh, tmp, version=gmsh_version, binary=binary)
        elif fmt in ("vtu", "vtk"):
            from flexpipe.mesh.meshio_io import write_vtk

            write_vtk(mesh, tmp, file_format=fmt)
        elif fmt == "abaqus":
            from flexpipe.mesh.abaqus_write import abaqus_text

            tmp.write_text(abaqus_text(mesh))
        else:
            from flexpipe.mesh.nastran_write import nastran_text

            tmp.write_text(nastran_text(mesh))
    return path
