"""Dotted-key overrides of ``load_car`` (the sweeps' ``car.<key>`` parameters): every
section of the car, the linkage suspension and the steering rack included, is read from the
one overridden document, and an override key outside the car file's schema is refused."""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.vehicle import load_car

ROOT = Path(__file__).resolve().parents[1]
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"
SEDAN = ROOT / "cars" / "sedan.toml"


@pytest.fixture(scope="module")
def raw():
    return tomllib.loads(LINKAGE.read_text())


def test_suspension_overrides_reach_the_loaded_linkage(raw):
    k0 = raw["suspension"]["front"]["spring"]["rate_N_per_m"]
    base = load_car(LINKAGE)
    car = load_car(LINKAGE, overrides={"suspension.front.spring.rate_N_per_m": 2 * k0})
    front = car.suspension.axles["front"]
    assert front.left.spring().rate == front.right.spring().rate == 2 * k0
    assert base.suspension.axles["front"].left.spring().rate == k0
    # the other axle and the geometry are the file's
    rear, rear0 = car.suspension.axles["rear"].left, base.suspension.axles["rear"].left
    assert rear.spring().rate == raw["suspension"]["rear"]["spring"]["rate_N_per_m"]
    assert front.left.spring().design_length == base.suspension.axles[
        "front"].left.spring().design_length
    # a damper table, a rack key and a part mass reach the model too
    force = [-3000.0, 0.0, 6000.0]
    car = load_car(LINKAGE, overrides={"suspension.rear.damper.force_N": force,
                                       "steering.rack.travel_per_rev_m": 0.045,
                                       "suspension.rear.parts.knuckle.mass_kg": 6.0})
    rear = car.suspension.axles["rear"].left
    assert np.array_equal(rear.damper().table[1], force)
    assert not np.array_equal(rear0.damper().table[1], force)
    assert car.suspension.rack.travel_per_rev == 0.045
    knuckle = next(p for p in rear.parts if p.name == "knuckle")
    assert knuckle.mass == 6.0
    # the unsprung mass of the corner follows the overridden part mass
    assert car.corner("rl").unsprung_mass - base.corner("rl").unsprung_mass == pytest.approx(
        6.0 - raw["suspension"]["rear"]["parts"]["knuckle"]["mass_kg"])


@pytest.mark.parametrize("car, key, valid", [
    (LINKAGE, "suspension.front.spring.rate_N_per_mm", "rate_N_per_m"),
    (LINKAGE, "suspension.front.wheel_load", "wheel_load_N"),
    (LINKAGE, "suspension.rear.bump_stop.clearance", "clearance_m"),
    (LINKAGE, "suspension.mod", "mode"),
    (LINKAGE, "steering.rack.travel_per_rev", "travel_per_rev_m"),
    (LINKAGE, "corners.fl.wheel_mass", "wheel_mass_kg"),
    (SEDAN, "corners.fl.spring_rate", "spring_rate_N_per_m"),
    (SEDAN, "drive.layot", "layout"),
])
def test_an_override_key_outside_the_schema_is_refused(car, key, valid):
    with pytest.raises(InputError) as err:
        load_car(car, overrides={key: 1.0})
    msg = str(err.value).replace(str(car), "<car>")
    assert err.value.key == key
    assert f"'{key}'" in msg and "unknown key" in msg and valid in msg
    assert "override" in msg  # says the key came from an override, not the file


def test_bad_override_values_and_tables_are_named():
    with pytest.raises(InputError) as err:
        load_car(LINKAGE, overrides={"suspension.front.spring.rate_N_per_m": 111.0})
    msg = str(err.value)
    assert err.value.key == "suspension.front.spring.rate_N_per_m"
    assert "N/mm" in msg and "override" in msg
    with pytest.raises(InputError, match=r"suspension\.front\.sprng.*valid names under "
                                         r"\[suspension\.front\]:.*spring"):
        load_car(LINKAGE, overrides={"suspension.front.sprng.rate_N_per_m": 1.0})
