"""Tyre models against closed forms computed here from the raw file coefficients.

* Magic Formula: peak D = mu Fz and slope BCD = K at FNOMIN, camber 0, written out below
  with the PAC2002 equations (Pacejka, Tire and Vehicle Dynamics, ch. 4) from the raw text;
* combined slip: the PAC2002 weighting functions G evaluated independently;
* vertical: k d + k3 d^3 + c d_dot, lift-off; relaxation: 1 - exp(-x/sigma);
* contact kinematics: geometry of a disc on a plane, rotation equivariance;
* Fiala: Fy = -mu Fz (1 - H^3), H = 1 - C_alpha |tan a| / (3 mu Fz), saturation mu Fz.
"""

from __future__ import annotations

import math
import re
import warnings

import numpy as np
import pytest
from _tirdata import REFERENCE_TIRS, SAMPLE, raw_numbers

from flexpipe.errors import InputError
from flexpipe.tires import (
    FialaParameters,
    FialaTire,
    SlipState,
    VerticalModel,
    iso_to_sae,
    read_tir,
    relax,
    relax_slip_velocity,
    tire_from_file,
)


def load(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return tire_from_file(path)


def tir_paths(reference_dir):
    return [reference_dir / "tires" / n for n in REFERENCE_TIRS] + [SAMPLE]


def closed_form(r: dict, Fz: float) -> dict:
    """PAC2002 pure-slip peak, stiffness and shifts at camber 0 (independent few lines)."""
    g = r.get
    fz0 = r["FNOMIN"] * g("LFZO", 1.0)
    dfz = (Fz - fz0) / fz0
    return {
        "Dx": (r["PDX1"] + g("PDX2", 0) * dfz) * g("LMUX", 1) * Fz,
        "Kx": Fz * (r["PKX1"] + g("PKX2", 0) * dfz) * math.exp(g("PKX3", 0) * dfz) * g("LKX", 1),
        "SHx": (g("PHX1", 0) + g("PHX2", 0) * dfz) * g("LHX", 1),
        "SVx": Fz * (g("PVX1", 0) + g("PVX2", 0) * dfz) * g("LVX", 1) * g("LMUX", 1),
        "Dy": (r["PDY1"] + g("PDY2", 0) * dfz) * g("LMUY", 1) * Fz,
        "Ky": r["PKY1"] * fz0 * math.sin(2 * math.atan(Fz / (r["PKY2"] * fz0))) * g("LKY", 1),
        "SHy": (g("PHY1", 0) + g("PHY2", 0) * dfz) * g("LHY", 1),
        "SVy": Fz * (g("PVY1", 0) + g("PVY2", 0) * dfz) * g("LVY", 1) * g("LMUY", 1),
        "dfz": dfz,
    }


# ----------------------------------------------------------------- Magic Formula
def test_pure_slip_peak_and_stiffness_match_closed_form(reference_dir):
    for path in tir_paths(reference_dir):
        r = raw_numbers(path)
        Fz = r["FNOMIN"]
        ref = closed_form(r, Fz)
        tire = load(path)
        kappa = np.linspace(-1.5, 1.5, 150001)
        Fx = tire.slip_forces(kappa, 0.0, Fz).Fx
        np.testing.assert_allclose(Fx, tire.mf.fx0(kappa, Fz), rtol=0, atol=1e-9)
        assert Fx.max() - ref["SVx"] == pytest.approx(ref["Dx"], rel=1e-6), path.name
        assert Fx.min() - ref["SVx"] == pytest.approx(-ref["Dx"], rel=1e-6), path.name
        h = 1e-6
        k0 = -ref["SHx"]
        slope = (tire.mf.fx0(k0 + h, Fz) - tire.mf.fx0(k0 - h, Fz)) / (2 * h)
        assert slope == pytest.approx(ref["Kx"], rel=1e-6), path.name  # BCD_x

        alpha = np.linspace(-1.5, 1.5, 150001)
        Fy = tire.slip_forces(0.0, alpha, Fz).Fy
        np.testing.assert_allclose(Fy, tire.mf.fy0(alpha, Fz), rtol=0, atol=1e-9)
        assert Fy.max() - ref["SVy"] == pytest.approx(ref["Dy"], rel=1e-6), path.name
        assert Fy.min() - ref["SVy"] == pytest.approx(-ref["Dy"], rel=1e-6), path.name
        a0 = -ref["SHy"]
        slope = (tire.mf.fy0(a0 + h, Fz) - tire.mf.fy0(a0 - h, Fz)) / (2 * h)
        assert slope == pytest.approx(ref["Ky"], rel=1e-6), path.name  # BCD_y
        assert ref["Ky"] < 0  # ISO/TYDEX: cornering stiffness negative


def test_iso_signs_of_forces_and_aligning_moment(reference_dir):
    for path in tir_paths(reference_dir):
        tire = load(path)
        Fz = tire.mf.fnomin
        f = tire.slip_forces(np.array([0.05, -0.05, 0.0, 0.0]), np.array([0, 0, 0.05, -0.05]), Fz)
        assert f.Fx[0] > 0 > f.Fx[1], path.name           # driving slip -> forward force
        assert f.Fy[2] < 0 < f.Fy[3], path.name           # alpha > 0 -> Fy < 0 (ISO W)
        assert f.Mz[2] > 0 > f.Mz[3], path.name           # aligning moment restores
        if tire.mf.c.QSY1:
            assert np.all(f.My < 0), path.name            # resists forward rolling


def test_symmetric_sample_is_odd_and_mirror_flips_asymmetric_file(reference_dir):
    tire = load(SAMPLE)
    k = np.linspace(-0.5, 0.5, 11)
    a = np.linspace(-0.3, 0.3, 13)[:, None]
    f, g = tire.slip_forces(k, a, 4200.0, 0.02), tire.slip_forces(-k, -a, 4200.0, -0.02)
    np.testing.assert_allclose(g.Fx, -f.Fx, atol=1e-9)
    np.testing.assert_allclose(g.Fy, -f.Fy, atol=1e-9)
    np.testing.assert_allclose(g.Mz, -f.Mz, atol=1e-9)
    # asymmetric reference tyre (conicity/ply-steer): mirrored use on the other side
    sedan = load(reference_dir / "tires" / "Sedan_Pac02Tire.tir")
    assert list(sedan.mirror_for(["left", "right"])) == [False, True]  # TYRESIDE = LEFT
    a1 = np.linspace(-0.2, 0.2, 9)
    plain = sedan.slip_forces(0.0, -a1, 4850.0)
    mirrored = sedan.slip_forces(0.0, a1, 4850.0, mirror=True)
    np.testing.assert_allclose(mirrored.Fy, -plain.Fy, atol=1e-9)
    assert abs(plain.Fy[4]) > 10.0  # the file really is asymmetric at alpha = 0


def G(B, C, E, x, shift):
    def f(u):
        return math.cos(C * math.atan(B * u - E * (B * u - math.atan(B * u))))
    return f(x) / f(shift)


@pytest.mark.parametrize("which", ["mf_185_80R14.tir", "HMMWV_Pac02Tire.tir", "sample"])
def test_combined_slip_weighting_matches_pac2002(reference_dir, which):
    path = SAMPLE if which == "sample" else reference_dir / "tires" / which
    r, tire = raw_numbers(path), load(path)
    Fz = r["FNOMIN"]
    dfz = closed_form(r, Fz)["dfz"]
    kappa, alpha = 0.05, 0.1
    Gxa = G(r["RBX1"] * math.cos(math.atan(r["RBX2"] * kappa)) * r["LXAL"], r["RCX1"],
            min(r["REX1"] + r["REX2"] * dfz, 1.0), alpha + r["RHX1"], r["RHX1"])
    shk = r["RHY1"] + r["RHY2"] * dfz
    Gyk = G(r["RBY1"] * math.cos(math.atan(r["RBY2"] * (alpha - r["RBY3"]))) * r["LYKA"],
            r["RCY1"], min(r["REY1"] + r["REY2"] * dfz, 1.0), kappa + shk, shk)
    muy = (r["PDY1"] + r["PDY2"] * dfz) * r["LMUY"]
    SVyk = (muy * Fz * (r["RVY1"] + r["RVY2"] * dfz) * math.cos(math.atan(r["RVY4"] * alpha))
            * math.sin(r["RVY5"] * math.atan(r["RVY6"] * kappa)) * r["LVYKA"])
    comb, px, py = (tire.slip_forces(kappa, alpha, Fz), tire.slip_forces(kappa, 0.0, Fz),
                    tire.slip_forces(0.0, alpha, Fz))
    assert comb.Fx / px.Fx == pytest.approx(Gxa, rel=1e-9)
    assert (comb.Fy - SVyk) / py.Fy == pytest.approx(Gyk, rel=1e-9)
    assert Gxa < 1 and Gyk < 1
    # combined slip reduces the longitudinal force over a grid of slips
    k = np.linspace(-1.0, 1.0, 41)
    for a in (-0.2, -0.1, -0.05, 0.05, 0.1, 0.2):
        assert np.all(np.abs(tire.slip_forces(k, a, Fz).Fx)
                      <= np.abs(tire.slip_forces(k, 0.0, Fz).Fx) + 1e-9), a


def test_file_without_combined_coefficients_warns_and_does_not_reduce(reference_dir):
    path = reference_dir / "tires" / "Sedan_Pac02Tire.tir"
    with pytest.warns(UserWarning, match="no combined-slip coefficients"):
        tire = tire_from_file(path)
    k = np.linspace(-0.3, 0.3, 7)
    np.testing.assert_allclose(tire.slip_forces(k, 0.1, 4850.0).Fx,
                               tire.slip_forces(k, 0.0, 4850.0).Fx, rtol=1e-12)


def test_use_mode_switches_outputs():
    tire = load(SAMPLE)
    props = read_tir(SAMPLE)
    from flexpipe.tires import Pac2002Tire

    f1 = Pac2002Tire.from_properties(props, use_mode=1).slip_forces(0.05, 0.05, 4000.0)
    f2 = Pac2002Tire.from_properties(props, use_mode=2).slip_forces(0.05, 0.05, 4000.0)
    f3 = Pac2002Tire.from_properties(props, use_mode=3).slip_forces(0.05, 0.05, 4000.0)
    f4 = tire.slip_forces(0.05, 0.05, 4000.0)
    assert f1.Fy == 0 and f1.Mz == 0 and f1.Fx == f3.Fx
    assert f2.Fx == 0 and f2.My == 0 and f2.Fy == f3.Fy
    assert abs(f4.Fx) < abs(f3.Fx) and abs(f4.Fy) < abs(f3.Fy)  # mode 4 combines
    f0 = Pac2002Tire.from_properties(props, use_mode=0).slip_forces(0.05, 0.05, 4000.0)
    assert f0.Fx == f0.Fy == f0.Mz == 0
    assert tire.relaxation  # USE_MODE 14


def test_iso_to_sae_conversion():
    tire = load(SAMPLE)
    f = tire.slip_forces(0.0, 0.05, 4000.0)
    Fx, Fy, Fz, Mx, My, Mz, a_sae, g_sae = iso_to_sae(f.Fx, f.Fy, 4000.0, f.Mx, f.My, f.Mz,
                                                      0.05, 0.01)
    # SAE (y right, z down): positive SAE slip angle gives negative SAE side force
    assert a_sae == -0.05 and Fy == -f.Fy and Fz == -4000.0 and Mz == -f.Mz and g_sae == 0.01
    assert Fx == f.Fx and Mx == f.Mx and My == -f.My
    # SAE convention (Milliken): a positive SAE slip angle gives a negative SAE side force.
    # SAE alpha = +0.05 is ISO alpha = -0.05:
    g = tire.slip_forces(0.0, -0.05, 4000.0)
    assert iso_to_sae(g.Fx, g.Fy, 4000.0, g.Mx, g.My, g.Mz, -0.05)[1] < 0


# ----------------------------------------------------------------- vertical
def test_vertical_linear_duffing_and_lift_off():
    lin = VerticalModel(k=2.0e5, c=300.0)
    d = np.array([-0.01, 0.0, 0.01, 0.02])
    np.testing.assert_allclose(lin.force(d, 0.1), [0.0, 0.0, 2.0e5 * 0.01 + 30.0,
                                                   2.0e5 * 0.02 + 30.0])
    # fast rebound: the damper cannot pull the wheel onto the road
    assert lin.force(0.001, -5.0) == 0.0
    duf = VerticalModel(k=2.0e5, c=0.0, k3=3.0e7)
    np.testing.assert_allclose(duf.force(d), np.where(d > 0, 2.0e5 * d + 3.0e7 * d ** 3, 0.0))
    d0 = duf.static_deflection(4000.0)
    assert 2.0e5 * d0 + 3.0e7 * d0 ** 3 == pytest.approx(4000.0, rel=1e-12)
    assert d0 < 4000.0 / 2.0e5  # hardening spring deflects less


def test_sample_duffing_fit_reproduces_load_curve_table():
    rows = [ln.split() for ln in SAMPLE.read_text().splitlines()
            if re.match(r"^\s*\d+\.\d+\s+\d+\s*$", ln)]
    d, F = np.array(rows, dtype=float).T
    A = np.column_stack([d, d ** 3])
    (k, k3), *_ = np.linalg.lstsq(A, F, rcond=None)
    vert = load(SAMPLE).vertical
    assert vert.k == pytest.approx(k, rel=1e-9) and vert.k3 == pytest.approx(k3, rel=1e-9)
    np.testing.assert_allclose(vert.force(d[1:]), F[1:], rtol=2e-3)
    assert vert.c == raw_numbers(SAMPLE)["VERTICAL_DAMPING"]


def test_reference_files_give_linear_vertical(reference_dir):
    path = reference_dir / "tires" / "HMMWV_Pac02Tire.tir"
    r = raw_numbers(path)
    vert = load(path).vertical
    assert vert.is_linear and vert.k == pytest.approx(r["VERTICAL_STIFFNESS"] * r["LCZ"])


# ----------------------------------------------------------------- relaxation
@pytest.mark.parametrize("dt", [1e-4, 1e-2, 0.2])
def test_relaxation_step_response_is_exact_exponential(dt):
    sigma, vx, target = 0.4, 12.0, 0.08
    s, t = 0.0, 0.0
    for _ in range(20):
        s = relax(s, target, vx, sigma, dt)
        t += dt
        assert s == pytest.approx(target * (1 - math.exp(-vx * t / sigma)), rel=1e-10)
    # slip-velocity form: same response for w = target |vx|, linear growth at standstill
    w = relax_slip_velocity(0.0, target * vx, vx, sigma, 3 * dt)
    assert w == pytest.approx(target * (1 - math.exp(-vx * 3 * dt / sigma)), rel=1e-10)
    assert relax_slip_velocity(0.01, 0.5, 0.0, sigma, dt) == pytest.approx(0.01 + 0.5 * dt / sigma)


def test_wheel_forces_relax_lateral_slip_with_tyre_relaxation_length(reference_dir):
    path = reference_dir / "tires" / "mf_185_80R14.tir"
    r = raw_numbers(path)
    tire = tire_from_file(path, relaxation=True)
    R0, k = r["UNLOADED_RADIUS"], r["VERTICAL_STIFFNESS"]
    defl = 0.02
    Fz = k * defl  # linear tyre, no vertical velocity
    fz0 = r["FNOMIN"] * r["LFZO"]
    sigma_a = r["PTY1"] * math.sin(2 * math.atan(Fz / (r["PTY2"] * fz0))) * R0 * r["LFZO"]
    vx, vy, dt = 15.0, 0.3, 2e-3
    state = SlipState.zeros(1)
    for i in range(1, 31):
        out = tire.wheel_forces([0.0, 0.0, R0 - defl], [0, 1, 0], 0.0, [vx, vy, 0.0],
                                road_height=0.0, state=state, dt=dt)
        state = out.state
        expect = vy / vx * (1 - math.exp(-vx * i * dt / sigma_a))
        assert state.tan_alpha[0] == pytest.approx(expect, rel=1e-9)
    assert out.Fz[0] == pytest.approx(Fz)


def test_relaxed_state_at_standstill_and_lift_off():
    tire = load(SAMPLE)
    R0 = raw_numbers(SAMPLE)["UNLOADED_RADIUS"]
    C = np.array([[0.0, 0.0, R0 - 0.015], [2.0, 0.0, R0 + 0.05]])  # second wheel lifted
    state = SlipState(np.array([0.2, 0.2]), np.array([0.1, 0.1]))
    dt, omega = 1e-3, 5.0
    out = tire.wheel_forces(C, [0, 1, 0], omega, np.zeros((2, 3)), road_height=0.0,
                            state=state, dt=dt)
    sk, sa = tire.relaxation_lengths(out.Fz[0])
    Re = tire.effective_rolling_radius(0.015)
    # standstill: sigma d(kappa')/dt = -Vsx = omega Re (no decay), tan(alpha') unchanged
    assert out.state.kappa[0] == pytest.approx(0.2 + omega * Re * dt / sk, rel=1e-12)
    assert out.state.tan_alpha[0] == pytest.approx(0.1, rel=1e-12)
    assert out.state.kappa[1] == 0 and out.state.tan_alpha[1] == 0 and out.Fz[1] == 0
    # a wheel spinning at standstill for a long time: bounded state
    s = state
    for _ in range(50):
        s = tire.wheel_forces(C, [0, 1, 0], 200.0, np.zeros((2, 3)), road_height=0.0,
                              state=s, dt=0.05).state
    assert s.kappa[0] == 1.5


# ----------------------------------------------------------------- contact kinematics
def test_upright_wheel_contact_geometry_and_slips():
    tire = load(SAMPLE)
    r = raw_numbers(SAMPLE)
    R0, defl, V = r["UNLOADED_RADIUS"], 0.015, 20.0
    vert = tire.vertical
    # effective rolling radius, PAC2002: R0 - rho0 (D atan(B rho/rho0) + F rho/rho0)
    rho0 = r["FNOMIN"] / vert.k
    Re = R0 - rho0 * (r["DREFF"] * math.atan(r["BREFF"] * defl / rho0) + r["FREFF"] * defl / rho0)
    C = np.array([[1.0, 0.7, R0 - defl]] * 3)
    omega = np.array([V / Re, 1.1 * V / Re, 0.9 * V / Re])  # free, driving, braking
    v = np.array([[V, 0.0, -0.2]] * 3)
    out = tire.wheel_forces(C, [0, 1, 0], omega, v, road_height=0.0)
    np.testing.assert_allclose(out.deflection, defl)
    np.testing.assert_allclose(out.deflection_rate, 0.2)
    np.testing.assert_allclose(out.contact_point, [[1.0, 0.7, 0.0]] * 3, atol=1e-15)
    np.testing.assert_allclose(out.kappa, [0.0, 0.1, -0.1], atol=1e-12)
    np.testing.assert_allclose(out.Fz, vert.k * defl + vert.k3 * defl ** 3 + vert.c * 0.2)
    assert abs(out.force[0, 0]) < 1e-6 * out.Fz[0] + abs(out.Fx[0])
    assert out.force[1, 0] > 0 > out.force[2, 0]
    # moment about the centre: contact force at -Rl z gives My = -Rl Fx (plus rolling resist.)
    Rl = R0 - defl
    np.testing.assert_allclose(out.moment[:, 1], -Rl * out.force[:, 0] + out.My, rtol=1e-12)
    # side slip towards +y: alpha = atan(vy/vx) > 0 and the force opposes the sliding
    side = tire.wheel_forces(C[0], [0, 1, 0], V / Re, [V, 1.0, 0.0], road_height=0.0)
    assert side.alpha[0] == pytest.approx(math.atan(1.0 / V))
    assert side.force[0, 1] < 0
    # lift-off: no force at all
    up = tire.wheel_forces([0, 0, R0 + 0.01], [0, 1, 0], V / R0, [V, 1.0, -1.0], road_height=0.0)
    assert np.all(up.force == 0) and np.all(up.moment == 0)


def test_camber_angle_and_loaded_radius():
    tire = load(SAMPLE)
    R0 = raw_numbers(SAMPLE)["UNLOADED_RADIUS"]
    g, h = 0.05, 0.3
    out = tire.wheel_forces([0, 0, h], [0, math.cos(g), math.sin(g)], 0.0, [0.0, 0.0, 0.0],
                            road_height=0.0)
    assert out.gamma[0] == pytest.approx(g)
    assert out.deflection[0] == pytest.approx(R0 - h / math.cos(g))
    # positive gamma: the top leans to -y, so the contact point (on the road, in the wheel
    # plane below the centre) is displaced to +y
    P = out.contact_point[0]
    assert P[2] == pytest.approx(0.0, abs=1e-15) and P[1] == pytest.approx(h * math.tan(g))
    top = np.array([0.0, 0.0, h]) - (P - [0.0, 0.0, h])
    assert top[1] < 0


def _rot(axis, angle):
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    K = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + math.sin(angle) * K + (1 - math.cos(angle)) * K @ K


def test_wheel_forces_are_rotation_equivariant():
    """Yawing the whole scene and tilting the road rotate force and moment alike."""
    tire = load(SAMPLE)
    R0 = raw_numbers(SAMPLE)["UNLOADED_RADIUS"]
    C = np.array([[0.0, 0.0, R0 - 0.02], [2.5, 1.0, R0 - 0.015]])
    s = np.array([[0.0, 1.0, 0.03], [0.1, 1.0, -0.02]])
    v = np.array([[18.0, 1.2, 0.1], [18.0, -0.8, -0.2]])
    omega = np.array([18.0 / 0.31 * 1.05, 18.0 / 0.31 * 0.97])
    w = np.array([[0.0, 0.0, 0.3], [0.1, 0.0, -0.2]])
    base = tire.wheel_forces(C, s, omega, v, road_height=np.zeros(2), angular_velocity=w)
    for Q in (_rot([0, 0, 1], 0.7), _rot([1, 0.3, 0], 0.15)):
        n = Q @ [0, 0, 1.0]
        Cq = C @ Q.T
        P0 = np.zeros(3)  # the rotated road plane passes through the origin
        road_h = -(n[0] * (Cq[:, 0] - P0[0]) + n[1] * (Cq[:, 1] - P0[1])) / n[2]
        rot = tire.wheel_forces(Cq, s @ Q.T, omega, v @ Q.T, road_height=road_h, road_normal=n,
                                angular_velocity=w @ Q.T)
        np.testing.assert_allclose(rot.force, base.force @ Q.T, atol=1e-7)
        np.testing.assert_allclose(rot.moment, base.moment @ Q.T, atol=1e-7)
        np.testing.assert_allclose(rot.kappa, base.kappa, atol=1e-12)
        np.testing.assert_allclose(rot.alpha, base.alpha, atol=1e-12)
        np.testing.assert_allclose(rot.gamma, base.gamma, atol=1e-12)


# ----------------------------------------------------------------- Fiala
def _fiala(**kw):
    p = FialaParameters(c_slip=8.0e4, c_alpha=6.0e4, mu_x=1.1, mu_y=1.0, **kw)
    return FialaTire(params=p, vertical=VerticalModel(k=2.2e5, c=0.0), unloaded_radius=0.31)


def test_fiala_pure_lateral_closed_form_stiffness_and_saturation():
    tire, Fz, mu, Ca = _fiala(), 4000.0, 1.0, 6.0e4
    alpha = np.radians(np.linspace(-20, 20, 81))
    Fy = tire.slip_forces(0.0, alpha, Fz).Fy
    H = 1 - Ca * np.abs(np.tan(alpha)) / (3 * mu * Fz)
    expect = np.where(H > 0, -mu * Fz * (1 - H ** 3) * np.sign(alpha), -mu * Fz * np.sign(alpha))
    np.testing.assert_allclose(Fy, expect, rtol=1e-12, atol=1e-9)
    h = 1e-7
    slope = (tire.slip_forces(0.0, h, Fz).Fy - tire.slip_forces(0.0, -h, Fz).Fy) / (2 * h)
    assert slope == pytest.approx(-Ca, rel=1e-6)
    assert tire.slip_forces(0.0, 1.0, Fz).Fy == pytest.approx(-mu * Fz)
    kx = (tire.slip_forces(h, 0.0, Fz).Fx - tire.slip_forces(-h, 0.0, Fz).Fx) / (2 * h)
    assert kx == pytest.approx(8.0e4, rel=1e-6)
    assert tire.slip_forces(0.9, 0.0, Fz).Fx == pytest.approx(1.1 * Fz)
    # brush pneumatic trail a/3 at small slip, a = half chord at the static deflection
    rho = Fz / 2.2e5
    a = math.sqrt(2 * 0.31 * rho - rho ** 2)
    small = tire.slip_forces(0.0, 1e-6, Fz)
    assert small.Mz / -small.Fy == pytest.approx(a / 3, rel=1e-5)


def test_fiala_combined_slip_stays_inside_friction_ellipse():
    tire, Fz = _fiala(), 3000.0
    k = np.linspace(-1, 1, 41)[:, None]
    a = np.linspace(-0.5, 0.5, 41)[None, :]
    f = tire.slip_forces(k, a, Fz)
    util = np.hypot(f.Fx / (1.1 * Fz), f.Fy / (1.0 * Fz))
    assert util.max() <= 1 + 1e-12 and util.max() > 0.999
    assert np.all(np.abs(f.Fx) <= np.abs(tire.slip_forces(k, 0.0, Fz).Fx) + 1e-9)


def test_fiala_tir_file_with_umin_umax(tmp_path):
    text = """[MDI_HEADER]
FILE_TYPE = 'tir'
[UNITS]
LENGTH = 'meter'
FORCE = 'newton'
ANGLE = 'radian'
[MODEL]
PROPERTY_FILE_FORMAT = 'FIALA'
USE_MODE = 12
[DIMENSION]
UNLOADED_RADIUS = 0.31
WIDTH = 0.2
[VERTICAL]
VERTICAL_STIFFNESS = 200000
VERTICAL_DAMPING = 100
FNOMIN = 4000
[PARAMETER]
CSLIP = 80000
CALPHA = 60000
UMIN = 0.7
UMAX = 1.0
RELAX_LENGTH_X = 0.1
RELAX_LENGTH_Y = 0.3
"""
    path = tmp_path / "fiala.tir"
    path.write_text(text)
    tire = tire_from_file(path, model="fiala")
    assert tire.relaxation and tire.relaxation_lengths(4000.0) == (0.1, 0.3)
    Fz = 4000.0
    # comprehensive slip S = 0.5 (sliding, since C_alpha*0.5 >> 3 mu Fz): mu = 1 - 0.3*0.5
    assert tire.slip_forces(0.0, math.atan(0.5), Fz).Fy == pytest.approx(-0.85 * Fz)
    assert tire.slip_forces(0.0, math.atan(2.0), Fz).Fy == pytest.approx(-0.7 * Fz)
    with pytest.raises(InputError, match="PAC2002"):
        tire_from_file(path, model="pac2002")
    bad = tmp_path / "fiala_bad.tir"
    bad.write_text(text.replace("CALPHA = 60000", "CALFA = 60000"))
    lineno = text.splitlines().index("CALPHA = 60000") + 1
    with pytest.raises(InputError, match=rf"fiala_bad.tir, line {lineno}.*CALFA.*CALPHA"):
        tire_from_file(bad, model="fiala")


def test_fiala_from_pac2002_file_uses_mf_stiffness_at_fnomin():
    r = raw_numbers(SAMPLE)
    ref = closed_form(r, r["FNOMIN"])
    tire = tire_from_file(SAMPLE, model="fiala")
    assert tire.params.c_alpha == pytest.approx(abs(ref["Ky"]))
    assert tire.params.c_slip == pytest.approx(ref["Kx"])
    assert tire.params.mu_y * r["FNOMIN"] == pytest.approx(ref["Dy"])


# ----------------------------------------------------------------- sample tyre
def test_sample_tyre_is_complete_and_plausible():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        tire = tire_from_file(SAMPLE)
    r = raw_numbers(SAMPLE)
    ref = closed_form(r, r["FNOMIN"])
    # published passenger-car ranges (Pacejka 2006, ch. 1/4): ~15-25 N/deg per 100 kg of load
    ky_per_deg = abs(ref["Ky"]) * math.pi / 180
    assert 800 < ky_per_deg < 1600
    assert 0.9 < ref["Dx"] / r["FNOMIN"] < 1.3 and 0.9 < ref["Dy"] / r["FNOMIN"] < 1.3
    sk, sa = tire.relaxation_lengths(r["FNOMIN"])
    assert 0.1 < sk < 0.6 and 0.2 < sa < 0.8
    assert tire.relaxation and tire.mf.use_mode == 4 and not tire.vertical.is_linear
