"""OpenCRG data blocks: formatted text and big-endian binary rows, NaN borders.

Used by :func:`flexpipe.roads.crg.read_crg`; every error names the file and, for text
data, the line.
"""

from __future__ import annotations

import math

import numpy as np

from flexpipe.errors import InputError


def parse_text_values(raw: bytes, fmt: str, n_ch: int, n_u: int | None, first_line: int,
                      path):
    """Values of a formatted data block, shape (n_u, n_ch), and each row's first line;
    ``n_u`` None reads every row the block holds (a row left incomplete at its end is an
    error)."""
    width = 10 if fmt[1] == "R" else 20
    lines = raw.decode("latin-1").splitlines()
    values, rows_line, row = [], [], []
    per_line = 80 // width
    for offset, text in enumerate(lines):
        k = first_line + offset
        fields = [text[i:i + width] for i in range(0, min(len(text), per_line * width), width)]
        if fmt[0] == "K":
            while fields and not fields[-1].strip():
                fields.pop()
        for f in fields:
            if fmt[0] == "L" and len(row) == n_ch:
                break
            s = f.strip()
            if s.startswith("*"):
                v = math.nan
            else:
                try:
                    v = float(s.replace("D", "E").replace("d", "e"))
                except ValueError:
                    v = math.nan
                if not math.isfinite(v):
                    raise InputError(f"data value {f!r} is not a finite number (fields are "
                                     f"{width} characters wide in format {fmt}; a missing "
                                     "value starts with '*')", file=path, line=k)
            if not row:
                rows_line.append(k)
            row.append(v)
            if len(row) == n_ch:
                values.append(row)
                row = []
                if len(values) == n_u:
                    return np.array(values), np.array(rows_line)
        if fmt[0] == "L" and row and len(row) < n_ch and len(fields) < per_line:
            raise InputError(f"data row has {len(row)} values, expected {n_ch}", file=path,
                             line=k)
    if n_u is None:
        if row:
            raise InputError(f"the data block ends inside a row: its last row has {len(row)} "
                             f"of {n_ch} values (truncated file?)", file=path,
                             line=rows_line[-1])
        return np.array(values).reshape(-1, n_ch), np.array(rows_line[:len(values)])
    raise InputError(f"data block holds {len(values)} complete rows, expected {n_u} "
                     f"(from REFERENCE_LINE_START_U/END_U/INCREMENT)", file=path)


def parse_binary_values(raw: bytes, fmt: str, n_ch: int, n_u: int | None, path):
    """Values of a binary data block, shape (n_u, n_ch); ``n_u`` None reads every row the
    block holds, less the all-NaN rows that pad its last 80-byte record (as OpenCRG)."""
    dtype = np.dtype(">f4") if fmt[1] == "R" else np.dtype(">f8")
    row_bytes = n_ch * dtype.itemsize
    if fmt[0] == "L":
        row_bytes = -(-row_bytes // 80) * 80
    if n_u is None:
        n_u = len(raw) // row_bytes
        if len(raw) % 80 == 0:
            vals = parse_binary_values(raw, fmt, n_ch, n_u, path)
            while n_u > 0 and np.all(np.isnan(vals[n_u - 1])):
                n_u -= 1
            return vals[:n_u]
    need = row_bytes * n_u
    if len(raw) % 80:
        raise InputError(f"binary data block has {len(raw)} bytes, not a whole number of "
                         f"80-byte records (truncated file?); {n_u} rows x {n_ch} channels in "
                         f"format {fmt} need {need} bytes padded to {-(-need // 80) * 80}",
                         file=path)
    if len(raw) < need:
        raise InputError(f"binary data block has {len(raw)} bytes, expected at least {need} "
                         f"({n_u} rows x {n_ch} channels, format {fmt})", file=path)
    if fmt[0] == "K":
        vals = np.frombuffer(raw, dtype=dtype, count=n_u * n_ch).reshape(n_u, n_ch)
    else:
        per_row = row_bytes // dtype.itemsize
        vals = np.frombuffer(raw, dtype=dtype, count=n_u * per_row).reshape(n_u, per_row)
        vals = vals[:, :n_ch]
    return vals.astype(float)


def reject_text_as_binary(data: bytes, fmt: str, first_line: int, path):
    """A binary format whose data block is plain text would read as ~1e-10 m garbage."""
    head = data[:4096]
    if not head:
        return
    text = sum(32 <= b < 127 or b in (9, 10, 13) for b in head)
    if text == len(head) and any(ch in head for ch in b"0123456789") and b"\n" in head:
        raise InputError(f"$KD_DEFINITION declares the binary format {fmt} but the data "
                         f"block is text; for text data use {'L' + fmt[1] + 'FI'} (or "
                         f"{'K' + fmt[1] + 'FI'})", file=path, line=first_line)


def fill_border_nans(z, u, row_line, path, *, mode: int = 2, offset: float = 0.0):
    """The grid ``z`` (n_u, n_v) with its NaNs filled by OpenCRG's ``GRID_NAN_MODE``:
    2, a NaN at a border of a cross section takes the last valid value plus ``offset``
    (NaNs between valid values, or a cross section without any, are errors); 1, every NaN
    becomes ``offset``; 0, NaNs are an error (a car needs a height everywhere)."""
    if np.isinf(z).any():
        i, j = np.argwhere(np.isinf(z))[0]
        raise InputError(f"cross section at u = {u[i]:g} m (row {i + 1}), long section "
                         f"{j + 1} holds {z[i, j]}; heights must be finite (NaN marks a "
                         "missing value)", file=path,
                         line=None if row_line is None else int(row_line[i]))
    bad = ~np.isfinite(z)
    if not bad.any():
        return z
    if mode == 0:
        i, j = np.argwhere(bad)[0]
        raise InputError(f"cross section at u = {u[i]:g} m (row {i + 1}), long section "
                         f"{j + 1} is NaN and GRID_NAN_MODE = 0 keeps it: a car needs a "
                         "height everywhere; use GRID_NAN_MODE 1 (NaN -> GRID_NAN_OFFSET) "
                         "or 2 (the last valid value)", file=path,
                         line=None if row_line is None else int(row_line[i]))
    z = z.copy()
    if mode == 1:
        z[bad] = offset
        return z
    for i in np.flatnonzero(bad.any(axis=1)):
        good = np.flatnonzero(~bad[i])
        where = dict(file=path, line=None if row_line is None else int(row_line[i]))
        if good.size == 0:
            raise InputError(f"cross section at u = {u[i]:g} m (row {i + 1}) has no valid "
                             "height; every cross section needs at least one", **where)
        lo, hi = good[0], good[-1]
        if hi - lo + 1 != good.size:
            raise InputError(f"cross section at u = {u[i]:g} m (row {i + 1}) has a NaN "
                             "between valid heights; NaN is only allowed at the borders",
                             **where)
        z[i, :lo] = z[i, lo] + offset
        z[i, hi + 1:] = z[i, hi] + offset
    return z
