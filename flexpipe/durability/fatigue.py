"""Fatigue: rainflow counting (ASTM E1049-85), Basquin S-N curve, Miner's rule.

Rainflow counting uses the ``rainflow`` package (Piotrowski; a small, dependency-free and
widely used implementation of the ASTM E1049-85 four-point algorithm that counts half
cycles exactly as the standard's worked example).  Damage per cycle follows Basquin's
curve ``sigma_a = sigma_f' (2 N)^b`` (stress amplitude ``sigma_a = range / 2``, no
mean-stress correction), optionally cut off below an endurance limit; Miner's rule sums
``n_i / N_i``.

The car file gives the material::

    [body.fatigue]
    sigma_f_Pa = 896e6        # fatigue strength coefficient sigma_f'
    b = -0.12                 # fatigue strength (Basquin) exponent
    endurance_limit_Pa = 0.0  # amplitudes below it do no damage [0]
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError


@dataclass(frozen=True)
class FatigueMaterial:
    """Basquin S-N curve ``sigma_a = sigma_f (2 N)^b`` (SI units).

    Parameters
    ----------
    sigma_f : float
        Fatigue strength coefficient, Pa (> 0).
    b : float
        Basquin exponent (< 0).
    endurance_limit : float
        Amplitudes at or below this do no damage, Pa (default 0: none).
    name : str
    """

    sigma_f: float
    b: float
    endurance_limit: float = 0.0
    name: str = ""

    def __post_init__(self):
        if not (self.sigma_f > 0 and np.isfinite(self.sigma_f)):
            raise InputError(f"sigma_f must be > 0 Pa, got {self.sigma_f}", key="sigma_f_Pa")
        if not (-1.0 < self.b < 0):
            raise InputError(f"Basquin exponent b must lie in (-1, 0), got {self.b}", key="b")
        if not self.endurance_limit >= 0:
            raise InputError("endurance_limit_Pa must be >= 0", key="endurance_limit_Pa")

    def cycles_to_failure(self, amplitude) -> np.ndarray:
        """``N = (sigma_a / sigma_f)^(1/b) / 2``; infinite at or below the endurance limit."""
        a = np.abs(np.asarray(amplitude, dtype=float))
        with np.errstate(divide="ignore"):
            N = 0.5 * (a / self.sigma_f) ** (1.0 / self.b)
        return np.where(a > self.endurance_limit, N, np.inf)


def read_fatigue_table(t):
    """The ``[body.fatigue]`` table of a car file (a :class:`flexpipe.vehicle._toml.Table`)."""
    args = (t.number("sigma_f_Pa", lo=0, lo_open=True, doc="fatigue strength coefficient"),
            t.number("b", lo=-1, hi=0, doc="Basquin exponent (negative)"),
            t.number("endurance_limit_Pa", 0.0, lo=0), t.string("name", ""))
    t.finish()
    try:
        return FatigueMaterial(*args)
    except InputError as exc:
        raise t.error(exc.key, str(exc).split(": ", 1)[-1]) from None


def rainflow_cycles(signal) -> np.ndarray:
    """Rainflow cycles ``(range, mean, count)`` rows of a signal (count 0.5 or 1).

    Uses :func:`rainflow.extract_cycles` (ASTM E1049-85).
    """
    import rainflow

    x = np.asarray(signal, dtype=float).ravel()
    if x.size < 2:
        return np.zeros((0, 3))
    rows = [(r, m, c) for r, m, c, _, _ in rainflow.extract_cycles(x)]
    return np.array(rows, dtype=float).reshape(-1, 3)


def reversals(signal) -> np.ndarray:
    """The turning points of a signal (first and last sample included), vectorised.

    Rainflow counting of the turning points equals that of the signal.
    """
    x = np.asarray(signal, dtype=float).ravel()
    if x.size < 3:
        return x
    d = np.diff(x)
    nz = np.flatnonzero(d)
    if nz.size == 0:
        return x[:1]
    s = np.sign(d[nz])
    turn = nz[1:][s[1:] != s[:-1]]  # index of the sample after which the slope changes
    return np.concatenate([x[:1], x[turn], x[-1:]])


def miner_damage(signal, material: FatigueMaterial) -> float:
    """Miner damage ``sum n_i / N_i`` of a stress signal (Pa) over rainflow cycles."""
    cyc = rainflow_cycles(reversals(signal))
    if not len(cyc):
        return 0.0
    return float(np.sum(cyc[:, 2] / material.cycles_to_failure(0.5 * cyc[:, 0])))


def damage_bound(signal_max, signal_min, n_reversals, material: FatigueMaterial):
    """Upper bound of Miner damage: every half cycle at the largest range (vectorised)."""
    amp = 0.5 * (np.asarray(signal_max) - np.asarray(signal_min))
    return 0.5 * np.asarray(n_reversals) / material.cycles_to_failure(amp)
