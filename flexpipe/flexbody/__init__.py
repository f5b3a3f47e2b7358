"""FlexBody stage: the reduced flexible body (flexpipe's modal neutral file), its inertia
invariants and its ``.npz`` storage."""

from flexpipe.flexbody.body import BodyInterface, FlexBody, load_body
from flexpipe.flexbody.invariants import FFRFInvariants, ffrf_invariants, mass_properties

__all__ = ["BodyInterface", "FFRFInvariants", "FlexBody", "ffrf_invariants", "load_body",
           "mass_properties"]
