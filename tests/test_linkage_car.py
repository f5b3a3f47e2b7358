"""The full car on linkage suspensions (cars/sedan_linkage.toml) in Exudyn: statics.

References: the whole car's weight (vertical force balance at rest), the tyres' static
loaded radius under the static wheel loads, and the design position the springs are
preloaded for (virtual work through each linkage,
:func:`flexpipe.vehicle.suspension.statics.spring_preload`).
"""

from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.vehicle import bodymodel
from flexpipe.vehicle.suspension.model import ARB_ARM_MASS, RACK_MASS

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan_linkage.toml"
CORNERS = ("fl", "fr", "rl", "rr")


@pytest.fixture(scope="module")
def parked():
    car = fp.load_car(CAR)
    return car, fp.simulate(car, speed=0.0, t_end=3.0, body="rigid")


def test_parked_linkage_car_carries_its_weight(parked):
    car, r = parked
    assert r.status == 0, r.message
    rb = bodymodel.rigid_properties(car)
    n_arb = sum(a.anti_roll_bar is not None for a in car.suspension.axles.values())
    mass = rb.mass + sum(c.unsprung_mass for c in car.corners) + RACK_MASS \
        + 2 * n_arb * ARB_ARM_MASS
    Fz = sum(r[f"tire_{c}_Fz"][-1] for c in CORNERS)
    assert Fz == pytest.approx(mass * 9.81, rel=1e-5)


def test_linkage_car_starts_in_static_equilibrium_at_design_ride_height(parked):
    _, r = parked
    assert abs(r["z"][-1] - r["z"][0]) < 0.5e-3  # the body does not settle, m
    for c in CORNERS:
        assert abs(r[f"travel_{c}"][-1]) < 0.5e-3  # suspension at its design position, m
        # vertical hub and tyre forces at t = 0 are the static ones (the horizontal ones
        # build up while the compliant steering column takes the static steering moment)
        for ch in (f"hub_{c}_z", f"tire_{c}_Fz"):
            assert r[ch][0] == pytest.approx(r[ch][-1], rel=1e-3)


def test_parked_linkage_car_does_not_creep(parked):
    _, r = parked
    late = r.t > r.t[-1] - 0.5
    for c in CORNERS:
        for k in "xyz":
            assert np.ptp(r[f"hub_{c}_{k}"][late]) < 0.5  # N
