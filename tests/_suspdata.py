"""Suspension hardpoints for the tests: typed literals and readers of Chrono's JSON files.

The literals are Chrono's Sedan double wishbone / multi-link hardpoints placed in the car
frame (front: +0.418 m in z; rear: -2.75 m in x, +0.3013 m in z), typed here so the tests run
without ../shared; the readers take the same files when present.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

REF = Path(__file__).resolve().parents[1] / ".." / "shared" / "reference" / "vehicle"

SEDAN_FRONT = {
    "lower_arm_front": (0.200, 0.420, 0.148), "lower_arm_rear": (-0.200, 0.470, 0.153),
    "lower_arm_outer": (0.000, 0.770, 0.098), "upper_arm_front": (-0.100, 0.470, 0.523),
    "upper_arm_rear": (-0.250, 0.510, 0.528), "upper_arm_outer": (-0.040, 0.695, 0.523),
    "tie_rod_inner": (-0.200, 0.420, 0.298), "tie_rod_outer": (-0.150, 0.770, 0.298),
    "spring_upper": (-0.040, 0.520, 0.648), "spring_lower": (0.000, 0.620, 0.148),
    "damper_upper": (-0.040, 0.520, 0.648), "damper_lower": (0.000, 0.620, 0.148),
    "wheel_center": (0.000, 0.7979, 0.2983),
}
SEDAN_REAR = {
    "upper_arm_front": (-2.690, 0.397, 0.3833), "upper_arm_rear": (-2.907, 0.358, 0.3633),
    "upper_arm_outer": (-2.694, 0.714, 0.4523), "lateral_link_inner": (-2.714, 0.188, 0.1683),
    "lateral_link_outer": (-2.721, 0.692, 0.2083), "trailing_link_front": (-2.027, 0.449, 0.2293),
    "trailing_link_outer": (-2.750, 0.714, 0.1453), "tie_rod_inner": (-3.007, 0.170, 0.1853),
    "tie_rod_outer": (-2.894, 0.712, 0.2453), "spring_upper": (-2.569, 0.491, 0.4113),
    "spring_lower": (-2.569, 0.419, 0.1373), "damper_upper": (-2.579, 0.478, 0.6163),
    "damper_lower": (-2.569, 0.519, 0.1393), "wheel_center": (-2.750, 0.800, 0.3013),
}
SEDAN_REAR_UNIVERSAL = ((0.0, 0.0, 1.0), (-0.272, 0.962, 0.0))


def _read(name):
    path = REF / name
    if not path.is_file():
        return None
    return json.loads(path.read_text())


def chrono_double_wishbone(name="Sedan_DoubleWishbone.json", offset=(0, 0, 0)):
    """Hardpoints of a Chrono DoubleWishbone JSON file (None when absent)."""
    d = _read(name)
    if d is None:
        return None
    o = np.asarray(offset, float)
    lo, up = d["Lower Control Arm"], d["Upper Control Arm"]
    pts = {"lower_arm_front": lo["Location Chassis Front"],
           "lower_arm_rear": lo["Location Chassis Back"], "lower_arm_outer": lo["Location Upright"],
           "upper_arm_front": up["Location Chassis Front"],
           "upper_arm_rear": up["Location Chassis Back"], "upper_arm_outer": up["Location Upright"],
           "tie_rod_inner": d["Tierod"]["Location Chassis"],
           "tie_rod_outer": d["Tierod"]["Location Upright"],
           "spring_upper": d["Spring"]["Location Chassis"],
           "spring_lower": d["Spring"]["Location Arm"],
           "damper_upper": d["Shock"]["Location Chassis"],
           "damper_lower": d["Shock"]["Location Arm"], "wheel_center": d["Spindle"]["COM"]}
    return {k: np.asarray(v, float) + o for k, v in pts.items()}


def chrono_macpherson(name="MacPhersonStrut.json"):
    """Hardpoints of Chrono's generic MacPherson strut (strut axis = spring line)."""
    d = _read(name)
    if d is None:
        return None
    pts = {"lower_arm_front": d["Control Arm"]["Location Chassis Front"],
           "lower_arm_rear": d["Control Arm"]["Location Chassis Back"],
           "lower_arm_outer": d["Control Arm"]["Location Upright"],
           "strut_top": d["Spring"]["Location Chassis"],
           "strut_lower": d["Spring"]["Location Upright"],
           "tie_rod_inner": d["Tierod"]["Location Chassis"],
           "tie_rod_outer": d["Tierod"]["Location Upright"],
           "spring_upper": d["Spring"]["Location Chassis"],
           "spring_lower": d["Spring"]["Location Upright"],
           "damper_upper": d["Shock"]["Location Chassis"],
           "damper_lower": d["Shock"]["Location Upright"], "wheel_center": d["Spindle"]["COM"]}
    return {k: np.asarray(v, float) for k, v in pts.items()}


def chrono_multi_link(name="Sedan_MultiLink.json", offset=(0, 0, 0)):
    """Hardpoints and universal-joint axes of a Chrono MultiLink file (None when absent)."""
    d = _read(name)
    if d is None:
        return None
    o = np.asarray(offset, float)
    up, lat, tr = d["Upper Arm"], d["Lateral"], d["Trailing Link"]
    pts = {"upper_arm_front": up["Location Chassis Front"],
           "upper_arm_rear": up["Location Chassis Back"], "upper_arm_outer": up["Location Upright"],
           "lateral_link_inner": lat["Location Chassis"],
           "lateral_link_outer": lat["Location Upright"],
           "trailing_link_front": tr["Location Chassis"],
           "trailing_link_outer": tr["Location Upright"],
           "tie_rod_inner": d["Tierod"]["Location Chassis"],
           "tie_rod_outer": d["Tierod"]["Location Upright"],
           "spring_upper": d["Spring"]["Location Chassis"],
           "spring_lower": d["Spring"]["Location Link"],
           "damper_upper": d["Shock"]["Location Chassis"],
           "damper_lower": d["Shock"]["Location Link"], "wheel_center": d["Spindle"]["COM"]}
    axes = (tr["Universal Joint Axis Link"], tr["Universal Joint Axis Chassis"])
    return {k: np.asarray(v, float) + o for k, v in pts.items()}, axes
