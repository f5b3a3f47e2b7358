"""The output folder of a sweep: one record per finished run, channel files, the table.

Layout (``out/``)::

    runs/<key>.json                  one record per run (parameters, status, metrics)
    channels/run=<key>/part-0.parquet  t and every channel of the run (SI units: field
                                     metadata ``unit``; schema metadata ``units``)
    metrics.parquet, metrics.csv     the table of the sweep's runs, in run order
    plots/*.png                      chosen metrics against the swept parameters
    sweep.json                       what ran: spec, counts, reductions, timing
    .flexpipe-sweep                  marker: this folder is a sweep's output

The marker is written before the first run, so a sweep interrupted before ``sweep.json``
is written is still recognised: :func:`check_sweep_folder` lets a sweep write only into an
absent or empty folder or a previous sweep's, never into a folder of the user's files.

Every file is written atomically (temporary name, then rename) and a run's channels are
written before its record, so a record on disk means the run is complete: a rerun skips
it, and killing anything at any moment loses no finished run.  The channel folder is a
Hive-partitioned Parquet dataset: ``pandas.read_parquet(out / "channels")`` or
``dask.dataframe.read_parquet`` return every run with a ``run`` column.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from flexpipe._io import atomic_path, write_text_atomic
from flexpipe.sweeps.tasks import STATUS_LOST

MARKER = ".flexpipe-sweep"
_OWN = {"runs", "channels", "plots", "metrics.parquet", "metrics.csv", "sweep.json", MARKER}


def check_sweep_folder(out, *, option: str = "--out") -> Path:
    """Check, before any work, that a sweep may write into ``out``.

    ``out`` must be absent, an empty folder, or a previous sweep's output folder (it holds
    the :data:`MARKER` file or ``sweep.json``, or only a sweep's files and ``runs/``), and
    be creatable (:func:`flexpipe._io.check_output_folder`).

    Parameters
    ----------
    out : str or Path
        The sweep's output folder.
    option : str
        The option or key that gave it, named in the error.

    Returns
    -------
    Path

    Raises
    ------
    InputError
        ``out`` is a file, a folder holding other files (a run folder, the user's data),
        or cannot be created.
    """
    from flexpipe._io import check_output_folder
    from flexpipe.errors import InputError

    out = check_output_folder(out, option=option)
    if not out.is_dir():
        return out
    entries = {e.name for e in out.iterdir()}
    if not entries or MARKER in entries or "sweep.json" in entries:
        return out
    if "runs" in entries and entries <= _OWN and (out / "runs").is_dir():
        return out
    names = sorted(entries)
    shown = ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")
    what = "a flexpipe run folder" if "summary.json" in entries else "not a sweep's output"
    raise InputError(f"the folder holds other files ({shown}): {what} (no {MARKER} or "
                     f"sweep.json); a sweep writes metrics.csv, runs/, channels/ and plots/ "
                     f"there and would overwrite or mix with them: choose a new or empty "
                     f"folder as {option}, or a previous sweep's", file=out, key=option)


def _plain(v):
    if isinstance(v, np.generic):
        v = v.item()
    if isinstance(v, float) and not math.isfinite(v):
        return None
    return v



def _channel_table(pa, channels: dict):
    """Arrow table of a run's channels; every field carries its SI unit (field metadata
    ``unit``, as :func:`flexpipe.vehicle.export.channel_unit` names it: the channel
    files' headers) and the schema maps every name to its unit (metadata ``units``, JSON).
    """
    from flexpipe.vehicle.export import channel_unit

    units = {k: channel_unit(k) for k in channels}
    fields = [pa.field(k, pa.float64(), metadata={"unit": units[k]}) for k in channels]
    schema = pa.schema(fields, metadata={"units": json.dumps(units)})
    return pa.table({k: np.asarray(v, dtype=float) for k, v in channels.items()},
                    schema=schema)

class Store:
    """Records and channels of the runs of a sweep under ``out``."""

    def __init__(self, out):
        self.out = Path(out)
        self.runs_dir = self.out / "runs"
        self.channels_dir = self.out / "channels"

    def mark(self) -> None:
        """Create the folder and its :data:`MARKER` file (before the first run)."""
        self.out.mkdir(parents=True, exist_ok=True)
        marker = self.out / MARKER
        if not marker.exists():
            write_text_atomic(marker, "flexpipe sweep output folder\n")

    def record_path(self, key: str) -> Path:
        """File of the record of run ``key``."""
        return self.runs_dir / f"{key}.json"

    def channels_path(self, key: str) -> Path:
        """Channel file of run ``key``."""
        return self.channels_dir / f"run={key}" / "part-0.parquet"

    def finished(self, *, retry_failed: bool = False) -> dict:
        """``{key: record}`` of the runs on disk that a rerun skips.

        Lost runs (their worker died too often) are always run again; failed runs too when
        ``retry_failed``.
        """
        out = {}
        if not self.runs_dir.is_dir():
            return out
        for f in self.runs_dir.glob("*.json"):
            try:
                rec = json.loads(f.read_text())
            except (OSError, ValueError):
                continue  # unreadable: run it again
            if rec.get("status") == STATUS_LOST or (retry_failed and rec.get("status", 0) < 0):
                continue
            out[rec["key"]] = rec
        return out

    def write(self, record: dict, channels) -> None:
        """Store one run: channels first (if any), then the record."""
        import pyarrow as pa
        import pyarrow.parquet as pq

        key = record["key"]
        if channels is not None and len(channels.get("t", ())) > 0:
            table = _channel_table(pa, channels)
            path = self.channels_path(key)
            with atomic_path(path) as tmp:
                pq.write_table(table, tmp)
        rec = {k: _plain(v) for k, v in record.items()}
        write_text_atomic(self.record_path(key), json.dumps(rec, indent=1, sort_keys=True))

    def table(self, keys):
        """DataFrame of the records of ``keys`` (in that order) with units in the names."""
        import pandas as pd

        rows = []
        for k in keys:
            p = self.record_path(k)
            if p.is_file():
                rows.append(json.loads(p.read_text()))
        df = pd.DataFrame(rows)
        if not df.empty:
            df = df.sort_values("index", kind="stable").reset_index(drop=True)
        return df

    def write_table(self, df) -> tuple[Path, Path]:
        """``metrics.parquet`` and ``metrics.csv``, atomically."""
        pq_path, csv_path = self.out / "metrics.parquet", self.out / "metrics.csv"
        with atomic_path(pq_path) as tmp:
            df.to_parquet(tmp, index=False)
        with atomic_path(csv_path) as tmp:
            df.to_csv(tmp, index=False)
        return pq_path, csv_path


__all__ = ["MARKER", "Store", "check_sweep_folder"]
