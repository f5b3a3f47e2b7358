"""The bad-input corpus (issue 14): every case of every ``tests/badinput/gen_*.py``.

Each case is written to its own folder and read in-process by the reader its file name
selects (``tests/badinput/runner.py``).  Fails on a raw exception or hang, on an invalid
input that loads (accepted-wrong) and on a valid one that is rejected; prints the counts
(clear / vague / raw / accepted-wrong) of every generator and in total.
"""

from __future__ import annotations

import json
import os
from collections import Counter

import pytest

from flexpipe.vehicle import warmup
from tests.badinput import runner
from tests.badinput.gen_cli import SEDAN

GENERATORS = runner.generators()
RESULTS: dict[str, list] = {}
FAILING = ("raw", "accepted-wrong", "rejected-valid")
CATEGORIES = ("clear", "vague", "raw", "accepted-wrong", "ok", "rejected-valid")


@pytest.fixture(autouse=True)
def _cache(tmp_path, monkeypatch):
    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path / "cache"))
    monkeypatch.setenv("MPLBACKEND", "Agg")


@pytest.mark.parametrize("name", sorted(GENERATORS))
def test_generator(name, tmp_path, monkeypatch):
    cases = list(GENERATORS[name].cases())
    if name == "gen_cli" and warmup.pending():  # valid runs among the cases: compile the
        warmup.warm_up([SEDAN])                 # kernels first, outside the hang limit
    ids = [c[0] for c in cases]
    assert len(set(ids)) == len(ids), "case ids must be unique"
    outcomes = []
    for k, case in enumerate(cases):
        folder = tmp_path / f"c{k}"
        folder.mkdir()
        monkeypatch.chdir(folder)
        outcomes.append(runner.run_case(name, case, folder,
                                        getattr(GENERATORS[name], "load", None)))
    RESULTS[name] = outcomes
    bad = [o for o in outcomes if o.category in FAILING]
    assert not bad, "\n".join(f"{o.category}: {o.case_id} ({o.filename}): {o.message}"
                              for o in bad[:40])


def test_corpus_summary(capsys):
    """Totals over every generator; the corpus holds at least 500 cases."""
    if not RESULTS:
        pytest.skip("no generator ran (selected alone)")
    rows, total = [], Counter()
    for name, outs in sorted(RESULTS.items()):
        c = Counter(o.category for o in outs)
        total.update(c)
        rows.append(f"{name:<18}{len(outs):>6}" + "".join(f"{c[k]:>9}" for k in CATEGORIES))
    head = f"{'generator':<18}{'cases':>6}" + "".join(f"{k[:8]:>9}" for k in CATEGORIES)
    n = sum(len(o) for o in RESULTS.values())
    text = "\n".join([head, *rows, f"{'total':<18}{n:>6}"
                      + "".join(f"{total[k]:>9}" for k in CATEGORIES)])
    vague = [f"  {o.generator}/{o.case_id}: {o.message[:150]}" for outs in RESULTS.values()
             for o in outs if o.category == "vague"]
    with capsys.disabled():
        print("\n\nbad-input corpus (issue 14)\n" + text)
        if vague:
            print("vague messages:\n" + "\n".join(vague[:60]))
    target = os.environ.get("FLEXPIPE_BADINPUT_SUMMARY")
    if target:
        with open(target, "w") as fh:
            json.dump({"counts": dict(total), "cases": n,
                       "generators": {k: dict(Counter(o.category for o in v))
                                      for k, v in RESULTS.items()},
                       "vague": vague}, fh, indent=2)
    if len(RESULTS) == len(GENERATORS):
        assert n >= 500
