"""Sweeps at scale: many roads, speeds, bodies and car variants from one spec, run on
dask.distributed (a local cluster or an existing one), with resumable Parquet results.

Public API: :func:`sweep`, :func:`load_sweep`, :class:`SweepResult`; ISO 2631-1 ride
weightings in :mod:`flexpipe.sweeps.iso2631`.  See ``docs/sweeps.md``.
"""

from __future__ import annotations

import importlib

_EXPORTS = {
    "sweep": "flexpipe.sweeps.execute",
    "SweepResult": "flexpipe.sweeps.execute",
    "load_sweep": "flexpipe.sweeps.spec",
    "SweepSpec": "flexpipe.sweeps.spec",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name):
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'flexpipe.sweeps' has no attribute {name!r}")


def __dir__():
    return __all__
