"""flexpipe: meshed car body -> FE -> component mode synthesis -> Exudyn flexible body -> full car.

The public API is re-exported here lazily, so ``import flexpipe`` stays fast and a stage
that is not used is never imported.
"""

from __future__ import annotations

from flexpipe._lazy import lazy_exports

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
    "load_road": "flexpipe.roads",
    "simulate": "flexpipe.vehicle",
    "compare": "flexpipe.vehicle",
    "Result": "flexpipe.vehicle",
    "load_result": "flexpipe.vehicle",
    "kc": "flexpipe.vehicle.suspension.kc",
    "linear_modes": "flexpipe.vehicle.linear",
    "LinearModes": "flexpipe.vehicle.linear",
    "ride_response": "flexpipe.vehicle.linear_ride",
    "RideResponse": "flexpipe.vehicle.linear_ride",
    "ride_vs_speed": "flexpipe.vehicle.linear_ride",
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

__getattr__, __dir__, __all__ = lazy_exports(__name__, _EXPORTS, extra=("__version__",))
