"""Plausibility of road heights read from a file: catch heights in the wrong unit.

Road files hold heights in metres.  A profile written in millimetres (a 50 mm bump as
``50``) still reads as valid numbers and gives a run with tyre loads of hundreds of kN, so
the readers (:func:`~flexpipe.roads.read_csv`, :func:`~flexpipe.roads.read_crg` and the
generated roads of a TOML spec) reject heights that change more than
:data:`MAX_RISE` within :data:`WINDOW` along the road.

Why these bounds: 2 m of rise within 1 m is a wall steeper than 60 degrees and taller
than the wheel diameter of any road vehicle (passenger-car tyres about 0.65 m, truck tyres
about 1.1 m), and twice the most any real profile reaches: public roads stay below 40 %
grade, the largest step a wheeled off-road vehicle is specified to climb is about 0.6 m,
the measured OpenCRG twist track in ``../shared/reference`` (Horstwalde) ends with a drop
of 0.77 m (0.86 m within 1 m, the roughest real profile known to the project), and ISO
8608 class H, the roughest class, changes by at most about 1 m within 1 m in km-long
realisations.  Only the *local* change is bounded, never the range: a mountain road
climbs hundreds of metres over kilometres at 10-15 %.  In millimetres even gentle
profiles break the bound by far: a 50 mm bump becomes 50 m, a 10 mm irregularity 20 m
within 1 m, an ISO 8608 class A road (the smoothest) several metres.
"""

from __future__ import annotations

import numpy as np

from flexpipe.errors import InputError

#: Largest height change (m) accepted within :data:`WINDOW` along the road.
MAX_RISE = 2.0
#: Horizontal window (m) along the road over which :data:`MAX_RISE` is measured.
WINDOW = 1.0


def local_rise(x, h):
    """Height range of every window of two consecutive ``WINDOW / 2`` bins along ``x``.

    Memory and time grow with the number of samples, not with the road's length: where
    most bins would be empty, only the bins that hold a sample or neighbour one are
    formed.  Two bins neither of which does lie on one straight piece of the profile, more
    than ``WINDOW`` long, whose rise within any window is its slope times ``WINDOW``: one
    window per such piece stands for them.  A damaged distance (``9e8`` m after a flat
    30 m road) used to ask for one bin per half metre of the whole length (27 GB).

    Parameters
    ----------
    x : ndarray, shape (n,)
        Strictly increasing distances (m), n >= 2.
    h : ndarray, shape (n,) or (n, m)
        Heights (m) at ``x``, one column per track or long section.

    Returns
    -------
    start : ndarray, shape (k,)
        Start of each window (m), ascending; each window is ``WINDOW`` long.
    rise : ndarray, shape (k, m)
        Largest minus smallest height in the window, of the piecewise-linear profile
        sampled at its samples and the bin edges.  Any two points less than ``WINDOW/2``
        apart lie in one window; no window is longer than ``WINDOW``.
    """
    x = np.asarray(x, dtype=float)
    h = np.asarray(h, dtype=float).reshape(x.size, -1)
    half = 0.5 * WINDOW
    nb = int((x[-1] - x[0]) // half) + 1
    b = np.minimum(((x - x[0]) // half).astype(np.intp), nb - 1)
    sparse = nb > 4 * x.size + 16  # most bins empty: keep those near a sample only
    if sparse:
        occupied = b[np.r_[True, np.diff(b) > 0]]  # b is non-decreasing
        kept = np.unique(np.clip(np.concatenate([occupied - 1, occupied, occupied + 1]),
                                 0, nb - 1))
        at = np.searchsorted(kept, b)
    else:
        kept, at = np.arange(nb), b
    hi = np.full((kept.size, h.shape[1]), -np.inf)
    lo = np.full((kept.size, h.shape[1]), np.inf)
    np.maximum.at(hi, at, h)
    np.minimum.at(lo, at, h)
    # heights at both edges of each bin: a bin between two far-apart samples sees the slope
    def at_edges(k):
        return _heights_at(x, h, np.minimum(x[0] + half * k, x[-1]))

    if sparse:
        left, right = at_edges(kept), at_edges(kept + 1)
    else:  # every bin: each inner edge is shared by two
        he = at_edges(np.arange(nb + 1))
        left, right = he[:-1], he[1:]
    hi = np.maximum(hi, np.maximum(left, right))
    lo = np.minimum(lo, np.minimum(left, right))
    if nb > 1:  # windows: two neighbouring bins, both kept
        pair = np.flatnonzero(np.diff(kept) == 1)
        start = x[0] + half * kept[pair]
        rise = np.maximum(hi[pair], hi[pair + 1]) - np.minimum(lo[pair], lo[pair + 1])
    else:
        start, rise = x[:1].copy(), hi - lo
    gap = np.diff(x)
    line = np.flatnonzero(gap > WINDOW) if sparse else []  # straight pieces > a window
    if len(line):
        start = np.concatenate([start, x[line] + 0.5 * (gap[line] - WINDOW)])
        rise = np.vstack([rise, np.abs(h[line + 1] - h[line]) * (WINDOW / gap[line])[:, None]])
        order = np.argsort(start, kind="stable")
        start, rise = start[order], rise[order]
    return start, rise


def _heights_at(x, h, xe):
    """Heights of the piecewise-linear profile ``(x, h)`` at ``xe`` (within ``x``)."""
    i = np.clip(np.searchsorted(x, xe, side="right") - 1, 0, x.size - 2)
    t = ((xe - x[i]) / (x[i + 1] - x[i]))[:, None]
    return h[i] * (1.0 - t) + h[i + 1] * t


def check_heights(x, h, *, file, labels=None, lines=None, key=None,
                  cause: str = "heights look like millimetres; the file's unit is metres"
                  ) -> None:
    """Raise :class:`InputError` if the heights change more than ``MAX_RISE`` within ``WINDOW``.

    Parameters
    ----------
    x : ndarray, shape (n,)
        Strictly increasing distances along the road (m).
    h : ndarray, shape (n,) or (n, m)
        Heights (m), one column per track or long section.
    file : str or pathlib.Path
        The road file, for the message.
    labels : sequence of str, optional
        Name of each column (e.g. ``"left track"``).
    lines : sequence of int, optional
        Line number of each sample (text files), for the message.
    key : str, optional
        Key of a specification that produced the heights.
    cause : str
        The likely cause, appended to the message.
    """
    h = np.asarray(h, dtype=float).reshape(np.size(x), -1)
    start, rise = local_rise(x, h)
    bad = np.argwhere(rise > MAX_RISE)
    if not bad.size:
        return
    k, j = (int(v) for v in bad[0])
    x = np.asarray(x, dtype=float)
    inside = np.flatnonzero((x >= start[k]) & (x <= start[k] + WINDOW))
    # the sample farthest in height from the window's first one: the top of the bump,
    # the bottom of the pothole, the far side of the step
    n = int(inside[np.argmax(np.abs(h[inside, j] - h[inside[0], j]))]) if inside.size \
        else int(np.searchsorted(x, start[k]))
    n = min(n, x.size - 1)
    label = f" on the {labels[j]}" if labels is not None else ""
    raise InputError(
        f"the road height changes by {rise[k, j]:.4g} m between x = {start[k]:g} and "
        f"{start[k] + WINDOW:g} m{label} (height {h[n, j]:g} m at x = {x[n]:g} m); no drivable "
        f"road rises or falls more than {MAX_RISE:g} m within {WINDOW:g} m (valid: a change "
        f"of at most {MAX_RISE:g} m within any {WINDOW:g} m of road); {cause}",
        file=file, line=None if lines is None else lines[n], key=key)
