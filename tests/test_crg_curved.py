"""Curved, sloped and banked OpenCRG roads against pyopencrg (Apache-2.0, an independent
reader and evaluator of the same files), and a car following a curved road.

The test files are written here by hand (header text and a big-endian binary or
fixed-width text data block), not by flexpipe's writer.
"""

from __future__ import annotations

import pathlib

import numpy as np
import pytest

from flexpipe.roads import read_crg, write_crg

crg = pytest.importorskip("pyopencrg")

REF = pathlib.Path(__file__).resolve().parents[2] / "shared" / "reference" / "roads"


def _write_crg(path, u0, du, v, columns, names, *, fmt="KDBI", extra=(), mods=None):
    """An OpenCRG file with data ``columns`` (n_u, n_ch) named ``names`` (D: channels);
    ``mods``: lines of a ``$ROAD_CRG_MODS`` section (``[]``: an empty one; ``None``:
    none, so that OpenCRG's default modifiers apply)."""
    n_u = columns.shape[0]
    keys = {"REFERENCE_LINE_START_U": u0, "REFERENCE_LINE_END_U": u0 + (n_u - 1) * du,
            "REFERENCE_LINE_INCREMENT": du, "LONG_SECTION_V_RIGHT": v[0],
            "LONG_SECTION_V_LEFT": v[-1], "LONG_SECTION_V_INCREMENT": v[1] - v[0]}
    head = ["$CT", "hand-written test road", "$", "$ROAD_CRG",
            *[f"{k} = {float(x)!r}" for k, x in keys.items()],
            *extra, *([] if mods is None else ["$", "$ROAD_CRG_MODS", *mods]),
            "$", "$KD_DEFINITION", f"#:{fmt}", *[f"D:{n}" for n in names], "$", "$" * 72]
    body = ("\n".join(head) + "\n").encode()
    if fmt == "KDBI":
        flat = columns.ravel()
        flat = np.concatenate([flat, np.full(-flat.size % 10, np.nan)])   # 80-byte records
        body += flat.astype(">f8").tobytes()
    else:                                     # LDFI: 4 fields of 20 characters per line
        out = []
        for row in columns:
            fields = ["*missing*".ljust(20) if np.isnan(x) else f"{x:20.12e}" for x in row]
            out += ["".join(fields[i:i + 4]) for i in range(0, len(fields), 4)]
        body += ("\n".join(out) + "\n").encode()
    path.write_bytes(body)
    return path


def _curved_road(tmp_path, fmt="KDBI"):
    """An S-bend with varying slope and banking, a 5 cm bump, random texture."""
    rng = np.random.default_rng(7)
    u0, du = 3.0, 0.1
    u = u0 + du * np.arange(1201)
    v = np.linspace(-2.0, 2.0, 17)
    phi = 0.6 * np.sin((u - u0) / 18.0) + 0.3          # interval heading (first unused)
    slope = 0.04 * np.cos((u - u0) / 25.0)
    bank = 0.03 * np.sin((u - u0) / 30.0)
    z = rng.normal(0.0, 0.002, (u.size, v.size))
    bump = np.abs(u - 60.0) < 0.25
    z[bump] += 0.05
    return curved_file(tmp_path / f"s_bend_{fmt}.crg", u0, du, v, phi, slope, bank, z,
                       fmt=fmt)


def curved_file(path, u0, du, v, phi, slope, bank, z, *, fmt="KDBI", mods=None):
    """A road file with heading, slope and banking channels and the grid ``z``, its
    reference line starting at (100, -40), 2.5 m up (``mods``: see :func:`_write_crg`)."""
    cols = np.column_stack([phi, slope, bank, z])
    cols[0, 0] = cols[0, 1] = np.nan
    names = ["reference line phi,rad", "reference line slope,m/m",
             "reference line banking,m/m"] + [f"long section {j + 1},m" for j in range(v.size)]
    extra = ("REFERENCE_LINE_START_X = 100.0", "REFERENCE_LINE_START_Y = -40.0",
             "REFERENCE_LINE_START_Z = 2.5")
    return _write_crg(path, u0, du, v, cols, names, fmt=fmt, extra=extra, mods=mods)


def _random_points(ref, n, rng, margin=1.0):
    """Global (x, y) of random (u, v) over the road and a margin beyond its edges and ends."""
    u = rng.uniform(ref.u_start - margin, ref.u_end + margin, n)
    v = rng.uniform(ref.v[0] - margin, ref.v[-1] + margin, n)
    return ref.uv_to_xy(u, v)


def assert_same_as_pyopencrg(road, ref, *, n=10_000, seed=1, margin=1.0):
    """flexpipe's ``road`` against pyopencrg's ``ref`` at ``n`` random points over the road
    and ``margin`` beyond it: heights, the (x, y) -> (u, v) map and the reference line in
    the plane, within 1e-9 m; returns the points and pyopencrg's heights."""
    x, y = _random_points(ref, n, np.random.default_rng(seed), margin=margin)
    z_ref = ref.xy_to_z(x, y)
    assert np.all(np.isfinite(z_ref))
    dz = np.abs(road.height_xy(x, y) - z_ref)
    assert dz.max() < 1e-9, dz.max()
    u_ref, v_ref = ref.xy_to_uv(x, y)
    u, v = road.to_uv(x, y)
    np.testing.assert_allclose(u, u_ref, atol=1e-9)
    np.testing.assert_allclose(v, v_ref, atol=1e-9)
    X, Y = road.reference_line()
    np.testing.assert_allclose(X, ref.x, atol=1e-9)
    np.testing.assert_allclose(Y, ref.y, atol=1e-9)
    return x, y, z_ref


@pytest.mark.parametrize("fmt", ["KDBI", "LDFI"])
def test_curved_crg_heights_equal_pyopencrg(tmp_path, fmt):
    path = _curved_road(tmp_path, fmt)
    ref = crg.read(path, apply_mods=True)     # as a simulator loads it: OpenCRG's defaults
    assert not ref.is_straight
    road = read_crg(path)
    x, y, z_ref = assert_same_as_pyopencrg(road, ref)
    # scalar queries give the same as arrays
    assert road.height_xy(float(x[0]), float(y[0])) == pytest.approx(z_ref[0], abs=1e-9)


def test_bump_at_its_true_global_position(tmp_path):
    """The issue's case: the 5 cm bump is where the curved line puts it, not at x = u."""
    road = read_crg(_curved_road(tmp_path))
    ref = crg.read(road.source, apply_mods=True)
    xb, yb = ref.uv_to_xy(60.0, 0.0)
    flat_ref = ref.copy()
    z_with = road.height_xy(xb, yb)
    base = road.height(59.0, 0.0) + (road.height(61.0, 0.0) - road.height(59.0, 0.0)) / 2
    assert z_with - base == pytest.approx(0.05, abs=0.01)
    assert flat_ref.xy_to_z(xb, yb) == pytest.approx(z_with, abs=1e-9)


def test_written_curved_road_reads_back_the_same(tmp_path):
    road = read_crg(_curved_road(tmp_path))
    out = tmp_path / "back.crg"
    write_crg(road, out, fmt="KDBI")
    back = read_crg(out)
    ref = crg.read(out)                       # pyopencrg reads flexpipe's file the same way
    x, y = _random_points(ref, 2000, np.random.default_rng(3))
    np.testing.assert_allclose(back.height_xy(x, y), ref.xy_to_z(x, y), atol=1e-9)
    np.testing.assert_allclose(back.height_xy(x, y), road.height_xy(x, y), atol=1e-9)


@pytest.mark.parametrize("name", ["Horstwalde.crg", "halfround_4in.crg",
                                  "detrended_rms_course_1in.crg"])
def test_reference_files_equal_pyopencrg(name):
    path = REF / name
    if not path.is_file():
        pytest.skip(f"reference road {path} not available")
    ref = crg.read(path, apply_mods=True)
    road = read_crg(path)
    x, y = _random_points(ref, 10_000, np.random.default_rng(5), margin=0.5)
    assert np.abs(road.height_xy(x, y) - ref.xy_to_z(x, y)).max() < 1e-9


def test_straight_line_placed_by_start_position_and_heading(tmp_path):
    v = np.array([-1.0, 1.0])
    z = np.zeros((11, 2))
    z[5] = 0.1
    f = _write_crg(tmp_path / "rot.crg", 0.0, 1.0, v, z,
                   ["long section 1,m", "long section 2,m"],
                   extra=("REFERENCE_LINE_START_X = 10.0", "REFERENCE_LINE_START_Y = 5.0",
                          f"REFERENCE_LINE_START_PHI = {float(np.pi / 2)!r}"),
                   mods=[])                   # an empty section: no default placement
    road = read_crg(f)
    assert road.height_xy(10.0, 10.0) == pytest.approx(0.1)      # u = 5 lies north
    assert road.height_xy(15.0, 5.0) == pytest.approx(0.0)
    assert crg.read(f).xy_to_z(10.0, 10.0) == pytest.approx(0.1)


def test_car_follows_curved_road(tmp_path, monkeypatch):
    """A rigid car driven along a curved, sloped, banked road's reference line stays on it.

    The lateral offset of the rear axle from the reference line is computed by pyopencrg
    (its xy -> uv map of the same file), not by flexpipe's path code.
    """
    from flexpipe.vehicle import load_car, simulate

    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path / "cache"))
    du = 0.5
    u = du * np.arange(241)                                       # 120 m
    v = np.linspace(-3.0, 3.0, 7)
    # 20 m straight, then a left arc of radius 60 m
    phi = np.where(u < 20.0, 0.0, (u - 20.0) / 60.0)
    cols = np.column_stack([phi, np.full(u.size, 0.02), np.full(u.size, 0.03),
                            np.zeros((u.size, v.size))])
    names = ["reference line phi,rad", "reference line slope,m/m",
             "reference line banking,m/m"] + [f"long section {j + 1},m" for j in range(v.size)]
    path = _write_crg(tmp_path / "arc.crg", 0.0, du, v, cols, names)
    car = load_car(pathlib.Path(__file__).resolve().parents[1] / "cars" / "sedan.toml")
    r = simulate(car, road=path, path="road", speed=12.0, t_end=5.0, body="rigid", h=2e-3)
    assert r.status == 0, r.message
    ref = crg.read(path)
    u_car, v_car = ref.xy_to_uv(r["x_rear"], r["y_rear"])
    assert u_car[-1] > 60.0                                       # well into the arc
    late = r.t > 1.0
    err = np.abs(v_car[late]).max()
    assert err < 0.15, err                                        # measured 0.052 m
    # the car climbs with the road: body height above the road surface stays the ride height
    gap = r["z"] - ref.xy_to_z(r["x"], r["y"])
    assert np.ptp(gap[late]) < 0.05


def test_run_pair_path_road_needs_a_road(tmp_path):
    from flexpipe.errors import InputError
    from flexpipe.scenarios.runner import run_pair

    car = pathlib.Path(__file__).resolve().parents[1] / "cars" / "sedan.toml"
    with pytest.raises(InputError, match="path 'road'"):
        run_pair(car, road=None, path="road", speed=10.0, t_end=1.0, out=tmp_path, title="t")


def test_non_finite_positions_give_nan_heights(tmp_path):
    """A diverging run passes NaN positions: NaN comes back, the solver reports it."""
    road = read_crg(_curved_road(tmp_path))
    h = road.height_xy(np.array([np.nan, 120.0, np.inf]), np.array([0.0, 20.0, 0.0]))
    assert np.isnan(h[0]) and np.isfinite(h[1]) and np.isnan(h[2])
    assert np.isnan(road.height(float("nan"), 0.0))
    assert np.isnan(road.height(np.array([np.nan]), 0.0)[0])
