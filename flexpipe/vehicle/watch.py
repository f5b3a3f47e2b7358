"""What stops a car run: states that no car reaches, found before every step.

:class:`~flexpipe.vehicle.dynamics.CarController` asks :func:`state_problem` about the
state at the start of each step and :func:`tire_problem` about the tyre forces over the
step just taken; a sentence comes back when the run must stop (``None`` otherwise), and
the run stops with it and the simulated time (:func:`flexpipe.vehicle.diagnose.explain`
then adds the channel that grew most and the implausible inputs).

The limits sit far beyond any manoeuvre a car survives, so a stop is either numerical
divergence or an input outside what the model represents, never a hard but physical run:

* body angular velocity above :data:`MAX_BODY_RATE` (20 rad/s): a car rolling over turns
  at a few rad/s; an attitude that changes faster is divergence, whatever angle it
  reaches (the overturn check alone would blame the driving);
* wheel spin above :data:`MAX_SPIN` (1000 rad/s, a 0.3 m wheel rolling at 1080 km/h);
* a tyre normal force above :data:`MAX_TIRE_LOAD` (10) times the car's weight: a pothole
  hit gives a few times the static wheel load, so such a force is divergence or a road
  step the point-contact tyre cannot take;
* roll or pitch beyond :data:`MAX_ATTITUDE` (1 rad): the car overturned;
* suspension travel beyond :data:`MAX_TRAVEL` (0.5 m).
"""

from __future__ import annotations

import math

import numpy as np

from flexpipe.vehicle.spec import CORNERS

#: rad/s: the body's angular velocity beyond which a run is divergence, not driving
MAX_BODY_RATE = 20.0
#: rad/s: wheel spin beyond which a run is divergence
MAX_SPIN = 1000.0
#: tyre normal force beyond this many times the car's weight: divergence or a bad road
MAX_TIRE_LOAD = 10.0
#: rad: roll or pitch beyond which the car overturned
MAX_ATTITUDE = 1.0
#: m: suspension travel beyond which a wheel left its range
MAX_TRAVEL = 0.5

_STIFF = ("numerical divergence: an element too stiff for the step (spring, anti-roll bar, "
          "bushing or tyre rates, a tiny mass or spin inertia in the car file) or a too "
          "large step h")


def state_problem(st, roll: float, pitch: float) -> str | None:
    """Why the run must stop at state ``st`` (roll and pitch in rad), or ``None``.

    Runs before every step, so it works on Python floats (a few microseconds; NumPy
    calls on these 3- and 4-vectors cost several times more)."""
    total = (float(st.body_p.sum()) + float(st.wheel_p.sum()) + float(st.jounce.sum())
             + float(st.spin_rate.sum()))
    if not math.isfinite(total):  # a NaN or inf anywhere makes the sum non-finite
        return "the state became non-finite (NaN/inf): numerical divergence; try a smaller step h"
    wx, wy, wz = st.body_w.tolist()
    w = math.sqrt(wx * wx + wy * wy + wz * wz)
    if w > MAX_BODY_RATE:
        return (f"the body turns at {w:.3g} rad/s (roll {math.degrees(roll):.0f} deg, pitch "
                f"{math.degrees(pitch):.0f} deg), beyond the {MAX_BODY_RATE:g} rad/s no car "
                f"reaches even when rolling over: {_STIFF}")
    spin = st.spin_rate.tolist()
    if max(map(abs, spin)) > MAX_SPIN:
        i = max(range(4), key=lambda k: abs(spin[k]))
        return (f"wheel {CORNERS[i]} spins at {spin[i]:.3g} rad/s, beyond "
                f"{MAX_SPIN:g} rad/s: {_STIFF}")
    if abs(roll) > MAX_ATTITUDE or abs(pitch) > MAX_ATTITUDE:
        return (f"roll {math.degrees(roll):.0f} deg / pitch {math.degrees(pitch):.0f} deg: "
                "the car overturned (speed or manoeuvre too severe)")
    travel = st.jounce.tolist()
    if max(map(abs, travel)) > MAX_TRAVEL:
        i = max(range(4), key=lambda k: abs(travel[k]))
        return (f"suspension travel {travel[i]:.2f} m at corner {CORNERS[i]}: the wheel "
                f"left its travel range: missing bump/rebound stops, or {_STIFF}")
    return None


def tire_problem(Fz, weight_N: float | None) -> str | None:
    """Why the tyre normal forces ``Fz`` (4,) stop the run (``weight_N``: the car's
    weight; ``None`` checks nothing), or ``None``."""
    if weight_N is None:
        return None
    Fz = np.asarray(Fz, dtype=float).tolist()
    if max(Fz) > MAX_TIRE_LOAD * weight_N:
        i = max(range(len(Fz)), key=Fz.__getitem__)
        return (f"tyre normal force {Fz[i]:.3g} N at corner {CORNERS[i]}, "
                f"{Fz[i] / weight_N:.0f} times the car's weight ({weight_N:.0f} N): "
                "a road step or edge the point-contact tyre cannot take (check the road "
                f"under the {CORNERS[i]} wheel here) or {_STIFF}")
    return None
