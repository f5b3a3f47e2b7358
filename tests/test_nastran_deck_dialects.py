"""Nastran decks as pre-processors and hand edits write them (audit_decks findings 3, 4, 5,
7, 8, 9): each variant against the same model in the plain dialect and the closed forms.

References: the simply supported plate (a = 0.5 m, t = 5 mm, steel, 20 x 20 CQUAD4, edges
SPC 123): f11 = (pi/2)(2/a^2) sqrt(D/(rho t)) = 98.343 Hz, m = rho a^2 t = 9.8125 kg; the
cantilever bar (L = 1 m, 0.02 x 0.01, 20 CBAR): Euler-Bernoulli f = lambda^2/(2 pi L^2)
sqrt(EI/(rho A)).  Nastran rules from the MSC/NX Quick Reference Guide: SPC1 remark 3 (ids
of a THRU range need not exist), PARAM COUPMASS (default -1: lumped mass), CQUAD4/CTRIA3
TFLAG/Ti (Ti default the PSHELL T; TFLAG = 1: factors on T), INCLUDE (a quoted name may
continue on the next lines), case control METHOD(STRUCTURE/BOTH/FLUID).
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from flexpipe.cli import main
from flexpipe.errors import MeshError
from flexpipe.fem import assemble
from flexpipe.mesh import read_mesh
from flexpipe.mesh.validate import MeshWarning

E, NU, RHO, A_PLATE, T_PLATE = 2.1e11, 0.3, 7850.0, 0.5, 0.005
D = E * T_PLATE**3 / (12 * (1 - NU**2))
F11 = np.pi / 2 * 2 / A_PLATE**2 * np.sqrt(D / (RHO * T_PLATE))       # 98.343 Hz
MASS = RHO * A_PLATE**2 * T_PLATE                                      # 9.8125 kg
HEAD = ["SOL 103", "CEND", "SUBCASE 1", "  SPC = 1", "  METHOD = 1", "BEGIN BULK"]


def _row(*f) -> str:
    """One small-field line (name left-, values right-justified)."""
    return "".join(f"{x!s:<8}" if i == 0 else f"{x!s:>8}" for i, x in enumerate(f)).rstrip()


def _plate(head=HEAD, t="0.005", corner=None, extra=(), tria=False, eigrl=("EIGRL", 1, "",
                                                                           "", 8)) -> str:
    n = 20
    lines = list(head)

    def nid(i, j):
        return 1 + i * (n + 1) + j

    for i in range(n + 1):
        for j in range(n + 1):
            lines.append(_row("GRID", nid(i, j), "", f"{A_PLATE * i / n:.6f}",
                              f"{A_PLATE * j / n:.6f}", "0."))
    e = 1
    for i in range(n):
        for j in range(n):
            q = (nid(i, j), nid(i + 1, j), nid(i + 1, j + 1), nid(i, j + 1))
            if tria:
                for tri in ((q[0], q[1], q[2]), (q[0], q[2], q[3])):
                    lines.append(_row("CTRIA3", e, 1, *tri))
                    if corner:
                        lines.append(corner(e))
                    e += 1
                continue
            lines.append(_row("CQUAD4", e, 1, *q))
            if corner:
                lines.append(corner(e))
            e += 1
    lines.append(_row("PSHELL", 1, 1, t, 1))
    lines.append(_row("MAT1", 1, "2.1+11", "", "0.3", "7850."))
    edge = sorted({nid(i, j) for i in range(n + 1) for j in range(n + 1)
                   if i in (0, n) or j in (0, n)})
    lines += [_row("SPC1", 1, 123, *edge[k:k + 6]) for k in range(0, len(edge), 6)]
    lines += list(extra) + [_row(*eigrl), "ENDDATA"]
    return "\n".join(lines) + "\n"


def _modes(path, tmp_path, capsys, *opts):
    """(frequencies, stdout) of ``flexpipe modes path``."""
    out = tmp_path / f"out_{path.stem}"
    assert main(["modes", str(path), "-q", "-o", str(out), *opts]) == 0
    text = capsys.readouterr().out
    f = np.loadtxt(out / "frequencies.csv", delimiter=",", skiprows=1, ndmin=2)[:, 1]
    return f, text


def _write(tmp_path, name, text):
    p = tmp_path / name
    p.parent.mkdir(parents=True, exist_ok=True)
    p.write_text(text)
    return p


# ------------------------------------------------------------------ 3. BEGIN BULK spacing
@pytest.mark.parametrize("begin", ["BEGIN  BULK", "BEGIN\tBULK", "  begin   bulk  $ data",
                                   "Begin Bulk AUXMODEL-free text"])
def test_begin_bulk_in_nastran_free_format_starts_the_bulk_data(tmp_path, capsys, begin):
    ref, _ = _modes(_write(tmp_path, "one.bdf", _plate()), tmp_path, capsys)
    p = _write(tmp_path, "two.bdf", _plate(head=HEAD[:-1] + [begin]))
    with warnings.catch_warnings():
        warnings.simplefilter("error", MeshWarning)        # no "unknown card" warning
        f, out = _modes(p, tmp_path, capsys)
    assert "deck SPC: SPC1" in out                         # the SPC set is applied
    assert np.array_equal(f, ref)                          # = the single-blank deck
    assert f[0] == pytest.approx(F11, rel=5e-3)            # simply supported, not free


def test_cend_without_begin_bulk_is_an_error_naming_the_line(tmp_path):
    p = _write(tmp_path, "nobulk.bdf", _plate(head=HEAD[:-1] + ["BEGINBULK"]))
    with pytest.raises(MeshError, match=r"nobulk.bdf, line 2: CEND .* no BEGIN BULK line"):
        read_mesh(p)


# ------------------------------------------------------------------ 4. SPC1 THRU ranges
def _bar(spc_lines) -> str:
    lines = ["SOL 103", "CEND", "SPC = 1", "METHOD = 1", "BEGIN BULK"]
    lines += [f"GRID,{i + 1},,{i * 0.05},0.,0." for i in range(21)]
    lines += [f"CBAR,{100 + i},7,{i + 1},{i + 2},0.,0.,1." for i in range(20)]
    lines += ["PBAR,7,1,2.-4,1.6666667-9,6.6666667-9,4.577-9", "MAT1,1,2.1+11,,0.3,7850."]
    return "\n".join(lines + spc_lines + ["EIGRL,1,,,2", "ENDDATA"]) + "\n"


def test_spc1_thru_skips_ids_that_are_not_grids_as_nastran_does(tmp_path, capsys):
    """Clamped at grid 1, components 345 held on '1 THRU 99999' (grids 1-21 exist): the
    in-plane (y) bending of an Euler-Bernoulli cantilever, I = 0.02^3 0.01 / 12."""
    wide = _write(tmp_path, "wide.bdf", _bar(["SPC1,1,123456,1", "SPC1,1,345,1,THRU,99999"]))
    with pytest.warns(MeshWarning, match=r"SPC1 THRU ranges hold 99978 id\(s\) that are not "
                                         r"GRIDs; skipped, as Nastran does \(SPC1 1 \(wide.bdf "
                                         r"line 50\): 99978\)"):
        read_mesh(wide)
    f, _ = _modes(wide, tmp_path, capsys)
    explicit = _bar(["SPC1,1,123456,1"] + [f"SPC1,1,345,{g}" for g in range(1, 22)])
    ref, _ = _modes(_write(tmp_path, "explicit.bdf", explicit), tmp_path, capsys)
    assert np.array_equal(f, ref)
    I, A = 0.01 * 0.02**3 / 12, 2e-4
    eb = np.array([1.8751041, 4.6940911]) ** 2 / (2 * np.pi) * np.sqrt(E * I / (RHO * A))
    assert np.allclose(f, eb, rtol=2e-4), (f, eb)


def test_spc1_thru_range_without_any_grid_and_a_missing_listed_grid_are_errors(tmp_path):
    p = _write(tmp_path, "none.bdf", _bar(["SPC1,1,123456,1", "SPC1,1,3,22,THRU,25"]))
    with pytest.raises(MeshError, match=r"none.bdf, line 50: SPC1 1: THRU range 22 THRU 25 "
                                        r"contains no GRID"):
        read_mesh(p)
    p = _write(tmp_path, "listed.bdf", _bar(["SPC1,1,123456,1,22"]))
    with pytest.raises(MeshError, match=r"listed.bdf, line 49: SPC1 1: .*GRID 22, which is "
                                        r"not defined"):
        read_mesh(p)


# ------------------------------------------------------------------ 5. default mass
def test_sol_deck_without_coupmass_gets_nastrans_lumped_mass(tmp_path, capsys):
    f, out = _modes(_write(tmp_path, "nocoup.bdf", _plate()), tmp_path, capsys)
    assert "mass: lumped (Nastran's default, PARAM,COUPMASS absent)" in out
    # the reference: the same deck saying COUPMASS = -1 (the QRG default) explicitly
    lumped, out_l = _modes(_write(tmp_path, "coup.bdf", _plate(
        extra=[_row("PARAM", "COUPMASS", "-1")])), tmp_path, capsys)
    assert "mass: lumped (PARAM,COUPMASS,-1)" in out_l
    assert np.array_equal(f, lumped)
    assert f[0] == pytest.approx(F11, rel=5e-3) and f[0] < F11   # lumped: from below here
    cons, out_c = _modes(_write(tmp_path, "coup1.bdf", _plate(
        extra=[_row("PARAM", "COUPMASS", "1")])), tmp_path, capsys)
    assert "mass: consistent (PARAM,COUPMASS,1)" in out_c
    assert cons[0] == pytest.approx(F11, rel=5e-3) and cons[0] > f[0]


def test_bulk_data_without_sol_keeps_the_consistent_mass_and_says_so(tmp_path, capsys):
    """Bulk data only (as the car body decks): free-free, consistent mass as before."""
    f, out = _modes(_write(tmp_path, "bulk.bdf", _plate(head=["BEGIN BULK"])), tmp_path,
                    capsys)
    assert "mass: consistent (no SOL statement in the deck" in out
    cons, _ = _modes(_write(tmp_path, "bulk1.bdf", _plate(head=["BEGIN BULK"], extra=[
        _row("PARAM", "COUPMASS", "1")])), tmp_path, capsys)
    lumped, _ = _modes(_write(tmp_path, "bulk_1.bdf", _plate(head=["BEGIN BULK"], extra=[
        _row("PARAM", "COUPMASS", "-1")])), tmp_path, capsys)
    assert np.array_equal(f, cons) and not np.allclose(f[6:], lumped[6:], rtol=1e-3)


def test_sol_deck_of_bars_keeps_the_consistent_mass_with_a_note(tmp_path, capsys):
    p = _write(tmp_path, "bar.bdf", _bar(["SPC1,1,123456,1"]))
    f, out = _modes(p, tmp_path, capsys)
    assert "mass: consistent (PARAM,COUPMASS absent: Nastran's default is lumped, but for " \
           "line elements" in out
    I, A = 0.02 * 0.01**3 / 12, 2e-4
    assert f[0] == pytest.approx(1.8751041**2 / (2 * np.pi) * np.sqrt(E * I / (RHO * A)),
                                 rel=1e-4)


def test_written_deck_keeps_its_coupmass(tmp_path):
    from flexpipe.mesh import write_mesh

    for value, lumped in (("1", False), ("-1", True)):
        mesh = read_mesh(_write(tmp_path, f"c{value}.bdf", _plate(
            extra=[_row("PARAM", "COUPMASS", value)])))
        out = tmp_path / f"w{value}.bdf"
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", MeshWarning)
            write_mesh(mesh, out)
        back = read_mesh(out)
        assert back.solution["lumped_mass"] is lumped and back.solution["sol"] == 103


# ------------------------------------------------------------------ 7. INCLUDE continued
@pytest.mark.parametrize("include", ["INCLUDE 'sub/\n        grids.bdf'",
                                     "include 'sub/\ngri\n  ds.bdf'   $ split twice"])
def test_include_name_continued_on_the_next_lines(tmp_path, capsys, include):
    text = _plate()
    head, rest = text.split("BEGIN BULK\n")
    grids = [ln for ln in rest.splitlines() if ln.startswith("GRID")]
    others = [ln for ln in rest.splitlines() if not ln.startswith("GRID")]
    _write(tmp_path, "sub/grids.bdf", "\n".join(grids) + "\n")
    ref, _ = _modes(_write(tmp_path, "m1.bdf", head + "BEGIN BULK\nINCLUDE 'sub/grids.bdf'\n"
                           + "\n".join(others) + "\n"), tmp_path, capsys)
    p = _write(tmp_path, "m2.bdf", head + "BEGIN BULK\n" + include + "\n" + "\n".join(others)
               + "\n")
    f, _ = _modes(p, tmp_path, capsys)
    assert np.array_equal(f, ref) and f[0] == pytest.approx(F11, rel=5e-3)
    bad = _write(tmp_path, "m3.bdf", head + "BEGIN BULK\nINCLUDE 'sub/\n  grids.bdf\n"
                 + "\n".join(others) + "\n")
    with pytest.raises(MeshError, match=r"m3.bdf, line 7: INCLUDE: the file name opened with "
                                        r"' on this line is never closed"):
        read_mesh(bad)


# ------------------------------------------------------------------ 8. METHOD(STRUCTURE)
@pytest.mark.parametrize("method", ["METHOD(STRUCTURE) = 2", "METHOD (BOTH)=2",
                                    "method(structure) = 2"])
def test_method_with_a_describer_selects_its_eigrl(tmp_path, capsys, method):
    extra = [_row("EIGRL", 2, "50.", "300.")]
    ref, _ = _modes(_write(tmp_path, "plain.bdf", _plate(
        head=HEAD[:4] + ["  METHOD = 2", "BEGIN BULK"], extra=extra)), tmp_path, capsys)
    f, _ = _modes(_write(tmp_path, "descr.bdf", _plate(
        head=HEAD[:4] + ["  " + method, "BEGIN BULK"], extra=extra)), tmp_path, capsys)
    assert len(ref) == 3 and np.array_equal(f, ref)      # the modes in 50-300 Hz
    assert ((f > 50) & (f < 300)).all()


def test_method_fluid_and_unreadable_case_lines_are_named_in_a_warning(tmp_path):
    p = _write(tmp_path, "fluid.bdf", _plate(head=HEAD[:3] + [
        "  SPC = ALL", "  METHOD(FLUID) = 1", "BEGIN BULK"]))
    with pytest.warns(MeshWarning) as rec:
        mesh = read_mesh(p)
    text = " | ".join(str(w.message) for w in rec)
    assert "fluid.bdf, line 4: case control 'SPC = ALL' is not understood and ignored" in text
    assert "fluid.bdf, line 5: case control 'METHOD(FLUID) = 1' is ignored: METHOD(FLUID) " \
           "selects the fluid's eigenvalue method" in text
    assert "spc" not in mesh.solution


# ------------------------------------------------------------------ 9. corner thicknesses
def _corners(*t, tflag=""):
    return lambda e: _row("", "", tflag, *t)     # CQUAD4: blank, TFLAG, T1..T4


@pytest.mark.parametrize("t, corner", [
    ("", _corners(".005", ".005", ".005", ".005")),               # PSHELL T blank (Femap)
    ("0.002", _corners(".005", ".005", ".005", ".005")),          # Ti override T
    ("0.002", _corners("2.5", "2.5", "2.5", "2.5", tflag="1")),   # TFLAG 1: factors on T
    ("0.005", _corners("", ".005", "", "")),                      # blank Ti = PSHELL T
])
def test_corner_thicknesses_give_the_plate_of_that_thickness(tmp_path, capsys, t, corner):
    ref, _ = _modes(_write(tmp_path, "plain.bdf", _plate()), tmp_path, capsys)
    p = _write(tmp_path, "corner.bdf", _plate(t=t, corner=corner))
    with warnings.catch_warnings():
        warnings.simplefilter("error", MeshWarning)              # none per element
        f, out = _modes(p, tmp_path, capsys)
    assert f"mass {MASS:.6g} kg" in out
    assert np.allclose(f, ref, rtol=1e-12)


def test_unequal_corner_thicknesses_take_the_mean_with_one_warning(tmp_path):
    p = _write(tmp_path, "taper.bdf", _plate(corner=_corners(".004", ".006", ".006", ".004"),
                                             t=""))
    with pytest.warns(MeshWarning) as rec:
        mesh = read_mesh(p)
    msgs = [str(w.message) for w in rec if "corner" in str(w.message)]
    assert len(msgs) == 1 and "400 shell element(s) have unequal corner thicknesses" in msgs[0]
    assert "takes the mean of its corners" in msgs[0]
    fe = assemble(mesh)
    # the mean of a bilinear thickness over a rectangle is exact for its mass
    assert fe.total_mass == pytest.approx(MASS, rel=1e-12)


def test_ctria3_corner_thicknesses(tmp_path, capsys):
    ref, _ = _modes(_write(tmp_path, "t.bdf", _plate(tria=True)), tmp_path, capsys)
    f, out = _modes(_write(tmp_path, "tc.bdf", _plate(
        tria=True, t="", corner=lambda e: _row("", "", "", "", ".005", ".005", ".005"))),
        tmp_path, capsys)
    assert f"mass {MASS:.6g} kg" in out and np.allclose(f, ref, rtol=1e-12)


def test_blank_pshell_t_without_corner_thicknesses_names_both_fields(tmp_path, capsys):
    p = _write(tmp_path, "noT.bdf", _plate(t=""))
    assert main(["modes", str(p), "-q", "-o", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert "PSHELL 1 (noT.bdf line 848) has T blank and 400 of its element(s) give no " \
           "corner thicknesses T1-T4 either (e.g. CQUAD4 1, noT.bdf line 448" in err
    p = _write(tmp_path, "flag.bdf", _plate(t="", corner=_corners("2.", "2.", "2.", "2.",
                                                                   tflag="1")))
    with pytest.raises(MeshError, match=r"flag.bdf, line 448: CQUAD4 1: TFLAG = 1 .* PSHELL 1 "
                                        r"\(line 1248\) has T blank"):
        read_mesh(p)


@pytest.mark.parametrize("cards", [
    # CQUAD8: G7 G8 T1-T4 THETA ZOFFS on the 2nd line (TFLAG on a 3rd)
    ["CQUAD8,1,1,1,2,3,4,5,6,+", "+,7,8,.004,.006,.006,.004"],
    # CTRIA6 (two of them): THETA ZOFFS T1-T3 TFLAG on the 2nd line
    ["CTRIA6,1,1,1,2,3,5,6,9,+", "+,,,.005,.005,.005",
     "CTRIA6,2,1,1,3,4,9,7,8,+", "+,,,.005,.005,.005"],
])
def test_second_order_shells_take_their_corner_thicknesses(tmp_path, cards):
    """A 0.2 x 0.1 m panel: the mass is rho A t with t the mean corner thickness."""
    grids = ["GRID,1,,0.,0.,0.", "GRID,2,,.2,0.,0.", "GRID,3,,.2,.1,0.", "GRID,4,,0.,.1,0.",
             "GRID,5,,.1,0.,0.", "GRID,6,,.2,.05,0.", "GRID,7,,.1,.1,0.",
             "GRID,8,,0.,.05,0.", "GRID,9,,.1,.05,0."]
    text = "BEGIN BULK\n" + "\n".join(grids + cards + ["PSHELL,1,1,,1",
                                                      "MAT1,1,2.1+11,,0.3,7850."]) + "\nENDDATA\n"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)      # the unused centre grid 9 (CQUAD8)
        mesh = read_mesh(_write(tmp_path, "q8.bdf", text))
    assert assemble(mesh).total_mass == pytest.approx(RHO * 0.02 * 0.005, rel=1e-12)
