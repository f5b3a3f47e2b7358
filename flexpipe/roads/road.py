"""The :class:`Road` data object and its CSV form.

A road is described in road coordinates: ``s`` (OpenCRG ``u``) is the distance along its
reference line (m) and ``lateral`` (``v``) the offset from it, positive to the left (m).
The height is given either by two wheel tracks (``left`` at ``+track_width/2``, ``right``
at ``-track_width/2``) or, for OpenCRG roads, by a full grid ``z[i, j]`` at
``(x[i], y[j])``.  :meth:`Road.height` takes road coordinates; :meth:`Road.height_xy`
takes global plane positions: a road with a :attr:`Road.plan` (OpenCRG) lies where its
reference line puts it (curved or straight), any other road along the global x axis
(``s = x``, ``lateral = y``).  :meth:`Road.reference_path` gives the line as a driver path.

Evaluation rules (:meth:`Road.height`)
-------------------------------------
* Along the path: linear interpolation between samples; beyond either end the end value is
  held (constant extrapolation).  Use :meth:`Road.require_length` before a run to make sure
  the road covers it.
* Across the path, two-track roads: linear between the right and the left track, the track
  value held beyond either track.
* Across the path, grid roads: bilinear on the grid, the border long section held beyond
  the outermost one (the OpenCRG default border mode).
"""

from __future__ import annotations

import bisect
import dataclasses
import math
import pathlib

import numpy as np

from flexpipe._args import as_path, checked_number
from flexpipe._arrays import readonly
from flexpipe._io import atomic_path, header_columns, read_numeric_table
from flexpipe.errors import InputError
from flexpipe.roads._plausible import check_heights
from flexpipe.roads.refline import ReferenceLine

_SCALARS = (float, int, np.float64, np.float32, np.int64)


@dataclasses.dataclass(frozen=True, eq=False)
class Road:
    """Road heights along a path.

    Parameters
    ----------
    x : ndarray, shape (n,)
        Distance along the path of the samples, strictly increasing (m).
    left, right : ndarray, shape (n,)
        Height under the left and right wheel tracks (m).
    track_width : float
        Lateral distance between the tracks ``left`` and ``right`` (m); the tracks lie at
        ``lateral = +track_width/2`` and ``-track_width/2``.
    y : ndarray, shape (n_y,), optional
        Lateral grid (m, positive left, strictly increasing), with ``z``.
    z : ndarray, shape (n, n_y), optional
        Heights on the grid ``(x, y)`` (m).  When given, :meth:`height` interpolates it.
    heading : ndarray, shape (n,), optional
        Heading of the reference line at each ``x`` (rad), for curved OpenCRG roads:
        ``heading[i]`` is the direction from sample ``i-1`` to ``i`` (``heading[0]`` is
        not used).  Needs uniform ``x`` spacing; gives ``plan`` when that is not given.
    plan : ReferenceLine, optional
        Position of the reference line in the global plane (OpenCRG roads).  Without it
        (and without ``heading``) the road lies along the global x axis with ``s = x``
        and ``lateral = y``; see :meth:`height_xy`.
    name : str
        Short name.
    source : str
        Where it came from (file name or generator description).
    """

    x: np.ndarray
    left: np.ndarray
    right: np.ndarray
    track_width: float = 1.5
    y: np.ndarray | None = None
    z: np.ndarray | None = None
    heading: np.ndarray | None = None
    name: str = ""
    source: str = ""
    plan: ReferenceLine | None = None

    def __post_init__(self):
        where = self.source or self.name or None
        x = readonly(self.x)
        left = readonly(self.left)
        right = readonly(self.right)
        if x.ndim != 1 or x.size < 2:
            raise InputError(f"a road needs at least 2 distance samples, got shape {x.shape}",
                             file=where)
        if left.shape != x.shape or right.shape != x.shape:
            raise InputError(f"left {left.shape} and right {right.shape} heights must match "
                             f"the distance samples {x.shape}", file=where)
        for label, a in (("distance", x), ("left height", left), ("right height", right)):
            bad = np.flatnonzero(~np.isfinite(a))
            if bad.size:
                raise InputError(f"{label} sample {bad[0]} is {a[bad[0]]}; all values must "
                                 "be finite", file=where)
        step = np.diff(x)
        if np.any(step <= 0.0):
            i = int(np.flatnonzero(step <= 0.0)[0]) + 1
            raise InputError(f"distance must increase strictly: sample {i} is {x[i]} m after "
                             f"{x[i - 1]} m", file=where)
        tw = checked_number(self.track_width, "track_width", lo=0.0, unit="m", file=where)
        object.__setattr__(self, "x", x)
        object.__setattr__(self, "left", left)
        object.__setattr__(self, "right", right)
        object.__setattr__(self, "track_width", tw)
        if (self.y is None) != (self.z is None):
            raise InputError("give both the lateral grid y and the height grid z, or neither",
                             file=where)
        if self.y is not None:
            y = readonly(self.y)
            z = readonly(self.z)
            if y.ndim != 1 or y.size < 2 or np.any(np.diff(y) <= 0.0):
                raise InputError("lateral grid y must hold >= 2 strictly increasing values",
                                 file=where)
            if z.shape != (x.size, y.size):
                raise InputError(f"height grid z has shape {z.shape}, expected "
                                 f"{(x.size, y.size)}", file=where)
            if not np.all(np.isfinite(z)):
                i, j = np.argwhere(~np.isfinite(z))[0]
                raise InputError(f"height grid value at x = {x[i]} m, y = {y[j]} m is "
                                 f"{z[i, j]}; all values must be finite", file=where)
            object.__setattr__(self, "y", y)
            object.__setattr__(self, "z", z)
        if self.heading is not None:
            heading = readonly(self.heading)
            if heading.shape != x.shape or not np.all(np.isfinite(heading)):
                raise InputError("heading must be finite with one value per distance sample",
                                 file=where)
            object.__setattr__(self, "heading", heading)
        # uniform spacing enables index arithmetic instead of a search in the grid lookup
        dx = (x[-1] - x[0]) / (x.size - 1)
        uniform = bool(np.all(np.abs(step - dx) <= 1e-9 * max(1.0, abs(x[-1]))))
        object.__setattr__(self, "_dx", dx if uniform else 0.0)
        if self.plan is None and self.heading is not None:
            if not uniform:
                raise InputError("a road with a heading needs uniform distance samples",
                                 file=where)
            object.__setattr__(self, "plan", ReferenceLine.from_heading(
                x[0], dx, self.heading[1:]))
        if self.plan is not None:
            if not isinstance(self.plan, ReferenceLine):
                raise InputError(f"plan must be a ReferenceLine, got {type(self.plan).__name__}",
                                 file=where)
            if self.plan.n != x.size or abs(self.plan.u0 - x[0]) > 1e-9 * max(1.0, abs(x[0])) \
                    or not uniform or abs(self.plan.du - dx) > 1e-9 * max(1.0, dx):
                raise InputError("the reference line (plan) must have one point per uniform "
                                 "distance sample, starting at x[0]", file=where)

    # ----------------------------------------------------------------- constructors
    @classmethod
    def from_grid(cls, x, y, z, *, track_width: float = 1.5, heading=None, name: str = "",
                  source: str = "", plan: ReferenceLine | None = None) -> Road:
        """A road from a height grid; the tracks are read at ``±track_width/2``."""
        track_width = checked_number(track_width, "track_width", lo=0.0, unit="m",
                                     file=source or None)
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        z = np.asarray(z, dtype=float)
        if y.ndim != 1 or y.size < 2 or z.shape != (x.size, y.size):
            raise InputError(f"grid shapes do not match: x {x.shape}, y {y.shape}, z {z.shape}",
                             file=source or None)
        half = 0.5 * track_width
        jl, tl = _lateral_weights(y, np.array([half, -half]))
        tracks = z[:, jl] * (1.0 - tl) + z[:, jl + 1] * tl
        return cls(x=x, left=tracks[:, 0], right=tracks[:, 1], track_width=track_width,
                   y=y, z=z, heading=heading, name=name, source=source, plan=plan)

    # ----------------------------------------------------------------- properties
    @property
    def length(self) -> float:
        """Covered distance ``x[-1] - x[0]`` (m)."""
        return float(self.x[-1] - self.x[0])

    @property
    def dx(self) -> float:
        """Sample spacing if uniform, else the mean spacing (m)."""
        return float((self.x[-1] - self.x[0]) / (self.x.size - 1))

    # ----------------------------------------------------------------- evaluation
    def _along(self, s):
        """Index ``i`` and fraction ``t`` so that s lies between x[i] and x[i+1] (held ends)."""
        s = np.asarray(s, dtype=float)
        n = self.x.size
        if self._dx:
            f = np.clip((s - self.x[0]) / self._dx, 0.0, n - 1)
        else:
            f = np.interp(s, self.x, np.arange(n, dtype=float))
        i = np.minimum(f.astype(np.intp), n - 2)
        return i, f - i

    def left_height(self, s):
        """Height under the left track at distance ``s`` (scalar or array, m)."""
        return np.interp(s, self.x, self.left)

    def right_height(self, s):
        """Height under the right track at distance ``s`` (scalar or array, m)."""
        return np.interp(s, self.x, self.right)

    def height(self, s, lateral=0.0):
        """Road height at distance ``s`` and lateral offset ``lateral`` (positive left).

        Parameters
        ----------
        s, lateral : float or array_like
            Broadcast against each other (m).

        Returns
        -------
        float or ndarray
            Height (m); see the module notes for the interpolation and end rules.  NaN
            where ``s`` or ``lateral`` is not finite.
        """
        if type(s) in _SCALARS and type(lateral) in _SCALARS:
            if not (math.isfinite(s) and math.isfinite(lateral)):
                return math.nan
            return self._height_scalar(float(s), float(lateral))
        if self.z is None:
            w = np.clip(np.asarray(lateral, dtype=float) / self.track_width + 0.5, 0.0, 1.0)
            return (1.0 - w) * self.right_height(s) + w * self.left_height(s)
        s, lateral = np.broadcast_arrays(np.asarray(s, dtype=float),
                                         np.asarray(lateral, dtype=float))
        bad = ~(np.isfinite(s) & np.isfinite(lateral))
        if bad.any():          # NaN in, NaN out (e.g. a diverging simulation)
            s, lateral = np.where(bad, self.x[0], s), np.where(bad, 0.0, lateral)
        i, t = self._along(s)
        j, u = _lateral_weights(self.y, lateral)
        z = self.z
        h = ((1.0 - t) * ((1.0 - u) * z[i, j] + u * z[i, j + 1])
             + t * ((1.0 - u) * z[i + 1, j] + u * z[i + 1, j + 1]))
        if bad.any():
            h = np.where(bad, np.nan, h)
        return h[()] if h.ndim == 0 else h

    def _height_scalar(self, s: float, lateral: float) -> float:
        """:meth:`height` for one point without array overhead (same rules)."""
        x = self.x
        n = x.size
        if self._dx:
            f = (s - x[0]) / self._dx
            f = 0.0 if f < 0.0 else (n - 1.0 if f > n - 1.0 else f)
            i = min(int(f), n - 2)
            t = f - i
        elif s <= x[0]:
            i, t = 0, 0.0
        elif s >= x[-1]:
            i, t = n - 2, 1.0
        else:
            i = bisect.bisect_right(x, s) - 1
            t = (s - x[i]) / (x[i + 1] - x[i])
        if self.z is None:
            w = lateral / self.track_width + 0.5
            w = 0.0 if w < 0.0 else (1.0 if w > 1.0 else w)
            left = self.left[i] + t * (self.left[i + 1] - self.left[i])
            right = self.right[i] + t * (self.right[i + 1] - self.right[i])
            return float(right + w * (left - right))
        y = self.y
        if lateral <= y[0]:
            j, u = 0, 0.0
        elif lateral >= y[-1]:
            j, u = y.size - 2, 1.0
        else:
            j = bisect.bisect_right(y, lateral) - 1
            u = (lateral - y[j]) / (y[j + 1] - y[j])
        z0 = self.z[i]
        z1 = self.z[i + 1]
        a = z0[j] + u * (z0[j + 1] - z0[j])
        b = z1[j] + u * (z1[j + 1] - z1[j])
        return float(a + t * (b - a))

    def slope(self, s, lateral=0.0):
        """Longitudinal slope dh/ds at ``(s, lateral)`` (zero beyond the ends)."""
        s = np.asarray(s, dtype=float)
        i, _ = self._along(s)
        inside = (s >= self.x[0]) & (s <= self.x[-1])
        h0 = self.height(self.x[i], lateral)
        h1 = self.height(self.x[i + 1], lateral)
        g = np.where(inside, (h1 - h0) / (self.x[i + 1] - self.x[i]), 0.0)
        return g[()] if np.ndim(g) == 0 else g

    def require_length(self, distance_needed: float, *, what: str = "the run",
                       start: float | None = None) -> None:
        """Raise :class:`InputError` unless the road covers ``distance_needed`` metres.

        Parameters
        ----------
        distance_needed : float
            Distance the vehicle will travel (m).
        what : str
            Description of the run, used in the message.
        start : float, optional
            Distance at which the run starts; defaults to ``x[0]``.
        """
        start = self.x[0] if start is None else float(start)
        end = start + float(distance_needed)
        if end > self.x[-1] + 1e-9 or start < self.x[0] - 1e-9:
            raise InputError(
                f"road '{self.name}' covers {self.x[0]:g} .. {self.x[-1]:g} m but {what} "
                f"needs {start:g} .. {end:g} m; use a longer road or a shorter run",
                file=self.source or None)

    def height_xy(self, x, y):
        """Road height under global plan positions ``(x, y)`` (arrays broadcast, m).

        With a :attr:`plan` (OpenCRG roads) the positions are mapped to road coordinates
        ``(u, v)`` along the reference line (curved or straight, placed by the file's
        start position and heading) and :meth:`height` is evaluated there; without one
        the road lies along the x axis and this is ``height(x, y)``.
        """
        if self.plan is None:
            return self.height(x, y)
        scalar = np.ndim(x) == 0 and np.ndim(y) == 0
        u, v = self.plan.xy_to_uv(x, y)
        h = self.height(u, v)
        return float(h) if scalar else h

    def to_uv(self, x, y):
        """Road coordinates ``(u, v)`` of global plan positions ``(x, y)`` (m)."""
        if self.plan is None:
            return np.broadcast_arrays(np.asarray(x, dtype=float), np.asarray(y, dtype=float))
        return self.plan.xy_to_uv(x, y)

    def reference_line(self):
        """Plan coordinates ``(X, Y)`` of the reference line samples (m).

        The global positions from :attr:`plan`; without one the x axis (``X = x``).
        """
        if self.plan is None:
            return self.x.copy(), np.zeros_like(self.x)
        return self.plan.x.copy(), self.plan.y.copy()

    def reference_path(self, *, ds: float = 0.5):
        """The reference line as a :class:`flexpipe.driver.Path` for the driver to follow.

        Parameters
        ----------
        ds : float
            Largest spacing of the path points (m); the road's samples are thinned to
            about this spacing (first and last kept).

        Returns
        -------
        flexpipe.driver.Path
            Starting at the road's first sample (arc length 0 at ``u = x[0]``).
        """
        from flexpipe.driver.path import Path

        if not (isinstance(ds, int | float) and math.isfinite(ds) and ds > 0.0):
            raise InputError(f"ds must be a finite number > 0, got {ds!r}", key="ds")
        X, Y = self.reference_line()
        step = max(1, int(ds / max(self.dx, 1e-12)))
        keep = np.unique(np.r_[np.arange(0, X.size, step), X.size - 1])
        return Path.from_xy(X[keep], Y[keep], name=f"{self.name or 'road'} reference line",
                            source=self.source)

    # ----------------------------------------------------------------- output
    def to_csv(self, path) -> None:
        """Write ``distance_m,left_m,right_m`` rows to ``path`` atomically."""
        path = pathlib.Path(path)
        data = np.column_stack([self.x, self.left, self.right])
        with atomic_path(path) as tmp:
            with open(tmp, "w") as fh:
                fh.write(f"# flexpipe road '{self.name}' track_width_m={self.track_width:g}\n")
                fh.write("distance_m,left_m,right_m\n")
                np.savetxt(fh, data, delimiter=",", fmt="%.10g")


def _lateral_weights(y: np.ndarray, lateral):
    """Cell index ``j`` and fraction ``u`` of ``lateral`` in grid ``y`` (held borders)."""
    f = np.interp(lateral, y, np.arange(y.size, dtype=float))
    j = np.minimum(np.asarray(f).astype(np.intp), y.size - 2)
    return j, f - j


#: column names a road CSV header may use, by role (see :func:`read_csv`)
ROAD_COLUMNS = {
    "distance": ("distance", "x", "s", "u"),
    "left": ("left", "z_left", "left_z", "height_left", "left_height", "h_left"),
    "right": ("right", "z_right", "right_z", "height_right", "right_height", "h_right"),
    "height": ("height", "z", "h"),
}


def _road_layout(table, path):
    """Column index and factor to metres of (distance, left, right), from the header or,
    without one, by position."""
    if table.header is None:
        return None
    try:
        xy = header_columns(table.header, names={"x": ("x",), "y": ("y",)}, file=path,
                            line=table.header_line, kind="path")
    except InputError:
        xy = []
    if {role for role, _ in xy} == {"x", "y"}:
        raise InputError(f"the header ({', '.join(map(repr, table.header))}) names x and y "
                         "points: this is a driver path (flexpipe run --path, "
                         "flexpipe.driver.read_path), not a road; a road header names the "
                         "distance and the track heights, e.g. 'distance_m,left_m,right_m'",
                         file=path, line=table.header_line)
    cols = header_columns(table.header, names=ROAD_COLUMNS, file=path,
                          line=table.header_line, kind="road")
    where = {role: (i, f) for i, (role, f) in enumerate(cols)}
    given = ", ".join(repr(h) for h in table.header)
    hint = ("a road header names the distance and either the left and the right track or "
            "one height for both, e.g. 'distance_m,left_m,right_m' or 'distance_m,height_m'")
    if "distance" not in where:
        raise InputError(f"road file header ({given}) has no distance column; {hint}",
                         file=path, line=table.header_line)
    if "height" in where and ("left" in where or "right" in where):
        raise InputError(f"road file header ({given}) has a height column and a track "
                         f"column; {hint}", file=path, line=table.header_line)
    if "height" in where:
        return where["distance"], where["height"], where["height"]
    if "left" not in where or "right" not in where:
        missing = "right" if "left" in where else "left"
        raise InputError(f"road file header ({given}) has no {missing} track column; {hint}",
                         file=path, line=table.header_line)
    return where["distance"], where["left"], where["right"]


def read_csv(path, *, track_width: float = 1.5, name: str | None = None) -> Road:
    """Read a road from a CSV file.

    The file holds one sample per line: ``distance, left, right`` or ``distance, height``
    (the same height under both tracks).  Lines starting with ``#`` and blank lines are
    ignored (a UTF-8 byte order mark too).  The first other line may be a header of
    column names; it then says which column is which and in what unit:

    * distance: ``distance``, ``x``, ``s`` or ``u``;
    * tracks: ``left`` and ``right`` (also ``z_left``, ``height_left``, ``left_z``, ...),
      or one ``height`` (``z``, ``h``) for both tracks;
    * each optionally with a length unit, ``distance_m``, ``left_mm``, ``x [mm]``,
      ``z (m)``: m, cm, mm or km, converted to metres (no unit: metres).

    Columns may come in any order (``distance_m,right_m,left_m`` is read as written).  A
    file without a header is read by position, in metres.

    Parameters
    ----------
    path : str or pathlib.Path
        The CSV file.
    track_width : float
        Lateral distance between the two tracks (m).
    name : str, optional
        Road name (default: the file stem).

    Returns
    -------
    Road

    Raises
    ------
    InputError
        Naming the file and line: a header column that is not a road column (the message
        lists the names) or in a unit that is not a length, a non-numeric or non-finite
        value, a wrong number of columns, a distance that does not increase strictly,
        fewer than two samples, heights that change more than a drivable road can (likely
        millimetres; see :mod:`flexpipe.roads._plausible`).
    """
    path = as_path(path, "path")
    track_width = checked_number(track_width, "track_width", lo=0.0, unit="m")
    rows, line_no = [], []
    ncol = None
    columns = "'distance, left, right' in metres"
    table = read_numeric_table(path, kind="road", columns=columns)
    layout = _road_layout(table, path)
    for k, _text, values in table.rows:
        if ncol is None:
            ncol = len(values)
            if layout is not None and ncol != len(table.header):
                raise InputError(f"{ncol} columns but the header on line {table.header_line} "
                                 f"names {len(table.header)}", file=path, line=k)
            if ncol not in (2, 3):
                raise InputError(f"{ncol} columns; expected 3 (distance, left, right) or 2 "
                                 "(distance, height)", file=path, line=k)
            if layout is None:
                layout = ((0, 1.0), (1, 1.0), (ncol - 1, 1.0))
        elif len(values) != ncol:
            raise InputError(f"{len(values)} columns where earlier lines have {ncol}",
                             file=path, line=k)
        sample = [values[i] * f for i, f in layout]
        if rows and sample[0] <= rows[-1][0]:
            raise InputError(f"distance {sample[0]:g} m does not increase (previous sample "
                             f"{rows[-1][0]:g} m on line {line_no[-1]}); distances must "
                             "increase strictly", file=path, line=k)
        rows.append(sample)
        line_no.append(k)
    if len(rows) < 2:
        raise InputError(f"{len(rows)} data line(s); a road needs at least 2 samples",
                         file=path, line=line_no[-1] if line_no else 1)
    data = np.array(rows)
    two = layout[1][0] != layout[2][0]
    road = Road(x=data[:, 0], left=data[:, 1], right=data[:, 2], track_width=track_width,
                name=path.stem if name is None else name, source=str(path))
    check_heights(data[:, 0], data[:, 1:] if two else data[:, 1:2], file=path, lines=line_no,
                  labels=("left track", "right track") if two else ("tracks",))
    return road
