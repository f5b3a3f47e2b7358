"""``flexpipe ride CAR.toml``: ride comfort and road holding on an ISO 8608 road against
speed, from the car's linear model.

At each of ``--speeds`` the car is linearized in steady straight running
(:func:`flexpipe.linear_modes`) and its response to a road of ``--road-class`` is found
from the road's spectrum (:func:`flexpipe.vehicle.linear_ride.ride_vs_speed`): the RMS of
the vertical tyre forces and body-point accelerations, the ISO 2631-1 weighted RMS, each
point's comfort value ``a_v`` and each tyre's dynamic load coefficient; with
``--reference BODY`` also the RMS of the outputs' difference from the car with that body
on the same road (e.g. flexible minus rigid hub forces).  Prints a table and writes
``ride_vs_speed.csv`` / ``.json`` / ``.png`` into ``--out`` (default
``out/ride/<car>-<body>-<class>``).  For one speed's spectra: ``flexpipe linear --speed
KMH --road-class CLASS``.
"""

from __future__ import annotations

import argparse
import math

_EPILOG = """\
The linear model holds the controls fixed and takes a dual-rate damper at its mean slope
(docs/linear.md: against the nonlinear run over a 400 m class-C road at 70 km/h, the
vertical tyre forces within 0.7 %, the floor's vertical acceleration within 5 %).  Both
tracks share the class's PSD; --coherence sets how alike they are.  Each speed takes one
linearization: on the sample 4 s (rigid body) and 9-25 s (flexible) per speed on a
2-core machine.
"""


def add_arguments(p) -> None:
    """Options of ``flexpipe ride``."""
    from flexpipe.cli.linear import add_model_arguments, add_reference_argument

    p.formatter_class = argparse.RawDescriptionHelpFormatter
    p.epilog = _EPILOG
    p.add_argument("car", help="car file with [suspension.front] / [suspension.rear]")
    p.add_argument("--road-class", default="C", metavar="CLASS",
                   help="ISO 8608 road class A..H (default C)")
    p.add_argument("--speeds", default="30,50,70,90,110,130", metavar="KMH,...",
                   help="speeds, km/h, comma separated (default 30,50,70,90,110,130)")
    add_model_arguments(p)
    add_reference_argument(p, where=" at each speed")
    p.add_argument("-o", "--out", default=None,
                   help="output folder (default out/ride/<car>-<body>-<class>)")


def check_options(args) -> None:
    """Refuse a bad ``--speeds``, ``--road-class``, ``--body``, ``--reference``,
    ``--f-max`` or ``--coherence`` before the first linearization; sets ``args.kmh`` (the
    speeds).

    Raises
    ------
    InputError
        Naming the option, the value given and what is valid.
    """
    from flexpipe.cli.linear import check_model_options, check_reference, check_road_class
    from flexpipe.errors import InputError

    check_model_options(args)
    check_reference(args)
    check_road_class(args.road_class)
    try:
        kmh = [float(s) for s in args.speeds.split(",")]
    except ValueError:
        kmh = []
    if not kmh or any(not (math.isfinite(s) and 0.0 < s <= 300.0) for s in kmh) \
            or len(set(kmh)) != len(kmh):
        raise InputError(f"--speeds must be distinct speeds in (0, 300] km/h, comma "
                         f"separated, got {args.speeds!r}")
    args.kmh = kmh


def run(args) -> int:
    """Run ``flexpipe ride``."""
    from pathlib import Path

    from flexpipe._io import check_output_folder
    from flexpipe.cli.linear import check_road_class
    from flexpipe.vehicle import load_car
    from flexpipe.vehicle.linear_ride import ride_vs_speed
    from flexpipe.vehicle.linear_ride_output import NOTES, speed_table, write_ride_vs_speed

    check_options(args)
    body = args.body.strip().lower()
    road_class = check_road_class(args.road_class)
    car = load_car(args.car)
    out = args.out or Path("out") / "ride" / f"{car.name}-{body}-{road_class}"
    out = check_output_folder(out, option="-o")
    rides = ride_vs_speed(car, [s / 3.6 for s in args.kmh], road_class, body=body,
                          coherence=args.coherence, f_max=args.f_max,
                          reference=args.reference)
    head, rows = speed_table(rides)
    pick = [0] + [j for j, h in enumerate(head) if "_a_v_" in h or "dynamic_load" in h]
    print(f"{car.name}, {body} body, ISO 8608 class {road_class}, coherence "
          f"{args.coherence}: comfort value a_v (m/s^2) per body point, dynamic load "
          "coefficient per tyre")
    names = [head[j].replace("_m/s^2", "") for j in pick]
    print("  ".join(names))
    for row in rows:
        print("  ".join(f"{row[j]:{len(n)}.{1 if k == 0 else 3}f}"
                        for k, (j, n) in enumerate(zip(pick, names, strict=True))))
    if rides[0].difference_rms is not None:
        hubs = [j for j, name in enumerate(rides[0].outputs) if name.startswith("hub_")]
        print(f"hub forces, RMS of {body} minus {rides[0].info['reference_body']} on the "
              "same road (N, body axes)")
        names = ["speed_km/h"] + [rides[0].outputs[j][4:] for j in hubs]
        print("  ".join(f"{n:>6s}" for n in names))
        for r in rides:
            print("  ".join(f"{v:6.1f}" for v in [r.speed * 3.6, *r.difference_rms[hubs]]))
    for note in NOTES:
        print(f"note: {note}")
    paths = write_ride_vs_speed(rides, out)
    print("written: " + ", ".join(str(p) for p in paths))
    return 0
