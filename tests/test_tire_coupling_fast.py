"""The compiled tyre corrector/predictor (flexpipe.vehicle._tire_coupling_fast) against
the NumPy reference (:class:`flexpipe.vehicle.tire_coupling.ImplicitTires` with the
compiled groups switched off), which drives the NumPy tyre model.

Both must agree to rounding over a sequence of steps on random wheel states, with and
without relaxation, for one tyre on all wheels, two tyres on one car (front and rear
groups: consecutive wheels, read and written as slices; crossed groups: gathered and
scattered by index), mirrored wheels, a lifted wheel and a wheel at standstill.
"""

from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.tires import _fast, tire_from_file
from flexpipe.vehicle.tire_coupling import ImplicitTires

ROOT = Path(__file__).resolve().parents[1]
TIR = sorted(ROOT.glob("tires/*.tir"))

pytestmark = pytest.mark.skipif(not _fast.enabled() or not TIR, reason="numba or .tir")


def _kin(rng, r0):
    n = 4
    C = np.c_[rng.normal(size=(n, 2)), r0 * (0.9 + 0.08 * rng.random(n))]
    C[0, 2] = 2.0 * r0  # a lifted wheel
    s = np.c_[0.05 * rng.normal(size=n), np.ones(n), 0.05 * rng.normal(size=n)]
    v = np.c_[rng.uniform(-3.0, 40.0, n), rng.normal(size=n), 0.2 * rng.normal(size=n)]
    v[1] = 0.0  # standstill
    return {"C": C, "s": s, "v": v, "w": rng.normal(size=(n, 3)),
            "omega": v[:, 0] / r0 * (1.0 + 0.1 * rng.normal(size=n)),
            "h_road": 0.01 * rng.normal(size=n),
            "n_road": np.c_[0.05 * rng.normal(size=(n, 2)), np.ones(n)]}


#: tyre ("f" front, "r" rear) per wheel and the wheel groups expected (a slice for
#: consecutive wheels, else the index list)
LAYOUTS = {
    "one_tyre": ("ffff", [slice(0, 4)]),  # one group holding every wheel
    "front_rear": ("ffrr", [slice(0, 2), slice(2, 4)]),
    "crossed": ("frfr", [[0, 2], [1, 3]]),
    "mixed": ("frrf", [[0, 3], slice(1, 3)]),
}


def _pair(relaxation, *, layout="front_rear"):
    """Fast and reference tyre sets for a layout of :data:`LAYOUTS`."""
    front = tire_from_file(TIR[0], relaxation=relaxation)
    rear = tire_from_file(TIR[-1], relaxation=relaxation)
    if rear is front or len(TIR) == 1:
        rear = tire_from_file(TIR[0], relaxation=relaxation)
    which, groups = LAYOUTS[layout]
    tires = [front if c == "f" else rear for c in which]
    mirror = np.array([False, True, False, True])
    fast, ref = ImplicitTires(tires, mirror), ImplicitTires(tires, mirror)
    ref.compiled = set()
    assert len(fast.compiled) == len(groups)
    assert [ix if isinstance(ix, slice) else ix.tolist() for _, ix in fast.groups] == groups
    return fast, ref, front.unloaded_radius


@pytest.mark.parametrize("layout", list(LAYOUTS))
@pytest.mark.parametrize("relaxation", [True, False])
def test_compiled_steps_equal_the_numpy_reference(relaxation, layout):
    rng = np.random.default_rng(7)
    fast, ref, r0 = _pair(relaxation, layout=layout)
    h = 2e-3
    for _ in range(5):
        kin = _kin(rng, r0)
        ahead = 0.01 * rng.normal(size=4)
        a, b = fast.correct(kin, h), ref.correct(kin, h)
        for k in ("Fx", "Fy", "Fz", "force"):
            np.testing.assert_allclose(a[k], b[k], rtol=1e-10, atol=1e-8)
        kin_ahead = dict(kin, n_road=kin["n_road"] + 0.01 * rng.normal(size=(4, 3)))
        p, q = fast.predict(kin_ahead, h, ahead), ref.predict(kin_ahead, h, ahead)
        for k in ("F0", "Dv", "dw", "A", "r", "moment", "S"):
            scale = max(np.abs(getattr(q, k)).max(), 1.0)
            np.testing.assert_allclose(getattr(p, k), getattr(q, k), rtol=0,
                                       atol=1e-7 * scale, err_msg=k)
        # the tyre element's input: the force rows (as the fields above) and the own
        # moment's rows, each to its own scale
        for x, y in zip(p.lin6, q.lin6, strict=True):
            for rows in (slice(0, 3), slice(3, 6)):
                np.testing.assert_allclose(x[:, rows], y[:, rows], rtol=0,
                                           atol=1e-7 * max(np.abs(y[:, rows]).max(), 1.0))
        for key in fast.state:
            np.testing.assert_allclose(fast.state[key].kappa, ref.state[key].kappa,
                                       rtol=1e-10, atol=1e-12)
            np.testing.assert_allclose(fast.state[key].tan_alpha, ref.state[key].tan_alpha,
                                       rtol=1e-10, atol=1e-12)
    # the states did move: the test compares more than the initial zeros
    assert not relaxation or any(np.abs(s.kappa).max() > 1e-4 for s in fast.state.values())


def test_compiled_path_names_a_bad_spin_axis():
    fast, _, r0 = _pair(True)
    kin = _kin(np.random.default_rng(1), r0)
    kin["s"][2] = 0.0
    with pytest.raises(InputError, match="spin_axis must be non-zero"):
        fast.correct(kin, 2e-3)
    with pytest.raises(InputError, match="spin_axis must be non-zero"):
        fast.predict(kin, 2e-3, np.zeros(4))


def _rot(rng, n):
    """Random rotation matrices (n, 3, 3) near the identity."""
    from scipy.spatial.transform import Rotation

    return Rotation.from_rotvec(0.3 * rng.normal(size=(n, 3))).as_matrix()


def test_compiled_applied_force_equals_the_numpy_reference():
    """The force the integrator applied at the end of a step (the linearization carried to
    the new state), compiled against ``tire_coupling.applied_force_reference``."""
    from types import SimpleNamespace

    from flexpipe.vehicle._tire_coupling_fast import applied_force
    from flexpipe.vehicle.tire_coupling import TireStep, applied_force_reference

    rng = np.random.default_rng(7)
    n = 4

    def state():
        R = _rot(rng, n)
        return SimpleNamespace(wheel_w=rng.normal(size=(n, 3)), wheel_v=rng.normal(size=(n, 3)),
                               wheel_p=rng.normal(size=(n, 3)), wheel_R=R)

    st0, st = state(), state()
    ts = TireStep(F0=rng.normal(size=(n, 3)), Dv=rng.normal(size=(n, 3, 3)),
                  dw=rng.normal(size=(n, 3)), A=rng.normal(size=(n, 3)),
                  r=rng.normal(size=(n, 3)), moment=np.zeros((n, 3)),
                  spin_axis=st0.wheel_R[:, :, 1], S=rng.normal(size=(n, 3, 3)),
                  lin6=())  # the tyre element's input: not read by the applied force
    om0, om = rng.normal(size=n), rng.normal(size=n)
    ref = applied_force_reference((ts, st0, om0), st, st.wheel_R[:, :, 1], om)
    got = applied_force(ts.F0, ts.Dv, ts.dw, ts.A, ts.S, ts.r, ts.spin_axis, st0.wheel_w,
                        st0.wheel_v, om0, st0.wheel_p[:, 2], st0.wheel_R, st.wheel_R[:, :, 1],
                        st.wheel_w, st.wheel_v, om, st.wheel_p[:, 2], st.wheel_R)
    np.testing.assert_allclose(got, ref, rtol=1e-12, atol=1e-12)
    assert np.abs(ref - ts.F0).max() > 0.1  # every term moved the force
