"""Full car: TOML car spec, body reduction (cached), rigid / flexible / full body
simulation on Exudyn with tyres, road and driver, results and comparisons.

Public API: :func:`load_car`, :func:`simulate`, :func:`compare`, :class:`Result`,
:func:`load_result`.
Submodules are imported lazily so that ``load_car`` does not pull in Exudyn.
"""

from __future__ import annotations

from flexpipe._lazy import lazy_exports

_EXPORTS = {
    "load_car": "flexpipe.vehicle.spec",
    "Car": "flexpipe.vehicle.spec",
    "simulate": "flexpipe.vehicle.simulation",
    "compare": "flexpipe.vehicle.result",
    "Result": "flexpipe.vehicle.result",
    "load_result": "flexpipe.vehicle.export",
}

__getattr__, __dir__, __all__ = lazy_exports(__name__, _EXPORTS)
