"""Magic Formula version, MF 5.2 / 6.x file formats and TeimOrbit corner cases of the .tir
reader.

References written out here, independent of flexpipe:

* slip stiffnesses from the raw coefficients with the MF 5.2 / PAC2002 equations (Pacejka,
  Tire and Vehicle Dynamics, 2nd ed. 2006, eqs. 4.E15 and 4.E25) and with the MF 6.1
  equations (3rd ed. 2012, same numbers, with PKY4 and the inflation-pressure factors
  ``1 + PPX1 dpi + PPX2 dpi^2``, ``dpi = (INFLPRES - NOMPRES) / NOMPRES``);
* the FITTYP values MF-Tyre writes: 6 or 21 for MF 5.2, 60 / 61 / 62 for MF 6.0 / 6.1 / 6.2
  (as MFeval and the Magic Formula Tyre Library read them);
* every message's file, line and key, located in the text by the test.
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
import pytest
from _tirdata import SAMPLE, raw_numbers

from flexpipe.errors import InputError
from flexpipe.tires import read_tir, tire_from_file

BASE = SAMPLE.read_text()
FZ = 4000.0   # the sample's FNOMIN


def line_of(text: str, needle: str) -> int:
    return next(i for i, ln in enumerate(text.splitlines(), 1) if ln.strip().startswith(needle))


def insert_after(text: str, anchor: str, new: str) -> str:
    """``new`` (lines) inserted after the line starting with ``anchor``."""
    out, done = [], False
    for ln in text.splitlines(keepends=True):
        out.append(ln)
        if not done and ln.strip().startswith(anchor):
            out.append(new if new.endswith("\n") else new + "\n")
            done = True
    assert done, anchor
    return "".join(out)


def write(tmp_path, text, name="case.tir"):
    path = tmp_path / name
    path.write_text(text)
    return path


def quiet(fn, *args, **kw):
    """Call with every warning turned into an error."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        return fn(*args, **kw)


def mf52_stiffness(r: dict, Fz: float) -> tuple[float, float]:
    """(Kx, Ky) of MF 5.2 / PAC2002 at camber 0."""
    fz0 = r["FNOMIN"] * r.get("LFZO", 1.0)
    dfz = (Fz - fz0) / fz0
    kx = Fz * (r["PKX1"] + r["PKX2"] * dfz) * math.exp(r["PKX3"] * dfz) * r.get("LKX", 1.0)
    ky = r["PKY1"] * fz0 * math.sin(2.0 * math.atan(Fz / (r["PKY2"] * fz0))) * r.get("LKY", 1.0)
    return kx, ky


def mf61_stiffness(r: dict, Fz: float, dpi: float = 0.0) -> tuple[float, float]:
    """(Kx, Ky) of MF 6.1 at camber 0 (PKY4 default 2, pressure terms default 0)."""
    g = r.get
    fz0 = r["FNOMIN"] * g("LFZO", 1.0)
    dfz = (Fz - fz0) / fz0
    kx = (Fz * (r["PKX1"] + r["PKX2"] * dfz) * math.exp(r["PKX3"] * dfz)
          * (1.0 + g("PPX1", 0.0) * dpi + g("PPX2", 0.0) * dpi ** 2) * g("LKX", 1.0))
    ky = (r["PKY1"] * fz0 * (1.0 + g("PPY1", 0.0) * dpi)
          * math.sin(g("PKY4", 2.0) * math.atan(Fz / (r["PKY2"] * (1.0 + g("PPY2", 0.0) * dpi)
                                                      * fz0))) * g("LKY", 1.0))
    return kx, ky


def forces(tire):
    k, a, g = np.meshgrid([-0.1, 0.0, 0.05], [-0.1, 0.0, 0.08], [-0.03, 0.0, 0.03])
    f = tire.slip_forces(k, a, FZ, g)
    return np.array([f.Fx, f.Fy, f.Mz, f.Mx, f.My])


def base_forces():
    return forces(quiet(tire_from_file, SAMPLE))


# ======================================================================== FITTYP
def test_mf60_fittyp_is_refused_naming_file_line_key_and_supported_versions(tmp_path):
    """MF 6.0's equations are neither MF 5.2's nor MF 6.1's: refused, not guessed."""
    text = insert_after(BASE, "[MODEL]", "FITTYP                   = 60")
    path = write(tmp_path, text)
    for load in (read_tir, tire_from_file, lambda p: tire_from_file(p, model="fiala")):
        with pytest.raises(InputError) as exc:
            load(path)
        msg = str(exc.value)
        assert str(path) in msg and f"line {line_of(text, 'FITTYP')}" in msg
        assert "key 'FITTYP'" in msg and "Magic Formula 6.0" in msg
        assert "6, 21, 61, 62" in msg and "wrong forces" in msg


@pytest.mark.parametrize("fittyp", [61, 62])
def test_mf61_and_mf62_fits_are_evaluated_with_the_mf6_equations(tmp_path, fittyp):
    """The audit's case (FITTYP 61, PKY4 = 1.5, once evaluated silently as MF 5.2): the
    cornering stiffness is MF 6.1's closed form, 805.2 N/deg, not MF 5.2's 1005.3, in
    both the Magic Formula and the Fiala tyre derived from the file."""
    text = insert_after(BASE, "[MODEL]", f"FITTYP                   = {fittyp}")
    text = insert_after(text, "PKY3", "PKY4                     = 1.5")
    path = write(tmp_path, text)
    props = quiet(read_tir, path)
    assert props.is_mf6 and props.fittyp == fittyp
    r = raw_numbers(path)
    kx61, ky61 = mf61_stiffness(r, FZ)
    assert abs(ky61) * math.pi / 180 == pytest.approx(805.2, abs=0.1)
    kx, ky = quiet(tire_from_file, path).mf.slip_stiffness(FZ)
    assert float(ky) == pytest.approx(ky61, rel=1e-12) and float(kx) == pytest.approx(kx61)
    fiala = quiet(tire_from_file, path, model="fiala")
    assert fiala.params.c_alpha == pytest.approx(abs(ky61), rel=1e-12)


def test_mf61_file_as_mf_tool_writes_it_is_read(tmp_path):
    """MF 6.x files as MF-Tool writes them: no PROPERTY_FILE_FORMAT, empty entries in
    [MODEL] (skipped), MF-Tyre's three-digit USE_MODE (slip part 4: combined)."""
    text = BASE.replace("PROPERTY_FILE_FORMAT     = 'PAC2002'",
                        "FITTYP                   = 61\nROAD_INCREMENT           =")
    text = text.replace("USE_MODE                 = 14", "USE_MODE                 = 124")
    path = write(tmp_path, text)
    props = quiet(read_tir, path)
    assert props.is_mf6 and props.get("MODEL", "ROAD_INCREMENT") is None
    tire = quiet(tire_from_file, path)
    assert tire.mf.use_mode == 4 and tire.relaxation


@pytest.mark.parametrize("fittyp", [6, 21])
def test_mf52_fittyp_loads_quietly_with_unchanged_forces(tmp_path, fittyp):
    text = insert_after(BASE, "[MODEL]", f"FITTYP                   = {fittyp}  $MF version")
    path = write(tmp_path, text)
    assert quiet(read_tir, path).fittyp == fittyp
    np.testing.assert_array_equal(forces(quiet(tire_from_file, path)), base_forces())
    assert read_tir(SAMPLE).fittyp is None


@pytest.mark.parametrize("value, shown", [("5", "FITTYP = 5 "), ("52", "FITTYP = 52 "),
                                          ("'abc'", "'abc'"), ("6.5", "'6.5'")])
def test_other_fittyp_values_are_refused_with_the_valid_ones(tmp_path, value, shown):
    text = insert_after(BASE, "[MODEL]", f"FITTYP = {value}")
    path = write(tmp_path, text)
    with pytest.raises(InputError) as exc:
        read_tir(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {line_of(text, 'FITTYP')}" in msg
    assert "key 'FITTYP'" in msg and shown in msg and "6 or 21" in msg


# ======================================================================== MF 6.x coefficients
def test_pky4_is_ignored_with_a_warning_naming_key_and_line(tmp_path):
    """MF 6.1 with PKY4 = 1.5 gives Ky 805 N/deg; flexpipe's MF 5.2 keeps 1005 N/deg and
    says so."""
    text = insert_after(BASE, "PKY3", "PKY4                     = 1.5")
    path = write(tmp_path, text)
    with pytest.warns(UserWarning) as rec:
        tire = tire_from_file(path)
    msgs = [str(w.message) for w in rec if "MF 6.x" in str(w.message)]
    assert len(msgs) == 1
    assert str(path) in msgs[0] and "PKY4 = 1.5" in msgs[0]
    assert f"line {line_of(text, 'PKY4')}" in msgs[0] and "ignored" in msgs[0]
    r = raw_numbers(path)
    kx52, ky52 = mf52_stiffness(r, FZ)
    _, ky61 = mf61_stiffness(r, FZ)
    assert abs(ky52) * math.pi / 180 == pytest.approx(1005.3, abs=0.1)
    assert abs(ky61) * math.pi / 180 == pytest.approx(805.2, abs=0.1)
    kx, ky = tire.mf.slip_stiffness(FZ)
    assert float(ky) == pytest.approx(ky52, rel=1e-12) and float(kx) == pytest.approx(kx52)


@pytest.mark.parametrize("anchor, line", [
    ("PKY3", "PKY5                     = 0.5"),
    ("PKY3", "PKY6                     = -0.9"),
    ("PKY3", "PKY7                     = 0.2"),
    ("PEY4", "PEY5                     = 0.3"),
    ("QSX3", "QSX4                     = 0.1"),
    ("QSX3", "QSX12                    = 0.05"),
    ("QSY4", "QSY5                     = 0.01"),
    ("QSY4", "QSY6                     = 0.02"),
    ("QSY4", "QSY7                     = 0.85"),
])
def test_mf6_only_coefficient_with_an_effect_warns_and_is_ignored(tmp_path, anchor, line):
    text = insert_after(BASE, anchor, line)
    key = line.split()[0]
    path = write(tmp_path, text)
    with pytest.warns(UserWarning) as rec:
        tire = tire_from_file(path)
    msgs = [str(w.message) for w in rec if "MF 6.x" in str(w.message)]
    assert len(msgs) == 1
    assert str(path) in msgs[0] and f"{key} = " in msgs[0]
    assert f"line {line_of(text, key + ' ')}" in msgs[0]
    np.testing.assert_array_equal(forces(tire), base_forces())


@pytest.mark.parametrize("units, inflpres, nompres", [
    ("", "180000", "250000"),
    ("PRESSURE                 = 'bar'\n", "1.8", "2.5"),
])
def test_pressure_term_warns_when_pressure_is_not_nominal(tmp_path, units, inflpres, nompres):
    """The audit's case: PPX1 = -0.5 at 1.8 bar vs 2.5 bar nominal gives MF 6.1 Kx 95.8 kN;
    flexpipe (no pressure dependence) keeps the MF 5.2 84.0 kN and warns."""
    text = insert_after(BASE, "PKX3", "PPX1                     = -0.5")
    text = insert_after(text, "TIME", units) if units else text
    text += (f"[OPERATING_CONDITIONS]\nINFLPRES = {inflpres}\nNOMPRES  = {nompres}\n")
    path = write(tmp_path, text)
    with pytest.warns(UserWarning) as rec:
        tire = tire_from_file(path)
    msgs = [str(w.message) for w in rec if "MF 6.x" in str(w.message)]
    assert len(msgs) == 1
    msg = msgs[0]
    assert str(path) in msg and "PPX1 = -0.5" in msg and f"line {line_of(text, 'PPX1')}" in msg
    assert "INFLPRES = 180000 Pa" in msg and "NOMPRES = 250000 Pa" in msg
    assert f"line {line_of(text, 'INFLPRES')}" in msg
    r = raw_numbers(path)
    kx52, _ = mf52_stiffness(r, FZ)
    kx61, _ = mf61_stiffness(r, FZ, dpi=(180000.0 - 250000.0) / 250000.0)
    assert kx52 == pytest.approx(84.0e3) and kx61 == pytest.approx(95.76e3)
    assert float(tire.mf.slip_stiffness(FZ)[0]) == pytest.approx(kx52, rel=1e-12)


@pytest.mark.parametrize("units, inflpres, nompres", [
    ("", "180000", "250000"),
    ("PRESSURE                 = 'bar'\n", "1.8", "2.5"),
])
def test_pressure_term_acts_in_an_mf61_fit(tmp_path, units, inflpres, nompres):
    """The same file as an MF 6.1 fit: Kx is MF 6.1's 95.76 kN at 1.8 of 2.5 bar, without a
    warning; ``pressure=`` moves it along the closed form, the vertical stiffness with
    ``1 + PFZ1 dpi``."""
    text = insert_after(BASE, "[MODEL]", "FITTYP                   = 61")
    text = insert_after(text, "PKX3", "PPX1                     = -0.5")
    text = insert_after(text, "FNOMIN", "PFZ1                     = 0.6")
    text = insert_after(text, "TIME", units) if units else text
    text += (f"[OPERATING_CONDITIONS]\nINFLPRES = {inflpres}\nNOMPRES  = {nompres}\n")
    path = write(tmp_path, text)
    tire = quiet(tire_from_file, path, vertical_law="linear")
    r = raw_numbers(path)
    kx61, _ = mf61_stiffness(r, FZ, dpi=(180000.0 - 250000.0) / 250000.0)
    assert kx61 == pytest.approx(95.76e3)
    assert float(tire.mf.slip_stiffness(FZ)[0]) == pytest.approx(kx61, rel=1e-12)
    assert tire.vertical.k == pytest.approx(r["VERTICAL_STIFFNESS"] * (1.0 - 0.6 * 0.28))
    at = quiet(tire_from_file, path, vertical_law="linear", pressure=300000.0)
    kx61, _ = mf61_stiffness(r, FZ, dpi=0.2)
    assert float(at.mf.slip_stiffness(FZ)[0]) == pytest.approx(kx61, rel=1e-12)
    assert at.vertical.k == pytest.approx(r["VERTICAL_STIFFNESS"] * (1.0 + 0.6 * 0.2))


def test_pressure_term_warns_with_adams_tire_conditions(tmp_path):
    text = insert_after(BASE, "PKY3", "PPY1                     = 0.4")
    text += "[TIRE_CONDITIONS]\nIP     = 200000\nIP_NOM = 230000\n"
    path = write(tmp_path, text)
    with pytest.warns(UserWarning, match=r"PPY1 = 0\.4 \(line \d+.*IP = 200000 Pa differs "
                                         r"from IP_NOM = 230000 Pa"):
        read_tir(path)


def test_several_mf6_coefficients_give_one_warning_listing_each_line(tmp_path):
    text = insert_after(BASE, "PKY3", "PKY4 = 1.6\nPKY6 = -0.8")
    text = insert_after(text, "QSY4", "QSY7 = 0.9")
    path = write(tmp_path, text)
    with pytest.warns(UserWarning) as rec:
        read_tir(path)
    msgs = [str(w.message) for w in rec if "MF 6.x" in str(w.message)]
    assert len(msgs) == 1 and "3 MF 6.x coefficients" in msgs[0]
    for key in ("PKY4", "PKY6", "QSY7"):
        assert f"{key} = " in msgs[0] and f"line {line_of(text, key)}" in msgs[0]


def with_edit(anchor: str, new: str) -> str:
    """The sample with ``new`` after ``anchor``; an [OPERATING_CONDITIONS] part of ``new``
    goes to the end of the file."""
    key_line, _, extra = new.partition("\n")
    return insert_after(BASE, anchor, key_line) + (extra + "\n" if extra else "")


PRESSURES = "[OPERATING_CONDITIONS]\nINFLPRES = {}\nNOMPRES = 250000"


@pytest.mark.parametrize("anchor, neutral, effective", [
    ("PKY3", ["PKY4 = 2", "PKY4 = 0"], "PKY4 = 2.2"),
    ("PKY3", ["PKY5 = 0"], "PKY5 = 0.1"),
    ("QSY4", ["QSY7 = 1", "QSY7 = 0"], "QSY7 = 0.5"),
    ("QSX3", ["QSX4 = 0.0"], "QSX4 = 0.02"),
    ("PKX3", ["PPX1 = -0.5",                                       # no pressure given
              "PPX1 = -0.5\n" + PRESSURES.format(250000),          # nominal pressure
              "PPX1 = 0\n" + PRESSURES.format(180000)],            # no pressure term
     "PPX1 = -0.5\n" + PRESSURES.format(180000)),
])
def test_neutral_mf6_values_stay_quiet_and_others_warn(tmp_path, anchor, neutral, effective):
    """A neutral value gives the MF 5.2 result under MF 6.1 too (or is a PAC2002
    placeholder 0): no warning; the non-neutral one next to it warns."""
    for i, new in enumerate(neutral):
        path = write(tmp_path, with_edit(anchor, new), f"neutral{i}.tir")
        np.testing.assert_array_equal(forces(quiet(tire_from_file, path)), base_forces())
    text = with_edit(anchor, effective)
    key = effective.split()[0]
    with pytest.warns(UserWarning, match=rf"{key} = .*line {line_of(text, key)}\b"):
        read_tir(write(tmp_path, text, "effective.tir"))


def test_hmmwv_zero_mf6_terms_stay_quiet(reference_dir, tmp_path):
    """The HMMWV file lists PPX1.. = 0, QSX4.. = 0, QSY5..QSY8 = 0 and IP = IP_NOM: quiet;
    the same file at a non-nominal pressure with PPX1 = -0.5 warns."""
    path = reference_dir / "tires" / "HMMWV_Pac02Tire.tir"
    r = raw_numbers(path)
    assert r["PPX1"] == 0.0 and r["QSY7"] == 0.0 and r["IP"] == r["IP_NOM"]
    quiet(tire_from_file, path)
    text = re.sub(r"(?m)^PPX1(\s*)= 0.0", r"PPX1\1= -0.5", path.read_text())
    text = re.sub(r"(?m)^IP(\s+)= 800000", r"IP\1= 700000", text)
    with pytest.warns(UserWarning, match=rf"PPX1 = -0.5 \(line {line_of(text, 'PPX1')};.*"
                                         r"IP = 700000 Pa differs from IP_NOM = 800000 Pa"):
        read_tir(write(tmp_path, text, "hmmwv.tir"))


# ======================================================================== MF_05
@pytest.mark.parametrize("fittyp", ["", "FITTYP                   = 6\n",
                                    "FITTYP                   = 21\n"])
def test_mf05_file_is_evaluated_as_mf52(tmp_path, fittyp):
    text = BASE.replace("PROPERTY_FILE_FORMAT     = 'PAC2002'",
                        f"{fittyp}PROPERTY_FILE_FORMAT     = 'MF_05'")
    assert "'MF_05'" in text
    path = write(tmp_path, text)
    props = quiet(read_tir, path)
    assert props.property_file_format == "MF_05" and props.is_mf52
    tire = quiet(tire_from_file, path)
    kx, ky = mf52_stiffness(raw_numbers(path), FZ)
    assert [float(v) for v in tire.mf.slip_stiffness(FZ)] == pytest.approx([kx, ky], rel=1e-12)
    np.testing.assert_array_equal(forces(tire), base_forces())
    fiala = quiet(tire_from_file, path, model="fiala")
    assert fiala.params.c_alpha == pytest.approx(abs(ky), rel=1e-12)


def test_mf05_file_keeps_the_strict_key_check(tmp_path):
    text = BASE.replace("'PAC2002'", "'MF_05'").replace("PKY1                     = -18.0",
                                                        "PKY11                    = -18.0")
    path = write(tmp_path, text)
    with pytest.raises(InputError) as exc:
        read_tir(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {line_of(text, 'PKY11')}" in msg and "MF_05" in msg


def test_unsupported_format_names_the_supported_ones(tmp_path):
    text = BASE.replace("'PAC2002'", "'MF-TYRE'")
    path = write(tmp_path, text)
    with pytest.raises(InputError) as exc, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        tire_from_file(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {line_of(text, 'PROPERTY_FILE_FORMAT')}" in msg
    assert "'MF-TYRE'" in msg and "'PAC2002'" in msg and "'MF_05'" in msg
    assert "6.1 / 6.2" in msg and "FITTYP 61 or 62" in msg


# ======================================================================== comment blocks
COMMENTS = ("(COMMENTS)\n{comment_string}\n'Tyre 205/55 R16 $ not a comment'\n"
            "'measured at 2.3 bar ! nor this'\n")


def same_as_base(props, skip=("MDI_HEADER",)):
    base = read_tir(SAMPLE)
    assert set(props.sections) == set(base.sections)
    for name, sec in base.sections.items():
        if name not in skip:
            assert dict(props.sections[name]) == dict(sec), name
    assert set(props.tables) == set(base.tables)
    for name, table in base.tables.items():
        np.testing.assert_array_equal(props.tables[name].data, table.data)


def test_mdi_header_comment_block_and_free_text_are_skipped(tmp_path):
    text = insert_after(BASE, "FILE_FORMAT", COMMENTS + "Created by hand, not KEY = value\n")
    path = write(tmp_path, text)
    props = quiet(read_tir, path)
    same_as_base(props, skip=())
    assert props.get("MDI_HEADER", "FILE_TYPE") == "tir"
    assert props.get("MDI_HEADER", "FILE_FORMAT") == "ASCII"


@pytest.mark.parametrize("anchor", ["[MODEL]", "[DEFLECTION_LOAD_CURVE]"])
def test_comment_block_in_other_free_sections_is_skipped(tmp_path, anchor):
    """In [MODEL] the keys after the block, in [DEFLECTION_LOAD_CURVE] the {pen fz} table
    after it, are still read."""
    path = write(tmp_path, insert_after(BASE, anchor, COMMENTS))
    same_as_base(quiet(read_tir, path))


def test_comment_block_in_a_coefficient_section_is_an_error(tmp_path):
    text = insert_after(BASE, "[VERTICAL]", COMMENTS)
    path = write(tmp_path, text)
    with pytest.raises(InputError) as exc:
        read_tir(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {line_of(text, '(COMMENTS)')}" in msg
    assert "[VERTICAL]" in msg and "(COMMENTS)" in msg and "[MDI_HEADER]" in msg


# ======================================================================== warning once
def deg_file(tmp_path):
    text = BASE.replace("ANGLE                    = 'radian'", "ANGLE                    = 'deg'")
    assert "'deg'" in text
    return write(tmp_path, text, "deg.tir"), text


def test_flexpipe_info_shows_the_angle_warning_once(tmp_path, capsys):
    from flexpipe.cli import main

    path, text = deg_file(tmp_path)
    with warnings.catch_warnings():
        warnings.resetwarnings()            # Python's default filter, as in a shell
        assert main(["info", str(path)]) == 0
    err = capsys.readouterr().err
    hits = [ln for ln in err.splitlines() if "ANGLE" in ln]
    assert len(hits) == 1, err
    assert str(path) in hits[0] and f"line {line_of(text, 'ANGLE')}" in hits[0]
    assert "'deg'" in hits[0]


def test_repeated_reads_warn_once_by_default_and_every_time_when_asked(tmp_path):
    path, _ = deg_file(tmp_path)
    with warnings.catch_warnings(record=True) as rec:
        warnings.resetwarnings()
        read_tir(path)
        tire_from_file(path)
        read_tir(path)
    assert sum("ANGLE" in str(w.message) for w in rec) == 1
    for load in (read_tir, tire_from_file):
        with pytest.warns(UserWarning, match="ANGLE"):
            load(path)


# ======================================================================== no WIDTH
def test_file_without_width_loads_and_reports_width_none(tmp_path):
    text = re.sub(r"(?m)^WIDTH\s*=.*\n", "", BASE)
    assert "RIM_WIDTH" in text and not re.search(r"(?m)^WIDTH", text)
    path = write(tmp_path, text)
    props = quiet(read_tir, path)
    assert props.width is None and read_tir(SAMPLE).width == pytest.approx(0.205)
    # what `flexpipe info` shows besides the width
    assert (props.property_file_format, props.use_mode, props.tyre_side) == \
        ("PAC2002", 14, "SYMMETRIC")
    assert props.unloaded_radius == 0.316 and props.fnomin == 4000.0
    assert props.vertical_stiffness == 220000.0 and props.vertical_damping == 250.0
    np.testing.assert_array_equal(forces(quiet(tire_from_file, path)), base_forces())
