"""FlexBody: storage round trip, mass properties (closed form), FFRF invariants against
Exudyn's own ObjectFFRFreducedOrderInterface, and a shell body against a solid one."""

from __future__ import annotations

import numpy as np
import pytest

import flexpipe
from flexpipe.errors import InputError
from flexpipe.fem import Material, assemble
from flexpipe.flexbody.invariants import ffrf_invariants, translational_block
from flexpipe.mesh.generate import box, plate

STEEL = Material(210e9, 0.3, 7850.0)
L, B, H = 1.0, 0.2, 0.1


@pytest.fixture(scope="module")
def bar_body():
    fe = assemble(box(L, B, H, 12, 3, 2), STEEL)
    itfs = [flexpipe.Interface((0.0, B / 2, H / 2), radius=0.07, name="left"),
            flexpipe.Interface((L, B / 2, H / 2), radius=0.07, name="right")]
    return fe, flexpipe.reduce(fe, itfs, method="craig-bampton", n_modes=4)


def test_mass_properties_equal_closed_form_of_the_block(bar_body):
    _, body = bar_body
    m = 7850.0 * L * B * H
    assert body.mass == pytest.approx(m, rel=1e-12)
    np.testing.assert_allclose(body.center_of_mass, [L / 2, B / 2, H / 2], atol=1e-12)
    J = m / 12 * np.diag([B**2 + H**2, L**2 + H**2, L**2 + B**2])
    np.testing.assert_allclose(body.inertia, J, atol=1e-10 * J.max())
    c = body.center_of_mass
    J0 = J + m * (c @ c * np.eye(3) - np.outer(c, c))  # parallel axis theorem
    np.testing.assert_allclose(body.inertia_origin, J0, atol=1e-10 * J0.max())
    # the reduced basis carries the rigid-body mass matrix of the full mesh
    np.testing.assert_allclose(body.checks["rigid_mass_matrix_reduced"],
                               body.checks["rigid_mass_matrix_full"], atol=1e-9 * m)


def test_save_load_round_trip_is_exact(tmp_path, bar_body):
    _, body = bar_body
    path = body.save(tmp_path / "bar.npz")
    back = flexpipe.load_body(path)
    assert back == body
    for name in ("modes", "M", "K", "D", "frequencies_hz", "inertia", "nodes", "triangles"):
        a, b = getattr(body, name), getattr(back, name)
        assert a.dtype == b.dtype and np.array_equal(a, b)
    assert back.interface("right").shapes.tobytes() == body.interface("right").shapes.tobytes()
    assert back.source_hash == body.source_hash and len(body.source_hash) == 64
    assert not list(tmp_path.glob(".*"))  # no temporary file left behind


def test_load_rejects_bad_files(tmp_path, bar_body):
    _, body = bar_body
    with pytest.raises(InputError, match="not found"):
        flexpipe.load_body(tmp_path / "missing.npz")
    np.savez(tmp_path / "other.npz", a=np.zeros(3))
    with pytest.raises(InputError, match="header"):
        flexpipe.load_body(tmp_path / "other.npz")
    data = dict(np.load(body.save(tmp_path / "b.npz")))
    del data["modes"]
    np.savez(tmp_path / "trunc.npz", **data)
    with pytest.raises(InputError, match="modes"):
        flexpipe.load_body(tmp_path / "trunc.npz")



@pytest.mark.parametrize("content", [b"hello", b"", b"$ written by flexpipe\nGRID*"])
def test_load_says_a_non_zip_file_is_not_an_npz_archive(tmp_path, content):
    path = tmp_path / "text.npz"
    path.write_bytes(content)
    with pytest.raises(InputError) as err:
        flexpipe.load_body(path)
    msg = str(err.value)
    assert "text.npz" in msg and "not a .npz (zip) archive" in msg
    assert "flexpipe reduce" in msg and "pickle" not in msg

def test_invariants_match_exudyn_interface(bar_body):
    from exudyn.FEM import FEMinterface, ObjectFFRFreducedOrderInterface

    fe, body = bar_body
    fem = FEMinterface()
    fem.nodes = {"Position": np.array(fe.nodes)}
    fem.massMatrix = fe.M.tocsr()
    fem.stiffnessMatrix = fe.K.tocsr()
    fem.modeBasis = {"matrix": body.elastic_modes, "type": "HCBmodes"}
    fem.surface = [{"Name": "s", "Trigs": np.array(body.triangles)}]
    ref = ObjectFFRFreducedOrderInterface(fem, roundMassMatrix=0, roundStiffnessMatrix=0)
    for name, ours in body.invariants.as_dict().items():
        theirs = getattr(ref, name)
        np.testing.assert_allclose(ours, theirs, atol=1e-11 * max(1.0, np.abs(theirs).max()),
                                   err_msg=name)
    assert ref.totalMass == pytest.approx(body.mass, rel=1e-12)
    np.testing.assert_allclose(ref.chiU, body.center_of_mass, atol=1e-12)
    np.testing.assert_allclose(ref.inertiaLocal, body.inertia_origin, rtol=1e-11)
    np.testing.assert_allclose(ref.massMatrixReduced, np.eye(body.n_elastic), atol=1e-9)


def test_translational_invariants_function_on_random_data():
    rng = np.random.default_rng(3)
    nodes = rng.standard_normal((5, 3))
    Psi = rng.standard_normal((15, 2))
    m = rng.uniform(1, 2, 5)
    Mt = np.kron(np.diag(m), np.eye(3))
    inv = ffrf_invariants(nodes, translational_block(Mt, 3), Psi)
    # mPhitTPsi = sum_i m_i psi_i ; mXRefTildePsi = sum_i m_i x_i x psi_i (S^T = -S)
    P = Psi.reshape(5, 3, 2)
    np.testing.assert_allclose(inv.mPhitTPsi, np.einsum("i,iaj->aj", m, P))
    np.testing.assert_allclose(inv.mXRefTildePsi,
                               -np.einsum("i,iaj->aj", m, np.cross(nodes[:, :, None], P,
                                                                   axisa=1, axisb=1, axisc=1)))


def test_shell_body_against_solid_body_of_the_same_plate():
    """A 1.0 x 0.5 x 0.01 m plate as quad shells and as a hex8 solid (3 layers)."""
    t = 0.01
    shell_fe = assemble(plate(1.0, 0.5, 20, 10, origin=(0, 0, t / 2)), STEEL, thickness=t)
    solid_fe = assemble(box(1.0, 0.5, t, 20, 10, 3, cell="hexahedron"), STEEL)
    bodies = []
    for fe in (shell_fe, solid_fe):
        itf = [flexpipe.Interface((0.0, 0.25, t / 2), radius=0.051, name="edge")]
        bodies.append(flexpipe.reduce(fe, itf, method="craig-bampton", n_modes=3))
    shell, solid = bodies
    m = 7850.0 * 1.0 * 0.5 * t
    assert shell.mass == pytest.approx(m, rel=1e-12)
    assert solid.mass == pytest.approx(m, rel=1e-12)
    np.testing.assert_allclose(shell.center_of_mass, solid.center_of_mass, atol=1e-12)
    # the exact inertia of the plate; the shell's nodal rotary inertia supplies the
    # thickness term m t^2 / 12 (1e-4 of the in-plane terms here)
    J = m / 12 * np.diag([0.5**2 + t**2, 1.0**2 + t**2, 1.0**2 + 0.5**2])
    np.testing.assert_allclose(solid.inertia, J, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(shell.inertia, J, rtol=2e-4, atol=1e-9)
    # the shell's Exudyn invariants use the translational block only: they must agree
    # with the solid's to the (t / L)^2 level in the rigid-body terms they imply
    Mt = translational_block(shell_fe.M, 6)
    assert float(np.ones(Mt.shape[0]) @ (Mt @ np.ones(Mt.shape[0]))) / 3 == \
        pytest.approx(m, rel=1e-12)
    # first bending and torsion of the edge-mounted plate agree within discretization
    # error (hex8 with 3 layers vs Mindlin quads); measured 0.2% and 3%
    f_sh, f_so = shell.frequencies_hz[6:8], solid.frequencies_hz[6:8]
    np.testing.assert_allclose(f_sh, f_so, rtol=0.05)
