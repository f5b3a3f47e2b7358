"""Plan-view paths for the driver: a polyline with arc length, heading and curvature.

Conventions: ``x`` forward, ``y`` to the left, heading counter-clockwise from ``x`` (rad),
curvature positive for a left turn.  Beyond its ends a path continues straight along its
end tangents (for look-ahead points and projections of a vehicle that overshoots); use
:meth:`Path.require_length` to make sure a run stays on it.
"""

from __future__ import annotations

import bisect
import dataclasses
import math

import numpy as np

from flexpipe._arrays import readonly
from flexpipe.errors import InputError

_SCALARS = (float, int, np.float64, np.float32)


@dataclasses.dataclass(frozen=True, eq=False)
class Path:
    """A path through points ``(x, y)``; build it with :meth:`from_xy` or a constructor.

    Attributes
    ----------
    x, y : ndarray, shape (n,)
        Points (m).
    s : ndarray, shape (n,)
        Cumulative arc length of the polyline (m), ``s[0] = 0``.
    heading : ndarray, shape (n,)
        Tangent direction at the points (rad, unwrapped).
    curvature : ndarray, shape (n,)
        Curvature at the points (1/m), from finite differences of the heading.
    name, source : str
        Description.
    """

    x: np.ndarray
    y: np.ndarray
    s: np.ndarray
    heading: np.ndarray
    curvature: np.ndarray
    name: str = ""
    source: str = ""
    _hint: list = dataclasses.field(default_factory=lambda: [-1], repr=False, compare=False)

    def __post_init__(self):
        # plain lists make the per-step scalar queries cheap (no array overhead)
        object.__setattr__(self, "_xl", self.x.tolist())
        object.__setattr__(self, "_yl", self.y.tolist())
        object.__setattr__(self, "_sl", self.s.tolist())

    @classmethod
    def from_xy(cls, x, y, *, name: str = "", source: str = "", lines=None) -> Path:
        """Build a path from points, validating them.

        Parameters
        ----------
        x, y : array_like, shape (n,)
            Points (m), n >= 2, finite, consecutive points distinct.
        name, source : str
            Description (``source`` is used as the file in error messages).
        lines : sequence of int, optional
            File line of each point, for error messages.
        """
        where = source or None
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        if x.ndim != 1 or x.shape != y.shape or x.size < 2:
            raise InputError(f"a path needs >= 2 points with matching x and y, got shapes "
                             f"{x.shape} and {y.shape}", file=where)

        def line_of(i):
            return None if lines is None else lines[i]

        bad = np.flatnonzero(~(np.isfinite(x) & np.isfinite(y)))
        if bad.size:
            i = int(bad[0])
            raise InputError(f"point {i} ({x[i]}, {y[i]}) is not finite", file=where,
                             line=line_of(i))
        seg = np.hypot(np.diff(x), np.diff(y))
        if np.any(seg <= 1e-9):
            i = int(np.flatnonzero(seg <= 1e-9)[0]) + 1
            raise InputError(f"point {i} ({x[i]:g}, {y[i]:g}) repeats the previous point; "
                             "consecutive points must differ", file=where, line=line_of(i))
        s = np.concatenate([[0.0], np.cumsum(seg)])
        seg_heading = np.unwrap(np.arctan2(np.diff(y), np.diff(x)))
        turn = np.abs(np.diff(seg_heading))
        if np.any(turn > np.deg2rad(120.0)):
            j = int(np.flatnonzero(turn > np.deg2rad(120.0))[0])
            i = j + 2
            raise InputError(f"the path turns by {np.rad2deg(turn[j]):.0f} deg at point "
                             f"{j + 1} on the way to point {i} ({x[i]:g}, {y[i]:g}); a "
                             "drivable path turns smoothly (points out of order?)",
                             file=where, line=line_of(i))
        if x.size > 2:
            dx = np.gradient(x, s)
            dy = np.gradient(y, s)
            heading = np.unwrap(np.arctan2(dy, dx))
            curvature = np.gradient(heading, s)
        else:
            heading = np.full(2, seg_heading[0])
            curvature = np.zeros(2)
        x, y, s, heading, curvature = map(readonly, (x, y, s, heading, curvature))
        return cls(x=x, y=y, s=s, heading=heading, curvature=curvature, name=name,
                   source=source)

    # ------------------------------------------------------------------ queries
    @property
    def length(self) -> float:
        """Arc length of the path (m)."""
        return float(self.s[-1])

    def require_length(self, distance_needed: float, *, what: str = "the run",
                       start: float = 0.0) -> None:
        """Raise :class:`InputError` unless the path is at least ``start + distance_needed``.

        Parameters
        ----------
        distance_needed : float
            Distance the vehicle will travel along the path (m).
        what : str
            Description of the run for the message (e.g. ``"10 s at 60 km/h"``).
        start : float
            Arc length at which the run starts (m).
        """
        end = float(start) + float(distance_needed)
        if end > self.length + 1e-9:
            raise InputError(
                f"path '{self.name}' is {self.length:.1f} m long but {what} needs "
                f"{end:.1f} m (from s = {float(start):g} m); extend the path (lead_out) or "
                "shorten the run", file=self.source or None)

    def point_at(self, s):
        """Point ``(x, y)`` at arc length ``s`` (straight continuation beyond the ends)."""
        if type(s) in _SCALARS:
            return self._point_scalar(float(s))
        s = np.asarray(s, dtype=float)
        x = np.interp(s, self.s, self.x)
        y = np.interp(s, self.s, self.y)
        for end, idx, sign in ((s < 0.0, 0, 1.0), (s > self.s[-1], -1, 1.0)):
            if np.any(end):
                h = self.heading[idx]
                ds = sign * (s - self.s[idx])
                x = np.where(end, self.x[idx] + ds * np.cos(h), x)
                y = np.where(end, self.y[idx] + ds * np.sin(h), y)
        if x.ndim == 0:
            return float(x), float(y)
        return x, y

    def _point_scalar(self, s: float):
        sl, xl, yl = self._sl, self._xl, self._yl
        if s <= 0.0 or s >= sl[-1]:
            idx = 0 if s <= 0.0 else -1
            h = float(self.heading[idx])
            ds = s - sl[idx]
            return xl[idx] + ds * math.cos(h), yl[idx] + ds * math.sin(h)
        i = bisect.bisect_right(sl, s) - 1
        t = (s - sl[i]) / (sl[i + 1] - sl[i])
        return xl[i] + t * (xl[i + 1] - xl[i]), yl[i] + t * (yl[i + 1] - yl[i])

    def heading_at(self, s):
        """Tangent heading at arc length ``s`` (rad; end value beyond the ends)."""
        return np.interp(s, self.s, self.heading)

    def curvature_at(self, s):
        """Curvature at arc length ``s`` (1/m; zero beyond the ends)."""
        return np.interp(s, self.s, self.curvature, left=0.0, right=0.0)

    def project(self, x, y):
        """Nearest point of the path to ``(x, y)``.

        Parameters
        ----------
        x, y : float or array_like
            Query points (m).

        Returns
        -------
        s : float or ndarray
            Arc length of the nearest point; beyond the ends the path is continued along
            its end tangents, so ``s`` may be < 0 or > ``length``.
        lateral : float or ndarray
            Signed distance from the path, positive to the left of the direction of travel.

        Notes
        -----
        A scalar query first searches a window of segments around the previous scalar
        result (kept in a private hint), so per-step calls cost O(1); it falls back to a
        full search when the nearest point lies at the window edge.
        """
        if type(x) in _SCALARS and type(y) in _SCALARS:
            return self._project_scalar(float(x), float(y))
        x, y = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        shape = x.shape
        px, py = x.ravel(), y.ravel()
        s_out = np.empty(px.size)
        e_out = np.empty(px.size)
        chunk = max(1, 2_000_000 // self.x.size)
        for a in range(0, px.size, chunk):
            s_out[a:a + chunk], e_out[a:a + chunk], _ = self._project_many(
                px[a:a + chunk], py[a:a + chunk], 0, self.x.size - 1)
        if not shape:
            return float(s_out[0]), float(e_out[0])
        return s_out.reshape(shape), e_out.reshape(shape)

    def _project_many(self, px, py, lo, hi):
        """Nearest segment among lo..hi-1 for points (px, py): s, lateral, segment."""
        ax, ay = self.x[lo:hi], self.y[lo:hi]
        dx, dy = self.x[lo + 1:hi + 1] - ax, self.y[lo + 1:hi + 1] - ay
        L2 = dx * dx + dy * dy
        rx = px[:, None] - ax[None, :]
        ry = py[:, None] - ay[None, :]
        t = (rx * dx + ry * dy) / L2
        n_seg = self.x.size - 1
        t_lo = np.where(np.arange(lo, hi) == 0, -np.inf, 0.0)
        t_hi = np.where(np.arange(lo, hi) == n_seg - 1, np.inf, 1.0)
        t = np.clip(t, t_lo, t_hi)
        ex, ey = rx - t * dx, ry - t * dy
        d2 = ex * ex + ey * ey
        k = np.argmin(d2, axis=1)
        rows = np.arange(px.size)
        L = np.sqrt(L2[k])
        s = self.s[lo + k] + t[rows, k] * L
        lateral = (dx[k] * ry[rows, k] - dy[k] * rx[rows, k]) / L
        return s, lateral, lo + k

    def _global_segment(self, px: float, py: float, prev: int) -> int:
        """The segment nearest to (px, py); among segments within 0.5 m of the nearest
        distance (a path that overlaps itself: laps of a circle, a figure eight, its end
        continuation) the one closest in index to ``prev`` (none: the first)."""
        ax, ay = self.x[:-1], self.y[:-1]
        dx, dy = np.diff(self.x), np.diff(self.y)
        rx, ry = px - ax, py - ay
        t = (rx * dx + ry * dy) / (dx * dx + dy * dy)
        t_lo = np.zeros(t.size)
        t_lo[0] = -np.inf
        t_hi = np.ones(t.size)
        t_hi[-1] = np.inf
        t = np.clip(t, t_lo, t_hi)
        d = np.hypot(rx - t * dx, ry - t * dy)
        near = np.flatnonzero(d <= d.min() + 0.5)
        if prev < 0 or near.size == 1:
            return int(np.argmin(d))
        return int(near[np.argmin(np.abs(near - prev))])

    def _segment(self, k: int, px: float, py: float):
        """Squared distance, parameter t and lateral offset of (px, py) to segment k."""
        xl, yl = self._xl, self._yl
        ax, ay = xl[k], yl[k]
        dx, dy = xl[k + 1] - ax, yl[k + 1] - ay
        rx, ry = px - ax, py - ay
        L2 = dx * dx + dy * dy
        t = (rx * dx + ry * dy) / L2
        if t < 0.0 and k > 0:
            t = 0.0
        elif t > 1.0 and k < len(xl) - 2:
            t = 1.0
        ex, ey = rx - t * dx, ry - t * dy
        return ex * ex + ey * ey, t, (dx * ry - dy * rx) / math.sqrt(L2)

    def reset_projection(self) -> None:
        """Forget the previous scalar projection (:meth:`project`): the next query searches
        the whole path.  A run calls it at its start, so two runs sharing a path (a
        rigid and a flexible one) do not depend on each other."""
        self._hint[:] = [-1]

    def _project_scalar(self, px, py):
        n_seg = self.x.size - 1
        k = self._hint[0]
        if k < 0:
            k = self._global_segment(px, py, self._hint[1] if len(self._hint) > 1 else -1)
        best = self._segment(k, px, py)
        # walk from the previous answer towards decreasing distance (continuity of a
        # vehicle along its path); a long walk means a jump, so search everything
        for _ in range(200):
            if k + 1 < n_seg:
                cand = self._segment(k + 1, px, py)
                if cand[0] < best[0]:
                    k, best = k + 1, cand
                    continue
            if k > 0:
                cand = self._segment(k - 1, px, py)
                if cand[0] < best[0]:
                    k, best = k - 1, cand
                    continue
            break
        else:  # a jump: the nearest segment, the one closest along the path on a tie
            prev = self._hint[0]
            self._hint[0] = -1
            self._hint[1:] = [prev]
            return self._project_scalar(px, py)
        self._hint[0] = k
        sl = self._sl
        return sl[k] + best[1] * (sl[k + 1] - sl[k]), best[2]
