"""Argument checks of :func:`flexpipe.vehicle.simulation.simulate`: numbers in range, and
the car, road and path each given as an object, a file or ``None``, turned into objects
with a clear error naming the argument otherwise."""

from __future__ import annotations

import math
from pathlib import Path

from flexpipe.errors import InputError
from flexpipe.vehicle.spec import Car, load_car


def checked_number(value, name, *, lo=None, hi=None, lo_closed=False):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}", key=name) from None
    below = lo is not None and (v < lo if lo_closed else v <= lo)
    if not math.isfinite(v) or below or (hi is not None and v > hi):
        left = "[" if lo_closed else "("
        rng = f"in {left}{lo:g}, {hi:g}]" if hi is not None else f"> {lo:g}"
        raise InputError(f"{name} must be finite and {rng}, got {value!r}", key=name)
    return v


def as_road(road, needed: float):
    from flexpipe.roads import Road, flat, load_road

    if road is None:
        return flat(needed + 50.0, dx=1.0, track_width=1.5)
    if isinstance(road, Road):
        return road
    if isinstance(road, (str, Path, dict)):
        return load_road(road)
    raise InputError(f"road must be a flexpipe Road, a road file (.toml/.crg/.csv) or None, "
                     f"got {type(road).__name__}", key="road")


def as_car(car) -> Car:
    if isinstance(car, Car):
        return car
    if isinstance(car, (str, Path)):
        return load_car(car)
    raise InputError(f"car must be a Car or a car file, got {type(car).__name__}", key="car")


def as_path(path, needed: float):
    from flexpipe.driver import Path as DPath
    from flexpipe.driver import read_path, straight

    if path is None or (isinstance(path, str) and path == "straight"):
        return straight(needed + 50.0, ds=1.0)
    if isinstance(path, DPath):
        return path
    if isinstance(path, (str, Path)):
        return read_path(path)
    raise InputError(f"path must be a flexpipe.driver.Path, a path file (.csv/.toml), "
                     f"'straight' or None, got {type(path).__name__}", key="path")
