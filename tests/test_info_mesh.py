"""``flexpipe info`` on a mesh: the structural mass and centre of mass from the properties
the file carries (shells rho t area, beams rho A L, solids rho V, point masses), without
assembling the model, and section properties printed with their SI units."""

import dataclasses
import re
import time
from pathlib import Path

import numpy as np
import pytest

from flexpipe.cli import main

ROOT = Path(__file__).resolve().parents[1]
SEDAN = ROOT / "meshes" / "sedan_biw.bdf"


def _card(*fields) -> str:
    """A small-field Nastran card (8-character fields)."""
    return "".join(f"{str(v):<8}" if i == 0 else f"{str(v):>8}"
                   for i, v in enumerate(fields)).rstrip()


def _small_deck(path, *, ratio=0.5):
    """A 0.2 x 0.1 m quad (t = 2 mm, PSHELL 12I/T^3 = ``ratio``), a 0.2 m bar along x
    (A = 1e-4 m^2) and a 1 kg CONM2 at node 3 offset 0.05 m in y; steel 7850 kg/m^3."""
    path.write_text("\n".join([
        "BEGIN BULK",
        _card("GRID", 1, "", 0.0, 0.0, 0.0), _card("GRID", 2, "", 0.2, 0.0, 0.0),
        _card("GRID", 3, "", 0.2, 0.1, 0.0), _card("GRID", 4, "", 0.0, 0.1, 0.0),
        _card("CQUAD4", 1, 1, 1, 2, 3, 4), _card("CBAR", 2, 2, 1, 2, 0.0, 0.0, 1.0),
        _card("CONM2", 3, 3, "", 1.0, 0.0, 0.05, 0.0),
        _card("PSHELL", 1, 1, 0.002, 1, ratio),
        _card("PBAR", 2, 1, "1.-4", "1.-9", "2.-9", "3.-9"),
        _card("MAT1", 1, "2.1+11", "", 0.3, 7850.0), "ENDDATA"]) + "\n")
    return path


def _structural(out: str):
    m = re.search(r"structural mass ([0-9.e+-]+) kg \((.*)\), centre of mass \(([^)]*)\) m",
                  out)
    assert m, out
    parts = {k: float(v) for k, v in re.findall(r"([a-z ]+) ([0-9.e+-]+) kg",
                                                 m.group(2).replace(", ", ","))}
    com = np.array([float(c) for c in m.group(3).split(",")])
    return float(m.group(1)), {k.strip(): v for k, v in parts.items()}, com


def test_small_deck_mass_by_hand(capsys, tmp_path):
    """Shell 7850 x 0.002 x 0.02 = 0.314 kg at (0.1, 0.05), bar 7850 x 1e-4 x 0.2 =
    0.157 kg at (0.1, 0), CONM2 1 kg at (0.2, 0.15): 1.471 kg at (0.16798, 0.11265, 0)."""
    path = _small_deck(tmp_path / "small.bdf")
    assert main(["info", str(path)]) == 0
    total, parts, com = _structural(capsys.readouterr().out)
    shell, bar, pm = 7850 * 0.002 * 0.2 * 0.1, 7850 * 1e-4 * 0.2, 1.0
    assert parts["shells"] == pytest.approx(shell, rel=1e-4)
    assert parts["beams"] == pytest.approx(bar, rel=1e-4)
    assert parts["point masses"] == pytest.approx(pm, rel=1e-4)
    assert total == pytest.approx(shell + bar + pm, rel=1e-4)
    want = (shell * np.array([0.1, 0.05, 0]) + bar * np.array([0.1, 0, 0])
            + pm * np.array([0.2, 0.15, 0])) / (shell + bar + pm)
    np.testing.assert_allclose(com, want, atol=5e-4)


def test_sedan_biw_structural_mass(capsys):
    """The audit's hand sum: shells 80.35 + bars 241.21 + CONM2 75.00 = 396.57 kg.  The
    reference here splits every quad into two triangles (|a x b| / 2 each) with rho and t
    of its PID, beams rho A |x2 - x1|, CONM2 mass at node + offset; and the FE model's
    own mass matrix (assembled, rigid-body mass properties) gives the same mass and centre
    of mass."""
    from flexpipe.fem import assemble
    from flexpipe.flexbody.invariants import mass_properties
    from flexpipe.mesh import read_mesh

    assert main(["info", str(SEDAN)]) == 0
    out = capsys.readouterr().out
    total, parts, com = _structural(out)
    mesh = read_mesh(SEDAN)
    ref = {"shells": 0.0, "beams": 0.0, "point masses": 0.0}
    moment = np.zeros(3)
    for name, members in mesh.cell_sets.items():
        sec = mesh.sections.get(name, {})
        for bi, cells in members.items():
            block = mesh.blocks[bi]
            X = mesh.points[block.cells[cells]]
            if block.type == "quad":
                m = np.zeros(len(cells))
                c = np.zeros((len(cells), 3))
                for tri in ((0, 1, 2), (0, 2, 3)):
                    T = X[:, tri]
                    a = 0.5 * np.linalg.norm(np.cross(T[:, 1] - T[:, 0], T[:, 2] - T[:, 0]),
                                             axis=1)
                    mt = sec["rho"] * sec["thickness"] * a
                    m += mt
                    c += mt[:, None] * T.mean(axis=1)
                ref["shells"] += m.sum()
                moment += c.sum(axis=0)
            elif block.type == "line":
                m = sec["rho"] * sec["A"] * np.linalg.norm(X[:, 1] - X[:, 0], axis=1)
                ref["beams"] += m.sum()
                moment += m @ X.mean(axis=1)
    for pm in mesh.point_masses:
        ref["point masses"] += pm.mass
        moment += pm.mass * (mesh.points[pm.node] + pm.offset)
    for k in ref:
        assert parts[k] == pytest.approx(ref[k], rel=1e-4), k
    assert total == pytest.approx(396.57, abs=0.01)
    assert total == pytest.approx(sum(ref.values()), rel=1e-4)
    np.testing.assert_allclose(com, moment / sum(ref.values()), atol=1e-3)
    fe = assemble(mesh, allow_disconnected=True)
    m_fe, c_fe, _, _ = mass_properties(fe.M, fe.nodes, fe.dofs_per_node)
    from flexpipe.fem.structural_mass import structural_mass

    _, m_info, c_info, missing = structural_mass(mesh)
    assert not missing
    assert m_info == pytest.approx(m_fe, rel=1e-10)
    np.testing.assert_allclose(c_info, c_fe, atol=1e-9)


@pytest.mark.parametrize("cell", ["tetra", "tetra10", "hexahedron"])
def test_solid_mass_and_centre(cell):
    """A 0.3 x 0.2 x 0.1 m steel box at (1, 2, 3): 7800 x 0.006 = 46.8 kg at its centre;
    sheared (z += 0.2 x, volume kept) the centre moves to z + 0.2 x_c, and the FE mass
    matrix agrees."""
    from flexpipe.fem import assemble
    from flexpipe.fem.structural_mass import structural_mass
    from flexpipe.flexbody.invariants import mass_properties
    from flexpipe.mesh.generate import box

    mesh = box(0.3, 0.2, 0.1, 3, 2, 2, cell=cell, origin=(1.0, 2.0, 3.0))
    mesh = dataclasses.replace(mesh, sections={"solid": {"E": 2e11, "nu": 0.3, "rho": 7800.0}})
    parts, total, com, missing = structural_mass(mesh)
    assert not missing and set(parts) == {"solids"}
    assert total == pytest.approx(7800 * 0.3 * 0.2 * 0.1, rel=1e-12)
    np.testing.assert_allclose(com, [1.15, 2.1, 3.05], rtol=1e-12)
    pts = mesh.points.copy()
    pts[:, 2] += 0.2 * pts[:, 0] + 0.3 * pts[:, 0] * pts[:, 1]   # shear and twist
    bent = dataclasses.replace(mesh, points=pts)
    _, total, com, _ = structural_mass(bent)
    fe = assemble(bent)
    m_fe, c_fe, _, _ = mass_properties(fe.M, fe.nodes, fe.dofs_per_node)
    assert total == pytest.approx(m_fe, rel=1e-10)
    np.testing.assert_allclose(com, c_fe, atol=1e-10)


def test_shell_offset_and_beam_offsets_move_the_mass():
    """A 1 x 1 m plate, t = 10 mm, rho 1000: 10 kg; ZOFFS 20 mm puts its mid-surface (and
    centre of mass) at z = 0.02.  A beam whose ends are offset by (0, 0, 0.1) from its
    nodes has its mass there; both as the FE model has them."""
    from flexpipe.fem import assemble
    from flexpipe.fem.structural_mass import structural_mass
    from flexpipe.flexbody.invariants import mass_properties
    from flexpipe.mesh import CellBlock
    from flexpipe.mesh.generate import plate

    mesh = plate(1.0, 1.0, 2, 2)
    quads = CellBlock("quad", mesh.blocks[0].cells,
                      data={"zoffset": np.full(len(mesh.blocks[0]), 0.02)})
    mesh = dataclasses.replace(mesh, blocks=(quads,), sections={
        "shell": {"E": 2e11, "nu": 0.3, "rho": 1000.0, "thickness": 0.01}})
    parts, total, com, _ = structural_mass(mesh)
    assert total == pytest.approx(10.0, rel=1e-12)
    np.testing.assert_allclose(com, [0.5, 0.5, 0.02], atol=1e-12)
    fe = assemble(mesh)
    np.testing.assert_allclose(mass_properties(fe.M, fe.nodes, 6)[1], com, atol=1e-12)

    from flexpipe.mesh import Mesh

    beam = CellBlock("line", [[0, 1]], data={"offset_a": [[0.0, 0.0, 0.1]],
                                             "offset_b": [[0.0, 0.0, 0.1]],
                                             "orientation": [[0.0, 1.0, 0.0]]})
    bar = Mesh(points=[[0, 0, 0], [2.0, 0, 0]], blocks=(beam,),
               cell_sets={"b": {0: np.array([0])}},
               sections={"b": {"E": 2e11, "nu": 0.3, "rho": 7850.0, "A": 1e-4,
                               "Iy": 1e-8, "Iz": 1e-8, "J": 2e-8}})
    _, total, com, _ = structural_mass(bar)
    assert total == pytest.approx(7850 * 1e-4 * 2.0, rel=1e-12)
    np.testing.assert_allclose(com, [1.0, 0.0, 0.1], atol=1e-12)
    fe = assemble(bar)
    np.testing.assert_allclose(mass_properties(fe.M, fe.nodes, 6)[1], com, atol=1e-12)


def test_structural_mass_does_not_assemble(monkeypatch):
    """A 250,000-quad plate: the mass comes from the geometry, not from element matrices
    or an assembly (which take minutes and GBs on a 1M-element deck): both are made to
    fail here, and the sum takes seconds."""
    import importlib

    import flexpipe.fem
    import flexpipe.fem.shell_quad4 as quad4
    from flexpipe.fem.structural_mass import structural_mass
    from flexpipe.mesh.generate import plate

    def boom(*a, **k):
        raise AssertionError("structural_mass must not build element matrices")

    monkeypatch.setattr(quad4, "matrices", boom)
    monkeypatch.setattr(importlib.import_module("flexpipe.fem.assemble"), "assemble", boom)
    monkeypatch.setattr(flexpipe.fem, "assemble", boom)
    mesh = dataclasses.replace(plate(2.0, 1.0, 500, 500), sections={
        "shell": {"E": 7e10, "nu": 0.33, "rho": 2700.0, "thickness": 0.003}})
    t0 = time.perf_counter()
    _, total, com, _ = structural_mass(mesh)
    seconds = time.perf_counter() - t0
    assert total == pytest.approx(2700 * 0.003 * 2.0, rel=1e-12)
    np.testing.assert_allclose(com, [1.0, 0.5, 0.0], atol=1e-12)
    assert seconds < 30.0, seconds


def test_mesh_without_material_says_the_mass_is_unknown(capsys):
    """meshes/plate_quad.msh carries no material: no mass, and what is missing."""
    assert main(["info", str(ROOT / "meshes" / "plate_quad.msh")]) == 0
    out = capsys.readouterr().out
    assert "structural mass: unknown" in out and "48 quad elements without a density" in out
    assert "--material" in out


#: dimensionless section keys (as printed) and the unit of every other one
DIMENSIONLESS = {"nu", "bending_ratio", "k1", "k2"}
UNITS = {"E": "Pa", "rho": "kg/m^3", "thickness": "m", "A": "m^2", "Iy": "m^4",
         "Iz": "m^4", "J": "m^4", "theta": "deg"}


def test_section_lines_carry_si_units(capsys, tmp_path):
    """Every dimensioned section value has its SI unit; PSHELL 12I/T^3 = 0.5 with MID2 =
    MID1 prints as bending_ratio=0.5, explained under the sections."""
    path = _small_deck(tmp_path / "small.bdf", ratio=0.5)
    assert main(["info", str(path)]) == 0
    out = capsys.readouterr().out
    sections = [line for line in out.splitlines() if line.startswith("  section ")]
    assert len(sections) == 2
    seen = set()
    for line in sections:
        for item in line.split(": ", 1)[1].split(", "):
            key, rest = item.split("=")
            value, _, unit = rest.partition(" ")
            float(value)
            seen.add(key)
            if key in DIMENSIONLESS:
                assert not unit, line
            else:
                assert unit == UNITS[key], (key, line)
    assert {"E", "rho", "thickness", "A", "Iz", "J", "bending_ratio"} <= seen
    assert "bending_ratio=0.5" in out and "bending=" not in out
    assert "E=2.1e+11 Pa" in out and "rho=7850 kg/m^3" in out and "thickness=0.002 m" in out
    assert "A=0.0001 m^2" in out
    assert re.search(r"bending_ratio: .*12I/T\^3", out)
