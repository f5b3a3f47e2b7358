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
    """Hub force of one corner for several runs on one plot (paper Fig. 7 / Fig. 9).

    With a ``rigid`` run and others, a lower panel shows each run minus the rigid one,
    so that the effect of body flexibility is visible even where the curves overlap.
    """
    name = f"hub_{corner}_{component}"
    others = [k for k in results if k != "rigid"]
    with_diff = "rigid" in results and bool(others)
    plt, fig = _figure((9, 6) if with_diff else (9, 4.5))
    if with_diff:
        ax, ax_d = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2.2, 1]})
    else:
        ax = fig.add_subplot(111)
    for label, r in results.items():
        ax.plot(r.t, r[name] / 1e3, label=f"{label} body", **STYLE.get(label, {}))
    label_y = (f"{'vertical' if component == 'z' else component} hub force "
               f"{corner.upper()} [kN]")
    ax.set_ylabel(label_y)
    ax.set_title(title or f"Force on the {corner.upper()} wheel hub", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend()
    last = ax
    if with_diff:
        rigid = results["rigid"]
        for label in others:
            r = results[label]
            # rigid minus the other, as summary.json's hub_force_difference states it
            diff = np.interp(r.t, rigid.t, rigid[name]) - r[name]
            ax_d.plot(r.t, diff / 1e3, label=f"rigid - {label}",
                      **{**STYLE.get(label, {}), "ls": "-"})
        ax_d.axhline(0.0, color="k", lw=0.6)
        ax_d.set_ylabel("difference [kN]")
        ax_d.grid(True, alpha=0.3)
        ax_d.legend(loc="upper right")
        last = ax_d
    last.set_xlabel("time [s]")
    fig.tight_layout()
    return _save(plt, fig, path)


def spectra(results: dict, path, *, t_from: float, corner: str = "fl",
            point: str | None = None, title: str = "") -> Path:
    """Where the runs differ in frequency: power spectral densities (Welch, 2 s Hann
    segments, half overlap, samples from ``t_from``) of a corner's vertical hub force
    with the PSD of each run's difference from the rigid one, of a body point's
    vertical acceleration (``point``: the first named point by default) and of the
    first seat's (:mod:`flexpipe.vehicle.seats`, if the car has one), each with its ISO
    2631-1 Wk weighting dotted."""
    from scipy.signal import welch

    from flexpipe.sweeps.iso2631 import response
    from flexpipe.sweeps.metrics import points_of

    first = next(iter(results.values()))
    seats = (getattr(first, "info", None) or {}).get("seats") or {}
    point = point or next((p for p in points_of(first.channels) if p not in seats), None)
    seat = next((s for s in seats if f"acc_{s}_z" in first.channels), None)
    panels = [p for p in (point, seat) if p]
    plt, fig = _figure((9, 4.5 + 3.0 * len(panels)))
    axes = fig.subplots(1 + len(panels), 1, sharex=True, squeeze=False)[:, 0]
    name = f"hub_{corner}_z"

    def psd(r, x):
        keep = r.t >= t_from - 1e-12
        dt = float(np.median(np.diff(r.t)))
        n = min(int(round(2.0 / dt)), int(keep.sum()))
        return welch(x[keep] - np.mean(x[keep]), fs=1.0 / dt, nperseg=n)

    rigid = results.get("rigid")
    for label, r in results.items():
        f, p = psd(r, r[name])
        axes[0].semilogy(f, p, label=f"{label} body", **STYLE.get(label, {}))
        if rigid is not None and label != "rigid":
            f, p = psd(r, np.interp(r.t, rigid.t, rigid[name]) - r[name])
            axes[0].semilogy(f, p, label=f"rigid - {label}", color="tab:orange", lw=1.0)
    axes[0].set_ylabel(f"vertical hub force {corner.upper()}\nPSD [N^2/Hz]")
    axes[0].set_title(title or "Spectra of the runs", fontsize=10)
    for ax, pt in zip(axes[1:], panels, strict=True):
        for label, r in results.items():
            f, p = psd(r, r[f"acc_{pt}_z"])
            style = STYLE.get(label, {})
            line, = ax.semilogy(f, p, label=f"{label} body", **style)
            ax.semilogy(f, np.abs(response(f, "Wk")) ** 2 * p, lw=0.8, ls=":",
                        color=line.get_color(), label=f"{label}, Wk weighted")
        where = f"{pt} (seat on {seats[pt]})" if pt in seats else pt
        ax.set_ylabel(f"vertical acceleration, {where}\nPSD [(m/s^2)^2/Hz]")
    for ax in axes:
        ax.set_xlim(0.0, min(60.0, ax.get_xlim()[1]))
        shown = [ln.get_ydata()[(ln.get_xdata() > 0.5) & (ln.get_xdata() <= 60.0)]
                 for ln in ax.get_lines()]
        top = max(float(np.max(y)) for y in shown)
        low = min(float(np.min(y[y > 0])) for y in shown if np.any(y > 0))
        ax.set_ylim(max(low / 3.0, top * 1e-8), top * 3.0)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    axes[-1].set_xlabel("frequency [Hz]")
    fig.tight_layout()
    return _save(plt, fig, path)


#: trajectory styles: the rigid trace wide and grey underneath, the others narrow and
#: dashed / dotted on top, so that each stays visible where they coincide
TRAJECTORY_STYLE = {"rigid": dict(color="0.55", lw=2.6, ls="-", zorder=2),
                    "flexible": dict(color="tab:red", lw=1.2, ls="--", zorder=4),
                    "full": dict(color="tab:blue", lw=1.2, ls=":", zorder=5)}


def run_title(results: dict, path_obj=None) -> str:
    """Car (and its file), speed, road and path of the runs, from their ``info``."""
    info = getattr(next(iter(results.values())), "info", None) or {}
    parts = []
    car = info.get("car")
    if car:
        file = info.get("car_file")
        parts.append(f"{car} ({Path(file).name})" if file else str(car))
    if info.get("speed") is not None:
        parts.append(f"{float(info['speed']) * 3.6:.0f} km/h")
    road = info.get("road")
    parts.append(f"road {Path(str(road)).name}" if road else "flat road")
    if path_obj is not None:
        name = getattr(path_obj, "name", "") or Path(getattr(path_obj, "source", "") or "").name
        if name:
            parts.append(f"path {name}")
    return ", ".join(parts)


def trajectory(results: dict, path_obj, path, *, title: str = "") -> Path:
    """Desired path and the followed rear-axle trajectories (paper Fig. 8).

    The rigid trace is wide and grey, the flexible one dashed red on top (full: dotted
    blue), so that both stay visible where they coincide; the default title names the
    car, speed, road and path (:func:`run_title`).
    """
    plt, fig = _figure((10, 4.3))
    ax = fig.add_subplot(111)
    r0 = next(iter(results.values()))
    x_lo, x_hi = float(np.nanmin(r0["x_rear"])), float(np.nanmax(r0["x_rear"]))
    sel = (path_obj.x >= x_lo - 5) & (path_obj.x <= x_hi + 5)
    ax.plot(path_obj.x[sel], path_obj.y[sel], color="k", lw=0.9, zorder=3,
            label="desired path")
    for label, r in results.items():
        st = TRAJECTORY_STYLE.get(label, dict(lw=1.2, ls="-.", zorder=6))
        ax.plot(r["x_rear"], r["y_rear"], label=f"followed ({label} body)", **st)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    head = "Desired / followed vehicle trajectory (rear-axle centre)"
    ax.set_title(title or f"{head}\n{run_title(results, path_obj)}", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return _save(plt, fig, path)
