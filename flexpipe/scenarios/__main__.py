"""``python -m flexpipe.scenarios NAME --out DIR``."""

from __future__ import annotations

import argparse
import sys


def main(argv=None) -> int:
    from flexpipe.cli import _notes, _one_line
    from flexpipe.errors import FlexpipeError
    from flexpipe.scenarios.runner import SCENARIOS, run_scenario

    p = argparse.ArgumentParser(prog="python -m flexpipe.scenarios",
                                description="Run a ready-made car scenario (rigid and "
                                            "flexible body) and write CSVs, plots and "
                                            "summary.json.")
    p.add_argument("name", choices=sorted(SCENARIOS), help="scenario")
    p.add_argument("--out", required=True, help="output directory")
    p.add_argument("--car", default=None, help="car file (default: cars/sedan_linkage.toml)")
    p.add_argument("--t-end", type=float, default=None, help="simulated time, s")
    p.add_argument("--no-cache", action="store_true", help="rebuild the reduced body")
    args = p.parse_args(argv)
    from flexpipe._signals import interrupt_info, interrupt_text, interrupts_as_exceptions

    try:
        with interrupts_as_exceptions():
            summary = run_scenario(args.name, out=args.out, car=args.car, t_end=args.t_end,
                                   cache=not args.no_cache)
    except (FlexpipeError, OSError) as exc:
        print(f"error: {_one_line(exc)}", file=sys.stderr)
        return 2
    except KeyboardInterrupt as exc:
        print(interrupt_text(exc) + _notes(exc), file=sys.stderr)
        return interrupt_info(exc)[0]
    return 0 if summary["status"] == 0 else 1


if __name__ == "__main__":
    raise SystemExit(main())
