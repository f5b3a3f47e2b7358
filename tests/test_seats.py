"""Seats (:mod:`flexpipe.vehicle.seats`): the base-excited one-degree-of-freedom
transmissibility in closed form, the run's seat channel and SEAT value against the floor's
spectrum filtered in the frequency domain, and bad seat tables named by file and key."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.errors import InputError
from flexpipe.scenarios.comfort import ride_summary
from flexpipe.scenarios.runner import _straight_road
from flexpipe.sweeps.iso2631 import response
from flexpipe.vehicle.seats import Seat

REPO = Path(__file__).resolve().parents[1]
SAMPLE = REPO / "cars" / "sedan_linkage.toml"


def _closed_form(f, fn, zeta):
    """|T| of a base-excited mass on a spring and damper: sqrt(1 + (2 zeta r)^2) /
    sqrt((1 - r^2)^2 + (2 zeta r)^2), r = f / fn."""
    r = f / fn
    return np.sqrt((1 + (2 * zeta * r) ** 2) / ((1 - r * r) ** 2 + (2 * zeta * r) ** 2))


@pytest.mark.parametrize("f", [0.5, 2.0, 3.72, 5.66, 8.0, 20.0])
def test_a_sine_through_the_seat_has_the_closed_form_transmissibility(f):
    seat = Seat("s", "floor", 4.0, 0.3)
    dt = 2.5e-4
    t = np.arange(int(round(30.0 / dt))) * dt
    a = np.sin(2 * np.pi * f * t)
    y = seat.acceleration(t, a)
    steady = t >= 15.0  # the start's transient has decayed (time constant 0.13 s)
    # amplitude and phase of the steady response: least squares on sin and cos
    basis = np.column_stack([np.sin(2 * np.pi * f * t[steady]), np.cos(2 * np.pi * f * t[steady])])
    (s, c), *_ = np.linalg.lstsq(basis, y[steady], rcond=None)
    T = seat.transmissibility(f)
    assert np.hypot(s, c) == pytest.approx(_closed_form(f, 4.0, 0.3), rel=2e-4)
    assert abs(T) == pytest.approx(_closed_form(f, 4.0, 0.3), rel=1e-12)
    assert np.arctan2(c, s) == pytest.approx(np.angle(T), abs=2e-3)


@pytest.mark.parametrize("f", [1.0, 3.0, 9.0])
def test_an_in_plane_resonance_filters_its_axis_and_an_axis_without_one_passes(f):
    seat = Seat("s", "floor", 4.0, 0.3, fore_aft=(3.0, 0.2))
    dt = 2.5e-4
    t = np.arange(int(round(30.0 / dt))) * dt
    a = np.sin(2 * np.pi * f * t)
    steady = t >= 15.0
    x = seat.acceleration(t, a, "x")[steady]
    assert np.sqrt(2 * np.mean(x**2)) == pytest.approx(_closed_form(f, 3.0, 0.2), rel=5e-4)
    assert np.array_equal(seat.acceleration(t, a, "y"), a)  # lateral: the floor's
    assert abs(seat.transmissibility(f, "y")) == 1.0


def test_a_constant_floor_acceleration_reaches_the_seat_unchanged():
    seat = Seat("s", "floor", 4.0, 0.3)
    t = np.arange(0, 5.0, 1e-3)
    y = seat.acceleration(t, np.full_like(t, 2.0))
    assert y[0] == 0.0  # at rest on the floor: the cushion takes the step first
    assert y[-1] == pytest.approx(2.0, rel=1e-9)


@pytest.fixture(scope="module")
def run():
    return fp.simulate(str(SAMPLE), road=_straight_road(), speed=70 / 3.6, t_end=6.0,
                       body="rigid", progress=False)


def test_the_seat_of_a_run_answers_its_floor_as_its_transmissibility_says(run):
    assert run.status == 0, run.message
    assert run.info["seats"] == {"driver_seat": "driver_floor"}
    ch = run.channels
    for k in "xy":  # a seat rigid in its plane
        assert np.array_equal(ch[f"acc_driver_seat_{k}"], ch[f"acc_driver_floor_{k}"])
    t = run.t
    dt = float(t[1] - t[0])
    floor, seat = ch["acc_driver_floor_z"], ch["acc_driver_seat_z"]
    # independent method: the floor's spectrum times T(j w), zero-padded so that the
    # product is the linear convolution of a record that starts at rest
    n = len(t)
    f = np.fft.rfftfreq(4 * n, dt)
    X = np.fft.rfft(floor, 4 * n)
    r = f / 4.0
    T = (1 + 0.6j * r) / (1 - r * r + 0.6j * r)  # base excitation, zeta = 0.3, in closed form
    by_fft = np.fft.irfft(T * X, 4 * n)[:n]
    assert np.abs(by_fft - seat).max() < 5e-3 * np.std(seat)
    # its SEAT value in the run's summary: Wk-weighted seat over floor RMS, from t = 1 s,
    # against the same weighting applied in the frequency domain (the standard's
    # weighting function, checked against its table in test_iso2631.py)
    W = response(np.maximum(f, 1e-9), "Wk")
    W[0] = 0.0
    keep = t >= 1.0
    w_floor = np.fft.irfft(W * X, 4 * n)[:n][keep]
    w_seat = np.fft.irfft(W * T * X, 4 * n)[:n][keep]
    seat_value = 100 * np.sqrt(np.mean(w_seat**2) / np.mean(w_floor**2))
    out = ride_summary({"rigid": run}, t_from=1.0)["ride_comfort"]["rigid"]["driver_seat"]
    assert out["floor_point"] == "driver_floor"
    assert out["SEAT_%"] == pytest.approx(seat_value, rel=0.01)


@pytest.mark.parametrize("table, key, words", [
    ('floor_point = "nowhere"\nnatural_frequency_hz = 4.0\ndamping_ratio = 0.3',
     "body.seats.s.floor_point", "'nowhere' is not a [body.points] name; valid: "),
    ('floor_point = "driver_floor"\nnatural_frequency_hz = 0.0\ndamping_ratio = 0.3',
     "body.seats.s.natural_frequency_hz", "must be >= 0.5"),
    ('floor_point = "driver_floor"\nnatural_frequency_hz = 4.0\ndamping_ratio = 0',
     "body.seats.s.damping_ratio", "must be > 0"),
    ('floor_point = "driver_floor"\nnatural_frequency_hz = 4.0\ndamping_ratio = 0.3\n'
     'stiffness_N_per_m = 1e4', "stiffness_N_per_m", "unknown key"),
    ('floor_point = "driver_floor"\nnatural_frequency_hz = 4.0\ndamping_ratio = 0.3\n'
     'fore_aft_frequency_hz = 3.0', "body.seats.s.fore_aft_frequency_hz",
     "give both fore_aft_frequency_hz and fore_aft_damping_ratio"),
    ('floor_point = "driver_floor"\nnatural_frequency_hz = 4.0\ndamping_ratio = 0.3\n'
     'lateral_frequency_hz = 30.0\nlateral_damping_ratio = 0.2',
     "body.seats.s.lateral_frequency_hz", "must be <= 20"),
])
def test_a_bad_seat_is_named_by_file_and_key(tmp_path, table, key, words):
    p = tmp_path / "variant.toml"
    p.write_text(f'base = "{SAMPLE}"\n[body.seats.s]\n{table}\n')
    with pytest.raises(InputError) as info:
        fp.load_car(p)
    msg = str(info.value)
    assert "variant.toml" in msg and key in msg and words in msg, msg


def test_a_seat_named_as_a_point_is_refused(tmp_path):
    p = tmp_path / "variant.toml"
    p.write_text(f'base = "{SAMPLE}"\n[body.seats.rear_floor]\nfloor_point = "driver_floor"\n'
                 'natural_frequency_hz = 4.0\ndamping_ratio = 0.3\n')
    with pytest.raises(InputError, match="seat name 'rear_floor' is also a \\[body.points\\]"):
        fp.load_car(p)


def test_flexpipe_info_lists_the_seat_as_the_car_file_gives_it():
    import tomllib

    from flexpipe.vehicle.describe import car_text

    table = tomllib.loads(SAMPLE.read_text())["body"]["seats"]["driver_seat"]
    text = car_text(fp.load_car(SAMPLE))
    assert (f"seat driver_seat on {table['floor_point']}: "
            f"{table['natural_frequency_hz']:g} Hz, damping ratio "
            f"{table['damping_ratio']:g}") in text, text


def test_an_in_plane_resonance_reaches_the_runs_channel_and_flexpipe_info(tmp_path):
    from flexpipe.vehicle.describe import car_text
    from flexpipe.vehicle.seats import seat_channels

    p = tmp_path / "variant.toml"
    p.write_text(f'base = "{SAMPLE}"\n[body.seats.driver_seat]\nfore_aft_frequency_hz = 3.0\n'
                 'fore_aft_damping_ratio = 0.2\n')
    car = fp.load_car(p)
    (seat,) = car.body.seats
    assert (seat.natural_frequency_hz, seat.fore_aft, seat.lateral) == (4.0, (3.0, 0.2), None)
    assert "fore-aft 3 Hz, 0.2" in car_text(car)
    t = np.arange(0.0, 2.0, 1e-3)
    floor = {f"acc_driver_floor_{k}": np.sin(2 * np.pi * (2 + i) * t)
             for i, k in enumerate("xyz")}
    out = seat_channels(car.body.seats, t, floor)
    for k in "xyz":
        assert np.array_equal(out[f"acc_driver_seat_{k}"],
                              seat.acceleration(t, floor[f"acc_driver_floor_{k}"], k))
    assert np.array_equal(out["acc_driver_seat_y"], floor["acc_driver_floor_y"])


def test_a_still_floor_gives_no_seat_value_rather_than_nan():
    from types import SimpleNamespace

    t = np.arange(0.0, 4.0, 1e-3)
    still = np.zeros_like(t)
    ch = {f"acc_{p}_{k}": still for p in ("floor", "seat") for k in "xyz"}
    run = SimpleNamespace(t=t, channels=ch, status=0, info={"seats": {"seat": "floor"}})
    out = ride_summary({"rigid": run}, t_from=1.0)["ride_comfort"]["rigid"]["seat"]
    assert out["SEAT_%"] is None  # 0 / 0: summary.json stays valid JSON
