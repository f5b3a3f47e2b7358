"""flexpipe: meshed car body -> FE -> component mode synthesis -> Exudyn flexible body -> full car.

The public API is re-exported here lazily, so ``import flexpipe`` stays fast and a stage
that is not used is never imported.
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

_EXPORTS = {
    "read_mesh": "flexpipe.mesh",
    "Mesh": "flexpipe.mesh",
    "write_mesh": "flexpipe.mesh",
    "MeshWarning": "flexpipe.mesh",
    "Material": "flexpipe.fem",
    "BeamSection": "flexpipe.fem",
    "FEModel": "flexpipe.fem",
    "assemble": "flexpipe.fem",
    "eigenmodes": "flexpipe.fem",
    "Interface": "flexpipe.reduction",
    "reduce": "flexpipe.reduction",
    "FlexBody": "flexpipe.reduction",
    "load_body": "flexpipe.reduction",
    "load_car": "flexpipe.vehicle",
    "simulate": "flexpipe.vehicle",
    "compare": "flexpipe.vehicle",
    "Result": "flexpipe.vehicle",
    "kc": "flexpipe.vehicle.suspension.kc",
    "BodyMotion": "flexpipe.vehicle.result",
    "recover_stress": "flexpipe.durability",
    "FatigueMaterial": "flexpipe.durability",
    "sweep": "flexpipe.sweeps",
    "load_sweep": "flexpipe.sweeps",
    "FlexpipeError": "flexpipe.errors",
    "InputError": "flexpipe.errors",
    "MeshError": "flexpipe.errors",
    "ModelError": "flexpipe.errors",
    "SolverError": "flexpipe.errors",
}

__all__ = sorted(_EXPORTS) + ["__version__"]


def __getattr__(name):
    if name in _EXPORTS:
        return getattr(importlib.import_module(_EXPORTS[name]), name)
    raise AttributeError(f"module 'flexpipe' has no attribute {name!r}")


def __dir__():
    return __all__
