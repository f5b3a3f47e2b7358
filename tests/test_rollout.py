"""Roll-out and standstill of the full car (issue "Numbers that converge").

References: the rolling resistance of the ``.tir`` file (PAC2002 ``My = -R0 Fz QSY1`` at
``QSY2..4 = 0``, a force ``My / R_loaded`` at the ground) decelerating the car's mass plus
the wheels' spin inertia (``J / R_e^2`` each); symmetry (no lateral or yaw drift on a
straight flat road); a car at rest stays at rest.
"""

from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.driver import SpeedPI
from flexpipe.tires import tire_from_file
from flexpipe.vehicle import bodymodel
from flexpipe.vehicle.corners import static_loaded_radius, static_wheel_loads
from flexpipe.vehicle.simulation import default_driver

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan.toml"


def _coasting_driver(car, mass):
    steering, _ = default_driver(car, mass)
    return steering, SpeedPI(kp=0.0, ki=0.0, drive_torque_max=1.0, brake_torque_max=1.0)


def test_rollout_deceleration_is_the_tyres_rolling_resistance():
    car = fp.load_car(CAR)
    rb = bodymodel.rigid_properties(car)
    mass = rb.mass + car.unsprung_mass
    r = fp.simulate(car, speed=70 / 3.6, t_end=4.0, body="rigid",
                    driver=_coasting_driver(car, mass))
    assert r.status == 0, r.message
    sel = r.t >= 1.0
    decel = -np.polyfit(r.t[sel], r["speed"][sel], 1)[0]
    tire = tire_from_file(car.corners[0].tire)
    c = tire.mf.c
    assert c.QSY2 == c.QSY3 == c.QSY4 == 0.0
    N = static_wheel_loads(car, rb.mass, rb.center_of_mass)
    R_l = np.array([static_loaded_radius(tire, n) for n in N])
    F_rr = float(np.sum(tire.unloaded_radius * N * c.QSY1 * c.LMY / R_l))
    R_e = np.array([float(tire.effective_rolling_radius(tire.unloaded_radius - x)) for x in R_l])
    m_eff = mass + sum(cn.spin_inertia / re**2 for cn, re in zip(car.corners, R_e, strict=True))
    assert decel == pytest.approx(F_rr / m_eff, rel=0.05)
    assert np.abs(r["y"]).max() < 0.01  # m
    assert np.abs(r["yaw"]).max() < 1e-3  # rad


@pytest.mark.parametrize("body", ["rigid", "flexible"])
def test_parked_car_stays_parked(body):
    car = fp.load_car(CAR)
    r = fp.simulate(car, speed=0.0, t_end=8.0, body=body)
    assert r.status == 0, r.message
    late = r.t >= r.t[-1] - 2.0
    mid = (r.t >= 2.0) & (r.t < 4.0)
    for c in ("fl", "fr", "rl", "rr"):
        for k in "xyz":
            x = r[f"hub_{c}_{k}"]
            assert np.ptp(x[late]) <= np.ptp(x[mid]) + 1e-6  # no growth
            assert np.abs(x[late] - x[late].mean()).max() < 5.0  # N, at rest
