"""Mode shapes as VTK ``.vtu`` files that ParaView opens.

One file holds every mode: point-data vectors ``mode_01``, ``mode_02``, ... (nodal
translations, plus ``mode_01_rotation``... for models with rotational DOF) and the field
data array ``frequency_hz``.  Optionally one file per mode (``mode_01.vtu``, point data
``displacement``, field data ``frequency_hz``) for ParaView's *Warp By Vector* and
animation.  Shapes are written as given - mass-normalized for :func:`flexpipe.fem.eigenmodes`
output - so choose the warp scale in ParaView.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flexpipe._io import atomic_path
from flexpipe.errors import InputError
from flexpipe.mesh.mesh import Mesh
from flexpipe.mesh.meshio_io import write_vtk


def mode_name(k: int, n: int) -> str:
    """Name of mode ``k`` (0-based) among ``n``: ``mode_01`` ... (zero-padded to >= 2)."""
    return f"mode_{k + 1:0{max(2, len(str(n)))}d}"


def _nodal(mesh: Mesh, shapes: np.ndarray):
    shapes = np.asarray(shapes, dtype=float)
    if shapes.ndim == 1:
        shapes = shapes[:, None]
    n_dof, n = shapes.shape
    if n_dof % mesh.n_nodes:
        raise InputError(f"shapes have {n_dof} rows, not a multiple of the {mesh.n_nodes} "
                         "mesh nodes (expected node-major DOF of the same mesh)")
    dpn = n_dof // mesh.n_nodes
    if dpn not in (3, 6):
        raise InputError(f"shapes imply {dpn} DOF per node; expected 3 or 6")
    return shapes.reshape(mesh.n_nodes, dpn, n), n


def write_modes(path, mesh: Mesh, frequencies_hz, shapes, *, per_mode_dir=None) -> list[Path]:
    """Write mode shapes of ``mesh`` to ``path`` (and per-mode files to ``per_mode_dir``).

    Parameters
    ----------
    path : str or Path
        The ``.vtu`` file with all modes.
    mesh : Mesh
    frequencies_hz : array_like, shape (n,)
    shapes : ndarray, shape (n_nodes * dofs_per_node, n)
        Node-major mode shapes (as returned by :func:`flexpipe.fem.eigenmodes`).
    per_mode_dir : str or Path, optional
        Also write ``mode_01.vtu`` ... into this directory.

    Returns
    -------
    list of Path
        The files written.
    """
    U, n = _nodal(mesh, shapes)
    f = np.asarray(frequencies_hz, dtype=float).ravel()
    if len(f) != n:
        raise InputError(f"{len(f)} frequencies for {n} mode shapes")
    point_data = {}
    for k in range(n):
        name = mode_name(k, n)
        point_data[name] = np.ascontiguousarray(U[:, :3, k])
        if U.shape[1] == 6:
            point_data[f"{name}_rotation"] = np.ascontiguousarray(U[:, 3:, k])
    path = Path(path)
    written = []
    with atomic_path(path, suffix=".vtu") as tmp:
        write_vtk(mesh, tmp, file_format="vtu", point_data=point_data,
                  field_data={"frequency_hz": f})
    written.append(path)
    if per_mode_dir is not None:
        d = Path(per_mode_dir)
        for k in range(n):
            p = d / f"{mode_name(k, n)}.vtu"
            pd = {"displacement": np.ascontiguousarray(U[:, :3, k])}
            if U.shape[1] == 6:
                pd["rotation"] = np.ascontiguousarray(U[:, 3:, k])
            with atomic_path(p, suffix=".vtu") as tmp:
                write_vtk(mesh, tmp, file_format="vtu", point_data=pd,
                          field_data={"frequency_hz": f[k:k + 1]})
            written.append(p)
    return written
