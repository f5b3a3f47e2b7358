"""A car whose body is a ready reduced body (``[body] body_file``), and mounts tied by node
set or the mesh file's node ids (``[body.mounts.<name>]``): the same body reached by another
route must give the same car (reference: the car built from the mesh)."""

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

import flexpipe as fp
from flexpipe.errors import InputError
from flexpipe.vehicle import bodymodel
from flexpipe.vehicle.simulation import body_mounts, prepare

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan_linkage.toml"


def _variant(tmp_path, body_lines: str) -> Path:
    """cars/sedan_linkage.toml with its [body] mesh line replaced; paths made absolute."""
    text = CAR.read_text().replace('"../', f'"{ROOT}/')
    old = f'mesh = "{ROOT}/meshes/sedan_biw.bdf"'
    assert old in text
    out = tmp_path / "car.toml"
    out.write_text(text.replace(old, body_lines, 1))
    return out


@pytest.fixture(scope="module")
def mesh_car_runs():
    car = fp.load_car(CAR)
    prep = prepare(car, body="flexible", speed=0.0)
    return car, prep


def test_ready_body_file_gives_the_same_car(tmp_path, mesh_car_runs):
    car, prep = mesh_car_runs
    fb = prep["flexbody"]
    body_npz = tmp_path / "body.npz"
    fb.save(body_npz)
    # a ready body carries its own masses: drop the [[body.mass]] tables
    text = _variant(tmp_path, f'body_file = "{body_npz}"').read_text()
    text = "\n".join(ln for ln in text.split("\n[[body.mass]]")[0].splitlines()) + \
        "\n[corners" + text.split("\n[corners", 1)[1]
    (tmp_path / "car2.toml").write_text(text)
    car2 = fp.load_car(tmp_path / "car2.toml")
    rb, rb2 = bodymodel.rigid_properties(car), bodymodel.rigid_properties(car2)
    assert rb2.mass == pytest.approx(rb.mass, rel=1e-9)
    assert np.allclose(rb2.center_of_mass, rb.center_of_mass, atol=1e-9)
    a = fp.simulate(car, speed=0.0, t_end=0.3, body="flexible", prepared=prep)
    b = fp.simulate(car2, speed=0.0, t_end=0.3, body="flexible")
    assert b.status == 0, b.message
    for ch in ("hub_fl_z", "hub_rr_y", "tire_rl_Fz"):
        assert np.allclose(a[ch], b[ch], rtol=1e-6, atol=1e-6)


def _body_file_car(tmp_path, body, name):
    """The sample car with ``body`` saved as its ready body file (its [[body.mass]] tables
    dropped: a ready body carries its own masses)."""
    npz = tmp_path / f"{name}.npz"
    body.save(npz)
    text = _variant(tmp_path, f'body_file = "{npz}"').read_text()
    text = text.split("\n[[body.mass]]")[0] + "\n[corners" + text.split("\n[corners", 1)[1]
    (tmp_path / f"{name}.toml").write_text(text)
    return fp.load_car(tmp_path / f"{name}.toml")


def test_body_file_lacking_a_mount_is_named(tmp_path, mesh_car_runs):
    from flexpipe.reduction import Interface

    car, _ = mesh_car_runs
    fe = bodymodel.body_fe(car)
    small = fp.reduce(fe, [Interface((0.2, 0.42, 0.148), radius=0.02, name="only_one")],
                      method="craig-bampton", n_modes=2)
    car3 = _body_file_car(tmp_path, small, "car3")
    with pytest.raises(InputError, match="body_file.*no interface 'front_lower_arm_front_l'"):
        fp.simulate(car3, speed=0.0, t_end=0.1, body="flexible")


def test_mount_by_node_ids_ties_the_same_node(tmp_path):
    """``[body.mounts] node_ids`` are the mesh file's ids (GRID ids), as in an interface spec:
    the id of the node at the mount point ties that node, not the one after it."""
    from flexpipe.vehicle.mounts import mount_interfaces

    car = fp.load_car(CAR)
    mesh = bodymodel.body_mesh(car)
    name = "front_upper_arm_front_l"
    p = car.suspension.mounts()[name]
    k = int(np.argmin(np.linalg.norm(mesh.points - p, axis=1)))
    grid = int(mesh.node_ids[k])
    path = _variant(tmp_path, f'mesh = "{ROOT}/meshes/sedan_biw.bdf"')
    path.write_text(path.read_text() + f"\n[body.mounts.{name}]\nnode_ids = [{grid}]\ndofs = 6\n")
    car2 = fp.load_car(path)
    m = {mm.name: mm for mm in body_mounts(car2)}[name]
    assert m.node_ids == (grid,) and m.nodes is None and m.dofs == 6 and m.radius is None
    itf = {i.name: i for i in mount_interfaces(body_mounts(car2), mesh, file=car2.file)}[name]
    assert itf.nodes == (k,) and np.allclose(mesh.points[k], p, atol=1e-6)
    # docs/car-file.md shows this very mount with its GRID id
    doc = (ROOT / "docs" / "car-file.md").read_text()
    assert f"[body.mounts.{name}]\nnode_ids = [{grid}]" in doc


def test_mount_node_ids_not_in_the_mesh_are_named(tmp_path):
    from flexpipe.vehicle.mounts import mount_interfaces

    car = fp.load_car(CAR)
    mesh = bodymodel.body_mesh(car)
    name = "front_upper_arm_front_l"
    path = _variant(tmp_path, f'mesh = "{ROOT}/meshes/sedan_biw.bdf"')
    path.write_text(path.read_text() + f"\n[body.mounts.{name}]\nnode_ids = [0, 99999]\n")
    line = path.read_text().splitlines().index(f"[body.mounts.{name}]") + 1
    car2 = fp.load_car(path)
    with pytest.raises(InputError) as e:
        mount_interfaces(body_mounts(car2), mesh, file=car2.file)
    msg = str(e.value)
    lo, hi = int(mesh.node_ids.min()), int(mesh.node_ids.max())
    assert str(path) in msg and f"line {line}" in msg
    assert f"key 'body.mounts.{name}.node_ids'" in msg
    assert f"{lo}..{hi}" in msg and str(mesh.n_nodes) in msg  # valid range and count
    assert f"0 -> {lo}" in msg and f"99999 -> {hi}" in msg  # nearest existing ids
    path.write_text(path.read_text().replace("node_ids = [0, 99999]", "node_ids = [1.5]"))
    with pytest.raises(InputError, match=rf"key 'body.mounts.{name}.node_ids'.*node ids"):
        fp.load_car(path)


def test_old_mount_key_nodes_is_a_migration_error(tmp_path):
    """``nodes`` meant 0-based positions, then file ids: a car file that still has it is an
    error naming the file, line and key and telling to give the deck's ids as node_ids."""
    name = "front_upper_arm_front_l"
    path = _variant(tmp_path, f'mesh = "{ROOT}/meshes/sedan_biw.bdf"')
    path.write_text(path.read_text() + f"\n[body.mounts.{name}]\nnodes = [5530]\n")
    line = path.read_text().splitlines().index("nodes = [5530]") + 1
    with pytest.raises(InputError) as e:
        fp.load_car(path)
    msg = str(e.value)
    assert str(path) in msg and f"line {line}" in msg and f"key 'body.mounts.{name}.nodes'" in msg
    assert "no longer accepted" in msg and "node_ids" in msg and "from your deck" in msg


def _bad_id_car(tmp_path) -> tuple:
    name = "front_upper_arm_front_l"
    path = _variant(tmp_path, f'mesh = "{ROOT}/meshes/sedan_biw.bdf"')
    path.write_text(path.read_text() + f"\n[body.mounts.{name}]\nnode_ids = [99999]\n")
    line = path.read_text().splitlines().index(f"[body.mounts.{name}]") + 1
    return path, f"line {line}", f"key 'body.mounts.{name}.node_ids'"


def test_bad_mount_node_ids_are_caught_by_check_run(tmp_path):
    """Before any reduction or output: check_run (a run's and a sweep's up-front check) and
    flexpipe info name the bad id like the reduction does; a rigid run does not need it."""
    from flexpipe.vehicle.run_inputs import check_run

    path, line, key = _bad_id_car(tmp_path)
    hi = int(bodymodel.body_mesh(fp.load_car(CAR)).node_ids.max())
    for body in ("flexible", "full"):
        with pytest.raises(InputError) as e:
            check_run(path, speed=10.0, t_end=0.1, body=body)
        msg = str(e.value)
        assert str(path) in msg and line in msg and key in msg and f"99999 -> {hi}" in msg
    check_run(path, speed=10.0, t_end=0.1, body="rigid")


def test_flexible_run_with_bad_mount_id_touches_no_output(tmp_path, capsys):
    from flexpipe.cli import main

    path, line, key = _bad_id_car(tmp_path)
    out = tmp_path / "run"
    code = main(["run", str(path), "--speed", "36", "--t-end", "0.1", "--body", "flexible",
                 "--out", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and key in err and line in err and "99999" in err
    assert not out.exists() and not (tmp_path / "run.failed").exists()
    assert main(["info", str(path)]) == 2
    assert key in capsys.readouterr().err


def test_unknown_mount_name_is_an_error(tmp_path):
    path = _variant(tmp_path, f'mesh = "{ROOT}/meshes/sedan_biw.bdf"')
    path.write_text(path.read_text() + "\n[body.mounts.front_lower_arm_frnt_l]\ndofs = 6\n")
    with pytest.raises(InputError, match="body.mounts.front_lower_arm_frnt_l"):
        fp.load_car(path)  # at load since every run (rigid too), info and kc read the file
    car = fp.load_car(CAR)  # a Car built around the loader still meets the run's check
    car = replace(car, body=replace(car.body, mounts={"front_lower_arm_frnt_l": {}}))
    with pytest.raises(InputError, match="body.mounts.front_lower_arm_frnt_l"):
        body_mounts(car)


def test_interface_band_is_read_and_checked(tmp_path):
    """``[body] interface_band_hz``: a frequency (>= 100 Hz) or "all" (every static mode);
    a full body keeps every static mode whatever the car file says; bad values and a
    prismatic-corner car name the key."""
    from flexpipe.vehicle.linkage_setup import INTERFACE_F_MAX_HZ, interface_band

    mesh = f'mesh = "{ROOT}/meshes/sedan_biw.bdf"'
    car = fp.load_car(CAR)
    assert car.body.interface_band_hz is None
    assert interface_band(car) == INTERFACE_F_MAX_HZ
    assert interface_band(car, full=True) == math.inf
    for value, want in (("800.0", 800.0), ('"all"', math.inf)):
        c = fp.load_car(_variant(tmp_path, f"{mesh}\ninterface_band_hz = {value}"))
        assert interface_band(c) == want and interface_band(c, full=True) == math.inf
    for value, words in (("50.0", ">= 100"), ('"most"', '"all"'), ("-1.0", ">= 100"),
                         ("inf", '"all"'), ("true", '"all"')):
        with pytest.raises(InputError, match=words) as exc:
            fp.load_car(_variant(tmp_path, f"{mesh}\ninterface_band_hz = {value}"))
        assert "body.interface_band_hz" in str(exc.value) and "car.toml" in str(exc.value)
    prismatic = (ROOT / "cars" / "sedan.toml").read_text().replace('"../', f'"{ROOT}/')
    assert "[body]\n" in prismatic
    p = tmp_path / "prismatic.toml"
    p.write_text(prismatic.replace("[body]\n", "[body]\ninterface_band_hz = 800.0\n", 1))
    with pytest.raises(InputError, match="prismatic corners") as exc:
        fp.load_car(p)
    assert "body.interface_band_hz" in str(exc.value)


def test_body_file_with_swapped_interface_names_is_refused(tmp_path, mesh_car_runs):
    """Two interfaces' names swapped in the interface spec: each mount's interface sits at
    the other mount's point (0.4 m away), so a flexible run would put the joints elsewhere
    than the rigid one.  Refused up front, naming both the distance and the swap."""
    from dataclasses import replace

    from flexpipe.vehicle.bodymodel import check_body_file

    car, prep = mesh_car_runs
    fb = prep["flexbody"]
    a, b = "front_lower_arm_front_l", "front_lower_arm_rear_l"
    names = {a: b, b: a}
    swapped = replace(fb, interfaces=tuple(replace(i, name=names.get(i.name, i.name))
                                           for i in fb.interfaces))
    car4 = _body_file_car(tmp_path, swapped, "car4")
    d = float(np.linalg.norm(np.subtract(*(i.point for i in fb.interfaces if i.name in names))))
    with pytest.raises(InputError) as e:
        check_body_file(car4)
    msg = str(e.value)
    assert f"interface '{a}' sits at" in msg and f"{d * 1e3:.1f} mm from the car's point" in msg
    assert f"the body's interface at that point is '{b}': are the names swapped" in msg


def test_info_names_the_ready_body_file_as_the_body(tmp_path, mesh_car_runs):
    """``flexpipe info`` said "[body.rigid] mass properties" for a body_file car, whose
    masses come from the body file; its mass there is the reduced body's own."""
    from flexpipe.vehicle.describe import car_text

    car, prep = mesh_car_runs
    car2 = _body_file_car(tmp_path, prep["flexbody"], "car5")
    line = car_text(car2).splitlines()[1]
    assert f"body: ready body file {car2.body.body_file} (its own masses)" in line
    assert f"{bodymodel.rigid_properties(car).mass:.2f} kg" in line
