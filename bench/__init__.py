"""Benchmarks (``make bench``): timings and memory on large models, not timed tests.

Every ``bench/bench_*.py`` module exposes ``run() -> dict`` returning its figures
(name -> number, bool or str).  ``python -m bench [name ...]`` runs them, each in its own
process, and prints one table.
"""

import flexpipe.exu  # noqa: E402,F401  (Exudyn's module as flexpipe chooses it, before any bench imports exudyn)
