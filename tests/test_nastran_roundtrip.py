"""A hand-written deck with every new card, written back through write_mesh and read
again, gives identical M, K, C and constraint map; the deck's SOL 103 set-up survives."""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest
from _meshdata import write as _write

from flexpipe.fem import assemble
from flexpipe.mesh import read_mesh, write_mesh

DECK = """SOL 103
CEND
SPC = 3
METHOD = 4
BEGIN BULK
MAT1,1,2.1+11,,0.3,7850.
MAT1,2,7.0+10,,0.33,2700.
PSOLID,1,1
PSHELL,2,2,0.004,2,0.8,,,
PBARL,3,1,,L
,0.05,0.04,0.005,0.004
PBEAML,4,1,,I
,0.1,0.05,0.05,0.004,0.006,0.006
PROD,5,1,1.-4,2.-9
PBUSH,6,K,1.+6,2.+6,3.+6,100.,200.,300.,,B,10.,20.,30.,1.,2.,3.
PELAS,7,5.+5
CORD2R,9,,0.,0.,0.,0.,0.,1.,+
+,0.,1.,0.
GRID,1,,0.,0.,0.
GRID,2,,1.,0.,0.
GRID,3,,1.,1.,0.
GRID,4,,0.,1.,0.
GRID,5,,0.,0.,1.
GRID,6,,1.,0.,1.
GRID,7,,1.,1.,1.
GRID,8,,0.,1.,1.
GRID,9,,2.,0.,0.
GRID,10,,2.,0.,1.
GRID,11,,0.5,0.5,-0.8
GRID,12,9,1.5,0.,0.5
GRID,13,,0.,1.,2.
GRID,14,,0.,1.,3.
GRID,15,,0.5,0.5,1.5
GRID,16,,3.,0.,0.
GRID,17,,2.,1.,0.
CHEXA,1,1,1,2,3,4,5,6,+
+,7,8
CPENTA,2,1,2,9,3,6,10,7
CPYRAM,3,1,4,3,2,1,11
CQUAD4,4,2,5,6,7,8,,0.002
CTRIA3,5,2,2,9,17
CBAR,6,3,8,13,1.,0.,0.,,+
+,,,0.,0.,0.01,0.,0.01,0.
CBEAM,7,4,13,14,1.,0.,0.
CROD,8,5,7,15
CONROD,9,6,15,1,1.-4,2.-9
CBUSH,10,6,9,16,0.,0.,1.
CELAS2,11,4.+5,16,2
CELAS1,12,7,16,3,9,3
CONM2,20,16,,3.0
CONM2,21,15,,1.0,0.,0.,0.1,,+
+,0.01,,0.02,,,0.03
CONM1,22,14,,2.0,,2.0,,,2.0,+
+,,,,0.1,,,,,+
+,0.1,,,,,,0.1
RBE2,30,11,123,1,2,3
RBE3,31,,15,123456,1.0,123,5,6,2.0,123,7,8
SPC1,3,123456,11
SPC1,3,3,16
EIGRL,4,,,8
ENDDATA
"""


def _fe(mesh):
    return assemble(mesh)


def test_hand_written_deck_round_trips_with_identical_matrices(tmp_path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = read_mesh(_write(tmp_path, "all.bdf", DECK))
        out = write_mesh(a, tmp_path / "again.bdf")
        b = read_mesh(out)
    assert {bl.type for bl in a.blocks} == {"hexahedron", "wedge", "pyramid", "quad",
                                            "triangle", "line", "spring", "spring1"}
    fa, fb = _fe(a), _fe(b)
    for X, Y in ((fa.K, fb.K), (fa.M, fb.M), (fa.C, fb.C), (fa.T, fb.T)):
        d = abs(X - Y).max()
        assert d <= 1e-12 * abs(X).max(), d
    assert b.solution["spc"] == "SPC3" and b.solution["n_modes"] == 8
    assert np.array_equal(a.dof_sets["SPC3"], b.dof_sets["SPC3"])
    assert len(b.interpolations) == 1 and len(b.rigid_links) == 1


def test_rbe3_and_wedges_round_trip_through_abaqus(tmp_path):
    deck = """BEGIN BULK
MAT1,1,2.1+11,,0.3,7850.
PSOLID,1,1
GRID,1,,0.,0.,0.
GRID,2,,1.,0.,0.
GRID,3,,0.,1.,0.
GRID,4,,0.,0.,1.
GRID,5,,1.,0.,1.
GRID,6,,0.,1.,1.
GRID,7,,1.,1.,0.
GRID,8,,1.,1.,1.
GRID,9,,0.5,0.5,2.
CPENTA,1,1,1,2,3,4,5,6
CPENTA,2,1,2,7,3,5,8,6
RBE3,3,,9,123456,1.0,123,4,5,2.0,123,6,8
CONM2,4,9,,10.
ENDDATA
"""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = read_mesh(_write(tmp_path, "w.bdf", deck))
        b = read_mesh(write_mesh(a, tmp_path / "w.inp"))
    fa, fb = _fe(a), _fe(b)
    for X, Y in ((fa.K, fb.K), (fa.M, fb.M), (fa.T, fb.T)):
        assert abs(X - Y).max() <= 1e-12 * abs(X).max()


def test_small_field_cards_read_back_to_eight_character_precision(tmp_path):
    """Small-field cards (the sample BIW generator's writer) read back through the Nastran
    reader: every real within the precision eight characters allow."""
    from flexpipe.mesh.nastran_write import card, real8

    def small_card(name, *fields):
        return card(name, fields, small=True)

    rng = np.random.default_rng(3)
    xyz = rng.uniform(-2.0, 2.0, (4, 3)) * np.array([1.0, 1e-2, 1e2])
    cards = [small_card("MAT1", 1, 2.1e11, "", 0.3, 7850.0),
             small_card("PSHELL", 1, 1, 0.00123456, 1, "", 1)]
    cards += [small_card("GRID", i + 1, "", *map(float, p)) for i, p in enumerate(xyz)]
    cards += [small_card("CQUAD4", 1, 1, 1, 2, 3, 4),
              small_card("SET1", 7, 1, 1, 1, 1, 1, 1, 2, 4)]  # a continuation line
    p = tmp_path / "small.bdf"
    p.write_text("BEGIN BULK\n" + "".join(cards) + "ENDDATA\n")
    mesh = read_mesh(p)
    # 8 characters: at least 5 significant digits for |x| in [1e-3, 1e3), 4 with a sign
    np.testing.assert_allclose(mesh.points, xyz, rtol=5e-4, atol=0)
    sec = next(iter(mesh.sections.values()))
    assert sec["E"] == 2.1e11 and sec["rho"] == 7850.0
    assert abs(sec["thickness"] - 0.00123456) <= 5e-5 * 0.00123456
    assert np.unique(mesh.node_sets["SET7"]).tolist() == [0, 1, 3]  # node 4 on the "+" line
    for x in np.concatenate([rng.uniform(1e-3, 1e3, 200), 10.0 ** rng.uniform(-9, 12, 200)]):
        s = real8(x)
        value = float(re.sub(r"(?<=\d)([+-])(?=\d+$)", r"E\1", s) if "E" not in s else s)
        assert len(s) <= 8 and "." in s
        assert abs(value - x) <= (5e-5 if 1e-3 <= x < 1e3 else 5e-4) * x, (x, s)
    with pytest.raises(ValueError, match="8 characters"):
        real8(-1.2345678e-300)
