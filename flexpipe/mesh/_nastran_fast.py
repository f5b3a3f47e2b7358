"""Vectorized parsing of the cards that make up most of a body deck (GRID, CQUAD4,
CTRIA3) when they are written in plain small-field format.

:func:`flexpipe.mesh._bulk.read_cards` keeps such lines as text; here they are cut into
8-character fields with one NumPy view and converted column by column.  Anything the
fast path cannot convert exactly (blank or non-integer ids, Nastran's implied-exponent
reals such as ``1.5-3``) makes it return ``None`` and the reader parses those lines card
by card instead, with the usual located error messages.
"""

from __future__ import annotations

import numpy as np

BLANK = b" " * 8


def _fields(lines: list[str], n: int) -> np.ndarray:
    """Data fields 2..n+1 of small-field lines as an (len, n) array of 8-byte strings."""
    w = 8 * (n + 1)
    buf = "".join([ln[:w].ljust(w) for ln in lines]).encode("latin-1")
    return np.frombuffer(buf, dtype="S8").reshape(len(lines), n + 1)[:, 1:]


def _num(col: np.ndarray, dtype, default) -> np.ndarray:
    """Column(s) of fields as numbers, blank = ``default``; raises ValueError if bad."""
    col = np.where(col == BLANK, str(default).encode(), col)
    return col.astype(dtype)


def grids(lines: list[str], seq) -> dict | None:
    """``gid, cp, X, cd, has_ps, seq`` of GRID lines, or None when not exactly parsable."""
    if not lines:
        return {"gid": np.zeros(0, np.int64), "cp": np.zeros(0, np.int64),
                "X": np.zeros((0, 3)), "cd": np.zeros(0, np.int64),
                "has_ps": np.zeros(0, bool), "seq": np.zeros(0, np.int64)}
    A = _fields(lines, 7)
    try:
        gid = A[:, 0].astype(np.int64)
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
        eid = A[:, 0].astype(np.int64)
        pid = np.where(A[:, 1] == BLANK, eid, _num(A[:, 1], np.int64, 0))
        g = A[:, 2:2 + nodes].astype(np.int64)
        z = _num(A[:, 3 + nodes], float, 0.0)
    except ValueError:
        return None
    if (g == 0).any():
        return None
    return {"eid": eid, "pid": pid, "g": g, "zoffs": z, "seq": np.asarray(seq, np.int64)}


class Lazy:
    """A read-only sequence whose items are built on access (cards for messages)."""

    def __init__(self, fn, n: int):
        self.fn, self.n = fn, n

    def __getitem__(self, i):
        return self.fn(int(i))

    def __len__(self):
        return self.n
