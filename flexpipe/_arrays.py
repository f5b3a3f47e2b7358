"""Array helpers shared by the frozen data objects."""

from __future__ import annotations

import numpy as np


def readonly_floats(a) -> np.ndarray:
    """A float64 copy of ``a`` that cannot be written (frozen dataclass fields)."""
    a = np.array(a, dtype=float, copy=True)
    a.setflags(write=False)
    return a
