"""Self-describing result files: channel units, CSV / HDF5 / MATLAB export, DataFrames.

Units follow the channel names of :mod:`flexpipe.vehicle.dynamics` (SI).  HDF5 files
(h5py) hold one dataset per channel with a ``unit`` attribute, ``t`` and, when recorded,
the body motion under ``motion/``.  MATLAB files (:func:`scipy.io.savemat`, level 5) hold
``t``, every channel by its full name as ``channel_names`` (cell array), ``channel_units``
(cell array) and ``channel_data`` (matrix, one row per time, column ``j`` the channel
``channel_names{j}``), and the same channels by name in the structs ``channels`` and
``units``, whose field names may have up to 63 characters (MATLAB 7.6 and later); a
channel whose name MATLAB cannot use as a field (longer, or not a letter followed by
letters, digits and underscores) is only in the cell array and the matrix.
"""

from __future__ import annotations

import json
import re
import warnings
from pathlib import Path

from flexpipe._io import atomic_path
from flexpipe.errors import InputError

FORMATS = ("csv", "hdf5", "mat")
SUFFIX = {"csv": ".csv", "hdf5": ".h5", "mat": ".mat"}

#: a MATLAB struct field name: a letter, then letters, digits, underscores; at most
#: namelengthmax = 63 characters (what savemat(long_field_names=True) writes)
_MATLAB_FIELD = re.compile(r"[A-Za-z][A-Za-z0-9_]{0,62}")

_UNITS = (
    (r"^(x|y|z|x_rear|y_rear|lateral_error)$", "m"),
    (r"^(roll|pitch|yaw|steer|steering_wheel)$", "rad"),
    (r"^speed$", "m/s"),
    (r"^ay$", "m/s^2"),
    (r"^drive_torque$", "N m"),
    (r"^hub_\w+_[xyz]$", "N"),
    (r"^mount_\w+_[xyz]$", "N"),
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


def save_result(result, path, *, format: str = "csv", channels=None) -> Path:  # noqa: A002
    """Write ``result`` to ``path`` as ``csv``, ``hdf5`` or ``mat`` (see module docstring)."""
    fmt = check_format(format)
    path = Path(path)
    if fmt == "csv":
        return result.to_csv(path, channels=channels)
    names = result._names(channels)
    info = json.dumps(result.info, default=str, sort_keys=True)
    if fmt == "hdf5":
        try:
            import h5py
        except ImportError:  # pragma: no cover - h5py is a core dependency
            raise InputError("format 'hdf5' needs h5py (pip install h5py)", key="format") from None
        with atomic_path(path, suffix=".h5") as tmp, h5py.File(tmp, "w") as f:
            f.attrs["info"] = info
            f.attrs["status"] = result.status
            f.attrs["message"] = result.message
            d = f.create_dataset("t", data=result.t)
            d.attrs["unit"] = "s"
            g = f.create_group("channels")
            for n in names:
                d = g.create_dataset(n, data=result.channels[n])
                d.attrs["unit"] = channel_unit(n)
            mo = _motion_arrays(result)
            if mo:
                gm = f.create_group("motion")
                gm.attrs["description"] = (
                    "body-frame origin position (m) and body-to-global rotation, elastic "
                    "modal coordinates q of the FlexBody modes mode_index")
                for k, v in mo.items():
                    gm.create_dataset(k, data=v)
        return path
    from scipy.io import savemat

    data = {"t": result.t, **_mat_channels(result, names, path),
            "info": info, "status": result.status, "message": result.message}
    mo = _motion_arrays(result)
    if mo:
        data["motion"] = mo
    with atomic_path(path, suffix=".mat") as tmp:
        savemat(tmp, data, do_compression=True, long_field_names=True)
    return path


def _mat_channels(result, names, path) -> dict:
    """The MAT variables of the channels ``names`` (see the module docstring)."""
    import numpy as np

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
