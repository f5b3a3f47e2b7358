"""Verified on-disk cache entries of :mod:`flexpipe.vehicle.bodymodel`.

An entry is trusted only when it proves itself:

* it records the **input key** (SHA-256 over the mesh bytes and every setting that
  changes the result) and the key matches the one asked for;
* it records a **content hash** over its own data (the arrays of a reduced body, see
  :func:`flexpipe.flexbody.body.content_hash`; the numbers of a mass-properties entry),
  and the data still hash to it -- a CRC-corrupt zip member, a NaN, a scaled stiffness
  or inertia all fail;
* the data pass the physical checks of :func:`flexpipe.flexbody.load_body` (finite,
  positive mass, ``K = diag(omega^2)``, ...).

A bad entry is reported with a :class:`CacheWarning` naming the file and the reason and
is then rebuilt.  Writes go through :func:`flexpipe._io.atomic_path` (temporary file +
``os.replace``), so concurrent writers of the same entry never corrupt it: the last
complete file wins and readers see either the old or the new file.  Temporary files of
writers killed mid-write are removed after :data:`STALE_AGE_S`.
"""

from __future__ import annotations

import contextlib
import hashlib
import json
import os
import time
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np

from flexpipe.errors import InputError

#: a temporary cache file older than this (s) belongs to a writer that died
STALE_AGE_S = 600.0


class CacheWarning(UserWarning):
    """A cache entry failed verification and is being rebuilt."""


def _warn(path, reason: str) -> None:
    warnings.warn(CacheWarning(f"cache entry {path} is invalid ({reason}); rebuilding it"),
                  stacklevel=3)


def clean_stale(folder, *, max_age: float = STALE_AGE_S) -> list[Path]:
    """Remove temporary files (``.NAME.*``) of dead writers from the cache folder."""
    folder = Path(folder)
    removed = []
    if not folder.is_dir():
        return removed
    now = time.time()
    for p in folder.glob(".*"):
        try:
            if p.is_file() and now - p.stat().st_mtime > max_age:
                p.unlink()
                removed.append(p)
        except OSError:
            continue
    return removed


# --------------------------------------------------------------------------- mass properties
def _numbers_hash(key: str, mass: float, cg, inertia) -> str:
    h = hashlib.sha256(key.encode())
    h.update(np.asarray([mass, *np.ravel(cg), *np.ravel(inertia)], dtype="<f8").tobytes())
    return h.hexdigest()


def load_massprops(path, key: str):
    """``(mass, cg, inertia)`` of a verified entry, or None (missing or bad, warned)."""
    path = Path(path)
    if not path.is_file():
        return None
    try:
        d = json.loads(path.read_text())
        mass = float(d["mass"])
        cg = np.asarray(d["cg"], dtype=float).reshape(3)
        J = np.asarray(d["inertia"], dtype=float).reshape(3, 3)
        stored_key, stored_hash = str(d["key"]), str(d["sha256"])
    except (OSError, ValueError, TypeError, KeyError) as exc:
        _warn(path, f"not a mass-properties record: {type(exc).__name__}")
        return None
    if stored_key != key:
        _warn(path, "written for other inputs")
        return None
    if stored_hash != _numbers_hash(key, mass, cg, J):
        _warn(path, "content hash mismatch: the numbers were changed after writing")
        return None
    if not (np.isfinite(mass) and mass > 0 and np.all(np.isfinite(J)) and np.all(np.isfinite(cg))
            and np.linalg.eigvalsh(0.5 * (J + J.T)).min() >= 0):
        _warn(path, "non-physical mass properties")
        return None
    return mass, cg, J


def save_massprops(path, key: str, mass: float, cg, inertia) -> None:
    """Write a mass-properties entry atomically with its key and content hash."""
    from flexpipe._io import write_text_atomic

    cg, J = np.asarray(cg, dtype=float), np.asarray(inertia, dtype=float)
    write_text_atomic(path, json.dumps({
        "key": key, "mass": float(mass), "cg": cg.tolist(), "inertia": J.tolist(),
        "sha256": _numbers_hash(key, float(mass), cg, J)}))


# --------------------------------------------------------------------------- reduced bodies
def load_cached_body(path, key: str):
    """The verified FlexBody of a cache entry, or None (missing or bad, warned)."""
    from flexpipe.flexbody import load_body

    path = Path(path)
    if not path.is_file():
        return None
    try:
        body = load_body(path)
    except InputError as exc:
        _warn(path, " ".join(str(exc).split()).replace(f"{path}: ", "", 1))
        return None
    if body.meta.get("cache_key") != key:
        _warn(path, "written for other inputs (cache key mismatch)")
        return None
    if "content_sha256" not in _header(path):
        _warn(path, "no content hash")
        return None
    return body


def _header(path) -> dict:
    with contextlib.suppress(Exception), np.load(path, allow_pickle=False) as d:
        return json.loads(str(d["header"]))
    return {}


def save_cached_body(body, path, key: str):
    """Store ``body`` under ``path`` with its input key (atomic write); returns the body."""
    body = replace(body, meta={**dict(body.meta), "cache_key": key})
    body.save(path)
    return body


def remove(path) -> None:
    """Delete a bad entry (ignored when another process already replaced it)."""
    with contextlib.suppress(OSError):
        os.unlink(path)
