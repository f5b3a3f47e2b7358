"""Rainflow counting against the ASTM E1049-85 worked example; Miner damage against the
closed form of Basquin's curve; car-file fatigue data."""

from __future__ import annotations

from collections import Counter

import numpy as np
import pytest

from flexpipe.durability.fatigue import (
    FatigueMaterial,
    damage_bound,
    miner_damage,
    rainflow_cycles,
    reversals,
)
from flexpipe.errors import InputError


def test_rainflow_astm_e1049_example():
    # ASTM E1049-85 (2017), section 5.4.4 and Table 4: the load history of Fig. 6(a)
    history = [-2, 1, -3, 5, -1, 3, -4, 4, -2]
    cyc = rainflow_cycles(history)
    counts = Counter()
    for rng, _, c in cyc:
        counts[float(rng)] += c
    assert dict(counts) == {3.0: 0.5, 4.0: 1.5, 6.0: 0.5, 8.0: 1.0, 9.0: 0.5}


def test_reversals_keep_the_rainflow_count():
    rng = np.random.default_rng(1)
    x = np.repeat(np.cumsum(rng.standard_normal(400)), 3)  # flat runs included
    a = rainflow_cycles(x)
    b = rainflow_cycles(reversals(x))
    np.testing.assert_allclose(sorted(map(tuple, a[:, [0, 2]])), sorted(map(tuple, b[:, [0, 2]])))


def test_miner_damage_of_constant_amplitude_equals_closed_form():
    mat = FatigueMaterial(sigma_f=1020e6, b=-0.138)
    amp, n_cycles = 150e6, 200
    t = np.linspace(0.0, n_cycles, 40 * n_cycles + 1)
    signal = 20e6 + amp * np.cos(2 * np.pi * t)  # mean stress is not corrected (Basquin)
    N = 0.5 * (amp / mat.sigma_f) ** (1.0 / mat.b)  # sigma_a = sigma_f (2N)^b solved for N
    d = miner_damage(signal, mat)
    assert d == pytest.approx(n_cycles / N, rel=1e-12)  # 400 half cycles, peak to peak


def test_endurance_limit_and_bound():
    mat = FatigueMaterial(sigma_f=1e9, b=-0.1, endurance_limit=100e6)
    x = 90e6 * np.sin(np.linspace(0, 20 * np.pi, 2001))
    assert miner_damage(x, mat) == 0.0
    mat0 = FatigueMaterial(sigma_f=1e9, b=-0.1)
    d = miner_damage(x, mat0)
    assert 0 < d <= damage_bound(x.max(), x.min(), len(reversals(x)), mat0)


def test_bad_material_is_named():
    with pytest.raises(InputError, match="b"):
        FatigueMaterial(sigma_f=1e9, b=0.1)


@pytest.mark.parametrize("value", ["0.2", "0.0"])
def test_car_file_fatigue_table_errors_name_file_and_key(tmp_path, value):
    from pathlib import Path

    from flexpipe.vehicle.spec import load_car

    root = Path(__file__).resolve().parents[1]
    text = (root / "cars" / "sedan.toml").read_text()
    text = text.replace("b = -0.138", f"b = {value}").replace('"../', f'"{root}/')
    path = tmp_path / "car.toml"
    path.write_text(text)
    with pytest.raises(InputError) as exc:
        load_car(path)
    msg = str(exc.value)
    assert str(path) in msg and "body.fatigue.b" in msg


def test_sample_car_fatigue_material():
    from pathlib import Path

    from flexpipe.vehicle.spec import load_car

    car = load_car(Path(__file__).resolve().parents[1] / "cars" / "sedan.toml")
    assert car.body.fatigue == FatigueMaterial(1020e6, -0.138, 0.0, "SAE 1015")


@pytest.mark.parametrize("seed", range(6))
def test_compiled_rainflow_equals_the_library(seed):
    """The compiled counter against :func:`rainflow.extract_cycles` (the reference), cycle
    for cycle: random walks with plateaus, repeated values, short and constant signals."""
    from flexpipe.durability import fatigue
    from flexpipe.tires import _fast

    if not _fast.enabled():
        pytest.skip("numba")
    rng = np.random.default_rng(seed)
    n = [2, 3, 5, 50, 400, 5000][seed]
    x = np.round(np.cumsum(rng.standard_normal(n)), 1)  # rounding makes equal neighbours
    if seed == 4:
        x = np.repeat(x, 3)  # plateaus
    for sig in (x, -x, np.zeros(7), np.array([1.0, 1.0, 2.0])):
        ref = fatigue._rainflow_library(sig)
        got = fatigue._rainflow_compiled(np.ascontiguousarray(sig, dtype=float))
        np.testing.assert_array_equal(got, ref)
    if n >= 400:  # long signals have many cycles to compare
        assert len(fatigue._rainflow_library(x)) > 50
