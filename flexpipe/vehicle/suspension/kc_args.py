"""Argument checks of :func:`flexpipe.vehicle.suspension.kc.kc`: every bad argument is an
:class:`~flexpipe.errors.InputError` naming it and what would be valid, raised before the
analysis (which takes seconds) and before anything is written."""

from __future__ import annotations

from pathlib import Path

from flexpipe._args import as_path, checked_int, checked_number
from flexpipe.errors import InputError

#: fewest points per sweep (``flexpipe kc --points``): the tables' rates are slopes
#: (:func:`numpy.gradient`) of the sweep, which need a point between its ends; the summary
#: is evaluated at the design position whatever the sweep
N_MIN = 3
#: largest wheel travel +-, m: beyond any road car's bump/rebound travel; a larger value
#: is most likely millimetres given as metres (the CLI's ``--travel`` is in mm)
TRAVEL_MAX_M = 0.5
#: largest rack travel +-, m (a steering rack moves some 0.05-0.1 m each way)
RACK_TRAVEL_MAX_M = 0.5


def _suspension(car):
    """The ``Suspension`` of ``car``: a ``Suspension``, a ``Car`` or a car file; the axles
    of a car know their subframes (:func:`~flexpipe.vehicle.suspension.carrier.
    with_subframes`)."""
    from flexpipe.vehicle._car_base import parse_car
    from flexpipe.vehicle.spec import Car, load_car
    from flexpipe.vehicle.suspension.carrier import with_subframes
    from flexpipe.vehicle.suspension.spec import Suspension, load_suspension

    if isinstance(car, Suspension):
        return car
    if isinstance(car, Car):
        if car.suspension is None:
            raise InputError("this car has prismatic corners, no [suspension.*] tables; the "
                             "K&C rig needs a linkage car (e.g. cars/sedan_linkage.toml)",
                             file=car.file, key="car")
        return with_subframes(car.suspension, car.subframes)
    if not isinstance(car, (str, Path)) and not hasattr(car, "__fspath__"):
        raise InputError(f"car must be a Car (flexpipe.load_car), a car file (str or "
                         f"pathlib.Path) or a Suspension, got {type(car).__name__}",
                         key="car")
    path = as_path(car, "car")
    if path.suffix.lower() == ".toml" and path.is_file() and "subframe" in parse_car(path)[0]:
        return _suspension(load_car(path))   # its subframes need the whole car file
    return load_suspension(path)


def _axle_names(axles, valid) -> set | None:
    """The axles to run, as names of ``valid`` (case-insensitive), or None for all."""
    if axles is None:
        return None
    items = [axles] if isinstance(axles, str) else axles
    try:
        items = list(items)
    except TypeError:
        items = [items]
    names = set()
    for a in items:
        match = [v for v in valid if isinstance(a, str) and v.lower() == a.strip().lower()]
        if not match:
            raise InputError(f"unknown axle {a!r}; valid: {', '.join(valid)} (or None for "
                             "all)", key="axles")
        names.add(match[0])
    if not names:
        raise InputError(f"axles is empty; give some of {', '.join(valid)} or None for all",
                         key="axles")
    return names


def check_kc_arguments(car, *, out, travel, n, rack_travel, force, axles):
    """The checked arguments of :func:`~flexpipe.vehicle.suspension.kc.kc`.

    Returns
    -------
    tuple
        ``(suspension, travel, n, rack_travel, force, axle names or None)``.

    Raises
    ------
    InputError
        The first bad argument, named by its ``key``.
    """
    travel = checked_number(travel, "travel", lo=0.0, hi=TRAVEL_MAX_M, unit="m")
    n = checked_int(n, "n", lo=N_MIN)
    rack_travel = checked_number(rack_travel, "rack_travel", lo=0.0, hi=RACK_TRAVEL_MAX_M,
                                 unit="m")
    force = checked_number(force, "force", lo=0.0, unit="N")
    if out is not None:
        from flexpipe._io import check_output_folder

        check_output_folder(as_path(out, "out"), option="out")
    susp = _suspension(car)
    return susp, travel, n, rack_travel, force, _axle_names(axles, list(susp.axles))


__all__ = ["N_MIN", "RACK_TRAVEL_MAX_M", "TRAVEL_MAX_M", "check_kc_arguments"]
