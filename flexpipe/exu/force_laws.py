"""Suspension force elements as Exudyn symbolic user functions: inside every Newton step.

A spring, damper or stop (:class:`flexpipe.vehicle.suspension.model.ForceElement`) acts
along the line between its seats through an ``ObjectConnectorSpringDamper`` whose force
law is an Exudyn *symbolic* user function: an expression tree that Exudyn evaluates in
C++ at every Newton iteration, so the element's nonlinearity (table, dual-rate damper,
stop contact) is met where the implicit integrator balances the forces, with no Python
call during the run.  Tables are interpolated as :func:`numpy.interp` does (linear,
clamped at the ends), written as a sum of clipped segments::

    f(x) = y_0 + sum_k s_k (min(max(x, x_k), x_{k+1}) - x_k),  s_k = slope of segment k

A bushing with nonlinear force-deflection tables gets the same treatment
(:func:`bushing_law`, the ``springForceTorqueUserFunction`` of its
``ObjectConnectorRigidBodySpringDamper``); a linear bushing keeps Exudyn's own law.

``tests/test_force_laws.py`` checks every law against the element's own NumPy methods
(:meth:`ForceElement.static_force`, :meth:`ForceElement.damper_force`,
:meth:`Bushing.force`).
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


def symbolic_law(mbs, *elements):
    """The force law of one element, or the sum of several acting between the same two
    seats (same design length), as an Exudyn symbolic user function (keep it alive for
    the lifetime of the system: it owns the expression tree).

    Elements between the same seats share one connector (:func:`seat_groups`): their
    forces act along the same line and depend on the same length change and rate, so
    the connector's force is the sum of theirs, and the body's marker at the seat is
    evaluated once per Newton iteration instead of once per element.
    """
    if not elements:
        raise ValueError("symbolic_law needs at least one force element")
    lengths = {round(float(f.design_length), 12) for f in elements}
    if len(lengths) != 1:
        raise ValueError("elements summed into one law must share their seats; design "
                         f"lengths {sorted(lengths)} m differ")
    laws = [_law(f) for f in elements]
    if len(laws) == 1:
        law = laws[0]
    else:
        def law(mbs, t, item, u, v, k, d, f0):
            out = laws[0](mbs, t, item, u, v, k, d, f0)
            for other in laws[1:]:
                out = out + other(mbs, t, item, u, v, k, d, f0)
            return out
    return CreateSymbolicUserFunction(mbs, law, "springForceUserFunction",
                                      itemTypeName=_ITEM)


def seat_groups(elements) -> list:
    """The force elements grouped by their seats (the body mount, and the part with its
    point), in the order of first appearance: each group is one connector."""
    groups: dict = {}
    for f in elements:
        key = (f.mount, f.part, tuple(round(float(x), 9) for x in f.point))
        groups.setdefault(key, []).append(f)
    return list(groups.values())


def bushing_law(mbs, bushing):
    """A bushing with nonlinear tables (:class:`flexpipe.vehicle.suspension.model.Bushing`)
    as the symbolic ``springForceTorqueUserFunction`` of an
    ``ObjectConnectorRigidBodySpringDamper``: per direction of the bushing frame the
    table's force (or the linear rate) of the deflection plus the linear damping, as
    Exudyn's own linear law ``K (displacement, rotation) + D (velocity, angular
    velocity)`` does without tables."""
    from flexpipe.vehicle.suspension.model import BUSHING_DOFS

    k = [float(v) for v in bushing.stiffness]
    c = [float(v) for v in bushing.damping]
    tables = {BUSHING_DOFS.index(d): t for d, t in bushing.tables.items()}

    def law(mbs, t, item, displacement, rotation, velocity, angular_velocity, stiffness,
            damping, rot0, rot1, offset):
        x = [displacement[0], displacement[1], displacement[2],
             rotation[0], rotation[1], rotation[2]]
        v = [velocity[0], velocity[1], velocity[2],
             angular_velocity[0], angular_velocity[1], angular_velocity[2]]
        out = []
        for i in range(6):
            f = interp(x[i], *tables[i]) if i in tables else k[i] * x[i]
            out.append(f + c[i] * v[i])
        return out

    return CreateSymbolicUserFunction(mbs, law, "springForceTorqueUserFunction",
                                      itemTypeName="ObjectConnectorRigidBodySpringDamper")
