"""Regenerate the small sample meshes of this folder: ``python meshes/make_samples.py``.

``plate_quad.msh``
    Gmsh 2.2 ASCII: a 0.4 m x 0.3 m plate of 8 x 6 quad shells (physical group
    ``plate``) with the clamped edge x = 0 as a line physical group ``clamped`` (read as a
    node set).  No thickness: ``flexpipe modes meshes/plate_quad.msh --material steel
    --thickness 0.002 --fixed clamped``.
``bracket.bdf``
    Nastran bulk data in SI units: an L-bracket of CQUAD4 shells (PSHELL 3 mm, MAT1
    steel; base flange PID 1, upright PID 2), a CBAR stiffener along the top edge (PBAR,
    PID 3), and a 0.5 kg CONM2 on an RBE2 spider tied to the upright.
    ``flexpipe modes meshes/bracket.bdf --fixed PID1``.
"""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np

from flexpipe.mesh import CellBlock, Mesh, PointMass, RigidLink, write_mesh

HERE = Path(__file__).resolve().parent


def plate_quad(path: Path) -> None:
    nx, ny, Lx, Ly = 8, 6, 0.4, 0.3
    x, y = np.meshgrid(np.linspace(0, Lx, nx + 1), np.linspace(0, Ly, ny + 1), indexing="ij")
    pts = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    i, j = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    n0 = (i * (ny + 1) + j).ravel()
    quads = np.column_stack([n0, n0 + ny + 1, n0 + ny + 2, n0 + 1])
    edge = np.arange(ny + 1)                       # nodes with x = 0
    lines = np.column_stack([edge[:-1], edge[1:]])
    m = meshio.Mesh(pts, [("quad", quads), ("line", lines)],
                    cell_data={"gmsh:physical": [np.full(len(quads), 1), np.full(len(lines), 2)],
                               "gmsh:geometrical": [np.full(len(quads), 1),
                                                    np.full(len(lines), 1)]},
                    field_data={"plate": np.array([1, 2]), "clamped": np.array([2, 1])})
    meshio.write(path, m, file_format="gmsh22", binary=False)


def bracket(path: Path) -> None:
    nx, ny, nz, L, w, h = 5, 3, 3, 0.10, 0.06, 0.05
    xs = np.linspace(0, L, nx + 1)
    base = np.array([[x, y, 0.0] for x in xs for y in np.linspace(0, w, ny + 1)])
    up = np.array([[x, 0.0, z] for x in xs for z in np.linspace(0, h, nz + 1)[1:]])
    pts = np.vstack([base, up])
    nb = len(base)

    def bnode(i, j):
        return i * (ny + 1) + j

    def unode(i, k):  # k = 0 is the shared fold line y = 0, z = 0
        return bnode(i, 0) if k == 0 else nb + i * nz + (k - 1)

    q_base = [[bnode(i, j), bnode(i + 1, j), bnode(i + 1, j + 1), bnode(i, j + 1)]
              for i in range(nx) for j in range(ny)]
    q_up = [[unode(i, k), unode(i, k + 1), unode(i + 1, k + 1), unode(i + 1, k)]
            for i in range(nx) for k in range(nz)]
    top = [[unode(i, nz), unode(i + 1, nz)] for i in range(nx)]
    master = len(pts)
    pts = np.vstack([pts, [[L / 2, -0.02, h / 2]]])
    slaves = np.array([unode(2, 1), unode(3, 1), unode(2, 2), unode(3, 2)])
    quads = np.array(q_base + q_up)
    tags = np.r_[np.full(len(q_base), 1), np.full(len(q_up), 2)]
    steel = {"E": 210e9, "nu": 0.3, "rho": 7850.0}
    b = 0.01
    mesh = Mesh(
        points=pts,
        blocks=(CellBlock("quad", quads, np.arange(1, len(quads) + 1), tags),
                CellBlock("line", np.array(top), np.arange(101, 101 + len(top)),
                          np.full(len(top), 3), {"orientation": np.tile([0.0, 1.0, 0.0],
                                                                         (len(top), 1))})),
        cell_sets={"PID1": {0: np.flatnonzero(tags == 1)}, "PID2": {0: np.flatnonzero(tags == 2)},
                   "PID3": {1: np.arange(len(top))}},
        sections={"PID1": {"thickness": 0.003, **steel}, "PID2": {"thickness": 0.003, **steel},
                  "PID3": {"A": b * b, "Iy": b**4 / 12, "Iz": b**4 / 12,
                           "J": 0.1406 * b**4, **steel}},
        point_masses=(PointMass(master, 0.5, np.diag([2e-4, 2e-4, 2e-4]), id=201),),
        rigid_links=(RigidLink(master, slaves, "123456", 202),),
        source="meshes/make_samples.py",
    )
    write_mesh(mesh, path)


if __name__ == "__main__":
    plate_quad(HERE / "plate_quad.msh")
    bracket(HERE / "bracket.bdf")
    print("wrote", HERE / "plate_quad.msh", HERE / "bracket.bdf")
