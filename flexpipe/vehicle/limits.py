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
#: deflect 0.1-5 mm, 10-70 times stiffer than the tyre (1.5e5-1e6 N/m), so the wheel would
#: hardly move on its suspension.  Passenger-car springs: 2e4-2e5 N/m (the
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
#: spin inertia of a wheel (rim + tyre, with hub and brake disc), kg m^2.  Passenger cars
#: 0.3-3 (the samples 1.0), the smallest road wheels (10-inch rim with tyre, about 5 kg at
#: 0.2-0.25 m radius) about 0.1-0.2, a heavy truck's twin-tyre wheel end 20-50.  The low
#: bound, 5 times below the smallest wheel, also keeps the wheel-spin coupling stable at the
#: largest step h = 5 ms: measured on cars/sedan.toml at 30 km/h, 1e-3 kg m^2 runs and 1e-4
#: diverges (spin beyond 1000 rad/s within 0.1 s).  The high bound is the heaviest wheel end
#: WHEEL_MASS_KG admits (2000 kg) as a ring at a heavy-truck tyre's 0.7 m radius.  A value in
#: kg mm^2 or kg cm^2 (CAD units) is 1e6 or 1e4 times too large.
WHEEL_SPIN_INERTIA_KG_M2 = (0.02, 1e3)
INERTIA_SLIPS = ((1e-6, "kg mm^2"), (1e-4, "kg cm^2"))
#: anti-roll bar of a prismatic-corner car, N/m at each wheel per metre of left-right
#: travel difference (when not 0, which means no bar).  Road cars 5e3-1e5 N/m (the sample
#: 6e3 / 1.8e4).  Above 1e6 N/m the bar is 5 times stiffer than a car's tyre (1.5e5-3e5
#: N/m) and as stiff as a heavy truck's (about 1e6 N/m): the tyres in series with it then
#: set the axle's roll stiffness alone, so no bar is made stiffer (and the bar, applied
#: explicitly, diverges at the largest step h = 5 ms from about 1e6 N/m on a 40 kg corner).
#: Below 1e3 N/m a bar adds under 5 % to the softest springs' roll stiffness (2e4 N/m): a
#: value in N/mm is 1000 times too small.
ARB_RATE_N_PER_M = (1e3, 1e6)
#: anti-roll bar of a linkage car: torsion rate between its two arms, N m/rad.  A solid
#: steel bar (G = 79 GPa) has k = G pi d^4 / (32 l): 10 mm thick and 1.5 m long about 50,
#: 60 mm and 0.8 m (heavy truck) about 1.3e5 N m/rad (the samples 220 and 6300).  1e6 N m/rad
#: would need a 90 mm solid bar of 0.5 m, 10 N m/rad a 6 mm wire.  A value in N m/deg is
#: 57 times too small.
ARB_TORSION_RATE_N_M_PER_RAD = (10.0, 1e6)
ARB_TORSION_SLIPS = ((180.0 / 3.141592653589793, "N m/deg"),)
#: rack travel per pinion revolution (c-factor), m: pi times the pinion's pitch diameter.
#: Steering pinions have pitch diameters of about 12-35 mm, so 0.03-0.12 m/rev (passenger
#: cars 0.04-0.065, the sample 0.055).  0.02 m/rev is a 6 mm pinion, too small to carry the
#: rack's kN forces; 0.2 m/rev a 64 mm one, which no rack housing holds.  A value in mm is
#: 1000 times too large.
RACK_TRAVEL_PER_REV_M = (0.02, 0.2)
LENGTH_SLIPS = ((1e-3, "mm"),)
#: a suspension bushing's translational stiffness, N/m (when not 0: a free direction).
#: Rubber bushings: about 1e5 (axial, voided) to 2e7 N/m (radial; the sample 6e5-8e6).  At
#: 1e4 N/m a bushing in the load path would deflect 0.4 m under a 4 kN wheel load; above
#: 1e8 N/m it is a metal joint, which the kinematic mode models as such.  Verified on
#: cars/sedan_linkage.toml in compliant mode at h = 1 ms (ISO C, 20 m/s): every
#: bushing at 1e8 N/m runs and gives the kinematic mode's vertical hub forces within 5 % of
#: their fluctuation (tests/test_car_limits.py
#: ``test_stiffest_valid_bushings_act_as_the_joints_they_surround``).  A value in N/mm or
#: kN/mm is 1e3 or 1e6 times too small.
BUSHING_STIFFNESS_N_PER_M = (1e4, 1e8)
BUSHING_STIFFNESS_SLIPS = ((1e3, "N/mm"), (1e6, "kN/mm"))
#: a bushing's rotational (torsional and conical) stiffness, N m/rad.  Rubber bushings: about
#: 1e2-1e4 N m/rad, large truck and cab mounts up to about 1e5 (the sample 150-500, and 2e5
#: where it stands in for the third rotation a universal joint locks).  1e6 N m/rad is
#: 10 times any elastomer mount: it only models a locked joint.  (About an arm's pivot axis
#: such a bushing locks the wheel travel: measured, it gives the same hub forces at h = 1 ms
#: and 0.25 ms, so it is the physics of a locked arm, not a numerical failure.)
BUSHING_ROT_STIFFNESS_N_M_PER_RAD = (0.0, 1e6)
#: a bushing's damping, N s/m and N m s/rad: its loss factor eta = c omega / k is at most
#: about 1 (hydro-bushings at their tuned frequency; rubber 0.05-0.3), so at the wheel-hop
#: band (about 15 Hz) and the stiffness bounds above c <= k / omega is about 1e6 N s/m and
#: 1e4 N m s/rad (the sample: 60-800 N s/m, 0.2-200 N m s/rad).
BUSHING_DAMPING_N_S_PER_M = (0.0, 1e6)
BUSHING_ROT_DAMPING_N_M_S_PER_RAD = (0.0, 1e4)
#: largest distance between a prismatic corner's hardpoint (strut top mount or spring seat)
#: and its wheel centre, m: the mount sits in the wheel house or above the axle, 0.3-0.7 m
#: from the wheel centre in cars (the sample 0.42-0.57 m) and up to about 1 m in heavy
#: trucks (spring hangers); beyond 1.5 m it lies outside any wheel house, and a strut there
#: could not carry that wheel.
HARDPOINT_TO_WHEEL_CENTER_M = 1.5
#: principal moments of inertia obey the triangle inequality I1 <= I2 + I3 for every body,
#: since I2 + I3 - I1 = 2 sum m x1^2 >= 0 (x1 along the first axis); a flat body meets it
#: with equality, so moments rounded to a few digits get this margin, relative to the
#: largest moment
INERTIA_TRIANGLE_TOL = 0.01
