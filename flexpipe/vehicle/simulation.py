"""``simulate(car, road=..., path=..., speed=..., t_end=..., body=...)``: one call from a car
file and a road to a :class:`~flexpipe.vehicle.result.Result`.

Bodies
------
``"rigid"``
    The body as one rigid body with the trimmed FE model's exact mass, centre of mass and
    inertia (or the ``[body.rigid]`` properties of a car without mesh).
``"flexible"``
    The body reduced by component mode synthesis (Craig-Bampton, interfaces at the four
    suspension hardpoints, or at every suspension mount of a linkage car with their static
    modes reduced to the characteristic constraint modes up to ``[body]
    interface_band_hz``) for a band chosen from the speed and the road content
    (:func:`flexpipe.vehicle.bodymodel.choose_band`), cached on disk.
``"full"``
    The same FE model with every fixed-interface mode up to :data:`FULL_CUTOFF_HZ` (over
    four times the flexible body's cut-off) plus every static constraint mode (no
    interface reduction), so the quasi-static response of all higher modes is kept
    exactly.  This is what "unreduced"
    can mean for an FFRF multibody body at acceptable cost: it differs from the full FE
    model only by the *dynamics* of modes far above the road and ride excitation (and
    above what the default 1.25 ms step resolves).  Meant for short validation runs.
"""

from __future__ import annotations

import math

import numpy as np

from flexpipe._io import absolute
from flexpipe.errors import InputError
from flexpipe.flexbody.invariants import MAX_MEAN_AXIS_COSINE, mean_axis_cosine
from flexpipe.vehicle import bodymodel, warmup
from flexpipe.vehicle.corners import GRAVITY, corner_arrays
from flexpipe.vehicle.linkage_setup import (  # noqa: F401 - re-exported
    FULL_CUTOFF_HZ,
    INTERFACE_F_MAX_HZ,
    MOUNT_RADIUS_M,
    body_mounts,
    linkage_statics,
    reduce_car_body,
)
from flexpipe.vehicle.result import BodyMotion, Result
from flexpipe.vehicle.run_inputs import (  # noqa: F401 - re-exported: BODIES, START_MARGIN_M, the steps
    BODIES,
    COMPLIANT_STEP,
    DEFAULT_STEP,
    START_MARGIN_M,
    as_car,
    as_road,
    check_run,
)
from flexpipe.vehicle.seats import seat_channels
from flexpipe.vehicle.settle import settled_start
from flexpipe.vehicle.spec import Car

#: generalized-alpha spectral radius of the runs (see :mod:`flexpipe.exu.car`); the
#: flexible body's modes are pre-warped for it (:mod:`flexpipe.exu.prewarp`).  At 1 ms
#: (the default before 2026-12-04), flexible linkage car, ISO C 70 km/h, worst corner
#: x / y / z against h/8:
#: 4.42 / 1.90 / 0.35 % at 0.4, 4.43 / 1.79 / 0.29 at 0.5, 3.97 / 1.63 / 0.26 at 0.6,
#: 3.74 / 1.54 / 0.23 at 0.7, 3.66 / 1.52 / 0.21 at 0.8; rigid, 100 km/h: 2.4 / 0.9 /
#: 0.3 at 0.5, 2.32 / 0.94 / 0.22 at 0.7 (2026-12-01)
SPECTRAL_RADIUS = 0.7


def static_deflection(fb, corners, n_modes=None) -> np.ndarray:
    """Elastic modal coordinates of the body resting on its springs (static preloads).

    Gravity does not load free-free elastic modes (they are mass-orthogonal to the rigid
    translations); the spring preloads at the hardpoints do:
    ``q = Omega^-2 Phi_h^T F`` with ``Phi_h`` the hardpoint translations per mode.
    """
    sel = slice(fb.n_rigid, fb.n_rigid + (fb.n_elastic if n_modes is None else n_modes))
    f = np.zeros(sel.stop - sel.start)
    names = [itf.name for itf in fb.interfaces]
    for i, name in enumerate(("fl", "fr", "rl", "rr")):
        itf = fb.interfaces[names.index(name)]
        f += itf.shapes[2, sel] * corners.preload[i]
    return f / fb.omega[sel] ** 2


def default_driver(car: Car, mass: float):
    """Pure pursuit and PI speed controller with gains scaled to the car.  The preview
    (2 m + 0.1 s x speed) is short because the controller applies it to the pose predicted
    0.3 s ahead (:class:`~flexpipe.vehicle.dynamics.CarController`): with that and the
    driver's 0.1 s neuromuscular lag the linkage sedan tracks ``make slalom``'s 18 m /
    0.8 m slalom at 60 km/h within 0.074 m (2026-12-03; 0.126 m without the lag; a plain
    pure pursuit on the dynamic car lags by a quarter period).
    """
    from flexpipe.driver import PurePursuit, SpeedPI

    rear_x = float(np.mean([c.wheel_center[0] for c in car.corners[2:]]))
    radius = float(np.mean([c.wheel_radius for c in car.corners]))
    kp = mass * radius / 0.5  # 0.5 s speed time constant
    # a speed profile's acceleration: the car's mass and the wheels' spin inertia
    ff = mass * radius + sum(c.spin_inertia for c in car.corners) / radius
    steering = PurePursuit(wheelbase=car.wheelbase, lookahead_base=2.0, lookahead_time=0.1,
                           max_steer=car.steering.max_wheel_angle, rear_axle_offset=-rear_x)
    speed = SpeedPI(kp=kp, ki=kp / 2.0, drive_torque_max=car.drive.max_drive_torque,
                    brake_torque_max=car.drive.max_brake_torque, integral_band=2.0,
                    feedforward=ff)
    return steering, speed


def _tires(car: Car):
    from flexpipe.tires import tire_from_file

    models, out = {}, []
    for c in car.corners:
        key = (str(c.tire), c.tire_pressure)
        if key not in models:
            try:
                models[key] = tire_from_file(c.tire, **(
                    {} if c.tire_pressure is None else {"pressure": c.tire_pressure}))
            except InputError as exc:
                if exc.key != "pressure":
                    raise
                raise InputError(str(exc), file=car.file,
                                 key=f"corners.{c.name}.tire_pressure_Pa") from None
        tire = models[key]
        if abs(tire.unloaded_radius - c.wheel_radius) > 1e-3:
            raise InputError(f"wheel_radius_m = {c.wheel_radius:g} m but the tyre file "
                             f"{c.tire.name} has UNLOADED_RADIUS = {tire.unloaded_radius:g} m; "
                             "make them agree", file=car.file,
                             key=f"corners.{c.name}.wheel_radius_m")
        out.append(tire)
    return out


def prepare(car, *, body: str, speed: float, road=None, f_max=None, cache=True, log=None,
            bodies=None):
    """Everything a run needs that does not depend on the time integration.

    ``car`` and ``road`` take what :func:`simulate` takes (a Car or car file; a Road, road
    file, road table or None).  Returns a dict with ``rigid`` (mass properties),
    ``corners``, ``tires``, ``flexbody`` (None for rigid), ``band_hz`` and ``reduction``
    (cache info); it pickles with the standard :mod:`pickle`.  ``bodies`` may supply
    ``{"rigid": RigidBodyData, "flexbody": FlexBody, "reduction": info}`` computed once
    elsewhere (a sweep's per-body task) instead of reading the cache.
    """
    log = log or (lambda *a: None)
    car = as_car(car)  # --- sweep (issue 12): same car/road arguments as simulate()
    if road is not None:
        road = as_road(road, 0.0)
    bodies = bodies or {}
    rb = bodies.get("rigid") or bodymodel.rigid_properties(car, cache=cache)
    tires = _tires(car)
    m_s, cg_s = rb.mass, rb.center_of_mass  # the sprung mass, with powertrain and subframes
    for b in car.mounted_bodies:
        cg_s = (m_s * cg_s + b.mass * b.center_of_mass) / (m_s + b.mass)
        m_s += b.mass
    corners = corner_arrays(car, m_s, cg_s, tires=tires)
    out = {"rigid": rb, "corners": corners, "tires": tires, "flexbody": None,
           "band_hz": None, "reduction": None}
    if body in ("flexible", "full"):
        band = f_max if f_max is not None else bodymodel.choose_band(speed, road)
        if bodies.get("flexbody") is not None:
            fb, info = bodies["flexbody"], bodies["reduction"]
        else:
            fb, info = reduce_car_body(car, f_max=band, cache=cache, log=log,
                                       full=body == "full")
        out.update(flexbody=fb, band_hz=None if body == "full" else band, reduction=info)
    return out


def simulate(car, *, road=None, path=None, speed, t_end, body: str = "flexible",
             h: float | None = None, output_step: float | None = None, driver=None, f_max=None,
             max_mode_hz=None, initial_rates=(0.0, 0.0, 0.0), progress: bool = False,
             cache: bool = True, log=None, prepared=None, settle: bool = True,
             prewarp: bool = True, inertia_coupling: str = "auto",
             profile: bool = False, probe=None, threads: int | str = 1) -> Result:
    """Simulate the car on a road following a path at a target speed or speed profile.

    Parameters
    ----------
    car : Car or str or Path
        A car (:func:`load_car`) or its TOML file.
    road : Road, str, Path or None
        Road (file: ``.toml`` spec, ``.crg``, ``.csv``); ``None`` for a flat road.  Heights
        are taken at global positions (:meth:`Road.height_xy`): OpenCRG roads lie where
        their reference line and modifiers put them (curved, sloped, banked;
        :mod:`flexpipe.roads.crg_mods`); others along the x axis.
    path : flexpipe.driver.Path, str, Path or None
        Path the driver follows (file ``.csv``/``.toml``); ``None`` or ``"straight"`` for
        a straight path from the road's first sample along its start heading (the x axis
        from 0 for a road starting at 0, or no road); ``"road"`` for the road's reference
        line (:meth:`Road.reference_path`).
    speed : float, SpeedProfile, str or Path
        Target (and initial) speed, m/s (0 for a car at rest, its wheels braked), or a
        :class:`~flexpipe.driver.speed.SpeedProfile` or its file (``.toml``
        ``[speed_profile]`` or ``.csv``): speed against time or distance travelled, which
        the driver follows with a feed-forward torque for its acceleration; the run
        starts at its first speed.
    t_end : float
        Simulated time, s.
    body : {"flexible", "rigid", "full"}
        Body model (see module docstring).
    h : float, optional
        Time step, s (1e-5 .. 5e-3).  Default: the car's
        :func:`~flexpipe.vehicle.run_inputs.default_step`, :data:`DEFAULT_STEP` (1.25 ms),
        or :data:`COMPLIANT_STEP` (0.25 ms) for a linkage suspension in compliant mode.
        Measured at 1.25 ms against h/8 on ISO class C at 70/100 km/h and on the slalom,
        4 s, output every step (``bench/bench_convergence.py``, README, worst corner,
        percent of the fluctuating part, x / y / z): the linkage car rigid within 3.8 /
        0.8 / 0.3 %, flexible 3.5 / 0.9 / 0.3 %; the prismatic car rigid 2.6 / 0.3 / 0.3 %,
        flexible 2.4 / 5.5 / 0.3 % (its single hardpoints' lever, README) (2026-12-04,
        16:44 UTC); at 2 ms the linkage car 8.3 %.  Check any run with
        :func:`flexpipe.vehicle.convergence.check_step` (``flexpipe run --check-step``).
    output_step : float, optional
        Output sampling interval, s (a multiple of ``h``; default ``h``, every step).
        Coarser output keeps every n-th step without filtering: content above the
        output's Nyquist frequency aliases (the flexible linkage car at 1 ms had hub-force
        content up to its 670 Hz body modes; on the 30 Hz body of 2026-12-01, sampled at
        2 ms, its x step error read 3.5 or 5.2 % depending on which steps are kept, 4.4 %
        over all steps, at spectral radius 0.5).
    driver : (PurePursuit or OpenLoopSteer, SpeedPI or None) or str or Path, optional
        Controllers, or a driver TOML file (``[steering]``, ``[speed]``); default
        :func:`default_driver` (also for a missing speed controller).  An
        :class:`~flexpipe.driver.open_loop.OpenLoopSteer` (``[steering] type =
        "open_loop"``) steers by a steering-wheel angle against time (step, ramp, sine with
        dwell, ...) instead of following ``path``, which then only is the reference of
        the ``lateral_error`` channel.
    f_max : float, optional
        Band of the flexible body in Hz (default: chosen from speed and road).
    max_mode_hz : float, optional
        Keep only the reduced body's modes up to this frequency (default: all); 0 (or
        below the lowest mode) keeps none: the flexible body with every elastic mode off,
        which reproduces the rigid car (tests/test_linkage_car.py).
    initial_rates : (3,) float
        Extra initial heave velocity (m/s), roll and pitch rate (rad/s) of the body, e.g.
        to excite the ride modes in a validation run (wheels start without them).
    progress : bool
        Show a progress bar.
    settle : bool
        Start from the car settled at rest (:func:`flexpipe.vehicle.settle.settled_start`:
        body deflection, parts, steering and tyres in static equilibrium); False starts
        at the design position.
    prewarp : bool
        Fit the flexible body's modal masses and damping to the step so the integrator
        rings every elastic mode at its own frequency and damping
        (:mod:`flexpipe.exu.prewarp`; stiffness and statics unchanged, no effect as
        h -> 0).  False integrates the modes as they are.
    inertia_coupling : {"auto", "constant", "full"}
        Inertia of the flexible body's floating frame
        (:func:`flexpipe.exu.body.add_flexible_body`): ``"full"`` evaluates Exudyn's
        complete floating-frame terms, ``"constant"`` the rigid inertia plus the constant
        modal mass (Adams/Flex's constant coupling; needs mean-axis modes), ``"auto"``
        (default) takes ``"constant"`` when the body's modes are mean-axis modes
        (:func:`flexpipe.flexbody.invariants.mean_axis_cosine`), else ``"full"``.  The
        choice is in ``Result.info["inertia_coupling"]``.  Measured on the linkage
        sample, see the README ("Inertia coupling").
    profile : bool
        Switch on Exudyn's computation timers: ``Result.info["profile_ms_per_step"]``
        splits the CPU time per step into the Python step and Exudyn's parts (constraint
        reaction forces and equations, body and force terms, mass matrix,
        back-substitution, sensors) on Exudyn's range-checked module; its default fast
        module times only the total, split into the Python step and ``exudyn`` (see
        :mod:`flexpipe.exu`, ``FLEXPIPE_EXUDYN``).  ``info["newton_iterations_per_step"]``
        and ``info["newton_jacobians"]`` (Jacobians computed and factorized: modified
        Newton keeps one until the body has turned by
        :data:`flexpipe.exu.timeloop.JACOBIAN_RENEW_DEG` or Newton stalls) are there in
        every run.
    threads : int or "auto"
        Exudyn's threads (:mod:`flexpipe.exu.threads`; ``"auto"``: 2 for a flexible or
        full body when two cores are idle as the run starts).  Results equal one
        thread's to rounding; two keep two cores busy (spinning), so sweeps use one.
        ``Result.info["threads"]``; the measured gain is in the README.
    cache : bool
        Use and fill the on-disk cache of reduced bodies.
    log : callable, optional
        Receives progress messages (default: silent).
    prepared : dict, optional
        Output of :func:`prepare` to reuse between runs.
    probe : callable, optional
        ``probe(system, controller)`` is called with the assembled car in its start state
        instead of the run, and its value returned (:func:`flexpipe.vehicle.linear
        .linear_modes` linearizes the car this way).

    Returns
    -------
    Result
        ``status`` 0 on success, -1 when the run stopped early (``message`` names the
        simulated time and the likely cause).

    Raises
    ------
    InputError
        Bad arguments, bad car file, path too short, or the road not under the path (a
        given path is not moved onto a road that starts elsewhere).
    """
    a = check_run(car, road=road, path=path, speed=speed, t_end=t_end, body=body, h=h,
                  output_step=output_step, driver=driver, f_max=f_max,
                  max_mode_hz=max_mode_hz, initial_rates=initial_rates, prewarp=prewarp,
                  inertia_coupling=inertia_coupling, threads=threads)
    car, speed, t_end, h, every = a.car, a.speed, a.t_end, a.h, a.every
    max_mode_hz, f_max, rates, start = a.max_mode_hz, a.f_max, a.rates, a.start
    road_obj, path_obj, steering, speed_pi = a.road, a.path, a.steering, a.speed_pi
    if log is not None and warmup.pending():  # the first run after installing: say why
        log(warmup.MESSAGE)                     # it takes half a minute longer
    vprof = a.profile  # SpeedProfile or None (constant speed)
    prep = prepared or prepare(car, body=body, speed=vprof.maximum if vprof else speed,
                               road=road_obj, f_max=f_max,
                               cache=cache, log=log)
    rb, corners, tires = prep["rigid"], prep["corners"], prep["tires"]
    total_mass = rb.mass + corners.m_unsprung.sum() + car.mounted_mass
    if steering is None or speed_pi is None:  # a driver file may leave [speed] out
        default_steering, default_speed = default_driver(car, total_mass)
        steering = steering or default_steering
        speed_pi = speed_pi or default_speed
    steering = steering.with_path(path_obj)
    path_obj.reset_projection()  # a path shared with an earlier run starts afresh
    speed_pi.reset()

    # initial pose: body origin on the path at arc length `start`, heading along the path
    x0, y0 = path_obj.point_at(start)
    psi = float(path_obj.heading_at(start))
    R0 = np.array([[math.cos(psi), -math.sin(psi), 0.0], [math.sin(psi), math.cos(psi), 0.0],
                   [0.0, 0.0, 1.0]])
    W = corners.wheel_center
    Pw = np.array([x0, y0, 0.0]) + W @ R0.T
    z0 = float(np.mean(road_obj.height_xy(Pw[:, 0], Pw[:, 1])))
    susp = None
    if car.suspension is None:  # ground reactions at rest, as flexpipe info gives them
        from flexpipe.vehicle.corners import static_wheel_loads

        static_N = static_wheel_loads(car, rb.mass, rb.center_of_mass, g=GRAVITY)
    else:
        # springs preloaded for the static wheel loads of the true mass distribution; the
        # body in its design attitude on tyres carrying those loads: heave and pitch by the
        # tyres' static loaded radius minus the design wheel-centre height
        from flexpipe.vehicle.corners import static_loaded_radius

        susp, static_N = linkage_statics(car, rb)
        dz = np.array([static_loaded_radius(t, n) for t, n in zip(tires, static_N,
                                                                 strict=True)]) - W[:, 2]
        xf, xr = W[:2, 0].mean(), W[2:, 0].mean()
        slope = (dz[:2].mean() - dz[2:].mean()) / (xf - xr)
        theta = -math.atan(slope)  # rotation about the body y axis
        Ry = np.array([[math.cos(theta), 0.0, math.sin(theta)], [0.0, 1.0, 0.0],
                       [-math.sin(theta), 0.0, math.cos(theta)]])
        R0 = R0 @ Ry
        z0 += dz[:2].mean() - slope * xf
    p0 = np.array([x0, y0, z0])
    re = np.array([float(t.effective_rolling_radius(t.unloaded_radius - wz))
                   for t, wz in zip(tires, W[:, 2], strict=True)])
    spin0 = speed / re

    from flexpipe.exu import compiled_module
    from flexpipe.exu.car import CarBuild, CarSystem
    from flexpipe.exu.threads import auto_threads
    from flexpipe.exu.timeloop import solver_info
    from flexpipe.vehicle.dynamics import CarController

    fb = prep["flexbody"]
    kind = "rigid" if body == "rigid" else "flexible"
    names = list(car.body.points)
    pn = {}
    if car.body.mesh is not None or car.body.body_file is not None:
        if fb is not None:
            nodes = fb.nodes
        elif car.body.body_file is not None:
            nodes = bodymodel.ready_body(car).nodes
        else:
            nodes = bodymodel.body_mesh(car).points
        pn = bodymodel.point_nodes(car, nodes)
        local = {n: nodes[pn[n]] for n in names}
    else:
        local = dict(car.body.points)
    n_modes = None
    q0 = None
    if fb is not None:
        if max_mode_hz is not None:
            # 0 keeps none: the flexible body's own frame, markers and mounts with every
            # elastic mode off, the consistency check against the rigid twin (issue 9)
            n_modes = int(np.count_nonzero(fb.frequencies_hz[fb.n_rigid:] <= max_mode_hz))
        q0 = None if car.suspension is not None else static_deflection(fb, corners, n_modes)
        if inertia_coupling == "auto":
            cos, _ = mean_axis_cosine(fb, n_modes)
            inertia_coupling = "constant" if cos <= MAX_MEAN_AXIS_COSINE else "full"
    build = CarBuild(
        chassis=kind, flexbody=fb, n_modes=n_modes, modal_q0=q0, mass=rb.mass,
        center_of_mass=rb.center_of_mass,
        inertia_origin=rb.inertia_origin, hardpoints=corners.hardpoint,
        wheel_centers=corners.wheel_center, m_unsprung=corners.m_unsprung,
        J_unsprung=corners.J_unsprung, spin_inertia=corners.spin_inertia,
        spring_k=corners.k, spring_preload=corners.preload, damper_c=corners.c_jounce,
        steered=np.array([c.axle == car.steering.axle for c in car.corners]),
        position=p0, rotation=R0, speed=speed, spin_rate=spin0, gravity=GRAVITY,
        body_rates=rates,
        point_nodes=pn if pn else {n: -1 for n in names}, point_local=local,
        suspension=susp, reaction_mounts=car.drive.reaction_mounts,
        powertrain=car.powertrain, subframes=car.subframes,
        modal_prewarp=(h, SPECTRAL_RADIUS) if prewarp and fb is not None else None,
        inertia_coupling=inertia_coupling if fb is not None else "full")
    def make_system(b):
        if susp is not None:
            from flexpipe.exu.linkage_car import LinkageCarSystem

            return LinkageCarSystem(b)
        return CarSystem(b)

    def make_controller(system, *, target_speed, h, t_end, parked=None):
        return CarController(corners=corners, tires=tires, road=road_obj, steering=steering,
                             speed_pi=speed_pi, target_speed=target_speed, car=car, h=h,
                             t_end=t_end, output_every=every, points=names,
                             point_acc=system.point_accelerations,
                             joint_forces=system.joint_forces,
                             wheel_acc=system.wheel_accelerations, gravity=GRAVITY,
                             linkage=getattr(system, "linkage", None),
                             body_motion=system.body_motion_sample,
                             output_history=system.output_history,
                             weight_N=total_mass * GRAVITY, parked=parked)

    start = settled_start(build, make_system, make_controller) if settle else None
    system = make_system(build)
    ctrl = make_controller(system, target_speed=vprof or speed, h=h, t_end=t_end)
    if start is not None:
        system.set_initial_coordinates(start[0])
        if speed == 0.0:  # parked: the tyres keep the deflection they settled in
            ctrl.tires.state = start[1]
    speed_pi.reset()
    if probe is not None:
        return probe(system, ctrl)
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(total=int(round(t_end / h)), desc=f"{car.name} {body}", unit="step",
                   leave=True, mininterval=0.5)
    try:
        completed, t_reached, cpu, wall, solver_msg, python_cpu, stats, python_wall = system.run(
            ctrl, t_end=t_end, h=h, spectral_radius=SPECTRAL_RADIUS,
            progress=bar.update if bar is not None else None, output_step=every * h,
            timers=bool(profile), threads=auto_threads(body) if a.threads == "auto"
            else a.threads)
    finally:
        if bar is not None:
            bar.close()
    if ctrl.status < 0:
        status, message = -1, ctrl.message
    elif not completed:
        status = -1
        cause = (f"likely causes: a too large step h = {h:g} s for the stiffness of the "
                 "model, or a diverging state")
        if t_reached < 1.5 * h:  # at the very start no step is small enough: the model
            cause = ("at the first step, so the step is rarely the cause: the car cannot "
                     "start from its initial state - look for a suspension joint or link "
                     "that locks or leaves a part free (flexpipe kc CAR shows whether each "
                     "corner assembles), a stiffness or mass far out of range in the car "
                     f"file, or try a smaller step than h = {h:g} s")
        message = (f"simulation stopped at t = {t_reached:.4f} s: the implicit solver did not "
                   f"converge ({solver_msg or 'Newton failure'}); {cause}")
    else:
        status, message = 0, f"reached t_end = {t_end:g} s"
    ctrl.fill_from_sensors()
    ch = ctrl.rec.channels()
    ch.update(seat_channels(car.body.seats, ctrl.rec.t[: ctrl.rec.rows], ch))
    if status != 0:  # flexpipe#14 (robust): say what diverged and which input is implausible
        from flexpipe.vehicle.diagnose import explain

        message = explain(message, car=car, body_mass=rb.mass, body_cg=rb.center_of_mass,
                          t=ctrl.rec.t[: ctrl.rec.rows], channels=ch)
    info = {
        "car": car.name, "car_file": absolute(car.file), "body": body, "h": h,
        "output_step": every * h, "speed": speed, "t_end": t_end,
        "speed_profile": vprof.describe() if vprof is not None else None,
        "steering": steering.describe(), "speed_control": speed_pi.describe(),
        "seats": {seat.name: seat.floor_point for seat in car.body.seats},
        "road": getattr(road_obj, "source", "") or getattr(road_obj, "name", ""),
        "path": getattr(path_obj, "source", "") or getattr(path_obj, "name", ""),
        "mass_body_kg": rb.mass, "mass_total_kg": total_mass,
        # the car's ground reactions at rest (every mass: body, wheels, a linkage's parts,
        # rack and anti-roll-bar arms), the loads flexpipe info prints; they sum to m g.
        # They are the zero-warp loads of the mass distribution: a prismatic car given
        # unequal spring_preload_N values (corner weights) settles to other loads
        "static_wheel_load_N": np.asarray(static_N, dtype=float).tolist(),
        "cpu_python_step_s": float(python_cpu), "wall_python_step_s": float(python_wall),
        "cpu_settle_s": float(start[2]) if start is not None else 0.0,
        "modal_prewarp": build.modal_prewarp is not None,
        "inertia_coupling": build.inertia_coupling if fb is not None else None,
        "exudyn_module": compiled_module(),
        "suspension": "prismatic" if car.suspension is None else
        f"linkage ({car.suspension.mode} mode)",
        **solver_info(stats, python_cpu, cpu_s=cpu),
    }
    if fb is not None:
        used = fb.n_elastic if n_modes is None else n_modes
        info.update(n_elastic_modes=used, band_hz=prep["band_hz"],
                    highest_mode_hz=float(fb.frequencies_hz[fb.n_rigid + used - 1]),
                    reduction_cached=prep["reduction"]["cached"],
                    reduction_s=prep["reduction"]["seconds"])
    t_out = ctrl.rec.t[: ctrl.rec.rows].copy()
    return Result(t=t_out, channels=ch, status=status,
                  message=message, body=body, cpu_time=cpu, wall_time=wall,
                  simulated_time=t_end if status == 0 else max(t_reached, 0.0), info=info,
                  motion=BodyMotion.from_rows(t_out, ctrl.motion,
                                              fb.n_rigid if fb is not None else 0))

