"""A mount or interface tied by node set / node ids must reach its point, and node set
names match ignoring case (Abaqus).

Reference: the sample BIW deck (meshes/sedan_biw.bdf), where GRID 5531 is the node at
``front_upper_arm_front_l`` and GRID 1 lies 2.6 m away, and the set ``strut_fl`` (the
prismatic sample's strut top) lies 0.21 m from ``front_spring_upper_l``.
"""

from __future__ import annotations

import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.errors import InputError
from flexpipe.fem import Material, assemble
from flexpipe.mesh.generate import box
from flexpipe.reduction.interface import find_node_set, resolve_interfaces
from flexpipe.vehicle.mounts import Mount, check_mount_node_ids, mount_interfaces

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan_linkage.toml"
STEEL = Material(210e9, 0.3, 7850.0)


def _car(tmp_path, extra: str) -> Path:
    text = CAR.read_text().replace('"../', f'"{ROOT}/')
    out = tmp_path / "car.toml"
    out.write_text(text + "\n" + extra)
    return out


@pytest.fixture(scope="module")
def block():
    mesh = box(1.0, 0.4, 0.1, 20, 8, 2, cell="hexahedron")
    near = np.flatnonzero(np.linalg.norm(mesh.points - (0.1, 0, 0), axis=1) < 0.06)
    mesh = replace(mesh, node_sets={**mesh.node_sets, "Corner_A": near})
    return assemble(mesh, STEEL)


def test_car_mount_tied_by_far_node_ids_is_an_error(tmp_path):
    path = _car(tmp_path, "[body.mounts.front_upper_arm_front_l]\nnode_ids = [1]\n")
    car = fp.load_car(path)
    with pytest.raises(InputError) as e:
        check_mount_node_ids(car)  # what info and a run do before any output
    msg = str(e.value)
    assert str(path) in msg and "key 'body.mounts.front_upper_arm_front_l.node_ids'" in msg
    assert "does not reach the mount point" in msg and "2.6" in msg and "0.05 m" in msg
    assert "5531" in msg  # the node at the mount: what would be valid
    ok = _car(tmp_path, "[body.mounts.front_upper_arm_front_l]\nnode_ids = [5531]\n")
    check_mount_node_ids(fp.load_car(ok))


def test_car_mount_tied_by_another_mounts_node_set_is_an_error(tmp_path):
    path = _car(tmp_path, '[body.mounts.front_spring_upper_l]\nnode_set = "strut_fl"\n')
    with pytest.raises(InputError, match=r"node_set'.*node set 'strut_fl'.*0\.2\d\d m away"):
        check_mount_node_ids(fp.load_car(path))


def test_car_node_set_matches_ignoring_case(tmp_path):
    path = _car(tmp_path, '[body.mounts.front_lower_arm_front_l]\n'
                          'node_set = "FRONT_LOWER_ARM_FRONT_L"\n')
    check_mount_node_ids(fp.load_car(path))  # no error: the set of the deck, any case


def test_mount_interfaces_checks_the_tie_against_the_point(block):
    far = int(np.linalg.norm(block.nodes - (0.9, 0.4, 0.1), axis=1).argmin())
    with pytest.raises(InputError, match=r"does not reach the mount point.*0\.05 m"):
        mount_interfaces([Mount("a", (0.1, 0.0, 0.0), nodes=(far,))], block.mesh)
    # a ring of nodes centred on the point, none of them within 0.05 m, is valid
    X = block.nodes
    ring = np.flatnonzero(np.isclose(np.abs(X[:, 0] - 0.5), 0.1) & np.isclose(X[:, 2], 0.1)
                          & np.isclose(np.abs(X[:, 1] - 0.2), 0.1))
    itf = mount_interfaces([Mount("e", (0.5, 0.2, 0.1), nodes=tuple(ring))], block.mesh)
    assert len(itf) == 1


def test_reduce_interface_node_set_far_from_its_point_is_an_error(block):
    itf = fp.Interface((100.0, 0.0, 0.0), node_set="Corner_A", name="fl")
    with pytest.raises(InputError, match=r"interface 'fl'.*lies 99\.85 m from its point"):
        resolve_interfaces(block, [itf])
    ok = resolve_interfaces(block, [fp.Interface((0.1, 0.0, 0.0), node_set="corner_a",
                                                 name="fl")])  # any case
    assert ok[0].nodes.size > 1


def test_large_radius_warns(block):
    with pytest.warns(UserWarning, match="radius 0.5 m ties"):
        resolve_interfaces(block, [fp.Interface((0.5, 0.2, 0.1), radius=0.5, name="x")])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        resolve_interfaces(block, [fp.Interface((0.5, 0.2, 0.1), radius=0.03, name="x")])


def test_find_node_set_case_rules():
    sets = {"MOUNT_FL": [1], "a": [2], "A": [3]}
    assert find_node_set(sets, "mount_fl") == "MOUNT_FL"
    assert find_node_set(sets, "a") == "a"
    with pytest.raises(InputError, match="ambiguous"):
        find_node_set({"Ab": [1], "AB": [2]}, "ab")
    with pytest.raises(InputError, match="no node set 'x'"):
        find_node_set(sets, "x")


def _corner_body(tmp_path, dofs_rr: int) -> Path:
    """A small reduced plate whose corners are the sample car's four corner hardpoints,
    with the four corner interfaces there (``rr`` with ``dofs_rr``)."""
    from dataclasses import replace

    car = fp.load_car(ROOT / "cars" / "sedan.toml")
    pts = {c: tuple(car.corner(c).hardpoint) for c in ("fl", "fr", "rl", "rr")}
    lo = np.min(list(pts.values()), axis=0)
    size = np.max(list(pts.values()), axis=0) - lo
    mesh = box(size[0], size[1], 0.1, 28, 13, 1, cell="hexahedron")  # 0.1 m elements
    fe = assemble(replace(mesh, points=mesh.points + lo), STEEL)
    itf = [fp.Interface(p, radius=0.12, name=n, dofs=dofs_rr if n == "rr" else 6)
           for n, p in pts.items()]
    npz = tmp_path / f"corners{dofs_rr}.npz"
    fp.reduce(fe, itf, method="craig-bampton", n_modes=2).save(npz)
    return npz


def _prismatic_body_file_car(tmp_path, npz) -> Path:
    text = (ROOT / "cars" / "sedan.toml").read_text().replace('"../', f'"{ROOT}/')
    text = text.replace(f'mesh = "{ROOT}/meshes/sedan_biw.bdf"', f'body_file = "{npz}"', 1)
    text = text.split("\n[[body.mass]]")[0] + "\n[corners" + text.split("\n[corners", 1)[1]
    out = tmp_path / "prismatic.toml"
    out.write_text(text)
    return out


def test_prismatic_car_with_a_3dof_corner_in_its_body_file_is_named(tmp_path):
    """The BYO audit's D6: a raw KeyError 'rr' after the rigid run; now an error naming
    the car file, body_file and the interface, before any run (as info checks)."""
    car = fp.load_car(_prismatic_body_file_car(tmp_path, _corner_body(tmp_path, 3)))
    with pytest.raises(InputError) as e:
        check_mount_node_ids(car)
    msg = str(e.value)
    assert "key 'body.body_file'" in msg and "3-DOF" in msg and " rr;" in msg
    assert "dofs = 6" in msg
    ok = fp.load_car(_prismatic_body_file_car(tmp_path, _corner_body(tmp_path, 6)))
    check_mount_node_ids(ok)


def test_keys_a_body_file_ignores_are_named_once(tmp_path):
    path = _prismatic_body_file_car(tmp_path, _corner_body(tmp_path, 6))
    path.write_text(path.read_text().replace(
        "[body.fatigue]", "[body.rigid]\nmass_kg = 1335.0\ncg_m = [-1.2, 0.0, 0.55]\n"
        "inertia_kg_m2 = [500.0, 2000.0, 2200.0]\n\n[body.fatigue]", 1))
    with pytest.warns(UserWarning) as got:
        fp.load_car(path)
    msgs = [str(w.message) for w in got if "body_file these keys are ignored" in str(w.message)]
    assert len(msgs) == 1 and str(path) in msgs[0]
    for key in ("[body.rigid]", "damping_ratio", "interface_radius_m"):
        assert key in msgs[0]
