"""Per-step vehicle physics: the linearization of the tyres and the suspension force law for
the implicit step, the driver, the steering geometry and the recording of output channels.

:class:`CarController` is called once per time step with the state read from the
multibody model (:class:`flexpipe.exu.car.CarState`) and returns the loads for the step
(:class:`flexpipe.exu.car.CarLoads`), vectorized over the four corners.  It also records
the output channels into preallocated arrays every ``output_every`` steps.

Output channels (SI units; "body axes" = the chassis frame, ISO 8855 orientation)
-----------------------------------------------------------------------------
``x, y, z`` body-origin position, ``x_rear, y_rear`` rear-axle centre (the point the
driver steers along the path), ``roll, pitch, yaw`` (rad), ``speed`` (body origin, forward),
``steer`` road-wheel angle (rad), ``steering_wheel`` (rad), ``drive_torque`` (N m, total),
``lateral_error`` (m, rear-axle centre from the path), ``ay`` lateral acceleration of the
body origin (m/s^2, body axes, from its velocity), ``speed_target`` (m/s, the driver's),
``wheel_angle_c`` road-wheel angle of each wheel (rad, + left; steer, toe, compliance);
per corner ``c`` in ``fl, fr, rl, rr``: ``hub_c_x|y|z`` force the corner applies to the body
at its hardpoint (N, body axes), ``tire_c_Fx|Fy|Fz`` contact force (N, tyre W-axes),
``travel_c`` suspension jounce (m, + compression), ``spin_c`` wheel spin rate (rad/s);
per named point or seat ``p``: ``acc_p_x|y|z`` acceleration (m/s^2, body axes, no gravity);
linkage cars, per body mount ``m``: ``mount_m_x|y|z`` force the suspension applies to the
body there (N, body axes; ``hub_c_*`` is the sum over the corner's own mounts; on the
subframe for a mount a subframe carries), and the force on the body at every mount of a
powertrain or subframe (``[drive] reaction_mounts``: the drive's reaction couple there).
"""

from __future__ import annotations

import math

import numpy as np

from flexpipe.driver.control import FirstOrderLag
from flexpipe.roads._contact_fast import for_road as contact_for_road
from flexpipe.tires._fast import enabled as _jit_enabled
from flexpipe.vehicle import mounted_motion, sensor_rows, watch
from flexpipe.vehicle._tire_coupling_fast import applied_force
from flexpipe.vehicle.corners import ackermann_angles, road_wheel_angles
from flexpipe.vehicle.reaction_mounts import CoupleSplit
from flexpipe.vehicle.sensor_rows import BUSHING_AXES, Recorder, record_mounts
from flexpipe.vehicle.spec import CORNERS
from flexpipe.vehicle.tire_coupling import ImplicitTires, applied_force_reference

#: half the base of the road normal's central differences (m): the slope a tyre meets
ROAD_NORMAL_HALF_BASE_M = 0.05
#: sign that turns the GenericJoint's ForceLocal into the force on the body (checked against
#: the wheel carriers' Newton law, which gives the hub force after the first step)
JOINT_FORCE_SIGN = 1.0


def _rpy(R: np.ndarray):
    """Roll, pitch, yaw (Tait-Bryan z-y-x) of a body-to-world rotation matrix."""
    yaw = math.atan2(R[1, 0], R[0, 0])
    pitch = -math.asin(max(-1.0, min(1.0, R[2, 0])))
    roll = math.atan2(R[2, 1], R[2, 2])
    return roll, pitch, yaw


class CarController:
    """Tyres, suspension, driver and recording for one run (see module docstring).

    Parameters
    ----------
    corners : CornerArrays
    tires : list of TireModel
        One per corner (the same object may be shared).
    road : Road
        Heights in global coordinates: ``s = x``, ``lateral = y``.
    steering : PurePursuit or OpenLoopSteer
        Bound to the path (the reference of ``lateral_error`` for an open-loop input).
    speed_pi : SpeedPI
    target_speed : float or SpeedProfile
        Constant target speed (m/s; 0 parks the car, wheels braked) or a profile.
    car : Car
        For steering ratio/limits and the drive layout.
    h : float
        Step size, s.
    t_end : float
    output_every : int
        Record every this many steps.
    points : list of str
        Named body points whose accelerations are recorded.
    point_acc : callable
        ``point_acc() -> {name: global acceleration}`` (read from the multibody model).
    body_motion : callable, optional
        ``body_motion() -> (q, p, R)`` recorded at every output row (``Result.motion``).
    driver_dt : float
        Driver (steering and speed controller) sampling period, s, independent of ``h``;
        the driver acts at the first step at or after each sampling instant.  Its
        commands reach the steering actuator and the drive/brake torque through a
        first-order hold: each ramps linearly from where it is to the new command,
        reaching it at the next sampling instant (a continuous steering angle with a
        piecewise-constant rate; a staircase put 40 N at 100 Hz and its harmonics into
        the lateral hub forces of a slalom).
    weight_N : float, optional
        The car's weight, N: a tyre normal force beyond ten times it stops the run
        (:func:`flexpipe.vehicle.watch.tire_problem`); ``None`` checks nothing.
    parked : bool, optional
        Wheels braked, no driver (default: a constant target speed of 0 without an
        open-loop torque).
    """

    #: linkage cars: hub forces from Exudyn's sensor records (see ``_record``)
    hub_sensors = True
    #: named points' accelerations and the body motion from Exudyn's sensor records when
    #: ``output_history`` is given (False: read every row in the step, as the tests compare)
    output_sensors = True

    def __init__(self, *, corners, tires, road, steering, speed_pi, target_speed, car, h, t_end,
                 output_every=2, points=(), point_acc=None, joint_forces=None,
                 wheel_acc=None, gravity=9.81, driver_dt=0.01, body_com=None, track=None,
                 preview_time=0.3, linkage=None,
                 body_motion=None, output_history=None, weight_N=None, parked=None):
        self.c = corners
        self.road = road
        self.steering = steering
        self.open_loop = hasattr(steering, "steering_wheel")  # OpenLoopSteer
        self.speed_pi = speed_pi
        self.profile = target_speed if hasattr(target_speed, "target") else None
        self.v_target = self.profile.initial if self.profile else float(target_speed)
        self.open_torque = hasattr(speed_pi, "torque_at")  # OpenLoopTorque
        self.parked = (self.profile is None and self.v_target == 0.0 and not self.open_torque
                       ) if parked is None else bool(parked)  # (the settle pre-run: True)
        self._odometer = 0.0  # distance travelled (m), for a profile against distance
        self.car = car
        self.h = float(h)
        self.output_every = int(output_every)
        self.linkage = linkage  # LinkageModel of a linkage car (None: prismatic corners)
        self.weight_N = weight_N  # the car's weight, for the tyre-load stop (watch)
        self._compiled = _jit_enabled()  # chosen once per run, as the state reader does
        self._contact = contact_for_road(road, ROAD_NORMAL_HALF_BASE_M, compiled=self._compiled)
        from flexpipe.exu.car import CarLoads  # (Exudyn is imported only for a run)

        self._loads = CarLoads
        self.driver_dt = float(driver_dt)
        self._next_driver_t = 0.0
        self.points = list(points)
        self.point_acc = point_acc
        self.joint_forces = joint_forces
        self.wheel_acc = wheel_acc
        self.body_motion = body_motion  # durability: () -> (q, p, R), one per output row
        #: t -> the points' accelerations and the body motion at the output times t,
        #: recorded by Exudyn (flexpipe.exu.output_sensors.history); rows after the first
        #: are filled from it after the run (fill_from_sensors)
        self.output_history = output_history if self.output_sensors else None
        self.motion = []
        self._first_row = None  # arguments of the t = 0 row (refresh_first_row)
        self.gvec = np.array([0.0, 0.0, -float(gravity)])
        self.preview_time = float(preview_time)
        self._tire_lin = None
        self._prev_rate = None
        self.body_com = np.zeros(3) if body_com is None else np.asarray(body_com, dtype=float)
        groups = {}
        for i, t in enumerate(tires):
            groups.setdefault(id(t), (t, []))[1].append(i)
        self.tire_groups = [(t, np.array(ix)) for t, ix in groups.values()]
        sides = ["left" if n[1] == "l" else "right" for n in CORNERS]
        self.mirror = np.zeros(4, dtype=bool)
        for t, ix in self.tire_groups:
            self.mirror[ix] = t.mirror_for([sides[i] for i in ix])
        self.tires = ImplicitTires(tires, self.mirror)
        st = car.steering
        self.steered = [car.corners[i].axle == st.axle for i in range(4)]
        self.max_angle = st.max_wheel_angle
        self.max_rate = st.max_rate
        self.ratio = st.ratio
        self.wheelbase = car.wheelbase
        self.rear_offset = -float(np.mean(corners.wheel_center[2:, 0]))
        self.track = float(np.mean(np.abs(corners.wheel_center[:2, 1])) * 2) \
            if track is None else track
        self.spin_inertia = np.array([c.spin_inertia for c in car.corners])
        self.drive_share, self.brake_share = car.drive.drive_shares(), car.drive.brake_shares()
        self.body_reaction = car.drive.reaction == "body"  # driveshafts, not in-wheel motors
        self.delta = self.delta_cmd = self.torque = 0.0
        #: first-order hold of the driver's commands: (t0, t1, steer0, steer1, torque0,
        #: torque1), both commands ramping linearly from t0 to t1 (None: no command yet)
        self._hold = None
        # the driver's neuromuscular lag on each closed-loop command (none on an open-loop
        # input: a steering robot's or a measured drive's)
        self._steer_lag = FirstOrderLag(0.0 if self.open_loop else steering.neuromuscular_lag)
        self._torque_lag = FirstOrderLag(0.0 if self.open_torque else
                                         speed_pi.neuromuscular_lag)
        self.step_no = self.status = 0
        self.message = ""
        names = ["x", "y", "z", "x_rear", "y_rear", "roll", "pitch", "yaw", "speed", "ay",
                 "steer", "steering_wheel", "drive_torque", "lateral_error", "speed_target",
                 *(f"wheel_angle_{c}" for c in CORNERS)]
        self._c0 = len(names)  # first corner column (_record fills the row by position)
        for cn in CORNERS:
            names += [f"hub_{cn}_x", f"hub_{cn}_y", f"hub_{cn}_z", f"tire_{cn}_Fx",
                      f"tire_{cn}_Fy", f"tire_{cn}_Fz", f"travel_{cn}", f"spin_{cn}"]
        for p in self.points:
            names += [f"acc_{p}_x", f"acc_{p}_y", f"acc_{p}_z"]
        #: powertrain mounts passing the drive's reaction couple (``[drive]
        #: reaction_mounts``): their forces on the body, body axes, before the suspension's
        self.reaction, self._tau = None, np.zeros(3)
        if car.drive.reaction_mounts and self.body_reaction:
            self.reaction = CoupleSplit(car.drive.reaction_mounts, car.drive.reaction_points)
            names += [f"mount_{m}_{a}" for m in self.reaction.names for a in "xyz"]
        self.mounts, self.bushings = [], []
        #: per-mount forces recorded by Exudyn sensors (LinkageModel.add_mount_sensors)
        self.mount_sensors = bool(getattr(linkage, "_sensors", None))
        #: hub forces of the rows after the first made of Exudyn's sensor records after
        #: the run (False: read every row in the step, the reference the tests compare)
        self.hub_sensors = self.mount_sensors and self.hub_sensors
        self._hub_rows = {}  # row -> (tyre force (4, 3), mount frames (4, 3, 3))
        if linkage is not None:  # force on the body at every mount (body axes)
            self.mounts = sorted({m for m, *_ in linkage.body_links})
            for m in self.mounts:
                names += [f"mount_{m}_x", f"mount_{m}_y", f"mount_{m}_z"]
            self.bushings = sorted({m for m, _ in linkage.bushings})  # their deflections
            names += [f"bushing_{m}_{a}" for m in self.bushings for a in BUSHING_AXES]
            names += mounted_motion.names(car, self.bushings)   # powertrain, subframes
        n_rows = int(round(t_end / h)) // self.output_every + 2
        self.rec = Recorder(names, n_rows)
        self._row = np.full(len(names), np.nan)  # one output row, filled by _record
        self._prev_v = None

    # ------------------------------------------------------------------ pieces
    def road_contact(self, P: np.ndarray):
        """Road height (n,) and upward unit normal (n, 3) under points P (n, 3)
        (:mod:`flexpipe.roads._contact_fast`: compiled for a road along x, else NumPy)."""
        return self._contact(P)

    def wheel_angles(self, delta: float) -> np.ndarray:
        """Road-wheel angles (4,) of an Ackermann steering for the bicycle angle ``delta``."""
        return ackermann_angles(delta, wheelbase=self.wheelbase, track=self.track,
                                steered=self.steered)

    def driver(self, st, yaw: float) -> None:
        """Update steering command and drive torque (every ``driver_dt`` seconds).

        The pure-pursuit law is applied to the pose predicted ``preview_time`` ahead
        (constant velocity and yaw rate): a driver anticipates the vehicle's own response
        lag (tyre relaxation, yaw inertia), which a kinematic pure pursuit does not know.
        The speed is the car's as a speedometer reads it, the wheel centres' mean velocity
        along the heading: the body reference point's adds its pitch rate times its height
        above the pitch centre (0.57 m on the sample, coherent with the pitch rate to
        0.97-1.00 at 0.5-8 Hz on ISO C at 70 km/h), which the speed controller answered.
        """
        v = float(np.mean(st.wheel_v @ st.body_R[:, 0]))
        dt, tau = self.driver_dt, self.preview_time
        t1 = self._next_driver_t + dt  # where the hold reaches the new commands
        if self.open_loop:  # the input at t1: no lag
            cmd = self.steering.steering_wheel(t1) / self.ratio
        else:
            p = st.body_p + tau * st.body_v
            cmd = self.steering.steer(float(p[0]), float(p[1]), yaw + tau * st.body_w[2], v)
        cmd = self._steer_lag(max(-self.max_angle, min(self.max_angle, cmd)), dt)
        a_target = 0.0
        if self.profile is not None:
            self.v_target, a_target = self.profile.target(float(st.t), self._odometer)
            self._odometer += abs(v) * dt
        pi = self.speed_pi
        torque = pi.torque_at(t1) if self.open_torque else pi.lagged(
            pi.torque(self.v_target, v, dt, a_target), a_target, self._torque_lag, dt)
        t = float(st.t)
        # first-order hold: from the held values now to the new commands at the next
        # sampling instant (the first one: the steering from the actuator's angle, the
        # torque at once, as a car started at speed has it before the first sample)
        if self._hold is None:
            d0, q0 = self.delta, torque
        else:
            d0, q0 = self._held(t)
        self._hold = (t, max(t1, t + 1e-12), d0, cmd, q0, torque)
        self.delta_cmd = cmd

    def hold_controls(self) -> None:
        """Hold the steering and the drive torque at their present values from now on: the
        driver stops sampling (the controls of a linear model, :mod:`flexpipe.vehicle.linear`,
        in a run continued from its state)."""
        self._next_driver_t = math.inf
        self._hold = (0.0, 1.0, self.delta, self.delta, self.torque, self.torque)
        self.delta_cmd = self.delta

    def _held(self, t: float):
        """Steering command and drive torque of the first-order hold at time ``t``."""
        t0, t1, d0, d1, q0, q1 = self._hold
        u = min(1.0, max(0.0, (t - t0) / (t1 - t0)))
        return d0 + u * (d1 - d0), q0 + u * (q1 - q0)

    # ------------------------------------------------------------------ step
    def __call__(self, st):
        R = st.body_R
        roll, pitch, yaw = _rpy(R)
        why = watch.state_problem(st, roll, pitch)
        if why is not None:
            return self._fail(st.t, why)
        v = float(R[:, 0] @ st.body_v)
        if self.parked:
            self.torque = 0.0  # parked: no driver, wheels braked below
        elif st.t >= self._next_driver_t - 1e-9:
            self.driver(st, yaw)
            self._next_driver_t += self.driver_dt
        # steering actuator: rate limit towards the held command at the end of the step
        # (the angle the step reaches); the torque acts through the step, held at its middle
        delta_ref = self.delta_cmd
        if not self.parked and self._hold is not None:
            delta_ref = self._held(st.t + self.h)[0]
            self.torque = self._held(st.t + 0.5 * self.h)[1]
        dmax = self.max_rate * self.h
        self.delta += max(-dmax, min(dmax, delta_ref - self.delta))
        steer = self.wheel_angles(self.delta)

        # tyres: correct the relaxation over the step just taken, then linearize the
        # force for the coming one (solved implicitly, flexpipe.vehicle.tire_coupling)
        s_axis = st.wheel_R[:, :, 1]
        omega = st.spin_rate  # the wheels' absolute spin (flexpipe/exu/_tire_element.py)
        # road under the wheels now and where they will be at the end of the step (the
        # force is balanced there: the normal's tilt carries the road slope into Fx, Fy)
        ahead = st.wheel_p + self.h * st.wheel_v
        heights, normals = self.road_contact(np.vstack([st.wheel_p, ahead]))
        h_road, n_road = heights[:4], normals[:4]
        road_ahead, n_ahead = heights[4:], normals[4:]
        kin = {"C": st.wheel_p, "s": s_axis, "v": st.wheel_v, "omega": omega,
               "w": st.wheel_w + st.spin_rate[:, None] * s_axis,
               "h_road": h_road, "n_road": n_road}
        now = self.tires.correct(kin, self.h)
        why = watch.tire_problem(now["Fz"], self.weight_N)
        if why is not None:
            return self._fail(st.t, why)
        Fw = np.column_stack([now["Fx"], now["Fy"], now["Fz"]])
        F_applied = self._applied_tire_force(st, s_axis, omega)
        ts = self.tires.predict(dict(kin, n_road=n_ahead), self.h, road_ahead)
        if not math.isfinite(float(ts.F0.sum()) + float(ts.Dv.sum())):
            return self._fail(st.t, "tyre forces became non-finite")
        share = self.drive_share if self.torque >= 0 else self.brake_share
        T = self.torque * share
        if self.torque < 0 or self.parked:  # a brake acts on the disc against its caliper
            rel = omega - np.einsum("ij,ij->i", st.wheel_w, s_axis)
        if self.torque < 0:
            T = -np.abs(T) * np.sign(np.where(rel == 0, 1.0, rel))
        if self.parked:  # parking brake: viscous, at half the explicit limit
            T = -0.5 * self.spin_inertia / self.h * rel
        # the tyre's own moments are in the implicit element: only drive and brake here
        spin_torque = np.array(T, dtype=float) if np.ndim(T) else np.full(4, float(T))
        drive = spin_torque if self.torque > 0.0 and self.body_reaction else None
        if self.reaction is not None:  # the couple on the body (global), as exu.car applies
            self._tau = np.zeros(3) if drive is None else \
                -(drive[:, None] * st.wheel_R[:, :, 1]).sum(axis=0)

        if self.linkage is not None:  # the linkage's force elements linearize themselves
            rk = self.car.suspension.rack
            s_rack = None
            if rk is not None:
                s_rack = -self.delta * self.ratio * rk.travel_per_rev / (2 * math.pi)
            loads = self._loads(suspension=np.zeros(4), damper_c=np.zeros(4), tire=ts,
                             spin_torque=spin_torque, drive_torque=drive,
                             steer=steer, rack_travel=s_rack)
            self._tire_lin = (ts, st, omega)
            if self.step_no % self.output_every == 0:
                # at t = 0 the force the tyre element applies at the start state (the
                # predicted force F0 at its linearization point), the force Exudyn's
                # initial accelerations balance, so Newton's law of the parts holds
                self._record(st, np.zeros(4), Fw, v, roll, pitch, yaw,
                             ts.F0 if F_applied is None else F_applied)
            self.step_no += 1
            return loads
        # suspension: spring, damper (rate by the sign of the jounce rate) and the stops are
        # one implicit connector linearized at the start of the step; the anti-roll bars
        # come explicitly
        Fs = self.c.force(st.jounce, st.jounce_rate)
        # the anti-roll bars (explicit) at the travel predicted for the end of the step
        j_end = st.jounce + self.h * st.jounce_rate
        F_arb = self.c.force(j_end, st.jounce_rate) - self.c.force(j_end, st.jounce_rate,
                                                                    anti_roll=False)
        # damping: the secant of the dual-rate law between the rate now and the one
        # predicted for the end of the step, so a change of sign within the step is met
        # where the integrator balances the forces
        r0 = st.jounce_rate
        r1 = 2.0 * r0 - (r0 if self._prev_rate is None else self._prev_rate)
        self._prev_rate = r0.copy()

        def fd(r):
            return np.where(r > 0.0, self.c.c_jounce, self.c.c_rebound) * r

        dr = r1 - r0
        c_step = np.where(np.abs(dr) > 1e-9, (fd(r1) - fd(r0)) / np.where(
            np.abs(dr) > 1e-9, dr, 1.0), np.where(r0 > 0.0, self.c.c_jounce, self.c.c_rebound))
        Fs_own = self.c.force(st.jounce, st.jounce_rate, anti_roll=False)
        k_t = self.c.stiffness(st.jounce)
        f0 = Fs_own - k_t * st.jounce - c_step * st.jounce_rate

        loads = self._loads(suspension=F_arb, damper_c=c_step, tire=ts,
                         spin_torque=spin_torque, drive_torque=drive, steer=steer,
                         suspension_k=k_t, suspension_f0=f0)
        self._tire_lin = (ts, st, omega)
        if self.step_no % self.output_every == 0:
            self._record(st, Fs, Fw, v, roll, pitch, yaw, F_applied)
        self.step_no += 1
        return loads

    def fill_from_sensors(self) -> None:
        """The rows after the first from Exudyn's sensor records
        (:func:`flexpipe.vehicle.sensor_rows.fill`)."""
        sensor_rows.fill(self)

    def _fail(self, t: float, why: str):
        self.status = -1
        self.message = f"simulation stopped at t = {t:.4f} s: {why}"
        return None

    def _applied_tire_force(self, st, s_axis, omega):
        """Tyre force (4, 3) the integrator applied at the end of the step just taken (the
        linearized force of :mod:`flexpipe.vehicle.tire_coupling` at the new state)."""
        if self._tire_lin is None:
            return None
        ts, st0, om0 = self._tire_lin
        if self._compiled:
            return applied_force(ts.F0, ts.Dv, ts.dw, ts.A, ts.S, ts.r, ts.spin_axis,
                                 st0.wheel_w, st0.wheel_v, om0, st0.wheel_p[:, 2],
                                 st0.wheel_R, s_axis, st.wheel_w, st.wheel_v, omega,
                                 st.wheel_p[:, 2], st.wheel_R)
        return applied_force_reference(self._tire_lin, st, s_axis, omega)

    def refresh_first_row(self) -> None:
        """Record the t = 0 row again once the integrator has solved the initial
        accelerations and constraint forces (before, joint and link forces read 0)."""
        if self._first_row is None or self.rec.rows != 1:
            return
        self.rec.rows, self._prev_v = 0, None
        self.motion.clear()
        self._record(*self._first_row)

    def _record(self, st, Fs, Fw, v, roll, pitch, yaw, F_tire=None):
        if self.rec.rows == 0:
            self._first_row = (st, Fs, Fw, v, roll, pitch, yaw, F_tire)
        R = st.body_R
        # hub force on the body at each hardpoint, in that mount's frame (~ body axes)
        if F_tire is None or self.wheel_acc is None:
            jf = st.joint_force if st.joint_force is not None else self.joint_forces()
            hub = JOINT_FORCE_SIGN * np.asarray(jf, dtype=float)
            hub[:, 2] += Fs
        else:
            # Newton's law of each wheel carrier under the loads of the step just taken:
            # what the corner applies to the body = tyre force + weight - m a
            if self.linkage is not None and self.rec.rows > 0 and self.hub_sensors:
                # the parts' accelerations and the rack and bar links are recorded by
                # Exudyn's sensors: the hub force is made of them after the run
                self._hub_rows[self.rec.rows] = (np.array(F_tire, dtype=float),
                                                 st.mount_R.copy())
                hub = np.full((4, 3), np.nan)
            else:
                if self.linkage is not None:
                    hub_g = self.linkage.hub_forces(F_tire)
                else:
                    a = self.wheel_acc()
                    hub_g = F_tire + self.c.m_unsprung[:, None] * (self.gvec - a)
                hub = np.einsum("nji,nj->ni", st.mount_R, hub_g)
        # lateral acceleration of the body origin from its velocity history
        if self._prev_v is None:
            ay = 0.0
        else:
            dt = self.h * self.output_every
            ay = float(R[:, 1] @ (st.body_v - self._prev_v)) / dt
        self._prev_v = st.body_v.copy()
        rx = st.body_p[0] - self.rear_offset * R[0, 0]
        ry = st.body_p[1] - self.rear_offset * R[1, 0]
        path = self.steering.path
        lat = path.project(float(rx), float(ry))[1] if path is not None else 0.0
        # the row in the channel order of __init__: the scalars, 8 per corner, 3 per point
        # and per mount
        row = self._row
        c0 = self._c0
        row[0:3] = st.body_p
        row[3:c0] = (rx, ry, roll, pitch, yaw, v, ay, self.delta, self.delta * self.ratio,
                     self.torque, lat, self.v_target, *road_wheel_angles(R, st.wheel_R))
        corner = row[c0:c0 + 32].reshape(4, 8)
        corner[:, 0:3] = hub
        corner[:, 3:6] = Fw
        corner[:, 6] = st.jounce
        corner[:, 7] = st.spin_rate
        k = c0 + 32
        later = self.rec.rows > 0 and self.output_history is not None
        if self.points:
            if later:  # filled after the run from Exudyn's sensors (fill_from_sensors)
                row[k:k + 3 * len(self.points)] = np.nan
                k += 3 * len(self.points)
            else:
                acc = self.point_acc()
                for p in self.points:
                    row[k:k + 3] = R.T @ acc[p]
                    k += 3
        if self.reaction is not None:
            f = self.reaction.forces(R.T @ self._tau)
            row[k:k + f.size] = f.ravel()
            k += f.size
        if self.mounts:
            record_mounts(self, row, k, R)
        self.rec.add(st.t, row)
        if self.body_motion is not None and len(self.motion) < self.rec.rows and not later:
            self.motion.append(self.body_motion())
