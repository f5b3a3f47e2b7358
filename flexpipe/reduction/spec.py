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

import math
import tomllib
from pathlib import Path

import numpy as np

from flexpipe.errors import InputError
from flexpipe.mesh.mesh import index_of_ids
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


def _is_number(v) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def read_interfaces(path, *, node_ids=None) -> list[Interface]:
    """Read the interfaces of a TOML spec file.

    Parameters
    ----------
    path : str or Path
    node_ids : ndarray of int, optional
        The mesh's node ids (``Mesh.node_ids``), to translate ``nodes = [ids]`` into
        node indices; without it ``nodes`` are taken as 0-based indices.

    Raises
    ------
    InputError
        Naming the file, the line of the ``[[interface]]`` table and the key: unreadable
        or non-UTF-8 file, invalid TOML, unknown keys, a point that is not three finite
        numbers, node ids that are not integers, a non-positive radius, more than one of
        ``radius``, ``nodes``, ``node_set`` in one entry, duplicate names.
    """
    path = Path(path)
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read the interface file ({exc.strerror})", file=path) from None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text (byte 0x{raw[exc.start]:02x}); an interface spec is "
                         "a TOML text file", file=path,
                         line=raw[: exc.start].count(b"\n") + 1) from None
    try:
        doc = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"not valid TOML: {exc}", file=path) from None
    except RecursionError:
        raise InputError("not valid TOML: arrays or tables nested too deeply (hundreds of "
                         "levels); an interface spec needs two", file=path, line=1) from None
    lines = text.splitlines()
    unknown = set(doc) - {"interface", "radius"}
    if unknown:
        raise InputError(f"unknown top-level key(s) {sorted(unknown)}; valid: interface, radius",
                         file=path, key=sorted(unknown)[0])
    entries = doc.get("interface")
    if not isinstance(entries, list) or not entries:
        raise InputError("no [[interface]] tables (write each interface as a table "
                         "[[interface]] with name, point and radius/nodes/node_set)",
                         file=path, key="interface")
    default_r = doc.get("radius")
    if default_r is not None and not (_is_number(default_r) and default_r > 0):
        raise InputError(f"radius must be a positive length in m, got {default_r!r}",
                         file=path, key="radius")
    out, seen = [], {}
    for k, e in enumerate(entries):
        line = _line_of(lines, k)
        where = dict(file=path, line=line)
        if not isinstance(e, dict):
            raise InputError(f"entry {k + 1} is {e!r}, not a table; write [[interface]] "
                             "tables", key=f"interface[{k}]", **where)
        bad = set(e) - _KEYS
        if bad:
            raise InputError(f"unknown key(s) {sorted(bad)}; valid: {sorted(_KEYS)}",
                             key=f"interface[{k}].{sorted(bad)[0]}", **where)
        name = e.get("name", f"if{k + 1}")
        if not isinstance(name, str) or not name.strip():
            raise InputError("name must be a non-empty string", key=f"interface[{k}].name",
                             **where)
        if name in seen:
            raise InputError(f"name '{name}' is used twice (also at line {seen[name]}); "
                             "interface names must be unique", key=f"interface[{k}].name",
                             **where)
        seen[name] = line
        p = e.get("point")
        if not (isinstance(p, list) and len(p) == 3 and all(_is_number(v) for v in p)):
            raise InputError(f"point must be [x, y, z]: three finite numbers in m, got {p!r}",
                             key=f"interface[{k}].point", **where)
        given = [g for g in ("radius", "nodes", "node_set") if g in e]
        if len(given) > 1:
            raise InputError(f"give only one of radius, nodes, node_set (got {given}); the "
                             "interface would otherwise silently ignore one",
                             key=f"interface[{k}].{given[1]}", **where)
        kw = {"name": name, "source": (str(path), line, f"interface[{k}]")}
        if "dofs" in e:
            if e["dofs"] not in (3, 6) or isinstance(e["dofs"], bool):
                raise InputError(f"dofs must be 3 (forces only) or 6 (forces and moments), "
                                 f"got {e['dofs']!r}", key=f"interface[{k}].dofs", **where)
            kw["dofs"] = int(e["dofs"])
        if "node_set" in e:
            if not isinstance(e["node_set"], str) or not e["node_set"]:
                raise InputError(f"node_set must be the name of a node set of the mesh, got "
                                 f"{e['node_set']!r}", key=f"interface[{k}].node_set", **where)
            kw["node_set"] = e["node_set"]
        elif "nodes" in e:
            kw["nodes"] = _node_indices(e["nodes"], node_ids, key=f"interface[{k}].nodes",
                                        where=where)
        elif "radius" in e or default_r is not None:
            r = e.get("radius", default_r)
            if not (_is_number(r) and r > 0):
                raise InputError(f"radius must be a positive length in m, got {r!r}",
                                 key=f"interface[{k}].radius", **where)
            kw["radius"] = float(r)
        try:
            out.append(Interface(tuple(float(v) for v in p), **kw))
        except InputError as exc:
            raise InputError(exc.message, key=f"interface[{k}]", **where) from None
    return out


def _node_indices(ids, node_ids, *, key, where):
    if not (isinstance(ids, list) and ids and all(
            isinstance(v, int) and not isinstance(v, bool) for v in ids)):
        raise InputError(f"nodes must be a non-empty list of integer node ids, got {ids!r}",
                         key=key, **where)
    if node_ids is not None:  # the error names the valid ids and the nearest ones
        return index_of_ids(node_ids, ids, key=key, **where)
    if min(ids) < 0:
        raise InputError(f"node indices must be >= 0, got {min(ids)}", key=key, **where)
    return np.array(ids, dtype=np.int64)
