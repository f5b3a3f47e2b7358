"""Mesh stage: the Mesh data object and readers for the formats users have."""

from flexpipe.mesh.mesh import CellBlock, Mesh, PointMass, RigidLink

__all__ = ["CellBlock", "Mesh", "PointMass", "RigidLink"]
