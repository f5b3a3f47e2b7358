"""Line-exact structure checks of ASCII STL, OBJ and OFF surface files; see
:mod:`flexpipe.mesh.text_checks`."""

from __future__ import annotations

from flexpipe.mesh.text_checks import _err, _floats, _ints, _is_int


def check_stl_ascii(path, text: str) -> None:
    """facet normal / outer loop / 3 x vertex / endloop / endfacet ... endsolid."""
    lines = text.splitlines()
    k = next((i for i, ln in enumerate(lines) if ln.strip()), None)
    if k is None or not lines[k].strip().lower().startswith("solid"):
        raise _err(path, 1, "an ASCII STL starts with 'solid'")
    state, nv, n_facets = "solid", 0, 0
    expect = {"solid": ("facet", "endsolid"), "facet": ("outer",), "outer": ("vertex",),
              "vertex": ("vertex", "endloop"), "endloop": ("endfacet",),
              "endfacet": ("facet", "endsolid")}
    for i in range(k + 1, len(lines)):
        parts = lines[i].split()
        if not parts:
            continue
        word = parts[0].lower()
        if word not in expect[state]:
            raise _err(path, i + 1, f"expected {' or '.join(expect[state])!s}, found "
                                    f"{lines[i].strip()[:40]!r}")
        if word == "facet":
            if len(parts) != 5 or parts[1].lower() != "normal":
                raise _err(path, i + 1, "a facet line is 'facet normal nx ny nz'")
            _floats(path, i + 1, parts[2:], "facet normal")
        elif word == "vertex":
            nv += 1
            if nv > 3:
                raise _err(path, i + 1, "a facet has exactly 3 vertices")
            if len(parts) != 4:
                raise _err(path, i + 1, f"a vertex line is 'vertex x y z', got "
                                        f"{lines[i].strip()!r}")
            _floats(path, i + 1, parts[1:], f"vertex of facet {n_facets + 1}")
        elif word == "endloop":
            if nv != 3:
                raise _err(path, i + 1, f"facet {n_facets + 1} has {nv} vertices; it needs 3")
        elif word == "outer":
            nv = 0
        elif word == "endfacet":
            n_facets += 1
        elif word == "endsolid":
            if n_facets == 0:
                raise _err(path, i + 1, "the solid has no facets")
            return
        state = word
    raise _err(path, len(lines), "the file ends before 'endsolid' (truncated?)")


def check_obj(path, text: str) -> None:
    """``v x y z`` with finite numbers; ``f`` with >= 3 valid vertex indices."""
    nv = 0
    for i, line in enumerate(text.splitlines(), start=1):
        parts = line.split()
        if not parts or parts[0].startswith("#"):
            continue
        if parts[0] == "v":
            if len(parts) not in (4, 5, 7):
                raise _err(path, i, f"a vertex line is 'v x y z', got {line.strip()!r}")
            _floats(path, i, parts[1:], "vertex")
            nv += 1
        elif parts[0] == "f":
            if len(parts) < 4:
                raise _err(path, i, f"a face needs at least 3 vertices, got {line.strip()!r}")
            for p in parts[1:]:
                head = p.split("/")[0]
                if not _is_int(head):
                    raise _err(path, i, f"face vertex {p!r} is not an index")
                j = int(head)
                if j == 0 or j > nv or j < -nv:
                    raise _err(path, i, f"face refers to vertex {j}; {nv} vertices are defined "
                                        "before this line (indices count from 1)")


def check_off(path, text: str) -> None:
    """``OFF`` header, counts, then exactly the announced vertices and faces."""
    rows = [(i, ln.split()) for i, ln in enumerate(text.splitlines(), start=1)
            if ln.strip() and not ln.lstrip().startswith("#")]
    if not rows or rows[0][1][0] != "OFF":
        raise _err(path, 1, "an OFF file starts with 'OFF'")
    head = rows[0][1][1:] or (rows[1][1] if len(rows) > 1 else [])
    start = 1 if rows[0][1][1:] else 2
    line = rows[0][0] if rows[0][1][1:] else (rows[1][0] if len(rows) > 1 else 1)
    if len(head) != 3 or not all(_is_int(h) for h in head):
        raise _err(path, line, "the counts line is 'n_vertices n_faces n_edges'")
    nv, nf, _ = (int(h) for h in head)
    body = rows[start:]
    if len(body) != nv + nf:
        raise _err(path, line, f"announces {nv} vertices and {nf} faces ({nv + nf} lines); "
                               f"{len(body)} follow")
    for i, parts in body[:nv]:
        if len(parts) != 3:
            raise _err(path, i, "a vertex line is 'x y z'")
        _floats(path, i, parts, "vertex")
    for i, parts in body[nv:]:
        v = _ints(path, i, " ".join(parts), "face line")
        if v[0] < 3 or len(v) < 1 + v[0]:
            raise _err(path, i, "a face line is 'n i1 ... in' with n >= 3")
        bad = [j for j in v[1:1 + v[0]] if not 0 <= j < nv]
        if bad:
            raise _err(path, i, f"face refers to vertex {bad[0]}; valid 0 .. {nv - 1}")
