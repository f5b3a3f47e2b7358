"""Nonlinear corner laws: dual-rate ("bilinear") dampers and Duffing tires with contact.

Each law is written as a linear reference part, kept in the linear matrices, plus a
deviation ``g`` that enters the equations of motion as ``B g`` with ``B = [-D, E]``:

* damper force (extension positive) ``F_d(v) = c(v) v`` with ``c = c_rebound`` for
  ``v > 0`` (extension) and ``c_jounce`` for ``v <= 0``; ``g_d = F_d - c_ref v``;
* tire force (compression positive) ``F_t(d) = k_t d + k_t3 d^3`` about static
  equilibrium; with unilateral contact the total load ``F0 + F_t`` cannot become
  negative, so ``F_t >= -F0``; ``g_t = F_t - k_ref d``.

Both laws are continuous and piecewise smooth; their kinks (``v = 0``, loss of
contact) are reported by :meth:`CornerLaws.kink_functions` so that integrators can
locate them exactly.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError
from flexpipe.halfcar.model import HalfCarModel

#: switching hysteresis of the integrators: damper velocity (m/s) and tire load (N)
EVENT_EPS = 1e-9
EVENT_EPS_F = 1e-6

DAMPERS = ("linear", "dual_rate")
TIRES = ("linear", "duffing")


@dataclass(frozen=True)
class Nonlinearity:
    """Which corner laws are used.

    Parameters
    ----------
    damper : {"linear", "dual_rate"}
        ``linear``: ``zeta`` in both directions; ``dual_rate``: ``zeta_jounce`` in
        compression, ``zeta_rebound`` in extension.
    tire : {"linear", "duffing"}
    contact : bool
        Unilateral tire contact (the wheel may leave the road).
    """

    damper: str = "linear"
    tire: str = "linear"
    contact: bool = False

    def __post_init__(self):
        if self.damper not in DAMPERS:
            raise InputError(f"unknown damper law {self.damper!r}; valid: {DAMPERS}",
                             key="damper")
        if self.tire not in TIRES:
            raise InputError(f"unknown tire law {self.tire!r}; valid: {TIRES}", key="tire")

    @property
    def is_linear(self) -> bool:
        """True when every law is linear."""
        return self.damper == "linear" and self.tire == "linear" and not self.contact

    @property
    def label(self) -> str:
        """Short description for legends."""
        parts = ["dual-rate dampers" if self.damper == "dual_rate" else "linear dampers"]
        if self.tire == "duffing":
            parts.append("Duffing tires")
        if self.contact:
            parts.append("contact")
        return ", ".join(parts)


class CornerLaws:
    """Corner laws of one model, vectorized over arrays shaped ``(2, ...)`` (front, rear).

    Parameters
    ----------
    model : HalfCarModel
    nl : Nonlinearity
    c_ref, k_ref : array_like, shape (2,), optional
        Linear reference damper and tire rates kept in the matrices.  Defaults: the
        mean of the two damper rates and the tire rate.
    """

    def __init__(self, model: HalfCarModel, nl: Nonlinearity, *, c_ref=None, k_ref=None):
        self.nl = nl
        if nl.damper == "dual_rate":
            self.c_minus, self.c_plus = model.c_jounce, model.c_rebound
        else:
            self.c_minus = self.c_plus = model.c_lin
        self.k_t = model.k_t
        self.k_t3 = model.k_t3 if nl.tire == "duffing" else np.zeros(2)
        self.F0 = model.static_tire_force
        self.c_ref = (np.asarray(c_ref, dtype=float) if c_ref is not None
                      else 0.5 * (self.c_minus + self.c_plus))
        self.k_ref = np.asarray(k_ref, dtype=float) if k_ref is not None else self.k_t.copy()
        # channels whose deviation g is not identically zero
        self.damper_active = bool(np.any(self.c_minus != self.c_ref)
                                  or np.any(self.c_plus != self.c_ref))
        self.tire_active = bool(nl.tire == "duffing" or nl.contact
                                or np.any(self.k_ref != self.k_t))

    @staticmethod
    def _col(a, ndim):
        return np.asarray(a).reshape((2,) + (1,) * (ndim - 1))

    def damper_force(self, v):
        """Damper force (extension positive) and its slope ``dF/dv``."""
        v = np.asarray(v, dtype=float)
        c = np.where(v > 0.0, self._col(self.c_plus, v.ndim), self._col(self.c_minus, v.ndim))
        return c * v, c

    def tire_force(self, d):
        """Dynamic tire force (compression positive) and its slope ``dF/dd``."""
        d = np.asarray(d, dtype=float)
        kt, k3 = self._col(self.k_t, d.ndim), self._col(self.k_t3, d.ndim)
        F = kt * d + k3 * d**3
        slope = kt + 3.0 * k3 * d**2
        if self.nl.contact:
            F0 = self._col(self.F0, d.ndim)
            off = F < -F0
            F = np.where(off, -F0, F)
            slope = np.where(off, 0.0, slope)
        return F, slope

    def deviations(self, v, d):
        """``g`` and its slopes: ``(g_d, dg_d/dv, g_t, dg_t/dd)``."""
        Fd, cd = self.damper_force(v)
        Ft, kt = self.tire_force(d)
        cr = self._col(self.c_ref, np.ndim(v))
        kr = self._col(self.k_ref, np.ndim(d))
        return Fd - cr * v, cd - cr, Ft - kr * d, kt - kr

    def kink_functions(self, v, d):
        """Functions whose sign changes mark the kinks of the laws, shape ``(m, ...)``.

        Rows: damper velocities (dual-rate only) and total tire loads (contact only).
        """
        rows = []
        if self.nl.damper == "dual_rate" and np.any(self.c_minus != self.c_plus):
            rows.append(np.asarray(v, dtype=float))
        if self.nl.contact:
            d = np.asarray(d, dtype=float)
            kt, k3 = self._col(self.k_t, d.ndim), self._col(self.k_t3, d.ndim)
            rows.append(self._col(self.F0, d.ndim) + kt * d + k3 * d**3)
        if not rows:
            return np.zeros((0,) + np.shape(v)[1:])
        return np.concatenate(rows, axis=0)

    @property
    def smooth_slopes(self) -> bool:
        """True when the slopes are piecewise constant between kinks (no Duffing term)."""
        return not np.any(self.k_t3)
