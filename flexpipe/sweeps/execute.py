"""``sweep(spec)``: run every case of a sweep on dask.distributed and collect the results.

The client (this process) validates every run first (its settings, car, road, path and
the ``[plots]`` metrics: :mod:`flexpipe.sweeps.checks`; a bad one stops the sweep before
anything runs), skips runs whose record is already on disk, then submits

* one mass-properties task per distinct body mesh and trim (the FE model assembled once),
* one reduction task per distinct reduced body (mesh, trim, hardpoints and band: the
  on-disk cache key), depending on the first,
* one task per run, depending on the body tasks it needs, so no body is ever reduced
  twice and the bodies reach the workers through Dask, not through a shared disk.

Results are written as they arrive (:class:`~flexpipe.sweeps.store.Store`); when a worker
dies, the scheduler reruns its unfinished tasks elsewhere (Dask's ``allowed-failures``),
and a run that still cannot finish is recorded as lost and retried by the next rerun.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from pathlib import Path

from flexpipe.errors import InputError
from flexpipe.sweeps.spec import load_sweep
from flexpipe.sweeps.store import Store
from flexpipe.sweeps.tasks import (
    STATUS_ERROR,
    STATUS_LOST,
    body_keys,
    body_task,
    mass_task,
    road_of,
    run_task,
)


@dataclass
class SweepResult:
    """Outcome of :func:`sweep`.

    Attributes
    ----------
    table : pandas.DataFrame
        One row per run of the spec (run order): parameters, ``key``, ``status``,
        ``message``, ``cpu_s`` and the metrics (:mod:`flexpipe.sweeps.metrics`).
    out : Path
        Output folder (``metrics.parquet``, ``channels/``, ``plots/``...).
    n_runs, n_skipped, n_failed : int
        Runs in the spec, runs found finished on disk, runs with ``status < 0``.
    reductions : list of dict
        One entry per distinct reduced body: ``key``, ``cached``, ``seconds``.
    wall_s : float
        Wall time of the sweep, s.
    """

    table: object
    out: Path
    n_runs: int
    n_skipped: int
    n_failed: int
    reductions: list = field(default_factory=list)
    wall_s: float = 0.0

    @property
    def n_reduced(self) -> int:
        """Bodies actually reduced by this sweep (not taken from the cache)."""
        return sum(1 for r in self.reductions if not r["cached"])


def _client(scheduler, n_workers):
    from flexpipe.sweeps.connect import connect, local_cluster

    if scheduler is not None:
        if hasattr(scheduler, "submit"):
            return scheduler, None, False  # the caller's client: leave it open
        return connect(scheduler), None, True
    client, cluster = local_cluster(n_workers)
    return client, cluster, True


def _cars(runs):
    from flexpipe.vehicle.spec import load_car

    cars = {}
    out = []
    for r in runs:
        ident = (str(r.car_file), repr(sorted(r.car_overrides.items())))
        if ident not in cars:
            try:
                cars[ident] = load_car(r.car_file, overrides=r.car_overrides)
            except InputError as exc:
                params = ", ".join(f"{k} = {v!r}" for k, v in r.params.items())
                raise InputError(f"run {r.index} ({params}): {exc}") from None
        out.append(cars[ident])
    return out


def sweep(spec, *, out=None, scheduler=None, n_workers=None, progress: bool = True,
          retry_failed: bool = False, cache: bool = True, plots: bool = True) -> SweepResult:
    """Run a sweep (grid, list or Latin hypercube of runs) on dask.distributed.

    Parameters
    ----------
    spec : str, Path, dict or SweepSpec
        Sweep TOML file or the same structure as a dict (see :mod:`flexpipe.sweeps.spec`).
    out : str or Path, optional
        Output folder (default: the spec's ``out``, else ``out/sweep-<spec name>``): absent,
        empty or a previous sweep's (:func:`flexpipe.sweeps.store.check_sweep_folder`).
    scheduler : str or dask.distributed.Client, optional
        Address of a running Dask scheduler (``tcp://host:8786``) or a client; default: a
        local cluster with one single-threaded worker process per core.  An address is
        checked before any work and connected with a deadline
        (:func:`flexpipe.sweeps.connect.connect`).
    n_workers : int, optional
        Workers of the local cluster (default: number of cores).
    progress : bool
        Progress bar over runs.
    retry_failed : bool
        Run again the runs recorded as failed (default: a rerun skips every finished run,
        failed or not, and reruns only lost ones).
    cache : bool
        Use and fill the on-disk cache of reduced bodies (``$FLEXPIPE_CACHE``).
    plots : bool
        Write the plots of the spec's ``[plots] metrics``.

    Returns
    -------
    SweepResult

    Raises
    ------
    InputError
        A bad spec, a run whose car overrides or arguments do not validate (named with
        its parameters and the sweep key), an unknown ``[plots]`` metric or an output
        folder that cannot be written, before any run starts.

    Notes
    -----
    The local cluster starts worker processes by spawning: in a script, call ``sweep``
    under ``if __name__ == "__main__":``.
    """
    from flexpipe.sweeps.checks import check_plot_metrics, check_runs
    from flexpipe.sweeps.connect import check_scheduler_address
    from flexpipe.sweeps.store import check_sweep_folder

    t_start = time.perf_counter()
    if scheduler is not None and not hasattr(scheduler, "submit"):
        check_scheduler_address(scheduler)
    spec = load_sweep(spec)
    runs = spec.runs()
    option = "out" if out is not None else "sweep.out"
    if out is None:
        stem = spec.file.stem if spec.file is not None else "sweep"
        out = spec.out or Path("out") / f"sweep-{stem}"
    check_sweep_folder(out, option=option)
    cars = _cars(runs)
    check_runs(spec, runs, cars)  # every run's arguments, before any run starts
    check_plot_metrics(spec, cars)
    store = Store(out)
    done = store.finished(retry_failed=retry_failed)
    todo = [(r, c) for r, c in zip(runs, cars, strict=True) if r.key not in done]
    reductions = []
    if todo:
        reductions = _execute(todo, store, scheduler=scheduler, n_workers=n_workers,
                              progress=progress, cache=cache)
    store.mark()  # (also when no run was left to do)
    table = store.table([r.key for r in runs])
    if not table.empty:  # swept parameters, key, status... first (docs/sweeps.md)
        from flexpipe.sweeps.metrics import table_columns

        table = table[table_columns(table.columns, swept_parameters(spec))]
    store.write_table(table)
    n_failed = int((table["status"] < 0).sum()) if "status" in table else 0
    result = SweepResult(table=table, out=Path(out), n_runs=len(runs),
                         n_skipped=len(runs) - len(todo), n_failed=n_failed,
                         reductions=reductions, wall_s=time.perf_counter() - t_start)
    if plots:
        from flexpipe.sweeps.plots import plot_metrics

        plot_metrics(table, spec, Path(out) / "plots")
    _summary(result, spec)
    return result


def swept_parameters(spec) -> list[str]:
    """Names of the swept parameters: the ``[parameters]`` keys, else those of the
    ``[[runs]]`` tables in first-seen order."""
    if spec.parameters:
        return list(spec.parameters)
    out: list[str] = []
    for r in spec.runs_list:
        out += [k for k in r if k not in out]
    return out


def _summary(result: SweepResult, spec) -> None:
    import json

    from flexpipe._io import write_text_atomic

    info = {"spec": str(spec.file) if spec.file else None, "design": spec.design,
            "n_runs": result.n_runs, "n_skipped": result.n_skipped,
            "n_failed": result.n_failed, "n_reduced": result.n_reduced,
            "reductions": result.reductions, "wall_s": result.wall_s,
            "units": "column names carry units: _N, _m, _m_per_s2, _m_per_s1.75, _s"}
    write_text_atomic(result.out / "sweep.json", json.dumps(info, indent=1, default=str))


def _execute(todo, store, *, scheduler, n_workers, progress, cache) -> list:
    from dask.distributed import as_completed

    client, cluster, own = _client(scheduler, n_workers)
    try:
        store.mark()  # connected: the folder is the sweep's from now on
        mass_f, body_f, reductions = {}, {}, []
        futures = []
        for run, car in todo:
            road = road_of(run) if run.body != "rigid" and car.body.mesh is not None else None
            mkey, bkey, band = body_keys(car, run, road)
            rigid = bodies = None
            if mkey is not None:
                if mkey not in mass_f:
                    mass_f[mkey] = client.submit(mass_task, car, cache, key=mkey)
                rigid = mass_f[mkey]
            if bkey is not None:
                if bkey not in body_f:
                    body_f[bkey] = client.submit(body_task, car, run.body, band, rigid, cache,
                                                 key=bkey)
                bodies = body_f[bkey]
            futures.append(client.submit(run_task, run, car, rigid, bodies,
                                         key=f"run-{run.key}"))
        bar = None
        if progress:
            from tqdm import tqdm

            bar = tqdm(total=len(futures), desc="sweep", unit="run", mininterval=0.5)
        by_key = {f.key: run for f, (run, _) in zip(futures, todo, strict=True)}
        for fut in as_completed(futures):
            run = by_key[fut.key]
            try:
                record, channels = fut.result()
            except Exception as exc:  # a body task failed, or the run's workers kept dying
                lost = type(exc).__name__ in ("KilledWorker", "CancelledError", "CommClosedError")
                record = {"key": run.key, "index": run.index, **run.params,
                          "status": STATUS_LOST if lost else STATUS_ERROR,
                          "message": f"{type(exc).__name__}: {exc}"}
                channels = None
            store.write(record, channels)
            fut.release()
            if bar is not None:
                bar.update(1)
        if bar is not None:
            bar.close()
        for key, f in body_f.items():
            try:
                info = f.result()["reduction"]
                reductions.append({"key": key, "cached": bool(info["cached"]),
                                   "seconds": float(info["seconds"])})
            except Exception as exc:
                reductions.append({"key": key, "cached": False, "seconds": float("nan"),
                                   "error": f"{type(exc).__name__}: {exc}"})
        return reductions
    finally:
        from flexpipe.sweeps.connect import close_quietly

        close_quietly(client if own else None, cluster)


__all__ = ["SweepResult", "sweep"]
