"""Rigid bodies on bushings at body mounts: the powertrain and subframes of a linkage car.

Each moves as one rigid body (mass, centre of mass, inertia) held by bushings at its
mounts, each a ``[body.mounts.<name>]`` table (where the mount sits on the body and which
body nodes it is bolted to; on a flexible body a 3-DOF interface).

* ``[powertrain]``: engine, gearbox and final drive.  The drive torque's reaction
  (``[drive] drive_reaction = "body"``) acts on it, and it passes that, with its own weight
  and inertia, through its mounts: the mount system's six modes are in the car.
* ``[subframe.<name>]``: a cradle that ``carries`` suspension mounts (the arms' bushings,
  the rack housing, the anti-roll bar's bearings), which then load it instead of the body;
  it passes their forces to the body through its own bushings.

:meth:`MountedBody.stiffness_matrix` is the mounts' 6x6 stiffness at the centre of mass
(body held); :meth:`MountedBody.frequencies` the undamped natural frequencies on the
mounts with the body held, the figures a mount-system layout is judged by.  The file
format is in docs/car-file.md.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy.linalg import eigh

from flexpipe._arrays import frozen_arrays
from flexpipe.vehicle.suspension.kinematics import skew
from flexpipe.vehicle.suspension.model import BUSHING_DOFS

#: deflection (m or rad) about which a nonlinear table's slope counts as its rate
TABLE_SLOPE_STEP = 1e-4


@dataclass(frozen=True)
@frozen_arrays
class MountedBody:
    """A rigid body on bushings (body coordinates at the design position).

    Parameters
    ----------
    mass : float
        kg.
    center_of_mass : ndarray (3,)
        m.
    inertia : ndarray (3, 3)
        About the centre of mass, body axes, kg m^2.
    mounts : tuple of str
        Names of the mounts (``[body.mounts.<name>]``).
    points : ndarray (n, 3)
        Mount points, m.
    bushings : tuple of Bushing
        One per mount (:class:`flexpipe.vehicle.suspension.model.Bushing`).
    name : str
        ``"powertrain"`` or ``"subframe.<name>"`` (the car file's table).
    carries : tuple of str
        Suspension mounts on it instead of on the body (subframes).
    """

    mass: float
    center_of_mass: np.ndarray
    inertia: np.ndarray
    mounts: tuple
    points: np.ndarray
    bushings: tuple
    name: str = "powertrain"
    carries: tuple = ()

    @staticmethod
    def rates(b) -> np.ndarray:
        """The six rates of bushing ``b`` at zero deflection (a table's slope there)."""
        k = np.array(b.stiffness, dtype=float)
        for i, dof in enumerate(BUSHING_DOFS):
            if dof in b.tables:
                x, y = b.tables[dof]
                h = TABLE_SLOPE_STEP
                k[i] = (np.interp(h, x, y) - np.interp(-h, x, y)) / (2 * h)
        return k

    def stiffness_matrix(self) -> np.ndarray:
        """6x6 stiffness of the mounts for a motion ``(u, theta)`` of the centre of mass
        (body axes), the body held: ``sum_j T_j^T K_j T_j`` with ``T_j`` taking it to the
        mount's deflection ``(u + theta x r_j, theta)``."""
        K = np.zeros((6, 6))
        for p, b in zip(self.points, self.bushings, strict=True):
            A = b.frame
            k = self.rates(b)
            Kj = np.zeros((6, 6))
            Kj[:3, :3] = A @ np.diag(k[:3]) @ A.T
            Kj[3:, 3:] = A @ np.diag(k[3:]) @ A.T
            T = np.eye(6)
            T[:3, 3:] = -skew(p - self.center_of_mass)
            K += T.T @ Kj @ T
        return K

    def mass_matrix(self) -> np.ndarray:
        """6x6 mass matrix at the centre of mass."""
        M = np.zeros((6, 6))
        M[:3, :3] = self.mass * np.eye(3)
        M[3:, 3:] = self.inertia
        return M

    def frequencies(self) -> tuple[np.ndarray, np.ndarray]:
        """Natural frequencies (6,) Hz, ascending, and mode shapes (6, 6) (columns
        ``(u, theta)`` at the centre of mass) of the powertrain on its mounts, body held,
        undamped."""
        lam, V = eigh(self.stiffness_matrix(), self.mass_matrix())
        return np.sqrt(np.clip(lam, 0.0, None)) / (2 * np.pi), V


def mount_names(t, key: str) -> list:
    """The list of mount names under ``key`` of table ``t``: non-empty strings, each once."""
    names = t.raw(key)
    if not (isinstance(names, list) and names and all(isinstance(n, str) and n.strip()
                                                      for n in names)):
        raise t.error(key, f"expected a list of mount names (strings), got {names!r}")
    if len(set(names)) < len(names):
        raise t.error(key, "a mount is named more than once: "
                           f"{sorted({n for n in names if names.count(n) > 1})}")
    return names


def mount_points(t, key: str, names, body, suspension) -> np.ndarray:
    """Points (n, 3) of the body mounts ``names`` (listed under ``key`` of table ``t``):
    each a ``[body.mounts.<name>]`` table with ``point_m``, and no suspension mount."""
    given, susp = body.mounts or {}, suspension.mounts()
    points = []
    for n in names:
        if n in susp:
            raise t.error(key, f"'{n}' is a suspension mount; a mount of [{t.name}] needs a "
                               "name of its own (a [body.mounts.<name>] table with point_m)")
        if n not in given:
            raise t.error(key, f"'{n}' has no [body.mounts.{n}] table: give one with point_m "
                               "(where the mount sits on the body, m) and radius_m, node_set "
                               "or node_ids (the body nodes it is bolted to)")
        if given[n].get("point") is None:
            raise t.error(key, f"[body.mounts.{n}] needs point_m: where the mount sits on the "
                               "body (m, body coordinates)")
        points.append(given[n]["point"])
    return np.array(points, dtype=float)


def _read_mounted(t, body, suspension, *, carries=()) -> MountedBody:
    """The rigid body on bushings of table ``t``: mass, centre of mass, inertia,
    ``mounts`` naming ``[body.mounts.<name>]`` tables with a ``point_m``, one
    ``[<table>.bushings.<name>]`` per mount."""
    from flexpipe.vehicle._toml import check_principal_moments
    from flexpipe.vehicle.body_spec import read_inertia
    from flexpipe.vehicle.suspension.spec import read_bushing

    mass = t.number("mass_kg", lo=0, lo_open=True)
    cm = t.vector("center_of_mass_m")
    J = read_inertia(t, "inertia_kg_m2")
    check_principal_moments(t, "inertia_kg_m2", J)
    names = mount_names(t, "mounts")
    points = mount_points(t, "mounts", names, body, suspension)
    bt = t.sub("bushings")
    for n in bt.data:
        if n not in names:
            raise bt.error(n, f"a bushing for '{n}', which is no mount of [{t.name}] "
                              f"mounts ({', '.join(names)})")
    bushings = []
    for n in names:
        if not bt.has(n):
            raise bt.error(None, f"mount '{n}' has no bushing: add [{t.name}.bushings.{n}] "
                                 "with stiffness (6) and damping (6)")
        bushings.append(read_bushing(bt.sub(n)))
    bt.finish()
    t.finish()
    out = MountedBody(mass, cm, J, tuple(names), points, tuple(bushings),
                      name=t.name, carries=tuple(carries))
    lam = np.linalg.eigvalsh(out.stiffness_matrix())
    if lam[0] <= 1e-9 * max(lam[-1], 1e-300):
        raise t.error("mounts", f"the mounts' bushings leave [{t.name}] free to move in "
                                "some direction (their 6x6 stiffness at the centre of mass is "
                                "singular): give rates in every direction, or mounts not on "
                                "one line")
    return out


def read_powertrain(doc, body, suspension, drive) -> MountedBody:
    """``[powertrain]`` of the car document ``doc`` (a :class:`~flexpipe.vehicle._toml.
    Table`).

    Raises
    ------
    InputError
        Naming the file, line and key: a prismatic-corner car, ``[drive]
        reaction_mounts`` as well, a mount without its tables or point, a bushing left
        out or given for no mount, mounts that leave the powertrain free in some
        direction.
    """
    t = doc.sub("powertrain")
    if suspension is None:
        raise t.error(None, "a powertrain on mounts needs a linkage suspension car "
                            "([suspension.*], whose body mounts are tied in [body.mounts]); "
                            "on this prismatic-corner car give its mass as a [[body.mass]]")
    if drive.reaction_mounts:
        raise t.error(None, "[drive] reaction_mounts passes the drive's reaction couple "
                            "quasi-statically; with a [powertrain] on mounts its mounts pass "
                            "it: remove reaction_mounts")
    return _read_mounted(t, body, suspension)


def read_subframes(doc, body, suspension) -> tuple:
    """``[subframe.<name>]`` tables of the car document ``doc``: each a rigid body on
    bushings (as ``[powertrain]``) plus ``carries``, the suspension mounts on it.

    Raises
    ------
    InputError
        As :func:`read_powertrain`, and: a carried name that is no suspension mount, one
        carried twice, or one with a ``[body.mounts]`` table (it is no body mount then).
    """
    st = doc.sub("subframe")
    if suspension is None:
        raise st.error(None, "a subframe carries mounts of a linkage suspension "
                             "([suspension.*]); this car has prismatic corners: remove it")
    susp, given = suspension.mounts(), body.mounts or {}
    seen, out = {}, []
    for name in list(st.data):
        t = st.sub(name)
        carries = mount_names(t, "carries")
        for n in carries:
            if n not in susp:
                raise t.error("carries", f"'{n}' is no mount of this car's suspension; "
                                         f"valid: {', '.join(susp)}")
            if n in seen:
                raise t.error("carries", f"'{n}' is carried by [subframe.{seen[n]}] too")
            if n in given:
                raise t.error("carries", f"'{n}' is on the subframe, not on the body: "
                                         f"remove its [body.mounts.{n}] table")
            seen[n] = name
        out.append(_read_mounted(t, body, suspension, carries=carries))
    st.finish()
    return tuple(out)
