"""Gmsh (``.msh`` v2.2/v4.x, ASCII and binary) and VTK (``.vtu``, ``.vtk``) through meshio.

Gmsh rule for lower-dimensional cells
-------------------------------------
A Gmsh file holds, besides the elements, the lines and points of the geometry that carry
physical groups (boundaries, interface faces, ...).  flexpipe keeps

* every cell of the file's highest dimension (3 for a solid mesh, 2 for a shell mesh,
  1 for a beam frame),
* lower-dimensional cells whose physical group name starts with ``beam`` (lines) or
  ``shell`` (triangles/quads), or whose type is listed in ``keep``
  (``read_mesh(..., keep=("line",))``).

Every physical group of lower dimension also becomes a *node set* of the same name
(``fixed``, ``hub_front_left``, ...) - the natural way to mark interface nodes; physical
groups of kept cells become *cell sets*.  Element ids are the 1-based positions of the
elements in the file; node ids the 1-based positions of the nodes (both equal Gmsh's own
tags for files Gmsh numbered consecutively, its default).
"""

from __future__ import annotations

import contextlib
import io
import threading
import warnings
from pathlib import Path

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.mesh._common import dimension, unsupported_type_message
from flexpipe.mesh.mesh import NODES_PER_CELL, CellBlock, Mesh
from flexpipe.mesh.validate import MeshWarning

PREFIX_KEEP = {1: "beam", 2: "shell"}


_SPY_LOCK = threading.Lock()


def _meshio_read(path, file_format):
    """``meshio.read`` that turns every failure into a :class:`MeshError` naming the file.

    For a file its reader rejects (``ReadError``: empty file, bad XML, wrong header),
    ``meshio.read`` prints the reason, then calls ``sys.exit(1)``; the printout is captured
    here and the ``SystemExit`` becomes the MeshError, so a corrupt file never ends the
    calling program.
    """
    import meshio

    said = io.StringIO()
    try:
        with warnings.catch_warnings(), contextlib.redirect_stdout(said), \
                contextlib.redirect_stderr(said):
            warnings.simplefilter("ignore")
            return meshio.read(str(path), file_format=file_format)
    except (Exception, SystemExit) as exc:  # meshio raises many types for corrupt files
        if isinstance(exc, SystemExit):
            # the reader's reason, without meshio's (line-wrapped) closing "Error: ..." line
            said_text = " ".join(said.getvalue().split())
            reason = said_text.split("Error: Couldn't read", 1)[0].strip()
            empty = Path(path).stat().st_size == 0
            msg = reason or ("the file is empty" if empty else
                             f"meshio's {file_format} reader rejected it")
        else:
            msg = str(exc).strip() or type(exc).__name__
        raise MeshError(f"cannot read as {file_format} file ({msg}); is the file complete "
                        "and in that format?", file=str(path)) from None


def _read_gmsh_with_tags(path):
    """meshio.read of a Gmsh file, plus the node tags meshio does not return.

    meshio's version-specific ``_read_nodes`` functions return the tags as their second
    value; they are observed for the duration of the call.  Returns ``(mesh, tags)``,
    ``tags`` None if they could not be observed.
    """
    from meshio.gmsh import _gmsh22, _gmsh40, _gmsh41

    seen = []
    modules = [mod for mod in (_gmsh22, _gmsh40, _gmsh41) if hasattr(mod, "_read_nodes")]
    with _SPY_LOCK:
        originals = {mod: mod._read_nodes for mod in modules}

        def spy(orig, shift):
            def wrapped(*args, **kwargs):
                out = orig(*args, **kwargs)
                seen.append(np.asarray(out[1]).ravel() + shift)
                return out
            return wrapped

        for mod in modules:  # the 4.1 reader returns tags - 1, the others the tags
            mod._read_nodes = spy(originals[mod], 1 if mod is _gmsh41 else 0)
        try:
            m = _meshio_read(path, "gmsh")
        finally:
            for mod, orig in originals.items():
                mod._read_nodes = orig
    tags = seen[-1].astype(np.int64) if seen and len(seen[-1]) == len(m.points) else None
    return m, tags


def _merge_by_type(pieces):
    """pieces: list of (type, cells, ids, tags) -> blocks merged by type, index maps."""
    order, acc = [], {}
    for t, cells, ids, tags in pieces:
        if t not in acc:
            order.append(t)
            acc[t] = []
        acc[t].append((cells, ids, tags))
    blocks, offsets = [], {}
    for t in order:
        parts = acc[t]
        blocks.append(CellBlock(t, np.vstack([p[0] for p in parts]),
                                np.concatenate([p[1] for p in parts]),
                                np.concatenate([p[2] for p in parts])))
    pos = {t: 0 for t in order}
    for k, (t, cells, _, _) in enumerate(pieces):
        offsets[k] = (order.index(t), pos[t])
        pos[t] += len(cells)
    return blocks, offsets


def read_gmsh(path, *, keep=()) -> Mesh:
    """Read a Gmsh ``.msh`` file (see module docstring for what is kept)."""
    from flexpipe.mesh.check_gmsh import check_gmsh

    check_gmsh(path)  # ASCII files: damaged lines named before meshio sees them
    m, tags = _read_gmsh_with_tags(path)
    points = np.asarray(m.points, dtype=float)
    if tags is not None and len(np.unique(tags)) == len(tags):
        order = np.argsort(tags, kind="stable")       # nodes in the order of their tags
        inv = np.empty_like(order)
        inv[order] = np.arange(len(order))
        points, node_ids = points[order], tags[order]
        cdata = [inv[np.asarray(b.data)] for b in m.cells]
    else:
        node_ids = None
        cdata = [np.asarray(b.data) for b in m.cells]
    names = {}
    for name, val in m.field_data.items():
        tag, dim = (int(v) for v in np.asarray(val).ravel()[:2])
        names[name] = (dim, tag)
    phys = m.cell_data.get("gmsh:physical")
    dims = [dimension(b.type) for b in m.cells]
    if not dims:
        raise MeshError("the file has no elements", file=str(path))
    top = max(dims)
    # membership of each physical group: list of (block, local indices)
    groups: dict[str, list] = {n: [] for n in names}
    meshio_sets = {k: v for k, v in m.cell_sets.items() if k in names}
    for k in range(len(m.cells)):
        for n, (d, tag) in names.items():
            if d != dims[k]:
                continue
            if meshio_sets:
                idx = np.asarray(meshio_sets[n][k] if meshio_sets[n][k] is not None else [],
                                 dtype=np.int64)
            elif phys is not None:
                idx = np.flatnonzero(np.asarray(phys[k]) == tag)
            else:
                idx = np.zeros(0, dtype=np.int64)
            if idx.size:
                groups[n].append((k, idx))
    kept_mask = []
    for k, b in enumerate(m.cells):
        d = dims[k]
        mask = np.full(len(b.data), d == top or b.type in keep)
        if not mask.all() and d in PREFIX_KEEP:
            for n, members in groups.items():
                if n.lower().startswith(PREFIX_KEEP[d]):
                    for kk, idx in members:
                        if kk == k:
                            mask[idx] = True
        kept_mask.append(mask)
    pieces, piece_of_block, start = [], {}, 0
    for k, b in enumerate(m.cells):
        mask = kept_mask[k]
        ids = np.arange(start + 1, start + len(b.data) + 1)
        start += len(b.data)
        if not mask.any():
            continue
        if b.type not in NODES_PER_CELL or b.type == "vertex" and "vertex" not in keep:
            if b.type != "vertex":
                raise MeshError(unsupported_type_message(b.type)
                                + f" (e.g. element {ids[mask][0]})", file=str(path))
            continue
        ptags = (np.asarray(phys[k], dtype=np.int64) if phys is not None
                 else np.zeros(len(b.data), dtype=np.int64))
        piece_of_block[k] = (len(pieces), np.cumsum(mask) - 1)
        pieces.append((b.type, cdata[k][mask], ids[mask], ptags[mask]))
    if not pieces:
        found = sorted({b.type for b in m.cells})
        raise MeshError(f"no elements of a supported type; found {found}", file=str(path))
    blocks, offsets = _merge_by_type(pieces)
    cell_sets, node_sets = {}, {}
    for n, members in groups.items():
        d = names[n][0]
        cs: dict[int, list] = {}
        nodes = []
        for k, idx in members:
            nodes.append(cdata[k][idx].ravel())
            if k in piece_of_block:
                p, local = piece_of_block[k]
                sel = idx[kept_mask[k][idx]]
                if sel.size:
                    bi, off = offsets[p]
                    cs.setdefault(bi, []).append(off + local[sel])
        if cs:
            cell_sets[n] = {bi: np.sort(np.concatenate(v)) for bi, v in cs.items()}
        if d < top and nodes:
            node_sets[n] = np.unique(np.concatenate(nodes))
    return Mesh(points=points, blocks=tuple(blocks), node_ids=node_ids,
                node_sets=node_sets, cell_sets=cell_sets, source=str(path))


def read_vtk(path, file_format: str) -> Mesh:
    """Read a ``.vtu``/``.vtk`` file; ``node_id``/``element_id``/``property_id`` arrays
    (written by flexpipe) restore ids and tags."""
    from flexpipe.mesh.check_vtu import check_vtk, check_vtu

    # damaged arrays and lines named before meshio sees them
    (check_vtu if file_format == "vtu" else check_vtk)(path)
    m = _meshio_read(path, file_format)
    pieces, start = [], 0
    eid = m.cell_data.get("element_id")
    pid = m.cell_data.get("property_id") or m.cell_data.get("gmsh:physical")
    for k, b in enumerate(m.cells):
        n = len(b.data)
        ids = (np.asarray(eid[k], dtype=np.int64).ravel() if eid is not None
               else np.arange(start + 1, start + n + 1))
        start += n
        if b.type not in NODES_PER_CELL:
            raise MeshError(unsupported_type_message(b.type) + f" (e.g. cell {ids[0]})",
                            file=str(path))
        tags = (np.asarray(pid[k], dtype=np.int64).ravel() if pid is not None
                else np.zeros(n, dtype=np.int64))
        pieces.append((b.type, np.asarray(b.data), ids, tags))
    if not pieces:
        raise MeshError("the file has no cells", file=str(path))
    blocks, _ = _merge_by_type(pieces)
    nid = m.point_data.get("node_id")
    return Mesh(points=np.asarray(m.points, dtype=float), blocks=tuple(blocks),
                node_ids=None if nid is None else np.asarray(nid, dtype=np.int64).ravel(),
                source=str(path))


def _groups(mesh: Mesh):
    """Split every block by the first cell set containing each cell: (type, cells, name)."""
    out = []
    names = list(mesh.cell_sets)
    overlap = False
    for bi, b in enumerate(mesh.blocks):
        group = np.full(len(b), -1, dtype=np.int64)
        for k, n in enumerate(names):
            cells = mesh.cell_sets[n].get(bi)
            if cells is None:
                continue
            overlap |= bool((group[cells] >= 0).any())
            free = cells[group[cells] < 0]
            group[free] = k
        for k in np.unique(group):
            sel = group == k
            out.append((b.type, b.cells[sel], names[k] if k >= 0 else None))
    if overlap:
        warnings.warn(MeshWarning("overlapping cell sets: Gmsh files give each element one "
                                  "physical group; the first set wins"), stacklevel=3)
    return out


def to_gmsh_meshio(mesh: Mesh):
    """meshio.Mesh with physical groups for cell sets (per element) and node sets
    (vertex cells); lower-dimensional element groups get a ``beam``/``shell`` prefix so
    that :func:`read_gmsh` keeps them."""
    import meshio

    groups = _groups(mesh)
    top = max((dimension(t) for t, _, _ in groups if t != "vertex"), default=0)
    field_data, cells, phys, geo = {}, [], [], []
    tag_of = {}
    for k, (t, conn, name) in enumerate(groups):
        d = dimension(t)
        if name is None and (d < top or any(n is not None for _, _, n in groups)):
            name = f"{PREFIX_KEEP.get(d, 'cells')}_{t}" if d < top else f"unnamed_{t}"
        if d in PREFIX_KEEP and d < top and name is not None \
                and not name.lower().startswith(PREFIX_KEEP[d]):
            name = f"{PREFIX_KEEP[d]}_{name}"
        tag = 0
        if name is not None:
            tag = tag_of.setdefault((d, name), len(tag_of) + 1)
            field_data[name] = np.array([tag, d])
        cells.append(meshio.CellBlock(t, conn))
        phys.append(np.full(len(conn), tag, dtype=int))
        geo.append(np.full(len(conn), k + 1, dtype=int))
    for name, idx in mesh.node_sets.items():
        if name in field_data:
            warnings.warn(MeshWarning(f"node set '{name}' has the name of a cell set; written "
                                      f"as 'nodes_{name}'"), stacklevel=3)
            name = f"nodes_{name}"
        tag = tag_of.setdefault((0, name), len(tag_of) + 1)
        field_data[name] = np.array([tag, 0])
        cells.append(meshio.CellBlock("vertex", np.asarray(idx).reshape(-1, 1)))
        phys.append(np.full(len(idx), tag, dtype=int))
        geo.append(np.full(len(idx), len(cells), dtype=int))
    cell_data = {"gmsh:physical": phys, "gmsh:geometrical": geo} if field_data else {}
    return meshio.Mesh(mesh.points, cells, cell_data=cell_data, field_data=field_data)


def _dim_tags(mesh_m) -> np.ndarray:
    """Node entity tags for the Gmsh 4.1 writer: every cell block is one entity.

    Gmsh 4.1 lists entities through their nodes, so each block needs at least one node
    that no other block claims: blocks are served in order of decreasing dimension, and
    a block whose nodes are all taken gets one that is not another block's only node.
    """
    n = len(mesh_m.points)
    tags = np.zeros((n, 2), dtype=int)
    owner = np.full(n, -1, dtype=np.int64)
    anchored = np.zeros(n, dtype=bool)
    geo = mesh_m.cell_data["gmsh:geometrical"]
    for k in sorted(range(len(mesh_m.cells)), key=lambda k: -dimension(mesh_m.cells[k].type)):
        b = mesh_m.cells[k]
        nodes = np.unique(b.data)
        fresh = nodes[owner[nodes] < 0]
        if fresh.size == 0:
            free = nodes[~anchored[nodes]]
            if free.size == 0:
                raise MeshError("cannot write this mesh as Gmsh 4.1 (a node set has no node of "
                                "its own); write Gmsh 2.2 instead")
            fresh = free[:1]
        anchored[fresh[0]] = True
        tags[fresh] = [dimension(b.type), int(geo[k][0])]
        owner[fresh] = k
    if (owner < 0).any() and (owner >= 0).any():
        tags[owner < 0] = tags[np.flatnonzero(owner >= 0)[0]]
    return tags


def write_gmsh(mesh: Mesh, path, *, version: str = "2.2", binary: bool = False) -> None:
    """Write ``mesh`` as Gmsh ``.msh`` (``version`` "2.2" or "4.1") to ``path``."""
    m = to_gmsh_meshio(mesh)
    if version == "4.1":
        if "gmsh:geometrical" not in m.cell_data:
            m.cell_data["gmsh:geometrical"] = [np.full(len(b.data), k + 1)
                                               for k, b in enumerate(m.cells)]
            m.cell_data["gmsh:physical"] = [np.zeros(len(b.data), dtype=int) for b in m.cells]
        m.point_data["gmsh:dim_tags"] = _dim_tags(m)
    elif version != "2.2":
        raise MeshError(f"unknown Gmsh version {version!r}; valid: '2.2', '4.1'", file=str(path))
    import meshio

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        meshio.write(str(path), m, file_format="gmsh22" if version == "2.2" else "gmsh",
                     binary=binary)


def write_vtk(mesh: Mesh, path, *, file_format: str = "vtu", point_data=None,
              field_data=None) -> None:
    """Write ``mesh`` (plus optional point/field data) as ``.vtu``/``.vtk`` to ``path``."""
    import meshio

    # springs have no VTK cell type of their own: two-node springs as lines, grounded
    # ones as vertices
    as_vtk = {"spring": "line", "spring1": "vertex"}
    cells = [meshio.CellBlock(as_vtk.get(b.type, b.type), b.cells) for b in mesh.blocks]
    pd = {"node_id": np.asarray(mesh.node_ids)}
    pd.update(point_data or {})
    cd = {"element_id": [np.asarray(b.ids) for b in mesh.blocks],
          "property_id": [np.asarray(b.tags) for b in mesh.blocks]}
    m = meshio.Mesh(mesh.points, cells, point_data=pd, cell_data=cd)
    if not field_data:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            meshio.write(str(path), m, file_format=file_format)
        return
    if file_format != "vtu":
        raise MeshError("field data can only be written to .vtu files", file=str(path))
    # meshio's VTU writer has no FieldData: write, then copy with the block inserted
    path = Path(path)
    raw = path.with_name(path.name + ".raw.vtu")
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            meshio.write(str(raw), m, file_format="vtu")
        _insert_field_data(raw, path, field_data)
    finally:
        raw.unlink(missing_ok=True)


def _insert_field_data(src: Path, dst: Path, field_data) -> None:
    """Copy VTU ``src`` to ``dst`` with a ``<FieldData>`` block of float arrays."""
    parts = ["<FieldData>\n"]
    for name, values in field_data.items():
        v = np.asarray(values, dtype=float).ravel()
        parts.append(f'<DataArray type="Float64" Name="{name}" NumberOfTuples="{len(v)}" '
                     f'format="ascii">\n{" ".join(repr(float(x)) for x in v)}\n</DataArray>\n')
    parts.append("</FieldData>\n")
    block = "".join(parts)
    inserted = False
    with open(src, encoding="utf-8") as fin, open(dst, "w", encoding="utf-8") as fout:
        for line in fin:
            fout.write(line)
            if not inserted and line.lstrip().startswith("<UnstructuredGrid"):
                fout.write(block)
                inserted = True
    if not inserted:
        raise MeshError("unexpected VTU layout: no <UnstructuredGrid> element", file=str(dst))
