"""``flexpipe linear CAR.toml``: linear modes of the whole car (Adams/Linear).

Assembles the car as ``flexpipe run`` does, settles it at rest (or runs it straight on a
flat road at ``--speed`` until steady), linearizes body, suspension and tyres there and
prints the modes: natural and damped frequency, damping ratio and the dominant motion by
kinetic energy (:func:`flexpipe.vehicle.linear.linear_modes`).  Writes
``linear_modes.csv`` / ``.json`` / ``.png`` into ``--out`` (default
``out/linear/<car>-<body>-<speed>kmh``); ``linear_frf.csv`` / ``.png``: the vertical
tyre forces and floor accelerations per metre of a road whose two tracks carry the same
profile (at rest: all four wheels in phase), ``linear_frf_opposite.*`` the same for the
right track carrying the left one's negative (roll input); ``linear_state_space.mat``:
the state matrices A, B, C, D with the input, output and state names (MATLAB
``ss(A, B, C, D)``); and for a flexible body
``linear_modes.vtu``: the body's mesh with the modes up to ``--show`` as displacement
fields for ParaView.  With ``--road-class`` (and ``--speed``) also the ride on an ISO 8608
road from the linear model (:func:`flexpipe.vehicle.linear_ride.ride_response`): RMS of
the tyre forces and floor accelerations, ISO 2631-1 weighted RMS and comfort values,
``ride.csv`` / ``.json`` and ``ride_psd.csv`` / ``.png``.
"""

from __future__ import annotations

import argparse
import math

BODIES = ("rigid", "flexible", "full")

_EPILOG = """\
The linear model holds the controls fixed (no driver, no speed controller); a dual-rate
damper enters with the mean of its two slopes at zero velocity; at rest no brake acts (the
car may roll away: a free mode, counted and not listed).  Needs a car with linkage
suspensions.  Check: tests/test_linear.py releases the car from a disturbed state and
compares the nonlinear run with the linear model's response.
"""


def add_arguments(p) -> None:
    """Options of ``flexpipe linear``."""
    p.formatter_class = argparse.RawDescriptionHelpFormatter
    p.epilog = _EPILOG
    p.add_argument("car", help="car file with [suspension.front] / [suspension.rear]")
    p.add_argument("--speed", type=float, default=0.0, metavar="KMH",
                   help="0 (default): parked and settled; > 0: straight on a flat road at "
                        "this speed, km/h, linearized after 2 s")
    p.add_argument("--show", type=float, default=60.0, metavar="HZ",
                   help="print the modes up to this frequency, Hz (default 60; the files "
                        "hold all)")
    p.add_argument("--road-class", default=None, metavar="CLASS",
                   help="with --speed: the ride on an ISO 8608 road of this class (A..H) "
                        "from the linear model: RMS, ISO 2631-1 weighted RMS and spectra "
                        "(ride.csv/.json, ride_psd.csv/.png)")
    add_model_arguments(p, what="with --road-class: ")
    add_reference_argument(p, what="with --road-class: ")
    p.add_argument("-o", "--out", default=None,
                   help="output folder (default out/linear/<car>-<body>-<speed>kmh)")


def add_reference_argument(p, *, what: str = "", where: str = "") -> None:
    """``--reference`` of ``flexpipe linear`` and ``ride``: a second body to compare."""
    p.add_argument("--reference", default=None, metavar="BODY",
                   help=f"{what}also linearize the car with this body (rigid, flexible or "
                        f"full){where} and give the RMS of the outputs' difference on the "
                        "same road (e.g. flexible minus rigid hub forces)")


def add_model_arguments(p, *, what: str = "") -> None:
    """``--body``, ``--f-max`` and ``--coherence`` of ``flexpipe linear`` and ``ride``."""
    p.add_argument("--body", default="flexible", metavar="BODY",
                   help="body model: rigid, flexible or full (default flexible)")
    p.add_argument("--f-max", type=float, default=None, metavar="HZ",
                   help="top of the flexible body's band, Hz (default as flexpipe run)")
    p.add_argument("--coherence", default="isotropic", metavar="GAMMA",
                   help=f"{what}the tracks' coherence, 'isotropic' (default) or a number "
                        "in [0, 1] (1: both tracks the same)")


def check_options(args) -> None:
    """Refuse bad options in their own terms.

    Raises
    ------
    InputError
        Naming the option, the value given and what is valid.
    """
    from flexpipe.errors import InputError

    check_model_options(args)
    if not (math.isfinite(args.speed) and 0.0 <= args.speed <= 300.0):
        raise InputError(f"--speed must be in [0, 300] km/h, got {args.speed:g}")
    if not (math.isfinite(args.show) and args.show > 0):
        raise InputError(f"--show must be a frequency > 0 Hz, got {args.show:g}")
    if args.road_class is not None:
        check_road_class(args.road_class)
        if args.speed <= 0.0:
            raise InputError("--road-class needs --speed > 0 km/h: at rest the road does "
                             "not move under the wheels")
    if args.reference is not None and args.road_class is None:
        raise InputError("--reference needs --road-class (and --speed): it compares the "
                         "two bodies on a road")
    check_reference(args)


def check_reference(args) -> None:
    """``--reference`` (if given) names another body than ``--body``."""
    from flexpipe.errors import InputError

    if args.reference is not None:
        ref = args.reference.strip().lower()
        if ref not in BODIES or ref == args.body.strip().lower():
            raise InputError(f"--reference must be another body than --body "
                             f"({', '.join(BODIES)}), got {args.reference!r}")


def check_model_options(args) -> None:
    """``--body``, ``--f-max`` and ``--coherence`` (made ``'isotropic'`` or a float), as
    ``flexpipe linear`` and ``flexpipe ride`` take them."""
    from flexpipe.errors import InputError

    if args.body.strip().lower() not in BODIES:
        raise InputError(f"--body must be one of {', '.join(BODIES)}, got {args.body!r}")
    if args.f_max is not None and not (math.isfinite(args.f_max) and args.f_max > 0):
        raise InputError(f"--f-max must be a frequency > 0 Hz, got {args.f_max:g}")
    args.coherence = _coherence(args.coherence)


def check_road_class(text: str) -> str:
    """``--road-class``: an ISO 8608 class A..H (any case), returned in capitals."""
    from flexpipe.errors import InputError
    from flexpipe.roads import ISO8608_GD0

    if text.strip().upper() not in ISO8608_GD0:
        raise InputError(f"--road-class must be one of {', '.join(ISO8608_GD0)}, got "
                         f"{text!r}")
    return text.strip().upper()


def _coherence(text):
    """``--coherence``: 'isotropic' or a number in [0, 1]."""
    from flexpipe.errors import InputError

    if isinstance(text, str) and text.strip().lower() == "isotropic":
        return "isotropic"
    try:
        value = float(text)
    except (TypeError, ValueError):
        value = math.nan
    if not 0.0 <= value <= 1.0:
        raise InputError(f"--coherence must be 'isotropic' or a number in [0, 1], got "
                         f"{text!r}")
    return value


def run(args) -> int:
    """Run ``flexpipe linear``."""
    from pathlib import Path

    from flexpipe._io import check_output_folder
    from flexpipe.vehicle import load_car
    from flexpipe.vehicle.linear import linear_modes
    from flexpipe.vehicle.linear_output import (
        NOTES,
        table_text,
        write_modes,
        write_shapes,
        write_state_space,
        write_track_response,
    )

    check_options(args)
    body = args.body.strip().lower()
    car = load_car(args.car)
    out = args.out or Path("out") / "linear" / f"{car.name}-{body}-{args.speed:g}kmh"
    out = check_output_folder(out, option="-o")
    modes = linear_modes(car, body=body, speed=args.speed / 3.6, f_max=args.f_max,
                         log=print)
    info = modes.info
    print(f"{car.name}, {body} body, {args.speed:g} km/h: {info['n_dof']} degrees of "
          f"freedom, {info['n_slip_states']} tyre slip states; force out of balance at "
          f"the linearization state {modes.residual_N:.3g} N; free motions: "
          f"{info['free_modes']}")
    print(table_text(modes, f_max=args.show))
    for note in NOTES:
        print(f"note: {note}")
    paths = (write_modes(modes, out) + write_track_response(modes, out)
             + write_track_response(modes, out, tracks="opposite"))
    paths.append(write_state_space(modes, Path(out) / "linear_state_space.mat"))
    vtu = write_shapes(modes, Path(out) / "linear_modes.vtu", f_max=args.show)
    if vtu is not None:
        paths.append(vtu)
    if args.road_class is not None:
        from flexpipe.vehicle.linear_ride import ride_response
        from flexpipe.vehicle.linear_ride_output import NOTES as RIDE_NOTES
        from flexpipe.vehicle.linear_ride_output import ride_text, write_ride

        reference = None if args.reference is None else linear_modes(
            car, body=args.reference.strip().lower(), speed=args.speed / 3.6,
            f_max=args.f_max, log=print)
        ride = ride_response(modes, args.road_class.strip().upper(),
                             coherence=args.coherence, reference=reference)
        print(ride_text(ride))
        for note in RIDE_NOTES:
            print(f"note: {note}")
        paths += write_ride(ride, out)
    print("written: " + ", ".join(str(p) for p in paths))
    return 0
