"""Line-exact structure checks of text mesh files read by third-party parsers.

meshio (Gmsh ``.msh``, VTK ``.vtu``) and trimesh (STL, OBJ, OFF) report a damaged file
with the exception of whatever step failed ("cannot reshape array", "list index out of
range") or skip broken lines silently.  These checks walk the text first and raise a
:class:`~flexpipe.errors.MeshError` naming the file, the line and what would be valid:

* :func:`check_gmsh` - ASCII ``.msh`` 2.2 and 4.1: sections closed, counts equal to the
  lines that follow, finite coordinates, integer connectivity with the node count of the
  element type, every referenced node defined;
* :func:`check_vtu` - ``.vtu`` with inline ASCII or base64 (zlib) arrays: well-formed
  XML, each ``DataArray`` decodes to numbers of its type, the ``Points`` and cell arrays
  have the sizes the ``Piece`` announces, connectivity inside the points (non-finite
  coordinates are left to :func:`~flexpipe.mesh.validate.validate`, which names the
  node ids);
* :func:`check_stl_ascii`, :func:`check_obj`, :func:`check_off`.

Binary files are left to the parsers (their own errors are wrapped by the callers).
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from flexpipe.errors import MeshError

#: nodes per Gmsh element type (the types flexpipe reads, plus common ones to skip)
GMSH_NODES = {1: 2, 2: 3, 3: 4, 4: 4, 5: 8, 6: 6, 7: 5, 8: 3, 9: 6, 10: 9, 11: 10, 12: 27,
              13: 18, 14: 14, 15: 1, 16: 8, 17: 20, 18: 15, 19: 13, 20: 9, 21: 10, 26: 4,
              27: 5, 28: 6, 29: 20, 30: 35, 31: 56, 92: 64, 93: 125}


def _err(path, line, message):
    return MeshError(message, file=str(path), line=line)


def _lines(path) -> list[str] | None:
    """The file's lines, or None for a binary (non-UTF-8) file."""
    raw = Path(path).read_bytes()
    try:
        return raw.decode("utf-8").splitlines()
    except UnicodeDecodeError:
        return None


def _ints(path, k, line, what, n=None):
    parts = line.split()
    try:
        vals = [int(p) for p in parts]
    except ValueError:
        bad = next(p for p in parts if not _is_int(p))
        raise _err(path, k, f"{what}: {bad!r} is not an integer (line {line.strip()!r})"
                   ) from None
    if n is not None and len(vals) != n:
        raise _err(path, k, f"{what}: expected {n} integers, found {len(vals)} "
                            f"({line.strip()!r})")
    return vals


def _is_int(s):
    try:
        int(s)
    except ValueError:
        return False
    return True


def _floats(path, k, parts, what):
    out = []
    for p in parts:
        try:
            v = float(p)
        except ValueError:
            raise _err(path, k, f"{what}: {p!r} is not a number") from None
        if not math.isfinite(v):
            raise _err(path, k, f"{what}: {p!r} is not a finite number")
        out.append(v)
    return out


# --------------------------------------------------------------------------- Gmsh
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


# --------------------------------------------------------------------------- VTU
_ARRAY = re.compile(r"<DataArray\b([^>]*)>(.*?)</DataArray>", re.S)
_ATTR = re.compile(r'(\w+)\s*=\s*"([^"]*)"')


_VTK_TYPES = {"Int8": "i1", "Int16": "i2", "Int32": "i4", "Int64": "i8", "UInt8": "u1",
              "UInt16": "u2", "UInt32": "u4", "UInt64": "u8", "Float32": "f4",
              "Float64": "f8"}


def check_vtu(path) -> None:
    """Check a ``.vtu`` with inline ASCII or base64 (optionally zlib) data arrays."""
    import xml.etree.ElementTree as ET

    lines = _lines(path)
    if lines is None:
        return
    text = "\n".join(lines)
    try:
        ET.fromstring(text)
    except ET.ParseError as exc:
        raise _err(path, exc.position[0], f"not well-formed XML ({exc})") from None
    root = re.search(r"<VTKFile\b([^>]*)>", text)
    rattrs = dict(_ATTR.findall(root.group(1))) if root else {}
    if root is None or rattrs.get("type") != "UnstructuredGrid":
        raise _err(path, 1, "not a VTK UnstructuredGrid file (<VTKFile "
                            "type=\"UnstructuredGrid\">)")
    if rattrs.get("compressor", "vtkZLibDataCompressor") != "vtkZLibDataCompressor":
        return
    piece = re.search(r"<Piece\b([^>]*)>", text)
    if piece is None:
        raise _err(path, None, "no <Piece> element: not an UnstructuredGrid .vtu file")
    pattrs = dict(_ATTR.findall(piece.group(1)))
    pline = text[: piece.start()].count("\n") + 1
    try:
        n_points = int(pattrs.get("NumberOfPoints", ""))
        n_cells = int(pattrs.get("NumberOfCells", ""))
    except ValueError:
        raise _err(path, pline, "<Piece> needs integer NumberOfPoints and NumberOfCells"
                   ) from None
    if n_points <= 0 or n_cells <= 0:
        raise _err(path, pline, f"the grid is empty (NumberOfPoints={n_points}, "
                                f"NumberOfCells={n_cells})")
    arrays = {}
    for m in _ARRAY.finditer(text):
        attrs = dict(_ATTR.findall(m.group(1)))
        line = text[: m.start()].count("\n") + 1
        name = attrs.get("Name", "Points")
        if attrs.get("type") not in _VTK_TYPES:
            raise _err(path, line, f"DataArray '{name}': type {attrs.get('type')!r} is not a VTK "
                                   f"type; valid: {', '.join(_VTK_TYPES)}")
        try:
            nc = int(attrs.get("NumberOfComponents", "1"))
        except ValueError:
            raise _err(path, line, f"DataArray '{name}': NumberOfComponents must be an "
                                   "integer") from None
        fmt = attrs.get("format", "ascii")
        if fmt == "appended":
            return
        if fmt not in ("ascii", "binary"):
            raise _err(path, line, f"DataArray '{name}': format {fmt!r}; valid: ascii, binary, "
                                   "appended")
        values = _vtu_array(path, line, name, attrs["type"], m.group(2), fmt, rattrs)
        if nc > 0 and values.size % nc:
            raise _err(path, line, f"DataArray '{name}': {values.size} values do not make "
                                   f"rows of {nc} components")
        arrays.setdefault(name, (line, values, nc))
    pts = arrays.get("Points") or next((v for v in arrays.values() if v[2] == 3), None)
    if pts is not None and pts[1].size != 3 * n_points:
        raise _err(path, pts[0], f"Points hold {pts[1].size} values; NumberOfPoints = "
                                 f"{n_points} needs {3 * n_points}")
    for name in ("offsets", "types"):
        if name in arrays and arrays[name][1].size != n_cells:
            raise _err(path, arrays[name][0], f"DataArray '{name}' holds "
                                              f"{arrays[name][1].size} values; NumberOfCells "
                                              f"= {n_cells}")
    if "connectivity" in arrays and "offsets" in arrays:
        line, conn, _ = arrays["connectivity"]
        offs = arrays["offsets"][1]
        if offs.size and (offs[-1] != conn.size or np.any(np.diff(offs) <= 0)):
            raise _err(path, arrays["offsets"][0], f"offsets end at {offs[-1]} but the "
                       f"connectivity holds {conn.size} entries (or they do not increase)")
        bad = conn[(conn < 0) | (conn >= n_points)]
        if bad.size:
            raise _err(path, line, f"connectivity refers to point {bad[0]}; valid 0 .. "
                                   f"{n_points - 1}")


def _b64(path, line, name, data: str) -> bytes:
    import base64
    import binascii

    try:
        return base64.b64decode(data, validate=True)
    except (binascii.Error, ValueError):
        raise _err(path, line, f"DataArray '{name}': the binary data are not valid base64 "
                               "(damaged or truncated)") from None


def _vtu_array(path, line, name, vtype, content, fmt, rattrs) -> np.ndarray:
    """Decode one inline DataArray (ASCII text or base64 with a size header)."""
    import zlib

    dtype = np.dtype(_VTK_TYPES[vtype])
    if fmt == "ascii":
        out = []
        for tok in content.split():
            try:
                out.append(int(tok) if dtype.kind in "iu" else float(tok))
            except ValueError:
                raise _err(path, line, f"DataArray '{name}': {tok!r} is not "
                                       f"{'an integer' if dtype.kind in 'iu' else 'a number'}"
                           ) from None
        return np.array(out, dtype=float if dtype.kind == "f" else np.int64)
    order = "<" if rattrs.get("byte_order", "LittleEndian") == "LittleEndian" else ">"
    hdt = np.dtype(order + ("u8" if rattrs.get("header_type") == "UInt64" else "u4"))
    dtype = dtype.newbyteorder(order)
    data = "".join(content.split())
    hs = hdt.itemsize
    bad = _err(path, line, f"DataArray '{name}': the binary data do not match their size "
                           "header (damaged or truncated)")

    def chars(nbytes):
        return -(-nbytes // 3) * 4

    if "compressor" in rattrs:
        first = _b64(path, line, name, data[: chars(hs)])[:hs]
        if len(first) < hs:
            raise bad
        nb = int(np.frombuffer(first, hdt)[0])
        if nb > 10**6:
            raise bad
        nh = chars((3 + nb) * hs)
        header = _b64(path, line, name, data[:nh])
        if len(header) < (3 + nb) * hs:
            raise bad
        sizes = np.frombuffer(header[: (3 + nb) * hs], hdt)[3:].astype(np.int64)
        body = _b64(path, line, name, data[nh:])
        if sizes.sum() != len(body):
            raise bad
        try:
            raw = b"".join(zlib.decompress(body[a:b]) for a, b in
                           zip(np.r_[0, np.cumsum(sizes)[:-1]], np.cumsum(sizes), strict=True))
        except zlib.error:
            raise _err(path, line, f"DataArray '{name}': compressed data damaged (zlib "
                                   "cannot inflate them)") from None
    else:
        head = _b64(path, line, name, data[: chars(hs)])
        if len(head) < hs:
            raise bad
        n = int(np.frombuffer(head[:hs], hdt)[0])
        body = _b64(path, line, name, data[chars(hs):]) if len(head) == hs else head[hs:]
        if len(body) < n:
            raise bad
        raw = body[:n]
    if len(raw) % dtype.itemsize:
        raise bad
    return np.frombuffer(raw, dtype).astype(float if dtype.kind == "f" else np.int64)


# --------------------------------------------------------------------------- STL / OBJ / OFF
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
