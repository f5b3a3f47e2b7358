"""Reproduce the half-car study of the paper: Table 1, Figs 2-5 and an error summary.

``python -m flexpipe.halfcar.paper --out out/paper`` writes ``table1.md``, ``fig2.png``
... ``fig5.png`` and ``summary.json`` (reduced/truncated/rigid errors against the
complete model, harmonic balance against direct integration, CPU times; its keys are
described in ``flexpipe/halfcar/README.md``).

The parameters and ``--out`` are checked before anything is created.  The files are
written into a staging folder next to ``--out`` that replaces it only when every stage
has finished, so a run that fails or is interrupted leaves the previous output as it
was.  Exit codes, as for the ``flexpipe`` command: 0 done, 2 bad input (one line
``error: FILE, line N, key 'K': message``), 1 a solver failure (the frequency or time
where it failed and a hint), 130 / 143 interrupted (Ctrl-C / SIGTERM).
"""

from __future__ import annotations

import argparse
import json
import shutil
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from flexpipe._io import (
    absolute,
    check_run_folder,
    commit_directory,
    staging_folder,
    write_text_atomic,
)
from flexpipe.errors import FlexpipeError, SolverError
from flexpipe.halfcar.elements import Nonlinearity
from flexpipe.halfcar.floquet import eval_series
from flexpipe.halfcar.hb import HarmonicBalance, sweep
from flexpipe.halfcar.linear import linear_spectrum
from flexpipe.halfcar.model import VARIANTS, build_model, natural_frequencies
from flexpipe.halfcar.paper_transient import (  # noqa: F401  (part of this module's API)
    TRANSIENT_LAWS,
    LiftOffWarning,
    transient_case,
    transient_runs,
    transient_study,
)
from flexpipe.halfcar.params import HalfCarParams, load_params
from flexpipe.halfcar.plots import STYLES, figure2, figure3
from flexpipe.halfcar.transient import Road, simulate

PROG = "python -m flexpipe.halfcar.paper"
DUAL = Nonlinearity(damper="dual_rate")
DUFFING = Nonlinearity(damper="dual_rate", tire="duffing", contact=True)
#: preferred speeds of the direct-integration check (used when inside the sweep range)
CHECK_FREQ_HZ = (3.0, 10.4, 20.0)
#: what to try when the harmonic balance does not converge
HB_HINT = ("hint: the periodic response is strongly nonlinear there (e.g. a wheel leaving "
           "the road with Duffing tires, or a fold of the response curve, which the "
           "continuation does not follow); try a smaller [road] amplitude_m; more [sweep] "
           "harmonics (with time_samples >= 4 x harmonics) or n_points help only when the "
           "resolution is the cause")


def sweep_grid(p: HalfCarParams, *, refine: bool = True) -> np.ndarray:
    """Sweep frequencies: uniform grid plus the refinement band of the parameter file."""
    f = np.linspace(p.sweep_f_min_Hz, p.sweep_f_max_Hz, p.sweep_n_points)
    if refine and p.refine_points:
        f = np.union1d(f, np.linspace(*p.refine_band_Hz, p.refine_points))
    return f


def _max_rel(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a) / np.asarray(b) - 1.0)))


def rms_rel(a, b, freq_Hz) -> float:
    """Relative RMS difference of ``a`` against ``b`` over a frequency band.

    Parameters
    ----------
    a, b : array_like, shape (nf,) or (k, nf)
        Spectra on the grid ``freq_Hz``; rows (e.g. front and rear) are compared apart.
    freq_Hz : array_like, shape (nf,)
        Ascending, not necessarily uniform (trapezoidal weights).

    Returns
    -------
    float
        ``sqrt(int (a - b)^2 df / int b^2 df)`` as a fraction; the largest over the rows.
    """
    a, b = np.atleast_2d(np.asarray(a, float)), np.atleast_2d(np.asarray(b, float))
    f = np.asarray(freq_Hz, float)
    num = np.trapezoid((a - b) ** 2, f, axis=-1)
    den = np.trapezoid(b**2, f, axis=-1)
    return float(np.sqrt(num / den).max())


def _errors(s, ref) -> dict:
    return {"acc_A": _max_rel(s.acc_A, ref.acc_A), "travel": _max_rel(s.travel, ref.travel),
            "tire_force": _max_rel(s.tire_force, ref.tire_force)}


def _rms_errors(s, ref) -> dict:
    f = ref.freq_Hz
    return {"acc_A": rms_rel(s.acc_A, ref.acc_A, f), "travel": rms_rel(s.travel, ref.travel, f),
            "tire_force": rms_rel(s.tire_force, ref.tire_force, f)}


def _cell(values, i: int, fmt: str) -> str:
    return format(values[i], fmt) if i < len(values) else ""


def _err_cell(computed, published, i: int) -> str:
    if i < len(computed) and i < len(published):
        return f"{100 * (computed[i] / published[i] - 1):+.2f}"
    return ""


def _reduced_vs_paper_text(errors: dict) -> str:
    """``, reduced (modes 7-8) 3.00 % (mode 8: -3.00 %)``: the largest relative error of
    the reduced model's upper modes (those its residual-flexibility modes carry) against
    the paper's reduced column, signed per mode; empty when there are none."""
    if not errors:
        return ""
    modes = sorted(errors, key=int)
    worst = max(modes, key=lambda m: abs(errors[m]))
    span = modes[0] if len(modes) == 1 else f"{modes[0]}-{modes[-1]}"
    per_mode = ", ".join(f"mode {m}: {100 * errors[m]:+.2f} %" for m in modes)
    return (f", reduced (modes {span}, vs the paper's reduced column) "
            f"{100 * abs(errors[worst]):.2f} % ({per_mode})")


def table1(p: HalfCarParams) -> tuple[str, dict]:
    """Table 1 for all four variants (markdown) and the numbers.

    Rows run over the modes that the published columns or the reduced and truncated
    models have (8 for the paper's set); a cell is blank where a model has fewer modes
    or no value was published.
    """
    f = {v: natural_frequencies(v, p) for v in VARIANTS}
    pc, pr, pg = (np.asarray(x) for x in (p.table1_complete_Hz, p.table1_reduced_Hz,
                                          p.table1_rigid_Hz))
    fc, fr, ft, fg = (f[v] for v in ("complete", "reduced", "truncated", "rigid"))
    n_rows = min(fc.size, max(pc.size, pr.size, pg.size, fr.size, ft.size, fg.size))
    rows = ["| mode | complete (paper) | complete | err % | reduced (paper) | reduced | "
            "truncated | rigid (paper) | rigid | err % |", "|" + "---|" * 10]
    for i in range(n_rows):
        cells = [str(i + 1), _cell(pc, i, ".2f"), _cell(fc, i, ".3f"), _err_cell(fc, pc, i),
                 _cell(pr, i, ".2f"), _cell(fr, i, ".3f"), _cell(ft, i, ".3f"),
                 _cell(pg, i, ".2f"), _cell(fg, i, ".3f"), _err_cell(fg, pg, i)]
        rows.append("| " + " | ".join(cells) + " |")
    # the reduced model's modes carried by kept modes (2 rigid-body, the free-interface
    # ones, 2 wheel hops); the 2 residual-flexibility modes add its highest ones
    k = 4 + p.free_interface_modes
    stats = {
        "computed_Hz": {v: f[v][:n_rows].tolist() for v in VARIANTS},
        "complete_vs_paper_max_rel_err_fraction": _max_rel(fc[:pc.size], pc),
        "rigid_vs_paper_max_rel_err_fraction": _max_rel(fg[:pg.size], pg),
        "reduced_vs_complete_lowest_modes": k,
        "reduced_vs_complete_max_rel_err_fraction": _max_rel(fr[:k], fc[:k]),
        "reduced_upper_modes_vs_paper_rel_err_fraction": {
            str(i + 1): float(fr[i] / pr[i] - 1) for i in range(k, min(fr.size, pr.size))},
    }
    md = "\n".join([
        "# Table 1: natural frequencies of the half car with beam body (Hz)", "",
        f"Parameter set: `{p.source.name}`; paper values from Verros et al., Table 1. "
        f"Complete: {p.body_dof} beam DOF + 2 wheels; reduced: 2 rigid + "
        f"{p.free_interface_modes} free-interface + 2 residual-flexibility body modes + 2 "
        f"wheels; truncated: {p.truncated_modes} lowest body modes + 2 wheels (no residual "
        "flexibility); rigid: heave + pitch + 2 wheels.", "", *rows, "",
        "Max relative error vs paper: complete "
        f"{100 * stats['complete_vs_paper_max_rel_err_fraction']:.2f} %, rigid "
        f"{100 * stats['rigid_vs_paper_max_rel_err_fraction']:.2f} %"
        + _reduced_vs_paper_text(stats["reduced_upper_modes_vs_paper_rel_err_fraction"])
        + f"; reduced modes 1-{k} vs "
        f"complete {100 * stats['reduced_vs_complete_max_rel_err_fraction']:.4f} %.", ""])
    return md, stats


def _hb_failure(exc: SolverError, what: str) -> SolverError:
    """The harmonic balance's error with the study it failed in and the hint."""
    return SolverError(f"{what}: {' '.join(str(exc).split())}; {HB_HINT}")


def linear_study(p, out: Path) -> dict:
    """Fig 2 (closed form) and the harmonic-balance check of the linear laws."""
    f = np.linspace(p.sweep_f_min_Hz, p.sweep_f_max_Hz, 1000)
    spectra = {v: linear_spectrum(build_model(v, p), f, label=v) for v in VARIANTS}
    figure2(spectra, out / "fig2.png", title=(
        f"Fig. 2 - linear half car, zeta = {p.zeta}\nharmonic road s0 = "
        f"{1e3 * p.road_amplitude_m:g} mm, lambda = {p.road_wavelength_m:.3f} m, rear input "
        f"delayed by wheelbase / v"))
    ref = spectra["complete"]
    res = {"max_rel_err_vs_complete_fraction": {v: _errors(spectra[v], ref)
                                                for v in VARIANTS[1:]}}
    # the harmonic-balance machinery on the linear laws, with only part of them in the
    # linear reference so that Newton/AFT do the work, against the closed form
    m = build_model("reduced", p)
    hb = HarmonicBalance(m, Nonlinearity(), c_ref=0.4 * m.c_lin, k_ref=0.6 * m.k_t)
    fs = f[::50]
    closed = linear_spectrum(m, fs)
    try:
        acc = [abs(hb.solve(2 * np.pi * fi).acc_A[1]) for fi in fs]
    except SolverError as exc:
        raise _hb_failure(exc, "harmonic-balance check of the linear laws") from None
    res["hb_linear_vs_closed_form_max_rel_err_fraction"] = _max_rel(acc, closed.acc_A)
    return res


def nonlinear_study(p, out: Path, *, progress: bool) -> tuple[dict, dict]:
    """Fig 3: dual-rate dampers (and Duffing tires) by harmonic balance + Floquet."""
    f = sweep_grid(p)
    runs, cpu = {}, {}
    for key, variant, nl in (("dual_complete", "complete", DUAL),
                             ("dual_reduced", "reduced", DUAL),
                             ("duffing_complete", "complete", DUFFING),
                             ("duffing_reduced", "reduced", DUFFING)):
        t0 = time.process_time()
        try:
            runs[key] = sweep(build_model(variant, p), nl, f, progress=progress,
                              label=f"{variant}, {nl.label}")
        except SolverError as exc:
            raise _hb_failure(exc, f"Fig. 3 sweep of the {variant} model with "
                                   f"{nl.label}") from None
        cpu[key] = time.process_time() - t0
    lin = linear_spectrum(build_model("complete", p), f)
    # every curve is drawn solid where stable (the line style is the stability, as the
    # title says): the curves differ by colour and width only, widest first, so that the
    # narrower ones stay visible on top where they coincide
    solid = {k: {**STYLES[k], "ls": "-"} for k in ("complete", "reduced")}
    figure3([("complete, dual-rate", runs["dual_complete"], solid["complete"]),
             ("complete, dual-rate + Duffing tires + contact", runs["duffing_complete"],
              dict(color="tab:purple", lw=1.6, ls="-")),
             ("reduced, dual-rate", runs["dual_reduced"], {**solid["reduced"], "lw": 0.9})],
            out / "fig3.png", reference=lin, reference_label=f"complete, linear zeta = {p.zeta}",
            title=(f"Fig. 3 - dual-rate dampers zeta- = {p.zeta_jounce} (jounce), zeta+ = "
                   f"{p.zeta_rebound} (rebound)\nharmonic balance, H = {p.harmonics} "
                   f"harmonics; solid: stable, dashed: unstable (Floquet)"))
    F0 = build_model("complete", p).static_tire_force
    load_ratio = {k: float((r.tire_force.max(axis=1) / F0).max()) for k, r in runs.items()}
    res = {
        "n_points": int(f.size),
        "dual_rate_reduced_vs_complete_max_rel_err_fraction": _errors(runs["dual_reduced"],
                                                                      runs["dual_complete"]),
        "duffing_reduced_vs_complete_max_rel_err_fraction": _errors(runs["duffing_reduced"],
                                                                    runs["duffing_complete"]),
        "duffing_effect_max_rel_change_fraction": _errors(runs["duffing_complete"],
                                                          runs["dual_complete"]),
        "duffing_effect_rms_rel_change_fraction": _rms_errors(runs["duffing_complete"],
                                                              runs["dual_complete"]),
        "dual_rate_vs_linear_max_rel_change_fraction": _errors(runs["dual_complete"], lin),
        "dual_rate_vs_linear_rms_rel_change_fraction": _rms_errors(runs["dual_complete"], lin),
        "all_stable": bool(all(r.stable.all() for r in runs.values())),
        "max_floquet_modulus": {k: float(r.floquet_max.max()) for k, r in runs.items()},
        "unstable_points": {k: int((~r.stable).sum()) for k, r in runs.items()},
        "max_newton_iterations": {k: int(r.iterations.max()) for k, r in runs.items()},
        "max_tire_load_ratio": max(load_ratio.values()),
    }
    bilateral = max(load_ratio["dual_complete"], load_ratio["dual_reduced"])
    if bilateral > 1.0:
        warnings.warn(
            f"Fig. 3: with bilateral tires (dual-rate curves) the dynamic tire force reaches "
            f"{bilateral:.2f} x the static load at s0 = {1e3 * p.road_amplitude_m:g} mm: the "
            "tire would pull the wheel onto the road; the Duffing + contact curve lets it "
            "lift off", LiftOffWarning, stacklevel=2)
    return res, cpu


def check_frequencies(p: HalfCarParams) -> tuple[float, ...]:
    """Three forcing frequencies of the direct-integration check, inside the sweep range.

    The preferred :data:`CHECK_FREQ_HZ` that lie in ``[frequency_min_Hz,
    frequency_max_Hz]`` are kept; the others are replaced by points at 15, 50 and 85 %
    of the range (rounded to 4 digits) that lie more than 10 % of it away from a kept
    one.

    Returns
    -------
    tuple of float
        Three distinct frequencies in Hz, ascending.
    """
    lo, hi = p.sweep_f_min_Hz, p.sweep_f_max_Hz
    kept = [f for f in CHECK_FREQ_HZ if lo <= f <= hi]
    for frac in (0.15, 0.5, 0.85):
        f = min(max(float(f"{lo + frac * (hi - lo):.4g}"), lo), hi)  # 4 digits, in range
        if len(kept) < 3 and all(abs(f - k) > 0.1 * (hi - lo) for k in kept):
            kept.append(f)
    return tuple(sorted(kept))


def integration_cases(p: HalfCarParams) -> list[tuple[str, Nonlinearity, float, str | None]]:
    """``(variant, laws, frequency Hz, solve_ivp method or None = exact)`` of the check:
    dual-rate dampers at the three :func:`check_frequencies` on both models, Duffing
    tires with contact on the reduced model at the middle one (DOP853)."""
    freqs = check_frequencies(p)
    cases = [(v, DUAL, f, None) for v in ("reduced", "complete") for f in freqs]
    cases.append(("reduced", DUFFING, freqs[1], "DOP853"))
    return cases


def integration_check(p) -> list[dict]:
    """Harmonic balance against long direct integration from rest at sample speeds."""
    out = []
    for variant, nl, f, method in integration_cases(p):
        m = build_model(variant, p)
        omega, T = 2 * np.pi * f, 1.0 / f
        try:
            sol = HarmonicBalance(m, nl).with_stability(HarmonicBalance(m, nl).solve(omega))
        except SolverError as exc:
            raise _hb_failure(exc, f"direct-integration check of the {variant} model with "
                                   f"{nl.label}") from None
        t_end = np.ceil(12.0 / T) * T
        te = t_end - T + np.linspace(0.0, T, 257)
        kw = {"method": method, "rtol": 1e-10, "atol": 1e-13} if method else {}
        t0 = time.process_time()
        tr = simulate(m, nl, Road(p.road_amplitude_m, p.road_wavelength_m),
                      f * p.road_wavelength_m, t_end, t_eval=te, **kw)
        y = eval_series(sol.Z[:2], omega, te)
        F = eval_series(sol.tire_force, omega, te)
        a = eval_series(sol.acc_A[None], omega, te)[0]
        out.append({
            "variant": variant, "laws": nl.label, "freq_Hz": f, "t_end_s": float(t_end),
            "integrator": method or "exact piecewise-linear",
            "cpu_s": time.process_time() - t0,
            "travel_rel_err_fraction": float(np.abs(tr.travel - y).max() / np.abs(y).max()),
            "tire_force_rel_err_fraction": float(np.abs(tr.tire_force - F).max()
                                                 / np.abs(F).max()),
            "max_acc_rel_err_fraction": abs(float(np.abs(tr.acc_A).max() / np.abs(a).max()
                                                  - 1)),
            "max_floquet_modulus": float(np.abs(sol.multipliers[0])),
        })
    return out


def run_study(p: HalfCarParams, out: Path, *, progress: bool = True) -> dict:
    """All stages, writing ``table1.md``, ``fig2-5.png`` and ``summary.json`` into ``out``.

    Returns
    -------
    dict
        The summary.
    """
    t_start = time.perf_counter()
    md, t1 = table1(p)
    write_text_atomic(out / "table1.md", md)
    print(md)
    summary = {"parameters_file": absolute(p.source), "table1": t1}
    summary["linear_spectra"] = linear_study(p, out)
    summary["nonlinear_spectra"], cpu_nl = nonlinear_study(p, out, progress=progress)
    summary["hb_vs_direct_integration"] = integration_check(p)
    summary["transients"], cpu_tr = transient_study(p, out)
    summary["cpu_s"] = {**cpu_nl, **cpu_tr}
    summary["cpu_ratio_complete_to_reduced"] = {
        "dual_rate_sweep": cpu_nl["dual_complete"] / cpu_nl["dual_reduced"],
        "duffing_sweep": cpu_nl["duffing_complete"] / cpu_nl["duffing_reduced"],
        "fig4_transient": cpu_tr["fig4_complete"] / cpu_tr["fig4_reduced"],
        "fig5_transient": cpu_tr["fig5_complete"] / cpu_tr["fig5_reduced"],
    }
    summary["wall_time_s"] = time.perf_counter() - t_start
    write_text_atomic(out / "summary.json", json.dumps(summary, indent=2))
    return summary


def _run(args) -> int:
    p = load_params(args.params)  # input errors first: nothing is created before
    out = check_run_folder(args.out)
    missing = [d for d in out.resolve().parents if not d.exists()]  # deepest first
    stage = staging_folder(out)
    try:
        summary = run_study(p, stage, progress=not args.no_progress)
        commit_directory(stage, out)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        for d in missing:  # the folders made for the staging folder, if still empty
            try:
                d.rmdir()
            except OSError:
                break
        raise
    lin = summary["linear_spectra"]["max_rel_err_vs_complete_fraction"]
    print(f"linear spectra, max relative error vs complete ({p.sweep_f_min_Hz:g}-"
          f"{p.sweep_f_max_Hz:g} Hz):")
    for v, e in lin.items():
        print(f"  {v:9s} acc {e['acc_A']:.2e}  travel {e['travel']:.2e}  "
              f"tire {e['tire_force']:.2e}")
    print(f"wrote {out}/table1.md, fig2-5.png, summary.json in {summary['wall_time_s']:.1f} s")
    return 0


def main(argv=None) -> int:
    """Command-line entry point; returns the exit code (see the module docstring)."""
    from flexpipe._signals import interrupt_info, interrupt_text, interrupts_as_exceptions
    from flexpipe.cli import EXIT_ERROR, _one_line

    ap = argparse.ArgumentParser(prog=PROG, description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/paper", help="output directory")
    ap.add_argument("--params", default=None, help="half-car TOML (default: paper set)")
    ap.add_argument("--no-progress", action="store_true", help="hide progress bars")
    try:
        args = ap.parse_args(argv)
    except SystemExit as exc:
        return int(exc.code or 0)

    def show_warning(message, category, filename, lineno, file=None, line=None):
        print(f"{PROG}: warning: {' '.join(str(message).split())}", file=sys.stderr)

    try:
        with warnings.catch_warnings(), interrupts_as_exceptions():
            warnings.showwarning = show_warning
            return _run(args)
    except SolverError as exc:
        print(f"{PROG}: error: {_one_line(exc)}; {args.out} is unchanged", file=sys.stderr)
        return 1
    except (FlexpipeError, OSError) as exc:
        print(f"{PROG}: error: {_one_line(exc)}", file=sys.stderr)
        return EXIT_ERROR
    except KeyboardInterrupt as exc:
        print(f"{PROG}: {interrupt_text(exc)}; {args.out} is unchanged", file=sys.stderr)
        return interrupt_info(exc)[0]


if __name__ == "__main__":
    raise SystemExit(main())
