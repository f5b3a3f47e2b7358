"""Start a run in static equilibrium: the whole car settled at rest before t = 0.

A car built at its design position is in vertical equilibrium on rigid parts only: a
flexible body starts undeformed and rings in its modes (measured on the linkage sample,
parked: 300-820 N hub-force peaks in the first 10 ms), and horizontal forces that the
geometry and the steering column carry at rest build up during the first second.
:func:`settled_start` finds the static state by dynamic relaxation: the same car, parked on
the same road, integrated for :data:`SETTLE_T_S` with a coarse step and the integrator's
largest numerical damping (generalized-alpha, spectral radius 0).  The run then starts
from those coordinates (body deflection, part positions, steering, tyre deflections) with
its own velocities, and, for a parked run, with the settled tyre relaxation states.
"""

from __future__ import annotations

import copy
import dataclasses

import numpy as np

#: simulated settling time (s), step (s) and spectral radius of the pre-run
SETTLE_T_S = 1.0
SETTLE_H_S = 4e-3
SETTLE_SPECTRAL_RADIUS = 0.0


def settled_start(build, make_system, make_controller):
    """Coordinates and tyre relaxation states of the car of ``build`` settled at rest.

    Parameters
    ----------
    build : flexpipe.exu.car.CarBuild
        The run's build; the pre-run uses it with zero speed and rates.
    make_system : callable
        ``make_system(build) -> CarSystem``.
    make_controller : callable
        ``make_controller(system, *, target_speed, h, t_end, parked) -> CarController``.

    Returns
    -------
    (ndarray, dict, float) or None
        The settled coordinates, relaxation states and the pre-run's CPU time (s); None if
        the pre-run failed (the run then starts at the design position, as without
        settling).
    """
    parked = dataclasses.replace(build, speed=0.0, spin_rate=np.zeros_like(build.spin_rate),
                                 body_rates=np.zeros(3))
    system = make_system(parked)
    ctrl = make_controller(system, target_speed=0.0, h=SETTLE_H_S, t_end=SETTLE_T_S,
                           parked=True)
    ok, _t, cpu, *_ = system.run(ctrl, t_end=SETTLE_T_S, h=SETTLE_H_S,
                                 spectral_radius=SETTLE_SPECTRAL_RADIUS)
    if not ok or ctrl.status < 0:
        return None
    return system.coordinates(), copy.deepcopy(ctrl.tires.state), cpu
