"""The compiled tyre (flexpipe.tires._fast) against the NumPy reference implementation.

Reference: :meth:`flexpipe.tires.contact.TireModel.wheel_forces` with
:meth:`flexpipe.tires.pac2002.MagicFormula.forces`, the vectorised code that the PAC2002
tests check against the model's closed forms.  Both must agree to rounding on random
states for every ``.tir`` file at hand, every USE_MODE, with and without relaxation,
mirrored wheels, lifted wheels, standstill and tilted roads.
"""

from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.tires import SlipState, _fast, tire_from_file
from flexpipe.tires.contact import TireModel

ROOT = Path(__file__).resolve().parents[1]
FILES = sorted({*ROOT.glob("tires/*.tir"), *(ROOT.parent / "shared" / "reference" / "tires")
                .glob("*.tir")})
#: the repository's own tyre (sorting FILES by path put a reference tyre without slip
#: relaxation first in checkouts whose path sorts after ../shared)
SAMPLE = ROOT / "tires" / "sedan_205_55R16.tir"
FIELDS = ("force", "moment", "contact_point", "frame", "Fx", "Fy", "Fz", "Mx", "My", "Mz",
          "kappa", "alpha", "gamma", "deflection", "deflection_rate")

pytestmark = pytest.mark.skipif(not _fast.enabled(), reason="numba not installed")


def _inputs(rng, n, r0):
    C = np.c_[rng.normal(size=(n, 2)), r0 * (0.9 + 0.08 * rng.random(n))]
    C[0, 2] = 2.0 * r0  # a lifted wheel
    s = np.c_[0.05 * rng.normal(size=n), np.ones(n), 0.05 * rng.normal(size=n)]
    v = np.c_[rng.uniform(-3.0, 40.0, n), rng.normal(size=n), 0.2 * rng.normal(size=n)]
    v[1] = 0.0  # standstill
    omega = v[:, 0] / r0 * (1.0 + 0.1 * rng.normal(size=n))
    kw = dict(road_height=0.01 * rng.normal(size=n),
              road_normal=np.c_[0.05 * rng.normal(size=(n, 2)), np.ones(n)],
              angular_velocity=rng.normal(size=(n, 3)), mirror=rng.random(n) > 0.5,
              mu_scale=rng.uniform(0.3, 1.0, n),
              state=SlipState(0.05 * rng.normal(size=n), 0.05 * rng.normal(size=n)), dt=2e-3)
    return C, s, omega, v, kw


@pytest.mark.parametrize("path", FILES, ids=lambda p: p.name)
@pytest.mark.parametrize("use_mode", [1, 2, 3, 4])
@pytest.mark.parametrize("relaxation", [True, False])
def test_compiled_wheel_forces_equal_the_numpy_model(path, use_mode, relaxation):
    tire = tire_from_file(path, use_mode=use_mode, relaxation=relaxation)
    rng = np.random.default_rng(use_mode + 10 * relaxation)
    C, s, omega, v, kw = _inputs(rng, 24, tire.unloaded_radius)
    fast = tire.wheel_forces(C, s, omega, v, **kw)
    ref = TireModel.wheel_forces(tire, C, s, omega, v, **kw)
    for f in FIELDS:
        a, b = getattr(fast, f), getattr(ref, f)
        np.testing.assert_allclose(a, b, rtol=1e-10, atol=1e-9 * (np.abs(b).max() + 1.0),
                                   err_msg=f)
    np.testing.assert_allclose(fast.state.kappa, ref.state.kappa, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(fast.state.tan_alpha, ref.state.tan_alpha, rtol=1e-10,
                               atol=1e-12)
    assert np.all(fast.Fz[0] == 0.0) and np.all(fast.force[0] == 0.0)  # lifted


def test_compiled_path_takes_single_wheels_and_no_state():
    tire = tire_from_file(SAMPLE)
    args = ([0.0, 0.0, 0.95 * tire.unloaded_radius], [0.0, 1.0, 0.0], 50.0, [15.0, 0.3, 0.0])
    fast = tire.wheel_forces(*args, road_height=0.0)
    ref = TireModel.wheel_forces(tire, *args, road_height=0.0)
    assert fast.state is None and ref.state is None
    np.testing.assert_allclose(fast.force, ref.force, rtol=1e-12)


def test_compiled_path_rejects_what_the_numpy_path_rejects():
    tire = tire_from_file(SAMPLE)
    with pytest.raises(InputError, match="spin_axis"):
        tire.wheel_forces([0.0, 0.0, 0.3], [0.0, 0.0, 0.0], 50.0, [15.0, 0.0, 0.0],
                          road_height=0.0)
    with pytest.raises(InputError, match="road_normal"):
        tire.wheel_forces([0.0, 0.0, 0.3], [0.0, 1.0, 0.0], 50.0, [15.0, 0.0, 0.0],
                          road_height=0.0, road_normal=[0.0, 0.0, np.nan])
    with pytest.raises(InputError, match="dt"):
        tire.wheel_forces([0.0, 0.0, 0.3], [0.0, 1.0, 0.0], 50.0, [15.0, 0.0, 0.0],
                          road_height=0.0, state=SlipState.zeros(1))


@pytest.mark.parametrize("compiled", [True, False])
def test_zero_step_reads_the_force_of_the_state_as_it_is(compiled):
    """dt = 0: the relaxed slips stay as given (the exact update at dt = 0 is the
    identity) and the force is the Magic Formula of those slips."""
    tire = tire_from_file(SAMPLE, relaxation=True)
    rng = np.random.default_rng(3)
    C, s, omega, v, kw = _inputs(rng, 8, tire.unloaded_radius)
    kw["dt"] = 0.0
    if compiled:
        out = tire.wheel_forces(C, s, omega, v, **kw)
    else:
        out = TireModel.wheel_forces(tire, C, s, omega, v, **kw)
    touch = out.Fz > 0
    assert touch.sum() >= 6
    np.testing.assert_allclose(out.state.kappa[touch], kw["state"].kappa[touch], rtol=1e-14)
    np.testing.assert_allclose(out.state.tan_alpha[touch], kw["state"].tan_alpha[touch],
                               rtol=1e-14)
    # Fx and Fy (not My) are independent of the contact speed given the slips
    sf = tire.slip_forces(out.kappa, out.alpha, out.Fz, out.gamma, mirror=kw["mirror"],
                          mu_scale=kw["mu_scale"])
    np.testing.assert_allclose(out.alpha[touch], np.arctan(kw["state"].tan_alpha[touch]),
                               rtol=1e-14)
    np.testing.assert_allclose(out.Fx, sf.Fx, rtol=1e-12, atol=1e-9)
    np.testing.assert_allclose(out.Fy, sf.Fy, rtol=1e-12, atol=1e-9)
