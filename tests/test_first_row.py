"""The t = 0 output row records the state the integration starts from.

A run starts from the car settled at rest (:mod:`flexpipe.vehicle.settle`); its first row
must hold that state (pitch, travels) on the actual road with its real hub forces, not the
design position the model was built in.  On a rough road the two differ by hundreds of
newtons at a hub (the bug: hub_fl_z 2656 N at t = 0, 3527 N from t = h on).

References: continuity (the row at t = 0 differs from the one at t = h by no more than
about one step of motion, bounded here by the next steps' changes), the parked run from
the same settled coordinates (same pitch and travels), and the static balance (the tyre
normal loads at t = 0 carry the car's weight).
"""

from __future__ import annotations

import pathlib

import numpy as np
import pytest

from flexpipe.vehicle import simulate
from flexpipe.vehicle.spec import load_car

REPO = pathlib.Path(__file__).resolve().parents[1]
CORNERS = ("fl", "fr", "rl", "rr")
H = 1e-3


@pytest.fixture(scope="module")
def runs():
    from flexpipe.scenarios.runner import _straight_road

    car = load_car(REPO / "cars" / "sedan_linkage.toml")
    road = _straight_road()  # ISO 8608 class C
    out = {}
    for speed in (70.0 / 3.6, 0.0):
        res = simulate(car, road=road, speed=speed, t_end=5 * H, body="rigid", h=H,
                       output_step=H)
        assert res.status == 0, res.message
        out[speed] = res
    return out[70.0 / 3.6], out[0.0]


def _step_bound(x, floor):
    """The largest change over one step seen in rows 1..4, doubled, plus ``floor``."""
    return 2.0 * np.max(np.abs(np.diff(x[1:5]))) + floor


@pytest.mark.parametrize("name,floor", [
    *[(f"hub_{c}_{a}", 2.0) for c in CORNERS for a in "xyz"],
    *[(f"travel_{c}", 1e-6) for c in CORNERS],
    ("pitch", 1e-6), ("roll", 1e-6), ("z", 1e-6)])
def test_first_row_continues_into_the_run(runs, name, floor):
    moving, _ = runs
    x = moving.channels[name]
    assert moving.t[1] == pytest.approx(H)
    assert abs(x[0] - x[1]) <= _step_bound(x, floor), (name, x[:5])


def test_first_row_is_the_settled_state(runs):
    moving, parked = runs
    for name in ["pitch", "roll", "z", *[f"travel_{c}" for c in CORNERS]]:
        # same settled coordinates: identical position and travels at t = 0
        assert moving.channels[name][0] == pytest.approx(parked.channels[name][0], abs=1e-9), \
            name
        assert parked.channels[name][0] == pytest.approx(parked.channels[name][1], abs=1e-6), \
            name
    for c in CORNERS:  # the settled car is at rest: its hub loads are static
        assert parked.channels[f"hub_{c}_z"][0] == pytest.approx(
            parked.channels[f"hub_{c}_z"][1], abs=5.0)
        assert moving.channels[f"travel_{c}"][0] != 0.0  # not the design position


def test_first_row_tyre_loads_carry_the_weight(runs):
    moving, parked = runs
    weight = moving.info["mass_total_kg"] * 9.81
    for res in (moving, parked):
        fz = sum(res.channels[f"tire_{c}_Fz"][0] for c in CORNERS)
        assert fz == pytest.approx(weight, rel=0.02)
    # the hub loads of the parked car at t = 0 carry the sprung weight (the body's, the
    # linkage's parts share it with the tyres)
    hub = sum(parked.channels[f"hub_{c}_z"][0] for c in CORNERS)
    assert hub == pytest.approx(moving.info["mass_body_kg"] * 9.81, rel=0.01)
