"""Run the benchmark modules and print their figures as one table.

Usage::

    python -m bench                      # every bench/bench_*.py
    python -m bench fem halfcar          # a subset (with or without the bench_ prefix)
    python -m bench --json out/bench.json

Each module runs in a child process: one failing, crashing or out-of-memory benchmark
does not stop the others, and each module's peak memory is its own.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent

_CHILD = """
import json, sys, importlib
res = importlib.import_module("bench." + sys.argv[1]).run()
with open(sys.argv[2], "w") as fh:
    json.dump(res, fh, default=str)
"""


def discover() -> list[str]:
    """Names of the benchmark modules, sorted."""
    return sorted(p.stem for p in HERE.glob("bench_*.py"))


def _select(names: list[str]) -> list[str]:
    available = discover()
    if not names:
        return available
    chosen = []
    for name in names:
        mod = name if name.startswith("bench_") else f"bench_{name}"
        mod = mod.removesuffix(".py")
        if mod not in available:
            raise SystemExit(f"unknown benchmark '{name}'; valid: "
                             f"{[n.removeprefix('bench_') for n in available]}")
        chosen.append(mod)
    return chosen


def run_module(name: str, *, timeout: float | None = None) -> tuple[dict, str]:
    """Run ``bench.<name>.run()`` in a child process; return (figures, status)."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "result.json"
        t0 = time.perf_counter()
        try:
            proc = subprocess.run([sys.executable, "-c", _CHILD, name, str(out)], cwd=ROOT,
                                  timeout=timeout)
        except subprocess.TimeoutExpired:
            return {}, f"timeout after {timeout:.0f} s"
        wall = time.perf_counter() - t0
        if proc.returncode != 0 or not out.exists():
            return {}, f"failed (exit code {proc.returncode}) after {wall:.0f} s"
        return json.loads(out.read_text()), f"ok in {wall:.0f} s"


def _fmt(value) -> str:
    if isinstance(value, bool) or value is None:
        return str(value)
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


def format_table(results: dict[str, tuple[dict, str]]) -> str:
    """One row per figure: module, figure, value."""
    rows = [("module", "figure", "value")]
    for mod, (figures, status) in results.items():
        short = mod.removeprefix("bench_")
        rows.append((short, "(status)", status))
        for key, value in figures.items():
            rows.append((short, key, _fmt(value)))
    w0 = max(len(r[0]) for r in rows)
    w1 = max(len(r[1]) for r in rows)
    lines = [f"{a:<{w0}}  {b:<{w1}}  {c}" for a, b, c in rows]
    lines.insert(1, "-" * len(lines[0]))
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m bench", description=__doc__.split("\n")[0])
    ap.add_argument("names", nargs="*", help="benchmark modules to run (default: all)")
    ap.add_argument("--json", type=Path, help="also write the figures to this JSON file")
    ap.add_argument("--timeout", type=float, default=None, help="seconds per module")
    args = ap.parse_args(argv)
    results = {}
    for name in _select(args.names):
        print(f"=== {name}", flush=True)
        results[name] = run_module(name, timeout=args.timeout)
        print(f"=== {name}: {results[name][1]}", flush=True)
    print()
    print(format_table(results))
    if args.json:
        sys.path.insert(0, str(ROOT))
        from flexpipe._io import write_text_atomic

        write_text_atomic(args.json, json.dumps(
            {k: {"status": s, "figures": f} for k, (f, s) in results.items()}, indent=2))
    return 0 if all(s.startswith("ok") for _, s in results.values()) else 1


if __name__ == "__main__":
    sys.exit(main())
