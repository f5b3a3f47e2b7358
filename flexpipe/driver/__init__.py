"""Driver: paths to follow, a pure-pursuit steering controller and a PI speed controller.

* :class:`Path` (frozen) with constructors :func:`straight`, :func:`slalom`,
  :func:`iso3888_1`, :func:`circle` and readers :func:`read_path` (``.csv`` x, y points or ``.toml``
  ``[path]`` table), :func:`path_from_spec`.
* :class:`PurePursuit` (frozen; gains from ``[steering]``) and :class:`SpeedPI`
  (gains from ``[speed]``, keeps its integral), :func:`read_driver`; both commands pass
  the driver's neuromuscular lag (:class:`FirstOrderLag`, 0.1 s unless the file says).
* :class:`OpenLoopSteer` (frozen): a steering-wheel angle against time (step, ramp,
  sine with dwell, sine, table) in place of the path follower; :class:`OpenLoopTorque`
  (frozen): a wheel torque against time in place of the speed controller.
* :class:`SpeedProfile` (frozen): target speed against time or distance,
  :func:`read_speed_profile` (``.toml`` ``[speed_profile]`` or ``.csv``).
* :class:`KinematicBicycle` and :func:`simulate`: a cheap test vehicle.
"""

from flexpipe.driver.bicycle import KinematicBicycle, simulate
from flexpipe.driver.control import FirstOrderLag, PurePursuit, SpeedPI, read_driver
from flexpipe.driver.open_loop import OpenLoopSteer, OpenLoopTorque
from flexpipe.driver.path import Path
from flexpipe.driver.speed import SpeedProfile, read_speed_profile
from flexpipe.driver.tracks import (
    ISO3888_1_LENGTHS,
    ISO3888_1_OFFSET,
    PATH_TYPES,
    circle,
    iso3888_1,
    iso3888_1_lanes,
    path_from_spec,
    read_path,
    read_path_csv,
    slalom,
    straight,
)

__all__ = [
    "FirstOrderLag",
    "ISO3888_1_LENGTHS",
    "ISO3888_1_OFFSET",
    "PATH_TYPES",
    "KinematicBicycle",
    "OpenLoopSteer",
    "OpenLoopTorque",
    "Path",
    "PurePursuit",
    "SpeedPI",
    "SpeedProfile",
    "circle",
    "iso3888_1",
    "iso3888_1_lanes",
    "path_from_spec",
    "read_driver",
    "read_path",
    "read_path_csv",
    "read_speed_profile",
    "simulate",
    "slalom",
    "straight",
]
