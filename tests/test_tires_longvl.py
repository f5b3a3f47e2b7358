"""``[MODEL] LONGVL``, the reference speed of a tyre measurement: PAC2002 divides the wheel
speed by it, so a zero gave a raw ZeroDivisionError; it must be a measurement speed."""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import pytest

from flexpipe.errors import InputError
from flexpipe.tires import tire_from_file
from flexpipe.tires.tir import read_tir

ROOT = Path(__file__).resolve().parents[1]
SAMPLE = ROOT / "tires" / "sedan_205_55R16.tir"
REFERENCE = ROOT / ".." / "shared" / "reference" / "tires"


def _with_longvl(tmp_path, value: str) -> Path:
    text, n = re.subn(r"^LONGVL\s*=\s*\S+", f"LONGVL = {value}", SAMPLE.read_text(),
                      count=1, flags=re.M)
    assert n == 1
    path = tmp_path / "longvl.tir"
    path.write_text(text)
    return path


@pytest.mark.parametrize("value", ["0.0", "-16.7", "0.5", "1000.0"])
def test_longvl_outside_measurement_speeds_is_refused(tmp_path, value):
    path = _with_longvl(tmp_path, value)
    with pytest.raises(InputError) as exc:
        tire_from_file(path)
    err = exc.value
    assert err.key == "LONGVL" and err.file == path
    assert path.read_text().splitlines()[err.line - 1].startswith("LONGVL")
    assert "1 .. 100 m/s" in str(err)


def test_longvl_is_the_speed_of_the_reference_rolling_resistance(tmp_path):
    """A valid LONGVL is used as PAC2002's reference speed: the rolling-resistance moment
    My at v = LONGVL is the same for any LONGVL (vr = v / LONGVL = 1)."""
    a = tire_from_file(_with_longvl(tmp_path, "10.0"))
    b = tire_from_file(_with_longvl(tmp_path, "30.0"))
    assert a.mf.longvl == 10.0 and b.mf.longvl == 30.0
    my_a = a.slip_forces(0.0, 0.0, 4000.0, vx=10.0).My
    my_b = b.slip_forces(0.0, 0.0, 4000.0, vx=30.0).My
    assert float(my_a) == pytest.approx(float(my_b), rel=1e-6)
    assert float(my_a) < 0.0  # resists forward rolling


@pytest.mark.skipif(not REFERENCE.is_dir(), reason="no ../shared/reference")
def test_published_files_are_within_the_range():
    files = sorted(REFERENCE.glob("*.tir"))
    assert files
    for f in files:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            v = read_tir(f).get("MODEL", "LONGVL")
            tire_from_file(f)
        assert 10.0 <= v <= 30.0, f
