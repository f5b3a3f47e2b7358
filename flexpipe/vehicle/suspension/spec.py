"""Suspension part of the car file: ``[suspension.<axle>]``, ``[steering.rack]``.

Every error is an :class:`~flexpipe.errors.InputError` naming the file, line and key
(through :class:`flexpipe.vehicle._toml.Table`).  See ``docs/car-file.md`` for the format.
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from flexpipe._arrays import frozen_arrays
from flexpipe.errors import InputError, ModelError
from flexpipe.vehicle import limits as lim
from flexpipe.vehicle._toml import Table, check_principal_moments
from flexpipe.vehicle.suspension.checks import check_bushing, check_hardpoints
from flexpipe.vehicle.suspension.mobility import check_mobility
from flexpipe.vehicle.suspension.model import (
    BUSHING_DOFS,
    AntiRollBar,
    Axle,
    Bushing,
    Rack,
    mirror_corner,
)
from flexpipe.vehicle.suspension.templates import HARDPOINTS, PARTS, SPRING_PART, build

AXLES = ("front", "rear")
#: Adams/Car's two modes: bushings as bushings, or replaced by the joints they surround
MODES = ("compliant", "kinematic")


@dataclass(frozen=True)
@frozen_arrays
class Suspension:
    """The car's suspension: ``axles`` ``{"front": Axle, "rear": Axle}`` and the rack.

    ``wheels`` is ``{"fl": (mass_kg, inertia 3x3 about the wheel centre), ...}``: the rim
    and tyre of every corner whose ``[corners.<c>]`` table gives ``wheel_mass_kg`` (the
    knuckle carries it; :func:`flexpipe.vehicle.suspension.statics.with_wheels`).
    """

    file: Path
    axles: dict
    rack: Rack | None = None
    mode: str = "compliant"
    wheels: dict = field(default_factory=dict)

    def require_both_axles(self) -> None:
        """Refuse a car with one axle's suspension (a K&C file may give one only)."""
        for axle in AXLES:
            if axle not in self.axles:
                raise InputError(f"no [suspension.{axle}]: a car needs a suspension on both "
                                 f"axles (this file gives {', '.join(self.axles) or 'none'}; "
                                 "a file with one axle is for flexpipe kc only); see "
                                 "docs/car-file.md", file=self.file, key=f"suspension.{axle}")

    def corners(self) -> dict:
        """``{"fl": CornerLinkage, "fr": ..., "rl": ..., "rr": ...}``."""
        out = {}
        for a in self.axles.values():
            out[a.left.corner], out[a.right.corner] = a.left, a.right
        return out

    def mounts(self) -> dict:
        """Every body mount ``{name: point}`` (corners, rack housing, anti-roll bars)."""
        out = {}
        for c in self.corners().values():
            out.update(c.mounts)
        if self.rack is not None:
            out.update(self.rack.mounts)
        for a in self.axles.values():
            if a.anti_roll_bar is not None:
                out.update(dict(a.anti_roll_bar.mounts))
        return out

    def mount_dofs(self) -> dict:
        """``{mount: 3 | 6}``: 6 where a moment passes into the body (a bushing, a
        revolute or universal joint, the rack housing, an anti-roll-bar bearing), 3 where
        only a force passes (ball joints, inline joints, links, spring and damper
        seats).  In the kinematic mode a bushing is the joint it surrounds, so a bushed
        ball or inline joint passes no moment there either."""
        out = {name: 3 for name in self.mounts()}
        bushed = self.mode != "kinematic"
        for c in self.corners().values():
            for j in c.joints:
                if j.mount is not None and ((j.bushing is not None and bushed)
                                            or j.kind not in ("spherical", "inline")):
                    out[j.mount] = 6
        if self.rack is not None:
            out.update({n: 6 for n in self.rack.mounts})
        for a in self.axles.values():
            if a.anti_roll_bar is not None:
                out.update({n: 6 for n, _ in a.anti_roll_bar.mounts})
        return out


def _table_xy(t: Table, xkey: str, ykey: str, *, rising: str | None = None,
              pushing: bool = False):
    """Table ``xkey`` -> ``ykey``: equal-length lists of finite numbers, ``xkey`` strictly
    increasing.  ``rising`` (what the element is) rejects a force that falls as ``xkey``
    grows: a passive damper, spring, stop or bushing has no negative slope (negative
    damping feeds energy into the car, negative stiffness is unstable).  ``pushing``
    rejects negative forces (a stop only pushes)."""
    x, y = t.raw(xkey), t.raw(ykey)
    ok = (isinstance(x, list) and isinstance(y, list) and len(x) == len(y) >= 2
          and all(isinstance(v, int | float) and not isinstance(v, bool) for v in x + y))
    if not ok:
        raise t.error(xkey, f"'{xkey}' and '{ykey}' must be lists of numbers of equal "
                            "length >= 2")
    x, y = np.array(x, float), np.array(y, float)
    for key, v in ((xkey, x), (ykey, y)):
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise t.error(key, f"entry {bad[0]} is {v[bad[0]]}; '{key}' must hold finite "
                               f"numbers, got {v.tolist()}")
    if np.any(np.diff(x) <= 0):
        raise t.error(xkey, f"'{xkey}' must increase strictly, got {x.tolist()}")
    fall = np.flatnonzero(np.diff(y) < 0)
    if rising is not None and fall.size:
        i = fall[0]
        raise t.error(ykey, f"the force falls from {y[i]:g} to {y[i + 1]:g} between {xkey} "
                            f"{x[i]:g} and {x[i + 1]:g}; {rising}, so '{ykey}' must not "
                            f"decrease as '{xkey}' increases, got {y.tolist()}")
    if pushing and y.min() < 0:
        raise t.error(ykey, f"a stop only pushes: '{ykey}' must be >= 0, got {y.tolist()}")
    return x, y


def read_bushing(t: Table) -> Bushing:
    """A bushing table: ``stiffness`` and ``damping`` (6 each), ``axis``, ``dofs``,
    ``[tables]`` (see docs/car-file.md)."""
    dofs = t.string("dofs", "all", choices=("all", "translational"))
    k = t.vector("stiffness", 6, doc="kx ky kz [N/m] krx kry krz [N m/rad]")
    c = t.vector("damping", 6, np.zeros(6))
    for key, v in (("stiffness", k), ("damping", c)):
        if np.any(v < 0):  # a passive bushing stores or dissipates energy, never gives it
            raise t.error(key, f"every '{key}' value must be >= 0, got {v.tolist()}")
    check_bushing(t, k, c)
    if dofs == "translational":
        k, c = k.copy(), c.copy()
        k[3:] = c[3:] = 0.0
    frame = np.eye(3)
    if t.has("axis"):
        z = t.vector("axis")
        if np.linalg.norm(z) == 0:
            raise t.error("axis", "the bushing axis must not be zero")
        z = z / np.linalg.norm(z)
        x = np.cross([0, 1.0, 0], z) if abs(z[1]) < 0.9 else np.cross(z, [0, 0, 1.0])
        x /= np.linalg.norm(x)
        frame = np.column_stack([x, np.cross(z, x), z])
    tables = {}
    tt = t.sub("tables", None)
    if tt is not None:
        for dof in list(tt.data):
            if dof not in BUSHING_DOFS:
                raise tt.error(dof, f"unknown bushing direction; valid: {', '.join(BUSHING_DOFS)}")
            d = tt.sub(dof)
            tables[dof] = _table_xy(d, "deflection", "force",
                                    rising="a bushing's force rises with its deflection "
                                           "(stiffness >= 0)")
            d.finish()
        tt.finish()
    t.finish()
    return Bushing(k, c, frame, tables)


def _forces(t: Table) -> dict:
    out = {}
    s = t.sub("spring", None)
    if s is not None:
        rate = s.number("rate_N_per_m", lo=0, lo_open=True)
        d = {"rate": s.magnitude("rate_N_per_m", rate, *lim.SPRING_RATE_N_PER_M, unit="N/m",
                                 what="a suspension spring rate",
                                 slips=lim.SPRING_RATE_SLIPS)}
        if s.has("free_length_m") and s.has("preload_N"):
            raise s.error("preload_N", "give free_length_m or preload_N, not both")
        d["free_length"] = s.number("free_length_m", None, lo=0, lo_open=True)
        if s.has("compression_m"):
            d["table"] = _table_xy(s, "compression_m", "force_N",
                                   rising="a spring's force rises with its compression "
                                          "(stiffness >= 0)")
        out["spring"] = d
        out["_preload"] = s.number("preload_N", None)
        s.finish()
    dm = t.sub("damper", None)
    if dm is not None:
        if dm.has("velocity_m_per_s"):
            out["damper"] = {"table": _table_xy(
                dm, "velocity_m_per_s", "force_N",
                rising="a passive damper's force rises with the extension velocity (a "
                       "falling force is negative damping, which feeds energy into the car)")}
        else:
            cb = dm.number("bump_N_s_per_m", lo=0, doc="compression damping (dual rate)")
            cr = dm.number("rebound_N_s_per_m", lo=0, doc="extension damping")
            out["damper"] = {"table": (np.array([-1.0, 0.0, 1.0]), np.array([-cb, 0.0, cr]))}
        dm.finish()
    for kind in ("bump_stop", "rebound_stop"):
        st = t.sub(kind, None)
        if st is not None:
            out[kind] = {"clearance": st.number("clearance_m", lo=0),
                         "table": _table_xy(st, "deflection_m", "force_N", pushing=True,
                                            rising="a stop's force rises with its "
                                                   "deflection")}
            st.finish()
    return out


def _axle(st: Table, axle: str, rack_axle: str | None) -> Axle:
    t = st.sub(axle)
    template = t.string("template", choices=tuple(HARDPOINTS))
    loc = t.vector("location_m", 3, np.zeros(3))
    hpt = t.sub("hardpoints_m")
    req, opt = HARDPOINTS[template]
    for k in hpt.data:
        if k not in req + opt:
            raise hpt.error(k, f"unknown hardpoint for template {template}; valid: "
                               f"{', '.join(req + opt)}")
    for k in req:
        if k not in hpt.data:
            raise hpt.error(None, f"missing hardpoint '{k}' of template {template} "
                                  f"(required: {', '.join(req)})")
    raw = {k: hpt.vector(k) for k in list(hpt.data)}
    hpt.finish()
    hp = {k: v + loc for k, v in raw.items()}
    check_hardpoints(template, hp, raw, loc, t, hpt)
    parts = {}
    pt = t.sub("parts", None)
    if pt is not None:
        for name in list(pt.data):
            if name not in PARTS[template]:
                raise pt.error(name, f"unknown part for template {template}; valid: "
                                     f"{', '.join(PARTS[template])}")
            p = pt.sub(name)
            inertia = p.vector("inertia_kg_m2", 3, np.zeros(3), doc="Ixx Iyy Izz about cm")
            check_principal_moments(p, "inertia_kg_m2", np.diag(inertia))
            parts[name] = {"mass": p.number("mass_kg", lo=0),
                           "cm": p.vector("cm_m") + loc, "inertia": np.diag(inertia)}
            p.finish()
        pt.finish()
    bushings = {}
    bt = t.sub("bushings", None)
    if bt is not None:
        for name in list(bt.data):
            if name not in req + opt:
                raise bt.error(name, f"unknown hardpoint for a bushing; valid: body-side "
                                     f"hardpoints of {template}")
            bushings[name] = read_bushing(bt.sub(name))
        bt.finish()
    forces = _forces(t)
    preload = forces.pop("_preload", None)
    wheel_load = t.number("wheel_load_N", None, lo=0, lo_open=True,
                          doc="the K&C rig's design tyre load")
    if wheel_load is not None and (preload is not None or forces.get("spring", {}).get(
            "free_length") is not None):
        raise t.error("wheel_load_N", "the spring's preload_N / free_length_m already sets "
                                      "the K&C rig's spring preload, which wheel_load_N would "
                                      f"set too (it would be ignored): give one of them in "
                                      f"[{t.name}] or [{t.name}.spring]")
    kw = dict(axle=axle, corner=axle[0] + "l", camber_deg=t.number("camber_deg", 0.0),
              toe_deg=t.number("toe_deg", 0.0),
              wheel_radius=t.number("wheel_radius_m", float(hp["wheel_center"][2]),
                                    lo=0, lo_open=True),
              parts=parts, bushings=bushings, forces=forces, steered=(rack_axle == axle),
              file=t.file)
    if template == "multi_link" and t.has("universal_axes"):
        ax = t.raw("universal_axes")
        ok = isinstance(ax, list) and len(ax) == 2 and all(
            isinstance(a, list) and len(a) == 3 and all(
                isinstance(v, int | float) and not isinstance(v, bool) and np.isfinite(v)
                for v in a) and any(a) for a in ax)
        if not ok:
            raise t.error("universal_axes", "expected [[link axis], [body axis]]: two "
                                            f"non-zero vectors of 3 finite numbers, got {ax!r}")
        kw["universal_axes"] = tuple(np.array(a, float) for a in ax)
    try:
        left = build(template, hp, **kw)
    except InputError as exc:  # name the table and line of the offending key
        key = exc.key or ""
        sub = bt if bt is not None and key in bt.data else hpt
        raise sub.error(key if key in sub.data else None, str(exc).split(": ", 1)[-1]) from None
    if preload is not None:
        from flexpipe.vehicle.suspension.statics import with_preload

        left = with_preload(left, preload)
    arb = None
    at = t.sub("anti_roll_bar", None)
    if at is not None:
        for k in ("arb_bushing", "arb_arm_end", "drop_link_lower"):
            if k not in hp:
                raise at.error(None, f"an anti-roll bar needs hardpoint '{k}' in "
                                     f"[{t.name}.hardpoints_m]")
        k_t = at.magnitude("torsion_rate_N_m_per_rad",
                           at.number("torsion_rate_N_m_per_rad", lo=0, lo_open=True),
                           *lim.ARB_TORSION_RATE_N_M_PER_RAD, unit="N m/rad",
                           what="an anti-roll bar's torsion rate",
                           slips=lim.ARB_TORSION_SLIPS)
        arb = AntiRollBar(k_t,
                          hp["arb_bushing"], hp["arb_arm_end"], hp["drop_link_lower"],
                          SPRING_PART[template],
                          mounts=((f"{axle}_arb_bushing_l", hp["arb_bushing"]),
                                  (f"{axle}_arb_bushing_r", hp["arb_bushing"] * [1, -1, 1])),
                          bushing_stiffness=(read_bushing(at.sub("bushing"))
                                             if at.has("bushing") else None))
        at.finish()
    t.finish()
    _check_assembles(left, t, hpt)
    check_mobility(left, t, hpt)  # one wheel-travel DOF: no arm, tie rod or link degenerate
    return Axle(axle, left, mirror_corner(left, axle[0] + "r"), anti_roll_bar=arb,
                wheel_load=wheel_load)


def _check_assembles(corner, t: Table, hpt: Table) -> None:
    """Every constraint must hold at the design position; name the one that does not."""
    from flexpipe.vehicle.suspension.kinematics import Linkage

    lk = Linkage(corner)
    g, _, names = lk.constraints(lk.design())
    g[-1] -= corner.wheel_center[2]
    k = int(np.argmax(np.abs(g)))
    if abs(g[k]) <= 1e-6:
        return
    msg = (f"the linkage does not assemble at the design position: {names[k]} has "
           f"residual {g[k]:.3g} (m or rad)")
    if "(universal)" in names[k] and "universal_axes" in t.data:
        raise t.error("universal_axes", msg + "; the two axes must be perpendicular")
    joint = names[k].split("'")[1] if "'" in names[k] else None
    raise hpt.error(joint if joint in hpt.data else None, msg)


def load_suspension(path, *, overrides=None) -> Suspension:
    """Read the suspension of the car file ``path`` (``[suspension.*]``, ``[steering.rack]``).

    Parameters
    ----------
    path : str or Path
        Car file.
    overrides : dict, optional
        Dotted key to value set on the parsed file first, as
        :func:`flexpipe.vehicle.spec.load_car` takes them.

    Raises
    ------
    InputError
        Naming file, line and key: unknown or missing hardpoint, bad table, a linkage that
        does not assemble (the failing constraint and its residual) or that is not a
        one-degree-of-freedom wheel travel at the design position
        (:func:`~flexpipe.vehicle.suspension.mobility.check_mobility`).
    """
    from flexpipe.vehicle._car_base import parse_car

    path = Path(path)
    doc, lines, bases = parse_car(path)
    if overrides:
        from flexpipe.sweeps.overrides import apply_overrides

        doc = apply_overrides(doc, overrides, file=path, origin="car override")
    return read_suspension(Table(doc, "", path, lines, bases))


def read_suspension(top: Table) -> Suspension:
    """The suspension of the parsed car document ``top`` (its top-level table).

    :func:`flexpipe.vehicle.spec.load_car` passes the document it reads every other section
    from, so overrides set on it reach the suspension too.  Unknown keys of
    ``[suspension.*]`` and ``[steering.rack]`` are refused here; ``top`` itself and
    ``[steering]`` are left for the caller to finish.
    """
    path, lines = top.file, top.lines
    st = top.sub("suspension", None)
    if st is None:
        raise InputError("no [suspension.front] / [suspension.rear] tables; see "
                         "docs/car-file.md", file=path, key="suspension")
    rack, rack_axle = None, None
    steer = top.sub("steering", None)
    if steer is not None and steer.has("rack"):
        rt = steer.sub("rack")
        rack_axle = rt.string("axle", "front", choices=AXLES)
        mount = rt.vector("mount_m")
        rack = Rack({f"{rack_axle}_rack_mount_l": mount,
                     f"{rack_axle}_rack_mount_r": mount * [1, -1, 1]},
                     rt.magnitude("travel_per_rev_m",
                                  rt.number("travel_per_rev_m", lo=0, lo_open=True,
                                            doc="rack travel per pinion revolution"),
                                  *lim.RACK_TRAVEL_PER_REV_M, unit="m",
                                  what="the rack travel per pinion revolution",
                                  slips=lim.LENGTH_SLIPS),
                     rt.number("ratio", None, lo=0, lo_open=True),
                     rt.number("column_stiffness_N_m_per_rad", None, lo=0, lo_open=True))
        rt.finish()
    axles = {}
    mode = st.string("mode", "compliant", choices=MODES,
                     doc="the car in time runs: bushings as given (compliant) or joints "
                         "(kinematic)")
    for name in list(st.data):
        if name == "mode":
            continue
        if name not in AXLES:
            raise st.error(name, "unknown key; valid keys in [suspension]: mode, and the axle "
                                 f"tables {', '.join(AXLES)}")
        axles[name] = _axle(st, name, rack_axle)
    st.finish()
    if rack is not None:
        if rack_axle not in axles:
            raise InputError(f"the rack is on the {rack_axle} axle, which has no "
                             f"[suspension.{rack_axle}]", file=path, key="steering.rack.axle")
        axles[rack_axle] = replace(axles[rack_axle], rack=rack)
    susp = Suspension(path, axles, rack, mode, _wheels(top))
    _check_body_mounts(top.data, susp, lines)
    return susp


def _wheels(top: Table) -> dict:
    """``{corner: (mass, inertia)}`` of the ``[corners.<c>]`` tables that give
    ``wheel_mass_kg`` (rim + tyre; ``wheel_inertia_kg_m2`` about x and z [0]).  A car file
    needs all four (``load_car`` names a missing one); a suspension-only file for the K&C
    rig may give none."""
    from flexpipe.vehicle.body_spec import read_inertia

    ct = top.sub("corners", None)
    out = {}
    for name in ("fl", "fr", "rl", "rr"):
        if ct is None or not isinstance(ct.data.get(name), dict) \
                or "wheel_mass_kg" not in ct.data[name]:
            continue
        c = ct.sub(name)
        m = c.magnitude("wheel_mass_kg",
                        c.number("wheel_mass_kg", lo=0, lo_open=True, doc="rim + tyre mass"),
                        *lim.WHEEL_MASS_KG, unit="kg", what="a wheel (rim + tyre)",
                        slips=lim.MASS_SLIPS)
        J = read_inertia(c, "wheel_inertia_kg_m2") if c.has("wheel_inertia_kg_m2") else \
            np.zeros((3, 3))
        check_principal_moments(c, "wheel_inertia_kg_m2", J)
        out[name] = (m, J)
    return out


#: largest distance (m) of a ``[body.mounts.<m>] point_m`` from the mount's hardpoint
POINT_M_TOL = 1e-3


def _check_body_mounts(doc: dict, susp: Suspension, lines: list[str]) -> None:
    """Every ``[body.mounts.<name>]`` must name a mount of ``susp``: checked here, when
    any tool reads the car (``info``, ``kc``, every run), not only by the flexible run."""
    body = doc.get("body")
    mounts = body.get("mounts") if isinstance(body, dict) else None
    valid = susp.mounts()
    others = set()  # mounts of the powertrain, the subframes and the drive's reaction
    sub = doc.get("subframe")
    tables = [(doc.get("drive"), "reaction_mounts"), (doc.get("powertrain"), "mounts")] + [
        (t, "mounts") for t in (sub.values() if isinstance(sub, dict) else ())]
    for t, key in tables:
        names = t.get(key) if isinstance(t, dict) else None
        if isinstance(names, list) and all(isinstance(n, str) for n in names):
            others |= set(names)
        elif names is not None:  # malformed: that table's reader names it, not this check
            return
    for name in mounts if isinstance(mounts, dict) else ():  # else read_body names it
        where = dict(file=susp.file, line=Table({}, f"body.mounts.{name}", susp.file,
                                                lines)._line(None))
        if name in others and name not in valid:
            continue  # a powertrain, subframe or drive-reaction mount
        if name not in valid:
            raise InputError(f"[body.mounts] names '{name}', which is no mount of this car's "
                             f"suspension nor a mount of [powertrain], [subframe.*] or [drive] "
                             f"reaction_mounts; "
                             f"valid: {', '.join(valid)}", key=f"body.mounts.{name}", **where)
        p = mounts[name].get("point_m") if isinstance(mounts[name], dict) else None
        try:
            off = float(np.linalg.norm(np.asarray(p, dtype=float) - valid[name]))
        except (TypeError, ValueError):
            continue  # not three numbers: read_body names it
        if p is not None and off > POINT_M_TOL:
            raise InputError(
                f"point_m {tuple(p)} is {off * 1e3:.1f} mm from the suspension's point of mount "
                f"'{name}' {tuple(np.round(valid[name], 4))} m: a flexible run would put the "
                "joint at point_m and the rigid run at the hardpoint, so their difference "
                "would depend on a point with no physical meaning; leave point_m out (the tie "
                f"is centred on the hardpoint) or move the hardpoint (valid: within "
                f"{POINT_M_TOL * 1e3:g} mm of it)", key=f"body.mounts.{name}.point_m", **where)


__all__ = ["Suspension", "load_suspension", "read_suspension", "ModelError"]
