"""Checks of a whole sweep before any run starts: every run's arguments as
:func:`~flexpipe.vehicle.simulation.simulate` will see them (road keys, road and path
lengths, body models) and the ``[plots] metrics``, each error naming the sweep file and
the sweep key.  The settings' ranges are checked earlier, in
:meth:`flexpipe.sweeps.spec.SweepSpec.runs`.
"""

from __future__ import annotations

import difflib
import json

from flexpipe.errors import InputError

#: keys of :func:`~flexpipe.vehicle.run_inputs.check_run` errors -> sweep settings
_SETTING = {"speed": "speed_kmh", "t_end": "t_end_s", "h": "h_s",
            "output_step": "output_step_s", "body": "body", "path": "path", "road": "road",
            "driver": "driver"}


def _sweep_key(spec, run, key, file=None) -> str | None:
    """The sweep key behind the ``key`` of an error raised for ``run`` (in ``file``)."""
    for name in ("driver", "speed_profile"):  # an error in the run's driver or profile file
        given = getattr(run, name, None)
        if given and file is not None and str(file) == given:
            return spec._key(name, run.params, run.index)
    if key == "speed" and getattr(run, "speed_profile", None):
        return spec._key("speed_profile", run.params, run.index)
    if key in _SETTING:
        return spec._key(_SETTING[key], run.params, run.index)
    if isinstance(key, str) and key.startswith("road.") and key in run.params:
        return spec._key(key, run.params, run.index)
    if isinstance(key, str) and key.startswith("road."):  # a key of the base [road] table
        return key if "road" not in run.params else spec._key("road", run.params, run.index)
    return key


def check_runs(spec, runs, cars) -> None:
    """Check every run's arguments (:func:`~flexpipe.vehicle.run_inputs.check_run`) and
    build every distinct road once, before any run starts.

    Raises
    ------
    InputError
        The first bad run, named with its parameters, the sweep file and the sweep key.
    """
    from flexpipe.sweeps.spec import _describe_road
    from flexpipe.sweeps.tasks import road_of
    from flexpipe.vehicle.run_inputs import check_run

    roads = {}
    for run, car in zip(runs, cars, strict=True):
        try:
            ident = json.dumps(_describe_road(run.road), sort_keys=True, default=str)
            if ident not in roads:
                roads[ident] = road_of(run)
            check_run(car, road=roads[ident], path=run.path,
                      speed=run.speed_profile or run.speed, t_end=run.t_end, body=run.body,
                      h=run.h, output_step=run.output_step, driver=run.driver)
        except InputError as exc:
            params = ", ".join(f"{k} = {v!r}" for k, v in run.params.items())
            raise InputError(f"run {run.index} ({params}): {exc}", file=spec.file,
                             key=_sweep_key(spec, run, exc.key, exc.file)) from None


def check_plot_metrics(spec, cars, runs=None) -> None:
    """Every name of ``[plots] metrics`` is a metric the sweep's runs write (the
    figures of an open-loop step or sine with dwell when a run's ``driver`` is one;
    ``runs`` default: ``spec.runs()``).

    Raises
    ------
    InputError
        An unknown name, with the closest valid one and the list of valid metrics.
    """
    from flexpipe.sweeps.manoeuvres import open_loop_kind
    from flexpipe.sweeps.metrics import metric_names

    if not spec.plots:
        return
    points = []
    for car in cars:
        points += [p for p in car.body.points if p not in points]
    runs = spec.runs() if runs is None else runs
    kinds = {open_loop_kind(r.driver) for r in runs if getattr(r, "driver", None)}
    valid = metric_names(points, tuple(k for k in kinds if k))
    for name in spec.plots:
        if name not in valid:
            close = difflib.get_close_matches(name, valid, n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else ""
            raise InputError(f"unknown metric {name!r}{hint}; valid metrics: "
                             f"{', '.join(valid)}", file=spec.file, key="plots.metrics")


__all__ = ["check_plot_metrics", "check_runs"]
