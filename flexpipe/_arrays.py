"""Array helpers shared by the frozen data objects."""

from __future__ import annotations

import dataclasses

import numpy as np


def readonly(a, dtype=float) -> np.ndarray:
    """A contiguous copy of ``a`` as ``dtype`` that cannot be written (frozen dataclass
    fields): a copy, so freezing never makes the caller's own array read-only, nor does a
    later change of it show through the field."""
    a = np.array(a, dtype=dtype, copy=True, order="C")
    a.setflags(write=False)
    return a


def _frozen(v):
    """``v`` with its arrays read-only: arrays, and arrays in plain tuples and dicts at any
    depth (``v`` itself when there is nothing to freeze)."""
    if isinstance(v, np.ndarray):
        return readonly(v, v.dtype) if v.flags.writeable else v
    if type(v) is tuple:
        w = tuple(_frozen(x) for x in v)
        return w if any(a is not b for a, b in zip(w, v, strict=True)) else v
    if type(v) is dict:
        w = {k: _frozen(x) for k, x in v.items()}
        return w if any(w[k] is not v[k] for k in v) else v
    return v


def freeze_arrays(obj) -> None:
    """Make the array fields of the frozen dataclass ``obj`` read-only (call it at the end
    of ``__post_init__``): a frozen object whose arrays can be changed in place is not
    frozen, and a cached result keyed on the object's file would no longer match it."""
    for f in dataclasses.fields(obj):
        v = getattr(obj, f.name)
        w = _frozen(v)
        if w is not v:
            object.__setattr__(obj, f.name, w)


def frozen_arrays(cls):
    """Class decorator, placed below ``@dataclass(frozen=True)``: after the class's own
    ``__post_init__`` (if any), its array fields are made read-only (:func:`freeze_arrays`)."""
    own = cls.__dict__.get("__post_init__")

    def __post_init__(self):
        if own is not None:
            own(self)
        freeze_arrays(self)

    __post_init__.__doc__ = own.__doc__ if own is not None else None
    cls.__post_init__ = __post_init__
    return cls


def uniform_step(x) -> float:
    """The spacing of ``x`` if its samples are uniform (within 1e-9 of its scale), else 0."""
    step = np.diff(np.asarray(x, dtype=float))
    if step.size and np.ptp(step) <= 1e-9 * max(1.0, float(np.max(np.abs(x)))):
        return float(step.mean())
    return 0.0


def uniform_samples(x, z, *, finest: float = 1e-3, most: int = 2**20):
    """``(x, z, dx)`` on uniform samples: as given when uniform, else ``z`` (linear
    between its samples) resampled at ``finest`` or the finest spacing of ``x`` if that is
    coarser, but at least the range / ``most``, so that a profile sampled at its corners
    only (an Adams 2D plank, a CSV with gaps) keeps the spectrum of its shape, corners
    included."""
    x = np.asarray(x, dtype=float)
    dx = uniform_step(x)
    if dx:
        return x, np.asarray(z, dtype=float), dx
    dx = max(min(float(np.diff(x).min()), finest), float(x[-1] - x[0]) / most)
    xu = np.arange(x[0], x[-1] + 0.5 * dx, dx)
    return xu, np.interp(xu, x, z), dx
