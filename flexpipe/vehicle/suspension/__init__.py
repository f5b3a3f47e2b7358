"""Suspension linkages from hardpoints: data model, templates, kinematics, K&C rig.

``templates`` builds a :class:`~flexpipe.vehicle.suspension.model.CornerLinkage` (parts,
joints, links, bushings, spring/damper/stops) from Adams/Car-style hardpoints;
``kinematics`` solves its pose for a wheel and rack travel (and the static compliance
with bushings); ``kc`` runs the suspension analyses of a K&C rig; ``spec`` reads the
``[suspension.*]`` tables of a car file.  Public entry points are re-exported lazily.
"""

from __future__ import annotations

from flexpipe._lazy import lazy_exports

_EXPORTS = {
    "kc": "flexpipe.vehicle.suspension.kc",
    "KCResult": "flexpipe.vehicle.suspension.kc",
    "load_suspension": "flexpipe.vehicle.suspension.spec",
    "Suspension": "flexpipe.vehicle.suspension.spec",
    "build": "flexpipe.vehicle.suspension.templates",
    "double_wishbone": "flexpipe.vehicle.suspension.templates",
    "macpherson": "flexpipe.vehicle.suspension.templates",
    "multi_link": "flexpipe.vehicle.suspension.templates",
    "spring_preload": "flexpipe.vehicle.suspension.statics",
    "wheel_rate": "flexpipe.vehicle.suspension.statics",
}

__getattr__, __dir__, __all__ = lazy_exports(__name__, _EXPORTS)
