"""Static corner quantities: spring preload for a wheel load and wheel rates.

The preload follows from virtual work at the design position: with s the wheel-centre
travel, MR = -dL/ds of the spring and dz_i/ds of every part's centre of mass,
``preload * MR = wheel_load * dz_patch/ds - sum(m_i g dz_i/ds)``.
The wheel rate including compliance is d(rig force)/ds from compliance solves (bushings,
compliant links, spring, stops), so bushing torsion and compliance enter as they do on a
K&C rig; the kinematic wheel rate is spring rate x motion ratio^2 (joints rigid).

Two loads set a spring's preload: time runs (and ``flexpipe info``'s "static" figures)
preload every spring for the static tyre load of the car's mass distribution
(:func:`preloaded`), so the car rests at its design position; the K&C rig (``flexpipe
kc``) uses the file's spring ``free_length_m`` / ``preload_N`` or the axle's
``wheel_load_N`` (:func:`rig_corner`).
Force compliance at the contact patch is in :mod:`flexpipe.vehicle.suspension.kc`.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from flexpipe.errors import InputError
from flexpipe.vehicle.suspension.kinematics import G, Linkage, solve_compliance, solve_kinematics
from flexpipe.vehicle.suspension.metrics import rates
from flexpipe.vehicle.suspension.model import CornerLinkage


def spring_preload(corner: CornerLinkage, wheel_load: float, *, g: float = G) -> float:
    """Spring force (N, compression > 0) that holds the design position under ``wheel_load``.

    Parameters
    ----------
    corner : CornerLinkage
        The corner (its spring is the first ``spring`` force element).
    wheel_load : float
        Vertical tyre force at the contact patch (N).
    g : float
        Gravity (m/s^2) acting on the linkage's parts.
    """
    spring = corner.spring()
    if spring is None:
        raise InputError(f"corner {corner.corner} has no spring to preload")
    lk = Linkage(corner)
    pose = solve_kinematics(lk, 0.0)
    r = rates(lk, pose)
    masses = np.array([p.mass for p in corner.parts])
    work = wheel_load * r["patch_velocity"][2] - g * masses @ r["part_dz"]
    return float(work / r["spring_mr"])


def with_preload(corner: CornerLinkage, preload: float) -> CornerLinkage:
    """``corner`` whose spring free length gives ``preload`` (N) at the design length."""
    forces = []
    for f in corner.forces:
        if f.kind == "spring":
            if f.table is not None:
                comp = float(np.interp(preload, f.table[1], f.table[0]))
            else:
                comp = preload / f.rate
            f = replace(f, free_length=f.design_length + comp)
        forces.append(f)
    return replace(corner, forces=tuple(forces))


def wheel_rate(corner: CornerLinkage, travel: float = 0.0, *, h: float = 5e-4,
               carrier=None, mode: str = "symmetric") -> float:
    """Vertical wheel-centre rate (N/m) at ``travel``, including compliance: central
    difference of the rig force from compliance solves (bushings, compliant links, spring
    with its preload, stops; the subframe ``carrier`` of
    :func:`~flexpipe.vehicle.suspension.carrier.half_carrier` in parallel travel, or in
    opposite travel with ``mode="antisymmetric"``)."""
    lk = Linkage(corner, carrier=carrier, mode=mode)
    f = [solve_compliance(lk, s).force for s in (travel - h, travel + h)]
    return (f[1] - f[0]) / (2 * h)


def kinematic_corner(corner: CornerLinkage) -> CornerLinkage:
    """``corner`` as the time runs' kinematic mode has it: every bushing replaced by the
    joint it surrounds, every link rigid (:mod:`flexpipe.exu.linkage`)."""
    return replace(corner, joints=tuple(replace(j, bushing=None) for j in corner.joints),
                   links=tuple(replace(k, axial_stiffness=None) for k in corner.links))


def corner_figures(corner: CornerLinkage, *, carrier=None) -> dict:
    """Spring figures of ``corner`` as preloaded, at the design position.

    Returns
    -------
    dict
        ``"spring preload [N]"`` (spring force, compression > 0), ``"spring motion ratio
        [-]"``, ``"kinematic wheel rate [N/m]"`` (spring rate x motion ratio^2, joints
        rigid: the K&C rig's column of that name) and ``"wheel rate incl. compliance
        [N/m]"`` (:func:`wheel_rate`: bushings, the preloaded spring's geometric stiffness
        and stops included; the K&C rig's wheel rate) and ``"wheel rate, joints rigid
        [N/m]"`` (the same with every bushing its joint and every link rigid: the wheel
        rate of the time runs' kinematic mode; the preloaded spring's geometric stiffness
        and the stops still in).
    """
    sp = corner.spring()
    if sp is None:
        raise InputError(f"corner {corner.corner} has no spring")
    lk = Linkage(corner)
    mr = rates(lk, solve_kinematics(lk, 0.0))["spring_mr"]
    return {"spring preload [N]": sp.static_force(sp.design_length),
            "spring motion ratio [-]": float(mr),
            "kinematic wheel rate [N/m]": float(sp.rate * mr**2),
            "wheel rate incl. compliance [N/m]": wheel_rate(corner, carrier=carrier),
            "wheel rate, joints rigid [N/m]": wheel_rate(kinematic_corner(corner))}


def rig_corner(axle, corner: CornerLinkage) -> CornerLinkage:
    """``corner`` of ``axle`` as the K&C rig (``flexpipe kc``) holds it: the spring keeps
    the free length the file gives (``free_length_m`` or ``preload_N``), else is preloaded
    (virtual work) for the axle's ``wheel_load_N``, else is unloaded at the design
    position.  Time runs ignore all three: :func:`preloaded` holds the design position
    under the static loads of the car's mass distribution."""
    spring = corner.spring()
    if spring is None or spring.free_length is not None or axle.wheel_load is None:
        return corner
    return with_preload(corner, spring_preload(corner, axle.wheel_load))


def rig_suspension(suspension):
    """``suspension`` with the wheels the car file gives (``Suspension.wheels``) in the
    knuckles, as on the K&C rig: the rig's preload for ``wheel_load_N`` (a tyre load)
    then allows for the wheel's weight as a time run's preload does."""
    none = (0.0, np.zeros((3, 3)))
    return with_wheels(suspension, {c: suspension.wheels.get(c, none)
                                    for c in suspension.corners()})


def preloaded(suspension, wheel_loads: dict, *, g: float = G):
    """``suspension`` with every spring preloaded for its corner's static wheel load.

    Parameters
    ----------
    suspension : Suspension
    wheel_loads : dict
        ``{"fl": N, ...}`` vertical tyre loads at rest (N).
    """
    axles = {}
    for name, a in suspension.axles.items():
        left = with_preload(a.left, spring_preload(a.left, wheel_loads[a.left.corner], g=g))
        right = with_preload(a.right, spring_preload(a.right, wheel_loads[a.right.corner],
                                                     g=g))
        axles[name] = replace(a, left=left, right=right)
    return replace(suspension, axles=axles)


def with_wheels(suspension, wheels: dict):
    """``suspension`` whose knuckles carry the wheels (rim + tyre) at the wheel centres.

    ``wheels`` is ``{"fl": (mass_kg, inertia 3x3 about the wheel centre), ...}``; the
    knuckle's mass, centre of mass and inertia become those of knuckle plus wheel, so the
    spring preload (virtual work) and the multibody model both see the wheel's weight.
    """
    axles = {}
    for name, a in suspension.axles.items():
        sides = []
        for c in (a.left, a.right):
            mw, Jw = wheels[c.corner]
            parts = []
            for p in c.parts:
                if p.name == c.knuckle and mw > 0:
                    w = np.asarray(c.wheel_center, float)
                    m = p.mass + mw
                    cm = (p.mass * p.cm + mw * w) / m
                    dk, dw = p.cm - cm, w - cm
                    J = (p.inertia + p.mass * (dk @ dk * np.eye(3) - np.outer(dk, dk))
                         + np.asarray(Jw, float) + mw * (dw @ dw * np.eye(3) - np.outer(dw, dw)))
                    p = replace(p, mass=m, cm=cm, inertia=J)
                parts.append(p)
            sides.append(replace(c, parts=tuple(parts)))
        axles[name] = replace(a, left=sides[0], right=sides[1])
    return replace(suspension, axles=axles)


def point_masses(suspension) -> list:
    """``[(mass, position)]`` of every part of the suspension (body coordinates at design):
    the corners' parts (with the wheels when :func:`with_wheels` put them in), the rack at
    the middle of its mounts and each anti-roll-bar arm at the middle of its arm."""
    from flexpipe.vehicle.suspension.model import ARB_ARM_MASS, RACK_MASS

    out = [(p.mass, np.asarray(p.cm, float)) for c in suspension.corners().values()
           for p in c.parts]
    if suspension.rack is not None:
        out.append((RACK_MASS, np.mean([np.asarray(v, float)
                                        for v in suspension.rack.mounts.values()], axis=0)))
    for a in suspension.axles.values():
        arb = a.anti_roll_bar
        if arb is not None:
            for side in (1.0, -1.0):
                S = np.array([1.0, side, 1.0])
                out.append((ARB_ARM_MASS, S * 0.5 * (arb.bushing + arb.arm_end)))
    return out
