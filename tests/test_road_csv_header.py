"""Road and path CSV headers say which column is which and in what unit.

Finding: the header line was dropped and the columns used by position, always in metres:
``x [mm],z_left [mm],z_right [mm]`` became a 30 km road with a 20 m hill, ``distance_m,
right_m,left_m`` swapped the tracks and a path ``y_m,x_m`` swapped x and y; a UTF-8 byte
order mark made a headerless file's first row look like a header, so it was lost.  The
expected profiles are written out by hand here.
"""

from __future__ import annotations

import pathlib

import numpy as np
import pytest

from flexpipe.driver import read_path
from flexpipe.errors import InputError
from flexpipe.roads import load_road, read_csv

REPO = pathlib.Path(__file__).resolve().parents[1]


def _write(tmp_path, name, text, *, bom=False):
    path = tmp_path / name
    path.write_bytes((b"\xef\xbb\xbf" if bom else b"") + text.encode())
    return path


def test_header_in_millimetres_is_converted(tmp_path):
    path = _write(tmp_path, "mm.csv", "x [mm],z_left [mm],z_right [mm]\n"
                                      "0,0,0\n10000,20,10\n30000,0,0\n")
    road = read_csv(path)
    np.testing.assert_array_equal(road.x, [0.0, 10.0, 30.0])       # a 30 m road ...
    np.testing.assert_allclose(road.left, [0.0, 0.020, 0.0], rtol=1e-15)   # ... a 20 mm bump
    np.testing.assert_allclose(road.right, [0.0, 0.010, 0.0], rtol=1e-15)
    assert road.length == 30.0


@pytest.mark.parametrize("header", ["distance_m,right_m,left_m", "s (m),right (m),left (m)",
                                    "Distance [m], Right [m], Left [m]",
                                    "distance_m right_m left_m"])
def test_columns_are_read_by_their_names(tmp_path, header):
    sep = "," if "," in header else " "
    rows = ["0,0.000,0.010", "10,0.020,0.030", "20,0.000,0.010"]
    path = _write(tmp_path, "swap.csv", header + "\n" + "\n".join(
        r.replace(",", sep) for r in rows) + "\n")
    road = read_csv(path)
    np.testing.assert_array_equal(road.x, [0.0, 10.0, 20.0])
    np.testing.assert_array_equal(road.left, [0.010, 0.030, 0.010])    # the third column
    np.testing.assert_array_equal(road.right, [0.000, 0.020, 0.000])   # the second column


def test_one_height_column_by_name_and_unit(tmp_path):
    path = _write(tmp_path, "h.csv", "height_mm,distance_cm\n5,0\n-5,150\n0,300\n")
    road = read_csv(path)
    np.testing.assert_allclose(road.x, [0.0, 1.5, 3.0], rtol=1e-15)
    np.testing.assert_allclose(road.left, [0.005, -0.005, 0.0], rtol=1e-15)
    np.testing.assert_array_equal(road.left, road.right)


def test_headerless_file_is_read_by_position_in_metres(tmp_path):
    road = read_csv(_write(tmp_path, "plain.csv", "# c\n0,0,0.01\n10,0.02,0.03\n"))
    np.testing.assert_array_equal(road.left, [0.0, 0.02])
    np.testing.assert_array_equal(road.right, [0.01, 0.03])


@pytest.mark.parametrize("text, line, words", [
    ("distance_ft,left_m,right_m\n0,0,0\n1,0,0\n", 1,
     ["'distance_ft'", "'ft'", "m, cm, mm, km"]),
    ("distance [in],left,right\n0,0,0\n1,0,0\n", 1, ["'distance [in]'", "'in'"]),
    ("distance_m,left_m,rigth_m\n0,0,0\n1,0,0\n", 1,
     ["column 3 'rigth_m'", "distance: distance, x, s, u", "right: right, z_right"]),
    ("time_s,z_m\n0,0\n1,0\n", 1, ["'time_s'", "valid names"]),
    ("distance_m,left_m\n0,0\n1,0\n", 1, ["no right track column"]),
    ("left_m,right_m\n0,0\n1,0\n", 1, ["no distance column"]),
    ("distance_m,left_m,height_m\n0,0,0\n1,0,0\n", 1, ["a height column and a track"]),
    ("distance_m,left_m,left_mm\n0,0,0\n1,0,0\n", 1, ["left again"]),
    ("# road\ndistance_m,left_m,right_m\n0,0\n1,0\n", 3, ["2 columns", "header on line 2"]),
    ("x_m,y_m\n0,0\n1,0\n", 1, ["driver path", "--path"]),
])
def test_header_that_cannot_be_placed_is_an_error(tmp_path, text, line, words):
    path = _write(tmp_path, "bad_head.csv", text)
    with pytest.raises(InputError) as exc:
        load_road(path)
    msg = str(exc.value)
    assert "bad_head.csv" in msg and f"line {line}" in msg, msg
    for w in words:
        assert w in msg, msg


def test_path_columns_by_name_and_unit(tmp_path):
    path = read_path(_write(tmp_path, "yx.csv", "y_m,x_m\n0,0\n0,10\n1,20\n"))
    np.testing.assert_array_equal(path.x, [0.0, 10.0, 20.0])
    np.testing.assert_array_equal(path.y, [0.0, 0.0, 1.0])
    mm = read_path(_write(tmp_path, "mm.csv", "x [mm]  y [mm]\n0 0\n10000 0\n20000 500\n"))
    np.testing.assert_allclose(mm.x, [0.0, 10.0, 20.0], rtol=1e-15)
    np.testing.assert_allclose(mm.y, [0.0, 0.0, 0.5], rtol=1e-15)


@pytest.mark.parametrize("text, words", [
    ("distance_m,left_m,right_m\n0,0,0\n1,0,0\n", ["'distance_m'", "x: x; y: y"]),
    ("x_m,y_ft\n0,0\n1,0\n", ["'y_ft'", "'ft'"]),
    ("x_m,x_mm\n0,0\n1,0\n", ["x again"]),
    ("x_m\n0,0\n1,0\n", ["no y column"]),
])
def test_path_header_that_cannot_be_placed_is_an_error(tmp_path, text, words):
    path = _write(tmp_path, "bad_path.csv", text)
    with pytest.raises(InputError) as exc:
        read_path(path)
    msg = str(exc.value)
    assert "bad_path.csv" in msg and "line 1" in msg, msg
    for w in words:
        assert w in msg, msg


@pytest.mark.parametrize("header", ["", "distance_m,left_m,right_m\n"])
def test_utf8_byte_order_mark_keeps_the_first_row(tmp_path, header):
    path = _write(tmp_path, "bom.csv", header + "0,0.01,0.01\n1,0.02,0.02\n2,0,0\n", bom=True)
    road = read_csv(path)
    np.testing.assert_array_equal(road.x, [0.0, 1.0, 2.0])
    np.testing.assert_array_equal(road.left, [0.01, 0.02, 0.0])
    p = read_path(_write(tmp_path, "bom_path.csv", "0,0\n1,0\n2,1\n", bom=True))
    np.testing.assert_array_equal(p.x, [0.0, 1.0, 2.0])


def test_a_mixed_first_line_is_bad_data_not_a_header(tmp_path):
    """'0,a,0' holds numbers: a bad data line (named), not a header to skip."""
    path = _write(tmp_path, "mixed.csv", "0,a,0\n1,0,0\n2,0,0\n")
    with pytest.raises(InputError, match="not a number") as exc:
        read_csv(path)
    assert "mixed.csv, line 1" in str(exc.value)


def test_shipped_files_read_as_before():
    """roads/bump.csv (distance_m,left_m,right_m) and paths/sample_xy.csv (x_m,y_m): the
    header names the columns in the order they always had."""
    raw = np.loadtxt(REPO / "roads" / "bump.csv", delimiter=",", comments="#", skiprows=3)
    road = read_csv(REPO / "roads" / "bump.csv")
    np.testing.assert_array_equal(np.column_stack([road.x, road.left, road.right]), raw)
    xy = np.loadtxt(REPO / "paths" / "sample_xy.csv", delimiter=",", comments="#",
                    skiprows=2)
    path = read_path(REPO / "paths" / "sample_xy.csv")
    np.testing.assert_array_equal(np.column_stack([path.x, path.y]), xy)
