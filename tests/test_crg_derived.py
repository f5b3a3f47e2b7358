"""OpenCRG header values that OpenCRG derives when a file leaves them out.

``REFERENCE_LINE_INCREMENT`` ((END_U - START_U) / (records - 1), or the increment of a
``U:reference line u,m,<start>,<increment>`` channel), ``REFERENCE_LINE_END_U`` (from the
number of records), ``LONG_SECTION_V_INCREMENT`` ((LEFT - RIGHT) / (sections - 1)) and
``LONG_SECTION_V_RIGHT`` / ``LEFT`` (centred on the reference line) were required by
flexpipe's reader.  Each variant is written here by hand (header text and a text or
big-endian binary data block) and compared with pyopencrg (an independent reader and
evaluator of the same files) and with the axes computed by hand.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.roads import read_crg

crg = pytest.importorskip("pyopencrg")

N_U, N_V = 41, 5


def _grid():
    """Heights (N_U, N_V): a 3 cm bump across the road and a lateral ramp, in metres."""
    i = np.arange(N_U)[:, None]
    j = np.arange(N_V)[None, :]
    return 0.03 * np.exp(-((i - 20.0) / 3.0) ** 2) + 0.004 * j + 0.001 * np.sin(0.7 * i)


def _write(path, keys, *, fmt="LDFI", u_line=None, z=None):
    """An OpenCRG file with ``$ROAD_CRG`` ``keys`` ({KEY: value}), numbered long sections
    and the data ``z`` (default :func:`_grid`)."""
    z = _grid() if z is None else z
    head = ["$CT", "hand-written test road", "$", "$ROAD_CRG",
            *[f"{k} = {v!r}" for k, v in keys.items()], "$", "$KD_DEFINITION", f"#:{fmt}",
            *([u_line] if u_line else []),
            *[f"D:long section {j + 1},m" for j in range(z.shape[1])], "$", "$" * 72]
    body = ("\n".join(head) + "\n").encode()
    if fmt == "KDBI":
        flat = z.ravel()
        flat = np.concatenate([flat, np.full(-flat.size % 10, np.nan)])   # 80-byte records
        body += flat.astype(">f8").tobytes()
    else:                                   # LDFI: 4 fields of 20 characters per line
        out = []
        for row in z:
            fields = [f"{x:20.12e}" for x in row]
            out += ["".join(fields[k:k + 4]) for k in range(0, len(fields), 4)]
        body += ("\n".join(out) + "\n").encode()
    path.write_bytes(body)
    return path


def _same_as_pyopencrg(road, path, n=4000):
    """Heights at random global points over the road (and 1 m beyond) equal pyopencrg's."""
    ref = crg.read(path, apply_mods=True)
    rng = np.random.default_rng(5)
    u = rng.uniform(ref.u_start - 1.0, ref.u_end + 1.0, n)
    v = rng.uniform(ref.v[0] - 1.0, ref.v[-1] + 1.0, n)
    x, y = ref.uv_to_xy(u, v)
    np.testing.assert_allclose(road.height_xy(x, y), ref.xy_to_z(x, y), atol=1e-9)
    return ref


FULL = {"REFERENCE_LINE_START_U": 2.0, "REFERENCE_LINE_END_U": 12.0,
        "REFERENCE_LINE_INCREMENT": 0.25, "LONG_SECTION_V_RIGHT": -1.0,
        "LONG_SECTION_V_LEFT": 1.0, "LONG_SECTION_V_INCREMENT": 0.5}


def _without(*keys, **more):
    out = {k: v for k, v in FULL.items() if k not in keys}
    out.update(more)
    return out


# (keys, U: channel line, u0, du, v right, v increment) -- the axes computed by hand
VARIANTS = {
    "increment_from_end_u": (_without("REFERENCE_LINE_INCREMENT"), None, 2.0, 0.25, -1.0, 0.5),
    "end_u_from_records": (_without("REFERENCE_LINE_END_U"), None, 2.0, 0.25, -1.0, 0.5),
    "u_axis_from_u_channel": (_without("REFERENCE_LINE_START_U", "REFERENCE_LINE_END_U",
                                       "REFERENCE_LINE_INCREMENT"),
                              "U:reference line u,m,3.0,0.5", 3.0, 0.5, -1.0, 0.5),
    "end_u_and_u_channel": (_without("REFERENCE_LINE_INCREMENT"),
                            "U:reference line u,m,2.0,0.25", 2.0, 0.25, -1.0, 0.5),
    "v_increment_from_right_left": (_without("LONG_SECTION_V_INCREMENT",
                                             LONG_SECTION_V_RIGHT=-1.2, LONG_SECTION_V_LEFT=2.0),
                                    None, 2.0, 0.25, -1.2, 0.8),
    "v_centred": (_without("LONG_SECTION_V_RIGHT", "LONG_SECTION_V_LEFT",
                           LONG_SECTION_V_INCREMENT=0.75), None, 2.0, 0.25, -1.5, 0.75),
    "v_right_only": (_without("LONG_SECTION_V_LEFT", LONG_SECTION_V_RIGHT=-0.5), None, 2.0,
                     0.25, -0.5, 0.5),
}


@pytest.mark.parametrize("fmt", ["LDFI", "KDBI"])
@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_derived_axes_equal_pyopencrg(tmp_path, variant, fmt):
    keys, u_line, u0, du, v0, dv = VARIANTS[variant]
    path = _write(tmp_path / f"{variant}.crg", keys, fmt=fmt, u_line=u_line)
    with warnings.catch_warnings():
        warnings.simplefilter("error")          # every value follows from the file
        road = read_crg(path)
    np.testing.assert_allclose(road.x, u0 + du * np.arange(N_U), rtol=0, atol=1e-12)
    np.testing.assert_allclose(road.y, v0 + dv * np.arange(N_V), rtol=0, atol=1e-12)
    np.testing.assert_allclose(road.height(road.x[20], road.y[2]) - road.height(road.x[0],
                               road.y[2]), _grid()[20, 2] - _grid()[0, 2], atol=1e-12)
    ref = _same_as_pyopencrg(road, path)
    assert ref.u_start == pytest.approx(u0) and ref.u_end == pytest.approx(u0 + du * (N_U - 1))


def test_v_left_with_increment_gives_the_right_border(tmp_path):
    """LEFT and INCREMENT without RIGHT: the sections end at LEFT (right = LEFT - 4 INC);
    the OpenCRG C loader starts them at 0 when RIGHT is missing, which this file's LEFT
    = 4 INC agrees with."""
    keys = _without("LONG_SECTION_V_RIGHT", LONG_SECTION_V_LEFT=2.0)
    road = read_crg(_write(tmp_path / "left.crg", keys))
    np.testing.assert_allclose(road.y, [0.0, 0.5, 1.0, 1.5, 2.0], atol=1e-12)


@pytest.mark.parametrize("drop, what", [
    (("REFERENCE_LINE_INCREMENT", "REFERENCE_LINE_END_U"), "REFERENCE_LINE_INCREMENT"),
    (("LONG_SECTION_V_INCREMENT", "LONG_SECTION_V_LEFT"), "LONG_SECTION_V_INCREMENT")])
def test_opencrg_default_increment_with_a_warning(tmp_path, drop, what):
    """Nothing to derive an increment from: OpenCRG's fallback 0.01 m, said in a warning."""
    path = _write(tmp_path / "bare.crg", _without(*drop), z=_grid() * 0.01)
    with pytest.warns(UserWarning, match=f"no {what}.*0.01 m"):
        road = read_crg(path)
    if "REFERENCE_LINE_INCREMENT" in drop:
        np.testing.assert_allclose(np.diff(road.x), 0.01, atol=1e-12)
    else:
        np.testing.assert_allclose(road.y, -1.0 + 0.01 * np.arange(N_V), atol=1e-12)
    _same_as_pyopencrg(road, path)


@pytest.mark.parametrize("keys, match, key", [
    (_without("LONG_SECTION_V_INCREMENT", LONG_SECTION_V_LEFT=-2.0), "must lie left",
     "LONG_SECTION_V_LEFT"),
    (_without("REFERENCE_LINE_INCREMENT", REFERENCE_LINE_END_U=1.0), "END_U > START_U",
     "REFERENCE_LINE_END_U"),
    (_without(LONG_SECTION_V_LEFT=2.2), "end at 1 m, but LONG_SECTION_V_LEFT = 2.2",
     "LONG_SECTION_V_LEFT")])
def test_contradicting_values_are_errors(tmp_path, keys, match, key):
    path = _write(tmp_path / "bad.crg", keys)
    with pytest.raises(InputError, match=match) as exc:
        read_crg(path)
    assert "bad.crg" in str(exc.value) and f"key '{key}'" in str(exc.value)
    assert "line " in str(exc.value)


def test_truncated_text_block_without_end_u_is_an_error(tmp_path):
    path = _write(tmp_path / "cut.crg", _without("REFERENCE_LINE_END_U"))
    text = path.read_text().rstrip("\n")
    path.write_text(text[: text.rindex("\n")] + "\n")      # the last row loses its 5th value
    with pytest.raises(InputError, match="ends inside a row") as exc:
        read_crg(path)
    assert "cut.crg" in str(exc.value) and "line " in str(exc.value)
