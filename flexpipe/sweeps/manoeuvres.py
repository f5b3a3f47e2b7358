"""The manoeuvre settings of a sweep: ``driver`` (a driver TOML file) and ``speed_profile``
(a speed-profile file used instead of ``speed_kmh``).  Both are files relative to the
sweep file, read when the sweep is loaded (so a bad file is named, with the sweep key that
gave it, before any run) and entered into the run's identity by their contents' sha.
"""

from __future__ import annotations

import functools
from pathlib import Path

from flexpipe.errors import InputError
from flexpipe.vehicle.run_inputs import SPEED_MAX


@functools.lru_cache(maxsize=256)
def _profile(path: str, sha: str):
    """The speed profile of ``path`` (cached by its contents' ``sha``)."""
    from flexpipe.driver import read_speed_profile

    return read_speed_profile(path, speed_max=SPEED_MAX)


@functools.lru_cache(maxsize=256)
def _driver(path: str, sha: str):
    """``(steering, speed controller or None)`` of a driver file (cached by ``sha``)."""
    from flexpipe.driver import read_driver

    return read_driver(path)


def speed_profile(path: Path, sha: str, *, where, key: str):
    """The :class:`~flexpipe.driver.SpeedProfile` of the file ``path``; a bad file raises
    :class:`InputError` naming the sweep file ``where`` and ``key``, with the profile's
    own file and key in the message."""
    try:
        return _profile(str(path), sha)
    except InputError as exc:
        raise InputError(f"speed profile {path}: {exc}", file=where, key=key) from None


def driver(path: Path, sha: str, *, where, key: str):
    """The controllers of the driver file ``path`` (as :func:`flexpipe.driver.read_driver`);
    a bad file raises :class:`InputError` naming the sweep file ``where`` and ``key``."""
    try:
        return _driver(str(path), sha)
    except InputError as exc:
        raise InputError(f"driver file {path}: {exc}", file=where, key=key) from None


def open_loop_kind(path) -> str | None:
    """``"step"``, ``"sine_with_dwell"``, ... for a driver file with an open-loop
    ``[steering]`` input, None for a path follower, no file or a file that does not read."""
    if not path:
        return None
    import hashlib

    from flexpipe.driver import OpenLoopSteer

    try:
        sha = hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
        steering, _ = _driver(str(path), sha)
    except (InputError, OSError):
        return None
    return steering.kind if isinstance(steering, OpenLoopSteer) else None


def speed_setting(point: dict, base: dict, *, where, key) -> str:
    """Which setting gives a run's speed: ``"speed_profile"`` or ``"speed_kmh"``.  A value
    of the run (``point``) replaces the base value of the other setting; both given for
    one run (both in the run, or both in ``[sweep]``) raise :class:`InputError`."""
    if "speed_profile" in point and "speed_kmh" in point:
        raise InputError("speed_kmh and speed_profile both set for this run; give one (a "
                         "speed profile replaces the constant speed)", file=where,
                         key=key("speed_profile"))
    if "speed_profile" in point:
        return "speed_profile"
    if "speed_kmh" in point or base.get("speed_profile") is None:
        return "speed_kmh"
    return "speed_profile"


__all__ = ["driver", "open_loop_kind", "speed_profile", "speed_setting"]
