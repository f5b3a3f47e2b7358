"""Seats: the acceleration at the seat surface, from the floor's.

ISO 2631-1 measures whole-body vibration where the occupant sits, on the seat cushion, and
a car's floor vibration reaches the occupant through the seat.  A seat here is the
occupant on the cushion as one vertical degree of freedom on the floor point it is
mounted at (``[body.seats.<name>]`` in the car file, docs/car-file.md): natural frequency
``f_n`` and damping ratio ``zeta``, the model behind a conventional car seat's
transmissibility (a resonance near 4 Hz, attenuation above about 6 Hz).  Its absolute
acceleration answers the floor's through the base-excitation transmissibility

    T(s) = (2 zeta w s + w^2) / (s^2 + 2 zeta w s + w^2),   w = 2 pi f_n,

applied to the recorded floor acceleration after the run (one-way coupling: the
occupant's mass is in the body's masses, the seat's dynamics do not load the floor).
Fore-aft and lateral pass unchanged (a seat rigid in its plane) unless the seat pan's own
resonance is given for that axis, which then acts the same way.  The run's channels
``acc_<seat>_x|y|z`` then enter the ride summary like a body point's, and the seat's
SEAT value (seat effective amplitude transmissibility, the seat's Wk-weighted vertical RMS
over the floor's, in %) is reported with it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


def _sdof_transmissibility(f_hz, fn: float, zeta: float) -> np.ndarray:
    """Base excitation of a mass on a spring and damper: absolute over base acceleration."""
    s = 2j * np.pi * np.asarray(f_hz, dtype=float)
    w = 2 * np.pi * fn
    c = 2 * zeta * w
    return (c * s + w * w) / (s * s + c * s + w * w)


def _sdof_response(t, a, fn: float, zeta: float) -> np.ndarray:
    """The mass's acceleration for the base's ``a`` at the uniform times ``t``, starting at
    rest: ``z'' + 2 zeta w z' + w^2 z = -a`` for the relative motion ``z``, the mass's
    acceleration ``a + z'' = -(2 zeta w z' + w^2 z)``; SciPy's :func:`~scipy.signal.lsim`
    integrates it exactly for an input linear between samples."""
    from scipy.signal import lsim

    if len(t) < 2:  # at rest on the floor: the cushion has not yet passed anything
        return np.zeros_like(a)
    w = 2 * np.pi * fn
    c = 2 * zeta * w
    system = (np.array([[0.0, 1.0], [-w * w, -c]]), np.array([[0.0], [-1.0]]),
              np.array([[-w * w, -c]]), np.zeros((1, 1)))
    _, y, _ = lsim(system, a, t - t[0], X0=np.zeros(2))
    return np.asarray(y, dtype=float).reshape(-1)


@dataclass(frozen=True)
class Seat:
    """A seat on a named floor point.

    Parameters
    ----------
    name : str
        The seat's name (its channels are ``acc_<name>_x|y|z``).
    floor_point : str
        The ``[body.points]`` entry the seat is mounted at.
    natural_frequency_hz : float
        Vertical resonance of the occupant on the cushion (Hz).
    damping_ratio : float
        Its damping ratio.
    fore_aft, lateral : (float, float), optional
        Natural frequency (Hz) and damping ratio of the seat pan's own fore-aft or
        lateral resonance; None: that axis is the floor's (a seat rigid in it).
    """

    name: str
    floor_point: str
    natural_frequency_hz: float
    damping_ratio: float
    fore_aft: tuple | None = None
    lateral: tuple | None = None

    def mode(self, axis: str):
        """``(f_n, zeta)`` of an axis (``"x"``, ``"y"``, ``"z"``), or None (rigid)."""
        if axis == "z":
            return self.natural_frequency_hz, self.damping_ratio
        return self.fore_aft if axis == "x" else self.lateral

    def transmissibility(self, f_hz, axis: str = "z") -> np.ndarray:
        """``T(j 2 pi f)``, complex: seat over floor acceleration along ``axis``."""
        m = self.mode(axis)
        if m is None:
            return np.ones(np.shape(f_hz), dtype=complex)
        return _sdof_transmissibility(f_hz, *m)

    def acceleration(self, t: np.ndarray, a_floor: np.ndarray, axis: str = "z") -> np.ndarray:
        """The seat's acceleration along ``axis`` for the floor's ``a_floor`` at the
        uniform times ``t``, the occupant starting at rest on the floor."""
        a = np.asarray(a_floor, dtype=float)
        m = self.mode(axis)
        return a.copy() if m is None else _sdof_response(np.asarray(t, dtype=float), a, *m)

    def describe(self) -> str:
        """One line for ``flexpipe info``."""
        extra = "".join(f"; {key.replace('_', '-')} {m[0]:g} Hz, {m[1]:g}"
                        for key, m in (("fore_aft", self.fore_aft), ("lateral", self.lateral))
                        if m is not None)
        return (f"seat {self.name} on {self.floor_point}: {self.natural_frequency_hz:g} Hz, "
                f"damping ratio {self.damping_ratio:g}{extra}")


def read_seats(table, points: dict) -> tuple[Seat, ...]:
    """The ``[body.seats]`` sub-tables of a body table reader ``table`` (named floor
    points ``points``); every error names the file, line and key."""
    if not table.has("seats"):
        return ()
    st = table.sub("seats")
    seats = []
    for name in list(st.data):
        s = st.sub(name)
        floor = s.string("floor_point", doc="a [body.points] name: where the seat stands")
        if floor not in points:
            raise s.error("floor_point", f"'{floor}' is not a [body.points] name; valid: "
                                         f"{sorted(points) or 'none defined'}")
        if name in points:
            raise s.error(None, f"the seat name '{name}' is also a [body.points] name; "
                                "their channels acc_<name>_x|y|z would clash: rename one")
        fn = s.number("natural_frequency_hz", lo=0.5, hi=20.0,
                      doc="vertical seat-occupant resonance (car seats: about 4 Hz)")
        zeta = s.number("damping_ratio", lo=0.0, hi=2.0, lo_open=True)
        in_plane = {}
        for key in ("fore_aft", "lateral"):
            f_key, z_key = f"{key}_frequency_hz", f"{key}_damping_ratio"
            if s.has(f_key) != s.has(z_key):
                raise s.error(f_key if s.has(f_key) else z_key,
                              f"give both {f_key} and {z_key} (the seat pan's own {key} "
                              "resonance), or neither (that axis is the floor's)")
            if s.has(f_key):
                in_plane[key] = (s.number(f_key, lo=0.5, hi=20.0),
                                 s.number(z_key, lo=0.0, hi=2.0, lo_open=True))
        s.finish()
        seats.append(Seat(name, floor, fn, zeta, **in_plane))
    st.finish()
    return tuple(seats)


def seat_channels(seats, t, channels: dict) -> dict:
    """``acc_<seat>_x|y|z`` of each seat from its floor point's channels (a seat whose
    floor point has no channels gets none); a failed run's NaN tail stays NaN."""
    out = {}
    for seat in seats:
        key = f"acc_{seat.floor_point}_"
        if key + "z" not in channels:
            continue
        for axis in "xyz":
            a = np.asarray(channels[key + axis], dtype=float)
            ok = np.isfinite(a)
            y = np.full_like(a, np.nan)
            n = int(np.argmin(ok)) if not ok.all() else len(a)  # up to a failed run's end
            y[:n] = seat.acceleration(np.asarray(t)[:n], a[:n], axis)
            out[f"acc_{seat.name}_{axis}"] = y
    return out


def seat_value(aw_seat_z: float, aw_floor_z: float) -> float:
    """SEAT value (%): the seat's weighted vertical RMS over the floor's."""
    ok = aw_floor_z > 0  # False for NaN too (a run too short for its metrics)
    return float(100.0 * aw_seat_z / aw_floor_z) if ok else math.nan


def with_seats(modes, f_hz, *responses):
    """A linear model's outputs and frequency responses ``(len(f_hz), outputs)`` extended
    by each seat's ``acc_<seat>_x|y|z`` (its floor point's times
    :meth:`Seat.transmissibility`); ``modes.info["seats"]`` lists the car's seats as
    the fields of :class:`Seat`."""
    outputs = list(modes.outputs)
    extra = []  # (name, column of the floor's output, factor)
    for fields in modes.info.get("seats", ()):
        seat = Seat(**fields)
        if f"acc_{seat.floor_point}_z" not in outputs:
            continue
        extra += [(f"acc_{seat.name}_{ax}", outputs.index(f"acc_{seat.floor_point}_{ax}"),
                   seat.transmissibility(f_hz, ax)) for ax in "xyz"]
    if not extra:
        return (tuple(outputs), *responses)
    out = [np.concatenate([H, np.stack([H[:, j] * c for _, j, c in extra], axis=1)], axis=1)
           for H in responses]
    return (tuple(outputs + [n for n, _, _ in extra]), *out)
