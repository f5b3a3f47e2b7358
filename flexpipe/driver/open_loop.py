"""Open-loop steering: a steering-wheel angle against time in place of the path follower.

The standard transient handling manoeuvres drive the steering wheel by a prescribed
input, not along a path: a step steer (ISO 7401), a ramp steer at constant speed (ISO
13674-2; also a handling diagram), a sine with dwell (UN R140 / FMVSS 126 electronic
stability control test), a sine (ISO 7401 frequency response) or any table.  A driver
file gives it as its ``[steering]`` table, e.g. ``paths/driver_step_steer.toml``::

    [steering]
    type = "open_loop"
    input = "step"
    steering_wheel_deg = 40.0   # positive to the left
    t_start_s = 1.0
    rise_time_s = 0.15

``input`` is ``step`` (``steering_wheel_deg``, ``t_start_s`` = 1, ``rise_time_s`` =
0.15), ``ramp`` (``rate_deg_per_s``, ``max_deg``, ``t_start_s`` = 1), ``sine_with_dwell``
(``amplitude_deg``, ``frequency_hz`` = 0.7, ``dwell_s`` = 0.5, ``t_start_s`` = 1,
``direction`` = "left": the first half-wave's side), ``sine`` (``amplitude_deg``,
``frequency_hz``, ``cycles`` = 1, ``t_start_s`` = 1) or ``table`` (``time_s``,
``steering_wheel_deg`` lists).  The angle is linear between points and held after the
last; the car's steering ratio turns it into the road-wheel angle, and its actuator's
rate limit applies.  The speed controller (the file's ``[speed]`` table, or the car's
default) keeps the speed as it does with a path.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexpipe._arrays import readonly
from flexpipe.errors import InputError

INPUTS = ("step", "ramp", "sine_with_dwell", "sine", "table")


@dataclasses.dataclass(frozen=True, eq=False)
class OpenLoopSteer:
    """A steering-wheel angle ``angle`` (rad, positive left) at times ``t`` (s).

    Build it with :meth:`from_table` or a constructor (:meth:`step`, :meth:`ramp`,
    :meth:`sine_with_dwell`, :meth:`sine`), or from a driver file (:meth:`from_dict`).
    ``path`` is only the reference the run's ``lateral_error`` channel is measured
    from (:meth:`with_path`).
    """

    t: np.ndarray
    angle: np.ndarray
    kind: str = "table"
    source: str = ""
    path: object = dataclasses.field(default=None, repr=False)

    @classmethod
    def from_table(cls, t, angle, *, kind: str = "table", source: str = "") -> OpenLoopSteer:
        """A validated input: ``t`` from 0, strictly increasing; finite angles (rad)."""
        where = source or None
        t, a = _time_table(t, angle, what="steering input", values="angles",
                           key="steering_wheel_deg", where=where)
        if np.abs(a).max() > math.radians(1080.0):
            i = int(np.argmax(np.abs(a)))
            raise InputError(f"entry {i} is {math.degrees(a[i]):g} deg; a steering wheel "
                             "turns at most 1080 deg (3 turns) either way (degrees, not "
                             "radians, are expected)", file=where, key="steering_wheel_deg")
        return cls(t=readonly(t), angle=readonly(a), kind=kind, source=source)

    # ------------------------------------------------------------------ standard inputs
    @classmethod
    def step(cls, angle_deg: float, *, t_start: float = 1.0,
             rise_time: float = 0.15) -> OpenLoopSteer:
        """Step steer (ISO 7401): 0 until ``t_start``, a linear rise to ``angle_deg`` over
        ``rise_time`` (ISO 7401 asks for at most 0.15 s), then held."""
        _check(t_start=t_start, rise_time=rise_time)
        a = math.radians(angle_deg)
        return cls.from_table([0.0, t_start, t_start + rise_time], [0.0, 0.0, a],
                              kind="step", source=f"step {angle_deg:g} deg")

    @classmethod
    def ramp(cls, rate_deg_per_s: float, *, max_deg: float,
             t_start: float = 1.0) -> OpenLoopSteer:
        """Ramp steer: from ``t_start`` at ``rate_deg_per_s`` up to ``max_deg``."""
        _check(t_start=t_start, rate=rate_deg_per_s)
        if max_deg * rate_deg_per_s <= 0.0:
            raise InputError(f"ramp steer: max_deg = {max_deg:g} must be nonzero and have "
                             f"the sign of rate_deg_per_s = {rate_deg_per_s:g}", key="max_deg")
        t1 = t_start + max_deg / rate_deg_per_s
        return cls.from_table([0.0, t_start, t1], [0.0, 0.0, math.radians(max_deg)],
                              kind="ramp", source=f"ramp {rate_deg_per_s:g} deg/s")

    @classmethod
    def sine_with_dwell(cls, amplitude_deg: float, *, frequency: float = 0.7,
                        dwell: float = 0.5, t_start: float = 1.0,
                        direction: str = "left") -> OpenLoopSteer:
        """Sine with dwell (UN R140, FMVSS 126): a sine of ``frequency`` whose second
        peak (at 3/4 of the period) is held for ``dwell`` seconds before the last
        quarter wave returns to 0."""
        _check(t_start=t_start, frequency=frequency)
        if not (math.isfinite(dwell) and dwell >= 0.0):
            raise InputError(f"sine with dwell: dwell_s = {dwell!r}; give >= 0 s", key="dwell_s")
        sign = _sign(direction)
        T = 1.0 / frequency
        tau = np.linspace(0.0, 0.75 * T, 151)
        first = np.sin(2 * np.pi * frequency * tau)
        tau2 = np.linspace(0.75 * T, T, 51)[1:]
        t, a = _at_rest_before(t_start, np.concatenate([tau, dwell + tau2]),
                               np.concatenate([first, np.sin(2 * np.pi * frequency * tau2)]))
        return cls.from_table(t, sign * math.radians(amplitude_deg) * a,
                              kind="sine_with_dwell",
                              source=f"sine with dwell {amplitude_deg:g} deg, "
                                     f"{frequency:g} Hz, dwell {dwell:g} s")

    @classmethod
    def sine(cls, amplitude_deg: float, *, frequency: float, cycles: float = 1.0,
             t_start: float = 1.0) -> OpenLoopSteer:
        """``cycles`` periods of a sine of ``frequency`` from ``t_start``, then 0."""
        _check(t_start=t_start, frequency=frequency)
        if not (math.isfinite(cycles) and cycles > 0.0):
            raise InputError(f"sine steer: cycles = {cycles!r}; give > 0", key="cycles")
        n = max(20, int(math.ceil(100 * cycles)))
        tau = np.linspace(0.0, cycles / frequency, n + 1)
        t, a = _at_rest_before(t_start, tau, np.sin(2 * np.pi * frequency * tau))
        return cls.from_table(t, math.radians(amplitude_deg) * a, kind="sine",
                              source=f"sine {amplitude_deg:g} deg, {frequency:g} Hz")

    @classmethod
    def from_dict(cls, table: dict, *, file=None, name: str = "steering") -> OpenLoopSteer:
        """From a driver file's ``[steering]`` table with ``type = "open_loop"`` (keys in
        the module notes)."""
        from flexpipe.roads._tables import TableReader

        t = TableReader(table, file=file, name=name)
        t.str("type", choices=("open_loop",))
        kind = t.str("input", choices=INPUTS)
        start = t.float("t_start_s", 1.0, nonnegative=True) if kind != "table" else 0.0
        try:
            if kind == "step":
                obj = cls.step(t.float("steering_wheel_deg"), t_start=start,
                               rise_time=t.float("rise_time_s", 0.15, positive=True))
            elif kind == "ramp":
                obj = cls.ramp(t.float("rate_deg_per_s"), max_deg=t.float("max_deg"),
                               t_start=start)
            elif kind == "sine_with_dwell":
                obj = cls.sine_with_dwell(t.float("amplitude_deg", positive=True),
                                          frequency=t.float("frequency_hz", 0.7, positive=True),
                                          dwell=t.float("dwell_s", 0.5, nonnegative=True),
                                          t_start=start,
                                          direction=t.str("direction", "left",
                                                          choices=("left", "right")))
            elif kind == "sine":
                obj = cls.sine(t.float("amplitude_deg", positive=True),
                               frequency=t.float("frequency_hz", positive=True),
                               cycles=t.float("cycles", 1.0, positive=True), t_start=start)
            else:
                ts, deg = t.float_list("time_s"), t.float_list("steering_wheel_deg")
                obj = cls.from_table(ts, np.radians(deg), source=str(file or ""))
        except InputError as exc:
            key = f"{name}.{exc.key}" if exc.key else name
            raise InputError(exc.message, file=file, key=key) from None
        t.finish()
        return dataclasses.replace(obj, source=f"{obj.source} ({file})" if file and
                                   kind != "table" else obj.source)

    # ------------------------------------------------------------------ use
    def with_path(self, path) -> OpenLoopSteer:
        """A copy whose ``lateral_error`` reference is ``path``."""
        return dataclasses.replace(self, path=path)

    def steering_wheel(self, t: float) -> float:
        """Steering-wheel angle at time ``t`` (rad; the first and last values held)."""
        return float(np.interp(t, self.t, self.angle))

    @property
    def end_time(self) -> float:
        """Time of the last point (s)."""
        return float(self.t[-1])

    def describe(self) -> str:
        return f"open-loop steering: {self.source or self.kind}"


def _at_rest_before(t_start: float, tau, a):
    """The input ``a`` at times ``t_start + tau`` (``tau`` from 0), led by a point at rest
    at t = 0 when it starts later."""
    if t_start > 0.0:
        return np.concatenate([[0.0], t_start + tau]), np.concatenate([[0.0], a])
    return tau, a


def _time_table(t, v, *, what: str, values: str, key: str, where):
    """``(t, v)`` as float arrays after the checks every open-loop table gets: as many
    values as times (>= 1), all finite, times from >= 0 and strictly increasing; errors
    name ``where`` and the key (``time_s`` or ``key``)."""
    t = np.asarray(t, dtype=float).reshape(-1)
    v = np.asarray(v, dtype=float).reshape(-1)
    if t.size < 1 or t.shape != v.shape:
        raise InputError(f"an open-loop {what} needs >= 1 point and as many {values} as "
                         f"times, got {t.size} and {v.size}", file=where, key="time_s")
    for name, arr in (("time_s", t), (key, v)):
        bad = np.flatnonzero(~np.isfinite(arr))
        if bad.size:
            raise InputError(f"entry {bad[0]} is {arr[bad[0]]!r}; every value must be a "
                             "finite number", file=where, key=name)
    if t[0] < 0.0:
        raise InputError(f"the first time is {t[0]:g} s; times start at >= 0", file=where,
                         key="time_s")
    step = np.flatnonzero(np.diff(t) <= 0.0)
    if step.size:
        i = int(step[0]) + 1
        raise InputError(f"entry {i} ({t[i]:g} s) does not exceed entry {i - 1} "
                         f"({t[i - 1]:g} s); time_s must increase strictly", file=where,
                         key="time_s")
    return t, v


def _sign(direction: str) -> float:
    if direction not in ("left", "right"):
        raise InputError(f"direction must be 'left' or 'right', got {direction!r}",
                         key="direction")
    return 1.0 if direction == "left" else -1.0


def _check(*, t_start: float, rise_time: float = 1.0, rate: float = 1.0,
           frequency: float = 1.0) -> None:
    for key, value, ok in (("t_start_s", t_start, t_start >= 0.0),
                           ("rise_time_s", rise_time, rise_time > 0.0),
                           ("rate_deg_per_s", rate, rate != 0.0),
                           ("frequency_hz", frequency, frequency > 0.0)):
        if not (math.isfinite(value) and ok):
            raise InputError(f"{key} = {value!r} is out of range", key=key)


@dataclasses.dataclass(frozen=True, eq=False)
class OpenLoopTorque:
    """A total wheel torque against time in place of the speed controller (N m; drive > 0
    on the driven wheels, brake < 0 on all four by the brake split), e.g. a brake
    application in a turn or a launch.  From a driver file's ``[speed]`` table::

        [speed]
        type = "open_loop"
        time_s = [0.0, 2.0, 2.2, 5.0]
        torque_Nm = [0.0, 0.0, -3000.0, -3000.0]

    Linear between the points, held after the last.  :meth:`torque` has the
    :class:`~flexpipe.driver.SpeedPI` signature; the car's controller calls
    :meth:`torque_at` with the time instead.
    """

    t: np.ndarray
    value: np.ndarray
    source: str = ""

    @classmethod
    def from_table(cls, t, torque, *, source: str = "") -> OpenLoopTorque:
        """A validated table: times from >= 0, strictly increasing; finite torques."""
        t, q = _time_table(t, torque, what="torque", values="torques", key="torque_Nm",
                           where=source or None)
        return cls(t=readonly(t), value=readonly(q), source=source)

    @classmethod
    def from_dict(cls, table: dict, *, file=None, name: str = "speed") -> OpenLoopTorque:
        """From a driver file's ``[speed]`` table with ``type = "open_loop"``."""
        from flexpipe.roads._tables import TableReader

        t = TableReader(table, file=file, name=name)
        t.str("type", choices=("open_loop",))
        ts, q = t.float_list("time_s"), t.float_list("torque_Nm")
        t.finish()
        try:
            return cls.from_table(ts, q, source=str(file or ""))
        except InputError as exc:
            raise InputError(exc.message, file=file, key=f"{name}.{exc.key}") from None

    def torque_at(self, t: float) -> float:
        """Total wheel torque at time ``t`` (N m)."""
        return float(np.interp(t, self.t, self.value))

    def torque(self, v_target, v, dt, a_target=0.0) -> float:  # noqa: ARG002 - SpeedPI's
        """The torque at t = 0 (the car's controller uses :meth:`torque_at`)."""
        return self.torque_at(0.0)

    def reset(self) -> None:
        """Nothing to clear (:class:`~flexpipe.driver.SpeedPI` has an integral)."""

    def describe(self) -> str:
        return f"open-loop torque ({self.source or 'table'})"
