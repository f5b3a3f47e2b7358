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
``travel_<c>_max_m``, ``travel_<c>_min_m``, ``travel_absmax_m``
    Largest jounce (compression +) and rebound (-) per corner, largest magnitude overall.
``lateral_error_absmax_m``
    Largest distance of the rear-axle centre from the path.

Samples before ``settle`` seconds are left out (the car starts at static equilibrium, so
the default is 0).
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


def metric_names(points) -> list[str]:
    """Every metric column :func:`run_metrics` writes for a car with the named body
    ``points`` (its ``[body.points]``), in the order it writes them, then
    :data:`RECORD_NUMBERS`."""
    out = [f"hub_{c}_{k}_{s}" for c in CORNERS for k in "xyz" for s in ("std_N", "rms_N", "peak_N")]
    for p in points:
        for k in "xyz":
            out += [f"aw_{p}_{k}_m_per_s2", f"crest_{p}_{k}", f"vdv_{p}_{k}_m_per_s1.75"]
        out.append(f"av_{p}_m_per_s2")
    out += [f"travel_{c}_{s}" for c in CORNERS for s in ("max_m", "min_m")]
    out += ["travel_absmax_m", "lateral_error_absmax_m", *RECORD_NUMBERS]
    return out


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
    known = [c for c in metric_names(points) if c in columns and c not in first]
    seen = set(first) | set(known)
    return first + known + [c for c in columns if c not in seen]


__all__ = ["LEADING_COLUMNS", "MIN_SAMPLES", "RECORD_NUMBERS", "metric_names", "points_of",
           "run_metrics", "table_columns"]
