"""Road generators, CSV roads, interpolation rules and road specs.

References used (independent of the code under test):
* ISO 8608 class values Gd(n0) = 16e-6 * 4**k m^3 (n0 = 0.1 cycles/m, waviness 2), as
  tabulated by Loprencipe & Zoccali (2017) and Mucka (2018);
* Welch PSD / coherence estimates from scipy.signal;
* the isotropic-surface coherence, obtained here by numerically integrating the 2-D
  spectrum S(k) ~ |k|^-3 over the lateral wavenumber (Dodds & Robson 1973);
* the paper's closed form s(z) = s0 sin(2 pi z / lambda).
"""

from __future__ import annotations

import math
import pathlib

import numpy as np
import pytest
import scipy.integrate
import scipy.signal

from flexpipe.errors import InputError
from flexpipe.roads import (
    Road,
    flat,
    harmonic,
    irregularity,
    iso8608,
    load_road,
    read_csv,
    road_from_spec,
)

REPO = pathlib.Path(__file__).resolve().parents[1]
GD0_PUBLISHED = {"A": 16e-6, "B": 64e-6, "C": 256e-6, "D": 1024e-6, "E": 4096e-6,
                 "F": 16384e-6, "G": 65536e-6, "H": 262144e-6}


def _octave_levels_db(h, dx, gd0):
    """Welch PSD / ISO line, in dB, per octave band from 0.011 cycles/m."""
    n, p = scipy.signal.welch(h, fs=1.0 / dx, nperseg=8192)
    g = gd0 * (np.where(n > 0, n, 1.0) / 0.1) ** -2
    edges = 0.011 * 2.0 ** np.arange(9)         # 0.011 .. 2.816 cycles/m
    levels = []
    for a, b in zip(edges[:-1], edges[1:], strict=True):
        m = (n >= a) & (n < b)
        levels.append(10.0 * math.log10(p[m].mean() / g[m].mean()))
    band = (n >= 0.011) & (n <= 2.83)
    overall = 10.0 * math.log10(np.mean(p[band] / g[band]))
    return np.array(levels), overall


@pytest.mark.parametrize("road_class", ["A", "C", "E", "H"])
def test_iso8608_psd_matches_class_line_within_1db(road_class):
    road = iso8608(road_class, 2000.0, 0.05, seed=11)
    for track in (road.left, road.right):
        levels, overall = _octave_levels_db(track, 0.05, GD0_PUBLISHED[road_class])
        assert abs(overall) < 1.0, overall
        assert np.all(np.abs(levels) < 1.0), levels


def test_iso8608_variance_equals_integral_of_class_psd():
    # Parseval: the mean square equals the integral of Gd over the synthesized band
    length, dx = 1000.0, 0.05
    road = iso8608("D", length, dx, seed=3)
    n = np.arange(1, int(length / (2 * dx))) / length
    n = n[(n >= 0.011) & (n <= 2.83)]
    expected = np.sum(GD0_PUBLISHED["D"] * (n / 0.1) ** -2 / length)
    assert np.mean(road.left[:-1] ** 2) == pytest.approx(expected, rel=1e-9)


def test_iso8608_is_deterministic_for_a_seed():
    a = iso8608("B", 300.0, 0.1, seed=42)
    b = iso8608("B", 300.0, 0.1, seed=42)
    c = iso8608("B", 300.0, 0.1, seed=43)
    assert np.array_equal(a.left, b.left) and np.array_equal(a.right, b.right)
    assert not np.allclose(a.left, c.left)


def _isotropic_coherence_numeric(n, b):
    """gamma(n) = int S(sqrt(n^2+m^2)) cos(2 pi m b) dm / int S(...) dm with S ~ k^-3."""
    def weight(m):
        return (n * n + m * m) ** -1.5
    num = scipy.integrate.quad(weight, 0.0, np.inf, weight="cos", wvar=2 * np.pi * b)[0]
    den = scipy.integrate.quad(weight, 0.0, np.inf)[0]
    return num / den


def test_iso8608_left_right_coherence_follows_isotropic_model():
    b = 1.5
    road = iso8608("C", 4000.0, 0.1, seed=5, track_width=b)
    n, coh = scipy.signal.coherence(road.left, road.right, fs=10.0, nperseg=1024)
    checked = 0
    for a, c in ((0.015, 0.03), (0.03, 0.06), (0.06, 0.12), (0.12, 0.25), (0.25, 0.5),
                 (0.5, 2.5)):
        m = (n >= a) & (n < c)
        model = np.mean([_isotropic_coherence_numeric(f, b) ** 2 for f in n[m]])
        assert coh[m].mean() == pytest.approx(model, abs=0.08), (a, c)
        checked += 1
    assert checked == 6
    # long waves nearly identical on both tracks, short waves independent
    assert coh[(n > 0.015) & (n < 0.03)].mean() > 0.75
    assert coh[(n > 0.5) & (n < 2.8)].mean() < 0.05


@pytest.mark.parametrize("gamma", [0.0, 1.0])
def test_iso8608_constant_coherence_limits(gamma):
    road = iso8608("C", 2000.0, 0.1, seed=9, coherence=gamma)
    if gamma == 1.0:
        np.testing.assert_allclose(road.right, road.left, atol=1e-15)
    else:
        n, coh = scipy.signal.coherence(road.left, road.right, fs=10.0, nperseg=1024)
        assert coh[(n > 0.011) & (n < 2.8)].mean() < 0.05


def test_iso8608_bad_arguments():
    with pytest.raises(InputError, match="class 'Q'"):
        iso8608("Q", 100.0, 0.05, seed=1)
    with pytest.raises(InputError, match="n_max"):
        iso8608("A", 100.0, 0.5, seed=1)
    with pytest.raises(InputError, match="coherence"):
        iso8608("A", 100.0, 0.05, seed=1, coherence=1.5)


def test_irregularity_matches_paper_formula():
    lam = (150.0 / 3.6) / 20.0                  # 20 Hz at 150 km/h
    road = irregularity(s0=0.01, wavelength=lam, n_periods=10, start=20.0, length=80.0,
                        dx=0.01)
    z = np.linspace(0.0, 80.0, 20001)
    inside = (z >= 20.0) & (z < 20.0 + 10 * lam)
    expected = np.where(inside, 0.01 * np.sin(2 * np.pi * (z - 20.0) / lam), 0.0)
    # linear interpolation of a sine sampled at dx: error <= s0 (2 pi dx / lam)^2 / 8
    tol = 0.01 * (2 * np.pi * 0.01 / lam) ** 2 / 8 + 1e-12
    assert np.max(np.abs(road.height(z) - expected)) <= tol
    assert np.max(np.abs(road.left_height(z) - road.right_height(z))) == 0.0


def test_harmonic_and_flat():
    road = harmonic(wavelength=5.0, amplitude=0.02, length=50.0, dx=0.05, phase_right=np.pi)
    np.testing.assert_allclose(road.left, 0.02 * np.sin(2 * np.pi * road.x / 5.0), atol=1e-15)
    np.testing.assert_allclose(road.right, -road.left, atol=1e-15)
    assert np.all(flat(100.0, dx=2.0).height(np.linspace(-5, 105, 50), 0.3) == 0.0)
    with pytest.raises(InputError, match="too coarse"):
        harmonic(wavelength=1.0, amplitude=0.01, length=10.0, dx=0.5)


def test_height_interpolation_and_end_rules():
    road = Road(x=[0.0, 1.0, 3.0], left=[0.0, 0.2, 0.2], right=[0.0, 0.0, -0.4],
                track_width=2.0)
    # linear along the path, linear across between the tracks, held beyond
    assert road.height(0.5, 1.0) == pytest.approx(0.1)
    assert road.height(2.0, -1.0) == pytest.approx(-0.2)
    assert road.height(2.0, 0.0) == pytest.approx(0.5 * (0.2 - 0.2))
    assert road.height(2.0, 0.5) == pytest.approx(0.75 * 0.2 + 0.25 * -0.2)
    assert road.height(-10.0, 5.0) == 0.0
    assert road.height(10.0, 5.0) == pytest.approx(0.2)
    assert road.height(10.0, -5.0) == pytest.approx(-0.4)
    s = np.array([-1.0, 0.25, 2.0, 7.0])
    lat = np.array([0.3, -1.0, 1.0, 0.0])
    scalar = [road.height(float(a), float(b)) for a, b in zip(s, lat, strict=True)]
    np.testing.assert_allclose(road.height(s, lat), scalar, rtol=0, atol=1e-15)
    assert road.slope(0.5, 1.0) == pytest.approx(0.2)
    assert road.slope(5.0, 1.0) == 0.0


def test_grid_road_bilinear():
    x = np.array([0.0, 1.0, 2.0])
    y = np.array([-1.0, 0.0, 1.0])
    z = np.array([[0.0, 0.0, 0.0], [0.0, 1.0, 2.0], [1.0, 1.0, 1.0]])
    road = Road.from_grid(x, y, z, track_width=1.0)
    assert road.height(0.5, 0.5) == pytest.approx(0.5 * 0.5 * 1.0 + 0.5 * 0.5 * 2.0)
    assert road.height(1.5, -0.5) == pytest.approx(0.5 * 0.5 + 0.5 * 1.0)
    assert road.left_height(1.0) == pytest.approx(1.5)
    assert road.right_height(1.0) == pytest.approx(0.5)
    assert road.height(1.0, 3.0) == pytest.approx(2.0)   # held beyond the border


def test_csv_roundtrip(tmp_path):
    road = iso8608("B", 50.0, 0.1, seed=1)
    out = tmp_path / "r.csv"
    road.to_csv(out)
    back = read_csv(out)
    np.testing.assert_allclose(back.x, road.x, rtol=1e-9)
    np.testing.assert_allclose(back.left, road.left, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(back.right, road.right, rtol=1e-9, atol=1e-15)


def test_sample_bump_csv_heights():
    road = read_csv(REPO / "roads" / "bump.csv")
    raw = np.loadtxt(REPO / "roads" / "bump.csv", delimiter=",", comments="#", skiprows=3)
    np.testing.assert_array_equal(road.x, raw[:, 0])
    # 1-cosine bump 50 mm high, 0.6 m long, at 10 m on both tracks, at 20 m left only
    assert road.left_height(10.3) == pytest.approx(0.05)
    assert road.right_height(10.3) == pytest.approx(0.05)
    assert road.left_height(20.3) == pytest.approx(0.05)
    assert road.right_height(20.3) == 0.0


@pytest.mark.parametrize(("content", "line", "what"), [
    ("distance_m,left_m,right_m\n0,0,0\n1,nan,0\n", 3, "non-finite"),
    ("0,0,0\n1,0,0\n0.5,0,0\n", 3, "does not increase"),
    ("0,0,0\n1,0,0\n1,0,0\n", 3, "does not increase"),
    ("# c\n0,0,0\n1,0\n", 3, "columns"),
    ("0,0,0\n1,a,0\n", 2, "not a number"),
])
def test_csv_bad_input_names_file_and_line(tmp_path, content, line, what):
    f = tmp_path / "bad_road.csv"
    f.write_text(content)
    with pytest.raises(InputError, match=what) as info:
        read_csv(f)
    assert "bad_road.csv" in str(info.value) and f"line {line}" in str(info.value)


def test_road_require_length():
    road = flat(100.0)
    road.require_length(100.0)
    with pytest.raises(InputError, match="covers 0 .. 100 m"):
        road.require_length(150.0, what="10 s at 15 m/s")


def test_sample_specs_load():
    iso = load_road(REPO / "roads" / "iso_c_200m.toml")
    assert iso.length == pytest.approx(200.0) and iso.left[0] == 0.0   # faded in
    irr = load_road(REPO / "roads" / "irregularity.toml")
    lam = 2.0833333333333335
    assert irr.height(20.0 + lam / 4) == pytest.approx(0.01, rel=1e-4)
    assert irr.height(20.0 + 10 * lam + 1.0) == 0.0
    csv = load_road(REPO / "roads" / "bump_csv.toml")
    assert csv.left_height(10.3) == pytest.approx(0.05)
    assert load_road(REPO / "roads" / "flat_500m.toml").length == 500.0


def test_spec_errors_name_file_and_key(tmp_path):
    f = tmp_path / "r.toml"
    f.write_text('[road]\ntype = "iso8608"\nroad_class = "C"\nlength_m = 100.0\n'
                 'dx_m = 0.05\nseed = 1\nlenght_m = 3\n')
    with pytest.raises(InputError, match="lenght_m") as info:
        load_road(f)
    assert "r.toml" in str(info.value)
    with pytest.raises(InputError, match="type"):
        road_from_spec({"type": "bumpy"})
    f.write_text("[road\n")
    with pytest.raises(InputError, match="line 1"):
        load_road(f)
    with pytest.raises(InputError, match="unknown road file type"):
        load_road(tmp_path / "x.txt")
