"""Reproduce the half-car study of the paper: Table 1, Figs 2-5 and an error summary.

``python -m flexpipe.halfcar.paper --out out/paper`` writes ``table1.md``, ``fig2.png``
... ``fig5.png`` and ``summary.json`` (reduced/truncated/rigid errors against the
complete model, harmonic balance against direct integration, CPU times).
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from flexpipe._io import write_text_atomic
from flexpipe.halfcar.elements import Nonlinearity
from flexpipe.halfcar.floquet import eval_series
from flexpipe.halfcar.hb import HarmonicBalance, sweep
from flexpipe.halfcar.linear import linear_spectrum
from flexpipe.halfcar.model import VARIANTS, build_model, natural_frequencies
from flexpipe.halfcar.params import HalfCarParams, load_params
from flexpipe.halfcar.plots import STYLES, figure2, figure3, figure_transient
from flexpipe.halfcar.transient import Road, simulate

DUAL = Nonlinearity(damper="dual_rate")
DUFFING = Nonlinearity(damper="dual_rate", tire="duffing", contact=True)
CHECK_FREQ_HZ = (3.0, 10.4, 20.0)  # sample speeds of the direct-integration check


def sweep_grid(p: HalfCarParams, *, refine: bool = True) -> np.ndarray:
    """Sweep frequencies: uniform grid plus the refinement band of the parameter file."""
    f = np.linspace(p.sweep_f_min_Hz, p.sweep_f_max_Hz, p.sweep_n_points)
    if refine and p.refine_points:
        f = np.union1d(f, np.linspace(*p.refine_band_Hz, p.refine_points))
    return f


def _max_rel(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a) / np.asarray(b) - 1.0)))


def _errors(s, ref) -> dict:
    return {"acc_A": _max_rel(s.acc_A, ref.acc_A), "travel": _max_rel(s.travel, ref.travel),
            "tire_force": _max_rel(s.tire_force, ref.tire_force)}


def table1(p: HalfCarParams) -> tuple[str, dict]:
    """Table 1 for all four variants (markdown) and the numbers."""
    f = {v: natural_frequencies(v, p) for v in VARIANTS}
    pc, pr, pg = (np.asarray(x) for x in (p.table1_complete_Hz, p.table1_reduced_Hz,
                                          p.table1_rigid_Hz))
    rows = ["| mode | complete (paper) | complete | err % | reduced (paper) | reduced | "
            "truncated | rigid (paper) | rigid | err % |", "|" + "---|" * 10]
    for i in range(8):
        rig = (f"{pg[i]:.2f} | {f['rigid'][i]:.3f} | {100 * (f['rigid'][i] / pg[i] - 1):+.2f}"
               if i < 4 else " | | ")
        rows.append(f"| {i + 1} | {pc[i]:.2f} | {f['complete'][i]:.3f} | "
                    f"{100 * (f['complete'][i] / pc[i] - 1):+.2f} | {pr[i]:.2f} | "
                    f"{f['reduced'][i]:.3f} | {f['truncated'][i]:.3f} | {rig} |")
    stats = {
        "computed_Hz": {v: f[v][:8].tolist() for v in VARIANTS},
        "complete_vs_paper_max_rel_err": _max_rel(f["complete"][:8], pc),
        "rigid_vs_paper_max_rel_err": _max_rel(f["rigid"], pg),
        "reduced_first6_vs_complete_max_rel_err": _max_rel(f["reduced"][:6], f["complete"][:6]),
        "reduced_modes7_8_vs_paper_rel_err": (f["reduced"][6:8] / pr[6:8] - 1).tolist(),
    }
    md = "\n".join([
        "# Table 1: natural frequencies of the half car with beam body (Hz)", "",
        f"Parameter set: `{p.source.name}`; paper values from Verros et al., Table 1. "
        "Complete: 22 beam DOF + 2 wheels; reduced: 2 rigid + 2 free-interface + 2 "
        "residual-flexibility body modes + 2 wheels; truncated: 6 lowest body modes + 2 "
        "wheels (no residual flexibility); rigid: heave + pitch + 2 wheels.", "", *rows, "",
        "Max relative error vs paper: complete "
        f"{100 * stats['complete_vs_paper_max_rel_err']:.2f} %, rigid "
        f"{100 * stats['rigid_vs_paper_max_rel_err']:.2f} %; reduced modes 1-6 vs "
        f"complete {100 * stats['reduced_first6_vs_complete_max_rel_err']:.4f} %.", ""])
    return md, stats


def linear_study(p, out: Path) -> dict:
    """Fig 2 (closed form) and the harmonic-balance check of the linear laws."""
    f = np.linspace(p.sweep_f_min_Hz, p.sweep_f_max_Hz, 1000)
    spectra = {v: linear_spectrum(build_model(v, p), f, label=v) for v in VARIANTS}
    figure2(spectra, out / "fig2.png", title=(
        f"Fig. 2 - linear half car, zeta = {p.zeta}\nharmonic road s0 = "
        f"{1e3 * p.road_amplitude_m:g} mm, lambda = {p.road_wavelength_m:.3f} m, rear input "
        f"delayed by wheelbase / v"))
    ref = spectra["complete"]
    res = {"max_rel_err_vs_complete": {v: _errors(spectra[v], ref) for v in VARIANTS[1:]}}
    # the harmonic-balance machinery on the linear laws, with only part of them in the
    # linear reference so that Newton/AFT do the work, against the closed form
    m = build_model("reduced", p)
    hb = HarmonicBalance(m, Nonlinearity(), c_ref=0.4 * m.c_lin, k_ref=0.6 * m.k_t)
    fs = f[::50]
    closed = linear_spectrum(m, fs)
    acc = [abs(hb.solve(2 * np.pi * fi).acc_A[1]) for fi in fs]
    res["hb_linear_vs_closed_form_max_rel_err"] = _max_rel(acc, closed.acc_A)
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
        runs[key] = sweep(build_model(variant, p), nl, f, progress=progress,
                          label=f"{variant}, {nl.label}")
        cpu[key] = time.process_time() - t0
    lin = linear_spectrum(build_model("complete", p), f)
    figure3([("complete, dual-rate", runs["dual_complete"], STYLES["complete"]),
             ("reduced, dual-rate", runs["dual_reduced"], STYLES["reduced"]),
             ("complete, dual-rate + Duffing tires + contact", runs["duffing_complete"],
              dict(color="tab:purple", lw=1.0, ls="-."))],
            out / "fig3.png", reference=lin, title=(
                f"Fig. 3 - dual-rate dampers zeta- = {p.zeta_jounce} (jounce), zeta+ = "
                f"{p.zeta_rebound} (rebound)\nharmonic balance, H = {p.harmonics} harmonics; "
                f"solid: stable, dashed: unstable (Floquet)"))
    res = {
        "n_points": int(f.size),
        "dual_rate_reduced_vs_complete_max_rel_err": _errors(runs["dual_reduced"],
                                                             runs["dual_complete"]),
        "duffing_reduced_vs_complete_max_rel_err": _errors(runs["duffing_reduced"],
                                                           runs["duffing_complete"]),
        "duffing_effect_max_rel_change": _errors(runs["duffing_complete"],
                                                 runs["dual_complete"]),
        "dual_rate_vs_linear_max_rel_change": _errors(runs["dual_complete"], lin),
        "all_stable": bool(all(r.stable.all() for r in runs.values())),
        "max_floquet_modulus": {k: float(r.floquet_max.max()) for k, r in runs.items()},
        "unstable_points": {k: int((~r.stable).sum()) for k, r in runs.items()},
        "max_newton_iterations": {k: int(r.iterations.max()) for k, r in runs.items()},
        "max_tire_load_ratio": float(max(
            (runs[k].tire_force.max(axis=1) / build_model("complete", p).static_tire_force)
            .max() for k in runs)),
    }
    return res, cpu


def integration_check(p) -> list[dict]:
    """Harmonic balance against long direct integration from rest at sample speeds."""
    out = []
    cases = [(v, DUAL, f, None) for v in ("reduced", "complete") for f in CHECK_FREQ_HZ]
    cases.append(("reduced", DUFFING, 10.4, "DOP853"))
    for variant, nl, f, method in cases:
        m = build_model(variant, p)
        omega, T = 2 * np.pi * f, 1.0 / f
        sol = HarmonicBalance(m, nl).with_stability(HarmonicBalance(m, nl).solve(omega))
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
            "travel_rel_err": float(np.abs(tr.travel - y).max() / np.abs(y).max()),
            "tire_force_rel_err": float(np.abs(tr.tire_force - F).max() / np.abs(F).max()),
            "max_acc_rel_err": abs(float(np.abs(tr.acc_A).max() / np.abs(a).max() - 1)),
            "max_floquet_modulus": float(np.abs(sol.multipliers[0])),
        })
    return out


def transient_study(p, out: Path) -> tuple[dict, dict]:
    """Figs 4 and 5: the isolated irregularity at 150 km/h (20 Hz)."""
    v = p.road_wavelength_m * 20.0  # the wavelength gives 20 Hz at the reference speed
    road = Road(p.road_amplitude_m, p.road_wavelength_m, p.irregularity_cycles)
    t_end = (p.irregularity_cycles * p.road_wavelength_m + 3.0) / v + 1.0
    te = np.linspace(0.0, t_end, 6001)
    res, cpu = {}, {}
    for fig, nl, title in (
            ("fig4", Nonlinearity(), f"Fig. 4 - linear dampers zeta = {p.zeta}"),
            ("fig5", DUAL, f"Fig. 5 - dual-rate dampers zeta- = {p.zeta_jounce}, "
                           f"zeta+ = {p.zeta_rebound}")):
        runs = []
        for variant in ("complete", "reduced"):
            tr = simulate(build_model(variant, p), nl, road, v, t_end, t_eval=te)
            runs.append((variant, tr))
            cpu[f"{fig}_{variant}"] = tr.cpu_s
        figure_transient(runs, out / f"{fig}.png", damper_strip=(fig == "fig5"), title=(
            f"{title}\nirregularity s0 sin(2 pi z / lambda), 0 <= z < "
            f"{p.irregularity_cycles} lambda, s0 = {1e3 * p.road_amplitude_m:g} mm, "
            f"v = {3.6 * v:.0f} km/h (20 Hz)"))
        (_, c), (_, r) = runs
        diff = np.abs(r.acc_A - c.acc_A)
        res[fig] = {"reduced_vs_complete_max_abs_diff_rel_to_peak":
                    float(diff.max() / np.abs(c.acc_A).max()),
                    "reduced_vs_complete_rms_diff_rel_to_rms":
                    float(np.sqrt(np.mean(diff**2) / np.mean(c.acc_A**2))),
                    "peak_acc_A_complete": float(np.abs(c.acc_A).max()),
                    "damper_switches_complete": c.n_events}
    return res, cpu


def main(argv=None) -> int:
    """Command-line entry point."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="out/paper", help="output directory")
    ap.add_argument("--params", default=None, help="half-car TOML (default: paper set)")
    ap.add_argument("--no-progress", action="store_true", help="hide progress bars")
    args = ap.parse_args(argv)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    p = load_params(args.params)
    t_start = time.perf_counter()
    md, t1 = table1(p)
    write_text_atomic(out / "table1.md", md)
    print(md)
    summary = {"parameters_file": str(p.source), "table1": t1}
    summary["linear_spectra"] = linear_study(p, out)
    summary["nonlinear_spectra"], cpu_nl = nonlinear_study(p, out,
                                                           progress=not args.no_progress)
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
    lin = summary["linear_spectra"]["max_rel_err_vs_complete"]
    print("linear spectra, max relative error vs complete (0-25 Hz):")
    for v, e in lin.items():
        print(f"  {v:9s} acc {e['acc_A']:.2e}  travel {e['travel']:.2e}  "
              f"tire {e['tire_force']:.2e}")
    print(f"wrote {out}/table1.md, fig2-5.png, summary.json in {summary['wall_time_s']:.1f} s")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
