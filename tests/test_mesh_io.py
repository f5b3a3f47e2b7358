"""Mesh import/export: literal decks parsed to their literal values, Gmsh v2/v4 files
written by meshio, round trips through every format (same M and K); bad input is in
test_mesh_errors.py."""

from __future__ import annotations

import importlib.util
import warnings

import meshio
import numpy as np
import pytest
from _meshdata import STEEL
from _meshdata import deck as _deck
from _meshdata import write as _write

from flexpipe.errors import MeshError
from flexpipe.fem import BeamSection, assemble
from flexpipe.mesh import CellBlock, Mesh, MeshWarning, PointMass, RigidLink, read_mesh, write_mesh
from flexpipe.mesh.generate import box, plate


def _row(*fields):
    """One small-field (8 character) line, as typed into a fixed-format deck."""
    return "".join(f"{f:<8}" if i == 0 else f"{f:>8}" for i, f in enumerate(fields))


def _large(*fields):
    """One large-field line: 8-character name/continuation, then 16-character fields."""
    return f"{fields[0]:<8}" + "".join(f"{f:>16}" for f in fields[1:])


DECK = "\n".join([
    "$ parser test deck: free, small and large field, continuations",
    "SOL 103",
    "CEND",
    "TITLE = parser test",
    "BEGIN BULK",
    "GRID,1,,0.,0.,0.",
    "GRID,2,,1.,0.,0.",
    "GRID,3,,1.,1.,0.",
    "GRID,4,,0.,1.,0.",
    _row("GRID", "5", "", "0.", "0.", "1."),
    _row("GRID", "6", "", "1.0+0", "0.", "1."),
    _large("GRID*", "7", "", "1.0", "1.0"),
    _large("*", "1.0E+00"),
    "GRID*,8,,0.,1.",
    "*,1.",
    "GRID,9,,2.,0.,0.",
    "GRID,10,,2.,1.,0.",
    "GRID,11,,3.,0.,0.",
    "GRID,12,,0.,0.,2.",
    "GRID,13,,1.,0.,2.",
    "GRID,14,,.5,.5,.5   $ trailing comment",
    _row("CHEXA", "10", "1", "1", "2", "3", "4", "5", "6", "+HEX1"),
    _row("+HEX1", "7", "8"),
    "CQUAD4,20,2,2,9,10,3",
    _row("CTRIA3", "21", "2", "9", "11", "10"),
    "CBAR,30,3,5,12,8",
    _row("CBAR", "31", "3", "12", "13", "0.", "0.", "1."),
    "CTETRA,40,1,1,2,4,5",
    "PSOLID,1,1",
    _row("PSHELL", "2", "2", "2.-3", "2"),
    "PBAR,3,1,1.-4,2.-9,3.-9,4.-9",
    "MAT1,1,2.1+11,,0.3,7850.",
    _row("MAT1", "2", "7.0E+10", "2.6E+10", "", "2700."),
    _large("CONM2*", "50", "14", "0", "2.5"),
    _large("*", "0.1", "0.0", "0.0"),
    _large("*", "1.0", "0.1", "2.0", "0.2"),
    _large("*", "0.3", "3.0"),
    "RBE2,60,14,123456,1,2,3,4",
    "ENDDATA",
    "GRID,99,,9.,9.,9.   $ after ENDDATA: ignored",
]) + "\n"

XYZ = {1: (0, 0, 0), 2: (1, 0, 0), 3: (1, 1, 0), 4: (0, 1, 0), 5: (0, 0, 1), 6: (1, 0, 1),
       7: (1, 1, 1), 8: (0, 1, 1), 9: (2, 0, 0), 10: (2, 1, 0), 11: (3, 0, 0), 12: (0, 0, 2),
       13: (1, 0, 2), 14: (0.5, 0.5, 0.5)}




def _by_type(mesh):
    return {b.type: b for b in mesh.blocks}


def test_nastran_deck_literal_values(tmp_path):
    mesh = read_mesh(_write(tmp_path, "deck.bdf", DECK))
    assert mesh.node_ids.tolist() == list(XYZ)
    np.testing.assert_array_equal(mesh.points, np.array(list(XYZ.values()), dtype=float))
    b = _by_type(mesh)
    conn = {t: mesh.node_ids[blk.cells].tolist() for t, blk in b.items()}
    assert conn == {"hexahedron": [[1, 2, 3, 4, 5, 6, 7, 8]], "quad": [[2, 9, 10, 3]],
                    "triangle": [[9, 11, 10]], "line": [[5, 12], [12, 13]],
                    "tetra": [[1, 2, 4, 5]]}
    assert b["line"].ids.tolist() == [30, 31] and b["line"].tags.tolist() == [3, 3]
    # CBAR 30 orientation from G0 = 8: X8 - X5; CBAR 31 from its vector
    np.testing.assert_array_equal(b["line"].data["orientation"], [[0, 1, 0], [0, 0, 1]])
    s = mesh.sections
    assert s["PID1"] == {"E": 2.1e11, "nu": 0.3, "rho": 7850.0}
    assert s["PID2"]["thickness"] == 2e-3 and s["PID2"]["rho"] == 2700.0
    assert s["PID2"]["E"] == 7.0e10 and s["PID2"]["nu"] == pytest.approx(7.0 / 5.2 - 1, 1e-14)
    assert (s["PID3"]["A"], s["PID3"]["Iz"], s["PID3"]["Iy"], s["PID3"]["J"]) == (
        1e-4, 2e-9, 3e-9, 4e-9)  # Nastran I1 bends in the x-y plane: Iz
    assert sorted(mesh.cell_sets["PID1"]) == [0, 4]  # hexahedron and tetra blocks
    (pm,) = mesh.point_masses
    assert (int(mesh.node_ids[pm.node]), pm.mass, pm.id) == (14, 2.5, 50)
    np.testing.assert_array_equal(pm.offset, [0.1, 0.0, 0.0])
    np.testing.assert_array_equal(pm.inertia, [[1.0, -0.1, -0.2], [-0.1, 2.0, -0.3],
                                               [-0.2, -0.3, 3.0]])
    (link,) = mesh.rigid_links
    assert int(mesh.node_ids[link.master]) == 14 and link.dofs == "123456"
    assert mesh.node_ids[link.slaves].tolist() == [1, 2, 3, 4]


def test_nastran_units_and_scale(tmp_path):
    p = _write(tmp_path, "deck.bdf", DECK)
    mm = read_mesh(p, units="mm-t-s")   # E in MPa, rho in t/mm^3, mass in t
    np.testing.assert_allclose(mm.points, np.array(list(XYZ.values())) * 1e-3, rtol=1e-15)
    assert mm.sections["PID1"]["E"] == pytest.approx(2.1e11 * 1e6, rel=1e-15)
    assert mm.sections["PID1"]["rho"] == pytest.approx(7850.0 * 1e12, rel=1e-15)
    assert mm.sections["PID2"]["thickness"] == pytest.approx(2e-6, rel=1e-15)
    assert mm.sections["PID3"]["A"] == pytest.approx(1e-4 * 1e-6, rel=1e-15)
    assert mm.sections["PID3"]["Iz"] == pytest.approx(2e-9 * 1e-12, rel=1e-15)
    (pm,) = mm.point_masses
    assert pm.mass == pytest.approx(2.5e3, rel=1e-15)
    np.testing.assert_allclose(pm.inertia[0], [1e-3, -1e-4, -2e-4], rtol=1e-15)  # t mm^2
    np.testing.assert_allclose(pm.offset, [1e-4, 0, 0], rtol=1e-15)
    geo = read_mesh(p, 1e-3)          # scale: geometry only, materials untouched
    assert geo.sections["PID1"]["E"] == 2.1e11 and geo.point_masses[0].mass == 2.5
    assert geo.sections["PID2"]["thickness"] == pytest.approx(2e-6, rel=1e-15)
    with pytest.raises(Exception, match="contradicts"):
        read_mesh(p, 0.5, units="mm-t-s")


def test_nastran_include_and_cord2r(tmp_path):
    _write(tmp_path, "grids.inc", "GRID,1,,0.,0.,0.\nGRID,2,5,1.,0.,0.\n"
                                  "GRID,3,5,0.,1.,0.\nGRID,4,5,0.,0.,1.\n")
    # system 5: origin (10, 0, 0), z along basic x, x-z plane through basic (10, 0, -1)
    main = _write(tmp_path, "main.bdf", "BEGIN BULK\nINCLUDE 'grids.inc'\n"
                  "CORD2R,5,,10.,0.,0.,11.,0.,0.\n,10.,0.,-1.\nCTETRA,1,1,1,2,3,4\n")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        mesh = read_mesh(main, prune_unreferenced=False)
    # local x = y_l x z_l with y_l = z_l x (C - A) = (1,0,0) x (0,0,-1) = (0, 1, 0)
    np.testing.assert_allclose(mesh.points, [[0, 0, 0], [10, 0, -1], [10, 1, 0], [11, 0, 0]],
                               atol=1e-14)


ABAQUS = """*HEADING
test deck
** comment
*NODE, NSET=ALLN
1, 0., 0., 0.
2, 1., 0., 0.
3, 0., 1., 0.
4, 0., 0., 1.
5, 1., 1., 0.
6, 2., 0., 0.
7, 2., 1., 0.
8, 0.5, 0.5, -1.
*ELEMENT, TYPE=C3D4, ELSET=SOLID
10, 1, 2, 3, 4
*ELEMENT, TYPE=S4R, ELSET=SKIN
20, 2, 6, 7, 5
*ELEMENT, TYPE=MASS, ELSET=PMASS
30, 8
*NSET, NSET=BASE, GENERATE
1, 3, 1
*ELSET, ELSET=ALL
SOLID, SKIN
*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL
*SHELL SECTION, ELSET=SKIN, MATERIAL=ALU
0.0015
*MATERIAL, NAME=STEEL
*ELASTIC
2.1e11, 0.3
*DENSITY
7850.
*MATERIAL, NAME=ALU
*ELASTIC
7.0e10, 0.33
*DENSITY
2700.
*MASS, ELSET=PMASS
1.5
*KINEMATIC COUPLING, REF NODE=8
BASE, 1, 6
*STEP
*STATIC
*END STEP
"""


def test_abaqus_deck_literal_values(tmp_path):
    mesh = read_mesh(_write(tmp_path, "deck.inp", ABAQUS))
    assert mesh.node_ids.tolist() == list(range(1, 9))
    assert mesh.points[7].tolist() == [0.5, 0.5, -1.0]
    b = _by_type(mesh)
    assert mesh.node_ids[b["tetra"].cells].tolist() == [[1, 2, 3, 4]]
    assert mesh.node_ids[b["quad"].cells].tolist() == [[2, 6, 7, 5]]
    assert b["quad"].ids.tolist() == [20]
    assert mesh.node_ids[mesh.node_sets["BASE"]].tolist() == [1, 2, 3]
    assert len(mesh.node_sets["ALLN"]) == 8
    assert {k: sorted(v) for k, v in mesh.cell_sets["ALL"].items()} == {0: [0], 1: [0]}
    assert mesh.sections["SOLID"] == {"E": 2.1e11, "nu": 0.3, "rho": 7850.0}
    assert mesh.sections["SKIN"] == {"thickness": 0.0015, "E": 7.0e10, "nu": 0.33,
                                     "rho": 2700.0}
    (pm,) = mesh.point_masses
    assert (int(mesh.node_ids[pm.node]), pm.mass) == (8, 1.5)
    (link,) = mesh.rigid_links
    assert int(mesh.node_ids[link.master]) == 8 and link.dofs == "123456"
    assert sorted(mesh.node_ids[link.slaves].tolist()) == [1, 2, 3]


def test_beam_orientation_nodes_are_used_then_dropped(tmp_path):
    bdf = _write(tmp_path, "bars.bdf", _deck(
        "GRID,1,,0.,0.,0.", "GRID,2,,1.,0.,0.", "GRID,3,,2.,0.,0.", "GRID,9,,0.,5.,3.",
        "CBAR,1,7,1,2,9", "CBAR,2,7,2,3,0.,0.,1.", "PBAR,7,1,6.-4,2.-8,4.5-8,3.-8",
        "MAT1,1,2.1+11,,0.3,7850."))
    mesh = read_mesh(bdf)
    assert mesh.node_ids.tolist() == [1, 2, 3]            # GRID 9 only orients CBAR 1
    np.testing.assert_array_equal(mesh.blocks[0].data["orientation"], [[0, 5, 3], [0, 0, 1]])
    inp = _write(tmp_path, "beams.inp", "\n".join([
        "*NODE", "1, 0., 0., 0.", "2, 1., 0., 0.", "3, 2., 0., 0.", "9, 0., 5., 3.",
        "*ELEMENT, TYPE=B31, ELSET=RAIL", "1, 1, 2, 9", "2, 2, 3",
        "*BEAM SECTION, ELSET=RAIL, MATERIAL=STEEL, SECTION=RECT", "0.02, 0.03", "0., 0., 1.",
        "*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1e11, 0.3", "*DENSITY", "7850."]) + "\n")
    mesh = read_mesh(inp)
    assert mesh.node_ids.tolist() == [1, 2, 3]
    np.testing.assert_array_equal(mesh.blocks[0].data["orientation"], [[0, 5, 3], [0, 0, 1]])
    sec = mesh.sections["RAIL"]
    # RECT a (along n1 = local y) x b (along n2 = local z): Iy = a b^3 / 12, Iz = b a^3 / 12
    assert sec["A"] == pytest.approx(6e-4, rel=1e-14)
    assert sec["Iy"] == pytest.approx(0.02 * 0.03**3 / 12, rel=1e-14)
    assert sec["Iz"] == pytest.approx(0.03 * 0.02**3 / 12, rel=1e-14)
    assert (sec["E"], sec["nu"], sec["rho"]) == (2.1e11, 0.3, 7850.0)


def _gmsh_source(version):
    """A tet body with a physical boundary face, a beam line and a lonely vertex."""
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 1], [2, 2, 2]], float)
    cells = [("tetra", np.array([[0, 1, 2, 3], [1, 2, 3, 4]])), ("triangle", np.array([[0, 1, 2]])),
             ("line", np.array([[4, 5]])), ("vertex", np.array([[3]]))]
    phys = [np.array([1, 1]), np.array([2]), np.array([3]), np.array([4])]
    geo = [np.array([1, 1]), np.array([1]), np.array([1]), np.array([1])]
    field = {"body": np.array([1, 3]), "fixed": np.array([2, 2]),
             "beam_rail": np.array([3, 1]), "tip": np.array([4, 0])}
    m = meshio.Mesh(pts, cells, cell_data={"gmsh:physical": phys, "gmsh:geometrical": geo},
                    field_data=field)
    if version == "4.1":  # each entity needs a node of its own in Gmsh 4.1
        dim_tags = np.array([[2, 1], [3, 1], [3, 1], [0, 1], [3, 1], [1, 1]])
        m.point_data["gmsh:dim_tags"] = dim_tags
    return m


@pytest.mark.parametrize("version,binary", [("2.2", False), ("2.2", True), ("4.1", False),
                                            ("4.1", True)])
def test_gmsh_written_by_meshio(tmp_path, version, binary):
    src = _gmsh_source(version)
    p = tmp_path / "body.msh"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        meshio.write(p, src, file_format="gmsh22" if version == "2.2" else "gmsh", binary=binary)
    mesh = read_mesh(p)
    np.testing.assert_array_equal(mesh.points, src.points)
    b = _by_type(mesh)
    assert sorted(b) == ["line", "tetra"]          # beam_ kept, face and vertex dropped
    np.testing.assert_array_equal(b["tetra"].cells, [[0, 1, 2, 3], [1, 2, 3, 4]])
    np.testing.assert_array_equal(b["line"].cells, [[4, 5]])
    assert mesh.node_sets["fixed"].tolist() == [0, 1, 2]
    assert mesh.node_sets["tip"].tolist() == [3]
    assert mesh.node_sets["beam_rail"].tolist() == [4, 5]
    assert {k: v.tolist() for k, v in mesh.cell_sets["body"].items()} == {0: [0, 1]}
    assert b["tetra"].tags.tolist() == [1, 1]
    kept = read_mesh(p, keep=("triangle",))       # explicitly kept lower-dimensional cells
    assert sorted(_by_type(kept)) == ["line", "tetra", "triangle"]


def test_gmsh_node_tags_become_node_ids(tmp_path):
    p = _write(tmp_path, "tags.msh", "\n".join([
        "$MeshFormat", "2.2 0 8", "$EndMeshFormat", "$Nodes", "5",
        "40 0 0 1", "10 0 0 0", "20 1 0 0", "30 0 1 0", "50 9 9 9", "$EndNodes",
        "$Elements", "1", "7 4 2 1 1 10 20 30 40", "$EndElements"]) + "\n")
    with pytest.raises(MeshError, match=r"tags.msh: 1 node.*node ids \[50\]"):
        read_mesh(p)
    mesh = read_mesh(p, prune_unreferenced=True)
    assert mesh.node_ids.tolist() == [10, 20, 30, 40]          # sorted by tag
    np.testing.assert_array_equal(mesh.points, [[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    assert mesh.node_ids[mesh.blocks[0].cells].tolist() == [[10, 20, 30, 40]]


def _matrices_equal(a, b, tol=1e-12):
    for X, Y in ((a.K, b.K), (a.M, b.M)):
        assert X.shape == Y.shape
        assert abs(X - Y).max() <= tol * abs(X).max()


def _solid_bodies():
    out = [("tetra", box(0.5, 0.2, 0.1, 4, 2, 2))]
    for cell in ("hexahedron", "tetra10"):
        fam = {"hexahedron": "flexpipe.fem.hex8", "tetra10": "flexpipe.fem.tet10"}[cell]
        if importlib.util.find_spec(fam) is not None:
            out.append((cell, box(0.5, 0.2, 0.1, 3, 2, 1, cell=cell)))
    return out


FORMATS = [("msh", {}), ("msh", {"gmsh_version": "4.1", "binary": True}), ("inp", {}),
           ("bdf", {}), ("vtu", {}), ("vtk", {})]


@pytest.mark.parametrize("ext,opts", FORMATS, ids=[f"{e}{o.get('gmsh_version', '')}"
                                                   for e, o in FORMATS])
def test_round_trip_solids_same_matrices(tmp_path, ext, opts):
    for name, body in _solid_bodies():
        fe0 = assemble(body, STEEL)
        p = tmp_path / f"{name}.{ext}"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", MeshWarning)
            write_mesh(body, p, **opts)
            back = read_mesh(p)
        assert back.n_nodes == body.n_nodes
        _matrices_equal(assemble(back, STEEL), fe0)


def _shell_beam_body():
    p = plate(0.4, 0.3, 4, 3)
    edge = p.node_sets["ymin"]
    lines = np.column_stack([edge[:-1], edge[1:]])
    return Mesh(p.points, (p.blocks[0], CellBlock("line", lines)), node_sets=p.node_sets,
                cell_sets={"shell": {0: np.arange(len(p.blocks[0]))},
                           "rail": {1: np.arange(len(lines))}})


@pytest.mark.parametrize("ext", ["msh", "inp", "bdf", "vtu"])
def test_round_trip_shells_and_beams(tmp_path, ext):
    body = _shell_beam_body()
    sec = BeamSection.rectangle(0.02, 0.03)
    fe0 = assemble(body, STEEL, thickness=0.002, beam_section=sec)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        write_mesh(body, tmp_path / f"b.{ext}")
        back = read_mesh(tmp_path / f"b.{ext}")
    assert sorted(b.type for b in back.blocks) == ["line", "quad"]
    _matrices_equal(assemble(back, STEEL, thickness=0.002, beam_section=sec), fe0)


def _rich_body():
    """Shells and beams whose properties the file must carry, a point mass and an RBE2."""
    p = plate(0.4, 0.3, 4, 3)
    edge = p.node_sets["ymin"]
    lines = np.column_stack([edge[:-1], edge[1:]])
    pts = np.vstack([p.points, [[0.2, 0.15, 0.1]]])
    master = len(pts) - 1
    ori = np.tile([0.0, 1.0, 1.0], (len(lines), 1))
    steel = {"E": 210e9, "nu": 0.3, "rho": 7850.0}
    return Mesh(
        pts, (CellBlock("quad", p.blocks[0].cells, tags=np.ones(len(p.blocks[0]), int)),
              CellBlock("line", lines, tags=np.full(len(lines), 2), data={"orientation": ori})),
        cell_sets={"PID1": {0: np.arange(len(p.blocks[0]))}, "PID2": {1: np.arange(len(lines))}},
        sections={"PID1": {"thickness": 0.0015, "E": 70e9, "nu": 0.33, "rho": 2700.0},
                  "PID2": {"A": 6e-4, "Iy": 2e-8, "Iz": 4.5e-8, "J": 3.3e-8, **steel}},
        point_masses=(PointMass(master, 3.0, np.array([[0.1, 0.01, 0], [0.01, 0.2, 0],
                                                       [0, 0, 0.3]]), id=900),),
        rigid_links=(RigidLink(master, np.array([6, 7, 10, 11]), "123456", 901),),
    )


@pytest.mark.parametrize("ext", ["inp", "bdf"])
def test_round_trip_properties_masses_links(tmp_path, ext):
    body = _rich_body()
    fe0 = assemble(body)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        write_mesh(body, tmp_path / f"rich.{ext}")
        back = read_mesh(tmp_path / f"rich.{ext}")
    assert len(back.point_masses) == 1 and len(back.rigid_links) == 1
    fe = assemble(back)
    _matrices_equal(fe, fe0)
    assert abs(fe.T - fe0.T).max() < 1e-12


def test_surface_stl_as_shell_mid_surface(tmp_path):
    import trimesh

    tri = plate(0.5, 0.2, 5, 2, cell="triangle")
    trimesh.Trimesh(tri.points, tri.blocks[0].cells, process=False).export(tmp_path / "s.stl")
    # STL stores every triangle's corners separately: they must be merged again
    mesh = read_mesh(tmp_path / "s.stl", thickness=0.003)
    assert mesh.n_nodes == tri.n_nodes and len(mesh.blocks[0]) == len(tri.blocks[0])
    fe = assemble(mesh, STEEL)   # binary STL stores float32 coordinates: ~1e-7 relative
    assert fe.total_mass == pytest.approx(7850.0 * 0.5 * 0.2 * 0.003, rel=1e-6)


# ---------------------------------------------------------------- bad input


def test_sample_meshes_match_their_files():
    from pathlib import Path

    root = Path(__file__).resolve().parents[1] / "meshes"
    bdf = root / "bracket.bdf"
    grids = [ln for ln in bdf.read_text().splitlines() if ln.startswith("GRID")]
    mesh = read_mesh(bdf)
    assert mesh.n_nodes == len(grids)
    assert {"PID1", "PID2", "PID3"} <= set(mesh.sections)
    assert len(mesh.point_masses) == 1 and mesh.point_masses[0].mass == 0.5
    plate_mesh = read_mesh(root / "plate_quad.msh")
    assert np.all(plate_mesh.points[plate_mesh.node_sets["clamped"], 0] == 0.0)
    assert [b.type for b in plate_mesh.blocks] == ["quad"]


# ------------------------------------------------- surfaces, scale, CBEAM, degenerate cells


@pytest.mark.parametrize("ext", ["obj", "ply", "off"])
def test_surface_obj_ply_off_as_shell_mid_surfaces_in_mm(tmp_path, ext):
    """A 500 mm x 200 mm triangulated surface, written by trimesh, read with scale=1e-3
    and a user thickness: the original node count and the mass rho * A * t."""
    import trimesh

    tri = plate(0.5, 0.2, 5, 2, cell="triangle")
    p = tmp_path / f"s.{ext}"
    trimesh.Trimesh(tri.points * 1e3, tri.blocks[0].cells, process=False).export(p)
    mesh = read_mesh(p, 1e-3, thickness=0.003)
    assert mesh.n_nodes == tri.n_nodes and [b.type for b in mesh.blocks] == ["triangle"]
    assert len(mesh.blocks[0]) == len(tri.blocks[0])
    assert np.ptp(mesh.points, axis=0) == pytest.approx([0.5, 0.2, 0.0], abs=1e-9)
    fe = assemble(mesh, STEEL)          # binary PLY stores float32: ~1e-7 relative
    assert fe.total_mass == pytest.approx(7850.0 * 0.5 * 0.2 * 0.003, rel=1e-6)
    assert mesh.sections["default_thickness"]["thickness"] == 0.003   # not scaled


@pytest.mark.parametrize("ext", ["msh", "vtu", "inp", "bdf"])
def test_scale_reads_a_millimetre_mesh_as_the_metre_mesh(tmp_path, ext):
    """The same body in mm, read with scale=1e-3, gives the matrices of the metre body."""
    body = box(0.5, 0.2, 0.1, 4, 2, 2, cell="hexahedron")
    mm = Mesh(body.points * 1e3, body.blocks, node_sets=body.node_sets)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        write_mesh(mm, tmp_path / f"mm.{ext}")
        back = read_mesh(tmp_path / f"mm.{ext}", scale=1e-3)
    np.testing.assert_allclose(back.points, body.points, rtol=0, atol=1e-15)
    _matrices_equal(assemble(back, STEEL), assemble(body, STEEL))
    unscaled = assemble(read_mesh(tmp_path / f"mm.{ext}"), STEEL)
    assert unscaled.total_mass == pytest.approx(7850.0 * 500 * 200 * 100, rel=1e-12)


@pytest.mark.parametrize("ext", ["nas", "dat"])
def test_nastran_cbeam_pbeam_and_deck_suffixes(tmp_path, ext):
    p = _write(tmp_path, f"frame.{ext}", _deck(
        "GRID,1,,0.,0.,0.", "GRID,2,,0.5,0.,0.", "GRID,3,,1.,0.,0.", "GRID,8,,0.,3.,4.",
        "CBEAM,11,4,1,2,0.,1.,0.", "CBEAM,12,4,2,3,8",
        "PBEAM,4,7,6.-4,2.-8,4.5-8,0.,3.-8", "MAT1,7,2.1+11,,0.3,7850."))
    mesh = read_mesh(p)
    (b,) = mesh.blocks
    assert b.type == "line" and b.ids.tolist() == [11, 12]
    assert mesh.node_ids.tolist() == [1, 2, 3]          # GRID 8 only orients CBEAM 12
    # CBEAM 12: v = X(G0) - X(GA) = (0, 3, 4) - (0.5, 0, 0)
    np.testing.assert_array_equal(b.data["orientation"], [[0, 1, 0], [-0.5, 3, 4]])
    # PBEAM: PID MID A I1 I2 I12 J; Nastran I1 bends in the element x-y plane (our Iz)
    s = mesh.sections["PID4"]
    assert (s["A"], s["Iz"], s["Iy"], s["J"]) == (6e-4, 2e-8, 4.5e-8, 3e-8)
    assert (s["E"], s["nu"], s["rho"]) == (2.1e11, 0.3, 7850.0)
    assert assemble(mesh).total_mass == pytest.approx(7850.0 * 6e-4 * 1.0, rel=1e-12)


def test_a_mesh_copies_its_arrays_and_leaves_the_callers_writable():
    """Frozen Mesh fields are read-only copies: the caller's arrays stay writable and a
    later change of them does not show through the mesh."""
    points = np.array([[0.0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])
    cells = np.array([[0, 1, 2, 3]], dtype=np.int64)
    mesh = Mesh(points=points, blocks=[CellBlock("tetra", cells)])
    assert points.flags.writeable and cells.flags.writeable
    assert not mesh.points.flags.writeable and not mesh.blocks[0].cells.flags.writeable
    points[1, 0] = 9.0
    cells[0, 0] = 3
    assert mesh.points[1, 0] == 1.0 and mesh.blocks[0].cells[0, 0] == 0
