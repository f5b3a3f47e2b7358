"""``flexpipe stress OUT_DIR``: modal stress recovery, hot spots and fatigue of a run."""

from __future__ import annotations


def add_arguments(p) -> None:
    p.add_argument("out_dir", metavar="OUT_DIR",
                   help="run folder written by 'make straight' / 'flexpipe run' (holds "
                        "summary.json, flexible.csv, motion_flexible.npz)")
    p.add_argument("--top", type=int, default=20,
                   help="hot spots listed by max von Mises and by damage (default 20)")
    p.add_argument("--no-fatigue", action="store_true",
                   help="skip rainflow counting and Miner damage")


def run(args) -> int:
    from pathlib import Path

    from flexpipe._io import check_output_folder
    from flexpipe.durability.pipeline import stress_outputs
    from flexpipe.errors import InputError

    if args.top < 1:
        raise InputError(f"--top must be >= 1, got {args.top}", key="--top")
    if Path(args.out_dir).is_dir():  # else load_run says the run folder is missing
        check_output_folder(Path(args.out_dir) / "stress", option="OUT_DIR")
    files = stress_outputs(args.out_dir, top=args.top, fatigue=not args.no_fatigue,
                           progress=True)
    print(f"wrote {args.out_dir}/: {', '.join(sorted(files))}")
    return 0
