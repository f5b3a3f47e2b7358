"""Self-describing result files: channel units, CSV / HDF5 / MATLAB export and import.

Units follow the channel names of :mod:`flexpipe.vehicle.dynamics` (SI).  The format of
a file follows its suffix: ``.csv``, ``.h5`` / ``.hdf5`` or ``.mat``.

* CSV: a header ``t [s],hub_fl_z [N],...``, one row per time (time with 12 significant
  digits, channels with 7); nothing else.
* HDF5 (h5py): ``t``; one dataset per channel in the group ``channels``, in order, with
  the attributes ``unit`` and ``name`` (the full name: a name HDF5 cannot use, e.g. one
  holding ``/``, is stored under another key); the file attributes ``info`` (JSON),
  ``status``, ``message``, ``body``, ``cpu_time``, ``wall_time``, ``simulated_time``;
  when recorded, the body motion under ``motion/``.
* MATLAB (:func:`scipy.io.savemat`, level 5): ``t``, every channel by its full name as
  ``channel_names`` (cell array), ``channel_units`` (cell array) and ``channel_data``
  (matrix, one row per time, column ``j`` the channel ``channel_names{j}``), and the same
  channels by name in the structs ``channels`` and ``units``, whose field names may have
  up to 63 characters (MATLAB 7.6 and later); a channel whose name MATLAB cannot use as a
  field (longer, or not a letter followed by letters, digits and underscores) is only in
  the cell array and the matrix.  Also ``info`` (JSON text), ``status``, ``message``,
  ``body``, ``cpu_time``, ``wall_time``, ``simulated_time`` and the struct ``motion``.

:func:`load_result` reads any of them back into a :class:`~flexpipe.vehicle.result.Result`.
"""

from __future__ import annotations

import json
import os
import re
import warnings
from pathlib import Path

import numpy as np

from flexpipe._io import atomic_path
from flexpipe.errors import InputError

FORMATS = ("csv", "hdf5", "mat")
SUFFIX = {"csv": ".csv", "hdf5": ".h5", "mat": ".mat"}
#: the format of each result-file suffix (compared in lower case)
SUFFIX_FORMAT = {".csv": "csv", ".h5": "hdf5", ".hdf5": "hdf5", ".mat": "mat"}
_VALID_SUFFIXES = ".csv (csv), .h5 or .hdf5 (hdf5), .mat (mat)"

#: a MATLAB struct field name: a letter, then letters, digits, underscores; at most
#: namelengthmax = 63 characters (what savemat(long_field_names=True) writes)
_MATLAB_FIELD = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,62}")

_UNITS = (
    (r"^(x|y|z|x_rear|y_rear|lateral_error)$", "m"),
    (r"^(roll|pitch|yaw|steer|steering_wheel|wheel_angle_\w+)$", "rad"),
    (r"^speed(_target)?$", "m/s"),
    (r"^ay$", "m/s^2"),
    (r"^drive_torque$", "N m"),
    (r"^hub_\w+_[xyz]$", "N"),
    (r"^mount_\w+_[xyz]$", "N"),
    (r"^bushing_\w+_d[xyz]$", "m"),
    (r"^bushing_\w+_r[xyz]$", "rad"),
    (r"^(powertrain|subframe_\w+)_[xyz]$", "m"),
    (r"^(powertrain|subframe_\w+)_r[xyz]$", "rad"),
    (r"^tire_\w+_F[xyz]$", "N"),
    (r"^travel_\w+$", "m"),
    (r"^spin_\w+$", "rad/s"),
    (r"^acc_\w+_[xyz]$", "m/s^2"),
    (r"^hardpoint_\w+_u[xyz]$", "m"),
    (r"^hardpoint_\w+_r[xyz]$", "rad"),
    (r"^(vm|von_mises)_\w+$", "Pa"),
    (r"^(t|time)$", "s"),
)


def channel_unit(name: str) -> str:
    """SI unit of a result channel (``"-"`` when unknown)."""
    for pattern, unit in _UNITS:
        if re.match(pattern, name):
            return unit
    return "-"


def _motion_arrays(result):
    m = result.motion
    if m is None:
        return {}
    return {"t": m.t, "q": m.q, "position": m.position, "rotation": m.rotation,
            "mode_index": m.mode_index}


def check_format(format: str) -> str:  # noqa: A002
    """The result-file format ``format`` names (``h5`` and ``hdf`` read as ``hdf5``).

    Raises
    ------
    InputError
        ``format`` is none of :data:`FORMATS`.
    """
    fmt = str(format).lower()
    if fmt in ("h5", "hdf"):
        fmt = "hdf5"
    if fmt not in FORMATS:
        raise InputError(f"unknown format {format!r}; valid: {', '.join(FORMATS)}", key="format")
    return fmt


def check_output_path(path) -> Path:
    """``path`` as a :class:`~pathlib.Path` once it is known to be writable as a file:
    a str or path-like, not an existing folder, and its first existing ancestor a
    writable folder.

    Raises
    ------
    InputError
        Naming the path and what is wrong with it.
    """
    if not isinstance(path, (str, os.PathLike)) or not isinstance(os.fspath(path), str):
        raise InputError(f"the output path must be a file name (str or pathlib.Path), got "
                         f"{path!r}", key="path")
    if os.fspath(path) == "":
        raise InputError("the output path is empty; give a file name such as 'run.csv'",
                         key="path")
    from flexpipe._io import check_output_file

    return check_output_file(path, option="path")


def result_format(path, format=None) -> str:  # noqa: A002
    """The format of the result file ``path``: its suffix's (:data:`SUFFIX_FORMAT`), which
    ``format``, when given, must agree with.

    Raises
    ------
    InputError
        ``format`` is unknown, the suffix is none of ``.csv .h5 .hdf5 .mat``, or the two
        disagree (naming the path and the valid suffixes).
    """
    fmt = None if format is None else check_format(format)
    path = Path(path)
    by_suffix = SUFFIX_FORMAT.get(path.suffix.lower())
    if by_suffix is None:
        hint = (f"; for format {fmt!r} name it {path.with_suffix(SUFFIX[fmt]).name}"
                if fmt is not None and path.name not in ("", ".", "..") else "")
        raise InputError(f"unknown result-file suffix {path.suffix or '(none)'!r}: the format "
                         f"follows the suffix, one of {_VALID_SUFFIXES}{hint}", file=path)
    if fmt is not None and fmt != by_suffix:
        raise InputError(f"the suffix {path.suffix!r} means format {by_suffix!r} but format="
                         f"{format!r} was given: name the file "
                         f"{path.with_suffix(SUFFIX[fmt]).name} or leave format out (the "
                         f"suffix picks it; valid: {_VALID_SUFFIXES})", file=path, key="format")
    return by_suffix


def save_result(result, path, *, format=None, channels=None) -> Path:  # noqa: A002
    """Write ``result`` to ``path`` as ``csv``, ``hdf5`` or ``mat`` (see module docstring),
    atomically; the format follows the suffix of ``path`` (see :func:`result_format`)."""
    path = check_output_path(path)
    fmt = result_format(path, format)
    if fmt == "csv":
        return result.to_csv(path, channels=channels)
    names = result._names(channels)
    info = json.dumps(dict(result.info), default=str, sort_keys=True)
    meta = {"info": info, "status": int(result.status), "message": str(result.message),
            "body": str(result.body), "cpu_time": float(result.cpu_time),
            "wall_time": float(result.wall_time),
            "simulated_time": float(result.simulated_time)}
    if fmt == "hdf5":
        _write_hdf5(result, path, names, meta)
        return path
    from scipy.io import savemat

    data = {"t": result.t, **_mat_channels(result, names, path), **meta}
    mo = _motion_arrays(result)
    if mo:
        data["motion"] = mo
    with atomic_path(path, suffix=".mat") as tmp:
        savemat(tmp, data, do_compression=True, long_field_names=True)
    return path


def _h5_keys(names) -> list:
    """Dataset keys of the channels ``names``: the name itself, or ``channel_J`` for a name
    HDF5 cannot use (empty, ``.``, holding ``/`` or NUL)."""
    taken = set(names)
    keys = []
    for j, n in enumerate(names):
        if n and n != "." and "/" not in n and "\0" not in n:
            keys.append(n)
            continue
        key = f"channel_{j}"
        while key in taken:
            key += "_"
        taken.add(key)
        keys.append(key)
    return keys


def _write_hdf5(result, path, names, meta) -> None:
    try:
        import h5py
    except ImportError:  # pragma: no cover - h5py is a core dependency
        raise InputError("format 'hdf5' needs h5py (pip install h5py)", key="format") from None
    with atomic_path(path, suffix=".h5") as tmp, h5py.File(tmp, "w") as f:
        f.attrs.update(meta)
        d = f.create_dataset("t", data=result.t)
        d.attrs["unit"] = "s"
        g = f.create_group("channels", track_order=True)
        for n, key in zip(names, _h5_keys(names), strict=True):
            d = g.create_dataset(key, data=result.channels[n])
            d.attrs["unit"] = channel_unit(n)
            d.attrs["name"] = n
        mo = _motion_arrays(result)
        if mo:
            gm = f.create_group("motion")
            gm.attrs["description"] = (
                "body-frame origin position (m) and body-to-global rotation, elastic "
                "modal coordinates q of the FlexBody modes mode_index")
            for k, v in mo.items():
                gm.create_dataset(k, data=v)


def _mat_channels(result, names, path) -> dict:
    """The MAT variables of the channels ``names`` (see the module docstring)."""
    fields = [n for n in names if _MATLAB_FIELD.fullmatch(n)]
    if len(fields) < len(names):
        ok = set(fields)
        other = [n for n in names if n not in ok]
        warnings.warn(f"{path}: channels {other[:3]}{' ...' if len(other) > 3 else ''} are "
                      "not valid MATLAB field names (a letter, then letters, digits, "
                      "underscores; at most 63 characters): they are in channel_names and "
                      "channel_data only, not in the channels and units structs",
                      stacklevel=4)
    cell = np.empty(len(names), dtype=object)  # an object array is written as a cell array
    cell[:] = names
    units = np.empty(len(names), dtype=object)
    units[:] = [channel_unit(n) for n in names]
    matrix = np.column_stack([result.channels[n] for n in names]) if names else \
        np.empty((len(result.t), 0))
    return {"channel_names": cell, "channel_units": units, "channel_data": matrix,
            "channels": {n: result.channels[n] for n in fields},
            "units": {n: channel_unit(n) for n in fields}}


def to_dataframe(result, names):
    """pandas DataFrame of the channels ``names``, index ``t [s]``, unit in column names."""
    try:
        import pandas as pd
    except ImportError:
        raise InputError("Result.to_dataframe needs pandas (pip install pandas)") from None
    df = pd.DataFrame({f"{n} [{channel_unit(n)}]": result.channels[n] for n in names},
                      index=pd.Index(result.t, name="t [s]"))
    return df


# --------------------------------------------------------------------------- reading back
_HDF5_MAGIC = b"\x89HDF\r\n\x1a\n"
_MAT5_MAGIC = b"MATLAB 5.0 MAT-file"
_NOT_RESULT = "not a result file written by Result.save (.csv, .h5, .hdf5 or .mat)"


def load_result(path):
    """Read a result file written by :meth:`Result.save <flexpipe.vehicle.result.Result.save>`.

    Parameters
    ----------
    path : str or Path
        A ``.csv``, ``.h5`` / ``.hdf5`` or ``.mat`` file.  The format is recognised from
        the content, so a file an earlier flexpipe version wrote under another suffix
        (CSV text in a ``.mat`` file) reads too.

    Returns
    -------
    Result
        ``t`` and every saved channel, by its exact name and in the saved order (as
        written: CSV keeps 7 significant digits of a channel and 12 of the time, HDF5 and
        MAT every bit).  HDF5 and MAT files also restore ``status``, ``message``, ``info``
        and the body motion, and (files of this version) ``body``, ``cpu_time``,
        ``wall_time`` and ``simulated_time``.

    Notes
    -----
    Not restored:

    * from a CSV file, everything but ``t`` and the channels: the result has
      ``status = 0``, a ``message`` saying so, ``body = "unknown"``, ``cpu_time`` and
      ``wall_time`` NaN, ``simulated_time`` the last time in the file, ``info = {}`` and
      ``motion = None``;
    * from HDF5/MAT files of earlier versions, ``body`` ("unknown") and the timings (NaN;
      ``simulated_time`` the last time);
    * ``info`` values JSON cannot hold (numpy arrays, paths) come back as their text;
    * units are not part of a Result: they follow the names (:func:`channel_unit`).

    Raises
    ------
    InputError
        The file is missing, a folder, or not a result file (naming the path).
    """
    from flexpipe.vehicle.result import Result

    if not isinstance(path, (str, os.PathLike)):
        raise InputError(f"the result file must be a path (str or pathlib.Path), got {path!r}",
                         key="path")
    path = Path(path)
    if path.is_dir():
        raise InputError(f"is a folder; {_NOT_RESULT}", file=path)
    if not path.is_file():
        raise InputError("result file not found", file=path)
    try:
        with open(path, "rb") as fh:
            head = fh.read(len(_MAT5_MAGIC))
    except OSError as exc:
        raise InputError(f"cannot read it ({exc.strerror})", file=path) from None
    if head.startswith(_HDF5_MAGIC):
        fields = _read_hdf5(path)
    elif head.startswith(_MAT5_MAGIC):
        fields = _read_mat(path)
    else:
        fields = _read_csv(path)
    try:
        return Result(**fields)
    except InputError as exc:  # e.g. a channel of another length than t
        raise InputError(f"{exc.message}: {_NOT_RESULT}", file=path) from None


#: the cure for a result file that cannot be read
_DAMAGED = "it is damaged or cut short; write it again (rerun, or Result.save)"


def _strip_unit(header: str) -> str:
    """``"hub_fl_z [N]"`` -> ``"hub_fl_z"`` (only the last ``" [unit]"``, as written)."""
    name, sep, unit = header.rpartition(" [")
    return name if sep and unit.endswith("]") and "]" not in unit[:-1] else header


def _read_csv(path: Path) -> dict:
    import csv
    import io

    try:
        text = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        raise InputError(f"neither CSV text nor an HDF5 or MAT-file: {_NOT_RESULT}",
                         file=path) from None
    buf = io.StringIO(text)
    header = next(csv.reader(buf), None)
    if not header:
        raise InputError(f"empty file: {_NOT_RESULT}", file=path)
    if _strip_unit(header[0]).strip() not in ("t", "time"):
        raise InputError(f"the CSV header does not start with the time 't [s]': {_NOT_RESULT}",
                         file=path)
    rest = buf.read()
    data = np.empty((0, len(header)))
    if rest.strip():
        try:
            data = np.loadtxt(io.StringIO(rest), delimiter=",", dtype=float, ndmin=2)
        except ValueError as exc:
            raise InputError(f"bad CSV data ({exc}): {_NOT_RESULT}", file=path) from None
    if data.shape[1] != len(header):
        raise InputError(f"the CSV rows have {data.shape[1]} values but the header "
                         f"{len(header)} columns", file=path)
    t = data[:, 0]
    return {"t": t, "channels": {_strip_unit(h): data[:, j] for j, h in enumerate(header)
                                 if j > 0},
            "status": 0, "body": "unknown", "info": {}, "motion": None,
            "message": f"read from the CSV file {path.name}, which holds t and the channels "
                       "only (no status, message, info or body motion)",
            "cpu_time": float("nan"), "wall_time": float("nan"),
            "simulated_time": float(t[-1]) if t.size else 0.0}


def _text(v) -> str:
    """A string attribute (h5py) or MAT char array as ``str``."""
    if isinstance(v, bytes):
        return v.decode("utf-8")
    if isinstance(v, str):
        return v
    a = np.asarray(v)
    if a.dtype.kind == "O":
        return "".join(_text(x) for x in a.ravel())
    return "".join(str(x) for x in a.ravel())


def _scalar(v, kind=float):
    (a,) = np.ravel(v)  # ValueError unless exactly one number
    return kind(a)


def _fields(path, t, channels, meta: dict, motion) -> dict:
    """The Result fields of an HDF5 or MAT file: ``meta`` holds its (raw) attributes."""
    from flexpipe.vehicle.result import BodyMotion

    t = np.ravel(np.asarray(t, dtype=float))
    try:
        info = json.loads(_text(meta["info"])) if "info" in meta else {}
        fields = {
            "t": t, "channels": channels, "info": info if isinstance(info, dict) else {},
            "status": _scalar(meta.get("status", 0), int),
            "message": _text(meta.get("message", "")),
            "body": _text(meta.get("body", "unknown")),
            "cpu_time": _scalar(meta.get("cpu_time", np.nan)),
            "wall_time": _scalar(meta.get("wall_time", np.nan)),
            "simulated_time": _scalar(meta.get("simulated_time",
                                               t[-1] if t.size else 0.0))}
        if motion is not None:
            mt = np.ravel(motion["t"])
            mi = np.ravel(motion["mode_index"]).astype(np.int64)
            n = mt.size
            motion = BodyMotion(t=mt, q=np.reshape(motion["q"], (n, mi.size)),
                                position=np.reshape(motion["position"], (n, 3)),
                                rotation=np.reshape(motion["rotation"], (n, 3, 3)),
                                mode_index=mi)
    except (ValueError, KeyError, TypeError) as exc:
        raise InputError(f"unreadable result metadata ({type(exc).__name__}: {exc}): "
                         f"{_NOT_RESULT}", file=path) from None
    return {**fields, "motion": motion}


def _read_hdf5(path: Path) -> dict:
    import h5py

    try:
        with h5py.File(path, "r") as f:
            if "t" not in f or not isinstance(f.get("channels"), h5py.Group):
                raise InputError(f"an HDF5 file without 't' and 'channels': {_NOT_RESULT}",
                                 file=path)
            t = f["t"][()]
            channels = {_text(ds.attrs.get("name", key)): ds[()]
                        for key, ds in f["channels"].items()}
            meta = dict(f.attrs)
            motion = ({k: v[()] for k, v in f["motion"].items()}
                      if isinstance(f.get("motion"), h5py.Group) else None)
    except OSError as exc:
        raise InputError(f"cannot read the HDF5 file ({exc}): {_DAMAGED}", file=path) from None
    return _fields(path, t, channels, meta, motion)


def _read_mat(path: Path) -> dict:
    from scipy.io import loadmat

    try:
        d = loadmat(path)
    except (ValueError, OSError, TypeError) as exc:
        raise InputError(f"cannot read the MAT-file ({exc}): {_DAMAGED}", file=path) from None
    if "t" not in d:
        raise InputError(f"a MAT-file without 't': {_NOT_RESULT}", file=path)
    n = np.size(d["t"])
    if "channel_names" in d and "channel_data" in d:
        names = [_text(c) for c in np.ravel(d["channel_names"])]
        data = np.asarray(d["channel_data"], dtype=float)
        if data.size != n * len(names):
            raise InputError(f"channel_data holds {data.size} values, not {n} times x "
                             f"{len(names)} channel_names", file=path)
        data = data.reshape(n, len(names))
        channels = {name: data[:, j] for j, name in enumerate(names)}
    elif "channels" in d:  # the struct of a file without the cell array
        s = d["channels"]
        channels = {name: np.ravel(s[name][0, 0]) for name in (s.dtype.names or ())}
    else:
        raise InputError(f"a MAT-file without 'channel_names' and 'channel_data': "
                         f"{_NOT_RESULT}", file=path)
    motion = None
    m = d.get("motion")
    if m is not None and m.dtype.names:
        motion = {k: m[k][0, 0] for k in m.dtype.names}
    meta = {k: v for k, v in d.items() if not k.startswith("__")}
    return _fields(path, d["t"], channels, meta, motion)
