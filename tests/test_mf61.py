"""Magic Formula 6.1 / 6.2 tyres (flexpipe.tires.mf61) against an independent evaluation.

Reference: ``tests/data/mf61_reference.csv``, 972 points (3 pressures x 3 loads x 3
cambers x 6 slip ratios x 6 slip angles) of the sample MF 6.1 tyre evaluated by a scalar
transliteration of MFeval.jl (the Julia port of MATLAB MFeval, the toolbox checked against
TNO's MF-Tyre), written apart from flexpipe's code; TyreDyn, a second Python MF 6.x code
run unmodified, agrees with it to rounding on Fx, My, the slip stiffnesses and the
relaxation lengths everywhere, and on Fy and Mx at nominal pressure or zero camber (the
file's header says where and why the two codes differ).  Besides: the compiled kernel
against the NumPy model at a non-nominal pressure, and the errors of bad pressures.
"""

from __future__ import annotations

import io
import re
from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.tires import SlipState, _fast, read_tir, tire_from_file
from flexpipe.tires.contact import TireModel
from tests._carfiles import absolute_text

ROOT = Path(__file__).resolve().parents[1]
MF61 = ROOT / "tires" / "sedan_205_55R16_mf61.tir"
MF52 = ROOT / "tires" / "sedan_205_55R16.tir"
REF = Path(__file__).parent / "data" / "mf61_reference.csv"
OUTPUTS = ("Fx_n", "Fy_n", "Mz_nm", "Mx_nm", "My_nm", "Kya_n_per_rad", "Kxk_n",
           "sigma_kappa_m", "sigma_alpha_m")


def reference():
    text = "".join(ln for ln in REF.read_text().splitlines(keepends=True)
                   if not ln.startswith("#"))
    return np.genfromtxt(io.StringIO(text), delimiter=",", names=True)


def ours(tire, d):
    f = tire.mf.forces(d["kappa"], d["alpha_rad"], d["Fz_n"], d["gamma_rad"], vx=16.7)
    kx, ky = tire.mf.slip_stiffness(d["Fz_n"], d["gamma_rad"])
    sk, sa = tire.mf.relaxation_lengths(d["Fz_n"], d["gamma_rad"])
    return dict(zip(OUTPUTS, (f.Fx, f.Fy, f.Mz, f.Mx, f.My, ky, kx, sk, sa), strict=True))


@pytest.mark.parametrize("pressure", [190000.0, 230000.0, 270000.0])
def test_forces_moments_and_relaxation_lengths_match_the_mfeval_reference(pressure):
    """Every output within 1e-6 of its largest magnitude (measured: Fx, Fy, Mx <= 6e-11,
    Mz 6e-8 from MFeval's 1e-6 m/s speed guard in cos(alpha'), the rest to rounding)."""
    d = reference()
    d = d[d["p_pa"] == pressure]
    assert len(d) == 324
    got = ours(tire_from_file(MF61, pressure=pressure), d)
    for name in OUTPUTS:
        ref = d[name]
        np.testing.assert_allclose(got[name], ref, rtol=0.0,
                                   atol=1e-6 * np.abs(ref).max(), err_msg=name)


def test_the_pressure_moves_the_forces_as_the_reference_does():
    """Not a test that cannot fail at one pressure: between 190 and 270 kPa the reference
    cornering stiffness falls by 17.7 %, and so does flexpipe's."""
    d = reference()
    lo, hi = (d[(d["p_pa"] == p) & (d["Fz_n"] == 4000.0) & (d["gamma_rad"] == 0.0)
                & (d["kappa"] == 0.0) & (d["alpha_rad"] == 0.01)] for p in (190000.0, 270000.0))
    ratio_ref = float(hi["Kya_n_per_rad"][0] / lo["Kya_n_per_rad"][0])
    assert ratio_ref == pytest.approx(0.823, abs=1e-3)
    ky = [float(tire_from_file(MF61, pressure=p).mf.slip_stiffness(4000.0)[1])
          for p in (190000.0, 270000.0)]
    assert ky[1] / ky[0] == pytest.approx(ratio_ref, rel=1e-12)


@pytest.mark.skipif(not _fast.enabled(), reason="numba not installed")
@pytest.mark.parametrize("pressure", [175000.0, 300000.0])
def test_compiled_kernel_equals_the_numpy_model_off_nominal_pressure(pressure):
    tire = tire_from_file(MF61, pressure=pressure)
    rng = np.random.default_rng(7)
    n = 16
    C = np.c_[rng.normal(size=(n, 2)), tire.unloaded_radius * (0.9 + 0.08 * rng.random(n))]
    s = np.c_[0.05 * rng.normal(size=n), np.ones(n), 0.05 * rng.normal(size=n)]
    v = np.c_[rng.uniform(1.0, 40.0, n), rng.normal(size=n), 0.1 * rng.normal(size=n)]
    omega = v[:, 0] / tire.unloaded_radius * (1.0 + 0.1 * rng.normal(size=n))
    kw = dict(road_height=0.0, mirror=rng.random(n) > 0.5,
              state=SlipState(0.05 * rng.normal(size=n), 0.05 * rng.normal(size=n)), dt=1e-3)
    fast = tire.wheel_forces(C, s, omega, v, **kw)
    ref = TireModel.wheel_forces(tire, C, s, omega, v, **kw)
    for f in ("force", "moment", "Fx", "Fy", "Fz", "Mx", "My", "Mz"):
        b = getattr(ref, f)
        np.testing.assert_allclose(getattr(fast, f), b, rtol=1e-10,
                                   atol=1e-9 * (np.abs(b).max() + 1.0), err_msg=f)
    np.testing.assert_allclose(fast.state.kappa, ref.state.kappa, rtol=1e-10, atol=1e-12)


def test_the_mf61_sample_is_the_mf52_sample_at_nominal_pressure_in_pure_slip():
    """The sample MF 6.1 file writes the MF 5.2 sample's slip curves in MF 6.1 terms: at its
    nominal pressure, zero camber and a small slip angle (tan a = a) the pure-slip Fx, Fy
    and the slip stiffnesses are the MF 5.2 tyre's."""
    t61, t52 = tire_from_file(MF61), tire_from_file(MF52)
    k = np.linspace(-0.3, 0.3, 13)
    np.testing.assert_allclose(t61.mf.fx0(k, 4000.0), t52.mf.fx0(k, 4000.0), rtol=1e-12)
    a = np.linspace(-0.01, 0.01, 5)
    np.testing.assert_allclose(t61.mf.fy0(a, 4000.0), t52.mf.fy0(a, 4000.0), rtol=2e-4,
                               atol=1e-9)
    for x, y in zip(t61.mf.slip_stiffness(3000.0), t52.mf.slip_stiffness(3000.0), strict=True):
        assert float(x) == pytest.approx(float(y), rel=1e-12)


# ------------------------------------------------------------------------ bad input
def test_a_pressure_outside_the_fit_range_names_file_range_and_key():
    with pytest.raises(InputError) as exc:
        tire_from_file(MF61, pressure=400000.0)
    msg = str(exc.value)
    assert str(MF61) in msg and "pressure" in msg and "150000 .. 320000 Pa" in msg


def test_a_pressure_for_an_mf52_tyre_is_an_error():
    with pytest.raises(InputError, match="Magic Formula 5.2 fit.*no inflation pressure"):
        tire_from_file(MF52, pressure=230000.0)


@pytest.mark.parametrize("bad", [0.0, -1.0, "high", float("nan")])
def test_a_bad_pressure_value_is_refused_before_reading(bad):
    with pytest.raises(InputError, match="pressure"):
        tire_from_file(MF61, pressure=bad)


@pytest.mark.parametrize("key", ["PCFX3", "PCFY1", "LATERAL_STIFFNESS"])
def test_a_structural_value_that_is_no_number_names_line_and_key(tmp_path, key):
    """A damaged [STRUCTURAL] value ('0.3  PCFX3 = 0.3', text run together) raised a raw
    ValueError when the MF 6.1 pressure terms read it (found by damaging the sample at
    random); a carcass stiffness that is no number was taken as absent."""
    lines = MF61.read_text().splitlines()
    n = next(i for i, s in enumerate(lines) if s.split("=")[0].strip() == key)
    lines[n] = lines[n].replace("=", "= 0.3  junk  ", 1).split("$")[0]
    path = tmp_path / "damaged.tir"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(InputError, match=rf"damaged\.tir, line {n + 1}, key '{key}': "
                                         rf"\[STRUCTURAL\] {key} must be a number"):
        tire_from_file(path)


def test_pressure_terms_without_operating_conditions_are_an_error(tmp_path):
    text = re.sub(r"\[OPERATING_CONDITIONS\]\n(.*\n){2}", "", MF61.read_text())
    path = tmp_path / "no_pressure.tir"
    path.write_text(text)
    assert read_tir(path).pressures is None
    with pytest.raises(InputError) as exc:
        tire_from_file(path)
    assert str(path) in str(exc.value) and "INFLPRES and NOMPRES" in str(exc.value)


def test_pky4_zero_is_an_error_naming_line_and_key(tmp_path):
    text = MF61.read_text().replace("PKY4                     = 2.0", "PKY4 = 0")
    path = tmp_path / "pky4.tir"
    path.write_text(text)
    with pytest.raises(InputError) as exc:
        tire_from_file(path)
    line = next(i for i, ln in enumerate(text.splitlines(), 1) if ln.startswith("PKY4"))
    assert f"line {line}" in str(exc.value) and "PKY4" in str(exc.value)


# ------------------------------------------------------------------------ vertical spring
def _without_load_curve(tmp_path, extra: str):
    text = re.sub(r"\[DEFLECTION_LOAD_CURVE\]\n\{pen +fz\}\n( *[0-9.]+ +[0-9]+\n)+", "",
                  MF61.read_text())
    text = text.replace("PFZ1                     = 0.7", "PFZ1 = 0.7\n" + extra)
    path = tmp_path / "vertical.tir"
    path.write_text(text)
    return path


@pytest.mark.parametrize("pressure, factor", [(230000.0, 1.0), (276000.0, 1.14)])
def test_q_fz2_spring_against_the_mf_tyre_law(tmp_path, pressure, factor):
    """MF-Tyre's Fz = Fz0 (Q_FZ1 rho/R0 + Q_FZ2 (rho/R0)^2), Q_FZ1 from Cz at the nominal
    load, written out here: the spring is that law, its stiffness at the nominal load is
    Cz; 20 % over NOMPRES both are 1 + PFZ1 0.2 = 1.14 times as much."""
    path = _without_load_curve(tmp_path, "Q_FZ2 = 15.0")
    props = read_tir(path)
    assert "DEFLECTION_LOAD_CURVE" not in props.tables
    tire = tire_from_file(path, pressure=pressure)
    r0, fz0, cz = 0.316, 4000.0, 220000.0
    q1 = np.sqrt((cz * r0 / fz0) ** 2 - 4.0 * 15.0)
    d = np.linspace(0.005, 0.045, 30)
    law = factor * fz0 * (q1 * d / r0 + 15.0 * (d / r0) ** 2)
    np.testing.assert_allclose(tire.vertical.spring_force(d), law, rtol=1e-12)
    d0 = tire.vertical.static_deflection(factor * fz0)
    k_nom = (tire.vertical.spring_force(d0 + 1e-6) - tire.vertical.spring_force(d0 - 1e-6)) / 2e-6
    assert k_nom == pytest.approx(factor * cz, rel=1e-6)
    C = np.c_[np.zeros((4, 2)), r0 - np.array([0.005, 0.015, 0.03, 0.045])]
    kw = dict(road_height=0.0)
    args = (C, [0.0, 1.0, 0.0], 50.0, [16.7, 0.0, 0.0])
    np.testing.assert_allclose(tire.wheel_forces(*args, **kw).Fz,
                               TireModel.wheel_forces(tire, *args, **kw).Fz, rtol=1e-12)


def test_unmodelled_mf6_vertical_terms_warn_naming_key_and_line(tmp_path):
    path = _without_load_curve(tmp_path, "Q_V2 = 0.04\nQ_FCY = 0.3")
    with pytest.warns(UserWarning, match=r"Q_V2 = 0\.04 \(line \d+\); Q_FCY = 0\.3") as rec:
        tire_from_file(path)
    assert any(str(path) in str(w.message) for w in rec)


# ------------------------------------------------------------------------ in a car
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"


def linkage_with(tmp_path, tire_line: str) -> Path:
    text = absolute_text(LINKAGE)
    old = f'tire = "{MF52}"'
    assert text.count(old) == 4
    path = tmp_path / "car.toml"
    path.write_text(text.replace(old, tire_line))
    return path


def test_a_car_on_the_mf61_sample_drives_as_on_the_mf52_sample(tmp_path):
    """The MF 6.1 sample writes the MF 5.2 sample's tyre (same slip curves at its nominal
    pressure, relaxation lengths equal at FNOMIN); the rigid linkage car over ISO class C
    at 70 km/h on either: every hub force within 5 % of its fluctuating part in x and y
    (measured 0.8-3.0 % at the 1.25 ms default step, 0.8-2.7 % at 1 ms: the MF 6.x camber
    and tan(alpha) terms) and 1.5 % in z (0.4-0.75 %, 0.4-0.7 %), after the start."""
    import flexpipe.exu  # noqa: F401  (Exudyn's module before exudyn)
    from flexpipe.scenarios.runner import _straight_road
    from flexpipe.vehicle import load_car, simulate

    road = _straight_road()
    runs = [simulate(load_car(p), road=road, speed=70 / 3.6, t_end=6.0, body="rigid",
                     output_step=0.0025)
            for p in (LINKAGE, linkage_with(tmp_path, f'tire = "{MF61}"'))]
    assert all(r.status == 0 for r in runs), [r.message for r in runs]
    sel = runs[0].t > 0.5
    for c in ("fl", "fr", "rl", "rr"):
        for a, tol in (("x", 0.05), ("y", 0.05), ("z", 0.015)):
            ref, got = (r[f"hub_{c}_{a}"][sel] for r in runs)
            fluct = np.sqrt(np.mean((ref - ref.mean()) ** 2))
            assert np.sqrt(np.mean((got - ref) ** 2)) < tol * fluct, (c, a)


def test_a_car_file_tire_pressure_reaches_the_tyre_and_is_checked(tmp_path):
    """``tire_pressure_Pa`` of a corner: the tyre's pressure (``flexpipe info`` shows it),
    its vertical stiffness times 1 + PFZ1 dpi; a value in bar, or one for an MF 5.2 tyre,
    is an error naming the key."""
    from flexpipe.vehicle import load_car
    from flexpipe.vehicle.describe import car_text
    from flexpipe.vehicle.simulation import _tires

    path = linkage_with(tmp_path, f'tire = "{MF61}"\ntire_pressure_Pa = 240000')
    assert "tyres: sedan_205_55R16_mf61.tir at 240 kPa;" in car_text(load_car(path))
    tires = _tires(load_car(path))
    assert all(t.mf.pressure == 240000.0 for t in tires)
    k0 = tire_from_file(MF61).vertical.k
    assert tires[0].vertical.k == pytest.approx(k0 * (1.0 + 0.7 * 10000 / 230000), rel=1e-12)
    # a sweep's override sets it on a car file without the key (docs/sweeps.md)
    plain = linkage_with(tmp_path, f'tire = "{MF61}"')
    over = load_car(plain, overrides={"corners.rl.tire_pressure_Pa": 250000.0})
    assert [t.mf.pressure for t in _tires(over)] == [230000.0, 230000.0, 250000.0, 230000.0]
    path = linkage_with(tmp_path, f'tire = "{MF61}"\ntire_pressure_Pa = 2.4')
    with pytest.raises(InputError, match=r"corners\.fl\.tire_pressure_Pa.*2\.4 Pa is not a "
                                         r"tyre pressure.*2\.3 bar = 230 kPa"):
        load_car(path)
    path = linkage_with(tmp_path, f'tire = "{MF52}"\ntire_pressure_Pa = 240000')
    with pytest.raises(InputError) as exc:
        _tires(load_car(path))
    assert "corners.fl.tire_pressure_Pa" in str(exc.value)
    assert "no inflation pressure" in str(exc.value)


def test_a_pressure_that_moves_the_ride_height_names_the_linkage_wheel_centre(tmp_path):
    """190 kPa (from 230) lowers the rear wheel centres 3.0 mm, over the 3 mm design
    ride-height tolerance: the error names the linkage's wheel-centre hardpoint, the
    pressure and the height to set (not the prismatic corner's key)."""
    import flexpipe.exu  # noqa: F401  (Exudyn's module before exudyn)
    from flexpipe.vehicle import load_car, simulate

    car = load_car(linkage_with(tmp_path, f'tire = "{MF61}"\ntire_pressure_Pa = 190000'))
    with pytest.raises(InputError) as exc:
        simulate(car, speed=10.0, t_end=0.1, body="rigid")
    msg = str(exc.value)
    assert "suspension.rear.hardpoints_m.wheel_center (+ location_m) z = 0.3013 m" in msg
    assert "at 190000 Pa" in msg and "set z to 0.2983" in msg
    assert "corners.rl.wheel_center_m" not in msg and "suspension.front" not in msg


def test_info_prints_the_tyre_over_its_pressure_range(capsys):
    """``flexpipe info`` on the MF 6.1 sample: at FNOMIN and 150 / 230 / 320 kPa the
    cornering stiffness ``PKY1 Fz0 (1 + PPY1 dpi) sin(PKY4 atan(1 / (PKY2 (1 + PPY2
    dpi))))``, slip stiffness ``Fz0 PKX1 (1 + PPX1 dpi + PPX2 dpi^2)``, ``mu_y = PDY1 (1 +
    PPY3 dpi + PPY4 dpi^2)`` and the vertical stiffness times ``1 + PFZ1 dpi``, written
    out here from the file's numbers."""
    import math

    from flexpipe.cli import main

    assert main(["info", str(MF61)]) == 0
    out = capsys.readouterr().out
    assert "Magic Formula 6.1 at 230 kPa (NOMPRES 230 kPa)" in out
    k0 = tire_from_file(MF61).vertical.k
    rows = re.findall(r"(\d+) kPa: cornering stiffness ([0-9.e+]+) N/deg, slip stiffness "
                      r"([0-9.e+]+) N, mu_y ([0-9.]+), vertical stiffness ([0-9.e+]+) N/m", out)
    assert [int(r[0]) for r in rows] == [150, 230, 320]
    for p, ky, kx, muy, cz in rows:
        d = (float(p) - 230.0) / 230.0
        want_ky = 18.0 * 4000.0 * (1 - 0.6 * d) * math.sin(
            2.0 * math.atan(1.0 / (2.0 * (1 - 0.07 * d)))) * math.pi / 180
        assert float(ky) == pytest.approx(want_ky, rel=1e-3)
        assert float(kx) == pytest.approx(4000.0 * 21.0 * (1 - 0.35 * d + 0.3 * d * d),
                                          rel=1e-3)
        assert float(muy) == pytest.approx(1.05 * (1 - 0.15 * d + 0.25 * d * d), abs=6e-4)
        assert float(cz) == pytest.approx(k0 * (1 + 0.7 * d), rel=1e-3)
