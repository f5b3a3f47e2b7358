"""PCOMP/PCOMPG + MAT8 by classical lamination: ABD by hand, a one-ply isotropic laminate
equals PSHELL, and plies turned by 90 degrees equal the original ones on elements whose
x axis (G1 -> G2) is turned by -90 degrees."""

from __future__ import annotations

import numpy as np
import pytest
from _meshdata import deck as _deck
from _meshdata import write as _write

from flexpipe.errors import MeshError
from flexpipe.fem import assemble, eigenmodes
from flexpipe.fem.laminate import abd, ply_q
from flexpipe.mesh import read_mesh

MAT8 = "MAT8,2,140.+9,10.+9,0.3,5.+9,5.+9,4.+9,1600."


def test_cross_ply_abd_by_hand():
    E1, E2, nu12, G12, t = 140e9, 10e9, 0.3, 5e9, 0.25e-3
    d = 1 - nu12 * nu12 * E2 / E1
    Q0 = np.array([[E1 / d, nu12 * E2 / d, 0], [nu12 * E2 / d, E2 / d, 0], [0, 0, G12]])
    Q90 = Q0[[1, 0, 2]][:, [1, 0, 2]]
    A, B, D, T = abd([(ply_q(E1, E2, nu12, G12), t, th) for th in (0, 90, 90, 0)])
    assert T == pytest.approx(4 * t)
    assert np.allclose(A, 2 * t * (Q0 + Q90), rtol=1e-12)
    assert np.abs(B).max() < 1e-12 * np.abs(A).max() * t
    # plies at [-2t, -t], [-t, 0], [0, t], [t, 2t]: D = 14/3 t^3 Q0 + 2/3 t^3 Q90
    assert np.allclose(D, (14 / 3 * Q0 + 2 / 3 * Q90) * t**3, rtol=1e-12)


def _plate(tmp_path, name, prop, mats, shift=False):
    """A 0.3 x 0.18 m plate of 6 x 6 CQUAD4; ``shift``: connectivity starts at G4."""
    n = 6
    cards = []
    for j in range(n + 1):
        for i in range(n + 1):
            cards.append(f"GRID,{j * (n + 1) + i + 1},,{0.05 * i},{0.03 * j},0.")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            g = [a, a + 1, a + n + 2, a + n + 1]
            if shift:
                g = g[3:] + g[:3]
            cards.append(f"CQUAD4,{j * n + i + 1},1,{g[0]},{g[1]},{g[2]},{g[3]}")
    return read_mesh(_write(tmp_path, name, _deck(*cards, *prop, *mats)))


def test_isotropic_one_ply_laminate_equals_pshell(tmp_path):
    mat = ["MAT1,1,7.+10,,0.33,2700."]
    a = assemble(_plate(tmp_path, "ps.bdf", ["PSHELL,1,1,0.002,1"], mat))
    b = assemble(_plate(tmp_path, "pc.bdf", ["PCOMP,1,,,,,,,,+", "+,1,0.002,0."], mat))
    assert abs(a.M - b.M).max() <= 1e-12 * abs(a.M).max()
    # transverse shear of PCOMP uses G t as PSHELL does: identical stiffness
    assert abs(a.K - b.K).max() <= 1e-9 * abs(a.K).max()


def test_ply_angles_turn_with_the_plate(tmp_path):
    ply0 = ["PCOMP,1,,,,,,,SYM,+", "+,2,0.0005,0.,,2,0.0005,30."]
    ply90 = ["PCOMPG,1,,,,,,,SYM,+", "+,1,2,0.0005,90.,,,,,+", "+,2,2,0.0005,120."]
    f0, _ = eigenmodes(assemble(_plate(tmp_path, "a.bdf", ply0, [MAT8])), 12)
    f90, _ = eigenmodes(assemble(_plate(tmp_path, "b.bdf", ply90, [MAT8], shift=True)), 12)
    assert np.allclose(f0[6:], f90[6:], rtol=1e-9)
    # and the orthotropy matters: a 0-degree plate differs from a 90-degree one
    f90b, _ = eigenmodes(assemble(_plate(tmp_path, "c.bdf", ply90, [MAT8])), 12)
    assert np.abs(f90b[6:] / f0[6:] - 1).max() > 0.05


def test_unsymmetric_laminate_is_an_error(tmp_path):
    with pytest.raises(MeshError, match=r"uns.bdf, line \d+: PCOMP 1: the laminate is not "
                                        r"symmetric"):
        _plate(tmp_path, "uns.bdf", ["PCOMP,1,,,,,,,,+", "+,2,0.001,0.,,2,0.001,90."],
               [MAT8])


def test_element_theta_and_mcid_orient_the_plies(tmp_path):
    """THETA = 90 on the elements with plies [0/30]s = plies [90/120]s; an MCID system
    whose x axis is global y = THETA 90 on these x-aligned elements; writing a laminate
    back is refused (the writer has no PCOMP)."""
    from flexpipe.errors import InputError
    from flexpipe.mesh import write_mesh

    def plate(name, plies, theta=""):
        m = _plate(tmp_path, name, plies, [MAT8, "CORD2R,7,,0.,0.,0.,0.,0.,1.,+",
                                            "+,0.,1.,0."])
        if theta:
            text = (tmp_path / name).read_text().splitlines()
            text = [ln + f",{theta}" if ln.startswith("CQUAD4") else ln for ln in text]
            (tmp_path / name).write_text("\n".join(text) + "\n")
            m = read_mesh(tmp_path / name)
        return m

    ref = assemble(plate("r.bdf", ["PCOMP,1,,,,,,,SYM,+", "+,2,0.0005,90.,,2,0.0005,120."]))
    ply0 = ["PCOMP,1,,,,,,,SYM,+", "+,2,0.0005,0.,,2,0.0005,30."]
    for name, theta in (("t.bdf", "90."), ("m.bdf", "7")):
        mesh = plate(name, ply0, theta)
        fe = assemble(mesh)
        assert abs(fe.K - ref.K).max() <= 1e-9 * abs(ref.K).max(), name
        with pytest.raises(InputError, match="laminate"):
            write_mesh(mesh, tmp_path / f"w{name}")


def test_abaqus_composite_shell_equals_pcomp(tmp_path):
    """*SHELL SECTION, COMPOSITE with *ELASTIC, TYPE=LAMINA plies (angles from the global X
    axis, Abaqus' default on x-aligned elements) = the same PCOMP/MAT8 laminate."""
    n = 6
    nodes = [f"{j * (n + 1) + i + 1}, {0.05 * i}, {0.03 * j}, 0." for j in range(n + 1)
             for i in range(n + 1)]
    els = []
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            els.append(f"{j * n + i + 1}, {a}, {a + 1}, {a + n + 2}, {a + n + 1}")
    inp = (["*NODE"] + nodes + ["*ELEMENT, TYPE=S4, ELSET=P"] + els
           + ["*SHELL SECTION, ELSET=P, COMPOSITE, SYMMETRIC", "0.0005, 3, CF, 0.",
              "0.0005, 3, CF, 30.", "*MATERIAL, NAME=CF",
              "*ELASTIC, TYPE=LAMINA", "140.E9, 10.E9, 0.3, 5.E9, 5.E9, 4.E9",
              "*DENSITY", "1600."])
    a = assemble(read_mesh(_write(tmp_path, "c.inp", "\n".join(inp) + "\n")))
    b = assemble(_plate(tmp_path, "c.bdf", ["PCOMP,1,,,,,,,SYM,+",
                                            "+,2,0.0005,0.,,2,0.0005,30."], [MAT8]))
    for X, Y in ((a.K, b.K), (a.M, b.M)):
        assert abs(X - Y).max() <= 1e-9 * abs(X).max()
