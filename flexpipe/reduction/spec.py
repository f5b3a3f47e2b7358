"""Interface specification files (TOML) for ``flexpipe reduce --interfaces``.

Example::

    # body coordinates in m
    radius = 0.10                 # default radius for entries that give none

    [[interface]]
    name = "strut_fl"
    point = [0.00, 0.65, 0.85]    # hardpoint
    radius = 0.08                 # tie the nodes within 8 cm (RBE2)

    [[interface]]
    name = "damper_rl"
    point = [-2.75, 0.55, 0.65]
    node_set = "damper_rl"        # or a named node set of the mesh

    [[interface]]
    name = "tow"
    point = [1.1, 0.0, 0.3]
    nodes = [101, 102, 103]       # or node ids of the mesh file
    dofs = 3                      # translations only (ball joint, bushing); default 6

An entry with neither ``radius``, ``node_set`` nor ``nodes`` (and no top-level radius)
uses the 6-DOF shell/beam node at the point.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np

from flexpipe.errors import InputError
from flexpipe.reduction.interface import Interface

_KEYS = {"name", "point", "radius", "node_set", "nodes", "dofs"}


def _line_of(lines, k):
    """Line number (1-based) of the k-th ``[[interface]]`` header."""
    count = -1
    for i, line in enumerate(lines):
        if line.strip().startswith("[[interface]]"):
            count += 1
            if count == k:
                return i + 1
    return None


def read_interfaces(path, *, node_ids=None) -> list[Interface]:
    """Read the interfaces of a TOML spec file.

    Parameters
    ----------
    path : str or Path
    node_ids : ndarray of int, optional
        The mesh's node ids (``Mesh.node_ids``), to translate ``nodes = [ids]`` into
        node indices; without it ``nodes`` are taken as 0-based indices.
    """
    path = Path(path)
    try:
        text = path.read_text()
    except OSError as exc:
        raise InputError(f"cannot read the interface file ({exc.strerror})", file=path) from None
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"not valid TOML: {exc}", file=path) from None
    lines = text.splitlines()
    unknown = set(doc) - {"interface", "radius"}
    if unknown:
        raise InputError(f"unknown top-level key(s) {sorted(unknown)}; valid: interface, radius",
                         file=path, key=sorted(unknown)[0])
    entries = doc.get("interface")
    if not isinstance(entries, list) or not entries:
        raise InputError("no [[interface]] tables", file=path, key="interface")
    default_r = doc.get("radius")
    out = []
    for k, e in enumerate(entries):
        line = _line_of(lines, k)
        where = dict(file=path, line=line)
        bad = set(e) - _KEYS
        if bad:
            raise InputError(f"unknown key(s) {sorted(bad)}; valid: {sorted(_KEYS)}",
                             key=f"interface[{k}].{sorted(bad)[0]}", **where)
        name = e.get("name", f"if{k + 1}")
        if not isinstance(name, str) or not name:
            raise InputError("name must be a non-empty string", key=f"interface[{k}].name",
                             **where)
        p = e.get("point")
        if not (isinstance(p, list) and len(p) == 3
                and all(isinstance(v, (int, float)) for v in p)):
            raise InputError(f"point must be [x, y, z] in m, got {p!r}",
                             key=f"interface[{k}].point", **where)
        kw = {"name": name}
        if "dofs" in e:
            if e["dofs"] not in (3, 6) or isinstance(e["dofs"], bool):
                raise InputError(f"dofs must be 3 (forces only) or 6 (forces and moments), "
                                 f"got {e['dofs']!r}", key=f"interface[{k}].dofs", **where)
            kw["dofs"] = int(e["dofs"])
        if "node_set" in e:
            kw["node_set"] = str(e["node_set"])
        elif "nodes" in e:
            ids = np.asarray(e["nodes"], dtype=np.int64).ravel()
            if node_ids is not None:
                pos = {int(v): i for i, v in enumerate(np.asarray(node_ids))}
                missing = [int(v) for v in ids if int(v) not in pos]
                if missing:
                    raise InputError(f"node ids {missing[:10]} are not in the mesh",
                                     key=f"interface[{k}].nodes", **where)
                ids = np.array([pos[int(v)] for v in ids])
            kw["nodes"] = ids
        elif "radius" in e or default_r is not None:
            r = e.get("radius", default_r)
            if not isinstance(r, (int, float)) or r <= 0:
                raise InputError(f"radius must be a positive length in m, got {r!r}",
                                 key=f"interface[{k}].radius", **where)
            kw["radius"] = float(r)
        try:
            out.append(Interface(tuple(float(v) for v in p), **kw))
        except InputError as exc:
            raise InputError(str(exc), key=f"interface[{k}]", **where) from None
    return out
