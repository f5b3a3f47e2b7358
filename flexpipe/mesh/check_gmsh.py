"""Line-exact structure check of ASCII Gmsh ``.msh`` files (2.2 and 4.1); see
:mod:`flexpipe.mesh.text_checks`."""

from __future__ import annotations

from flexpipe.mesh.text_checks import _err, _floats, _ints, _is_int, _lines

#: nodes per Gmsh element type (the types flexpipe reads, plus common ones to skip)
GMSH_NODES = {1: 2, 2: 3, 3: 4, 4: 4, 5: 8, 6: 6, 7: 5, 8: 3, 9: 6, 10: 9, 11: 10, 12: 27,
              13: 18, 14: 14, 15: 1, 16: 8, 17: 20, 18: 15, 19: 13, 20: 9, 21: 10, 26: 4,
              27: 5, 28: 6, 29: 20, 30: 35, 31: 56, 92: 64, 93: 125}



def _sections(path, lines):
    """{name: (first content line index, end line index)}; checks $X ... $EndX pairs."""
    out, k = {}, 0
    while k < len(lines):
        s = lines[k].strip()
        if s.startswith("$") and not s.startswith("$End"):
            name = s[1:]
            end = next((j for j in range(k + 1, len(lines))
                        if lines[j].strip().startswith("$")), None)
            if end is None or lines[end].strip() != f"$End{name}":
                raise _err(path, k + 1, f"section ${name} is not closed by $End{name}"
                           + (f" (found {lines[end].strip()!r} at line {end + 1})"
                              if end is not None else " (file truncated?)"))
            out.setdefault(name, (k + 1, end))
            k = end + 1
            continue
        k += 1
    return out


def check_gmsh(path) -> None:
    """Check an ASCII Gmsh file (binary files and unknown versions are left alone)."""
    lines = _lines(path)
    if lines is None or not any(ln.strip() for ln in lines):
        return  # binary or empty: meshio's reader says why
    head = [ln.split() for ln in lines[:2]]
    if head[0] == ["$MeshFormat"] and len(head) > 1 and len(head[1]) >= 2:
        if head[1][0] not in ("2", "2.2", "4", "4.0", "4.1"):
            raise _err(path, 2, f"unsupported Gmsh version: need mesh format in 2.2, 4.1 (ASCII "
                                f"or binary), got {head[1][0]}")
        if head[1][1] != "0":
            return  # binary: left to meshio
    sec = _sections(path, lines)
    if "MeshFormat" not in sec:
        raise _err(path, 1, "no $MeshFormat section: not a Gmsh .msh file")
    a, b = sec["MeshFormat"]
    if b - a < 1:
        raise _err(path, a, "empty $MeshFormat section")
    fmt = lines[a].split()
    if len(fmt) < 3:
        raise _err(path, a + 1, f"$MeshFormat line must be 'version file-type data-size', got "
                                f"{lines[a].strip()!r}")
    version, binary = fmt[0], fmt[1]
    if binary != "0":
        return
    if version.startswith("2"):
        _gmsh2(path, lines, sec)
    elif version.startswith("4"):
        _gmsh4(path, lines, sec)


def _count_then_rows(path, lines, sec, name):
    if name not in sec:
        raise _err(path, None, f"no ${name} section")
    a, b = sec[name]
    if a >= b:
        raise _err(path, a, f"empty ${name} section")
    (n,) = _ints(path, a + 1, lines[a], f"${name} count", 1)
    rows = b - a - 1
    if rows != n:
        raise _err(path, a + 1, f"${name} announces {n} entries but {rows} lines follow "
                                f"before $End{name}")
    return a, n


def _gmsh_type(path, line, eid, etype) -> int:
    if etype not in GMSH_NODES:
        raise _err(path, line, f"element {eid}: type {etype} is not a Gmsh element type "
                               f"flexpipe knows (known: {sorted(GMSH_NODES)})")
    return GMSH_NODES[etype]


def _gmsh2(path, lines, sec):
    a, n = _count_then_rows(path, lines, sec, "Nodes")
    ids = set()
    for k in range(a + 1, a + 1 + n):
        parts = lines[k].split()
        if len(parts) != 4:
            raise _err(path, k + 1, f"node line must be 'id x y z', got {lines[k].strip()!r}")
        (nid,) = _ints(path, k + 1, parts[0], "node id", 1)
        _floats(path, k + 1, parts[1:], f"node {nid} coordinates")
        ids.add(nid)
    a, n = _count_then_rows(path, lines, sec, "Elements")
    for k in range(a + 1, a + 1 + n):
        v = _ints(path, k + 1, lines[k], "element line")
        if len(v) < 3:
            raise _err(path, k + 1, f"element line must be 'id type ntags tags... nodes...', "
                                    f"got {lines[k].strip()!r}")
        eid, etype, ntags = v[:3]
        nn = _gmsh_type(path, k + 1, eid, etype)
        if len(v) != 3 + ntags + nn:
            raise _err(path, k + 1, f"element {eid} (type {etype}) needs {nn} nodes after "
                                    f"{ntags} tags, the line has {len(v) - 3 - ntags}")
        missing = [x for x in v[3 + ntags:] if x not in ids]
        if missing:
            raise _err(path, k + 1, f"element {eid} references node {missing[0]}, which is not "
                                    "in $Nodes")


def _gmsh4_entities(path, lines, sec):
    """{dim: set of entity tags} of the $Entities section (None when absent)."""
    if "Entities" not in sec:
        return None
    a, b = sec["Entities"]
    counts = _ints(path, a + 1, lines[a], "$Entities header 'points curves surfaces "
                                          "volumes'", 4)
    out, k = {}, a + 1
    for dim, n in enumerate(counts):
        out[dim] = set()
        for _ in range(n):
            if k >= b:
                raise _err(path, a + 1, f"$Entities announces {sum(counts)} entities; the "
                                        "section ends early")
            head = lines[k].split()[:1]
            if not head or not _is_int(head[0]):
                raise _err(path, k + 1, f"entity line must start with its tag, got "
                                        f"{lines[k].strip()[:40]!r}")
            out[dim].add(int(head[0]))
            k += 1
    return out


def _entity(path, line, entities, dim, tag, what):
    if dim not in (0, 1, 2, 3):
        raise _err(path, line, f"{what} block: entity dimension {dim}; valid 0 .. 3")
    if entities is not None and tag not in entities.get(dim, ()):
        raise _err(path, line, f"{what} block: entity {tag} of dimension {dim} is not in "
                               "$Entities")


def _gmsh4(path, lines, sec):
    if "Nodes" not in sec or "Elements" not in sec:
        raise _err(path, None, "a Gmsh 4 file needs $Nodes and $Elements sections")
    entities = _gmsh4_entities(path, lines, sec)
    a, b = sec["Nodes"]
    nb, total, _, _ = _ints(path, a + 1, lines[a], "$Nodes header 'blocks nodes min max'", 4)
    k, ids = a + 1, set()
    for _ in range(nb):
        if k >= b:
            raise _err(path, k + 1, f"$Nodes announces {nb} blocks; the section ends early")
        dim, tag, param, m = _ints(path, k + 1, lines[k], "node block header", 4)
        _entity(path, k + 1, entities, dim, tag, "node")
        k += 1
        if k + 2 * m > b:
            raise _err(path, k, f"node block of {m} nodes runs past $EndNodes")
        for j in range(m):
            (nid,) = _ints(path, k + j + 1, lines[k + j], "node tag", 1)
            ids.add(nid)
        for j in range(m):
            parts = lines[k + m + j].split()
            if len(parts) < 3 or (not param and len(parts) != 3):
                raise _err(path, k + m + j + 1, f"node coordinates must be 'x y z', got "
                                                f"{lines[k + m + j].strip()!r}")
            _floats(path, k + m + j + 1, parts, "node coordinates")
        k += 2 * m
    if k != b or len(ids) != total:
        raise _err(path, a + 1, f"$Nodes announces {total} nodes in {nb} blocks; the section "
                                f"holds {len(ids)} in {b - a - 1} lines")
    a, b = sec["Elements"]
    nb, total, _, _ = _ints(path, a + 1, lines[a], "$Elements header 'blocks elements min "
                                                   "max'", 4)
    k, count = a + 1, 0
    for _ in range(nb):
        if k >= b:
            raise _err(path, k + 1, f"$Elements announces {nb} blocks; the section ends early")
        dim, tag, etype, m = _ints(path, k + 1, lines[k], "element block header", 4)
        _entity(path, k + 1, entities, dim, tag, "element")
        nn = _gmsh_type(path, k + 1, "block", etype)
        k += 1
        if k + m > b:
            raise _err(path, k, f"element block of {m} elements runs past $EndElements")
        for j in range(m):
            v = _ints(path, k + j + 1, lines[k + j], "element line")
            if len(v) != 1 + nn:
                raise _err(path, k + j + 1, f"element {v[0] if v else '?'} (type {etype}) needs "
                                            f"{nn} nodes, the line has {len(v) - 1}")
            missing = [x for x in v[1:] if x not in ids]
            if missing:
                raise _err(path, k + j + 1, f"element {v[0]} references node {missing[0]}, "
                                            "which is not in $Nodes")
        k += m
        count += m
    if k != b or count != total:
        raise _err(path, a + 1, f"$Elements announces {total} elements in {nb} blocks; the "
                                f"section holds {count} in {b - a - 1} lines")
