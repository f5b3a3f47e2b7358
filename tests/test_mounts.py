"""Every body-side suspension mount an interface of the flexible body.

References: the unreduced FE model solved here with dense linear algebra (supported
static flexibility at the mounts, free-free frequencies), the mount coordinates of the
brief (sedan BIW), and for the Exudyn adapter the unreduced model held at three mounts.
"""

from __future__ import annotations

import math
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import scipy.sparse.linalg as spla

import flexpipe
from flexpipe.errors import InputError
from flexpipe.fem import Material, assemble
from flexpipe.flexbody import load_body
from flexpipe.mesh.generate import box
from flexpipe.reduction.verify import (
    block_errors,
    supported_flexibility_full,
    supported_flexibility_reduced,
)
from flexpipe.vehicle.mounts import Mount, mount_interfaces, read_hardpoints

ROOT = Path(__file__).resolve().parents[1]
BIW = ROOT / "meshes" / "sedan_biw.bdf"
STEEL = Material(210e9, 0.3, 7850.0)
#: mount points on the 1.0 x 0.4 x 0.1 m hex block (grid nodes, 50 mm spacing)
POINTS = {
    "a": (0.10, 0.0, 0.0), "b": (0.10, 0.40, 0.0), "c": (0.90, 0.0, 0.0),
    "d": (0.90, 0.40, 0.0), "e": (0.50, 0.20, 0.10), "f": (0.30, 0.0, 0.05),
    "g": (0.70, 0.40, 0.05), "h": (0.50, 0.0, 0.10),
}
#: statically determinate support: a (x, y, z), c (y, z), b (z)
SUPPORT = [("a", (0, 1, 2)), ("c", (1, 2)), ("b", (2,))]
#: the mount coordinates of the brief (left side; right side mirrored)
BRIEF = {
    "front_lower_arm_front": (0.200, 0.420, 0.148), "front_lower_arm_rear": (-0.200, 0.470, 0.153),
    "front_upper_arm_front": (-0.100, 0.470, 0.523), "front_upper_arm_rear": (-0.250, 0.510, 0.528),
    "front_spring_upper": (-0.040, 0.520, 0.648), "front_rack_mount": (-0.200, 0.300, 0.298),
    "front_arb_bushing": (-0.150, 0.350, 0.220), "rear_upper_arm_front": (-2.690, 0.397, 0.383),
    "rear_upper_arm_rear": (-2.907, 0.358, 0.363),
    "rear_lateral_link_inner": (-2.714, 0.188, 0.168),
    "rear_trailing_link_front": (-2.027, 0.449, 0.229),
    "rear_tie_rod_inner": (-3.007, 0.170, 0.185), "rear_spring_upper": (-2.569, 0.491, 0.411),
    "rear_damper_upper": (-2.579, 0.478, 0.616), "rear_arb_bushing": (-2.950, 0.350, 0.250),
}


@pytest.fixture(scope="module")
def block():
    return assemble(box(1.0, 0.4, 0.1, 20, 8, 2, cell="hexahedron"), STEEL)


def _mounts(dofs=3):
    return [flexpipe.Interface(p, name=n, dofs=dofs) for n, p in POINTS.items()]


def _node_dofs(fe, p):
    i = int(np.linalg.norm(fe.nodes - np.asarray(p), axis=1).argmin())
    return i * fe.dofs_per_node + np.arange(3)


@pytest.fixture(scope="module")
def reference(block):
    """Dense unreduced model: supported flexibility at the mounts and free-free spectrum."""
    K = block.K.toarray()
    tr = np.concatenate([_node_dofs(block, p) for p in POINTS.values()])
    names = list(POINTS)
    pinned = np.array([tr[3 * names.index(n) + c] for n, cs in SUPPORT for c in cs])
    free = np.setdiff1d(np.arange(K.shape[0]), pinned)
    F = np.zeros((K.shape[0], tr.size))
    F[tr, np.arange(tr.size)] = 1.0
    u = np.zeros_like(F)
    u[free] = np.linalg.solve(K[np.ix_(free, free)], F[free])
    # SciPy's ARPACK in shift-invert mode (not flexpipe's eigensolver)
    lam = np.sort(spla.eigsh(block.K.tocsc(), k=30, M=block.M.tocsc(), sigma=-1.0e3,
                             which="LM", return_eigenvectors=False))
    return u[tr], np.sqrt(np.clip(lam, 0, None)) / (2 * np.pi)


# --------------------------------------------------------------------------- reduction
def test_translational_mounts_give_exact_static_flexibility(block, reference):
    G_ref, _ = reference
    body = flexpipe.reduce(block, _mounts(3), f_max=2000.0)
    assert body.meta["n_boundary_dof"] == 3 * len(POINTS)
    assert all(i.dofs == 3 and i.kind == "node" for i in body.interfaces)
    G = supported_flexibility_reduced(body, SUPPORT)
    np.testing.assert_allclose(G, G_ref, rtol=0, atol=1e-8 * np.abs(G_ref).max())
    # the helper the bench uses reproduces the dense reference too
    G_helper = supported_flexibility_full(block, _mounts(3), SUPPORT)
    np.testing.assert_allclose(G_helper, G_ref, rtol=0, atol=1e-9 * np.abs(G_ref).max())


def test_free_free_frequencies_below_band(block, reference):
    _, f_ref = reference
    f_max = 1.05 * f_ref[10]  # five elastic modes in the band
    body = flexpipe.reduce(block, _mounts(3), f_max=f_max)
    f = body.frequencies_hz
    below = (f_ref[6:] <= f_max)
    assert below.sum() == 5
    np.testing.assert_array_less(f_ref[6:][below] * (1 - 1e-9), f[6:6 + below.sum()])
    assert np.max(f[6:6 + below.sum()] / f_ref[6:][below] - 1) < 5e-3


def test_interface_reduction_converges_to_full_craig_bampton(block, reference):
    G_ref, f_ref = reference
    f_max = 1.05 * f_ref[10]
    full = flexpipe.reduce(block, _mounts(3), f_max=f_max)
    errors, counts = [], []
    for cut in (2000.0, 5000.0, 20000.0, 1e9, math.inf):  # inf: every CC mode
        body = flexpipe.reduce(block, _mounts(3), f_max=f_max, interface_f_max=cut)
        counts.append(body.meta["n_constraint_modes"])
        G = supported_flexibility_reduced(body, SUPPORT)
        errors.append(block_errors(G, G_ref, skip=(0,)).max())
        f = body.frequencies_hz
        below = f_ref[6:] <= f_max
        assert np.all(f[6:6 + below.sum()] >= f_ref[6:][below] * (1 - 1e-9))  # Ritz bound
    assert counts[0] < counts[1] < counts[2] == counts[3] == counts[4] == 3 * len(POINTS)
    assert errors[0] > errors[1] > errors[2] and max(errors[3:]) < 1e-8
    # every CC mode kept: the full Craig-Bampton space plus the inertia vectors, so no
    # frequency is higher than full Craig-Bampton's (Rayleigh-Ritz)
    k = full.n_modes
    assert np.all(body.frequencies_hz[6:k] <= full.frequencies_hz[6:k] * (1 + 1e-9))


def test_interface_reduction_keeps_the_band(block, reference):
    _, f_ref = reference
    f_max = 1.05 * f_ref[10]
    body = flexpipe.reduce(block, _mounts(3), f_max=f_max, interface_f_max=2 * f_max)
    below = f_ref[6:] <= f_max
    f = body.frequencies_hz[6:6 + below.sum()]
    assert body.meta["n_inertia_vectors"] == body.meta["n_constraint_modes"]
    assert body.n_modes < flexpipe.reduce(block, _mounts(3), f_max=f_max).n_modes
    assert np.max(f / f_ref[6:][below] - 1) < 5e-3  # measured 1.9e-3


def test_mixed_three_and_six_dof_mounts_round_trip(block, tmp_path):
    itfs = _mounts(3)[:6] + [flexpipe.Interface((0.0, 0.2, 0.05), radius=0.06, name="end",
                                                dofs=6)]
    body = flexpipe.reduce(block, itfs, n_modes=4)
    assert body.meta["n_boundary_dof"] == 6 * 3 + 6
    assert body.interface("end").dofs == 6 and body.interface("a").dofs == 3
    # solid nodes have no rotation: a 3-DOF node mount has zero rotation rows
    assert not np.any(body.interface("a").shapes[3:])
    back = load_body(body.save(tmp_path / "b.npz"))
    assert back == body and back.interface("a").dofs == 3
    # with interface reduction: a residual compliance per mount, symmetric and >= 0
    red = flexpipe.reduce(block, itfs, f_max=2000.0, interface_f_max=3000.0)
    C6, C3 = red.interface("end").residual_compliance, red.interface("a").residual_compliance
    assert C6.shape == (6, 6) and C3.shape == (3, 3)
    for C in (C6, C3):
        np.testing.assert_allclose(C, C.T, atol=1e-12 * np.abs(C).max())
        assert np.linalg.eigvalsh(C).min() >= -1e-12 * np.abs(C).max() and C.max() > 0
    assert load_body(red.save(tmp_path / "r.npz")) == red


# --------------------------------------------------------------------------- mounts API
def test_mount_input_errors(block):
    with pytest.raises(InputError, match="off the body"):
        mount_interfaces([("m", (3.0, 0.0, 0.0))], block.nodes, file="car.toml")
    with pytest.raises(InputError, match="not a mesh node"):
        mount_interfaces([("m", (0.52, 0.2, 0.1))], block.nodes)
    with pytest.raises(InputError, match="dofs must be 3"):
        Mount("m", (0.1, 0.0, 0.0), None, 4)
    with pytest.raises(InputError, match="no node set"):
        mount_interfaces([Mount("m", node_set="nope")], block.mesh)
    with pytest.raises(InputError, match="used twice"):
        mount_interfaces([("m", (0.1, 0.0, 0.0)), ("m", (0.9, 0.0, 0.0))], block.nodes)
    with pytest.raises(InputError, match="dofs must be 3"):
        flexpipe.Interface((0.1, 0.0, 0.0), name="x", dofs=2)


def test_mount_by_point_radius_node_set_and_node_ids(block):
    i = int(np.linalg.norm(block.nodes - np.array([0.5, 0.2, 0.1]), axis=1).argmin())
    itfs = mount_interfaces([("p", POINTS["a"]), ("r", (0.9, 0.2, 0.05), 0.06, 6),
                             Mount("s", node_set="xmin", dofs=6), Mount("n", nodes=(i,))],
                            block.mesh)
    assert [t.name for t in itfs] == ["p", "r", "s", "n"]
    assert [t.dofs for t in itfs] == [3, 6, 6, 3]
    np.testing.assert_allclose(itfs[2].point, [0.0, 0.2, 0.05])  # centroid of the set
    body = flexpipe.reduce(block, itfs, n_modes=2)
    assert body.interface("s").nodes.size == len(block.mesh.node_sets["xmin"])


def test_mount_by_mesh_file_ids_and_by_positions(block):
    """``node_ids`` are the mesh file's ids, ``nodes`` 0-based positions; both tie the same
    node, and ``Mesh.node_index`` turns one into the other."""
    ids = np.arange(101, 101 + block.mesh.n_nodes) * 2  # file ids unlike the positions
    mesh = replace(block.mesh, node_ids=ids)
    i = int(np.linalg.norm(mesh.points - np.array([0.5, 0.2, 0.1]), axis=1).argmin())
    (by_id,) = mount_interfaces([Mount("i", node_ids=(int(ids[i]),))], mesh)
    (by_pos,) = mount_interfaces([Mount("p", nodes=(i,))], mesh)
    assert by_id.nodes == by_pos.nodes == (i,)
    assert mesh.node_index([ids[i], ids[0]]).tolist() == [i, 0]
    with pytest.raises(InputError) as e:
        mount_interfaces([Mount("i", node_ids=(int(ids[i]) + 1, 1))], mesh, file="car.toml")
    msg = str(e.value)
    assert "car.toml" in msg and "key 'mounts.i.node_ids'" in msg
    assert f"{ids[0]} and {ids[-1]}" in msg and str(mesh.n_nodes) in msg  # ids with gaps
    assert f"{ids[i] + 1} -> {ids[i]} or {ids[i + 1]}" in msg and f"1 -> {ids[0]}" in msg
    with pytest.raises(InputError, match="node_ids"):  # a position past the end: hint at ids
        mount_interfaces([Mount("p", nodes=(mesh.n_nodes,))], mesh)
    with pytest.raises(InputError, match="a flexpipe.mesh.Mesh"):
        mount_interfaces([Mount("i", node_ids=(1,))], block.nodes)


# --------------------------------------------------------------------------- sedan BIW
@pytest.fixture(scope="module")
def biw():
    return flexpipe.read_mesh(BIW)


def test_sedan_biw_carries_every_mount_of_the_brief(biw):
    hp = read_hardpoints(BIW)
    expected = {}
    for name, (x, y, z) in BRIEF.items():
        expected[f"{name}_l"] = (x, y, z)
        expected[f"{name}_r"] = (x, -y, z)
    assert len(expected) == 30
    for name, p in expected.items():
        assert hp[name] == pytest.approx(p, abs=1e-9), name
        d = np.linalg.norm(biw.points - np.asarray(p), axis=1)
        assert d.min() < 1e-6, f"{name} is {d.min():.3f} m from the body"
        # the SET1 named by its '$ SET name' comment is that node
        np.testing.assert_array_equal(biw.node_sets[name], [int(d.argmin())])
    itfs = mount_interfaces([Mount(n, p) for n, p in expected.items()], biw)
    assert len(itfs) == 30
    for name in ("strut_fl", "strut_fr", "damper_rl", "damper_rr"):  # the old four remain
        assert name in hp and biw.node_sets[name].size > 1


def test_sedan_biw_mount_structure_is_connected(biw):
    # every mount node belongs to at least two beam elements (a bracket, not a loose end)
    line = [b for b in biw.blocks if b.type == "line"][0].cells
    for name, p in read_hardpoints(BIW).items():
        if name.startswith(("front_", "rear_")):
            i = int(np.linalg.norm(biw.points - np.asarray(p), axis=1).argmin())
            assert np.count_nonzero(line == i) >= 2, name


# --------------------------------------------------------------------------- car
def test_reduced_body_with_mounts(tmp_path, monkeypatch):
    sys.path.insert(0, str(Path(__file__).parent))
    from test_vehicle_flex import _car_text, _write_bdf

    from flexpipe.vehicle import bodymodel as bm
    from flexpipe.vehicle import load_car

    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path / "cache"))
    mesh = tmp_path / "frame.bdf"
    _write_bdf(mesh)
    car_file = tmp_path / "frame.toml"
    car_file.write_text(_car_text(mesh))
    car = load_car(car_file)
    mounts = [("tower_l", (0.0, 0.55, 0.75), None, 6), ("tower_r", (0.0, -0.55, 0.75), None, 6),
              ("rail_fl", (0.6, 0.55, 0.4), None, 3), ("rail_fr", (0.6, -0.55, 0.4), None, 3),
              ("rail_rl", (-2.7, 0.55, 0.4), None, 3), ("rail_rr", (-2.7, -0.55, 0.4), None, 3)]
    body, info = bm.reduced_body(car, f_max=30.0, mounts=mounts, log=lambda *_: None)
    assert not info["cached"] and body.interface_names == tuple(m[0] for m in mounts)
    assert body.meta["n_boundary_dof"] == 2 * 6 + 4 * 3
    again, info2 = bm.reduced_body(car, f_max=30.0, mounts=mounts, log=lambda *_: None)
    assert info2["cached"] and again == body
    _, info3 = bm.reduced_body(car, f_max=30.0, mounts=mounts, interface_f_max=200.0,
                               log=lambda *_: None)
    assert not info3["cached"]  # the interface reduction is part of the cache key
    with pytest.raises(InputError, match="off the body"):
        bm.reduced_body(car, f_max=30.0, mounts=[("x", (0.3, 0.0, 2.0), None, 3)],
                        log=lambda *_: None, cache=False)


# --------------------------------------------------------------------------- Exudyn
def test_exudyn_markers_for_every_mount_and_static_deflection(block):
    exu = pytest.importorskip("exudyn")
    import exudyn.itemInterface as eii

    from flexpipe.exu.body import add_flexible_body, add_rigid_twin

    itfs = _mounts(3) + [flexpipe.Interface((1.0, 0.2, 0.05), radius=0.06, name="end", dofs=6)]
    body = flexpipe.reduce(block, itfs, n_modes=10)
    SC = exu.SystemContainer()
    mbs = SC.AddSystem()
    h = add_flexible_body(mbs, body, gravity=(0, 0, 0), damping=False)
    SC2 = exu.SystemContainer()
    mbs2 = SC2.AddSystem()
    r = add_rigid_twin(mbs2, body, position=(0, 2.0, 0), gravity=(0, 0, 0))
    mbs2.Assemble()
    for n, p in POINTS.items():  # the twin's position markers sit on the mount points
        np.testing.assert_allclose(r.interface_position(mbs2, n), np.add(p, (0, 2.0, 0)),
                                   atol=1e-12)
    names = set(body.interface_names)
    assert set(h.position_markers) == set(r.position_markers) == names
    assert set(h.markers) == set(r.markers) == {"end"}  # rigid markers for 6-DOF mounts only
    # held at a, b, c (every translation) by spherical joints; 1 kN at e
    ground = mbs.AddObject(eii.ObjectGround())
    for n in ("a", "b", "c"):
        mg = mbs.AddMarker(eii.MarkerBodyPosition(bodyNumber=ground,
                                                  localPosition=list(POINTS[n])))
        mbs.AddObject(eii.SphericalJoint(markerNumbers=[mg, h.position_markers[n]]))
    F = np.array([300.0, -200.0, 1000.0])
    mbs.AddLoad(eii.LoadForceVector(markerNumber=h.position_markers["e"], loadVector=list(F)))
    mbs.Assemble()
    ss = exu.SimulationSettings()
    ss.staticSolver.verboseMode = 0
    ss.solution.file.write = False  # noqa: SLF001
    mbs.SolveStatic(ss)
    u_exu = {n: np.asarray(mbs.GetMarkerOutput(h.position_markers[n],
                                               exu.OutputVariableType.Position))
             - np.asarray(POINTS[n]) for n in ("d", "e", "h")}
    # unreduced model held at the same 9 DOF
    K = block.K.toarray()
    pinned = np.concatenate([_node_dofs(block, POINTS[n]) for n in ("a", "b", "c")])
    free = np.setdiff1d(np.arange(K.shape[0]), pinned)
    f = np.zeros(K.shape[0])
    f[_node_dofs(block, POINTS["e"])] = F
    u = np.zeros(K.shape[0])
    u[free] = np.linalg.solve(K[np.ix_(free, free)], f[free])
    scale = np.abs(u).max()
    for n in ("d", "e", "h"):
        np.testing.assert_allclose(u_exu[n], u[_node_dofs(block, POINTS[n])], rtol=0,
                                   atol=1e-3 * scale)  # measured 4.2e-4


def test_residual_compliance_restores_the_driving_point_flexibility(block, reference):
    G_ref, f_ref = reference
    for cut in (2000.0, 5000.0):
        body = flexpipe.reduce(block, _mounts(3), f_max=1.05 * f_ref[10], interface_f_max=cut)
        G = supported_flexibility_reduced(body, SUPPORT)
        C = np.zeros_like(G)
        for i, itf in enumerate(body.interfaces):  # in series at each mount
            C[3 * i:3 * i + 3, 3 * i:3 * i + 3] = itf.residual_compliance
        plain = block_errors(G, G_ref, skip=(0,))
        series = block_errors(G + C, G_ref, skip=(0,))
        assert series.max() < plain.max()


def test_interface_spec_file_takes_dofs(tmp_path):
    from flexpipe.reduction.spec import read_interfaces

    spec = tmp_path / "i.toml"
    spec.write_text('[[interface]]\nname = "ball"\npoint = [0.1, 0.0, 0.0]\ndofs = 3\n'
                    '[[interface]]\nname = "strut"\npoint = [0.9, 0.0, 0.0]\nradius = 0.06\n')
    a, b = read_interfaces(spec)
    assert (a.dofs, b.dofs) == (3, 6)
    spec.write_text('[[interface]]\nname = "ball"\npoint = [0.1, 0.0, 0.0]\ndofs = 5\n')
    with pytest.raises(InputError, match=r"line 1.*interface\[0\]\.dofs"):
        read_interfaces(spec)


def test_cli_reduce_with_translational_mounts_and_interface_reduction(tmp_path, capsys):
    from flexpipe.cli import main
    from flexpipe.mesh.write import write_mesh

    write_mesh(box(1.0, 0.4, 0.1, 10, 4, 2, cell="hexahedron"), tmp_path / "b.msh")
    lines = []
    for n, p in POINTS.items():
        lines += ["[[interface]]", f'name = "{n}"', f"point = {list(p)}", "dofs = 3"]
    (tmp_path / "s.toml").write_text("\n".join(lines) + "\n")
    out = tmp_path / "b.npz"
    args = ["reduce", str(tmp_path / "b.msh"), "--interfaces", str(tmp_path / "s.toml"),
            "-o", str(out), "--material", "steel", "--f-max", "3000", "--no-check", "-q"]
    assert main(args) == 0
    full = load_body(out)
    assert main(args + ["--interface-f-max", "3000"]) == 0
    red = load_body(out)
    assert "3 DOF" in capsys.readouterr().out
    assert full.meta["n_constraint_modes"] == 24 > red.meta["n_constraint_modes"]


def test_step_cost_runs_and_names_bad_supports(block):
    pytest.importorskip("exudyn")
    from flexpipe.exu.timing import step_cost

    body = flexpipe.reduce(block, _mounts(3), n_modes=2)
    assert np.isfinite(step_cost(body, ["a", "b", "c", "d"], t_end=0.01))
    with pytest.raises(InputError, match="no interfaces"):
        step_cost(body, ["a", "zz"], t_end=0.01)
