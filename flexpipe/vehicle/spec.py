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
                     [0.5] (all-wheel drive)

Checks made when the body is built (they need the mesh or the tyre): hardpoints within
0.05 m of the structure, non-structural masses surrounded by body nodes, wheel radius equal
to the tyre's UNLOADED_RADIUS, wheel-centre heights equal to the tyre's static loaded
radius under the static wheel loads (so the design position is the ride height at rest).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flexpipe.errors import InputError
from flexpipe.fem.material import LIBRARY, Material
from flexpipe.vehicle._toml import Table, parse

CORNERS = ("fl", "fr", "rl", "rr")
AXLE_OF = {"fl": "front", "fr": "front", "rl": "rear", "rr": "rear"}
DRIVE_LAYOUTS = ("front", "rear", "all")


@dataclass(frozen=True)
class AddedMass:
    """A non-structural mass spread over the body nodes near ``position``.

    The nodal shares are chosen so that their total is ``mass`` and their centre of mass
    is ``position`` (see :func:`flexpipe.vehicle.bodymodel.spread_mass`).
    """

    name: str
    mass: float
    position: np.ndarray
    spread_radius: float


@dataclass(frozen=True)
class RigidProps:
    """Rigid mass properties: mass (kg), centre of gravity (m), inertia about it (kg m^2)."""

    mass: float
    cg: np.ndarray
    inertia: np.ndarray


@dataclass(frozen=True)
class BodySpec:
    """The car body: a mesh (flexible) and/or rigid mass properties, plus added masses."""

    mesh: Path | None
    mesh_scale: float
    mesh_units: str | None
    material: Material | None
    shell_thickness: float | None
    damping_ratio: float
    interface_radius: float
    rigid: RigidProps | None
    added_masses: tuple[AddedMass, ...]
    points: dict
    fatigue: object = None  # FatigueMaterial of [body.fatigue] (feat/durability)
    body_file: Path | None = None  # ready reduced body (.npz from flexpipe reduce)
    mounts: dict = None  # {mount: {"point", "radius", "dofs", "node_set", "nodes"}} overrides


@dataclass(frozen=True)
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

    @property
    def axle(self) -> str:
        """``"front"`` or ``"rear"``."""
        return AXLE_OF[self.name]

    @property
    def side(self) -> int:
        """+1 for a left corner, -1 for a right one."""
        return 1 if self.name[1] == "l" else -1


@dataclass(frozen=True)
class SteeringSpec:
    """Steering of one axle: steering-wheel to road-wheel ``ratio`` and limits (rad)."""

    axle: str
    ratio: float
    max_wheel_angle: float
    max_rate: float


@dataclass(frozen=True)
class DriveSpec:
    """Drive layout and torque limits (total at the wheels)."""

    layout: str
    max_drive_torque: float
    max_brake_torque: float
    brake_front_share: float
    front_share: float

    def drive_shares(self) -> np.ndarray:
        """Share of the drive torque per corner in CORNERS order."""
        f = {"front": 1.0, "rear": 0.0, "all": self.front_share}[self.layout]
        return np.array([f, f, 1 - f, 1 - f]) / 2.0

    def brake_shares(self) -> np.ndarray:
        """Share of the brake torque per corner in CORNERS order."""
        f = self.brake_front_share
        return np.array([f, f, 1 - f, 1 - f]) / 2.0


@dataclass(frozen=True)
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
def _inertia(t: Table, key: str) -> np.ndarray:
    """3 principal values or 6 [Ixx, Iyy, Izz, Ixy, Ixz, Iyz]; positive semi-definite."""
    v = t.raw(key)
    n = len(v) if isinstance(v, list) else 0
    if n not in (3, 6):
        raise t.error(key, f"expected [Ixx, Iyy, Izz] or [Ixx, Iyy, Izz, Ixy, Ixz, Iyz] in "
                           f"kg m^2, got {v!r}")
    a = t.vector(key, n)
    J = np.diag(a[:3])
    if n == 6:
        J[0, 1] = J[1, 0] = a[3]
        J[0, 2] = J[2, 0] = a[4]
        J[1, 2] = J[2, 1] = a[5]
    if np.any(np.linalg.eigvalsh(J) < -1e-12 * max(1.0, abs(J).max())):
        raise t.error(key, f"inertia tensor {a.tolist()} is not positive semi-definite")
    return J


def _material(t: Table, key: str) -> Material | None:
    if not t.has(key):
        return None
    v = t.raw(key)
    if isinstance(v, str):
        if v.lower() not in LIBRARY:
            raise t.error(key, f"unknown material {v!r}; valid: {sorted(set(LIBRARY))} or a "
                               "table {E_Pa, nu, rho_kg_per_m3}")
        return LIBRARY[v.lower()]
    m = t.sub(key)
    mat = Material(m.number("E_Pa", lo=0, lo_open=True), m.number("nu", lo=-0.99, hi=0.499),
                   m.number("rho_kg_per_m3", lo=0), name=m.string("name", ""))
    m.finish()
    return mat


def _body(doc: Table, base: Path) -> BodySpec:
    t = doc.sub("body")
    mesh = None
    if t.has("mesh"):
        mesh = (base / t.string("mesh")).resolve()
        if not mesh.is_file():
            raise t.error("mesh", f"mesh file {mesh} does not exist (paths are relative to "
                                  "the car file)")
    body_file = None
    if t.has("body_file"):
        body_file = (base / t.string("body_file", doc="reduced body from flexpipe reduce")
                     ).resolve()
        if not body_file.is_file():
            raise t.error("body_file", f"body file {body_file} does not exist (paths are "
                                       "relative to the car file)")
        if mesh is not None:
            raise t.error("body_file", "give either 'mesh' (reduced for each run's band) or "
                                       "'body_file' (a ready reduced body), not both")
    scale = t.number("mesh_scale", 1.0, lo=0, lo_open=True)
    units = t.string("mesh_units", None)
    material = _material(t, "material")
    thick = t.number("shell_thickness_m", None, lo=0, lo_open=True)
    zeta = t.number("damping_ratio", 0.02, lo=0, hi=1.0)
    radius = t.number("interface_radius_m", 0.12, lo=0, lo_open=True)
    rigid = None
    if t.has("rigid"):
        r = t.sub("rigid")
        rigid = RigidProps(r.number("mass_kg", lo=0, lo_open=True, doc="body mass"),
                           r.vector("cg_m"), _inertia(r, "inertia_kg_m2"))
        r.finish()
    if mesh is None and rigid is None and body_file is None:
        raise t.error(None, "the body needs a 'mesh' (flexible body), a 'body_file' (ready "
                            "reduced body .npz) or a [body.rigid] table with mass_kg, cg_m, "
                            "inertia_kg_m2")
    masses = []
    raw = t.raw("mass", [])
    if not isinstance(raw, list):
        raise t.error("mass", "expected an array of tables [[body.mass]]")
    for i, item in enumerate(raw):
        m = Table(item, f"body.mass[{i}]", t.file, t.lines)
        name = m.string("name", f"mass{i}")
        masses.append(AddedMass(
            name, m.number("mass_kg", lo=0, doc="non-structural mass"),
            m.vector("position_m"), m.number("spread_radius_m", 0.3, lo=0, lo_open=True)))
        m.finish()
    points = {}
    if t.has("points"):
        p = t.sub("points")
        for k in list(p.data):
            points[k] = p.vector(k)
        p.finish()
    if body_file is not None and masses:
        raise t.error("mass", "a ready body file carries its own masses: add the "
                              "non-structural masses before reducing it (flexpipe reduce), "
                              "or give the mesh instead of body_file")
    mounts = {}
    if t.has("mounts"):  # per-mount ties: point + radius, a node set, or node ids
        mt = t.sub("mounts")
        for name in list(mt.data):
            m = mt.sub(name)
            d = {"point": m.vector("point_m") if m.has("point_m") else None,
                 "radius": m.number("radius_m", None, lo=0, lo_open=True),
                 "dofs": int(m.number("dofs", 0, lo=0, hi=6)) or None,
                 "node_set": m.string("node_set", None), "nodes": None}
            if m.has("nodes"):
                raw_nodes = m.raw("nodes")
                if not (isinstance(raw_nodes, list) and raw_nodes and all(
                        isinstance(v, int) and not isinstance(v, bool) and v >= 0
                        for v in raw_nodes)):
                    raise m.error("nodes", "expected a list of node indices (integers >= 0, "
                                           "0-based)")
                d["nodes"] = tuple(raw_nodes)
            if d["dofs"] not in (None, 3, 6):
                raise m.error("dofs", f"must be 3 or 6, got {d['dofs']}")
            if sum(x is not None for x in (d["radius"], d["node_set"], d["nodes"])) > 1:
                raise m.error(None, "give one of radius_m, node_set or nodes")
            m.finish()
            mounts[name] = d
        mt.finish()
    fatigue = None
    if t.has("fatigue"):  # feat/durability: Basquin S-N data, flexpipe.durability.fatigue
        from flexpipe.durability.fatigue import read_fatigue_table

        fatigue = read_fatigue_table(t.sub("fatigue"))
    t.finish()
    return BodySpec(mesh, scale, units, material, thick, zeta, radius, rigid, tuple(masses), points,
                    fatigue, body_file, mounts)


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
        unsprung_inertia=_inertia(c, "unsprung_inertia_kg_m2"),
        wheel_radius=c.number("wheel_radius_m", lo=0, lo_open=True),
        spin_inertia=c.number("wheel_spin_inertia_kg_m2", lo=0, lo_open=True),
        tire=tire,
    )
    c.finish()
    side = 1 if name[1] == "l" else -1
    for key, p in (("hardpoint_m", spec.hardpoint), ("wheel_center_m", spec.wheel_center)):
        if p[1] * side <= 0:
            raise c.error(key, f"y = {p[1]:g} m puts a {'left' if side > 0 else 'right'} "
                               f"corner on the wrong side (ISO axes: y > 0 is left)")
    if spec.wheel_center[2] <= 0:
        raise c.error("wheel_center_m", f"wheel centre height {spec.wheel_center[2]:g} m must "
                                        "be > 0 (z = 0 is the ground in the design position)")
    return spec


def _wheel_corner(corners: Table, name: str, base: Path, linkage) -> CornerSpec:
    """A corner of a car with linkage suspension: wheel, tyre and the linkage's masses."""
    c = corners.sub(name)
    tire = (base / c.string("tire", doc="tire property file (.tir)")).resolve()
    if not tire.is_file():
        raise c.error("tire", f"tire file {tire} does not exist (paths are relative to the "
                              "car file)")
    m_wheel = c.number("wheel_mass_kg", lo=0, lo_open=True, doc="rim + tyre mass")
    J_wheel = _inertia(c, "wheel_inertia_kg_m2") if c.has("wheel_inertia_kg_m2") else \
        np.zeros((3, 3))
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
        tire=tire)
    c.finish()
    return spec


def load_car(path, *, overrides=None) -> Car:
    """Read and validate a car file.

    Parameters
    ----------
    path : str or Path
        TOML car file (see :mod:`flexpipe.vehicle.spec` for the keys).
    overrides : dict, optional
        Dotted key to value, set on the parsed file before validation (e.g.
        ``{"corners.fl.spring_rate_N_per_m": 35000.0}``; see
        :func:`flexpipe.sweeps.overrides.apply_overrides`).

    Returns
    -------
    Car

    Raises
    ------
    InputError
        Missing, unknown or out-of-range keys, with the file, line, key and valid options.
    """
    path = Path(path)
    if path.suffix.lower() != ".toml":
        raise InputError(f"expected a .toml car file, got '{path.suffix}'", file=path)
    data, lines = parse(path)
    if overrides:  # --- sweep (issue 12): dotted-key overrides before validation
        from flexpipe.sweeps.overrides import apply_overrides

        data = apply_overrides(data, overrides, file=path, origin="car override")
    base = path.resolve().parent
    doc = Table(data, "", path, lines)
    ct = doc.sub("car")
    name = ct.string("name", path.stem)
    ct.finish()
    body = _body(doc, base)
    corners_t = doc.sub("corners")
    suspension = None
    if doc.has("suspension"):
        from flexpipe.vehicle.suspension import load_suspension

        doc.raw("suspension")
        suspension = load_suspension(path)
        links = suspension.corners()
        corners = tuple(_wheel_corner(corners_t, n, base, links[n]) for n in CORNERS)
    else:
        corners = tuple(_corner(corners_t, n, base) for n in CORNERS)
    corners_t.finish()
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
        st.raw("rack")  # read by flexpipe.vehicle.suspension.load_suspension
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
                a.finish()
        at.finish()
    dt = doc.sub("drive")
    drive = DriveSpec(
        dt.string("layout", choices=DRIVE_LAYOUTS),
        dt.number("max_drive_torque_N_m", 3000.0, lo=0, lo_open=True),
        dt.number("max_brake_torque_N_m", 6000.0, lo=0, lo_open=True),
        dt.number("brake_front_share", 0.65, lo=0, hi=1),
        dt.number("front_share", 0.5, lo=0, hi=1))
    dt.finish()
    doc.finish()
    return Car(name, path, body, corners, steering, arbs, drive, suspension)
