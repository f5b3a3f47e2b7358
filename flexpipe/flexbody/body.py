"""The :class:`FlexBody`: flexpipe's modal neutral file, and its ``.npz`` storage.

A FlexBody is everything a multibody code needs about a modally reduced flexible body:
node positions and surface triangles (drawing), translational mode shapes, reduced
mass/stiffness/damping, the exact rigid-body mass properties, the FFRF inertia
invariants (:mod:`flexpipe.flexbody.invariants`) and the interfaces (hardpoints with
their 6-DOF motion per mode).  The first ``n_rigid`` modes are the rigid-body modes;
the floating frame of reference replaces them in a multibody model.

``body.save(path)`` writes one versioned ``.npz`` file atomically; :func:`load_body`
reads it back bit-for-bit (no pickles: plain arrays plus a JSON header).
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path
from types import MappingProxyType

import numpy as np

from flexpipe._args import as_path
from flexpipe._arrays import readonly
from flexpipe._io import atomic_path
from flexpipe.errors import InputError
from flexpipe.flexbody.invariants import FFRFInvariants
from flexpipe.flexbody.stress import StressModes

FORMAT = "flexpipe-modal-neutral-file"
VERSION = 1
_ARRAYS = ("nodes", "triangles", "modes", "frequencies_hz", "M", "K", "D", "damping_ratio",
           "center_of_mass", "inertia", "inertia_origin")


@dataclass(frozen=True, eq=False)
class BodyInterface:
    """An interface of a reduced body: a hardpoint and the mesh nodes tied to it.

    Attributes
    ----------
    name : str
    point : ndarray (3,)
        Hardpoint position in body (mesh) coordinates, m.
    nodes : ndarray of int (k,)
        Mesh node indices tied to the hardpoint (the node itself for a 6-DOF node).
    shapes : ndarray (6, n_modes)
        Hardpoint motion per mode: translations ux, uy, uz (m) and small rotations
        rx, ry, rz (rad) per unit modal coordinate.
    kind : {"rbe2", "node"}
        A rigid spider to a new hardpoint, or a mesh node used directly.
    dofs : {6, 3}
        Boundary DOF of the reduction at this interface: 6 (forces and moments) or 3
        (translations only: ball joints, bushings, spring seats).  For a 3-DOF interface
        the rotation rows of ``shapes`` are the spider's rotation where the model has one
        (zero for a solid node); moments applied there are not reproduced exactly.
    residual_compliance : ndarray (dofs, dofs)
        Static flexibility at this interface that an interface reduction dropped (m/N,
        rad/(N m)): put it in series with the bushing there.  Zero without interface
        reduction.
    """

    name: str
    point: np.ndarray
    nodes: np.ndarray
    shapes: np.ndarray
    kind: str = "rbe2"
    dofs: int = 6
    residual_compliance: np.ndarray | None = None

    def __post_init__(self):
        if int(self.dofs) not in (3, 6):
            raise ValueError(f"interface {self.name!r}: dofs must be 3 or 6, got {self.dofs!r}")
        object.__setattr__(self, "dofs", int(self.dofs))
        C = np.zeros((self.dofs, self.dofs)) if self.residual_compliance is None \
            else self.residual_compliance
        object.__setattr__(self, "residual_compliance", readonly(C).reshape(self.dofs, self.dofs))
        object.__setattr__(self, "point", readonly(self.point).reshape(3))
        object.__setattr__(self, "nodes", readonly(self.nodes, np.int64).reshape(-1))
        object.__setattr__(self, "shapes", readonly(self.shapes).reshape(6, -1))


@dataclass(frozen=True, eq=False)
class FlexBody:
    """A modally reduced flexible body (frozen; arrays are read-only).

    Attributes
    ----------
    nodes : ndarray (n, 3)
        Mesh node positions in body coordinates (the mesh's own), m.
    triangles : ndarray of int (t, 3)
        Outer-surface triangles over ``nodes``, for drawing.
    modes : ndarray (n, 3, m)
        Translational mode shapes, orthonormal with respect to the full mass matrix.
    frequencies_hz : ndarray (m,)
        Free-free natural frequencies of the reduced body, ascending; the ``n_rigid``
        rigid-body modes (~0 Hz) first.
    n_rigid : int
        Number of rigid-body modes (6 for a free body).
    M, K, D : ndarray (m, m)
        Reduced mass (identity), stiffness (``diag(omega^2)``), damping
        (``diag(2 zeta omega)``).
    damping_ratio : ndarray (m,)
        Modal damping ratio per mode (0 for rigid-body modes).
    mass : float
        kg.
    center_of_mass : ndarray (3,)
        Body coordinates, m.
    inertia : ndarray (3, 3)
        Inertia tensor about the centre of mass, body axes, kg m^2.
    inertia_origin : ndarray (3, 3)
        Inertia tensor about the body-coordinate origin (what Exudyn takes), kg m^2.
    invariants : FFRFInvariants
        FFRF invariants of the elastic modes ``modes[:, :, n_rigid:]``.
    interfaces : tuple of BodyInterface
    method : str
        "craig-bampton", "residual-flexibility" or "modal-truncation".
    source_hash : str
        SHA-256 of the source mesh (points and cells).
    meta : mapping
        Scalars and strings: DOF counts, options used, flexpipe version, timings.
    checks : mapping of str to ndarray
        Optional verification data written by ``reduce(..., check=True)``: full-model
        frequencies, MAC matrix, mesh mass properties.
    stress : StressModes or None
        Element stresses per elastic mode (``reduce(..., stress=...)``), for modal stress
        recovery (:mod:`flexpipe.flexbody.stress`).
    """

    nodes: np.ndarray
    triangles: np.ndarray
    modes: np.ndarray
    frequencies_hz: np.ndarray
    n_rigid: int
    M: np.ndarray
    K: np.ndarray
    D: np.ndarray
    damping_ratio: np.ndarray
    mass: float
    center_of_mass: np.ndarray
    inertia: np.ndarray
    inertia_origin: np.ndarray
    invariants: FFRFInvariants
    interfaces: tuple[BodyInterface, ...] = ()
    method: str = ""
    source_hash: str = ""
    meta: Mapping[str, object] = field(default_factory=dict)
    checks: Mapping[str, np.ndarray] = field(default_factory=dict)
    stress: StressModes | None = None

    def __post_init__(self):
        for name in _ARRAYS:
            dtype = np.int64 if name == "triangles" else float
            object.__setattr__(self, name, readonly(getattr(self, name), dtype))
        n, m = len(self.nodes), len(self.frequencies_hz)
        if self.modes.shape != (n, 3, m):
            raise ValueError(f"modes must have shape ({n}, 3, {m}), got {self.modes.shape}")
        for name in ("M", "K", "D"):
            if getattr(self, name).shape != (m, m):
                raise ValueError(f"{name} must be ({m}, {m}), got {getattr(self, name).shape}")
        if not 0 <= int(self.n_rigid) <= m:
            raise ValueError(f"n_rigid={self.n_rigid} must lie in [0, {m}]")
        object.__setattr__(self, "n_rigid", int(self.n_rigid))
        object.__setattr__(self, "mass", float(self.mass))
        object.__setattr__(self, "interfaces", tuple(self.interfaces))
        names = [i.name for i in self.interfaces]
        if len(set(names)) != len(names):
            raise ValueError(f"interface names must be unique, got {names}")
        object.__setattr__(self, "meta", MappingProxyType(dict(self.meta)))
        object.__setattr__(self, "checks", MappingProxyType(
            {k: readonly(v) for k, v in dict(self.checks).items()}))
        inv = {k: readonly(v) for k, v in self.invariants.as_dict().items()}
        object.__setattr__(self, "invariants", FFRFInvariants(**inv))

    def __reduce__(self):
        # standard pickle cannot take the read-only mapping proxies: rebuild from plain dicts
        args = tuple(dict(v) if isinstance(v, MappingProxyType) else v
                     for v in (getattr(self, f.name) for f in fields(self)))
        return (type(self), args)

    # ------------------------------------------------------------------ views
    @property
    def n_nodes(self) -> int:
        """Number of mesh nodes."""
        return len(self.nodes)

    @property
    def n_modes(self) -> int:
        """Number of modes including rigid-body modes."""
        return len(self.frequencies_hz)

    @property
    def n_elastic(self) -> int:
        """Number of elastic modes (the modal coordinates of the floating-frame body)."""
        return self.n_modes - self.n_rigid

    @property
    def omega(self) -> np.ndarray:
        """Circular frequencies, rad/s."""
        return 2 * np.pi * self.frequencies_hz

    @property
    def elastic_modes(self) -> np.ndarray:
        """Elastic mode shapes as a (3 n, n_elastic) matrix, node-major x, y, z rows."""
        return self.modes[:, :, self.n_rigid:].reshape(3 * self.n_nodes, self.n_elastic)

    @property
    def interface_names(self) -> tuple[str, ...]:
        """Interface names, in order."""
        return tuple(i.name for i in self.interfaces)

    def interface(self, name: str) -> BodyInterface:
        """The interface called ``name``."""
        for itf in self.interfaces:
            if itf.name == name:
                return itf
        raise InputError(f"body has no interface {name!r}; valid: {list(self.interface_names)}",
                         key=name)

    def __eq__(self, other) -> bool:
        if not isinstance(other, FlexBody):
            return NotImplemented
        a, b = _to_arrays(self), _to_arrays(other)
        return a.keys() == b.keys() and all(np.array_equal(a[k], b[k]) for k in a)

    __hash__ = None

    def __repr__(self) -> str:
        return (f"FlexBody({self.method}, {self.n_nodes} nodes, {self.n_rigid} rigid + "
                f"{self.n_elastic} elastic modes, mass {self.mass:.6g} kg, interfaces "
                f"{list(self.interface_names)})")

    # ------------------------------------------------------------------ storage
    def save(self, path) -> Path:
        """Write the body to ``path`` (``.npz``) atomically; returns the path."""
        path = as_path(path, "path")
        if path.suffix != ".npz":
            raise InputError("a FlexBody file must end in .npz", file=path)
        with atomic_path(path, suffix=".npz") as tmp, open(tmp, "wb") as fh:
            np.savez(fh, **_to_arrays(self, with_hash=True))
        return path


def _to_arrays(body: FlexBody, *, with_hash: bool = False) -> dict:
    header = {
        "format": FORMAT, "version": VERSION, "n_rigid": body.n_rigid, "mass": body.mass,
        "method": body.method, "source_hash": body.source_hash, "meta": dict(body.meta),
        "interfaces": [{"name": i.name, "kind": i.kind, "dofs": i.dofs}
                       for i in body.interfaces],
        "checks": sorted(body.checks),
    }
    stress_arrays = {}
    if body.stress is not None:  # optional entries: files without them load as before
        header["stress"], stress_arrays = body.stress.to_arrays()
    out = {}
    for name in _ARRAYS:
        out[name] = getattr(body, name)
    for k, v in body.invariants.as_dict().items():
        out[f"invariants.{k}"] = v
    for j, itf in enumerate(body.interfaces):
        out[f"interface.{j}.point"] = itf.point
        out[f"interface.{j}.nodes"] = itf.nodes
        out[f"interface.{j}.shapes"] = itf.shapes
        out[f"interface.{j}.residual_compliance"] = itf.residual_compliance
    for k, v in body.checks.items():
        out[f"checks.{k}"] = v
    out.update(stress_arrays)
    if with_hash:
        header["content_sha256"] = content_hash(header, out)
    out["header"] = np.array(json.dumps(header, sort_keys=True))
    return out


def content_hash(header: dict, arrays: Mapping[str, np.ndarray]) -> str:
    """SHA-256 over the header (without its own hash) and every stored array.

    Each array enters with its name, dtype, shape and bytes, so a changed value, a
    scaled matrix or a NaN written into the file changes the hash.
    """
    h = hashlib.sha256()
    head = {k: v for k, v in header.items() if k != "content_sha256"}
    h.update(json.dumps(head, sort_keys=True).encode())
    for name in sorted(arrays):
        if name == "header":
            continue
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}|{a.dtype.str}|{a.shape}|".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def load_body(path) -> FlexBody:
    """Read a FlexBody written by :meth:`FlexBody.save`, verified.

    The stored content hash (files written since flexpipe 0.1 carry one) is checked
    against the arrays, then the body itself: finite arrays, positive mass, a symmetric
    positive semi-definite inertia, non-negative ascending frequencies, ``K`` matching
    the frequencies, triangle and interface node indices inside the node range.

    Raises
    ------
    InputError
        Missing or unreadable file, not a flexpipe modal neutral file, unsupported
        version, a missing or malformed entry (named by its key), a content-hash
        mismatch or an inconsistent body (named by key).
    """
    path = as_path(path, "path")
    if not path.is_file():
        raise InputError("file not found (or not a regular file)", file=path)
    try:
        return _load(path)
    except InputError:
        raise
    except Exception as exc:  # noqa: BLE001 - any other failure means a corrupt file
        raise InputError(f"corrupt or truncated flexpipe body file ({_reason(exc)}); write it "
                         "again with FlexBody.save or 'flexpipe reduce'", file=path) from None


def _reason(exc: BaseException) -> str:
    text = " ".join(str(exc).split()) or type(exc).__name__
    if "allow_pickle" in text:  # numpy's hint would invite loading untrusted pickles
        text = "holds Python objects (pickles), not plain arrays"
    return f"{type(exc).__name__}: {text[:200]}"


def _load(path: Path) -> FlexBody:
    with path.open("rb") as fh:   # a zip starts with a local header or (empty) end record
        head = fh.read(16)
    if not head.startswith((b"PK\x03\x04", b"PK\x05\x06", np.lib.format.MAGIC_PREFIX)):
        what = f"it starts with {head!r}" if head else "the file is empty"
        raise InputError(f"not a .npz (zip) archive ({what}); expected a flexpipe body file "
                         "written by 'flexpipe reduce' (FlexBody.save)", file=path)
    try:
        data = np.load(path, allow_pickle=False)
    except Exception as exc:  # noqa: BLE001 - any reader failure is a bad file
        raise InputError(f"not a readable .npz file ({_reason(exc)})", file=path) from None
    if not hasattr(data, "files"):
        raise InputError("a single .npy array, not a flexpipe .npz body file", file=path)
    with data:
        if "header" not in data.files:
            raise InputError("not a flexpipe modal neutral file (no 'header' entry)", file=path)

        def get(key):
            if key not in data.files:
                raise InputError("entry missing (file truncated or written by another tool)",
                                 file=path, key=key)
            try:
                return data[key]
            except Exception as exc:  # noqa: BLE001 - CRC error, truncated member, pickle
                raise InputError(f"entry unreadable ({_reason(exc)})", file=path,
                                 key=key) from None

        try:
            header = json.loads(str(get("header")))
        except ValueError as exc:
            raise InputError(f"header is not JSON ({exc})", file=path, key="header") from None
        if not isinstance(header, dict):
            raise InputError("header must be a JSON object", file=path, key="header")
        if header.get("format") != FORMAT:
            raise InputError(f"format is {header.get('format')!r}, expected {FORMAT!r}",
                             file=path, key="format")
        if header.get("version") != VERSION:
            raise InputError(f"version {header.get('version')!r} is not supported; this "
                             f"flexpipe reads version {VERSION}", file=path, key="version")
        _check_header(path, header)
        stored = {k: get(k) for k in data.files if k != "header"}
    for key in stored:
        if stored[key].dtype.kind not in "biuf":
            raise InputError(f"entry has dtype {stored[key].dtype}; expected numbers",
                             file=path, key=key)
    required = [*_ARRAYS, *(f"invariants.{f.name}" for f in fields(FFRFInvariants)),
                *(f"interface.{j}.{k}" for j in range(len(header["interfaces"]))
                  for k in ("point", "nodes", "shapes")),
                *(f"checks.{k}" for k in header["checks"])]
    for key in required:
        if key not in stored:
            raise InputError("entry missing (file truncated or written by another tool)",
                             file=path, key=key)
    if "content_sha256" in header and content_hash(header, stored) != header[
            "content_sha256"]:
        raise InputError("content hash mismatch: the stored arrays or header were changed or "
                         "corrupted after the file was written; write it again", file=path,
                         key="content_sha256")

    def get2(key):
        if key not in stored:
            raise InputError("entry missing (file truncated or written by another tool)",
                             file=path, key=key)
        return stored[key]

    arrays = {name: get2(name) for name in _ARRAYS}
    inv = FFRFInvariants(**{f.name: get2(f"invariants.{f.name}")
                            for f in fields(FFRFInvariants)})
    interfaces = []
    for j, h in enumerate(header["interfaces"]):
        try:
            interfaces.append(BodyInterface(
                name=h["name"], kind=h["kind"], dofs=h.get("dofs", 6),
                point=get2(f"interface.{j}.point"), nodes=get2(f"interface.{j}.nodes"),
                shapes=get2(f"interface.{j}.shapes"),
                residual_compliance=stored.get(f"interface.{j}.residual_compliance")))
        except (ValueError, TypeError) as exc:
            raise InputError(f"malformed interface ({exc})", file=path,
                             key=f"interface.{j}") from None
    checks = {k: get2(f"checks.{k}") for k in header["checks"]}
    stress = _stress(path, header, get2)
    from flexpipe.flexbody.checks import check_body_arrays

    check_body_arrays(path, header, arrays, inv, interfaces)
    try:
        return FlexBody(**arrays, n_rigid=header["n_rigid"], mass=header["mass"],
                        invariants=inv, interfaces=interfaces, method=header["method"],
                        source_hash=header["source_hash"], meta=header["meta"], checks=checks,
                        stress=stress)
    except (ValueError, TypeError) as exc:
        raise InputError(f"inconsistent body: {exc}", file=path, key="header") from None


def _stress(path, header, get):
    """The optional stress modes (None for files without them)."""
    if not header.get("stress"):
        return None
    try:
        return StressModes.from_arrays(header["stress"], get)
    except InputError:
        raise
    except (KeyError, IndexError, TypeError, ValueError, AttributeError) as exc:
        raise InputError(f"malformed stress modes ({type(exc).__name__}: {exc})", file=path,
                         key="stress") from None


def _check_header(path, header) -> None:
    types = {"n_rigid": int, "mass": (int, float), "method": str, "source_hash": str,
             "meta": dict, "interfaces": list, "checks": list}
    for key, t in types.items():
        if key not in header:
            raise InputError("header entry missing", file=path, key=f"header.{key}")
        v = header[key]
        if not isinstance(v, t) or isinstance(v, bool):
            raise InputError(f"header entry has the wrong type ({type(v).__name__})",
                             file=path, key=f"header.{key}")
    for j, h in enumerate(header["interfaces"]):
        if not (isinstance(h, dict) and isinstance(h.get("name"), str)
                and h.get("kind") in ("rbe2", "node")):
            raise InputError("each interface needs a string 'name' and kind 'rbe2' or 'node'",
                             file=path, key=f"header.interfaces[{j}]")
    if not all(isinstance(c, str) for c in header["checks"]):
        raise InputError("check names must be strings", file=path, key="header.checks")
