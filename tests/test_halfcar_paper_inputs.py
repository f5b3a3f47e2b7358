"""Half-car parameter files: mode counts, Table 1 lists, reference speed, other file kinds.

References: the unreduced (complete) model, the hand-built rigid model's column, the
Rayleigh-Ritz bound, and the error messages' file / line / key.
"""

from pathlib import Path

import numpy as np
import pytest
from _halfcardata import variant

from flexpipe.errors import InputError
from flexpipe.halfcar import load_params, natural_frequencies
from flexpipe.halfcar.paper import table1

REPO = Path(__file__).resolve().parents[1]


def line_of(path: Path, needle: str) -> int:
    return next(i for i, s in enumerate(path.read_text().splitlines(), 1) if needle in s)


def rows_of(md: str) -> list[list[str]]:
    """Cells of Table 1's data rows."""
    return [[c.strip() for c in r.strip("|").split("|")] for r in md.splitlines()
            if r.startswith("| ") and r[2].isdigit()]


# ----------------------------------------------------------------- finding 6: mode counts
def test_too_many_free_interface_modes_names_the_key_and_valid_range(tmp_path):
    bad = variant(tmp_path, ("free_interface_modes = 2", "free_interface_modes = 30"))
    with pytest.raises(InputError) as err:
        load_params(bad)
    msg = str(err.value)
    assert err.value.key == "reduction.free_interface_modes"
    assert f"line {line_of(bad, 'free_interface_modes = 30')}" in msg
    assert "0..18" in msg and "22 DOF" in msg and "n_modes" not in msg


def test_truncated_modes_checked_against_the_beam_of_n_elements(tmp_path):
    bad = variant(tmp_path, ("n_elements = 10", "n_elements = 1"),
                  ("attachment_node = 2", "attachment_node = 0"),
                  ("attachment_node = 9", "attachment_node = 1"),
                  ("free_interface_modes = 2", "free_interface_modes = 0"))
    with pytest.raises(InputError) as err:
        load_params(bad)
    assert err.value.key == "reduction.truncated_modes"
    assert "2..4" in str(err.value) and "n_elements = 1" in str(err.value)
    assert f"line {line_of(bad, 'truncated_modes = 6')}" in str(err.value)
    with pytest.raises(InputError, match=r"free_interface_modes.*valid values are 0\.\.0"):
        load_params(variant(tmp_path, ("n_elements = 10", "n_elements = 1"),
                            ("attachment_node = 2", "attachment_node = 0"),
                            ("attachment_node = 9", "attachment_node = 1")))


def test_largest_valid_free_interface_count_gives_the_complete_model(tmp_path):
    # 2 rigid + 18 elastic + 2 residual modes span the whole 22-DOF beam: the reduced
    # model must then be the unreduced one
    p = load_params(variant(tmp_path, ("free_interface_modes = 2", "free_interface_modes = 18")))
    np.testing.assert_allclose(natural_frequencies("reduced", p),
                               natural_frequencies("complete", p), rtol=1e-8)
    with pytest.raises(InputError, match="0..18"):
        load_params(variant(tmp_path, ("free_interface_modes = 2", "free_interface_modes = 19")))


# ------------------------------------------------------------- finding 5: Table 1 sizes
def test_residual_flexibility_only_reduction_runs_table1_with_blank_cells(tmp_path):
    p = load_params(variant(tmp_path, ("free_interface_modes = 2", "free_interface_modes = 0")))
    fc, fr = natural_frequencies("complete", p), natural_frequencies("reduced", p)
    assert fr.size == 6  # 2 rigid + 2 residual-flexibility body modes + 2 wheels
    assert np.all(fr >= fc[:6] * (1 - 1e-9))  # Rayleigh-Ritz: a subspace stiffens
    np.testing.assert_allclose(fr[:2], fc[:2], rtol=1e-6)  # ride modes barely change
    md, stats = table1(p)
    rows = rows_of(md)
    assert len(rows) == 8
    assert [r[5] for r in rows] == [f"{x:.3f}" for x in fr] + ["", ""]
    assert [r[4] for r in rows][6:] == ["62.70", "140.75"]  # the paper's column stays
    assert "0 free-interface" in md and "reduced modes 1-4" in md
    assert stats["reduced_vs_complete_lowest_modes"] == 4
    assert set(stats["reduced_upper_modes_vs_paper_rel_err_fraction"]) == {"5", "6"}


@pytest.mark.parametrize("n", [2, 3])
def test_few_truncated_modes_run_table1(tmp_path, n):
    p = load_params(variant(tmp_path, ("truncated_modes = 6", f"truncated_modes = {n}")))
    ft, fc = natural_frequencies("truncated", p), natural_frequencies("complete", p)
    assert ft.size == n + 2
    assert np.all(ft >= fc[:n + 2] * (1 - 1e-9))
    if n == 2:  # the two rigid-body modes of the beam: the rigid (heave + pitch) model
        np.testing.assert_allclose(ft, natural_frequencies("rigid", p), rtol=1e-9)
    md, _ = table1(p)
    rows = rows_of(md)
    assert len(rows) == 8
    assert [r[6] for r in rows] == [f"{x:.3f}" for x in ft] + [""] * (6 - n)
    assert f"truncated: {n} lowest body modes" in md


def test_short_published_lists_leave_blank_cells(tmp_path):
    p = load_params(variant(
        tmp_path, ("complete_Hz = [0.89, 1.27, 10.17, 10.27, 10.42, 28.15, 55.21, 91.41]",
                   "complete_Hz = [0.89, 1.27]"),
        ("rigid_Hz = [0.89, 1.27, 10.27, 10.36]", "rigid_Hz = [0.89, 1.27, 10.27]")))
    md, stats = table1(p)
    rows = rows_of(md)
    assert len(rows) == 8
    assert [r[1] for r in rows] == ["0.89", "1.27"] + [""] * 6
    assert all(r[3] == "" for r in rows[2:]) and rows[1][3] != ""
    assert [r[7] for r in rows[:4]] == ["0.89", "1.27", "10.27", ""]
    assert rows[3][8] != "" and rows[3][9] == ""  # computed 4th rigid mode, no error
    fc, fg = natural_frequencies("complete", p), natural_frequencies("rigid", p)
    assert stats["complete_vs_paper_max_rel_err_fraction"] == pytest.approx(
        np.abs(fc[:2] / [0.89, 1.27] - 1).max(), rel=1e-12)
    assert stats["rigid_vs_paper_max_rel_err_fraction"] == pytest.approx(
        np.abs(fg[:3] / [0.89, 1.27, 10.27] - 1).max(), rel=1e-12)


def test_more_published_frequencies_than_a_model_has_is_an_input_error(tmp_path):
    bad = variant(tmp_path, ("rigid_Hz = [0.89, 1.27, 10.27, 10.36]",
                             "rigid_Hz = [0.89, 1.27, 10.27, 10.36, 11.0]"))
    with pytest.raises(InputError) as err:
        load_params(bad)
    assert err.value.key == "table1.rigid_Hz"
    assert "1 to 4" in str(err.value) and f"line {line_of(bad, 'rigid_Hz =')}" in str(err.value)
    bad = variant(tmp_path, ("complete_Hz = [0.89", "complete_Hz = [0.0, 0.89"))
    with pytest.raises(InputError, match=r"table1.complete_Hz.*> 0 Hz"):
        load_params(bad)


# --------------------------------------------------------- finding 1: reference speed
def test_reference_speed_and_frequency_are_read_and_give_the_wavelength(tmp_path):
    p = load_params(variant(tmp_path, ("reference_frequency_Hz = 20.0",
                                       "reference_frequency_Hz = 10.0")))
    assert p.reference_speed_m_per_s == pytest.approx(150 / 3.6, rel=1e-15)
    assert p.reference_frequency_Hz == 10.0
    assert p.road_wavelength_m == pytest.approx(150 / 3.6 / 10.0, rel=1e-15)


# ------------------------------------------------------ finding 4: a file of another kind
def test_full_car_file_is_refused_in_one_line():
    with pytest.raises(InputError) as err:
        load_params(REPO / "cars" / "sedan.toml")
    msg = str(err.value)
    assert msg.startswith(str(REPO / "cars" / "sedan.toml"))
    assert "not a half-car parameter file" in msg and "car file" in msg
    assert "halfcar_paper.toml" in msg and "\n" not in msg
