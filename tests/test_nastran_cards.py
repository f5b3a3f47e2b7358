"""Body-deck Nastran cards against closed forms: CPENTA/CPYRAM patch tests and wedges vs
hexes, RBE3 load distribution, CELAS/CBUSH spring-mass, PBARL + SPC + EIGRL run by
``flexpipe modes`` as a SOL 103 deck, coordinate systems, strictness."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.sparse.linalg as spla
from _meshdata import STEEL
from _meshdata import deck as _deck
from _meshdata import write as _write

from flexpipe.errors import MeshError
from flexpipe.fem import assemble, eigenmodes
from flexpipe.mesh import CellBlock, Mesh, MeshWarning, read_mesh
from flexpipe.mesh.generate import box

MAT = "MAT1,1,2.1+11,,0.3,7850."


def _wedges(hexmesh: Mesh) -> Mesh:
    """Split every hex (meshio order) into two wedges along the 0-2 / 4-6 diagonal."""
    c = hexmesh.blocks[0].cells
    w = np.vstack([c[:, [0, 1, 2, 4, 5, 6]], c[:, [0, 2, 3, 4, 6, 7]]])
    return Mesh(hexmesh.points, (CellBlock("wedge", w),))


def _pyramids(hexmesh: Mesh) -> tuple[Mesh, int]:
    """Split every hex into six pyramids around a new centre node."""
    c = hexmesh.blocks[0].cells
    n = hexmesh.n_nodes
    centre = hexmesh.points[c].mean(axis=1)
    k = n + np.arange(len(c))
    faces = [[0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0]]
    p = np.vstack([np.column_stack([c[:, f], k]) for f in faces])
    return Mesh(np.vstack([hexmesh.points, centre]), (CellBlock("pyramid", p),)), len(c)


def _patch(mesh: Mesh):
    """Linear displacement on the boundary: interior nodes must follow exactly."""
    rng = np.random.default_rng(3)
    pts = mesh.points + 0.0
    inner = np.all((pts > 1e-9) & (pts < pts.max(axis=0) - 1e-9), axis=1)
    pts[inner] += rng.uniform(-0.02, 0.02, (inner.sum(), 3))      # distort the interior
    mesh = Mesh(pts, mesh.blocks)
    fe = assemble(mesh, STEEL)
    A = np.array([[1e-3, 2e-4, -3e-4], [5e-4, -2e-3, 1e-4], [2e-4, 3e-4, 1.5e-3]])
    u = (pts @ A.T).ravel()
    K = fe.K.tocsr()
    free = np.repeat(inner, 3)
    x = spla.spsolve(K[free][:, free].tocsc(), -K[free][:, ~free] @ u[~free])
    return np.abs(x - u[free]).max() / np.abs(u).max(), fe


@pytest.mark.parametrize("split", ["wedge", "pyramid"])
def test_pentahedra_and_pyramids_pass_the_patch_test_and_weigh_rho_v(split):
    hexes = box(1.0, 1.0, 1.0, 3, 3, 3, cell="hexahedron")
    mesh = _wedges(hexes) if split == "wedge" else _pyramids(hexes)[0]
    err, fe = _patch(mesh)
    assert err < 1e-10
    assert fe.total_mass == pytest.approx(STEEL.rho * 1.0, rel=1e-12)
    f, _ = eigenmodes(assemble(mesh, STEEL), 7)
    assert np.all(f[:6] < 1e-3 * f[6])                       # six rigid modes, no more


def test_wedge_mesh_converges_to_the_hex_mesh_on_the_same_block():
    diffs = []
    for n in (2, 4):
        hexes = box(1.0, 0.25, 0.25, 4 * n, n, n, cell="hexahedron")
        fh, _ = eigenmodes(assemble(hexes, STEEL), 12)
        fw, _ = eigenmodes(assemble(_wedges(hexes), STEEL), 12)
        diffs.append(np.abs(fw[6:] / fh[6:] - 1).max())
    # linear wedges are stiffer in bending than incompatible-mode hexes; the gap closes
    # with refinement (measured: 34 % -> 11 %)
    assert diffs[1] < 0.5 * diffs[0] and diffs[1] < 0.15


def _spring_deck(extra):
    return _deck("GRID,1,,0.,0.,0.", "GRID,2,,0.,0.,0.", "CONM2,10,2,,2.0,,,,,+",
                 "+,0.5,,0.5,,,0.5", *extra)


def test_celas_and_cbush_spring_mass_frequencies(tmp_path):
    ks = [1.0e4, 2.0e4, 3.0e4, 400.0, 500.0, 600.0]
    p = _write(tmp_path, "bush.bdf", "SOL 103\nCEND\nSPC = 1\n" + _spring_deck([
        "CBUSH,20,21,1,2,,,,0", "PBUSH,21,K," + ",".join(map(str, ks)), "SPC1,1,123456,1"]))
    mesh = read_mesh(p)
    fe = assemble(mesh)
    fixed = np.arange(6)
    f, _ = eigenmodes(fe, 6, fixed_dofs=fixed)
    ref = np.sqrt(np.array(ks) / np.array([2.0, 2, 2, 0.5, 0.5, 0.5])) / (2 * np.pi)
    assert np.allclose(np.sort(f), np.sort(ref), rtol=1e-10)
    # grounded scalar springs (CELAS2, G2 blank) on each component, CELAS1 + PELAS too
    p = _write(tmp_path, "celas.bdf", _spring_deck([
        "CELAS2,31,1.0+4,2,1", "CELAS2,32,2.0+4,2,2", "CELAS1,33,34,2,3", "PELAS,34,3.0+4",
        "CELAS2,35,400.,2,4", "CELAS2,36,500.,2,5", "CELAS2,37,600.,2,6"]))
    with pytest.warns(MeshWarning, match="1 GRID"):
        mesh = read_mesh(p)
    f, _ = eigenmodes(assemble(mesh), 6)
    assert np.allclose(np.sort(f), np.sort(ref), rtol=1e-10)


def test_cbush_between_apart_nodes_is_free_under_rigid_motion(tmp_path):
    p = _write(tmp_path, "b2.bdf", _deck(
        "GRID,1,,0.,0.,0.", "GRID,2,,1.,0.5,0.", "CBUSH,20,21,1,2,0.,0.,1.",
        "PBUSH,21,K,1.+4,2.+4,3.+4,400.,500.,600.,,B,1.,2.,3.,4.,5.,6."))
    fe = assemble(read_mesh(p))
    X = fe.nodes
    for r in np.eye(6):   # rigid translations and rotations about the origin
        u = np.zeros((2, 6))
        u[:, :3] = r[:3] + np.cross(r[3:], X)
        u[:, 3:] = r[3:]
        assert np.abs(fe.K @ u.ravel()).max() < 1e-9 * 3e4
    assert fe.C is not None and fe.C.nnz > 0 and np.abs(fe.C - fe.C.T).max() == 0


def _rbe3_deck(weights=(1.0, 1.0, 1.0, 1.0), ref=(0.0, 0.0)):
    corners = [(1, -1.0, -0.5), (2, 1.0, -0.5), (3, 1.0, 0.5), (4, -1.0, 0.5)]
    cards = [f"GRID,{g},,{x},{y},0." for g, x, y in corners]
    cards.append(f"GRID,9,,{ref[0]},{ref[1]},0.")
    cards += [f"CBUSH,{10 + g},20,{g},,,,,0" for g, _, _ in corners]
    cards.append("PBUSH,20,K,1.+6,1.+6,1.+6,1.,1.,1.")
    groups = ",".join(f"{w},123,{g}" for w, (g, _, _) in zip(weights, corners, strict=True))
    cards.append(f"RBE3,30,,9,123456,{groups}")
    return _deck(*cards)


def _static(fe, node, load):
    f = np.zeros(fe.n_dof)
    f[node * 6: node * 6 + 6] = load
    q = spla.spsolve(fe.Kr.tocsc(), fe.T.T @ f)
    u = (fe.T @ q).reshape(-1, 6)
    return 1.0e6 * u[:, :3]            # forces in the grounded translational springs


def test_rbe3_distributes_loads_as_nastran(tmp_path):
    mesh = read_mesh(_write(tmp_path, "rbe3.bdf", _rbe3_deck()))
    fe = assemble(mesh)
    ref = int(np.flatnonzero(mesh.node_ids == 9)[0])
    F = _static(fe, ref, [0, 0, 100.0, 0, 0, 0])
    assert np.allclose(F[:4, 2], 25.0, rtol=1e-9)          # equal shares of a central force
    # a moment about x: forces proportional to y, sum y F = M, sum F = 0
    y = mesh.points[:4, 1]
    F = _static(fe, ref, [0, 0, 0, 40.0, 0, 0])
    assert np.allclose(F[:4, 2], 40.0 * y / (y @ y), rtol=1e-9)
    # unequal weights, reference at the weighted centroid: forces follow the weights
    w = np.array([1.0, 2.0, 3.0, 4.0])
    x = np.array([-1.0, 1.0, 1.0, -1.0])
    yy = np.array([-0.5, -0.5, 0.5, 0.5])
    mesh = read_mesh(_write(tmp_path, "rbe3w.bdf", _rbe3_deck(w, (w @ x / 10, w @ yy / 10))))
    fe = assemble(mesh)
    ref = int(np.flatnonzero(mesh.node_ids == 9)[0])
    F = _static(fe, ref, [0, 0, 100.0, 0, 0, 0])
    assert np.allclose(F[:4, 2], 100.0 * w / w.sum(), rtol=1e-9)
    # the reference node adds no stiffness: with no load it carries no force anywhere
    assert np.abs(_static(fe, ref, np.zeros(6))).max() == 0


def test_sol103_deck_runs_with_its_spc_set_and_eigrl(tmp_path, capsys):
    """A stubby PBARL ROD cantilever: SPC set and EIGRL from the deck, no options."""
    from test_timoshenko import _exact

    from flexpipe.cli import main

    n, L, r = 40, 0.5, 0.05          # L / d = 5
    grids = [f"GRID,{i + 1},,{L * i / n},0.,0." for i in range(n + 1)]
    bars = [f"CBAR,{100 + i},7,{i + 1},{i + 2},0.,0.,1." for i in range(n)]
    text = ("SOL 103\nCEND\nTITLE = rod\nSUBCASE 1\n  SPC = 5\n  METHOD = 10\nBEGIN BULK\n"
            + "\n".join(grids + bars + ["PBARL,7,1,,ROD", ",0.05", MAT,
                                        "SPC1,5,123456,1", "EIGRL,10,,,6",
                                        "PARAM,AUTOSPC,YES"]) + "\nENDDATA\n")
    p = _write(tmp_path, "rod103.bdf", text)
    assert main(["modes", str(p), "-o", str(tmp_path / "out"), "-q"]) == 0
    out = capsys.readouterr().out
    assert "deck SPC: SPC5" in out
    f = np.loadtxt(tmp_path / "out" / "frequencies.csv", delimiter=",", skiprows=1)[:, 1]
    assert len(f) == 6                                     # EIGRL ND = 6
    nu = 0.3
    k = 6 * (1 + nu) / (7 + 6 * nu)                        # Cowper, solid circle
    A, I = np.pi * r**2, np.pi * r**4 / 4
    bend = _exact(L, 2.1e11, 2.1e11 / 2.6, 7850.0, A, I, k, "cantilever", 2)
    # the bending pairs (two planes) and the first torsion mode, exact Saint-Venant rod
    torsion = np.sqrt(2.1e11 / 2.6 / 7850.0) / (4 * L)
    ref = np.sort(np.concatenate([np.repeat(bend, 2), [torsion]]))
    assert np.allclose(f[:5], ref, rtol=2e-3), (f, ref)


def test_cord2c_positions_and_cd_spring_directions(tmp_path):
    # grid 2 at r = 1, theta = 90 deg in a cylindrical system: basic (0, 1, 0); its CD
    # radial direction is basic y, so a spring on component 1 acts along y
    p = _write(tmp_path, "cyl.bdf", _deck(
        "CORD2C,5,,0.,0.,0.,0.,0.,1.,+", "+,1.,0.,0.",
        "GRID,2,5,1.,90.,0.,5", "CONM2,10,2,,2.0", "CELAS2,31,800.,2,1"))
    mesh = read_mesh(p)
    assert np.allclose(mesh.points[0], [0.0, 1.0, 0.0], atol=1e-15)
    K = assemble(mesh).K.toarray()
    assert K[1, 1] == pytest.approx(800.0) and abs(K[0, 0]) < 1e-9


def test_strictness_duplicates_unknown_and_misspelt_cards(tmp_path):
    tet = ["GRID,1,,0.,0.,0.", "GRID,2,,1.,0.,0.", "GRID,3,,0.,1.,0.", "GRID,4,,0.,0.,1.",
           "CTETRA,1,1,1,2,3,4", "PSOLID,1,1"]
    p = _write(tmp_path, "dupmat.bdf", _deck(*tet, MAT, "MAT1,1,7.+10,,0.3,2700."))
    with pytest.raises(MeshError, match=r"dupmat.bdf, line 9: material id 1 is defined twice: "
                                        r"MAT1 at dupmat.bdf line 8 and MAT1 at dupmat.bdf line 9"):
        read_mesh(p)
    p = _write(tmp_path, "dupprop.bdf", _deck(*tet, MAT, "PSOLID,1,1"))
    with pytest.raises(MeshError, match=r"property id 1 is defined twice"):
        read_mesh(p)
    p = _write(tmp_path, "typo.bdf", _deck(*tet, MAT, "CQAUD4,2,1,1,2,3,4"))
    with pytest.raises(MeshError, match=r"typo.bdf, line 9: CQAUD4 2: unknown card 'CQAUD4': "
                                        r"a misspelt CQUAD4\?"):
        read_mesh(p)
    p = _write(tmp_path, "loads.bdf", _deck(*tet, MAT, "FORCE,1,2,,1.,0.,0.,1.",
                                            "FORCE,1,3,,1.,0.,0.,1.", "WIBBLE,3"))
    with pytest.warns(MeshWarning, match=r"FORCE x2 \(first at line 9\); WIBBLE x1"):
        mesh = read_mesh(p)
    assert mesh.info["dropped"] == {"FORCE": 2, "WIBBLE": 1}
    p = _write(tmp_path, "nu.bdf", _deck(*tet, "MAT1,1,2.1+11,,0.5,7850."))
    with pytest.raises(MeshError, match=r"nu.bdf, line 8: MAT1 1: Poisson's ratio NU = 0.5"):
        read_mesh(p)


def test_abaqus_distributing_coupling_and_springs_match_the_nastran_deck(tmp_path):
    """*COUPLING + *DISTRIBUTING = RBE3 and SPRING1 = grounded CELAS2: same M, K, T."""
    corners = [(1, -1.0, -0.5), (2, 1.0, -0.5), (3, 1.0, 0.5), (4, -1.0, 0.5)]
    bdf = [f"GRID,{g},,{x},{y},0." for g, x, y in corners] + ["GRID,9,,0.,0.,0."]
    bdf += [f"CELAS2,{10 * g + c},{1e5 * c},{g},{c}" for g, _, _ in corners for c in (1, 2, 3)]
    bdf += ["RBE3,30,,9,123456,1.0,123,1,2,3,4", "CONM2,40,9,,5.0"]
    inp = ["*NODE"] + [f"{g}, {x}, {y}, 0." for g, x, y in corners] + ["9, 0., 0., 0."]
    for c in (1, 2, 3):
        inp += [f"*ELEMENT, TYPE=SPRING1, ELSET=S{c}"]
        inp += [f"{10 * g + c}, {g}" for g, _, _ in corners]
        inp += [f"*SPRING, ELSET=S{c}", f"{c}", f"{1e5 * c}"]
    inp += ["*ELEMENT, TYPE=MASS, ELSET=M", "40, 9", "*MASS, ELSET=M", "5.0",
            "*NSET, NSET=C", "1, 2, 3, 4", "*SURFACE, TYPE=NODE, NAME=S", "C, 1.0",
            "*COUPLING, REF NODE=9, SURFACE=S", "*DISTRIBUTING", "1, 6"]
    a = assemble(read_mesh(_write(tmp_path, "c.bdf", _deck(*bdf))))
    b = assemble(read_mesh(_write(tmp_path, "c.inp", "\n".join(inp) + "\n")))
    for X, Y in ((a.K, b.K), (a.M, b.M), (a.T, b.T)):
        assert abs(X - Y).max() <= 1e-12 * abs(X).max()


def test_info_lists_read_converted_and_dropped(tmp_path, capsys):
    from flexpipe.cli import main

    deck = _deck("GRID,1,,0.,0.,0.", "GRID,2,,1.,0.,0.", "GRID,3,,1.,1.,0.", "GRID,4,,0.,1.,0.",
                 "GRID,5,,0.5,0.,0.", "GRID,6,,1.,0.5,0.", "GRID,7,,0.5,1.,0.",
                 "GRID,8,,0.,0.5,0.", "CQUAD8,1,2,1,2,3,4,5,6,+", "+,7,8",
                 "PSHELL,2,1,0.01,1", MAT, "FORCE,1,2,,1.,1.,0.,0.")
    assert main(["info", str(_write(tmp_path, "q8.bdf", deck))]) == 0
    out = capsys.readouterr().out
    assert "converted: CQUAD8 1 -> 4 CQUAD4 (+1 centre grids)" in out
    assert "not used (dropped): FORCE 1" in out and "read: CQUAD8 1" in out


@pytest.mark.parametrize("coupmass", [-1, 1])
def test_coupmass_lumped_rod_chain_matches_the_discrete_closed_form(tmp_path, coupmass):
    """Fixed-free CROD chain, axial only (SPC1 23456): lumped masses m (m/2 at the free
    end) give omega_j = 2 sqrt(k/m) sin(theta_j / 2), theta_j = (2j - 1) pi / (2n)."""
    from flexpipe.cli import main

    n, L, A = 10, 1.0, 1e-4
    h = L / n
    grids = [f"GRID,{i + 1},,{h * i},0.,0." for i in range(n + 1)]
    rods = [f"CROD,{100 + i},5,{i + 1},{i + 2}" for i in range(n)]
    text = ("SOL 103\nCEND\nSPC = 1\nMETHOD = 2\nBEGIN BULK\n" + "\n".join(
        grids + rods + ["PROD,5,1,1.-4,1.-9", MAT, "SPC1,1,123456,1",
                        f"SPC1,1,23456,2,THRU,{n + 1}", "EIGRL,2,,,4",
                        f"PARAM,COUPMASS,{coupmass}"]) + "\nENDDATA\n")
    p = _write(tmp_path, "chain.bdf", text)
    assert main(["modes", str(p), "-o", str(tmp_path / "o"), "-q"]) == 0
    f = np.loadtxt(tmp_path / "o" / "frequencies.csv", delimiter=",", skiprows=1)[:, 1]
    k, m = 2.1e11 * A / h, 7850.0 * A * h
    theta = (2 * np.arange(1, 5) - 1) * np.pi / (2 * n)
    lumped = 2 * np.sqrt(k / m) * np.sin(theta / 2) / (2 * np.pi)
    if coupmass < 0:
        assert np.allclose(f, lumped, rtol=1e-10)
    else:   # consistent mass: above the lumped values (and above the exact rod)
        assert (f > lumped * 1.0001).all()


def test_spc_on_a_cylindrical_cd_component_is_a_directional_constraint(tmp_path):
    """Radial SPC (component 1 of a CORD2C displacement system) at theta = 30 deg: the
    mass moves tangentially with stiffness K1 sin^2 + K2 cos^2 (and along z with K3)."""
    from flexpipe.cli import main

    K1, K2, K3, m = 1.0e4, 4.0e4, 9.0e4, 2.0
    text = ("SOL 103\nCEND\nSPC = 7\nBEGIN BULK\n" + "\n".join([
        "CORD2C,5,,0.,0.,0.,0.,0.,1.,+", "+,1.,0.,0.",
        "GRID,1,5,1.,30.,0.,5", "CONM2,10,1,,2.0",
        "CBUSH,20,21,1,,,,,0", f"PBUSH,21,K,{K1},{K2},{K3},1.,1.,1.",
        "SPC1,7,1456,1", "EIGRL,1,,,2"]) + "\nENDDATA\n")
    p = _write(tmp_path, "radial.bdf", text)
    assert main(["modes", str(p), "-o", str(tmp_path / "o"), "-q"]) == 0
    f = np.loadtxt(tmp_path / "o" / "frequencies.csv", delimiter=",", skiprows=1)[:, 1]
    s, c = np.sin(np.radians(30)), np.cos(np.radians(30))
    ref = np.sort(np.sqrt(np.array([K1 * s * s + K2 * c * c, K3]) / m) / (2 * np.pi))
    assert np.allclose(f, ref, rtol=1e-10), (f, ref)


def test_abaqus_bushing_connector_equals_cbush(tmp_path):
    ks, bs = [1e5, 2e5, 3e5, 40.0, 50.0, 60.0], [1.0, 2.0, 3.0, 0.4, 0.5, 0.6]
    bdf = _deck("GRID,1,,0.,0.,0.", "GRID,2,,0.,0.,0.", "CBUSH,5,6,1,2,,,,0",
                "PBUSH,6,K," + ",".join(map(str, ks)) + ",,B," + ",".join(map(str, bs)),
                "CONM2,7,2,,2.0")
    inp = ["*NODE", "1, 0., 0., 0.", "2, 0., 0., 0.", "*ELEMENT, TYPE=CONN3D2, ELSET=C",
           "5, 1, 2", "*CONNECTOR SECTION, ELSET=C, BEHAVIOR=B1", "BUSHING,",
           "*ELEMENT, TYPE=MASS, ELSET=M", "7, 2", "*MASS, ELSET=M", "2.0",
           "*CONNECTOR BEHAVIOR, NAME=B1"]
    for c in range(6):
        inp += [f"*CONNECTOR ELASTICITY, COMPONENT={c + 1}", f"{ks[c]},",
                f"*CONNECTOR DAMPING, COMPONENT={c + 1}", f"{bs[c]},"]
    a = assemble(read_mesh(_write(tmp_path, "b.bdf", bdf)))
    b = assemble(read_mesh(_write(tmp_path, "b.inp", "\n".join(inp) + "\n")))
    for X, Y in ((a.K, b.K), (a.M, b.M), (a.C, b.C), (a.T, b.T)):
        assert abs(X - Y).max() <= 1e-12 * abs(X).max()
    assert np.allclose(b.K.diagonal()[:6], ks) and np.allclose(b.C.diagonal()[:6], bs)


def test_massless_deck_is_a_clear_error(tmp_path):
    from flexpipe.errors import ModelError

    p = _write(tmp_path, "norho.bdf", _deck(
        "GRID,1,,0.,0.,0.", "GRID,2,,1.,0.,0.", "GRID,3,,0.,1.,0.", "GRID,4,,0.,0.,1.",
        "CTETRA,1,1,1,2,3,4", "PSOLID,1,1", "MAT1,1,2.1+11,,0.3"))
    with pytest.warns(MeshWarning, match="MAT1 1 has no RHO"):
        fe = assemble(read_mesh(p))
    with pytest.raises(ModelError, match=r"norho.bdf: the model has no mass"):
        eigenmodes(fe, 3)


def _free_freqs(mesh, n=14):
    return eigenmodes(assemble(mesh), n)[0][6:]


def test_zoffs_and_beam_offsets_equal_rigid_links(tmp_path):
    """A stiffened strip: CBAR along the node line, skin with ZOFFS = d (or the skin at the
    nodes and the bar with WA = WB = (0, 0, -d)) vibrates exactly as the unoffset parts
    joined by RBE2 rigid links across the distance d (an independent formulation)."""
    d = 0.02
    n = 10
    base = [f"GRID,{j * 20 + i + 1},,{0.1 * i},{0.05 * j},0." for j in range(2)
            for i in range(n)]
    up = [f"GRID,{j * 20 + i + 101},,{0.1 * i},{0.05 * j},{d}" for j in range(2)
          for i in range(n)]
    props = ["PSHELL,1,1,0.003,1", "PBARL,2,1,,BAR", ",0.01,0.02", MAT]

    def quads(off, first=1):
        return [f"CQUAD4,{i + 1},1,{i + first},{i + first + 1},{i + first + 21},"
                f"{i + first + 20}" + (f",,{off}" if off else "") for i in range(n - 1)]

    def bars(first=1, w=None):
        tail = f",,+\n+,,,0.,0.,{w},0.,0.,{w}" if w else ""
        return "\n".join(f"CBAR,{100 + i},2,{i + first},{i + first + 1},0.,1.,0.{tail}"
                         for i in range(n - 1)).split("\n")

    links = [f"RBE2,{300 + k},{g},123456,{g + 100}" for k, g in enumerate(
        [j * 20 + i + 1 for j in range(2) for i in range(n)])]
    skin_off = read_mesh(_write(tmp_path, "a.bdf", _deck(*base, *quads(d), *bars(), *props)))
    skin_rbe = read_mesh(_write(tmp_path, "b.bdf", _deck(*base, *up, *quads(None, 101),
                                                         *bars(), *links, *props)))
    f_off, f_rbe = _free_freqs(skin_off), _free_freqs(skin_rbe)
    assert np.allclose(f_off, f_rbe, rtol=1e-8), (f_off, f_rbe)
    bar_off = read_mesh(_write(tmp_path, "c.bdf", _deck(*up, *quads(None, 101),
                                                        *bars(101, -d), *props)))
    assert np.allclose(_free_freqs(bar_off), f_rbe, rtol=1e-8)
    # the offsets matter: without them the strip is far softer in bending
    plain = read_mesh(_write(tmp_path, "d.bdf", _deck(*base, *quads(None), *bars(), *props)))
    assert _free_freqs(plain)[0] < 0.9 * f_rbe[0]


def test_surface_of_wedges_and_pyramids_is_the_block_boundary():
    from flexpipe.flexbody.surface import surface_triangles

    hexes = box(1.0, 1.0, 1.0, 2, 2, 2, cell="hexahedron")
    for mesh in (_wedges(hexes), _pyramids(hexes)[0]):
        t = surface_triangles(mesh)
        X = mesh.points
        nrm = np.cross(X[t[:, 1]] - X[t[:, 0]], X[t[:, 2]] - X[t[:, 0]])
        assert np.isclose(0.5 * np.linalg.norm(nrm, axis=1).sum(), 6.0)   # cube area
        assert (np.einsum("ij,ij->i", nrm, X[t].mean(axis=1) - 0.5) > 0).all()  # outward


def test_second_order_solids_become_linear_with_a_warning(tmp_path):
    corners = ["GRID,1,,0.,0.,0.", "GRID,2,,1.,0.,0.", "GRID,3,,1.,1.,0.", "GRID,4,,0.,1.,0.",
               "GRID,5,,0.,0.,1.", "GRID,6,,1.,0.,1.", "GRID,7,,1.,1.,1.", "GRID,8,,0.,1.,1."]
    mids = [f"GRID,{9 + k},,{x},{y},{z}" for k, (x, y, z) in enumerate(
        [(.5, 0, 0), (1, .5, 0), (.5, 1, 0), (0, .5, 0), (0, 0, .5), (1, 0, .5), (1, 1, .5),
         (0, 1, .5), (.5, 0, 1), (1, .5, 1), (.5, 1, 1), (0, .5, 1)])]
    hex20 = ["CHEXA,1,1,1,2,3,4,5,6,+", "+,7,8,9,10,11,12,13,14,+", "+,15,16,17,18,19,20"]
    with pytest.warns(MeshWarning, match=r"second-order solids converted .*CHEXA x1"):
        a = read_mesh(_write(tmp_path, "h20.bdf", _deck(*corners, *mids, *hex20,
                                                        "PSOLID,1,1", MAT)))
    assert a.info["converted"]["CHEXA"].startswith("1 second-order")
    b = read_mesh(_write(tmp_path, "h8.bdf", _deck(*corners, "CHEXA,1,1,1,2,3,4,5,6,+",
                                                   "+,7,8", "PSOLID,1,1", MAT)))
    assert abs(assemble(a).K - assemble(b).K).max() == 0


def test_set_name_comment_is_reread_when_the_same_deck_is_edited(tmp_path):
    """The ``$ SET name`` comment before a SET1 names the node set; reading the same path
    again after an edit gives the new name (no stale text of the earlier read)."""
    quad = ["GRID,1,,0.,0.,0.", "GRID,2,,1.,0.,0.", "GRID,3,,1.,1.,0.", "GRID,4,,0.,1.,0.",
            "CQUAD4,1,1,1,2,3,4", "PSHELL,1,1,0.01,1", MAT]
    for name in ("front", "rear"):
        mesh = read_mesh(_write(tmp_path, "set.bdf", _deck(*quad, f"$ SET {name}",
                                                           "SET1,3,2,3")))
        assert {"SET3", name} <= set(mesh.node_sets)
        assert {"front", "rear"} - {name} - set(mesh.node_sets)   # the other name is gone
        assert mesh.node_ids[mesh.node_sets[name]].tolist() == [2, 3]
