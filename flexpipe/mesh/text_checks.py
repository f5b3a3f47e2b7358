"""Line-exact structure checks of text mesh files read by third-party parsers (shared
helpers here; the checks in :mod:`~flexpipe.mesh.check_gmsh`,
:mod:`~flexpipe.mesh.check_vtu`, :mod:`~flexpipe.mesh.check_surface`).

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
from pathlib import Path

from flexpipe.errors import MeshError


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
