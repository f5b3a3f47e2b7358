"""Abaqus decks that run as the solver would: ``*SHELL SECTION, OFFSET=`` (= Nastran ZOFFS),
``*BOUNDARY`` and ``*FREQUENCY`` in the model data and in the steps (= the SPC set, DOF set
``SPC1``, and the EIGRL of a SOL 103 deck), Abaqus/CAE part/assembly decks with a reference
point numbered like a part node and an assembly set named like a part set, ``*SHELL GENERAL
SECTION``.

References: the closed-form simply supported plate (a = 0.5 m, t = 5 mm, steel:
f11 = 98.343 Hz, m = 9.8125 kg), the same models written as Nastran decks (which flexpipe
reads right, ZOFFS included), hand masses and centres of mass."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from _meshdata import write as _write

from flexpipe import cli
from flexpipe.errors import MeshError
from flexpipe.fem import assemble, eigenmodes
from flexpipe.fem.structural_mass import structural_mass
from flexpipe.mesh import MeshWarning, read_mesh

A, N, T = 0.5, 20, 0.005            # SS plate: side, elements per side, thickness
F11 = np.pi / 2 * 2 / A**2 * np.sqrt(2.1e11 * T**3 / (12 * (1 - 0.3**2)) / (7850 * T))
MAT = ["*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1E11, 0.3", "*DENSITY", "7850."]


# ---------------------------------------------------------------- decks
def _plate_nodes(scale=1.0):
    return {1 + i + (N + 1) * j: (A * i / N * scale, A * j / N * scale, 0.0)
            for j in range(N + 1) for i in range(N + 1)}


def _plate_quads():
    out = []
    for j in range(N):
        for i in range(N):
            a = 1 + i + (N + 1) * j
            out.append((1 + i + N * j, a, a + 1, a + N + 2, a + N + 1))
    return out


def _edge():
    return [1 + i + (N + 1) * j for j in range(N + 1) for i in range(N + 1)
            if i in (0, N) or j in (0, N)]


def _chunks(ids, k=16):
    return [", ".join(map(str, ids[i:i + k])) for i in range(0, len(ids), k)]


def _abaqus_plate(after, section="*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL"):
    """The SS plate as a flat Abaqus deck; ``after``: lines after the material."""
    lines = ["*HEADING", "SS plate", "*NODE"]
    lines += [f"{k}, {x!r}, {y!r}, {z!r}" for k, (x, y, z) in _plate_nodes().items()]
    lines += ["*ELEMENT, TYPE=S4R, ELSET=PLATE"] + [", ".join(map(str, q))
                                                   for q in _plate_quads()]
    lines += ["*NSET, NSET=EDGE"] + _chunks(_edge()) + [section, f"{T}, 5"] + MAT + after
    return "\n".join(lines) + "\n"


def _nastran_plate(extra=(), pshell=f"PSHELL,1,1,{T},1"):
    """The SS plate as a Nastran SOL 103 deck (SPC 123 on the edges, consistent mass)."""
    lines = ["SOL 103", "CEND", "SPC = 1", "METHOD = 1", "BEGIN BULK", "PARAM,COUPMASS,1"]
    lines += [f"GRID,{k},,{x!r},{y!r},{z!r}" for k, (x, y, z) in _plate_nodes().items()]
    lines += [f"CQUAD4,{q[0]},1,{q[1]},{q[2]},{q[3]},{q[4]}" for q in _plate_quads()]
    lines += [pshell, "MAT1,1,2.1E11,,0.3,7850.", *extra, "EIGRL,1,,,8", "ENDDATA"]
    lines[-2:-2] = [f"SPC1,1,123,{g}" for g in _edge()]
    return "\n".join(lines) + "\n"


def _cae_plate(boundary="Set-1, PINNED", m_rp=5e-4):
    """The SS plate as Abaqus/CAE writes it in mm-t-s: part Plate (with a set Set-1 of all
    its nodes), instance Plate-1, an assembly reference point numbered 1 (like the part's
    node 1) carrying a MASS element numbered 1 (like the part's element 1), coupled
    kinematically to the plate centre, and the boundary condition in the step on the
    *assembly* set Set-1 (the edges)."""
    lines = ["*Heading", "** Job name: a_cae Model name: Model-1",
             "*Preprint, echo=NO, model=NO, history=NO, contact=NO", "** PARTS",
             "*Part, name=Plate", "*Node"]
    lines += [f"{k:7d}, {x:12.6g}, {y:12.6g}, {z:12.6g}"
              for k, (x, y, z) in _plate_nodes(1000.0).items()]
    lines += ["*Element, type=S4R"] + [", ".join(map(str, q)) for q in _plate_quads()]
    lines += ["*Nset, nset=Set-1, generate", "1, 441, 1", "*Elset, elset=Set-1, generate",
              "1, 400, 1", "** Section: Section-1",
              "*Shell Section, elset=Set-1, material=Steel", "5., 5", "*End Part",
              "** ASSEMBLY", "*Assembly, name=Assembly",
              "*Instance, name=Plate-1, part=Plate", "*End Instance",
              "*Node", "      1,         250.,         250.,          50.",
              "*Nset, nset=RP-1, internal", "1,",
              "*Nset, nset=Set-1, instance=Plate-1"] + _chunks(_edge())
    lines += ["*Nset, nset=_PickedSet5, internal, instance=Plate-1", "221,",
              "*Element, type=MASS, elset=Set-2_Inertia-1_", "1, 1",
              "*Mass, elset=Set-2_Inertia-1_", f"{m_rp},",
              "*Surface, type=NODE, name=m_Surf-1, internal", "_PickedSet5, 1.",
              "** Constraint: Constraint-1",
              "*Coupling, constraint name=Constraint-1, ref node=RP-1, surface=m_Surf-1",
              "*Kinematic", "*End Assembly", "** MATERIALS", "*Material, name=Steel",
              "*Density", "7.85e-09,", "*Elastic", "210000., 0.3", "** STEP: modal",
              "*Step, name=modal, nlgeom=NO, perturbation",
              "*Frequency, eigensolver=Lanczos, sim, acoustic coupling=on, "
              "normalization=displacement", "8, , , , ,", "** BOUNDARY CONDITIONS",
              "** Name: BC-1 Type: Symmetry/Antisymmetry/Encastre", "*Boundary", boundary,
              "** OUTPUT REQUESTS", "*Restart, write, frequency=0",
              "*Output, field, variable=PRESELECT", "*End Step"]
    return "\n".join(lines) + "\n"


LX, B, TA = 0.3, 0.1, 0.01           # L-angle: length, leg width, thickness


def _angle_nodes(nx=12, nb=4):
    """Leg 1 in the plane z = 0 (normal +z), leg 2 in y = 0 (normal +y), one shared edge."""
    out, k = {}, 0
    for j in range(2 * nb + 1):
        s = -B + B * j / nb
        for i in range(nx + 1):
            k += 1
            out[k] = (LX * i / nx, s, 0.0) if s >= 0 else (LX * i / nx, 0.0, -s)
    return out


def _angle_quads(nx=12, nb=4):
    out = []
    for j in range(2 * nb):
        for i in range(nx):
            a = 1 + i + (nx + 1) * j
            out.append((len(out) + 1, a, a + 1, a + nx + 2, a + nx + 1))
    return out


def _abaqus_angle(params=""):
    lines = ["*HEADING", "L angle", "*NODE"]
    lines += [f"{k}, {x!r}, {y!r}, {z!r}" for k, (x, y, z) in _angle_nodes().items()]
    lines += ["*ELEMENT, TYPE=S4R, ELSET=ALL"] + [", ".join(map(str, q))
                                                 for q in _angle_quads()]
    lines += [f"*SHELL SECTION, ELSET=ALL, MATERIAL=STEEL{params}", f"{TA}, 5"] + MAT
    return "\n".join(lines) + "\n"


def _nastran_angle(zoffs=""):
    lines = ["BEGIN BULK"]
    lines += [f"GRID,{k},,{x!r},{y!r},{z!r}" for k, (x, y, z) in _angle_nodes().items()]
    lines += [f"CQUAD4,{q[0]},1,{q[1]},{q[2]},{q[3]},{q[4]},,{zoffs}" for q in _angle_quads()]
    lines += [f"PSHELL,1,1,{TA},1", "MAT1,1,2.1E11,,0.3,7850.", "ENDDATA"]
    return "\n".join(lines) + "\n"


def _read(tmp_path, name, text, **kw):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        return read_mesh(_write(tmp_path, name, text), **kw)


def _free_modes(mesh, n=10):
    return eigenmodes(assemble(mesh), n)[0][6:]


def _cli_modes(tmp_path, path, *args):
    out = tmp_path / f"out_{path.stem}"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        assert cli.main(["modes", str(path), "-o", str(out), "-q", *args]) == 0
    return np.loadtxt(out / "frequencies.csv", delimiter=",", skiprows=1, ndmin=2)[:, 1]


# ---------------------------------------------------------------- finding 1: OFFSET
@pytest.mark.parametrize("offset, zoffs", [("SPOS", -TA / 2), ("SNEG", TA / 2),
                                           ("0.25", -0.25 * TA), ("-0.3", 0.3 * TA)])
def test_shell_offset_gives_the_frequencies_of_the_nastran_zoffs(tmp_path, offset, zoffs):
    """OFFSET is the mid-surface -> nodes distance (fraction of t along the normal): the
    Nastran ZOFFS (nodes -> mid-surface) is -OFFSET t.  Free-free L-angle, modes 7-10."""
    f_abq = _free_modes(_read(tmp_path, "a.inp", _abaqus_angle(f", OFFSET={offset}")))
    f_nas = _free_modes(_read(tmp_path, "n.bdf", _nastran_angle(repr(zoffs))))
    f_none = _free_modes(_read(tmp_path, "n0.bdf", _nastran_angle()))
    np.testing.assert_allclose(f_abq, f_nas, rtol=1e-9)
    assert np.max(np.abs(f_abq / f_none - 1)) > 0.02      # the offset matters here


@pytest.mark.parametrize("offset, side", [("SPOS", -1.0), ("SNEG", 1.0)])
def test_shell_offset_moves_the_mass_centre_to_the_hand_value(tmp_path, offset, side):
    """SPOS: nodes on the positive face, the material t/2 below them along each leg's
    normal (+z for leg 1, +y for leg 2); each leg weighs rho t L b."""
    mesh = _read(tmp_path, "a.inp", _abaqus_angle(f", OFFSET={offset}"))
    _, total, com, _ = structural_mass(mesh)
    assert total == pytest.approx(2 * 7850 * TA * LX * B, rel=1e-12)
    c = (B / 2 + side * TA / 2) / 2          # mean of the two legs' in-plane and offset
    np.testing.assert_allclose(com, [LX / 2, c, c], rtol=1e-12, atol=1e-15)


@pytest.mark.parametrize("params, named", [
    (", NODAL THICKNESS", "parameter NODAL THICKNESS"),
    (", SHELL THICKNESS=TDIST", "parameter SHELL THICKNESS"),
    (", OFFSET=ODIST", "OFFSET=ODIST"),
    (", STACK DIRECTION=3", "parameter STACK DIRECTION")])
def test_section_parameters_that_change_the_section_are_refused(tmp_path, params, named):
    p = _write(tmp_path, "bad.inp", _abaqus_angle(params))
    line = _abaqus_angle(params).splitlines().index(
        f"*SHELL SECTION, ELSET=ALL, MATERIAL=STEEL{params}") + 1
    with pytest.raises(MeshError, match=rf"bad.inp, line {line}: \*SHELL SECTION.*{named}.*"
                                        "valid: "):
        read_mesh(p)


def test_section_parameters_that_keep_m_and_k_are_accepted(tmp_path):
    plain = assemble(_read(tmp_path, "a.inp", _abaqus_angle()))
    more = assemble(_read(tmp_path, "b.inp", _abaqus_angle(
        ", SECTION INTEGRATION=GAUSS, CONTROLS=EC-1, POISSON=0.5, TEMPERATURE=GRADIENTS")))
    assert abs(plain.K - more.K).max() == 0 and abs(plain.M - more.M).max() == 0


def test_section_density_is_a_mass_per_area_as_pshell_nsm(tmp_path):
    """DENSITY=2 kg/m^2 on the 0.25 m^2 plate adds 0.5 kg (hand), as PSHELL NSM = 2."""
    mesh = _read(tmp_path, "a.inp", _abaqus_plate(
        [], "*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL, DENSITY=2."))
    assert structural_mass(mesh)[1] == pytest.approx(7850 * T * A**2 + 2.0 * A**2, rel=1e-12)
    nas = _read(tmp_path, "n.bdf", _nastran_plate(pshell=f"PSHELL,1,1,{T},1,,,,2."))
    np.testing.assert_allclose(_free_modes(mesh), _free_modes(nas), rtol=1e-9)


# ---------------------------------------------------------------- finding 2: BOUNDARY
def test_ss_plate_deck_runs_with_its_boundary_and_frequency(tmp_path, capsys):
    """*BOUNDARY in the model data and *FREQUENCY's 8 eigenvalues: the SS plate, as the
    Nastran deck with SPC1 123 and EIGRL ND = 8 (without them it ran free-free, 67.1 Hz)."""
    inp = _write(tmp_path, "a_flat.inp", _abaqus_plate([
        "*BOUNDARY", "EDGE, 1, 3", "*STEP, name=modal", "*FREQUENCY, EIGENSOLVER=LANCZOS",
        "8, , , , ,", "*END STEP"]))
    f = _cli_modes(tmp_path, inp)
    assert "deck SPC: SPC1" in capsys.readouterr().out
    ref = _cli_modes(tmp_path, _write(tmp_path, "p.bdf", _nastran_plate()))
    assert len(f) == 8
    np.testing.assert_allclose(f, ref, rtol=1e-8)
    assert f[0] == pytest.approx(F11, rel=2e-3)            # 98.485 vs 98.343 Hz
    assert F11 == pytest.approx(98.343, abs=1e-3)


def test_boundary_inside_the_step_as_abaqus_cae_writes_it(tmp_path):
    """*Boundary with a named type inside *Step (loads and outputs around it not used)."""
    inp = _write(tmp_path, "a_step.inp", _abaqus_plate([
        "*Step, name=modal, perturbation", "*Frequency, eigensolver=Lanczos", "8, , , , ,",
        "*Boundary", "EDGE, PINNED", "*Cload", "221, 3, 1.", "*Output, field, "
        "variable=PRESELECT", "*End Step"]))
    with pytest.warns(MeshWarning, match=r"not used for M and K: .*\*CLOAD x1"):
        mesh = read_mesh(inp)
    assert mesh.solution["spc"] == "SPC1" and mesh.solution["n_modes"] == 8
    assert len(mesh.dof_sets["SPC1"]) == 3 * len(_edge())
    f = _cli_modes(tmp_path, inp)
    ref = _cli_modes(tmp_path, _write(tmp_path, "p.bdf", _nastran_plate()))
    np.testing.assert_allclose(f, ref, rtol=1e-8)


def test_boundary_types_and_ranges_hold_the_abaqus_components(tmp_path):
    text = _abaqus_plate(["*BOUNDARY", "1, XSYMM", "2, YSYMM", "3, ZSYMM", "4, XASYMM",
                          "5, YASYMM", "6, ZASYMM", "7, PINNED", "8, ENCASTRE", "9, 2, 4",
                          "10, 5", "11, 1, 1, 0."])
    rows = _read(tmp_path, "t.inp", text).dof_sets["SPC1"]
    got = {}
    for node, c in rows.tolist():
        got.setdefault(node + 1, "")
        got[node + 1] += str(c + 1)
    assert got == {1: "156", 2: "246", 3: "345", 4: "234", 5: "135", 6: "126", 7: "123",
                   8: "123456", 9: "234", 10: "5", 11: "1"}


def test_constraints_of_the_frequency_step_with_op_new_and_later_steps(tmp_path):
    """Model data clamps the edges; step 1 (static) replaces that with OP=NEW by 1-3; the
    frequency step 2 inherits it; step 3 (after it) is not used."""
    text = _abaqus_plate([
        "*BOUNDARY", "EDGE, ENCASTRE",
        "*STEP", "*STATIC", "*BOUNDARY, OP=NEW", "EDGE, 1, 3", "*END STEP",
        "*STEP", "*FREQUENCY, EIGENSOLVER=SUBSPACE", "5, 300.", "*END STEP",
        "*STEP", "*FREQUENCY", "20", "*BOUNDARY", "EDGE, ENCASTRE", "*END STEP"])
    mesh = _read(tmp_path, "ops.inp", text)
    assert len(mesh.dof_sets["SPC1"]) == 3 * len(_edge())
    assert dict(mesh.solution) == {"spc": "SPC1", "n_modes": 5, "f_max": 300.0}
    assert mesh.info["dropped"]["STEP"] == 1 and mesh.info["dropped"]["STATIC"] == 1
    f = _cli_modes(tmp_path, _write(tmp_path, "ops.inp", text))
    assert len(f) == 3 and f[-1] < 300                  # 98.5, 247.9, 247.9 Hz
    assert f[0] == pytest.approx(F11, rel=2e-3)


def test_frequency_range_of_the_lanczos_solver(tmp_path):
    text = _abaqus_plate(["*BOUNDARY", "EDGE, 1, 3", "*STEP", "*FREQUENCY", ", 200., 450.",
                          "*END STEP"])
    mesh = _read(tmp_path, "rng.inp", text)
    assert dict(mesh.solution) == {"spc": "SPC1", "f_min": 200.0, "f_max": 450.0}
    f = _cli_modes(tmp_path, _write(tmp_path, "rng.inp", text))
    np.testing.assert_allclose(f, [247.949, 247.949, 396.773], rtol=1e-5)


def test_nonzero_boundary_value_is_held_at_zero_with_a_warning(tmp_path):
    p = _write(tmp_path, "nz.inp", _abaqus_plate(["*BOUNDARY", "EDGE, 1, 3", "221, 3, 3, 2.5"]))
    line = p.read_text().splitlines().index("221, 3, 3, 2.5") + 1
    with pytest.warns(MeshWarning) as got:
        mesh = read_mesh(p)
    assert any(f"nz.inp line {line}: *BOUNDARY prescribes non-zero values (1 line(s), e.g. "
               "221 = 2.5)" in str(w.message) for w in got)
    assert [220, 2] in mesh.dof_sets["SPC1"].tolist()


@pytest.mark.parametrize("lines, message", [
    (["*BOUNDARY, TYPE=VELOCITY", "EDGE, 1, 3"], r"\*BOUNDARY TYPE=VELOCITY is not supported"
                                                 "; valid: DISPLACEMENT"),
    (["*BOUNDARY, USER", "EDGE, 1, 3"], "parameter USER is not supported; valid: OP"),
    (["*BOUNDARY", "EDGE, 1, 7"], r"DOF 1..7; valid: first <= last within 1..6"),
    (["*BOUNDARY", "EDGE, FIXED"], "type 'FIXED' is not known; valid: .*ENCASTRE, PINNED"),
    (["*BOUNDARY", "NOPE, 1, 3"], "node set 'NOPE', which is not defined"),
    (["*STEP", "*FREQUENCY", "8", "*BOUNDRY", "EDGE, 1, 3", "*END STEP"],
     r"\*BOUNDRY: a misspelt \*BOUNDARY"),
    (["*FREQUENCY", "8"], r"\*FREQUENCY outside a step"),
    (["*STEP", "*FREQUENCY", ", 300., 200.", "*END STEP"], "range 300..200"),
    (["*STEP", "*FREQUENCY, EIGENSOLVER=QR", "8", "*END STEP"], "EIGENSOLVER=QR; valid"),
    (["*STEP", "*MODEL CHANGE, REMOVE", "PLATE", "*FREQUENCY", "8", "*END STEP"],
     r"\*MODEL CHANGE is not supported")])
def test_bad_boundary_and_step_input_names_file_line_and_keyword(tmp_path, lines, message):
    p = _write(tmp_path, "bad.inp", _abaqus_plate(lines))
    with pytest.raises(MeshError, match=r"bad.inp, line \d+: .*" + message):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", MeshWarning)
            read_mesh(p)


# ---------------------------------------------------------------- finding 6: CAE assembly
def test_cae_deck_with_a_reference_point_numbered_like_a_part_node(tmp_path, capsys):
    """The assembly's node 1 and MASS element 1 are not the part's node/element 1; the
    step's Set-1 is the assembly's (edges), not the part's (all nodes).  Reference: the
    same model as a Nastran deck (RP = GRID 1001 with a 0.5 kg CONM2, RBE2 to the centre)."""
    inp = _write(tmp_path, "a_rp.inp", _cae_plate())
    mesh = _read(tmp_path, "a_rp.inp", _cae_plate(), units="mm-t-s")
    rp = mesh.node_sets["RP-1"]
    assert mesh.node_ids[rp].tolist() == [1001]
    np.testing.assert_allclose(mesh.points[rp[0]], [0.25, 0.25, 0.05])
    assert len(mesh.node_sets["Set-1"]) == 441 and len(mesh.node_sets["Assembly.Set-1"]) == 80
    assert mesh.point_masses[0].node == rp[0] and mesh.point_masses[0].mass == pytest.approx(0.5)
    assert "1 -> 1001" in mesh.info["converted"]["assembly-level *NODE"]
    f = _cli_modes(tmp_path, inp, "--units", "mm-t-s")
    assert "mass 10.3125 kg" in capsys.readouterr().out      # 9.8125 + 0.5 by hand
    nas = _write(tmp_path, "p_rp.bdf", _nastran_plate([
        "GRID,1001,,0.25,0.25,0.05", "RBE2,9001,1001,123456,221", "CONM2,9002,1001,,0.5"]))
    ref = _cli_modes(tmp_path, nas)
    assert len(f) == 8
    np.testing.assert_allclose(f, ref, rtol=1e-8)


def test_cae_deck_without_the_point_mass_is_the_ss_plate(tmp_path):
    f = _cli_modes(tmp_path, _write(tmp_path, "a0.inp", _cae_plate(m_rp=0.0)), "--units",
                   "mm-t-s")
    assert f[0] == pytest.approx(F11, rel=2e-3)


def test_instance_qualified_and_bare_labels_in_a_cae_step(tmp_path):
    mesh = _read(tmp_path, "q.inp", _cae_plate("Set-1, PINNED\nPlate-1.221, 3, 3"),
                 units="mm-t-s")  # the CAE deck is mm-t-s: without units it is refused
    assert [220, 2] in mesh.dof_sets["SPC1"].tolist()    # the part's node 221
    p = _write(tmp_path, "bare.inp", _cae_plate("Set-1, PINNED\n221, 3, 3"))
    with pytest.raises(MeshError, match=r"bare.inp, line \d+: \*BOUNDARY refers to "
                                        r"assembly-level node 221 .*write Plate-1.221"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", MeshWarning)
            read_mesh(p)


# ---------------------------------------------------------------- finding 10
def test_shell_general_section_with_a_material_is_the_shell_section(tmp_path):
    a = assemble(_read(tmp_path, "s.inp", _abaqus_angle(", OFFSET=SPOS")))
    text = _abaqus_angle(", OFFSET=SPOS").replace(
        "*SHELL SECTION, ELSET=ALL, MATERIAL=STEEL, OFFSET=SPOS\n0.01, 5",
        "*Shell General Section, elset=ALL, material=STEEL, offset=SPOS\n0.01,")
    b = assemble(_read(tmp_path, "g.inp", text))
    assert abs(a.K - b.K).max() == 0 and abs(a.M - b.M).max() == 0


def test_shell_general_section_given_by_stiffness_is_refused_by_its_name(tmp_path):
    text = _abaqus_angle().replace("*SHELL SECTION, ELSET=ALL, MATERIAL=STEEL\n0.01, 5",
                                   "*SHELL GENERAL SECTION, ELSET=ALL, DENSITY=78.5\n"
                                   "1.e9, 0., 1.e9, 0., 0., 3.e8, 0., 0.")
    with pytest.raises(MeshError, match=r"\*SHELL GENERAL SECTION without MATERIAL= or "
                                        "COMPOSITE.*is not supported; give MATERIAL="):
        read_mesh(_write(tmp_path, "gen.inp", text))


def test_real_keywords_are_not_taken_for_misspelt_ones(tmp_path):
    text = _abaqus_plate(["*NODAL THICKNESS", "1, 0.005", "*SURFACE SECTION, ELSET=X",
                          "*DISTRIBUTION, NAME=D1, LOCATION=NODE", ", 1.", "*PLASTIC",
                          "300.E6, 0."])
    with pytest.warns(MeshWarning, match=r"\*NODAL THICKNESS x1, \*SURFACE SECTION x1, "
                                         r"\*DISTRIBUTION x1, \*PLASTIC x1"):
        read_mesh(_write(tmp_path, "real.inp", text))


def test_boundary_and_frequency_survive_the_bdf_writer(tmp_path):
    """The *BOUNDARY set is a Nastran SPC set: written as SPC = 1 / SPC1 / EIGRL, read back
    the same, with the same constrained frequencies."""
    from flexpipe.cli.modes import deck_fixed_dofs
    from flexpipe.mesh import write_mesh

    a = _read(tmp_path, "a_rp.inp", _cae_plate(), units="mm-t-s")
    assert "80 nodes -> DOF set SPC1" in a.info["converted"]["*BOUNDARY"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)    # named sets are not written
        b = read_mesh(write_mesh(a, tmp_path / "w.bdf"))
    assert b.dof_sets["SPC1"].tolist() == a.dof_sets["SPC1"].tolist()
    assert b.solution["spc"] == "SPC1" and b.solution["n_modes"] == 8
    f = [eigenmodes(fe, 8, fixed_dofs=deck_fixed_dofs(m, fe.dofs_per_node))[0]
         for m in (a, b) for fe in [assemble(m)]]
    np.testing.assert_allclose(f[0], f[1], rtol=1e-9)


# ------------------------------------------------- unit slips and set names (audit BYO)
def test_mm_t_s_deck_read_without_units_is_refused_as_nastran_does(tmp_path):
    """The whole deck in mm-t-s (E in MPa, rho in t/mm^3) read as SI: refused with the
    material's name, file and line and the --units hint, as the Nastran reader does for a
    MAT1 card (reference: mm-t-s steel has c = 5.2e6 m/s taken as SI, 1000x steel's)."""
    text = _abaqus_plate([]).replace("2.1E11, 0.3", "210000., 0.3").replace("7850.", "7.85e-9")
    path = tmp_path / "mm.inp"
    path.write_text(text)
    line = text.splitlines().index("*MATERIAL, NAME=STEEL") + 1
    for scale in (1.0, 1e-3):  # --scale only converts lengths, not E and rho
        with pytest.raises(MeshError) as e:
            read_mesh(path, scale)
        msg = str(e.value)
        assert str(path) in msg and f"line {line}" in msg and "*MATERIAL STEEL" in msg
        assert "units='mm-t-s'" in msg and "--units mm-t-s" in msg
    mesh = read_mesh(path, units="mm-t-s")  # the same deck with its units: steel
    assert mesh.sections["PLATE"]["E"] == pytest.approx(2.1e11)


def test_abaqus_nset_names_match_ignoring_case(tmp_path):
    import flexpipe as fp
    from flexpipe.reduction.interface import resolve_interfaces

    fe = assemble(_read(tmp_path, "p.inp", _abaqus_plate([])))
    got = resolve_interfaces(fe, [fp.Interface((0.0, 0.0, 0.0), node_set="edge", name="e")])
    assert got[0].nodes.size == len(_edge())


def test_modes_arpack_failure_names_the_file_and_the_units(tmp_path, capsys, monkeypatch):
    """A mesh in mm read as m can make ARPACK give up (the BYO audit's 4.4 km ladder):
    one error line naming the file, the mesh's span and the units options, and a warning
    before the solve; not a scipy traceback."""
    import scipy.sparse.linalg as spla

    import flexpipe.fem as fem

    text = _abaqus_plate([])
    for k, (x, y, z) in _plate_nodes().items():  # the plate in mm, E and rho SI
        text = text.replace(f"\n{k}, {x!r}, {y!r}, {z!r}\n",
                            f"\n{k}, {x * 1e3!r}, {y * 1e3!r}, {z!r}\n", 1)
    path = _write(tmp_path, "mm.inp", text)

    def fail(*a, **kw):
        raise spla.ArpackNoConvergence("ARPACK error -1: No convergence", [], [])

    monkeypatch.setattr(fem, "eigenmodes", fail)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        code = cli.main(["modes", str(path), "-o", str(tmp_path / "o"), "-q"])
    assert code == 2
    err = capsys.readouterr().err
    assert "warning:" in err and "the mesh spans 500 m" in err  # before the solve
    assert "Traceback" not in err and str(path) in err
    assert "did not converge" in err and "--scale 0.001" in err and "--units mm-t-s" in err
