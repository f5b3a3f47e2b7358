"""Argument checks of :func:`flexpipe.vehicle.simulation.simulate`: numbers in range, and
the car, road and path each given as an object, a file or ``None``, turned into objects
with a clear error naming the argument otherwise.

:func:`check_run` does every check of a run that needs no reduction and no time
integration, so callers that write outputs (``flexpipe run``, a sweep) can reject bad
arguments before they touch their output folder."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flexpipe._args import checked_number
from flexpipe._io import absolute
from flexpipe.errors import InputError
from flexpipe.vehicle.spec import Car, load_car

#: body models of a run (see :mod:`flexpipe.vehicle.simulation`)
BODIES = ("flexible", "rigid", "full")
#: highest target speed, m/s (288 km/h): faster than a road car is driven in any ride,
#: durability or handling run; a larger number is most likely km/h given as m/s
SPEED_MAX = 80.0
#: longest simulated time, s: one hour of driving (2.9 million steps at the default
#: 1.25 ms); more is most likely milliseconds given as seconds
T_END_MAX = 3600.0
#: time step range, s, that :func:`~flexpipe.vehicle.simulation.simulate` documents: at
#: 2 ms the hub forces are already 6-7 % off in x (README, step convergence), so
#: beyond 5 ms the run means little; below 10 us a few seconds take days.  A value outside
#: is most likely milliseconds given as seconds
H_MIN, H_MAX = 1e-5, 5e-3
#: distance along the path of the body origin at t = 0, beyond the wheelbase, m
START_MARGIN_M = 3.0
#: default time step, s: the linkage sample's hub forces are within 5 % of h/8 in x, y and
#: z at it, rigid and flexible, on ISO C 70/100 km/h and the slalom (worst 3.8 %,
#: ``bench/bench_convergence.py``, 2026-12-04 16:44 UTC); 1 ms, the default until then,
#: took 26-27 % more CPU for a worst 2.8 % (``bench_linkage``, 17:25 UTC, and two
#: alternating pairs at 16:39), and 2 ms leaves x at 6.8 % (flexible) and 8.3 % (rigid)
#: at 100 km/h (README, "Step convergence")
DEFAULT_STEP = 1.25e-3
#: default time step of a car whose linkage suspension runs in compliant mode (every
#: bushing as given), s: its light arms on stiff bushings ring at roughly 70-350 Hz; the
#: sample's hub forces in that mode (rigid body, ISO C 70 km/h, worst corner, x / y / z
#: against h/8) are 1.9 / 0.4 / 0.1 % off at 0.25 ms, but 44 / 7.0 / 1.2 % at 1.25 ms and
#: 7.4 % (x) at 0.5 ms (against 0.0625 ms) (``bench/bench_compliant.py``, 2026-12-04)
COMPLIANT_STEP = 2.5e-4


class StepWarning(UserWarning):
    """A run at a step coarser than its car's measured default (a compliant linkage
    suspension above :data:`COMPLIANT_STEP`)."""


def default_step(car) -> float:
    """The step a run of ``car`` (a Car or car file) takes when none is given, s:
    :data:`COMPLIANT_STEP` for a linkage suspension in compliant mode, else
    :data:`DEFAULT_STEP`."""
    mode = getattr(as_car(car).suspension, "mode", None)
    return COMPLIANT_STEP if mode == "compliant" else DEFAULT_STEP


def as_road(road, needed: float):
    from flexpipe.roads import Road, flat, load_road

    if road is None:
        return flat(needed + 50.0, dx=1.0, track_width=1.5)
    if isinstance(road, Road):
        return road
    if isinstance(road, (str, Path, dict)):
        return load_road(road)
    raise InputError(f"road must be a flexpipe Road, a road file (.toml/.crg/.csv) or None, "
                     f"got {type(road).__name__}", key="road")


def _warn_coarse_compliant(car: Car, h: float) -> None:
    """Warn when a compliant linkage suspension runs at a step coarser than its default."""
    if default_step(car) != COMPLIANT_STEP or h <= COMPLIANT_STEP * (1 + 1e-9):
        return
    import warnings

    warnings.warn(StepWarning(
        f"{car.file}: [suspension] mode = \"compliant\" (every bushing as given) at h = "
        f"{h:g} s, coarser than that mode's default {COMPLIANT_STEP:g} s: its light arms on "
        "stiff bushings ring at 70-350 Hz, and the sample's hub forces in this mode are 7 % "
        "(0.5 ms) to 44 % (1.25 ms) of their fluctuation off h/8 in x; run at the default "
        "or check this run with --check-step (check_step)"), stacklevel=3)


def as_car(car) -> Car:
    if isinstance(car, Car):
        return car
    if isinstance(car, (str, Path)):
        return load_car(car)
    raise InputError(f"car must be a Car or a car file, got {type(car).__name__}", key="car")


def road_start(road) -> tuple[float, float, float]:
    """Global position ``(x, y)`` (m) and heading (rad) of a road's first sample on its
    reference line: ``(x[0], 0, 0)`` for a road along the x axis (CSV, generated), the
    start of the plan of a placed OpenCRG road."""
    if road is None:
        return 0.0, 0.0, 0.0
    if road.plan is None:
        return float(road.x[0]), 0.0, 0.0
    return float(road.plan.x[0]), float(road.plan.y[0]), float(road.plan.phi_start)


def as_path(path, needed: float, road=None):
    """The path of a run.  ``None`` or ``"straight"``: a straight path of ``needed + 50``
    metres from the first sample of ``road`` along its start heading (:func:`road_start`;
    from the origin along x for a road that starts there, or without a road), so that the
    car starts at the same run-in on any road; a file or a Path object is used as given."""
    from flexpipe.driver import Path as DPath
    from flexpipe.driver import read_path, straight

    if path is None or (isinstance(path, str) and path == "straight"):
        x0, y0, heading = road_start(road)
        if x0 == 0.0 and y0 == 0.0 and heading == 0.0:
            return straight(needed + 50.0, ds=1.0)
        line = straight(needed + 50.0, ds=1.0, heading=heading)
        return DPath.from_xy(line.x + x0, line.y + y0, name="straight",
                             source=f"straight(length={needed + 50.0:g}) from the road's "
                                    f"first sample ({x0:g}, {y0:g}) m")
    if isinstance(path, DPath):
        return path
    if isinstance(path, (str, Path)):
        return read_path(path)
    raise InputError(f"path must be a flexpipe.driver.Path, a path file (.csv/.toml), "
                     f"'straight' or None, got {type(path).__name__}", key="path")


@dataclass(frozen=True)
class RunArguments:
    """The checked arguments of one run (:func:`check_run`)."""

    car: Car
    body: str
    speed: float
    t_end: float
    h: float
    every: int
    max_mode_hz: float | None
    f_max: float | None
    rates: np.ndarray
    start: float
    road: object
    path: object
    steering: object
    speed_pi: object
    profile: object = None  # SpeedProfile of a run whose speed varies (speed: its first)
    threads: int | str = 1  # Exudyn's threads or "auto" (check_threads)


def check_run(car, *, road=None, path=None, speed, t_end, body: str = "flexible",
              h: float | None = None, output_step: float | None = None, driver=None, f_max=None,
              max_mode_hz=None, initial_rates=(0.0, 0.0, 0.0), prewarp: bool = True,
              inertia_coupling: str = "auto", threads: int | str = 1) -> RunArguments:
    """Check the arguments of :func:`~flexpipe.vehicle.simulation.simulate` (same meaning,
    same units: speed in m/s, times in s) without reducing or integrating anything: the
    numbers, the body model, the car, road, path and driver files, that the path is long
    enough and the road lies under it (:func:`_check_road_covers`; the default straight
    path starts at the road's first sample, :func:`as_path`, so a road starting at 100 m
    is driven from 100 m on as one starting at 0 is from 0), and for a flexible or full
    body that the car file's mount ``node_ids`` are nodes of the body mesh (which reads
    the mesh when a mount gives ids).  ``h=None`` takes the car's :func:`default_step`.

    Raises
    ------
    InputError
        The first bad argument, named by its ``key``.
    """
    car = as_car(car)
    if body not in BODIES:
        raise InputError(f"body must be one of {BODIES}, got {body!r}", key="body")
    if not isinstance(prewarp, (bool, np.bool_)):
        raise InputError(f"prewarp must be True or False, got {prewarp!r}", key="prewarp")
    speed, profile = _speed(speed)
    t_end = checked_number(t_end, "t_end", lo=0.0, hi=T_END_MAX)
    h = checked_number(default_step(car) if h is None else h, "h", lo=0.0, hi=H_MAX)
    _warn_coarse_compliant(car, h)
    if h < H_MIN:
        raise InputError(f"h must be >= {H_MIN:g} s, got {h}", key="h")
    if output_step is None:
        output_step = h
    output_step = checked_number(output_step, "output_step", lo=0.0, hi=1.0)
    if h > t_end:  # flexpipe#14 (robust): checked here, not by Exudyn
        raise InputError(f"h = {h:g} s is longer than t_end = {t_end:g} s; choose h <= t_end",
                         key="h")
    # the integrator takes t_end / n steps: another step than h would make the channels'
    # time base wrong (the controller and the output rows count steps of h)
    n = t_end / h
    if abs(n - round(n)) > 1e-6 * max(1.0, n):
        lo, hi = math.floor(n) * h, math.ceil(n) * h
        raise InputError(f"t_end = {t_end:g} s is not a whole number of steps h = {h:g} s "
                         f"({n:.4g} steps); use t_end = {lo:.6g} or {hi:.6g} s, or another h",
                         key="t_end")
    k = output_step / h
    if k < 1.0 - 1e-9 or abs(k - round(k)) > 1e-6 * max(1.0, k) or output_step > t_end:
        raise InputError(f"output_step = {output_step:g} s must be a whole multiple of the "
                         f"step h = {h:g} s (h, 2h, ...) and at most t_end = {t_end:g} s",
                         key="output_step")
    if inertia_coupling not in ("auto", "constant", "full"):
        raise InputError(f"inertia_coupling {inertia_coupling!r}; valid: auto, constant, full",
                         key="inertia_coupling")
    threads = check_threads(threads)
    if max_mode_hz is not None:  # flexpipe#14 (robust)
        max_mode_hz = checked_number(max_mode_hz, "max_mode_hz", lo=0.0, hi=1e6, lo_closed=True)
    every = max(1, int(round(output_step / h)))
    if body in ("full", "flexible") and car.body.mesh is None and car.body.body_file is None:
        raise InputError(f"body='{body}' needs a body mesh; this car has only rigid mass "
                         "properties ([body.rigid]); use body='rigid'", file=car.file,
                         key="body.mesh")
    if body != "rigid":  # the mount ids, before a run writes anything (not at reduction)
        from flexpipe.vehicle.mounts import check_mount_node_ids

        check_mount_node_ids(car)
    if f_max is not None:
        f_max = checked_number(f_max, "f_max", lo=0.0, hi=5000.0)
    try:
        rates = np.asarray(initial_rates, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        rates = np.full(1, np.nan)
    if rates.shape != (3,) or not np.all(np.isfinite(rates)):
        raise InputError(f"initial_rates must be 3 finite numbers, got {initial_rates!r}",
                         key="initial_rates")
    start = abs(min(c.wheel_center[0] for c in car.corners)) + START_MARGIN_M
    travel = speed * t_end if profile is None else profile.distance(t_end)
    needed = start + travel + 10.0
    road_obj = as_road(road, needed)
    path_obj = road_obj.reference_path() if isinstance(path, str) and path == "road" \
        else as_path(path, needed, road_obj)  # path="road": follow the road's reference line
    what = f"{t_end:g} s at {speed * 3.6:.0f} km/h" if profile is None else \
        f"{t_end:g} s of the {profile.describe()}"
    if road is not None:  # (the default flat road is flat beyond its ends too)
        _check_road_covers(road_obj, path_obj, needed, what=what,
                           given=not (path is None or path in ("straight", "road")))
    path_obj.require_length(travel + 10.0, what=what, start=start)
    if driver is None:
        steering = speed_pi = None
    elif isinstance(driver, (str, Path)):
        from flexpipe.driver import read_driver

        steering, speed_pi = read_driver(driver)
    else:
        from flexpipe.driver import OpenLoopSteer, OpenLoopTorque, PurePursuit, SpeedPI

        try:
            steering, speed_pi = driver
        except (TypeError, ValueError):
            raise InputError("driver must be (steering, speed controller) or a driver TOML "
                             "file", key="driver") from None
        if not (isinstance(steering, (PurePursuit, OpenLoopSteer))
                and (speed_pi is None or isinstance(speed_pi, (SpeedPI, OpenLoopTorque)))):
            raise InputError("driver must be (PurePursuit or OpenLoopSteer, SpeedPI, "
                             "OpenLoopTorque or None) "
                             f"or a driver TOML file, got ({type(steering).__name__}, "
                             f"{type(speed_pi).__name__})", key="driver")
    if car.suspension is None:  # tyres and ride height at rest, before a run writes anything
        _check_ride_height(car)  # (last: it may fill the body cache)
    return RunArguments(car=car, body=body, speed=speed, t_end=t_end, h=h, every=every,
                        max_mode_hz=max_mode_hz, f_max=f_max, rates=rates, start=start,
                        road=road_obj, path=path_obj, steering=steering, speed_pi=speed_pi,
                        profile=profile, threads=threads)


def check_threads(threads) -> int | str:
    """Exudyn's threads for a run: a whole number from 1 to the cores this process may
    use, or ``"auto"``, returned as it is: ``simulate`` resolves it just before the time
    integration (:func:`flexpipe.exu.threads.auto_threads`: 2 for a flexible or full body
    when two cores are idle, else 1)."""
    if isinstance(threads, str) and threads == "auto":
        return threads
    from flexpipe.exu.threads import usable_cores

    cores = usable_cores()
    if isinstance(threads, (bool, np.bool_)) or not isinstance(threads, (int, np.integer)) \
            or not 1 <= threads <= cores:
        raise InputError(f"threads must be 'auto' or a whole number from 1 to {cores} (the "
                         f"cores this process may use), got {threads!r}", key="threads")
    return int(threads)


def speed_summary(speed) -> dict:
    """The ``summary.json`` fields of a run's ``speed`` argument: ``speed_kmh`` (the
    initial speed) and, for a profile, ``speed_profile`` (its points) and its file."""
    v0, prof = _speed(speed)
    out = {"speed_kmh": round(v0 * 3.6, 3)}
    if prof is not None:
        out["speed_profile"] = prof.describe()
        if prof.source:
            out["speed_profile_file"] = absolute(prof.source)
    return out


def _speed(speed):
    """``(initial speed, profile or None)`` of a run's ``speed`` argument: a number (m/s), a
    :class:`~flexpipe.driver.speed.SpeedProfile` or a profile file (.toml, .csv)."""
    from flexpipe.driver.speed import SpeedProfile, read_speed_profile

    if isinstance(speed, (str, Path)):
        speed = read_speed_profile(speed, speed_max=SPEED_MAX)
    if isinstance(speed, SpeedProfile):
        if speed.maximum > SPEED_MAX:
            raise InputError(f"the speed profile reaches {speed.maximum * 3.6:g} km/h; the "
                             f"highest allowed is {SPEED_MAX * 3.6:g} km/h", key="speed")
        if speed.is_constant:
            return speed.initial, None
        return speed.initial, speed
    return checked_number(speed, "speed", lo=0.0, hi=SPEED_MAX, lo_closed=True), None


def _check_road_covers(road, path, needed: float, *, what: str, given: bool) -> None:
    """Raise :class:`InputError` unless the road lies under the path from its start to
    ``needed`` metres along it (the car's body origin starts ``START_MARGIN_M`` beyond the
    rear wheels and stops 10 m short of that end): the road's distance ``x`` (``u`` along
    the reference line of an OpenCRG road) of those path points must lie within the
    road's samples, where a road holds its end heights."""
    s = np.concatenate([[0.0], path.s[(path.s > 0.0) & (path.s < needed)], [needed]])
    x, y = path.point_at(s)
    u = road.to_uv(x, y)[0]
    lo, hi = float(np.min(u)), float(np.max(u))
    x0, x1 = float(road.x[0]), float(road.x[-1])
    tol = 1e-9 * max(1.0, abs(x0), abs(x1))
    if lo >= x0 - tol and hi <= x1 + tol:
        return
    coord = "x" if road.plan is None else "u (along its reference line)"
    if given:
        why = (f"the path '{path.name}' is used as given (only the default straight path "
               "starts at the road's first sample): use a road whose distances cover the "
               "path, a path on the road, or --path road to follow the road")
    else:
        why = "use a longer road or a shorter run"
    raise InputError(f"road '{road.name}' covers {x0:g} .. {x1:g} m; {what} needs {coord} "
                     f"from {lo:g} to {hi:g} m; {why}", file=road.source or None)


def _check_ride_height(car) -> None:
    """The tyre files and the design wheel-centre heights of a prismatic-corner car against
    the tyres' static loaded radius (:func:`flexpipe.vehicle.corners.corner_arrays`), as
    the run itself checks them; the body's mass properties come from the cache."""
    from flexpipe.vehicle import bodymodel
    from flexpipe.vehicle.corners import corner_arrays
    from flexpipe.vehicle.simulation import _tires

    rb = bodymodel.rigid_properties(car)
    corner_arrays(car, rb.mass, rb.center_of_mass, tires=_tires(car))
