"""Mesh stage: the Mesh data object and readers/writers for the formats users have."""

from flexpipe.mesh.mesh import CellBlock, Interpolation, Mesh, PointMass, RigidLink
from flexpipe.mesh.read import read_mesh
from flexpipe.mesh.validate import MeshWarning
from flexpipe.mesh.write import write_mesh

__all__ = ["CellBlock", "Interpolation", "Mesh", "MeshWarning", "PointMass", "RigidLink",
           "read_mesh", "write_mesh"]
