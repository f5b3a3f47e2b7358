"""Road heights in the wrong unit (millimetres for metres) are rejected at load.

Finding: ``roads/bump.csv`` with heights x 1000 (a 50 m bump) loaded and a run completed
with a peak tyre load of 425 kN.  The readers now reject a height change of more than
2 m within 1 m of road (flexpipe.roads._plausible) and name the file, the position, the
line where known and the likely cause; real roads, steep and long ones included, load.
"""

from __future__ import annotations

import pathlib
import re
import warnings

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.roads import Road, load_road, read_crg, read_csv, write_crg

REPO = pathlib.Path(__file__).resolve().parents[1]
REF = REPO.parent / "shared" / "reference" / "roads"


def _bump_in_mm(tmp_path, name="bump_mm.csv"):
    """roads/bump.csv with every height written in millimetres."""
    out = []
    for line in (REPO / "roads" / "bump.csv").read_text().splitlines():
        if line[:1].isdigit():
            d, left, right = line.split(",")
            line = f"{d},{float(left) * 1e3:g},{float(right) * 1e3:g}"
        out.append(line)
    path = tmp_path / name
    path.write_text("\n".join(out) + "\n")
    return path


def _line_of(path, prefix):
    return next(i for i, t in enumerate(path.read_text().splitlines(), 1) if t.startswith(prefix))


def test_csv_heights_in_millimetres_name_file_line_position_and_cause(tmp_path):
    path = _bump_in_mm(tmp_path)
    with pytest.raises(InputError) as exc:
        load_road(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {_line_of(path, '10.300,')}" in msg   # the bump top
    assert "x = 10.3 m" in msg and "left track" in msg
    assert "2 m within any 1 m" in msg and "millimetres" in msg and "metres" in msg


def test_csv_pothole_in_millimetres_points_at_its_bottom(tmp_path):
    path = tmp_path / "pothole.csv"
    path.write_text("0,0\n5,0\n5.1,-80\n5.2,-80\n5.3,0\n10,0\n")
    with pytest.raises(InputError) as exc:
        read_csv(path)
    msg = str(exc.value)
    assert "pothole.csv" in msg and "line 3" in msg and "x = 5.1 m" in msg
    assert "millimetres" in msg


def test_toml_csv_reference_names_the_csv_file(tmp_path):
    _bump_in_mm(tmp_path, "bump.csv")
    spec = tmp_path / "road.toml"
    spec.write_text('[road]\ntype = "csv"\nfile = "bump.csv"\n')
    with pytest.raises(InputError, match=r"bump\.csv, line \d+: .*millimetres"):
        load_road(spec)


@pytest.mark.parametrize("body, key", [
    ('type = "harmonic"\nwavelength_m = 2.0\namplitude_m = 50.0\nlength_m = 100.0\n'
     'dx_m = 0.1\n', "road.amplitude_m"),
    ('type = "irregularity"\ns0_m = 10.0\nwavelength_m = 2.0833\nlength_m = 120.0\n',
     "road.s0_m")], ids=["harmonic", "irregularity"])
def test_toml_generator_heights_in_millimetres_name_file_and_key(tmp_path, body, key):
    spec = tmp_path / "road.toml"
    spec.write_text("[road]\n" + body)
    with pytest.raises(InputError) as exc:
        load_road(spec)
    msg = str(exc.value)
    assert "road.toml" in msg and f"key '{key}'" in msg and "millimetres" in msg
    assert "2 m within any 1 m" in msg


@pytest.mark.parametrize("fmt", ["LRFI", "KRBI"])
def test_crg_heights_in_millimetres(tmp_path, fmt):
    road = read_crg(REPO / "roads" / "sample_bump.crg")
    mm = Road.from_grid(road.x, road.y, road.z * 1e3, name="mm")
    path = tmp_path / f"bump_mm_{fmt}.crg"
    write_crg(mm, path, fmt=fmt)
    with pytest.raises(InputError) as exc:
        load_road(path)
    msg = str(exc.value)
    assert str(path) in msg and "long section at v =" in msg and "millimetres" in msg
    x = float(re.search(r"at x = ([-\d.]+) m\)", msg).group(1))
    assert 5.0 <= x <= 6.0                          # the 40 mm bump at u = 5 .. 6 m
    if fmt == "LRFI":                               # a text file: the data line too
        assert re.search(r"line \d+", msg)


def test_steep_long_and_stepped_real_roads_load(tmp_path):
    """A mountain road (3 km at 12 %, 360 m climb, with a 0.3 m kerb), an ISO 8608 class H
    road and a CRG with a 12 % slope in its header are real roads: no error."""
    x = np.arange(0.0, 3000.0, 0.1)
    h = 0.12 * x + 0.01 * np.sin(x) + np.where((x > 100.0) & (x < 101.0), 0.3, 0.0)
    path = tmp_path / "mountain.csv"
    np.savetxt(path, np.column_stack([x, h]), delimiter=",", fmt="%.6f")
    assert read_csv(path).left[-1] == pytest.approx(h[-1], abs=1e-6)
    rough = tmp_path / "iso_h.toml"
    rough.write_text('[road]\ntype = "iso8608"\nroad_class = "H"\nlength_m = 1000.0\n'
                     'dx_m = 0.05\nseed = 3\n')
    load_road(rough)
    crg = tmp_path / "climb.crg"
    write_crg(Road(x=x, left=0.0 * x, right=0.0 * x), crg, fmt="KRBI")
    crg.write_bytes(crg.read_bytes().replace(
        b"$ROAD_CRG\n", b"$ROAD_CRG\nREFERENCE_LINE_START_S = 0.12\n", 1))
    assert read_crg(crg).height(2999.0, 0.0) == pytest.approx(0.12 * 2999.0, rel=1e-6)


@pytest.mark.parametrize("rise, ok", [(1.9, True), (2.1, False)])
def test_bound_is_two_metres_within_one_metre(tmp_path, rise, ok):
    """A ramp of ``rise`` over 1 m: at most 2 m within 1 m is accepted, more is not."""
    path = tmp_path / "ramp.csv"
    path.write_text(f"0,0\n10,0\n10.99,{rise}\n20,{rise}\n")
    _loads_or_is_named(path, ok, "ramp.csv, line 3")


def _loads_or_is_named(path, ok: bool, match: str):
    """``read_csv(path)`` loads when ``ok``, else raises an InputError matching ``match``."""
    if ok:
        read_csv(path)
    else:
        with pytest.raises(InputError, match=match):
            read_csv(path)


@pytest.mark.parametrize("name", sorted(p.name for p in (REPO / "roads").iterdir()))
def test_shipped_roads_load(name):
    load_road(REPO / "roads" / name)


@pytest.mark.parametrize("name", ["Horstwalde.crg", "halfround_4in.crg",
                                  "detrended_rms_course_1in.crg"])
def test_reference_crg_roads_load(name):
    path = REF / name
    if not path.is_file():
        pytest.skip(f"reference road {path} not available")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")    # header notes of the measured files
        load_road(path)


def _exact_rise(x, h, width):
    """Brute force: the largest height range of the piecewise-linear profile over any
    ``width`` of road.  The range of a window moves linearly with its start between the
    starts at which a sample enters or leaves it, so its maximum is at one of those."""
    a = np.concatenate([x, x - width])
    a = np.unique(a[(a >= x[0]) & (a <= x[-1] - width)])
    best = 0.0
    for s in a:
        inside = h[(x >= s) & (x <= s + width)]
        ends = np.interp([s, s + width], x, h)
        v = np.r_[inside, ends]
        best = max(best, float(v.max() - v.min()))
    return best


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("far", [0.3, 0.95])
def test_local_rise_with_long_straight_stretches_is_bounded_by_brute_force(seed, far):
    """Profiles with samples both closer and much farther apart than the 1 m window (a
    fraction ``far`` of the gaps long: all bins formed, or, for 0.95, only those near a
    sample): the largest rise reported lies between the brute-force largest rise within
    0.5 m and within 1 m, which is what local_rise promises."""
    from flexpipe.roads._plausible import WINDOW, local_rise

    rng = np.random.default_rng(seed)
    gaps = np.where(rng.random(60) < far, rng.uniform(1.5, 8.0, 60),
                    rng.uniform(0.05, 0.9, 60))
    x = np.r_[0.0, np.cumsum(gaps)]
    h = np.cumsum(rng.normal(0.0, 0.4, x.size))
    _, rise = local_rise(x, h)
    got = float(rise.max())
    assert _exact_rise(x, h, WINDOW / 2) - 1e-12 <= got <= _exact_rise(x, h, WINDOW) + 1e-12


@pytest.mark.parametrize("slope, ok", [(1.5, True), (2.5, False)])
def test_straight_line_over_a_megametre_checks_its_slope(tmp_path, slope, ok):
    """Two samples 1,000 km apart: every 1 m of the line rises by the slope (closed form),
    without one bin per half metre of road."""
    from flexpipe.roads._plausible import WINDOW, local_rise

    start, rise = local_rise(np.array([0.0, 1e6]), np.array([0.0, slope * 1e6]))
    assert start.size <= 8
    assert float(rise.max()) == pytest.approx(slope * WINDOW, rel=1e-9)
    path = tmp_path / "line.csv"
    path.write_text(f"0,0\n1000000,{slope * 1e6:g}\n")
    _loads_or_is_named(path, ok, "line.csv")


def test_a_far_damaged_distance_loads_in_memory_of_the_samples(tmp_path):
    """roads/bump.csv with its last distance damaged to 9e8 m: a flat road that is very
    long.  It used to need 27 GB (one bin per half metre; a CI worker was killed for a
    hypothesis-damaged file like it); it now loads, with its bumps."""
    lines = (REPO / "roads" / "bump.csv").read_text().splitlines()
    lines[-1] = "900000000.0,0.0,0.0"
    path = tmp_path / "far.csv"
    path.write_text("\n".join(lines) + "\n")
    road, bump = read_csv(path), read_csv(REPO / "roads" / "bump.csv")
    assert road.x[-1] == 9e8
    for name in ("left", "right"):  # the bumps as in the undamaged file
        np.testing.assert_array_equal(getattr(road, name)[:-1], getattr(bump, name)[:-1])
