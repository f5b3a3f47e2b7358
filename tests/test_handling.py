"""The handling diagram (ISO 4138) of the full car on a circle.

References: the kinematics of a car turning on a circle (the Ackermann angle from the
yaw rate and speed, ``atan(L r / v)``, equals ``atan(L / R)`` for the radius the rear
axle drives); the quasi-steady equivalence of a slowly rising speed on the circle and
steady runs at fixed speeds (ISO 4138 methods 1 and 2 give the same understeer angle at
the same lateral acceleration); a synthetic run whose understeer gradient is known.
"""

import math
from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.driver import SpeedProfile, circle
from flexpipe.errors import InputError
from flexpipe.vehicle.handling import handling_diagram, plot

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan.toml"
R = 40.0


def _synthetic(K_deg_per_g, *, L=2.7, radius=R):
    """Channels of a car on a circle whose speed rises 8 -> 16 m/s, steering
    delta = atan(L / R) + K ay: the closed form of a known understeer gradient."""
    t = np.arange(0.0, 20.0, 0.01)
    v = 8.0 + 0.4 * t
    ay = v**2 / radius
    yaw = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) / radius * 0.01)])
    steer = math.atan(L / radius) + np.radians(K_deg_per_g) / 9.81 * ay
    return t, {"ay": ay, "speed": v, "yaw": yaw, "steer": steer}


class _Run:
    def __init__(self, t, ch):
        self.t, self.channels = t, ch

    def __getitem__(self, k):
        return self.channels[k]


@pytest.mark.parametrize("K", [2.5, -0.8])
def test_the_fit_recovers_a_known_gradient(K):
    run = _Run(*_synthetic(K))
    d = handling_diagram(run, wheelbase=2.7, t_from=1.0)
    assert d.gradient_deg_per_g == pytest.approx(K, rel=2e-3)
    assert abs(d.intercept_deg) < 0.01


def test_bad_arguments_say_what_is_valid():
    t, ch = _synthetic(1.0)
    run = _Run(t, ch)
    with pytest.raises(InputError, match="wheelbase"):
        handling_diagram(run, wheelbase=0.0)
    with pytest.raises(InputError, match=r"only 0 samples with \|ay\| in 9 .. 10 m/s\^2 "
                                         r"\(the run covers 2\.0\d \.\. 6\.2\d m/s\^2"):
        handling_diagram(run, wheelbase=2.7, ay_fit=(9.0, 10.0))
    with pytest.raises(InputError, match="no 'steer' channel"):
        handling_diagram(_Run(run.t, {k: ch[k] for k in ("ay", "yaw", "speed")}),
                         wheelbase=2.7)


def test_rising_speed_on_the_circle_equals_steady_runs(tmp_path):
    car = fp.load_car(CAR)
    L = car.wheelbase
    prof = SpeedProfile.from_table([0.0, 2.0, 14.0], np.array([30.0, 30.0, 50.0]) / 3.6)
    ramp = fp.simulate(car, path=circle(radius=R, turns=1.0, lead_in=10.0), speed=prof,
                       t_end=14.0, body="rigid", output_step=0.01)
    assert ramp.status == 0, ramp.message
    d = handling_diagram(ramp, wheelbase=L, t_from=5.0, ay_fit=(2.0, 4.5))
    assert d.n_fit > 100
    assert d.gradient_deg_per_g > 0.0  # this front-heavy sedan understeers
    plot({"rigid": d}, tmp_path / "handling.png", title="test")
    assert (tmp_path / "handling.png").stat().st_size > 10_000
    for kmh in (36.0, 44.0):  # steady runs inside the ramp's range
        r = fp.simulate(car, path=circle(radius=R, turns=0.6, lead_in=10.0),
                        speed=kmh / 3.6, t_end=8.0, body="rigid", output_step=0.01)
        sel = r.t > 6.0
        ay = r["ay"][sel].mean()
        yaw_rate = np.gradient(np.unwrap(r["yaw"]), r.t)[sel].mean()
        ackermann = math.atan(L * yaw_rate / r["speed"][sel].mean())
        # from yaw rate and speed: the circle's atan(L / R), R the radius the rear axle
        # drives (the path's, less the driver's mean lateral error, positive inside)
        e = r["lateral_error"][sel].mean()
        assert ackermann == pytest.approx(math.atan(L / (R - e)), rel=2e-3)
        under = r["steer"][sel].mean() - ackermann
        # the ramp's understeer angle at the same lateral acceleration
        order = np.argsort(d.ay)
        ramp_under = np.interp(ay, d.ay[order], d.understeer[order])
        assert math.degrees(ramp_under) == pytest.approx(math.degrees(under), abs=0.03)


def test_a_circle_run_writes_the_handling_diagram(tmp_path):
    import json

    from flexpipe.scenarios.runner import run_pair

    out = tmp_path / "circle"
    prof = SpeedProfile.from_table([0.0, 1.0, 9.0], np.array([30.0, 30.0, 45.0]) / 3.6)
    summary = run_pair(CAR, road=None, path=ROOT / "paths" / "circle_40m.toml", speed=prof,
                       t_end=9.0, out=out, title="circle", bodies=("rigid",), log=lambda m: None,
                       progress=False)
    assert summary["status"] == 0
    data = json.loads((out / "summary.json").read_text())
    h = data["handling"]["rigid"]
    assert h["understeer_gradient_deg_per_g"] > 0.0 and h["samples_fitted"] > 100
    assert (out / "handling.png").is_file() and "handling.png" in data["file_descriptions"]


def test_a_path_shared_by_two_runs_gives_the_same_run():
    """The projection onto a path that overlaps itself (laps of a circle) continues from
    its previous point; a second run on the same Path object must not start from where
    the first ended (it once stuck on a later lap and drove off at the path's end)."""
    p = circle(radius=15.0, turns=1.3, lead_in=10.0, transition=10.0)
    walk = [p.project(float(x), float(y))[0] for x, y in zip(p.x[::5], p.y[::5], strict=True)]
    assert np.all(np.diff(walk) > 0.0)  # along the laps in order
    p.reset_projection()
    assert p.project(float(p.x[10]), float(p.y[10]))[0] == pytest.approx(p.s[10], abs=1e-9)
    car = fp.load_car(CAR)
    runs = [fp.simulate(car, path=p, speed=8.0, t_end=15.0, body="rigid", output_step=0.01)
            for _ in range(2)]
    assert runs[0].status == runs[1].status == 0
    np.testing.assert_array_equal(runs[0]["lateral_error"], runs[1]["lateral_error"])
    assert np.abs(runs[0]["lateral_error"][runs[0].t > 3.0]).max() < 0.3
