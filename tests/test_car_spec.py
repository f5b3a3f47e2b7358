"""Car spec (TOML) loading and validation, against the raw file read independently."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.vehicle import load_car
from flexpipe.vehicle.spec import CORNERS

ROOT = Path(__file__).resolve().parents[1]
SEDAN = ROOT / "cars" / "sedan.toml"


@pytest.fixture(scope="module")
def raw():
    return tomllib.loads(SEDAN.read_text())


def _variant(tmp_path, edit, name="car.toml"):
    """A copy of the sedan file with ``edit(text) -> text`` applied, paths made absolute."""
    text = SEDAN.read_text().replace('"../', f'"{ROOT.as_posix()}/')
    path = tmp_path / name
    path.write_text(edit(text))
    return path


def test_sedan_values_match_the_file(raw):
    car = load_car(SEDAN)
    assert car.name == raw["car"]["name"]
    assert car.body.mesh == (SEDAN.parent / raw["body"]["mesh"]).resolve()
    assert car.body.damping_ratio == raw["body"]["damping_ratio"]
    assert len(car.body.added_masses) == len(raw["body"]["mass"])
    total = sum(m["mass_kg"] for m in raw["body"]["mass"])
    assert sum(m.mass for m in car.body.added_masses) == pytest.approx(total)
    for c in car.corners:
        t = raw["corners"][c.name]
        np.testing.assert_array_equal(c.hardpoint, t["hardpoint_m"])
        np.testing.assert_array_equal(c.wheel_center, t["wheel_center_m"])
        assert c.spring_rate == t["spring_rate_N_per_m"]
        assert c.damper_jounce == t["damper_jounce_N_s_per_m"]
        assert c.damper_rebound == t["damper_rebound_N_s_per_m"]
        assert c.unsprung_mass == t["unsprung_mass_kg"]
        assert np.diag(c.unsprung_inertia).tolist() == t["unsprung_inertia_kg_m2"]
        assert c.spring_preload is None  # omitted: computed for the design position
    assert car.steering.ratio == raw["steering"]["ratio"]
    assert car.steering.max_wheel_angle == pytest.approx(
        np.radians(raw["steering"]["max_wheel_angle_deg"]))
    assert car.anti_roll_bars["front"] == raw["anti_roll_bar"]["front"]["rate_N_per_m"]
    assert car.drive.layout == raw["drive"]["layout"]
    # front-wheel drive: all drive torque on the front corners, split evenly
    np.testing.assert_allclose(car.drive.drive_shares(), [0.5, 0.5, 0.0, 0.0])
    x = [raw["corners"][n]["wheel_center_m"][0] for n in CORNERS]
    assert car.wheelbase == pytest.approx(np.mean(x[:2]) - np.mean(x[2:]))


def test_sample_car_dimensions_are_a_sedan(raw):
    """Wheelbase 2.6-2.9 m and track 1.45-1.65 m, typical of a mid-size sedan."""
    car = load_car(SEDAN)
    assert 2.6 <= car.wheelbase <= 2.9
    track = 2 * abs(car.corner("fl").wheel_center[1])
    assert 1.45 <= track <= 1.65


@pytest.mark.parametrize("edit, key, words", [
    (lambda s: s.replace("spring_rate_N_per_m = 30000.0", "", 1),
     "corners.fl.spring_rate_N_per_m", ["missing required key 'spring_rate_N_per_m'"]),
    (lambda s: s.replace("spring_rate_N_per_m = 30000.0", "sprng_rate_N_per_m = 30000.0", 1),
     "corners.fl.spring_rate_N_per_m", ["missing required key", "'sprng_rate_N_per_m'",
                                        "misspelt"]),
    (lambda s: s.replace("rebound_stop_rate_N_per_m = 200000.0",
                         "rebound_stop_rate_N_per_m = 200000.0\nrebound_stop_rate = 1.0", 1),
     "corners.fl.rebound_stop_rate", ["unknown key", "did you mean", "valid keys"]),
    (lambda s: s.replace("mass_kg = 190.0", "mass_kg = -190.0", 1), "body.mass[0].mass_kg",
     ["must be >= 0"]),
    (lambda s: s.replace("unsprung_mass_kg = 42.0", "unsprung_mass_kg = -42.0", 1),
     "corners.fl.unsprung_mass_kg", ["must be > 0"]),
    (lambda s: s.replace('layout = "front"', 'layout = "middle"'), "drive.layout",
     ["'front'", "'rear'", "'all'"]),
    (lambda s: s.replace("damper_jounce_N_s_per_m = 1800.0",
                         "damper_N_s_per_m = 2000.0\ndamper_jounce_N_s_per_m = 1800.0", 1),
     "corners.fl.damper_N_s_per_m", ["either damper_N_s_per_m"]),
    (lambda s: s.replace("hardpoint_m = [0.0, 0.65, 0.85]", "hardpoint_m = [0.0, -0.65, 0.85]"),
     "corners.fl.hardpoint_m", ["wrong side"]),
    (lambda s: s.replace('tire = "', 'tire = "missing_', 1), "corners.fl.tire",
     ["does not exist"]),
    (lambda s: s.replace("[steering]", "[steeering]"), "steering",
     ["missing required key 'steering'", "'steeering' - misspelt"]),
])
def test_bad_car_files_name_file_key_and_fix(tmp_path, edit, key, words):
    path = _variant(tmp_path, edit)
    with pytest.raises(InputError) as exc:
        load_car(path)
    msg = str(exc.value)
    assert str(path) in msg
    assert f"key '{key}'" in msg
    for w in words:
        assert w in msg
    assert re.search(r"line \d+", msg) or key == "steering"


def test_syntax_error_reports_line(tmp_path):
    path = _variant(tmp_path, lambda s: s.replace("ratio = 15.5", "ratio = = 15.5"))
    with pytest.raises(InputError, match=r"line \d+"):
        load_car(path)
    line = next(i for i, t in enumerate(path.read_text().splitlines(), 1) if "= = 15.5" in t)
    with pytest.raises(InputError, match=f"line {line}"):
        load_car(path)


def test_missing_file_and_wrong_suffix(tmp_path):
    with pytest.raises(InputError, match="cannot read"):
        load_car(tmp_path / "nope.toml")
    with pytest.raises(InputError, match=".toml"):
        load_car(tmp_path / "car.json")


def test_rigid_only_body_needs_mass_properties(tmp_path):
    def edit(s):
        s = s.replace('mesh = "', '# mesh = "', 1)
        return s.replace("[body.points]", "[body.rigid]\nmass_kg = 1200.0\ncg_m = [-1.2, 0.0, "
                                          "0.55]\ninertia_kg_m2 = [450.0, 2000.0, 2200.0]\n\n"
                                          "[body.points]")
    car = load_car(_variant(tmp_path, edit))
    assert car.body.mesh is None and car.body.rigid.mass == 1200.0
    np.testing.assert_array_equal(np.diag(car.body.rigid.inertia), [450.0, 2000.0, 2200.0])
    path = _variant(tmp_path, lambda s: s.replace('mesh = "', '# mesh = "', 1), "bare.toml")
    with pytest.raises(InputError, match=r"needs a 'mesh'.*\[body.rigid\]"):
        load_car(path)


def _line(path, needle, nth=1):
    hits = [i for i, t in enumerate(path.read_text().splitlines(), 1) if needle in t]
    return hits[nth - 1]


def test_off_body_mass_error_names_the_car_file(tmp_path):
    from flexpipe.vehicle.bodymodel import body_mesh

    path = _variant(tmp_path, lambda s: s.replace("position_m = [0.10, 0.0, 0.55]",
                                                  "position_m = [10.0, 0.0, 0.55]", 1))
    with pytest.raises(InputError) as exc:
        body_mesh(load_car(path))
    msg = str(exc.value)
    assert str(path) in msg and "key 'body.mass.powertrain'" in msg
    assert "spread_radius_m" in msg.replace(str(path), "")


def test_unknown_mesh_units_are_named_at_load(tmp_path):
    path = _variant(tmp_path, lambda s: s.replace("damping_ratio = 0.02",
                                                  'mesh_units = "inch"\ndamping_ratio = 0.02', 1))
    with pytest.raises(InputError) as exc:
        load_car(path)
    msg = str(exc.value)
    assert str(path) in msg and f"line {_line(path, 'mesh_units')}" in msg
    assert "key 'body.mesh_units'" in msg and "'inch'" in msg and "mm-t-s" in msg


@pytest.mark.parametrize("old, new, key, words", [
    ("spring_rate_N_per_m = 30000.0", "spring_rate_N_per_m = 30.0",
     "corners.fl.spring_rate_N_per_m", ["N/mm", "between 1000 and 1e+07 N/m"]),
    ("spring_rate_N_per_m = 26000.0", "spring_rate_N_per_m = 2.6e10",
     "corners.rl.spring_rate_N_per_m", ["between 1000 and 1e+07 N/m"]),
    ("damper_rebound_N_s_per_m = 3600.0", "damper_rebound_N_s_per_m = 3.6",
     "corners.fl.damper_rebound_N_s_per_m", ["N s/mm", "between 10 and"]),
    ("bump_stop_rate_N_per_m = 200000.0", "bump_stop_rate_N_per_m = 200.0",
     "corners.fl.bump_stop_rate_N_per_m", ["N/mm"]),
    ("unsprung_mass_kg = 42.0", "unsprung_mass_kg = 0.042", "corners.fl.unsprung_mass_kg",
     ["tonnes", "between 1 and 2000 kg"]),
    ("unsprung_mass_kg = 42.0", "unsprung_mass_kg = 42000.0", "corners.fl.unsprung_mass_kg",
     ["grams"]),
])
def test_unit_slips_in_rates_and_masses_are_named(tmp_path, old, new, key, words):
    path = _variant(tmp_path, lambda s: s.replace(old, new, 1))
    with pytest.raises(InputError) as exc:
        load_car(path)
    msg = str(exc.value)
    assert str(path) in msg and f"key '{key}'" in msg and re.search(r"line \d+", msg)
    for w in words:
        assert w in msg.replace(str(path), "")


def test_zero_damper_and_stop_rates_still_mean_none(tmp_path):
    path = _variant(tmp_path, lambda s: s.replace("bump_stop_rate_N_per_m = 200000.0",
                                                  "bump_stop_rate_N_per_m = 0.0", 1))
    assert load_car(path).corner("fl").bump_stop_rate == 0.0


def test_duplicate_mass_names_are_refused_naming_both(tmp_path):
    path = _variant(tmp_path, lambda s: s.replace('name = "door_fr"', 'name = "door_fl"'))
    with pytest.raises(InputError) as exc:
        load_car(path)
    msg = str(exc.value)
    assert str(path) in msg and "'door_fl'" in msg and "key 'body.mass[7].name'" in msg
    assert f"line {_line(path, 'door_fl', 2)}" in msg and f"line {_line(path, 'door_fl')}" in msg
    assert "body.mass[6]" in msg and "own name" in msg.replace(str(path), "")


def test_mounts_table_of_a_prismatic_car_is_refused(tmp_path):
    """[body.mounts] ties linkage mounts; a prismatic-corner car would ignore it."""
    path = _variant(tmp_path, lambda s: s + "\n[body.mounts.fl]\nradius_m = 0.02\n")
    with pytest.raises(InputError) as exc:
        load_car(path)
    msg = str(exc.value)
    assert str(path) in msg and "key 'body.mounts.fl'" in msg
    assert "prismatic corners" in msg.replace(str(path), "")
    assert f"line {_line(path, '[body.mounts.fl]')}" in msg
