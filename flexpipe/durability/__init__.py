"""Durability and post-processing of flexible-body runs.

* :mod:`~flexpipe.durability.recover` - modal stress recovery (:func:`recover_stress`).
* :mod:`~flexpipe.durability.fatigue` - rainflow counting, Basquin S-N, Miner damage.
* :mod:`~flexpipe.durability.report` - hot-spot table, max-stress ``.vtu`` and PNG.
* :mod:`~flexpipe.durability.animate` - ParaView ``.pvd`` animation of the deformed body.
"""

from flexpipe.durability.fatigue import (
    FatigueMaterial,
    miner_damage,
    rainflow_cycles,
)
from flexpipe.durability.recover import StressResult, recover_stress

__all__ = ["FatigueMaterial", "StressResult", "miner_damage", "rainflow_cycles",
           "recover_stress"]
