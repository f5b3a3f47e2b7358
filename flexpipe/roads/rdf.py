"""Reader for Adams/Tire 2D road data files (``.rdf``, TeimOrbit format).

An Adams/Car or Adams/Tire user's 2D road is a TeimOrbit file with ``[MODEL] METHOD =
'2D'`` and a ``ROAD_TYPE``; this reader turns it into a :class:`~flexpipe.roads.Road`
whose distance axis is the road's x axis (laid along the run's path) and whose left
track is the road's +y side::

    [UNITS]
     LENGTH = 'mm'
     ANGLE  = 'degrees'
    [MODEL]
     METHOD    = '2D'
     ROAD_TYPE = 'plank'
    [PARAMETERS]
     OFFSET                  = 0.0
     ROTATION_ANGLE_XY_PLANE = 0.0
     HEIGHT            = 15.0
     START             = 20000.0
     LENGTH            = 50.0
     BEVEL_EDGE_LENGTH = 5.0
     DIRECTION         = 0.0

Road types and their ``[PARAMETERS]`` (lengths in ``[UNITS] LENGTH``, angles in ``ANGLE``;
[default]); the shapes are those of :mod:`flexpipe.roads.rdf_shapes`:

============  ============================================================================
flat          none
poly_line     an ``(XZ_DATA)`` sub-block: rows ``x z_left z_right``, x increasing
plank         HEIGHT (< 0: a groove), START, LENGTH (bevels included),
              BEVEL_EDGE_LENGTH [0] (45-degree top edges; the radius of rounded edges
              with EDGE_ROUNDED = 1 [0]), DIRECTION [0], MU_FACTOR_CLEAT [1]
pot_hole      DEPTH (the depth below the road; < 0 makes a bump and warns), START,
              LENGTH, DIRECTION [0]
ramp          HEIGHT (< 0: falling), START, SLOPE (dz/dx, 1 = 45 degrees)
roof          HEIGHT, START, LENGTH (a triangle, highest at its middle)
sine          AMPLITUDE, WAVE_LENGTH, START, LENGTH [endless: sampled 1 km]
sine_sweep    START, END, AMPLITUDE_AT_START, AMPLITUDE_AT_END, WAVE_LENGTH_AT_START,
              WAVE_LENGTH_AT_END (<= at start), SWEEP_TYPE [0 linear, 1 logarithmic]
============  ============================================================================

Common keys: OFFSET [0] (added to every height), ROTATION_ANGLE_XY_PLANE [0] (0 or 180,
see below) and MU [1].  DIRECTION turns a plank or pot hole about the vertical axis,
counter-clockwise from the road's y axis seen from above, so that at lateral position
``y`` it starts ``y tan(DIRECTION)`` earlier: the road becomes a height grid (1 cm
laterally, 2 mm along x) and a wheel track meets it at its own distance.

Not read: ``stochastic_uneven`` (COSIN's random generator cannot be reproduced: flexpipe's
ISO 8608 road, ``type = "iso8608"`` in a ``.toml`` road, is the equivalent), the test rigs
(``drum``, ``flatbelt``, ``hydraulic_test_rig``), 3D, 3D spline and other ``METHOD`` s
(an OpenCRG ``.crg`` carries a 3D road), road friction (``MU`` and ``MU_FACTOR_CLEAT``
other than 1: scale the tyre's LMUX / LMUY instead) and a road rotated other than 0 or
180 degrees: flexpipe lays the road along the path, so both read the same (Adams/Car
vehicles face -x, which is why its road files often say 180).  Each is an error naming the
file, the line and the key.  Before its first feature and 1 km after its last the road is
flat (a ramp holds its height), which the run's length check reports.
"""

from __future__ import annotations

import difflib
import math
import warnings
from pathlib import Path

import numpy as np

from flexpipe import _teimorbit as teim
from flexpipe.errors import InputError
from flexpipe.roads import rdf_shapes as shp
from flexpipe.roads.road import Road
from flexpipe.tires._keys import UNIT_FACTORS

COMMON = {"OFFSET": 0.0, "ROTATION_ANGLE_XY_PLANE": 0.0, "MU": 1.0}
#: per road type: required keys, optional keys with defaults; L = length, A = angle
TYPES = {
    "flat": ({}, {}),
    "poly_line": ({}, {}),
    "plank": ({"HEIGHT": "L", "START": "L", "LENGTH": "L"},
              {"BEVEL_EDGE_LENGTH": ("L", 0.0), "EDGE_ROUNDED": ("-", 0.0),
               "DIRECTION": ("A", 0.0), "MU_FACTOR_CLEAT": ("-", 1.0)}),
    "pot_hole": ({"DEPTH": "L", "START": "L", "LENGTH": "L"}, {"DIRECTION": ("A", 0.0)}),
    "ramp": ({"HEIGHT": "L", "START": "L", "SLOPE": "-"}, {"DIRECTION": ("A", 0.0)}),
    "roof": ({"HEIGHT": "L", "START": "L", "LENGTH": "L"}, {"DIRECTION": ("A", 0.0)}),
    "sine": ({"AMPLITUDE": "L", "WAVE_LENGTH": "L", "START": "L"},
             {"LENGTH": ("L", None), "DIRECTION": ("A", 0.0)}),
    "sine_sweep": ({"START": "L", "END": "L", "AMPLITUDE_AT_START": "L",
                    "AMPLITUDE_AT_END": "L", "WAVE_LENGTH_AT_START": "L",
                    "WAVE_LENGTH_AT_END": "L"},
                   {"SWEEP_TYPE": ("-", 0.0), "DIRECTION": ("A", 0.0)}),
}
ALIASES = {"cleat": "plank", "pothole": "pot_hole", "sweep": "sine_sweep",
           "polyline": "poly_line", "sine_wave": "sine"}
REFUSED = {
    "stochastic_uneven": "COSIN's random road generator cannot be reproduced; for a "
                         "random road of a given roughness use flexpipe's ISO 8608 road "
                         "(a .toml road with type = \"iso8608\" and its class)",
    "drum": "a tyre test drum is a rig, not a road a car drives on",
    "flatbelt": "a flat-belt test rig is a rig, not a road a car drives on",
    "hydraulic_test_rig": "a hydraulic (four-poster) test rig is not a road; give the "
                          "actuator displacements as a .csv road profile",
}
#: lateral half-width (m) and spacings (m) of the height grid of an oblique obstacle
GRID_HALF_WIDTH_M, GRID_DY_M, GRID_DX_M = 2.0, 0.01, 0.002
MAX_DIRECTION_DEG = 60.0


def read_rdf(path, *, track_width: float = 1.5) -> Road:
    """Read an Adams 2D road data file (see the module notes).

    Parameters
    ----------
    path : str or Path
        The ``.rdf`` file.
    track_width : float
        Lateral distance of the ``left`` and ``right`` track samples (m); the wheels read
        the road at their own lateral positions.

    Returns
    -------
    Road

    Raises
    ------
    InputError
        Unreadable or malformed file, a METHOD or ROAD_TYPE flexpipe does not read, a
        missing, unknown or out-of-range key: naming the file, line and key.
    """
    path = Path(path)
    sections, lines, xz = _parse(path)

    def err(msg, section, key=None):
        return InputError(msg, file=path, line=lines.get((section, key or "")) or
                          lines.get((section, "")), key=key or section)

    model = sections.get("MODEL")
    if model is None:
        raise InputError("no [MODEL] section: a 2D road file needs METHOD = '2D' and a "
                         "ROAD_TYPE", file=path, key="MODEL")
    if "METHOD" not in model:
        raise err("[MODEL] has no METHOD; flexpipe reads Adams 2D roads: give METHOD = '2D'",
                  "MODEL")
    method = str(model["METHOD"]).strip().upper()
    if method != "2D":
        raise err(f"METHOD = '{model.get('METHOD', '')}' is not read; flexpipe reads Adams "
                  "2D roads (METHOD = '2D'); a 3D road goes in as an OpenCRG .crg file",
                  "MODEL", "METHOD")
    if "ROAD_TYPE" not in model:
        raise err(f"[MODEL] has no ROAD_TYPE; valid: {', '.join(TYPES)}", "MODEL")
    raw_type = str(model["ROAD_TYPE"]).strip().lower()
    kind = ALIASES.get(raw_type, raw_type)
    if kind in REFUSED:
        raise err(f"ROAD_TYPE = '{raw_type}' is not read: {REFUSED[kind]}", "MODEL",
                  "ROAD_TYPE")
    if kind not in TYPES:
        close = difflib.get_close_matches(kind, list(TYPES) + list(REFUSED), n=1)
        hint = f" (did you mean '{close[0]}'?)" if close else ""
        raise err(f"ROAD_TYPE = '{raw_type}' is unknown{hint}; valid: {', '.join(TYPES)}",
                  "MODEL", "ROAD_TYPE")
    f_len, f_ang = _units(path, sections.get("UNITS", {}), lines)
    params = sections.get("PARAMETERS", {})
    p = _parameters(kind, params, f_len, f_ang, err)
    if kind == "poly_line":
        if xz is None:
            raise err("a poly_line road needs an (XZ_DATA) sub-block in [PARAMETERS] with "
                      "rows 'x z_left z_right'", "PARAMETERS")
        return _poly_line(path, xz, f_len, p["OFFSET"], track_width, raw_type)
    if xz is not None:
        raise InputError(f"an (XZ_DATA) sub-block belongs to a poly_line road, not a "
                         f"'{raw_type}' one", file=path, line=xz[2], key="XZ_DATA")
    x, z = _shape(kind, p, err)
    if kind == "pot_hole" and p["DEPTH"] < 0.0:
        warnings.warn(f"{path}, line {lines.get(('PARAMETERS', 'DEPTH'))}: pot_hole DEPTH "
                      f"= {params['DEPTH']:g} < 0 makes a bump {-p['DEPTH'] * 1e3:.4g} mm "
                      "high (flexpipe reads DEPTH as the depth below the road, as the "
                      "TeimOrbit definition does; some road tools read the opposite sign)",
                      UserWarning, stacklevel=2)
    lo, hi = shp.road_extent(x)
    source = f"{path} (Adams 2D road, {raw_type})"
    direction = p.get("DIRECTION") or 0.0
    if direction == 0.0:
        x, z = shp.on_extent(x, z + p["OFFSET"], lo, hi)
        return Road(x=x, left=z, right=z.copy(), track_width=track_width, name=path.stem,
                    source=source)
    return _oblique(x, z, p["OFFSET"], direction, lo, hi, track_width, path, source)


def _parse(path: Path):
    """Sections (KEY -> value), their lines, and the (XZ_DATA) rows with their line."""
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read the road file ({exc.strerror})", file=path) from None
    text = raw.decode("utf-8", errors="replace") if b"\0" not in raw else None
    if text is None:
        raise InputError("not a text file: a .rdf road data file is TeimOrbit text",
                         file=path)
    sections: dict[str, dict] = {}
    lines: dict[tuple[str, str], int] = {}
    current, block, xz = None, None, None
    for lineno, line in enumerate(text.splitlines(), start=1):
        body = teim.strip_comment(line).strip()
        if not body:
            continue
        m = teim.SECTION_RE.match(body)
        if m:
            current = m.group(1).strip().upper().replace(" ", "_")
            sections.setdefault(current, {})
            lines.setdefault((current, ""), lineno)
            block = None
            continue
        if current is None:
            raise InputError(f"entry '{body}' appears before the first [SECTION] header",
                             file=path, line=lineno)
        if current == "MDI_HEADER" or block == "SKIP":
            continue
        m = teim.SUBBLOCK_RE.match(body)
        if m:
            name = m.group(1).upper()
            if name == "XZ_DATA":
                if xz is not None:
                    raise InputError("a second (XZ_DATA) sub-block", file=path, line=lineno,
                                     key="XZ_DATA")
                xz, block = ([], None, lineno), "XZ_DATA"
            else:
                block = "SKIP" if name == "COMMENTS" else _unknown_block(path, name, lineno)
            continue
        if block == "XZ_DATA":
            if teim.TABLE_RE.match(body):
                continue
            parts = body.replace(",", " ").split()
            if len(parts) != 3 or not all(teim.NUMBER_RE.match(t) for t in parts):
                raise InputError(f"(XZ_DATA) row '{body}' must hold 3 numbers: x z_left "
                                 "z_right", file=path, line=lineno, key="XZ_DATA")
            xz[0].append(([teim.number(t) for t in parts], lineno))
            continue
        m = teim.KEY_RE.match(body)
        if not m:
            raise InputError(f"cannot parse '{body}' in [{current}]: expected KEY = value, "
                             "a [SECTION] header or an (XZ_DATA) sub-block", file=path,
                             line=lineno)
        key, value = m.group(1).upper(), teim.parse_value(m.group(2))
        if key in sections[current]:
            raise InputError(f"[{current}] {key} is given twice (first on line "
                             f"{lines[(current, key)]})", file=path, line=lineno, key=key)
        sections[current][key] = value
        lines[(current, key)] = lineno
    if not sections:
        raise InputError("no [SECTION] found: not a TeimOrbit road data file", file=path)
    return sections, lines, xz


def _unknown_block(path, name, lineno):
    raise InputError(f"unknown sub-block ({name}); a 2D road file has (XZ_DATA) (poly_line "
                     "roads) and (COMMENTS)", file=path, line=lineno, key=name)


def _units(path, units: dict, lines) -> tuple[float, float]:
    """Factors to metres and radians from ``[UNITS]``.  Adams 2D roads are written in
    millimetres or metres, so a file without ``LENGTH`` is refused rather than guessed;
    ``ANGLE`` defaults to radians (only DIRECTION and ROTATION_ANGLE_XY_PLANE use it)."""
    factors = []
    for q, default in (("LENGTH", None), ("ANGLE", "radians")):
        name = units.get(q, default)
        if name is None:
            raise InputError("[UNITS] LENGTH is not given; state it (e.g. LENGTH = 'mm' "
                             "or 'meter'): 2D road files are written in either", file=path,
                             line=lines.get(("UNITS", "")), key="LENGTH")
        table = UNIT_FACTORS[q]
        key = str(name).strip().lower()
        if key not in table:
            raise InputError(f"[UNITS] {q} = '{name}' is not a known unit; valid: "
                             f"{', '.join(sorted(table))}", file=path,
                             line=lines.get(("UNITS", q)), key=q)
        factors.append(table[key])
    return factors[0], factors[1]


def _parameters(kind, params, f_len, f_ang, err) -> dict:
    """The road type's [PARAMETERS] in metres and radians (with defaults), checked."""
    required, optional = TYPES[kind]
    dims = dict(required) | {k: d for k, (d, _) in optional.items()} | \
        {"OFFSET": "L", "ROTATION_ANGLE_XY_PLANE": "A", "MU": "-"}
    for key in params:
        if key not in dims:
            close = difflib.get_close_matches(key, list(dims), n=1)
            hint = f" (did you mean {close[0]}?)" if close else ""
            raise err(f"[PARAMETERS] {key} is not a key of a {kind} road{hint}; valid: "
                      f"{', '.join(dims)}", "PARAMETERS", key)
    missing = [k for k in required if k not in params]
    if missing:
        raise err(f"[PARAMETERS] of a {kind} road needs {', '.join(missing)}", "PARAMETERS")
    out = {}
    for key, dim in dims.items():
        value = params.get(key, COMMON.get(key, optional.get(key, (None, None))[1]))
        if value is None:
            out[key] = None
            continue
        if not isinstance(value, float) or not math.isfinite(value):
            raise err(f"[PARAMETERS] {key} must be a finite number, got {value!r}",
                      "PARAMETERS", key)
        out[key] = value * {"L": f_len, "A": f_ang, "-": 1.0}[dim]
    rot = math.degrees(out["ROTATION_ANGLE_XY_PLANE"]) % 360.0
    if min(rot, abs(rot - 180.0), 360.0 - rot) > 1e-6:
        raise err(f"ROTATION_ANGLE_XY_PLANE = {params['ROTATION_ANGLE_XY_PLANE']:g}: flexpipe "
                  "lays a 2D road along the run's path, which takes 0 or 180 degrees (the "
                  "same road); give a path at that angle instead", "PARAMETERS",
                  "ROTATION_ANGLE_XY_PLANE")
    for key in ("MU", "MU_FACTOR_CLEAT"):
        if out.get(key) is not None and out[key] != 1.0:
            raise err(f"{key} = {out[key]:g}: flexpipe's roads carry no friction; give 1.0 "
                      "and scale the tyre's friction (LMUX, LMUY in its .tir) instead",
                      "PARAMETERS", key)
    _check_ranges(kind, out, params, err)
    return out


def _positive(out, params, err, *keys):
    for key in keys:
        if out.get(key) is not None and not out[key] > 0.0:
            raise err(f"[PARAMETERS] {key} = {params[key]:g} must be > 0", "PARAMETERS", key)


def _check_ranges(kind, out, params, err) -> None:
    _positive(out, params, err, "LENGTH", "SLOPE", "WAVE_LENGTH", "WAVE_LENGTH_AT_START",
              "WAVE_LENGTH_AT_END")
    d = out.get("DIRECTION") or 0.0
    if abs(math.degrees(d)) > MAX_DIRECTION_DEG + 1e-9:
        raise err(f"DIRECTION = {params['DIRECTION']:g} is beyond +-{MAX_DIRECTION_DEG:g} "
                  "degrees from crosswise", "PARAMETERS", "DIRECTION")
    if d and kind not in ("plank", "pot_hole"):
        raise err(f"DIRECTION = {params['DIRECTION']:g}: only a plank or a pot hole may be "
                  "turned; give 0", "PARAMETERS", "DIRECTION")
    if kind == "plank":
        b, h = out["BEVEL_EDGE_LENGTH"], abs(out["HEIGHT"])
        what = "edge radius" if out["EDGE_ROUNDED"] == 1.0 else "bevel"
        if out["EDGE_ROUNDED"] not in (0.0, 1.0):
            raise err(f"EDGE_ROUNDED = {params['EDGE_ROUNDED']:g} must be 0 or 1",
                      "PARAMETERS", "EDGE_ROUNDED")
        if b < 0.0 or b > h + 1e-12 or 2.0 * b > out["LENGTH"] + 1e-12:
            top = min(abs(params["HEIGHT"]), 0.5 * params["LENGTH"])
            raise err(f"BEVEL_EDGE_LENGTH = {params['BEVEL_EDGE_LENGTH']:g} (the {what}) must "
                      f"lie in 0 .. min(|HEIGHT|, LENGTH / 2) = {top:g}", "PARAMETERS",
                      "BEVEL_EDGE_LENGTH")
    if kind == "sine_sweep":
        if not out["END"] > out["START"]:
            raise err(f"END = {params['END']:g} must be beyond START = {params['START']:g}",
                      "PARAMETERS", "END")
        if out["WAVE_LENGTH_AT_END"] > out["WAVE_LENGTH_AT_START"]:
            raise err("WAVE_LENGTH_AT_END must not exceed WAVE_LENGTH_AT_START (the sweep "
                      "goes to shorter waves)", "PARAMETERS", "WAVE_LENGTH_AT_END")
        if out["SWEEP_TYPE"] not in (0.0, 1.0):
            raise err(f"SWEEP_TYPE = {params['SWEEP_TYPE']:g} must be 0 (linear) or 1 "
                      "(logarithmic)", "PARAMETERS", "SWEEP_TYPE")


def _shape(kind, p, err):
    try:
        if kind == "flat":
            return np.array([0.0, 1.0]), np.zeros(2)
        if kind == "plank":
            return shp.plank(p["HEIGHT"], p["START"], p["LENGTH"], p["BEVEL_EDGE_LENGTH"],
                             rounded=p["EDGE_ROUNDED"] == 1.0)
        if kind == "pot_hole":
            return shp.pot_hole(p["DEPTH"], p["START"], p["LENGTH"])
        if kind == "ramp":
            return shp.ramp(p["HEIGHT"], p["START"], p["SLOPE"])
        if kind == "roof":
            return shp.roof(p["HEIGHT"], p["START"], p["LENGTH"])
        if kind == "sine":
            return shp.sine(p["AMPLITUDE"], p["WAVE_LENGTH"], p["START"], p["LENGTH"])
        return shp.sine_sweep(p["START"], p["END"], p["AMPLITUDE_AT_START"],
                              p["AMPLITUDE_AT_END"], p["WAVE_LENGTH_AT_START"],
                              p["WAVE_LENGTH_AT_END"], log=p["SWEEP_TYPE"] == 1.0)
    except ValueError as exc:   # too many samples
        key, fix = (("LENGTH", "a shorter LENGTH or a longer WAVE_LENGTH") if kind == "sine"
                    else ("WAVE_LENGTH_AT_END", "a shorter sweep (END) or a longer "
                          "WAVE_LENGTH_AT_END"))
        raise err(f"the {kind} needs {exc} to be sampled within 3e-4 of its amplitude: "
                  f"give {fix}", "PARAMETERS", key) from None


def _poly_line(path, xz, f_len, offset, track_width, raw_type) -> Road:
    rows, _, line = xz
    if len(rows) < 2:
        raise InputError("(XZ_DATA) needs at least 2 rows", file=path, line=line,
                         key="XZ_DATA")
    data = np.array([r for r, _ in rows]) * f_len
    bad = np.flatnonzero(np.diff(data[:, 0]) <= 0.0)
    if bad.size:
        i = int(bad[0]) + 1
        raise InputError(f"(XZ_DATA) x must increase: {rows[i][0][0]:g} after "
                         f"{rows[i - 1][0][0]:g}", file=path, line=rows[i][1], key="XZ_DATA")
    lo, hi = shp.road_extent(data[:, 0])
    x, zl = shp.on_extent(data[:, 0], data[:, 1] + offset, lo, hi)
    _, zr = shp.on_extent(data[:, 0], data[:, 2] + offset, lo, hi)
    # each side of the road's centre line reads its own track (no blend between them)
    y = np.array([-GRID_HALF_WIDTH_M, -1e-3, 1e-3, GRID_HALF_WIDTH_M])
    z = np.column_stack([zr, zr, zl, zl])
    return Road(x=x, left=zl, right=zr, track_width=track_width, y=y, z=z,
                name=path.stem, source=f"{path} (Adams 2D road, {raw_type})")


def _oblique(x, z, offset, direction, lo, hi, track_width, path, source) -> Road:
    """A plank or pot hole turned by ``direction``: heights on a grid, each lateral line
    the crosswise profile shifted by ``y tan(direction)``."""
    t = math.tan(direction)
    y = np.arange(-GRID_HALF_WIDTH_M, GRID_HALF_WIDTH_M + 0.5 * GRID_DY_M, GRID_DY_M)
    a = x[0] - GRID_HALF_WIDTH_M * abs(t) - GRID_DX_M
    b = x[-1] + GRID_HALF_WIDTH_M * abs(t) + GRID_DX_M
    xs = np.concatenate([[min(lo, a - 1.0)], np.arange(a, b + GRID_DX_M, GRID_DX_M),
                         [max(hi, b + 1.0)]])
    grid = np.interp(xs[:, None] + t * y[None, :], x, z, left=0.0, right=0.0) + offset
    half = 0.5 * track_width
    left = np.interp(xs + t * half, x, z, left=0.0, right=0.0) + offset
    right = np.interp(xs - t * half, x, z, left=0.0, right=0.0) + offset
    return Road(x=xs, left=left, right=right, track_width=track_width, y=y, z=grid,
                name=path.stem, source=source)
