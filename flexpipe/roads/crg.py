"""OpenCRG road files: reader and writer.

An OpenCRG file is a text header of ``$SECTION ... $`` blocks (72 significant characters
per line; ``!`` starts a comment, a line starting with ``*`` is a comment) closed by a
line of ``$$$$``, followed by the data block.  The parts used here:

* ``$ROAD_CRG``: ``REFERENCE_LINE_START_U / END_U / INCREMENT`` (the distance grid ``u``),
  ``LONG_SECTION_V_RIGHT / LEFT / INCREMENT`` (the lateral grid ``v``, positive left),
  ``REFERENCE_LINE_START_X / START_Y / START_PHI`` (plan position and heading of the
  reference line; ``END_X / END_Y`` close a heading channel's integration),
  ``REFERENCE_LINE_START_Z / START_S / START_B`` (elevation, slope and banking; without a
  data channel the start value holds along the whole road, as in OpenCRG, and a different
  ``END_S`` / ``END_B`` / ``END_PHI`` gives a warning).  Any other key is an error.
* ``$KD_DEFINITION``: ``#:FMT``, ``U:reference line u,m,<start>,<increment>`` (used
  when ``$ROAD_CRG`` gives no START_U, and no INCREMENT or END_U) and the channels
  ``D:long section <i>,m`` (by index, the lateral position is
  ``v_right + (i-1) v_increment``) or ``D:long section at v = <v>,m`` and
  ``D:reference line phi,rad`` / ``slope,m/m`` / ``banking,m/m``.
* Values a file leaves out are derived as OpenCRG derives them (:func:`_u_axis`,
  :func:`_v_axis`): START_U 0; INCREMENT ``(END_U - START_U) / (records - 1)``; END_U
  from the number of records; LONG_SECTION_V_INCREMENT ``(LEFT - RIGHT) / (sections - 1)``;
  RIGHT ``LEFT - (sections - 1) INCREMENT``, or the sections centred on the reference line
  when neither border is given; an increment with nothing to derive it from is OpenCRG's
  fallback 0.01 m, with a warning.
* The data block, one row per ``u`` sample with one value per ``D:`` channel.  ``FMT`` is
  four letters: ``K``ompact (rows run on without alignment) or ``L``ong (every row starts a
  new 80-byte/80-character record); ``R``eal (single) or ``D``ouble precision;
  ``F``ormatted text (10 or 20 characters per number, ``*`` starts a NaN placeholder) or
  ``B``inary (IEEE big-endian); the last letter is ``I``.  The three measured files in
  ``../shared/reference/roads`` are ``KRBI`` (compact single-precision binary).

The height at ``(u, v)`` is ``z_grid(u, v) + z_ref(u) + b(u) v``, with ``z_ref`` the
integral of the slope (``v`` held at the outermost long section beyond it).  The road is
placed in the global plane by its reference line (:class:`~flexpipe.roads.refline.ReferenceLine`,
the OpenCRG ``(x, y) <-> (u, v)`` map); :meth:`Road.height_xy` evaluates it at global
positions, :meth:`Road.height` at ``(u, v)``. Heights equal pyopencrg's (tested at 10,000
random points of a curved, sloped, banked road and of the reference files). NaNs at the
lateral borders of a cross section are replaced by the nearest valid value of that cross
section (OpenCRG ``GRID_NAN_MODE`` 2, "keep last"); NaNs between valid values, or cross
sections without any valid value, are errors (other ``GRID_NAN_MODE`` s: below).
``$ROAD_CRG_MODS`` (scaling, NaN filling, placement; without that section OpenCRG's
default modifiers, which put the start of the reference line at the origin) is applied
as a simulator applies it (:mod:`flexpipe.roads.crg_mods`), ``$ROAD_CRG_OPTS`` (border
modes, smoothing zones) as :mod:`flexpipe.roads.crg_opts` says.
"""

from __future__ import annotations

import difflib
import math
import re
import warnings

import numpy as np

from flexpipe._args import as_path, checked_number
from flexpipe.errors import InputError
from flexpipe.roads._plausible import check_heights
from flexpipe.roads.crg_data import (
    fill_border_nans,
    parse_binary_values,
    parse_text_values,
    reject_text_as_binary,
)
from flexpipe.roads.crg_mods import key_values, moved, nan_rule, placement, read_mods, scale
from flexpipe.roads.crg_opts import apply as apply_opts
from flexpipe.roads.crg_opts import read_opts
from flexpipe.roads.crg_write import write_crg  # noqa: F401 (re-exported)
from flexpipe.roads.refline import ReferenceLine
from flexpipe.roads.road import Road

_LONG_SECTION = re.compile(r"long\s+section\s+(at\s+v\s*=\s*)?([-+0-9.eEdD]+)", re.IGNORECASE)


def _header_lines(raw: bytes, path):
    """Split the header into (line number, text) pairs; return them and the data offset."""
    lines, pos, k = [], 0, 0
    while pos < len(raw):
        end = raw.find(b"\n", pos)
        end = len(raw) if end < 0 else end
        k += 1
        text = raw[pos:end].rstrip(b"\r").decode("latin-1")
        pos = end + 1
        if text.startswith("$$"):
            return lines, pos, k
        lines.append((k, text))
    raise InputError("no data block: the header is never closed by a '$$$$' line", file=path)


def _strip_comment(text: str) -> str:
    return text[:72].split("!", 1)[0].strip()


def _parse_header(lines, path):
    sections: dict[str, dict] = {}
    current = None
    for k, text in lines:
        body = _strip_comment(text)
        if text.startswith("$"):
            name = body[1:].strip().upper()
            current = name or None
            if current is not None:
                sections.setdefault(current, {"_line": k, "_items": []})
            continue
        if current is None or not body or body.startswith("*"):
            continue
        sections[current]["_items"].append((k, body))
    return sections


#: Keys of the ``$ROAD_CRG`` section (OpenCRG 1.2); any other key is an error.
ROAD_CRG_KEYS = tuple(f"REFERENCE_LINE_{k}" for k in (
    "START_U", "END_U", "INCREMENT", "START_S", "END_S", "START_B", "END_B", "START_X",
    "START_Y", "END_X", "END_Y", "OFFSET_X", "OFFSET_Y", "START_PHI", "END_PHI", "OFFSET_PHI",
    "START_Z", "END_Z", "OFFSET_Z", "START_LON", "START_LAT", "END_LON", "END_LAT",
    "START_ALT", "END_ALT")) + ("LONG_SECTION_V_RIGHT", "LONG_SECTION_V_LEFT",
                                "LONG_SECTION_V_INCREMENT")


def _road_params(section, path):
    return key_values(section, path, "ROAD_CRG", ROAD_CRG_KEYS)


def _u_channel(section, path):
    """``(start, increment)`` from a ``U:reference line u,m,<start>,<increment>`` line, or None.

    OpenCRG takes the ``$ROAD_CRG`` values first; this fills in a missing increment.
    """
    for k, body in section["_items"]:
        if body[:2].upper() != "U:":
            continue
        items = [t.strip() for t in body[2:].split(",")]
        if items[0].lower() != "reference line u" or len(items) < 4 or not items[3]:
            continue
        try:
            start, inc = float(items[2] or 0.0), float(items[3])
        except ValueError:
            raise InputError(f"channel {body!r}: start and increment must be numbers",
                             file=path, line=k) from None
        if not (math.isfinite(start) and math.isfinite(inc)):
            raise InputError(f"channel {body!r}: start and increment must be finite",
                             file=path, line=k)
        return start, inc
    return None


def _channels(section, path):
    """Data format and the list of channels ``(kind, position, line)`` in file order."""
    fmt, channels = None, []
    for k, body in section["_items"]:
        head = body[:2].upper()
        if head == "#:":
            fmt = body[2:6].upper()
            if len(fmt) != 4 or fmt[0] not in "KL" or fmt[1] not in "RD" or fmt[2] not in "FB":
                raise InputError(f"unknown data format {body[2:].strip()!r}; valid: KRBI, "
                                 "KDBI, LRFI, LDFI (and KRFI, KDFI, LRBI, LDBI)", file=path,
                                 line=k)
        elif head == "D:":
            desc = body[2:].strip()
            items = [t.strip() for t in desc.split(",")]
            label, unit = items[0], (items[1] if len(items) > 1 else "")
            m = _LONG_SECTION.fullmatch(label)
            low = label.lower()
            if m:
                if unit != "m":
                    raise InputError(f"channel {desc!r} has unit {unit!r}; long sections are "
                                     "in 'm'", file=path, line=k)
                try:
                    pos = float(m.group(2).replace("D", "E").replace("d", "e"))
                except ValueError:
                    raise InputError(f"channel {desc!r}: {m.group(2)!r} is not a number",
                                     file=path, line=k) from None
                channels.append(("v" if m.group(1) else "index", pos, k))
            elif low.startswith("reference line"):
                what = " ".join(low[len("reference line"):].split())
                units = {"phi": "rad", "slope": "m/m", "banking": "m/m"}
                if what not in units:
                    raise InputError(f"reference line channel {what!r} is not supported; "
                                     "supported: phi, slope, banking", file=path, line=k)
                if unit != units[what]:
                    raise InputError(f"channel {desc!r} has unit {unit!r}; 'reference line "
                                     f"{what}' is in '{units[what]}'", file=path, line=k)
                if what in [c[0] for c in channels]:
                    raise InputError(f"channel 'reference line {what}' is given twice",
                                     file=path, line=k)
                channels.append((what, 0.0, k))
            else:
                raise InputError(f"unknown data channel {desc!r}; expected 'long section "
                                 "<i>,m', 'long section at v = <v>,m' or 'reference line "
                                 "phi,rad / slope,m/m / banking,m/m'", file=path, line=k)
    if fmt is None:
        raise InputError("$KD_DEFINITION has no '#:' data format line", file=path,
                         line=section["_line"])
    return fmt, channels


def read_crg(path, *, track_width: float = 1.5, name: str | None = None,
             modifiers: bool = True) -> Road:
    """Read an OpenCRG file (formats KRBI, KDBI, LRFI, LDFI and the other combinations).

    Parameters
    ----------
    path : str or pathlib.Path
        The ``.crg`` file.
    track_width : float
        Lateral distance between the two wheel tracks used for ``Road.left/right`` (m).
    name : str, optional
        Road name (default: the file stem).
    modifiers : bool
        Apply the file's ``$ROAD_CRG_MODS`` (or, without that section, OpenCRG's default
        modifiers, which put the start of the reference line at the origin), as a
        simulator loading the file does (:mod:`flexpipe.roads.crg_mods`); ``False``
        keeps the grid and the placement the file's ``$ROAD_CRG`` gives.

    Returns
    -------
    Road
        With ``x = u`` samples, the lateral grid ``y = v`` and heights ``z``; ``heading``
        when the file has a ``reference line phi`` channel or a non-zero start heading.

    Raises
    ------
    InputError
        Naming the file (and line where known): a malformed header or data block, or
        heights that change more than a drivable road can (likely millimetres; see
        :mod:`flexpipe.roads._plausible`).
    """
    path = as_path(path, "path")
    track_width = checked_number(track_width, "track_width", lo=0.0, unit="m")
    try:
        raw = path.read_bytes()
    except OSError as exc:
        raise InputError(f"cannot read the CRG file ({exc.strerror})", file=path) from None
    lines, data_offset, sep_line = _header_lines(raw, path)
    sections = _parse_header(lines, path)
    for missing in ("ROAD_CRG", "KD_DEFINITION"):
        if missing not in sections:
            close = difflib.get_close_matches(missing, list(sections), n=1, cutoff=0.7)
            hint = (f"; ${close[0]} on line {sections[close[0]]['_line']} is misspelt?"
                    if close else f"; sections found: {', '.join(sections) or 'none'}")
            raise InputError(f"no ${missing} section{hint}", file=path)
    mods = read_mods(sections, path) if modifiers else {}
    opts = read_opts(sections, path)
    if "ROAD_CRG_FILE" in sections and sections["ROAD_CRG_FILE"]["_items"]:
        warnings.warn(f"{path}: $ROAD_CRG_FILE is not applied by flexpipe", stacklevel=2)
    p = _road_params(sections["ROAD_CRG"], path)

    def get(key, default=None):
        if key in p:
            return p[key][0]
        if default is None:
            raise InputError(f"$ROAD_CRG has no {key}", file=path,
                             line=sections["ROAD_CRG"]["_line"])
        return default

    u_channel = _u_channel(sections["KD_DEFINITION"], path)
    fmt, channels = _channels(sections["KD_DEFINITION"], path)
    u0, du, u1, n_u = _u_axis(p, u_channel, path, sections["ROAD_CRG"]["_line"])
    kinds = [c[0] for c in channels]
    sec_idx = [i for i, c in enumerate(channels) if c[0] in ("index", "v")]
    if len(sec_idx) < 2:
        raise InputError("need at least 2 'long section' channels", file=path,
                         line=sections["KD_DEFINITION"]["_line"])
    if "index" in kinds and "v" in kinds:
        raise InputError("mixes 'long section <i>' and 'long section at v =' channels",
                         file=path, line=sections["KD_DEFINITION"]["_line"])
    if "index" in kinds:
        numbers = [channels[i][1] for i in sec_idx]
        if numbers != [float(i + 1) for i in range(len(sec_idx))]:
            raise InputError(f"long sections are numbered {numbers}, expected 1..{len(numbers)}",
                             file=path, line=channels[sec_idx[0]][2])
        v = _v_axis(p, len(sec_idx), path, sections["ROAD_CRG"]["_line"])
    else:
        v = np.array([channels[i][1] for i in sec_idx])
    order = np.argsort(v)
    if np.any(np.diff(v[order]) <= 0.0):
        raise InputError(f"two long sections share the same lateral position (v = "
                         f"{np.sort(v)[np.flatnonzero(np.diff(np.sort(v)) <= 0.0)[0]]:g} m)",
                         file=path, line=sections["KD_DEFINITION"]["_line"])

    data = raw[data_offset:]
    if fmt[2] == "F":
        vals, row_line = parse_text_values(data, fmt, len(channels), n_u, sep_line + 1, path)
    else:
        reject_text_as_binary(data, fmt, sep_line + 1, path)
        vals = parse_binary_values(data, fmt, len(channels), n_u, path)
        row_line = None
    if n_u is None:  # END_U or INCREMENT derived from the number of records (OpenCRG)
        n_u = vals.shape[0]
        if n_u < 2:
            raise InputError(f"the data block holds {n_u} cross section(s); a road needs at "
                             "least 2", file=path, line=sep_line)
        if du is None:
            du = (u1 - u0) / (n_u - 1)
            if u_channel and abs(u_channel[1] - du) > 1e-6 * max(du, 1e-3):
                warnings.warn(f"{path}: the 'U:reference line u' increment {u_channel[1]:g} m "
                              f"differs from (REFERENCE_LINE_END_U - START_U) / (records - 1) "
                              f"= {du:g} m; OpenCRG uses the latter", UserWarning,
                              stacklevel=2)
        else:
            u1 = u0 + (n_u - 1) * du
    u = u0 + du * np.arange(n_u)
    z = vals[:, sec_idx][:, order]
    v = v[order]
    plan, z_ref, bank = _reference_line(p, kinds, vals, u, path, get)
    # $ROAD_CRG_MODS (flexpipe.roads.crg_mods): scaling, NaN filling, placement
    du, v, z, plan, z_ref, bank = scale(mods, du=du, v=v, z_grid=z, plan=plan, z_ref=z_ref,
                                        bank=bank)
    u = u0 + du * np.arange(n_u)
    mode, offset = nan_rule(mods)
    z = fill_border_nans(z, u, row_line, path, mode=mode, offset=offset)

    def build(plan, z_ref):
        heading = None
        if not plan.straight or plan.phi_start != 0.0:
            heading = np.concatenate([[plan.phi[0]], plan.phi])
        # $ROAD_CRG_OPTS: smoothing zones and the heights beyond the lateral borders
        try:
            vo, Z = apply_opts(opts, u, v, z + z_ref[:, None] + bank[:, None] * v[None, :],
                               z_ref[0], z_ref[-1])
        except InputError as exc:
            raise InputError(exc.message, file=path, line=opts["BORDER_MODE_V"][1],
                             key=exc.key) from None
        return Road.from_grid(u, vo, Z, track_width=track_width, heading=heading, plan=plan,
                              name=path.stem if name is None else name, source=str(path))

    road = build(plan, z_ref)
    place = placement(mods, plan, road.height, v_min=float(v[0]), v_max=float(v[-1]))
    if place is not None:
        dx, dy, dz, dphi, center = place
        road = build(moved(plan, dx, dy, dphi, center), z_ref + dz)
    check_heights(u, z + z_ref[:, None] + bank[:, None] * v[None, :], file=path,
                  labels=[f"long section at v = {vj:g} m" for vj in v],
                  lines=None if row_line is None else [int(k) for k in row_line],
                  cause="heights look like millimetres (or a slope or banking like per "
                        "cent); OpenCRG heights are in metres, slopes and banking in m/m")
    return road


#: OpenCRG's increment when a file gives none (the reference loader's fallback), m
DEFAULT_INCREMENT = 0.01


def _u_axis(p, u_channel, path, section_line):
    """``(u0, du, u1, n_u)`` of the reference line; ``du`` or ``u1`` None and ``n_u``
    None when they follow from the number of records.

    As OpenCRG: START_U, else the ``U:`` channel's start, else 0; INCREMENT, else
    ``(END_U - START_U) / (records - 1)`` when END_U is given, else the ``U:`` channel's
    increment, else 0.01 m (with a warning); END_U, else ``START_U + (records - 1)
    INCREMENT``.
    """
    def line(key):
        return p[key][1] if key in p else section_line

    u0 = p["REFERENCE_LINE_START_U"][0] if "REFERENCE_LINE_START_U" in p else (
        u_channel[0] if u_channel else 0.0)
    u1 = p["REFERENCE_LINE_END_U"][0] if "REFERENCE_LINE_END_U" in p else None
    if "REFERENCE_LINE_INCREMENT" in p:
        du = p["REFERENCE_LINE_INCREMENT"][0]
    elif u1 is not None:
        du = None
    elif u_channel:
        du = u_channel[1]
    else:
        du = DEFAULT_INCREMENT
        warnings.warn(f"{path}: $ROAD_CRG gives no REFERENCE_LINE_INCREMENT or END_U and "
                      f"there is no 'U:reference line u' channel; OpenCRG's default increment "
                      f"{DEFAULT_INCREMENT:g} m is used", UserWarning, stacklevel=3)
    if du is not None and not du > 0.0:
        raise InputError(f"REFERENCE_LINE_INCREMENT must be > 0, got {du:g}", file=path,
                         line=line("REFERENCE_LINE_INCREMENT"), key="REFERENCE_LINE_INCREMENT")
    if u1 is not None and not u1 > u0:
        raise InputError(f"need REFERENCE_LINE_END_U > START_U, got {u0:g}, {u1:g}", file=path,
                         line=line("REFERENCE_LINE_END_U"), key="REFERENCE_LINE_END_U")
    if u1 is None or du is None:
        return u0, du, u1, None
    if (u1 - u0) / du > 1e8:
        raise InputError(f"REFERENCE_LINE_END_U - START_U = {u1 - u0:g} m in steps of {du:g} m "
                         "gives more than 1e8 cross sections; check both values", file=path,
                         line=line("REFERENCE_LINE_END_U"))
    n_u = int(round((u1 - u0) / du)) + 1
    if n_u < 2:
        raise InputError(f"REFERENCE_LINE_END_U - START_U = {u1 - u0:g} m is less than one "
                         f"increment ({du:g} m): a road needs at least 2 cross sections",
                         file=path, line=line("REFERENCE_LINE_END_U"),
                         key="REFERENCE_LINE_END_U")
    if abs(u0 + (n_u - 1) * du - u1) > 1e-6 * max(1.0, abs(u1)):
        raise InputError(f"REFERENCE_LINE_END_U - START_U = {u1 - u0:g} m is not a multiple "
                         f"of the increment {du:g} m", file=path,
                         line=line("REFERENCE_LINE_END_U"))
    return u0, du, u1, n_u


def _v_axis(p, n_v, path, section_line):
    """Lateral positions of ``n_v`` numbered long sections, as OpenCRG derives them:
    LONG_SECTION_V_INCREMENT, else ``(LEFT - RIGHT) / (n_v - 1)``, else 0.01 m (with a
    warning); LONG_SECTION_V_RIGHT, else ``LEFT - (n_v - 1) INCREMENT``, else centred on
    the reference line.  A given LEFT must agree with RIGHT and INCREMENT."""
    def value(key):
        return p[key][0] if key in p else None

    right, left, dv = (value(f"LONG_SECTION_V_{k}") for k in ("RIGHT", "LEFT", "INCREMENT"))
    if dv is None:
        if right is not None and left is not None:
            dv = (left - right) / (n_v - 1)
            if not dv > 0.0:
                raise InputError(f"LONG_SECTION_V_LEFT = {left:g} m must lie left of "
                                 f"LONG_SECTION_V_RIGHT = {right:g} m (v is positive to the "
                                 "left)", file=path, line=p["LONG_SECTION_V_LEFT"][1],
                                 key="LONG_SECTION_V_LEFT")
        else:
            dv = DEFAULT_INCREMENT
            warnings.warn(f"{path}: $ROAD_CRG gives no LONG_SECTION_V_INCREMENT and not both "
                          f"LONG_SECTION_V_RIGHT and LEFT; OpenCRG's default increment "
                          f"{DEFAULT_INCREMENT:g} m is used", UserWarning, stacklevel=3)
    elif not dv > 0.0:
        raise InputError(f"LONG_SECTION_V_INCREMENT must be > 0, got {dv:g}", file=path,
                         line=p["LONG_SECTION_V_INCREMENT"][1], key="LONG_SECTION_V_INCREMENT")
    if right is None:
        right = -0.5 * (n_v - 1) * dv if left is None else left - (n_v - 1) * dv
    v = right + dv * np.arange(n_v)
    if left is not None and abs(v[-1] - left) > 1e-6 * max(1.0, abs(left)):
        raise InputError(f"{n_v} long sections from {right:g} m by {dv:g} m end at {v[-1]:g} "
                         f"m, but LONG_SECTION_V_LEFT = {left:g} m", file=path,
                         line=p["LONG_SECTION_V_LEFT"][1], key="LONG_SECTION_V_LEFT")
    return v


def _reference_line(p, kinds, vals, u, path, get):
    """Plan position, elevation and banking of the reference line (OpenCRG definitions).

    ``phi`` and ``slope`` channels hold one value per interval (the value of record ``i``
    belongs to the interval from ``i-1`` to ``i``; the first is not used); ``banking`` one
    value per record.  Without a channel the start value holds for the whole road (the
    OpenCRG reference behaviour; a different end value gives a warning).
    """
    n_u, du = u.size, u[1] - u[0]
    length = u[-1] - u[0]
    tol = max(1e-6 * length, 1e-4)

    def column(kind, first):
        c = vals[first:, kinds.index(kind)]
        bad = np.flatnonzero(~np.isfinite(c))
        if bad.size:
            raise InputError(f"reference line {kind} channel value of record "
                             f"{bad[0] + first + 1} is {c[bad[0]]}; all values must be finite",
                             file=path)
        return c

    def constant(start_key, end_key, what):
        a = get(start_key, 0.0)
        b = get(end_key, a)
        if abs(b - a) > 1e-6 * max(1.0, abs(a)):
            warnings.warn(f"{path}: no {what} channel and {end_key} = {b:g} differs from "
                          f"{start_key} = {a:g}; OpenCRG uses the start value for the whole "
                          f"road (add a 'reference line {what}' channel for a varying one)",
                          UserWarning, stacklevel=4)
        return a

    x0, y0 = get("REFERENCE_LINE_START_X", 0.0), get("REFERENCE_LINE_START_Y", 0.0)
    xe, ye = p.get("REFERENCE_LINE_END_X", (None,))[0], p.get("REFERENCE_LINE_END_Y", (None,))[0]
    if "phi" in kinds:
        phi = column("phi", 1)
        plan = ReferenceLine.from_heading(u[0], du, phi, x0=x0, y0=y0)
        if xe is not None and ye is not None:
            err = math.hypot(plan.x[-1] - xe, plan.y[-1] - ye)
            if err > tol:
                warnings.warn(f"{path}: the integrated headings end {err:.4g} m away from "
                              "REFERENCE_LINE_END_X/Y; the difference is spread along the "
                              "line", UserWarning, stacklevel=3)
            plan = ReferenceLine.from_heading(u[0], du, phi, x0=x0, y0=y0, x_end=xe, y_end=ye)
    else:
        phi0 = constant("REFERENCE_LINE_START_PHI", "REFERENCE_LINE_END_PHI", "phi")
        plan = ReferenceLine.from_heading(u[0], du, np.full(n_u - 1, phi0), x0=x0, y0=y0)
        if xe is not None and ye is not None:
            err = math.hypot(plan.x[-1] - xe, plan.y[-1] - ye)
            if err > tol:
                warnings.warn(f"{path}: REFERENCE_LINE_END_X/Y lie {err:.4g} m from the end of "
                              "the straight line given by the start position and heading; "
                              "the end position is not used", UserWarning, stacklevel=3)
    z0 = get("REFERENCE_LINE_START_Z", 0.0)
    slope = column("slope", 1) if "slope" in kinds else np.full(
        n_u - 1, constant("REFERENCE_LINE_START_S", "REFERENCE_LINE_END_S", "slope"))
    z_ref = np.empty(n_u)
    z_ref[0] = z0
    z_ref[1:] = z0 + np.cumsum(du * slope)
    ze = p.get("REFERENCE_LINE_END_Z", (None,))[0]
    if "slope" in kinds and ze is not None:
        z_ref += np.linspace(0.0, 1.0, n_u) * (ze - z_ref[-1])
    bank = column("banking", 0) if "banking" in kinds else np.full(
        n_u, constant("REFERENCE_LINE_START_B", "REFERENCE_LINE_END_B", "banking"))
    return plan, z_ref, bank
