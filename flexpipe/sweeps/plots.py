"""Plots of chosen sweep metrics against the swept parameters (matplotlib PNGs)."""

from __future__ import annotations

from pathlib import Path

from flexpipe._io import atomic_path


def default_metrics(table) -> list[str]:
    """Vertical ISO 2631-1 weighted RMS at the first body point and the front-left
    vertical hub force RMS, when present."""
    cols = list(table.columns)
    out = [c for c in cols if c.startswith("aw_") and c.endswith("_z_m_per_s2")][:1]
    out += [c for c in ("hub_fl_z_rms_N",) if c in cols]
    return out


def plot_metrics(table, spec, folder, *, metrics=None) -> list[Path]:
    """One PNG per (metric, numeric swept parameter): the metric against the parameter,
    one line per combination of the other swept parameters; failed runs are left out.

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
    written = []
    for metric in metrics:
        if metric not in ok:
            continue
        for x in params:
            if not pd.api.types.is_numeric_dtype(ok[x]) or ok[x].nunique() < 2:
                continue
            others = [p for p in params if p != x and ok[p].nunique() > 1]
            fig, ax = plt.subplots(figsize=(6.4, 4.2))
            groups = ok.groupby(others, dropna=False) if others else [((), ok)]
            for name, g in groups:
                g = g.sort_values(x)
                name = name if isinstance(name, tuple) else (name,)
                label = ", ".join(f"{p}={v}" for p, v in zip(others, name, strict=True))
                ax.plot(g[x], g[metric], "o-", label=label or None)
            ax.set_xlabel(x)
            ax.set_ylabel(metric)
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


__all__ = ["default_metrics", "plot_metrics"]
