"""Reduction stage: component mode synthesis (Craig-Bampton, residual flexibility, modal
truncation) of an FE model with interfaces into a :class:`~flexpipe.flexbody.FlexBody`.

``reduce(fe, interfaces, method=..., n_modes=..., f_max=...)`` is the entry point;
:mod:`flexpipe.reduction.cms` holds the matrix-level bases.
"""

from flexpipe.flexbody.body import FlexBody, load_body
from flexpipe.reduction.interface import Interface
from flexpipe.reduction.reduce import adams_damping, mac, reduce

__all__ = ["FlexBody", "Interface", "adams_damping", "load_body", "mac", "reduce"]
