"""The road, CRG, path, driver and tyre bad-input corpora (tests/badinput/gen_*.py).

Each case is written to its own file and loaded with the loader its generator names
(``load``).  An ``"error"`` case must raise a :class:`~flexpipe.errors.FlexpipeError`
whose message names the file; an ``"ok"`` case must load.  Anything else (a raw
exception, an accepted bad file, a FlexpipeError without the file name) fails.
"""

from __future__ import annotations

import importlib.util
import pathlib
import warnings

import pytest

from flexpipe.errors import FlexpipeError

HERE = pathlib.Path(__file__).resolve().parent / "badinput"
GENERATORS = ("gen_tir", "gen_crg", "gen_roads")


def _module(name):
    spec = importlib.util.spec_from_file_location(f"badinput_{name}", HERE / f"{name}.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _all_cases():
    out = []
    for name in GENERATORS:
        if not (HERE / f"{name}.py").is_file():
            continue
        mod = _module(name)
        for case_id, filename, content, expect in mod.cases():
            out.append(pytest.param(mod, filename, content, expect, id=f"{name}:{case_id}"))
    return out


def classify(mod, path: pathlib.Path, expect: str) -> str:
    """'clear' / 'vague' / 'raw' / 'accepted-wrong' for an error case; 'ok' / 'rejected-ok'
    (a FlexpipeError) / 'raw' for an ok case."""
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            mod.load(path)
    except FlexpipeError as exc:
        if expect == "ok":
            return "rejected-ok"
        return "clear" if path.name in str(exc) else "vague"
    except Exception:  # noqa: BLE001 - the point is to catch anything else
        return "raw"
    return "ok" if expect == "ok" else "accepted-wrong"


@pytest.mark.parametrize("mod, filename, content, expect", _all_cases())
def test_case(tmp_path, mod, filename, content, expect):
    path = tmp_path / filename
    path.write_bytes(content)
    outcome = classify(mod, path, expect)
    if outcome not in ("clear", "ok"):       # re-run unguarded to show the exception
        if outcome in ("raw", "vague", "rejected-ok"):
            mod.load(path)
    assert outcome == ("ok" if expect == "ok" else "clear"), outcome


def test_corpus_size():
    counts = {name: sum(1 for _ in _module(name).cases()) for name in GENERATORS}
    assert all(n >= 60 for n in counts.values()), counts
