"""Reduction stage: component mode synthesis (Craig-Bampton, residual flexibility, modal
truncation) of an FE model with interfaces into a :class:`FlexBody`."""
