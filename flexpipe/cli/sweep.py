"""``flexpipe sweep SWEEP.toml``: run a sweep of speeds, roads, bodies and car variants on
dask.distributed and write the metrics table, channel files and plots.

Examples::

    flexpipe sweep sweeps/sample.toml                       # local cluster, 1 worker/core
    flexpipe sweep sweeps/sample.toml --workers 4 --out out/my_sweep
    flexpipe sweep study.toml --scheduler tcp://10.0.0.5:8786   # an existing Dask cluster

A rerun of the same command skips the runs already finished (by parameter key).
"""

from __future__ import annotations


def add_arguments(parser) -> None:
    """Options of ``flexpipe sweep``."""
    parser.add_argument("spec", help="sweep file (.toml), e.g. sweeps/sample.toml")
    parser.add_argument("--out", default=None,
                        help="output folder: new, empty or a previous sweep's (default: the "
                             "spec's out, else out/sweep-<name>)")
    parser.add_argument("--scheduler", default=None, metavar="ADDRESS",
                        help="address of a running Dask scheduler, e.g. tcp://host:8786 (the "
                             "scheduler's port, not the dashboard's 8787; default: a local "
                             "cluster)")
    parser.add_argument("--workers", type=int, default=None,
                        help="worker processes of the local cluster (default: one per core)")
    parser.add_argument("--retry-failed", action="store_true",
                        help="run again the runs recorded as failed")
    parser.add_argument("--no-cache", action="store_true",
                        help="do not read or write the reduced-body cache")
    parser.add_argument("--no-progress", action="store_true", help="no progress bar")


def run(args) -> int:
    """Run the sweep; exit code 0 when every run reached its end time, else 1."""
    from flexpipe.errors import InputError
    from flexpipe.sweeps import sweep
    from flexpipe.sweeps.connect import check_scheduler_address
    from flexpipe.sweeps.store import check_sweep_folder

    if args.workers is not None and args.workers < 1:
        raise InputError(f"--workers must be >= 1, got {args.workers}", key="workers")
    if args.scheduler is not None:
        check_scheduler_address(args.scheduler)  # before any work
    if args.out is not None:
        check_sweep_folder(args.out, option="--out")  # before the sweep, not after
    res = sweep(args.spec, out=args.out, scheduler=args.scheduler, n_workers=args.workers,
                progress=not args.no_progress, retry_failed=args.retry_failed,
                cache=not args.no_cache)
    print(f"{res.n_runs} runs ({res.n_skipped} already done, {res.n_failed} failed, "
          f"{res.n_reduced} bodies reduced) in {res.wall_s:.1f} s -> {res.out}/metrics.parquet")
    if res.n_failed:
        bad = res.table[res.table["status"] < 0]
        for _, row in bad.head(5).iterrows():
            print(f"  failed run {row['key']}: {row['message']}")
    return 0 if res.n_failed == 0 else 1
