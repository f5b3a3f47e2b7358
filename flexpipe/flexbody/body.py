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

import json
from collections.abc import Mapping
from dataclasses import dataclass, field, fields
from pathlib import Path
from types import MappingProxyType

import numpy as np

from flexpipe._io import atomic_path
from flexpipe.errors import InputError
from flexpipe.flexbody.invariants import FFRFInvariants

FORMAT = "flexpipe-modal-neutral-file"
VERSION = 1
_ARRAYS = ("nodes", "triangles", "modes", "frequencies_hz", "M", "K", "D", "damping_ratio",
           "center_of_mass", "inertia", "inertia_origin")


def _ro(a, dtype=float):
    a = np.array(a, dtype=dtype, copy=True)
    a.setflags(write=False)
    return a


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
        A rigid spider to a new hardpoint, or a 6-DOF mesh node used directly.
    """

    name: str
    point: np.ndarray
    nodes: np.ndarray
    shapes: np.ndarray
    kind: str = "rbe2"

    def __post_init__(self):
        object.__setattr__(self, "point", _ro(self.point).reshape(3))
        object.__setattr__(self, "nodes", _ro(self.nodes, np.int64).reshape(-1))
        object.__setattr__(self, "shapes", _ro(self.shapes).reshape(6, -1))


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

    def __post_init__(self):
        for name in _ARRAYS:
            dtype = np.int64 if name == "triangles" else float
            object.__setattr__(self, name, _ro(getattr(self, name), dtype))
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
            {k: _ro(v) for k, v in dict(self.checks).items()}))
        inv = {k: _ro(v) for k, v in self.invariants.as_dict().items()}
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
        path = Path(path)
        if path.suffix != ".npz":
            raise InputError("a FlexBody file must end in .npz", file=path)
        with atomic_path(path, suffix=".npz") as tmp, open(tmp, "wb") as fh:
            np.savez(fh, **_to_arrays(self))
        return path


def _to_arrays(body: FlexBody) -> dict:
    header = {
        "format": FORMAT, "version": VERSION, "n_rigid": body.n_rigid, "mass": body.mass,
        "method": body.method, "source_hash": body.source_hash, "meta": dict(body.meta),
        "interfaces": [{"name": i.name, "kind": i.kind} for i in body.interfaces],
        "checks": sorted(body.checks),
    }
    out = {"header": np.array(json.dumps(header, sort_keys=True))}
    for name in _ARRAYS:
        out[name] = getattr(body, name)
    for k, v in body.invariants.as_dict().items():
        out[f"invariants.{k}"] = v
    for j, itf in enumerate(body.interfaces):
        out[f"interface.{j}.point"] = itf.point
        out[f"interface.{j}.nodes"] = itf.nodes
        out[f"interface.{j}.shapes"] = itf.shapes
    for k, v in body.checks.items():
        out[f"checks.{k}"] = v
    return out


def load_body(path) -> FlexBody:
    """Read a FlexBody written by :meth:`FlexBody.save`.

    Raises
    ------
    InputError
        Missing file, not a flexpipe modal neutral file, unsupported version or a
        missing entry (named).
    """
    path = Path(path)
    if not path.is_file():
        raise InputError("file not found", file=path)
    try:
        data = np.load(path, allow_pickle=False)
    except Exception as exc:  # noqa: BLE001 - any reader failure is a bad file
        raise InputError(f"not a readable .npz file ({exc})", file=path) from None
    with data:
        if "header" not in data.files:
            raise InputError("not a flexpipe modal neutral file (no 'header' entry)", file=path)
        header = json.loads(str(data["header"]))
        if header.get("format") != FORMAT:
            raise InputError(f"format is {header.get('format')!r}, expected {FORMAT!r}",
                             file=path, key="format")
        if header.get("version") != VERSION:
            raise InputError(f"version {header.get('version')} is not supported; this "
                             f"flexpipe reads version {VERSION}", file=path, key="version")

        def get(key):
            if key not in data.files:
                raise InputError("entry missing (file truncated or written by another tool)",
                                 file=path, key=key)
            return data[key]

        arrays = {name: get(name) for name in _ARRAYS}
        inv = FFRFInvariants(**{f.name: get(f"invariants.{f.name}")
                                for f in fields(FFRFInvariants)})
        interfaces = tuple(
            BodyInterface(name=h["name"], kind=h["kind"], point=get(f"interface.{j}.point"),
                          nodes=get(f"interface.{j}.nodes"),
                          shapes=get(f"interface.{j}.shapes"))
            for j, h in enumerate(header["interfaces"]))
        checks = {k: get(f"checks.{k}") for k in header["checks"]}
    return FlexBody(**arrays, n_rigid=header["n_rigid"], mass=header["mass"], invariants=inv,
                    interfaces=interfaces, method=header["method"],
                    source_hash=header["source_hash"], meta=header["meta"], checks=checks)
