"""Height profiles of the Adams 2D road types, as exact samples for a :class:`Road`.

Each function takes lengths in metres and returns ``(x, z)``: distances along the road
(strictly increasing) and heights, such that linear interpolation between the samples is
the road type's shape.  Piecewise-linear shapes (plank with 45-degree bevels, pot hole,
ramp, roof, poly line) are sampled at their corners only and are exact; a vertical edge
rises over :data:`EDGE_M` (1 um) just outside the feature, which is exact from its START
to its end.  Curved shapes are sampled finely enough that linear interpolation stays
within a stated bound of the curve: rounded plank edges at :data:`ARC_POINTS` points per
quarter circle (within 1.4e-4 of the radius: ``1 - cos(pi / 192)``), sine waves at
:data:`WAVE_POINTS` points per (local) wavelength (within 3.1e-4 of the amplitude:
``1 - cos(pi / 128)``).

Before its first feature and after its last one a 2D road is flat at height 0 (a ramp
holds its final height); :func:`road_extent` gives the sampled range.
"""

from __future__ import annotations

import math

import numpy as np

#: width of a vertical edge (m): the rise of a plank or pot hole edge
EDGE_M = 1e-6
#: samples per quarter circle of a rounded plank edge
ARC_POINTS = 48
#: samples per wavelength of a sine or swept sine
WAVE_POINTS = 128
#: distance a 2D road is sampled beyond its last feature (m): flat there (held heights)
RUN_OUT_M = 1000.0
#: a sine without LENGTH runs this far from its start (m)
ENDLESS_SINE_M = 1000.0
#: most samples a sine or sweep may take (about 40 MB of road arrays)
MAX_SAMPLES = 2_000_000


def plank(height: float, start: float, length: float, bevel: float = 0.0, *,
          rounded: bool = False):
    """A plank (cleat) from ``start`` over ``length`` (bevels included), ``height`` high
    (a groove when negative); its two top edges are 45-degree bevels ``bevel`` long
    along x, or quarter circles of radius ``bevel`` when ``rounded``.  The sides below
    the bevels are vertical."""
    h = abs(height)
    end = start + length
    e = EDGE_M
    if bevel <= 0.0:
        x = [start - e, start, end, end + e]
        z = [0.0, h, h, 0.0]
    elif not rounded:
        x = [start - e, start, start + bevel, end - bevel, end, end + e]
        z = [0.0, h - bevel, h, h, h - bevel, 0.0]
    else:
        t = np.linspace(0.0, 0.5 * math.pi, ARC_POINTS + 1)
        up_x = start + bevel * (1.0 - np.cos(t))
        up_z = h - bevel + bevel * np.sin(t)
        x = np.concatenate([[start - e], up_x, (end - (up_x - start))[::-1], [end + e]])
        z = np.concatenate([[0.0], up_z, up_z[::-1], [0.0]])
    if bevel >= h:   # bevels or arcs down to the road: no vertical sides
        x, z = x[1:-1], z[1:-1]
    x, z = _strictly_increasing(np.asarray(x, float), np.asarray(z, float))
    return x, math.copysign(1.0, height) * z


def pot_hole(depth: float, start: float, length: float):
    """A rectangular pot hole ``depth`` deep (a bump when ``depth`` < 0) from ``start``
    over ``length``."""
    x = np.array([start - EDGE_M, start, start + length, start + length + EDGE_M])
    return x, np.array([0.0, -depth, -depth, 0.0])


def ramp(height: float, start: float, slope: float):
    """A ramp rising (falling when ``height`` < 0) from ``start`` at ``slope`` (dz/dx, 1
    is 45 degrees) to ``height``, which the road then holds."""
    return np.array([start, start + abs(height) / slope]), np.array([0.0, height])


def roof(height: float, start: float, length: float):
    """A triangular obstacle from ``start`` over ``length``, ``height`` at its middle."""
    return (np.array([start, start + 0.5 * length, start + length]),
            np.array([0.0, height, 0.0]))


def sine(amplitude: float, wavelength: float, start: float, length: float | None):
    """``amplitude * sin(2 pi (x - start) / wavelength)`` from ``start`` over ``length``
    (:data:`ENDLESS_SINE_M` when None), 0 elsewhere."""
    span = ENDLESS_SINE_M if length is None else length
    n = _samples(span / wavelength * WAVE_POINTS)
    x = start + np.linspace(0.0, span, n + 1)
    z = amplitude * np.sin(2.0 * math.pi * (x - start) / wavelength)
    return _closed(x, z, open_end=length is None)


def sweep_phase(u, span: float, wl0: float, wl1: float, log: bool):
    """Phase (rad) of a swept sine ``u`` metres after its start.

    Linear sweep (``log`` False): the spatial frequency rises linearly from ``1/wl0`` to
    ``1/wl1`` over ``span``, phase ``2 pi (f0 u + (f1 - f0) u^2 / (2 span))``.
    Logarithmic sweep: the wavelength falls linearly from ``wl0`` to ``wl1`` (so every
    cycle is shorter than the one before by a constant factor), reaching zero at
    ``u_inf = wl0 span / (wl0 - wl1)``: phase ``-2 pi (u_inf / wl0) ln(1 - u / u_inf)``.
    """
    u = np.asarray(u, float)
    if not log:
        f0, f1 = 1.0 / wl0, 1.0 / wl1
        return 2.0 * math.pi * (f0 * u + (f1 - f0) * u * u / (2.0 * span))
    if wl1 >= wl0:
        return 2.0 * math.pi * u / wl0
    u_inf = wl0 * span / (wl0 - wl1)
    return -2.0 * math.pi * (u_inf / wl0) * np.log1p(-u / u_inf)


def sine_sweep(start: float, end: float, amp0: float, amp1: float, wl0: float, wl1: float,
               *, log: bool = False):
    """A swept sine from ``start`` to ``end``: amplitude linear from ``amp0`` to ``amp1``,
    wavelength from ``wl0`` down to ``wl1`` (:func:`sweep_phase`); 0 elsewhere."""
    span = end - start
    n = _samples(span / wl1 * WAVE_POINTS)
    u = np.linspace(0.0, span, n + 1)
    z = (amp0 + (amp1 - amp0) * u / span) * np.sin(sweep_phase(u, span, wl0, wl1, log))
    return _closed(start + u, z, open_end=False)


def road_extent(xs) -> tuple[float, float]:
    """Sampled range of a 2D road whose features lie at the distances ``xs``: from 0 (or
    its first feature when that lies before 0) to :data:`RUN_OUT_M` beyond the last."""
    xs = np.asarray(xs, float)
    lo = min(0.0, float(xs.min())) if xs.size else 0.0
    hi = max(0.0, float(xs.max())) if xs.size else 0.0
    return lo, hi + RUN_OUT_M


def on_extent(x, z, lo: float, hi: float):
    """``(x, z)`` of a feature with the road's flat ends added at ``lo`` and ``hi``
    (heights held: 0 before, the last height after)."""
    x = np.asarray(x, float)
    z = np.asarray(z, float)
    if x[0] > lo:
        x, z = np.concatenate([[lo], x]), np.concatenate([[z[0]], z])
    if x[-1] < hi:
        x, z = np.concatenate([x, [hi]]), np.concatenate([z, [z[-1]]])
    return x, z


def _samples(n: float) -> int:
    n = max(int(math.ceil(n)), 2)
    if n > MAX_SAMPLES:
        raise ValueError(f"{n} samples (more than {MAX_SAMPLES})")
    return n


def _closed(x, z, *, open_end: bool):
    """A wave section that is 0 beyond its end: a vertical edge down to 0 there."""
    if open_end:
        return x, z
    if abs(z[-1]) <= 1e-12 * max(1e-300, float(np.abs(z).max())):
        return x, np.append(z[:-1], 0.0)
    return np.append(x, x[-1] + EDGE_M), np.append(z, 0.0)


def _strictly_increasing(x, z):
    keep = np.concatenate([[True], np.diff(x) > 0.0])
    return x[keep], z[keep]
