"""What a sweep worker runs: one task per distinct body (mass properties, reduction) and
one task per run.  Plain module-level functions of picklable arguments, so they run on any
Dask worker (or a process pool) that has flexpipe installed and sees the input files.
"""

from __future__ import annotations

import time
import traceback

import numpy as np

#: status of a run that raised instead of returning a Result (bad input found late, bug)
STATUS_ERROR = -2
#: status of a run whose task was lost (its worker died more often than Dask allows)
STATUS_LOST = -3


def road_of(run):
    """The run's road: a Road from its file, its ``[road]`` table, or None (flat)."""
    from flexpipe.roads import load_road, road_from_spec

    if run.road is None:
        return None
    if isinstance(run.road, dict):
        return road_from_spec(run.road, file=run.road_base, name="road")
    return load_road(run.road)


def body_keys(car, run, road=None):
    """Cache identities of what the run needs reduced or integrated once.

    Returns ``(mass_key, body_key, band)``: ``mass_key`` names the body's mass properties
    (None for a car given by rigid properties), ``body_key`` the reduced body (None for a
    rigid run; for a linkage car it includes every suspension mount, so runs that move a
    mount get their own reduction) and ``band`` its band (Hz).
    """
    from flexpipe.vehicle import bodymodel
    from flexpipe.vehicle.linkage_setup import FULL_CUTOFF_HZ

    if car.body.mesh is None:
        return None, None, None
    mass_key = "mass-" + bodymodel._digest(car, {})
    if run.body == "rigid":
        return mass_key, None, None
    band = bodymodel.choose_band(run.speed, road)
    full = run.body == "full"
    kw = {}
    if car.suspension is not None:  # every suspension mount is an interface of the body
        from flexpipe.vehicle.linkage_setup import body_mounts, interface_band

        kw = {"mounts": body_mounts(car), "interface_f_max": interface_band(car, full=full)}
    cutoff = FULL_CUTOFF_HZ if full else bodymodel.CB_RATIO * band
    return mass_key, "body-" + bodymodel.body_key(car, cutoff=cutoff, **kw), band


def mass_task(car, cache: bool = True):
    """Mass properties of the car body (the FE model is assembled at most once)."""
    from flexpipe.vehicle import bodymodel

    return bodymodel.rigid_properties(car, cache=cache)


def body_task(car, body: str, band: float, rigid, cache: bool = True) -> dict:
    """The reduced body of a flexible or full run: ``{"rigid", "flexbody", "reduction"}``.

    ``reduction["cached"]`` tells whether it came from the on-disk cache; the sweep counts
    the others as reductions done.
    """
    from flexpipe.vehicle.linkage_setup import reduce_car_body

    fb, info = reduce_car_body(car, f_max=band, cache=cache, full=body == "full")
    return {"rigid": rigid, "flexbody": fb, "reduction": dict(info, band_hz=band)}


def run_task(run, car, rigid=None, bodies=None):
    """Simulate one run; never raises.

    Returns
    -------
    record : dict
        ``key``, the swept parameters, ``status``, ``message``, CPU and wall time and the
        metrics of :func:`flexpipe.sweeps.metrics.run_metrics` (and, for an open-loop step
        or sine-with-dwell run, :func:`~flexpipe.sweeps.metrics.manoeuvre_metrics`).
    channels : dict of str to ndarray, or None
        ``t`` and every output channel (None when the run raised before integrating).
    """
    from flexpipe.sweeps.metrics import centre_of_mass, manoeuvre_metrics, run_metrics
    from flexpipe.vehicle.seats import seat_value
    from flexpipe.vehicle.simulation import prepare, simulate

    t0 = time.perf_counter()
    record = {"key": run.key, "index": run.index, **run.params}
    channels = None
    try:
        road = road_of(run)
        given = dict(bodies) if bodies is not None else {}
        if rigid is not None:
            given["rigid"] = rigid
        prep = prepare(car, body=run.body, speed=run.speed, road=road, bodies=given)
        res = simulate(car, road=road, path=run.path, speed=run.speed_profile or run.speed,
                       t_end=run.t_end, body=run.body, h=run.h, output_step=run.output_step,
                       driver=run.driver, prepared=prep)
        record.update(status=int(res.status), message=res.message, cpu_s=res.cpu_time,
                      wall_s=res.wall_time, simulated_time_s=res.simulated_time)
        if "n_elastic_modes" in res.info:
            record["n_elastic_modes"] = int(res.info["n_elastic_modes"])
        record.update(run_metrics(res.t, res.channels, settle=run.settle))
        for seat, floor in res.info.get("seats", {}).items():  # flexpipe.vehicle.seats
            record[f"seat_{seat}_SEAT_pct"] = seat_value(
                record.get(f"aw_{seat}_z_m_per_s2", np.nan),
                record.get(f"aw_{floor}_z_m_per_s2", np.nan))
        figures, note = manoeuvre_metrics(res, cg=centre_of_mass(res, car, prep["rigid"]))
        record.update(figures)  # (none unless an open-loop step or sine-with-dwell run)
        if note:
            record["message"] = f"{res.message}; {note}" if res.message else note
        channels = {"t": np.asarray(res.t), **{k: np.asarray(v) for k, v in
                                              res.channels.items()}}
    except Exception as exc:  # a failed run is a result, never the end of the sweep
        last = traceback.extract_tb(exc.__traceback__)[-1]
        record.update(status=STATUS_ERROR, message=f"{type(exc).__name__}: {exc} "
                      f"(at {last.filename.rsplit('/', 1)[-1]}:{last.lineno})")
    record["task_s"] = time.perf_counter() - t0
    return record, channels


__all__ = ["STATUS_ERROR", "STATUS_LOST", "body_keys", "body_task", "mass_task", "road_of",
           "run_task"]
