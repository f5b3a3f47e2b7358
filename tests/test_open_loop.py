"""Open-loop steering inputs (step, ramp, sine with dwell, sine, table) and the step steer.

References: the closed forms of the inputs (UN R140 / FMVSS 126 sine with dwell: zero
crossings and the dwell at the second peak); the steady state of a step steer equals a
closed-loop run on the circle of the radius the step drives, at the same speed (the
same steady cornering reached by two routes); kinematics of steady cornering, ``a_y =
v r`` at the centre of mass.
"""

import json
import math
from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.driver import OpenLoopSteer, circle, read_driver
from flexpipe.errors import InputError
from flexpipe.vehicle.handling import ay_at, centre_of_mass, step_response

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan.toml"


def test_step_and_ramp_are_their_closed_forms():
    s = OpenLoopSteer.step(30.0, t_start=1.0, rise_time=0.15)
    a = math.radians(30.0)
    assert s.steering_wheel(0.5) == 0.0 and s.steering_wheel(1.0) == 0.0
    assert s.steering_wheel(1.075) == pytest.approx(0.5 * a)
    assert s.steering_wheel(9.0) == pytest.approx(a)
    r = OpenLoopSteer.ramp(-20.0, max_deg=-90.0, t_start=2.0)
    assert r.steering_wheel(3.0) == pytest.approx(math.radians(-20.0))
    assert r.steering_wheel(20.0) == pytest.approx(math.radians(-90.0))


def test_sine_with_dwell_holds_the_second_peak():
    f, dwell, t0, A = 0.7, 0.5, 1.0, 100.0
    s = OpenLoopSteer.sine_with_dwell(A, frequency=f, dwell=dwell, t_start=t0,
                                      direction="right")
    T = 1.0 / f
    deg = lambda t: math.degrees(s.steering_wheel(t))  # noqa: E731
    assert deg(t0) == pytest.approx(0.0, abs=1e-9)
    assert deg(t0 + T / 4) == pytest.approx(-A, rel=1e-3)     # right first
    assert deg(t0 + T / 2) == pytest.approx(0.0, abs=0.05)
    for t in np.linspace(t0 + 0.75 * T, t0 + 0.75 * T + dwell, 7):
        assert deg(t) == pytest.approx(A, rel=1e-3)            # the dwell
    assert deg(t0 + T + dwell) == pytest.approx(0.0, abs=1e-6)
    assert deg(t0 + T + dwell + 5.0) == pytest.approx(0.0, abs=1e-6)


def test_sine_has_its_period():
    s = OpenLoopSteer.sine(10.0, frequency=0.5, cycles=2.0, t_start=0.0)
    t = np.linspace(0.0, 4.0, 401)
    a = np.array([s.steering_wheel(x) for x in t])
    np.testing.assert_allclose(np.degrees(a), 10.0 * np.sin(np.pi * t), atol=0.01)


def test_driver_file_with_an_open_loop_input_and_no_speed_table():
    steering, speed = read_driver(ROOT / "paths" / "driver_step_steer.toml")
    assert isinstance(steering, OpenLoopSteer) and speed is None
    assert math.degrees(steering.steering_wheel(5.0)) == pytest.approx(30.0)
    steering, _ = read_driver(ROOT / "paths" / "driver_sine_with_dwell.toml")
    assert steering.kind == "sine_with_dwell"


@pytest.mark.parametrize("body, words", [
    ('input = "step"\n', "steering_wheel_deg"),
    ('input = "wiggle"\nsteering_wheel_deg = 3\n', "wiggle"),
    ('input = "step"\nsteering_wheel_deg = 3\nrise_time_s = 0\n', "rise_time_s"),
    ('input = "table"\ntime_s = [0, 1, 1]\nsteering_wheel_deg = [0, 5, 6]\n',
     r"entry 2 \(1 s\) does not exceed"),
    ('input = "table"\ntime_s = [0, 1]\nsteering_wheel_deg = [0, 2000]\n',
     "at most 1080 deg"),
    ('input = "ramp"\nrate_deg_per_s = 10\nmax_deg = -40\n', "sign of rate_deg_per_s"),
    ('input = "step"\nsteering_wheel_deg = 3\nstep_deg = 3\n', "step_deg"),
])
def test_bad_open_loop_inputs_name_the_file_and_key(tmp_path, body, words):
    f = tmp_path / "drv.toml"
    f.write_text('[steering]\ntype = "open_loop"\n' + body)
    with pytest.raises(InputError, match=words) as exc:
        read_driver(f)
    assert str(f) in str(exc.value)


def test_unknown_driver_table_is_named(tmp_path):
    f = tmp_path / "drv.toml"
    f.write_text('[steering]\ntype = "open_loop"\ninput = "step"\nsteering_wheel_deg = 3\n'
                 "[speeds]\nkp_Nm_s_per_m = 1\n")
    with pytest.raises(InputError, match=r"unknown table\(s\) \['speeds'\]"):
        read_driver(f)


def test_step_steer_settles_on_the_circle_it_drives():
    car = fp.load_car(CAR)
    v0 = 80 / 3.6
    r = fp.simulate(car, speed=v0, t_end=5.0, body="rigid", output_step=0.01,
                    driver=ROOT / "paths" / "driver_step_steer.toml")
    assert r.status == 0, r.message
    assert r.info["steering"].startswith("open-loop steering: step 30 deg")
    # the road-wheel angle is the input over the steering ratio
    assert math.degrees(r["steer"][-1]) == pytest.approx(30.0 / 15.5, rel=1e-9)
    tail = r.t > 4.0
    cg = centre_of_mass(r, car)
    yaw_rate = np.gradient(np.unwrap(r["yaw"]), r.t)[tail].mean()
    v = r["speed"][tail].mean()
    assert ay_at(r, *cg)[tail].mean() == pytest.approx(v * yaw_rate, rel=0.01)
    # the radius the rear axle centre drives (a circle through its track)
    x, y = r["x_rear"][tail], r["y_rear"][tail]
    cx, cy, c = np.linalg.lstsq(np.c_[2 * x, 2 * y, np.ones(x.size)], x**2 + y**2,
                                rcond=None)[0]
    radius = math.sqrt(c + cx**2 + cy**2)
    ref = fp.simulate(car, path=circle(radius=radius, turns=0.3, lead_in=10.0), speed=v0,
                      t_end=7.0, body="rigid", output_step=0.01)
    assert ref.status == 0, ref.message
    late = ref.t > 5.5
    assert ref["steer"][late].mean() == pytest.approx(r["steer"][tail].mean(), rel=5e-3)
    assert ref["ay"][late].mean() == pytest.approx(r["ay"][tail].mean(), rel=5e-3)
    fig = step_response(r, cg=cg)
    assert fig["yaw_rate_steady_deg_per_s"] == pytest.approx(math.degrees(yaw_rate), rel=1e-3)
    assert 0.0 < fig["yaw_rate_response_time_s"] < fig["yaw_rate_peak_response_time_s"]


def test_cli_run_with_a_step_steer_driver_writes_the_response(tmp_path):
    from flexpipe.cli import main

    out = tmp_path / "step"
    code = main(["run", str(CAR), "--driver", str(ROOT / "paths" / "driver_step_steer.toml"),
                 "--speed", "80", "--t-end", "3.5", "--body", "rigid", "--out", str(out), "-q"])
    assert code == 0
    summary = json.loads((out / "summary.json").read_text())
    step = summary["step_steer"]["rigid"]
    assert step["steering_wheel_deg"] == pytest.approx(30.0)
    assert step["yaw_rate_overshoot_pct"] > 0.0
    assert (out / "steer_response.png").is_file()


class _Run:
    def __init__(self, *, t, channels):
        self.t, self.channels = t, channels

    def __getitem__(self, key):
        return self.channels[key]


def _synthetic_sine_with_dwell(psi0_deg=30.0):
    """A run along heading psi0 whose input is a sine with dwell and whose yaw rate,
    lateral drift and position are closed forms."""
    psi0 = math.radians(psi0_deg)
    s = OpenLoopSteer.sine_with_dwell(100.0, t_start=1.0)
    t = np.round(np.arange(0.0, 6.0, 0.001), 9)
    sw = np.array([s.steering_wheel(x) for x in t])
    r = np.radians(30.0) * np.sin(np.pi * np.clip(t - 1.0, 0.0, None))  # yaw rate
    yaw = psi0 + np.concatenate([[0.0], np.cumsum(0.5 * (r[1:] + r[:-1]) * np.diff(t))])
    lateral = 0.5 * np.clip(t - 1.0, 0.0, None) ** 2   # 1 m/s^2 to the left from BOS
    ch = {"steering_wheel": sw, "yaw": yaw,
          "x": 20.0 * t * math.cos(psi0) - lateral * math.sin(psi0),
          "y": 20.0 * t * math.sin(psi0) + lateral * math.cos(psi0)}
    return _Run(t=t, channels=ch), r


def test_sine_with_dwell_figures_against_their_closed_forms():
    from flexpipe.vehicle.handling import sine_with_dwell_response

    run, r = _synthetic_sine_with_dwell()
    # the centre of mass at the body origin: the position channels are its own
    f = sine_with_dwell_response(run, cg=(0.0, 0.0))
    T = 1.0 / 0.7
    assert f["bos_s"] == pytest.approx(1.0, abs=2e-3)
    assert f["cos_s"] == pytest.approx(1.0 + T + 0.5, abs=2e-3)
    # the input turns negative at 1 + T/2; the yaw rate's first peak after it is its
    # largest negative value, -30 deg/s at t = 2.5 s
    assert f["yaw_rate_peak_deg_per_s"] == pytest.approx(-30.0, rel=1e-4)
    assert f["yaw_rate_peak_time_s"] == pytest.approx(2.5, abs=2e-3)
    cos_ = 1.0 + T + 0.5
    want = math.sin(math.pi * (cos_ + 1.0 - 1.0)) / -1.0
    # (COS is found on the 1 ms grid: r changes by 0.1 % of its peak per ms there)
    assert f["yaw_rate_ratio_cos_plus_1s"] == pytest.approx(want, abs=3e-3)
    assert f["lateral_displacement_bos_plus_1_07s_m"] == pytest.approx(0.5 * 1.07**2, rel=1e-4)
    assert f["responsive"] is False  # 0.57 m < 1.83 m


def test_a_sine_with_dwell_run_reports_the_regulation_figures(tmp_path):
    from flexpipe.scenarios.runner import run_pair

    out = tmp_path / "swd"
    summary = run_pair(CAR, road=None, path=None, speed=80 / 3.6, t_end=4.7, out=out,
                       title="sine with dwell", bodies=("rigid",), log=lambda m: None,
                       progress=False, driver=ROOT / "paths" / "driver_sine_with_dwell.toml")
    assert summary["status"] == 0
    f = json.loads((out / "summary.json").read_text())["sine_with_dwell"]["rigid"]
    assert f["bos_s"] == pytest.approx(1.0, abs=2e-3)  # the file's t_start_s
    assert f["cos_s"] == pytest.approx(1.0 + 1 / 0.7 + 0.5, abs=2e-3)
    assert f["yaw_rate_peak_time_s"] > 1.0 + 0.5 / 0.7  # after the input's reversal
    assert {"stable", "responsive", "yaw_rate_ratio_cos_plus_1_75s"} <= set(f)
    assert (out / "steer_response.png").is_file()


def test_wheel_angle_channels_are_the_ackermann_geometry_at_crawling_speed():
    """At 3 m/s the tyres' aligning moments are small: each front wheel's angle is the
    Ackermann angle of the bicycle angle (closed form for the track and wheelbase)."""
    car = fp.load_car(CAR)
    r = fp.simulate(car, speed=3.0, t_end=4.0, body="rigid", output_step=0.01,
                    driver=(OpenLoopSteer.step(60.0, t_start=0.5), None))
    assert r.status == 0, r.message
    delta = r["steer"][-1]
    W = np.array([c.wheel_center for c in car.corners])
    L, half = car.wheelbase, np.mean(np.abs(W[:2, 1]))
    inner = math.atan(L * math.tan(delta) / (L - half * math.tan(delta)))  # left, a left turn
    outer = math.atan(L * math.tan(delta) / (L + half * math.tan(delta)))
    assert r["wheel_angle_fl"][-1] == pytest.approx(inner, rel=0.01)
    assert r["wheel_angle_fr"][-1] == pytest.approx(outer, rel=0.01)
    for c in ("rl", "rr"):
        assert abs(r[f"wheel_angle_{c}"][-1]) < 1e-4  # rad: the rear wheels do not steer
    before = r.t < 0.45  # straight ahead before the step
    for c in ("fl", "fr", "rl", "rr"):
        assert np.abs(r[f"wheel_angle_{c}"][before]).max() < math.radians(0.05)


def test_open_loop_torque_accelerates_and_brakes_the_car_by_newtons_law():
    """A constant wheel torque T (after a ramp): the car's acceleration is
    ``(sum(T_i / R_l) - F_rr) / (m + sum(J / (R_e R_l)))`` with the ``.tir`` file's rolling
    resistance ``F_rr`` and loaded and effective radii (as in test_rollout.py)."""
    from flexpipe.driver import OpenLoopTorque
    from flexpipe.tires import tire_from_file
    from flexpipe.vehicle import bodymodel
    from flexpipe.vehicle.corners import static_loaded_radius, static_wheel_loads
    from flexpipe.vehicle.simulation import default_driver

    car = fp.load_car(CAR)
    rb = bodymodel.rigid_properties(car)
    mass = rb.mass + car.unsprung_mass
    steer, _ = default_driver(car, mass)
    tire = tire_from_file(car.corners[0].tire)
    c = tire.mf.c
    assert c.QSY2 == c.QSY3 == c.QSY4 == 0.0
    N = static_wheel_loads(car, rb.mass, rb.center_of_mass)
    R_l = np.array([static_loaded_radius(tire, n) for n in N])
    R_e = np.array([float(tire.effective_rolling_radius(tire.unloaded_radius - x))
                    for x in R_l])
    F_rr = float(np.sum(tire.unloaded_radius * N * c.QSY1 * c.LMY / R_l))
    J = np.array([cn.spin_inertia for cn in car.corners])
    for T in (600.0, -1500.0):  # front drive; braking on all four by the brake split
        drv = (steer, OpenLoopTorque.from_table([0.0, 0.5, 0.7], [0.0, 0.0, T]))
        r = fp.simulate(car, speed=15.0, t_end=3.0, body="rigid", driver=drv,
                        output_step=0.01)
        assert r.status == 0, r.message
        assert r["drive_torque"][-1] == pytest.approx(T)
        sel = r.t > 1.5
        a = np.polyfit(r.t[sel], r["speed"][sel], 1)[0]
        share = car.drive.drive_shares() if T > 0 else car.drive.brake_shares()
        want = (np.sum(T * share / R_l) - F_rr) / (mass + np.sum(J / (R_e * R_l)))
        assert a == pytest.approx(want, rel=0.02)


def test_open_loop_torque_from_a_driver_file(tmp_path):
    from flexpipe.driver import OpenLoopTorque

    f = tmp_path / "brake_in_turn.toml"
    f.write_text('[steering]\ntype = "pure_pursuit"\nwheelbase_m = 2.7\n'
                 '[speed]\ntype = "open_loop"\ntime_s = [0, 2, 2.3]\n'
                 'torque_Nm = [0, 0, -2500]\n')
    _, speed = read_driver(f)
    assert isinstance(speed, OpenLoopTorque)
    assert speed.torque_at(2.15) == pytest.approx(-1250.0)
    f.write_text('[steering]\ntype = "pure_pursuit"\nwheelbase_m = 2.7\n'
                 '[speed]\ntype = "open_loop"\ntime_s = [0, 2, 2]\ntorque_Nm = [0, 0, 1]\n')
    with pytest.raises(InputError, match=r"speed\.time_s.*entry 2 \(2 s\) does not exceed") \
            as exc:
        read_driver(f)
    assert str(f) in str(exc.value)
