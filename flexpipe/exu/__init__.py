"""Exudyn adapters: the only place in flexpipe that imports exudyn.

``flexpipe.exu.body``: :func:`add_flexible_body` (ObjectFFRFreducedOrder with a
MarkerSuperElementRigid per interface) and :func:`add_rigid_twin`.  Import the
submodules directly; importing this package does not import exudyn.
"""
