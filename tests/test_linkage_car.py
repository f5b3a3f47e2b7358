"""The full car on linkage suspensions (cars/sedan_linkage.toml) in Exudyn: statics.

References: the whole car's weight (conservation of vertical force at rest) and the design
ride height the springs are preloaded for (virtual work through each linkage,
:func:`flexpipe.vehicle.suspension.statics.spring_preload`).
"""

from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.exu.linkage import ARB_ARM_MASS, RACK_MASS
from flexpipe.vehicle import bodymodel

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
    assert Fz == pytest.approx(mass * 9.81, rel=1e-4)


def test_parked_linkage_car_sits_at_design_ride_height(parked):
    _, r = parked
    assert abs(r["z"][-1]) < 0.5e-3  # body origin height change, m
    for c in CORNERS:
        assert abs(r[f"travel_{c}"][-1]) < 2e-3  # wheel travel from the design position


def test_parked_linkage_car_does_not_creep(parked):
    _, r = parked
    late = r.t > r.t[-1] - 0.5
    for c in CORNERS:
        for k in "xyz":
            assert np.ptp(r[f"hub_{c}_{k}"][late]) < 5.0  # N
