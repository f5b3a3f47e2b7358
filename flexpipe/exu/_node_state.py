"""Rigid-body node states from one bulk read of the system's coordinates.

The Python step of a car run needs the position, velocity, rotation matrix and angular
velocity of the body frame and the four wheel carriers.  Read with
``GetNodeOutput``, that is 32 calls into Exudyn and as many small arrays per step; read
here, it is two calls (``GetODE2Coordinates`` and its rates, every coordinate of the
system at once) and one compiled function over the nodes.  The formulas are Exudyn's for
a node with Euler parameters ``e`` (``NodeRigidBodyEP``): position = reference +
displacement, the rotation matrix of ``e`` and the global angular velocity ``G(e) e_t``
with ``G = 2 [-e1 e0 -e3 e2; -e2 e3 e0 -e1; -e3 -e2 e1 e0]``.
``tests/test_node_state.py`` checks them against ``GetNodeOutput`` on a running car.
"""

from __future__ import annotations

import numpy as np

from flexpipe.tires._fast import _jit
from flexpipe.tires._fast import enabled as jit_enabled


def node_states_numpy(q, qt, start, ref):
    """Reference formulation: ``(p, v, R, w, coords, coords_t)`` of the nodes whose seven
    coordinates (position, Euler parameters) start at ``start`` (n,) in the system's
    coordinate vectors ``q`` and ``qt``; ``ref`` (n, 7) their reference coordinates."""
    idx = np.asarray(start)[:, None] + np.arange(7)
    c, ct = q[idx], qt[idx]
    p = ref[:, :3] + c[:, :3]
    e = ref[:, 3:] + c[:, 3:]
    e0, e1, e2, e3 = e.T
    R = np.empty((len(start), 3, 3))
    R[:, 0, 0] = 1 - 2 * (e2 * e2 + e3 * e3)
    R[:, 0, 1] = 2 * (e1 * e2 - e3 * e0)
    R[:, 0, 2] = 2 * (e1 * e3 + e2 * e0)
    R[:, 1, 0] = 2 * (e1 * e2 + e3 * e0)
    R[:, 1, 1] = 1 - 2 * (e1 * e1 + e3 * e3)
    R[:, 1, 2] = 2 * (e2 * e3 - e1 * e0)
    R[:, 2, 0] = 2 * (e1 * e3 - e2 * e0)
    R[:, 2, 1] = 2 * (e2 * e3 + e1 * e0)
    R[:, 2, 2] = 1 - 2 * (e1 * e1 + e2 * e2)
    G = 2 * np.stack([np.stack([-e1, e0, -e3, e2], 1), np.stack([-e2, e3, e0, -e1], 1),
                      np.stack([-e3, -e2, e1, e0], 1)], 1)
    w = np.einsum("nij,nj->ni", G, ct[:, 3:])
    return p, ct[:, :3].copy(), R, w, c, ct


@_jit
def node_states(q, qt, start, ref):
    """Compiled :func:`node_states_numpy` (same arguments and results)."""
    n = start.shape[0]
    p, v, w = np.empty((n, 3)), np.empty((n, 3)), np.empty((n, 3))
    R = np.empty((n, 3, 3))
    c, ct = np.empty((n, 7)), np.empty((n, 7))
    for i in range(n):
        s = start[i]
        for k in range(7):
            c[i, k] = q[s + k]
            ct[i, k] = qt[s + k]
        for k in range(3):
            p[i, k] = ref[i, k] + c[i, k]
            v[i, k] = ct[i, k]
        e0, e1, e2, e3 = (ref[i, 3] + c[i, 3], ref[i, 4] + c[i, 4], ref[i, 5] + c[i, 5],
                          ref[i, 6] + c[i, 6])
        R[i, 0, 0] = 1 - 2 * (e2 * e2 + e3 * e3)
        R[i, 0, 1] = 2 * (e1 * e2 - e3 * e0)
        R[i, 0, 2] = 2 * (e1 * e3 + e2 * e0)
        R[i, 1, 0] = 2 * (e1 * e2 + e3 * e0)
        R[i, 1, 1] = 1 - 2 * (e1 * e1 + e3 * e3)
        R[i, 1, 2] = 2 * (e2 * e3 - e1 * e0)
        R[i, 2, 0] = 2 * (e1 * e3 - e2 * e0)
        R[i, 2, 1] = 2 * (e2 * e3 + e1 * e0)
        R[i, 2, 2] = 1 - 2 * (e1 * e1 + e2 * e2)
        d0, d1, d2, d3 = ct[i, 3], ct[i, 4], ct[i, 5], ct[i, 6]
        w[i, 0] = 2 * (-e1 * d0 + e0 * d1 - e3 * d2 + e2 * d3)
        w[i, 1] = 2 * (-e2 * d0 + e3 * d1 + e0 * d2 - e1 * d3)
        w[i, 2] = 2 * (-e3 * d0 - e2 * d1 + e1 * d2 + e0 * d3)
    return p, v, R, w, c, ct


class NodeReader:
    """Reads the states of a fixed list of Euler-parameter rigid nodes and 1-coordinate
    nodes of an assembled system (``mbs.Assemble()`` done) in one go.

    Parameters
    ----------
    mbs : exudyn MainSystem
    rigid_nodes : sequence of int
        Rigid-body nodes with Euler parameters (seven coordinates each).
    scalar_nodes : sequence of int
        Nodes with one coordinate (e.g. wheel spin), read as value and rate.
    """

    def __init__(self, mbs, rigid_nodes, scalar_nodes=()):
        self.mbs = mbs
        for n, kind in [(n, "RigidBodyEP") for n in rigid_nodes] + \
                [(n, "1D") for n in scalar_nodes]:
            got = mbs.GetNode(n)["nodeType"]
            if got != kind:  # the formulas below are those of these node types only
                raise ValueError(f"NodeReader: node {n} is a {got} node, expected {kind}")
        self.start = np.array([mbs.GetNodeODE2Index(n) for n in rigid_nodes], dtype=np.int64)
        self.ref = np.array([mbs.GetNodeParameter(n, "referenceCoordinates")
                             for n in rigid_nodes], dtype=float).reshape(-1, 7)
        self.scalar = np.array([mbs.GetNodeODE2Index(n) for n in scalar_nodes], dtype=np.int64)
        self.kernel = node_states if jit_enabled() else node_states_numpy

    def read(self):
        """``(p, v, R, w, coords, coords_t)`` of the rigid nodes and the rates (m,) of the
        scalar nodes, now."""
        sd = self.mbs.systemData
        q = np.asarray(sd.GetODE2Coordinates(), dtype=float)
        qt = np.asarray(sd.GetODE2Coordinates_t(), dtype=float)
        return self.kernel(q, qt, self.start, self.ref), qt[self.scalar]
