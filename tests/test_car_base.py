"""Car variants (``base = "..."`` in a car file, :mod:`flexpipe.vehicle._car_base`).

Reference: the same changes made by the sweeps' dotted-key overrides on the base file
(:func:`flexpipe.sweeps.overrides.apply_overrides`, an independent code path), which must
give the same car; and the error locations (file, line, key) for keys a variant writes and
keys only its base writes.
"""

import dataclasses
import pickle
from pathlib import Path

import pytest

from flexpipe.cli import main
from flexpipe.errors import InputError
from flexpipe.vehicle import load_car
from flexpipe.vehicle.suspension.kc import kc
from tests._carfiles import absolute_text

ROOT = Path(__file__).resolve().parents[1]
BASE = ROOT / "cars" / "sedan_linkage.toml"
VARIANT = ROOT / "cars" / "variants" / "sedan_linkage_mf61.toml"
MF61 = "../tires/sedan_205_55R16_mf61.tir"   # relative to cars/, as an override of BASE


def _same_car(a, b):
    """Equal cars but for their file and name (compared as pickles, arrays included)."""
    def strip(car):
        susp = dataclasses.replace(car.suspension, file=None)
        return pickle.dumps(dataclasses.replace(car, file=None, name="", suspension=susp))

    assert strip(a) == strip(b)


def test_sample_variant_is_its_base_with_the_overrides():
    overrides = {"suspension.front.spring.rate_N_per_m": 95000.0}
    for c in ("fl", "fr", "rl", "rr"):
        overrides[f"corners.{c}.tire"] = MF61
        overrides[f"corners.{c}.tire_pressure_Pa"] = 230000.0
    variant = load_car(VARIANT)
    _same_car(variant, load_car(BASE, overrides=overrides))
    assert variant.name == "sedan_linkage_mf61"        # its own name, not the base's
    assert variant.body.mesh == (ROOT / "meshes" / "sedan_biw.bdf").resolve()


def test_chain_of_bases_and_paths_relative_to_each_file(tmp_path):
    """A variant of a variant in another folder: the base's paths stay relative to the
    base, the middle file's tyre to the middle file, the last file's body mesh to it."""
    (tmp_path / "a" / "b").mkdir(parents=True)
    mesh = tmp_path / "a" / "b" / "body.bdf"
    mesh.write_bytes((ROOT / "meshes" / "sedan_biw.bdf").read_bytes())
    middle = tmp_path / "a" / "middle.toml"
    middle.write_text(f'base = "{VARIANT}"\n[corners.fl]\ntire = "nowhere.tir"\n')
    last = tmp_path / "a" / "b" / "last.toml"
    last.write_text('base = "../middle.toml"\n[car]\nname = "last"\n[body]\nmesh = "body.bdf"\n')
    with pytest.raises(InputError, match="nowhere.tir") as err:
        load_car(last)   # the middle file's tyre, relative to the middle file
    assert err.value.file == middle and err.value.line == 3
    assert str(tmp_path / "a" / "nowhere.tir") in str(err.value)
    middle.write_text(f'base = "{VARIANT}"\n')
    car = load_car(last)
    assert car.name == "last" and car.body.mesh == mesh.resolve()
    assert car.corners[0].tire == (ROOT / "tires" / "sedan_205_55R16_mf61.tir").resolve()


def test_error_in_a_key_only_the_base_writes_names_the_base(tmp_path):
    base = tmp_path / "base.toml"
    base.write_text(absolute_text(BASE).replace("rate_N_per_m = 111000.0",
                                                "rate_N_per_m = -111000.0"))
    variant = tmp_path / "variant.toml"
    variant.write_text('base = "base.toml"\n[suspension.rear.spring]\nrate_N_per_m = 40000.0\n')
    with pytest.raises(InputError) as err:
        load_car(variant)
    lines = base.read_text().splitlines()
    assert err.value.file == base and "-111000.0" in lines[err.value.line - 1]
    assert err.value.key == "suspension.front.spring.rate_N_per_m"
    # ... and one the variant writes names the variant
    base.write_text(absolute_text(BASE))
    variant.write_text('base = "base.toml"\n\n[suspension.front.spring]\nrate_N_per_m = -5.0\n')
    with pytest.raises(InputError) as err:
        load_car(variant)
    assert err.value.file == variant and err.value.line == 4


@pytest.mark.parametrize("text, match, line", [
    ('base = 3\n', "expected the base car file as a string", 1),
    ('base = "nowhere.toml"\n', "does not exist", 1),
    ('base = "base.txt"\n', "is no .toml file", 1),
    ('base = "variant.toml"\n', "the bases form a cycle", 1),
    ('base = "base.toml"\ncorners = 3\n', "'corners' is a table in the base", 2),
    ('base = "base.toml"\n[car.name]\nx = 1\n', "'car.name' is a value in the base", 2),
])
def test_bad_base_names_file_line_and_key(tmp_path, text, match, line):
    (tmp_path / "base.toml").write_text(absolute_text(BASE))
    (tmp_path / "base.txt").write_text("")
    variant = tmp_path / "variant.toml"
    variant.write_text(text)
    with pytest.raises(InputError, match=match) as err:
        load_car(variant)
    assert err.value.file == variant and err.value.line == line


def test_too_long_a_chain(tmp_path):
    (tmp_path / "f0.toml").write_text(absolute_text(BASE))
    for i in range(1, 10):
        (tmp_path / f"f{i}.toml").write_text(f'base = "f{i - 1}.toml"\n')
    load_car(tmp_path / "f7.toml")          # 8 files
    with pytest.raises(InputError, match="more than 8 files in the chain"):
        load_car(tmp_path / "f8.toml")


def test_kc_and_info_read_the_variant(capsys):
    """The K&C rig reads the variant's softer front springs: its kinematic wheel rate is
    the base's scaled by the spring rates (95 / 111 kN/m), the motion ratio unchanged."""
    a = kc(BASE, axles=["front"], n=5).summary["front"]
    b = kc(VARIANT, axles=["front"], n=5).summary["front"]
    key = "kinematic wheel rate [N/m]"
    assert b[key] == pytest.approx(a[key] * 95000.0 / 111000.0, rel=1e-12)
    assert main(["info", str(VARIANT)]) == 0
    out = capsys.readouterr().out
    assert f"based on {BASE.resolve()}" in out and "spring 95000 N/m" in out


def test_sweep_key_follows_the_base(tmp_path):
    """A sweep's run key hashes every file of the chain (``car_files``), so that editing
    the base changes the key of every run on the variant."""
    from flexpipe.vehicle._car_base import car_files

    base = tmp_path / "base.toml"
    base.write_text(absolute_text(BASE))
    variant = tmp_path / "variant.toml"
    variant.write_text('base = "base.toml"\n')
    assert car_files(variant) == [variant, base.resolve()]


def test_a_sweep_over_car_files_runs_each_variant(tmp_path):
    """``car`` as a parameter: each run loads its own car file (here the linkage sample and
    its variant cars/variants/sedan_linkage_mf61.toml), keys differ, ``car.<key>``
    overrides apply to each, and a changed base file changes the variant's run key."""
    from flexpipe.sweeps import load_sweep
    from flexpipe.sweeps.execute import _cars

    road = ROOT / "roads" / "iso_c_200m.toml"
    spec = {"sweep": {"car": str(BASE), "road": str(road), "body": "rigid",
                      "t_end_s": 0.4, "speed_kmh": 60.0},
            "parameters": {"car": [str(BASE), str(VARIANT)],
                           "car.suspension.rear.spring.rate_N_per_m": [40000.0]}}
    runs = load_sweep(spec).runs()
    assert [r.car_file for r in runs] == [BASE, VARIANT] and runs[0].key != runs[1].key
    cars = _cars(runs)
    assert [c.suspension.axles["front"].left.spring().rate for c in cars] == [111000.0,
                                                                              95000.0]
    assert all(c.suspension.axles["rear"].left.spring().rate == 40000.0 for c in cars)
    assert cars[1].corners[0].tire.name == "sedan_205_55R16_mf61.tir"
    base = tmp_path / "base.toml"
    base.write_text(absolute_text(BASE))
    mine = tmp_path / "variant.toml"
    mine.write_text('base = "base.toml"\n')
    spec["parameters"] = {"car": [str(mine)]}
    before = load_sweep(spec).runs()[0].key
    base.write_text(absolute_text(BASE).replace("rate_N_per_m = 111000.0",
                                                   "rate_N_per_m = 100000.0"))
    assert load_sweep(spec).runs()[0].key != before
