"""Physical bounds of car-file values (flexpipe/vehicle/limits.py): the audit's bad values
are refused at load naming file, line, key and the valid range, the sample values and the
edges of the ranges load, and the edges are values the integrator handles.

Runs are short (rigid body, 0.5-1 s) and only where the bound's reason is numerical.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.vehicle import limits as lim
from flexpipe.vehicle import load_car
from tests._rigidcar import rigid_sedan

ROOT = Path(__file__).resolve().parents[1]
SEDAN = ROOT / "cars" / "sedan.toml"
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"


def _variant(tmp_path, car: Path, *subs, name="car.toml") -> Path:
    """``car`` with each ``(old, new)`` replaced once (paths made absolute)."""
    text = car.read_text().replace('"../', f'"{ROOT.as_posix()}/')
    for old, new in subs:
        assert old in text, old
        text = text.replace(old, new, 1)
    path = tmp_path / name
    path.write_text(text)
    return path


def _refused(path: Path, key: str, *fragments: str) -> InputError:
    with pytest.raises(InputError) as exc:
        load_car(path)
    err = exc.value
    assert err.key == key and err.file == path and err.line is not None, str(err)
    for f in fragments:
        assert f in str(err), str(err)
    return err


# ------------------------------------------------------------------ wheel spin inertia
SPIN = "wheel_spin_inertia_kg_m2 = 1.0"


@pytest.mark.parametrize("car", [SEDAN, LINKAGE], ids=["prismatic", "linkage"])
@pytest.mark.parametrize("value, hint", [("1.0e-9", ""), ("1.0e-6", ""),
                                         ("1.0e4", "kg cm^2")])
def test_spin_inertia_out_of_range_is_refused(tmp_path, car, value, hint):
    p = _variant(tmp_path, car, (SPIN, f"wheel_spin_inertia_kg_m2 = {value}"))
    _refused(p, "corners.fl.wheel_spin_inertia_kg_m2", "between 0.02 and 1000 kg m^2", hint)


@pytest.mark.parametrize("car", [SEDAN, LINKAGE], ids=["prismatic", "linkage"])
def test_spin_inertia_of_a_small_road_wheel_loads(tmp_path, car):
    """A 10-inch wheel with tyre (about 5 kg at 0.2 m: 0.1 kg m^2) is a road wheel."""
    p = _variant(tmp_path, car, (SPIN, "wheel_spin_inertia_kg_m2 = 0.1"))
    assert load_car(p).corner("fl").spin_inertia == 0.1


def test_spin_inertia_at_the_lower_bound_rolls_freely_at_the_largest_step(tmp_path):
    """At the smallest valid spin inertia and the largest step (5 ms) a free-rolling wheel
    turns at v / R_e and stays there (the audit's 1e-9 reached 3e10 rad/s)."""
    from flexpipe.vehicle import simulate

    lo = lim.WHEEL_SPIN_INERTIA_KG_M2[0]
    text = rigid_sedan(tmp_path).read_text().replace(SPIN, f"wheel_spin_inertia_kg_m2 = {lo}")
    p = tmp_path / "small_spin.toml"
    p.write_text(text)
    v = 30 / 3.6
    r = simulate(p, speed=v, t_end=0.5, body="rigid", h=5e-3)
    assert r.status == 0, r.message
    for c in ("fl", "fr", "rl", "rr"):
        spin = np.asarray(r[f"spin_{c}"])
        rolling = np.median(spin)  # v / R_e with the loaded tyre's effective radius
        assert v / 0.316 < rolling < v / 0.29  # between v / R0 and v / (R0 - 26 mm)
        np.testing.assert_allclose(spin, rolling, rtol=0.03)


# ------------------------------------------------------------------ anti-roll bars
ARB = "rate_N_per_m = 18000.0"


@pytest.mark.parametrize("car", [SEDAN, LINKAGE], ids=["prismatic", "linkage"])
@pytest.mark.parametrize("value, hint", [("1.0e12", ""), ("18.0", "looks like N/mm")])
def test_anti_roll_bar_rate_out_of_range_is_refused(tmp_path, car, value, hint):
    p = _variant(tmp_path, car, (ARB, f"rate_N_per_m = {value}"))
    _refused(p, "anti_roll_bar.front.rate_N_per_m", "between 1000 and 1e+06 N/m", hint)


def test_anti_roll_bar_zero_means_none(tmp_path):
    p = _variant(tmp_path, SEDAN, (ARB, "rate_N_per_m = 0.0"))
    assert load_car(p).anti_roll_bars["front"] == 0.0


def test_anti_roll_bar_at_the_upper_bound_runs_at_the_default_step(tmp_path):
    """Bars of 1e6 N/m on both axles on an ISO class C road: the run completes with wheel
    loads of the order of the static ones (the audit's 1e12 overturned within 5 steps)."""
    from flexpipe.roads import iso8608
    from flexpipe.vehicle import simulate

    hi = lim.ARB_RATE_N_PER_M[1]
    text = rigid_sedan(tmp_path).read_text().replace(ARB, f"rate_N_per_m = {hi}").replace(
        "rate_N_per_m = 6000.0", f"rate_N_per_m = {hi}")
    p = tmp_path / "stiff_bars.toml"
    p.write_text(text)
    road = iso8608("C", length=100.0, dx=0.05, seed=3, track_width=1.55, fade=5.0)
    r = simulate(p, road=road, speed=20.0, t_end=1.0, body="rigid", h=1e-3)
    assert r.status == 0, r.message
    static = 9.81 * 1484 / 4
    for c in ("fl", "fr", "rl", "rr"):
        assert np.all(np.abs(r[f"hub_{c}_z"]) < 3 * static)
    assert np.max(np.abs(r["roll"])) < math.radians(3)


def test_linkage_anti_roll_bar_torsion_rate(tmp_path):
    key = "suspension.front.anti_roll_bar.torsion_rate_N_m_per_rad"
    old = "torsion_rate_N_m_per_rad = 6300.0"
    p = _variant(tmp_path, LINKAGE, (old, "torsion_rate_N_m_per_rad = 1.0e12"))
    _refused(p, key, "between 10 and 1e+06 N m/rad")
    # 110 N m/deg is the sample's 6300 N m/rad; 3.84 N m/deg its rear 220 N m/rad
    p = _variant(tmp_path, LINKAGE, ("torsion_rate_N_m_per_rad = 220.0",
                                     "torsion_rate_N_m_per_rad = 3.84"))
    _refused(p, "suspension.rear.anti_roll_bar.torsion_rate_N_m_per_rad", "N m/deg")


# ------------------------------------------------------------------ steering rack
@pytest.mark.parametrize("value, hint", [("1.0e-9", ""), ("55.0", "looks like mm")])
def test_rack_travel_per_revolution(tmp_path, value, hint):
    p = _variant(tmp_path, LINKAGE, ("travel_per_rev_m = 0.055", f"travel_per_rev_m = {value}"))
    _refused(p, "steering.rack.travel_per_rev_m", "between 0.02 and 0.2 m", hint)


def test_rack_of_a_real_pinion_loads(tmp_path):
    """pi x pitch diameter: a 12 mm pinion 0.038 m/rev, a 35 mm one 0.11 m/rev."""
    for c in (math.pi * 0.012, math.pi * 0.035):
        p = _variant(tmp_path, LINKAGE, ("travel_per_rev_m = 0.055", f"travel_per_rev_m = {c}"))
        assert load_car(p).suspension.rack.travel_per_rev == pytest.approx(c)


# ------------------------------------------------------------------ bushings
BUSH_K = "stiffness = [8.0e6, 8.0e6, 1.0e6, 500.0, 500.0, 150.0]"
BUSH_C = "damping = [800.0, 800.0, 100.0, 0.5, 0.5, 0.2]"
BUSH_KEY = "suspension.front.bushings.lower_arm_front."


@pytest.mark.parametrize("old, new, key, fragments", [
    (BUSH_K, "stiffness = [1.0e13, 1.0e13, 1.0e13, 1.0e9, 1.0e9, 1.0e9]", "stiffness",
     ("entry 0 (x)", "1e+08 N/m")),
    (BUSH_K, "stiffness = [8.0e6, 8.0e6, 1.0e6, 500.0, 500.0, 1.0e9]", "stiffness",
     ("entry 5 (rz)", "0 to 1e+06 N m/rad")),
    (BUSH_K, "stiffness = [8.0, 8.0, 1.0, 500.0, 500.0, 150.0]", "stiffness",
     ("entry 0 (x)", "kN/mm")),
    (BUSH_C, "damping = [1.0e8, 800.0, 100.0, 0.5, 0.5, 0.2]", "damping",
     ("entry 0 (x)", "0 to 1e+06 N s/m")),
    (BUSH_C, "damping = [800.0, 800.0, 100.0, 0.5, 0.5, 1.0e6]", "damping",
     ("entry 5 (rz)", "0 to 10000 N m s/rad")),
])
def test_bushing_out_of_range_is_refused(tmp_path, old, new, key, fragments):
    _refused(_variant(tmp_path, LINKAGE, (old, new)), BUSH_KEY + key, *fragments)


def test_bushing_free_directions_and_bounds_load(tmp_path):
    p = _variant(tmp_path, LINKAGE,
                 (BUSH_K, "stiffness = [1.0e8, 1.0e4, 0.0, 1.0e6, 0.0, 150.0]"),
                 (BUSH_C, "damping = [1.0e6, 0.0, 0.0, 1.0e4, 0.0, 0.2]"))
    load_car(p)


def test_stiffest_valid_bushings_act_as_the_joints_they_surround(tmp_path):
    """Every bushing at the translational bound (1e8 N/m) in the compliant mode, at 1 ms
    on ISO class C: the hub loads are those of the kinematic mode, in which
    the bushings are the joints (the audit's 1e13 N/m made the car hop on a flat road)."""
    from flexpipe.roads import iso8608
    from flexpipe.vehicle import simulate

    k = lim.BUSHING_STIFFNESS_N_PER_M[1]
    stiff = _variant(tmp_path, LINKAGE, ('mode = "kinematic"', 'mode = "compliant"'),
                     ("stiffness = [8.0e6, 8.0e6, 1.0e6,", f"stiffness = [{k}, {k}, {k},"),
                     ("stiffness = [4.0e6, 4.0e6, 0.6e6,", f"stiffness = [{k}, {k}, {k},"),
                     ("stiffness = [3.0e6, 3.0e6, 1.5e6,", f"stiffness = [{k}, {k}, {k},"),
                     name="stiff.toml")
    road = iso8608("C", length=100.0, dx=0.05, seed=3, track_width=1.55, fade=5.0)
    runs = [simulate(p, road=road, speed=20.0, t_end=1.0, body="rigid", h=1e-3)
            for p in (stiff, LINKAGE)]
    for r in runs:
        assert r.status == 0, r.message
    for c in ("fl", "rl"):
        a, b = (np.asarray(r[f"hub_{c}_z"]) for r in runs)
        assert np.sqrt(np.mean((a - b) ** 2)) < 0.05 * np.std(b), c


# ------------------------------------------------------------------ prismatic geometry
WC = "wheel_center_m = [0.0, 0.775, 0.2983]"


def test_prismatic_wheel_centre_outside_the_envelope(tmp_path):
    p = _variant(tmp_path, SEDAN, (WC, "wheel_center_m = [0.0, 5.0, 0.2983]"))
    err = _refused(p, "corners.fl.wheel_center_m", "y = 5 m", "-3 < y <= 3 m")
    assert "millimetres" not in str(err)
    p = _variant(tmp_path, SEDAN, (WC, "wheel_center_m = [0.0, 775.0, 298.3]"))
    _refused(p, "corners.fl.wheel_center_m", "millimetres")


def test_prismatic_hardpoint_far_from_its_wheel(tmp_path):
    p = _variant(tmp_path, SEDAN, ("hardpoint_m = [0.0, 0.65, 0.85]",
                                   "hardpoint_m = [0.0, 0.65, 2.5]"))
    _refused(p, "corners.fl.hardpoint_m", "2.21 m from the wheel centre", "at most 1.5 m")


# ------------------------------------------------------------------ inertia
def test_unsprung_inertia_must_be_a_rigid_bodys(tmp_path):
    old = "unsprung_inertia_kg_m2 = [0.9, 1.3, 0.9]"
    p = _variant(tmp_path, SEDAN, (old, "unsprung_inertia_kg_m2 = [0.1, 0.1, 5.0]"))
    _refused(p, "corners.fl.unsprung_inertia_kg_m2", "5 > 0.2")
    # the same violation given as a full tensor in rotated axes
    R = np.array([[math.cos(0.3), -math.sin(0.3), 0], [math.sin(0.3), math.cos(0.3), 0],
                  [0, 0, 1]])
    J = R @ np.diag([0.1, 5.0, 0.1]) @ R.T
    six = [float(J[i, j]) for i, j in ((0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2))]
    p = _variant(tmp_path, SEDAN, (old, f"unsprung_inertia_kg_m2 = {six!r}"))
    _refused(p, "corners.fl.unsprung_inertia_kg_m2", "the sum of the other two")
    # a thin disc (I about the axle = twice that about a diameter) meets it with equality
    p = _variant(tmp_path, SEDAN, (old, "unsprung_inertia_kg_m2 = [0.6, 1.2, 0.6]"))
    load_car(p)


def test_rigid_body_inertia_must_be_a_rigid_bodys(tmp_path):
    text = rigid_sedan(tmp_path).read_text()
    old = "inertia_kg_m2 = [421.17, 2132.08, 2299.63, 0.0, -18.43, 0.0]"
    p = tmp_path / "bad_rigid.toml"
    p.write_text(text.replace(old, "inertia_kg_m2 = [421.17, 2132.08, 3000.0]"))
    _refused(p, "body.rigid.inertia_kg_m2", "the sum of the other two")


@pytest.mark.parametrize("old, new, key", [
    ("inertia_kg_m2 = [0.0151, 0.0207, 0.0355]", "inertia_kg_m2 = [0.0151, 0.0207, 0.05]",
     "suspension.front.parts.lower_arm.inertia_kg_m2"),
    ("wheel_inertia_kg_m2 = [0.45, 0.0, 0.45]", "wheel_inertia_kg_m2 = [0.45, 0.0, 1.45]",
     "corners.fl.wheel_inertia_kg_m2"),
])
def test_linkage_inertias_must_be_rigid_bodies(tmp_path, old, new, key):
    _refused(_variant(tmp_path, LINKAGE, (old, new)), key, "the sum of the other two")
