"""Figures 2-5 of the half-car study (matplotlib, Agg backend)."""

from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from flexpipe._io import atomic_path  # noqa: E402
from flexpipe.halfcar.linear import Spectrum  # noqa: E402

#: line styles of the paper: thick/thin solid complete/reduced, broken truncated, dotted rigid
STYLES = {
    "complete": dict(color="k", lw=2.4),
    "reduced": dict(color="tab:red", lw=1.0),
    "truncated": dict(color="tab:blue", lw=1.2, ls="--"),
    "rigid": dict(color="tab:green", lw=1.4, ls=":"),
}


def _save(fig, path):
    with atomic_path(path) as tmp:
        fig.savefig(tmp, dpi=130, format="png")
    plt.close(fig)


def _quantities(s: Spectrum):
    return [s.acc_A, 1e3 * s.travel[1], s.tire_force[1]]


LABELS = ["max |acceleration| at A\n[m/s$^2$]", "rear suspension\ntravel [mm]",
          "rear dynamic\ntire force [N]"]


def figure2(spectra: dict[str, Spectrum], path, *, title: str) -> None:
    """Linear spectra of the four variants, plus their errors against the complete one."""
    fig, axes = plt.subplots(4, 1, figsize=(8, 11), sharex=True)
    ref = spectra["complete"]
    for name, s in spectra.items():
        for ax, y in zip(axes[:3], _quantities(s), strict=True):
            ax.semilogy(s.freq_Hz, y, label=name, **STYLES[name])
        if name != "complete":
            err = np.abs(s.acc_A / ref.acc_A - 1.0)
            axes[3].semilogy(s.freq_Hz, np.maximum(err, 1e-12), label=name, **STYLES[name])
    for ax, lab in zip(axes, LABELS + ["relative error of\nacceleration at A"], strict=True):
        ax.set_ylabel(lab)
        ax.grid(True, which="both", alpha=0.3)
    axes[0].legend(loc="upper right", fontsize=8)
    axes[3].legend(loc="lower right", fontsize=8)
    axes[3].set_xlabel("forcing frequency v / lambda [Hz]")
    axes[0].set_title(title, fontsize=10)
    fig.tight_layout()
    _save(fig, path)


def _stability_plot(ax, f, y, stable, **style):
    """Solid where stable, dashed where unstable, a marker where stability changes."""
    edge = np.flatnonzero(np.diff(stable.astype(int)) != 0)
    for mask, dashed in ((stable, False), (~stable, True)):
        if not mask.any():
            continue
        yy = np.where(mask, y, np.nan)
        yy[edge] = y[edge]  # join the stable and unstable pieces
        yy[edge + 1] = y[edge + 1]
        ax.semilogy(f, yy, **({**style, "ls": "--"} if dashed else style))
    change = np.flatnonzero(np.diff(stable.astype(int)) != 0)
    if change.size:
        ax.plot(f[change], y[change], "o", mfc="none", color=style.get("color", "k"), ms=7)


def figure3(curves: list[tuple[str, Spectrum, dict]], path, *, title: str,
            reference: Spectrum | None = None, reference_label: str = "linear") -> None:
    """Nonlinear spectra (harmonic balance); line solid where stable, dashed if not.

    Parameters
    ----------
    curves : list of (label, Spectrum, style)
        The harmonic-balance spectra.
    path : str or Path
        PNG written (atomically).
    title : str
    reference : Spectrum, optional
        A linear spectrum drawn in grey behind the curves.
    reference_label : str
        Its legend entry, e.g. ``"complete, linear zeta = 0.3"`` (the caller knows the
        damping ratio it was computed with).
    """
    fig, axes = plt.subplots(3, 1, figsize=(8, 9.8), sharex=True)
    if reference is not None:
        for ax, y in zip(axes, _quantities(reference), strict=True):
            ax.semilogy(reference.freq_Hz, y, color="0.7", lw=1.0, label=reference_label)
    for label, s, style in curves:
        for ax, y in zip(axes, _quantities(s), strict=True):
            _stability_plot(ax, s.freq_Hz, y, s.stable, **style)
        axes[0].plot([], [], label=label, **style)
    for ax, lab in zip(axes, LABELS, strict=True):
        ax.set_ylabel(lab)
        ax.grid(True, which="both", alpha=0.3)
    unstable = sum(int((~s.stable).sum()) for _, s, _ in curves)
    mu = max(float(np.nanmax(s.floquet_max)) for _, s, _ in curves)
    note = (f"all periodic solutions stable (max |Floquet multiplier| = {mu:.3f})"
            if unstable == 0 else f"{unstable} unstable points (dashed); o = stability change")
    # the legend sits above the top panel, off the curves (title as the figure's title)
    axes[0].legend(loc="lower center", bbox_to_anchor=(0.5, 1.02), ncol=2, fontsize=8,
                   title=note, title_fontsize=8)
    axes[2].set_xlabel("forcing frequency v / lambda [Hz]")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    _save(fig, path)


def figure_transient(runs, path, *, title: str, damper_strip: bool = False) -> None:
    """Acceleration at A for complete vs reduced; optional damper-state strip above."""
    if damper_strip:
        fig, (top, ax) = plt.subplots(2, 1, figsize=(8, 6), sharex=True,
                                      gridspec_kw={"height_ratios": [1, 3]})
        ref = runs[0][1]
        for j, (name, off) in enumerate((("front", 0.0), ("rear", 2.5))):
            st = ref.damper_state[j]
            top.step(ref.t, off + (st > 0), where="post", color="k", lw=1.0)
            top.text(ref.t[-1], off + 0.5, f" {name}", va="center", fontsize=8)
        top.set_yticks([0, 1, 2.5, 3.5], ["jounce", "rebound", "jounce", "rebound"],
                       fontsize=7)
        top.set_title(title, fontsize=10)
        top.set_ylabel("damper\n(complete)", fontsize=8)
    else:
        fig, ax = plt.subplots(figsize=(8, 4.5))
        ax.set_title(title, fontsize=10)
    for name, tr in runs:
        ax.plot(tr.t, tr.acc_A, label=name, **{k: v for k, v in STYLES[name].items()
                                               if k != "ls"})
    ax.set_xlabel("time [s]")
    ax.set_ylabel("absolute acceleration at A [m/s$^2$]")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    _save(fig, path)
