"""Why a run stopped early: what diverged, where and when, and which input is implausible.

:func:`explain` extends the stop message of :func:`~flexpipe.vehicle.simulate` with

* the implausible inputs found by :func:`suspect_inputs` -- a spring preload that is
  not positive or differs from the force holding the design position (the car's
  static equilibrium, :func:`~flexpipe.vehicle.corners.corner_arrays`) by more than
  half a wheel load: such a car starts far from equilibrium, which no step size fixes;
* the last recorded state (:func:`last_state`): the channel that grew most in the
  last recorded steps (its name says what and where: ``travel_fl``, ``hub_rr_z``, ...),
  its value and the time, and the largest suspension travel.

Only the generic "try a smaller step" advice is kept when nothing else stands out.
"""

from __future__ import annotations

import numpy as np

from flexpipe.vehicle.corners import GRAVITY
from flexpipe.vehicle.spec import CORNERS

#: a preload off the static requirement by more than this share of the wheel load
PRELOAD_TOL = 0.5
_UNITS = {"travel": "m", "hub": "N", "tire": "N", "spin": "rad/s", "acc": "m/s^2",
          "roll": "rad", "pitch": "rad", "yaw": "rad", "speed": "m/s", "z": "m"}


def suspect_inputs(car, body_mass: float, body_cg, *, g: float = GRAVITY) -> list[str]:
    """Sentences naming implausible inputs of ``car`` (file key and value), may be empty."""
    from flexpipe.vehicle.corners import static_wheel_loads

    out = []
    if all(c.spring_preload is None for c in car.corners):
        return out
    need = static_wheel_loads(car, body_mass, body_cg, g=g) - g * np.array(
        [c.unsprung_mass for c in car.corners])
    for c, want in zip(car.corners, need, strict=True):
        if c.spring_preload is None:
            continue
        p = float(c.spring_preload)
        if p <= 0 or abs(p - want) > PRELOAD_TOL * abs(want):
            out.append(f"corners.{c.name}.spring_preload_N = {p:g} N in {car.file} (holding "
                       f"the design position needs {want:.0f} N: the car starts far from "
                       "equilibrium)")
    return out


def last_state(t: np.ndarray, channels: dict) -> str:
    """What diverged: the channel growing fastest over the last records, and when."""
    if t.size < 2:
        return ""
    worst, worst_growth = None, 1.0
    for name, v in channels.items():
        v = np.asarray(v, dtype=float)
        ok = np.isfinite(v)
        if ok.sum() < 2:
            continue
        vv, tt = v[ok], t[ok]
        early = np.abs(vv[: max(2, len(vv) // 2)]).max()
        late = np.abs(vv[-1])
        scale = max(early, 1e-3 if name.startswith(("travel", "roll", "pitch")) else 1.0)
        growth = late / scale
        if growth > worst_growth and (name.startswith(("travel", "hub", "tire"))):
            worst, worst_growth = (name, vv[-1], tt[-1]), growth
    parts = []
    if worst is not None and worst_growth > 3.0:
        name, val, tt = worst
        unit = _UNITS.get(name.split("_")[0], "")
        parts.append(f"{name} grew to {val:.4g} {unit} at t = {tt:.4f} s ({worst_growth:.0f}x "
                     "its earlier magnitude)")
    travel = [(c, np.asarray(channels.get(f"travel_{c}", [np.nan]), dtype=float)) for c in
              CORNERS]
    last = [(c, v[np.isfinite(v)][-1]) for c, v in travel if np.isfinite(v).any()]
    if last:
        c, val = max(last, key=lambda cv: abs(cv[1]))
        parts.append(f"largest suspension travel at the last record: {val:.4g} m at {c}")
    return "; ".join(parts)


def explain(message: str, *, car, body_mass: float, body_cg, t: np.ndarray,
            channels: dict) -> str:
    """``message`` plus what diverged and the implausible inputs (when found)."""
    extra = []
    suspects = suspect_inputs(car, body_mass, body_cg)
    if suspects:
        extra.append("implausible input: " + "; ".join(suspects))
    state = last_state(np.asarray(t, dtype=float), channels)
    if state:
        extra.append("last recorded state: " + state)
    return message if not extra else f"{message}. " + ". ".join(extra)
