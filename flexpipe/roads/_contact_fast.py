"""Road contact of a car step: heights and upward normals under the wheels.

A car step asks for the road under its four wheels now and at the end of the step, each
with a five-point stencil for the normal (40 heights).  :func:`numpy_contact` evaluates
them through :meth:`flexpipe.roads.road.Road.height_xy`, whose NumPy per-call overhead
dominates for so few points (43 us of the flexible linkage car's 341 us Python step,
measured 2026-12-04).  :func:`contact` evaluates the same interpolation row by row in one
compiled (Numba) call, for roads laid along the x axis (no OpenCRG reference line): two
tracks, or a height grid.  :func:`for_road` picks it where it applies and the NumPy path
elsewhere; ``tests/test_road_contact_fast.py`` checks both against each other and
against a plane's closed-form normal.
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np

from flexpipe.tires._fast import _jit

#: offsets (in units of the half base) of the normal's stencil: the point, then +-x, +-y
_DX = np.array([0.0, 1.0, -1.0, 0.0, 0.0])
_DY = np.array([0.0, 0.0, 0.0, 1.0, -1.0])


def numpy_contact(road, P: np.ndarray, e: float):
    """Road height (n,) and upward unit normal (n, 3) under the points ``P`` (n, 3), the
    normal from central differences of :meth:`~flexpipe.roads.road.Road.height_xy` over
    ``+-e`` (m) in x and in y (any road; the reference of :func:`contact`)."""
    x = (P[:, 0] + _DX[:, None] * e).ravel()  # the points and +-e in x, then in y
    y = (P[:, 1] + _DY[:, None] * e).ravel()
    z = np.asarray(road.height_xy(x, y), dtype=float).reshape(5, -1)
    n = np.empty((P.shape[0], 3))
    n[:, 0] = (z[2] - z[1]) / (2 * e)
    n[:, 1] = (z[4] - z[3]) / (2 * e)
    n[:, 2] = 1.0
    return z[0], n / np.sqrt(n[:, 0] ** 2 + n[:, 1] ** 2 + 1.0)[:, None]


@_jit
def _cell(x, dx, s):
    """Index ``i`` and fraction ``t`` of ``s`` in the samples ``x`` (held ends), as
    ``Road._along`` forms them: index arithmetic for uniform spacing ``dx``, else a search."""
    n = x.shape[0]
    if dx != 0.0:
        f = (s - x[0]) / dx
        f = 0.0 if f < 0.0 else (n - 1.0 if f > n - 1.0 else f)
    elif s <= x[0]:
        f = 0.0
    elif s >= x[n - 1]:
        f = n - 1.0
    else:
        k = np.searchsorted(x, s, side="right") - 1
        f = k + (s - x[k]) / (x[k + 1] - x[k])
    i = min(int(f), n - 2)
    return i, f - i


@_jit
def _height(x, dx, left, right, track_width, y, z, grid, s, lat):
    """Height at distance ``s`` and lateral offset ``lat`` (NaN for a non-finite input)."""
    if not (math.isfinite(s) and math.isfinite(lat)):
        return math.nan
    i, t = _cell(x, dx, s)
    if not grid:
        w = lat / track_width + 0.5
        w = 0.0 if w < 0.0 else (1.0 if w > 1.0 else w)
        hl = left[i] + t * (left[i + 1] - left[i])
        hr = right[i] + t * (right[i + 1] - right[i])
        return (1.0 - w) * hr + w * hl
    j, u = _cell(y, 0.0, lat)
    return ((1.0 - t) * ((1.0 - u) * z[i, j] + u * z[i, j + 1])
            + t * ((1.0 - u) * z[i + 1, j] + u * z[i + 1, j + 1]))


@_jit
def contact(x, dx, left, right, track_width, y, z, grid, P, e, heights, normals):
    """Road height (into ``heights`` (n,)) and upward unit normal (into ``normals``
    (n, 3)) under the points ``P`` (n, 3): the normal from central differences of the
    height over ``+-e`` in x and in y, as :func:`numpy_contact`."""
    for k in range(P.shape[0]):
        px, py = P[k, 0], P[k, 1]
        heights[k] = _height(x, dx, left, right, track_width, y, z, grid, px, py)
        # (-dz/dx, -dz/dy, 1), normalized: the upward normal
        gx = (_height(x, dx, left, right, track_width, y, z, grid, px - e, py)
              - _height(x, dx, left, right, track_width, y, z, grid, px + e, py)) / (2 * e)
        gy = (_height(x, dx, left, right, track_width, y, z, grid, px, py - e)
              - _height(x, dx, left, right, track_width, y, z, grid, px, py + e)) / (2 * e)
        norm = math.sqrt(gx * gx + gy * gy + 1.0)
        normals[k, 0], normals[k, 1], normals[k, 2] = gx / norm, gy / norm, 1.0 / norm


class FastContact:
    """:func:`contact` bound to one road laid along the x axis (see :func:`for_road`)."""

    def __init__(self, road, half_base: float):
        grid = road.z is not None
        # read-only copies throughout (a Road's own arrays are read-only, and Numba
        # compiles read-only and writable arrays apart): one machine code for every road
        self._args = (_frozen(road.x), float(road._dx), _frozen(road.left),
                      _frozen(road.right), float(road.track_width),
                      _frozen(road.y if grid else np.zeros(2)),
                      _frozen(road.z if grid else np.zeros((2, 2))), grid)
        self.e = float(half_base)

    def __call__(self, P: np.ndarray):
        """Heights (n,) and unit normals (n, 3) under the points ``P`` (n, 3)."""
        n = P.shape[0]
        heights, normals = np.empty(n), np.empty((n, 3))
        contact(*self._args, np.array(P, dtype=float, order="C"), self.e, heights, normals)
        return heights, normals


def _frozen(a) -> np.ndarray:
    """A read-only C-contiguous float copy of ``a``."""
    out = np.array(a, dtype=float, order="C")
    out.flags.writeable = False
    return out


def for_road(road, half_base: float, *, compiled: bool | None = None):
    """The contact of ``road``: a callable ``P -> (heights, normals)``, a
    :class:`FastContact` where the compiled path applies, else :func:`numpy_contact`
    (Numba off, a road with a reference line in the plane, or a road type whose height is
    not :class:`flexpipe.roads.road.Road`'s own).  ``compiled=False`` asks for NumPy."""
    from flexpipe.roads.road import Road
    from flexpipe.tires._fast import enabled

    if compiled is None:
        compiled = enabled()
    if compiled and type(road) is Road and road.plan is None:
        return FastContact(road, half_base)
    return partial(numpy_contact, road, e=float(half_base))
