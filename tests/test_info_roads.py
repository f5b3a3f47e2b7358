"""``flexpipe info`` on roads: the track RMS of a non-uniformly sampled road is the
length-weighted RMS of the profile the car drives, the sample spacing is given as a range
when it is not uniform, and an OpenCRG road's reference line is told for what it is
(straight along x, placed, or curved)."""

import math
import re
from pathlib import Path

import numpy as np
import pytest

from flexpipe.cli import main

ROOT = Path(__file__).resolve().parents[1]
REF_ROADS = ROOT.parent / "shared" / "reference" / "roads"


def _rms(out: str, side: str) -> float:
    m = re.search(rf"{side} track height \(mm\):.*RMS about the mean ([0-9.]+)", out)
    return float(m.group(1))


def _csv_columns(path):
    """``distance, left, right`` of a road CSV, read here without flexpipe."""
    rows = [line.split(",") for line in Path(path).read_text().splitlines()
            if line and not line.startswith("#") and line[0].isdigit()]
    return np.array(rows, dtype=float).T


def test_bump_rms_is_that_of_the_driven_profile(capsys):
    """roads/bump.csv: 0.05 m samples in the bumps, 9.2-9.9 m outside.  The RMS about the
    mean is checked two ways: numerical integration of the linearly interpolated profile
    (6.00 / 4.27 mm) and the 1-cos bumps in closed form, h = 50 mm, L = 0.6 m, two on the
    left and one on the right over 30 m: mean n h L / (2 X), mean square
    3 n h^2 L / (8 X) (6.04 / 4.30 mm).  np.std of the samples gave 18.63 / 15.59 mm."""
    path = ROOT / "roads" / "bump.csv"
    x, left, right = _csv_columns(path)
    assert main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    X = x[-1] - x[0]
    xf = np.linspace(x[0], x[-1], 600_001)       # 0.05 mm grid
    for side, z, n_bumps in (("left", left, 2), ("right", right, 1)):
        zf = np.interp(xf, x, z)
        mean = np.trapezoid(zf, xf) / X
        rms = math.sqrt(np.trapezoid((zf - mean) ** 2, xf) / X)
        assert _rms(out, side) == pytest.approx(1e3 * rms, abs=0.006)
        h, L = 0.05, 0.6
        mean_c = n_bumps * h * L / (2 * X)
        rms_c = math.sqrt(3 * n_bumps * h * h * L / (8 * X) - mean_c ** 2)
        assert _rms(out, side) == pytest.approx(1e3 * rms_c, rel=0.01)
    assert _rms(out, "left") == pytest.approx(6.00, abs=0.006)
    assert _rms(out, "right") == pytest.approx(4.27, abs=0.006)
    step = np.diff(x)
    assert f"{x.size} samples, spacing {step.min():.4g} .. {step.max():.4g} m (not uniform)" \
        in out
    assert "every 0.8571" not in out


def test_irregularity_spacing_and_rms(capsys):
    """roads/irregularity.toml: 10 sine periods (s0 = 10 mm, 2.0833 m) in 120 m, sampled
    every 0.01 m plus the irregularity's exact start and end: RMS s0 sqrt(n lambda / (2 L))
    = 2.95 mm, spacing 0.0033 .. 0.01 m (not "every 0.009999 m")."""
    path = ROOT / "roads" / "irregularity.toml"
    assert main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    s0, lam, n, length = 0.01, 150 / 3.6 / 20, 10, 120.0
    want = 1e3 * s0 * math.sqrt(n * lam / (2 * length))
    assert _rms(out, "left") == pytest.approx(want, abs=0.006)
    m = re.search(r"(\d+) samples, spacing ([0-9.e-]+) \.\. ([0-9.e-]+) m \(not uniform\)",
                  out)
    assert m, out
    assert float(m.group(3)) == pytest.approx(0.01, rel=1e-3)
    assert 0.0 < float(m.group(2)) < 0.01
    assert "every 0.009999" not in out


def test_track_statistics_of_a_triangle():
    """A 1 m high triangle over 0 .. 2 m on a 4 m road: mean 1/4, mean square 1/6 by
    hand, RMS about the mean sqrt(1/6 - 1/16) = sqrt(5/48); the samples' np.std differs."""
    from flexpipe.cli.info import track_statistics

    x = np.array([0.0, 1.0, 2.0, 4.0])
    z = np.array([0.0, 1.0, 0.0, 0.0])
    mean, rms = track_statistics(x, z)
    assert mean == pytest.approx(0.25, rel=1e-14)
    assert rms == pytest.approx(math.sqrt(5 / 48), rel=1e-14)
    assert abs(np.std(z) - rms) > 0.05
    # far above z = 0 the same (the RMS is taken about the mean, not about zero)
    assert track_statistics(x, z + 1e4)[1] == pytest.approx(rms, rel=1e-9)


def _text_crg(path, n, *, extra=(), phi=None, mods=True):
    """An OpenCRG text file (LRFI) of ``n`` flat cross sections 0.5 m apart, three long
    sections at v = -1, 0, 1 m; ``phi``: a heading channel (rad, first value unused);
    ``mods``: an empty $ROAD_CRG_MODS section (keep the file's own placement)."""
    head = ["$CT", "test", "$", "$ROAD_CRG", "REFERENCE_LINE_START_U = 0.0",
            f"REFERENCE_LINE_END_U = {0.5 * (n - 1)}", "REFERENCE_LINE_INCREMENT = 0.5",
            "LONG_SECTION_V_RIGHT = -1.0", "LONG_SECTION_V_LEFT = 1.0",
            "LONG_SECTION_V_INCREMENT = 1.0", *extra, "$",
            *(["$ROAD_CRG_MODS", "$"] if mods else []), "$KD_DEFINITION", "#:LRFI",
            *(["D:reference line phi,rad"] if phi is not None else []),
            "D:long section 1,m", "D:long section 2,m", "D:long section 3,m", "$",
            "$$$$$$$$"]
    rows = []
    for i in range(n):
        head_col = [] if phi is None else [" *missing*" if i == 0 else f"{phi[i]:10.7f}"]
        rows.append("".join(head_col + [" 0.0000000"] * 3))
    path.write_text("\n".join(head) + "\n" + "\n".join(rows) + "\n")
    return path


def _reference_line(capsys, path) -> str:
    assert main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    return re.search(r"reference line: (.*)", out).group(1)


def test_straight_unplaced_crg_is_straight_along_x(capsys, tmp_path):
    """roads/sample_bump.crg and a CRG without placement lie along x (s = x); they were
    called "curved or placed (OpenCRG plan)"."""
    for path in (ROOT / "roads" / "sample_bump.crg", _text_crg(tmp_path / "a.crg", 21),
                 _text_crg(tmp_path / "b.crg", 21, mods=False,
                           extra=("REFERENCE_LINE_START_X = 5.0",))):
        line = _reference_line(capsys, path)
        assert line.startswith("straight along x"), (path, line)
        assert "curved" not in line and "placed" not in line


@pytest.mark.parametrize("name", ["Horstwalde.crg", "halfround_4in.crg",
                                  "detrended_rms_course_1in.crg"])
def test_reference_crgs_are_straight_along_x(capsys, name):
    path = REF_ROADS / name
    if not path.is_file():
        pytest.skip(f"reference road {path} not present")
    assert _reference_line(capsys, path).startswith("straight along x")


def test_placed_crg_names_its_start_and_heading(capsys, tmp_path):
    """Start (5, 2) m, heading 0.5 rad = 28.65 deg, kept by an empty $ROAD_CRG_MODS."""
    path = _text_crg(tmp_path / "placed.crg", 21, extra=(
        "REFERENCE_LINE_START_X = 5.0", "REFERENCE_LINE_START_Y = 2.0",
        "REFERENCE_LINE_START_PHI = 0.5"))
    line = _reference_line(capsys, path)
    assert line.startswith("straight, placed at (5, 2) m")
    assert f"heading {math.degrees(0.5):.4g} deg" in line and "--path road" in line


def test_curved_crg_names_its_heading_channel(capsys, tmp_path):
    """A heading channel from 0.02 to 0.4 rad: curved, headings 1.146 .. 22.92 deg, the
    end point the integral of the headings (0.5 m steps) from the start (5, 0) m."""
    phi = np.linspace(0.0, 0.4, 21)
    path = _text_crg(tmp_path / "curved.crg", 21, phi=phi,
                     extra=("REFERENCE_LINE_START_X = 5.0",))
    line = _reference_line(capsys, path)
    assert line.startswith("curved (heading channel): from (5, 0) m")
    x_end = 5.0 + 0.5 * np.cos(phi[1:]).sum()
    y_end = 0.5 * np.sin(phi[1:]).sum()
    assert f"heading {math.degrees(phi[1]):.4g} deg" in line
    assert f"to ({x_end:.6g}, {y_end:.6g}) m, heading {math.degrees(phi[-1]):.4g} deg" in line
