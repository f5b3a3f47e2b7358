"""Road generators: flat, harmonic, the paper's isolated irregularity and ISO 8608 roads.

ISO 8608 random roads
---------------------
ISO 8608 classifies a road profile by the one-sided displacement PSD of the elevation,
fitted as ``Gd(n) = Gd(n0) (n / n0)^-w`` with ``n0 = 0.1`` cycles/m and waviness ``w = 2``.
The class values ``Gd(n0)`` (geometric mean of each class, 1e-6 m^3) are

=====  =======  =====  =======
class  Gd(n0)   class  Gd(n0)
=====  =======  =====  =======
A           16  E        4 096
B           64  F       16 384
C          256  G       65 536
D        1 024  H      262 144
=====  =======  =====  =======

i.e. ``16e-6 * 4**k`` for the k-th class, each class spanning a factor of 4 (the class
table of ISO 8608, reproduced e.g. by Loprencipe & Zoccali, J. Mod. Transport. 25 (2017)
24-33 and Mucka, J. Test. Eval. 46 (2018) 405-418).  The generator sums cosines on the
discrete frequencies ``n_k = k / L`` inside the band ``[n_min, n_max]`` (default 0.011 ..
2.83 cycles/m, wavelengths of about 91 m down to 0.35 m, the range commonly used with the
ISO 8608 classes; change it with ``n_min``/``n_max``), with amplitude ``sqrt(2 Gd(n_k) dn)``
(``dn = 1/L``) and uniformly random phases drawn from ``numpy.random.default_rng(seed)``.
The profile is therefore periodic over the road length and its periodogram equals
``Gd`` on every bin of the band.

Left/right coherence
--------------------
``coherence="isotropic"`` (default) uses the isotropic-surface model of Dodds & Robson
(J. Sound Vib. 31 (1973) 175-183): if the road surface is a homogeneous isotropic random
field whose single-track PSD is ``Gd ~ n^-2``, two parallel tracks a distance ``B`` apart
have the real cross-spectrum ``gamma(n) Gd(n)`` with

    gamma(n) = x K1(x),   x = 2 pi n B,

``K1`` the modified Bessel function of the second kind (derivation: the 2-D spectrum is
``~ |k|^-3``; integrate it over the lateral wavenumber with and without ``cos(2 pi k_y B)``).
``gamma -> 1`` for long waves and ``-> 0`` for waves much shorter than the track width.
The right track is built from the left track's phases and an independent set as
``gamma * left_k + sqrt(1 - gamma^2) * independent_k`` per frequency, so both tracks have
the PSD ``Gd`` and their magnitude-squared coherence is ``gamma^2``.  ``coherence`` may
also be a number in [0, 1] (the same ``gamma`` at every frequency): 1 gives identical
tracks, 0 independent ones.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.special import k1

from flexpipe._args import checked_number
from flexpipe.errors import InputError
from flexpipe.roads.road import Road

#: ISO 8608 class values Gd(n0) at n0 = 0.1 cycles/m (geometric class means), m^3.
ISO8608_GD0 = {c: 16e-6 * 4.0**k for k, c in enumerate("ABCDEFGH")}
#: Reference spatial frequency of ISO 8608 (cycles/m).
ISO8608_N0 = 0.1
#: Spatial frequency band of the ISO 8608 classification (cycles/m).
ISO8608_BAND = (0.011, 2.83)

_MAX_SAMPLES = 20_000_000


def _grid(length, dx, what):
    if not (math.isfinite(length) and length > 0.0):
        raise InputError(f"{what}: length must be > 0 m, got {length!r}")
    if not (math.isfinite(dx) and dx > 0.0):
        raise InputError(f"{what}: dx must be > 0 m, got {dx!r}")
    n = int(round(length / dx))
    if n < 1:
        raise InputError(f"{what}: dx = {dx:g} m is longer than the road ({length:g} m)")
    if n + 1 > _MAX_SAMPLES:
        raise InputError(f"{what}: {n + 1} samples (length {length:g} m / dx {dx:g} m) "
                         f"exceeds {_MAX_SAMPLES}; use a larger dx or a shorter road")
    return np.arange(n + 1) * (length / n)


def _tracks(h, tracks, what):
    if tracks == "both":
        return h, h
    if tracks == "left":
        return h, np.zeros_like(h)
    if tracks == "right":
        return np.zeros_like(h), h
    raise InputError(f"{what}: tracks must be 'both', 'left' or 'right', got {tracks!r}")


def flat(length: float, *, dx: float = 1.0, track_width: float = 1.5) -> Road:
    """A flat road of height zero.

    Parameters
    ----------
    length : float
        Road length (m).
    dx : float
        Sample spacing (m).
    track_width : float
        Distance between the wheel tracks (m).
    """
    x = _grid(length, dx, "flat road")
    zero = np.zeros_like(x)
    return Road(x=x, left=zero, right=zero, track_width=track_width, name="flat",
                source=f"flat(length={length:g})")


def harmonic(*, wavelength: float, amplitude: float, length: float, dx: float,
             phase_right: float = 0.0, track_width: float = 1.5) -> Road:
    """A sinusoidal road ``h = amplitude sin(2 pi x / wavelength)`` over its whole length.

    Parameters
    ----------
    wavelength, amplitude : float
        Wavelength (m, > 0) and amplitude (m).
    length, dx : float
        Road length and sample spacing (m); ``dx`` must be at most ``wavelength / 8``.
    phase_right : float
        Phase lag of the right track (rad); ``pi`` excites roll.
    track_width : float
        Distance between the wheel tracks (m).
    """
    what = "harmonic road"
    if not (math.isfinite(wavelength) and wavelength > 0.0):
        raise InputError(f"{what}: wavelength must be > 0 m, got {wavelength!r}")
    if not math.isfinite(amplitude):
        raise InputError(f"{what}: amplitude must be finite, got {amplitude!r}")
    if dx > wavelength / 8.0:
        raise InputError(f"{what}: dx = {dx:g} m is too coarse for wavelength {wavelength:g} "
                         f"m; use dx <= {wavelength / 8.0:g} m (8 samples per wave)")
    x = _grid(length, dx, what)
    arg = 2.0 * np.pi * x / wavelength
    return Road(x=x, left=amplitude * np.sin(arg), right=amplitude * np.sin(arg - phase_right),
                track_width=track_width, name="harmonic",
                source=f"harmonic(wavelength={wavelength:g}, amplitude={amplitude:g})")


def irregularity(*, s0: float, wavelength: float, n_periods: int = 10, start: float = 20.0,
                 length: float | None = None, dx: float = 0.01, tracks: str = "both",
                 track_width: float = 1.5) -> Road:
    """The paper's isolated irregularity ``s(z) = s0 sin(2 pi (z - start) / wavelength)``.

    The road is flat except for ``start <= z < start + n_periods * wavelength``.  The sample
    grid contains the start and end of the irregularity exactly.

    Parameters
    ----------
    s0 : float
        Amplitude (m).
    wavelength : float
        Wavelength (m).  The paper chooses it so that 150 km/h gives 20 Hz, i.e.
        ``wavelength = (150 / 3.6) / 20 = 2.0833`` m.
    n_periods : int
        Number of full periods (the paper uses 10).
    start : float
        Distance at which the irregularity begins (m).
    length : float, optional
        Road length (m); default: irregularity end + 50 m.
    dx : float
        Sample spacing (m), at most ``wavelength / 16``.
    tracks : {'both', 'left', 'right'}
        Which tracks carry the irregularity.
    track_width : float
        Distance between the wheel tracks (m).
    """
    what = "irregularity road"
    if not (math.isfinite(wavelength) and wavelength > 0.0):
        raise InputError(f"{what}: wavelength must be > 0 m, got {wavelength!r}")
    if not math.isfinite(s0):
        raise InputError(f"{what}: s0 must be finite, got {s0!r}")
    if int(n_periods) != n_periods or n_periods < 1:
        raise InputError(f"{what}: n_periods must be a positive integer, got {n_periods!r}")
    if not (math.isfinite(start) and start >= 0.0):
        raise InputError(f"{what}: start must be >= 0 m, got {start!r}")
    end = start + n_periods * wavelength
    length = end + 50.0 if length is None else length
    if length < end:
        raise InputError(f"{what}: length {length:g} m ends before the irregularity "
                         f"({start:g} .. {end:g} m)")
    if dx > wavelength / 16.0:
        raise InputError(f"{what}: dx = {dx:g} m is too coarse for wavelength {wavelength:g} "
                         f"m; use dx <= {wavelength / 16.0:g} m")
    x = np.union1d(_grid(length, dx, what), [start, end])
    x = x[np.concatenate([[True], np.diff(x) > 1e-9 * max(1.0, length)])]
    inside = (x >= start) & (x < end)
    h = np.where(inside, s0 * np.sin(2.0 * np.pi * (x - start) / wavelength), 0.0)
    left, right = _tracks(h, tracks, what)
    return Road(x=x, left=left, right=right, track_width=track_width, name="irregularity",
                source=f"irregularity(s0={s0:g}, wavelength={wavelength:g}, "
                       f"n_periods={n_periods}, start={start:g})")


def isotropic_coherence(n, track_width: float):
    """Coherence ``gamma(n) = x K1(x)``, ``x = 2 pi n B``, of parallel tracks (isotropic road).

    Parameters
    ----------
    n : float or array_like
        Spatial frequency (cycles/m), >= 0.
    track_width : float
        Lateral distance ``B`` between the tracks (m).
    """
    x = 2.0 * np.pi * np.asarray(n, dtype=float) * track_width
    with np.errstate(invalid="ignore", divide="ignore"):
        g = np.where(x > 0.0, x * k1(np.where(x > 0.0, x, 1.0)), 1.0)
    return g[()] if g.ndim == 0 else g


def iso8608_psd(road_class: str, n, *, n_band=ISO8608_BAND,
                what: str = "ISO 8608 road") -> np.ndarray:
    """One-sided displacement PSD ``Gd(n) = Gd(n0) (n / n0)^-2`` (m^3) of class
    ``road_class`` at the spatial frequencies ``n`` (cycles/m); zero outside ``n_band``.

    Raises
    ------
    InputError
        A class that is not one of A..H (the message starts with ``what``).
    """
    key = str(road_class).upper()
    if key not in ISO8608_GD0:
        raise InputError(f"{what}: road class {road_class!r} is not one of A..H")
    n = np.asarray(n, dtype=float)
    inside = (n >= n_band[0]) & (n <= n_band[1]) & (n > 0.0)
    gd = np.zeros(n.shape)
    gd[inside] = ISO8608_GD0[key] * (n[inside] / ISO8608_N0) ** -2.0
    return gd


def checked_coherence(coherence, *, what: str):
    """``coherence`` if it is ``"isotropic"`` or a number in [0, 1] (as a float), else an
    InputError starting with ``what``."""
    if isinstance(coherence, str):
        if coherence == "isotropic":
            return coherence
    elif isinstance(coherence, int | float) and 0.0 <= coherence <= 1.0:
        return float(coherence)
    raise InputError(f"{what}: coherence must be 'isotropic' or a number in [0, 1], got "
                     f"{coherence!r}")


def track_coherence(coherence, n, track_width: float) -> np.ndarray:
    """Coherence ``gamma`` of two tracks ``track_width`` apart at the spatial frequencies
    ``n``: the isotropic model or the constant ``coherence`` (see the module notes)."""
    n = np.asarray(n, dtype=float)
    if coherence == "isotropic":
        return np.asarray(isotropic_coherence(n, track_width), dtype=float)
    return np.full(n.shape, float(coherence))


def iso8608(road_class: str, length: float, dx: float, seed: int, *,
            track_width: float = 1.5, coherence="isotropic",
            n_min: float = ISO8608_BAND[0], n_max: float = ISO8608_BAND[1],
            fade: float = 0.0) -> Road:
    """A random road of ISO 8608 class ``road_class`` (see the module notes).

    Parameters
    ----------
    road_class : str
        One of ``'A'`` .. ``'H'``.
    length : float
        Road length (m); also the period of the profile.
    dx : float
        Sample spacing (m); must resolve ``n_max`` (``dx <= 1 / (2 n_max)``).
    seed : int
        Seed of the phases; the same seed gives the same road.
    track_width : float
        Distance ``B`` between the wheel tracks (m).
    coherence : 'isotropic' or float
        Left/right coherence model (module notes).
    n_min, n_max : float
        Frequency band of the synthesis (cycles/m).
    fade : float
        Length (m) over which the profile is faded in at the start and out at the end with
        a smooth step, so a simulation can start on level ground; 0 = none.  Fading changes
        the spectrum near the ends, so leave it 0 for spectral checks.

    Returns
    -------
    Road
    """
    what = "ISO 8608 road"
    track_width = checked_number(track_width, "track_width", lo=0.0, unit="m")
    key = str(road_class).upper()
    iso8608_psd(key, [], what=what)  # the class, before any work
    x = _grid(length, dx, what)
    if not (0.0 < n_min < n_max):
        raise InputError(f"{what}: need 0 < n_min < n_max, got {n_min!r}, {n_max!r}")
    if n_max > 0.5 / dx * (1.0 + 1e-9):
        raise InputError(f"{what}: dx = {dx:g} m cannot represent n_max = {n_max:g} cycles/m; "
                         f"use dx <= {0.5 / n_max:.4g} m or a lower n_max")
    checked_coherence(coherence, what=what)
    if not (0.0 <= fade <= 0.5 * length):
        raise InputError(f"{what}: fade must be in [0, length/2], got {fade!r}")

    n_fft = x.size - 1                       # samples per period; x[-1] repeats x[0]
    period = n_fft * (x[1] - x[0])
    dn = 1.0 / period
    k = np.arange(n_fft // 2 + 1)
    n = k * dn
    band = (n >= n_min) & (n <= n_max) & (k > 0) & (2 * k != n_fft)
    if not np.any(band):
        raise InputError(f"{what}: no frequency k/L lies in [{n_min:g}, {n_max:g}] "
                         f"cycles/m for length {length:g} m; use a longer road")
    gd = np.where(band, iso8608_psd(key, n, n_band=(n_min, n_max)), 0.0)
    amp = np.sqrt(2.0 * gd * dn)
    rng = np.random.default_rng(seed)
    phase_left = rng.uniform(0.0, 2.0 * np.pi, n.size)
    phase_indep = rng.uniform(0.0, 2.0 * np.pi, n.size)
    gamma = track_coherence(coherence, n, track_width)
    c_left = amp * np.exp(1j * phase_left)
    c_right = gamma * c_left + np.sqrt(1.0 - gamma**2) * amp * np.exp(1j * phase_indep)
    # irfft of (N/2) c_k gives sum_k |c_k| cos(2 pi n_k x + arg c_k)
    left = np.fft.irfft(0.5 * n_fft * c_left, n_fft)
    right = np.fft.irfft(0.5 * n_fft * c_right, n_fft)
    left = np.append(left, left[0])
    right = np.append(right, right[0])
    if fade > 0.0:
        w = _smoothstep(x / fade) * _smoothstep((x[-1] - x) / fade)
        left, right = left * w, right * w
    return Road(x=x, left=left, right=right, track_width=track_width,
                name=f"iso8608_{key}",
                source=f"iso8608(class={key}, length={length:g}, dx={dx:g}, seed={seed}, "
                       f"coherence={coherence})")


def _smoothstep(t):
    """C2 step from 0 (t <= 0) to 1 (t >= 1)."""
    t = np.clip(t, 0.0, 1.0)
    return t**3 * (10.0 - 15.0 * t + 6.0 * t**2)
