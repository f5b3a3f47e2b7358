"""OpenCRG reference line in the plane: the map between global ``(x, y)`` and road ``(u, v)``.

The reference line is sampled every ``du`` metres of ``u`` (points ``X[i], Y[i]`` at
``u = u0 + i du``); ``v`` is the lateral distance, positive to the left.  The mapping is
the one of the OpenCRG reference implementation (and of pyopencrg, which tests compare
against):

* Inside interval ``i`` (points ``i`` and ``i+1``) a point is
  ``P(u, v) = (1 - t) (X_i + v N1_i) + t (X_i+1 + v N2_i)``, ``t = (u - u_i)/du``, with the
  *corner normals* ``N1_i``, ``N2_i``: at an inner point ``k`` the normal of the secant
  ``X_k+1 - X_k-1``, scaled so that its component along the interval's own unit normal is
  1; at the two ends of the line the interval's unit normal.  The map is continuous across
  intervals and ``v`` is exactly the distance from the interval's chord.
* ``(x, y) -> (u, v)`` starts at the interval before the nearest reference point and walks
  interval by interval until the point lies between the interval's two corner normals.
* Before the first and after the last point the line continues straight along its start
  and end headings.
* A line whose interval headings span less than ``1e-6 pi`` rad is straight: the map is
  the rotation by the mean heading about the first point.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexpipe._arrays import readonly
from flexpipe.errors import InputError

#: Relative heading spread below which a reference line counts as straight (OpenCRG check_eps).
STRAIGHT_EPS = 1e-6


@dataclasses.dataclass(frozen=True, eq=False)
class ReferenceLine:
    """Plan position of a road's reference line; build with :meth:`from_heading`.

    Attributes
    ----------
    u0, du : float
        ``u`` of the first point and the spacing of the points along ``u`` (m).
    x, y : ndarray, shape (n,)
        Global plan position of the points (m).
    """

    u0: float
    du: float
    x: np.ndarray
    y: np.ndarray
    _cache: dict = dataclasses.field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self):
        x, y = readonly(self.x), readonly(self.y)
        if x.ndim != 1 or x.size < 2 or y.shape != x.shape:
            raise InputError(f"a reference line needs >= 2 points, got shapes {x.shape}, "
                             f"{y.shape}")
        if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
            raise InputError("reference line points must be finite")
        if not (math.isfinite(self.du) and self.du > 0.0 and math.isfinite(self.u0)):
            raise InputError(f"reference line spacing must be finite and > 0, got {self.du}")
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "y", y)
        dx, dy = np.diff(x), np.diff(y)
        if np.any(np.hypot(dx, dy) <= 0.0):
            raise InputError("two consecutive reference line points coincide")
        phi = np.arctan2(dy, dx)
        straight = bool(np.ptp(np.unwrap(phi)) <= STRAIGHT_EPS * math.pi)
        if straight:
            mean = math.atan2(float(np.sin(phi).sum()), float(np.cos(phi).sum()))
            start = end = mean
        else:
            start, end = float(phi[0]), float(phi[-1])
        object.__setattr__(self, "phi", readonly(phi))
        object.__setattr__(self, "straight", straight)
        object.__setattr__(self, "phi_start", start)
        object.__setattr__(self, "phi_end", end)

    # ------------------------------------------------------------------ construction
    @classmethod
    def from_heading(cls, u0: float, du: float, phi, *, x0: float = 0.0, y0: float = 0.0,
                     x_end: float | None = None, y_end: float | None = None) -> ReferenceLine:
        """Integrate interval headings into points.

        Parameters
        ----------
        u0, du : float
            ``u`` of the first point and the spacing (m).
        phi : array_like, shape (n - 1,)
            Heading of each interval (rad): interval ``i`` runs from point ``i`` to
            ``i + 1`` (the OpenCRG ``reference line phi`` value of record ``i + 1``).
        x0, y0 : float
            Position of the first point (m).
        x_end, y_end : float, optional
            Position of the last point; when both are given the closing error of the
            integration is spread linearly along the line (as OpenCRG does).
        """
        phi = np.asarray(phi, dtype=float)
        x = np.empty(phi.size + 1)
        y = np.empty(phi.size + 1)
        x[0], y[0] = x0, y0
        x[1:] = x0 + np.cumsum(du * np.cos(phi))
        y[1:] = y0 + np.cumsum(du * np.sin(phi))
        if x_end is not None and y_end is not None:
            w = np.linspace(0.0, 1.0, x.size)
            x += w * (x_end - x[-1])
            y += w * (y_end - y[-1])
        return cls(u0=float(u0), du=float(du), x=x, y=y)

    # ------------------------------------------------------------------ geometry
    @property
    def n(self) -> int:
        """Number of points."""
        return int(self.x.size)

    @property
    def u_end(self) -> float:
        """``u`` of the last point (m)."""
        return self.u0 + (self.n - 1) * self.du

    def _normals(self):
        """Corner normals (N1, N2), each shape (n - 1, 2)."""
        if "normals" not in self._cache:
            dx, dy = np.diff(self.x), np.diff(self.y)
            length = np.hypot(dx, dy)
            m = np.column_stack([-dy / length, dx / length])    # interval unit normals
            n1, n2 = m.copy(), m.copy()
            if self.n > 2:
                tx = self.x[2:] - self.x[:-2]
                ty = self.y[2:] - self.y[:-2]
                lt = np.hypot(tx, ty)
                a = np.column_stack([-ty / lt, tx / lt])        # normals at inner points
                n1[1:] = a / np.einsum("ij,ij->i", a, m[1:])[:, None]
                n2[:-1] = a / np.einsum("ij,ij->i", a, m[:-1])[:, None]
            self._cache["normals"] = (n1, n2)
        return self._cache["normals"]

    def _nearest(self, px, py):
        if "tree" not in self._cache:
            from scipy.spatial import cKDTree

            self._cache["tree"] = cKDTree(np.column_stack([self.x, self.y]))
        return self._cache["tree"].query(np.column_stack([px, py]))[1]

    def uv_to_xy(self, u, v):
        """Global plan position of road coordinates ``(u, v)`` (arrays broadcast)."""
        u, v = np.broadcast_arrays(np.asarray(u, dtype=float), np.asarray(v, dtype=float))
        shape = u.shape
        u, v = u.ravel(), v.ravel()
        if self.straight:
            c, s = math.cos(self.phi_start), math.sin(self.phi_start)
            d = u - self.u0
            px, py = self.x[0] + c * d - s * v, self.y[0] + s * d + c * v
        else:
            f = (u - self.u0) / self.du
            i = np.clip(np.floor(f), 0, self.n - 2).astype(np.intp)
            t = f - i
            n1, n2 = self._normals()
            xa, ya = self.x[i] + v * n1[i, 0], self.y[i] + v * n1[i, 1]
            xb, yb = self.x[i + 1] + v * n2[i, 0], self.y[i + 1] + v * n2[i, 1]
            px, py = xa + t * (xb - xa), ya + t * (yb - ya)
            for mask, k, h, d in ((t < 0.0, 0, self.phi_start, t * self.du),
                                  (t > 1.0, -1, self.phi_end, (t - 1.0) * self.du)):
                if np.any(mask):
                    c, s = math.cos(h), math.sin(h)
                    px[mask] = self.x[k] + c * d[mask] - s * v[mask]
                    py[mask] = self.y[k] + s * d[mask] + c * v[mask]
        return px.reshape(shape), py.reshape(shape)

    def xy_to_uv(self, x, y):
        """Road coordinates ``(u, v)`` of global plan positions ``(x, y)`` (arrays broadcast).

        Returns
        -------
        u, v : ndarray
            Same shape as the broadcast inputs (m); NaN where a position is not finite.
        """
        px, py = np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        shape = px.shape
        px, py = px.ravel(), py.ravel()
        ok = np.isfinite(px) & np.isfinite(py)
        if not ok.all():       # e.g. a diverging simulation: NaN out, the caller decides
            u, v = np.full(px.size, np.nan), np.full(px.size, np.nan)
            if ok.any():
                u[ok], v[ok] = self.xy_to_uv(px[ok], py[ok])
            return u.reshape(shape), v.reshape(shape)
        if self.straight:
            c, s = math.cos(self.phi_start), math.sin(self.phi_start)
            dx, dy = px - self.x[0], py - self.y[0]
            return ((self.u0 + c * dx + s * dy).reshape(shape),
                    (-s * dx + c * dy).reshape(shape))
        u, v = self._xy_to_uv_curved(px, py)
        return u.reshape(shape), v.reshape(shape)

    def _side(self, j, px, py):
        """Signed tests of the points against the start and end corner normals of interval j.

        ``back < 0``: before the start normal; ``ahead > 0``: beyond the end normal.
        """
        n1, n2 = self._normals()
        x, y = self.x, self.y
        back = (px - x[j]) * n1[j, 1] - (py - y[j]) * n1[j, 0]
        ahead = (px - x[j + 1]) * n2[j, 1] - (py - y[j + 1]) * n2[j, 0]
        return back, ahead

    def _start(self, px, py):
        """Interval to start the walk from: the previous call's result for points that
        moved a few sample spacings at most since (a vehicle's contact points), else the
        interval before the nearest reference point."""
        prev = self._cache.get("hints", {}).get(px.size)
        if prev is not None and np.max(np.abs(px - prev[0]) + np.abs(py - prev[1])) \
                < max(4.0 * self.du, 0.2):
            return prev[2].copy()
        return np.clip(self._nearest(px, py) - 1, 0, self.n - 2)

    def _xy_to_uv_curved(self, px, py):
        last = self.n - 2
        j = self._start(px, py)
        back, ahead = self._side(j, px, py)
        idx = None                  # points still walking (None: all of them)
        for _ in range(self.n + 1):
            jj = j if idx is None else j[idx]
            b, a = (back, ahead) if idx is None else (back[idx], ahead[idx])
            fwd = (a > 0.0) & (jj < last)
            bwd = (b < 0.0) & (jj > 0) & ~fwd
            move = fwd | bwd
            if not move.any():
                break
            idx = np.flatnonzero(move) if idx is None else idx[move]
            j[idx] += np.where(fwd[move], 1, -1)
            back[idx], ahead[idx] = self._side(j[idx], px[idx], py[idx])
        hints = self._cache.setdefault("hints", {})   # one per point-set size (few sizes)
        if len(hints) > 16:
            hints.clear()
        hints[px.size] = (px.copy(), py.copy(), j.copy())
        n1, n2 = self._normals()
        x1, y1, x2, y2 = self.x[j], self.y[j], self.x[j + 1], self.y[j + 1]
        cx, cy = x2 - x1, y2 - y1
        with np.errstate(invalid="ignore", divide="ignore"):
            v = (cx * (py - y1) - cy * (px - x1)) / np.hypot(cx, cy)
            ta = back / (n1[j, 1] * cx - n1[j, 0] * cy)
            tb = -ahead / (n2[j, 1] * cx - n2[j, 0] * cy)
            u = self.u0 + (j + ta / (ta + tb)) * self.du
        before = back < 0.0
        after = (ahead > 0.0) & ~before
        for mask, k, h, ue in ((before, 0, self.phi_start, self.u0),
                               (after, -1, self.phi_end, self.u_end)):
            if np.any(mask):
                c, s = math.cos(h), math.sin(h)
                dx, dy = px[mask] - self.x[k], py[mask] - self.y[k]
                u[mask] = ue + c * dx + s * dy
                v[mask] = -s * dx + c * dy
        return u, v

    def heading_at(self, u):
        """Heading of the reference line at ``u`` (rad): that of the interval holding ``u``."""
        u = np.asarray(u, dtype=float)
        if self.straight:
            return np.full(u.shape, self.phi_start)[()]
        i = np.floor((u - self.u0) / self.du).astype(np.intp)
        out = self.phi[np.clip(i, 0, self.phi.size - 1)]
        out = np.where(i < 0, self.phi_start, np.where(i > self.phi.size - 1, self.phi_end, out))
        return out[()]

    def curvature(self) -> np.ndarray:
        """Curvature at the inner points (1/m, positive turning left), shape (n - 2,)."""
        dx, dy = np.diff(self.x), np.diff(self.y)
        return (dx[:-1] * dy[1:] - dy[:-1] * dx[1:]) / self.du ** 3
