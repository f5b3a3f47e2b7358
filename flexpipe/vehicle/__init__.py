"""Full car: TOML car spec, body reduction (cached), rigid / flexible / full body
simulation on Exudyn with tyres, road and driver, results and comparisons.

Public API: :func:`load_car`, :func:`simulate`, :func:`compare`, :class:`Result`.
Submodules are imported lazily so that ``load_car`` does not pull in Exudyn.
"""

from __future__ import annotations

import importlib

_EXPORTS = {
    "load_car": "flexpipe.vehicle.spec",
    "Car": "flexpipe.vehicle.spec",
    "simulate": "flexpipe.vehicle.simulation",
    "compare": "flexpipe.vehicle.result",
    "Result": "flexpipe.vehicle.result",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name):
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'flexpipe.vehicle' has no attribute {name!r}")


def __dir__():
    return __all__
