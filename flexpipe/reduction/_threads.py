"""Keep OpenBLAS (NumPy/SciPy dense algebra) and MKL (PARDISO) from fighting over cores.

Between PARDISO calls the MKL OpenMP threads spin-wait; multi-threaded OpenBLAS calls
made meanwhile then crawl (measured on the 2-core reference machine: dense work in the
block eigensolver 3-5x slower).  :func:`dense_single_threaded` runs a block with OpenBLAS
on one thread and the spin time of Intel OpenMP (``libiomp5``, MKL's threading layer) at
zero, and restores both afterwards.  :func:`openblas_single_threaded` only pins
OpenBLAS (small dense problems such as the half car).

The libraries loaded in the process are found and driven by ``threadpoolctl`` (the
standard tool for this, from the scikit-learn project); where it finds none, nothing
changes.
"""

from __future__ import annotations

import contextlib
import ctypes

from threadpoolctl import ThreadpoolController

#: Intel OpenMP's default spin time before a thread sleeps, ms (restored after the block)
KMP_DEFAULT_BLOCKTIME_MS = 200


@contextlib.contextmanager
def openblas_single_threaded():
    """Context: every OpenBLAS loaded in the process on one thread; restored after."""
    ctl = ThreadpoolController().select(internal_api="openblas")
    with ctl.limit(limits=1):
        yield


@contextlib.contextmanager
def dense_single_threaded():
    """Context: OpenBLAS on one thread, MKL OpenMP threads sleep right after each call."""
    ctl = ThreadpoolController()
    iomp = [lib.dynlib for lib in ctl.lib_controllers
            if lib.prefix == "libiomp" and hasattr(lib.dynlib, "kmp_set_blocktime")]
    with ctl.select(internal_api="openblas").limit(limits=1):
        for lib in iomp:
            lib.kmp_set_blocktime(ctypes.c_int(0))
        try:
            yield
        finally:
            for lib in iomp:
                lib.kmp_set_blocktime(ctypes.c_int(KMP_DEFAULT_BLOCKTIME_MS))
