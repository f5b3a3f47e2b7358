"""ISO 2631-1:1997 whole-body vibration: frequency weightings Wk and Wd, weighted RMS,
crest factor and vibration dose value (VDV).

The weightings are the standard's filter definitions (ISO 2631-1:1997 Annex A, same
parameters as ISO 8041), a product of

* band limiting: 2nd-order Butterworth high pass at ``f1`` and low pass at ``f2``,
  ``Hh(s) = s^2 / (s^2 + sqrt(2) w1 s + w1^2)``,
  ``Hl(s) = w2^2 / (s^2 + sqrt(2) w2 s + w2^2)``;
* the acceleration-velocity transition
  ``Ht(s) = (1 + s/w3) / (1 + s/(Q4 w4) + s^2/w4^2)``;
* the upward step
  ``Hs(s) = (1 + s/(Q5 w5) + s^2/w5^2) / (1 + s/(Q6 w6) + s^2/w6^2) * (w5/w6)^2``

with ``w = 2 pi f`` and, in Hz:

====  ===  ===  ====  ====  ====  ====  ====  ====
      f1   f2   f3    f4    Q4    f5    Q5    f6 (Q6)
====  ===  ===  ====  ====  ====  ====  ====  ====
Wk    0.4  100  12.5  12.5  0.63  2.37  0.91  3.35 (0.91)
Wd    0.4  100  2.0   2.0   0.63  -     -     -
====  ===  ===  ====  ====  ====  ====  ====  ====

Wk weights vertical (z) and Wd horizontal (x, y) acceleration of a seated person
(health and comfort, ISO 2631-1 Table 1).  :func:`weight` applies the filter in the
frequency domain (exact analog magnitude and phase at every FFT bin, no bilinear-transform
warping near the Nyquist frequency of a 500 Hz output), after zero padding so the circular
convolution does not wrap the end of the record onto its start.
"""

from __future__ import annotations

import math

import numpy as np

from flexpipe.errors import InputError

#: filter parameters (f1, f2, f3, f4, Q4, f5, Q5, f6, Q6); inf = stage absent
PARAMETERS = {
    "Wk": (0.4, 100.0, 12.5, 12.5, 0.63, 2.37, 0.91, 3.35, 0.91),
    "Wd": (0.4, 100.0, 2.0, 2.0, 0.63, math.inf, 1.0, math.inf, 1.0),
}
#: weighting per axis of a seated person (ISO 2631-1 Table 1)
AXIS_WEIGHTING = {"x": "Wd", "y": "Wd", "z": "Wk"}
#: multiplying factors k for health (ISO 2631-1 7.2.3): 1.4 horizontal, 1 vertical
HEALTH_K = {"x": 1.4, "y": 1.4, "z": 1.0}


def response(f, weighting: str) -> np.ndarray:
    """Complex frequency response ``H(j 2 pi f)`` of weighting ``"Wk"`` or ``"Wd"``.

    Parameters
    ----------
    f : array_like
        Frequencies, Hz (>= 0).
    weighting : {"Wk", "Wd"}

    Returns
    -------
    ndarray of complex
    """
    if weighting not in PARAMETERS:
        raise InputError(f"unknown weighting {weighting!r}; valid: {', '.join(PARAMETERS)}",
                         key="weighting")
    f1, f2, f3, f4, q4, f5, q5, f6, q6 = PARAMETERS[weighting]
    s = 2j * np.pi * np.asarray(f, dtype=float)
    w1, w2, w3, w4 = (2 * np.pi * x for x in (f1, f2, f3, f4))
    hh = s**2 / (s**2 + math.sqrt(2.0) * w1 * s + w1**2)
    hl = w2**2 / (s**2 + math.sqrt(2.0) * w2 * s + w2**2)
    ht = (1 + s / w3) / (1 + s / (q4 * w4) + (s / w4) ** 2)
    h = hh * hl * ht
    if math.isfinite(f5):
        w5, w6 = 2 * np.pi * f5, 2 * np.pi * f6
        h = h * (1 + s / (q5 * w5) + (s / w5) ** 2) / (1 + s / (q6 * w6) + (s / w6) ** 2) \
            * (w5 / w6) ** 2
    return h


def weight(a, dt: float, weighting: str) -> np.ndarray:
    """Frequency-weighted acceleration time history.

    Parameters
    ----------
    a : array_like (n,)
        Acceleration samples, m/s^2, uniformly spaced.
    dt : float
        Sample interval, s.
    weighting : {"Wk", "Wd"}

    Returns
    -------
    ndarray (n,)
        ``a_w(t)``, m/s^2.
    """
    a = np.asarray(a, dtype=float)
    if a.ndim != 1 or a.size < 2:
        raise InputError(f"need a 1-D record of at least 2 samples, got shape {a.shape}")
    if not dt > 0:
        raise InputError(f"sample interval must be > 0, got {dt}", key="dt")
    n = a.size
    m = 1 << int(math.ceil(math.log2(2 * n)))
    spec = np.fft.rfft(a, m)
    spec *= response(np.fft.rfftfreq(m, dt), weighting)
    return np.fft.irfft(spec, m)[:n]


def ride_metrics(a, dt: float, weighting: str) -> dict:
    """Weighted RMS ``aw`` (m/s^2), crest factor (peak |a_w| / aw) and
    ``VDV = (int a_w^4 dt)^(1/4)`` (m/s^1.75) of one acceleration record."""
    aw = weight(a, dt, weighting)
    rms = float(np.sqrt(np.mean(aw**2)))
    peak = float(np.abs(aw).max())
    return {"aw": rms, "crest": peak / rms if rms > 0 else float("nan"),
            "vdv": float((np.sum(aw**4) * dt) ** 0.25)}


#: ISO 2631-1:1997 Annex C: comfort reactions to the total vibration value a_v (m/s^2),
#: (from, to, reaction); the standard's ranges overlap
COMFORT_REACTIONS = ((0.0, 0.315, "not uncomfortable"), (0.315, 0.63, "a little uncomfortable"),
                     (0.5, 1.0, "fairly uncomfortable"), (0.8, 1.6, "uncomfortable"),
                     (1.25, 2.5, "very uncomfortable"), (2.0, np.inf, "extremely uncomfortable"))


def comfort_reaction(a_v: float) -> str:
    """ISO 2631-1 Annex C reaction to the total vibration value ``a_v`` (m/s^2); where the
    standard's ranges overlap both are named ("a little uncomfortable / fairly
    uncomfortable")."""
    return " / ".join(name for lo, hi, name in COMFORT_REACTIONS if lo <= a_v < hi)


__all__ = ["AXIS_WEIGHTING", "COMFORT_REACTIONS", "HEALTH_K", "PARAMETERS",
           "comfort_reaction", "response", "ride_metrics", "weight"]
