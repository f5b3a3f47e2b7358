"""Tyres: TeimOrbit ``.tir`` files, PAC2002 Magic Formula, Fiala/brush, vertical, relaxation.

Public API
----------
:func:`read_tir` -> :class:`TireProperties`
    Parse a ``.tir`` file (sections as read-only mappings, tables as arrays, SI units).
:func:`tire_from_file` (``model="pac2002"`` or ``"fiala"``) -> :class:`TireModel`
    :class:`Pac2002Tire` or :class:`FialaTire`; both offer ``wheel_forces(...)`` (global
    force/moment on the wheel centres) and ``slip_forces(kappa, alpha, Fz, gamma)``.
:class:`MagicFormula`, :class:`VerticalModel`, :func:`relax`, :func:`relax_slip_velocity`.

Conventions
-----------
* Contact forces, slips and camber are in the TYDEX/ISO **W-axes** (x forward, y left, z up
  along the road normal), the system PAC2002 files are fitted in: positive slip angle
  (contact patch moving to +y) gives **negative** Fy and positive aligning moment Mz;
  positive longitudinal slip (driving) gives positive Fx; positive inclination means the
  wheel top leans to -y.  For SAE tyre axes (y right, z down) use :func:`iso_to_sae`:
  ``Fy, Fz, My, Mz`` and ``alpha`` change sign, ``Fx, Mx, kappa, gamma`` do not.
* ``wheel_forces`` returns force and moment in the **global ISO 8855** frame (x forward,
  y left, z up) — the same handedness as the W-axes, so no sign change is needed; the W-axes
  are rotated into the global frame with the contact frame ``WheelForces.frame``.

USE_MODE (Adams PAC2002 meaning, as documented in the reference files' headers)
-------------------------------------------------------------------------------
0 Fz only; 1 Fx and My only; 2 Fy, Mx, Mz only; 3 all, uncombined; 4 all, combined slip
(PAC2002 G-functions).  +10: first-order slip relaxation (PTX*, PTY* relaxation lengths).
+20 (Adams contact-mass transient) is accepted and treated as +10.  A negative value
mirrors the characteristic.  Combined slip needs the R*-coefficients (RBX1.., RBY1..);
files without them (e.g. Sedan_Pac02Tire.tir) give no combined-slip reduction, with a
warning.

Sections honoured
-----------------
[UNITS] (conversion to SI), [MODEL] (PROPERTY_FILE_FORMAT, USE_MODE, TYRESIDE = LEFT,
RIGHT or SYMMETRIC, VXLOW, LONGVL), [DIMENSION] (UNLOADED_RADIUS, WIDTH), [VERTICAL]
(VERTICAL_STIFFNESS, VERTICAL_DAMPING, FNOMIN, BREFF/DREFF/FREFF, flexpipe extension
VERTICAL_STIFFNESS_CUBIC),
[DEFLECTION_LOAD_CURVE] {pen fz} (Duffing fit), [LONG_SLIP_RANGE], [SLIP_ANGLE_RANGE],
[INCLINATION_ANGLE_RANGE] (inputs clipped), [VERTICAL_FORCE_RANGE] (FZMAX limits the load
used in the formula), [SCALING_COEFFICIENTS] (LFZO, LCX, LMUX, LEX, LKX, LHX, LVX, LGAX,
LCY, LMUY, LEY, LKY, LHY, LVY, LGAY, LTR, LRES, LGAZ, LXAL, LYKA, LVYKA, LS, LSGKP, LSGAL,
LMX, LVMX, LMY, LCZ), [LONGITUDINAL_COEFFICIENTS], [LATERAL_COEFFICIENTS],
[ALIGNING_COEFFICIENTS], [OVERTURNING_COEFFICIENTS] (QSX1-3), [ROLLING_COEFFICIENTS]
(QSY1-4), and for FIALA files [PARAMETER].  Accepted but not used: inflation-pressure
terms (PPX*, PPY*, QPZ*, ...), turn slip, belt dynamics, QSX4+, QSY5+, [SHAPE].
"""

from flexpipe.tires.contact import SlipState, TireModel, WheelForces, iso_to_sae
from flexpipe.tires.fiala import FialaParameters, FialaTire
from flexpipe.tires.model import Pac2002Tire, tire_from_file
from flexpipe.tires.pac2002 import MagicFormula, SlipForces
from flexpipe.tires.relaxation import relax, relax_slip_velocity
from flexpipe.tires.tir import TireProperties, TirTable, read_tir
from flexpipe.tires.vertical import VerticalModel, fit_duffing

__all__ = [
    "FialaParameters", "FialaTire", "MagicFormula", "Pac2002Tire", "SlipForces", "SlipState",
    "TirTable", "TireModel", "TireProperties", "VerticalModel", "WheelForces", "fit_duffing",
    "iso_to_sae",
    "read_tir", "relax", "relax_slip_velocity", "tire_from_file",
]
