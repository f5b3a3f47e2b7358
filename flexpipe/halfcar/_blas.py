"""Run small dense linear algebra on one BLAS thread.

The half-car matrices are tiny (16-48 states); a multi-threaded BLAS only adds
synchronisation cost to them, and on a loaded machine it can slow a sweep down several
times.  :func:`single_threaded_blas` pins every OpenBLAS library loaded in the process
to one thread for the duration of a ``with`` block and restores the previous setting
(through ``threadpoolctl``, see :mod:`flexpipe.reduction._threads`).
"""

from __future__ import annotations

from flexpipe.reduction._threads import openblas_single_threaded as single_threaded_blas

__all__ = ["single_threaded_blas"]
