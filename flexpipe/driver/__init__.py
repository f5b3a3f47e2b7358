"""Driver: paths to follow, a pure-pursuit steering controller and a PI speed controller.

* :class:`Path` (frozen) with constructors :func:`straight`, :func:`slalom`,
  :func:`iso3888_1` and readers :func:`read_path` (``.csv`` x, y points or ``.toml``
  ``[path]`` table), :func:`path_from_spec`.
* :class:`PurePursuit` (frozen; gains from ``[steering]``) and :class:`SpeedPI`
  (gains from ``[speed]``, keeps its integral), :func:`read_driver`.
* :class:`KinematicBicycle` and :func:`simulate`: a cheap test vehicle.
"""

from flexpipe.driver.bicycle import KinematicBicycle, simulate
from flexpipe.driver.control import PurePursuit, SpeedPI, read_driver
from flexpipe.driver.path import Path
from flexpipe.driver.tracks import (
    ISO3888_1_LENGTHS,
    ISO3888_1_OFFSET,
    PATH_TYPES,
    iso3888_1,
    iso3888_1_lanes,
    path_from_spec,
    read_path,
    read_path_csv,
    slalom,
    straight,
)

__all__ = [
    "ISO3888_1_LENGTHS",
    "ISO3888_1_OFFSET",
    "PATH_TYPES",
    "KinematicBicycle",
    "Path",
    "PurePursuit",
    "SpeedPI",
    "iso3888_1",
    "iso3888_1_lanes",
    "path_from_spec",
    "read_driver",
    "read_path",
    "read_path_csv",
    "simulate",
    "slalom",
    "straight",
]
