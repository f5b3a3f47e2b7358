"""OpenCRG modifiers (``$ROAD_CRG_MODS``): scaling, NaN filling and placement of a road.

A simulator applies a CRG file's modifiers when it loads the file, in this order:

1. scaling: ``SCALE_Z_GRID`` (the elevation grid), ``SCALE_SLOPE`` and ``SCALE_BANKING``
   (of the reference line), ``SCALE_LENGTH`` (every length along ``u``: the increment, the
   plan position and the elevation of the reference line about its start),
   ``SCALE_WIDTH`` (the lateral positions ``v``), ``SCALE_CURVATURE`` (the heading changes
   of a curved reference line, re-integrated from its start);
2. NaN filling: ``GRID_NAN_MODE`` 1 (every NaN becomes ``GRID_NAN_OFFSET``) or 2 (a NaN at
   the border of a cross section becomes the last valid value plus ``GRID_NAN_OFFSET``);
   mode 0 keeps the NaNs, which a car cannot drive on;
3. placement by a reference point: the point ``(REFPOINT_U, REFPOINT_V)`` of the road
   (or ``REFPOINT_U_FRACTION`` / ``REFPOINT_V_FRACTION`` of its length and width, each
   plus ``REFPOINT_U_OFFSET`` / ``REFPOINT_V_OFFSET``; default the start of the reference
   line) is moved to ``(REFPOINT_X, REFPOINT_Y, REFPOINT_Z)`` with the reference line's
   heading there turned to ``REFPOINT_PHI`` (the road turns about its start);
4. or placement by offset: the road turns by ``REFLINE_OFFSET_PHI`` about
   ``(REFLINE_ROTCENTER_X, REFLINE_ROTCENTER_Y)`` (default its start) and moves by
   ``REFLINE_OFFSET_X / _Y / _Z``.  With modifiers of both kinds the reference point wins
   (a warning says so).

A file **without** a ``$ROAD_CRG_MODS`` section gets OpenCRG's default modifiers,
``GRID_NAN_MODE = 2`` and ``REFPOINT_PHI = 0``: its reference line starts at the origin,
heading along x, with the surface at the start of the reference line at z = 0.  An empty
``$ROAD_CRG_MODS`` section keeps the file's own placement (the OpenCRG idiom; flexpipe's
writer emits one).  Angles in radians, lengths in metres.  The definitions follow the
OpenCRG format and are tested against pyopencrg's ``apply_mods``.
"""

from __future__ import annotations

import difflib
import math
import warnings

import numpy as np

from flexpipe.errors import InputError
from flexpipe.roads.refline import ReferenceLine

#: every modifier of the OpenCRG format (upper case as written in files)
SCALING = ("SCALE_Z_GRID", "SCALE_SLOPE", "SCALE_BANKING", "SCALE_LENGTH", "SCALE_WIDTH",
           "SCALE_CURVATURE")
NAN = ("GRID_NAN_MODE", "GRID_NAN_OFFSET")
BY_OFFSET = ("REFLINE_OFFSET_PHI", "REFLINE_OFFSET_X", "REFLINE_OFFSET_Y", "REFLINE_OFFSET_Z")
ROTCENTER = ("REFLINE_ROTCENTER_X", "REFLINE_ROTCENTER_Y")
BY_REFPOINT = ("REFPOINT_U", "REFPOINT_U_FRACTION", "REFPOINT_U_OFFSET", "REFPOINT_V",
               "REFPOINT_V_FRACTION", "REFPOINT_V_OFFSET", "REFPOINT_X", "REFPOINT_Y",
               "REFPOINT_Z", "REFPOINT_PHI")
MODIFIERS = SCALING + NAN + ROTCENTER + BY_OFFSET + BY_REFPOINT
#: OpenCRG's modifiers for a file without a ``$ROAD_CRG_MODS`` section
DEFAULTS = {"GRID_NAN_MODE": (2.0, None), "REFPOINT_PHI": (0.0, None)}


def read_mods(sections: dict, path) -> dict:
    """The modifiers of a parsed header (``{KEY: (value, line)}``), checked.

    Raises :class:`~flexpipe.errors.InputError` naming the file, line and key for an
    unknown key, a value that is not a finite number, a scale factor <= 0, a NaN mode
    other than 0, 1, 2, or a reference point given twice (absolute and as a fraction).
    """
    if "ROAD_CRG_MODS" not in sections:
        return dict(DEFAULTS)
    mods = key_values(sections["ROAD_CRG_MODS"], path, "ROAD_CRG_MODS", MODIFIERS)
    for key in ("SCALE_LENGTH", "SCALE_WIDTH"):
        if key in mods and mods[key][0] <= 0.0:
            raise InputError(f"{key} = {mods[key][0]:g}; a length factor must be > 0",
                             file=path, line=mods[key][1], key=key)
    if "GRID_NAN_MODE" in mods and mods["GRID_NAN_MODE"][0] not in (0.0, 1.0, 2.0):
        raise InputError(f"GRID_NAN_MODE = {mods['GRID_NAN_MODE'][0]:g}; valid: 0 (keep NaN), "
                         "1 (set to GRID_NAN_OFFSET), 2 (keep the last valid value)",
                         file=path, line=mods["GRID_NAN_MODE"][1], key="GRID_NAN_MODE")
    if mods.get("GRID_NAN_MODE", (2.0,))[0] == 0.0 and "GRID_NAN_OFFSET" in mods:
        raise InputError("GRID_NAN_OFFSET needs GRID_NAN_MODE 1 or 2, not 0", file=path,
                         line=mods["GRID_NAN_OFFSET"][1], key="GRID_NAN_OFFSET")
    for axis in ("U", "V"):
        a, b = f"REFPOINT_{axis}", f"REFPOINT_{axis}_FRACTION"
        if a in mods and b in mods:
            raise InputError(f"{a} and {b} are both given; give one", file=path,
                             line=mods[b][1], key=b)
    if any(k in mods for k in BY_REFPOINT) and any(k in mods for k in BY_OFFSET):
        warnings.warn(f"{path}: $ROAD_CRG_MODS places the road by a reference point and "
                      "by offset; the reference point is used (as in OpenCRG)", UserWarning,
                      stacklevel=3)
    return mods


def key_values(section: dict, path, name: str, keys) -> dict:
    """``{KEY: (number, line)}`` of the ``KEY = value`` lines of header section ``name``
    (keys upper-cased, Fortran ``D`` exponents read); an unknown or repeated key, or a
    value that is not a finite number, is an :class:`~flexpipe.errors.InputError` naming
    the file, line and key (with the closest valid keys)."""
    out: dict = {}
    for k, body in section["_items"]:
        if "=" not in body:
            raise InputError(f"expected 'KEY = value' in ${name}, got {body!r}", file=path,
                             line=k)
        key, value = (t.strip() for t in body.split("=", 1))
        key = key.upper()
        if key not in keys:
            close = difflib.get_close_matches(key, keys, n=2, cutoff=0.7)
            hint = f" (did you mean {' or '.join(close)}?)" if close else ""
            raise InputError(f"unknown ${name} key {key}{hint}; valid: {', '.join(keys)}",
                             file=path, line=k, key=key)
        if key in out:
            raise InputError(f"{key} is given twice (first on line {out[key][1]})",
                             file=path, line=k, key=key)
        try:
            number = float(value.replace("D", "E").replace("d", "e"))
        except ValueError:
            raise InputError(f"value of {key} is not a number: {value!r}", file=path,
                             line=k, key=key) from None
        if not math.isfinite(number):
            raise InputError(f"value of {key} must be a finite number, got {value!r}",
                             file=path, line=k, key=key)
        out[key] = (number, k)
    return out


def nan_rule(mods: dict) -> tuple[int, float]:
    """``(GRID_NAN_MODE, GRID_NAN_OFFSET)`` of the modifiers (2, 0 when not given)."""
    return int(mods.get("GRID_NAN_MODE", (2.0,))[0]), float(mods.get("GRID_NAN_OFFSET", (0.0,))[0])


def scale(mods: dict, *, du, v, z_grid, plan: ReferenceLine, z_ref, bank):
    """Step 1: the scaled ``du, v, z_grid, plan, z_ref, bank`` (see the module); NaNs in
    ``z_grid`` stay NaN."""
    f = {k: mods.get(k, (1.0,))[0] for k in SCALING}
    z_grid = z_grid * f["SCALE_Z_GRID"]  # before the NaN filling (its offset is not scaled)
    z_ref = z_ref[0] + f["SCALE_SLOPE"] * (z_ref - z_ref[0])
    bank = bank * f["SCALE_BANKING"]
    L = f["SCALE_LENGTH"]
    if L != 1.0:
        du = du * L
        x0, y0 = plan.x[0], plan.y[0]
        plan = ReferenceLine(u0=plan.u0, du=du, x=x0 + L * (plan.x - x0), y=y0 + L * (plan.y - y0))
        z_ref = z_ref[0] + L * (z_ref - z_ref[0])
    v = v * f["SCALE_WIDTH"]
    c = f["SCALE_CURVATURE"]
    if c != 1.0 and not plan.straight:
        p = np.unwrap(plan.phi)
        p = p[0] + np.concatenate([[0.0], np.cumsum(c * np.diff(p))])
        plan = ReferenceLine.from_heading(plan.u0, du, p, x0=plan.x[0], y0=plan.y[0])
    return du, v, z_grid, plan, z_ref, bank


def refpoint_uv(mods: dict, *, u_start, u_end, v_min, v_max) -> tuple[float, float]:
    """``(u, v)`` of the reference point on the scaled road."""
    if "REFPOINT_U_FRACTION" in mods:
        u = u_start + mods["REFPOINT_U_FRACTION"][0] * (u_end - u_start)
    else:
        u = mods.get("REFPOINT_U", (u_start,))[0]
    u += mods.get("REFPOINT_U_OFFSET", (0.0,))[0]
    if "REFPOINT_V_FRACTION" in mods:
        v = v_min + mods["REFPOINT_V_FRACTION"][0] * (v_max - v_min)
    else:
        v = mods.get("REFPOINT_V", (0.0,))[0]
    return u, v + mods.get("REFPOINT_V_OFFSET", (0.0,))[0]


def placement(mods: dict, plan: ReferenceLine, height_uv, *, v_min: float, v_max: float):
    """Steps 3 and 4: ``(dx, dy, dz, dphi, (cx, cy))``, the turn ``dphi`` about
    ``(cx, cy)`` followed by the shift ``(dx, dy, dz)`` that places the scaled road, or
    ``None`` when the modifiers keep it where it is.  ``height_uv(u, v)`` is the scaled
    road's surface height, ``v_min, v_max`` its lateral extent."""
    if any(k in mods for k in BY_REFPOINT):
        u, v = refpoint_uv(mods, u_start=plan.u0, u_end=plan.u_end, v_min=v_min, v_max=v_max)
        px, py = (float(a) for a in plan.uv_to_xy(u, v))
        pz = float(height_uv(u, v))
        dphi = mods.get("REFPOINT_PHI", (0.0,))[0] - float(plan.heading_at(u))
        cx, cy = float(plan.x[0]), float(plan.y[0])
        qx, qy = _turn(px, py, cx, cy, dphi)
        return (mods.get("REFPOINT_X", (0.0,))[0] - qx, mods.get("REFPOINT_Y", (0.0,))[0] - qy,
                mods.get("REFPOINT_Z", (0.0,))[0] - pz, dphi, (cx, cy))
    if any(k in mods for k in BY_OFFSET):
        cx = mods.get("REFLINE_ROTCENTER_X", (float(plan.x[0]),))[0]
        cy = mods.get("REFLINE_ROTCENTER_Y", (float(plan.y[0]),))[0]
        return (mods.get("REFLINE_OFFSET_X", (0.0,))[0], mods.get("REFLINE_OFFSET_Y", (0.0,))[0],
                mods.get("REFLINE_OFFSET_Z", (0.0,))[0], mods.get("REFLINE_OFFSET_PHI", (0.0,))[0],
                (cx, cy))
    return None


def moved(plan: ReferenceLine, dx, dy, dphi, center) -> ReferenceLine:
    """``plan`` turned by ``dphi`` about ``center``, then shifted by ``(dx, dy)``."""
    x, y = _turn(plan.x, plan.y, center[0], center[1], dphi)
    return ReferenceLine(u0=plan.u0, du=plan.du, x=x + dx, y=y + dy)


def _turn(x, y, cx, cy, phi):
    c, s = math.cos(phi), math.sin(phi)
    return cx + (x - cx) * c - (y - cy) * s, cy + (x - cx) * s + (y - cy) * c
