"""Target speed along a run: a table of speed against time or against distance travelled.

A run at constant speed takes a number (``simulate(speed=20.0)``); braking, launch,
accelerate-and-cruise or a measured drive take a :class:`SpeedProfile`, e.g. from a file::

    # speeds/brake_100_0.toml: 100 km/h for 2 s, then 6 m/s^2 to a stop
    [speed_profile]
    time_s = [0.0, 2.0, 6.63]
    speed_kmh = [100.0, 100.0, 0.0]

or ``distance_m = [...]`` in place of ``time_s`` (distance the car has travelled since the
start), or a CSV file with a header naming ``time_s`` or ``distance_m`` and ``speed_kmh``
or ``speed_mps``.  The speed is linear between the points and held beyond the last one.
The driver's speed controller follows it with a feed-forward torque for the profile's
acceleration (:class:`flexpipe.driver.SpeedPI`); the run starts at the profile's first
speed.
"""

from __future__ import annotations

import dataclasses
import math
import pathlib

import numpy as np

from flexpipe._arrays import readonly
from flexpipe.errors import InputError

#: the abscissae a profile may be given against, with their column/key names
BASES = {"time": "time_s", "distance": "distance_m"}
#: speed columns and their factor to m/s
SPEED_KEYS = {"speed_kmh": 1.0 / 3.6, "speed_mps": 1.0}


@dataclasses.dataclass(frozen=True, eq=False)
class SpeedProfile:
    """Target speed ``v`` (m/s) at points ``x`` of time (s) or distance travelled (m).

    Build it with :meth:`from_table`, which validates; read one with
    :func:`read_speed_profile`.

    Attributes
    ----------
    x : ndarray, shape (n,)
        Strictly increasing, starting at 0.
    v : ndarray, shape (n,)
        Target speeds (m/s), >= 0.
    basis : {"time", "distance"}
    source : str
        The file it came from (or a description).
    """

    x: np.ndarray
    v: np.ndarray
    basis: str
    source: str = ""

    @classmethod
    def from_table(cls, x, v, *, basis: str = "time", source: str = "",
                   speed_max: float = math.inf) -> SpeedProfile:
        """A validated profile; errors name ``source`` and the first bad entry."""
        where = source or None
        if basis not in BASES:
            raise InputError(f"speed profile basis {basis!r}; valid: {', '.join(BASES)}",
                             file=where)
        col = BASES[basis]
        x = np.asarray(x, dtype=float).reshape(-1)
        v = np.asarray(v, dtype=float).reshape(-1)
        if x.size < 1 or x.shape != v.shape:
            raise InputError(f"a speed profile needs >= 1 point and as many speeds as "
                             f"{col} values, got {x.size} and {v.size}", file=where, key=col)
        for name, arr in ((col, x), ("speed", v)):
            bad = np.flatnonzero(~np.isfinite(arr))
            if bad.size:
                raise InputError(f"entry {bad[0]} is {arr[bad[0]]!r}; every value must be a "
                                 "finite number", file=where, key=name)
        if x[0] != 0.0:
            raise InputError(f"the first {col} value is {x[0]:g}; a profile starts at 0 "
                             "(the start of the run)", file=where, key=col)
        step = np.flatnonzero(np.diff(x) <= 0.0)
        if step.size:
            i = int(step[0]) + 1
            raise InputError(f"entry {i} ({x[i]:g}) does not exceed entry {i - 1} "
                             f"({x[i - 1]:g}); {col} must increase strictly", file=where,
                             key=col)
        bad = np.flatnonzero((v < 0.0) | (v > speed_max))
        if bad.size:
            i = int(bad[0])
            raise InputError(f"entry {i} is {v[i] * 3.6:g} km/h; speeds lie in 0 .. "
                             f"{speed_max * 3.6:g} km/h (reverse driving is not modelled)",
                             file=where, key="speed")
        if basis == "distance" and v[0] <= 0.0:
            raise InputError("entry 0 is 0 km/h: a car at rest travels no distance, so a "
                             "profile against distance_m never leaves its first point; "
                             "start above 0 or give a launch against time_s", file=where,
                             key="speed")
        return cls(x=readonly(x), v=readonly(v), basis=basis, source=source)

    @classmethod
    def constant(cls, speed: float) -> SpeedProfile:
        """The profile of a run at constant ``speed`` (m/s)."""
        return cls.from_table([0.0], [speed], source=f"{speed * 3.6:g} km/h")

    @property
    def initial(self) -> float:
        """Speed at the start (m/s)."""
        return float(self.v[0])

    @property
    def maximum(self) -> float:
        """Highest speed (m/s)."""
        return float(self.v.max())

    @property
    def is_constant(self) -> bool:
        return bool(np.all(self.v == self.v[0]))

    def at(self, x: float) -> tuple[float, float]:
        """Target speed (m/s) and its slope ``dv/dx`` at ``x`` (time or distance)."""
        xs, vs = self.x, self.v
        if xs.size == 1 or x >= xs[-1]:
            return float(vs[-1]), 0.0
        if x <= 0.0:
            x = 0.0
        i = int(np.searchsorted(xs, x, side="right")) - 1
        slope = (vs[i + 1] - vs[i]) / (xs[i + 1] - xs[i])
        return float(vs[i] + slope * (x - xs[i])), float(slope)

    def target(self, t: float, distance: float) -> tuple[float, float]:
        """Target speed (m/s) and acceleration (m/s^2) at time ``t`` (s) of a car that has
        travelled ``distance`` (m)."""
        if self.basis == "time":
            return self.at(t)
        v, slope = self.at(distance)
        return v, slope * v

    def distance(self, t_end: float) -> float:
        """Distance (m) a car exactly on the profile travels in ``t_end`` seconds."""
        if self.basis == "time":
            t = np.union1d(self.x[self.x < t_end], [0.0, t_end])
            v = np.interp(t, self.x, self.v)
            return float(np.sum(0.5 * (v[1:] + v[:-1]) * np.diff(t)))
        # ds/dt = v(s), midpoint rule on a fine grid (used for path-length checks)
        n = 2000
        dt = t_end / n
        s = 0.0
        for _ in range(n):
            s_mid = s + 0.5 * dt * self.at(s)[0]
            s += dt * self.at(s_mid)[0]
        return s

    def describe(self) -> str:
        """One line for run logs and summaries."""
        unit = "s" if self.basis == "time" else "m"
        pts = ", ".join(f"{v * 3.6:g} km/h at {x:g} {unit}" for x, v in zip(self.x, self.v,
                                                                            strict=True))
        return f"speed profile ({pts})" if self.x.size > 1 else f"{self.v[0] * 3.6:g} km/h"


def profile_text(profile: SpeedProfile, *, file=None) -> str:
    """Summary for ``flexpipe info``: basis, range, points, steepest acceleration and
    deceleration, and the distance covered at the last point."""
    unit = "s" if profile.basis == "time" else "m"
    lines = [f"{file or profile.source}: speed profile against "
             f"{'time' if profile.basis == 'time' else 'distance travelled'}, "
             f"{profile.x.size} points, {profile.x[-1]:g} {unit}",
             f"  speed {profile.v.min() * 3.6:.4g} .. {profile.maximum * 3.6:.4g} km/h, "
             f"starting at {profile.initial * 3.6:.4g} km/h, held at "
             f"{profile.v[-1] * 3.6:.4g} km/h after the last point"]
    if profile.x.size > 1:
        slope = np.diff(profile.v) / np.diff(profile.x)
        if profile.basis == "distance":  # dv/dt = v dv/ds, largest at the piece's ends
            slope = slope * np.maximum(profile.v[:-1], profile.v[1:])
        t_end = profile.x[-1] if profile.basis == "time" else None
        lines.append(f"  acceleration {slope.min():.3g} .. {slope.max():.3g} m/s^2"
                     + (f" ({slope.min() / 9.81:.3g} .. {slope.max() / 9.81:.3g} g)"))
        if t_end is not None:
            lines.append(f"  distance at {t_end:g} s: {profile.distance(t_end):.4g} m")
    return "\n".join(lines)


def profile_file_text(path) -> str:
    """:func:`profile_text` of the profile file ``path`` (``flexpipe info``)."""
    return profile_text(read_speed_profile(path), file=path)


def profile_from_spec(table: dict, *, file=None, name: str = "speed_profile",
                      speed_max: float = math.inf) -> SpeedProfile:
    """A profile from a TOML table: ``time_s`` or ``distance_m``, and ``speed_kmh`` or
    ``speed_mps`` lists."""
    from flexpipe.roads._tables import TableReader

    t = TableReader(table, file=file, name=name)
    given = [b for b, key in BASES.items() if t.has(key)]
    if len(given) != 1:
        raise t.error("time_s", "give exactly one of time_s or distance_m (the points the "
                      f"speeds are at), found {len(given)}")
    speeds = [k for k in SPEED_KEYS if t.has(k)]
    if len(speeds) != 1:
        raise t.error("speed_kmh", f"give exactly one of {' or '.join(SPEED_KEYS)}, found "
                      f"{len(speeds)}")
    basis, skey = given[0], speeds[0]
    x = t.float_list(BASES[basis])
    v = [s * SPEED_KEYS[skey] for s in t.float_list(skey)]
    t.finish()
    src = str(file) if file is not None else ""
    try:
        return SpeedProfile.from_table(x, v, basis=basis, source=src, speed_max=speed_max)
    except InputError as exc:
        key = skey if exc.key == "speed" else exc.key
        raise InputError(exc.message, file=file, key=f"{name}.{key}") from None


def read_speed_profile(path, *, speed_max: float = math.inf) -> SpeedProfile:
    """Read a profile from a ``.toml`` file (``[speed_profile]`` table) or a ``.csv`` file
    (header: ``time_s`` or ``distance_m``, then ``speed_kmh`` or ``speed_mps``)."""
    from flexpipe._io import read_numeric_table
    from flexpipe.roads._tables import read_toml

    path = pathlib.Path(path)
    suffix = path.suffix.lower()
    if suffix == ".toml":
        doc = read_toml(path)
        if "speed_profile" not in doc:
            raise InputError("no [speed_profile] table", file=path, key="speed_profile")
        return profile_from_spec(doc["speed_profile"], file=path, speed_max=speed_max)
    if suffix != ".csv":
        raise InputError(f"unknown speed profile file type {path.suffix!r}; a speed profile "
                         "is a .toml file with a [speed_profile] table or a .csv file",
                         file=path)
    if not path.is_file():
        raise InputError("no such speed profile file", file=path)
    valid = f"'{BASES['time']}' or '{BASES['distance']}', then " + \
        " or ".join(f"'{k}'" for k in SPEED_KEYS)
    table = read_numeric_table(path, kind="speed profile", columns=valid)
    header = [h.strip().lower() for h in (table.header or [])]
    by_col = {v: k for k, v in BASES.items()}
    if len(header) != 2 or header[0] not in by_col or header[1] not in SPEED_KEYS:
        raise InputError(f"header {table.header!r}; a speed profile's header names two "
                         f"columns: {valid}", file=path, line=table.header_line or 1)
    xs, vs = [], []
    for k, _text, values in table.rows:
        if len(values) != 2:
            raise InputError(f"{len(values)} columns; expected 2 ({header[0]}, {header[1]})",
                             file=path, line=k)
        xs.append(values[0])
        vs.append(values[1] * SPEED_KEYS[header[1]])
    try:
        return SpeedProfile.from_table(xs, vs, basis=by_col[header[0]], source=str(path),
                                       speed_max=speed_max)
    except InputError as exc:
        i = None
        if exc.message.startswith("entry "):
            i = int(exc.message.split()[1])
        line = table.rows[i][0] if i is not None and i < len(table.rows) else None
        raise InputError(exc.message, file=path, line=line) from None
