"""Driver controllers: pure-pursuit steering and a PI speed controller.

Both read their gains from a TOML table (``from_dict``), e.g. ``paths/driver.toml``::

    [steering]
    wheelbase_m = 2.7
    lookahead_base_m = 2.0      # preview distance at standstill
    lookahead_time_s = 0.2      # + this time times the speed
    max_steer_rad = 0.6
    rear_axle_offset_m = 1.3    # reference point -> rear axle, along the body x axis

    [speed]
    kp_Nm_s_per_m = 600.0
    ki_Nm_per_m = 150.0
    drive_torque_max_Nm = 3000.0
    brake_torque_max_Nm = 8000.0
    integral_band_mps = 1.0     # optional; integrate only within this speed error
    feedforward_Nm_s2_per_m = 0.0  # optional; torque per m/s^2 of the target's acceleration
    neuromuscular_lag_s = 0.1   # optional; the foot's first-order lag (0: none)

Both commands pass a first-order lag, the driver's neuromuscular system (the lag of
McRuer's quasi-linear models of a human controller, of the order of 0.1 s; McRuer and
Krendel, *Mathematical models of human pilot behavior*, AGARDograph 188, 1974).  Without
it the pure pursuit, which acts on the pose predicted 0.3 s ahead, passes the body's
road-excited roll and yaw vibration to the steering: on the sample sedan (ISO C, 70 km/h,
rigid body, 10 s) 1.4 mrad RMS of road-wheel angle at 8-20 Hz, beyond any human driver's
bandwidth, and the front lateral hub force's 8-20 Hz content 67.8 N RMS against 55.4 N with
the steering held (52.5 N with the lag; 10 s runs of ``make straight``'s case, 2026-12-03;
``tests/test_driver_lag.py`` checks the same on 3 s runs).
"""

from __future__ import annotations

import dataclasses
import math
import pathlib

from flexpipe.driver.path import Path
from flexpipe.errors import InputError
from flexpipe.roads._tables import TableReader, read_toml


@dataclasses.dataclass(frozen=True)
class PurePursuit:
    """Pure-pursuit path follower with speed-dependent preview.

    The rear-axle centre ``R`` is projected onto the path; the goal point lies
    ``Ld = lookahead_base + lookahead_time * |v|`` further along it (on the straight
    continuation beyond the path end).  The road-wheel angle of a bicycle of wheelbase
    ``L`` whose rear axle moves on the circle through ``R`` and the goal point is
    ``delta = atan(2 L sin(alpha) / d)``, ``alpha`` the bearing of the goal relative to the
    heading and ``d`` its distance (Coulter, CMU-RI-TR-92-01, 1992).

    Parameters
    ----------
    wheelbase : float
        Wheelbase ``L`` (m).
    lookahead_base : float
        Preview distance at zero speed (m).
    lookahead_time : float
        Preview time (s); the preview grows by ``lookahead_time * |v|``.
    max_steer : float
        Road-wheel angle limit (rad).
    rear_axle_offset : float
        Distance from the vehicle reference point back to the rear-axle centre (m), so
        that :meth:`steer` can take the reference point's position.
    neuromuscular_lag : float
        Time constant (s) of the first-order lag between the law's angle and the
        steering the driver applies (:class:`FirstOrderLag`; 0: none).
    path : Path, optional
        The path to follow; gains come from data without one, then
        :meth:`with_path` binds it.
    """

    wheelbase: float
    lookahead_base: float = 2.0
    lookahead_time: float = 0.2
    max_steer: float = 0.6
    rear_axle_offset: float = 0.0
    neuromuscular_lag: float = 0.1
    path: Path | None = dataclasses.field(default=None, repr=False)

    def __post_init__(self):
        checks = (("wheelbase", self.wheelbase, 0.0, False),
                  ("lookahead_base", self.lookahead_base, 0.0, False),
                  ("lookahead_time", self.lookahead_time, 0.0, True),
                  ("max_steer", self.max_steer, 0.0, False),
                  ("rear_axle_offset", self.rear_axle_offset, -math.inf, True),
                  ("neuromuscular_lag", self.neuromuscular_lag, 0.0, True))
        for name, value, lo, closed in checks:
            ok = math.isfinite(value) and (value >= lo if closed else value > lo)
            if not ok or (name == "max_steer" and value >= math.pi / 2):
                raise InputError(f"PurePursuit: {name} = {value!r} is out of range")

    @classmethod
    def from_dict(cls, table: dict, *, file=None, name: str = "steering") -> PurePursuit:
        """Build from a ``[steering]`` table (keys in the module notes)."""
        t = TableReader(table, file=file, name=name)
        kind = t.str("type", "pure_pursuit", choices=("pure_pursuit", "open_loop"))
        del kind
        obj = cls(wheelbase=t.float("wheelbase_m", positive=True),
                  lookahead_base=t.float("lookahead_base_m", 2.0, positive=True),
                  lookahead_time=t.float("lookahead_time_s", 0.2, nonnegative=True),
                  max_steer=t.float("max_steer_rad", 0.6, positive=True, hi=1.5),
                  rear_axle_offset=t.float("rear_axle_offset_m", 0.0),
                  neuromuscular_lag=t.float("neuromuscular_lag_s", 0.1, nonnegative=True,
                                            hi=1.0))
        t.finish()
        return obj

    def with_path(self, path: Path) -> PurePursuit:
        """A copy of this controller that follows ``path``."""
        if not isinstance(path, Path):
            raise InputError(f"PurePursuit.with_path needs a flexpipe.driver.Path, got "
                             f"{type(path).__name__}")
        return dataclasses.replace(self, path=path)

    def describe(self) -> str:
        """One line for a run's ``info["steering"]`` and ``summary.json``."""
        return (f"path follower: pure pursuit, preview {self.lookahead_base:g} m + "
                f"{self.lookahead_time:g} s x speed, neuromuscular lag "
                f"{self.neuromuscular_lag:g} s")

    def lookahead(self, v: float) -> float:
        """Preview distance at speed ``v`` (m)."""
        return self.lookahead_base + self.lookahead_time * abs(v)

    def steer(self, x: float, y: float, yaw: float, v: float) -> float:
        """Road-wheel angle (rad, positive left) for the reference point at ``(x, y)``.

        Parameters
        ----------
        x, y : float
            Position of the vehicle reference point (m).
        yaw : float
            Heading of the vehicle body x axis (rad).
        v : float
            Forward speed (m/s).
        """
        path = self.path
        if path is None:
            raise InputError("PurePursuit has no path; call with_path(path) first")
        c, s = math.cos(yaw), math.sin(yaw)
        rx = x - self.rear_axle_offset * c
        ry = y - self.rear_axle_offset * s
        s_rear, _ = path.project(rx, ry)
        gx, gy = path.point_at(s_rear + self.lookahead(v))
        dx, dy = gx - rx, gy - ry
        d = math.hypot(dx, dy)
        alpha = math.atan2(dy, dx) - yaw
        delta = math.atan2(2.0 * self.wheelbase * math.sin(alpha), d)
        return max(-self.max_steer, min(self.max_steer, delta))


@dataclasses.dataclass
class SpeedPI:
    """PI speed controller producing a total wheel torque (drive > 0, brake < 0).

    ``T = kp e + ki I + kff a_target``, ``e = v_target - v``, ``a_target`` the
    acceleration of a speed profile (:class:`flexpipe.driver.speed.SpeedProfile`; 0 at
    constant speed), clamped to
    ``[-brake_torque_max, drive_torque_max]``.  Anti-windup by conditional integration:
    the integral ``I`` of ``e`` only changes while the output is not saturated in the
    direction of ``e`` and ``|e| <= integral_band`` (integral separation: during a large
    speed change the P part acts alone, so the integral does not collect the whole
    transient and overshoot).  The controller keeps ``I`` between calls (the only mutable
    object in :mod:`flexpipe.driver`); :meth:`reset` clears it.

    Parameters
    ----------
    kp : float
        Proportional gain (N m per m/s).
    ki : float
        Integral gain (N m per m).
    drive_torque_max, brake_torque_max : float
        Torque limits (N m), both > 0.
    integral_band : float
        Speed error (m/s) above which the integral is frozen; ``inf`` disables this.
    feedforward : float
        Torque per target acceleration (N m s^2/m): the car's mass times its wheel radius
        (plus the wheels' spin inertia over the radius) makes a profile's ramp need no
        speed error; 0 leaves it to the PI part.
    neuromuscular_lag : float
        Time constant (s) of the first-order lag between the controller's torque and the
        torque the driver's foot asks for (:class:`FirstOrderLag`; 0: none).
    """

    kp: float
    ki: float
    drive_torque_max: float
    brake_torque_max: float
    integral_band: float = math.inf
    feedforward: float = 0.0
    neuromuscular_lag: float = 0.1
    integral: float = dataclasses.field(default=0.0, compare=False)

    def __post_init__(self):
        for name in ("kp", "ki", "drive_torque_max", "brake_torque_max", "integral_band",
                     "feedforward", "neuromuscular_lag"):
            value = getattr(self, name)
            if math.isnan(value) or value < 0.0 or (math.isinf(value) and name != "integral_band") \
                    or (name.endswith(("max", "band")) and value == 0.0):
                raise InputError(f"SpeedPI: {name} = {value!r} is out of range")

    @classmethod
    def from_dict(cls, table: dict, *, file=None, name: str = "speed") -> SpeedPI:
        """Build from a ``[speed]`` table (keys in the module notes)."""
        t = TableReader(table, file=file, name=name)
        obj = cls(kp=t.float("kp_Nm_s_per_m", nonnegative=True),
                  ki=t.float("ki_Nm_per_m", nonnegative=True),
                  drive_torque_max=t.float("drive_torque_max_Nm", positive=True),
                  brake_torque_max=t.float("brake_torque_max_Nm", positive=True),
                  integral_band=t.float("integral_band_mps", math.inf, positive=True),
                  feedforward=t.float("feedforward_Nm_s2_per_m", 0.0, nonnegative=True),
                  neuromuscular_lag=t.float("neuromuscular_lag_s", 0.1, nonnegative=True,
                                            hi=1.0))
        t.finish()
        return obj

    def describe(self) -> str:
        """One line for a run's ``info["speed_control"]`` and ``summary.json``."""
        return (f"PI speed control: kp {self.kp:.4g} N m s/m, ki {self.ki:.4g} N m/m, "
                f"feed-forward {self.feedforward:.4g} N m s^2/m, neuromuscular lag "
                f"{self.neuromuscular_lag:g} s")

    def reset(self) -> None:
        """Clear the integral state."""
        self.integral = 0.0

    def torque(self, v_target: float, v: float, dt: float, a_target: float = 0.0) -> float:
        """Total wheel torque for this step (N m); ``dt`` is the step since the last call,
        ``a_target`` the target's acceleration (m/s^2)."""
        e = v_target - v
        trial = self.integral + e * dt if (dt > 0.0 and abs(e) <= self.integral_band) \
            else self.integral
        raw = self.kp * e + self.ki * trial + self.feedforward * a_target
        if raw > self.drive_torque_max:
            out = self.drive_torque_max
            if e < 0.0:
                self.integral = trial
        elif raw < -self.brake_torque_max:
            out = -self.brake_torque_max
            if e > 0.0:
                self.integral = trial
        else:
            out = raw
            self.integral = trial
        return out

    def lagged(self, torque: float, a_target: float, lag, dt: float) -> float:
        """This controller's ``torque`` (at the target acceleration ``a_target``) with its
        feedback part through ``lag`` (a :class:`FirstOrderLag` sampled every ``dt``):
        a speed profile's feed-forward is the driver's plan and passes as planned.
        Clamped to the torque limits."""
        ff = self.feedforward * a_target
        out = lag(torque - ff, dt) + ff
        return min(self.drive_torque_max, max(-self.brake_torque_max, out))


@dataclasses.dataclass
class FirstOrderLag:
    """First-order lag ``T y' = u - y`` of a command sampled every ``dt`` and held
    between samples (its exact update: ``y += (1 - exp(-dt / T)) (u - y)``).

    The first call returns its input (a car started at speed starts in the commands'
    steady state); ``time_constant = 0`` passes every input through.
    """

    time_constant: float
    value: float | None = None

    def __call__(self, u: float, dt: float) -> float:
        if self.value is None or self.time_constant <= 0.0:
            self.value = float(u)
        else:
            self.value += -math.expm1(-dt / self.time_constant) * (float(u) - self.value)
        return self.value


def read_driver(path):
    """Read a driver file: a ``[steering]`` table (pure pursuit, or ``type = "open_loop"``:
    :class:`flexpipe.driver.open_loop.OpenLoopSteer`) and a ``[speed]`` table.

    ``[speed]`` may be left out: the run then uses the car's default speed controller
    (:func:`flexpipe.vehicle.simulation.default_driver`); with ``type = "open_loop"`` it is
    a wheel torque against time (:class:`flexpipe.driver.open_loop.OpenLoopTorque`).

    Returns
    -------
    (PurePursuit or OpenLoopSteer, SpeedPI or OpenLoopTorque or None)
    """
    path = pathlib.Path(path)
    doc = read_toml(path)
    if "steering" not in doc:
        raise InputError("no [steering] table", file=path, key="steering")
    extra = sorted(set(doc) - {"steering", "speed"})
    if extra:
        raise InputError(f"unknown table(s) {extra}; a driver file has [steering] and "
                         "[speed]", file=path, key=extra[0])
    table = doc["steering"]
    if isinstance(table, dict) and table.get("type") == "open_loop":
        from flexpipe.driver.open_loop import OpenLoopSteer

        steering = OpenLoopSteer.from_dict(table, file=path)
    else:
        steering = PurePursuit.from_dict(table, file=path)
    speed = None
    if "speed" in doc:
        table = doc["speed"]
        if isinstance(table, dict) and table.get("type") == "open_loop":
            from flexpipe.driver.open_loop import OpenLoopTorque

            speed = OpenLoopTorque.from_dict(table, file=path)
        else:
            speed = SpeedPI.from_dict(table, file=path)
    return steering, speed
