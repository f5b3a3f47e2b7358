"""Per-run metrics of a sweep: hub forces, ISO 2631-1 ride values, suspension travel and
path error, computed from a :class:`~flexpipe.vehicle.result.Result`.

Every column name carries its unit.  For a corner ``c`` (fl, fr, rl, rr), an axis ``k``
(x, y, z, body axes) and a named body point ``p`` (channels ``acc_<p>_x|y|z``):

``hub_<c>_<k>_std_N``
    Fluctuation of the hub force on the body: its standard deviation about the mean over
    the window (``numpy.std``, population), i.e. the RMS of the dynamic part with the
    static load removed.  The measure to compare between runs (speeds, roads...).
``hub_<c>_<k>_rms_N``, ``hub_<c>_<k>_peak_N``
    RMS and largest magnitude of the *total* hub force on the body, static load
    included (``rms**2 = mean**2 + std**2``: for a vertical force it is dominated by the
    static wheel load and can fall with speed while the fluctuation rises).
``aw_<p>_<k>_m_per_s2``
    ISO 2631-1 frequency-weighted RMS acceleration (Wd for x and y, Wk for z).
``crest_<p>_<k>``
    Crest factor: peak of the weighted acceleration / its RMS (ISO 2631-1 6.2.1).
``vdv_<p>_<k>_m_per_s1.75``
    Vibration dose value ``(int a_w^4 dt)^(1/4)`` (ISO 2631-1 6.3.2).
``av_<p>_m_per_s2``
    Vibration total value ``sqrt(sum (k_i aw_i)^2)`` with the health factors
    kx = ky = 1.4, kz = 1 (ISO 2631-1 7.2.3).
``seat_<s>_SEAT_pct``
    A seat's SEAT value (:mod:`flexpipe.vehicle.seats`): its ``aw_<s>_z`` over its floor
    point's, in % (added by :func:`flexpipe.sweeps.tasks.run_task`, which knows the seats).
``travel_<c>_max_m``, ``travel_<c>_min_m``, ``travel_absmax_m``
    Largest jounce (compression +) and rebound (-) per corner, largest magnitude overall.
``lateral_error_absmax_m``
    Largest distance of the rear-axle centre from the path.

Samples before ``settle`` seconds are left out (the car starts at static equilibrium, so
the default is 0).

Only runs of an open-loop steering input (a ``driver`` file with ``[steering] type =
"open_loop"``; ``Result.info["steering"]``) have :func:`manoeuvre_metrics`: a ``step``
its ISO 7401 figures (:data:`STEP_METRICS`, from
:func:`flexpipe.vehicle.handling.step_response`), a ``sine_with_dwell`` its UN R140
figures (:data:`SINE_WITH_DWELL_METRICS`, from
:func:`~flexpipe.vehicle.handling.sine_with_dwell_response`, ``stable`` and
``responsive`` as 1 or 0); the lateral acceleration and displacement at the car's centre
of mass (:func:`centre_of_mass`).  They use the whole run (``settle`` does not apply:
the steady values are the means over the last second).
"""

from __future__ import annotations

import math

import numpy as np

from flexpipe.sweeps.iso2631 import AXIS_WEIGHTING, HEALTH_K, ride_metrics

CORNERS = ("fl", "fr", "rl", "rr")
#: fewest samples after ``settle`` the metrics are computed from (NaN below)
MIN_SAMPLES = 4
#: numeric columns of a run's record besides the metrics (a plot may show them too)
RECORD_NUMBERS = ("cpu_s", "wall_s", "simulated_time_s", "task_s", "n_elastic_modes")
#: metric column -> key of :func:`flexpipe.vehicle.handling.step_response`
STEP_METRICS = {
    "steering_wheel_steady_deg": "steering_wheel_deg", "step_t50_s": "t50_s",
    "speed_steady_kmh": "speed_kmh",
    **{k: k for k in ("yaw_rate_steady_deg_per_s", "yaw_rate_response_time_s",
                      "yaw_rate_peak_response_time_s", "yaw_rate_overshoot_pct",
                      "ay_steady_mps2", "ay_response_time_s", "ay_peak_response_time_s",
                      "ay_overshoot_pct", "yaw_rate_gain_per_s", "ay_gain_mps2_per_100deg",
                      "ay_at_x_m", "ay_at_z_m")}}
#: metric column -> key of :func:`flexpipe.vehicle.handling.sine_with_dwell_response`
SINE_WITH_DWELL_METRICS = {k: k for k in (
    "bos_s", "cos_s", "yaw_rate_peak_deg_per_s", "yaw_rate_peak_time_s",
    "yaw_rate_ratio_cos_plus_1s", "yaw_rate_ratio_cos_plus_1_75s",
    "lateral_displacement_bos_plus_1_07s_m", "stable", "responsive")}
#: open-loop input (``OpenLoopSteer.kind``) -> its metrics
MANOEUVRE_METRICS = {"step": STEP_METRICS, "sine_with_dwell": SINE_WITH_DWELL_METRICS}
_DESCRIBED = {"step": "open-loop steering: step",
              "sine_with_dwell": "open-loop steering: sine with dwell"}


def points_of(channels) -> list[str]:
    """Named body points that have ``acc_<p>_x|y|z`` channels, in channel order."""
    out = []
    for name in channels:
        if name.startswith("acc_") and name.endswith("_z"):
            p = name[4:-2]
            if f"acc_{p}_x" in channels and f"acc_{p}_y" in channels:
                out.append(p)
    return out


def run_metrics(t, channels, *, settle: float = 0.0) -> dict:
    """Metrics of one run (see the module docstring); NaN where a run has no samples.

    Parameters
    ----------
    t : ndarray (n,)
        Output times, s (uniform).
    channels : mapping of str to ndarray (n,)
    settle : float
        Leave out samples before this time, s.
    """
    t = np.asarray(t, dtype=float)
    sel = t >= settle - 1e-12
    n = int(sel.sum())
    ok = n >= MIN_SAMPLES
    dt = float(np.median(np.diff(t))) if t.size >= 2 else float("nan")

    def sig(name):
        return np.asarray(channels[name], dtype=float)[sel]

    nan = float("nan")
    out = {}
    for c in CORNERS:
        for k in "xyz":
            name = f"hub_{c}_{k}"
            if name in channels:
                x = sig(name)
                out[f"{name}_std_N"] = float(np.std(x)) if ok else nan
                out[f"{name}_rms_N"] = float(np.sqrt(np.mean(x**2))) if ok else nan
                out[f"{name}_peak_N"] = float(np.abs(x).max()) if ok else nan
    for p in points_of(channels):
        total = 0.0
        for k in "xyz":
            if ok:
                m = ride_metrics(sig(f"acc_{p}_{k}"), dt, AXIS_WEIGHTING[k])
            else:
                m = {"aw": nan, "crest": nan, "vdv": nan}
            out[f"aw_{p}_{k}_m_per_s2"] = m["aw"]
            out[f"crest_{p}_{k}"] = m["crest"]
            out[f"vdv_{p}_{k}_m_per_s1.75"] = m["vdv"]
            total += (HEALTH_K[k] * m["aw"]) ** 2
        out[f"av_{p}_m_per_s2"] = math.sqrt(total)
    biggest = nan
    for c in CORNERS:
        name = f"travel_{c}"
        if name in channels:
            x = sig(name)
            hi, lo = (float(x.max()), float(x.min())) if ok else (nan, nan)
            out[f"{name}_max_m"], out[f"{name}_min_m"] = hi, lo
            if ok:
                biggest = max(abs(hi), abs(lo), 0.0 if math.isnan(biggest) else biggest)
    out["travel_absmax_m"] = biggest
    if "lateral_error" in channels:
        out["lateral_error_absmax_m"] = float(np.abs(sig("lateral_error")).max()) if ok else nan
    return out


def manoeuvre_kind(result) -> str | None:
    """``"step"`` or ``"sine_with_dwell"`` for a run of that open-loop steering input
    (``result.info["steering"]``), else None."""
    steering = str(getattr(result, "info", {}).get("steering", ""))
    for kind, text in _DESCRIBED.items():
        if steering.startswith(text):
            return kind
    return None


def centre_of_mass(result, car, rigid) -> tuple[float, float]:
    """Body-axis ``(x, z)`` (m) of the car's centre of mass, as
    :func:`flexpipe.vehicle.handling.centre_of_mass` gives it, with the body's mass
    properties ``rigid`` of the run (so nothing is assembled again)."""
    loads = np.asarray(result.info["static_wheel_load_N"], dtype=float)
    x = np.array([c.wheel_center[0] for c in car.corners])
    return float(loads @ x / loads.sum()), float(rigid.center_of_mass[2])


def manoeuvre_metrics(result, *, cg=(0.0, 0.0)) -> tuple[dict, str]:
    """The open-loop manoeuvre's figures of a run (see the module docstring) and a note.

    Returns ``({}, "")`` for any other run; for a step steer or a sine with dwell the
    metrics of :data:`MANOEUVRE_METRICS` and ``""``, or, when the figures cannot be taken
    (a step run that has not settled, a sine with dwell that ends too early), every one
    of them NaN and the reason.
    """
    from flexpipe.errors import InputError
    from flexpipe.vehicle import handling

    kind = manoeuvre_kind(result)
    if kind is None or getattr(result, "status", 0) != 0:
        return {}, ""
    names = MANOEUVRE_METRICS[kind]
    figures = handling.step_response if kind == "step" else handling.sine_with_dwell_response
    try:
        got = figures(result, cg=cg)
    except InputError as exc:
        what = "step-steer" if kind == "step" else "sine-with-dwell"
        return {c: float("nan") for c in names}, f"no {what} metrics: {exc.message}"
    return {c: int(got[k]) if isinstance(got[k], bool) else float(got[k])
            for c, k in names.items()}, ""


def metric_names(points, manoeuvres=()) -> list[str]:
    """Every metric column :func:`run_metrics` writes for a car with the named body
    ``points`` (its ``[body.points]``), in the order it writes them, then the
    :data:`MANOEUVRE_METRICS` of the open-loop inputs ``manoeuvres`` (``"step"``,
    ``"sine_with_dwell"``), then :data:`RECORD_NUMBERS`."""
    out = [f"hub_{c}_{k}_{s}" for c in CORNERS for k in "xyz" for s in ("std_N", "rms_N", "peak_N")]
    for p in points:
        for k in "xyz":
            out += [f"aw_{p}_{k}_m_per_s2", f"crest_{p}_{k}", f"vdv_{p}_{k}_m_per_s1.75"]
        out.append(f"av_{p}_m_per_s2")
    out += [f"travel_{c}_{s}" for c in CORNERS for s in ("max_m", "min_m")]
    out += ["travel_absmax_m", "lateral_error_absmax_m"]
    for kind in MANOEUVRE_METRICS:
        if kind in manoeuvres:
            out += [c for c in MANOEUVRE_METRICS[kind] if c not in out]
    return out + list(RECORD_NUMBERS)


#: first columns of the metrics table after the swept parameters (docs/sweeps.md)
LEADING_COLUMNS = ("key", "status", "message", "cpu_s", "wall_s")


def table_columns(columns, params) -> list[str]:
    """``columns`` of the metrics table in the documented order: the swept ``params``,
    :data:`LEADING_COLUMNS`, the metrics in :func:`metric_names` order, then the other
    record fields (``index``, ``task_s``...) and any column not known here."""
    columns = list(columns)
    points = [c[3:-len("_m_per_s2")] for c in columns
              if c.startswith("av_") and c.endswith("_m_per_s2")]
    first = [c for c in (*params, *LEADING_COLUMNS) if c in columns]
    known = [c for c in metric_names(points, tuple(MANOEUVRE_METRICS))
             if c in columns and c not in first]
    seen = set(first) | set(known)
    return first + known + [c for c in columns if c not in seen]


__all__ = ["LEADING_COLUMNS", "MANOEUVRE_METRICS", "MIN_SAMPLES", "RECORD_NUMBERS",
           "SINE_WITH_DWELL_METRICS", "STEP_METRICS", "centre_of_mass", "manoeuvre_kind",
           "manoeuvre_metrics", "metric_names", "points_of", "run_metrics", "table_columns"]
