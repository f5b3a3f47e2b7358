"""The full car on linkage suspensions (cars/sedan_linkage.toml) in Exudyn: statics.

References: the whole car's weight (vertical force balance at rest), the tyres' static
loaded radius under the static wheel loads, and the design position the springs are
preloaded for (virtual work through each linkage,
:func:`flexpipe.vehicle.suspension.statics.spring_preload`).
"""

from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.vehicle import bodymodel
from flexpipe.vehicle.suspension.model import ARB_ARM_MASS, RACK_MASS

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
    assert Fz == pytest.approx(mass * 9.81, rel=1e-6)


def test_linkage_car_starts_in_static_equilibrium_at_design_ride_height(parked):
    _, r = parked
    assert abs(r["z"][-1] - r["z"][0]) < 0.5e-3  # the body does not settle, m
    for c in CORNERS:
        assert abs(r[f"travel_{c}"][-1]) < 0.5e-3  # suspension at its design position, m
        # vertical hub and tyre forces at t = 0 are the static ones (the horizontal ones
        # build up while the compliant steering column takes the static steering moment)
        for ch in (f"hub_{c}_z", f"tire_{c}_Fz"):
            assert r[ch][0] == pytest.approx(r[ch][-1], rel=1e-3)


def test_parked_linkage_car_does_not_creep(parked):
    _, r = parked
    late = r.t > r.t[-1] - 0.5
    for c in CORNERS:
        for k in "xyz":
            assert np.ptp(r[f"hub_{c}_{k}"][late]) < 0.5  # N


def test_flexpipe_info_summarises_a_car_file(capsys):
    from flexpipe.cli import main

    car = fp.load_car(CAR)
    assert main(["info", str(CAR)]) == 0
    out = capsys.readouterr().out
    assert "double_wishbone" in out and "multi_link" in out
    mounts = car.suspension.mounts()
    for name in mounts:
        assert name in out
    rb = bodymodel.rigid_properties(car)
    n_arb = sum(a.anti_roll_bar is not None for a in car.suspension.axles.values())
    weight = 9.81 * (rb.mass + sum(c.unsprung_mass for c in car.corners) + RACK_MASS
                     + 2 * n_arb * ARB_ARM_MASS)
    line = next(ln for ln in out.splitlines() if "static wheel loads" in ln)
    loads = [float(w.split()[1]) for w in line.split(":")[1].split(";")[0].split(",")]
    assert sum(loads) == pytest.approx(weight, rel=1e-3)


@pytest.mark.parametrize("output_step", [2.5e-3, 7.5e-3])
def test_mount_forces_sum_to_the_corner_hub_force(output_step):
    """Constraint forces at the mounts (Exudyn's joint and connector outputs, recorded by
    Exudyn sensors) against the hub force from Newton's law of the corner's parts (read
    by the Python step): the two must agree at every output row, whatever the output
    step."""
    from flexpipe.scenarios.runner import _straight_road

    car = fp.load_car(CAR)
    # the design-position start the limits below were measured with (the check compares
    # two estimates of the same forces along one trajectory)
    r = fp.simulate(car, road=_straight_road(), speed=70 / 3.6, t_end=0.6, body="rigid",
                    output_step=output_step, settle=False)
    assert r.status == 0, r.message
    corners = car.suspension.corners()
    sel = r.t > 0.1
    for c in CORNERS:
        for k in "xyz":
            assert all(np.isfinite(r[f"mount_{m}_{k}"]).all() for m in corners[c].mounts)
            total = sum(r[f"mount_{m}_{k}"] for m in corners[c].mounts)
            hub = r[f"hub_{c}_{k}"]
            d = (total - hub)[sel]
            # agreement to the integrator's consistency between the constraint forces and
            # the parts' accelerations (measured 2026-12-04 at the default 1.25 ms: up to
            # 0.02 % of the fluctuation, 0.01 N mean; when this test was written, at 2 ms
            # and with the earlier model: up to 2 %, random, no offset)
            assert np.sqrt(np.mean(d**2)) < 0.03 * hub[sel].std() + 0.5, (c, k)
            assert abs(d.mean()) < 0.5, (c, k)


@pytest.mark.parametrize("output_step", [2.5e-3, 7.5e-3])
def test_hub_forces_from_sensors_equal_the_python_reads(output_step, monkeypatch):
    """The hub channels made after the run from Exudyn's sensor records (parts'
    accelerations, rack and bar links) against the same forces read from Python in the
    step (``CarController.hub_sensors = False``): one trajectory, equal to rounding."""
    from flexpipe.scenarios.runner import _straight_road
    from flexpipe.vehicle.dynamics import CarController

    car = fp.load_car(CAR)
    kw = dict(road=_straight_road(), speed=70 / 3.6, t_end=0.4, body="rigid",
              output_step=output_step, settle=False)
    r = fp.simulate(car, **kw)
    monkeypatch.setattr(CarController, "hub_sensors", False)
    ref = fp.simulate(car, **kw)
    assert r.status == ref.status == 0
    for c in CORNERS:
        for k in "xyz":
            a, b = r[f"hub_{c}_{k}"], ref[f"hub_{c}_{k}"]
            assert np.isfinite(a).all()
            np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * np.abs(b).max() + 1e-9)


@pytest.mark.parametrize("body", ["rigid", "flexible"])
def test_point_accelerations_and_motion_from_sensors_equal_the_python_reads(body,
                                                                             monkeypatch):
    """The named points' accelerations and the body motion filled after the run from
    Exudyn's sensors (flexpipe.exu.output_sensors) against the same values read from
    Python at every output row (``CarController.output_sensors = False``): one
    trajectory, equal to rounding; on the flexible body the points are mesh nodes of the
    super element and the motion carries every elastic modal coordinate."""
    from flexpipe.scenarios.runner import _straight_road
    from flexpipe.vehicle.dynamics import CarController

    car = fp.load_car(CAR)
    kw = dict(road=_straight_road(), speed=70 / 3.6, t_end=0.2, body=body,
              output_step=2.5e-3, settle=False)
    r = fp.simulate(car, **kw)
    monkeypatch.setattr(CarController, "output_sensors", False)
    ref = fp.simulate(car, **kw)
    assert r.status == ref.status == 0
    names = [k for k in ref.channels if k.startswith("acc_")]
    assert len(names) == 3 * (len(car.body.points) + len(car.body.seats)) > 0
    for k in names:
        a, b = r[k], ref[k]
        assert np.isfinite(a).all()
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * np.abs(b).max() + 1e-12)
    m, mr = r.motion, ref.motion
    assert len(m.t) == len(r.t) and m.q.shape == mr.q.shape
    assert (m.q.shape[1] > 0) == (body == "flexible")
    for name in ("q", "position", "rotation"):
        a, b = getattr(m, name), getattr(mr, name)
        assert np.isfinite(a).all()
        np.testing.assert_allclose(a, b, rtol=0, atol=1e-9 * (np.abs(b).max(initial=0) + 1))


@pytest.fixture(scope="module")
def iso_c_runs():
    """Rigid twin and flexible bodies of the linkage car on ISO class C at 70 km/h."""
    import dataclasses

    from flexpipe.scenarios.runner import _straight_road
    from flexpipe.vehicle.simulation import prepare

    car = fp.load_car(CAR)
    road = _straight_road()
    kw = dict(road=road, speed=70 / 3.6, t_end=1.5)
    prep = prepare(car, body="flexible", speed=70 / 3.6, road=road)
    fb = prep["flexbody"]
    stiff = dataclasses.replace(fb, K=fb.K * 100.0, D=fb.D * 10.0,
                                frequencies_hz=fb.frequencies_hz * 10.0)
    return {"rigid": fp.simulate(car, body="rigid", **kw),
            "modes_off": fp.simulate(car, body="flexible", max_mode_hz=0, prepared=prep, **kw),
            "modes_off_full": fp.simulate(car, body="flexible", max_mode_hz=0, prepared=prep,
                                          inertia_coupling="full", **kw),
            "stiff": fp.simulate(car, body="flexible", prepared=dict(prep, flexbody=stiff),
                                 **kw),
            "constant": fp.simulate(car, body="flexible", prepared=prep,
                                    inertia_coupling="constant", **kw),
            "full": fp.simulate(car, body="flexible", prepared=prep, inertia_coupling="full",
                                **kw)}


def test_constant_inertia_coupling_equals_full_on_the_car(iso_c_runs):
    """The flexible car with Adams/Flex's constant inertia coupling (the default for its
    mean-axis body) against Exudyn's complete floating-frame terms: hub forces within
    0.5 % of their fluctuating part (4 s runs: 0.005-0.12 % on ISO C 70 and 100 km/h and
    the slalom, README "Inertia coupling")."""
    full, const = iso_c_runs["full"], iso_c_runs["constant"]
    assert full.info["inertia_coupling"] == "full"
    assert const.info["inertia_coupling"] == "constant"
    assert iso_c_runs["stiff"].info["inertia_coupling"] == "constant"  # "auto"
    d = fp.compare(full, const, t_from=0.5)
    worst = max(v["rel_rms_diff_dynamic"] for k, v in d.items() if k.startswith("hub_"))
    assert worst < 0.005, worst


@pytest.mark.parametrize("variant, tol", [("modes_off", 0.02), ("modes_off_full", 0.02),
                                          ("stiff", 0.05)])
def test_flexible_body_tends_to_its_rigid_twin(iso_c_runs, variant, tol):
    """Consistency of the flexible body with its rigid twin (issue 9): every elastic mode
    switched off reproduces the rigid car's hub forces within 2 % of their fluctuating
    part; a body 100x stiffer (modes 10x higher) within 5 %.  Mounts, brackets and
    markers are the flexible body's own, so any modelling point without physical meaning
    would show here."""
    rigid, other = iso_c_runs["rigid"], iso_c_runs[variant]
    assert rigid.status == 0 and other.status == 0, (rigid.message, other.message)
    d = fp.compare(rigid, other, t_from=0.5)
    worst = max(v["rel_rms_diff_dynamic"] for k, v in d.items() if k.startswith("hub_"))
    assert worst < tol, worst


@pytest.mark.parametrize("body", ["rigid", "flexible"])
def test_settled_start_is_static_equilibrium(body):
    """Issue 10: the run starts in the static equilibrium of the whole car (flexible body,
    suspension, steering, tyres): a parked car's hub forces at t = 0 and at every later
    output equal their settled values within 0.1 % of the static wheel load (without the
    settled start: 300-820 N peaks for the flexible body, 70 N lateral build-up)."""
    car = fp.load_car(CAR)
    r = fp.simulate(car, speed=0.0, t_end=2.0, body=body)
    assert r.status == 0, r.message
    late = r.t > 1.5
    for c in CORNERS:
        static_z = r[f"hub_{c}_z"][late].mean()
        for k in "xyz":
            x = r[f"hub_{c}_{k}"]
            assert np.abs(x - x[late].mean()).max() < 1e-3 * static_z, (c, k)
