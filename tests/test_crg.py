"""OpenCRG reader/writer against the real reference files and the project's sample file.

Each test parses the file's header and data block itself (NumPy big-endian reads for the
binary KRBI files, fixed-width text fields for LRFI), independently of flexpipe.roads.crg,
and compares heights.  The reference files live in ../shared/reference/roads and are not
part of the repository; the tests skip cleanly without them.
"""

from __future__ import annotations

import pathlib
import re

import numpy as np
import pytest
from scipy.interpolate import RegularGridInterpolator

from flexpipe.errors import InputError
from flexpipe.roads import Road, load_road, read_crg, write_crg

REPO = pathlib.Path(__file__).resolve().parents[1]
REF = pathlib.Path(__file__).resolve().parents[2] / "shared" / "reference" / "roads"
INCH = 0.0254


def _reference(name):
    path = REF / name
    if not path.is_file():
        pytest.skip(f"reference road {path} not available")
    return path


def _direct_read(path):
    """(u, v, z) read straight from the file: header keys by regex, data block by NumPy."""
    raw = path.read_bytes()
    sep = re.search(rb"\n\$\$\$\$+[^\n]*\n", raw)
    head = raw[:sep.start()].decode("latin-1")

    def key(name):
        return float(re.search(rf"^{name}\s*=\s*(\S+)", head, re.I | re.M).group(1))

    u = np.arange(key("reference_line_start_u"),
                  key("reference_line_end_u") + 0.5 * key("reference_line_increment"),
                  key("reference_line_increment"))
    n_sec = len(re.findall(r"^D:long section", head, re.M))
    v = key("long_section_v_right") + key("long_section_v_increment") * np.arange(n_sec)
    fmt = re.search(r"^#:(\w{4})", head, re.M).group(1)
    data = raw[sep.end():]
    if fmt == "KRBI":
        z = np.frombuffer(data, ">f4", count=u.size * n_sec).reshape(u.size, n_sec)
    elif fmt == "LRFI":
        rows = [line for line in data.decode().splitlines() if line.strip()]
        z = np.array([[float(line[i:i + 10]) for i in range(0, 10 * n_sec, 10)]
                      for line in rows])
    else:
        raise AssertionError(fmt)
    return u, v, z.astype(float), head


@pytest.mark.parametrize("name", ["Horstwalde.crg", "halfround_4in.crg",
                                  "detrended_rms_course_1in.crg"])
def test_reference_crg_heights_match_data_block(name):
    path = _reference(name)
    u, v, z, _ = _direct_read(path)
    road = read_crg(path, track_width=1.5)
    assert road.x.size == u.size and road.y.size == v.size
    np.testing.assert_allclose(road.x, u, atol=1e-9)
    np.testing.assert_allclose(road.y, v, atol=1e-12)
    np.testing.assert_array_equal(road.z, z)
    # at sample points
    rng = np.random.default_rng(0)
    i = rng.integers(0, u.size, 200)
    j = rng.integers(0, v.size, 200)
    np.testing.assert_allclose(road.height(u[i], v[j]), z[i, j], atol=1e-12)
    # between samples: bilinear, checked against scipy's grid interpolator
    interp = RegularGridInterpolator((u, v), z)
    s = rng.uniform(u[0], u[-1], 500)
    lat = rng.uniform(v[0], v[-1], 500)
    np.testing.assert_allclose(road.height(s, lat), interp(np.column_stack([s, lat])),
                               atol=1e-9)
    np.testing.assert_allclose(road.left_height(s), interp(np.column_stack(
        [s, np.full_like(s, 0.75)])), atol=1e-9)
    np.testing.assert_allclose(road.right_height(s), interp(np.column_stack(
        [s, np.full_like(s, -0.75)])), atol=1e-9)


def test_horstwalde_is_the_described_twist_track():
    road = read_crg(_reference("Horstwalde.crg"))
    assert road.length == pytest.approx(250.2)          # "250 m x 4.4 m"
    assert road.y[-1] - road.y[0] == pytest.approx(4.4)
    assert road.heading is None                          # straight reference line
    # a twist track: the left and right borders differ in height somewhere along it
    assert np.max(np.abs(road.z[:, 0] - road.z[:, -1])) > 0.01


def test_halfround_obstacle_is_4_inches_high():
    road = read_crg(_reference("halfround_4in.crg"))
    assert road.z.max() == pytest.approx(4 * INCH, abs=0.5e-3)
    assert road.left_height(road.x[np.argmax(road.left)]) == pytest.approx(4 * INCH, abs=0.5e-3)


def test_detrended_course_rms_matches_file_comment():
    path = _reference("detrended_rms_course_1in.crg")
    _, _, _, head = _direct_read(path)
    rms_in = float(re.search(r"Detrended RMS = ([\d.]+) in", head).group(1))
    start = float(re.search(r"starts at = ([\d.]+) m", head).group(1))
    length = float(re.search(r"surface = ([\d.]+) m", head).group(1))
    road = read_crg(path)
    m = (road.x >= start) & (road.x <= start + length)
    assert np.sqrt(np.mean(road.left[m] ** 2)) == pytest.approx(rms_in * INCH, rel=0.02)


def test_sample_crg_text_file():
    path = REPO / "roads" / "sample_bump.crg"
    u, v, z, _ = _direct_read(path)
    road = load_road(path)
    np.testing.assert_array_equal(road.z, z)
    np.testing.assert_allclose(road.y, v)
    # full-width bump 40 mm at u = 5.5 m; left-half bump 30 mm at u = 12.5 m
    assert road.height(5.5, -0.9) == pytest.approx(0.04, abs=1e-7)
    assert road.height(12.5, 1.0) == pytest.approx(0.03, abs=1e-7)
    assert road.height(12.5, 0.25) == pytest.approx(0.015, abs=1e-7)   # lateral interpolation
    assert road.height(12.5, -0.5) == 0.0


@pytest.mark.parametrize("fmt", ["KRBI", "KDBI", "LRFI", "LDFI"])
def test_write_read_roundtrip(tmp_path, fmt):
    rng = np.random.default_rng(4)
    x = np.arange(0.0, 10.01, 0.05)
    y = np.linspace(-1.2, 1.2, 7)
    z = rng.normal(0.0, 0.01, (x.size, y.size))
    road = Road.from_grid(x, y, z, name="rnd")
    out = tmp_path / f"r_{fmt}.crg"
    write_crg(road, out, fmt=fmt)
    back = read_crg(out)
    tol = 1e-7 if fmt[1] == "R" else 1e-12
    np.testing.assert_allclose(back.z, z, atol=tol)
    np.testing.assert_allclose(back.y, y, atol=1e-12)
    if fmt == "KRBI":           # independent read of the binary block
        raw = out.read_bytes()
        start = raw.index(b"$" * 72 + b"\n") + 73
        direct = np.frombuffer(raw[start:], ">f4", count=z.size).reshape(z.shape)
        np.testing.assert_array_equal(back.z, direct.astype(float))
        assert (len(raw) - start) % 80 == 0


def _text_crg(tmp_path, rows, fmt="LRFI", extra=""):
    head = ["$CT", "test", "$", "$ROAD_CRG", "REFERENCE_LINE_START_U = 0.0",
            f"REFERENCE_LINE_END_U = {0.5 * (len(rows) - 1)}", "REFERENCE_LINE_INCREMENT = 0.5",
            "LONG_SECTION_V_RIGHT = -1.0", "LONG_SECTION_V_LEFT = 1.0",
            "LONG_SECTION_V_INCREMENT = 1.0", extra, "$", "$KD_DEFINITION", f"#:{fmt}",
            "D:long section 1,m", "D:long section 2,m", "D:long section 3,m", "$", "$$$$$$$$"]
    f = tmp_path / "t.crg"
    f.write_text("\n".join(h for h in head if h) + "\n" + "\n".join(rows) + "\n")
    return f


def test_border_nan_is_filled_and_interior_nan_rejected(tmp_path):
    ok = _text_crg(tmp_path, [" 0.0100000 0.0200000 0.0300000",
                              " *missing* 0.0200000 0.0300000",
                              " 0.0100000 0.0200000 0.0300000"])
    road = read_crg(ok, modifiers=False)      # the grid as written (no default placement)
    assert road.z[1, 0] == pytest.approx(0.02)
    bad = _text_crg(tmp_path, [" 0.0100000 0.0200000 0.0300000",
                               " 0.0100000 *missing* 0.0300000",
                               " 0.0100000 0.0200000 0.0300000"])
    with pytest.raises(InputError, match="NaN between") as info:
        read_crg(bad)
    assert "t.crg" in str(info.value) and "line 20" in str(info.value)


def test_crg_slope_and_banking_from_header(tmp_path):
    rows = [" 0.0000000 0.0000000 0.0000000"] * 5
    f = _text_crg(tmp_path, rows, extra="REFERENCE_LINE_START_S = 0.02\n"
                                        "REFERENCE_LINE_START_B = 0.05")
    road = read_crg(f)
    # z = slope * u + banking * v (constant slope 2 %, banking 5 %)
    assert road.height(2.0, 1.0) == pytest.approx(0.02 * 2.0 + 0.05 * 1.0)
    assert road.height(1.0, -1.0) == pytest.approx(0.02 - 0.05)


def test_crg_bad_files(tmp_path):
    f = _text_crg(tmp_path, [" 0.0100000 0.0200000 0.0300000"] * 2)
    f.write_bytes(f.read_bytes().replace(b"LRFI", b"XYZI"))
    with pytest.raises(InputError, match="unknown data format"):
        read_crg(f)
    f = _text_crg(tmp_path, [" 0.0100000 0.0200000 0.0300000"] * 2)
    f.write_bytes(f.read_bytes().replace(b"$$$$$$$$\n", b""))
    with pytest.raises(InputError, match="never closed"):
        read_crg(f)
    f = _text_crg(tmp_path, [" 0.0100000 0.0200000 0.0300000"] * 3)
    f.write_text(f.read_text().replace("END_U = 1.0", "END_U = 2.0"))
    with pytest.raises(InputError, match="expected 5"):
        read_crg(f)


def test_curved_reference_line_from_heading_channel(tmp_path):
    head = ["$CT", "arc", "$", "$ROAD_CRG", "REFERENCE_LINE_START_U = 0.0",
            "REFERENCE_LINE_END_U = 4.0", "REFERENCE_LINE_INCREMENT = 1.0",
            "LONG_SECTION_V_RIGHT = -1.0", "LONG_SECTION_V_LEFT = 1.0",
            "LONG_SECTION_V_INCREMENT = 2.0", "$", "$KD_DEFINITION", "#:LRFI",
            "D:reference line phi,rad", "D:long section 1,m", "D:long section 2,m", "$",
            "$$$$$$$$"]
    phi = 0.1 * np.arange(5)                  # heading grows 0.1 rad per metre: an arc
    rows = [f"{p:10.7f} 0.0100000 0.0300000" for p in phi]
    f = tmp_path / "arc.crg"
    f.write_text("\n".join(head + rows) + "\n")
    road = read_crg(f, modifiers=False)       # as written (no default placement)
    assert road.height(2.0, 0.0) == pytest.approx(0.02)
    X, Y = road.reference_line()
    # segment i runs from point i-1 to i along heading phi[i] (OpenCRG convention)
    assert X[-1] == pytest.approx(sum(np.cos(phi[1:])))
    assert Y[-1] == pytest.approx(sum(np.sin(phi[1:])))


def test_issue_cases_infinite_end_and_text_data_declared_binary(tmp_path):
    """Issue 14: END_U = inf raised OverflowError; KRBI over text data read ~1e-10 m heights."""
    rows = [" 0.0100000 0.0200000 0.0300000"] * 3
    f = _text_crg(tmp_path, rows)
    f.write_text(f.read_text().replace("END_U = 1.0", "END_U = inf"))
    with pytest.raises(InputError, match="REFERENCE_LINE_END_U must be a finite number") as e:
        read_crg(f)
    assert "line 6" in str(e.value)
    f = _text_crg(tmp_path, rows, fmt="KRBI")
    with pytest.raises(InputError, match="binary format KRBI but the data block is text"):
        read_crg(f)


def test_misspelt_header_key_is_an_error(tmp_path):
    f = _text_crg(tmp_path, [" 0.0000000 0.0000000 0.0000000"] * 3,
                  extra="REFERENCE_LINE_STRAT_B = 0.05")
    with pytest.raises(InputError, match="did you mean REFERENCE_LINE_START_B"):
        read_crg(f)


def test_road_shorter_than_one_increment_is_named(tmp_path):
    """END_U - START_U below one increment gave one cross section and a raw IndexError (a
    damaged header found by probing the reader with extreme values)."""
    f = _text_crg(tmp_path, [" 0.0100000 0.0200000 0.0300000"] * 3)
    f.write_text(f.read_text().replace("END_U = 1.0", "END_U = 1e-9"))
    with pytest.raises(InputError, match=r"key 'REFERENCE_LINE_END_U'.*less than one "
                                         r"increment \(0\.5 m\).*at least 2 cross sections"):
        read_crg(f)
