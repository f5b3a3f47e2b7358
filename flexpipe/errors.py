"""Exception types shared by every flexpipe stage.

Every error a user can cause says *what* is wrong, *where* (file, line, key, element or
node id, interface name, simulated time) and *what would be valid*.  Catch
:class:`FlexpipeError` to handle all of them.
"""

from __future__ import annotations

import re

_NUMPY_SCALAR = re.compile(r"\bnp\.(?:float|int|uint|bool_?|complex|str_)\d*\(([^()]*)\)")


def plain_numbers(text: str) -> str:
    """``"got np.float64(0.2)"`` -> ``"got 0.2"``: numpy 2 scalar reprs read as plain numbers."""
    return _NUMPY_SCALAR.sub(r"\1", text)


class FlexpipeError(Exception):
    """Base class of all errors raised by flexpipe (messages show numbers plainly)."""

    def __init__(self, *args):
        super().__init__(*(plain_numbers(a) if isinstance(a, str) else a for a in args))


class InputError(FlexpipeError, ValueError):
    """Bad user input: a data file, a key, an argument."""

    def __init__(self, message: str, *, file=None, line=None, key=None):
        where = []
        if file is not None:
            where.append(str(file))
        if line is not None:
            where.append(f"line {line}")
        if key is not None:
            where.append(f"key '{key}'")
        prefix = (", ".join(where) + ": ") if where else ""
        super().__init__(prefix + message)
        self.message = message  # without the "file, line N, key 'k': " prefix
        self.file = file
        self.line = line
        self.key = key


class MeshError(InputError):
    """A mesh file that cannot be read or describes an invalid structure."""


class ModelError(FlexpipeError, ValueError):
    """A structural model that cannot be analysed (mechanism, disconnected part, ...)."""


class SolverError(FlexpipeError, RuntimeError):
    """A numerical failure: divergence, singular matrix, failed convergence.

    Parameters
    ----------
    message : str
        What failed and the likely cause.
    time : float, optional
        Simulated time at which it failed, in seconds.
    """

    def __init__(self, message: str, *, time: float | None = None):
        if time is not None:
            message = f"at simulated time t = {time:.6g} s: {message}"
        super().__init__(message)
        self.time = time


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) or SIGTERM received: the work stopped cleanly.

    A subclass of :class:`KeyboardInterrupt`, so it is never mistaken for a failure of
    the input or of a solver.  ``exit_code`` is the shell convention ``128 + signum``
    (130 for SIGINT, 143 for SIGTERM); ``t`` is the simulated time reached, seconds,
    when the interrupt stopped a time integration (else None).
    """

    def __init__(self, signum: int = 2, *, t: float | None = None):
        import signal

        self.signum = int(signum)
        self.t = t
        try:
            name = signal.Signals(self.signum).name
        except ValueError:
            name = f"signal {self.signum}"
        super().__init__(name)

    @property
    def exit_code(self) -> int:
        """128 + the signal number."""
        return 128 + self.signum
