"""Array helpers shared by the frozen data objects."""

from __future__ import annotations

import numpy as np


def readonly(a, dtype=float) -> np.ndarray:
    """A contiguous copy of ``a`` as ``dtype`` that cannot be written (frozen dataclass
    fields): a copy, so freezing never makes the caller's own array read-only, nor does a
    later change of it show through the field."""
    a = np.array(a, dtype=dtype, copy=True, order="C")
    a.setflags(write=False)
    return a
