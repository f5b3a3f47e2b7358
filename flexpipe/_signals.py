"""Ctrl-C and SIGTERM as exceptions, so that every command stops cleanly.

:func:`interrupts_as_exceptions` makes SIGINT and SIGTERM raise
:class:`~flexpipe.errors.Interrupted` (a ``KeyboardInterrupt``) in the main thread; the
commands catch it, record an "interrupted at t = ..." status and exit with 130 / 143.
:func:`interrupt_info` turns any ``KeyboardInterrupt`` into ``(exit_code, t)``.
"""

from __future__ import annotations

import contextlib
import signal
import threading

from flexpipe.errors import Interrupted

__all__ = ["Interrupted", "deferred_interrupts", "interrupt_info", "interrupt_text",
           "interrupts_as_exceptions"]


def _raise(signum, frame):
    raise Interrupted(signum)


@contextlib.contextmanager
def interrupts_as_exceptions():
    """Context: SIGINT and SIGTERM raise :class:`Interrupted`; previous handlers restored.

    Outside the main thread (where Python cannot install handlers) it does nothing.
    """
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    saved = {}
    for sig in (signal.SIGINT, signal.SIGTERM):
        try:
            saved[sig] = signal.signal(sig, _raise)
        except (ValueError, OSError):  # pragma: no cover - exotic embeddings
            pass
    try:
        yield
    finally:
        for sig, handler in saved.items():
            signal.signal(sig, handler)


def interrupt_info(exc: BaseException) -> tuple[int, float | None]:
    """``(exit_code, simulated time or None)`` of a KeyboardInterrupt."""
    code = exc.exit_code if isinstance(exc, Interrupted) else 130
    t = getattr(exc, "t", None)
    return code, t


def interrupt_text(exc: BaseException) -> str:
    """"interrupted (SIGTERM) at t = 1.234 s" or "interrupted (SIGINT)"."""
    name = str(exc) if isinstance(exc, Interrupted) else "SIGINT"
    t = getattr(exc, "t", None)
    return f"interrupted ({name})" + (f" at t = {t:.4f} s" if t is not None else "")


class _Pending:
    signum: int | None = None


@contextlib.contextmanager
def deferred_interrupts():
    """Context for native solver loops: SIGINT/SIGTERM only set ``state.signum``.

    A handler that raises can fire at any Python instruction a native loop calls back
    into - also outside the callback's own ``try`` - and the native code then reports a
    failure of its own.  Inside this context the signals are recorded instead; the
    callback polls ``state.signum`` and stops the loop, and the caller raises
    :class:`Interrupted` afterwards.  Signals whose handler is the system default (e.g.
    SIGTERM in a plain Python session) keep it; outside the main thread nothing changes.
    """
    state = _Pending()
    if threading.current_thread() is not threading.main_thread():
        yield state
        return

    def record(signum, frame):
        state.signum = signum

    saved = {}
    for sig in (signal.SIGINT, signal.SIGTERM):
        current = signal.getsignal(sig)
        if callable(current):  # Python-level handler (default_int_handler or ours)
            saved[sig] = signal.signal(sig, record)
    try:
        yield state
    finally:
        for sig, handler in saved.items():
            signal.signal(sig, handler)
