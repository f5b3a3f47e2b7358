"""Bad-input corpus for ``.tir`` tyre property files, generated from the sample file.

``cases()`` yields ``(case_id, filename, content, expect)``: ``expect`` is ``"error"``
(loading must raise a FlexpipeError naming the file) or ``"ok"``.  :func:`load` is the
loader the cases are meant for (``flexpipe.tires.tire_from_file``, PAC2002 model).
"""

from __future__ import annotations

import random
import re
from pathlib import Path

BASE = Path(__file__).resolve().parents[2] / "tires" / "sedan_205_55R16.tir"
MF61 = BASE.with_name("sedan_205_55R16_mf61.tir")


def load(path):
    """Load a case file the way a car does."""
    from flexpipe.tires import tire_from_file

    return tire_from_file(path)


def _set(text: str, key: str, value: str) -> str:
    new, n = re.subn(rf"^(\s*{key}\s*=\s*)[^\s$!]+", lambda m: m.group(1) + value, text,
                     count=1, flags=re.M)
    assert n == 1, key
    return new


def _rename(text: str, key: str, new_key: str) -> str:
    new, n = re.subn(rf"^(\s*){key}(\s*=)", rf"\g<1>{new_key}\g<2>", text, count=1, flags=re.M)
    assert n == 1, key
    return new


def _drop(text: str, key: str) -> str:
    new, n = re.subn(rf"^\s*{key}\s*=.*\n", "", text, count=1, flags=re.M)
    assert n == 1, key
    return new


def _cut_after(text: str, marker: str) -> str:
    i = text.index(marker) + len(marker)
    return text[:i]


def cases():
    """Yield the corpus (about 130 cases)."""
    base = BASE.read_text()
    b = base.encode()
    yield "ok_base", "base.tir", b, "ok"
    # ---- harmless variations: must load
    yield "ok_crlf", "crlf.tir", base.replace("\n", "\r\n").encode(), "ok"
    yield "ok_comments", "comments.tir", re.sub(r"^(\w+\s*=\s*\S+)", r"\1 ! note", base,
                                                flags=re.M).encode(), "ok"
    yield "ok_fortran_exponent", "fortran.tir", _set(base, "VERTICAL_STIFFNESS",
                                                     "2.2D+05").encode(), "ok"
    yield "ok_tabs", "tabs.tir", base.replace(" = ", "\t=\t").encode(), "ok"
    yield "ok_latin1_comment", "latin1.tir", (base + "$ Reifen für Prüfstand\n").encode(
        "latin-1"), "ok"
    # ---- truncations
    for sec in ("[MODEL]", "[VERTICAL]", "[LONGITUDINAL_COEFFICIENTS]",
                "[LATERAL_COEFFICIENTS]", "[ALIGNING_COEFFICIENTS]"):
        name = sec.strip("[]").lower()
        yield f"truncated_after_{name}", f"trunc_{name}.tir", _cut_after(base, sec).encode(), \
            "error"
    for key in ("FNOMIN", "PDX1", "PKY1", "UNLOADED_RADIUS"):
        i = base.index(key)
        yield f"truncated_in_key_{key}", f"trunc_{key}.tir", base[:i + 3].encode(), "error"
        j = base.index("=", i) + 1
        yield f"truncated_after_equals_{key}", f"trunc_eq_{key}.tir", base[:j].encode(), \
            "error"
    yield "empty", "empty.tir", b"", "error"
    yield "whitespace_only", "blank.tir", b"   \n\n\t\n", "error"
    yield "comments_only", "comments_only.tir", b"$ a comment\n! another\n", "error"
    # ---- garbage
    rng = random.Random(14)
    yield "binary_garbage", "garbage.tir", bytes(rng.randrange(256) for _ in range(4000)), \
        "error"
    yield "png_header", "image.tir", b"\x89PNG\r\n\x1a\n" + bytes(200), "error"
    yield "utf16", "utf16.tir", base.encode("utf-16"), "error"
    k = b.index(b"FNOMIN") + 3
    yield "nul_in_key", "nul.tir", b[:k] + b"\x00\x00\x00" + b[k:], "error"
    yield "garbage_line", "garbage_line.tir", base.replace(
        "[VERTICAL]", "[VERTICAL]\nthis is not a key value line").encode(), "error"
    yield "key_before_section", "key_first.tir", ("FNOMIN = 4000\n" + base).encode(), "error"
    # ---- NaN / inf
    for key, value in (("FNOMIN", "nan"), ("FNOMIN", "inf"), ("FNOMIN", "1e999"),
                       ("PDX1", "NaN"), ("UNLOADED_RADIUS", "-inf"), ("PKY1", "1e400"),
                       ("VERTICAL_STIFFNESS", "Infinity")):
        yield f"nonfinite_{key}_{value}", f"nf_{key}.tir", _set(base, key, value).encode(), \
            "error"
    # ---- zero / negative physical values
    for key, value in (("FNOMIN", "0"), ("FNOMIN", "-4000"), ("LFZO", "0"), ("PCX1", "0"),
                       ("PDX1", "0"), ("PCY1", "0"), ("PDY1", "0"), ("PKY1", "0"),
                       ("PKY2", "0"), ("LMUX", "0"), ("LMUY", "-1"),
                       ("UNLOADED_RADIUS", "-0.316"), ("UNLOADED_RADIUS", "0"),
                       ("VERTICAL_STIFFNESS", "0"), ("VERTICAL_STIFFNESS", "-220000"),
                       ("VERTICAL_DAMPING", "-250"), ("FZMAX", "-10000"), ("FZMAX", "0"),
                       ("FZMIN", "20000"), ("KPUMIN", "2.0"), ("KPUMIN", "0.5"),
                       ("KPUMAX", "-0.5"), ("ALPMAX", "-0.1"), ("ALPMAX", "3.0"),
                       ("CAMMIN", "1.0"),
                       # signs fixed by the physics (ISO/Adams W-axes): Fx = 0 at any slip,
                       # reversed side force, misspelt or unknown mounting side
                       ("PKX1", "0.0"), ("PKX1", "-21.0"), ("PKY1", "18.0"),
                       ("PCX1", "-1.6"), ("PDY1", "-1.05"), ("QSY1", "-0.01"),
                       ("TYRESIDE", "'RIGTH'"), ("TYRESIDE", "'MIDDLE'"),
                       # reference speed: PAC2002 divides the speed by it (was a raw
                       # ZeroDivisionError); tyre rigs run at 10-30 m/s
                       ("LONGVL", "0.0"), ("LONGVL", "-16.7"), ("LONGVL", "1000.0")):
        yield f"range_{key}_{value.strip(chr(39))}", f"range_{key}.tir", _set(
            base, key, value).encode(), "error"
    yield "ok_LONGVL_25", "longvl.tir", _set(base, "LONGVL", "25.0").encode(), "ok"
    for side in ("'LEFT'", "'right'", "'Symmetric'"):
        yield f"ok_tyreside_{side.strip(chr(39))}", "side.tir", _set(
            base, "TYRESIDE", side).encode(), "ok"
    yield "missing_PKX1", "missing_PKX1.tir", _drop(base, "PKX1").encode(), "error"
    yield "range_LCZ_0", "range_LCZ.tir", base.replace(
        "[SCALING_COEFFICIENTS]", "[SCALING_COEFFICIENTS]\nLCZ = 0").encode(), "error"
    # ---- wrong types
    for key, value in (("FNOMIN", "'abc'"), ("FNOMIN", "4000N"), ("USE_MODE", "'four'"),
                       ("USE_MODE", "4.5"), ("USE_MODE", "7"), ("PDX1", "1,15"),
                       ("PROPERTY_FILE_FORMAT", "'PAC2006'"),
                       ("PROPERTY_FILE_FORMAT", "'FIALA'")):
        yield f"type_{key}_{value.strip(chr(39))}", f"type_{key}.tir", _set(
            base, key, value).encode(), "error"
    # ---- typos in keys and sections
    for key, typo in (("PDX1", "PDXI"), ("FNOMIN", "FNOMN"), ("UNLOADED_RADIUS",
                                                              "UNLOADED_RADUIS"),
                      ("VERTICAL_STIFFNESS", "VERTICAL_STIFNESS"), ("KPUMAX", "KPUMXA"),
                      ("LFZO", "LFZ0"), ("PKY1", "PKY 1")):
        yield f"typo_{key}", f"typo_{key}.tir", _rename(base, key, typo).encode(), "error"
    for sec, typo in (("[VERTICAL]", "[VERTCAL]"), ("[SCALING_COEFFICIENTS]",
                                                     "[SCALING_COEFFICIENT]"),
                      ("[LATERAL_COEFFICIENTS]", "[LATERAL_COEFICIENTS]"),
                      ("[LONG_SLIP_RANGE]", "[LONG_SLIP_RANG]")):
        yield f"typo_section_{typo.strip('[]')}", "typo_section.tir", base.replace(
            sec, typo).encode(), "error"
    # ---- missing things, duplicates, units
    for key in ("FNOMIN", "UNLOADED_RADIUS", "PROPERTY_FILE_FORMAT", "PCY1", "PDX1"):
        yield f"missing_{key}", f"missing_{key}.tir", _drop(base, key).encode(), "error"
    yield "missing_model_section", "no_model.tir", base.replace("[MODEL]", "").encode(), \
        "error"
    yield "duplicate_key", "dup.tir", base.replace(
        "[VERTICAL]", "[VERTICAL]\nFNOMIN = 5000").encode(), "error"
    if "LENGTH" in base:
        for quantity, unit in (("LENGTH", "'furlong'"), ("LENGTH", "'mm'"),
                               ("FORCE", "'kN'"), ("FORCE", "3")):
            yield f"units_{quantity}_{unit.strip(chr(39))}", "units.tir", _set(
                base, quantity, unit).encode(), "error"
    # ---- the load-deflection table
    head = "{pen        fz}"
    if head in base:
        for label, row in (("three_numbers", " 0.055 14000 1"), ("text", " 0.055 lots"),
                           ("negative_pen", " -0.005 100"), ("decreasing_pen", " 0.001 14000"),
                           ("decreasing_fz", " 0.060 100"), ("nan", " 0.060 nan")):
            yield f"table_{label}", "table.tir", base.replace(
                " 0.050   12875", " 0.050   12875\n" + row).encode(), "error"
        yield "table_empty", "table_empty.tir", re.sub(
            r"(\{pen\s+fz\}\n)(\s*[-0-9.]+\s+[-0-9.]+\n)+", r"\1", base).encode(), "error"
        yield "table_and_stiffness_disagree", "disagree.tir", _set(
            base, "VERTICAL_STIFFNESS", "400000").encode(), "ok"
    yield from _mf61_cases()


def _mf61_cases():
    """The MF 6.1 sample: valid variants MF-Tool writes, and bad pressures and MF 6.x
    coefficients (each an error naming the file)."""
    m6 = MF61.read_text()
    yield "ok_mf61_base", "mf61.tir", m6.encode(), "ok"
    yield "ok_mf62", "mf62.tir", _set(m6, "FITTYP", "62").encode(), "ok"
    yield "ok_mf61_use_mode_124", "mf61_124.tir", _set(m6, "USE_MODE", "124").encode(), "ok"
    yield "ok_mf61_no_format_empty_entry", "mf61_tool.tir", m6.replace(
        "PROPERTY_FILE_FORMAT     = 'MF-TYRE'", "ROAD_INCREMENT           =").encode(), "ok"
    yield "ok_mf61_q_fz2", "mf61_qfz2.tir", re.sub(
        r"\[DEFLECTION_LOAD_CURVE\]\n\{pen +fz\}\n( *[0-9.]+ +[0-9]+\n)+", "",
        m6.replace("PFZ1 ", "Q_FZ2 = 12.0\nPFZ1 ")).encode(), "ok"
    for key, value in (("FITTYP", "60"), ("FITTYP", "63"), ("USE_MODE", "125"),
                       ("USE_MODE", "164"), ("INFLPRES", "400000"), ("INFLPRES", "0"),
                       ("INFLPRES", "-230000"), ("NOMPRES", "0"), ("PKY4", "0"),
                       ("PRESMIN", "300000")):
        yield f"mf61_{key}_{value}", f"mf61_{key}.tir", _set(m6, key, value).encode(), "error"
    yield "mf61_no_operating_conditions", "mf61_nop.tir", re.sub(
        r"\[OPERATING_CONDITIONS\]\n(.*\n){2}", "", m6).encode(), "error"
    yield "mf61_q_fz2_negative", "mf61_qfz2n.tir", re.sub(
        r"\[DEFLECTION_LOAD_CURVE\]\n\{pen +fz\}\n( *[0-9.]+ +[0-9]+\n)+", "",
        m6.replace("PFZ1 ", "Q_FZ2 = -5.0\nPFZ1 ")).encode(), "error"
    yield "mf61_pfz1_no_stiffness", "mf61_pfz1.tir", _set(_set(m6, "PFZ1", "-20.0"),
                                                            "INFLPRES", "300000").encode(), "error"
    yield "mf61_typo_PPX5", "mf61_ppx5.tir", _rename(m6, "PPX4", "PPX5").encode(), "error"
