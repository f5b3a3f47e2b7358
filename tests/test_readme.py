"""The README's Python example runs as written (examples double as tests)."""

import os
import re
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[1]


def test_readme_python_example_runs(tmp_path, monkeypatch):
    text = (REPO / "README.md").read_text()
    block = re.search(r"## Python API\s+```python\n(.*?)```", text, flags=re.S).group(1)
    monkeypatch.chdir(REPO)
    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path / "cache"))
    block = block.replace('"out/bar.npz"', repr(os.fspath(tmp_path / "bar.npz")))
    ns: dict = {}
    exec(compile(block, "README.md", "exec"), ns)
    # independent checks on what the example computed
    assert np.all(ns["f_hz"][:6] < 1e-2 * ns["f_hz"][6])          # six rigid-body modes
    assert ns["body"].mass == pytest.approx(7850.0 * 1.0 * 0.1 * 0.1, rel=1e-9)
    assert ns["res"].status == 0
