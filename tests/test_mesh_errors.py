"""Mesh bad input: corrupt, unknown, inverted, orphan, duplicate, disconnected, missing
properties — each error names the file, the line and the node or element id; writes are
atomic."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import meshio
import numpy as np
import pytest
from _meshdata import STEEL
from _meshdata import deck as _deck
from _meshdata import write as _write

from flexpipe.errors import MeshError, ModelError
from flexpipe.fem import assemble
from flexpipe.mesh import MeshWarning, read_mesh, write_mesh
from flexpipe.mesh.generate import box, plate

TET = ["GRID,1,,0.,0.,0.", "GRID,2,,1.,0.,0.", "GRID,3,,0.,1.,0.", "GRID,4,,0.,0.,1."]


def test_missing_and_unknown_files(tmp_path):
    with pytest.raises(MeshError, match="nope.bdf: file not found"):
        read_mesh(tmp_path / "nope.bdf")
    with pytest.raises(MeshError, match=r"x\.xyz.*unknown mesh format '\.xyz'"):
        read_mesh(_write(tmp_path, "x.xyz", "1 2 3"))


def test_corrupt_gmsh_names_file(tmp_path):
    p = _write(tmp_path, "broken.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0\n")
    with pytest.raises(MeshError, match=r"broken.msh, line 4: section \$Nodes is not closed"):
        read_mesh(p)
    p = tmp_path / "garbage.inp"
    p.write_bytes(b"\x00\x01\x02binary")
    with pytest.raises(MeshError, match="garbage.inp"):
        read_mesh(p)


def test_unsupported_element_types(tmp_path):
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0.5, 0, 0], [0.5, 0.5, 0], [0, 0.5, 0]])
    p = tmp_path / "t6.msh"
    meshio.write(p, meshio.Mesh(pts, [("triangle6", np.arange(6)[None])]), file_format="gmsh22",
                 binary=False)
    with pytest.raises(MeshError, match=r"t6.msh: element type 'triangle6'.*supported: .*quad"):
        read_mesh(p)
    bdf = _write(tmp_path, "gap.bdf", _deck(*TET, "GRID,5,,1.,1.,0.", "GRID,6,,1.,1.,1.",
                                            "CGAP,77,1,1,2"))
    with pytest.raises(MeshError, match=r"gap.bdf, line 8: CGAP 77: CGAP is not supported"):
        read_mesh(bdf)
    inp = _write(tmp_path, "c20.inp", "*NODE\n1,0,0,0\n*ELEMENT, TYPE=C3D20\n1,1\n")
    with pytest.raises(MeshError, match=r"c20.inp, line 3: element type 'C3D20' is not supported"):
        read_mesh(inp)


def test_nan_coordinates_name_node(tmp_path):
    pts = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, np.nan]])
    p = tmp_path / "nan.vtu"
    meshio.write(p, meshio.Mesh(pts, [("tetra", np.array([[0, 1, 2, 3]]))]))
    with pytest.raises(MeshError, match=r"nan.vtu: 1 node\(s\) have non-finite.*node ids \[4\]"):
        read_mesh(p)


def test_unreferenced_nodes_error_and_prune(tmp_path):
    p = _write(tmp_path, "orphan.inp", "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n"
               "99,5,5,5\n*ELEMENT, TYPE=C3D4\n1,1,2,3,4\n")
    with pytest.raises(MeshError, match=r"orphan.inp: 1 node.*ids \[99\].*prune_unreferenced=True"):
        read_mesh(p)
    mesh = read_mesh(p, prune_unreferenced=True)
    assert mesh.node_ids.tolist() == [1, 2, 3, 4]
    # Nastran accepts unreferenced GRIDs (AUTOSPC removes their DOF): a warning, left out
    p = _write(tmp_path, "orphan.bdf", _deck(*TET, "GRID,99,,5.,5.,5.", "CTETRA,1,1,1,2,3,4"))
    with pytest.warns(MeshWarning, match=r"orphan.bdf: 1 GRID\(s\) belong to no element.*99"):
        mesh = read_mesh(p)
    assert mesh.node_ids.tolist() == [1, 2, 3, 4]
    assert mesh.node_ids[mesh.blocks[0].cells].tolist() == [[1, 2, 3, 4]]


def test_duplicate_grid_names_both_lines(tmp_path):
    p = _write(tmp_path, "dup.bdf", _deck(*TET, "GRID,3,,0.,2.,0.", "CTETRA,1,1,1,2,3,4"))
    with pytest.raises(MeshError, match=r"dup.bdf, line 6: GRID id 3 is defined twice: GRID at "
                                        r"dup.bdf line 4 and GRID at dup.bdf line 6"):
        read_mesh(p)


def test_undefined_grid_and_bad_number(tmp_path):
    p = _write(tmp_path, "undef.bdf", _deck(*TET, "CTETRA,8,1,1,2,3,42"))
    with pytest.raises(MeshError, match=r"undef.bdf, line 6: CTETRA 8: .*GRID 42"):
        read_mesh(p)
    p = _write(tmp_path, "num.bdf", _deck("GRID,1,,0.,abc,0."))
    with pytest.raises(MeshError, match=r"num.bdf, line 2: GRID 1: field X2 = 'abc' is not a"):
        read_mesh(p)


def test_coincident_nodes_warn_with_ids(tmp_path):
    p = _write(tmp_path, "twin.bdf", _deck(*TET, "GRID,5,,1.,0.,0.", "GRID,6,,0.,1.,0.",
                                           "GRID,7,,0.,0.,1.", "CTETRA,1,1,1,2,3,4",
                                           "CTETRA,2,1,1,5,6,7"))
    with pytest.warns(MeshWarning, match=r"twin.bdf: 3 pair\(s\) .*2 & 5"):
        read_mesh(p)


def test_inverted_tet_names_element(tmp_path):
    p = _write(tmp_path, "inv.bdf", _deck(*TET, "CTETRA,31,1,1,3,2,4"))
    with pytest.raises(MeshError, match=r"inv.bdf: 1 tetra element\(s\) are inverted.*ids \[31\]"):
        read_mesh(p)


def test_disconnected_parts_from_file(tmp_path):
    far = ["GRID,5,,5.,0.,0.", "GRID,6,,6.,0.,0.", "GRID,7,,5.,1.,0.", "GRID,8,,5.,0.,1."]
    p = _write(tmp_path, "two.bdf", _deck(*TET, *far, "CTETRA,1,1,1,2,3,4",
                                          "CTETRA,2,1,5,6,7,8"))
    mesh = read_mesh(p)
    with pytest.raises(ModelError, match=r"two.bdf.*2 disconnected parts.*node [15] "):
        assemble(mesh, STEEL)


def test_shells_without_thickness_name_file_and_elements(tmp_path):
    p = tmp_path / "plate.msh"
    write_mesh(plate(0.2, 0.1, 2, 1), p)
    mesh = read_mesh(p)
    with pytest.raises(MeshError, match=r"plate.msh: 2 shell \(quad\) element\(s\) have no "
                                        r"positive thickness, e.g. ids \[1, 2\]"):
        assemble(mesh, STEEL)
    assert assemble(read_mesh(p, thickness=0.001), STEEL).total_mass == pytest.approx(
        7850.0 * 0.2 * 0.1 * 0.001, rel=1e-12)


def test_writes_are_atomic(tmp_path, monkeypatch):
    body = box(0.2, 0.1, 0.1, 1, 1, 1)
    p = tmp_path / "a.msh"
    p.write_text("old")

    def crash(path, *args, **kwargs):  # a writer that dies half-way through
        with open(path, "w") as fh:
            fh.write("$MeshFormat\n")
        raise RuntimeError("disk full")

    monkeypatch.setattr(meshio, "write", crash)
    with pytest.raises(RuntimeError, match="disk full"):
        write_mesh(body, p)
    assert p.read_text() == "old" and sorted(x.name for x in tmp_path.iterdir()) == ["a.msh"]


@pytest.mark.parametrize("cards,match", [
    (["GRID,5,,1.,1.,0.", "CTETRA,31,1,1,2,3,5"],                      # four nodes in z = 0
     r"flat.bdf: 1 tetra element\(s\) have zero volume.*ids \[31\]"),
    (["CTETRA,32,1,1,2,3,3"], r"flat.bdf: 1 tetra element\(s\) use the same node twice.*\[32\]"),
    (["GRID,5,,2.,0.,0.", "GRID,6,,3.,0.,0.", "CQUAD4,33,1,1,2,5,6"],  # collinear nodes
     r"flat.bdf: 1 quad shell element\(s\) have zero area.*ids \[33\]"),
])
def test_zero_volume_and_collapsed_elements_name_the_element(tmp_path, cards, match):
    p = _write(tmp_path, "flat.bdf", _deck(*TET, *cards))
    with pytest.raises(MeshError, match=match):
        read_mesh(p, prune_unreferenced=True)


@pytest.mark.parametrize("name,content", [
    ("broken.vtu", b"<VTKFile type='UnstructuredGrid'"),        # truncated XML
    ("empty.msh", b""),
    ("binary.msh", b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00$EndMeshFormat\n$Nodes\n\x07"),
    ("short.vtk", b"# vtk DataFile Version 4.2\nx\nASCII\nDATASET UNSTRUCTURED_GRID\n"
                  b"POINTS 3 double\n0 0\n"),
    ("junk.stl", b"\x00" * 30),
    ("junk.obj", b"v 0 0\nf 1 2 3\n"),
])
def test_corrupt_files_raise_mesh_error_naming_the_file(tmp_path, name, content):
    """meshio ends the process (sys.exit) on some unreadable files: flexpipe must turn
    that into a MeshError naming the file instead."""
    p = tmp_path / name
    p.write_bytes(content)
    with pytest.raises(MeshError, match=rf"{name.replace('.', r'[.]')}(, line \d+)?: "):
        read_mesh(p, thickness=0.001)


def test_unreadable_gmsh_says_why(tmp_path, capfd):
    with pytest.raises(MeshError, match=r"empty.msh: cannot read as gmsh file \(the file is "
                                        r"empty\)"):
        read_mesh(_write(tmp_path, "empty.msh", ""))
    with pytest.raises(MeshError, match=r"v9.msh(, line 2)?: .*mesh format in .*got 9.9"):
        read_mesh(_write(tmp_path, "v9.msh", "$MeshFormat\n9.9 0 8\n$EndMeshFormat\n"))
    out, err = capfd.readouterr()
    assert out == "" and err == ""                 # meshio's printout does not leak


def test_mode_shape_files_are_written_atomically(tmp_path, monkeypatch):
    from flexpipe.mesh.vtu import write_modes

    body = box(0.2, 0.1, 0.1, 1, 1, 1)
    shapes = np.ones((3 * body.n_nodes, 2))
    p = tmp_path / "modes.vtu"
    write_modes(p, body, [1.0, 2.0], shapes)
    before = p.read_bytes()

    def crash(path, *args, **kwargs):  # the VTU writer dies half-way through
        with open(path, "w") as fh:
            fh.write("<VTKFile")
        raise RuntimeError("disk full")

    monkeypatch.setattr(meshio, "write", crash)
    with pytest.raises(RuntimeError, match="disk full"):
        write_modes(p, body, [3.0, 4.0], 2 * shapes, per_mode_dir=tmp_path)
    assert p.read_bytes() == before
    assert sorted(x.name for x in tmp_path.iterdir()) == ["modes.vtu"]


def test_abaqus_duplicate_node_and_element_ids_name_both_lines(tmp_path):
    nodes = "*NODE\n1,0,0,0\n2,1,0,0\n3,0,1,0\n4,0,0,1\n"
    p = _write(tmp_path, "dupn.inp", nodes + "3,0,2,0\n*ELEMENT, TYPE=C3D4\n1,1,2,3,4\n")
    with pytest.raises(MeshError, match=r"dupn.inp, line 6: node 3 is defined twice: "
                                        r"dupn.inp line 4 and dupn.inp line 6"):
        read_mesh(p)
    p = _write(tmp_path, "dupe.inp", nodes + "*ELEMENT, TYPE=C3D4\n7,1,2,3,4\n7,1,2,4,3\n")
    with pytest.raises(MeshError, match=r"dupe.inp, line 8: element 7 is defined twice"):
        read_mesh(p)


@pytest.mark.parametrize("name, text, include", [
    ("loop.bdf", "BEGIN BULK\nINCLUDE 'loop.bdf'\nENDDATA\n", "INCLUDE"),
    ("loop.inp", "*HEADING\n*INCLUDE, INPUT=loop.inp\n", r"\*INCLUDE"),
])
def test_include_loops_name_the_file(tmp_path, name, text, include):
    with pytest.raises(MeshError, match=rf"{name.replace('.', '[.]')}: {include} loop"):
        read_mesh(_write(tmp_path, name, text))


@pytest.mark.parametrize("name, kind", [("bin.bdf", "Nastran bulk-data"),
                                         ("bin.inp", "Abaqus input")])
def test_binary_decks_name_the_file_and_line(tmp_path, name, kind):
    p = tmp_path / name
    p.write_bytes(b"$ header\n\x00\x01binary")
    with pytest.raises(MeshError, match=rf"{name.replace('.', '[.]')}, line 2: not an? {kind}"):
        read_mesh(p)


BRACKET = Path(__file__).resolve().parents[1] / "meshes" / "bracket.bdf"


def test_deck_cut_inside_a_field_names_file_line_and_card(tmp_path):
    p = tmp_path / "cut.bdf"
    p.write_bytes(BRACKET.read_bytes()[:2000])   # inside GRID* 20's continuation line
    with pytest.raises(MeshError, match=r"cut.bdf, line 41: GRID\* 20: the file ends at "
                                        r"column 15 of line 41.*cut short"):
        read_mesh(p)
    p.write_bytes(BRACKET.read_bytes()[:4323])   # inside the name of the 2nd CQUAD4
    with pytest.raises(MeshError, match=r"cut.bdf, line 89: CQ \?: the file ends.*cut short"):
        read_mesh(p)


def test_deck_with_no_element_names_its_last_card(tmp_path):
    p = _write(tmp_path, "grids.bdf", _deck(*TET, "PSHELL,1,1,0.002", "MAT1,1,2.1+11,,0.3,7850."))
    with pytest.raises(MeshError, match=r"grids.bdf, line 7: no element card: the deck has 4 "
                                        r"GRID\(s\).*last card is MAT1 1 \(line 7\)"):
        read_mesh(p)


def test_continuation_without_its_card_names_the_line(tmp_path):
    p = _write(tmp_path, "orphan.bdf", "BEGIN BULK\n*                     0.\n" +
               "\n".join(TET) + "\nENDDATA\n")
    with pytest.raises(MeshError, match=r"orphan.bdf, line 2: continuation line '\*  *0\.' "
                                        r"has no card before it"):
        read_mesh(p)


@pytest.mark.parametrize("after, where", [("CTETRA,9,1,1,2,3,4", "line 8 starts a new card "
                                                                  r"\(CTETRA 9\)"),
                                          ("", "the bulk data ends there")])
def test_card_whose_continuation_is_missing_names_the_card(tmp_path, after, where):
    marked = f"{'CHEXA':<8}{1:>8}{1:>8}" + "".join(f"{g:>8}" for g in range(1, 7)) + "+C1"
    p = _write(tmp_path, "nocont.bdf", _deck(*TET, "PSOLID,1,1", marked,
                                            *([after] if after else [])))
    with pytest.raises(MeshError, match=rf"nocont.bdf, line 7: CHEXA 1: line 7 ends with the "
                                        rf"continuation marker '\+C1' but {where}"):
        read_mesh(p)


def test_element_with_undefined_property_names_pid_card_and_defined_ids(tmp_path):
    text = BRACKET.read_text().replace(f"{'CQUAD4':<8}{1:>8}{1:>8}", f"{'CQUAD4':<8}{1:>8}{7:>8}")
    p = _write(tmp_path, "pid7.bdf", text)
    with pytest.warns(MeshWarning, match=r"pid7.bdf: element 1 \(CQUAD4, pid7.bdf line 88\) "
                                         r"refers to PID 7, which has no property card "
                                         r"\(expected a PSHELL.* card with PID 7; quad property "
                                         r"ids defined: "
                                         r"1, 2\)"):
        mesh = read_mesh(p)
    assert "PID7" in mesh.cell_sets
    with pytest.raises(MeshError, match=r"pid7.bdf: element 1 \(CQUAD4.*refers to PID 7.*"
                                        r"PSHELL.*PID 7; quad property ids defined: 1, 2\); no "
                                        r"material for 1 quad"):
        assemble(mesh)
    with pytest.raises(MeshError, match=r"refers to PID 7.*no positive thickness, e.g. ids \[1\]"):
        assemble(mesh, STEEL)


def _bracket_with(tmp_path, name, E="210000000000.0", rho="7850.0"):
    """bracket.bdf (SI) with the MAT1 E and RHO replaced (16-character fields)."""
    text = BRACKET.read_text().replace(f"{'MAT1*':<8}{1:>16}{'210000000000.0':>16}",
                                       f"{'MAT1*':<8}{1:>16}{E:>16}")
    return _write(tmp_path, name, text.replace(f"{'*':<8}{'7850.0':>16}", f"{'*':<8}{rho:>16}"))


@pytest.mark.parametrize("E, rho, speed, slip", [
    ("210000000000.0", "7.85e-09", "5.17e+09", r"RHO looks like t/mm\^3"),
    ("210000.0", "7850.0", "5.17", "E looks like MPa"),
    ("210000.0", "7.85e-09", "5.17e+06", r"mm-t-s values.*units='mm-t-s'"),
    ("210000000000.0", "7.85", "1.64e+05", r"RHO looks like g/cm\^3")])
def test_material_unit_slip_names_the_card_values_and_slip(tmp_path, E, rho, speed, slip):
    p = _bracket_with(tmp_path, "slip.bdf", E, rho)
    values = re.escape(f"E = {float(E):g} and RHO = {float(rho):g} ")
    with pytest.raises(MeshError, match=rf"slip.bdf, line 132: MAT1 1: {values}.*sqrt\(E/RHO\) "
                                        rf"= {re.escape(speed)} m/s; valid: 10 to 50000 "
                                        rf"m/s.*{slip}"):
        read_mesh(p)


def test_material_check_follows_the_stated_units(tmp_path):
    mm = _bracket_with(tmp_path, "mm.bdf", "210000.0", "7.85e-09")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mesh = read_mesh(mm, units="mm-t-s")      # consistent once converted: no warning
    assert mesh.sections["PID1"]["rho"] == pytest.approx(7850.0, rel=1e-12)
    with pytest.warns(MeshWarning, match=r"MAT1 1: .*5.17 m/s.*look like SI.*check units 'mm-t-s'"):
        read_mesh(BRACKET, units="mm-t-s")       # stated explicitly: a warning only


def _steel_tet_and_bar(bar_mat, tet_mat="MAT1,1,2.1+11,,0.3,7850."):
    """A steel tetrahedron (MAT1 1) with a connector bar of ``bar_mat`` (MAT1 2)."""
    return _deck(*TET, "GRID,5,,2.,0.,0.", "CTETRA,1,1,1,2,3,4", "PSOLID,1,1",
                 "CBAR,2,2,2,5,0.,0.,1.", "PBAR,2,2,1.-4,2.-9,3.-9,4.-9", tet_mat, bar_mat)


@pytest.mark.parametrize("bar_mat, speed", [("MAT1,2,2.1+14,,0.3,7.85", "5.17e+06"),
                                            ("MAT1,2,2.1+14,,0.3,7850.", "1.64e+05")])
def test_stiff_dummy_bar_material_beside_steel_is_a_warning(tmp_path, bar_mat, speed):
    """Finding: one stiff dummy material (connector bars: E 1000 x steel's, or
    nearly massless) in an SI deck was a MeshError; it is valid, so a warning naming the
    file, line, card, values and speed, and the steel is read as it is."""
    p = _write(tmp_path, "dummy.bdf", _steel_tet_and_bar(bar_mat))
    E, rho = (float(x.replace("+", "e+")) for x in bar_mat.split(",")[2:6:3])
    values = re.escape(f"MAT1 2: E = {E:g} and RHO = {rho:g} ")
    with pytest.warns(MeshWarning, match=rf"dummy.bdf line 12: {values}.*sqrt\(E/RHO\) = "
                                         rf"{re.escape(speed)} m/s; valid: 10 to 50000") as rec:
        mesh = read_mesh(p)
    assert len([w for w in rec if "wave speed" in str(w.message)]) == 1   # MAT1 1 is fine
    assert "mm-t-s" not in str(rec[0].message) and "looks like" not in str(rec[0].message)
    assert mesh.n_nodes == 5


def test_every_material_off_the_same_way_is_a_unit_slip_error(tmp_path):
    """A whole deck with RHO in t/mm^3 (every material above the range) stays an error,
    naming the first card and the others; materials off on both sides only warn."""
    text = _steel_tet_and_bar("MAT1,2,2.1+14,,0.3,7.85-9", "MAT1,1,2.1+11,,0.3,7.85-9")
    with pytest.raises(MeshError, match=r"slip2.bdf, line 11: MAT1 1: .*= 5.17e\+09 m/s; "
                                        r"valid: 10 to 50000 m/s.*other materials.*MAT1 2 "
                                        r"\(1.64e\+11 m/s\).*RHO looks like t/mm\^3"):
        read_mesh(_write(tmp_path, "slip2.bdf", text))
    text = _steel_tet_and_bar("MAT1,2,2.1+14,,0.3,7.85", "MAT1,1,2.1+5,,0.3,7850.")
    with pytest.warns(MeshWarning, match="wave speed") as rec:
        read_mesh(_write(tmp_path, "both.bdf", text))
    assert len([w for w in rec if "wave speed" in str(w.message)]) == 2


@pytest.mark.parametrize("name", sorted(p.name for p in BRACKET.parent.iterdir()
                                        if p.suffix in (".bdf", ".msh")))
def test_shipped_meshes_pass_the_material_check(name):
    with warnings.catch_warnings():
        warnings.filterwarnings("error", message=".*wave speed")
        read_mesh(BRACKET.parent / name)
