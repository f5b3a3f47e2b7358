"""The ``[body]`` table of the car file: mesh or rigid mass properties, non-structural
masses, output points, seats and per-mount ties (see :mod:`flexpipe.vehicle.spec` and
``docs/car-file.md``).

Every error is an :class:`~flexpipe.errors.InputError` naming the file, line and key.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flexpipe._arrays import frozen_arrays
from flexpipe.errors import InputError
from flexpipe.fem.material import LIBRARY, Material
from flexpipe.mesh.units import unit_system
from flexpipe.vehicle._toml import Table
from flexpipe.vehicle.seats import read_seats

#: lowest interface band a car file may ask for (Hz): the characteristic constraint modes
#: must reach well above the 20-40 Hz band of the body's fixed-interface modes
MIN_INTERFACE_BAND_HZ = 100.0


@dataclass(frozen=True)
@frozen_arrays
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
@frozen_arrays
class RigidProps:
    """Rigid mass properties: mass (kg), centre of gravity (m), inertia about it (kg m^2)."""

    mass: float
    cg: np.ndarray
    inertia: np.ndarray


@dataclass(frozen=True)
@frozen_arrays
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
    #: per-mount ties of ``[body.mounts.<mount>]``: {mount: {"point", "radius", "dofs",
    #: "node_set", "node_ids" (ids of the mesh file, checked against the mesh when it is
    #: reduced), "line" (of the table, for errors)}}
    mounts: dict = None
    #: linkage cars: characteristic constraint modes up to this frequency (Hz) replace the
    #: static modes of the mounts (interface reduction); ``inf``: keep every static mode
    #: (full Craig-Bampton, ``interface_band_hz = "all"``); None: the default
    #: (:data:`flexpipe.vehicle.linkage_setup.INTERFACE_F_MAX_HZ`)
    interface_band_hz: float | None = None
    #: ``[body.seats.<name>]``: seats on named floor points (:mod:`flexpipe.vehicle.seats`)
    seats: tuple = ()


# --------------------------------------------------------------------------- readers
def read_inertia(t: Table, key: str) -> np.ndarray:
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


#: ``[body]`` keys that a ready body (``body_file``) makes void: its mass properties,
#: damping and interfaces were fixed when ``flexpipe reduce`` wrote it
IGNORED_BY_BODY_FILE = {
    "rigid": "[body.rigid] (the body file's own mass properties are used)",
    "damping_ratio": "damping_ratio (the body file carries its modal damping)",
    "interface_radius_m": "interface_radius_m (the interfaces were tied at reduction)",
    "mounts": "[body.mounts] (the body file's interfaces are used as they are)",
    "interface_band_hz": "interface_band_hz (the body file's interface modes are used)",
    "mesh_scale": "mesh_scale", "mesh_units": "mesh_units", "material": "material",
    "shell_thickness_m": "shell_thickness_m",
}


def _warn_ignored_by_body_file(t: Table) -> None:
    """One warning naming the ``[body]`` keys a ``body_file`` car ignores."""
    given = [k for k in IGNORED_BY_BODY_FILE if k in t.data]
    if not given:
        return
    import warnings

    line = t._line(given[0])
    warnings.warn(
        f"{t.file}" + (f", line {line}" if line else "") + ": with [body] body_file these "
        f"keys are ignored: {'; '.join(IGNORED_BY_BODY_FILE[k] for k in given)}; set them "
        "when reducing the body (flexpipe reduce) or give [body] mesh instead of body_file",
        UserWarning, stacklevel=2)


def read_body(doc: Table, base: Path) -> BodySpec:
    """The ``[body]`` table of ``doc``; paths relative to ``base`` (the car file's folder)."""
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
    if units is not None:  # checked here, not first when the mesh is read (info, run)
        try:
            unit_system(units)
        except InputError as exc:
            raise t.error("mesh_units", str(exc).split(": ", 1)[-1]) from None
    material = _material(t, "material")
    thick = t.number("shell_thickness_m", None, lo=0, lo_open=True)
    zeta = t.number("damping_ratio", 0.02, lo=0, hi=1.0)
    radius = t.number("interface_radius_m", 0.12, lo=0, lo_open=True)
    band = None
    if t.has("interface_band_hz"):
        raw = t.raw("interface_band_hz")
        if raw == "all":
            band = math.inf
        elif isinstance(raw, bool) or not isinstance(raw, int | float) or not math.isfinite(raw):
            raise t.error("interface_band_hz", f"expected a frequency in Hz (>= "
                                               f"{MIN_INTERFACE_BAND_HZ:g}) or \"all\" (every "
                                               f"static mode), got {raw!r}")
        else:
            band = t.number("interface_band_hz", lo=MIN_INTERFACE_BAND_HZ,
                            doc="top of the mounts' characteristic constraint modes, Hz "
                                "(they must reach well above the 20-40 Hz body band)")
    rigid = None
    if t.has("rigid"):
        r = t.sub("rigid")
        rigid = RigidProps(r.number("mass_kg", lo=0, lo_open=True, doc="body mass"),
                           r.vector("cg_m"), read_inertia(r, "inertia_kg_m2"))
        r.finish()
    if mesh is None and rigid is None and body_file is None:
        raise t.error(None, "the body needs a 'mesh' (flexible body), a 'body_file' (ready "
                            "reduced body .npz) or a [body.rigid] table with mass_kg, cg_m, "
                            "inertia_kg_m2")
    masses = []
    raw = t.raw("mass", [])
    if not isinstance(raw, list):
        raise t.error("mass", "expected an array of tables [[body.mass]]")
    seen = {}
    for i, item in enumerate(raw):
        m = Table(item, f"body.mass[{i}]", t.file, t.lines)
        name = m.string("name", f"mass{i}")
        if name in seen:  # overrides (body.mass.<name>.mass_kg) and messages use the name
            j = seen[name]
            first = Table(raw[j], f"body.mass[{j}]", t.file, t.lines)._line("name")
            raise m.error("name", f"'{name}' names two [[body.mass]] entries, body.mass[{j}] "
                                  f"(line {first}) and body.mass[{i}]; each non-structural "
                                  "mass needs its own name")
        seen[name] = i
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
    seats = read_seats(t, points)
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
                 "node_set": m.string("node_set", None), "node_ids": None,
                 "line": m._line(None)}
            if m.has("nodes"):  # renamed: it meant 0-based positions, then file ids
                raise m.error("nodes", "`nodes` is no longer accepted; give the mesh file's "
                                       "node ids as `node_ids` (the ids your pre-processor "
                                       "shows, e.g. Nastran GRID ids); the old `nodes` "
                                       "counted positions from 0, which are id - 1 only in a "
                                       "deck numbered 1..n without gaps, so take the ids "
                                       "from your deck")
            if m.has("node_ids"):  # ids as in the mesh file, like `flexpipe reduce --interfaces`
                raw_ids = m.raw("node_ids")
                if not (isinstance(raw_ids, list) and raw_ids and all(
                        isinstance(v, int) and not isinstance(v, bool) for v in raw_ids)):
                    raise m.error("node_ids", "expected a non-empty list of node ids as in "
                                              "the mesh file (integers, e.g. Nastran GRID "
                                              f"ids), got {raw_ids!r}")
                d["node_ids"] = tuple(raw_ids)
            if d["dofs"] not in (None, 3, 6):
                raise m.error("dofs", f"must be 3 or 6, got {d['dofs']}")
            if sum(x is not None for x in (d["radius"], d["node_set"], d["node_ids"])) > 1:
                raise m.error(None, "give one of radius_m, node_set or node_ids")
            m.finish()
            mounts[name] = d
        mt.finish()
    fatigue = None
    if t.has("fatigue"):  # feat/durability: Basquin S-N data, flexpipe.durability.fatigue
        from flexpipe.durability.fatigue import read_fatigue_table

        fatigue = read_fatigue_table(t.sub("fatigue"))
    if body_file is not None:
        _warn_ignored_by_body_file(t)
    t.finish()
    return BodySpec(mesh, scale, units, material, thick, zeta, radius, rigid, tuple(masses), points,
                    fatigue, body_file, mounts, band, seats)


