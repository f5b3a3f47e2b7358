"""OpenCRG writer: :func:`write_crg` (formats KRBI, KDBI, LRFI, LDFI), atomically."""

from __future__ import annotations

import math

import numpy as np

from flexpipe._io import atomic_path
from flexpipe.errors import InputError
from flexpipe.roads.road import Road


def _fmt_text(v: float, width: int) -> str:
    if not math.isfinite(v):
        return "*missing*".ljust(width)[:width]
    for prec in range(width - 3, 0, -1):
        s = f"{v:{width}.{prec}f}"
        if len(s) <= width:
            return s
    s = f"{v:{width}.{width - 7}E}"
    if len(s) > width:
        raise InputError(f"value {v!r} does not fit a {width}-character CRG field")
    return s


def write_crg(road: Road, path, *, fmt: str = "KRBI", comment: str = "") -> None:
    """Write ``road`` as an OpenCRG file (atomically).

    Parameters
    ----------
    road : Road
        Must have uniform ``x`` spacing.  A road without a lateral grid is written with two
        long sections at ``-track_width/2`` (right) and ``+track_width/2`` (left).  The
        reference line's start position is written, and for a curved one its heading as a
        ``reference line phi`` channel; slope and banking are part of the written heights.
    path : str or pathlib.Path
        Output file.
    fmt : {'KRBI', 'KDBI', 'LRFI', 'LDFI'}
        Data format (binary single/double, text single/double).
    comment : str
        Text for the ``$CT`` block.
    """
    fmt = fmt.upper()
    if fmt not in ("KRBI", "KDBI", "LRFI", "LDFI"):
        raise InputError(f"CRG format {fmt!r} not writable; valid: KRBI, KDBI, LRFI, LDFI")
    if not road._dx:
        raise InputError(f"road '{road.name}' has non-uniform distance samples; OpenCRG needs "
                         "a constant REFERENCE_LINE_INCREMENT")
    if road.z is None:
        v = np.array([-0.5, 0.5]) * road.track_width
        z = np.column_stack([road.right, road.left])
    else:
        v, z = road.y, road.z
    dv = np.diff(v)
    if np.any(np.abs(dv - dv[0]) > 1e-9 * max(1.0, abs(v[-1]))):
        raise InputError("the lateral grid is not uniform; write_crg needs a uniform grid")
    du = road._dx
    head = ["$CT", *(comment.splitlines() or [road.name or "flexpipe road"]), "$",
            "$ROAD_CRG"]
    for key, value in (("REFERENCE_LINE_START_U", road.x[0]),
                       ("REFERENCE_LINE_END_U", road.x[-1]),
                       ("REFERENCE_LINE_INCREMENT", du),
                       ("LONG_SECTION_V_RIGHT", v[0]), ("LONG_SECTION_V_LEFT", v[-1]),
                       ("LONG_SECTION_V_INCREMENT", dv[0])):
        head.append(f"{key:<26}= {value:.16e}")
    plan = road.plan
    curved = plan is not None and not plan.straight
    if plan is not None:
        head += [f"{'REFERENCE_LINE_START_X':<26}= {plan.x[0]:.16e}",
                 f"{'REFERENCE_LINE_START_Y':<26}= {plan.y[0]:.16e}"]
        if not curved:
            head.append(f"{'REFERENCE_LINE_START_PHI':<26}= {plan.phi_start:.16e}")
    # an empty modifier section: a reader keeps the placement written above (without one,
    # OpenCRG's default modifiers would move the start to the origin)
    head += ["$", "$ROAD_CRG_MODS", "* no modifiers: the road stays where it is written",
             "$", "$KD_DEFINITION", f"#:{fmt}",
             f"U:reference line u,m,{road.x[0]:.3f},{du:.3f}"]
    if curved:
        head.append("D:reference line phi,rad")
        z = np.column_stack([np.r_[np.nan, plan.phi], z])
    head += [f"D:long section {j + 1},m" for j in range(v.size)]
    head += ["$", "$" * 72]
    body = "\n".join(line[:72] for line in head) + "\n"
    with atomic_path(path) as tmp:
        with open(tmp, "wb") as fh:
            fh.write(body.encode("ascii"))
            if fmt[2] == "B":
                dtype = ">f4" if fmt[1] == "R" else ">f8"
                flat = np.asarray(z, dtype=float).ravel()
                per_record = 80 // np.dtype(dtype).itemsize
                pad = (-flat.size) % per_record
                block = np.concatenate([flat, np.full(pad, np.nan)]).astype(dtype)
                fh.write(block.tobytes())
            else:
                width = 10 if fmt[1] == "R" else 20
                per_line = 80 // width
                out = []
                for row in z:
                    fields = [_fmt_text(float(val), width) for val in row]
                    out += ["".join(fields[i:i + per_line])
                            for i in range(0, len(fields), per_line)]
                fh.write(("\n".join(out) + "\n").encode("ascii"))
