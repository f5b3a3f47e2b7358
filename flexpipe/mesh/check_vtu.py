"""Structure check of ``.vtu`` files with inline ASCII or base64 (zlib) data arrays; see
:mod:`flexpipe.mesh.text_checks`."""

from __future__ import annotations

import re

import numpy as np

from flexpipe.mesh.text_checks import _err, _is_int, _lines

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


# --------------------------------------------------------------------------- legacy .vtk
def _tokens(lines, start):
    for k in range(start, len(lines)):
        for tok in lines[k].split():
            yield tok, k + 1


class _Stream:
    def __init__(self, path, lines, start):
        self.path, self.it, self.line = path, _tokens(lines, start), start

    def next(self, what):
        try:
            tok, self.line = next(self.it)
        except StopIteration:
            raise _err(self.path, self.line, f"the file ends inside {what} (truncated?)"
                       ) from None
        return tok

    def ints(self, n, what):
        out = []
        for _ in range(n):
            tok = self.next(what)
            if not _is_int(tok):
                raise _err(self.path, self.line, f"{what}: {tok!r} is not an integer")
            out.append(int(tok))
        return out

    def numbers(self, n, what):
        for _ in range(n):
            tok = self.next(what)
            try:
                float(tok)
            except ValueError:
                raise _err(self.path, self.line, f"{what}: {tok!r} is not a number") from None


_LEGACY_TYPES = {"bit", "unsigned_char", "char", "unsigned_short", "short", "unsigned_int",
                 "int", "unsigned_long", "long", "float", "double", "vtkidtype", "vtktypeint8",
                 "vtktypeuint8", "vtktypeint16", "vtktypeuint16", "vtktypeint32",
                 "vtktypeuint32", "vtktypeint64", "vtktypeuint64", "vtktypefloat32",
                 "vtktypefloat64"}


def _type(s, what) -> None:
    tok = s.next(what)
    if tok.lower() not in _LEGACY_TYPES:
        raise _err(s.path, s.line, f"{what}: {tok!r} is not a VTK data type; valid: "
                                   f"{', '.join(sorted(_LEGACY_TYPES))}")


def check_vtk(path) -> None:
    """Check a legacy ASCII ``.vtk`` UNSTRUCTURED_GRID (versions 2-5.1); binary files and
    other datasets are left to meshio."""
    lines = _lines(path)
    if lines is None or not any(ln.strip() for ln in lines):
        return
    if not lines[0].lower().startswith("# vtk datafile version"):
        raise _err(path, 1, "a legacy VTK file starts with '# vtk DataFile Version x.x'")
    if len(lines) < 4:
        raise _err(path, len(lines), "the header needs 4 lines (version, title, ASCII|BINARY, "
                                     "DATASET ...)")
    kind = lines[2].strip().upper()
    if kind == "BINARY":
        return
    if kind != "ASCII":
        raise _err(path, 3, f"line 3 must be ASCII or BINARY, got {lines[2].strip()[:40]!r}")
    s = _Stream(path, lines, 3)
    if s.next("DATASET").upper() != "DATASET":
        raise _err(path, s.line, "expected 'DATASET UNSTRUCTURED_GRID'")
    if s.next("DATASET").upper() != "UNSTRUCTURED_GRID":
        return
    n_points = n_cells = None
    while True:
        try:
            tok, s.line = next(s.it)
        except StopIteration:
            break
        key = tok.upper()
        if key == "POINTS":
            (n_points,) = s.ints(1, "POINTS count")
            _type(s, "POINTS type")
            s.numbers(3 * n_points, f"POINTS ({n_points} points, {3 * n_points} numbers)")
        elif key == "CELLS":
            a, b = s.ints(2, "CELLS counts")
            if s.line and lines[s.line - 1].split()[:1] and _peek(lines, s) == "OFFSETS":
                s.next("OFFSETS")
                _type(s, "OFFSETS type")
                offs = s.ints(a, f"OFFSETS ({a} values)")
                s.next("CONNECTIVITY")
                _type(s, "CONNECTIVITY type")
                conn = s.ints(b, f"CONNECTIVITY ({b} values)")
                if offs and (offs[0] != 0 or offs[-1] != b or any(
                        y < x for x, y in zip(offs, offs[1:], strict=False))):
                    raise _err(path, s.line, f"OFFSETS must rise from 0 to {b}")
                n_cells = a - 1
            else:
                flat = s.ints(b, f"CELLS ({a} cells in {b} numbers)")
                conn, k = [], 0
                for _ in range(a):
                    if k >= len(flat) or flat[k] < 1 or k + flat[k] >= len(flat) + 0 and \
                            k + 1 + flat[k] > len(flat):
                        raise _err(path, s.line, f"CELLS: the size {b} does not hold {a} "
                                                 "cells of 'n i1 .. in'")
                    conn += flat[k + 1:k + 1 + flat[k]]
                    k += 1 + flat[k]
                if k != len(flat):
                    raise _err(path, s.line, f"CELLS: {a} cells use {k} numbers, size says {b}")
                n_cells = a
            if n_points is not None:
                bad = [c for c in conn if not 0 <= c < n_points]
                if bad:
                    raise _err(path, s.line, f"cell connectivity refers to point {bad[0]}; "
                                             f"valid 0 .. {n_points - 1}")
        elif key == "CELL_TYPES":
            (n,) = s.ints(1, "CELL_TYPES count")
            if n_cells is not None and n != n_cells:
                raise _err(path, s.line, f"CELL_TYPES announces {n} cells, CELLS has "
                                         f"{n_cells}")
            types = s.ints(n, f"CELL_TYPES ({n} values)")
            bad = [t for t in types if not 1 <= t <= 83]
            if bad:
                raise _err(path, s.line, f"cell type {bad[0]} is not a VTK cell type")
        elif key in ("POINT_DATA", "CELL_DATA", "FIELD", "METADATA"):
            return  # data sections are left to meshio
        else:
            raise _err(path, s.line, f"unexpected {tok[:30]!r}; expected POINTS, CELLS, "
                                     "CELL_TYPES, POINT_DATA or CELL_DATA")
    if n_points is None or n_cells is None:
        raise _err(path, s.line, "an UNSTRUCTURED_GRID needs POINTS, CELLS and CELL_TYPES")


def _peek(lines, s) -> str:
    """First token of the line after the current one (the OFFSETS keyword of VTK 5.1)."""
    for k in range(s.line, len(lines)):
        parts = lines[k].split()
        if parts:
            return parts[0].upper()
    return ""
