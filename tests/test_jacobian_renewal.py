"""Newton's Jacobian renewed as the car turns (flexpipe.exu.timeloop.JACOBIAN_RENEW_DEG).

The joints' constraint Jacobians are in global axes, so the one Jacobian modified Newton
keeps goes stale as the car yaws.  A run through a slalom renews it each time the body
has turned by the set angle.  That changes how Newton gets to the step's solution, not
the solution: both runs agree with a run at a tolerance ten thousand times tighter within
what the default tolerance allows (README: 0.67 % of the hub forces' fluctuation at
1e-4 against 1e-8 on the straight road)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import flexpipe.exu.timeloop as timeloop
from flexpipe.driver import slalom
from flexpipe.roads import iso8608
from flexpipe.vehicle import load_car, simulate

LINKAGE_CAR = Path(__file__).resolve().parents[1] / "cars" / "sedan_linkage.toml"
T_END = 4.5
HUBS = [f"hub_{c}_{a}" for c in ("fl", "fr", "rl", "rr") for a in "xyz"]


def _run(car, monkeypatch, *, renew_deg, rtol=None):
    monkeypatch.setattr(timeloop, "JACOBIAN_RENEW_DEG", renew_deg)
    if rtol is not None:
        run = timeloop.run

        def tight(system, *a, **k):
            system.newton_rtol = rtol
            return run(system, *a, **k)

        monkeypatch.setattr(timeloop, "run", tight)
    path = slalom(cone_spacing=18.0, n_cones=3, offset=0.8, lead_in=36.0, lead_out=36.0)
    road = iso8608("B", length=180.0, dx=0.05, seed=3, track_width=1.55, fade=5.0)
    r = simulate(car, road=road, path=path, speed=60 / 3.6, t_end=T_END, body="rigid")
    assert r.status == 0, r.message
    monkeypatch.undo()
    return r


def _worst_percent(r, ref):
    """Worst hub channel's RMS difference after 0.5 s, % of the reference's fluctuation."""
    m = ref.t >= 0.5
    return max(100 * np.sqrt(np.mean((r[k][m] - ref[k][m]) ** 2)) / np.std(ref[k][m])
               for k in HUBS)


@pytest.mark.slow
def test_a_turning_car_renews_its_jacobian_and_keeps_its_solution(monkeypatch):
    car = load_car(LINKAGE_CAR)
    renewed = _run(car, monkeypatch, renew_deg=2.0)
    kept = _run(car, monkeypatch, renew_deg=math.inf)
    tight = _run(car, monkeypatch, renew_deg=2.0, rtol=1e-8)
    assert np.degrees(np.ptp(renewed["yaw"])) > 10.0  # the car did turn
    assert kept.info["newton_jacobians"] == 1
    assert renewed.info["newton_jacobians"] > 5
    assert (renewed.info["newton_iterations_per_step"]
            < kept.info["newton_iterations_per_step"] - 0.5)
    for r in (renewed, kept):
        assert _worst_percent(r, tight) < 1.0
