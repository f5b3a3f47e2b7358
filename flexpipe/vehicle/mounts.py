"""Body-side suspension mounts: every mount is an interface of the flexible body.

A :class:`Mount` names a point where the suspension loads the body (a bushing, ball joint,
spring or damper seat, rack mount) and how it ties into the mesh:

* ``point`` alone: the mesh node at the point (a shell/beam node; within
  :data:`NODE_TOL`) is the interface;
* ``point`` + ``radius``: the nodes within ``radius`` are tied to the point (RBE2 spider);
* ``node_set`` (a named set of the mesh, e.g. a Nastran ``SET1`` preceded by
  ``$ SET name``), ``node_ids`` (ids as in the mesh file: Nastran GRID ids, Gmsh node
  tags; what the car file's ``[body.mounts.<mount>] node_ids`` gives) or ``nodes`` (0-based
  positions in ``Mesh.points``, as :class:`flexpipe.Interface` takes; ``Mesh.node_index``
  turns ids into positions): those nodes are tied to ``point``, or to their centroid when
  no point is given.

``dofs`` = 3 (forces only: ball joints, bushings, spring seats) or 6 (forces and moments).
:func:`mount_interfaces` checks the mounts against the mesh and returns the
:class:`~flexpipe.reduction.Interface` list that :func:`flexpipe.reduce` takes;
:func:`read_hardpoints` reads the ``$ HARDPOINT name x y z`` comments of a Nastran deck.
"""

from __future__ import annotations

import functools
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from flexpipe.errors import InputError

#: a mount point farther than this from every body node is "off the body", m
OFF_BODY_TOL = 0.05
#: a mount without radius/node set/nodes must coincide with a node within this distance, m
NODE_TOL = 1e-6
_HARDPOINT = re.compile(r"^\$\s*HARDPOINT\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s*$")


@dataclass(frozen=True)
class Mount:
    """A body-side suspension mount (see the module docstring).

    Parameters
    ----------
    name : str
        Interface and marker name, e.g. ``front_lower_arm_front_l``.
    point : (3,) array_like, optional
        Mount point in body (mesh) coordinates, m.
    radius : float, optional
        Tie the nodes within this distance of ``point``, m.
    dofs : {3, 6}
        Boundary DOF of the reduction at this mount.
    node_set : str, optional
        Tie the nodes of this named mesh node set.
    nodes : tuple of int, optional
        Tie these nodes, given as 0-based positions in ``Mesh.points`` (not the file's ids).
    node_ids : tuple of int, optional
        Tie these nodes, given by their ids in the mesh file (``Mesh.node_ids``: Nastran
        GRID ids, Gmsh node tags, Abaqus node numbers), as the car file does.
    source : tuple, optional
        ``(file, line, table)`` of the car file's ``[body.mounts.<name>]`` table the tie
        came from; errors about the mount then name that file, line and key.
    """

    name: str
    point: tuple | None = None
    radius: float | None = None
    dofs: int = 3
    node_set: str | None = None
    nodes: tuple | None = None
    node_ids: tuple | None = None
    source: tuple | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        if not isinstance(self.name, str) or not self.name:
            raise InputError(f"a mount needs a name, got {self.name!r}", key="mounts")
        key = f"mounts.{self.name}"
        if self.point is not None:
            p = np.asarray(self.point, dtype=float).reshape(-1)
            if p.shape != (3,) or not np.all(np.isfinite(p)):
                raise InputError(f"point must be 3 finite numbers (m), got {self.point!r}",
                                 key=f"{key}.point")
            object.__setattr__(self, "point", tuple(float(v) for v in p))
        if self.dofs not in (3, 6) or isinstance(self.dofs, bool):
            raise InputError(f"dofs must be 3 (forces only) or 6 (forces and moments), got "
                             f"{self.dofs!r}", key=f"{key}.dofs")
        given = [k for k in ("radius", "node_set", "nodes", "node_ids")
                 if getattr(self, k) is not None]
        if len(given) > 1:
            raise InputError(f"give one of radius, node_set, nodes, node_ids (got {given})",
                             key=key)
        if self.point is None and not ({"node_set", "nodes", "node_ids"} & set(given)):
            raise InputError("give a point (with an optional radius), a node_set, nodes or "
                             "node_ids", key=key)
        if self.radius is not None and not (np.isfinite(self.radius) and self.radius > 0):
            raise InputError(f"radius must be a positive length in m, got {self.radius!r}",
                             key=f"{key}.radius")
        for k in ("nodes", "node_ids"):
            v = getattr(self, k)
            if v is not None:
                a = np.asarray(v).reshape(-1)
                if a.dtype == bool or (a.size and not np.issubdtype(a.dtype, np.integer)):
                    raise InputError(f"{k} must be integers, got {list(a)[:10]}",
                                     key=f"{key}.{k}")
                object.__setattr__(self, k, tuple(int(i) for i in a))

    def cache_key(self) -> list:
        """The fields that decide the reduced body (for the body cache's key)."""
        out = [self.name, self.point, self.radius, self.dofs, self.node_set, self.nodes]
        return out if self.node_ids is None else out + [list(self.node_ids)]

    def where(self, field: str | None = None, *, file=None) -> dict:
        """``file``, ``line`` and ``key`` of an error about ``field`` of this mount: its
        car-file table (``source``) when it has one, else ``file`` and ``mounts.<name>``."""
        if self.source is None:
            return {"file": file, "key": f"mounts.{self.name}" + (f".{field}" if field else "")}
        src, line, table = self.source
        car_key = {"point": "point_m", "radius": "radius_m"}
        return {"file": src, "line": line,
                "key": table + (f".{car_key.get(field, field)}" if field else "")}


def as_mount(m) -> Mount:
    """A :class:`Mount` from a Mount, a ``(name, point, radius, dofs)`` tuple (radius may be
    None) or a dict of Mount fields."""
    if isinstance(m, Mount):
        return m
    if isinstance(m, dict):
        unknown = set(m) - {"name", "point", "radius", "dofs", "node_set", "nodes", "node_ids"}
        if unknown:
            raise InputError(f"unknown mount keys {sorted(unknown)}; valid: name, point, "
                             "radius, dofs, node_set, nodes, node_ids",
                             key=f"mounts.{m.get('name')}")
        return Mount(**m)
    if isinstance(m, (tuple, list)) and 2 <= len(m) <= 4:
        return Mount(*m)
    raise InputError(f"a mount is a Mount, a dict or (name, point, radius, dofs), got {m!r}",
                     key="mounts")


def mount_interfaces(mounts, mesh, *, file=None) -> list:
    """Interfaces of ``mounts`` on ``mesh`` (a :class:`~flexpipe.mesh.Mesh` or an (n, 3)
    array of node positions), checked to lie on the body.

    Raises
    ------
    InputError
        A point farther than :data:`OFF_BODY_TOL` from every node, a point without
        radius that is not a node, an unknown node set, node ids that are not in the mesh
        (the valid range and the nearest ids named), positions out of range, duplicate
        names.  A mount read from the car file (``Mount.source``) is named by its file,
        line and key there, else by ``file`` and ``mounts.<name>``.
    """
    from flexpipe.reduction import Interface

    X = np.asarray(mesh.points if hasattr(mesh, "points") else mesh, dtype=float)
    sets = getattr(mesh, "node_sets", {}) or {}
    out, seen = [], set()
    for m in map(as_mount, mounts):
        if m.name in seen:
            raise InputError(f"mount name {m.name!r} is used twice", **m.where(file=file))
        seen.add(m.name)
        point = m.point
        if m.node_set is not None:
            from flexpipe.reduction.interface import find_node_set

            try:
                found = find_node_set(sets, m.node_set)
            except InputError as exc:
                raise InputError(exc.message.replace("the mesh", "the body mesh"),
                                 **m.where("node_set", file=file)) from None
            idx = np.asarray(sets[found], dtype=np.int64)
        elif m.node_ids is not None:
            if not hasattr(mesh, "node_index"):
                raise InputError("node ids need the body as a flexpipe.mesh.Mesh (its "
                                 "node_ids), not an array of node positions; give nodes= "
                                 "(0-based positions) instead", **m.where("node_ids", file=file))
            if not m.node_ids:
                raise InputError("node_ids is empty", **m.where("node_ids", file=file))
            idx = mesh.node_index(m.node_ids, **m.where("node_ids", file=file))
        elif m.nodes is not None:
            idx = np.asarray(m.nodes, dtype=np.int64)
            if idx.size == 0 or idx.min() < 0 or idx.max() >= len(X):
                raise InputError(f"node positions (0-based) must lie in [0, {len(X)}), got "
                                 f"{list(m.nodes)[:10]}; for the mesh file's node ids give "
                                 "node_ids", **m.where("nodes", file=file))
        else:
            idx = None
        if point is None:
            point = tuple(X[idx].mean(axis=0))
        elif idx is not None:
            _check_tie_reach(m, X, idx, point, mesh, file)
        d = np.linalg.norm(X - np.asarray(point), axis=1)
        k = int(d.argmin())
        if d[k] > OFF_BODY_TOL:
            raise InputError(
                f"mount point {tuple(np.round(point, 4))} m is off the body: the nearest body "
                f"node is {d[k]:.3f} m away at {tuple(np.round(X[k], 4))}; a mount must lie "
                f"within {OFF_BODY_TOL} m of the structure", **m.where("point", file=file))
        if idx is None and m.radius is None and d[k] > NODE_TOL:
            raise InputError(
                f"mount point {tuple(np.round(point, 4))} m is not a mesh node (nearest "
                f"{d[k] * 1e3:.1f} mm away); give a radius to tie the nodes around it",
                **m.where("radius", file=file))
        if idx is not None:
            out.append(Interface(point, nodes=idx, name=m.name, dofs=m.dofs))
        elif m.radius is not None:
            out.append(Interface(point, radius=m.radius, name=m.name, dofs=m.dofs))
        else:
            out.append(Interface(tuple(X[k]), name=m.name, dofs=m.dofs))
    return out


def _check_tie_reach(m: Mount, X, idx, point, mesh, file) -> None:
    """The nodes a mount ties by ``node_set``/``node_ids``/``nodes`` must reach its point
    (:data:`flexpipe.reduction.interface.TIE_TOL`: the nearest tied node or their
    centroid within 0.05 m), else an error naming the mount, the distance and the nodes
    that would be valid."""
    from flexpipe.reduction.interface import TIE_TOL, tie_distance

    near, kn, cen = tie_distance(X, idx, point)
    if min(near, cen) <= TIE_TOL:
        return
    field = next(k for k in ("node_set", "node_ids", "nodes") if getattr(m, k) is not None)

    def node(i):
        if hasattr(mesh, "describe_node"):
            return mesh.describe_node(int(i))
        return f"node position {int(i)} at {tuple(np.round(X[i], 4))} m"

    d = np.linalg.norm(X - np.asarray(point), axis=1)
    close = np.flatnonzero(d <= TIE_TOL)
    close = close[np.argsort(d[close])][:8] if close.size else np.array([int(d.argmin())])
    ids = getattr(mesh, "node_ids", None)
    valid = [int(ids[i]) if ids is not None else int(i) for i in close]
    what = {"node_set": f"node set {m.node_set!r}", "node_ids": "node_ids",
            "nodes": "nodes"}[field]
    raise InputError(
        f"mount {m.name!r}: its {what} ({len(idx)} node(s)) does not reach the mount point "
        f"{tuple(np.round(point, 4))} m: the nearest tied node is {near:.3f} m away "
        f"({node(kn)}) and their centroid {cen:.3f} m; the tied nodes must include a node "
        f"within {TIE_TOL} m of the mount point or be centred on it within {TIE_TOL} m. "
        f"Nodes near the point ({'ids' if ids is not None else 'positions'}): {valid}; "
        "give the node set or node ids of the nodes at this mount",
        **m.where(field, file=file))


@functools.lru_cache(maxsize=4)
def _body_mesh(path: str, stamp: tuple, scale: float, units, thickness):
    """The body mesh (node ids, positions, node sets), read once per file version
    (``stamp``: mtime, size) so that a sweep's checks of many runs on one body read its
    mesh once."""
    from flexpipe.mesh import read_mesh

    return read_mesh(path, scale, units=units, thickness=thickness, check_coincident=False)


def check_mount_node_ids(car) -> None:
    """Check the car file's ``[body.mounts.<mount>]`` ties by ``node_ids`` or
    ``node_set`` against the body mesh before any output is written (the reduction checks
    them again, with the same message): the ids must be nodes of the mesh, the set must
    exist, and the tied nodes must reach the mount point (:func:`mount_interfaces`).
    Reads the mesh only when a mount gives node ids or a node set.

    Raises
    ------
    InputError
        Ids that are no node of the mesh, named by the car file, the line of the
        ``[body.mounts.<mount>]`` table and the key ``body.mounts.<mount>.node_ids``,
        with the valid id range, the node count and the nearest existing ids; an unknown
        node set; tied nodes farther than 0.05 m from the mount point.
    MeshError
        The body mesh cannot be read.
    """
    from flexpipe.mesh.mesh import index_of_ids

    body = car.body
    if body.body_file is not None:  # a ready body: its interfaces, not the mesh's ids
        from flexpipe.vehicle.bodymodel import check_body_file

        check_body_file(car)
        return
    given = {n: g for n, g in (body.mounts or {}).items()
             if g.get("node_ids") is not None or g.get("node_set") is not None}
    if not given or body.mesh is None:
        return
    path = Path(body.mesh)
    try:
        st = path.stat()
        stamp = (st.st_mtime_ns, st.st_size)
    except OSError:
        stamp = None  # read_mesh names the missing file
    mesh = _body_mesh(str(path), stamp, body.mesh_scale, body.mesh_units,
                      body.shell_thickness)
    for name, g in given.items():
        if g.get("node_ids") is not None:
            index_of_ids(mesh.node_ids, g["node_ids"], file=car.file, line=g.get("line"),
                         key=f"body.mounts.{name}.node_ids")
    if getattr(car, "suspension", None) is not None:  # the ties against the mount points
        from flexpipe.vehicle.linkage_setup import body_mounts

        mount_interfaces([m for m in body_mounts(car) if m.name in given], mesh,
                         file=car.file)


def read_hardpoints(path) -> dict:
    """``{name: (x, y, z)}`` from the ``$ HARDPOINT name x y z`` comments of a deck."""
    path = Path(path)
    out = {}
    try:
        lines = path.read_text(errors="replace").splitlines()
    except OSError as exc:
        raise InputError(f"cannot read ({exc})", file=path) from None
    for i, line in enumerate(lines, start=1):
        hit = _HARDPOINT.match(line.strip())
        if hit:
            try:
                out[hit.group(1)] = tuple(float(v) for v in hit.groups()[1:])
            except ValueError:
                raise InputError(f"'{line.strip()}': expected $ HARDPOINT name x y z with "
                                 "numbers in m", file=path, line=i) from None
    return out


__all__ = ["Mount", "NODE_TOL", "OFF_BODY_TOL", "as_mount", "check_mount_node_ids",
           "mount_interfaces", "read_hardpoints"]


#: largest distance (m) of a ready body's interface from the car's point of that mount
INTERFACE_POINT_TOL = 5e-3


def check_interface_points(fb, points: dict, *, car) -> None:
    """Every interface of the ready body ``fb`` named in ``points`` ({name: point, m}) must
    sit within :data:`INTERFACE_POINT_TOL` of that point: else an error naming the car
    file, the body file, the interface, both points, and the interface of the body nearest
    the car's point (a swapped name shows as another mount's interface there)."""
    have = {i.name: np.asarray(i.point, dtype=float) for i in fb.interfaces}
    for name, p in points.items():
        p = np.asarray(p, dtype=float)
        off = float(np.linalg.norm(have[name] - p))
        if off > INTERFACE_POINT_TOL:
            near = min(have, key=lambda n: float(np.linalg.norm(have[n] - p)))
            hint = (f"; the body's interface at that point is {near!r}: are the names "
                    "swapped in the interface spec?" if near != name and np.linalg.norm(
                        have[near] - p) <= INTERFACE_POINT_TOL else "")
            raise InputError(
                f"the body file {car.body.body_file.name}: interface {name!r} sits at "
                f"{tuple(np.round(have[name], 4))} m, {off * 1e3:.1f} mm from the car's point "
                f"of that mount {tuple(np.round(p, 4))} m (valid: within "
                f"{INTERFACE_POINT_TOL * 1e3:g} mm){hint}; reduce the body with the car's "
                "mount points", file=car.file, key="body.body_file")
