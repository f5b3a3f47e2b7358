"""Magnitude bounds of car-file values outside which no road vehicle lies.

They catch unit slips (N/mm for N/m, tonnes or grams for kg), not unusual designs: each
bound lies one to several orders of magnitude beyond any road vehicle's value, and a slip
by a factor of 1000 crosses it.  Used through :meth:`flexpipe.vehicle._toml.Table.magnitude`,
which names the likely slip.
"""

from __future__ import annotations

#: suspension spring rate at the spring, N/m.  A road spring carries a static corner load of
#: about 1-50 kN (small cars 2-4 kN, heavy trucks tens of kN): at 1e3 N/m it would need
#: metres of static deflection, which no spring (under 0.5 m long) has; at 1e7 N/m it would
#: deflect well under a millimetre, 20-50 times stiffer than the tyre (1.5e5-1e6 N/m), so
#: the wheel would not move on its suspension.  Passenger-car springs: 2e4-2e5 N/m (the
#: samples 2.6e4-1.1e5), truck leaf springs up to about 1e6 N/m.  A value in N/mm or kN/m
#: is 1000 times too small.
SPRING_RATE_N_PER_M = (1e3, 1e7)
#: slips a spring rate below the bound is likely to be
SPRING_RATE_SLIPS = ((1e3, "N/mm"),)
#: a stop's rate, N/m (when not 0, which means no stop): rubber and polyurethane stops are
#: stiffer than the spring they back up, 1e4-1e7 N/m; below 1e3 N/m a stop would not stop
#: the wheel within its travel under a wheel load of a few kN.
STOP_RATE_N_PER_M = (1e3, 1e8)
#: a prismatic corner's damping, N s/m (when not 0, which means no damper).  A ride mode's
#: critical damping 2 sqrt(k m) is at least about 2e3 N s/m for any road vehicle (k >= 1e4
#: N/m, corner mass >= 100 kg) and dampers give 0.2-0.5 of it: a few hundred to tens of
#: thousands of N s/m.  Below 10 N s/m a damper damps less than 0.5 % of critical, which no
#: damper does; a value in N s/mm or kN s/m is 1000 times too small.  Above 1e6 N s/m the
#: wheel would barely move at 1 m/s under the largest road forces.
DAMPING_N_S_PER_M = (10.0, 1e6)
DAMPING_SLIPS = ((1e3, "N s/mm"),)
#: unsprung mass of a wheel station or mass of a wheel (rim + tyre), kg.  The smallest road
#: wheels weigh about 5 kg (10-inch rim with tyre), a heavy truck's twin-tyre wheel end with
#: its share of a rigid axle about 500 kg: outside 1-2000 kg the value is in tonnes
#: (1000 times too small) or grams (1000 times too large).
WHEEL_MASS_KG = (1.0, 2000.0)
MASS_SLIPS = ((1e3, "tonnes"), (1e-3, "grams"))
