"""flexpipe.reduce on a solid bar: Ritz bounds against the full model with its spiders,
exact Craig-Bampton statics, residual flexibility vs truncation, and bad input.

The full-model references are built here independently of flexpipe.reduction: the RBE2
spiders are written out as a constraint matrix from the node coordinates."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla

import flexpipe
from flexpipe.errors import InputError, ModelError
from flexpipe.fem import Material, assemble
from flexpipe.mesh.generate import box
from flexpipe.mesh.mesh import CellBlock, Mesh

STEEL = Material(210e9, 0.3, 7850.0)
L, B, H = 1.0, 0.2, 0.1
PA, PB = (0.0, B / 2, H / 2), (L, B / 2, H / 2)
R = 0.07


@pytest.fixture(scope="module")
def bar():
    return assemble(box(L, B, H, 16, 3, 2), STEEL)


def interfaces():
    return [flexpipe.Interface(PA, radius=R, name="a"), flexpipe.Interface(PB, radius=R, name="b")]


def spider_model(fe):
    """Full model with both spiders as dense matrices on [free node DOF, hp_a(6), hp_b(6)]."""
    n = fe.n_dof
    tied = {}
    for j, p in enumerate((PA, PB)):
        nodes = np.flatnonzero(np.linalg.norm(fe.nodes - p, axis=1) <= R + 1e-12)
        tied[j] = nodes
    tied_dofs = np.concatenate([3 * tied[j][:, None] + np.arange(3) for j in (0, 1)]).ravel()
    free = np.setdiff1d(np.arange(n), tied_dofs)
    nf = free.size
    T = np.zeros((n, nf + 12))
    T[free, np.arange(nf)] = 1.0
    for j, p in enumerate((PA, PB)):
        for i in tied[j]:
            d = fe.nodes[i] - p
            for c in range(3):
                T[3 * i + c, nf + 6 * j + c] = 1.0
                e = np.zeros(3)
                e[c] = 1.0
                # u_c = (theta x d)_c = theta . (d x e_c)
                T[3 * i + c, nf + 6 * j + 3: nf + 6 * j + 6] = np.cross(d, e)
    K = T.T @ fe.K.toarray() @ T
    M = T.T @ fe.M.toarray() @ T
    return K, M, nf


@pytest.fixture(scope="module")
def full(bar):
    K, M, nf = spider_model(bar)
    lam = sla.eigh(K, M, eigvals_only=True, subset_by_index=[0, 39])
    return K, M, nf, np.sqrt(np.clip(lam, 0, None)) / (2 * np.pi)


@pytest.mark.parametrize("method", ["craig-bampton", "residual-flexibility",
                                    "modal-truncation"])
def test_ritz_upper_bounds_and_accuracy_below_f_max(bar, full, method):
    _, _, _, f_full = full
    f_max = 1.2 * f_full[9]  # a band holding the first four elastic modes
    body = flexpipe.reduce(bar, interfaces(), method=method, f_max=f_max)
    f = body.frequencies_hz
    assert body.n_rigid == 6 and np.all(f[:6] < 1e-3 * f_full[6])
    k = min(len(f), len(f_full))
    assert np.all(f[6:k] >= f_full[6:k] * (1 - 1e-9))  # Rayleigh-Ritz from above
    below = f_full[6:k] <= f_max
    assert below.sum() >= 4
    np.testing.assert_allclose(f[6:k][below], f_full[6:k][below], rtol=5e-3)


def test_more_modes_approach_full_model_from_above(bar, full):
    _, _, _, f_full = full
    errors = []
    for n in (2, 6, 12):
        f = flexpipe.reduce(bar, interfaces(), n_modes=n).frequencies_hz
        assert np.all(f[6:] >= f_full[6:len(f)] * (1 - 1e-9))
        errors.append(f[6] / f_full[6] - 1)
    assert errors[0] > errors[1] > errors[2] >= 0


def _static(fe, body, K, nf, F_b):
    """Hardpoint a clamped, force/moment F_b at hardpoint b: full vs reduced."""
    keep = np.r_[np.arange(nf), nf + 6 + np.arange(6)]
    f = np.zeros(K.shape[0])
    f[nf + 6:] = F_b
    x = np.linalg.solve(K[np.ix_(keep, keep)], f[keep])
    u_full = x[-6:]
    Sa, Sb = body.interface("a").shapes, body.interface("b").shapes
    m = body.n_modes
    # reduced: min 1/2 q^T K q - q^T Sb^T F  s.t.  Sa q = 0
    A = np.block([[body.K, Sa.T], [Sa, np.zeros((6, 6))]])
    q = np.linalg.solve(A, np.r_[Sb.T @ F_b, np.zeros(6)])[:m]
    return u_full, Sb @ q


def test_craig_bampton_static_deflection_is_exact(bar, full):
    K, _, nf, _ = full
    body = flexpipe.reduce(bar, interfaces(), method="craig-bampton", n_modes=4)
    F_b = np.array([30.0, -200.0, 1000.0, 15.0, -40.0, 25.0])
    u_full, u_red = _static(bar, body, K, nf, F_b)
    np.testing.assert_allclose(u_red, u_full, rtol=0, atol=1e-9 * np.abs(u_full).max())


def test_residual_flexibility_beats_truncation_at_same_size(bar, full):
    K, _, nf, _ = full
    F_b = np.array([0.0, 0.0, 1000.0, 0.0, 0.0, 0.0])
    rf = flexpipe.reduce(bar, interfaces(), method="residual-flexibility", n_modes=2)
    mt = flexpipe.reduce(bar, interfaces(), method="modal-truncation", n_modes=rf.n_elastic)
    assert rf.n_modes == mt.n_modes == 6 + 2 + 12
    e = {}
    for name, body in (("rf", rf), ("mt", mt)):
        u_full, u_red = _static(bar, body, K, nf, F_b)
        e[name] = np.linalg.norm(u_red - u_full) / np.linalg.norm(u_full)
    # measured: residual flexibility 0 (the interface loads are in its span), truncation
    # ~1e-2 with 14 free-free modes
    assert e["rf"] < 1e-8
    assert e["mt"] > 100 * max(e["rf"], 1e-12)


def test_damping_defaults_follow_adams(bar):
    body = flexpipe.reduce(bar, interfaces(), n_modes=2)
    z = body.damping_ratio
    f = body.frequencies_hz
    assert np.all(z[:6] == 0)
    assert np.all(z[6:][f[6:] < 100] == 0.01)
    assert np.all(z[6:][(f[6:] >= 100) & (f[6:] < 1000)] == 0.10)
    assert np.all(z[6:][f[6:] >= 1000] == 1.0)
    np.testing.assert_allclose(np.diag(body.D), 2 * z * 2 * np.pi * f)
    np.testing.assert_array_equal(body.M, np.eye(body.n_modes))


def test_interface_selection_by_node_set_and_nodes(bar):
    sets = bar.mesh.node_sets
    a = flexpipe.Interface((0.0, B / 2, H / 2), node_set="xmin", name="a")
    b = flexpipe.Interface(PB, nodes=sets["xmax"], name="b")
    body = flexpipe.reduce(bar, [a, b], n_modes=2)
    np.testing.assert_array_equal(body.interface("a").nodes, np.sort(sets["xmin"]))
    # the spider moves the tied nodes rigidly with the hardpoint in every mode
    itf = body.interface("b")
    d = bar.nodes[itf.nodes] - itf.point
    u = itf.shapes[:3][None] + np.cross(itf.shapes[3:].T[None], d[:, None]).transpose(0, 2, 1)
    np.testing.assert_allclose(body.modes[itf.nodes], u, atol=1e-12 * np.abs(u).max())


def test_bad_input_names_the_interface(bar):
    with pytest.raises(InputError, match="'far'.*no mesh node within radius"):
        flexpipe.reduce(bar, [flexpipe.Interface((5.0, 0, 0), radius=0.01, name="far")],
                        n_modes=2)
    with pytest.raises(InputError, match="'a' and 'b' overlap"):
        flexpipe.reduce(bar, [flexpipe.Interface(PA, radius=0.6, name="a"),
                              flexpipe.Interface(PB, radius=0.6, name="b")], n_modes=2)
    with pytest.raises(InputError, match="'b'.*node set 'nope'"):
        flexpipe.reduce(bar, [flexpipe.Interface(PB, node_set="nope", name="b")], n_modes=2)
    with pytest.raises(InputError, match="'p'.*no rotational DOF"):
        flexpipe.reduce(bar, [flexpipe.Interface(tuple(bar.nodes[0]), name="p")], n_modes=2)
    with pytest.raises(InputError, match="modes requested.*only [0-9]+ interior DOF"):
        flexpipe.reduce(bar, interfaces(), n_modes=10**6)
    with pytest.raises(InputError, match="method"):
        flexpipe.reduce(bar, interfaces(), method="guyan", n_modes=2)
    edge = np.flatnonzero((bar.nodes[:, 0] == 0) & (bar.nodes[:, 2] == 0))  # collinear
    with pytest.raises(InputError, match="'e'.*line"):
        flexpipe.reduce(bar, [flexpipe.Interface(PA, nodes=edge, name="e")], n_modes=2)


def test_mechanism_is_reported():
    """Two blocks sharing a single node: a ball joint, i.e. a mechanism."""
    m1 = box(0.2, 0.1, 0.1, 2, 1, 1)
    pts2 = m1.points + np.array([0.2, 0.1, 0.1])
    shared = int(np.flatnonzero(np.all(np.isclose(m1.points, [0.2, 0.1, 0.1]), axis=1))[0])
    n1 = len(m1.points)
    keep2 = np.flatnonzero(~np.all(np.isclose(pts2, [0.2, 0.1, 0.1]), axis=1))
    own = np.flatnonzero(np.all(np.isclose(m1.points, [0.0, 0.0, 0.0]), axis=1))[0]
    idx = np.full(len(pts2), -1)
    idx[keep2] = n1 + np.arange(len(keep2))
    idx[own] = shared
    cells = np.vstack([m1.blocks[0].cells, idx[m1.blocks[0].cells]])
    mesh = Mesh(points=np.vstack([m1.points, pts2[keep2]]), blocks=(CellBlock("tetra", cells),))
    fe = assemble(mesh, STEEL)
    itf = [flexpipe.Interface((0.0, 0.05, 0.05), radius=0.08, name="left")]
    with pytest.raises(ModelError, match="9 zero-energy modes where a free body has 6"):
        flexpipe.reduce(fe, itf, n_modes=2)


def test_shell_node_is_its_own_interface():
    """A 6-DOF shell node at the hardpoint is the interface: no spider, no new DOF."""
    from flexpipe.mesh.generate import plate

    fe = assemble(plate(0.6, 0.3, 6, 3), STEEL, thickness=0.003)
    corner = int(np.flatnonzero(np.all(np.isclose(fe.nodes, [0.6, 0.3, 0.0]), axis=1))[0])
    itfs = [flexpipe.Interface((0.0, 0.15, 0.0), radius=0.051, name="edge"),
            flexpipe.Interface((0.6, 0.3, 0.0), name="corner")]
    body = flexpipe.reduce(fe, itfs, n_modes=3)
    c = body.interface("corner")
    assert c.kind == "node" and c.nodes.tolist() == [corner]
    np.testing.assert_array_equal(c.shapes[:3], body.modes[corner])
    assert body.n_modes == 12 + 3


def test_reduction_logs_each_stage_as_it_ends(bar):
    """``reduce(..., log=)`` reports every stage with its seconds and the time so far
    (the progress of a reduction that takes minutes), in the order they run; the body is
    the one reduced without a log."""
    lines = []
    body = flexpipe.reduce(bar, interfaces(), n_modes=6, log=lines.append)
    quiet = flexpipe.reduce(bar, interfaces(), n_modes=6)
    np.testing.assert_allclose(body.frequencies_hz, quiet.frequencies_hz, rtol=1e-10)
    names = [ln.split(":")[0] for ln in lines]
    expected = ["interfaces resolved", "K_ii factorized", "static (constraint) modes",
                "fixed-interface normal modes", "basis complete",
                "modes orthonormalized and expanded"]
    assert [n for n in names if n in expected] == expected
    so_far = [float(ln.split("(")[-1].split(" s so far")[0]) for ln in lines]
    assert all(b >= a for a, b in zip(so_far, so_far[1:], strict=False))
