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


def ay_at(result, x: float, z: float = 0.0) -> np.ndarray:
    """Lateral acceleration (m/s^2, body axes) at the body point ``(x, 0, z)`` (m) from the
    ``ay`` channel of the body origin: ``ay + dr/dt x - dp/dt z`` with the yaw and roll
    rates ``r``, ``p`` from ``yaw`` and ``roll`` (the centripetal terms, second order in
    the rates, are left out).  ISO 7401 takes it at the centre of mass."""
    t = np.asarray(result.t, dtype=float)
    r = np.gradient(np.unwrap(np.asarray(result["yaw"], dtype=float)), t)
    p = np.gradient(np.asarray(result["roll"], dtype=float), t)
    return np.asarray(result["ay"], dtype=float) + np.gradient(r, t) * float(x) \
        - np.gradient(p, t) * float(z)


def centre_of_mass(result, car) -> tuple[float, float]:
    """Body-axis ``(x, z)`` (m) of the car's centre of mass: ``x`` from a run's static wheel
    loads, ``z`` the body's own (:func:`flexpipe.vehicle.bodymodel.rigid_properties`; the
    mass that rolls)."""
    from flexpipe.vehicle import bodymodel

    loads = np.asarray(result.info["static_wheel_load_N"], dtype=float)
    x = np.array([c.wheel_center[0] for c in car.corners])
    return float(loads @ x / loads.sum()), float(bodymodel.rigid_properties(car)
                                                  .center_of_mass[2])


def step_response(result, *, cg=(0.0, 0.0), settle_s: float = 1.0,
                  smooth_s: float = 0.05) -> dict:
    """ISO 7401 step-steer figures of ``result`` (an open-loop step input); the lateral
    acceleration at the body point ``cg = (x, z)`` (:func:`ay_at`,
    :func:`centre_of_mass`; default the body origin).

    The time origin is the instant the steering-wheel angle passes half its final value
    (``t50``).  Response time: from there until the yaw rate (or the lateral
    acceleration, smoothed over ``smooth_s``) first reaches 90 % of its steady value,
    the mean over the last ``settle_s`` seconds; peak response time and overshoot from
    its largest value.  Gains are steady values per steering-wheel angle.

    Raises
    ------
    InputError
        No steering input, or a run that has not settled (the yaw rate of the last
        ``settle_s`` seconds varies by more than 2 % of its mean).
    """
    t = np.asarray(result.t, dtype=float)
    sw = np.asarray(result["steering_wheel"], dtype=float)
    tail = t >= t[-1] - settle_s
    sw_ss = float(sw[tail].mean())
    if abs(sw_ss) < 1e-6:
        raise InputError("the steering wheel ends at 0: not a step steer", key="steering")
    sign = math.copysign(1.0, sw_ss)
    t50 = float(t[np.argmax(sign * sw >= 0.5 * abs(sw_ss))])
    r = sign * np.gradient(np.unwrap(np.asarray(result["yaw"], dtype=float)), t)
    n = max(1, int(round(smooth_s / float(np.median(np.diff(t))))))
    ay = sign * np.convolve(ay_at(result, *cg), np.ones(n) / n, "same")
    out = {"steering_wheel_deg": math.degrees(sw_ss), "t50_s": t50,
           "ay_at_x_m": float(cg[0]), "ay_at_z_m": float(cg[1]),
           "speed_kmh": float(np.mean(result["speed"][tail]) * 3.6)}
    for name, x, unit in (("yaw_rate", r, "deg_per_s"), ("ay", ay, "mps2")):
        ss = float(x[tail].mean())
        if name == "yaw_rate" and np.ptp(x[tail]) > 0.02 * abs(ss):
            raise InputError(f"the yaw rate has not settled: it varies by "
                             f"{np.ptp(x[tail]) / abs(ss) * 100:.1f} % over the last "
                             f"{settle_s:g} s; run longer", key="t_end")
        after = t >= t50
        reach = np.flatnonzero(after & (x >= 0.9 * ss))
        k_peak = int(np.flatnonzero(after)[0] + np.argmax(x[after]))
        scale = math.degrees(1.0) if unit == "deg_per_s" else 1.0
        out.update({f"{name}_steady_{unit}": ss * scale,
                    f"{name}_response_time_s": float(t[reach[0]] - t50) if reach.size
                    else float("nan"),
                    f"{name}_peak_response_time_s": float(t[k_peak] - t50),
                    f"{name}_overshoot_pct": float((x[k_peak] - ss) / ss * 100.0)})
    out["yaw_rate_gain_per_s"] = out["yaw_rate_steady_deg_per_s"] / abs(out["steering_wheel_deg"])
    out["ay_gain_mps2_per_100deg"] = out["ay_steady_mps2"] / abs(out["steering_wheel_deg"]) * 100
    return {k: round(v, 5) for k, v in out.items()}


def sine_with_dwell_response(result, *, cg=(0.0, 0.0)) -> dict:
    """UN R140 / FMVSS 126 figures of a sine-with-dwell run (an open-loop input).

    From the steering-wheel channel: the beginning of steer (BOS, the input leaves 0) and
    the completion of steer (COS, it returns to 0 for good).  The yaw-rate peak is the
    one the reversal produces: the largest yaw rate against the first steer between the
    input's change of sign and COS; the regulation's stability criteria are the
    yaw rate 1.0 s and 1.75 s after COS at most 35 % and 20 % of it, its responsiveness
    criterion the lateral displacement of the centre of mass (``cg``, body axes) from its
    straight path at 1.07 s after BOS, towards the first steer, at least 1.83 m for cars
    up to 3.5 t.

    Raises
    ------
    InputError
        No sign change in the input, or a run that ends before COS + 1.75 s.
    """
    t = np.asarray(result.t, dtype=float)
    sw = np.asarray(result["steering_wheel"], dtype=float)
    moving = np.flatnonzero(np.abs(sw) > 1e-6)
    if moving.size == 0:
        raise InputError("the steering wheel never moves: not a sine with dwell",
                         key="steering")
    # the last sample at 0 before the input moves, the first at 0 for good after it
    bos = float(t[max(moving[0] - 1, 0)])
    cos_ = float(t[min(moving[-1] + 1, t.size - 1)])
    first = math.copysign(1.0, sw[moving[0] + 1] if moving[0] + 1 < t.size else sw[moving[0]])
    flipped = np.flatnonzero((np.arange(t.size) > moving[0]) & (first * sw < 0.0))
    if flipped.size == 0:
        raise InputError("the steering wheel does not change sign: not a sine with dwell",
                         key="steering")
    if t[-1] < cos_ + 1.75 - 1e-9:
        raise InputError(f"the run ends at {t[-1]:g} s, before COS + 1.75 s = "
                         f"{cos_ + 1.75:g} s; give t_end >= {cos_ + 1.75:g} s", key="t_end")
    yaw = np.unwrap(np.asarray(result["yaw"], dtype=float))
    r = np.gradient(yaw, t)
    after = flipped[0]  # the peak the reversal produces: between it and COS
    end = max(after + 1, int(np.searchsorted(t, cos_, side="right")))
    k = after + int(np.argmax(-first * r[after:end]))
    peak = float(r[k])

    def at(x, time):
        return float(np.interp(time, t, x))

    # the centre of mass's lateral displacement from the initial straight path
    psi0 = float(yaw[0])
    x_cg, _ = cg
    px = np.asarray(result["x"]) + x_cg * np.cos(yaw)
    py = np.asarray(result["y"]) + x_cg * np.sin(yaw)
    lateral = -(px - px[0]) * math.sin(psi0) + (py - py[0]) * math.cos(psi0)
    out = {"bos_s": bos, "cos_s": cos_, "yaw_rate_peak_deg_per_s": math.degrees(peak),
           "yaw_rate_peak_time_s": float(t[k]),
           "yaw_rate_ratio_cos_plus_1s": at(r, cos_ + 1.0) / peak,
           "yaw_rate_ratio_cos_plus_1_75s": at(r, cos_ + 1.75) / peak,
           "lateral_displacement_bos_plus_1_07s_m": first * at(lateral, bos + 1.07)}
    out["stable"] = bool(out["yaw_rate_ratio_cos_plus_1s"] <= 0.35
                         and out["yaw_rate_ratio_cos_plus_1_75s"] <= 0.20)
    out["responsive"] = bool(out["lateral_displacement_bos_plus_1_07s_m"] >= 1.83)
    return {k: (round(v, 5) if isinstance(v, float) else v) for k, v in out.items()}


def plot_response(results: dict, path, *, cg=(0.0, 0.0), title: str = ""):
    """``steer_response.png``: steering-wheel angle, yaw rate and lateral acceleration
    (at the body point ``cg = (x, z)``) against time for each run of an open-loop
    input."""
    from flexpipe.vehicle.plots import STYLE, _figure, _save

    plt, fig = _figure(figsize=(9, 7))
    axes = fig.subplots(3, 1, sharex=True)
    for body, r in results.items():
        style = STYLE.get(body, {})
        yaw_rate = np.gradient(np.unwrap(np.asarray(r["yaw"], dtype=float)), r.t)
        rows = (np.degrees(r["steering_wheel"]), np.degrees(yaw_rate), ay_at(r, *cg))
        for ax, y in zip(axes, rows, strict=True):
            ax.plot(r.t, y, label=body, **style)
    for ax, label in zip(axes, ("steering wheel [deg]", "yaw rate [deg/s]",
                                "lateral acceleration [m/s^2]"), strict=True):
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[-1].set_title(f"a_y at body point x = {cg[0]:.3g} m, z = {cg[1]:.3g} m (centre of "
                       "mass when given)", fontsize=8)
    axes[-1].set_xlabel("time t [s]")
    if title:
        fig.suptitle(title, fontsize=10)
    return _save(plt, fig, path)
