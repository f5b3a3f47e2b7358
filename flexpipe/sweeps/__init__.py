"""Sweeps at scale: many roads, speeds, bodies and car variants from one spec, run on
dask.distributed (a local cluster or an existing one), with resumable Parquet results.

Public API: :func:`sweep`, :func:`load_sweep`, :class:`SweepResult`; ISO 2631-1 ride
weightings in :mod:`flexpipe.sweeps.iso2631`.  See ``docs/sweeps.md``.
"""

from __future__ import annotations

from flexpipe._lazy import lazy_exports

_EXPORTS = {
    "sweep": "flexpipe.sweeps.execute",
    "SweepResult": "flexpipe.sweeps.execute",
    "load_sweep": "flexpipe.sweeps.spec",
    "SweepSpec": "flexpipe.sweeps.spec",
}

__getattr__, __dir__, __all__ = lazy_exports(__name__, _EXPORTS)
