"""Property-based tests (hypothesis) of the ``.tir`` and OpenCRG readers (and, for damage
only, the road, path and driver readers).

* Meaning-preserving edits of a valid file (spacing, comments, blank lines, key case,
  number spelling) load to the same model, value for value.
* Arbitrary edits (deleted, inserted, replaced or duplicated bytes and lines) either load
  or raise a :class:`~flexpipe.errors.FlexpipeError`; nothing else ever escapes.
"""

from __future__ import annotations

import re
import warnings
from pathlib import Path

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, example, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from flexpipe.errors import FlexpipeError  # noqa: E402
from flexpipe.roads import read_crg  # noqa: E402
from flexpipe.tires import read_tir, tire_from_file  # noqa: E402

REPO = Path(__file__).resolve().parents[1]
TIR = (REPO / "tires" / "sedan_205_55R16.tir").read_text()
CRG = (REPO / "roads" / "sample_bump.crg").read_text()
SETTINGS = settings(max_examples=120, deadline=None,
                    suppress_health_check=[HealthCheck.function_scoped_fixture])
_NUM = re.compile(r"^(\s*[A-Za-z_]\w*\s*=\s*)([-+]?\d+\.?\d*(?:[eE][-+]?\d+)?)(.*)$")


def _respell(number: str, how: int) -> str:
    """The same number written another way."""
    x = float(number)
    return [repr(x), f"{x:.17e}", f"{x:.17e}".replace("e", "D"), f" {number} "][how % 4]


@st.composite
def harmless_edits(draw, text: str, comment: str):
    """Apply spacing / comment / case / number-spelling edits to random lines."""
    lines = text.splitlines()
    out = []
    for line in lines:
        m = _NUM.match(line)
        what = draw(st.integers(0, 5))
        if m and what == 0:
            line = m.group(1) + _respell(m.group(2), draw(st.integers(0, 3))) + m.group(3)
        elif m and what == 1:
            line = re.sub(r"\s*=\s*", draw(st.sampled_from(["=", " =\t", "   =  "])), line,
                          count=1)
        elif m and what == 2 and "$" not in line and "!" not in line:
            line = line + f"   {comment} harmless note"
        elif m and what == 3:
            key, rest = line.split("=", 1)
            line = key.lower() + "=" + rest
        out.append(line)
        if draw(st.integers(0, 9)) == 0:
            out.append("")
    return "\n".join(out) + "\n"


@st.composite
def damaging_edits(draw, data: bytes):
    """Delete, insert, replace or duplicate a random piece of the file, 1-3 times."""
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(data)))
        j = min(len(data), i + draw(st.integers(0, 64)))
        kind = draw(st.integers(0, 4))
        blob = draw(st.binary(min_size=1, max_size=16))
        if kind == 0:
            data = data[:i] + data[j:]
        elif kind == 1:
            data = data[:i] + blob + data[i:]
        elif kind == 2:
            data = data[:i] + blob + data[j:]
        elif kind == 3:
            data = data[:i] + data[i:j] + data[i:]
        else:
            data = data[:i]
    return data


def _load_quietly(loader, path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return loader(path)


def _same_tir(a, b):
    assert set(a.sections) == set(b.sections)
    for name, sec in a.sections.items():
        assert dict(sec) == dict(b.sections[name]), name
    assert set(a.tables) == set(b.tables)
    for name, t in a.tables.items():
        np.testing.assert_array_equal(t.data, b.tables[name].data)


@SETTINGS
@given(text=harmless_edits(TIR, "$"))
def test_tir_harmless_edits_give_the_same_model(tmp_path, text):
    f = tmp_path / "edited.tir"
    f.write_text(text)
    _same_tir(_load_quietly(read_tir, f), _load_quietly(read_tir, REPO / "tires" /
                                                         "sedan_205_55R16.tir"))


@SETTINGS
@given(data=damaging_edits(TIR.encode()))
def test_tir_damaged_file_loads_or_raises_flexpipe_error(tmp_path, data):
    f = tmp_path / "damaged.tir"
    f.write_bytes(data)
    try:
        _load_quietly(tire_from_file, f)
    except FlexpipeError as exc:
        assert "damaged.tir" in str(exc)


def _same_road(a, b):
    for name in ("x", "y", "z", "left", "right"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    np.testing.assert_array_equal(a.plan.x, b.plan.x)
    np.testing.assert_array_equal(a.plan.y, b.plan.y)


def _crg_harmless(text: str):
    head, data = text.split("$" * 72 + "\n", 1)
    return harmless_edits(head, "!").map(lambda h: h + "$" * 72 + "\n" + data)


@SETTINGS
@given(text=_crg_harmless(CRG))
def test_crg_harmless_header_edits_give_the_same_road(tmp_path, text):
    f = tmp_path / "edited.crg"
    f.write_text(text)
    _same_road(_load_quietly(read_crg, f), _load_quietly(read_crg, REPO / "roads" /
                                                          "sample_bump.crg"))


@SETTINGS
@given(data=damaging_edits(CRG.encode()))
def test_crg_damaged_file_loads_or_raises_flexpipe_error(tmp_path, data):
    f = tmp_path / "damaged.crg"
    f.write_bytes(data)
    try:
        _load_quietly(read_crg, f)
    except FlexpipeError as exc:
        assert "damaged.crg" in str(exc)


def _other_readers():
    from flexpipe.driver import read_driver, read_path
    from flexpipe.roads import load_road

    return [("road.csv", REPO / "roads" / "bump.csv", load_road),
            ("road.toml", REPO / "roads" / "iso_c_200m.toml", load_road),
            ("path.csv", REPO / "paths" / "sample_xy.csv", read_path),
            ("path.toml", REPO / "paths" / "slalom_18m.toml", read_path),
            ("driver.toml", REPO / "paths" / "driver.toml", read_driver),
            ("mf61.tir", REPO / "tires" / "sedan_205_55R16_mf61.tir", tire_from_file)]


@pytest.mark.parametrize("name, base, loader", _other_readers(),
                         ids=[f"{n}-{b.name}" for n, b, _ in _other_readers()])
def test_other_damaged_files_load_or_raise_flexpipe_error(tmp_path, name, base, loader):
    """Road, path and driver readers, and the MF 6.1 tyre, under the same damage as the
    .tir and CRG files."""

    @settings(max_examples=60, deadline=None,
              suppress_health_check=[HealthCheck.function_scoped_fixture])
    @given(data=damaging_edits(base.read_bytes()))
    def check(data):
        _loads_or_names_itself(loader, tmp_path / f"damaged_{name}", data)

    check()


def _loads_or_names_itself(loader, f, data: bytes) -> None:
    """Write ``data`` to ``f``: ``loader(f)`` loads, or raises a FlexpipeError naming ``f``."""
    f.write_bytes(data)
    try:
        _load_quietly(loader, f)
    except FlexpipeError as exc:
        assert f.name in str(exc)


def test_damaged_car_file_loads_or_raises_flexpipe_error(tmp_path):
    """The linkage sample car under the same damage (a car file cut after its front
    suspension once raised a raw KeyError); its relative paths made absolute, so that the
    damage, not the folder, decides."""
    from flexpipe.vehicle import load_car

    car = REPO / "cars" / "sedan_linkage.toml"
    text = car.read_text().replace('"../', f'"{REPO.as_posix()}/')

    @settings(max_examples=60, deadline=None,
              suppress_health_check=[HealthCheck.function_scoped_fixture])
    @given(data=damaging_edits(text.encode()))
    @example(data=text[:text.index("[suspension.rear]")].encode())  # the KeyError case
    def check(data):
        _loads_or_names_itself(load_car, tmp_path / "damaged_car.toml", data)

    check()
