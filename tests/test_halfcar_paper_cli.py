"""``python -m flexpipe.halfcar.paper``: one-line errors, exit codes, no partial output.

Input errors: exit 2 and ``error: FILE, line N, key 'K': message`` before anything is
created; a harmonic-balance failure: exit 1 with the frequency and a hint; Ctrl-C: exit
130 without a traceback; in every failure the previous output folder stays as it was.
"""

import json
import signal
from pathlib import Path

import pytest

from flexpipe.halfcar import paper

REPO = Path(__file__).resolve().parents[1]
DATA = REPO / "cars" / "halfcar_paper.toml"


def run(capsys, *argv) -> tuple[int, str]:
    code = paper.main(["--no-progress", *map(str, argv)])
    err = capsys.readouterr().err
    assert "Traceback" not in err
    return code, err


def previous_run(folder: Path) -> dict:
    """A previous run's output folder; returns its files' contents."""
    folder.mkdir()
    files = {"summary.json": json.dumps({"previous": True}), "table1.md": "previous\n"}
    for name, text in files.items():
        (folder / name).write_text(text)
    return files


def assert_unchanged(folder: Path, files: dict) -> None:
    assert {p.name: p.read_text() for p in folder.iterdir()} == files
    leftovers = [p.name for p in folder.parent.iterdir() if p.name.startswith(".")
                 or p.name.endswith(".failed")]
    assert leftovers == []  # no staging folder left behind


def test_toml_syntax_error_is_one_line_and_creates_nothing(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(DATA.read_text().replace("mass_kg = 600.0", "mass_kg = 600.0 kg"))
    out = tmp_path / "out"
    code, err = run(capsys, "--params", bad, "--out", out)
    line = next(i for i, s in enumerate(bad.read_text().splitlines(), 1) if "600.0 kg" in s)
    assert code == 2
    assert err.count("\n") == 1 and "error: " in err
    assert f"{bad}, line {line}: invalid TOML" in err
    assert not out.exists()
    bad.write_text("[body]\nlength_m = [\n")  # cut off: the error is at the end
    code, err = run(capsys, "--params", bad, "--out", out)
    assert code == 2 and f"{bad}, line 2: invalid TOML" in err and not out.exists()


def test_bad_value_names_file_line_and_key(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(DATA.read_text().replace("free_interface_modes = 2",
                                            "free_interface_modes = 30"))
    out = tmp_path / "out"
    code, err = run(capsys, "--params", bad, "--out", out)
    line = next(i for i, s in enumerate(bad.read_text().splitlines(), 1) if "= 30" in s)
    assert code == 2 and err.count("\n") == 1
    assert f"error: {bad}, line {line}, key 'reduction.free_interface_modes': " in err
    assert not out.exists()


def test_missing_params_file_and_full_car_file(tmp_path, capsys):
    out = tmp_path / "out"
    code, err = run(capsys, "--params", tmp_path / "missing.toml", "--out", out)
    assert code == 2 and err.count("\n") == 1
    assert f"{tmp_path / 'missing.toml'}: cannot read half-car parameter file" in err
    code, err = run(capsys, "--params", REPO / "cars" / "sedan.toml", "--out", out)
    assert code == 2 and err.count("\n") == 1 and "not a half-car parameter file" in err
    assert not out.exists()


def test_out_that_is_a_file_is_refused_before_any_work(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(paper, "run_study", lambda *a, **k: pytest.fail("work started"))
    target = tmp_path / "afile"
    target.write_text("mine")
    code, err = run(capsys, "--out", target)
    assert code == 2 and err.count("\n") == 1
    assert f"{target}, key '--out': exists and is a file" in err
    assert target.read_text() == "mine"


def test_harmonic_balance_failure_exits_1_with_frequency_and_hint(tmp_path, capsys):
    # 10 mm: the rear wheel hops and the Duffing + contact harmonic balance breaks down
    # near the wheel-hop resonance; coarse sweep to keep the test short
    text = (DATA.read_text().replace("amplitude_m = 0.002 ", "amplitude_m = 0.010 ")
            .replace("n_points = 200", "n_points = 12").replace("refine_points = 60",
                                                                "refine_points = 0"))
    params = tmp_path / "hop.toml"
    params.write_text(text)
    out = tmp_path / "out"
    files = previous_run(out)
    code, err = run(capsys, "--params", params, "--out", out)
    assert code == 1
    lines = [s for s in err.splitlines() if s]
    assert len(lines) >= 1 and "error: " in lines[-1]
    assert "Fig. 3 sweep" in lines[-1] and "did not converge at" in lines[-1]
    assert " Hz " in lines[-1] and "hint: " in lines[-1] and "amplitude_m" in lines[-1]
    assert f"{out} is unchanged" in lines[-1]
    assert_unchanged(out, files)  # no table1.md / fig2.png of the failed run


def test_ctrl_c_exits_130_quietly_and_keeps_the_previous_output(tmp_path, capsys,
                                                                 monkeypatch):
    real = paper.linear_study

    def interrupted(p, out):
        real(p, out)  # table1.md and fig2.png are in the staging folder by now
        signal.raise_signal(signal.SIGINT)

    monkeypatch.setattr(paper, "linear_study", interrupted)
    out = tmp_path / "out"
    files = previous_run(out)
    try:
        code, err = run(capsys, "--out", out)
    except KeyboardInterrupt:
        pytest.fail("Ctrl-C escaped main() as a KeyboardInterrupt")
    assert code == 130
    assert err.strip() == f"{paper.PROG}: interrupted (SIGINT); {out} is unchanged"
    assert_unchanged(out, files)
