"""Stages of ``flexpipe.halfcar.paper``: transient speed and contact, Fig. 3 legend,
summary metrics and the direct-integration check frequencies.

References: the closed-form linear response, the tire law written out from the states,
the bilateral (paper) model where no tire lifts off, closed-form RMS values.
"""

import warnings

import numpy as np
import pytest
from _halfcardata import variant as variant_file

from flexpipe.halfcar import build_model, linear_spectrum, load_params, paper, simulate
from flexpipe.halfcar.elements import Nonlinearity
from flexpipe.halfcar.transient import Road


def variant(tmp_path, *edits, name="variant.toml"):
    """The parameters of the paper's file with ``(old, new)`` text replacements."""
    return load_params(variant_file(tmp_path, *edits, name=name))


# ------------------------------------------------------- finding 1: reference speed
def test_transient_runs_at_the_files_reference_speed_and_frequency(tmp_path):
    # 10 Hz at 150 km/h: lambda = 4.167 m.  40 cycles let the response settle; before the
    # front wheel leaves the irregularity (t = 40 lambda / v = 4 s) the linear transient
    # must equal the closed-form steady state at 10 Hz (it was run at 300 km/h = 20 Hz)
    p = variant(tmp_path, ("reference_frequency_Hz = 20.0", "reference_frequency_Hz = 10.0"),
                ("irregularity_cycles = 10", "irregularity_cycles = 40"))
    case = paper.transient_case(p)
    assert case["speed_m_per_s"] * 3.6 == pytest.approx(150.0, rel=1e-12)
    assert case["frequency_Hz"] == pytest.approx(10.0, rel=1e-12)
    (_, tr), _ = paper.transient_runs(p)["fig4"]
    window = (tr.t > 3.5) & (tr.t < 3.95)
    closed = linear_spectrum(build_model("complete", p), [10.0])
    assert np.abs(tr.acc_A[window]).max() == pytest.approx(closed.acc_A[0], rel=0.02)
    np.testing.assert_allclose(np.abs(tr.tire_force[:, window]).max(axis=1),
                               closed.tire_force[:, 0], rtol=0.01)
    res, _ = paper.transient_study(p, tmp_path)
    assert res["speed_km_per_h"] == pytest.approx(150.0)
    assert res["forcing_frequency_Hz"] == pytest.approx(10.0)
    assert res["wavelength_m"] == pytest.approx(150 / 3.6 / 10)


# ------------------------------------------------------- finding 2: tires cannot pull
def test_transient_tire_loads_never_negative_and_lift_off_reported(tmp_path):
    p = variant(tmp_path, ("amplitude_m = 0.002 ", "amplitude_m = 0.010 "))
    m = build_model("complete", p)
    case = paper.transient_case(p)
    # the bilateral law of the old transients pulls the rear wheel down (about -286 N)
    bilateral = simulate(m, Nonlinearity(damper="dual_rate"), case["road"],
                         case["speed_m_per_s"], case["t_end_s"], t_eval=case["t_eval"])
    assert bilateral.tire_load[1].min() < -200.0
    (_, tr), _ = paper.transient_runs(p)["fig5"]
    # the tire law from the states: load = F0 + k_t (road - wheel), or 0 off the road
    z = case["speed_m_per_s"] * tr.t[:, None] - np.array([0.0, m.wheelbase_m])
    free = m.static_tire_force + m.k_t * (case["road"].height(z) - tr.q @ m.E)
    on = tr.contact_state.T
    np.testing.assert_allclose(tr.tire_load.T[on], free[on], rtol=1e-9, atol=1e-6)
    np.testing.assert_allclose(tr.tire_load.T[~on], 0.0, atol=1e-9)
    assert (free[~on] <= 1e-3).all()  # off the road only where the tire would pull
    assert tr.tire_load.min() >= -1e-9 and tr.n_lift_offs[1] >= 1 and (~on[:, 1]).any()
    with pytest.warns(paper.LiftOffWarning) as caught:
        res, _ = paper.transient_study(p, tmp_path)
    assert [str(w.message)[:38] for w in caught] == [
        "Fig. 4: the rear tire leaves the road ", "Fig. 5: the rear tire leaves the road "]
    assert res["fig5"]["min_tire_load_complete_N"]["rear"] == pytest.approx(0.0, abs=1e-9)
    assert res["fig5"]["tire_lift_offs_complete"]["rear"] == tr.n_lift_offs[1]
    assert res["fig5"]["min_tire_load_complete_N"]["front"] > 0.0


def test_shipped_transients_keep_the_bilateral_results_when_no_tire_lifts_off(tmp_path):
    p = load_params()
    case = paper.transient_case(p)
    with warnings.catch_warnings():
        warnings.simplefilter("error", paper.LiftOffWarning)
        res, _ = paper.transient_study(p, tmp_path)
    for fig, laws in (("fig4", Nonlinearity()), ("fig5", Nonlinearity(damper="dual_rate"))):
        ref = simulate(build_model("complete", p), laws, case["road"], case["speed_m_per_s"],
                       case["t_end_s"], t_eval=case["t_eval"])
        assert res[fig]["peak_acc_A_complete_m_per_s2"] == pytest.approx(
            np.abs(ref.acc_A).max(), rel=1e-12)
        assert res[fig]["damper_switches_complete"] == ref.n_events
        assert res[fig]["tire_lift_offs_complete"] == {"front": 0, "rear": 0}
        assert min(res[fig]["min_tire_load_complete_N"].values()) > 2000.0


# ---------------------------------------------- findings 3, 7, 9: Fig. 3 and the metrics
@pytest.fixture(scope="module")
def small_nonlinear(tmp_path_factory):
    """nonlinear_study on a coarse grid with zeta = 0.45; the Fig. 3 figure kept open."""
    tmp = tmp_path_factory.mktemp("nl")
    p = variant(tmp, ("zeta = 0.3            #", "zeta = 0.45           #"),
                ("n_points = 200", "n_points = 16"), ("refine_points = 60", "refine_points = 0"))
    from flexpipe.halfcar import plots

    figures = []
    mp = pytest.MonkeyPatch()
    mp.setattr(plots, "_save", lambda fig, path: figures.append(fig))
    try:
        res, _ = paper.nonlinear_study(p, tmp, progress=False)
    finally:
        mp.undo()
    return p, res, figures


def test_figure3_legend_names_the_actual_linear_damping(small_nonlinear):
    p, _, figures = small_nonlinear
    assert p.zeta == 0.45
    (fig,) = figures
    labels = [t.get_text() for t in fig.axes[0].get_legend().get_texts()]
    assert "complete, linear zeta = 0.45" in labels
    assert not any("0.3" in s for s in labels)


def test_summary_metrics_carry_units_and_rms_alongside_max(small_nonlinear):
    _, res, _ = small_nonlinear
    for key in ("dual_rate_reduced_vs_complete_max_rel_err_fraction",
                "duffing_reduced_vs_complete_max_rel_err_fraction",
                "duffing_effect_max_rel_change_fraction",
                "duffing_effect_rms_rel_change_fraction",
                "dual_rate_vs_linear_rms_rel_change_fraction"):
        assert set(res[key]) == {"acc_A", "travel", "tire_force"}
    for q in ("acc_A", "travel", "tire_force"):  # RMS over the band <= the worst point
        assert 0 < res["duffing_effect_rms_rel_change_fraction"][q] \
            <= res["duffing_effect_max_rel_change_fraction"][q]
    assert not any(k.endswith("_rel_err") or k.endswith("_rel_change") for k in res)


def test_rms_relative_difference_against_closed_forms():
    f = np.linspace(0.0, 4.0, 4001)
    b = np.ones_like(f)
    # a uniform 3 % offset: 3 %; a ripple eps sin over whole periods: eps / sqrt 2
    assert paper.rms_rel(1.03 * b, b, f) == pytest.approx(0.03, rel=1e-12)
    assert paper.rms_rel(b + 0.2 * np.sin(2 * np.pi * f), b, f) == pytest.approx(
        0.2 / np.sqrt(2), rel=1e-6)
    # a 5 %-damped resonance shifted by 2 %: the band RMS weighs the flanks where the
    # two curves agree, the pointwise maximum only the worst frequency
    f = np.linspace(0.5, 25.0, 20001)

    def peak(f0):
        return 1 / np.abs(1 - (f / f0) ** 2 + 2j * 0.05 * f / f0)

    assert paper.rms_rel(peak(10.2), peak(10.0), f) < 0.6 * paper._max_rel(peak(10.2),
                                                                             peak(10.0))
    # rows (front, rear) are compared apart: the worse one counts
    assert paper.rms_rel(np.vstack([b, 1.1 * b]), np.vstack([b, b]), np.linspace(0, 1, 4001)) \
        == pytest.approx(0.1, rel=1e-12)


def test_table1_and_transient_keys_carry_units(tmp_path):
    _, t1 = paper.table1(load_params())
    assert "complete_vs_paper_max_rel_err_fraction" in t1
    assert not [k for k in t1 if k.endswith("_rel_err")]
    res, _ = paper.transient_study(load_params(), tmp_path)
    assert res["fig4"]["peak_acc_A_complete_m_per_s2"] > 0
    assert "peak_acc_A_complete" not in res["fig4"]


# -------------------------------------------- finding 8: check frequencies in the sweep
def test_integration_check_frequencies_lie_in_the_sweep_range(tmp_path):
    assert paper.check_frequencies(load_params()) == (3.0, 10.4, 20.0)
    p = variant(tmp_path, ("frequency_max_Hz = 25.0", "frequency_max_Hz = 5.0"),
                ("refine_band_Hz = [9.5, 11.0]", "refine_band_Hz = [3.0, 4.0]"))
    freqs = paper.check_frequencies(p)
    assert len(set(freqs)) == 3 and 3.0 in freqs
    assert all(0.5 <= f <= 5.0 for f in freqs)
    cases = paper.integration_cases(p)
    assert {c[2] for c in cases} == set(freqs)
    assert all(0.5 <= c[2] <= 5.0 for c in cases)
    p = variant(tmp_path, ("frequency_min_Hz = 0.5", "frequency_min_Hz = 30.0"),
                ("frequency_max_Hz = 25.0", "frequency_max_Hz = 40.0"),
                ("refine_band_Hz = [9.5, 11.0]", "refine_band_Hz = [31.0, 32.0]"))
    freqs = paper.check_frequencies(p)
    assert len(set(freqs)) == 3 and all(30.0 <= f <= 40.0 for f in freqs)


def test_integration_check_at_a_chosen_frequency_matches_harmonic_balance(tmp_path):
    # the exact piecewise-linear integration at a check frequency of a narrow sweep
    # (1-5 Hz) against the harmonic balance at that frequency
    p = variant(tmp_path, ("frequency_min_Hz = 0.5", "frequency_min_Hz = 1.0"),
                ("frequency_max_Hz = 25.0", "frequency_max_Hz = 5.0"),
                ("refine_band_Hz = [9.5, 11.0]", "refine_band_Hz = [3.0, 4.0]"))
    f = paper.check_frequencies(p)[0]
    from flexpipe.halfcar.floquet import eval_series
    from flexpipe.halfcar.hb import HarmonicBalance

    m = build_model("reduced", p)
    omega, T = 2 * np.pi * f, 1.0 / f
    sol = HarmonicBalance(m, paper.DUAL).solve(omega)
    t_end = np.ceil(12.0 / T) * T
    te = t_end - T + np.linspace(0.0, T, 129)
    tr = simulate(m, paper.DUAL, Road(p.road_amplitude_m, p.road_wavelength_m),
                  f * p.road_wavelength_m, t_end, t_eval=te)
    y = eval_series(sol.Z[:2], omega, te)
    assert np.abs(tr.travel - y).max() < 1e-3 * np.abs(y).max()


def test_figure3_line_styles_match_the_title_and_the_legend_is_off_the_curves(
        small_nonlinear):
    """The title says solid = stable, dashed = unstable: every stable curve is solid (no
    dash-dot), and the legend sits above the top panel, not over the curves."""
    _, _, figures = small_nonlinear
    (fig,) = figures
    assert "solid: stable, dashed: unstable" in fig._suptitle.get_text()
    legend = fig.axes[0].get_legend()
    for handle in legend.legend_handles:
        assert handle.get_linestyle() == "-", handle.get_label()
    fig.canvas.draw()
    box = legend.get_window_extent()
    assert box.y0 >= fig.axes[0].get_window_extent().y1 - 1  # above the top panel
