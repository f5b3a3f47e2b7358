"""OpenCRG modifiers (``$ROAD_CRG_MODS``) against pyopencrg's ``apply_mods`` (an
independent implementation of the same definitions), and their bad values.

The roads are hand-written files (``tests/test_crg_curved.py``); flexpipe's heights and
``(x, y) <-> (u, v)`` map are compared with pyopencrg's at random points over the road
and a margin beyond it.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.roads import read_crg, write_crg
from tests.test_crg_curved import _random_points, assert_same_as_pyopencrg, curved_file

crg = pytest.importorskip("pyopencrg")


def _road(tmp_path, mods, *, nan_border=False, name="m.crg"):
    """A curved, sloped, banked road (start at (100, -40, 2.5)) with modifiers ``mods``."""
    rng = np.random.default_rng(11)
    u0, du = 2.0, 0.2
    u = u0 + du * np.arange(301)
    v = np.linspace(-1.5, 2.5, 9)                # not centred: v fractions matter
    phi = 0.5 * np.sin((u - u0) / 9.0) + 0.4
    slope = 0.03 * np.cos((u - u0) / 11.0)
    bank = 0.02 * np.sin((u - u0) / 13.0)
    z = rng.normal(0.0, 0.003, (u.size, v.size))
    z[np.abs(u - 30.0) < 0.3] += 0.04
    if nan_border:
        z[10:20, 0] = np.nan
        z[40:45, -2:] = np.nan
    return curved_file(tmp_path / name, u0, du, v, phi, slope, bank, z, mods=mods)


def _same_as_pyopencrg(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")        # both warn of mixed placements alike
        ref = crg.read(path, apply_mods=True)
        road = read_crg(path)
    assert_same_as_pyopencrg(road, ref, seed=2, margin=0.5)
    return road, ref


MODS = {
    "scale z, slope, banking": ["SCALE_Z_GRID = 2.5", "SCALE_SLOPE = 0.5",
                                "SCALE_BANKING = -1.0"],
    "scale length": ["SCALE_LENGTH = 1.7"],
    "scale width": ["SCALE_WIDTH = 0.6"],
    "scale curvature": ["SCALE_CURVATURE = 0.4"],
    "all scalings": ["SCALE_Z_GRID = 0.5", "SCALE_SLOPE = 2.0", "SCALE_BANKING = 1.5",
                     "SCALE_LENGTH = 0.8", "SCALE_WIDTH = 1.3", "SCALE_CURVATURE = 1.8"],
    # (REFPOINT_U inside an interval: at a grid point the heading's interval is a tie that
    # the two codes' rounding may break differently)
    "reference point": ["REFPOINT_U = 20.05", "REFPOINT_V = 0.5", "REFPOINT_X = -7.0",
                        "REFPOINT_Y = 3.0", "REFPOINT_Z = 1.2", "REFPOINT_PHI = 2.0"],
    "reference point as fractions": ["REFPOINT_U_FRACTION = 0.4", "REFPOINT_U_OFFSET = 1.5",
                                     "REFPOINT_V_FRACTION = 0.25", "REFPOINT_V_OFFSET = -0.2",
                                     "REFPOINT_PHI = -0.7", "SCALE_LENGTH = 1.2"],
    "by offset": ["REFLINE_OFFSET_PHI = 0.9", "REFLINE_OFFSET_X = 12.0",
                  "REFLINE_OFFSET_Y = -5.0", "REFLINE_OFFSET_Z = 0.3"],
    "by offset about a centre": ["REFLINE_ROTCENTER_X = 50.0", "REFLINE_ROTCENTER_Y = 20.0",
                                 "REFLINE_OFFSET_PHI = -1.1", "SCALE_WIDTH = 1.1"],
    "lower case keys, Fortran exponent": ["refline_offset_x = 1.5D+01", "scale_z_grid = 2"],
}


@pytest.mark.parametrize("which", list(MODS))
def test_modifiers_equal_pyopencrg(tmp_path, which):
    _same_as_pyopencrg(_road(tmp_path, MODS[which]))


@pytest.mark.parametrize("lines", [["GRID_NAN_MODE = 2", "GRID_NAN_OFFSET = 0.05"],
                                   ["GRID_NAN_MODE = 1", "GRID_NAN_OFFSET = -0.02"],
                                   ["GRID_NAN_MODE = 1"]])
def test_nan_filling_equals_pyopencrg(tmp_path, lines):
    _same_as_pyopencrg(_road(tmp_path, lines, nan_border=True))


def test_without_a_modifier_section_the_road_starts_at_the_origin(tmp_path):
    """OpenCRG's default modifiers: the start of the reference line at x = y = 0 heading
    along x, the surface there at z = 0 (the file says (100, -40), 2.5 m up, 0.4 rad)."""
    road, _ = _same_as_pyopencrg(_road(tmp_path, None))
    X, Y = road.reference_line()
    assert (X[0], Y[0]) == pytest.approx((0.0, 0.0), abs=1e-12)
    assert np.arctan2(Y[1] - Y[0], X[1] - X[0]) == pytest.approx(0.0, abs=1e-12)
    assert road.height(2.0, 0.0) == pytest.approx(0.0, abs=1e-12)
    as_written = read_crg(tmp_path / "m.crg", modifiers=False)
    X0, Y0 = as_written.reference_line()
    assert (X0[0], Y0[0]) == pytest.approx((100.0, -40.0))
    # the same surface, moved: heights differ by one constant along the road
    u = np.linspace(2.0, 60.0, 50)
    d = as_written.height(u, 0.3) - road.height(u, 0.3)
    assert np.ptp(d) < 1e-9 and d[0] > 2.0


def test_an_empty_section_and_the_writer_keep_the_placement(tmp_path):
    road, _ = _same_as_pyopencrg(_road(tmp_path, []))
    X, Y = road.reference_line()
    assert (X[0], Y[0]) == pytest.approx((100.0, -40.0))
    out = tmp_path / "back.crg"
    write_crg(road, out, fmt="KDBI")           # writes an empty $ROAD_CRG_MODS section
    back = read_crg(out)
    x, y = _random_points(crg.read(out, apply_mods=True), 2000, np.random.default_rng(4))
    np.testing.assert_allclose(back.height_xy(x, y), road.height_xy(x, y), atol=1e-9)


@pytest.mark.parametrize("lines, match", [
    (["SCALE_Z = 2.0"], r"unknown \$ROAD_CRG_MODS key SCALE_Z \(did you mean SCALE_Z_GRID"),
    (["SCALE_LENGTH = 0"], "SCALE_LENGTH = 0; a length factor must be > 0"),
    (["SCALE_WIDTH = -1"], "SCALE_WIDTH = -1; a length factor must be > 0"),
    (["GRID_NAN_MODE = 3"], "GRID_NAN_MODE = 3; valid: 0 .*1 .*2"),
    (["GRID_NAN_MODE = 0", "GRID_NAN_OFFSET = 0.1"], "GRID_NAN_OFFSET needs GRID_NAN_MODE 1 or 2"),
    (["REFPOINT_U = 3", "REFPOINT_U_FRACTION = 0.5"], "REFPOINT_U and REFPOINT_U_FRACTION"),
    (["REFPOINT_X = abc"], "value of REFPOINT_X is not a number"),
    (["REFPOINT_X = nan"], "REFPOINT_X must be a finite number"),
    (["SCALE_SLOPE = 2", "SCALE_SLOPE = 3"], "SCALE_SLOPE is given twice"),
    (["SCALE_SLOPE 2"], "expected 'KEY = value' in \\$ROAD_CRG_MODS"),
])
def test_bad_modifiers_name_file_line_and_key(tmp_path, lines, match):
    path = _road(tmp_path, lines)
    with pytest.raises(InputError, match=match) as info:
        read_crg(path)
    assert "m.crg" in str(info.value) and "line" in str(info.value)


def test_nan_mode_0_keeps_nans_a_car_cannot_drive_on(tmp_path):
    path = _road(tmp_path, ["GRID_NAN_MODE = 0"], nan_border=True)
    with pytest.raises(InputError, match="GRID_NAN_MODE = 0 keeps it") as info:
        read_crg(path)
    assert "u = 4 m (row 11), long section 1" in str(info.value)
    read_crg(_road(tmp_path, ["GRID_NAN_MODE = 0"], name="clean.crg"))  # no NaN: fine


def test_both_placements_warn_and_the_reference_point_wins(tmp_path):
    both = ["REFPOINT_X = 5.0", "REFLINE_OFFSET_X = 100.0"]
    with pytest.warns(UserWarning, match="the reference point is used"):
        road = read_crg(_road(tmp_path, both))
    assert road.reference_line()[0][0] == pytest.approx(5.0)
    _same_as_pyopencrg(tmp_path / "m.crg")


def test_durability_road_strip_of_a_placed_road_equals_pyopencrg(tmp_path):
    """The road surface saved with a run's body motion (``road_strip``) is taken at global
    positions: on a curved road placed at (100, -40) it equals pyopencrg's heights along
    the driven track (before, it read the grid as if x were the distance along the road)."""
    from flexpipe.durability.rundir import road_strip

    path = _road(tmp_path, [])
    ref = crg.read(path, apply_mods=True)
    u = np.linspace(5.0, 50.0, 200)
    x, y = ref.uv_to_xy(u, np.zeros_like(u))
    X, Y, Z = road_strip(read_crg(path), x, y)
    np.testing.assert_allclose(Z, ref.xy_to_z(X, Y), atol=1e-9)
