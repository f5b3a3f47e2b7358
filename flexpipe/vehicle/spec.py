"""Car specification: the TOML schema, its validation and the :class:`Car` data object.

Units are SI and stated in key names (``_m``, ``_kg``, ``_N_per_m``, ``_N_s_per_m``,
``_kg_m2``, ``_deg``).  Coordinates are body coordinates with ISO 8855 axes (x forward,
y left, z up) in the *design position*: the car at rest on flat ground under its own
weight, with ``z = 0`` the ground plane.  ``wheel_center_m`` is where each wheel centre sits
in that position; the spring preload that holds it there is computed unless given.

File layout (see ``cars/sedan.toml`` for a complete example; defaults in brackets)::

    [car]            name [file stem]
    [body]           mesh (file read by flexpipe.read_mesh), mesh_scale [1], mesh_units
                     [SI], material (library name or {E_Pa, nu, rho_kg_per_m3}; replaces
                     every material of the mesh), shell_thickness_m (for shells without
                     one), damping_ratio [0.02] (elastic modes below 100 Hz),
                     interface_radius_m [0.12] (mesh nodes tied to each hardpoint)
    [body.rigid]     mass_kg, cg_m, inertia_kg_m2 (about the cg; 3 or 6 values):
                     rigid mass properties, for a car without mesh
    [[body.mass]]    name, mass_kg, position_m, spread_radius_m [0.3]
                     (non-structural masses: powertrain, trim, occupants)
    [body.points]    name = [x, y, z]  (named output points for accelerations)
    [body.seats.<name>]  floor_point, natural_frequency_hz, damping_ratio: a seat on a
                     named point (flexpipe.vehicle.seats: channels acc_<name>_x|y|z)
    [body.fatigue]   sigma_f_Pa, b, endurance_limit_Pa [0], name: Basquin S-N curve of the
                     body for fatigue damage (flexpipe.durability.fatigue)
    [corners.fl|fr|rl|rr]
                     hardpoint_m, wheel_center_m, spring_rate_N_per_m, spring_preload_N
                     [computed: holds the design position], damper_N_s_per_m (linear) or
                     damper_jounce_N_s_per_m + damper_rebound_N_s_per_m (dual rate),
                     bump_stop_clearance_m [0.08], bump_stop_rate_N_per_m [2e5],
                     rebound_stop_clearance_m [0.10], rebound_stop_rate_N_per_m [2e5],
                     unsprung_mass_kg, unsprung_inertia_kg_m2, wheel_radius_m (must match
                     the tyre file), wheel_spin_inertia_kg_m2, tire (.tir file)
    [steering]       axle ["front"], ratio, max_wheel_angle_deg [35],
                     max_rate_deg_per_s [60] (road-wheel angle rate)
    [anti_roll_bar.front|rear]  rate_N_per_m (force at each wheel per metre of left-right
                     travel difference)
    [drive]          layout ("front" | "rear" | "all"), max_drive_torque_N_m [3000],
                     max_brake_torque_N_m [6000], brake_front_share [0.65], front_share
                     [0.5] (all-wheel drive), drive_reaction ["body"], reaction_mounts
                     (powertrain mounts, [body.mounts.<name>] tables; docs/car-file.md)
    [powertrain]     linkage cars: mass_kg, center_of_mass_m, inertia_kg_m2, mounts,
                     [powertrain.bushings.<mount>] (a rigid powertrain on its mounts,
                     flexpipe.vehicle.mounted)
    [subframe.<name>]  linkage cars: the same keys plus carries (suspension mounts on it)

Checks made when the body is built (they need the mesh or the tyre): hardpoints within
0.05 m of the structure, non-structural masses surrounded by body nodes, wheel radius equal
to the tyre's UNLOADED_RADIUS, wheel-centre heights equal to the tyre's static loaded
radius under the static wheel loads (so the design position is the ride height at rest).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flexpipe._args import as_path, plain_value
from flexpipe._arrays import frozen_arrays
from flexpipe.errors import InputError
from flexpipe.vehicle import limits as lim
from flexpipe.vehicle._car_base import parse_car
from flexpipe.vehicle._toml import Table, check_principal_moments
from flexpipe.vehicle.body_spec import (  # noqa: F401  (re-exported)
    AddedMass,
    BodySpec,
    RigidProps,
    read_body,
    read_inertia,
)
from flexpipe.vehicle.suspension.checks import WHEEL_CENTER_BOX_M

CORNERS = ("fl", "fr", "rl", "rr")
AXLE_OF = {"fl": "front", "fr": "front", "rl": "rear", "rr": "rear"}
DRIVE_REACTIONS = ("body", "knuckle")
DRIVE_LAYOUTS = ("front", "rear", "all")


@dataclass(frozen=True)
@frozen_arrays
class CornerSpec:
    """One wheel corner: prismatic suspension along body z through ``hardpoint``."""

    name: str
    hardpoint: np.ndarray
    wheel_center: np.ndarray
    spring_rate: float
    spring_preload: float | None
    damper_jounce: float
    damper_rebound: float
    bump_stop_clearance: float
    bump_stop_rate: float
    rebound_stop_clearance: float
    rebound_stop_rate: float
    unsprung_mass: float
    unsprung_inertia: np.ndarray
    wheel_radius: float
    spin_inertia: float
    tire: Path
    tire_pressure: float | None = None

    @property
    def axle(self) -> str:
        """``"front"`` or ``"rear"``."""
        return AXLE_OF[self.name]

    @property
    def side(self) -> int:
        """+1 for a left corner, -1 for a right one."""
        return 1 if self.name[1] == "l" else -1


@dataclass(frozen=True)
@frozen_arrays
class SteeringSpec:
    """Steering of one axle: steering-wheel to road-wheel ``ratio`` and limits (rad)."""

    axle: str
    ratio: float
    max_wheel_angle: float
    max_rate: float


@dataclass(frozen=True)
@frozen_arrays
class DriveSpec:
    """Drive layout and torque limits (total at the wheels)."""

    layout: str
    max_drive_torque: float
    max_brake_torque: float
    brake_front_share: float
    front_share: float
    #: where the drive torque is reacted: "body" (driveshafts from a body-mounted engine
    #: or motor: the wheel gets the torque, the body its reaction) or "knuckle" (in-wheel
    #: motors, as brakes always are: the reaction on the wheel carrier)
    reaction: str = "body"
    #: powertrain mounts ``[body.mounts.<name>]`` that pass the "body" reaction into the
    #: body (flexpipe.vehicle.reaction_mounts); empty: the body's reference frame takes it
    reaction_mounts: tuple = ()
    #: their points (n, 3), body coordinates (m)
    reaction_points: np.ndarray | None = None

    def drive_shares(self) -> np.ndarray:
        """Share of the drive torque per corner in CORNERS order."""
        f = {"front": 1.0, "rear": 0.0, "all": self.front_share}[self.layout]
        return np.array([f, f, 1 - f, 1 - f]) / 2.0

    def brake_shares(self) -> np.ndarray:
        """Share of the brake torque per corner in CORNERS order."""
        f = self.brake_front_share
        return np.array([f, f, 1 - f, 1 - f]) / 2.0


@dataclass(frozen=True)
@frozen_arrays
class Car:
    """A validated car specification (see module docstring for the file format)."""

    name: str
    file: Path
    body: BodySpec
    corners: tuple[CornerSpec, ...]
    steering: SteeringSpec
    anti_roll_bars: dict
    drive: DriveSpec
    suspension: object = None  # flexpipe.vehicle.suspension.Suspension (linkage templates)
    powertrain: object = None  # flexpipe.vehicle.mounted.MountedBody (rigid, on mounts)
    subframes: tuple = ()  # MountedBody each, carrying suspension mounts

    @property
    def mounted_bodies(self) -> tuple:
        """The rigid bodies on bushings at body mounts: powertrain, then subframes."""
        return ((self.powertrain,) if self.powertrain is not None else ()) + self.subframes

    @property
    def mounted_mass(self) -> float:
        """Mass of the powertrain and subframes on mounts (0 without), kg."""
        return float(sum(b.mass for b in self.mounted_bodies))

    def carrier_of(self, mount: str):
        """The subframe carrying suspension mount ``mount``, or None (on the body)."""
        return next((s for s in self.subframes if mount in s.carries), None)

    def corner(self, name: str) -> CornerSpec:
        """The corner called ``name`` (fl, fr, rl, rr)."""
        return self.corners[CORNERS.index(name)]

    @property
    def unsprung_mass(self) -> float:
        """Sum of the four unsprung masses, kg."""
        return float(sum(c.unsprung_mass for c in self.corners))

    @property
    def wheelbase(self) -> float:
        """Mean front minus mean rear wheel-centre x, m."""
        x = np.array([c.wheel_center[0] for c in self.corners])
        return float(x[:2].mean() - x[2:].mean())


# --------------------------------------------------------------------------- readers
def _corner(corners: Table, name: str, base: Path) -> CornerSpec:
    c = corners.sub(name)
    has_lin = c.has("damper_N_s_per_m")
    has_dual = c.has("damper_jounce_N_s_per_m") or c.has("damper_rebound_N_s_per_m")
    if has_lin and has_dual:
        raise c.error("damper_N_s_per_m", "give either damper_N_s_per_m (linear) or "
                      "damper_jounce_N_s_per_m + damper_rebound_N_s_per_m (dual-rate), not both")
    if has_lin:
        cj = cr = c.number("damper_N_s_per_m", lo=0)
    elif has_dual:
        cj = c.number("damper_jounce_N_s_per_m", lo=0)
        cr = c.number("damper_rebound_N_s_per_m", lo=0)
    else:
        raise c.error(None, "missing damper: give damper_N_s_per_m (linear) or "
                            "damper_jounce_N_s_per_m and damper_rebound_N_s_per_m (dual-rate)")
    tire = (base / c.string("tire", doc="tire property file (.tir)")).resolve()
    if not tire.is_file():
        raise c.error("tire", f"tire file {tire} does not exist (paths are relative to the "
                              "car file)")
    spec = CornerSpec(
        name=name,
        hardpoint=c.vector("hardpoint_m", doc="suspension mount on the body"),
        wheel_center=c.vector("wheel_center_m", doc="wheel centre in the design position"),
        spring_rate=c.number("spring_rate_N_per_m", lo=0, lo_open=True),
        spring_preload=c.number("spring_preload_N", None),
        damper_jounce=cj, damper_rebound=cr,
        bump_stop_clearance=c.number("bump_stop_clearance_m", 0.08, lo=0, lo_open=True),
        bump_stop_rate=c.number("bump_stop_rate_N_per_m", 2e5, lo=0),
        rebound_stop_clearance=c.number("rebound_stop_clearance_m", 0.10, lo=0, lo_open=True),
        rebound_stop_rate=c.number("rebound_stop_rate_N_per_m", 2e5, lo=0),
        unsprung_mass=c.number("unsprung_mass_kg", lo=0, lo_open=True),
        unsprung_inertia=read_inertia(c, "unsprung_inertia_kg_m2"),
        wheel_radius=c.number("wheel_radius_m", lo=0, lo_open=True),
        spin_inertia=c.number("wheel_spin_inertia_kg_m2", lo=0, lo_open=True),
        tire=tire, tire_pressure=_tire_pressure(c),
    )
    c.finish()
    dampers = (("damper_N_s_per_m", cj),) if has_lin else (
        ("damper_jounce_N_s_per_m", cj), ("damper_rebound_N_s_per_m", cr))
    for key, v, bounds, unit, what, slips in (
            ("spring_rate_N_per_m", spec.spring_rate, lim.SPRING_RATE_N_PER_M, "N/m",
             "a suspension spring rate", lim.SPRING_RATE_SLIPS),
            *((k, v, lim.DAMPING_N_S_PER_M, "N s/m", "a suspension damper", lim.DAMPING_SLIPS)
              for k, v in dampers),
            ("bump_stop_rate_N_per_m", spec.bump_stop_rate, lim.STOP_RATE_N_PER_M, "N/m",
             "a bump stop (0: none)", lim.SPRING_RATE_SLIPS),
            ("rebound_stop_rate_N_per_m", spec.rebound_stop_rate, lim.STOP_RATE_N_PER_M, "N/m",
             "a rebound stop (0: none)", lim.SPRING_RATE_SLIPS),
            ("unsprung_mass_kg", spec.unsprung_mass, lim.WHEEL_MASS_KG, "kg",
             "the unsprung mass of a wheel", lim.MASS_SLIPS),
            ("wheel_spin_inertia_kg_m2", spec.spin_inertia, lim.WHEEL_SPIN_INERTIA_KG_M2,
             "kg m^2", "the spin inertia of a wheel", lim.INERTIA_SLIPS)):
        if v != 0 or key in ("spring_rate_N_per_m", "wheel_spin_inertia_kg_m2"):  # 0: none
            c.magnitude(key, v, *bounds, unit=unit, what=what, slips=slips)
    side = 1 if name[1] == "l" else -1
    for key, p in (("hardpoint_m", spec.hardpoint), ("wheel_center_m", spec.wheel_center)):
        if p[1] * side <= 0:
            raise c.error(key, f"y = {p[1]:g} m puts a {'left' if side > 0 else 'right'} "
                               f"corner on the wrong side (ISO axes: y > 0 is left)")
    if spec.wheel_center[2] <= 0:
        raise c.error("wheel_center_m", f"wheel centre height {spec.wheel_center[2]:g} m must "
                                        "be > 0 (z = 0 is the ground in the design position)")
    check_principal_moments(c, "unsprung_inertia_kg_m2", spec.unsprung_inertia)
    _check_corner_envelope(c, spec)
    return spec


def _check_corner_envelope(c: Table, spec: CornerSpec) -> None:
    """The wheel centre within a road vehicle's envelope (the linkage car's
    :data:`~flexpipe.vehicle.suspension.checks.WHEEL_CENTER_BOX_M`) and the hardpoint within
    :data:`~flexpipe.vehicle.limits.HARDPOINT_TO_WHEEL_CENTER_M` of it."""
    wc = spec.wheel_center
    for i, (lo, hi) in WHEEL_CENTER_BOX_M.items():
        if not lo < wc[i] <= hi:
            axis = "xyz"[i]
            mm = ("; the values look like millimetres, but the key's unit is metres"
                  if lo < wc[i] / 1e3 <= hi and abs(wc[i]) >= 50 else "")
            raise c.error("wheel_center_m", f"wheel centre {axis} = {wc[i]:g} m is outside any "
                                            f"road vehicle ({lo:g} < {axis} <= {hi:g} m in "
                                            "body coordinates: z = 0 the ground, |y| half the "
                                            f"track, at most 1.3 m in the 2.6 m width limit){mm}")
    d = float(np.linalg.norm(spec.hardpoint - wc))
    if d > lim.HARDPOINT_TO_WHEEL_CENTER_M:
        raise c.error("hardpoint_m", f"the suspension mount {spec.hardpoint.tolist()} lies "
                                     f"{d:.3g} m from the wheel centre {wc.tolist()} "
                                     f"(wheel_center_m); valid: at most "
                                     f"{lim.HARDPOINT_TO_WHEEL_CENTER_M:g} m (a strut top mount "
                                     "or spring seat sits in the wheel house or above the "
                                     "axle, 0.3-0.7 m from the wheel centre in cars)")


def _tire_pressure(c) -> float | None:
    """``tire_pressure_Pa``: the inflation pressure of an MF 6.x tyre (None: the file's
    INFLPRES); checked against the file's range when the tyre is built."""
    p = c.number("tire_pressure_Pa", None, lo=0, lo_open=True)
    if p is not None and not 2e4 <= p <= 2e6:
        raise c.error("tire_pressure_Pa", f"{p:g} Pa is not a tyre pressure; valid: "
                      "20000 .. 2000000 Pa (the key is in Pa: 2.3 bar = 230 kPa = 230000)")
    return p


def _wheel_corner(corners: Table, name: str, base: Path, linkage, wheel) -> CornerSpec:
    """A corner of a car with linkage suspension: wheel, tyre and the linkage's masses
    (``wheel``: rim + tyre mass and inertia, from ``Suspension.wheels``)."""
    c = corners.sub(name)
    tire = (base / c.string("tire", doc="tire property file (.tir)")).resolve()
    if not tire.is_file():
        raise c.error("tire", f"tire file {tire} does not exist (paths are relative to the "
                              "car file)")
    c.raw("wheel_mass_kg", doc="rim + tyre mass")  # required; read with the suspension
    c.has("wheel_inertia_kg_m2")
    m_wheel, J_wheel = wheel
    spring = linkage.spring()
    spec = CornerSpec(
        name=name, hardpoint=np.array(spring.body_point if spring is not None
                                      else linkage.wheel_center, dtype=float),
        wheel_center=np.array(linkage.wheel_center, dtype=float), spring_rate=0.0,
        spring_preload=None, damper_jounce=0.0, damper_rebound=0.0,
        bump_stop_clearance=0.0, bump_stop_rate=0.0, rebound_stop_clearance=0.0,
        rebound_stop_rate=0.0,
        unsprung_mass=m_wheel + sum(p.mass for p in linkage.parts),
        unsprung_inertia=J_wheel,
        wheel_radius=c.number("wheel_radius_m", lo=0, lo_open=True),
        spin_inertia=c.number("wheel_spin_inertia_kg_m2", lo=0, lo_open=True),
        tire=tire, tire_pressure=_tire_pressure(c))
    c.finish()
    c.magnitude("wheel_spin_inertia_kg_m2", spec.spin_inertia, *lim.WHEEL_SPIN_INERTIA_KG_M2,
                unit="kg m^2", what="the spin inertia of a wheel", slips=lim.INERTIA_SLIPS)
    return spec


def _check_mount_names(body: BodySpec, suspension, path: Path, lines: list[str]) -> None:
    """A prismatic-corner car has no suspension mounts for ``[body.mounts]`` or
    ``[body] interface_band_hz`` (they would be ignored); a linkage car's names are checked
    by ``load_suspension``."""
    if suspension is None and body.interface_band_hz is not None:
        raise InputError("[body] interface_band_hz sets the interface reduction of a linkage "
                         "car's mounts ([suspension.*]); this car has prismatic corners, "
                         "whose four hardpoints keep every static mode: remove the key",
                         file=path, line=Table({}, "body", path, lines)._line(
                             "interface_band_hz"), key="body.interface_band_hz")
    if suspension is None and body.mounts:
        name = next(iter(body.mounts))
        raise InputError("[body.mounts] ties the mounts of a linkage suspension "
                         "([suspension.*]) to the mesh; this car has prismatic corners, tied "
                         "at each corners.<c>.hardpoint_m within [body] interface_radius_m: "
                         "remove the table", file=path,
                         line=Table({}, f"body.mounts.{name}", path, lines)._line(None),
                         key=f"body.mounts.{name}")


def load_car(path, *, overrides=None) -> Car:
    """Read and validate a car file.

    Parameters
    ----------
    path : str or Path
        TOML car file (see :mod:`flexpipe.vehicle.spec` for the keys).
    overrides : dict, optional
        Dotted key to value, set on the parsed file before validation (e.g.
        ``{"corners.fl.spring_rate_N_per_m": 35000.0}`` or, for a linkage car,
        ``{"suspension.front.spring.rate_N_per_m": 1.2e5}``; see
        :func:`flexpipe.sweeps.overrides.apply_overrides`).  Every section, the suspension
        included, is read from the overridden document; a key its schema does not know is
        refused like one written in the file, the message naming the override.

    Returns
    -------
    Car

    Raises
    ------
    InputError
        Missing, unknown or out-of-range keys, with the file, line, key and valid options.
    """
    if isinstance(path, dict):
        raise InputError("path must be a car file (str or pathlib.Path), got a dict; to "
                         "change keys of a file give overrides={'dotted.key': value}",
                         key="path")
    path = as_path(path, "path")
    if overrides is not None and not isinstance(overrides, dict):
        raise InputError("overrides must be a dict of dotted key to value, e.g. "
                         "{'corners.fl.spring_rate_N_per_m': 35000.0}, got "
                         f"{type(overrides).__name__}", key="overrides")
    if overrides:  # numpy scalars and arrays as the plain numbers and lists TOML gives
        overrides = {k: plain_value(v) for k, v in overrides.items()}
    if path.suffix.lower() != ".toml":
        raise InputError(f"expected a .toml car file, got '{path.suffix}'", file=path)
    data, lines, bases = parse_car(path)
    if not overrides:
        return _read_car(Table(data, "", path, lines, bases))
    # --- sweep (issue 12): dotted-key overrides before validation; every section, the
    # suspension included, is read from this one overridden document
    from flexpipe.sweeps.overrides import apply_overrides

    data = apply_overrides(data, overrides, file=path, origin="car override")
    try:
        return _read_car(Table(data, "", path, lines, bases))
    except InputError as exc:
        raise _from_override(exc, overrides) from None


def _from_override(exc: InputError, overrides: dict) -> InputError:
    """``exc`` saying so when its key (or a table above it) was set by an override: the
    value or key is then not in the file at the line named."""
    key = exc.key or ""
    hit = next((k for k in overrides if key == k or key.startswith(f"{k}.")), None)
    if hit is None:
        return exc
    return InputError(f"{exc.message} (from the car override '{hit}' = "
                      f"{overrides[hit]!r}, not from the file)", file=exc.file, line=exc.line,
                      key=exc.key)


def _read_car(doc: Table) -> Car:
    """The car of the parsed (and possibly overridden) top-level table ``doc``."""
    path, lines = doc.file, doc.lines
    base = path.resolve().parent
    ct = doc.sub("car")
    name = ct.string("name", path.stem)
    ct.finish()
    body = read_body(doc, base)
    if body.rigid is not None:
        check_principal_moments(doc.sub("body").sub("rigid"), "inertia_kg_m2",
                                body.rigid.inertia)
    corners_t = doc.sub("corners")
    suspension = None
    if doc.has("suspension"):
        from flexpipe.vehicle.suspension.spec import read_suspension

        suspension = read_suspension(doc)
        suspension.require_both_axles()
        links = suspension.corners()
        corners = tuple(_wheel_corner(corners_t, n, base, links[n],
                                      suspension.wheels.get(n)) for n in CORNERS)
    else:
        corners = tuple(_corner(corners_t, n, base) for n in CORNERS)
    corners_t.finish()
    _check_mount_names(body, suspension, path, lines)
    x = [c.wheel_center[0] for c in corners]
    if min(x[:2]) <= max(x[2:]):
        raise InputError("front wheel centres must lie ahead (larger x) of the rear ones "
                         f"(ISO axes, x forward); got x = {dict(zip(CORNERS, x, strict=True))}",
                         file=path, key="corners")
    st = doc.sub("steering")
    steering = SteeringSpec(
        st.string("axle", "front", choices=("front", "rear")),
        st.number("ratio", lo=0, lo_open=True, doc="steering-wheel angle / road-wheel angle"),
        np.radians(st.number("max_wheel_angle_deg", 35.0, lo=0, lo_open=True, hi=80)),
        np.radians(st.number("max_rate_deg_per_s", 60.0, lo=0, lo_open=True)))
    if suspension is not None and st.has("rack"):
        st.raw("rack")  # read by flexpipe.vehicle.suspension.spec.read_suspension
    st.finish()
    arbs = {}
    if doc.has("anti_roll_bar"):
        at = doc.sub("anti_roll_bar")
        for axle in ("front", "rear"):
            if at.has(axle):
                a = at.sub(axle)
                arbs[axle] = a.number("rate_N_per_m", lo=0,
                                      doc="force at the wheel per metre of left-right travel "
                                          "difference")
                if arbs[axle] != 0:  # 0: no bar
                    a.magnitude("rate_N_per_m", arbs[axle], *lim.ARB_RATE_N_PER_M, unit="N/m",
                                what="an anti-roll bar (0: none)",
                                slips=lim.SPRING_RATE_SLIPS)
                a.finish()
        at.finish()
    dt = doc.sub("drive")
    drive = DriveSpec(
        dt.string("layout", choices=DRIVE_LAYOUTS),
        dt.number("max_drive_torque_N_m", 3000.0, lo=0, lo_open=True),
        dt.number("max_brake_torque_N_m", 6000.0, lo=0, lo_open=True),
        dt.number("brake_front_share", 0.65, lo=0, hi=1),
        dt.number("front_share", 0.5, lo=0, hi=1),
        dt.string("drive_reaction", "body", choices=DRIVE_REACTIONS))
    if dt.has("reaction_mounts"):
        from flexpipe.vehicle.reaction_mounts import read_reaction_mounts

        drive = read_reaction_mounts(dt, drive, body, suspension)
    dt.finish()
    powertrain = None
    if doc.has("powertrain"):
        from flexpipe.vehicle.mounted import read_powertrain

        powertrain = read_powertrain(doc, body, suspension, drive)
    subframes = ()
    if doc.has("subframe"):
        from flexpipe.vehicle.mounted import read_subframes

        subframes = read_subframes(doc, body, suspension)
    doc.finish()
    return Car(name, path, body, corners, steering, arbs, drive, suspension, powertrain,
               subframes)
