"""Finite-element stage: materials, element families, assembly, eigenmodes."""

from flexpipe.fem.assemble import BeamSection, assemble
from flexpipe.fem.material import Material
from flexpipe.fem.model import FEModel
from flexpipe.fem.modes import eigenmodes

__all__ = ["BeamSection", "FEModel", "Material", "assemble", "eigenmodes"]
