"""Bulk node states (flexpipe.exu._node_state) against Exudyn's own node outputs.

The Python step reads the body frame and the wheel carriers from one bulk read of the
system's coordinates; here that read must equal ``GetNodeOutput`` (position, velocity,
rotation matrix, angular velocity, coordinates and rates) on a car that has been driven
over a rough road, so every Euler parameter and rate is away from its reference.
"""

import exudyn as exu
import numpy as np
import pytest

import flexpipe as fp
from flexpipe.exu import _node_state
from flexpipe.roads.generators import iso8608

OV = exu.OutputVariableType


@pytest.fixture(scope="module")
def driven_system():
    import flexpipe.exu.timeloop as tl

    cap = {}
    orig = tl.run

    def run(system, step, **kw):
        cap["system"] = system
        return orig(system, step, **kw)

    tl.run = run
    try:
        fp.simulate("cars/sedan_linkage.toml", road=iso8608("D", 60.0, 0.05, seed=3),
                    speed=15.0, t_end=0.3, body="rigid", initial_rates=(0.2, -0.1, 0.3))
    finally:
        tl.run = orig
    return cap["system"]


@pytest.mark.parametrize("kernel", ["compiled", "numpy"])
def test_bulk_read_equals_node_outputs(driven_system, kernel):
    s = driven_system
    mbs = s.mbs
    reader = _node_state.NodeReader(mbs, list(s.wheel_node) + [s.body_node], s.spin_node)
    if kernel == "numpy":
        reader.kernel = _node_state.node_states_numpy
    (p, v, R, w, c, ct), spin = reader.read()
    nodes = list(s.wheel_node) + [s.body_node]
    g = mbs.GetNodeOutput
    for i, n in enumerate(nodes):
        np.testing.assert_allclose(p[i], g(n, OV.Position), rtol=0, atol=1e-12)
        np.testing.assert_allclose(v[i], g(n, OV.Velocity), rtol=0, atol=1e-12)
        np.testing.assert_allclose(R[i], np.reshape(g(n, OV.RotationMatrix), (3, 3)),
                                   rtol=0, atol=1e-12)
        np.testing.assert_allclose(w[i], g(n, OV.AngularVelocity), rtol=0, atol=1e-12)
        np.testing.assert_allclose(c[i], g(n, OV.Coordinates), rtol=0, atol=1e-15)
        np.testing.assert_allclose(ct[i], g(n, OV.Coordinates_t), rtol=0, atol=1e-15)
    np.testing.assert_allclose(spin, np.ravel([g(n, OV.Coordinates_t) for n in s.spin_node]),
                               rtol=0, atol=1e-15)
    # the state is away from its reference: the test would see a wrong formula
    assert np.abs(w).max() > 1e-3 and np.abs(c[:, 3:]).max() > 1e-4


def test_reader_refuses_nodes_it_cannot_read(driven_system):
    s = driven_system
    with pytest.raises(ValueError, match="expected RigidBodyEP"):
        _node_state.NodeReader(s.mbs, [s.spin_node[0]])
    with pytest.raises(ValueError, match="expected 1D"):
        _node_state.NodeReader(s.mbs, [], [s.wheel_node[0]])
