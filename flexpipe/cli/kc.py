"""``flexpipe kc CAR.toml [-o OUT]``: kinematics and compliance rig of a car's suspension.

Runs parallel and opposite wheel travel, static steer and longitudinal/lateral force
compliance per axle (:func:`flexpipe.vehicle.suspension.kc.kc`) and writes CSV tables with
units in the headers, ``kc_summary.json`` and PNG plots to OUT.
"""

from __future__ import annotations

import argparse

from flexpipe.vehicle.suspension.kc_args import N_MIN, RACK_TRAVEL_MAX_M, TRAVEL_MAX_M

#: upper limits of --travel and --rack (mm): the API's limits in the options' unit
TRAVEL_MAX_MM = TRAVEL_MAX_M * 1e3
RACK_MAX_MM = RACK_TRAVEL_MAX_M * 1e3
AXLES = ("front", "rear", "both")

_EPILOG = f"""\
Sweeps: parallel and opposite wheel travel (left up, right down) run over --travel
-MM .. +MM and static steer over --rack -MM .. +MM, each in --points evenly spaced points
(an odd number includes the design position); the force-compliance analyses apply 9
contact-patch forces over --force -N .. +N at the design height.  The summary (printed
and kc_summary.json) is evaluated at the design position itself and does not depend on
--points or --travel.

Limits: 0 < --travel <= {TRAVEL_MAX_MM:g} mm, --points >= {N_MIN}, 0 < --rack <= \
{RACK_MAX_MM:g} mm, --force > 0 N.
"""


def add_arguments(p) -> None:
    """Options of ``flexpipe kc``."""
    p.formatter_class = argparse.RawDescriptionHelpFormatter
    p.epilog = _EPILOG
    p.add_argument("car", help="car file with [suspension.front] / [suspension.rear]")
    p.add_argument("-o", "--out", default="out/kc",
                   help="output folder, created if needed (default out/kc)")
    p.add_argument("--travel", type=float, default=80.0, metavar="MM",
                   help="wheel travel range +- from the design position, mm (default 80; "
                        f"0 < MM <= {TRAVEL_MAX_MM:g})")
    p.add_argument("--points", type=int, default=33, metavar="N",
                   help="points of each wheel-travel and rack-travel sweep, evenly spaced "
                        f"over the range (default 33; N >= {N_MIN}; odd N includes the "
                        "design position)")
    p.add_argument("--rack", type=float, default=30.0, metavar="MM",
                   help="rack travel range +- of the static-steer analysis, mm (default "
                        f"30; 0 < MM <= {RACK_MAX_MM:g})")
    p.add_argument("--force", type=float, default=2000.0, metavar="N",
                   help="contact-patch force range +- of the compliance analyses, N "
                        "(default 2000; > 0)")
    p.add_argument("--axle", default="both", metavar="AXLE",
                   help="axle to run: front, rear or both (default both)")


def _in_range(value: float, option: str, hi: float | None, unit: str) -> float:
    """``value`` when it is finite, > 0 and <= ``hi`` (if given), else an InputError naming
    ``option``, its value and the valid range in ``unit``."""
    import math

    from flexpipe.errors import InputError

    if math.isfinite(value) and value > 0 and (hi is None or value <= hi):
        return value
    rng = f"in (0, {hi:g}] {unit}" if hi is not None else f"> 0 {unit}"
    raise InputError(f"{option} must be {rng}, got {value:g} {unit}")


def check_options(args) -> None:
    """Refuse bad ``flexpipe kc`` options in their own terms (option, unit, range).

    Raises
    ------
    InputError
        Naming the option, the value given and the valid range in the option's unit.
    """
    from flexpipe.errors import InputError

    _in_range(args.travel, "--travel", TRAVEL_MAX_MM, "mm")
    if args.points < N_MIN:
        raise InputError(f"--points must be an integer >= {N_MIN}, got {args.points}")
    _in_range(args.rack, "--rack", RACK_MAX_MM, "mm")
    _in_range(args.force, "--force", None, "N")
    if args.axle.strip().lower() not in AXLES:
        raise InputError(f"--axle must be one of {', '.join(AXLES)}, got {args.axle!r}")


def run(args) -> int:
    """Run ``flexpipe kc``."""
    from flexpipe._io import check_output_folder
    from flexpipe.vehicle.suspension.kc import kc

    check_options(args)
    out = check_output_folder(args.out, option="-o")  # before the analysis, not after
    axle = args.axle.strip().lower()
    res = kc(args.car, out=out, travel=args.travel / 1e3, n=args.points,
             rack_travel=args.rack / 1e3, force=args.force,
             axles=None if axle == "both" else [axle])
    for name, s in res.summary.items():
        sf = res.subframes.get(name)
        on = f", on [{sf}] (its bushings in the compliance figures)" if sf else ""
        print(f"{name} ({s['template']}{on}), at the design position:")
        for k, v in s.items():
            if k != "template":
                print(f"  {k:<46} {v:10.4g}")
    print(f"written to {out}/ (CSV, kc_summary.json, kc_wheel_travel.png, "
          "kc_steer_compliance.png)")
    return 0
