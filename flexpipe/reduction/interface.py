"""Interfaces: hardpoints tied to mesh nodes by a rigid spider (RBE2), and the constraint
map that turns them into 6 boundary DOF each.

An interface is resolved against an :class:`~flexpipe.fem.FEModel` into a set of mesh
nodes: those within ``radius`` of the point, a named node set of the mesh, explicit
nodes (0-based positions, ``Mesh.node_index`` for file ids), or -- when none is given --
the 6-DOF (shell/beam) node at the point, which is then the interface itself.  The spider
is applied on the independent DOF of the model: every tied node DOF is replaced by the
rigid motion of the hardpoint,
``u = u_h + theta_h x (x - x_h)`` and ``theta = theta_h``.

An interface has 6 boundary DOF (the hardpoint's translations and rotations: it transmits
forces and moments) or 3 (``dofs=3``: translations only, for ball joints, bushings and
spring seats that transmit forces only).  With 3, the spider stays rigid but its rotation
is an interior DOF of the reduction (statically condensed like the rest of the body); a
solid node without rotations can then be an interface on its own.
"""

from __future__ import annotations

from dataclasses import KW_ONLY, dataclass, field

import numpy as np
import scipy.sparse as sp

from flexpipe.errors import InputError
from flexpipe.fem.model import FEModel
from flexpipe.flexbody.invariants import skew

#: a tie given by nodes (node set, node ids) must reach its point: its nearest tied node,
#: or the centroid of its nodes (a ring of bolt-hole nodes around the point), within this
#: distance of the point, m.  The same 0.05 m as the car file's off-body rule for mount
#: points (flexpipe.vehicle.mounts.OFF_BODY_TOL): a few element sizes of a 10-30 mm body
#: mesh, far below the spacing of distinct mounts (0.25 m and more between a strut top and
#: its neighbours), so a set or id typed for another mount, or points typed in mm, fail.
TIE_TOL = 0.05
#: a radius tie catching more than this fraction of the mesh's nodes is warned about
RADIUS_WARN_FRACTION = 0.05


def find_node_set(sets: dict, name: str, *, key=None, file=None, line=None) -> str:
    """The key of ``sets`` that names node set ``name``: the exact name, else the one
    name equal to it ignoring case (Abaqus set names are case-insensitive: ``*NSET,
    NSET=MOUNT_FL`` is ``mount_fl``).

    Raises
    ------
    InputError
        No such set (the valid names listed, those matching ignoring case first), or
        several sets equal to ``name`` ignoring case and none exactly.
    """
    if name in sets:
        return name
    hits = sorted(k for k in sets if isinstance(k, str) and k.casefold() == name.casefold())
    if len(hits) == 1:
        return hits[0]
    where = {"key": key, "file": file, "line": line}
    if hits:
        raise InputError(f"node set {name!r} is ambiguous: the mesh has {hits}, which differ "
                         "only in case; give the exact name", **where)
    names = sorted(sets, key=lambda k: (not str(k)[:1].isalpha(), str(k).casefold()))
    raise InputError(f"the mesh has no node set {name!r}; valid: {names[:40]}"
                     + (f" and {len(names) - 40} more" if len(names) > 40 else ""), **where)


def tie_distance(X, nodes, point) -> tuple[float, int, float]:
    """``(nearest, k, centroid)`` for tied ``nodes`` (0-based positions in ``X``) of a
    point: the distance of the nearest tied node (``k``, a position in ``X``) and of
    the tied nodes' centroid from ``point``, m."""
    X = np.asarray(X, dtype=float)
    nodes = np.asarray(nodes, dtype=np.int64).reshape(-1)
    d = np.linalg.norm(X[nodes] - np.asarray(point, dtype=float), axis=1)
    j = int(d.argmin())
    centroid = float(np.linalg.norm(X[nodes].mean(axis=0) - np.asarray(point, dtype=float)))
    return float(d[j]), int(nodes[j]), centroid


def tie_reaches(X, nodes, point, tol: float = TIE_TOL) -> bool:
    """True when the tied ``nodes`` reach ``point`` (:data:`TIE_TOL`)."""
    near, _, centroid = tie_distance(X, nodes, point)
    return min(near, centroid) <= tol


@dataclass(frozen=True)
class Interface:
    """A hardpoint and the mesh nodes rigidly tied to it (RBE2 spider, 6 DOF).

    Parameters
    ----------
    point : (3,) array_like
        Hardpoint in mesh coordinates, m.
    radius : float, optional
        Tie every node within this distance of ``point``, m.
    nodes : array_like of int, optional
        Tie these nodes, given as 0-based positions in ``Mesh.points`` (as in
        ``Mesh.node_sets``), **not** the ids of the mesh file; ``mesh.node_index(ids)``
        turns file ids (Nastran GRID ids, Gmsh node tags) into positions.
    name : str, optional
        Interface name (markers, messages); default ``"if1"``, ``"if2"``, ...
    node_set : str, optional
        Tie the nodes of this named node set of the mesh.
    dofs : {6, 3}
        Boundary DOF in the reduction: 6 (forces and moments, default) or 3 (forces only).

    Notes
    -----
    Give at most one of ``radius``, ``nodes``, ``node_set``.  With none of them the
    point must coincide with a mesh node that has its own rotations (shell or beam
    node): that node's 6 DOF are the interface.
    """

    point: tuple
    radius: float | None = None
    nodes: tuple | None = None
    _: KW_ONLY
    name: str | None = None
    node_set: str | None = None
    dofs: int = 6
    #: where the interface was defined, ``(file, line)`` or ``(file, line, key)`` (the
    #: spec's key of its table, e.g. ``"interface[1]"``), named by errors about it
    source: tuple | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        if self.dofs not in (3, 6) or isinstance(self.dofs, bool):
            raise InputError(f"interface dofs must be 3 (translations, forces only) or 6 "
                             f"(with rotations, forces and moments), got {self.dofs!r}",
                             key=f"{self.name or 'interface'}.dofs")
        object.__setattr__(self, "dofs", int(self.dofs))
        for k in ("name", "node_set"):
            v = getattr(self, k)
            if v is not None and not isinstance(v, str):
                raise InputError(f"interface {k} must be a string or None, got "
                                 f"{type(v).__name__} {v!r}", key=k)
        try:
            p = np.asarray(self.point, dtype=float).reshape(-1)
        except (TypeError, ValueError):
            p = None
        if p is None or p.shape != (3,) or not np.all(np.isfinite(p)):
            raise InputError(f"interface point must be 3 finite numbers (x, y, z in m), got "
                             f"{self.point!r}", key=self.name or "point")
        object.__setattr__(self, "point", tuple(float(v) for v in p))
        given = [k for k in ("radius", "nodes", "node_set") if getattr(self, k) is not None]
        if len(given) > 1:
            raise InputError(f"give only one of radius, nodes, node_set (got {given})",
                             key=self.name or "interface")
        if self.radius is not None:
            from flexpipe._args import checked_number

            object.__setattr__(self, "radius", checked_number(
                self.radius, "radius", lo=0.0, unit="m", key=self.name or "radius"))
        if self.nodes is not None:
            object.__setattr__(self, "nodes", _node_positions(self.nodes, self.name))


def _node_positions(nodes, name) -> tuple:
    """``nodes`` as a tuple of ints: integers only (no float such as 1.5 or 1.0, no bool),
    else an :class:`InputError` naming the interface; :func:`resolve_interfaces` checks
    them against the model's node range."""
    from flexpipe._args import checked_int

    flat = np.asarray([nodes] if isinstance(nodes, (str, bytes)) else nodes, dtype=object)
    return tuple(checked_int(i, "interface nodes (0-based node positions)",
                             key=name or "nodes") for i in flat.reshape(-1))


@dataclass(frozen=True)
class ResolvedInterface:
    """An interface bound to a model: its name, hardpoint, node indices and kind."""

    name: str
    point: np.ndarray
    nodes: np.ndarray
    kind: str  # "rbe2" (new 6-DOF hardpoint) or "node" (a mesh node)
    dofs: int = 6  # boundary DOF in the reduction (3: translations only)


def _describe(fe: FEModel, i: int) -> str:
    if fe.mesh is not None:
        return fe.mesh.describe_node(int(i))
    x, y, z = fe.nodes[i]
    return f"node index {int(i)} at ({x:.4g}, {y:.4g}, {z:.4g}) m"


def _pt(p) -> str:
    return "(" + ", ".join(f"{float(v):.4g}" for v in p) + ") m"


def _has_rotations(fe: FEModel, nodes) -> np.ndarray:
    """Per node: True when all three rotation DOF are independent DOF of the model."""
    if fe.dofs_per_node < 6:
        return np.zeros(len(nodes), dtype=bool)
    rot = np.asarray(nodes)[:, None] * 6 + np.arange(3, 6)
    return (fe.independent_of_dof[rot] >= 0).all(axis=1)


def resolve_interfaces(fe: FEModel, interfaces) -> list[ResolvedInterface]:
    """Bind interfaces to the nodes of ``fe``; check they are valid and disjoint.

    An error about an interface read from a spec file (``Interface.source``) names that
    file, the line of its ``[[interface]]`` table and its key there (``interface[k]``).

    Raises
    ------
    InputError
        Naming the interface: a radius that catches no node, an unknown node set,
        node indices out of range, a point without a 6-DOF node, nodes that cannot
        carry a rotation (collinear solid nodes), overlapping interfaces, duplicate
        names.
    """
    if isinstance(interfaces, Interface):
        interfaces = [interfaces]
    interfaces = list(interfaces)
    try:
        return _resolve(fe, interfaces)
    except InputError as exc:
        src = {i.name: i.source for i in interfaces
               if isinstance(i, Interface) and i.source is not None}
        if exc.file is None and exc.key in src:  # the message names the interface
            file, line, *key = src[exc.key]
            raise InputError(exc.message, file=file, line=line,
                             key=key[0] if key else exc.key) from None
        raise


def _resolve(fe: FEModel, interfaces: list) -> list[ResolvedInterface]:
    if not interfaces:
        raise InputError("at least one interface is needed", key="interfaces")
    size = float(np.ptp(fe.nodes, axis=0).max()) if fe.n_nodes else 1.0
    tol = 1e-9 * max(size, 1e-12)
    out: list[ResolvedInterface] = []
    for k, itf in enumerate(interfaces):
        if not isinstance(itf, Interface):
            raise InputError(f"interfaces[{k}] must be a flexpipe.Interface, got "
                             f"{type(itf).__name__}", key="interfaces")
        name = itf.name or f"if{k + 1}"
        p = np.asarray(itf.point)
        dist = np.linalg.norm(fe.nodes - p, axis=1)
        nearest = int(dist.argmin())
        kind = "rbe2"
        if itf.radius is not None:
            nodes = np.flatnonzero(dist <= itf.radius + tol)
            if nodes.size == 0:
                raise InputError(
                    f"interface '{name}': no mesh node within radius {itf.radius:g} m of "
                    f"{_pt(p)}; the nearest is {_describe(fe, nearest)}, "
                    f"{dist[nearest]:.4g} m away", key=name)
        elif itf.node_set is not None:
            sets = fe.mesh.node_sets if fe.mesh is not None else {}
            try:
                found = find_node_set(sets, itf.node_set, key=name)
            except InputError as exc:
                raise InputError(f"interface '{name}': {exc.message}", key=name) from None
            nodes = np.unique(np.asarray(sets[found], dtype=np.int64))
            if nodes.size == 0:
                raise InputError(f"interface '{name}': node set '{itf.node_set}' is empty",
                                 key=name)
        elif itf.nodes is not None:
            nodes = np.unique(np.asarray(itf.nodes, dtype=np.int64))
            if nodes.size == 0 or nodes.min() < 0 or nodes.max() >= fe.n_nodes:
                raise InputError(f"interface '{name}': node indices must lie in "
                                 f"[0, {fe.n_nodes}), got {list(itf.nodes)[:10]}; nodes= "
                                 "takes 0-based positions, mesh.node_index(ids) turns the "
                                 "mesh file's ids into them", key=name)
        else:
            if dist[nearest] > max(tol, 1e-9):
                raise InputError(
                    f"interface '{name}': no mesh node at {_pt(p)} (nearest: "
                    f"{_describe(fe, nearest)}, {dist[nearest]:.4g} m away); give radius=, "
                    "node_set= or nodes=", key=name)
            nodes = np.array([nearest])
            if itf.dofs == 6 and not _has_rotations(fe, nodes)[0]:
                raise InputError(
                    f"interface '{name}': {_describe(fe, nearest)} has no rotational DOF "
                    "(solid node), so it cannot be a 6-DOF interface on its own; give "
                    "radius=, node_set= or nodes= to build a rigid spider", key=name)
            kind = "node"
        if itf.radius is None and kind == "rbe2":
            near, kn, cen = tie_distance(fe.nodes, nodes, p)
            if min(near, cen) > TIE_TOL:
                how = (f"node set '{itf.node_set}'" if itf.node_set is not None
                       else "nodes")
                raise InputError(
                    f"interface '{name}': its {how} ({nodes.size} node(s)) lies "
                    f"{near:.4g} m from its point {_pt(p)} (nearest tied node: "
                    f"{_describe(fe, kn)}; centroid {cen:.4g} m away); tied nodes must "
                    f"include a node within {TIE_TOL} m of the point or be centred on it "
                    f"within {TIE_TOL} m. The nearest mesh node to the point is "
                    f"{_describe(fe, nearest)}, {dist[nearest]:.4g} m away; check the "
                    "set/ids and the point's units (m)", key=name)
        elif itf.radius is not None and fe.n_nodes >= 200 \
                and nodes.size > RADIUS_WARN_FRACTION * fe.n_nodes:
            import warnings

            warnings.warn(
                f"interface '{name}': radius {itf.radius:g} m ties {nodes.size} of the "
                f"mesh's {fe.n_nodes} nodes ({100 * nodes.size / fe.n_nodes:.0f} %) rigidly "
                "to one point, which stiffens that part of the body; a mount's radius is "
                "usually a few cm (a radius typed in mm?)", stacklevel=3)
        if kind == "rbe2":
            on_node = nodes.size == 1 and dist[nodes[0]] <= max(tol, 1e-9)
            if on_node and (itf.dofs == 3 or _has_rotations(fe, nodes)[0]):
                kind = "node"
            else:
                _check_spider(fe, name, p, nodes)
        out.append(ResolvedInterface(name=name, point=p.copy(), nodes=nodes, kind=kind,
                                     dofs=itf.dofs))
    names = [r.name for r in out]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise InputError(f"interface names must be unique; repeated: {sorted(dup)}",
                         key="interfaces")
    owner = {}
    for r in out:
        for i in r.nodes.tolist():
            if i in owner:
                raise InputError(
                    f"interfaces '{owner[i]}' and '{r.name}' overlap: both tie "
                    f"{_describe(fe, i)}; reduce a radius or split the node sets", key=r.name)
            owner[i] = r.name
    return out


def _check_spider(fe, name, p, nodes):
    """The tied nodes must hold all six hardpoint motions."""
    if _has_rotations(fe, nodes).any():
        return
    d = fe.nodes[nodes] - p
    G = np.concatenate([np.broadcast_to(np.eye(3), (len(nodes), 3, 3)), -skew(d)], axis=2)
    s = np.linalg.svd(G.reshape(-1, 6), compute_uv=False)
    scale = max(np.abs(d).max(), 1e-12)
    if s[-1] <= 1e-8 * max(s[0], scale):
        raise InputError(
            f"interface '{name}': its {len(nodes)} solid node(s) lie on one line or point, "
            "so the spider cannot carry a rotation about that line; enlarge the radius or "
            "add nodes", key=name)


@dataclass(frozen=True)
class InterfaceSystem:
    """Model with interfaces applied: ``q_all = E @ x`` for the new coordinates ``x``.

    Attributes
    ----------
    K, M : scipy.sparse.csr_matrix
        Stiffness and mass on ``x``.
    E : scipy.sparse.csr_matrix (n_dof, n_x)
        Map to all DOF of the model.
    boundary : list of ndarray
        Per interface, its coordinates in ``x`` (ux, uy, uz, rx, ry, rz; only the three
        translations for a solid node).
    active : list of ndarray
        Per interface, its boundary DOF of the reduction: all of ``boundary`` for a 6-DOF
        interface, the translations for a 3-DOF one.
    """

    K: sp.csr_matrix
    M: sp.csr_matrix
    E: sp.csr_matrix
    boundary: list
    active: list


def interface_system(fe: FEModel, resolved: list[ResolvedInterface]) -> InterfaceSystem:
    """Apply the interfaces to the independent DOF of ``fe`` (see module docstring)."""
    dpn = fe.dofs_per_node
    n_q = fe.T.shape[1]
    col_of = fe.independent_of_dof
    drop, rows, cols, vals = [], [], [], []
    boundary_cols = []  # per interface: ("old", cols) or ("new", offset)
    n_new = 0
    for r in resolved:
        if r.kind == "node":
            c = col_of[r.nodes[0] * dpn + np.arange(6 if _has_rotations(fe, r.nodes)[0]
                                                    else 3)]
            if (c < 0).any():
                raise InputError(f"interface '{r.name}': {_describe(fe, r.nodes[0])} is tied "
                                 "by a rigid link of the mesh; use its master node", key=r.name)
            boundary_cols.append(("old", c))
            continue
        dofs = r.nodes[:, None] * dpn + np.arange(dpn)
        cidx = col_of[dofs]  # (k, dpn), -1 where not independent
        tied = np.abs(fe.T[dofs.ravel()]).sum(axis=1).A.ravel().reshape(dofs.shape) > 0
        bad = tied & (cidx < 0)
        if bad.any():
            i = int(r.nodes[np.flatnonzero(bad.any(axis=1))[0]])
            raise InputError(f"interface '{r.name}': {_describe(fe, i)} is already tied by a "
                             "rigid link of the mesh (RBE2 slave); use its master node", key=r.name)
        d = fe.nodes[r.nodes] - r.point
        base = n_new
        n_new += 6
        boundary_cols.append(("new", base))
        for c in range(dpn):
            ok = cidx[:, c] >= 0
            q = cidx[ok, c]
            drop.append(q)
            rows.append(q)
            cols.append(np.full(q.size, base + c))
            vals.append(np.ones(q.size))
            if c < 3:  # u_c += (theta x d)_c = -(S(d) theta)_c
                S = -skew(d[ok])  # (k, 3, 3)
                for k in range(3):
                    rows.append(q)
                    cols.append(np.full(q.size, base + 3 + k))
                    vals.append(S[:, c, k])
    drop = np.unique(np.concatenate(drop)) if drop else np.zeros(0, dtype=np.int64)
    keep = np.setdiff1d(np.arange(n_q), drop)
    n_x = keep.size + n_new
    new_index = np.full(n_q, -1, dtype=np.int64)
    new_index[keep] = np.arange(keep.size)
    rows = [keep] + rows
    cols = [np.arange(keep.size)] + [c + keep.size for c in cols]
    vals = [np.ones(keep.size)] + vals
    Ti = sp.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                       shape=(n_q, n_x))
    Ti.eliminate_zeros()
    boundary = []
    for kind, c in boundary_cols:
        boundary.append(new_index[c] if kind == "old" else keep.size + c + np.arange(6))
    active = [bj[:r.dofs] for bj, r in zip(boundary, resolved, strict=True)]
    K = sp.csr_matrix(Ti.T @ fe.Kr @ Ti)
    M = sp.csr_matrix(Ti.T @ fe.Mr @ Ti)
    E = sp.csr_matrix(fe.T @ Ti)
    return InterfaceSystem(K=K, M=M, E=E, boundary=boundary, active=active)
