"""Simulation results: :class:`Result` (named channels, status, message, body motion,
CSV/HDF5/MAT export) and :func:`compare` (rigid-vs-flexible differences)."""

from __future__ import annotations

from dataclasses import dataclass, field, fields
from pathlib import Path
from types import MappingProxyType

import numpy as np

from flexpipe._arrays import readonly
from flexpipe._io import atomic_path, write_matrix_csv
from flexpipe.errors import InputError


@dataclass(frozen=True, eq=False)
class BodyMotion:
    """Pose and elastic modal coordinates of the car body at every output step.

    The arrays are read-only copies of the ones given.

    Attributes
    ----------
    t : ndarray (n,)
        Output times, s.
    q : ndarray (n, m)
        Elastic modal coordinates (float64; ``m = 0`` for a rigid body).
    position : ndarray (n, 3)
        Global position of the body-frame origin (the mesh origin), m.
    rotation : ndarray (n, 3, 3)
        Body-to-global rotation matrices.
    mode_index : ndarray of int (m,)
        The :class:`~flexpipe.flexbody.FlexBody` modes (indices into its
        ``frequencies_hz``) the columns of ``q`` refer to.
    """

    t: np.ndarray
    q: np.ndarray
    position: np.ndarray
    rotation: np.ndarray
    mode_index: np.ndarray

    def __post_init__(self):
        n = len(np.asarray(self.t))
        for name, shape in (("t", (n,)), ("position", (n, 3)), ("rotation", (n, 3, 3))):
            a = readonly(getattr(self, name))
            if a.shape != shape:
                raise ValueError(f"BodyMotion.{name} must have shape {shape}, got {a.shape}")
            object.__setattr__(self, name, a)
        mi = readonly(np.reshape(self.mode_index, -1), dtype=np.int64)
        q = readonly(np.reshape(np.asarray(self.q, dtype=float), (n, mi.size)))
        object.__setattr__(self, "q", q)
        object.__setattr__(self, "mode_index", mi)

    @classmethod
    def from_rows(cls, t, rows, first_mode: int) -> BodyMotion | None:
        """From a run's recorded ``(q, p, R)`` rows at the output times ``t`` (None when
        the rows do not cover them); ``first_mode``: the body's first elastic mode."""
        if not rows or len(rows) != len(t):
            return None
        q = np.array([r[0] for r in rows], dtype=float).reshape(len(t), -1)
        return cls(t=t, q=q, position=np.array([r[1] for r in rows]),
                   rotation=np.array([r[2] for r in rows]),
                   mode_index=np.arange(first_mode, first_mode + q.shape[1]))

    @property
    def n_modes(self) -> int:
        """Number of elastic modal coordinates."""
        return self.q.shape[1]

    def save(self, path, **extra) -> Path:
        """Write to ``path`` (``.npz``) atomically; ``extra`` arrays are stored alongside."""
        path = Path(path)
        with atomic_path(path, suffix=".npz") as tmp, open(tmp, "wb") as fh:
            np.savez(fh, t=self.t, q=self.q, position=self.position, rotation=self.rotation,
                     mode_index=self.mode_index, **extra)
        return path

    @classmethod
    def load(cls, path) -> BodyMotion:
        """Read a file written by :meth:`save`."""
        path = Path(path)
        if not path.is_file():
            raise InputError("body motion file not found", file=path)
        with np.load(path, allow_pickle=False) as d:
            missing = [k for k in ("t", "q", "position", "rotation", "mode_index")
                       if k not in d.files]
            if missing:
                raise InputError(f"not a body motion file: missing {missing}", file=path)
            return cls(d["t"], d["q"], d["position"], d["rotation"], d["mode_index"])


@dataclass(frozen=True, eq=False)
class Result:
    """Outcome of :func:`flexpipe.simulate` (solve_ivp-like).

    A Result is read-only: ``t`` and the channel arrays cannot be written and
    ``channels`` is a read-only mapping (copies of what was given; build a changed result
    with :func:`dataclasses.replace`); ``info`` is a plain dict (a copy), so that it
    dumps to JSON.  :meth:`save` writes it to a file,
    :meth:`load` (:func:`flexpipe.load_result`) reads it back.

    Attributes
    ----------
    t : ndarray (n,)
        Output times, s.
    channels : mapping of str to ndarray (n,)
        Named output channels (see :mod:`flexpipe.vehicle.dynamics` for the list).
    status : int
        0: reached ``t_end``; -1: stopped early (numerical failure or physical limit).
    message : str
        What happened; for a failure the simulated time and the likely cause.
    body : str
        "rigid", "flexible" or "full".
    cpu_time : float
        CPU time of the time integration, s (CPU time of the calling thread, so
        runs in parallel threads do not count each other; excludes model building).
    wall_time : float
        Wall-clock time of the time integration, s.
    simulated_time : float
        Simulated time reached, s.
    info : mapping
        Settings and model facts: step size, modes, band, reduction time, car name...
    motion : BodyMotion or None
        Body pose and elastic modal coordinates at every output step (for stress
        recovery and animation); None when the model did not record them.
    """

    t: np.ndarray
    channels: dict
    status: int
    message: str
    body: str
    cpu_time: float
    wall_time: float
    simulated_time: float
    info: dict = field(default_factory=dict)
    motion: BodyMotion | None = None

    def __post_init__(self):
        t = readonly(self.t)
        if t.ndim != 1:
            raise InputError(f"Result.t must be one-dimensional, got shape {t.shape}", key="t")
        channels = {}
        for name, values in dict(self.channels).items():
            if not isinstance(name, str):
                raise InputError(f"channel names must be str, got {name!r}", key="channels")
            a = readonly(values)
            if a.shape != t.shape:
                raise InputError(f"channel {name!r} has shape {a.shape}; every channel holds "
                                 f"one value per time, shape {t.shape}", key="channels")
            channels[name] = a
        object.__setattr__(self, "t", t)
        object.__setattr__(self, "channels", MappingProxyType(channels))
        # info stays a plain dict (a copy): users json.dump it, which a mapping proxy breaks
        object.__setattr__(self, "info", dict(self.info))

    def __reduce__(self):
        # standard pickle cannot take the read-only mapping proxies: rebuild from plain dicts
        return (type(self), tuple(dict(v) if isinstance(v, MappingProxyType) else v
                                  for v in (getattr(self, f.name) for f in fields(self))))

    @property
    def success(self) -> bool:
        """True when the run reached its end time."""
        return self.status >= 0

    def __getitem__(self, name: str) -> np.ndarray:
        if name == "t":
            return self.t
        if name not in self.channels:
            raise KeyError(f"no channel {name!r}; valid: t, {', '.join(sorted(self.channels))}")
        return self.channels[name]

    @property
    def realtime_factor(self) -> float:
        """Simulated time per CPU second (> 1: faster than real time); with two threads
        (``info["threads"]``) the CPU of both, see :attr:`wall_realtime_factor`."""
        return self.simulated_time / self.cpu_time if self.cpu_time > 0 else float("inf")

    @property
    def wall_realtime_factor(self) -> float:
        """Simulated time per second of wall-clock time of the time integration."""
        return self.simulated_time / self.wall_time if self.wall_time > 0 else float("inf")

    def to_csv(self, path, *, channels=None) -> Path:
        """Write ``t`` and the channels (all, or the names given) to a CSV file atomically.

        The header names the unit of every column (``t [s]``, ``hub_fl_z [N]``); time is
        written with 12 significant digits (1e-8 s at 3600 s), channels with 7.  Any
        suffix is accepted; a ``path`` that cannot be written raises InputError first.
        """
        from flexpipe.vehicle.export import channel_unit, check_output_path

        path = check_output_path(path)
        names = self._names(channels)
        write_matrix_csv(path, ["t [s]"] + [f"{n} [{channel_unit(n)}]" for n in names],
                         np.column_stack([self.t] + [self.channels[n] for n in names]),
                         empty_nonfinite=False)
        return path

    def _names(self, channels):
        if isinstance(channels, str):  # one name: a one-element list, not its letters
            channels = [channels]
        names = list(self.channels) if channels is None else list(channels)
        for n in names:
            if n not in self.channels:
                raise InputError(f"no channel {n!r}; valid: {', '.join(sorted(self.channels))}",
                                 key="channels")
        return names

    def save(self, path, *, format: str | None = None, channels=None) -> Path:  # noqa: A002
        """Write ``t`` and the channels (all, or the names given) to a file atomically.

        Parameters
        ----------
        path : str or Path
            The file; its suffix picks the format: ``.csv``, ``.h5`` / ``.hdf5`` (h5py)
            or ``.mat`` (MATLAB, SciPy).
        format : {"csv", "hdf5", "mat"}, optional
            When given, it must agree with the suffix.
        channels : str or list of str, optional
            Default: every channel.

        Returns
        -------
        Path

        Raises
        ------
        InputError
            ``path`` is not a str or Path, is an existing folder, lies under a file or in
            a folder that cannot be written, has a suffix of no format or of another
            format than ``format``; naming the path.

        Notes
        -----
        HDF5 and MAT files also hold the units, ``status``, ``message``, the run's
        ``info`` and, when recorded, the body motion (``motion/t, q, position, rotation,
        mode_index``); :meth:`load` reads any of the three back.  See
        :mod:`flexpipe.vehicle.export` for the layouts.
        """
        from flexpipe.vehicle.export import save_result

        return save_result(self, path, format=format, channels=channels)

    @classmethod
    def load(cls, path) -> Result:
        """Read a file written by :meth:`save` (see :func:`flexpipe.load_result`)."""
        from flexpipe.vehicle.export import load_result

        return load_result(path)

    def to_dataframe(self, channels=None):
        """The channels as a pandas DataFrame indexed by time (needs pandas installed).

        Column names carry the unit, as in the CSV header (``hub_fl_z [N]``).
        """
        from flexpipe.vehicle.export import to_dataframe

        return to_dataframe(self, self._names(channels))

    def __repr__(self) -> str:
        return (f"Result(body={self.body!r}, status={self.status}, t=0..{self.simulated_time:.3g}"
                f" s, {len(self.channels)} channels, cpu {self.cpu_time:.2f} s, "
                f"message={self.message!r})")


def _aligned(a: Result, b: Result, name: str):
    ta, tb = a.t, b.t
    t_hi = min(ta[-1], tb[-1]) if len(ta) and len(tb) else 0.0
    sel = ta <= t_hi + 1e-12
    xa = a[name][sel]
    xb = np.interp(ta[sel], tb, b[name])
    return ta[sel], xa, xb


def compare(a: Result, b: Result, channels=None, *, t_from: float = 0.0) -> dict:
    """Differences between two runs, channel by channel (``b`` resampled on ``a``'s times).

    Parameters
    ----------
    a, b : Result
    channels : list of str, optional
        Default: the 3 hub-force components of every wheel.
    t_from : float
        Ignore samples before this time (e.g. the settling of the first 0.5 s).

    Returns
    -------
    dict
        ``{channel: {"rms_a", "rms_b", "std_a", "rms_diff", "peak_diff", "rel_rms_diff",
        "rel_rms_diff_dynamic"}}`` where ``rms_diff`` is the RMS of ``a - b``,
        ``peak_diff`` its largest magnitude, ``rel_rms_diff = rms_diff / rms_a`` (relative
        to the whole signal, static load included) and ``rel_rms_diff_dynamic = rms_diff /
        std_a`` (relative to the fluctuating part of ``a``).
    """
    if not isinstance(a, Result) or not isinstance(b, Result):
        raise InputError("compare needs two flexpipe Result objects")
    if channels is None:
        channels = [f"hub_{c}_{k}" for c in ("fl", "fr", "rl", "rr") for k in "xyz"]
    out = {}
    for name in channels:
        t, xa, xb = _aligned(a, b, name)
        sel = t >= t_from
        d = xa[sel] - xb[sel]
        if d.size == 0:
            raise InputError(f"no common samples after t = {t_from} s to compare")
        rms_a = float(np.sqrt(np.mean(xa[sel] ** 2)))
        std_a = float(np.std(xa[sel]))
        rms_d = float(np.sqrt(np.mean(d**2)))
        out[name] = {"rms_a": rms_a, "rms_b": float(np.sqrt(np.mean(xb[sel] ** 2))),
                     "std_a": std_a, "rms_diff": rms_d, "peak_diff": float(np.abs(d).max()),
                     "rel_rms_diff": rms_d / rms_a if rms_a > 0 else float("nan"),
                     "rel_rms_diff_dynamic": rms_d / std_a if std_a > 0 else float("nan")}
    return out
