"""Figs 4 and 5 of the paper: the half car crossing an isolated road irregularity.

Section 4 of the paper: the complete and the reduced model run over ``s0 sin(2 pi z /
lambda)``, ``0 <= z < cycles lambda``, at the reference speed of the parameter file, with
linear (Fig. 4) and dual-rate (Fig. 5) dampers.  A tire cannot pull, so contact is
unilateral; while both tires stay on the road this is the paper's bilateral model, and a
lift-off is reported (:class:`LiftOffWarning`, ``summary.json``).  Part of
:mod:`flexpipe.halfcar.paper`, which re-exports these names.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from flexpipe.halfcar.elements import Nonlinearity
from flexpipe.halfcar.model import build_model
from flexpipe.halfcar.params import HalfCarParams
from flexpipe.halfcar.plots import figure_transient
from flexpipe.halfcar.transient import Road, simulate

#: laws of the transients (Figs 4, 5): a tire cannot pull, so contact is unilateral
#: (while both tires stay on the road this is the bilateral model of the paper)
TRANSIENT_LAWS = {"fig4": Nonlinearity(contact=True),
                  "fig5": Nonlinearity(damper="dual_rate", contact=True)}


class LiftOffWarning(UserWarning):
    """A tire left the road (transients) or would have to pull (bilateral spectra)."""


def transient_case(p: HalfCarParams) -> dict:
    """Speed, forcing frequency, road and time grid of the transients (Figs 4, 5).

    Section 4 of the paper: the isolated irregularity ``s0 sin(2 pi z / lambda)``,
    ``0 <= z < cycles lambda``, is crossed at the reference speed ``v0`` (150 km/h), the
    wavelength being chosen so that ``v0 / lambda`` is the reference frequency (20 Hz).
    Both come from ``[road]`` of the parameter file.

    Returns
    -------
    dict
        ``speed_m_per_s``, ``frequency_Hz`` (``v0 / lambda``, the forcing frequency
        actually run), ``road`` (:class:`Road`), ``t_end_s`` (1 s after the rear wheel
        has left the irregularity) and ``t_eval`` (6001 output times).
    """
    v = p.reference_speed_m_per_s
    lam = p.road_wavelength_m
    span = p.irregularity_cycles * lam + max(3.0, build_model("complete", p).wheelbase_m)
    t_end = span / v + 1.0
    return {"speed_m_per_s": v, "frequency_Hz": v / lam,
            "road": Road(p.road_amplitude_m, lam, p.irregularity_cycles),
            "t_end_s": t_end, "t_eval": np.linspace(0.0, t_end, 6001)}


def transient_runs(p: HalfCarParams) -> dict:
    """Direct integrations of Figs 4 and 5, complete and reduced models.

    Returns
    -------
    dict
        ``{"fig4": [("complete", Transient), ("reduced", Transient)], "fig5": [...]}``
        with the laws of :data:`TRANSIENT_LAWS` (unilateral tire contact).
    """
    case = transient_case(p)
    return {fig: [(variant, simulate(build_model(variant, p), nl, case["road"],
                                     case["speed_m_per_s"], case["t_end_s"],
                                     t_eval=case["t_eval"]))
                  for variant in ("complete", "reduced")]
            for fig, nl in TRANSIENT_LAWS.items()}


def transient_study(p, out: Path) -> tuple[dict, dict]:
    """Figs 4 and 5: the isolated irregularity at the reference speed of the file."""
    case = transient_case(p)
    v, f_ref = case["speed_m_per_s"], case["frequency_Hz"]
    res = {"speed_km_per_h": 3.6 * v, "forcing_frequency_Hz": f_ref,
           "wavelength_m": p.road_wavelength_m, "t_end_s": case["t_end_s"]}
    cpu = {}
    titles = {"fig4": f"Fig. 4 - linear dampers zeta = {p.zeta}",
              "fig5": f"Fig. 5 - dual-rate dampers zeta- = {p.zeta_jounce}, "
                      f"zeta+ = {p.zeta_rebound}"}
    for fig, runs in transient_runs(p).items():
        for variant, tr in runs:
            cpu[f"{fig}_{variant}"] = tr.cpu_s
        (_, c), (_, r) = runs
        lifted = [name for name, n in zip(("front", "rear"), c.n_lift_offs, strict=True) if n]
        note = f"; {' and '.join(lifted)} tire leaves the road" if lifted else ""
        figure_transient(runs, out / f"{fig}.png", damper_strip=(fig == "fig5"), title=(
            f"{titles[fig]}\nirregularity s0 sin(2 pi z / lambda), 0 <= z < "
            f"{p.irregularity_cycles} lambda, s0 = {1e3 * p.road_amplitude_m:g} mm, "
            f"v = {3.6 * v:.0f} km/h ({f_ref:.4g} Hz){note}"))
        diff = np.abs(r.acc_A - c.acc_A)
        load = c.tire_load.min(axis=1)
        res[fig] = {"laws": TRANSIENT_LAWS[fig].label,
                    "reduced_vs_complete_max_abs_diff_rel_to_peak_fraction":
                    float(diff.max() / np.abs(c.acc_A).max()),
                    "reduced_vs_complete_rms_diff_rel_to_rms_fraction":
                    float(np.sqrt(np.mean(diff**2) / np.mean(c.acc_A**2))),
                    "peak_acc_A_complete_m_per_s2": float(np.abs(c.acc_A).max()),
                    "damper_switches_complete": c.n_damper_switches,
                    "min_tire_load_complete_N": {"front": float(load[0]),
                                                 "rear": float(load[1])},
                    "tire_lift_offs_complete": {"front": int(c.n_lift_offs[0]),
                                                "rear": int(c.n_lift_offs[1])}}
        if lifted:
            warnings.warn(
                f"Fig. {fig[-1]}: the {' and '.join(lifted)} tire leaves the road "
                f"({', '.join(str(int(n)) for n in c.n_lift_offs if n)} time(s)) at s0 = "
                f"{1e3 * p.road_amplitude_m:g} mm; contact is unilateral (the load stays "
                ">= 0 N), but the paper's comparison assumes the tires stay on the road",
                LiftOffWarning, stacklevel=2)
    return res, cpu
