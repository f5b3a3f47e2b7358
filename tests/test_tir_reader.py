"""TeimOrbit .tir reader: reference files, units, tables and error messages.

References: the raw text of the files (read here with a few independent lines), unit
definitions (1 mm = 1e-3 m, 1 kN = 1e3 N, 1 deg = pi/180 rad).
"""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest
from _tirdata import REFERENCE_TIRS, SAMPLE, raw_numbers

from flexpipe.errors import InputError
from flexpipe.tires import read_tir, tire_from_file


def line_of(text: str, needle: str) -> int:
    return next(i for i, ln in enumerate(text.splitlines(), 1) if ln.startswith(needle))


@pytest.mark.parametrize("name", REFERENCE_TIRS)
def test_reference_files_load_without_warnings(reference_dir, name):
    path = reference_dir / "tires" / name
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        props = read_tir(path)
    raw = raw_numbers(path)
    assert props.property_file_format == "PAC2002"
    assert props.use_mode == int(raw["USE_MODE"])
    assert props.unloaded_radius == raw["UNLOADED_RADIUS"]
    assert props.fnomin == raw["FNOMIN"]
    assert props.vertical_damping == raw["VERTICAL_DAMPING"]
    assert props.vertical_stiffness == pytest.approx(raw["VERTICAL_STIFFNESS"] * raw.get("LCZ", 1))
    for sec in ("LONGITUDINAL_COEFFICIENTS", "LATERAL_COEFFICIENTS", "ALIGNING_COEFFICIENTS"):
        for key, value in props.coefficients(sec).items():
            assert value == raw[key], (sec, key)
    # read-only mappings
    with pytest.raises(TypeError):
        props.sections["VERTICAL"]["FNOMIN"] = 1.0


def test_shape_table_kept_as_array(reference_dir):
    path = reference_dir / "tires" / "Sedan_Pac02Tire.tir"
    table = read_tir(path).tables["SHAPE"]
    assert table.columns == ("radial", "width")
    np.testing.assert_array_equal(table.data, [[1.0, 0.0], [1.0, 0.4], [1.0, 0.9], [0.9, 1.0]])
    assert not table.data.flags.writeable


def test_relaxation_length_accessors_match_mf52_formula(reference_dir):
    path = reference_dir / "tires" / "mf_185_80R14.tir"
    r = raw_numbers(path)
    props = read_tir(path)
    fz0 = r["FNOMIN"] * r["LFZO"]
    for Fz in (2000.0, r["FNOMIN"], 6000.0):
        dfz = (Fz - fz0) / fz0
        sk = (Fz * (r["PTX1"] + r["PTX2"] * dfz) * np.exp(-r["PTX3"] * dfz)
              * r["UNLOADED_RADIUS"] / r["FNOMIN"] * r["LSGKP"])
        sa = (r["PTY1"] * np.sin(2 * np.arctan(Fz / (r["PTY2"] * fz0))) * r["UNLOADED_RADIUS"]
              * r["LFZO"] * r["LSGAL"])
        assert props.relaxation_length_longitudinal(Fz) == pytest.approx(sk, rel=1e-12)
        assert props.relaxation_length_lateral(Fz) == pytest.approx(sa, rel=1e-12)


def _to_mm_kn(text: str) -> str:
    """The sample file rewritten in mm / kN / degree units (values converted by hand)."""
    r = raw_numbers(SAMPLE)
    subs = {
        "LENGTH                   = 'meter'": "LENGTH = 'mm'",
        "FORCE                    = 'newton'": "FORCE = 'kN'",
        "ANGLE                    = 'radian'": "ANGLE = 'degree'",
    }
    for a, b in subs.items():
        text = text.replace(a, b)
    conv = {"UNLOADED_RADIUS": 1e3, "WIDTH": 1e3, "RIM_RADIUS": 1e3, "RIM_WIDTH": 1e3,
            "VERTICAL_STIFFNESS": 1e-3 * 1e-3, "VERTICAL_DAMPING": 1e-3 * 1e-3,
            "FNOMIN": 1e-3, "FZMIN": 1e-3, "FZMAX": 1e-3, "LONGVL": 1e3, "VXLOW": 1e3,
            "ALPMIN": 180 / np.pi, "ALPMAX": 180 / np.pi, "CAMMIN": 180 / np.pi,
            "CAMMAX": 180 / np.pi}
    out = []
    for ln in text.splitlines():
        key = ln.split("=")[0].strip()
        if key in conv and "=" in ln:
            ln = f"{key} = {r[key] * conv[key]!r}"
        elif re.match(r"^\s*\d+\.\d+\s+\d+\s*$", ln):
            pen, fz = ln.split()
            ln = f" {float(pen) * 1e3!r} {float(fz) * 1e-3!r}"
        out.append(ln)
    return "\n".join(out) + "\n"


def test_units_section_converts_to_si(tmp_path):
    si = read_tir(SAMPLE)
    path = tmp_path / "mm_kn.tir"
    path.write_text(_to_mm_kn(SAMPLE.read_text()))
    with pytest.warns(UserWarning, match="radian-based"):
        other = read_tir(path)
    for sec, key in [("DIMENSION", "UNLOADED_RADIUS"), ("VERTICAL", "VERTICAL_STIFFNESS"),
                     ("VERTICAL", "VERTICAL_DAMPING"), ("VERTICAL", "FNOMIN"),
                     ("MODEL", "LONGVL"), ("SLIP_ANGLE_RANGE", "ALPMAX")]:
        assert other.get(sec, key) == pytest.approx(si.get(sec, key), rel=1e-12), key
    np.testing.assert_allclose(other.tables["DEFLECTION_LOAD_CURVE"].data,
                               si.tables["DEFLECTION_LOAD_CURVE"].data, rtol=1e-12)
    # the same physical tyre gives the same forces
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t_si, t_mm = tire_from_file(SAMPLE), tire_from_file(path)
    a = np.array([-0.1, 0.02, 0.2])
    np.testing.assert_allclose(t_mm.slip_forces(0.05, a, 3500.0).Fy,
                               t_si.slip_forces(0.05, a, 3500.0).Fy, rtol=1e-10)
    assert t_mm.vertical.k == pytest.approx(t_si.vertical.k, rel=1e-9)


def test_comments_quotes_and_fortran_exponents(tmp_path):
    text = SAMPLE.read_text()
    text = text.replace("FILE_TYPE                = 'tir'",
                        "FILE_TYPE = 'tir $ not a comment' ! trailing comment")
    text = text.replace("PKX1                     = 21.0", "PKX1 = 2.1D+01   ! Fortran")
    path = tmp_path / "c.tir"
    path.write_text(text)
    props = read_tir(path)
    assert props.get("MDI_HEADER", "FILE_TYPE") == "tir $ not a comment"
    assert props.get("LONGITUDINAL_COEFFICIENTS", "PKX1") == 21.0


def _write(tmp_path, text, name="bad.tir"):
    path = tmp_path / name
    path.write_text(text)
    return path


def test_unknown_coefficient_key_names_file_line_and_key(tmp_path):
    text = SAMPLE.read_text().replace("PKY1                     = -18.0",
                                      "PKY11                    = -18.0")
    path = _write(tmp_path, text)
    with pytest.raises(InputError) as exc:
        read_tir(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {line_of(text, 'PKY11')}" in msg
    assert "PKY11" in msg and "LATERAL_COEFFICIENTS" in msg and "PKY1" in msg


@pytest.mark.parametrize(
    ("old", "new", "needle", "what"),
    [
        ("PCY1                     = 1.35", "PCY1 1.35", "PCY1", "expected KEY = value"),
        ("PDY1                     = 1.05", "PDY1 = abc", "PDY1", "must be a number"),
        ("PDY2                     = -0.12", "PDY2 =", "PDY2", "has no value"),
        ("PEY1                     = -0.5", "PEY1 = -0.5\nPEY1 = -0.4", "PEY1 = -0.4",
         "given twice"),
        (" 0.010    2215", " 0.010    2215  7", " 0.010", "must hold 2 numbers"),
        ("USE_MODE                 = 14", "USE_MODE = 7", "USE_MODE", "USE_MODE"),
        ("LENGTH                   = 'meter'", "LENGTH = 'furlong'", "LENGTH", "not a known unit"),
    ],
)
def test_malformed_entries_name_file_and_line(tmp_path, old, new, needle, what):
    text = SAMPLE.read_text()
    assert old in text
    text = text.replace(old, new)
    path = _write(tmp_path, text)
    with pytest.raises(InputError) as exc:
        read_tir(path)
    msg = str(exc.value)
    assert str(path) in msg and what in msg
    assert f"line {line_of(text, needle)}" in msg


def test_entry_before_first_section(tmp_path):
    path = _write(tmp_path, "FNOMIN = 4000\n" + SAMPLE.read_text())
    with pytest.raises(InputError, match=r"line 1.*before the first \[SECTION\]"):
        read_tir(path)


@pytest.mark.parametrize("section", ["LATERAL_COEFFICIENTS", "VERTICAL", "DIMENSION"])
def test_missing_section_names_file_and_section(tmp_path, section):
    text = SAMPLE.read_text().replace(f"[{section}]", "[SOMETHING_ELSE]")
    path = _write(tmp_path, text)
    with pytest.raises(InputError) as exc, warnings.catch_warnings():
        warnings.simplefilter("ignore")
        read_tir(path)
    assert str(path) in str(exc.value) and f"[{section}]" in str(exc.value)


def test_missing_lateral_section_is_fine_for_longitudinal_only_use_mode(tmp_path):
    text = SAMPLE.read_text().replace("USE_MODE                 = 14", "USE_MODE = 1")
    text = text.replace("[LATERAL_COEFFICIENTS]", "[UNUSED_LATERAL]")
    path = _write(tmp_path, text)
    with pytest.warns(UserWarning, match="unknown section"):
        props = read_tir(path)
    assert "UNUSED_LATERAL" in props.sections  # kept
    with pytest.warns(UserWarning, match="unknown section"):
        tire = tire_from_file(path)
    f = tire.slip_forces(0.05, 0.1, 4000.0)
    assert f.Fx > 0 and f.Fy == 0 and f.Mz == 0


def test_unreadable_file_and_wrong_model(tmp_path):
    with pytest.raises(InputError, match="cannot read"):
        read_tir(tmp_path / "nope.tir")
    with pytest.raises(InputError, match="unknown tyre model"):
        tire_from_file(SAMPLE, model="pac89")
    with pytest.raises(InputError, match="no \\[SECTION\\]"):
        read_tir(_write(tmp_path, "$ only a comment\n"))


# ---------------------------------------------------------------- physical range checks
@pytest.mark.parametrize("key, value, valid", [
    ("FNOMIN", "0", "> 0"), ("LFZO", "0", "> 0"), ("PCX1", "0", "non-zero"),
    ("PDX1", "0", "non-zero"), ("UNLOADED_RADIUS", "-0.316", "> 0"), ("FNOMIN", "-4000", "> 0"),
    ("FZMAX", "-10000", "> 0"), ("KPUMIN", "2.0", "[-inf, 0]")])
def test_physical_range_errors_name_line_key_and_range(tmp_path, key, value, valid):
    """The issue's cases: each used to give NaN or plausible but wrong forces."""
    text = SAMPLE.read_text()
    line_no = next(i for i, t in enumerate(text.splitlines(), 1) if t.startswith(key))
    f = tmp_path / "bad.tir"
    f.write_text(re.sub(rf"^({key}\s*=\s*)\S+", rf"\g<1>{value}", text, count=1, flags=re.M))
    with pytest.raises(InputError) as exc:
        tire_from_file(f)
    msg = str(exc.value)
    assert "bad.tir" in msg and f"line {line_no}" in msg and key in msg and valid in msg


def test_stiffness_and_load_curve_disagreeing_says_which_is_used(tmp_path):
    text = re.sub(r"^(VERTICAL_STIFFNESS\s*=\s*)\S+", r"\g<1>400000", SAMPLE.read_text(),
                  count=1, flags=re.M)
    f = tmp_path / "disagree.tir"
    f.write_text(text)
    with pytest.warns(UserWarning, match="DEFLECTION_LOAD_CURVE.*is used.*400000.*not used"):
        tire = tire_from_file(f)
    # the model is the table's: least squares of the table read straight from the text
    rows = re.search(r"\{pen\s+fz\}\n((?:\s*[\d.]+\s+[\d.]+\n)+)", text).group(1)
    pen, fz = np.array([r.split() for r in rows.strip().splitlines()], dtype=float).T
    k, k3 = np.linalg.lstsq(np.column_stack([pen, pen ** 3]), fz, rcond=None)[0]
    assert tire.vertical.k == pytest.approx(k) and tire.vertical.k3 == pytest.approx(k3)


# ---------------------------------------------------------------- signs fixed by physics
def _with(tmp_path, key, value, name="bad.tir"):
    """The sample with ``key = value`` (first occurrence) and the line number of the key."""
    text = SAMPLE.read_text()
    line_no = line_of(text, key)
    new, n = re.subn(rf"^({key}\s*=\s*)\S+", rf"\g<1>{value}", text, count=1, flags=re.M)
    assert n == 1, key
    return _write(tmp_path, new, name), line_no


@pytest.mark.parametrize("key, value, valid", [
    ("PKX1", "0.0", "> 0"), ("PKX1", "-21.0", "> 0"),            # Fx = 0 / reversed
    ("PKY1", "18.0", "PKY1 < 0"),                                  # Fy reversed
    ("PKY2", "-2.0", "PKY2 > 0"),                                  # Fy reversed, via PKY2
    ("PCX1", "-1.6", "> 0"), ("PCY1", "-1.35", "> 0"),
    ("PDX1", "-1.15", "> 0"), ("PDY1", "-1.05", "> 0"),
    ("QSY1", "-0.01", ">= 0"), ("QDZ1", "-0.12", ">= 0"),
    ("PTX1", "-1.0", ">= 0"), ("PTY1", "-2.0", "PTY1 > 0"),
    ("LKX", "0", "> 0")])
def test_coefficient_sign_fixed_by_physics_names_file_line_key_and_range(tmp_path, key,
                                                                         value, valid):
    """Finding: PKX1 = 0 gave Fx = 0 at any slip and PKY1 = +18 a reversed side force,
    both accepted; the other coefficients here have a sign just as certain."""
    path, line_no = _with(tmp_path, key, value)
    with pytest.raises(InputError) as exc:
        read_tir(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {line_no}" in msg and f"key '{key}'" in msg
    assert valid in msg


def test_relaxation_sign_message_states_the_same_sign_rule(tmp_path):
    """Finding: the message said "PTY1 > 0 and PTY2 > 0" while the check (rightly)
    accepts both negative: the rule is that they have the same sign."""
    path, line_no = _with(tmp_path, "PTY2", "-1.8")
    with pytest.raises(InputError) as exc:
        read_tir(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {line_no}" in msg and "key 'PTY2'" in msg
    assert "same sign" in msg and "both < 0" in msg and "PTY2 = -1.8" in msg
    text, n = re.subn(r"^(PTY[12]\s*=\s*)(\S+)", r"\g<1>-\g<2>", SAMPLE.read_text(),
                      flags=re.M)
    assert n == 2
    read_tir(_write(tmp_path, text, "both_negative.tir"))   # same sign: accepted


def test_wrong_cornering_stiffness_sign_message_gives_the_convention(tmp_path):
    path, _ = _with(tmp_path, "PKY1", "18.0")
    with pytest.raises(InputError, match=r"Ky = \+.* N/rad.*ISO/Adams W-axes.*negative Fy"):
        tire_from_file(path)


def test_missing_slip_stiffness_is_an_error(tmp_path):
    text = re.sub(r"^PKX1\s*=.*\n", "", SAMPLE.read_text(), count=1, flags=re.M)
    path = _write(tmp_path, text)
    with pytest.raises(InputError) as exc:
        read_tir(path)
    assert str(path) in str(exc.value) and "PKX1" in str(exc.value)


@pytest.mark.parametrize("value", ["'RIGTH'", "'MIDDLE'", "'L'", "1"])
def test_unknown_tyre_side_names_file_line_value_and_valid_sides(tmp_path, value):
    path, line_no = _with(tmp_path, "TYRESIDE", value)
    with pytest.raises(InputError) as exc:
        tire_from_file(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {line_no}" in msg and "TYRESIDE" in msg
    assert value.strip("'") in msg
    assert all(side in msg for side in ("LEFT", "RIGHT", "SYMMETRIC"))


@pytest.mark.parametrize("value, mirrored", [("'left'", [False, True]),
                                             ("'Right'", [True, False]),
                                             ("'SYMMETRIC'", [False, False]),
                                             ("LEFT", [False, True])])
def test_valid_tyre_sides_any_case(tmp_path, value, mirrored):
    path, _ = _with(tmp_path, "TYRESIDE", value, name="ok.tir")
    tire = tire_from_file(path)
    assert [bool(m) for m in tire.mirror_for(["left", "right"])] == mirrored
