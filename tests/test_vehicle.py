"""Full car with a rigid body: statics, ride frequencies, cornering, slalom tracking, errors.

References are independent of the simulation: the weight of the car, the closed-form
two-degree-of-freedom bounce/pitch model, v^2/R of a circular path, Newton's second law
of the body, the driver issue's 0.3 m tracking bound.
"""

from __future__ import annotations

import math
import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from flexpipe.driver import Path as DPath
from flexpipe.driver import slalom
from flexpipe.errors import InputError
from flexpipe.roads import flat
from flexpipe.tires import tire_from_file
from flexpipe.vehicle import load_car, simulate
from flexpipe.vehicle.simulation import prepare
from flexpipe.vehicle.spec import CORNERS

ROOT = Path(__file__).resolve().parents[1]
SEDAN = ROOT / "cars" / "sedan.toml"
G = 9.81


@pytest.fixture(scope="module", autouse=True)
def _cache(tmp_path_factory):
    mp = pytest.MonkeyPatch()
    mp.setenv("FLEXPIPE_CACHE", str(tmp_path_factory.mktemp("cache")))
    yield
    mp.undo()


@pytest.fixture(scope="module")
def car():
    return load_car(SEDAN)


@pytest.fixture(scope="module")
def prep(car):
    return prepare(car, body="rigid", speed=0.0)


def _sum(r, fmt):
    return sum(r[fmt.format(c)] for c in CORNERS)


def test_static_equilibrium_and_ride_height(car, prep):
    r = simulate(car, speed=0.0, t_end=1.5, body="rigid", prepared=prep)
    assert r.status == 0, r.message
    raw = tomllib.loads(SEDAN.read_text())
    unsprung = sum(raw["corners"][c]["unsprung_mass_kg"] for c in CORNERS)
    m_body = r.info["mass_body_kg"]
    # body weight = added masses of the file + the BIW (the FE mass); unsprung from the file
    assert r.info["mass_total_kg"] == pytest.approx(m_body + unsprung)
    end = r.t > 1.0
    hub_z = _sum(r, "hub_{}_z")[end].mean()
    tire_z = _sum(r, "tire_{}_Fz")[end].mean()
    assert hub_z == pytest.approx(m_body * G, rel=0.005)
    assert tire_z == pytest.approx((m_body + unsprung) * G, rel=0.005)
    # design position = ride height at rest: body where the file puts it, travel ~ 0
    assert abs(r["z"][end]).max() < 1e-3
    assert abs(r["pitch"][end]).max() < 1e-3
    for c in CORNERS:
        assert abs(r[f"travel_{c}"][end]).max() < 1e-3


def _two_dof(car, prep):
    """Closed-form bounce/pitch frequencies (Hz): ride rates (spring + tyre in series)."""
    rb = prep["rigid"]
    tire = tire_from_file(car.corners[0].tire)
    d = np.array([tire.unloaded_radius - c.wheel_center[2] for c in car.corners])
    kt = tire.vertical.k + 3 * tire.vertical.k3 * d**2  # tangent at the static deflection
    ks = np.array([c.spring_rate for c in car.corners])
    k = ks * kt / (ks + kt)
    x = np.array([c.hardpoint[0] for c in car.corners]) - rb.center_of_mass[0]
    K = np.array([[k.sum(), -(k * x).sum()], [-(k * x).sum(), (k * x * x).sum()]])
    M = np.diag([rb.mass, rb.inertia[1, 1]])
    w2, V = np.linalg.eig(np.linalg.solve(M, K))
    order = np.argsort(w2.real)
    return np.sqrt(w2.real[order]) / (2 * np.pi), V.real[:, order]


def _crossing_frequency(t, s):
    """Frequency (Hz) from the mean spacing of interpolated zero crossings."""
    s = s - s.mean()
    i = np.flatnonzero(np.sign(s[:-1]) != np.sign(s[1:]))
    tz = t[i] - s[i] * (t[i + 1] - t[i]) / (s[i + 1] - s[i])
    return (len(tz) - 1) / (2 * (tz[-1] - tz[0]))


def test_bounce_and_pitch_match_two_dof_estimate(car, tmp_path):
    """Undamped car rolling on a flat road, each ride mode excited by its own shape."""
    text = SEDAN.read_text().replace('"../', f'"{ROOT.as_posix()}/')
    text = re.sub(r"damper_(jounce|rebound)_N_s_per_m = [0-9.]+", r"damper_\1_N_s_per_m = 0.0",
                  text)
    path = tmp_path / "undamped.toml"
    path.write_text(text)
    undamped = load_car(path)
    prep = prepare(undamped, body="rigid", speed=10.0)
    f_ref, V = _two_dof(undamped, prep)
    for mode, (signal, f0) in enumerate(zip(("z", "pitch"), f_ref, strict=True)):
        v = V[:, mode] / np.abs(V[:, mode]).max()
        r = simulate(undamped, speed=10.0, t_end=4.0, body="rigid", prepared=prep,
                     initial_rates=(0.05 * v[0], 0.0, -0.05 * v[1]))
        assert r.status == 0, r.message
        sel = r.t > 0.3
        f = _crossing_frequency(r.t[sel], r[signal][sel])
        assert f == pytest.approx(f0, rel=0.03), (signal, f, f0)


def test_steady_cornering_lateral_acceleration(car, prep):
    R, v = 40.0, 12.0
    s = np.arange(0.0, 30.0, 0.5)
    phi = np.arange(0.5 / R, 1.5 * 2 * np.pi, 0.5 / R)
    circle = DPath.from_xy(np.r_[s, 30 + R * np.sin(phi)], np.r_[0 * s, R * (1 - np.cos(phi))])
    r = simulate(car, path=circle, speed=v, t_end=9.0, body="rigid", prepared=prep)
    assert r.status == 0, r.message
    steady = r.t > 6.0
    speed = r["speed"][steady].mean()
    ay = r["ay"][steady].mean()
    assert ay == pytest.approx(speed**2 / R, rel=0.02)
    assert abs(r["lateral_error"][steady]).max() < 0.3
    # Newton's second law of the body, in its own axes: hub forces = m (a - g)
    roll, pitch = r["roll"][steady].mean(), r["pitch"][steady].mean()
    g_y = -G * math.sin(roll) * math.cos(pitch)
    assert _sum(r, "hub_{}_y")[steady].mean() == pytest.approx(
        r.info["mass_body_kg"] * (ay - g_y), rel=0.01)
    # outer (right) wheels carry more load in a left turn
    assert r["tire_fr_Fz"][steady].mean() > r["tire_fl_Fz"][steady].mean()


def test_slalom_tracked_within_driver_bound(car, prep):
    path = slalom(cone_spacing=18.0, n_cones=5, offset=0.8, lead_in=40.0, lead_out=40.0)
    r = simulate(car, path=path, speed=60 / 3.6, t_end=7.0, body="rigid", prepared=prep)
    assert r.status == 0, r.message
    assert abs(r["lateral_error"][r.t > 1.0]).max() < 0.3
    assert abs(r["speed"] - 60 / 3.6).max() < 1.0


@pytest.mark.parametrize("kwargs, key", [
    (dict(speed=-1.0, t_end=1.0), "speed"),
    (dict(speed=10.0, t_end=0.0), "t_end"),
    (dict(speed=10.0, t_end=1.0, body="soft"), "body"),
    (dict(speed=10.0, t_end=1.0, h=0.05), "h"),
    (dict(speed=10.0, t_end=1.0, road=42), "road"),
    (dict(speed=30.0, t_end=10.0, road=flat(100.0)), None),
])
def test_bad_arguments_raise_up_front(car, prep, kwargs, key):
    with pytest.raises(InputError) as exc:
        simulate(car, prepared=prep, **kwargs)
    if key is not None:
        assert f"'{key}'" in str(exc.value)
    else:
        assert "covers" in str(exc.value)


def test_divergence_gives_status_and_time(tmp_path):
    """An anti-roll bar of 1e8 N/m (applied explicitly) cannot be integrated at h = 5 ms."""
    from flexpipe.roads import iso8608

    text = SEDAN.read_text().replace('"../', f'"{ROOT.as_posix()}/')
    text = text.replace("rate_N_per_m = 18000.0", "rate_N_per_m = 1.0e6")
    path = tmp_path / "stiff_bar.toml"
    path.write_text(text)
    road = iso8608("C", length=200.0, dx=0.05, seed=3, track_width=1.55, fade=5.0)
    r = simulate(path, road=road, speed=20.0, t_end=3.0, body="rigid", h=5e-3)
    assert r.status == -1
    assert re.search(r"t = \d+\.\d+ s", r.message)
    assert "diverge" in r.message or "converge" in r.message or "non-finite" in r.message
    assert r.simulated_time < 3.0
    assert len(r.t) == len(r["hub_fl_z"])


def test_result_csv_round_trip(car, prep, tmp_path):
    r = simulate(car, speed=5.0, t_end=0.2, body="rigid", prepared=prep)
    out = r.to_csv(tmp_path / "run.csv")
    header = out.read_text().splitlines()[0].split(",")
    assert header[0] == "t [s]" and "hub_fl_z [N]" in header and "roll [rad]" in header
    values = np.loadtxt(out, delimiter=",", skiprows=1)
    data = {h.split(" [")[0]: values[:, i] for i, h in enumerate(header)}
    np.testing.assert_allclose(data["t"], r.t, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(data["hub_fl_z"], r["hub_fl_z"], rtol=1e-6)
    assert not list(tmp_path.glob(".*"))  # no temporary file left behind
