"""``flexpipe animate OUT_DIR``: ParaView time series of the deformed body on the road."""

from __future__ import annotations


def add_arguments(p) -> None:
    p.add_argument("out_dir", metavar="OUT_DIR",
                   help="run folder written by 'make straight' / 'flexpipe run'")
    p.add_argument("--scale", type=float, default=1.0,
                   help="deformation scale factor of the body (default 1: true scale)")
    p.add_argument("--every", type=int, default=1,
                   help="write every N-th output step (default 1: all)")
    p.add_argument("--dest", default=None,
                   help="folder for the frames (default OUT_DIR/animation)")


def run(args) -> int:
    from pathlib import Path

    from flexpipe._io import check_output_folder
    from flexpipe.durability.pipeline import animate_outputs

    check_output_folder(Path(args.out_dir) / "animation" if args.dest is None else args.dest,
                        option="--dest")
    files = animate_outputs(args.out_dir, dest=args.dest, scale=args.scale, every=args.every,
                            progress=True)
    print(f"wrote: {', '.join(sorted(files))}")
    return 0
