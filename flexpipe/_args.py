"""Checks of the arguments of the public Python functions: each bad value raises an
:class:`~flexpipe.errors.InputError` that names the argument and what would be valid,
before any work is done (and never a raw ``TypeError`` from deep inside).

:func:`checked_number` is :func:`flexpipe.vehicle.run_inputs.checked_number` (same
arguments, same messages, plus ``file``) in a module that imports nothing heavy, so the
road, tyre and mesh readers can use it without pulling in the FE and vehicle code.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

import numpy as np

from flexpipe.errors import InputError


def _shown(value) -> str:
    """``int 5``, ``NoneType None``, ``dict {}``: the type and (short) value of a bad one."""
    text = repr(value)
    if len(text) > 60:
        text = text[:57] + "..."
    return f"{type(value).__name__} {text}"


def checked_number(value, name, *, lo=None, hi=None, lo_closed=False, unit: str = "",
                   key: str | None = None, file=None) -> float:
    """``float(value)`` when it is finite and in the range, else an :class:`InputError`.

    Parameters
    ----------
    value : object
        The value to check (a number, a numpy scalar, or a string holding a number, as
        :func:`~flexpipe.vehicle.simulation.simulate` takes them).
    name : str
        Its name in the message (an argument, or a command-line option like ``--speed``).
    lo, hi : float, optional
        Bounds; ``lo`` is excluded unless ``lo_closed``, ``hi`` is included.
    unit : str
        Unit appended to the range and the value in the message (e.g. ``"km/h"``).
    key : str, optional
        ``key`` of the error (default ``name``).
    file : str or Path, optional
        ``file`` of the error.

    Raises
    ------
    InputError
        Not a number, not finite or out of the range.
    """
    key = name if key is None else key
    u = f" {unit}" if unit else ""
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{name} must be a number, got {value!r}", key=key,
                         file=file) from None
    below = lo is not None and (v < lo if lo_closed else v <= lo)
    if not math.isfinite(v) or below or (hi is not None and v > hi):
        left = "[" if lo_closed else "("
        if lo is None:
            rng = f"<= {hi:g}" if hi is not None else "finite"
        else:
            rng = f"in {left}{lo:g}, {hi:g}]" if hi is not None else \
                f"{'>=' if lo_closed else '>'} {lo:g}"
        raise InputError(f"{name} must be finite and {rng}{u}, got {value!r}{u}", key=key,
                         file=file)
    return v


def checked_int(value, name, *, lo=None, hi=None, key: str | None = None, file=None) -> int:
    """``int(value)`` when ``value`` is an integer (``int`` or a numpy integer, not a bool,
    not a float such as 5.5 or 5.0) within ``[lo, hi]``, else an :class:`InputError`."""
    key = name if key is None else key
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
        raise InputError(f"{name} must be an integer, got {_shown(value)}", key=key, file=file)
    v = int(value)
    if (lo is not None and v < lo) or (hi is not None and v > hi):
        rng = (f"in [{lo}, {hi}]" if lo is not None and hi is not None
               else f">= {lo}" if lo is not None else f"<= {hi}")
        raise InputError(f"{name} must be an integer {rng}, got {v}", key=key, file=file)
    return v


def checked_bool(value, name, *, key: str | None = None) -> bool:
    """``value`` as a bool when it is ``True``/``False`` (or a numpy bool), else an
    :class:`InputError`."""
    if not isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name} must be True or False, got {_shown(value)}",
                         key=name if key is None else key)
    return bool(value)


def checked_choice(value, name, choices, *, key: str | None = None):
    """``value`` when it is one of ``choices`` (compared as given), else an
    :class:`InputError` listing them."""
    try:
        ok = value in choices
    except TypeError:  # an unhashable value against a set/dict
        ok = False
    if not ok:
        valid = ", ".join(repr(c) for c in choices)
        raise InputError(f"{name} must be one of {valid}, got {value!r}",
                         key=name if key is None else key)
    return value


def as_path(value, name: str) -> Path:
    """``Path(value)`` when ``value`` is a file path (``str`` or ``os.PathLike``), else an
    :class:`InputError` naming the argument (``NAME must be a file path (str or
    pathlib.Path), got int 5``).

    Parameters
    ----------
    value : object
        The argument.
    name : str
        The argument's name in the message and the error's ``key``.
    """
    if isinstance(value, os.PathLike):
        value = os.fspath(value)
    if not isinstance(value, str):
        raise InputError(f"{name} must be a file path (str or pathlib.Path), got "
                         f"{_shown(value)}", key=name)
    if not value.strip():
        raise InputError(f"{name} must be a file path (str or pathlib.Path), got an empty "
                         "string", key=name)
    return Path(value)


def plain_value(value):
    """``value`` with numpy scalars and arrays (also inside lists, tuples and dicts) turned
    into the Python ``int``/``float``/``bool``/``list`` a TOML file would give."""
    if isinstance(value, np.ndarray):
        return plain_value(value.tolist())
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, dict):
        return {k: plain_value(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [plain_value(v) for v in value]
    return value


__all__ = ["as_path", "checked_bool", "checked_choice", "checked_int", "checked_number",
           "plain_value"]
