"""``flexpipe kc CAR.toml [-o OUT]``: kinematics and compliance rig of a car's suspension.

Runs parallel and opposite wheel travel, static steer and longitudinal/lateral force
compliance per axle (:func:`flexpipe.vehicle.suspension.kc.kc`) and writes CSV tables with
units in the headers, ``kc_summary.json`` and PNG plots to OUT.
"""

from __future__ import annotations


def add_arguments(p) -> None:
    """Options of ``flexpipe kc``."""
    p.add_argument("car", help="car file with [suspension.front] / [suspension.rear]")
    p.add_argument("-o", "--out", default="out/kc",
                   help="output folder, created if needed (default out/kc)")
    p.add_argument("--travel", type=float, default=80.0, help="wheel travel +- in mm")
    p.add_argument("--points", type=int, default=33, help="points per sweep")
    p.add_argument("--rack", type=float, default=30.0, help="rack travel +- in mm")
    p.add_argument("--force", type=float, default=2000.0,
                   help="contact-patch force +- in N for the compliance analyses")


def run(args) -> int:
    """Run ``flexpipe kc``."""
    from flexpipe._io import check_output_folder
    from flexpipe.errors import InputError
    from flexpipe.vehicle.suspension.kc import kc

    if args.travel <= 0 or args.points < 3 or args.rack <= 0 or args.force <= 0:
        raise InputError("--travel, --rack and --force must be > 0 and --points >= 3")
    out = check_output_folder(args.out, option="-o")  # before the analysis, not after
    res = kc(args.car, out=out, travel=args.travel / 1e3, n=args.points,
             rack_travel=args.rack / 1e3, force=args.force)
    for axle, s in res.summary.items():
        print(f"{axle} ({s['template']}):")
        for k, v in s.items():
            if k != "template":
                print(f"  {k:<46} {v:10.4g}")
    print(f"written to {out}/ (CSV, kc_summary.json, kc_wheel_travel.png, "
          "kc_steer_compliance.png)")
    return 0
