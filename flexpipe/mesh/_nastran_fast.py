"""Vectorized parsing of the cards that make up most of a body deck (GRID, CQUAD4,
CTRIA3) when they are written in plain small-field format.

:func:`flexpipe.mesh._bulk.read_cards` keeps such lines as text; here they are cut into
8-character fields with one NumPy view and converted column by column.  Anything the
fast path cannot convert exactly (blank or non-integer ids, Nastran's implied-exponent
reals such as ``1.5-3``) makes it return ``None`` and the reader parses those lines card
by card instead, with the usual located error messages.
"""

from __future__ import annotations

import warnings

import numpy as np

BLANK = b" " * 8


def _fields(lines: list[str], n: int) -> np.ndarray:
    """Data fields 2..n+1 of small-field lines as an (len, n) array of 8-byte strings."""
    w = 8 * (n + 1)
    buf = "".join([ln[:w].ljust(w) for ln in lines]).encode("latin-1")
    return np.frombuffer(buf, dtype="S8").reshape(len(lines), n + 1)[:, 1:]


def _num(col: np.ndarray, dtype, default) -> np.ndarray:
    """Column(s) of fields as numbers, blank = ``default``; raises ValueError if bad.

    The fields are parsed by one C-level ``np.fromstring`` over space-separated text when
    that is exact: plain decimal integers, or reals without Nastran's implied exponent
    (``1.5-3``) or ``D`` exponents; otherwise by ``astype`` (which rejects those).
    """
    col = np.ascontiguousarray(col)
    shape = col.shape
    b = col.view(np.uint8).reshape(shape + (8,)).copy()
    blank = (b == 32).all(axis=-1)
    if blank.any():
        d = str(default).encode()
        b[blank] = np.frombuffer(d.rjust(8), dtype=np.uint8)
    integer = np.dtype(dtype).kind == "i"
    digit = (b >= 48) & (b <= 57)
    sign = (b == 43) | (b == 45)
    bad = (b == 46) if integer else (b == 68) | (b == 100)      # '.' in ints; D exponents
    implied = sign[..., 1:] & (digit[..., :-1] | (b[..., :-1] == 46))
    if not bad.any() and not implied.any():
        buf = np.full(shape + (9,), 32, dtype=np.uint8)
        buf[..., :8] = b
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            try:
                v = np.fromstring(buf.tobytes(), dtype=dtype, sep=" ")
            except ValueError:
                v = np.zeros(0)
        if v.size == int(np.prod(shape)):
            return v.reshape(shape)
    return b.view("S8").reshape(shape).astype(dtype)


def grids(lines: list[str], seq) -> dict | None:
    """``gid, cp, X, cd, has_ps, seq`` of GRID lines, or None when not exactly parsable."""
    if not lines:
        return {"gid": np.zeros(0, np.int64), "cp": np.zeros(0, np.int64),
                "X": np.zeros((0, 3)), "cd": np.zeros(0, np.int64),
                "has_ps": np.zeros(0, bool), "seq": np.zeros(0, np.int64)}
    A = _fields(lines, 7)
    try:
        gid = _num(A[:, 0], np.int64, "x")
        cp = _num(A[:, 1], np.int64, 0)
        X = _num(A[:, 2:5], float, 0.0)
        cd = _num(A[:, 5], np.int64, 0)
    except ValueError:
        return None
    return {"gid": gid, "cp": cp, "X": X, "cd": cd, "has_ps": A[:, 6] != BLANK,
            "seq": np.asarray(seq, dtype=np.int64)}


def shells(lines: list[str], seq, nodes: int) -> dict | None:
    """``eid, pid, g, zoffs, seq`` of CQUAD4 (4) / CTRIA3 (3) lines, or None."""
    if not lines:
        return None
    A = _fields(lines, nodes + 4)
    try:
        eid = _num(A[:, 0], np.int64, "x")
        pid = np.where(A[:, 1] == BLANK, eid, _num(A[:, 1], np.int64, 0))
        g = _num(A[:, 2:2 + nodes], np.int64, 0)
        z = _num(A[:, 3 + nodes], float, 0.0)
    except ValueError:
        return None
    if (g == 0).any():
        return None
    return {"eid": eid, "pid": pid, "g": g, "zoffs": z, "theta": A[:, 2 + nodes],
            "seq": np.asarray(seq, np.int64)}


class Lazy:
    """A read-only sequence whose items are built on access (cards for messages)."""

    def __init__(self, fn, n: int):
        self.fn, self.n = fn, n

    def __getitem__(self, i):
        return self.fn(int(i))

    def __len__(self):
        return self.n
