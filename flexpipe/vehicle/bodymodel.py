"""The car body as a structure: mesh + added masses -> FE model -> reduced FlexBody (cached).

* :func:`body_mesh` reads the body mesh of a :class:`~flexpipe.vehicle.spec.Car` and adds
  its non-structural masses (:func:`spread_mass`).
* :func:`body_fe` assembles it; :func:`rigid_properties` gives mass, centre of mass and
  inertia (the rigid body of the car, identical to the flexible body's).
* :func:`corner_interfaces` ties the mesh nodes around each suspension hardpoint (RBE2
  spider of radius ``interface_radius_m``) and checks the hardpoints lie on the body.
* :func:`reduced_body` reduces the body for a frequency band, cached on disk under a key
  made of the mesh file bytes and every setting that changes the result; entries are
  verified on load and rebuilt when bad (:mod:`flexpipe.vehicle._cache`).
* :func:`describe_modes` names the global torsion and bending modes of a body.
"""

from __future__ import annotations

import hashlib
import json
import os
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from flexpipe._arrays import uniform_samples, uniform_step
from flexpipe.errors import InputError
from flexpipe.vehicle.spec import CORNERS, Car

DEFAULT_METHOD = "craig-bampton"
#: the car keeps Craig-Bampton fixed-interface modes up to this multiple of its band
CB_RATIO = 1.5
#: highest band :func:`choose_band` picks, Hz (fixed-interface modes to CB_RATIO x it).
#: The hub forces need the body's local dynamics above the 0-25 Hz ride band: on the
#: linkage car (ISO C, 70 km/h, 3 s, bench/bench_body_modes.py, 2026-12-02) a band of
#: 30 Hz (59 elastic modes) left them 20.7 % of their fluctuating part off the full body
#: (every fixed-interface mode to 250 Hz and every static mode; 6.4 % below 50 Hz,
#: 15.5 % at 50-150 Hz), 40 Hz (75 modes) 8.0 % (1.9 %, 4.8 %); the rest sits at
#: 150-300 Hz, in the mounts' static modes.  A higher cap gains little (60 Hz, 105 modes:
#: 7.5 %) and costs step accuracy: at 45 Hz the flexible x hub forces are 5.0-5.5 % off
#: h/8 at the default step (bench/bench_convergence.py), above the 5 % target
BAND_CAP_HZ = 40.0
#: a hardpoint farther than this from every body node is "off the body", m
OFF_BODY_TOL = 0.05
#: bump when the cache layout or the reduction settings' meaning changes
CACHE_VERSION = 1
#: stress modes stored with the car body (``reduce(..., stress=...)``): "all", a cell set, None
STRESS_MODES = "all"


def cache_dir() -> Path:
    """Directory of cached reduced bodies: ``$FLEXPIPE_CACHE`` or ``./.cache/flexpipe``."""
    return Path(os.environ.get("FLEXPIPE_CACHE", Path.cwd() / ".cache" / "flexpipe"))


# --------------------------------------------------------------------------- masses
def spread_mass(points: np.ndarray, mass: float, position, radius: float, *,
                name: str = "mass", max_growth: int = 4, file=None):
    """Nodal shares of a mass so that their total and centre of mass are exact.

    The candidates are the nodes within ``radius`` of ``position`` (the radius grows by 50 %
    up to ``max_growth`` times when the position is not inside their convex hull); among
    the non-negative shares with the exact total and centre, the ones closest to an even
    split are taken.  ``name`` and ``file`` (the car file) are for the error message.

    Returns
    -------
    nodes : ndarray of int
    shares : ndarray, kg
    """
    p = np.asarray(position, dtype=float)
    d = np.linalg.norm(points - p, axis=1)
    r = float(radius)
    for _ in range(max_growth + 1):
        idx = np.flatnonzero(d <= r)
        if idx.size >= 4:
            w = _nonnegative_shares(points[idx] - p, mass)
            if w is not None:
                keep = w > 1e-9 * mass
                return idx[keep], w[keep]
        r *= 1.5
    raise InputError(
        f"non-structural mass '{name}' at {tuple(p)} m cannot be spread over the body: its "
        f"position is not surrounded by body nodes even within {r / 1.5:.3g} m; move it "
        "closer to the structure or increase spread_radius_m", file=file,
        key=f"body.mass.{name}")


def _nonnegative_shares(R: np.ndarray, mass: float, *, iterations: int = 50):
    """Shares ``w >= 0`` with ``sum w = mass`` and ``sum w r = 0`` (``R`` relative to the
    target centre), closest to the even split; ``None`` when none exists.

    Active-set iteration on the closed-form minimum-norm correction
    ``w = w0 + A^T (A A^T)^-1 (b - A w0)``: shares that come out negative are fixed at 0.
    """
    k = len(R)
    active = np.ones(k, dtype=bool)
    w = np.zeros(k)
    for _ in range(iterations):
        A = np.vstack([np.ones(active.sum()), R[active].T])
        b = np.array([mass, 0.0, 0.0, 0.0])
        w0 = np.full(active.sum(), mass / active.sum())
        z, *_ = np.linalg.lstsq(A @ A.T, b - A @ w0, rcond=1e-12)
        wa = w0 + A.T @ z
        if np.abs(A @ wa - b).max() > 1e-6 * mass:
            return None  # the centre lies outside the candidates' hull
        if wa.min() >= -1e-12 * mass:
            w[:] = 0.0
            w[active] = np.maximum(wa, 0.0)
            return w
        idx = np.flatnonzero(active)
        active[idx[wa < 0]] = False
        if active.sum() < 4:
            return None
    return None


def body_mesh(car: Car):
    """The car's body mesh (SI units) with its non-structural masses added as point masses."""
    from dataclasses import replace

    from flexpipe.mesh import read_mesh
    from flexpipe.mesh.mesh import PointMass

    if car.body.mesh is None:
        raise InputError("the body has no mesh (rigid mass properties only); a flexible or "
                         "full body needs [body] mesh = ...", file=car.file, key="body.mesh")
    mesh = read_mesh(car.body.mesh, car.body.mesh_scale, units=car.body.mesh_units,
                     thickness=car.body.shell_thickness)
    pms = list(mesh.point_masses)
    next_id = max([pm.id for pm in pms] + [0]) + 1
    for am in car.body.added_masses:
        nodes, shares = spread_mass(mesh.points, am.mass, am.position, am.spread_radius,
                                    name=am.name, file=car.file)
        for n, w in zip(nodes, shares, strict=True):
            pms.append(PointMass(int(n), float(w), id=next_id))
            next_id += 1
    return replace(mesh, point_masses=tuple(pms))


def body_fe(car: Car, mesh=None):
    """Assembled FE model of the trimmed body."""
    from flexpipe.fem import assemble

    mesh = body_mesh(car) if mesh is None else mesh
    return assemble(mesh, material=car.body.material)


# --------------------------------------------------------------------------- interfaces
def corner_interfaces(car: Car, nodes: np.ndarray | None = None):
    """One RBE2 interface per corner hardpoint, named ``fl``, ``fr``, ``rl``, ``rr``.

    Raises
    ------
    InputError
        A hardpoint farther than :data:`OFF_BODY_TOL` from every body node (off the body).
    """
    from flexpipe.reduction import Interface

    out = []
    for c in car.corners:
        key = f"corners.{c.name}.hardpoint_m"
        if car.suspension is not None:  # a linkage car: the hardpoint is the spring's seat
            sp = car.suspension.corners()[c.name].spring()
            key = f"suspension.{c.axle}.hardpoints_m." + (
                sp.mount[len(c.axle) + 1:-2] if sp is not None else "wheel_center")
        if nodes is not None:
            d = np.linalg.norm(nodes - c.hardpoint, axis=1)
            k = int(d.argmin())
            if d[k] > OFF_BODY_TOL:
                raise InputError(
                    f"hardpoint {tuple(c.hardpoint)} m is off the body: the nearest body node "
                    f"is {d[k]:.3f} m away at {tuple(np.round(nodes[k], 4))}; a hardpoint must "
                    f"lie within {OFF_BODY_TOL} m of the structure", file=car.file,
                    key=key)
        out.append(Interface(tuple(c.hardpoint), radius=car.body.interface_radius,
                             name=c.name))
    return out


def point_nodes(car: Car, nodes: np.ndarray) -> dict:
    """Nearest body node index of every named output point (checked to be on the body)."""
    out = {}
    for name, p in car.body.points.items():
        d = np.linalg.norm(nodes - p, axis=1)
        k = int(d.argmin())
        if d[k] > OFF_BODY_TOL:
            raise InputError(f"point {tuple(p)} m is off the body (nearest node {d[k]:.3f} m "
                             "away)", file=car.file, key=f"body.points.{name}")
        out[name] = k
    return out


# --------------------------------------------------------------------------- rigid props
@dataclass(frozen=True)
class RigidBodyData:
    """Mass properties of the car body in body coordinates (kg, m, kg m^2)."""

    mass: float
    center_of_mass: np.ndarray
    inertia: np.ndarray  # about the centre of mass

    @property
    def inertia_origin(self) -> np.ndarray:
        """Inertia tensor about the body-coordinate origin."""
        c = self.center_of_mass
        return self.inertia + self.mass * (c @ c * np.eye(3) - np.outer(c, c))


def _digest(car: Car, extra: dict) -> str:
    h = hashlib.sha256()
    h.update(Path(car.body.mesh).read_bytes())
    b = car.body
    settings = {
        "v": CACHE_VERSION, "scale": b.mesh_scale, "units": b.mesh_units,
        "thickness": b.shell_thickness, "radius": b.interface_radius, "zeta": b.damping_ratio,
        "material": None if b.material is None else [b.material.E, b.material.nu,
                                                      b.material.rho],
        "masses": [[m.name, m.mass, *m.position.tolist(), m.spread_radius]
                   for m in b.added_masses],
        "hardpoints": [c.hardpoint.tolist() for c in car.corners], **extra,
    }
    h.update(json.dumps(settings, sort_keys=True).encode())
    return h.hexdigest()  # the full key is stored in the entry, 20 hex digits name it


def rigid_properties(car: Car, *, cache: bool = True) -> RigidBodyData:
    """Mass properties of the body: from ``[body.rigid]``, a ready body file or the trimmed
    FE model."""
    if car.body.body_file is not None:
        fb = ready_body(car)
        return RigidBodyData(fb.mass, np.array(fb.center_of_mass), np.array(fb.inertia))
    if car.body.mesh is None:
        r = car.body.rigid
        return RigidBodyData(r.mass, r.cg.copy(), r.inertia.copy())
    from flexpipe.vehicle import _cache

    key = _digest(car, {})
    path = cache_dir() / f"massprops-{key[:20]}.json"
    if cache:
        _cache.clean_stale(cache_dir())
        hit = _cache.load_massprops(path, key)
        if hit is not None:
            return RigidBodyData(*hit)
    from flexpipe.flexbody import mass_properties

    fe = body_fe(car)
    corner_interfaces(car, fe.nodes)
    mass, com, J, _ = mass_properties(fe.M, fe.nodes, fe.dofs_per_node)
    if cache:
        _cache.save_massprops(path, key, mass, com, J)
    return RigidBodyData(mass, com, J)


def ready_body(car: Car, required=()):
    """The car's ready reduced body (``[body] body_file``), checked to carry every
    interface in ``required`` (names)."""
    from flexpipe.flexbody import load_body

    fb = load_body(car.body.body_file)
    have = {i.name for i in fb.interfaces}
    missing = [n for n in required if n not in have]
    if missing:
        raise InputError(f"the body file {car.body.body_file.name} has no interface "
                         f"{missing[0]!r} ({len(missing)} missing); this car needs "
                         f"{', '.join(required)}; reduce the body with these interfaces (it "
                         f"has {', '.join(sorted(have))})", file=car.file, key="body.body_file")
    if car.suspension is None:  # prismatic corners: the corner joint carries moments
        three = [i.name for i in fb.interfaces if i.name in CORNERS and i.dofs != 6]
        if three:
            raise InputError(
                f"the body file {car.body.body_file.name} has 3-DOF (forces only) corner "
                f"interface(s) {', '.join(three)}; a car with prismatic corners ties each "
                f"corner ({', '.join(CORNERS)}) to the body with a 6-DOF interface (forces "
                "and moments): reduce the body again with dofs = 6 (the default) for these "
                "interfaces in the interface spec", file=car.file, key="body.body_file")
    return fb


def check_body_file(car: Car) -> None:
    """Check a ``body_file`` car's ready body before a run writes anything: the car's
    interfaces (:func:`ready_body`) at the car's points (:func:`~flexpipe.vehicle.mounts.
    check_interface_points`).  No-op without ``body_file``."""
    if car.body.body_file is None:
        return
    from flexpipe.vehicle.linkage_setup import body_mounts
    from flexpipe.vehicle.mounts import check_interface_points

    if car.suspension is not None:
        points = {m.name: m.point for m in body_mounts(car)}
    else:
        points = {c: car.corner(c).hardpoint for c in CORNERS}
    check_interface_points(ready_body(car, list(points)), points, car=car)


# --------------------------------------------------------------------------- reduction
def modal_damping(car: Car):
    """Damping ratio as a function of frequency: the car's ratio below 100 Hz, then the
    Adams/Flex defaults (10 % to 1 kHz, critical above) so stiff attachment modes are
    damped out."""
    zeta = car.body.damping_ratio

    def ratio(f):
        return zeta if f < 100.0 else (0.10 if f < 1000.0 else 1.0)

    return ratio


def body_key(car: Car, *, cutoff: float, method: str = DEFAULT_METHOD, mounts=None,
             interface_f_max: float | None = None) -> str:
    """Digest of everything the reduced body of :func:`reduced_body` depends on (its
    cache entry's name and the sweeps' grouping of runs that share a body): the mesh and
    body settings, the fixed-interface ``cutoff`` (Hz), the method and, with ``mounts``
    (:class:`~flexpipe.vehicle.mounts.Mount` list), every mount and the interface band."""
    key = {"cutoff": round(float(cutoff), 6), "m": method, "stress": STRESS_MODES}
    if mounts is not None:
        key["mounts"] = [m.cache_key() for m in mounts]
        key["interface_f_max"] = interface_f_max
    return _digest(car, key)


def reduced_body(car: Car, *, f_max: float, method: str = DEFAULT_METHOD,
                 cache: bool = True, log=print, cutoff: float | None = None,
                 mounts=None, interface_f_max: float | None = None):
    """The reduced flexible body for band ``f_max`` (Hz), from the cache when possible.

    Craig-Bampton keeps the fixed-interface modes up to ``cutoff`` (default
    ``CB_RATIO * f_max``) plus the static constraint modes of the interfaces, which keep
    the static flexibility of every higher mode exactly.

    The interfaces are the four corner hardpoints, or with ``mounts`` every body-side
    suspension mount: a list of :class:`~flexpipe.vehicle.mounts.Mount` or
    ``(name, point, radius, dofs)`` tuples (radius None: the mesh node at the point;
    dofs 3 or 6), see :func:`flexpipe.vehicle.mounts.mount_interfaces`.
    ``interface_f_max`` (Hz) reduces the interface: characteristic constraint modes up
    to that frequency replace the static constraint modes
    (:mod:`flexpipe.reduction.ccmodes`).

    Returns
    -------
    body : FlexBody
    info : dict
        ``cached`` (bool), ``seconds`` (reduction time, 0 when cached), ``path``.
    """
    from flexpipe.reduction import reduce
    from flexpipe.vehicle import _cache

    if car.body.body_file is not None:  # a ready body: used as it is, band and all
        names = [m[0] if isinstance(m, tuple) else m.name for m in mounts] if mounts \
            else list(CORNERS)
        return ready_body(car, names), {"cached": True, "seconds": 0.0,
                                        "path": str(car.body.body_file)}
    cutoff = CB_RATIO * f_max if cutoff is None else float(cutoff)
    if mounts is not None:  # every body-side mount an interface (flexpipe/vehicle/mounts.py)
        from flexpipe.vehicle.mounts import as_mount

        mounts = [as_mount(m) for m in mounts]
    key = body_key(car, cutoff=cutoff, method=method, mounts=mounts,
                   interface_f_max=interface_f_max)
    path = cache_dir() / f"body-{key[:20]}.npz"
    if cache:  # verified entry (input key, content hash, physics) or rebuilt with a warning
        _cache.clean_stale(cache_dir())
        hit = _cache.load_cached_body(path, key)
        if hit is not None:
            return hit, {"cached": True, "seconds": 0.0, "path": str(path)}
    t0 = time.perf_counter()
    log(f"reducing body {car.body.mesh.name} ({method}, modes to {cutoff:.0f} Hz) ...")
    fe = body_fe(car)
    if mounts is not None:
        from flexpipe.vehicle.mounts import mount_interfaces

        itf = mount_interfaces(mounts, fe.mesh if fe.mesh is not None else fe.nodes,
                               file=car.file)
    else:
        itf = corner_interfaces(car, fe.nodes)
    log(f"  assembled {fe.n_dof} DOF in {time.perf_counter() - t0:.1f} s")
    stage = {"log": lambda line: log("  " + line)}  # progress of a minutes-long reduction
    if method == "craig-bampton":  # the car's own cut-off for fixed-interface modes
        body = reduce(fe, itf, method=method, f_max=f_max, cb_factor=cutoff / f_max,
                      damping=modal_damping(car), stress=STRESS_MODES,
                      interface_f_max=interface_f_max, **stage)
    else:
        body = reduce(fe, itf, method=method, f_max=cutoff, damping=modal_damping(car),
                      stress=STRESS_MODES, **stage)
    seconds = time.perf_counter() - t0
    log(f"  {fe.n_dof} DOF -> {body.n_elastic} elastic modes "
        f"({body.frequencies_hz[body.n_rigid]:.1f}-{body.frequencies_hz[-1]:.0f} Hz) "
        f"in {seconds:.1f} s")
    if cache:
        body = _cache.save_cached_body(body, path, key)
    return body, {"cached": False, "seconds": seconds, "path": str(path)}


def choose_band(speed: float, road=None, *, lo: float = 20.0, hi: float = BAND_CAP_HZ,
                contact_length: float = 0.2) -> float:
    """Top of the frequency band the flexible body must reproduce, Hz.

    The road excites the car at ``f = v n`` for wavenumbers ``n`` up to the road's content;
    the tyre contact patch averages out wavelengths shorter than about ``contact_length``.
    The band is 1.5 x the road content up to the wavenumber holding 90 % of the profile's
    slope (velocity-input) variance, limited by the contact filter, but at least ``lo`` =
    20 Hz (1.5 x the ~13 Hz wheel hop, which every road and manoeuvre excites) and at most
    ``hi`` (:data:`BAND_CAP_HZ`, 40 Hz: what the hub forces need, not only the 0-25 Hz
    ride band, see there).  The car then keeps Craig-Bampton fixed-interface modes up to
    ``CB_RATIO`` x the band; the constraint modes keep the static flexibility of every
    higher mode at the hardpoints.
    """
    f_road, x = 0.0, None if road is None else np.asarray(road.x)
    if road is not None:
        if x.size > 16 or not uniform_step(x):
            z = 0.5 * (np.asarray(road.left) + np.asarray(road.right))
            x, z, dx = uniform_samples(x, z)
            slope = np.diff(z) / dx
            P = np.abs(np.fft.rfft(slope - slope.mean())) ** 2
            n = np.fft.rfftfreq(slope.size, dx)
            if P.sum() > 0:
                cum = np.cumsum(P) / P.sum()
                n90 = float(n[np.searchsorted(cum, 0.9)])
                f_road = abs(speed) * min(n90, 1.0 / contact_length)
    return float(np.clip(max(lo, 1.5 * f_road), lo, hi))


# --------------------------------------------------------------------------- modes
def classify_modes(nodes: np.ndarray, shapes: np.ndarray, *, stations=None, tol=0.06):
    """Label free-free elastic modes as ``torsion``, ``bending``, ``lateral`` or ``local``.

    ``shapes`` is (n_nodes, 3, m).  Each station (an x position) gets the least-squares
    rigid section motion (heave ``w``, roll ``theta_x``, sway ``v``); a mode is global when
    these reach 25 % of its largest nodal displacement; torsion when the section roll
    changes sign along the body and dominates, bending when heave dominates.
    """
    X = np.asarray(nodes)
    if stations is None:
        lo, hi = X[:, 0].min(), X[:, 0].max()
        stations = np.linspace(lo + 0.1 * (hi - lo), hi - 0.1 * (hi - lo), 7)
    half_width = 0.5 * np.ptp(X[:, 1])
    labels = []
    for k in range(shapes.shape[2]):
        U = shapes[:, :, k]
        amax = np.abs(U).max()
        w, th, v = [], [], []
        for x0 in stations:
            sel = np.abs(X[:, 0] - x0) < tol
            if sel.sum() < 3:
                continue
            A = np.column_stack([np.ones(sel.sum()), X[sel, 1]])
            (wi, ti), *_ = np.linalg.lstsq(A, U[sel, 2], rcond=None)
            w.append(wi)
            th.append(ti * half_width)
            v.append(U[sel, 1].mean())
        w, th, v = np.array(w), np.array(th), np.array(v)
        size = max(np.abs(w).max(), np.abs(th).max(), np.abs(v).max()) / amax
        if size < 0.25:
            labels.append("local")
        elif np.ptp(th) >= max(np.ptp(w), np.ptp(v)) and th.min() < 0 < th.max():
            labels.append("torsion")
        elif np.ptp(w) >= np.ptp(v):
            labels.append("bending")
        else:
            labels.append("lateral")
    return labels


def global_modes(fe, n: int = 20) -> dict:
    """First global torsion and vertical bending frequencies (Hz) of a free FE body."""
    from flexpipe.fem import eigenmodes

    f, Phi = eigenmodes(fe, n)
    shapes = Phi.reshape(fe.n_nodes, fe.dofs_per_node, -1)[:, :3, 6:]
    labels = classify_modes(fe.nodes, shapes)
    out = {"frequencies_hz": f[6:].tolist(), "labels": labels}
    for kind in ("torsion", "bending"):
        hits = [fk for fk, lab in zip(f[6:], labels, strict=True) if lab == kind]
        out[f"{kind}_hz"] = float(hits[0]) if hits else None
    return out


def describe_modes(mesh_path, *, car=None, n: int = 20) -> str:
    """Text report of a body mesh: mass and first global modes, bare and trimmed."""
    from flexpipe.fem import assemble
    from flexpipe.mesh import read_mesh
    from flexpipe.vehicle.spec import load_car

    lines = []
    fe = assemble(read_mesh(mesh_path))
    g = global_modes(fe, n)
    lines.append(f"BIW: mass {fe.total_mass:.1f} kg, first torsion {g['torsion_hz']} Hz, "
                 f"first bending {g['bending_hz']} Hz")
    if car is not None:
        car = load_car(car)
        fe_t = body_fe(car)
        gt = global_modes(fe_t, n)
        lines.append(f"trimmed ({Path(car.file).name}): mass {fe_t.total_mass:.1f} kg, first "
                     f"torsion {gt['torsion_hz']} Hz, first bending {gt['bending_hz']} Hz")
    return "\n".join(lines)


__all__ = ["CORNERS", "RigidBodyData", "body_fe", "body_key", "body_mesh", "cache_dir",
           "choose_band", "classify_modes", "corner_interfaces", "describe_modes", "global_modes",
           "modal_damping", "point_nodes", "reduced_body", "rigid_properties", "spread_mass"]
