"""Bad-input corpus for Adams 2D road data files (``.rdf``), generated from the
repository's samples ``roads/plank_15mm.rdf`` and ``roads/poly_line.rdf`` and from small
files of every road type.  ``cases()`` yields ``(case_id, filename, content, expect)``;
:func:`load` is ``flexpipe.roads.load_road``.
"""

from __future__ import annotations

import random
import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def load(path):
    """Load a case file."""
    from flexpipe.roads import load_road

    return load_road(path)


def _set(text: str, key: str, value: str) -> str:
    """``key`` set to ``value``: in [PARAMETERS] when the file has that section (LENGTH is
    a unit in [UNITS] too), else its first occurrence."""
    at = text.find("[PARAMETERS]") if key not in ("METHOD", "ROAD_TYPE") else -1
    head, tail = (text[:at], text[at:]) if at >= 0 else ("", text)
    new, n = re.subn(rf"^(\s*{key}\s*=\s*)\S+", lambda m: m.group(1) + value, tail, count=1,
                     flags=re.M)
    assert n == 1, key
    return head + new


def _drop(text: str, key: str) -> str:
    """``text`` without the line of ``key`` (in [PARAMETERS] as :func:`_set`)."""
    at = text.find("[PARAMETERS]") if key not in ("METHOD", "ROAD_TYPE") else -1
    head, tail = (text[:at], text[at:]) if at >= 0 else ("", text)
    new, n = re.subn(rf"^\s*{key}\s*=.*\n", "", tail, count=1, flags=re.M)
    assert n == 1, key
    return head + new


def _small(road_type: str, params: str) -> str:
    return (f"[UNITS]\n LENGTH = 'meter'\n ANGLE = 'degrees'\n[MODEL]\n METHOD = '2D'\n"
            f" ROAD_TYPE = '{road_type}'\n[PARAMETERS]\n{params}")


VALID = {
    "flat": "",
    "ramp": " HEIGHT = 0.05\n START = 10\n SLOPE = 0.2\n",
    "roof": " HEIGHT = 0.05\n START = 10\n LENGTH = 0.4\n",
    "pot_hole": " DEPTH = 0.05\n START = 10\n LENGTH = 0.4\n",
    "sine": " AMPLITUDE = 0.01\n WAVE_LENGTH = 2.0\n START = 10\n LENGTH = 20\n",
    "sine_sweep": (" START = 10\n END = 60\n AMPLITUDE_AT_START = 0.01\n AMPLITUDE_AT_END = "
                   "0.01\n WAVE_LENGTH_AT_START = 4\n WAVE_LENGTH_AT_END = 1\n"
                   " SWEEP_TYPE = 1\n"),
    "cleat": (" HEIGHT = 0.02\n START = 10\n LENGTH = 0.1\n BEVEL_EDGE_LENGTH = 0.01\n"
              " EDGE_ROUNDED = 1\n DIRECTION = 30\n"),
}


def cases():
    """Yield the corpus (about 80 cases)."""
    plank = (REPO / "roads" / "plank_15mm.rdf").read_text()
    poly = (REPO / "roads" / "poly_line.rdf").read_text()
    yield "plank_ok", "plank.rdf", plank.encode(), "ok"
    yield "poly_ok", "poly.rdf", poly.encode(), "ok"
    for kind, params in VALID.items():
        yield f"{kind}_ok", f"{kind}.rdf", _small(kind, params).encode(), "ok"
    for key, value in (("HEIGHT", "abc"), ("HEIGHT", "nan"), ("HEIGHT", "1e999"),
                       ("START", "'x'"), ("LENGTH", "0"), ("LENGTH", "-50"),
                       ("BEVEL_EDGE_LENGTH", "30"), ("BEVEL_EDGE_LENGTH", "-1"),
                       ("BEVEL_EDGE_LENGTH", "16"), ("DIRECTION", "75"),
                       ("DIRECTION", "-61"), ("ROTATION_ANGLE_XY_PLANE", "90"),
                       ("ROTATION_ANGLE_XY_PLANE", "45"), ("MU", "0.8"), ("OFFSET", "inf"),
                       ("METHOD", "'3D'"), ("METHOD", "'3D_SPLINE'"), ("METHOD", "'CRG'"),
                       ("ROAD_TYPE", "'stochastic_uneven'"), ("ROAD_TYPE", "'drum'"),
                       ("ROAD_TYPE", "'flatbelt'"), ("ROAD_TYPE", "'hydraulic_test_rig'"),
                       ("ROAD_TYPE", "'plnak'"), ("ROAD_TYPE", "'poly_line'"),
                       ("LENGTH", "'long'")):
        yield f"plank_{key}_{value}", "plank.rdf", _set(plank, key, value).encode(), "error"
    yield "plank_unit_furlong", "plank.rdf", plank.replace("LENGTH = 'mm'",
                                                           "LENGTH = 'furlong'").encode(), "error"
    yield "plank_angle_grad", "plank.rdf", plank.replace("ANGLE  = 'degrees'",
                                                         "ANGLE  = 'grad'").encode(), "error"
    yield "plank_no_length_unit", "plank.rdf", plank.replace(" LENGTH = 'mm'\n", "").encode(), \
        "error"
    for key in ("HEIGHT", "START", "LENGTH", "METHOD", "ROAD_TYPE"):
        yield f"plank_no_{key}", "plank.rdf", _drop(plank, key).encode(), "error"
    yield "plank_typo_key", "plank.rdf", plank.replace("BEVEL_EDGE_LENGTH",
                                                       "BEVEL_EDGE_LENGHT").encode(), "error"
    yield "plank_duplicate_key", "plank.rdf", plank.replace(
        " HEIGHT                  = 15.0", " HEIGHT = 15.0\n HEIGHT = 16.0").encode(), "error"
    yield "plank_no_model", "plank.rdf", plank.replace("[MODEL]", "[MODELL]").encode(), "error"
    yield "plank_entry_before_section", "plank.rdf", ("HEIGHT = 3\n" + plank).encode(), "error"
    yield "plank_free_text", "plank.rdf", plank.replace("[PARAMETERS]",
                                                        "[PARAMETERS]\nthis is text").encode(), \
        "error"
    yield "plank_xz_block", "plank.rdf", (plank + "(XZ_DATA)\n{}\n0 0 0\n1 0 0\n").encode(), \
        "error"
    yield "plank_other_block", "plank.rdf", (plank + "(TV_DATA)\n0 1\n").encode(), "error"
    yield "plank_truncated", "plank.rdf", plank[:plank.index("[PARAMETERS]") + 40].encode(), \
        "error"
    rows = poly.index("(XZ_DATA)")
    head, data = poly[:rows], poly[rows:].splitlines()
    for label, row in (("nan", " 25.3 nan 0.0"), ("text", " 25.3 abc 0.0"),
                       ("two_columns", " 25.3 -0.04"), ("four_columns", " 25.3 0 0 0"),
                       ("back", " 24.0 -0.04 0.0"), ("repeat", " 25.0 -0.04 0.0")):
        out = data[:]
        out[4] = row
        yield f"poly_row_{label}", "poly.rdf", (head + "\n".join(out) + "\n").encode(), "error"
    yield "poly_no_rows", "poly.rdf", (head + "(XZ_DATA)\n{x z_left z_right}\n").encode(), \
        "error"
    yield "poly_one_row", "poly.rdf", (head + "(XZ_DATA)\n{}\n0 0 0\n").encode(), "error"
    yield "poly_no_block", "poly.rdf", head.encode(), "error"
    yield "poly_two_blocks", "poly.rdf", (poly + "(XZ_DATA)\n0 0 0\n1 0 0\n").encode(), "error"
    yield "poly_key", "poly.rdf", poly.replace("ROTATION_ANGLE_XY_PLANE = 0.0",
                                               "ROTATION_ANGLE_XY_PLANE = 0.0\n HEIGHT = 1"
                                               ).encode(), "error"
    for kind, params, key, value in (
            ("ramp", VALID["ramp"], "SLOPE", "0"), ("ramp", VALID["ramp"], "SLOPE", "-1"),
            ("ramp", VALID["ramp"], "HEIGHT", "'high'"),
            ("roof", VALID["roof"], "LENGTH", "0"),
            ("pot_hole", VALID["pot_hole"], "LENGTH", "-0.4"),
            ("sine", VALID["sine"], "WAVE_LENGTH", "0"),
            ("sine", VALID["sine"], "WAVE_LENGTH", "1e-6"),
            ("sine", VALID["sine"], "LENGTH", "0"),
            ("sine_sweep", VALID["sine_sweep"], "END", "5"),
            ("sine_sweep", VALID["sine_sweep"], "WAVE_LENGTH_AT_END", "8"),
            ("sine_sweep", VALID["sine_sweep"], "WAVE_LENGTH_AT_END", "1e-7"),
            ("sine_sweep", VALID["sine_sweep"], "SWEEP_TYPE", "2"),
            ("cleat", VALID["cleat"], "EDGE_ROUNDED", "0.5"),
            ("cleat", VALID["cleat"], "BEVEL_EDGE_LENGTH", "0.06"),
            ("roof", VALID["roof"] + " DIRECTION = 10\n", "DIRECTION", "10")):
        yield f"{kind}_{key}_{value}", f"{kind}.rdf", _small(kind, _set(params, key, value)
                                                             ).encode(), "error"
    yield "sine_missing_amplitude", "sine.rdf", _small("sine", _drop(
        VALID["sine"], "AMPLITUDE")).encode(), "error"
    b = plank.encode()
    rng = random.Random(7)
    yield "empty", "empty.rdf", b"", "error:file"
    yield "garbage", "garbage.rdf", bytes(rng.randrange(256) for _ in range(2000)), "error:file"
    yield "utf16", "utf16.rdf", plank.encode("utf-16"), "error:file"
    yield "latin1_comment", "latin1.rdf", b"$ \xe9\xe8\xff\n" + b, "ok"
    yield "crlf", "crlf.rdf", plank.replace("\n", "\r\n").encode(), "ok"
    yield "directory_suffix", "plank.RDF", b, "ok"
