"""OpenCRG evaluation options (``$ROAD_CRG_OPTS``) against pyopencrg's evaluator (an
independent implementation of OpenCRG's reference evaluation), and their bad values."""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.roads import read_crg
from flexpipe.roads.crg_opts import PAD_M
from tests.test_crg_curved import curved_file

crg = pytest.importorskip("pyopencrg")


def _road(tmp_path, opts, *, name="o.crg", nonuniform=False):
    """A curved, sloped, banked road with the options ``opts`` (lines of the section)."""
    rng = np.random.default_rng(5)
    u0, du = 2.0, 0.2
    u = u0 + du * np.arange(301)
    v = np.linspace(-1.5, 2.5, 9)
    phi = 0.3 * np.sin((u - u0) / 15.0) + 0.2
    slope = 0.03 * np.cos((u - u0) / 11.0)
    bank = 0.02 * np.sin((u - u0) / 13.0)
    z = rng.normal(0.0, 0.003, (u.size, v.size))
    z[:, 0] += 0.01       # left and right borders at different heights: repeat seams jump
    return curved_file(tmp_path / name, u0, du, v, phi, slope, bank, z,
                       mods=["$", "$ROAD_CRG_OPTS", *opts])


def _compare(path, *, lateral=PAD_M - 0.5, n=20_000, seed=3):
    """Heights at random (u, v) over the road's length and ``lateral`` m beyond its edges:
    flexpipe's and pyopencrg's; returns the largest difference (m) and the points."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ref = crg.read(path, apply_mods=True)
        road = read_crg(path)
    rng = np.random.default_rng(seed)
    u = rng.uniform(ref.u_start, ref.u_end, n)
    v = rng.uniform(ref.v[0] - lateral, ref.v[-1] + lateral, n)
    z_ref = ref.uv_to_z(u, v)
    assert np.all(np.isfinite(z_ref))
    return np.abs(road.height(u, v) - z_ref), u, v


@pytest.mark.parametrize("opts", [
    ["BORDER_MODE_V = 1", "BORDER_OFFSET_V = 0.07"],
    ["BORDER_MODE_V = 1"],
    ["BORDER_MODE_V = 2", "BORDER_OFFSET_V = -0.03"],
    ["BORDER_MODE_V = 3"],
    ["BORDER_MODE_V = 4"],
    ["border_mode_v = 3", "border_mode_u = 1", "border_offset_u = 0.2", "check_eps = 1e-6"],
])
def test_lateral_border_modes_equal_pyopencrg(tmp_path, opts):
    """Beyond the left and right edges (up to 4.5 m): within 1e-9 m of pyopencrg."""
    dz, _, v = _compare(_road(tmp_path, opts))
    assert dz.max() < 1e-9, dz.max()


@pytest.mark.parametrize("opts", [["BORDER_SMOOTH_UBEG = 5.0"],
                                  ["BORDER_SMOOTH_UEND = 12.0", "BORDER_MODE_V = 4"],
                                  ["BORDER_SMOOTH_UBEG = 3.0", "BORDER_SMOOTH_UEND = 3.0"]])
def test_smoothing_zones_equal_pyopencrg(tmp_path, opts):
    """Smoothing zones: equal at the cross sections; between them OpenCRG blends the
    interpolated height, flexpipe interpolates the blended ones: the difference is at most
    a quarter of the blend's change over an increment (du / L) times the height's change
    over it.  Outside the zones: within 1e-9 m."""
    path = _road(tmp_path, opts)
    dz, u, _ = _compare(path)
    L = max(float(o.split("=")[1]) for o in opts if "SMOOTH" in o)
    near = (u < 2.0 + L + 0.2) | (u > 62.0 - L - 0.2)
    assert dz[~near].max() < 1e-9, dz[~near].max()
    # heights change by at most ~0.05 m over one 0.2 m increment on this road
    assert dz[near].max() <= 0.25 * (0.2 / L) * 0.05, dz[near].max()


@pytest.mark.parametrize("line, key, words", [
    ("BORDER_MODE_V = 0", "BORDER_MODE_V", "no height beyond the road's edges"),
    ("BORDER_MODE_V = 5", "BORDER_MODE_V", "valid: 0"),
    ("BORDER_MODE_U = 3", "BORDER_MODE_U", "give data as long as the run"),
    ("BORDER_SMOOTH_UBEG = -1", "BORDER_SMOOTH_UBEG", ">= 0"),
    ("REFLINE_CONTINUATION = 1", "REFLINE_CONTINUATION", "closed tracks"),
    ("BORDER_MODE_W = 2", "BORDER_MODE_W", "BORDER_MODE_"),
    ("BORDER_OFFSET_V = abc", "BORDER_OFFSET_V", ""),
])
def test_bad_options_name_file_line_and_key(tmp_path, line, key, words):
    path = _road(tmp_path, [line])
    with pytest.raises(InputError, match=words) as err:
        read_crg(path)
    assert err.value.key == key and err.value.line is not None and str(path) in str(err.value)


def test_options_that_change_no_height_are_read_and_ignored(tmp_path):
    plain = read_crg(_road(tmp_path, [], name="a.crg"))
    other = read_crg(_road(tmp_path, ["CHECK_TOL = 1e-3", "WARN_MSGS = 0", "LOG_EVAL = 10"],
                           name="b.crg"))
    np.testing.assert_array_equal(plain.z, other.z)


def test_repeating_a_very_narrow_road_is_refused(tmp_path):
    """A 1 mm wide road repeated 5 m beyond its edges would take 30,000 long sections."""
    u = np.arange(50) * 0.1
    z = np.zeros((50, 3))
    path = curved_file(tmp_path / "narrow.crg", 0.0, 0.1, np.array([-5e-4, 0.0, 5e-4]),
                       np.zeros(50), np.zeros(50), np.zeros(50), z + 0 * u[:, None],
                       mods=["$", "$ROAD_CRG_OPTS", "BORDER_MODE_V = 3"])
    with pytest.raises(InputError, match="give mode 2") as err:
        read_crg(path)
    assert err.value.key == "BORDER_MODE_V" and err.value.line is not None
