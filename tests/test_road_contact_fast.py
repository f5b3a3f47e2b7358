"""The compiled road contact of a car step (:mod:`flexpipe.roads._contact_fast`) against
the NumPy road (:meth:`flexpipe.roads.road.Road.height_xy` and central differences of it,
the reference the car used before): heights and normals on two-track and grid roads,
uniform and non-uniform distance samples, points beyond the ends and the tracks, and
non-finite points; and the roads it must leave to the NumPy path."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from flexpipe.roads import Road, iso8608, read_crg
from flexpipe.roads._contact_fast import FastContact, for_road, numpy_contact
from flexpipe.tires._fast import enabled

pytestmark = pytest.mark.skipif(not enabled(), reason="Numba is switched off")
ROOT = Path(__file__).resolve().parents[1]
E = 0.05  # the car's half base of the normal (dynamics.ROAD_NORMAL_HALF_BASE_M)


def _reference(road, P):
    """Heights and unit normals from the NumPy road (the car's path before the kernel)."""
    return numpy_contact(road, P, E)


def _points(road, rng, k=400):
    """Points on the road, beyond both ends and beyond both tracks."""
    x0, x1 = road.x[0], road.x[-1]
    x = rng.uniform(x0 - 5.0, x1 + 5.0, k)
    x[:20] = road.x[rng.integers(0, road.x.size, 20)]  # exactly on samples
    y = rng.uniform(-2.0, 2.0, k)
    return np.column_stack([x, y, rng.uniform(-1, 1, k)])


def _grid_road(rng, uniform):
    x = np.linspace(0.0, 30.0, 121) if uniform else np.sort(rng.uniform(0, 30, 121))
    x[0], x[-1] = 0.0, 30.0
    y = np.sort(rng.uniform(-1.5, 1.5, 9))
    z = 0.02 * rng.standard_normal((x.size, y.size))
    return Road(x=x, left=z[:, -1], right=z[:, 0], y=y, z=z)


def _two_track(rng, uniform):
    if uniform:
        return iso8608("D", 60.0, 0.05, seed=int(rng.integers(1 << 30)))
    x = np.concatenate([[0.0], np.sort(rng.uniform(0.1, 40.0, 300)), [40.0]])
    x = np.unique(x)
    return Road(x=x, left=0.03 * rng.standard_normal(x.size),
                right=0.03 * rng.standard_normal(x.size), track_width=1.6)


@pytest.mark.parametrize("make", [_two_track, _grid_road])
@pytest.mark.parametrize("uniform", [True, False])
def test_heights_and_normals_equal_numpy_road(make, uniform):
    rng = np.random.default_rng(11 if uniform else 12)
    for _ in range(5):
        road = make(rng, uniform)
        assert bool(road._dx) is uniform
        fast = for_road(road, E)
        assert isinstance(fast, FastContact)
        P = _points(road, rng)
        h, n = fast(P)
        h_ref, n_ref = _reference(road, P)
        np.testing.assert_allclose(h, h_ref, rtol=0, atol=1e-12)
        np.testing.assert_allclose(n, n_ref, rtol=0, atol=1e-9)
        np.testing.assert_allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-14)


def test_slope_of_a_plane_road():
    """A road rising 1 in 10 along x and tilted 1 in 20 across: the normal of the plane."""
    x = np.linspace(0.0, 100.0, 501)
    y = np.linspace(-2.0, 2.0, 5)
    z = 0.1 * x[:, None] + 0.05 * y[None, :]
    fast = for_road(Road(x=x, left=z[:, -1], right=z[:, 0], y=y, z=z), E)
    h, n = fast(np.array([[10.0, 0.3, 0.0], [55.55, -1.2, 0.0]]))
    np.testing.assert_allclose(h, [1.0 + 0.015, 5.555 - 0.06], atol=1e-12)
    expect = np.array([-0.1, -0.05, 1.0]) / np.sqrt(1.0125)
    np.testing.assert_allclose(n, [expect, expect], atol=1e-12)


def test_non_finite_points_give_nan():
    road = iso8608("C", 20.0, 0.05, seed=3)
    h, n = for_road(road, E)(np.array([[np.nan, 0.0, 0.0], [1.0, np.inf, 0.0],
                                       [2.0, 0.1, 0.0]]))
    assert np.isnan(h[:2]).all() and np.isnan(n[:2]).all()
    assert np.isfinite(h[2]) and np.isfinite(n[2]).all()


def test_roads_left_to_numpy(monkeypatch):
    """A road placed in the plane by a reference line (OpenCRG) and a Road subclass keep
    the NumPy path; so does every road with Numba switched off."""
    crg = read_crg(ROOT / "roads" / "sample_bump.crg")
    assert crg.plan is not None
    assert not isinstance(for_road(crg, E), FastContact)

    class Shifted(Road):
        def height(self, s, lateral=0.0):
            return super().height(s, lateral) + 1.0

    r = iso8608("C", 20.0, 0.05, seed=3)
    shifted = Shifted(x=r.x, left=r.left, right=r.right)
    assert not isinstance(for_road(shifted, E), FastContact)
    P = np.array([[3.0, 0.2, 0.0]])
    np.testing.assert_allclose(for_road(shifted, E)(P)[0], r.height(3.0, 0.2) + 1.0)
    assert not isinstance(for_road(r, E, compiled=False), FastContact)
    monkeypatch.setenv("FLEXPIPE_NO_JIT", "1")
    assert not isinstance(for_road(r, E), FastContact)


def test_one_machine_code_for_every_road():
    """Two-track and grid roads, and read-only query points, share one compiled signature,
    so the set-up's warm-up (a two-track road) leaves nothing to compile for a grid road."""
    from flexpipe.roads._contact_fast import contact

    rng = np.random.default_rng(5)
    P = _points(_two_track(rng, True), rng, k=40)
    P.flags.writeable = False
    for road in (_two_track(rng, True), _two_track(rng, False), _grid_road(rng, True)):
        for_road(road, E)(P)
    assert len(contact.signatures) == 1
