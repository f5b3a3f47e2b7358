"""Vertical tyre force: linear, quadratic (MF 6.x) or Duffing (cubic) spring with damping
and lift-off."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError
from flexpipe.tires.checks import file_warning


@dataclass(frozen=True)
class VerticalModel:
    """Radial tyre spring-damper that can only push.

    ``Fz = max(0, k d + k2 d^2 + k3 d^3 + c d_dot)`` for deflection ``d > 0`` and ``Fz = 0``
    when the tyre has lifted off (``d <= 0``).  Clipping at zero also keeps a fast rebound from
    letting the damper pull the wheel onto the road.

    Parameters
    ----------
    k : float
        Linear stiffness, N/m (> 0).
    c : float
        Damping, N s/m (>= 0).
    k3 : float
        Cubic (Duffing) stiffness, N/m^3; 0 for a linear tyre.  Negative values soften and
        must keep the spring force monotonic up to ``d_max``.
    d_max : float
        Deflection up to which a softening ``k3 < 0`` must keep ``dF/dd > 0``, m.
    k2 : float
        Quadratic stiffness, N/m^2 (MF-Tyre 6.x's ``Q_FZ2`` term; >= 0); 0 otherwise.
    """

    k: float
    c: float = 0.0
    k3: float = 0.0
    d_max: float = 0.1
    k2: float = 0.0

    def __post_init__(self):
        if not self.k > 0:
            raise InputError(f"vertical stiffness must be > 0 N/m, got {self.k}", key="k")
        if not self.c >= 0:
            raise InputError(f"vertical damping must be >= 0 N s/m, got {self.c}", key="c")
        if not self.k2 >= 0:
            raise InputError(f"quadratic stiffness must be >= 0 N/m^2, got {self.k2}",
                             key="k2")
        if self.k + 3.0 * self.k3 * self.d_max ** 2 <= 0:
            raise InputError(f"cubic stiffness k3 = {self.k3} N/m^3 makes the tyre spring "
                             f"lose stiffness before d_max = {self.d_max} m", key="k3")

    @property
    def is_linear(self) -> bool:
        """True when there is no quadratic or cubic term."""
        return self.k3 == 0.0 and self.k2 == 0.0

    def spring_force(self, d):
        """Elastic part ``k d + k2 d^2 + k3 d^3`` for ``d > 0``, else 0 (N)."""
        d = np.maximum(np.asarray(d, dtype=float), 0.0)
        return self.k * d + self.k2 * d * d + self.k3 * d ** 3

    def force(self, d, d_dot=0.0):
        """Vertical force, N, >= 0.

        Parameters
        ----------
        d : float or array
            Radial deflection (compression positive), m.
        d_dot : float or array
            Deflection rate, m/s.
        """
        d = np.asarray(d, dtype=float)
        f = (self.k * d + self.k2 * d * d + self.k3 * d ** 3
             + self.c * np.asarray(d_dot, dtype=float))
        return np.where(d > 0.0, np.maximum(f, 0.0), 0.0)

    def static_deflection(self, Fz: float) -> float:
        """Deflection carrying ``Fz`` at rest (solves ``k d + k2 d^2 + k3 d^3 = Fz``), m."""
        if self.is_linear:
            return Fz / self.k
        roots = np.roots([self.k3, self.k2, self.k, -Fz])
        real = roots[np.abs(roots.imag) < 1e-9 * max(1.0, abs(Fz))].real
        return float(np.min(real[real >= 0]))

    @classmethod
    def from_properties(cls, props, *, law: str = "auto") -> VerticalModel:
        """Build from a ``.tir`` file.

        Parameters
        ----------
        props : TireProperties
        law : {"auto", "linear", "duffing"}
            ``linear``: ``VERTICAL_STIFFNESS`` (times LCZ) and ``VERTICAL_DAMPING``.
            ``duffing``: ``k, k3`` from ``VERTICAL_STIFFNESS_CUBIC`` (flexpipe extension, with
            ``VERTICAL_STIFFNESS``) or else a least-squares fit ``Fz = k d + k3 d^3`` of the
            ``[DEFLECTION_LOAD_CURVE] {pen fz}`` table.  ``auto``: duffing when either is
            present, else linear.  When the table is used and ``VERTICAL_STIFFNESS``
            differs from its fitted ``k`` by more than 5 %, a warning says which is used.
        """
        if law not in ("auto", "linear", "duffing"):
            raise InputError(f"law must be 'auto', 'linear' or 'duffing', got {law!r}", key="law")
        c = props.vertical_damping
        cubic = props.vertical_stiffness_cubic
        table = props.tables.get("DEFLECTION_LOAD_CURVE")
        if law == "linear" or (law == "auto" and cubic is None and table is None):
            return cls(k=props.vertical_stiffness, c=c)
        if cubic is not None:
            try:
                return cls(k=props.vertical_stiffness, c=c, k3=cubic)
            except InputError as exc:
                raise InputError(str(exc), file=props.path, key="VERTICAL_STIFFNESS_CUBIC",
                                 line=props.lines.get(("VERTICAL", "VERTICAL_STIFFNESS_CUBIC"))
                                 ) from None
        if table is None:
            raise InputError("a Duffing tyre needs [VERTICAL] VERTICAL_STIFFNESS_CUBIC or a "
                             "[DEFLECTION_LOAD_CURVE] {pen fz} table", file=props.path,
                             key="DEFLECTION_LOAD_CURVE")
        k, k3 = fit_duffing(table.column("pen"), table.column("fz"))
        lcz = props.number("SCALING_COEFFICIENTS", "LCZ", 1.0)
        d_max = float(np.max(table.column("pen")))
        k_file = props.get("VERTICAL", "VERTICAL_STIFFNESS")
        if isinstance(k_file, float) and abs(k * lcz - k_file * lcz) > 0.05 * k_file * lcz:
            file_warning(
                f"{props.path}, line {table.line}: the [DEFLECTION_LOAD_CURVE] table is used "
                f"for the vertical force (fit k = {k * lcz:.6g} N/m, k3 = {k3 * lcz:.6g} "
                f"N/m^3); [VERTICAL] VERTICAL_STIFFNESS = {k_file:g} N/m (line "
                f"{props.lines.get(('VERTICAL', 'VERTICAL_STIFFNESS'))}) differs by more "
                "than 5 % and is not used (vertical_law='linear' uses it instead)")
        try:
            return cls(k=k * lcz, c=c, k3=k3 * lcz, d_max=d_max)
        except InputError as exc:
            raise InputError(f"[DEFLECTION_LOAD_CURVE] fit Fz = k d + k3 d^3: {exc}",
                             file=props.path, line=table.line) from None


#: MF 6.x vertical-model terms flexpipe's spring does not have (speed, force and camber
#: effects on the stiffness, bottoming): a non-zero one warns.
_MF6_VERTICAL_UNUSED = ("Q_V2", "Q_FCX", "Q_FCY", "Q_FCY2", "Q_CAM", "Q_CAM1", "Q_CAM2",
                        "Q_CAM3", "Q_FYS1", "Q_FYS2", "Q_FYS3", "Q_FZ3")


def mf6_vertical(props, *, law: str = "auto", dpi: float = 0.0) -> VerticalModel:
    """The vertical spring of an MF 6.1 / 6.2 tyre at the pressure ``dpi`` (normalised).

    As :meth:`VerticalModel.from_properties`, plus MF-Tyre's quadratic load-deflection
    law: with ``Q_FZ2`` > 0 (and no ``[DEFLECTION_LOAD_CURVE]``, law not "linear") the
    spring is ``Fz = Fz0 (Q_FZ1 rho/R0 + Q_FZ2 (rho/R0)^2)`` exactly, with
    ``Q_FZ1 = sqrt((Cz R0/Fz0)^2 - 4 Q_FZ2)`` (the MF 6.1 relation that keeps
    ``VERTICAL_STIFFNESS`` Cz the stiffness at the nominal load).  The stiffness is then
    scaled by ``1 + PFZ1 dpi``.  Non-zero speed, force or
    camber terms of the MF 6.x vertical model (Q_V2, Q_FCX, Q_FCY, Q_CAM ...) are not
    modelled: one warning names them.
    """
    vert = props.coefficients("VERTICAL")
    unused = [f"{k} = {vert[k]:g} (line {props.lines.get(('VERTICAL', k))})"
              for k in _MF6_VERTICAL_UNUSED if isinstance(vert.get(k), float) and vert[k]]
    if unused:
        file_warning(f"{props.path}: MF 6.x vertical-model terms are not modelled (flexpipe's "
                     f"radial spring has no speed, force or camber effect): {'; '.join(unused)}")
    q2 = vert.get("Q_FZ2")
    if isinstance(q2, float) and q2 < 0.0:
        raise InputError(f"[VERTICAL] Q_FZ2 = {q2:g}; valid: >= 0 (a softening quadratic "
                         "term would let the tyre lose stiffness)", file=props.path,
                         line=props.lines.get(("VERTICAL", "Q_FZ2")), key="Q_FZ2")
    if q2 and law != "linear" and props.tables.get("DEFLECTION_LOAD_CURVE") is None \
            and props.vertical_stiffness_cubic is None:
        r0, fz0, cz = props.unloaded_radius, props.fnomin, props.vertical_stiffness
        disc = (cz * r0 / fz0) ** 2 - 4.0 * q2
        if not disc > 0.0:
            raise InputError(f"[VERTICAL] Q_FZ2 = {q2:g} with VERTICAL_STIFFNESS = {cz:g} N/m "
                             "gives no real Q_FZ1 = sqrt((Cz R0/Fz0)^2 - 4 Q_FZ2); valid: "
                             f"Q_FZ2 < {(cz * r0 / fz0) ** 2 / 4.0:g}", file=props.path,
                             line=props.lines.get(("VERTICAL", "Q_FZ2")), key="Q_FZ2")
        q1 = math.sqrt(disc)
        base = VerticalModel(k=fz0 * q1 / r0, c=props.vertical_damping,
                             k2=fz0 * q2 / r0 ** 2)
    else:
        base = VerticalModel.from_properties(props, law=law)
    f = 1.0 + props.number("VERTICAL", "PFZ1", 0.0) * dpi
    if not f > 0.0:
        raise InputError(f"[VERTICAL] PFZ1 at this pressure gives a vertical stiffness factor "
                         f"1 + PFZ1 dpi = {f:g}; valid: > 0", file=props.path, key="PFZ1",
                         line=props.lines.get(("VERTICAL", "PFZ1")))
    return VerticalModel(k=base.k * f, c=base.c, k3=base.k3 * f, d_max=base.d_max,
                         k2=base.k2 * f)


def fit_duffing(d, Fz) -> tuple[float, float]:
    """Least-squares ``(k, k3)`` of ``Fz = k d + k3 d^3`` through the origin.

    Parameters
    ----------
    d, Fz : array_like
        Deflections (m) and loads (N); at least two points with ``d > 0``.
    """
    d = np.asarray(d, dtype=float)
    Fz = np.asarray(Fz, dtype=float)
    if np.count_nonzero(d > 0) < 2:
        raise InputError("a load-deflection curve needs at least two points with d > 0")
    A = np.column_stack([d, d ** 3])
    (k, k3), *_ = np.linalg.lstsq(A, Fz, rcond=None)
    return float(k), float(k3)
