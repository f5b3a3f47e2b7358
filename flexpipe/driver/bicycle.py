"""Kinematic bicycle test vehicle for checking the driver without the full car.

State: position ``(x, y)`` of the reference point (the centre of gravity, ``rear_to_cg``
ahead of the rear axle), yaw ``psi`` and speed ``v``.  With road-wheel angle ``delta``
and the slip angle of the reference point ``beta = atan(rear_to_cg tan(delta) / L)``:

    x' = v cos(psi + beta),   y' = v sin(psi + beta),   psi' = v cos(beta) tan(delta) / L,
    m v' = T / r_w - m g c_rr - 0.5 rho CdA v^2

(Rajamani, Vehicle Dynamics and Control, 2nd ed., section 2.2).  Integration: classic
Runge-Kutta 4 with the controller outputs held over each step (zero-order hold, like a
sampled controller).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexpipe.driver.control import PurePursuit, SpeedPI
from flexpipe.errors import InputError

G = 9.81


@dataclasses.dataclass(frozen=True)
class KinematicBicycle:
    """Parameters of the kinematic bicycle (SI units).

    Parameters
    ----------
    wheelbase : float
        Axle distance ``L`` (m).
    rear_to_cg : float
        Distance from the rear axle to the reference point (m).
    mass : float
        Vehicle mass (kg).
    wheel_radius : float
        Rolling radius ``r_w`` converting wheel torque to force (m).
    rolling_resistance : float
        Rolling-resistance coefficient ``c_rr``.
    drag_area : float
        ``Cd * A`` (m^2); air density 1.2 kg/m^3.
    """

    wheelbase: float = 2.7
    rear_to_cg: float = 1.3
    mass: float = 1500.0
    wheel_radius: float = 0.31
    rolling_resistance: float = 0.012
    drag_area: float = 0.7

    def derivatives(self, state, delta: float, torque: float):
        """Time derivative of ``state = (x, y, psi, v)`` for given inputs."""
        x, y, psi, v = state
        beta = math.atan(self.rear_to_cg * math.tan(delta) / self.wheelbase)
        resist = self.mass * G * self.rolling_resistance * (1.0 if v > 0.0 else 0.0) \
            + 0.6 * self.drag_area * v * abs(v)
        return np.array([v * math.cos(psi + beta), v * math.sin(psi + beta),
                         v * math.cos(beta) * math.tan(delta) / self.wheelbase,
                         (torque / self.wheel_radius - resist) / self.mass])


def simulate(vehicle: KinematicBicycle, steering: PurePursuit, speed: SpeedPI, *,
             v_target: float, t_end: float, dt: float = 0.01, v0: float | None = None,
             state0=None) -> dict:
    """Drive ``vehicle`` along ``steering.path`` at ``v_target`` for ``t_end`` seconds.

    Parameters
    ----------
    vehicle : KinematicBicycle
    steering : PurePursuit
        With a path bound (:meth:`PurePursuit.with_path`).
    speed : SpeedPI
        Speed controller (its state is reset first).
    v_target : float or callable
        Target speed (m/s), or a function of time.
    t_end, dt : float
        Duration and step (s).
    v0 : float, optional
        Initial speed (default ``v_target`` at t = 0).
    state0 : sequence, optional
        Initial ``(x, y, psi)``; default: on the path start, along its heading.

    Returns
    -------
    dict
        Arrays ``t, x, y, psi, v, delta, torque, s, lateral`` (the last two from projecting
        the reference point on the path).

    Raises
    ------
    InputError
        If the path is shorter than the distance the run can cover.
    """
    path = steering.path
    if path is None:
        raise InputError("simulate: the steering controller has no path (use with_path)")
    target = v_target if callable(v_target) else (lambda t, c=float(v_target): c)
    if not (t_end > 0.0 and dt > 0.0):
        raise InputError(f"simulate: need t_end > 0 and dt > 0, got {t_end!r}, {dt!r}")
    n = int(round(t_end / dt)) + 1
    times = np.arange(n) * dt
    v_max = max(abs(target(t)) for t in times[:: max(1, n // 200)])
    v_start = target(0.0) if v0 is None else float(v0)
    path.require_length(max(v_max, abs(v_start)) * t_end,
                        what=f"a {t_end:g} s run at up to {max(v_max, abs(v_start)):.2f} m/s")
    if state0 is None:
        h = float(path.heading[0])
        rear_x, rear_y = float(path.x[0]), float(path.y[0])
        state0 = (rear_x + vehicle.rear_to_cg * math.cos(h),
                  rear_y + vehicle.rear_to_cg * math.sin(h), h)
    state = np.array([*state0, v_start], dtype=float)
    speed.reset()
    out = np.empty((n, 6))
    for k, t in enumerate(times):
        delta = steering.steer(float(state[0]), float(state[1]), float(state[2]),
                               float(state[3]))
        torque = speed.torque(target(t), float(state[3]), dt)
        out[k] = (*state, delta, torque)
        if k == n - 1:
            break
        k1 = vehicle.derivatives(state, delta, torque)
        k2 = vehicle.derivatives(state + 0.5 * dt * k1, delta, torque)
        k3 = vehicle.derivatives(state + 0.5 * dt * k2, delta, torque)
        k4 = vehicle.derivatives(state + dt * k3, delta, torque)
        state = state + dt / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    s, lateral = path.project(out[:, 0], out[:, 1])
    return dict(t=times, x=out[:, 0], y=out[:, 1], psi=out[:, 2], v=out[:, 3],
                delta=out[:, 4], torque=out[:, 5], s=s, lateral=lateral)
