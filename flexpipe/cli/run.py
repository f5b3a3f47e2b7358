"""``flexpipe run CAR --road ROAD --path PATH --speed KMH``: simulate a car scenario.

Does for any car, road and path what ``make straight`` / ``make slalom`` do for the
sample: runs the car with the chosen body models (default rigid and flexible), writes
one CSV per run, ``hub_force_fl.png`` (and ``trajectory.png`` when a path is given) and
``summary.json`` into ``--out``.

A run is a transaction (:data:`OUTPUTS`): bad arguments are reported before anything is
written; the results are staged next to ``--out`` and put in its place only when the run
completes; a run that stops early, fails or is interrupted leaves ``--out`` as it was
and its own ``summary.json`` in ``OUT.failed``.

Examples::

    flexpipe run cars/sedan.toml --road roads/iso_c_200m.toml --speed 60 --t-end 8
    flexpipe run cars/sedan.toml --path paths/slalom_18m.toml --speed 60 --body rigid
    flexpipe run cars/sedan.toml --speed paths/speed_brake_100_40.toml --t-end 6
"""

from __future__ import annotations

import argparse
from pathlib import Path

#: what a run leaves in its output folder (shown by ``flexpipe run --help``)
OUTPUTS = """\
outputs: --out DIR receives BODY.csv (or .h5/.mat) per body model, hub_force_fl.png,
trajectory.png (with --path), summary.json and the durability files.  The run is a
transaction.  Bad arguments (--speed, --t-end, --h, --body, files, road or path too
short, an --out that is a file or a folder of other files) are reported before DIR is
created or touched.  The results are written to a staging folder .DIR.staging-PID and
renamed onto DIR only when the run completes (an earlier run in DIR is then replaced
as a whole; the next completed run also removes DIR.failed).  A run that stops early,
fails or is interrupted leaves DIR as it was (an earlier run's results stay) and puts
its own summary.json ("state": "stopped early", "error" or "interrupted", with the
message) and the files of the body runs that finished in DIR.failed, next to DIR.
Exit code 0 when every run reached --t-end, 1 when one stopped early, 2 on an error,
130/143 on Ctrl-C/SIGTERM.  --check-step is a transaction too: its DIR (default
out/<car>-<road>-<speed>kmh-check-step) receives step_check.csv and summary.json
("scenario": "check_step"); --t-from and every refined step are checked first."""


def add_arguments(parser) -> None:
    """Options of ``flexpipe run``."""
    parser.epilog = OUTPUTS
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.add_argument("car", help="car file (.toml), e.g. cars/sedan.toml")
    parser.add_argument("--road", default=None,
                        help="road file (.toml spec, .crg, .rdf, .csv); default: flat")
    parser.add_argument("--path", default=None,
                        help="path file (.csv x,y or .toml [path], e.g. "
                             "paths/slalom_18m.toml) or a keyword: 'straight' (the default: "
                             "straight from the road's first sample along its start heading; "
                             "along x from 0 for a road starting at 0 or no road) or 'road' "
                             "(follow the road's reference line)")
    parser.add_argument("--speed", required=True,
                        help="constant target speed in km/h, or a speed profile file: "
                             "speed against time or distance travelled (.toml "
                             "[speed_profile] or .csv, e.g. paths/speed_brake_100_40.toml)")
    parser.add_argument("--driver", default=None,
                        help="driver file (.toml): [steering] a path follower's gains or an "
                             "open-loop steering input (type = \"open_loop\": step, ramp, "
                             "sine_with_dwell, sine, table; e.g. paths/driver_step_steer.toml),"
                             " [speed] the speed controller's gains (optional); default: the "
                             "car's pure pursuit and PI controller")
    parser.add_argument("--t-end", type=float, default=10.0, help="simulated time, s (10)")
    parser.add_argument("--body", default="rigid,flexible",
                        help="comma-separated body models: rigid, flexible, full "
                             "(default: rigid,flexible)")
    parser.add_argument("--h", type=float, default=None,
                        help="time step, s (default 1.25e-3; 2.5e-4 for a linkage suspension "
                             "in compliant mode)")
    parser.add_argument("--out", default=None,
                        help="output directory (default: out/<car>-<road>-<speed>kmh); "
                             "replaced only by a completed run, see 'outputs' below")
    parser.add_argument("--no-cache", action="store_true", help="rebuild the reduced body")
    parser.add_argument("--f-max", type=float, default=None,
                        help="top of the flexible body's band, Hz (fixed-interface modes to "
                             "1.5x it; default from the road and speed, 20-40 Hz)")
    parser.add_argument("--check-step", action="store_true",
                        help="step-convergence study instead of a run: the first body model "
                             "at h, h/2 and h/4; prints the RMS hub-force differences (N, "
                             "and in percent of the finest run's fluctuation where that is "
                             "above a floor) and writes step_check.csv and summary.json "
                             "into --out (default out/<car>-<road>-<speed>kmh-check-step; "
                             "a run folder, replaced as a run's)")
    parser.add_argument("--t-from", type=float, default=None,
                        help="with --check-step: start of the comparison window, s "
                             "(default 0.5, skipping the start transient); at most "
                             "--t-end - --h")
    parser.add_argument("--no-prewarp", action="store_true",
                        help="integrate the flexible body's modes as they are instead of "
                             "pre-warped to the step (see README, step convergence)")
    parser.add_argument("--inertia-coupling", default="auto",
                        choices=("auto", "constant", "full"),
                        help="flexible body inertia: constant (Adams/Flex's constant coupling,"
                             " for mean-axis modes), full (Exudyn's complete floating-frame "
                             "terms) or auto (default: constant when the modes allow it)")
    parser.add_argument("--profile", action="store_true",
                        help="time Exudyn's parts of every step (constraints, body terms, "
                             "mass matrix, back-substitution) against the Python step; "
                             "printed and written to summary.json (profile_ms_per_step). "
                             "Uses Exudyn's range-checked module, which has these timers "
                             "(FLEXPIPE_EXUDYN=checked; slower than the default fast one)")
    parser.add_argument("--threads", default="auto", type=_threads_arg,
                        help="Exudyn's threads per run: a number, or auto (default: 2 for "
                             "the flexible body when two cores are idle, else 1); the "
                             "results equal one thread's to rounding")
    parser.add_argument("--format", default="csv", choices=("csv", "hdf5", "mat"),
                        help="channel files: csv (units in the header), hdf5 (h5py) or mat "
                             "(MATLAB); default csv")
    parser.add_argument("-q", "--quiet", action="store_true",
                        help="no progress messages (errors and warnings only)")


def _threads_arg(text: str):
    """``--threads``: ``auto`` or a whole number (range checked by ``check_run``)."""
    if text == "auto":
        return text
    try:
        return int(text)
    except ValueError:
        import argparse

        raise argparse.ArgumentTypeError(f"'{text}': give auto or a whole number of "
                                         "threads, e.g. 2") from None


def run(args) -> int:
    """Run the scenario; exit code 0 when every run reached its end time, else 1.

    Every argument is checked before anything is written (:func:`check_arguments`).
    The output folder is replaced as a whole only when the run completes; a run that
    stops early, fails or is interrupted leaves it as it was and writes ``OUT.failed``
    (see :data:`OUTPUTS` and :func:`~flexpipe.scenarios.runner.run_pair`)."""
    import os

    bodies = check_arguments(args)
    if args.profile:  # only the range-checked module times the parts (flexpipe.exu.MODULE_ENV)
        os.environ.setdefault("FLEXPIPE_EXUDYN", "checked")
    from flexpipe.scenarios.runner import run_pair

    out = args.out
    if out is None:
        tag = Path(args.road).stem if args.road else (Path(args.path).stem if args.path
                                                      else "flat")
        out = Path("out") / (f"{Path(args.car).stem}-{tag}-{args.speed_tag}"
                             + ("-check-step" if args.check_step else ""))
    if args.check_step:
        return _check_step(args, bodies[0], Path(out))
    title = (f"{Path(args.road).name if args.road else 'flat road'}, "
             f"{Path(args.path).name if args.path else 'straight'}, {args.speed_label}")
    summary = run_pair(args.car, road=args.road, path=args.path, speed=args.speed_value,
                       t_end=args.t_end, out=out, title=title,
                       plots=("hub_force_fl", "trajectory"), bodies=bodies,
                       cache=not args.no_cache, h=args.h, name="run", format=args.format,
                       log=(lambda *a: None) if args.quiet else print,
                       progress=not args.quiet, prewarp=not args.no_prewarp,
                       inertia_coupling=args.inertia_coupling, profile=args.profile,
                       f_max=args.f_max, driver=args.driver, threads=args.threads)
    if args.profile and not args.quiet:
        _print_profile(summary)
    if summary["status"] != 0:
        import sys

        from flexpipe._io import failed_folder

        print(f"flexpipe run: stopped early ({'; '.join(summary['messages'].values())}); "
              f"{out} is unchanged; this run's files are in {failed_folder(out)}",
              file=sys.stderr)
        return 1
    return 0


def check_arguments(args) -> tuple[str, ...]:
    """The body models of ``--body``, after checking the numbers of a ``flexpipe run`` in
    the options' own units (``--speed`` in km/h) against the ranges that
    :func:`~flexpipe.vehicle.run_inputs.check_run` accepts.

    Raises
    ------
    InputError
        Naming the option, its unit and the valid range.
    """
    from flexpipe.errors import FlexpipeError, InputError
    from flexpipe.vehicle.run_inputs import (
        DEFAULT_STEP,
        H_MAX,
        H_MIN,
        T_END_MAX,
        checked_number,
        default_step,
    )

    bodies = tuple(b.strip() for b in args.body.split(",") if b.strip())
    bad = [b for b in bodies if b not in ("rigid", "flexible", "full")]
    if bad or not bodies:
        raise InputError(f"--body {args.body!r}: valid body models are rigid, flexible, full "
                         "(comma-separated)", key="body")
    _check_speed(args)
    t_end = checked_number(args.t_end, "--t-end", lo=0.0, hi=T_END_MAX, unit="s",
                           key="t_end")
    if args.h is None:
        try:  # the car's default step; a bad car file is named by the run's own checks
            h = default_step(args.car)
        except FlexpipeError:
            h = DEFAULT_STEP
    else:
        h = checked_number(args.h, "--h", lo=H_MIN, hi=H_MAX, lo_closed=True, unit="s",
                           key="h")
    if h > t_end:
        raise InputError(f"--h {h:g} s is longer than --t-end {t_end:g} s; choose --h <= "
                         "--t-end", key="h")
    _check_step_arguments(args, h=h, t_end=t_end)
    if getattr(args, "f_max", None) is not None:
        checked_number(args.f_max, "--f-max", lo=0.0, hi=5000.0, unit="Hz", key="f_max")
        if "flexible" not in bodies:
            raise InputError(f"--f-max is the band of the flexible body; --body "
                             f"{','.join(bodies)} has none (the full body keeps every mode "
                             "to 250 Hz)", key="f_max")
    return bodies


def _check_speed(args) -> None:
    """``--speed``: a number in km/h or a speed profile file; sets ``args.speed_value``
    (m/s or the profile), ``args.speed_label`` and ``args.speed_tag`` (for titles and the
    default output folder)."""
    from flexpipe.driver.speed import read_speed_profile
    from flexpipe.vehicle.run_inputs import SPEED_MAX, checked_number

    text = str(args.speed).strip()
    try:
        number = float(text)
    except ValueError:
        number = None
    if number is None and not Path(text).suffix:
        from flexpipe.errors import InputError

        raise InputError(f"--speed {text!r} is neither a number (km/h) nor a speed profile "
                         "file (.toml with a [speed_profile] table, or .csv)", key="speed")
    if number is not None:
        kmh = checked_number(number, "--speed", lo=0.0, hi=round(SPEED_MAX * 3.6, 6),
                             lo_closed=True, unit="km/h", key="speed")
        args.speed_value, args.speed_label, args.speed_tag = kmh / 3.6, f"{kmh:g} km/h", \
            f"{kmh:g}kmh"
        return
    prof = read_speed_profile(text, speed_max=SPEED_MAX)
    args.speed_value = prof
    args.speed_label = f"speed profile {Path(text).name}"
    args.speed_tag = Path(text).stem


def _check_step_arguments(args, *, h: float, t_end: float) -> None:
    """``--t-from`` (only with ``--check-step``) and, for ``--check-step``, the window
    ``--t-from`` .. ``--t-end`` and the finest step h/4, in the options' terms."""
    from flexpipe.errors import InputError
    from flexpipe.scenarios.runner import HUB_COMPARE_FRACTION, HUB_COMPARE_FROM
    from flexpipe.vehicle.convergence import DEFAULT_T_FROM
    from flexpipe.vehicle.run_inputs import H_MIN, T_END_MAX, checked_number

    if not getattr(args, "check_step", False):
        if getattr(args, "t_from", None) is not None:
            raise InputError("--t-from is the start of --check-step's comparison window; "
                             "give it with --check-step (a run compares rigid and flexible "
                             f"from min({HUB_COMPARE_FROM:g} s, {HUB_COMPARE_FRACTION:g} x "
                             "--t-end))", key="t_from")
        return
    t_from = DEFAULT_T_FROM if args.t_from is None else checked_number(
        args.t_from, "--t-from", lo=0.0, hi=T_END_MAX, lo_closed=True, unit="s", key="t_from")
    if t_from > t_end - h:
        default = " (the default)" if args.t_from is None else ""
        raise InputError(
            f"--t-from {t_from:g} s{default} leaves no comparison window before --t-end "
            f"{t_end:g} s: --check-step compares the runs from --t-from to --t-end; give "
            f"--t-from <= {t_end - h:g} s (--t-end - --h), e.g. --t-from {t_end / 2:g}, or a "
            f"longer --t-end", key="t_from")
    if h / 4 < H_MIN:
        raise InputError(f"--check-step also runs h/2 and h/4 = {h / 4:g} s, below the "
                         f"smallest step {H_MIN:g} s; give --h >= {4 * H_MIN:g} s", key="h")


def _print_profile(summary: dict) -> None:
    """The per-step profile of each body run as a small table (ms per step)."""
    prof = summary.get("profile_ms_per_step", {})
    if not prof:
        return
    bodies = list(prof)
    from flexpipe.exu import MODULES

    module = summary.get("exudyn_module")
    clock = ("CPU time" if module == MODULES["fast"] else
             "wall-clock time (Exudyn's timers; a loaded machine inflates them)")
    print(f"{clock} per step, ms (Exudyn module {module})")
    print(" " * 17 + "".join(f"{b:>12s}" for b in bodies))
    for part in next(iter(prof.values())):
        print(f"  {part:28s}" + "".join(f"{prof[b].get(part, float('nan')):12.4f}"
                                        for b in bodies))
    its = summary.get("newton_iterations_per_step", {})
    print(f"  {'Newton iterations per step':28s}" + "".join(
        f"{its.get(b, float('nan')):12.3f}" for b in bodies))


def _check_step(args, body: str, out: Path) -> int:
    """``--check-step``: h, h/2, h/4 for one body model; the table to stdout, the study
    into the run folder ``out`` (:func:`~flexpipe.scenarios.step_study.run_step_check`);
    ``-q`` leaves only the table."""
    from flexpipe.scenarios.step_study import run_step_check

    path = None if args.path in (None, "straight") else args.path
    title = (f"{Path(args.road).name if args.road else 'flat road'}, "
             f"{Path(args.path).name if args.path else 'straight'}, {args.speed_label}")
    summary, _ = run_step_check(
        args.car, out=out, road=args.road, path=path, speed=args.speed_value,
        t_end=args.t_end, body=body, h=args.h, refinements=(2, 4), t_from=args.t_from,
        cache=not args.no_cache, prewarp=not args.no_prewarp,
        inertia_coupling=args.inertia_coupling, title=title, f_max=args.f_max,
        driver=args.driver, threads=args.threads,
        log=(lambda *a: None) if args.quiet else print, progress=not args.quiet,
        report=print)
    if summary["status"] != 0:  # as a run that stops early: exit 1, out unchanged
        import sys

        from flexpipe._io import failed_folder

        print(f"flexpipe run: stopped early ({summary['message']}); {out} is unchanged; "
              f"this study's files are in {failed_folder(out)}", file=sys.stderr)
        return 1
    return 0
