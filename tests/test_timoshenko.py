"""Timoshenko beams (shear + rotary inertia) against the exact solution of Timoshenko's
equations, Euler-Bernoulli when no shear factor is given, standard sections by hand."""

from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sla
from scipy.optimize import brentq

from flexpipe.fem import Material, assemble, eigenmodes
from flexpipe.fem.properties import BeamSection
from flexpipe.fem.sections import principal, standard_section
from flexpipe.mesh import CellBlock, Mesh

STEEL = Material(210e9, 0.3, 7850.0)


def _exact(L, E, G, rho, A, I, k, bc, n):
    """Lowest ``n`` frequencies (Hz) of Timoshenko's equations, by the transfer matrix
    ``expm`` of the first-order system y = (w, psi, M, V) and root finding on its
    boundary determinant (cantilever: clamped at 0, free at L; free-free)."""
    def det(f):
        w2 = (2 * np.pi * f) ** 2
        Am = np.array([[0, 1, 0, 1 / (k * G * A)], [0, 0, 1 / (E * I), 0],
                       [0, -rho * I * w2, 0, -1], [-rho * A * w2, 0, 0, 0]])
        T = sla.expm(Am * L)
        cols = [2, 3] if bc == "cantilever" else [0, 1]
        return np.linalg.det(T[np.ix_([2, 3], cols)])

    grid = np.linspace(1.0, 6000.0, 1200)
    vals = [det(f) for f in grid]
    roots = [brentq(det, a, b) for a, b, fa, fb in zip(grid, grid[1:], vals, vals[1:], strict=False)
             if np.sign(fa) != np.sign(fb)]
    return np.array(roots[:n])


def _beam(L, n_el):
    x = np.linspace(0, L, n_el + 1)
    pts = np.column_stack([x, np.zeros_like(x), np.zeros_like(x)])
    return Mesh(pts, (CellBlock("line", np.column_stack([np.arange(n_el),
                                                         np.arange(1, n_el + 1)])),))


def _bending_freqs(fe, fixed, n):
    f, X = eigenmodes(fe, n + 24, fixed_dofs=fixed)
    # default orientation v = global z: local y (bending with Iz) is global z
    uy = np.abs(X[2::6]).max(axis=0)
    other = np.max([np.abs(X[c::6]).max(axis=0) for c in (0, 1, 3, 5)], axis=0)
    keep = [i for i in range(len(f)) if f[i] > 1.0 and uy[i] > 1e6 * other[i]]
    return f[keep][:n]


@pytest.mark.parametrize("bc", ["cantilever", "free"])
def test_stubby_timoshenko_beam_matches_exact_theory(bc):
    L, b, h = 1.0, 0.1, 0.2            # L / h = 5: shear and rotary inertia matter
    k = 10 * (1 + 0.3) / (12 + 11 * 0.3)
    sec = BeamSection.rectangle(b, h)
    sec = BeamSection(sec.A, sec.Iy, sec.Iz, sec.J, k1=k, k2=k)
    fe = assemble(_beam(L, 60), STEEL, beam_section=sec)
    fixed = np.arange(6) if bc == "cantilever" else None
    n = 4 if bc == "cantilever" else 3
    got = _bending_freqs(fe, fixed, n)
    ref = _exact(L, STEEL.E, STEEL.G, STEEL.rho, sec.A, sec.Iz, k, bc, n)
    assert np.allclose(got, ref, rtol=1e-3), (got, ref)     # 60 elements: 1e-6 .. 6e-4
    # shear matters: the same theory with (almost) rigid shear is 2 % (mode 1) to 30 % higher
    rigid_shear = _exact(L, STEEL.E, STEEL.G * 1e9, STEEL.rho, sec.A, sec.Iz, k, bc, n)
    assert got[0] < 0.99 * rigid_shear[0] and (got[1:] < 0.9 * rigid_shear[1:]).all()


def test_no_shear_factor_is_euler_bernoulli():
    L, b, h = 1.0, 0.1, 0.2
    sec = BeamSection.rectangle(b, h)
    fe = assemble(_beam(L, 60), STEEL, beam_section=sec)
    got = _bending_freqs(fe, np.arange(6), 3)
    beta = np.array([1.875104068711961, 4.694091132974175, 7.854757438237613])
    ref = beta**2 / (2 * np.pi * L**2) * np.sqrt(STEEL.E * sec.Iz / (STEEL.rho * sec.A))
    assert np.allclose(got, ref, rtol=2e-4), (got, ref)


def test_standard_sections_by_hand():
    nu = 0.3
    s = standard_section("ROD", [0.05], nu)
    assert np.isclose(s["A"], np.pi * 0.05**2) and np.isclose(s["I1"], np.pi * 0.05**4 / 4)
    assert np.isclose(s["J"], np.pi * 0.05**4 / 2)
    assert np.isclose(s["K1"], 6 * 1.3 / (7 + 1.8))
    s = standard_section("TUBE", [0.05, 0.04], nu)
    assert np.isclose(s["I2"], np.pi * (0.05**4 - 0.04**4) / 4)
    s = standard_section("BAR", [0.1, 0.2], nu)              # width (z) 0.1, height (y) 0.2
    assert np.isclose(s["I1"], 0.1 * 0.2**3 / 12) and np.isclose(s["I2"], 0.2 * 0.1**3 / 12)
    # I-beam 200 high, flanges 100 x 10, web 6: textbook sums
    s = standard_section("I", [0.2, 0.1, 0.1, 0.006, 0.01, 0.01], nu)
    A = 2 * 0.1 * 0.01 + 0.006 * 0.18
    I1 = 0.1 * 0.2**3 / 12 - (0.1 - 0.006) * 0.18**3 / 12
    I2 = 2 * 0.01 * 0.1**3 / 12 + 0.18 * 0.006**3 / 12
    assert np.isclose(s["A"], A) and np.isclose(s["I1"], I1) and np.isclose(s["I2"], I2)
    assert np.isclose(s["J"], 2 * 0.1 * 0.01**3 / 3 + 0.18 * 0.006**3 / 3)
    assert np.isclose(s["K1"], 0.18 * 0.006 / A)
    # box 100 x 200, walls 10 (top/bottom) and 5 (sides): Bredt
    s = standard_section("BOX", [0.1, 0.2, 0.01, 0.005], nu)
    assert np.isclose(s["A"], 0.1 * 0.2 - 0.09 * 0.18)
    assert np.isclose(s["J"], 4 * (0.095 * 0.19) ** 2 / (2 * 0.095 / 0.01 + 2 * 0.19 / 0.005))
    # equal-leg angle 50 x 50 x 5: centroid, I12 and principal moments by hand
    s = standard_section("L", [0.05, 0.05, 0.005, 0.005], nu)
    a1, a2 = 0.005 * 0.05, 0.045 * 0.005
    A = a1 + a2
    c = (a1 * 0.025 + a2 * 0.0025) / A                      # both centroid coordinates
    Iyz = a1 * (0.025 - c) * (0.0025 - c) + a2 * (0.0025 - c) * (0.0275 - c)
    assert np.isclose(s["I12"], Iyz) and np.isclose(s["I1"], s["I2"])
    Ip1, Ip2, ang = principal(s["I1"], s["I2"], s["I12"])
    assert np.isclose(abs(ang), np.pi / 4)
    assert np.isclose(Ip1 + Ip2, s["I1"] + s["I2"]) and np.isclose(abs(Ip1 - Ip2), 2 * abs(Iyz))
    for shape, dims in (("T", [0.1, 0.1, 0.01, 0.008]), ("CHAN", [0.05, 0.1, 0.005, 0.006]),
                        ("HAT", [0.05, 0.003, 0.04, 0.02])):
        s = standard_section(shape, dims, nu)
        assert s["A"] > 0 and s["I1"] > 0 and s["I2"] > 0 and 0 < s["K1"] + s["K2"] <= 1
    with pytest.raises(ValueError, match="inner radius"):
        standard_section("TUBE", [0.04, 0.05])
    with pytest.raises(ValueError, match="not supported; valid: ROD"):
        standard_section("ZED", [1, 2])


def test_pin_flags_turn_a_clamped_beam_into_a_pinned_one(tmp_path):
    """Both ends clamped, but CBAR pin flags release the bending rotations (5, 6) at the
    outer ends: the beam is simply supported, f_k = k^2 pi / (2 L^2) sqrt(EI / rho A)."""
    from flexpipe.mesh import read_mesh, write_mesh

    n, L, d = 20, 2.0, 0.05
    lines = ["BEGIN BULK", "MAT1,1,2.1+11,,0.3,7850.", "PBARL,1,1,,BAR", ",0.05,0.05"]
    lines += [f"GRID,{i + 1},,{L * i / n},0.,0." for i in range(n + 1)]
    for i in range(n):
        pa = "56" if i == 0 else ""
        pb = "56" if i == n - 1 else ""
        lines += [f"CBAR,{i + 1},1,{i + 1},{i + 2},0.,0.,1.,,+", f"+,{pa},{pb}"]
    path = tmp_path / "pinned.bdf"
    path.write_text("\n".join(lines + ["ENDDATA"]) + "\n")
    mesh = read_mesh(path)
    # PBARL BAR carries shear factors: switch them off to compare with Euler-Bernoulli
    sec = BeamSection(d * d, d**4 / 12, d**4 / 12, 0.1406 * d**4)
    fe = assemble(mesh, beam_section=sec)
    fixed = np.concatenate([np.arange(6), n * 6 + np.arange(6)])
    f, _ = eigenmodes(fe, 4, fixed_dofs=fixed)
    I, A = d**4 / 12, d * d
    ref = np.array([1, 1, 4, 4]) * np.pi / (2 * L**2) * np.sqrt(2.1e11 * I / (7850.0 * A))
    assert np.allclose(f, ref, rtol=1e-5), (f, ref)
    # and the flags survive a round trip through the writer
    again = read_mesh(write_mesh(mesh, tmp_path / "again.bdf"))
    assert np.array_equal(again.blocks[0].data["release"], mesh.blocks[0].data["release"])


def test_tapered_pbeaml_uses_the_mean_section_with_a_warning(tmp_path):
    import warnings as _w

    from flexpipe.mesh import MeshWarning, read_mesh

    p = tmp_path / "tap.bdf"
    p.write_text("BEGIN BULK\nMAT1,1,2.1+11,,0.3,7850.\nGRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\n"
                 "CBEAM,1,4,1,2,0.,0.,1.\nPBEAML,4,1,,ROD\n,0.02,,YES,1.,0.04\nENDDATA\n")
    with _w.catch_warnings(record=True) as rec:
        _w.simplefilter("always")
        mesh = read_mesh(p)
    assert any(isinstance(r.message, MeshWarning) and "tapered" in str(r.message)
               for r in rec)
    assert np.isclose(mesh.sections["PID4"]["A"], np.pi * (0.02**2 + 0.04**2) / 2)
    assert np.isclose(mesh.sections["PID4"]["Iz"], np.pi * (0.02**4 + 0.04**4) / 8)
