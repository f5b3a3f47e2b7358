"""PNG plots of car runs (matplotlib, Agg backend, written atomically)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from flexpipe._io import atomic_path

STYLE = {"rigid": dict(color="k", lw=1.2, ls="-"),
         "flexible": dict(color="tab:red", lw=1.0, ls="--"),
         "full": dict(color="tab:blue", lw=0.9, ls=":")}


def _figure(figsize=(9, 4.5)):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt, plt.figure(figsize=figsize)


def _save(plt, fig, path) -> Path:
    path = Path(path)
    with atomic_path(path, suffix=".png") as tmp:
        fig.savefig(tmp, dpi=120, format="png")
    plt.close(fig)
    return path


def hub_force(results: dict, path, *, corner: str = "fl", component: str = "z",
              title: str = "") -> Path:
    """Hub force of one corner for several runs on one plot (paper Fig. 7 / Fig. 9)."""
    plt, fig = _figure()
    ax = fig.add_subplot(111)
    name = f"hub_{corner}_{component}"
    for label, r in results.items():
        ax.plot(r.t, r[name] / 1e3, label=f"{label} body", **STYLE.get(label, {}))
    ax.set_xlabel("time [s]")
    ax.set_ylabel(f"{'vertical' if component == 'z' else component} hub force "
                  f"{corner.upper()} [kN]")
    ax.set_title(title or f"Force on the {corner.upper()} wheel hub", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return _save(plt, fig, path)


def trajectory(results: dict, path_obj, path, *, title: str = "") -> Path:
    """Desired path and the followed rear-axle trajectories (paper Fig. 8)."""
    plt, fig = _figure((10, 4))
    ax = fig.add_subplot(111)
    r0 = next(iter(results.values()))
    x_lo, x_hi = float(np.nanmin(r0["x_rear"])), float(np.nanmax(r0["x_rear"]))
    sel = (path_obj.x >= x_lo - 5) & (path_obj.x <= x_hi + 5)
    ax.plot(path_obj.x[sel], path_obj.y[sel], color="k", lw=1.5, label="desired path")
    for label, r in results.items():
        st = STYLE.get(label, {})
        ax.plot(r["x_rear"], r["y_rear"], color=st.get("color"), ls="--", lw=1.0,
                label=f"followed ({label} body)")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title or "Desired / followed vehicle trajectory (rear-axle centre)")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    return _save(plt, fig, path)
