"""Path constructors: straight, slalom, ISO 3888-1 double lane change, and file import.

ISO 3888-1 double lane change
-----------------------------
ISO 3888-1 (Passenger cars - Test track for a severe lane-change manoeuvre - Part 1:
Double lane-change) fixes the section lengths; the lane widths depend on the vehicle
width ``b``:

=======  ======  ==================  =====================================
section  length  lane width          lane position
=======  ======  ==================  =====================================
1        15 m    1.1 b + 0.25 m      entry lane
2        30 m    (free)              lane change
3        25 m    1.2 b + 0.25 m      offset lane
4        25 m    (free)              lane change back
5        15 m    1.3 b + 0.25 m      exit lane
6        15 m    1.3 b + 0.25 m      exit lane
=======  ======  ==================  =====================================

The offset lane lies 3.5 m to the side.  This module reads the standard's figure as: the
right-hand boundary of the offset lane is 3.5 m to the left of the right-hand boundary of
the entry lane (left-hand version), and the exit lanes share the entry lane's right-hand
boundary.  Other implementations measure the 3.5 m differently (MathWorks' ISO 3888 scene
between lane centres, Project Chrono's demo from the entry-lane centre to the offset
lane's boundary); for b = 1.8 m the offset-lane centre lies at 3.59 m here, 3.50 m and
4.71 m there, so check the convention when comparing with another tool.
:func:`iso3888_1` returns the path through the lane centres, with C2-smooth transitions
(quintic smooth step) over sections 2 and 4; :func:`iso3888_1_lanes` returns the gates.
"""

from __future__ import annotations

import math
import pathlib

import numpy as np

from flexpipe._io import header_columns, read_numeric_table
from flexpipe.driver.path import Path
from flexpipe.errors import InputError
from flexpipe.roads._tables import TableReader, read_toml

#: ISO 3888-1 section lengths (m), sections 1..6.
ISO3888_1_LENGTHS = (15.0, 30.0, 25.0, 25.0, 15.0, 15.0)
#: ISO 3888-1 lateral offset of the offset lane (m).
ISO3888_1_OFFSET = 3.5


def _smoothstep(t):
    t = np.clip(t, 0.0, 1.0)
    return t**3 * (10.0 - 15.0 * t + 6.0 * t**2)


def _positive(value, what, name):
    if not (isinstance(value, int | float) and math.isfinite(value) and value > 0.0):
        raise InputError(f"{what}: {name} must be > 0, got {value!r}")


def _samples(length, ds, what):
    _positive(ds, what, "ds")
    n = max(2, int(math.ceil(length / ds)) + 1)
    if n > 5_000_000:
        raise InputError(f"{what}: {n} points (length {length:g} m / ds {ds:g} m) is too many; "
                         "use a larger ds")
    return np.linspace(0.0, length, n)


def straight(length: float, *, ds: float = 1.0, heading: float = 0.0) -> Path:
    """A straight path of ``length`` metres from the origin along ``heading`` (rad)."""
    _positive(length, "straight path", "length")
    r = _samples(length, ds, "straight path")
    return Path.from_xy(r * math.cos(heading), r * math.sin(heading), name="straight",
                        source=f"straight(length={length:g})")


def slalom(*, cone_spacing: float, n_cones: int, offset: float, lead_in: float,
           lead_out: float, ds: float = 0.2, first: str = "left") -> Path:
    """A slalom path passing ``n_cones`` cones alternately on either side.

    The cones stand on the x axis at ``x_i = lead_in + i * cone_spacing``.  The path is
    ``y = ±offset cos(pi (x - x_0) / cone_spacing)`` (so it passes cone ``i`` at lateral
    distance ``offset``, on the ``first`` side for cone 0) with an amplitude that rises
    from 0 over the two cone spacings before the first cone and falls back over the two
    after the last, by a quintic smooth step: the curvature is continuous and its peak
    stays within a few per cent of the steady value ``offset (pi / cone_spacing)^2``.

    Parameters
    ----------
    cone_spacing : float
        Distance between cones (m), e.g. 18 m (the common handling-test spacing).
    n_cones : int
        Number of cones (>= 1).
    offset : float
        Lateral distance of the path from the cone line at each cone (m).
    lead_in : float
        Distance from the path start to the first cone (m); at least ``2 cone_spacing``
        (the entry transition).
    lead_out : float
        Distance after the last cone (m); at least ``2 cone_spacing``.
    ds : float
        Point spacing (m).
    first : {'left', 'right'}
        Side on which the path passes the first cone.
    """
    what = "slalom path"
    _positive(cone_spacing, what, "cone_spacing")
    _positive(offset, what, "offset")
    if int(n_cones) != n_cones or n_cones < 1:
        raise InputError(f"{what}: n_cones must be a positive integer, got {n_cones!r}")
    for name, value in (("lead_in", lead_in), ("lead_out", lead_out)):
        if not (math.isfinite(value) and value >= 2.0 * cone_spacing):
            raise InputError(f"{what}: {name} must be >= 2 cone_spacing ({2 * cone_spacing:g} "
                             f"m) to hold the entry/exit transition, got {value!r}")
    if first not in ("left", "right"):
        raise InputError(f"{what}: first must be 'left' or 'right', got {first!r}")
    x_first = lead_in
    x_last = lead_in + (n_cones - 1) * cone_spacing
    total = x_last + lead_out
    x = _samples(total, ds, what)
    ramp = 2.0 * cone_spacing
    envelope = _smoothstep((x - (x_first - ramp)) / ramp) \
        * _smoothstep(((x_last + ramp) - x) / ramp)
    sign = 1.0 if first == "left" else -1.0
    y = sign * offset * envelope * np.cos(np.pi * (x - x_first) / cone_spacing)
    return Path.from_xy(x, y, name="slalom",
                        source=f"slalom(cone_spacing={cone_spacing:g}, n_cones={n_cones}, "
                               f"offset={offset:g})")


def circle(*, radius: float, turns: float = 1.0, lead_in: float = 20.0,
           transition: float | None = None, direction: str = "left",
           ds: float = 0.2) -> Path:
    """A constant-radius circle (ISO 4138 steady-state cornering) entered from a straight.

    From the origin along x for ``lead_in`` metres, then a clothoid whose curvature rises
    linearly from 0 to ``1 / radius`` over ``transition`` metres (a step in curvature would
    need a step in steering), then ``turns`` full turns at the radius.  Driven round more
    than once, the path overlaps itself; the driver follows it in order (its projection
    walks on from the previous point).

    Parameters
    ----------
    radius : float
        Radius of the circle (m), e.g. 40 m (ISO 4138 allows >= 30 m).
    turns : float
        Number of turns on the circle after the transition (> 0).
    lead_in : float
        Straight before the transition (m), >= 0.
    transition : float, optional
        Clothoid length (m); default ``min(radius, 30)``.
    direction : {'left', 'right'}
    ds : float
        Point spacing (m).
    """
    what = "circle path"
    _positive(radius, what, "radius")
    _positive(turns, what, "turns")
    transition = min(radius, 30.0) if transition is None else transition
    _positive(transition, what, "transition")
    if not (math.isfinite(lead_in) and lead_in >= 0.0):
        raise InputError(f"{what}: lead_in must be >= 0 m, got {lead_in!r}")
    if direction not in ("left", "right"):
        raise InputError(f"{what}: direction must be 'left' or 'right', got {direction!r}")
    total = lead_in + transition + turns * 2.0 * math.pi * radius
    s = _samples(total, ds, what)
    sign = 1.0 if direction == "left" else -1.0
    k = sign / radius * np.clip((s - lead_in) / transition, 0.0, 1.0)
    # heading = integral of the (piecewise-linear) curvature, exact by the trapezoid rule;
    # positions by integrating the tangent over each step at its mid heading
    dsv = np.diff(s)
    heading = np.concatenate([[0.0], np.cumsum(0.5 * (k[1:] + k[:-1]) * dsv)])
    mid = heading[:-1] + dsv * (k[:-1] / 2.0 + (k[1:] - k[:-1]) / 6.0)
    x = np.concatenate([[0.0], np.cumsum(dsv * np.cos(mid))])
    y = np.concatenate([[0.0], np.cumsum(dsv * np.sin(mid))])
    return Path.from_xy(x, y, name="circle",
                        source=f"circle(radius={radius:g}, turns={turns:g}, "
                               f"direction={direction})")


def iso3888_1_lanes(*, vehicle_width: float = 1.8, lead_in: float = 50.0,
                    direction: str = "left") -> list[dict]:
    """The gated lanes of ISO 3888-1 (module notes) in path coordinates.

    Returns
    -------
    list of dict
        One dict per gated section (1, 3, 5, 6) with ``section``, ``x_start``, ``x_end``,
        ``y_right``, ``y_left`` (m); the entry lane is centred on ``y = 0``.
    """
    _positive(vehicle_width, "ISO 3888-1 track", "vehicle_width")
    if direction not in ("left", "right"):
        raise InputError(f"ISO 3888-1 track: direction must be 'left' or 'right', got "
                         f"{direction!r}")
    b = vehicle_width
    widths = {1: 1.1 * b + 0.25, 3: 1.2 * b + 0.25, 5: 1.3 * b + 0.25, 6: 1.3 * b + 0.25}
    starts = lead_in + np.concatenate([[0.0], np.cumsum(ISO3888_1_LENGTHS)])
    base = -0.5 * widths[1]                      # right-hand boundary of the entry lane
    lanes = []
    for sec, w in widths.items():
        right = base + (ISO3888_1_OFFSET if sec == 3 else 0.0)
        lo, hi = right, right + w
        if direction == "right":
            lo, hi = -hi, -lo
        lanes.append(dict(section=sec, x_start=float(starts[sec - 1]),
                          x_end=float(starts[sec]), y_right=lo, y_left=hi))
    return lanes


def iso3888_1(*, vehicle_width: float = 1.8, lead_in: float = 50.0, lead_out: float = 50.0,
              ds: float = 0.2, direction: str = "left") -> Path:
    """The ISO 3888-1 double lane change as a path through the lane centres.

    Parameters
    ----------
    vehicle_width : float
        Vehicle width ``b`` (m), sets the lane widths.
    lead_in, lead_out : float
        Straight distance before section 1 and after section 6 (m), >= 0.
    ds : float
        Point spacing (m).
    direction : {'left', 'right'}
        Side of the first lane change.
    """
    for name, value in (("lead_in", lead_in), ("lead_out", lead_out)):
        if not (math.isfinite(value) and value >= 0.0):
            raise InputError(f"ISO 3888-1 track: {name} must be >= 0 m, got {value!r}")
    lanes = {lane["section"]: lane for lane in iso3888_1_lanes(
        vehicle_width=vehicle_width, lead_in=lead_in, direction=direction)}
    centre = {k: 0.5 * (v["y_right"] + v["y_left"]) for k, v in lanes.items()}
    total = lead_in + sum(ISO3888_1_LENGTHS) + lead_out
    x = _samples(total, ds, "ISO 3888-1 track")
    s2a, s2b = lanes[1]["x_end"], lanes[3]["x_start"]
    s4a, s4b = lanes[3]["x_end"], lanes[5]["x_start"]
    y = (centre[1] + (centre[3] - centre[1]) * _smoothstep((x - s2a) / (s2b - s2a))
         + (centre[5] - centre[3]) * _smoothstep((x - s4a) / (s4b - s4a)))
    return Path.from_xy(x, y, name="iso3888_1",
                        source=f"iso3888_1(vehicle_width={vehicle_width:g}, "
                               f"direction={direction})")


#: column names a path CSV header may use, by role (see :func:`read_path_csv`)
PATH_COLUMNS = {"x": ("x",), "y": ("y",)}


def read_path_csv(path) -> Path:
    """Read ``x, y`` points (m) from a CSV file.

    ``#`` lines and blank lines are ignored (a UTF-8 byte order mark too).  The first other
    line may be a header naming the columns ``x`` and ``y`` in either order, each
    optionally with a length unit (``x_m``, ``y_mm``, ``x [mm]``, ``y (m)``: m, cm, mm or
    km, converted to metres); a file without a header is read as ``x, y`` in metres.

    Raises
    ------
    InputError
        Naming the file and line (and the column for a header): a header column other
        than x and y or in a unit that is not a length, a bad number, a wrong number of
        columns, fewer than 2 points, repeated points or a turn back.
    """
    path = pathlib.Path(path)
    table = read_numeric_table(path, kind="path", columns="'x, y' in metres")
    layout = ((0, 1.0), (1, 1.0))
    if table.header is not None:
        cols = header_columns(table.header, names=PATH_COLUMNS, file=path,
                              line=table.header_line, kind="path")
        where = {role: (i, f) for i, (role, f) in enumerate(cols)}
        if len(where) != 2:
            raise InputError(f"path file header ({', '.join(map(repr, table.header))}) "
                             f"has no {'y' if 'x' in where else 'x'} column; a path header "
                             "names x and y, e.g. 'x_m,y_m'", file=path,
                             line=table.header_line)
        layout = (where["x"], where["y"])
    xs, ys, lines = [], [], []
    for k, _text, values in table.rows:
        if len(values) != 2:
            raise InputError(f"{len(values)} columns; expected 2 (x, y)", file=path, line=k)
        xs.append(values[layout[0][0]] * layout[0][1])
        ys.append(values[layout[1][0]] * layout[1][1])
        lines.append(k)
    if len(xs) < 2:
        raise InputError(f"{len(xs)} point(s); a path needs at least 2", file=path,
                         line=lines[-1] if lines else 1)
    return Path.from_xy(xs, ys, name=path.stem, source=str(path), lines=lines)


PATH_TYPES = ("straight", "slalom", "iso3888_1", "circle", "points", "csv")


def path_from_spec(table: dict, *, file=None, name: str = "path") -> Path:
    """Build a path from a TOML-style table with ``type`` in :data:`PATH_TYPES`.

    Keys: ``straight`` (length_m, ds_m); ``slalom`` (cone_spacing_m, n_cones, offset_m,
    lead_in_m, lead_out_m, ds_m, first); ``iso3888_1`` (vehicle_width_m, lead_in_m,
    lead_out_m, ds_m, direction); ``circle`` (radius_m, turns, lead_in_m, transition_m,
    direction, ds_m); ``points`` (x_m, y_m lists); ``csv`` (file, relative to
    the TOML file).
    """
    t = TableReader(table, file=file, name=name)
    kind = t.str("type", choices=PATH_TYPES)
    try:
        if kind == "straight":
            p = straight(t.float("length_m", positive=True), ds=t.float("ds_m", 1.0, positive=True))
        elif kind == "slalom":
            p = slalom(cone_spacing=t.float("cone_spacing_m", positive=True),
                       n_cones=t.int("n_cones", lo=1), offset=t.float("offset_m", positive=True),
                       lead_in=t.float("lead_in_m", positive=True),
                       lead_out=t.float("lead_out_m", positive=True),
                       ds=t.float("ds_m", 0.2, positive=True),
                       first=t.str("first", "left", choices=("left", "right")))
        elif kind == "iso3888_1":
            p = iso3888_1(vehicle_width=t.float("vehicle_width_m", 1.8, positive=True),
                          lead_in=t.float("lead_in_m", 50.0, nonnegative=True),
                          lead_out=t.float("lead_out_m", 50.0, nonnegative=True),
                          ds=t.float("ds_m", 0.2, positive=True),
                          direction=t.str("direction", "left", choices=("left", "right")))
        elif kind == "circle":
            tr = t.float("transition_m", positive=True) if t.has("transition_m") else None
            p = circle(radius=t.float("radius_m", positive=True),
                       turns=t.float("turns", 1.0, positive=True),
                       lead_in=t.float("lead_in_m", 20.0, nonnegative=True), transition=tr,
                       direction=t.str("direction", "left", choices=("left", "right")),
                       ds=t.float("ds_m", 0.2, positive=True))
        elif kind == "points":
            xs, ys = t.float_list("x_m"), t.float_list("y_m")
            if len(xs) != len(ys):
                raise t.error("y_m", f"{len(ys)} values but x_m has {len(xs)}")
            try:
                p = Path.from_xy(xs, ys, name=name, source=str(file) if file else "")
            except InputError as exc:
                msg = str(exc).split(": ", 1)[-1] if file else str(exc)
                raise t.error("x_m", f"{msg} (points are x_m[i], y_m[i])") from None
        else:
            base = pathlib.Path(file).parent if file is not None else pathlib.Path.cwd()
            target = (base / t.str("file")).resolve()
            if not target.is_file():
                raise t.error("file", f"path file {target} does not exist")
            p = read_path_csv(target)
    except InputError as exc:
        if exc.file is not None or file is None:
            raise
        raise InputError(str(exc), file=file, key=name) from None
    t.finish()
    return p


#: words a run takes in place of a path file (``simulate(path=...)``, ``flexpipe run --path``)
PATH_KEYWORDS = {"straight": "straight along x", "road": "the road's reference line"}
_VALID = ("a .csv file of x, y points, a .toml file with a [path] table, or a keyword: "
          + ", ".join(f"'{k}' ({v})" for k, v in PATH_KEYWORDS.items()))


def read_path(path) -> Path:
    """Read a path from a ``.csv`` (x, y points) or a ``.toml`` file with a ``[path]`` table.

    The keywords of :data:`PATH_KEYWORDS` are not files: :func:`flexpipe.vehicle.simulate`
    takes them in place of a path.

    Raises
    ------
    InputError
        No such file (a name without suffix that is not a keyword), an unknown suffix, or
        a bad file; the message lists the file types and the keywords.
    """
    path = pathlib.Path(path)
    suffix = path.suffix.lower()
    if suffix == ".csv":
        return read_path_csv(path)
    if suffix != ".toml":
        if not path.exists():
            near = [p.name for p in (path.with_suffix(".toml"), path.with_suffix(".csv"))
                    if p.is_file()] if path.name else []
            hint = f" (did you mean {near[0]}?)" if near else ""
            raise InputError(f"no such path file, and not a path keyword{hint}; a path is "
                             f"{_VALID}", file=path)
        raise InputError(f"unknown path file type {path.suffix!r}; a path is {_VALID}",
                         file=path)
    doc = read_toml(path)
    if "path" not in doc:
        raise InputError("no [path] table", file=path, key="path")
    return path_from_spec(doc["path"], file=path, name="path")
