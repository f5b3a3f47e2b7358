"""Keep OpenBLAS (NumPy/SciPy dense algebra) and MKL (PARDISO) from fighting over cores.

Between PARDISO calls the MKL OpenMP threads spin-wait; multi-threaded OpenBLAS calls
made meanwhile then crawl (measured on the 2-core reference machine: dense work in the
block eigensolver 3-5x slower).  :func:`dense_single_threaded` runs a block with OpenBLAS
on one thread and MKL's spin time at zero, and restores both afterwards.  Where the
libraries cannot be found it does nothing.
"""

from __future__ import annotations

import contextlib
import ctypes

_SET = ("scipy_openblas_set_num_threads64_", "scipy_openblas_set_num_threads",
        "openblas_set_num_threads64_", "openblas_set_num_threads")
_GET = ("scipy_openblas_get_num_threads64_", "scipy_openblas_get_num_threads",
        "openblas_get_num_threads64_", "openblas_get_num_threads")


def _libraries():
    """(OpenBLAS (get, set) pairs, libiomp5) loaded in this process; cached once complete."""
    global _FOUND
    if _FOUND is None:
        found = _scan()
        if found[0] and found[1] is not None:
            _FOUND = found
        return found
    return _FOUND


_FOUND = None


def _scan():
    blas, omp = [], None
    try:
        with open("/proc/self/maps") as fh:
            paths = {line.split()[-1] for line in fh if ".so" in line}
    except OSError:  # not Linux
        return (), None
    for path in sorted(paths):
        name = path.rsplit("/", 1)[-1]
        try:
            if "openblas" in name:
                lib = ctypes.CDLL(path)
                get = next((getattr(lib, f) for f in _GET if hasattr(lib, f)), None)
                set_ = next((getattr(lib, f) for f in _SET if hasattr(lib, f)), None)
                if get is not None and set_ is not None:
                    blas.append((get, set_))
            elif name.startswith("libiomp5") and omp is None:
                lib = ctypes.CDLL(path)
                if hasattr(lib, "kmp_set_blocktime"):
                    omp = lib
        except OSError:
            continue
    return tuple(blas), omp


@contextlib.contextmanager
def dense_single_threaded():
    """Context: OpenBLAS on one thread, MKL OpenMP threads sleep right after each call."""
    blas, omp = _libraries()
    saved = []
    try:
        for get, set_ in blas:
            saved.append((set_, int(get())))
            set_(1)
        if omp is not None:
            omp.kmp_set_blocktime(ctypes.c_int(0))
        yield
    finally:
        for set_, n in saved:
            set_(n)
        if omp is not None:
            omp.kmp_set_blocktime(ctypes.c_int(200))
