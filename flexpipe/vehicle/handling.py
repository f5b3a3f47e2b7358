"""Steady-state cornering (ISO 4138): the handling diagram and the understeer gradient.

From a run's channels: lateral acceleration ``ay`` (body axes), yaw rate ``r`` (from
``yaw``), forward speed ``v`` and the bicycle road-wheel angle ``steer``, each averaged
over a sliding window (the quasi-steady values; body vibration and road noise are far
above the window's frequency).  The Ackermann angle of the turn the car drives is
``delta_A = atan(L r / v)`` (``L`` the wheelbase: the angle a car whose tyres do not slip
needs for the radius ``v / r``); the understeer angle is ``delta - delta_A``, and the
understeer gradient ``K`` its slope against ``ay`` over the linear range
(``ay_fit``), in deg/g: positive understeer, negative oversteer.  The same gradient
follows from a constant-radius run with a slowly rising speed (ISO 4138 method 1), a
constant-speed run with a slowly growing steer, or steady runs at several speeds.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from flexpipe.errors import InputError

G = 9.81  # m/s^2 per g, for the per-g figures


@dataclasses.dataclass(frozen=True)
class HandlingDiagram:
    """Quasi-steady samples of a run and the fitted understeer gradient.

    Attributes
    ----------
    t, ay, v, yaw_rate, steer, ackermann : ndarray
        Window-averaged samples (s, m/s^2, m/s, rad/s, rad, rad).
    gradient_deg_per_g : float
        Slope of the understeer angle against ``ay`` over ``ay_fit`` (deg/g).
    intercept_deg : float
        Understeer angle of the fit at ``ay = 0`` (deg; near 0 for a symmetric car).
    ay_fit : (float, float)
        The range of ``|ay|`` fitted (m/s^2).
    n_fit : int
        Samples in it.
    """

    t: np.ndarray
    ay: np.ndarray
    v: np.ndarray
    yaw_rate: np.ndarray
    steer: np.ndarray
    ackermann: np.ndarray
    gradient_deg_per_g: float
    intercept_deg: float
    ay_fit: tuple
    n_fit: int

    @property
    def understeer(self) -> np.ndarray:
        """Understeer angle ``steer - ackermann`` (rad)."""
        return self.steer - self.ackermann


def _window_mean(x: np.ndarray, n: int) -> np.ndarray:
    c = np.concatenate([[0.0], np.cumsum(x)])
    return (c[n:] - c[:-n]) / n


def handling_diagram(result, *, wheelbase: float, t_from: float = 2.0, window_s: float = 1.0,
                     ay_fit=(0.5, 4.0), v_min: float = 3.0) -> HandlingDiagram:
    """The handling diagram of ``result`` (a :class:`~flexpipe.vehicle.result.Result`).

    Parameters
    ----------
    result : Result
        A run with the channels ``ay``, ``yaw``, ``speed`` and ``steer``.
    wheelbase : float
        ``L`` (m), e.g. ``car.wheelbase``.
    t_from : float
        Start of the part used (s): after the start transient and the entry into the turn.
    window_s : float
        Averaging window (s).
    ay_fit : (float, float)
        Range of ``|ay|`` fitted (m/s^2); the default 0.5 - 4 m/s^2 is the linear range
        of a passenger car (about 0.05 - 0.4 g).
    v_min : float
        Samples slower than this (m/s) are left out (the yaw-rate radius is ill defined).

    Raises
    ------
    InputError
        Missing channels, a bad argument, or fewer than 10 samples in the fit range (the
        message gives the range the run covers).
    """
    for name in ("ay", "yaw", "speed", "steer"):
        if name not in result.channels:
            raise InputError(f"the run has no '{name}' channel; a handling diagram needs ay, "
                             "yaw, speed and steer (a full-car run)", key=name)
    if not (math.isfinite(wheelbase) and wheelbase > 0.0):
        raise InputError(f"wheelbase = {wheelbase!r} m; give the car's (> 0)", key="wheelbase")
    lo, hi = (float(a) for a in ay_fit)
    if not (0.0 <= lo < hi):
        raise InputError(f"ay_fit = {ay_fit!r}: give (low, high) with 0 <= low < high, m/s^2",
                         key="ay_fit")
    t = np.asarray(result.t, dtype=float)
    keep = t >= t_from
    if np.count_nonzero(keep) < 3:
        raise InputError(f"t_from = {t_from:g} s leaves no samples (the run ends at "
                         f"{t[-1]:g} s)", key="t_from")
    dt = float(np.median(np.diff(t)))
    n = max(1, int(round(window_s / dt)))
    yaw = np.unwrap(np.asarray(result["yaw"], dtype=float))
    r = np.gradient(yaw, t)
    chans = [np.asarray(result[c], dtype=float)[keep] for c in ("ay", "speed", "steer")]
    if chans[0].size <= n:
        raise InputError(f"the run after t_from = {t_from:g} s is shorter than the "
                         f"{window_s:g} s averaging window", key="window_s")
    tm, ay, v, steer, rm = (_window_mean(x, n) for x in (t[keep], *chans, r[keep]))
    moving = v > v_min
    tm, ay, v, steer, rm = (x[moving] for x in (tm, ay, v, steer, rm))
    ack = np.arctan(wheelbase * rm / np.where(v > 0.0, v, np.inf))
    sel = (np.abs(ay) >= lo) & (np.abs(ay) <= hi)
    if np.count_nonzero(sel) < 10:
        span = f"{np.abs(ay).min():.3g} .. {np.abs(ay).max():.3g}" if ay.size else "no"
        raise InputError(f"only {np.count_nonzero(sel)} samples with |ay| in {lo:g} .. "
                         f"{hi:g} m/s^2 (the run covers {span} m/s^2 after t_from = "
                         f"{t_from:g} s); drive a circle with a rising speed or several "
                         "speeds", key="ay_fit")
    # the understeer angle against |ay| (a right turn mirrored onto a left one)
    sign = np.sign(ay[sel])
    slope, icpt = np.polyfit(np.abs(ay[sel]), sign * (steer[sel] - ack[sel]), 1)
    return HandlingDiagram(t=tm, ay=ay, v=v, yaw_rate=rm, steer=steer, ackermann=ack,
                           gradient_deg_per_g=float(np.degrees(slope) * G),
                           intercept_deg=float(np.degrees(icpt)), ay_fit=(lo, hi),
                           n_fit=int(np.count_nonzero(sel)))


def plot(diagrams: dict, path, *, title: str = ""):
    """``handling.png``: understeer angle against lateral acceleration with each body's
    fit, and the steer against the Ackermann angle (``diagrams``: body -> diagram)."""
    from flexpipe.vehicle.plots import _figure, _save

    plt, fig = _figure(figsize=(10, 4.5))
    ax1, ax2 = fig.subplots(1, 2)
    for body, d in diagrams.items():
        g = np.abs(d.ay) / G
        sign = np.sign(d.ay)
        line, = ax1.plot(g, sign * np.degrees(d.understeer), ".", ms=2, alpha=0.5,
                         label=f"{body}: K = {d.gradient_deg_per_g:.2f} deg/g")
        x = np.array(d.ay_fit) / G
        ax1.plot(x, d.intercept_deg + d.gradient_deg_per_g * x, "-", color=line.get_color())
        ax2.plot(g, sign * np.degrees(d.steer), ".", ms=2, color=line.get_color(),
                 label=f"{body}: road-wheel angle")
        ax2.plot(g, sign * np.degrees(d.ackermann), "--", color=line.get_color(), lw=1,
                 label=f"{body}: Ackermann angle atan(L r / v)")
    for a in (ax1, ax2):
        a.axvspan(*(np.array(next(iter(diagrams.values())).ay_fit) / G), color="0.9",
                  zorder=0)
        a.set_xlabel("lateral acceleration |a_y| [g]")
        a.grid(True, alpha=0.3)
        a.legend(fontsize=8)
    ax1.set_ylabel("understeer angle, steer - Ackermann [deg]")
    ax1.set_title("understeer gradient (fit over the shaded range)", fontsize=9)
    ax2.set_ylabel("angle [deg]")
    ax2.set_title("bicycle road-wheel angle and kinematic angle", fontsize=9)
    if title:
        fig.suptitle(title, fontsize=10)
    return _save(plt, fig, path)
