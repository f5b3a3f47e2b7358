"""Run small dense linear algebra on one BLAS thread.

The half-car matrices are tiny (16-48 states); a multi-threaded BLAS only adds
synchronisation cost to them, and on a loaded machine it can slow a sweep down several
times.  :func:`single_threaded_blas` pins every OpenBLAS library loaded in the process
to one thread for the duration of a ``with`` block and restores the previous setting.
It is a no-op where the libraries cannot be found (non-Linux, other BLAS).
"""

from __future__ import annotations

import contextlib
import ctypes
from pathlib import Path

_NAMES = [(f"{pre}openblas_set_num_threads{suf}", f"{pre}openblas_get_num_threads{suf}")
          for pre in ("", "scipy_") for suf in ("", "64_", "_")]


def _openblas_handles():
    maps = Path("/proc/self/maps")
    if not maps.exists():
        return []
    paths = {line.split()[-1] for line in maps.read_text().splitlines()
             if "openblas" in line.lower() and line.rstrip().endswith(".so")}
    handles = []
    for path in sorted(paths):
        try:
            lib = ctypes.CDLL(path)
        except OSError:
            continue
        for set_name, get_name in _NAMES:
            if hasattr(lib, set_name) and hasattr(lib, get_name):
                handles.append((getattr(lib, set_name), getattr(lib, get_name)))
                break
    return handles


@contextlib.contextmanager
def single_threaded_blas():
    """Context manager: one OpenBLAS thread inside, previous thread counts restored after."""
    handles = _openblas_handles()
    previous = []
    for set_threads, get_threads in handles:
        previous.append(get_threads())
        set_threads(1)
    try:
        yield
    finally:
        for (set_threads, _), n in zip(handles, previous, strict=True):
            set_threads(n)
