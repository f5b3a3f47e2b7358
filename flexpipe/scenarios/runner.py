"""Scenario runner: the same car with a rigid and a flexible body, CSVs, plots, summary."""

from __future__ import annotations

import json
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from flexpipe._io import absolute, write_text_atomic
from flexpipe.errors import FlexpipeError, InputError
from flexpipe.vehicle.spec import CORNERS

ROOT = Path(__file__).resolve().parents[2]
DEFAULT_CAR = ROOT / "cars" / "sedan_linkage.toml"
#: the rigid-vs-flexible hub-force comparison leaves out the start-up transient: the first
#: ``HUB_COMPARE_FROM`` s, or the first ``HUB_COMPARE_FRACTION`` of a shorter run
HUB_COMPARE_FROM = 0.5
HUB_COMPARE_FRACTION = 0.25


def _straight_road():
    from flexpipe.roads import iso8608

    return iso8608("C", length=260.0, dx=0.05, seed=8608, track_width=1.55, fade=5.0)


def _slalom_road():
    from flexpipe.roads import iso8608

    return iso8608("B", length=260.0, dx=0.05, seed=8609, track_width=1.55, fade=5.0)


def _slalom_path():
    from flexpipe.driver import slalom

    return slalom(cone_spacing=18.0, n_cones=8, offset=0.8, lead_in=40.0, lead_out=60.0)


@dataclass(frozen=True)
class Scenario:
    """A ready-made run: speed (km/h), duration (s), road and path factories, plots."""

    name: str
    title: str
    speed_kmh: float
    t_end: float
    road: object
    path: object = None
    plots: tuple = ("hub_force_fl",)
    notes: dict = field(default_factory=dict)


SCENARIOS = {
    "straight": Scenario(
        "straight", "straight ISO 8608 class C road, 70 km/h", 70.0, 10.0, _straight_road,
        None, ("hub_force_fl",),
        {"road": "ISO 8608 class C (Gd(n0) = 256e-6 m^3), 260 m, seed 8608, 5 m fade-in"}),
    "slalom": Scenario(
        "slalom", "slalom 8 cones x 18 m, offset 0.8 m, 60 km/h, ISO 8608 class B road",
        60.0, 10.0, _slalom_road, _slalom_path, ("hub_force_fl", "trajectory"),
        {"road": "ISO 8608 class B (Gd(n0) = 64e-6 m^3), 260 m, seed 8609",
         "path": "slalom(cone_spacing=18, n_cones=8, offset=0.8, lead_in=40, lead_out=60) "
                 "(as paths/slalom_18m.toml; peak path curvature asks 6.8 m/s^2)"}),
}


def _summary_diffs(diff: dict) -> dict:
    out = {}
    for name, d in diff.items():
        key = name.removeprefix("hub_")
        out[key] = {"rms_diff_N": round(d["rms_diff"], 3), "peak_diff_N": round(d["peak_diff"], 3),
                    "rel_rms_diff": round(d["rel_rms_diff"], 6),
                    "rel_rms_diff_dynamic": round(d["rel_rms_diff_dynamic"], 6),
                    "rms_rigid_N": round(d["rms_a"], 3), "rms_flexible_N": round(d["rms_b"], 3)}
    return out


def run_pair(car, *, road, path, speed: float, t_end: float, out, title: str,
             plots=("hub_force_fl",), bodies=("rigid", "flexible"), cache: bool = True,
             h: float | None = None, notes=None, name: str = "run", log=print,
             format: str = "csv", progress: bool = True,  # noqa: A002
             prewarp: bool = True, inertia_coupling: str = "auto",
             profile: bool = False, f_max: float | None = None, driver=None,
             threads: int | str = 1) -> dict:
    """Simulate ``car`` with each body kind, write channel files, plots and ``summary.json``.

    ``f_max`` (Hz) is the flexible body's band (``simulate``'s; default from the road and
    speed, :func:`flexpipe.vehicle.bodymodel.choose_band`); ``driver`` and ``threads``
    are ``simulate``'s (a driver file, or the controllers; default the car's; Exudyn's
    threads, ``"auto"`` chosen per body).

    The run is a transaction.  Every argument (numbers, body kinds, car, road and path
    files, road and path lengths) and the output folder are checked first
    (:func:`~flexpipe.vehicle.run_inputs.check_run`); a bad one raises before anything
    is written.  Then everything is written into a staging folder next to ``out``,
    which replaces ``out`` as a whole only when the run completes, so ``out`` never
    mixes files of two runs.  A run that stops early (``status`` -1), fails or is
    interrupted (Ctrl-C, SIGTERM) leaves ``out`` as it was (an earlier run's results
    stay) and puts its staging folder in place of ``OUT.failed`` next to it
    (:func:`flexpipe._io.failed_folder`): its ``summary.json`` (``state`` "stopped
    early", "error" or "interrupted", the message) and the files of the runs that
    finished; an exception propagates with a note naming that folder.  A completed run
    removes an earlier run's ``OUT.failed``.  A channel file that cannot be written in
    ``format`` (``hdf5``, ``mat``) is written as CSV instead and the other runs, plots
    and durability outputs go on; the run then counts as failed (``state`` "error",
    ``OUT.failed`` holds every output) and a :class:`~flexpipe.errors.FlexpipeError`
    says which file failed and where its channels are.

    Returns
    -------
    dict
        The summary: ``status`` 0 when every run reached its end time, -1 when one
        stopped early; ``state`` "completed" or "stopped early".
    """
    from flexpipe._io import check_run_folder, commit_directory, failed_folder, stage_directory
    from flexpipe.vehicle.export import check_format
    from flexpipe.vehicle.run_inputs import check_run, speed_summary
    from flexpipe.vehicle.simulation import simulate
    from flexpipe.vehicle.spec import Car, load_car

    fmt = check_format(format)  # before minutes of simulation
    car = car if isinstance(car, Car) else load_car(car)
    if isinstance(road, (str, Path)):
        from flexpipe.roads import load_road

        road = load_road(road)
    if isinstance(speed, (str, Path)):  # a speed profile file, read once for every body
        from flexpipe.driver.speed import read_speed_profile
        from flexpipe.vehicle.run_inputs import SPEED_MAX

        speed = read_speed_profile(speed, speed_max=SPEED_MAX)
    if isinstance(path, str) and path == "road":       # follow the road's reference line
        if road is None or not hasattr(road, "reference_path"):
            raise InputError("path 'road' follows the road's reference line: give a road "
                             "file", key="path")
        path = road.reference_path()
    elif isinstance(path, (str, Path)) and path != "straight":
        from flexpipe.driver import read_path

        path = read_path(path)
    elif path == "straight":
        path = None
    bodies = tuple(bodies)
    if not bodies:
        raise InputError("give at least one body kind", key="bodies")
    kw = {} if h is None else {"h": h}
    if f_max is not None:
        kw["f_max"] = f_max
    if driver is not None:
        kw["driver"] = driver
    for body in bodies:  # every argument checked before the output folder is touched
        check_run(car, road=road, path=path, speed=speed, t_end=t_end, body=body,
                  prewarp=prewarp, inertia_coupling=inertia_coupling, threads=threads, **kw)
    out = check_run_folder(out)  # after the arguments, so their errors come first
    stage = stage_directory(out)
    results, files, output_errors = {}, [], []
    base = {"scenario": name, "title": title, "car": car.name, "car_file": absolute(car.file),
            **speed_summary(speed), **({"notes": notes} if notes else {})}
    t0 = time.perf_counter()
    try:
        for i, body in enumerate(bodies, 1):
            log(f"[{i}/{len(bodies)}] {car.name}: {body} body, {title}")
            r = simulate(car, road=road, path=path, speed=speed, t_end=t_end, body=body,
                         progress=progress, cache=cache, log=lambda m: log("      " + m),
                         prewarp=prewarp, inertia_coupling=inertia_coupling,
                         profile=profile, threads=threads, **kw)
            results[body] = r
            files.append(_save_channels(r, stage, body, fmt, output_errors, log=log))
            n_thr = r.info.get("threads", 1)
            log(f"      {r.message}; " + (
                f"CPU {r.cpu_time:.2f} s for {r.simulated_time:.2f} s simulated (real-time "
                f"factor {r.realtime_factor:.2f})" if n_thr == 1 else
                f"{r.wall_time:.2f} s wall-clock time on {n_thr} threads for "
                f"{r.simulated_time:.2f} s simulated (real-time factor "
                f"{r.wall_realtime_factor:.2f}; CPU {r.cpu_time:.2f} s)"))
        summary = _summary(base, results, path=path, speed=speed)
        files += _plots(results, stage, plots=plots, path=path, title=title)
        files += _handling(results, stage, summary, car=car, title=title)
        summary["files"] = sorted(files + ["summary.json"])
        _durability(stage, results, summary, car=car, road=road, log=log, progress=progress,
                    final=out)
    except BaseException as exc:
        _write_failure(stage, base, results, files, exc, bodies=bodies, t0=t0,
                       output_errors=output_errors)
        failed = commit_directory(stage, failed_folder(out))
        exc.add_note(f"{out} {_kept(out)}; this run's summary.json is in {failed}")
        raise
    if output_errors:  # every result is kept, but not in the format asked for
        summary.update(status=2, state="error", message="; ".join(output_errors))
    summary["total_wall_time_s"] = round(time.perf_counter() - t0, 2)
    write_text_atomic(stage / "summary.json", json.dumps(summary, indent=2) + "\n")
    if summary["status"] != 0:  # stopped early or a format failed: out stays as it was
        failed = commit_directory(stage, failed_folder(out))
        if output_errors:
            raise FlexpipeError(f"{summary['message']}; {out} {_kept(out)}; this run's "
                                f"files are in {failed}/")
        log(f"stopped early; {out} {_kept(out)}; this run's files are in {failed}/")
        return summary
    commit_directory(stage, out)
    _remove_stale_failure(failed_folder(out))
    log(f"wrote {out}/: {', '.join(summary['files'])}")
    d = summary.get("hub_force_difference_rigid_vs_flexible", {}).get("fl_z")
    if d is not None:
        log(f"front-left vertical hub force, rigid vs flexible: RMS difference "
            f"{d['rms_diff_N']:.1f} N ({100 * d['rel_rms_diff_dynamic']:.1f} % of the rigid "
            f"force's fluctuation, {100 * d['rel_rms_diff']:.2f} % of its RMS), peak "
            f"{d['peak_diff_N']:.1f} N; " + _time_ratio(summary))
    return summary


def _time_ratio(summary: dict) -> str:
    """The flexible / rigid time of the closing line: CPU on one thread each, else
    wall-clock time with the threads named (two threads' CPU counts the spinning one)."""
    thr = summary.get("threads", {})
    if thr.get("flexible", 1) == thr.get("rigid", 1) == 1:
        return f"CPU flexible/rigid {summary['cpu_ratio_flexible_to_rigid']:.2f}"
    return (f"wall-clock time flexible/rigid {summary['wall_ratio_flexible_to_rigid']:.2f} "
            f"(threads {thr.get('flexible', 1)} / {thr.get('rigid', 1)}; CPU "
            f"{summary['cpu_ratio_flexible_to_rigid']:.2f})")


def _kept(out: Path) -> str:
    return "keeps the previous run" if out.exists() else "was not created"


def _remove_stale_failure(failed: Path) -> None:
    """A completed run removes the ``OUT.failed`` of an earlier failed run (only a run
    folder: :func:`flexpipe._io.check_run_folder` refused any other content)."""
    import shutil

    if (failed / "summary.json").is_file():
        shutil.rmtree(failed, ignore_errors=True)


def _summary(base: dict, results: dict, *, path, speed) -> dict:
    from flexpipe.scenarios.comfort import ride_summary
    from flexpipe.vehicle.result import compare

    ok = all(r.status == 0 for r in results.values())
    summary = {
        **base, "status": 0 if ok else -1, "state": "completed" if ok else "stopped early",
        "messages": {b: r.message for b, r in results.items()},
        "simulated_time_s": min(r.simulated_time for r in results.values()),
        "cpu_time_s": {b: round(r.cpu_time, 3) for b, r in results.items()},
        "wall_time_s": {b: round(r.wall_time, 3) for b, r in results.items()},
        "realtime_factor": {b: round(r.realtime_factor, 3) for b, r in results.items()},
        "wall_realtime_factor": {b: round(r.wall_realtime_factor, 3)
                                 for b, r in results.items()},
        "threads": {b: r.info.get("threads", 1) for b, r in results.items()},
        "time_step_s": next(iter(results.values())).info["h"],
        "driver": {k: next(iter(results.values())).info.get(k)
                   for k in ("steering", "speed_control")},
        "exudyn_module": next(iter(results.values())).info.get("exudyn_module"),
        "newton_iterations_per_step": {b: r.info.get("newton_iterations_per_step")
                                       for b, r in results.items()},
    }
    prof = {b: r.info["profile_ms_per_step"] for b, r in results.items()
            if "profile_ms_per_step" in r.info}
    if prof:  # flexpipe run --profile: Exudyn's timers and the Python step, ms per step
        summary["profile_ms_per_step"] = prof
    t_end = min(r.simulated_time for r in results.values())
    summary.update(ride_summary(results, t_from=_t_from(t_end)))
    summary["ride_note"] = (
        "ISO 2631-1: aw weighted RMS (Wd x, y; Wk z), a_v = sqrt(sum aw^2) (comfort, "
        "factors 1) and its Annex C reaction, at each named body point in body axes and "
        "on each seat (the occupant on the cushion over its floor_point; SEAT_% = its aw_z "
        "over the floor's); dynamic load coefficient = std / mean of the vertical tyre "
        "force; the samples of the hub-force comparison")
    if "rigid" in results and "flexible" in results:
        ra, rb = results["rigid"], results["flexible"]
        summary["cpu_ratio_flexible_to_rigid"] = round(rb.cpu_time / max(ra.cpu_time, 1e-9), 3)
        summary["wall_ratio_flexible_to_rigid"] = round(rb.wall_time / max(ra.wall_time, 1e-9),
                                                        3)
        if ra.status == 0 and rb.status == 0:
            t_from = _t_from(ra.simulated_time)
            diff = compare(ra, rb, t_from=t_from)
            summary["hub_force_difference_rigid_vs_flexible"] = _summary_diffs(diff)
            summary["hub_force_difference_note"] = (
                f"rigid minus flexible, from t = {t_from:g} s (min({HUB_COMPARE_FROM:g} s, "
                f"{HUB_COMPARE_FRACTION:g} x the run's {ra.simulated_time:g} s)); "
                "rel_rms_diff = rms_diff / "
                "rms_rigid (static load included), rel_rms_diff_dynamic = rms_diff / "
                "std_rigid (fluctuating part); hub force = force the corner applies to the "
                "body, summed over its mounts (a prismatic corner has one, its hardpoint), "
                "body axes")
        else:
            summary["hub_force_difference_note"] = (
                "not computed: the rigid and flexible runs did not both reach t_end "
                "(differences of diverged fragments would mean nothing)")
    fb = [r for r in results.values() if r.body != "rigid"]
    if fb:
        info = fb[0].info
        summary["flexible_body"] = {k: info.get(k) for k in (
            "n_elastic_modes", "band_hz", "highest_mode_hz", "reduction_s", "reduction_cached",
            "modal_prewarp", "inertia_coupling")}
    summary["static_wheel_load_N"] = {c: round(v, 3) for c, v in zip(
        CORNERS, next(iter(results.values())).info["static_wheel_load_N"], strict=True)}
    if path is not None:
        summary["lateral_error_max_m"] = {
            b: round(float(np.nanmax(np.abs(r["lateral_error"][r.t >= 1.0]))), 4)
            if np.any(r.t >= 1.0) else None for b, r in results.items()}
    return summary


def _save_channels(result, stage, body: str, fmt: str, errors: list, *, log) -> str:
    """Write ``result``'s channel file ``BODY.SUFFIX``; returns the name written.

    When the writer of an optional format (``hdf5``, ``mat``) raises, the channels are
    written as ``BODY.csv`` instead (the run is not lost) and the one-line reason is
    appended to ``errors``.
    """
    from flexpipe.vehicle.export import SUFFIX

    name = f"{body}{SUFFIX[fmt]}"
    try:
        return result.save(stage / name, format=fmt).name
    except Exception as exc:  # noqa: BLE001 - any writer failure: keep the run as CSV
        if fmt == "csv":
            raise
        reason = " ".join(str(exc).split()) or type(exc).__name__
        if not isinstance(exc, FlexpipeError):
            reason = f"{type(exc).__name__}: {reason}"
        fallback = result.save(stage / f"{body}.csv", format="csv").name
        errors.append(f"{name}: cannot write format {fmt!r} ({reason}); the {body} "
                      f"run's channels are in {fallback} instead")
        log(f"      error: {errors[-1]}")
        return fallback


def _t_from(t_end: float) -> float:
    """Start of the samples compared and summarised: past the start-up."""
    return min(HUB_COMPARE_FROM, HUB_COMPARE_FRACTION * t_end)


def _plots(results, stage, *, plots, path, title) -> list:
    from flexpipe.vehicle import plots as P

    files = []
    if "hub_force_fl" in plots:
        plot_title = f"Vertical force on the front-left wheel hub\n{title}"
        files.append(P.hub_force(results, stage / "hub_force_fl.png", title=plot_title).name)
    if "trajectory" in plots and path is not None:
        files.append(P.trajectory(results, path, stage / "trajectory.png").name)
    # where rigid and flexible differ, by frequency: both complete, 2 s past the start-up
    done = {b: r for b, r in results.items() if r.status == 0}
    t_end = min(r.simulated_time for r in results.values())
    if ("rigid" in done and len(done) == len(results) >= 2
            and t_end - _t_from(t_end) >= 2.0 and "hub_fl_z" in done["rigid"].channels):
        files.append(P.spectra(done, stage / "spectra.png", t_from=_t_from(t_end),
                               title=f"Spectra of the runs\n{title}").name)
    return files


def _handling(results, stage, summary, *, car, title) -> list:
    """On a circle path (ISO 4138): ``handling.png`` and ``summary["handling"]``, the
    understeer gradient of each completed body run (:mod:`flexpipe.vehicle.handling`); a
    run that covers too little lateral acceleration gets a note instead.  With an
    open-loop steering input: :func:`_open_loop`."""
    from flexpipe.vehicle import handling

    files = _open_loop(results, stage, summary, car=car, title=title)
    done = {b: r for b, r in results.items()
            if r.status == 0 and str(r.info.get("path", "")).startswith("circle(")}
    if not done:
        return files
    diagrams, out = {}, {}
    for body, r in done.items():
        try:
            d = handling.handling_diagram(r, wheelbase=car.wheelbase,
                                          t_from=min(5.0, 0.5 * r.simulated_time))
        except InputError as exc:
            out[body] = {"note": exc.message}
            continue
        diagrams[body] = d
        out[body] = {"understeer_gradient_deg_per_g": round(d.gradient_deg_per_g, 4),
                     "understeer_angle_at_0_deg": round(d.intercept_deg, 4),
                     "ay_fit_mps2": list(d.ay_fit), "samples_fitted": d.n_fit,
                     "ay_max_mps2": round(float(abs(d.ay).max()), 4)}
    summary["handling"] = out
    if not diagrams:
        return files
    handling.plot(diagrams, stage / "handling.png", title=f"Handling diagram\n{title}")
    return files + ["handling.png"]


def _open_loop(results, stage, summary, *, car, title) -> list:
    """An open-loop steering input: ``steer_response.png``; for a step steer also
    ``summary["step_steer"]`` (ISO 7401 figures), for a sine with dwell
    ``summary["sine_with_dwell"]`` (UN R140 criteria) of each completed run."""
    from flexpipe.vehicle import handling

    done = {b: r for b, r in results.items() if r.status == 0 and
            str(r.info.get("steering", "")).startswith("open-loop steering")}
    if not done:
        return []
    cg = handling.centre_of_mass(next(iter(done.values())), car)
    kinds = (("step", "step_steer", handling.step_response),
             ("sine with dwell", "sine_with_dwell", handling.sine_with_dwell_response))
    for prefix, key, figures in kinds:
        if not any(str(r.info["steering"]).startswith(f"open-loop steering: {prefix}")
                   for r in done.values()):
            continue
        out = {}
        for body, r in done.items():
            try:
                out[body] = figures(r, cg=cg)
            except InputError as exc:
                out[body] = {"note": exc.message}
        summary[key] = out
    handling.plot_response(done, stage / "steer_response.png", cg=cg,
                           title=f"{next(iter(done.values())).info['steering']}\n{title}")
    return ["steer_response.png"]


def _write_failure(stage, base, results, files, exc, *, bodies, t0, output_errors=()) -> None:
    """summary.json of a run that raised: state, message (and the channel files written
    as CSV instead of their format, ``output_errors``), the runs that finished."""
    from flexpipe._signals import interrupt_info, interrupt_text

    running = next((b for b in bodies if b not in results), None)
    if isinstance(exc, KeyboardInterrupt):
        code, _ = interrupt_info(exc)
        state, status = "interrupted", code
        message = interrupt_text(exc) + (f" during the {running} body run" if running else "")
    else:
        state, status = "error", 2
        message = " ".join(str(exc).split()) or type(exc).__name__
        if not isinstance(exc, FlexpipeError):
            message = f"{type(exc).__name__}: {message}"
    message = "; ".join([message, *output_errors])
    summary = {**base, "status": status, "state": state, "message": message,
               "completed_runs": {b: r.message for b, r in results.items()},
               "files": sorted(files + ["summary.json"]),
               "total_wall_time_s": round(time.perf_counter() - t0, 2)}
    write_text_atomic(stage / "summary.json", json.dumps(summary, indent=2) + "\n")


def _durability(out, results, summary, *, car, road, log, progress=False, final=None):
    """Durability outputs (feat/durability): body motion, hardpoints, stress and fatigue
    (``stress/``), ParaView animation (``animation/``); ``summary["file_descriptions"]``
    says what every file holds.  ``out`` is the staging folder, ``final`` the folder it
    becomes (the paths printed); ``progress`` shows the stress and frame progress bars."""
    from flexpipe.durability.pipeline import scenario_outputs

    if road is None:
        from flexpipe.roads import flat

        road = flat(1000.0, dx=1.0, track_width=1.5)
    t0 = time.perf_counter()
    desc = scenario_outputs(out, results, car=car, road=road, title=summary["title"], log=log,
                            progress=progress, final=final)
    if "flexible" in results:  # the durability outputs are the flexible body's
        summary["durability_wall_time_s"] = round(time.perf_counter() - t0, 2)
    flexible = results.get("flexible")
    if flexible is not None and flexible.status != 0:
        summary["durability"] = ("skipped: the flexible run did not complete "
                                 f"({flexible.message})")
    summary["files"] = sorted(set(summary["files"]) | set(desc))
    summary["file_descriptions"] = dict(sorted(desc.items()))


def run_scenario(name: str, *, out, car=None, t_end=None, cache: bool = True, log=print,
                 threads: int | str = "auto") -> dict:
    """Run the named scenario (see :data:`SCENARIOS`); ``threads`` as :func:`run_pair`'s
    (``"auto"``: two for the flexible body when two cores are idle)."""
    if name not in SCENARIOS:
        raise InputError(f"unknown scenario {name!r}; valid: {sorted(SCENARIOS)}", key="name")
    sc = SCENARIOS[name]
    path = sc.path() if sc.path is not None else None
    return run_pair(car or DEFAULT_CAR, road=sc.road(), path=path, speed=sc.speed_kmh / 3.6,
                    t_end=sc.t_end if t_end is None else t_end, out=out, title=sc.title,
                    plots=sc.plots, cache=cache, notes=sc.notes, name=name, log=log,
                    threads=threads)
