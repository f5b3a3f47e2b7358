"""Linkage cars' set-up between the car file and the Exudyn model.

* :func:`reduce_car_body`: the reduced flexible body with its interfaces at the four
  corner hardpoints, or for a linkage car at every suspension mount.
* :func:`body_mounts`: those mounts as :class:`~flexpipe.vehicle.mounts.Mount` ties.
* :func:`linkage_statics`: the suspension with the wheels in the knuckles and springs
  preloaded for the static wheel loads of the true mass distribution.
"""

from __future__ import annotations

import math

import numpy as np

from flexpipe.errors import InputError
from flexpipe.vehicle import bodymodel
from flexpipe.vehicle.corners import GRAVITY
from flexpipe.vehicle.spec import CORNERS, Car

#: Craig-Bampton cut-off of the "full" body, Hz (all fixed-interface modes below it)
FULL_CUTOFF_HZ = 250.0
#: interface reduction of a body with every suspension mount an interface: characteristic
#: constraint modes up to this frequency (Hz), see flexpipe.reduction.ccmodes
INTERFACE_F_MAX_HZ = 400.0
#: body nodes within this distance of a suspension mount are tied to it (RBE2), m
MOUNT_RADIUS_M = 0.005
#: interface DOFs of every mount unless ``[body.mounts.<name>] dofs`` says otherwise;
#: None: 6 where a moment passes into the body, else 3 (``Suspension.mount_dofs``).  A
#: joint at a 3-DOF mount that needs a frame (an inline joint) takes the body frame's
#: axes through a bracket (flexpipe.exu.linkage_car).
MOUNT_DOFS = None


def interface_band(car: Car, *, full: bool = False) -> float:
    """Top (Hz) of the characteristic constraint modes that replace a linkage car's mount
    static modes: the car file's ``[body] interface_band_hz``, else
    :data:`INTERFACE_F_MAX_HZ`; ``inf`` (``"all"``, and always for a ``full`` body) keeps
    every CC mode, i.e. the span of every static mode, plus the inertia vectors of the
    interface reduction (plain Craig-Bampton without them has the trimmed body's
    free-free frequencies 2 % high, ``bench/bench_mounts.py``)."""
    band = car.body.interface_band_hz
    if full:
        return math.inf
    return INTERFACE_F_MAX_HZ if band is None else float(band)


def reduce_car_body(car: Car, *, f_max: float, cache: bool = True, log=None,
                    full: bool = False):
    """The car's reduced flexible body for band ``f_max`` (Hz): interfaces at the four
    corner hardpoints, or for a linkage car at every suspension mount
    (:func:`body_mounts`, interface reduction to :func:`interface_band`).  A ``full`` body
    keeps every fixed-interface mode to :data:`FULL_CUTOFF_HZ` and every static mode.
    Returns ``(FlexBody, info)`` as :func:`flexpipe.vehicle.bodymodel.reduced_body`."""
    cutoff = FULL_CUTOFF_HZ if full else None
    kw = {}
    if car.suspension is not None:  # every body-side mount an interface of the body
        kw = {"mounts": body_mounts(car), "interface_f_max": interface_band(car, full=full)}
    return bodymodel.reduced_body(car, f_max=f_max, cache=cache, cutoff=cutoff,
                                  log=log or (lambda *a: None), **kw)


def body_mounts(car: Car) -> list:
    """The body's interfaces for a linkage car: every suspension mount, tied as
    ``[body.mounts.<name>]`` says (point + radius, node set or the mesh file's node ids,
    ``Mount.node_ids``, checked against the mesh by ``check_run`` and again when it is
    reduced) or else the nodes
    within :data:`MOUNT_RADIUS_M` of the mount point; :data:`MOUNT_DOFS` DOF unless the car
    file says otherwise (``None``: 6 where a joint or bushing needs the mount's frame, else
    3, ``Suspension.mount_dofs``); and every powertrain mount of ``[drive]
    reaction_mounts``, ``[powertrain]`` or ``[subframe.*]`` mounts at its ``point_m``, 3
    DOF unless its table says otherwise; not the suspension mounts a subframe carries."""
    from flexpipe.vehicle.mounts import Mount

    points = car.suspension.mounts()
    dofs = car.suspension.mount_dofs()
    if MOUNT_DOFS is not None:
        dofs = dict.fromkeys(dofs, MOUNT_DOFS)
    given = car.body.mounts or {}
    carried = {n for s in car.subframes for n in s.carries}  # on a subframe, not the body
    extra = car.drive.reaction_mounts + tuple(n for b in car.mounted_bodies for n in b.mounts)
    points = {**{n: p for n, p in points.items() if n not in carried},
              **{n: given[n]["point"] for n in extra}}
    dofs = {**dofs, **dict.fromkeys(extra, 3)}  # forces only; 6 where the table says
    for name in given:
        if name not in points:
            raise InputError(f"[body.mounts] names '{name}', which is no mount of this car's "
                             f"suspension; valid: {', '.join(points)}", file=car.file,
                             key=f"body.mounts.{name}")
    out = []
    for name, p in points.items():
        g = given.get(name, {})
        tie = g.get("node_set") is not None or g.get("node_ids") is not None
        source = (car.file, g.get("line"), f"body.mounts.{name}") if name in given else None
        out.append(Mount(name, tuple(g["point"]) if g.get("point") is not None else tuple(p),
                         radius=g.get("radius") or (None if tie else MOUNT_RADIUS_M),
                         dofs=g.get("dofs") or dofs[name], node_set=g.get("node_set"),
                         node_ids=g.get("node_ids"), source=source))
    return out


def linkage_statics(car: Car, rb):
    """Suspension of a linkage car ready to run and its static wheel loads (4,) N.

    The knuckles carry the wheels; the static loads follow from the whole car's mass
    distribution (body, every part at its centre of mass, rack, anti-roll-bar arms, a
    powertrain or subframe on mounts) and
    every spring is preloaded (virtual work) to hold the design position under them.
    """
    from flexpipe.vehicle.corners import static_wheel_loads
    from flexpipe.vehicle.suspension.statics import point_masses, preloaded, with_wheels

    susp = with_wheels(car.suspension, car.suspension.wheels)  # load_car requires all four
    pm = point_masses(susp)  # + powertrain and subframes: on mounts, not in the body
    pm += [(b.mass, np.asarray(b.center_of_mass)) for b in car.mounted_bodies]
    N = static_wheel_loads(car, rb.mass, rb.center_of_mass, g=GRAVITY, point_masses=pm)
    return preloaded(susp, dict(zip(CORNERS, N, strict=True)), g=GRAVITY), N
