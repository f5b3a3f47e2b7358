"""Suspension force elements as Exudyn symbolic user functions: inside every Newton step.

A spring, damper or stop (:class:`flexpipe.vehicle.suspension.model.ForceElement`) acts
along the line between its seats through an ``ObjectConnectorSpringDamper`` whose force
law is an Exudyn *symbolic* user function: an expression tree that Exudyn evaluates in
C++ at every Newton iteration, so the element's nonlinearity (table, dual-rate damper,
stop contact) is met where the implicit integrator balances the forces, with no Python
call during the run.  Tables are interpolated as :func:`numpy.interp` does (linear,
clamped at the ends), written as a sum of clipped segments::

    f(x) = y_0 + sum_k s_k (min(max(x, x_k), x_{k+1}) - x_k),  s_k = slope of segment k

``tests/test_force_laws.py`` checks every law against the element's own NumPy methods.
"""

from __future__ import annotations

import exudyn as exu
from exudyn.advancedUtilities import CreateSymbolicUserFunction

_esym = exu.symbolic
#: Exudyn item type whose user function the laws implement
_ITEM = "ObjectConnectorSpringDamper"


def interp(x, xs, ys):
    """``numpy.interp(x, xs, ys)`` for a symbolic ``x`` (or a float)."""
    out = float(ys[0])
    for k in range(len(xs) - 1):
        x0, x1 = float(xs[k]), float(xs[k + 1])
        slope = (float(ys[k + 1]) - float(ys[k])) / (x1 - x0)
        out = out + slope * (_esym.min(_esym.max(x, x0), x1) - x0)
    return out


def _law(f):
    """Python form of the element's Exudyn force (tension > 0) as a function of the
    length change ``u`` from the design length and its rate ``v``."""
    L0 = f.design_length
    zero = _esym.Real(0.0)
    if f.kind == "damper":
        xs, ys = f.table

        def law(mbs, t, item, u, v, k, d, f0):
            return interp(v, xs, ys)  # resists extension: tension while extending
    elif f.kind == "spring":
        free = f.free_length if f.free_length is not None else L0
        if f.table is not None:
            xs, ys = f.table

            def law(mbs, t, item, u, v, k, d, f0):
                return -interp(free - L0 - u, xs, ys)
        else:
            rate = float(f.rate)

            def law(mbs, t, item, u, v, k, d, f0):
                return -rate * (free - L0 - u)
    elif f.kind == "bump_stop":
        xs, ys = f.table
        c = float(f.clearance)

        def law(mbs, t, item, u, v, k, d, f0):
            dd = -c - u  # compression beyond the clearance
            return _esym.IfThenElse(dd > 0, -interp(dd, xs, ys), zero)
    else:  # rebound stop
        xs, ys = f.table
        c = float(f.clearance)

        def law(mbs, t, item, u, v, k, d, f0):
            dd = u - c  # extension beyond the clearance
            return _esym.IfThenElse(dd > 0, interp(dd, xs, ys), zero)
    return law


def symbolic_law(mbs, element):
    """The element's force law as an Exudyn symbolic user function (keep it alive for
    the lifetime of the system: it owns the expression tree)."""
    return CreateSymbolicUserFunction(mbs, _law(element), "springForceUserFunction",
                                      itemTypeName=_ITEM)
