"""Bad meshio/surface mesh files for ``read_mesh`` + ``assemble``: Gmsh ``.msh`` (v2.2
ASCII, v4.1 ASCII, v2.2 binary), VTK ``.vtu`` (ASCII), STL (ASCII and binary), OBJ, OFF.

Valid small meshes are written by flexpipe's own writers (and by hand for the surface
formats), then damaged: truncation, deleted lines, NaN/inf/garbage in coordinates,
connectivity pointing at missing nodes, random bytes, wrong headers.
"""

from __future__ import annotations

import struct
import tempfile
from functools import lru_cache
from pathlib import Path

import numpy as np


@lru_cache(maxsize=1)
def valid_files() -> dict:
    """{name: (filename, bytes)} of valid meshes."""
    import warnings

    warnings.filterwarnings("ignore", message="VTK ASCII files are only meant for debugging")
    from flexpipe.mesh import write_mesh
    from flexpipe.mesh.generate import box, plate

    out = {}
    solid = box(1.0, 0.2, 0.2, 3, 1, 1, cell="hexahedron")
    shell = plate(1.0, 0.5, 3, 2)
    with tempfile.TemporaryDirectory() as d:
        d = Path(d)
        for name, mesh, fname, kw in (
                ("msh22", solid, "mesh.msh", {"gmsh_version": "2.2"}),
                ("msh41", solid, "mesh.msh", {"gmsh_version": "4.1"}),
                ("msh22-shell", shell, "mesh.msh", {"gmsh_version": "2.2"}),
                ("vtu", solid, "mesh.vtu", {}),
                ("vtu-shell", shell, "mesh.vtu", {})):
            p = d / f"{name}-{fname}"
            write_mesh(mesh, p, **kw)
            out[name] = (fname, p.read_bytes())
        import meshio

        p = d / "legacy.vtk"
        meshio.write(p, meshio.Mesh(solid.points, [("hexahedron", solid.blocks[0].cells)]),
                     binary=False)
        out["vtk"] = ("mesh.vtk", p.read_bytes())
    out["stl"] = ("mesh.stl", ascii_stl(_square()).encode())
    out["stl-bin"] = ("mesh.stl", binary_stl(_square()))
    out["obj"] = ("mesh.obj", b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 0.5 0\n"
                              b"f 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n")
    out["off"] = ("mesh.off", b"OFF\n5 4 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 0.5 0\n"
                              b"3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n")
    return out


def _square():
    p = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0.5, 0.5, 0]], float)
    return [p[[0, 1, 4]], p[[1, 2, 4]], p[[2, 3, 4]], p[[3, 0, 4]]]


def ascii_stl(tris) -> str:
    s = "solid square\n"
    for t in tris:
        s += "  facet normal 0 0 1\n    outer loop\n"
        s += "".join(f"      vertex {float(x)!r} {float(y)!r} {float(z)!r}\n" for x, y, z in t)
        s += "    endloop\n  endfacet\n"
    return s + "endsolid square\n"


def binary_stl(tris, *, count=None) -> bytes:
    out = b"binary stl".ljust(80, b" ") + struct.pack("<I", len(tris) if count is None
                                                     else count)
    for t in tris:
        out += struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *v) for v in t)
        out += b"\0\0"
    return out


def _number_positions(text: str, start_marker: str | None = None):
    """Character spans of numbers in ``text`` (after ``start_marker``)."""
    import re

    start = text.find(start_marker) if start_marker else 0
    return [m.span() for m in re.finditer(r"-?\d+\.?\d*(?:e[-+]?\d+)?", text[start:])], start


def _text_mutations(text: str, marker: str | None):
    lines = text.splitlines(keepends=True)
    n = len(lines)
    for frac in (0.1, 0.3, 0.5, 0.7, 0.9, 0.98):
        yield f"truncated-{frac}", text[: int(len(text) * frac)].encode()
    for k in sorted({1, n // 4, n // 2, 3 * n // 4, n - 2}):
        if 0 <= k < n:
            yield f"line-{k + 1}-deleted", "".join(lines[:k] + lines[k + 1:]).encode()
    spans, start = _number_positions(text, marker)
    picks = sorted({len(spans) // 7, len(spans) // 3, len(spans) // 2, 2 * len(spans) // 3})
    for j in picks:
        a, b = spans[j]
        a, b = a + start, b + start
        for token in ("nan", "inf", "abc", "1e999", "-99999"):
            yield f"number-{j}-{token}", (text[:a] + token + text[b:]).encode()
    yield "empty", b""
    yield "random", np.random.default_rng(7).bytes(2000)
    yield "doubled", (text + text).encode()
    yield "crlf", text.replace("\n", "\r\n").encode()


#: mutations after which the file may still be valid (the reader may accept them)
MAY_LOAD = ("crlf", "doubled", "-99999", "1e999")


def cases():
    files = valid_files()
    for name, (fname, data) in files.items():
        yield f"{name}-valid", fname, data, "ok"
    markers = {"msh22": "$Nodes", "msh41": "$Nodes", "msh22-shell": "$Nodes",
               "vtu": "<Points", "vtu-shell": "<Points", "stl": "vertex", "obj": "v ",
               "off": "\n5 4 0", "vtk": "POINTS"}
    for name, marker in markers.items():
        fname, data = files[name]
        for mid, content in _text_mutations(data.decode(), marker):
            expect = "error:file" if mid in ("empty", "random") else "error"
            if any(mid.endswith(t) for t in MAY_LOAD) or mid in MAY_LOAD:
                expect = "maybe"
            if name in ("obj",) and (mid.startswith(("truncated", "line-"))):
                expect = "maybe"  # ends at a line boundary: a smaller valid OBJ
            if name == "obj" and mid == "truncated-0.1":
                expect = "error:file"  # vertices only: no face at all
            yield f"{name}-{mid}", fname, content, expect
    # binary STL
    tris = _square()
    yield "stl-bin-count-too-big", "mesh.stl", binary_stl(tris, count=10), "error:file"
    yield "stl-bin-count-too-small", "mesh.stl", binary_stl(tris, count=1), "error:file"
    yield "stl-bin-zero-triangles", "mesh.stl", binary_stl([], count=0), "error:file"
    yield "stl-bin-header-only", "mesh.stl", binary_stl(tris)[:84], "error:file"
    yield "stl-bin-truncated", "mesh.stl", binary_stl(tris)[:-7], "error:file"
    nan_tris = [t.copy() for t in tris]
    nan_tris[2][1, 0] = np.nan
    yield "stl-bin-nan-vertex", "mesh.stl", binary_stl(nan_tris), "error"
    inf_tris = [t.copy() for t in tris]
    inf_tris[0][0, 2] = np.inf
    yield "stl-bin-inf-vertex", "mesh.stl", binary_stl(inf_tris), "error"
    yield "stl-ascii-nan-vertex", "mesh.stl", ascii_stl(nan_tris).encode(), "error"
    yield "stl-all-degenerate", "mesh.stl", ascii_stl([np.zeros((3, 3))] * 3).encode(), \
        "error"
    yield "stl-garbage-binary-500", "mesh.stl", np.random.default_rng(1).bytes(500), \
        "error:file"
    yield "stl-solid-then-garbage", "mesh.stl", b"solid x\n" + bytes(range(128, 256)), \
        "error"
    yield "obj-latin1-vertex-line", "mesh.obj", b"v 0 0 0\nv 1 0 0\xe9\nv 0 1 0\nf 1 2 3\n", \
        "error"
    yield "obj-face-index-out-of-range", "mesh.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", \
        "error"
    yield "obj-no-faces", "mesh.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n", "error:file"
    yield "obj-nan", "mesh.obj", b"v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n", "error"
    yield "off-count-mismatch", "mesh.off", b"OFF\n9 4 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", \
        "error"
    yield "ply-garbage", "mesh.ply", np.random.default_rng(3).bytes(300), "error:file"
    yield "ply-header-only", "mesh.ply", b"ply\nformat ascii 1.0\nelement vertex 3\n" \
        b"property float x\nproperty float y\nproperty float z\nend_header\n", "error:file"
    yield "msh-wrong-version", "mesh.msh", b"$MeshFormat\n9.9 0 8\n$EndMeshFormat\n", "error"
    yield "msh-no-elements", "mesh.msh", b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n" \
        b"1 0 0 0\n$EndNodes\n$Elements\n0\n$EndElements\n", "error:file"
    yield "vtu-not-xml", "mesh.vtu", b"<VTKFile type='UnstructuredGrid'><oops", "error:file"
    yield "vtu-empty-grid", "mesh.vtu", (
        b'<?xml version="1.0"?><VTKFile type="UnstructuredGrid" version="0.1">'
        b'<UnstructuredGrid><Piece NumberOfPoints="0" NumberOfCells="0"><Points>'
        b'<DataArray type="Float64" NumberOfComponents="3" format="ascii"></DataArray>'
        b'</Points><Cells><DataArray type="Int64" Name="connectivity" format="ascii">'
        b'</DataArray><DataArray type="Int64" Name="offsets" format="ascii"></DataArray>'
        b'<DataArray type="UInt8" Name="types" format="ascii"></DataArray></Cells></Piece>'
        b'</UnstructuredGrid></VTKFile>'), "error"
