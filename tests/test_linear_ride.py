"""Ride on a random road from the linear model (flexpipe.vehicle.linear_ride).

References, each independent of the spectral route under test:

- a quarter car on an ISO 8608 road (exponent 2: the road's vertical velocity is white
  noise): the stationary covariance of its state equations, from the Lyapunov equation;
- two uncoupled quarter cars on tracks of constant coherence: the variance of their sum
  and difference, ``2 sigma^2 (1 +- gamma)``;
- the sample car's linear model run in time (``scipy.signal.lsim``) over roads synthesised
  with the same spectrum by :func:`flexpipe.roads.iso8608`, each wheel reading its own
  track at its own place, and its RMS and ISO 2631-1 weighted RMS taken from the samples.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest
from scipy.linalg import solve_continuous_lyapunov

from flexpipe.errors import InputError
from flexpipe.roads import ISO8608_GD0, ISO8608_N0
from flexpipe.sweeps.iso2631 import comfort_reaction
from flexpipe.vehicle.dynamics import ROAD_NORMAL_HALF_BASE_M
from flexpipe.vehicle.linear_ride import output_psd, ride_response, road_psd

# quarter car: sprung / unsprung mass (kg), spring, damper, tyre (N/m, N s/m)
MS, MU, KS, CS, KT = 400.0, 40.0, 2.2e4, 1.5e3, 2.0e5


def _quarter_car():
    """States (zs - zr, zu - zr, vs, vu), input the road's vertical velocity."""
    A = np.array([[0.0, 0.0, 1.0, 0.0],
                  [0.0, 0.0, 0.0, 1.0],
                  [-KS / MS, KS / MS, -CS / MS, CS / MS],
                  [KS / MU, -(KS + KT) / MU, CS / MU, -CS / MU]])
    E = np.array([-1.0, -1.0, 0.0, 0.0])
    # outputs: body acceleration, tyre force about static, suspension travel
    C = np.vstack([A[2], [0.0, -KT, 0.0, 0.0], [1.0, -1.0, 0.0, 0.0]])
    return A, E, C


def _quarter_car_response(f):
    """Outputs per metre of road height (the road displacement input zr)."""
    A, E, C = _quarter_car()
    s = 2j * np.pi * f
    # x' = A x + E zr'  with zr' = s zr
    X = np.linalg.solve(s[:, None, None] * np.eye(4) - A, (E[:, None] * s[None, :]).T[..., None])
    return (C @ X)[..., 0]


def test_quarter_car_rms_equals_lyapunov_covariance():
    v, road_class = 20.0, "C"
    # the road's vertical velocity is white: one-sided PSD (2 pi n0)^2 Gd(n0) V, so the
    # Lyapunov intensity is half of it
    g_v = (2 * np.pi * ISO8608_N0) ** 2 * ISO8608_GD0[road_class] * v
    A, E, C = _quarter_car()
    P = solve_continuous_lyapunov(A, -0.5 * g_v * np.outer(E, E))
    sigma = np.sqrt(np.diag(C @ P @ C.T))
    # the spectral route over a band wide enough to hold every output's variance
    f = np.geomspace(v * 1e-5, v * 1e4, 20000)
    H = _quarter_car_response(f)
    G = road_psd(f, road_class=road_class, speed=v, n_band=(1e-5, 1e4))
    S = output_psd(G, H, np.zeros_like(H), 1.0)
    rms = np.sqrt(np.trapezoid(S, f, axis=0))
    np.testing.assert_allclose(rms, sigma, rtol=1e-4)
    # the same outputs with independent tracks and the car answering both alike
    np.testing.assert_allclose(np.sqrt(np.trapezoid(output_psd(G, H, H, 0.0), f, axis=0)),
                               sigma, rtol=1e-4)


@pytest.mark.parametrize("gamma", [0.0, 0.4, 1.0])
def test_coherence_splits_sum_and_difference(gamma):
    """Two quarter cars, one per track: the left output plus the right one answers the
    road on both tracks with 2 H, their difference the opposite tracks with 2 H."""
    v = 15.0
    A, E, C = _quarter_car()
    g_v = (2 * np.pi * ISO8608_N0) ** 2 * ISO8608_GD0["B"] * v
    var = np.diag(C @ solve_continuous_lyapunov(A, -0.5 * g_v * np.outer(E, E)) @ C.T)
    f = np.geomspace(v * 1e-5, v * 1e4, 20000)
    H = _quarter_car_response(f)
    G = road_psd(f, road_class="B", speed=v, n_band=(1e-5, 1e4))
    total = np.trapezoid(output_psd(G, 2 * H, 0 * H, gamma), f, axis=0)
    diff = np.trapezoid(output_psd(G, 0 * H, 2 * H, gamma), f, axis=0)
    np.testing.assert_allclose(total, 2 * var * (1 + gamma), rtol=1e-4, atol=1e-12 * var.max())
    np.testing.assert_allclose(diff, 2 * var * (1 - gamma), rtol=1e-4, atol=1e-12 * var.max())


def test_comfort_reactions_follow_iso2631_annex_c():
    assert comfort_reaction(0.2) == "not uncomfortable"
    assert comfort_reaction(0.4) == "a little uncomfortable"
    assert comfort_reaction(0.55) == "a little uncomfortable / fairly uncomfortable"
    assert comfort_reaction(1.1) == "uncomfortable"
    assert comfort_reaction(1.3) == "uncomfortable / very uncomfortable"
    assert comfort_reaction(3.0) == "extremely uncomfortable"


def test_road_psd_refuses_bad_input():
    with pytest.raises(InputError, match="road class"):
        road_psd([1.0], road_class="Z", speed=10.0)
    with pytest.raises(InputError, match="speed > 0"):
        road_psd([1.0], road_class="C", speed=0.0)
    with pytest.raises(InputError, match="coherence"):
        output_psd(np.ones(2), np.ones((2, 1)), np.ones((2, 1)), 1.5)


# ----------------------------------------------------------------- the sample car
ROOT = Path(__file__).resolve().parent.parent
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"
V = 70 / 3.6


@pytest.fixture(scope="module")
def modes():
    import flexpipe as fp

    return {body: fp.linear_modes(LINKAGE, body=body, speed=V)
            for body in ("rigid", "flexible")}


def _track_width(m) -> float:
    y = np.asarray(m.info["wheel_y_m"], dtype=float)
    return float(np.mean(np.abs(y[0::2] - y[1::2])))


def _time_run(m, road, *, dt=1e-3, histories=False):
    """The linear model run in time over two periods of the periodic ``road``; RMS and
    ISO 2631-1 weighted RMS of every output and then each seat's over the second period
    (steady), or with ``histories`` the outputs over it (about their means)."""
    from scipy.signal import lsim

    from flexpipe.sweeps.iso2631 import response

    period = road.x[-1] - road.x[0]
    steps = round(period / m.speed / dt)  # a whole number of samples per period
    dt = period / m.speed / steps
    t = np.arange(2 * steps) * dt
    n = road.x.size - 1

    def at(h, s):
        return np.interp(np.mod(s, period), road.x - road.x[0], np.append(h[:n], h[0]))

    e = ROAD_NORMAL_HALF_BASE_M

    def slope(h, s):  # as a run's tyre meets it: the central difference over +-e
        return (at(h, s + e) - at(h, s - e)) / (2.0 * e)

    x = np.asarray(m.info["wheel_x_m"], dtype=float)
    y = np.asarray(m.info["wheel_y_m"], dtype=float)
    n_w = x.size
    U = np.zeros((t.size, 3 * n_w))
    for i in range(n_w):
        s = m.speed * t - (x.max() - x[i])  # the front wheels lead
        h = road.left if y[i] > 0 else road.right
        U[:, i] = at(h, s)
        U[:, n_w + i] = slope(h, s)
        axle = slice(i - i % 2, i - i % 2 + 2)
        U[:, 2 * n_w + i] = (at(road.left, s) - at(road.right, s)) / abs(np.diff(y[axle])[0])
    _, out, _ = lsim((m.A, m.B, m.C, m.D), U, t)
    names = list(m.outputs)
    # each seat: its floor point's motion through the seat's own ODE per axis that has a
    # resonance, z'' + 2 zeta w z' + w^2 z = -a_floor, the seat's acceleration
    # -(2 zeta w z' + w^2 z); the floor's along an axis without one
    for seat in m.info.get("seats", ()):
        floor = seat["floor_point"]
        modes_of = {"x": seat["fore_aft"], "y": seat["lateral"],
                    "z": (seat["natural_frequency_hz"], seat["damping_ratio"])}
        for ax in "xyz":
            a = out[:, names.index(f"acc_{floor}_{ax}")]
            if modes_of[ax] is not None:
                fn, zeta = modes_of[ax]
                w = 2 * np.pi * fn
                _, a, _ = lsim(([[0, 1], [-w * w, -2 * zeta * w]], [[0], [-1]],
                                [[-w * w, -2 * zeta * w]], [[0]]), a, t)
            out = np.column_stack([out, a])
            names.append(f"acc_{seat['name']}_{ax}")
    out = out[steps:] - out[steps:].mean(axis=0)
    if histories:
        return out
    rms = np.sqrt(np.mean(out**2, axis=0))
    w_rms = np.full(rms.shape, np.nan)
    f = np.fft.rfftfreq(steps, dt)
    for j, name in enumerate(names):
        if name.startswith("acc_"):  # periodic record: weighted exactly through its FFT
            aw = np.fft.irfft(np.fft.rfft(out[:, j]) * response(f, "Wk" if name[-1] == "z"
                                                                  else "Wd"), steps)
            w_rms[j] = np.sqrt(np.mean(aw**2))
    return rms, w_rms


@pytest.mark.parametrize(("body", "coherence", "length", "tol"), [
    ("rigid", 1.0, 400.0, 0.01), ("flexible", 1.0, 400.0, 0.01),
    # a random right track: one 3.2 km road's RMS scatters about the spectrum's by
    # up to 2 % (measured over four seeds)
    ("rigid", "isotropic", 3200.0, 0.03)])
def test_spectra_equal_the_linear_model_run_over_a_synthesised_road(modes, body, coherence,
                                                                    length, tol):
    from flexpipe.roads import iso8608

    m = modes[body]
    B = _track_width(m)
    road = iso8608("C", length=length, dx=0.02, seed=0, track_width=B, coherence=coherence)
    rms, w_rms = _time_run(m, road)
    r = ride_response(m, "C", coherence=coherence, track_width=B)
    from flexpipe.vehicle.linear import output_unit

    # the car's outputs and, after them, the seats' (the sample's driver seat)
    assert r.outputs[:len(m.outputs)] == m.outputs
    assert r.outputs[len(m.outputs):] == ("acc_driver_seat_x", "acc_driver_seat_y",
                                          "acc_driver_seat_z")
    acc = np.array([name.startswith("acc_") for name in r.outputs])
    assert {output_unit(name) for name in r.outputs} == {"N", "m", "m/s^2"}
    # outputs of weight, against the largest of their unit: the lateral accelerations on
    # identical tracks are a mirror asymmetry's (rigid: none; both routes agree on that)
    unit = np.array([output_unit(name) for name in r.outputs])
    scale = np.array([r.rms[unit == u].max() for u in unit])
    material = r.rms > 0.02 * scale
    np.testing.assert_allclose(rms[material], r.rms[material], rtol=tol)
    assert np.all(np.abs(rms - r.rms)[~material] <= 0.02 * scale[~material])
    np.testing.assert_allclose(w_rms[acc & material], r.weighted_rms[acc & material],
                               rtol=tol)
    assert set(r.points) == {name[4:-2] for name in r.outputs if name.endswith("_z")
                             and name.startswith("acc_")}
    seat_value = 100 * w_rms[r.outputs.index("acc_driver_seat_z")] / w_rms[
        r.outputs.index("acc_driver_floor_z")]
    assert r.points["driver_seat"]["SEAT_%"] == pytest.approx(seat_value, rel=tol)
    static = np.asarray(m.info["tire_Fz_N"])
    np.testing.assert_allclose([r.dynamic_load[c] for c in ("fl", "fr", "rl", "rr")],
                               r.rms[:4] / static, rtol=1e-12)


def test_flexible_minus_rigid_equals_their_time_runs_subtracted(modes):
    """``difference_rms``: the two bodies' linear models run in time over the same road,
    their outputs subtracted sample by sample, have the spectral RMS of the difference
    (hub forces, tyre forces, travel, floor accelerations)."""
    from flexpipe.roads import iso8608

    rigid, flexible = modes["rigid"], modes["flexible"]
    B = _track_width(flexible)
    road = iso8608("C", length=400.0, dx=0.02, seed=1, track_width=B, coherence=1.0)
    diff = (_time_run(flexible, road, histories=True)
            - _time_run(rigid, road, histories=True))
    rms = np.sqrt(np.mean(diff**2, axis=0))
    r = ride_response(flexible, "C", coherence=1.0, track_width=B, reference=rigid)
    assert r.info["reference_body"] == "rigid"
    hub = np.array([name.startswith("hub_") and name[-1] in "xz" for name in r.outputs])
    np.testing.assert_allclose(rms[hub], r.difference_rms[hub], rtol=0.01)
    for row, d in zip(r.rows(), r.difference_rms, strict=True):
        assert row["difference_rms"] == d
    # the difference's spectrum peaks at a mode of the body's elastic modes (+-0.5 Hz)
    np.testing.assert_allclose(np.sqrt(np.trapezoid(r.difference_psd, r.f_hz, axis=0)),
                               r.difference_rms, rtol=1e-12)
    f_peak = r.f_hz[np.argmax(r.difference_psd[:, r.outputs.index("hub_fl_x")])]
    elastic = [f for f, lab in zip(flexible.frequency_hz, flexible.label, strict=True)
               if lab.startswith("body elastic")]
    assert min(abs(f_peak - f) for f in elastic) < 0.5
    with pytest.raises(InputError, match="same car's linear model at the same speed"):
        ride_response(flexible, "C", reference=dataclasses.replace(rigid, speed=10.0))


def test_ride_refuses_a_parked_car_and_bad_options(modes):
    m = modes["rigid"]
    with pytest.raises(InputError, match="speed > 0"):
        ride_response(dataclasses.replace(m, speed=0.0), "C")
    with pytest.raises(InputError, match="road class"):
        ride_response(m, "K")
    with pytest.raises(InputError, match="coherence"):
        ride_response(m, "C", coherence=1.5)
    with pytest.raises(InputError, match="n_band"):
        ride_response(m, "C", n_band=(1.0, 0.5))


def test_cli_writes_the_ride_files(tmp_path, capsys, modes, monkeypatch):
    """``flexpipe linear --speed 70 --road-class C``: the files hold what the API gives,
    and ``linear_state_space.mat`` the linear model itself."""
    import json

    from flexpipe import cli
    from flexpipe.vehicle import linear

    monkeypatch.setattr(linear, "linear_modes", lambda *a, **k: modes["rigid"])
    out = tmp_path / "o"
    assert cli.main(["linear", str(LINKAGE), "--body", "rigid", "--speed", "70",
                     "--road-class", "c", "--coherence", "0.5", "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "ISO 8608 class C at 70 km/h" in text and "a_v" in text
    r = ride_response(modes["rigid"], "C", coherence=0.5)
    doc = json.loads((out / "ride.json").read_text())
    assert doc["road_class"] == "C" and doc["coherence_model"] == 0.5
    np.testing.assert_allclose([row["rms"] for row in doc["outputs"]], r.rms, rtol=1e-12)
    table = np.genfromtxt(out / "ride_psd.csv", delimiter=",", names=True)
    np.testing.assert_allclose(table["f_Hz"], r.f_hz, rtol=1e-6)
    np.testing.assert_allclose(table["coherence"], 0.5)
    head = (out / "ride.csv").read_text().splitlines()[0]
    assert head == "output,rms,unit,iso2631_weighting,weighted_rms_m/s^2"
    assert (out / "ride_psd.png").stat().st_size > 10_000
    # the state matrices for MATLAB: the loaded system answers as the model does
    from scipy.io import loadmat

    mat = loadmat(out / "linear_state_space.mat")
    m = modes["rigid"]
    assert [str(c[0]) for c in mat["inputs"][:, 0]] == list(m.inputs)
    assert [str(c[0]) for c in mat["outputs"][:, 0]] == list(m.outputs)
    assert len(mat["states"]) == m.A.shape[0]
    s = 2j * np.pi * 7.0
    H = mat["C"] @ np.linalg.solve(s * np.eye(len(mat["A"])) - mat["A"], mat["B"]) + mat["D"]
    np.testing.assert_allclose(H, m.frequency_response([7.0])[0], rtol=1e-12, atol=1e-12)
    assert float(mat["speed_m_per_s"][0, 0]) == m.speed


def _speed_table(out) -> dict:
    """``ride_vs_speed.csv`` in ``out`` as {column: values}."""
    import csv

    with open(out / "ride_vs_speed.csv", newline="") as fh:
        rows = list(csv.DictReader(fh))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def test_ride_vs_speed_and_its_command(tmp_path, capsys, modes):
    """``flexpipe ride``: at each speed the car linearized there and answered by
    ride_response (the 70 km/h entry equals the fixture's model's), written as a table
    with units in the headers."""
    import json

    from flexpipe import cli

    out = tmp_path / "r"
    assert cli.main(["ride", str(LINKAGE), "--body", "rigid", "--speeds", "70,35",
                     "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "driver_floor_a_v" in text and "tire_fl_dynamic_load" in text
    table = _speed_table(out)
    np.testing.assert_allclose(table["speed_km/h"], [70.0, 35.0], rtol=1e-6)
    r70 = ride_response(modes["rigid"], "C")
    np.testing.assert_allclose(table["driver_floor_a_v_m/s^2"][0],
                               r70.points["driver_floor"]["a_v_m/s^2"], rtol=1e-6)
    np.testing.assert_allclose(table["tire_rl_dynamic_load"][0], r70.dynamic_load["rl"],
                               rtol=1e-6)
    doc = json.loads((out / "ride_vs_speed.json").read_text())
    assert [s["speed_km/h"] for s in doc["speeds"]] == pytest.approx([70.0, 35.0])
    # a slower car on the same road: less of everything (the road's velocity PSD ~ V)
    assert table["driver_floor_a_v_m/s^2"][1] < table["driver_floor_a_v_m/s^2"][0]
    assert table["tire_fl_Fz_rms_N"][1] < table["tire_fl_Fz_rms_N"][0]
    assert (out / "ride_vs_speed.png").stat().st_size > 10_000


def test_ride_vs_speed_against_a_reference_body(tmp_path, capsys, modes, monkeypatch):
    """``flexpipe ride --body flexible --reference rigid``: at each speed both bodies'
    models on the same road; the difference columns are the RMS of the two responses'
    difference (as ride_response gives it), which obeys the triangle inequality of RMS
    values against the two bodies' own RMS, and the hub forces' difference table is
    printed."""
    import json

    from flexpipe import cli
    from flexpipe.vehicle import linear
    from flexpipe.vehicle.linear import output_unit
    from flexpipe.vehicle.linear_ride import ride_vs_speed

    monkeypatch.setattr(linear, "linear_modes",
                        lambda car, *, body, speed, f_max=None: modes[body])
    out = tmp_path / "r"
    assert cli.main(["ride", str(LINKAGE), "--speeds", "70", "--reference", "Rigid",
                     "-o", str(out)]) == 0
    text = capsys.readouterr().out
    assert "hub forces, RMS of flexible minus rigid" in text and "fl_x" in text
    table = _speed_table(out)
    flexible, rigid = (ride_response(modes[b], "C") for b in ("flexible", "rigid"))
    diff = ride_response(modes["flexible"], "C", reference=modes["rigid"]).difference_rms
    for j, name in enumerate(flexible.outputs):
        d = table[f"{name}_difference_rms_{output_unit(name)}"][0]
        np.testing.assert_allclose(d, diff[j], rtol=1e-6)
        assert abs(flexible.rms[j] - rigid.rms[j]) * (1 - 1e-6) <= d \
            <= (flexible.rms[j] + rigid.rms[j]) * (1 + 1e-6), name
    assert json.loads((out / "ride_vs_speed.json").read_text())["reference_body"] == "rigid"
    assert (out / "ride_vs_speed.png").stat().st_size > 10_000
    with pytest.raises(InputError, match="reference must be another body"):
        ride_vs_speed(LINKAGE, [20.0], body="rigid", reference="rigid")


@pytest.mark.parametrize(("command", "args", "expect"), [
    ("linear", ["--road-class", "C"], "--road-class needs --speed > 0"),
    ("linear", ["--speed", "70", "--road-class", "K"], "--road-class must be one of A, B"),
    ("linear", ["--speed", "70", "--road-class", "C", "--coherence", "2"],
     "--coherence must be 'isotropic' or a number in [0, 1], got '2'"),
    ("linear", ["--speed", "70", "--road-class", "C", "--coherence", "some"], "got 'some'"),
    ("linear", ["--reference", "rigid"], "--reference needs --road-class"),
    ("linear", ["--speed", "70", "--road-class", "C", "--reference", "flexible"],
     "--reference must be another body than --body"),
    ("ride", ["--speeds", "70,70"], "--speeds must be distinct speeds in (0, 300] km/h"),
    ("ride", ["--speeds", "0,50"], "got '0,50'"),
    ("ride", ["--speeds", "fast"], "got 'fast'"),
    ("ride", ["--road-class", "Q"], "--road-class must be one of A"),
    ("ride", ["--body", "soft"], "--body must be one of rigid, flexible, full"),
    ("ride", ["--coherence", "-0.1"], "--coherence must be"),
    ("ride", ["--reference", "flexible"], "--reference must be another body than --body"),
    ("ride", ["--reference", "stiff"], "got 'stiff'"),
])
def test_commands_refuse_bad_ride_options_before_any_work(tmp_path, capsys, monkeypatch,
                                                          command, args, expect):
    from flexpipe import cli
    from flexpipe.vehicle import linear, linear_ride

    def never(*a, **k):
        raise AssertionError("the analysis ran before the options were checked")

    monkeypatch.setattr(linear, "linear_modes", never)
    monkeypatch.setattr(linear_ride, "ride_vs_speed", never)
    assert cli.main([command, str(LINKAGE), "-o", str(tmp_path / "o"), *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and expect in err[0]


def test_ride_vs_speed_refuses_bad_arguments():
    from flexpipe.vehicle.linear_ride import ride_vs_speed

    for speeds in ([], [10.0, 10.0], [-1.0], [200.0], "fast"):
        with pytest.raises(InputError, match="speeds"):
            ride_vs_speed(LINKAGE, speeds)
    with pytest.raises(InputError, match="road class"):
        ride_vs_speed(LINKAGE, [20.0], "Z")
    with pytest.raises(InputError, match="coherence"):
        ride_vs_speed(LINKAGE, [20.0], coherence="flat")
