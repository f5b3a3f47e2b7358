"""Exudyn adapters: the only place in flexpipe that imports exudyn.

``flexpipe.exu.body``: :func:`add_flexible_body` (ObjectFFRFreducedOrder with a
MarkerSuperElementRigid per interface) and :func:`add_rigid_twin`.  Import the
submodules directly.

Importing this package chooses which of the two compiled modules Exudyn ships is loaded
(:data:`MODULE_ENV`): ``exudynCPPfast`` (``fast``, the default: built without range checks
and with AVX2) or ``exudynCPP`` (``checked``: every vector and matrix index checked, for
hunting a model-building error).  Both integrate the same equations; on the linkage car
(ISO C 70 km/h, 2 s, 2026-12-02) their hub forces differ by at most 4e-5 % of the
fluctuation (rounding), and the fast module takes about half of Exudyn's time for the
flexible body (3.67 -> 1.90 s) and 12 % less for the rigid one (0.66 -> 0.58 s).  A CPU
without AVX2 gets ``exudynCPP`` either way.  If exudyn was imported before flexpipe, its
module is already chosen and stays as it is.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys

#: environment variable choosing Exudyn's compiled module: ``fast`` (default) or ``checked``
MODULE_ENV = "FLEXPIPE_EXUDYN"
MODULES = {"fast": "exudynCPPfast", "checked": "exudynCPP"}


def _choose_module() -> None:
    asked = os.environ.get(MODULE_ENV, "").strip().lower()
    choice = asked or "fast"
    if choice not in MODULES:
        from flexpipe.errors import InputError

        raise InputError(f"{MODULE_ENV}={asked!r}; valid: {', '.join(MODULES)}",
                         key=MODULE_ENV)
    if "exudyn" in sys.modules or hasattr(sys, "exudynFast"):
        # chosen already, by an earlier import or by the user's own sys.exudynFast
        if asked and "exudyn" in sys.modules and compiled_module() != MODULES[choice]:
            import warnings

            warnings.warn(f"{MODULE_ENV}={asked} is not applied: exudyn was imported before "
                          f"flexpipe and runs its {compiled_module()} module; set "
                          f"{MODULE_ENV} before the first import of exudyn", stacklevel=2)
        return
    sys.exudynFast = choice == "fast"
    with contextlib.redirect_stdout(io.StringIO()):  # Exudyn announces its module on stdout
        import exudyn  # noqa: F401


def compiled_module() -> str:
    """Name of the compiled Exudyn module in use (``exudynCPPfast`` or ``exudynCPP``)."""
    return "exudynCPPfast" if "exudyn.exudynCPPfast" in sys.modules else "exudynCPP"


_choose_module()
