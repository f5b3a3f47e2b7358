"""Bad-input corpus for OpenCRG road files, generated from valid base files.

Bases: the repository's text sample ``roads/sample_bump.crg`` (LRFI), and two files built
here byte by byte: a straight KRBI (single-precision binary) road and a curved KDBI road
with heading, slope and banking channels.  ``cases()`` yields ``(case_id, filename,
content, expect)``; :func:`load` is ``flexpipe.roads.read_crg``.
"""

from __future__ import annotations

import math
import random
import struct
from pathlib import Path

TEXT_BASE = Path(__file__).resolve().parents[2] / "roads" / "sample_bump.crg"
SEP = "$" * 72


def load(path):
    """Load a case file."""
    from flexpipe.roads import read_crg

    return read_crg(path)


def _header(keys: dict, channels: list[str], fmt: str) -> str:
    head = ["$CT", "generated bad-input base", "$", "$ROAD_CRG"]
    head += [f"{k:<26}= {v}" for k, v in keys.items()]
    head += ["$", "$KD_DEFINITION", f"#:{fmt}"] + [f"D:{c}" for c in channels] + ["$", SEP]
    return "\n".join(head) + "\n"


def _binary(rows, fmt: str) -> bytes:
    code = ">f" if fmt[1] == "R" else ">d"
    flat = [x for row in rows for x in row]
    per = 80 // struct.calcsize(code)
    flat += [math.nan] * (-len(flat) % per)
    return b"".join(struct.pack(code, x) for x in flat)


def _straight_krbi():
    n_u, n_v = 41, 3
    keys = {"REFERENCE_LINE_START_U": "0.0", "REFERENCE_LINE_END_U": "20.0",
            "REFERENCE_LINE_INCREMENT": "0.5", "LONG_SECTION_V_RIGHT": "-1.5",
            "LONG_SECTION_V_LEFT": "1.5", "LONG_SECTION_V_INCREMENT": "1.5"}
    rows = [[0.01 * math.sin(0.3 * i + j) for j in range(n_v)] for i in range(n_u)]
    chans = [f"long section {j + 1},m" for j in range(n_v)]
    return keys, chans, rows


def _curved_kdbi():
    n_u = 61
    keys = {"REFERENCE_LINE_START_U": "0.0", "REFERENCE_LINE_END_U": "30.0",
            "REFERENCE_LINE_INCREMENT": "0.5", "LONG_SECTION_V_RIGHT": "-2.0",
            "LONG_SECTION_V_LEFT": "2.0", "LONG_SECTION_V_INCREMENT": "2.0",
            "REFERENCE_LINE_START_X": "10.0", "REFERENCE_LINE_START_Y": "5.0"}
    rows = [[0.02 * i, 0.01, 0.02, 0.0, 0.001 * i, 0.0] for i in range(n_u)]
    rows[0][0] = rows[0][1] = math.nan
    chans = ["reference line phi,rad", "reference line slope,m/m",
             "reference line banking,m/m", "long section 1,m", "long section 2,m",
             "long section 3,m"]
    return keys, chans, rows


def _build(keys, chans, rows, fmt="KRBI", *, drop=(), change=None, extra=(), data=None):
    keys = {k: v for k, v in keys.items() if k not in drop}
    keys.update(change or {})
    text = _header(keys, chans, fmt)
    if extra:
        text = text.replace("$KD_DEFINITION", "\n".join(extra) + "\n$\n$KD_DEFINITION")
    return text.encode() + (_binary(rows, fmt) if data is None else data)


def cases():
    """Yield the corpus (about 75 cases)."""
    text = TEXT_BASE.read_text()
    tb = text.encode()
    head, body = text.split(SEP + "\n", 1)
    yield "ok_text_base", "sample.crg", tb, "ok"
    yield "ok_text_crlf", "crlf.crg", text.replace("\n", "\r\n").encode(), "ok"
    yield "ok_text_comment", "comment.crg", text.replace(
        "$ROAD_CRG\n", "$ROAD_CRG\n* a comment line\n").encode(), "ok"
    yield "ok_text_inline_comment", "inline.crg", text.replace(
        "LONG_SECTION_V_RIGHT      = -1.0000000000000000e+00",
        "LONG_SECTION_V_RIGHT      = -1.0 ! right border").encode(), "ok"
    yield "ok_increment_from_u_channel", "u_channel.crg", "\n".join(
        t for t in text.split("\n") if not t.startswith("REFERENCE_LINE_INCREMENT")).encode(), \
        "ok"
    yield "u_channel_garbage_increment", "u_channel_bad.crg", "\n".join(
        t for t in text.split("\n") if not t.startswith("REFERENCE_LINE_INCREMENT")).replace(
        "U:reference line u,m,0.000,0.100", "U:reference line u,m,0.000,zero").encode(), "error"
    sk = _straight_krbi()
    cu = _curved_kdbi()
    yield "ok_krbi", "straight.crg", _build(*sk), "ok"
    yield "ok_kdbi_curved", "curved.crg", _build(*cu, fmt="KDBI"), "ok"
    yield "ok_at_v_channels", "at_v.crg", _build(
        sk[0], [f"long section at v = {v},m" for v in (-1.5, 0.0, 1.5)], sk[2]), "ok"
    yield "ok_border_nan", "border_nan.crg", _build(
        sk[0], sk[1], [[math.nan, 0.0, 0.0]] + sk[2][1:]), "ok"
    # ---- truncations
    lines = body.splitlines()
    yield "text_rows_missing", "short.crg", (head + SEP + "\n" + "\n".join(
        lines[:len(lines) // 2]) + "\n").encode(), "error"
    yield "text_last_row_cut", "cut_row.crg", (head + SEP + "\n" + "\n".join(
        lines[:-1]) + "\n" + lines[-1][:25] + "\n").encode(), "error"
    yield "no_separator", "no_sep.crg", head.encode(), "error"
    yield "header_only_with_separator", "no_data.crg", (head + SEP + "\n").encode(), "error"
    yield "cut_in_header", "cut_header.crg", tb[:tb.index(b"$KD_DEFINITION")], "error"
    full = _build(*sk)
    for frac in (0.5, 0.9, 0.99):
        n = len(full) - int((len(full) - full.index(SEP.encode())) * (1 - frac))
        yield f"binary_cut_{frac}", "bin_cut.crg", full[:n], "error"
    yield "empty", "empty.crg", b"", "error"
    # ---- garbage
    rng = random.Random(13)
    junk = bytes(rng.randrange(256) for _ in range(3000))
    yield "binary_garbage", "garbage.crg", junk, "error"
    yield "garbage_after_text_header", "text_junk.crg", head.encode() + SEP.encode() + b"\n" \
        + junk, "error"
    yield "krbi_with_text_data", "krbi_text.crg", (head.replace("#:LRFI", "#:KRBI") + SEP
                                                   + "\n" + body).encode(), "error"
    yield "utf16", "utf16.crg", text.encode("utf-16"), "error"
    yield "text_value_garbage", "value_junk.crg", (head + SEP + "\n" + body.replace(
        " 0.0000000", " abcdefghi", 1)).encode(), "error"
    # ---- NaN / inf in the header and data
    for key, value in (("REFERENCE_LINE_END_U", "inf"), ("REFERENCE_LINE_END_U", "nan"),
                       ("REFERENCE_LINE_INCREMENT", "inf"), ("REFERENCE_LINE_INCREMENT", "nan"),
                       ("REFERENCE_LINE_START_U", "-inf"), ("LONG_SECTION_V_INCREMENT", "nan"),
                       ("REFERENCE_LINE_END_U", "1e999"), ("REFERENCE_LINE_START_Z", "inf")):
        yield f"header_{key}_{value}", "nf_header.crg", _build(
            *sk, change={key: value}), "error"
    for label, value in (("nan", "       nan"), ("inf", "       inf"), ("huge", "    1e999")):
        yield f"text_data_{label}", "nf_data.crg", (head + SEP + "\n" + body.replace(
            " 0.0000000", value.rjust(10), 1)).encode(), "error"
    rows = [r[:] for r in sk[2]]
    rows[5][1] = math.inf
    yield "binary_data_inf", "bin_inf.crg", _build(sk[0], sk[1], rows), "error"
    rows = [r[:] for r in sk[2]]
    rows[5][1] = math.nan
    yield "binary_interior_nan", "bin_nan.crg", _build(sk[0], sk[1], rows), "error"
    rows = [r[:] for r in sk[2]]
    rows[7] = [math.nan] * 3
    yield "binary_row_all_nan", "bin_nan_row.crg", _build(sk[0], sk[1], rows), "error"
    for col, label in ((0, "phi"), (1, "slope"), (2, "banking")):
        rows = [r[:] for r in cu[2]]
        rows[10][col] = math.nan if col != 2 else math.inf
        yield f"curved_{label}_nonfinite", "curved_nf.crg", _build(
            cu[0], cu[1], rows, fmt="KDBI"), "error"
    # ---- zero / negative / inconsistent grid values
    for key, value in (("REFERENCE_LINE_INCREMENT", "0.0"), ("REFERENCE_LINE_INCREMENT", "-0.5"),
                       ("REFERENCE_LINE_END_U", "-20.0"), ("REFERENCE_LINE_END_U", "0.0"),
                       ("REFERENCE_LINE_END_U", "20.3"), ("REFERENCE_LINE_END_U", "1e12"),
                       ("LONG_SECTION_V_INCREMENT", "0.0"), ("LONG_SECTION_V_INCREMENT", "-1.5"),
                       ("LONG_SECTION_V_LEFT", "2.5"), ("REFERENCE_LINE_END_U", "40.0")):
        yield f"grid_{key}_{value}", "grid.crg", _build(*sk, change={key: value}), "error"
    # ---- wrong types, formats and channels
    for key, value in (("REFERENCE_LINE_END_U", "twenty"), ("REFERENCE_LINE_INCREMENT", "0,5"),
                       ("LONG_SECTION_V_RIGHT", "'-1.5'")):
        yield f"type_{key}", "type.crg", _build(*sk, change={key: value}), "error"
    for fmt in ("XRBI", "KRB", "KQBI", "KRXI", ""):
        yield f"format_{fmt or 'empty'}", "fmt.crg", _build(*sk).replace(
            b"#:KRBI", f"#:{fmt}".encode()), "error"
    yield "no_format_line", "nofmt.crg", _build(*sk).replace(b"#:KRBI\n", b""), "error"
    for label, chans in (
            ("unknown_channel", sk[1][:2] + ["temperature,C"]),
            ("numbering_gap", ["long section 1,m", "long section 3,m", "long section 4,m"]),
            ("one_section", ["long section 1,m", "reference line slope,m/m",
                             "reference line banking,m/m"]),
            ("mixed_index_and_v", ["long section 1,m", "long section 2,m",
                                   "long section at v = 1.5,m"]),
            ("same_v_twice", ["long section at v = 0,m", "long section at v = 0,m",
                              "long section at v = 1,m"]),
            ("unit_mm", ["long section 1,mm", "long section 2,mm", "long section 3,mm"]),
            ("no_unit", ["long section 1", "long section 2", "long section 3"]),
            ("phi_twice", ["reference line phi,rad", "reference line phi,rad",
                           "long section 1,m"])):
        yield f"channels_{label}", "chan.crg", _build(sk[0], chans, sk[2]), "error"
    wide = [[0.001] + r for r in sk[2]]           # one reference channel + 3 long sections
    for label, chan in (("phi_in_degrees", "reference line phi,deg"),
                        ("slope_in_percent", "reference line slope,%"),
                        ("banking_no_unit", "reference line banking"),
                        ("unknown_reference_channel", "reference line curvature,1/m")):
        yield f"channels_{label}", "chan.crg", _build(sk[0], [chan] + sk[1], wide), "error"
    yield "ok_slope_channel", "slope.crg", _build(
        sk[0], ["reference line slope,m/m"] + sk[1], wide), "ok"
    # ---- typos and missing keys or sections
    for key, typo in (("REFERENCE_LINE_END_U", "REFERENCE_LINE_END_UU"),
                      ("REFERENCE_LINE_INCREMENT", "REFRENCE_LINE_INCREMENT"),
                      ("LONG_SECTION_V_RIGHT", "LONG_SECTION_V_RIGT")):
        keys = {typo if k == key else k: v for k, v in sk[0].items()}
        yield f"typo_{typo}", "typo.crg", _build(keys, sk[1], sk[2]), "error"
    yield "typo_start_b", "typo_b.crg", _build(*sk, change={"REFERENCE_LINE_STRAT_B": "0.05"}), \
        "error"
    yield "typo_section_road_crg", "typo_sec.crg", _build(*sk).replace(
        b"$ROAD_CRG\n", b"$ROAD_CGR\n"), "error"
    yield "typo_section_kd", "typo_kd.crg", _build(*sk).replace(
        b"$KD_DEFINITION", b"$KD_DEFINTION"), "error"
    # values OpenCRG derives when the file leaves them out (tests/test_crg_derived.py
    # compares the heights with pyopencrg's)
    for key in ("REFERENCE_LINE_END_U", "REFERENCE_LINE_INCREMENT", "LONG_SECTION_V_RIGHT",
                "LONG_SECTION_V_INCREMENT"):
        yield f"ok_derived_{key}", "missing.crg", _build(*sk, drop=(key,)), "ok"
    yield "duplicate_key", "dup.crg", _build(*sk).replace(
        b"$ROAD_CRG\n", b"$ROAD_CRG\nREFERENCE_LINE_INCREMENT = 0.25\n"), "error"
    yield "key_without_equals", "noeq.crg", _build(*sk).replace(
        b"$ROAD_CRG\n", b"$ROAD_CRG\nREFERENCE_LINE_START_Z 1.0\n"), "error"
    # $ROAD_CRG_OPTS (flexpipe/roads/crg_opts.py): a section before $KD_DEFINITION
    for label, lines, expect in (
            ("ok_opts_repeat", "BORDER_MODE_V = 3\nBORDER_SMOOTH_UBEG = 2.0", "ok"),
            ("ok_opts_other_tools", "CHECK_TOL = 1e-3\nWARN_MSGS = 0", "ok"),
            ("opts_mode_v_none", "BORDER_MODE_V = 0", "error"),
            ("opts_mode_v_7", "BORDER_MODE_V = 7", "error"),
            ("opts_mode_u_repeat", "BORDER_MODE_U = 3", "error"),
            ("opts_closed_track", "REFLINE_CONTINUATION = 1", "error"),
            ("opts_smooth_negative", "BORDER_SMOOTH_UEND = -2", "error"),
            ("opts_typo", "BORDER_MODE_VV = 2", "error"),
            ("opts_text", "BORDER_OFFSET_V = high", "error"),
            ("opts_no_equals", "BORDER_MODE_V 2", "error")):
        yield label, "opts.crg", _build(*sk).replace(
            b"$KD_DEFINITION", f"$ROAD_CRG_OPTS\n{lines}\n$\n$KD_DEFINITION".encode(), 1), \
            expect
