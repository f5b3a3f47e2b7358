"""Self-describing result files: channel units, CSV / HDF5 / MATLAB export, DataFrames.

Units follow the channel names of :mod:`flexpipe.vehicle.dynamics` (SI).  HDF5 files
(h5py) hold one dataset per channel with a ``unit`` attribute, ``t`` and, when recorded,
the body motion under ``motion/``; MATLAB files (:func:`scipy.io.savemat`) hold a struct
``channels``, a struct ``units`` and ``t``.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

from flexpipe._io import atomic_path
from flexpipe.errors import InputError

FORMATS = ("csv", "hdf5", "mat")
SUFFIX = {"csv": ".csv", "hdf5": ".h5", "mat": ".mat"}

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


def save_result(result, path, *, format: str = "csv", channels=None) -> Path:  # noqa: A002
    """Write ``result`` to ``path`` as ``csv``, ``hdf5`` or ``mat`` (see module docstring)."""
    fmt = str(format).lower()
    if fmt in ("h5", "hdf"):
        fmt = "hdf5"
    if fmt not in FORMATS:
        raise InputError(f"unknown format {format!r}; valid: {', '.join(FORMATS)}", key="format")
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

    data = {"t": result.t,
            "channels": {n: result.channels[n] for n in names},
            "units": {n: channel_unit(n) for n in names},
            "info": info, "status": result.status, "message": result.message}
    mo = _motion_arrays(result)
    if mo:
        data["motion"] = mo
    with atomic_path(path, suffix=".mat") as tmp:
        savemat(tmp, data, do_compression=True)
    return path


def to_dataframe(result, names):
    """pandas DataFrame of the channels ``names``, index ``t [s]``, unit in column names."""
    try:
        import pandas as pd
    except ImportError:
        raise InputError("Result.to_dataframe needs pandas (pip install pandas)") from None
    df = pd.DataFrame({f"{n} [{channel_unit(n)}]": result.channels[n] for n in names},
                      index=pd.Index(result.t, name="t [s]"))
    return df
