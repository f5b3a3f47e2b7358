"""The README's Python example runs as written (examples double as tests)."""

import os
import re
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[1]


def test_readme_python_example_runs(tmp_path, monkeypatch):
    text = (REPO / "README.md").read_text()
    # (an HTML comment before the fence is the docs-test marker, tests/test_docs_examples.py)
    block = re.search(r"## Python API\s+(?:<!--[^\n]*-->\s+)?```python\n(.*?)```", text,
                      flags=re.S).group(1)
    monkeypatch.chdir(REPO)
    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path / "cache"))
    block = block.replace('"out/bar.npz"', repr(os.fspath(tmp_path / "bar.npz")))
    block = block.replace('"out/run.mat"', repr(os.fspath(tmp_path / "run.mat")))
    ns: dict = {}
    exec(compile(block, "README.md", "exec"), ns)
    # independent checks on what the example computed
    assert np.all(ns["f_hz"][:6] < 1e-2 * ns["f_hz"][6])          # six rigid-body modes
    assert ns["body"].mass == pytest.approx(7850.0 * 1.0 * 0.1 * 0.1, rel=1e-9)
    assert ns["res"].status == 0
    back, res = ns["back"], ns["res"]                              # the .mat read back
    assert set(back.channels) == set(res.channels)
    np.testing.assert_array_equal(back.t, res.t)
    np.testing.assert_array_equal(back["hub_fl_z"], res["hub_fl_z"])
    # roads load from the top-level API, as load_car does
    from flexpipe.roads import Road, load_road

    assert ns["fp"].load_road is load_road and "load_road" in dir(ns["fp"])
    assert isinstance(ns["road"], Road) and ns["z"] == pytest.approx(0.04, abs=1e-12)  # bump top
    assert ns["path"].x[0] == 0.0 and ns["path"].x[-1] == pytest.approx(20.0)  # the 20 m line


@pytest.mark.slow
def test_readme_sample_body_figures_are_what_the_check_prints():
    """The sample body's mass and first torsion / bending figures in the README are what
    ``python meshes/make_sedan_biw.py --check --car cars/sedan.toml`` computes."""
    from flexpipe.fem import assemble
    from flexpipe.mesh import read_mesh
    from flexpipe.vehicle.bodymodel import body_fe, global_modes
    from flexpipe.vehicle.spec import load_car

    text = " ".join((REPO / "README.md").read_text().split())
    m = re.search(r"--check --car cars/sedan\.toml`, re-run [0-9-]+\): BIW ([\d.]+) kg, torsion "
                  r"([\d.]+) Hz, bending ([\d.]+) Hz; trimmed ([\d.]+) kg, torsion ([\d.]+) Hz, "
                  r"bending ([\d.]+) Hz", text)
    assert m, "the README's sample-body figures (BIW and trimmed) are not where expected"
    fe = assemble(read_mesh(REPO / "meshes" / "sedan_biw.bdf"))
    fe_t = body_fe(load_car(REPO / "cars" / "sedan.toml"))
    g, gt = global_modes(fe, 20), global_modes(fe_t, 20)
    got = [fe.total_mass, g["torsion_hz"], g["bending_hz"],
           fe_t.total_mass, gt["torsion_hz"], gt["bending_hz"]]
    assert list(m.groups()) == [f"{v:.1f}" for v in got]
