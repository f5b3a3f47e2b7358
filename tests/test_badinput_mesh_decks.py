"""Bad-input corpus of the Nastran and Abaqus readers (tests/badinput/gen_*.py): every
"error" case raises a FlexpipeError naming the file, every "ok" case loads and assembles;
nothing else (no raw exception) ever escapes."""

from __future__ import annotations

import importlib.util
import warnings
from pathlib import Path

import pytest

from flexpipe.errors import FlexpipeError
from flexpipe.fem import assemble
from flexpipe.mesh import read_mesh

HERE = Path(__file__).parent / "badinput"


def _load(name):
    spec = importlib.util.spec_from_file_location(name, HERE / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


CASES = [(gen, *c) for gen in ("gen_nastran", "gen_abaqus")
         for c in _load(gen).cases()]


@pytest.mark.parametrize("gen, case_id, filename, content, expect", CASES,
                         ids=[f"{c[0][4:]}-{c[1]}" for c in CASES])
def test_bad_deck(tmp_path, gen, case_id, filename, content, expect):
    p = tmp_path / filename
    p.write_bytes(content)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        if expect == "ok":
            assemble(read_mesh(p))
            return
        with pytest.raises(FlexpipeError) as info:
            assemble(read_mesh(p))
    assert filename in str(info.value), str(info.value)


def test_corpus_size():
    assert sum(c[0] == "gen_nastran" for c in CASES) >= 80
    assert sum(c[0] == "gen_abaqus" for c in CASES) >= 80
