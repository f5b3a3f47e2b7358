"""Plots of chosen sweep metrics against the swept parameters (matplotlib PNGs).

Each plot is titled with the sweep's base settings (car, road, body, simulated time and
the settle time the metrics leave out; a swept setting says so), and its axes are labelled
with the quantity and its unit (:func:`axis_label`) instead of the raw column names.
"""

from __future__ import annotations

import re
from pathlib import Path

from flexpipe._io import atomic_path


def default_metrics(table) -> list[str]:
    """Vertical ISO 2631-1 weighted RMS at the first body point and the fluctuation of the
    front-left vertical hub force (its standard deviation, ``hub_fl_z_std_N``), when
    present.  (``hub_fl_z_rms_N`` includes the static wheel load, so it hides how the
    dynamic force grows with speed or road roughness.)"""
    cols = list(table.columns)
    out = [c for c in cols if c.startswith("aw_") and c.endswith("_z_m_per_s2")][:1]
    out += [c for c in ("hub_fl_z_std_N",) if c in cols]
    return out


#: unit suffixes of column names (longest first) and how the axis label writes them
_UNITS = (("_m_per_s1.75", "m/s^1.75"), ("_m_per_s2", "m/s²"), ("_N_per_m", "N/m"),
          ("_Ns_per_m", "N s/m"), ("_N", "N"), ("_kmh", "km/h"), ("_kg", "kg"),
          ("_mm", "mm"), ("_m", "m"), ("_s", "s"), ("_deg", "deg"), ("_rad", "rad"),
          ("_Hz", "Hz"))
_NAMED = {"speed_kmh": "speed [km/h]", "t_end_s": "simulated time t_end [s]",
          "h_s": "time step h [s]", "output_step_s": "output step [s]",
          "settle_s": "settle time [s]", "cpu_s": "integration CPU time [s]",
          "wall_s": "wall time [s]", "task_s": "task time [s]",
          "simulated_time_s": "simulated time [s]",
          "n_elastic_modes": "elastic modes of the body [-]",
          "travel_absmax_m": "largest |suspension travel|, any corner [m]",
          "lateral_error_absmax_m": "largest |lateral path error| (rear-axle centre) [m]"}
_HUB = {"std_N": "fluctuation (std about the mean)", "rms_N": "RMS incl. static load",
        "peak_N": "peak |F|"}


def _travel(m) -> str:
    what = "max (jounce +)" if m[2] == "max" else "min (rebound -)"
    return f"suspension travel {m[1].upper()}, {what} [m]"


#: (column pattern, axis label of its match)
_PATTERNS = (
    (r"hub_(fl|fr|rl|rr)_([xyz])_(std_N|rms_N|peak_N)",
     lambda m: f"hub force {m[1].upper()} {m[2]}, {_HUB[m[3]]} [N]"),
    (r"aw_(.+)_([xyz])_m_per_s2", lambda m: f"weighted RMS acceleration a_w, {m[1]} {m[2]} "
                                            f"({'Wk' if m[2] == 'z' else 'Wd'}) [m/s²]"),
    (r"vdv_(.+)_([xyz])_m_per_s1\.75", lambda m: f"vibration dose value, {m[1]} {m[2]} "
                                                  "[m/s^1.75]"),
    (r"crest_(.+)_([xyz])", lambda m: f"crest factor, {m[1]} {m[2]} [-]"),
    (r"av_(.+)_m_per_s2", lambda m: f"vibration total value a_v, {m[1]} [m/s²]"),
    (r"travel_(fl|fr|rl|rr)_(max|min)_m", _travel),
)


def axis_label(column: str) -> str:
    """The quantity and unit a metrics-table column holds, for an axis label:
    ``hub_fl_z_std_N`` -> ``hub force FL z, fluctuation (std about the mean) [N]``,
    ``speed_kmh`` -> ``speed [km/h]``; a column not recognised keeps its name, with the
    unit of its suffix in brackets when it has one."""
    if column in _NAMED:
        return _NAMED[column]
    for pattern, label in _PATTERNS:
        m = re.fullmatch(pattern, column)
        if m:
            return label(m)
    for suffix, unit in _UNITS:
        if column.endswith(suffix) and len(column) > len(suffix):
            return f"{column[:-len(suffix)]} [{unit}]"
    return column


def _road_text(road) -> str:
    if road is None:
        return "flat road"
    if isinstance(road, dict):
        if str(road.get("type", "")).lower() == "iso8608" and "road_class" in road:
            return f"ISO 8608 class {road['road_class']} road"
        return f"{road.get('type', 'inline')} road"
    return f"road {Path(road).name}"


def plot_title(spec, params) -> str:
    """Car, road, body, simulated time and settle time of the sweep's runs; a swept
    setting is named as swept (its values are on the x axis or in the legend)."""
    base = getattr(spec, "base", None) or {}
    swept = set(params)
    car = Path(spec.car).stem if getattr(spec, "car", None) else "car"
    if "car" in swept:
        car = "car swept"
    elif any(p.startswith("car.") for p in swept):
        car += " (overrides swept)"
    road = ("road swept" if "road" in swept else
            _road_text(getattr(spec, "road", None))
            + (" (keys swept)" if any(p.startswith("road.") for p in swept) else ""))
    parts = [car, road]
    parts.append("body swept" if "body" in swept else f"{base.get('body', 'rigid')} body")
    if "t_end_s" not in swept and base.get("t_end_s") is not None:
        parts.append(f"t_end {base['t_end_s']:g} s")
    if "speed_kmh" not in swept and base.get("speed_kmh") is not None:
        parts.append(f"{base['speed_kmh']:g} km/h")
    settle = base.get("settle_s") or 0.0
    parts.append(f"metrics from t = {settle:g} s" if settle else "metrics from t = 0")
    return ", ".join(parts)


def plot_metrics(table, spec, folder, *, metrics=None) -> list[Path]:
    """One PNG per (metric, numeric swept parameter): the metric against the parameter,
    one line per combination of the other swept parameters; failed runs are left out.
    Titled with :func:`plot_title`, axes labelled with :func:`axis_label`.

    Returns the files written.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import pandas as pd

    if table.empty or "status" not in table:
        return []
    metrics = list(metrics or spec.plots or default_metrics(table))
    params = [c for c in (list(spec.parameters) or sorted({k for r in spec.runs_list
                                                            for k in r})) if c in table]
    ok = table[table["status"] >= 0]
    title = plot_title(spec, params)
    written = []
    for metric in metrics:
        if metric not in ok:
            continue
        for x in params:
            if not pd.api.types.is_numeric_dtype(ok[x]) or ok[x].nunique() < 2:
                continue
            others = [p for p in params if p != x and ok[p].nunique() > 1]
            fig, ax = plt.subplots(figsize=(6.4, 4.4))
            groups = ok.groupby(others, dropna=False) if others else [((), ok)]
            for name, g in groups:
                g = g.sort_values(x)
                name = name if isinstance(name, tuple) else (name,)
                label = ", ".join(f"{p}={v}" for p, v in zip(others, name, strict=True))
                ax.plot(g[x], g[metric], "o-", label=label or None)
            ax.set_xlabel(axis_label(x))
            ax.set_ylabel(axis_label(metric), fontsize=9)
            ax.set_title(title, fontsize=8.5, wrap=True)
            ax.grid(True, alpha=0.3)
            if others:
                ax.legend(fontsize=7)
            fig.tight_layout()
            path = Path(folder) / f"{metric}__vs__{x}.png"
            with atomic_path(path) as tmp:
                fig.savefig(tmp, dpi=110)
            plt.close(fig)
            written.append(path)
    return written


__all__ = ["axis_label", "default_metrics", "plot_metrics", "plot_title"]
