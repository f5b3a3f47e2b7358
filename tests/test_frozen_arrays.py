"""Frozen objects are frozen all the way down: no array inside a loaded car or an
assembled FE model can be changed in place (a changed hardpoint would otherwise not reach
the body cache, which is keyed on the car file, and a shared object would change for
every holder)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from flexpipe.vehicle import load_car

ROOT = Path(__file__).resolve().parents[1]


def _arrays(obj, path="car", seen=None):
    """Every ndarray reachable from ``obj`` through dataclass fields, tuples and dicts."""
    seen = set() if seen is None else seen
    if id(obj) in seen:
        return
    seen.add(id(obj))
    if isinstance(obj, np.ndarray):
        yield path, obj
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        for f in dataclasses.fields(obj):
            yield from _arrays(getattr(obj, f.name), f"{path}.{f.name}", seen)
    elif isinstance(obj, (tuple, list)):
        for i, v in enumerate(obj):
            yield from _arrays(v, f"{path}[{i}]", seen)
    elif isinstance(obj, dict):
        for k, v in obj.items():
            yield from _arrays(v, f"{path}[{k!r}]", seen)


@pytest.mark.parametrize("name", ["sedan.toml", "sedan_linkage.toml"])
def test_no_array_of_a_loaded_car_is_writable(name):
    car = load_car(ROOT / "cars" / name)
    found = list(_arrays(car))
    assert len(found) >= 10, [p for p, _ in found]
    writable = [p for p, a in found if a.flags.writeable]
    assert not writable, writable
    hp = car.corners[0].hardpoint
    with pytest.raises(ValueError, match="read-only"):
        hp[2] += 0.01


def test_replace_builds_a_changed_car_and_leaves_the_original():
    car = load_car(ROOT / "cars" / "sedan.toml")
    c0 = car.corners[0]
    moved = dataclasses.replace(c0, hardpoint=c0.hardpoint + [0.0, 0.0, 0.01])
    assert moved.hardpoint[2] == pytest.approx(c0.hardpoint[2] + 0.01)
    assert not moved.hardpoint.flags.writeable
    given = np.array([1.0, 2.0, 3.0])
    other = dataclasses.replace(c0, hardpoint=given)
    given[0] = 9.0  # the caller's array stays the caller's
    assert other.hardpoint[0] == 1.0 and given.flags.writeable


def test_fe_model_nodes_are_read_only():
    from flexpipe.fem import assemble
    from flexpipe.mesh import read_mesh

    mesh = read_mesh(ROOT / "meshes" / "bracket.bdf")
    model = assemble(mesh)
    assert not model.nodes.flags.writeable
    with pytest.raises(ValueError, match="read-only"):
        model.nodes[0, 0] = 1.0
