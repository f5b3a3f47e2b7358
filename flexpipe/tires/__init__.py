"""Tyres: TeimOrbit ``.tir`` files, PAC2002 / MF 5.2 and MF 6.1 / 6.2 Magic Formula,
Fiala/brush, vertical, relaxation.

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

Magic Formula version
---------------------
flexpipe evaluates the Magic Formula 5.2 equations (Pacejka 2002; Adams PAC2002, TNO
MF-Tyre 5.2) and the MF 6.1 / 6.2 ones (:mod:`flexpipe.tires.mf61`; MF-Tyre/MF-Swift 6.x
fits, with inflation pressure, steady state without turn slip).  ``[MODEL]
PROPERTY_FILE_FORMAT`` ``'PAC2002'`` and ``'MF_05'`` (MF-Tyre 5.x: the same equations and
coefficient names) are read alike as MF 5.2; ``[MODEL] FITTYP`` decides the version when
given: 6 or 21 MF 5.2 (Adams PAC2002 files usually have none), 61 or 62 MF 6.1 / 6.2
whatever the PROPERTY_FILE_FORMAT ('MF-TYRE', 'USER', or none as MF-Tool writes them; their
empty ``[MODEL]`` entries are skipped).  Another FITTYP (e.g. 60, MF 6.0) is refused with an
:class:`~flexpipe.errors.InputError` naming FITTYP.  An MF 6.x tyre's inflation pressure is
the file's ``[OPERATING_CONDITIONS] INFLPRES`` unless ``tire_from_file(..., pressure=)``
(or a car file's ``tire_pressure_Pa``) gives another, within ``[INFLATION_PRESSURE_RANGE]``.
MF 6.x coefficients in an MF 5.2 file are ignored; when one has a value that would change an
MF 6.x result (PKY4 other than 2, PKY5-PKY7, PEY5, QSX4-QSX14, QSY5, QSY6 non-zero, QSY7
other than 1, or inflation-pressure terms PPX*, PPY*, PPZ*, QPZ*, PPMX1, QSY8 non-zero
while ``[OPERATING_CONDITIONS] INFLPRES`` differs from ``NOMPRES`` or ``[TIRE_CONDITIONS]
IP`` from ``IP_NOM``) the file gets one :class:`UserWarning` naming each such key and its
line.  A 0 in PKY4 or QSY7 is taken as the placeholder PAC2002 files write (in an MF 6.x
file an absent PKY4 / QSY7 is 2 / 1, and PKY4 = 0 is an error).

USE_MODE (Adams PAC2002 meaning, as documented in the reference files' headers)
-------------------------------------------------------------------------------
0 Fz only; 1 Fx and My only; 2 Fy, Mx, Mz only; 3 all, uncombined; 4 all, combined slip
(PAC2002 G-functions).  +10: first-order slip relaxation (PTX*, PTY* relaxation lengths;
in an MF 6.x file the slip stiffnesses over the ``[STRUCTURAL]`` carcass stiffnesses).
+20 (Adams contact-mass transient) is accepted and treated as +10.  An MF 6.x file may
give MF-Tyre's three digits (e.g. 124): the last two are read as above, the hundreds
(contact method) is not used.  A negative value
mirrors the characteristic.  Combined slip needs the R*-coefficients (RBX1.., RBY1..);
files without them (e.g. Sedan_Pac02Tire.tir) give no combined-slip reduction, with a
warning.

Sections honoured
-----------------
[UNITS] (conversion to SI), [MODEL] (PROPERTY_FILE_FORMAT, FITTYP, USE_MODE, TYRESIDE =
LEFT, RIGHT or SYMMETRIC, VXLOW, LONGVL), [DIMENSION] (UNLOADED_RADIUS; WIDTH is optional
and descriptive only: :attr:`TireProperties.width` is None without it), [VERTICAL]
(VERTICAL_STIFFNESS, VERTICAL_DAMPING, FNOMIN, BREFF/DREFF/FREFF, flexpipe extension
VERTICAL_STIFFNESS_CUBIC),
[DEFLECTION_LOAD_CURVE] {pen fz} (Duffing fit), [LONG_SLIP_RANGE], [SLIP_ANGLE_RANGE],
[INCLINATION_ANGLE_RANGE] (inputs clipped), [VERTICAL_FORCE_RANGE] (FZMAX limits the load
used in the formula), [SCALING_COEFFICIENTS] (LFZO, LCX, LMUX, LEX, LKX, LHX, LVX, LGAX,
LCY, LMUY, LEY, LKY, LHY, LVY, LGAY, LTR, LRES, LGAZ, LXAL, LYKA, LVYKA, LS, LSGKP, LSGAL,
LMX, LVMX, LMY, LCZ), [LONGITUDINAL_COEFFICIENTS], [LATERAL_COEFFICIENTS],
[ALIGNING_COEFFICIENTS], [OVERTURNING_COEFFICIENTS] (QSX1-3), [ROLLING_COEFFICIENTS]
(QSY1-4), and for FIALA files [PARAMETER].  In an MF 6.x file also the MF 6.x
coefficients (PKY4-7, PEY5, RBX3, RBY4, QBZ6, QDZ10-11, QSX4-14, QSY5-8, LKYC, LKZC),
the pressure terms (PPX*, PPY*, PPZ*, PPMX1, [VERTICAL] PFZ1), [OPERATING_CONDITIONS],
[INFLATION_PRESSURE_RANGE] and [STRUCTURAL] (LONGITUDINAL_STIFFNESS, LATERAL_STIFFNESS,
PCFX1-3, PCFY1-3), and [VERTICAL] Q_FZ2 (the quadratic load-deflection term, see
:func:`~flexpipe.tires.vertical.mf6_vertical`).  Accepted but not used: turn slip, belt
dynamics, MF 6.2's loaded-radius model and the speed, force and camber terms of the MF 6.x
vertical stiffness (Q_V2, Q_FCX, Q_FCY, Q_CAM ...: a warning names them), in an MF 5.2
file the MF 6.x terms (see above for the warning), [SHAPE].  [MDI_HEADER] is descriptive:
its ``KEY = value`` entries are kept, anything else (free text, TeimOrbit ``(COMMENTS)``
blocks with their ``{comment_string}`` header and quoted rows) is skipped; a ``(COMMENTS)``
block is skipped in the other free sections too ([MODEL], [SHAPE], ...) and is an error in
a coefficient section.

Warnings (:class:`UserWarning`) about a file name the file and line and are issued from
one code location, so under Python's default warning filter each is shown once per
process even when the file is read again (e.g. ``read_tir`` and then ``tire_from_file``).
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
