"""Surface meshes (``.stl``, ``.obj``, ``.ply``, ``.off``) through trimesh, as shell mid-surfaces.

The triangles become ``triangle`` shell cells; the thickness is not in these formats, so
give it with ``read_mesh(path, thickness=...)`` (metres) or to
:func:`~flexpipe.fem.assemble`.  Vertices that coincide (STL stores every triangle
separately; OBJ splits vertices at texture seams) are merged, zero-area triangles are
dropped with a warning.  The cell set ``surface`` holds all triangles; when trimesh
returns several named geometries (multi-object files), each also becomes a cell set of
that name (trimesh's OBJ loader usually merges ``o``/``g`` groups into one geometry).
"""

from __future__ import annotations

import warnings
from pathlib import Path

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.mesh.check_surface import check_obj, check_off, check_stl_ascii
from flexpipe.mesh.mesh import CellBlock, Mesh
from flexpipe.mesh.validate import MeshWarning

SURFACE_SUFFIXES = (".stl", ".obj", ".ply", ".off")


def read_surface(path) -> Mesh:
    """Read a triangulated surface as a shell mesh (units of the file)."""
    import trimesh

    suffix = str(path).lower().rsplit(".", 1)[-1]
    source = str(path)
    if suffix == "stl":
        if _check_stl_layout(path) == "ascii":
            check_stl_ascii(path, Path(path).read_bytes().decode("ascii"))
    elif suffix in ("obj", "off"):  # text formats: decoded here, not by trimesh's guesser
        import io

        text = _utf8_text(path)
        (check_obj if suffix == "obj" else check_off)(path, text)
        source = io.BytesIO(text.encode("utf-8"))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if isinstance(source, str):
                scene = trimesh.load_scene(source, process=False)
            else:
                scene = trimesh.load_scene(source, file_type=suffix, process=False)
    except Exception as exc:  # trimesh raises many types on corrupt input
        raise MeshError(f"cannot read surface mesh ({str(exc).strip() or type(exc).__name__})",
                        file=str(path)) from None
    verts, faces, names, counts = [], [], [], []
    offset = 0
    for node in scene.graph.nodes_geometry:
        transform, geom_name = scene.graph[node]
        g = scene.geometry.get(geom_name)
        if not isinstance(g, trimesh.Trimesh) or len(g.faces) == 0:
            continue
        v = trimesh.transform_points(np.asarray(g.vertices, dtype=float), transform)
        verts.append(v)
        faces.append(np.asarray(g.faces, dtype=np.int64) + offset)
        offset += len(v)
        names.append(str(node))
        counts.append(len(g.faces))
    if not faces:
        raise MeshError("no triangles found in the file", file=str(path))
    allv = np.vstack(verts)
    if not np.all(np.isfinite(allv)):
        _non_finite(path, int(np.flatnonzero(~np.isfinite(allv).all(axis=1))[0]))
    merged = trimesh.Trimesh(allv, np.vstack(faces), process=False)
    merged.merge_vertices(merge_tex=True, merge_norm=True)
    F = np.asarray(merged.faces, dtype=np.int64)
    P = np.asarray(merged.vertices, dtype=float)
    ids = np.arange(1, len(F) + 1)
    group = np.repeat(np.arange(len(counts)), counts)
    area = np.linalg.norm(np.cross(P[F[:, 1]] - P[F[:, 0]], P[F[:, 2]] - P[F[:, 0]]), axis=1)
    degenerate = ~(area > 1e-12 * max(float(np.ptp(P, axis=0).max()), 1e-300) ** 2)
    degenerate |= (F[:, 0] == F[:, 1]) | (F[:, 1] == F[:, 2]) | (F[:, 0] == F[:, 2])
    if degenerate.all():
        raise MeshError(f"all {len(F)} triangles have zero area (coincident or collinear "
                        "vertices, e.g. facet 1); the surface has no shell to model",
                        file=str(path))
    if degenerate.any():
        warnings.warn(MeshWarning(
            f"{path}: dropped {int(degenerate.sum())} zero-area triangle(s), e.g. ids "
            f"{ids[degenerate][:10].tolist()}"), stacklevel=3)
        F, ids, group = F[~degenerate], ids[~degenerate], group[~degenerate]
    used = np.unique(F)
    new_of = np.full(len(P), -1, dtype=np.int64)
    new_of[used] = np.arange(len(used))
    cell_sets = {"surface": {0: np.arange(len(F))}}
    if len(names) > 1:
        for k, n in enumerate(names):
            cell_sets.setdefault(n, {0: np.flatnonzero(group == k)})
    return Mesh(points=P[used], blocks=(CellBlock("triangle", new_of[F], ids),),
                cell_sets=cell_sets, source=str(path))


def _check_stl_layout(path) -> str:
    """Reject an STL that is neither a complete binary STL nor ASCII text, by its bytes.

    (trimesh would try to guess a text encoding, which needs an optional package, and
    report that instead of the real problem.)
    """
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise MeshError(f"cannot read the file ({exc.strerror})", file=str(path)) from None
    if not raw.strip():
        raise MeshError("the file is empty", file=str(path))
    if len(raw) >= 84:
        n = int.from_bytes(raw[80:84], "little")
        if len(raw) == 84 + 50 * n:
            if n == 0:
                raise MeshError("binary STL with 0 triangles", file=str(path))
            return "binary"  # a binary STL of consistent size
    if raw.lstrip()[:5].lower() == b"solid":
        try:
            raw.decode("ascii")
        except UnicodeDecodeError as exc:
            line = raw[: exc.start].count(b"\n") + 1
            raise MeshError(f"ASCII STL with a non-ASCII byte 0x{raw[exc.start]:02x}; an "
                            "ASCII STL holds 'facet normal', 'outer loop', 'vertex x y z' "
                            "lines only", file=str(path), line=line) from None
        return "ascii"
    expected = 84 + 50 * int.from_bytes(raw[80:84], "little") if len(raw) >= 84 else None
    raise MeshError(
        "neither an ASCII STL (text starting with 'solid') nor a complete binary STL ("
        + (f"its header announces {int.from_bytes(raw[80:84], 'little')} triangles, i.e. "
           f"{expected} bytes, but the file has {len(raw)}" if expected is not None else
           f"{len(raw)} bytes, shorter than the 84-byte binary header") + ")", file=str(path))


def _non_finite(path, vertex: int) -> None:
    """Raise for a NaN/inf coordinate: text files by line, binary STL by facet."""
    raw = Path(path).read_bytes()
    line = None
    try:
        text = raw.decode("utf-8")
    except UnicodeDecodeError:
        text = None
    if text is not None:
        for k, ln in enumerate(text.splitlines(), start=1):
            for tok in ln.replace(",", " ").split():
                try:
                    v = float(tok)
                except ValueError:
                    continue
                if not np.isfinite(v):
                    line = k
                    break
            if line is not None:
                break
    where = (f"vertex {vertex + 1}" if line is not None else
             f"vertex {vertex % 3 + 1} of facet {vertex // 3 + 1}")
    raise MeshError(f"non-finite coordinate (NaN or inf) at {where}; every vertex coordinate "
                    "must be a finite number", file=str(path), line=line)


def _utf8_text(path) -> str:
    """The file as UTF-8 text; bytes that are not UTF-8 are allowed in ``#`` comments only."""
    try:
        raw = Path(path).read_bytes()
    except OSError as exc:
        raise MeshError(f"cannot read the file ({exc.strerror})", file=str(path)) from None
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        pass
    for k, line in enumerate(raw.split(b"\n"), start=1):
        try:
            line.decode("utf-8")
        except UnicodeDecodeError as exc:
            if not line.lstrip().startswith(b"#"):
                raise MeshError(f"not a text file: byte 0x{line[exc.start]:02x} is not UTF-8 "
                                "text; OBJ and OFF files are text (v x y z / f i j k lines)",
                                file=str(path), line=k) from None
    return raw.decode("utf-8", errors="replace")
