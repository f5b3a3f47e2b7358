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
    two samples are more than ``WINDOW`` apart the profile between them is one straight
    line, so the samples on either side are checked as separate stretches, each reaching
    ``WINDOW`` into the line (every window inside the line has the rise of that
    piece).  A damaged distance (``9e8`` m after a flat 30 m road) used to ask for one
    bin per half metre of the whole length (27 GB).

    Parameters
    ----------
    x : ndarray, shape (n,)
        Strictly increasing distances (m), n >= 2.
    h : ndarray, shape (n,) or (n, m)
        Heights (m) at ``x``, one column per track or long section.

    Returns
    -------
    start : ndarray, shape (k,)
        Start of each window (m); each window is ``WINDOW`` long.
    rise : ndarray, shape (k, m)
        Largest minus smallest height in the window, of the piecewise-linear profile
        sampled at its samples and the bin edges.  Any two points less than ``WINDOW/2``
        apart lie in one window; no window is longer than ``WINDOW``.
    """
    x = np.asarray(x, dtype=float)
    h = np.asarray(h, dtype=float).reshape(x.size, -1)
    long_gap = np.flatnonzero(np.diff(x) > WINDOW)
    if not long_gap.size:
        return _binned_rise(x, h)
    starts, rises = [], []
    for a, b in zip(np.r_[0, long_gap + 1], np.r_[long_gap, x.size - 1], strict=True):
        xs, hs = x[a:b + 1], h[a:b + 1]
        if a > 0:  # the last WINDOW of the straight line before the stretch
            t = 1.0 - WINDOW / (x[a] - x[a - 1])
            xs = np.r_[x[a] - WINDOW, xs]
            hs = np.vstack([h[a - 1] + t * (h[a] - h[a - 1]), hs])
        if b < x.size - 1:  # the first WINDOW of the line after it
            t = WINDOW / (x[b + 1] - x[b])
            xs = np.r_[xs, x[b] + WINDOW]
            hs = np.vstack([hs, h[b] + t * (h[b + 1] - h[b])])
        s, r = _binned_rise(xs, hs)
        starts.append(s)
        rises.append(r)
    return np.concatenate(starts), np.concatenate(rises)


def _binned_rise(x, h):
    """:func:`local_rise` of samples no more than ``WINDOW`` apart (bins over their span)."""
    half = 0.5 * WINDOW
    nb = int((x[-1] - x[0]) // half) + 1
    b = np.minimum(((x - x[0]) // half).astype(np.intp), nb - 1)
    hi = np.full((nb, h.shape[1]), -np.inf)
    lo = np.full((nb, h.shape[1]), np.inf)
    np.maximum.at(hi, b, h)
    np.minimum.at(lo, b, h)
    # heights at the bin edges, so a bin between two far-apart samples sees the slope
    edges = np.minimum(x[0] + half * np.arange(nb + 1), x[-1])
    i = np.clip(np.searchsorted(x, edges, side="right") - 1, 0, x.size - 2)
    t = ((edges - x[i]) / (x[i + 1] - x[i]))[:, None]
    he = h[i] * (1.0 - t) + h[i + 1] * t
    hi = np.maximum(hi, np.maximum(he[:-1], he[1:]))
    lo = np.minimum(lo, np.minimum(he[:-1], he[1:]))
    if nb > 1:
        hi, lo = np.maximum(hi[:-1], hi[1:]), np.minimum(lo[:-1], lo[1:])
    start = x[0] + half * np.arange(hi.shape[0])
    return start, hi - lo


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
