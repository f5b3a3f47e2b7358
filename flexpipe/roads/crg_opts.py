"""OpenCRG evaluation options (``$ROAD_CRG_OPTS``) as flexpipe's road grid carries them.

OpenCRG evaluates a road outside its grid by its *border modes*, and blends its first and
last metres towards the reference line's start and end elevation (*smoothing zones*).
flexpipe's :class:`~flexpipe.roads.Road` is a height grid held beyond its borders, so the
options become grid edits (:func:`apply`), as OpenCRG's reference evaluator defines them
(heights equal pyopencrg's, ``tests/test_crg_opts.py``):

* ``BORDER_MODE_V`` beyond the left and right borders (``v`` outside the long sections):
  1 the height ``BORDER_OFFSET_V`` (absolute), 2 the border's height (default) plus
  ``BORDER_OFFSET_V``, 3 the cross section repeated, 4 it mirrored.  Repeated and mirrored
  sections are written out :data:`PAD_M` (5 m) beyond each border, held further out;
  0 (no height) is refused: a wheel there would have no road.
* ``BORDER_MODE_U`` / ``BORDER_OFFSET_U``: beyond the road's ends.  A run must stay on the
  road (it is refused otherwise), so modes 0, 1 and 2 change nothing within it but the road
  normal within 50 mm of an end; 3 and 4 (a road repeated or mirrored beyond its ends) are
  refused: give data as long as the run.
* ``BORDER_SMOOTH_UBEG`` / ``_UEND``: over that length from the start (end) the height
  rises linearly from the reference line's start (end) elevation to the road's; applied
  at every cross section (OpenCRG blends between them: equal at the sections, within the
  product of the blend's and the height's change over one increment between them).
* ``REFLINE_CONTINUATION`` 1 (a closed track) is refused.
* The check, search, warning and log options change no height and are read and ignored.
"""

from __future__ import annotations

import numpy as np

from flexpipe.errors import InputError

#: options that change heights, and their defaults
DEFAULTS = {"BORDER_MODE_U": 2.0, "BORDER_MODE_V": 2.0, "BORDER_OFFSET_U": 0.0,
            "BORDER_OFFSET_V": 0.0, "BORDER_SMOOTH_UBEG": 0.0, "BORDER_SMOOTH_UEND": 0.0,
            "REFLINE_CONTINUATION": 0.0}
#: options of other tools and of the checks: no height depends on them
IGNORED = ("CHECK_EPS", "CHECK_INC", "CHECK_TOL", "CHECK_PRO", "CHECK_WGS",
           "REFLINE_SEARCH_FAR", "REFLINE_SEARCH_CLOSE", "WARN_MSGS", "WARN_CURV_LOCAL",
           "WARN_CURV_GLOBAL", "LOG_MSGS", "LOG_EVAL", "LOG_EVAL_FREQ", "LOG_HIST",
           "LOG_HIST_FREQ", "LOG_STAT", "LOG_STAT_FREQ")
#: how far beyond each lateral border a repeated or mirrored cross section is written (m)
PAD_M = 5.0
#: width of the step at a border or a repeat seam (m)
EDGE_M = 1e-9
#: most long sections a repeated or mirrored road may take
MAX_COLUMNS = 20_000


def read_opts(sections: dict, path) -> dict:
    """``{KEY: (value, line)}`` of ``$ROAD_CRG_OPTS`` with the defaults, checked.

    Raises
    ------
    InputError
        Naming the file, line and key: an unknown key, a mode other than 0..4, mode 0 in
        v, modes 3 and 4 in u, a negative smoothing length, a closed track.
    """
    from flexpipe.roads.crg_mods import key_values

    out = {k: (v, None) for k, v in DEFAULTS.items()}
    if "ROAD_CRG_OPTS" not in sections:
        return out
    given = key_values(sections["ROAD_CRG_OPTS"], path, "ROAD_CRG_OPTS",
                       tuple(DEFAULTS) + IGNORED)
    out.update({k: v for k, v in given.items() if k in DEFAULTS})

    def bad(key, why):
        return InputError(f"{key} = {out[key][0]:g}: {why}", file=path, line=out[key][1],
                          key=key)

    for axis in ("U", "V"):
        key = f"BORDER_MODE_{axis}"
        if out[key][0] not in (0.0, 1.0, 2.0, 3.0, 4.0):
            raise bad(key, "valid: 0 (no height), 1 (BORDER_OFFSET), 2 (keep the border's), "
                           "3 (repeat), 4 (reflect)")
    if out["BORDER_MODE_V"][0] == 0.0:
        raise bad("BORDER_MODE_V", "no height beyond the road's edges, where a wheel may run; "
                                   "give 1 (BORDER_OFFSET_V), 2 (keep), 3 (repeat) or 4 "
                                   "(reflect)")
    if out["BORDER_MODE_U"][0] in (3.0, 4.0):
        raise bad("BORDER_MODE_U", "a road repeated or mirrored beyond its ends: flexpipe "
                                   "keeps a run on the road's own data, so give data as long "
                                   "as the run (or modes 0-2)")
    for key in ("BORDER_SMOOTH_UBEG", "BORDER_SMOOTH_UEND"):
        if out[key][0] < 0.0:
            raise bad(key, "a smoothing length must be >= 0 m")
    if out["REFLINE_CONTINUATION"][0] not in (0.0, 1.0):
        raise bad("REFLINE_CONTINUATION", "valid: 0 (extrapolate), 1 (close the track)")
    if out["REFLINE_CONTINUATION"][0] == 1.0:
        raise bad("REFLINE_CONTINUATION", "closed tracks are not supported: give 0 and a "
                                          "road as long as the run")
    return out


def apply(opts: dict, u, v, Z, zr_start: float, zr_end: float):
    """The grid ``(v, Z)`` of heights ``Z`` (n_u, n_v, reference line and banking
    included) at distances ``u`` and lateral positions ``v`` with the options ``opts``
    (:func:`read_opts`) written in: smoothing zones, then the lateral border columns.
    ``zr_start`` / ``zr_end``: the reference line's elevation at the start and end."""
    Z = np.array(Z, dtype=float)
    u = np.asarray(u, dtype=float)
    for key, z0, dist in (("BORDER_SMOOTH_UBEG", zr_start, u - u[0]),
                          ("BORDER_SMOOTH_UEND", zr_end, u[-1] - u)):
        length = opts[key][0]
        if length > 0.0:
            w = np.clip(dist / length, 0.0, 1.0)[:, None]
            Z = w * (Z - z0) + z0
    mode, offset = opts["BORDER_MODE_V"][0], opts["BORDER_OFFSET_V"][0]
    v = np.asarray(v, dtype=float)
    if mode in (1.0, 2.0):
        if mode == 2.0 and offset == 0.0:
            return v, Z
        right, left = (np.full(len(Z), offset) if mode == 1.0 else Z[:, i] + offset
                       for i in (0, -1))
        return (np.r_[v[0] - EDGE_M, v, v[-1] + EDGE_M],
                np.column_stack([right, Z, left]))
    return _wrapped(v, Z, reflect=mode == 4.0)


def _wrapped(v, Z, *, reflect: bool):
    """The cross sections repeated or mirrored :data:`PAD_M` beyond each border: blocks of
    the file's sections shifted by whole widths (mirrored every other block when
    ``reflect``); a repeat jumps from the right border's height to the left one's at each
    seam, over :data:`EDGE_M` (outside the file's own sections)."""
    lo, hi = float(v[0]), float(v[-1])
    period = hi - lo
    k = int(np.ceil(PAD_M / period)) + 1
    if (2 * k + 1) * v.size > MAX_COLUMNS:
        raise InputError(f"BORDER_MODE_V = {4 if reflect else 3}: the road is {period:g} m "
                         f"wide, so repeating it {PAD_M:g} m beyond each edge takes "
                         f"{(2 * k + 1) * v.size} long sections (at most {MAX_COLUMNS}); "
                         "give mode 2 (keep the border's height)", key="BORDER_MODE_V")
    pos, val = [], []
    for j in range(-k, k + 1):
        if reflect and j % 2:
            p, z = (lo + hi - v)[::-1] + j * period, Z[:, ::-1]
        else:
            p, z = v + j * period, Z
        p = p.copy()
        if pos and not reflect:   # the seam between block j - 1 and block j
            if j == 0:
                pos[-1] = pos[-1].copy()
                pos[-1][-1] -= EDGE_M
            else:
                p[0] += EDGE_M
        elif pos:                 # mirrored blocks meet with equal heights
            p, z = p[1:], z[:, 1:]
        pos.append(p)
        val.append(z)
    pos, val = np.concatenate(pos), np.concatenate(val, axis=1)
    keep = (pos >= lo - PAD_M) & (pos <= hi + PAD_M)
    return pos[keep], val[:, keep]
