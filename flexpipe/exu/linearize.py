"""Linearization of an assembled Exudyn car at its current state (Adams/Linear's step).

For a constrained multibody system ``M q'' + C_q^T lambda = f(q, q')``, ``g(q) = 0``, at
an equilibrium (or a steady motion) the linear equations in the constraints' nullspace
``N`` (``C_q N = 0``, ``q = q_0 + N y``) are

    N^T M N y'' + N^T D N y' + N^T K N y = 0,
    K = -d(f - C_q^T lambda)/dq,   D = -df/dq'.

The term ``(C_q^T lambda)_q`` is the geometric stiffness of the constraint forces: a
preloaded linkage (a spring acting through links and joints) changes its rate with it.
Exudyn's own ``ComputeLinearizedSystem`` leaves it out; here ``K`` and ``D`` are central
differences of Exudyn's ODE2 right-hand side and of its constraint Jacobian, with the
multipliers ``lambda`` of the current state fitted by least squares to ``C_q^T lambda =
f`` (its residual says how far the state is from equilibrium).  ``M`` is Exudyn's mass
matrix.  :mod:`flexpipe.vehicle.linear` adds the tyres and solves the eigenproblem;
``tests/test_linear.py`` checks the result against the nonlinear run.
"""

from __future__ import annotations

from dataclasses import dataclass

import exudyn as exu
import numpy as np

#: central-difference steps for coordinates (m or rad or modal) and velocities
EPS_Q, EPS_V = 1e-7, 1e-6


@dataclass(frozen=True)
class Linearized:
    """Linear ODE2 equations of an Exudyn system at one state (all ``n`` coordinates).

    ``M``, ``K``, ``D`` (n, n): mass, stiffness (incl. the constraint forces' geometric
    stiffness) and damping; ``C`` (m, n) the constraint Jacobian; ``N`` (n, k) an
    orthonormal basis of its nullspace; ``q``, ``v`` the state's coordinates and
    velocities; ``lam`` the constraint multipliers; ``residual_N`` the largest entry of
    ``f - C^T lam`` (the force out of balance, N or N m, 0 at an equilibrium).
    """

    M: np.ndarray
    K: np.ndarray
    D: np.ndarray
    C: np.ndarray
    N: np.ndarray
    q: np.ndarray
    v: np.ndarray
    lam: np.ndarray
    residual_N: float


class _Access:
    """Exudyn's ODE2 right-hand side and constraint Jacobian at chosen coordinates."""

    def __init__(self, mbs):
        self.mbs = mbs
        self.sd = mbs.systemData
        self.ss = exu.SimulationSettings()
        # no solution file: Exudyn's default writes solution/coordinatesSolution.txt into
        # the working directory when a solver is initialized
        self.ss.solution.file.write = False
        self.ss.solution.sensors.active = False
        self.solver = exu.MainSolverImplicitSecondOrder()
        # Exudyn's solver initialization (and ComputeLinearizedSystem) copies the
        # initial configuration into the current one: the state to linearize at is kept
        # and put back (a car run to a steady state is not at its initial state)
        here = self.sd.GetSystemState(exu.ConfigurationType.Current)
        self.solver.InitializeSolver(mbs, self.ss)
        self.sd.SetSystemState(here, configuration=exu.ConfigurationType.Current)
        self.n = self.solver.GetODE2size()
        self.m = self.solver.GetAEsize()

    def set(self, q, v) -> None:
        self.sd.SetODE2Coordinates([float(x) for x in q])
        self.sd.SetODE2Coordinates_t([float(x) for x in v])

    def rhs(self) -> np.ndarray:
        self.solver.ComputeODE2RHS(self.mbs)
        return np.array(self.solver.GetSystemResidual(), dtype=float)[: self.n].copy()

    def jacobian_ae(self) -> np.ndarray:
        """C_q (m, n): Exudyn adds it to the system Jacobian, so that is zeroed first."""
        size = self.n + self.m
        self.solver.SetSystemJacobian(np.zeros((size, size)))
        self.solver.ComputeJacobianAE(self.mbs, 1.0, 0.0, 1.0, False)
        J = np.asarray(self.solver.GetSystemJacobian(), dtype=float)
        return J[self.n:, : self.n].copy()

    def mass(self) -> np.ndarray:
        """Exudyn's mass matrix at the current state (``ComputeLinearizedSystem`` takes
        the initial configuration and makes it the current one: both are put back)."""
        cur, init = exu.ConfigurationType.Current, exu.ConfigurationType.Initial
        here, start = self.sd.GetSystemState(cur), self.sd.GetSystemState(init)
        self.sd.SetSystemState(here, configuration=init)
        try:
            return np.asarray(self.mbs.ComputeLinearizedSystem(self.ss)[0], dtype=float)
        finally:
            self.sd.SetSystemState(start, configuration=init)
            self.sd.SetSystemState(here, configuration=cur)


def linearize(mbs, *, external=None, follow=None, eps_q: float = EPS_Q,
              eps_v: float = EPS_V, rank_tol: float = 1e-10) -> Linearized:
    """Linear equations of ``mbs`` (assembled, its current configuration the state).

    Parameters
    ----------
    mbs : exudyn MainSystem
    external : callable, optional
        ``external() -> (n,)``: generalized forces the caller applies itself at the current
        configuration (they enter the multipliers' fit only; the caller adds their
        derivatives).
    follow : callable, optional
        ``follow() -> None``: sets the loads that follow the configuration (e.g. a drive
        torque about a wheel's spin axis) from Exudyn's current coordinates, as a run's
        step sets them; called at every perturbed configuration, so that their
        derivatives enter ``K`` (Exudyn's own loads are fixed vectors).
    eps_q, eps_v : float
        Central-difference steps.
    rank_tol : float
        Singular values of ``C`` below ``rank_tol`` times the largest span the nullspace.

    Returns
    -------
    Linearized
    """
    acc = _Access(mbs)
    sd = mbs.systemData
    q0 = np.array(sd.GetODE2Coordinates(), dtype=float)
    v0 = np.array(sd.GetODE2Coordinates_t(), dtype=float)
    n = acc.n
    acc.set(q0, v0)
    M = acc.mass()
    f0 = acc.rhs() + (external() if external is not None else 0.0)
    C0 = acc.jacobian_ae()
    lam = np.linalg.lstsq(C0.T, f0, rcond=None)[0]
    residual = float(np.abs(f0 - C0.T @ lam).max())
    K = np.empty((n, n))
    D = np.empty((n, n))
    for j in range(n):
        cols = []
        for sgn in (1.0, -1.0):
            q = q0.copy()
            q[j] += sgn * eps_q
            acc.set(q, v0)
            if follow is not None:
                follow()
            cols.append(acc.rhs() - acc.jacobian_ae().T @ lam)
        K[:, j] = -(cols[0] - cols[1]) / (2.0 * eps_q)
        rates = []
        for sgn in (1.0, -1.0):
            v = v0.copy()
            v[j] += sgn * eps_v
            acc.set(q0, v)
            rates.append(acc.rhs())
        D[:, j] = -(rates[0] - rates[1]) / (2.0 * eps_v)
    acc.set(q0, v0)
    if follow is not None:
        follow()
    _, s, Vt = np.linalg.svd(C0)
    rank = int(np.count_nonzero(s > rank_tol * s[0])) if s.size else 0
    N = Vt[rank:].T.copy()
    return Linearized(M=M, K=K, D=D, C=C0, N=N, q=q0, v=v0, lam=lam, residual_N=residual)


def steady_translation(mbs, velocity, *, keep=()) -> None:
    """Make the current velocities those of a steady motion: every rigid node translating
    with ``velocity`` (3,) without turning, every other coordinate at rest except those
    of the nodes ``keep`` (e.g. the wheels' spin).  A run reaches its steady state only
    up to decaying transients, and a law with a kink at zero relative velocity (a
    dual-rate damper) has no single slope there: at zero it has the mean of its two."""
    sd = mbs.systemData
    v = np.array(sd.GetODE2Coordinates_t(), dtype=float)
    keep = {int(k) for k in keep}
    for node, sl in node_slices(mbs).items():
        if node in keep:
            continue
        v[sl] = 0.0
        if str(mbs.GetNode(node).get("nodeType", "")).startswith("RigidBody"):
            v[sl.start:sl.start + 3] = velocity
    sd.SetODE2Coordinates_t([float(x) for x in v])


def node_slices(mbs) -> dict:
    """``{node: slice}`` of every node's ODE2 coordinates in the system vector."""
    out = {}
    for i in range(mbs.systemData.NumberOfNodes()):
        if "Ground" in str(mbs.GetNode(i).get("nodeType", "")):
            continue
        size = np.size(mbs.GetNodeOutput(i, exu.OutputVariableType.Coordinates,
                                         configuration=exu.ConfigurationType.Reference))
        if size:
            start = mbs.GetNodeODE2Index(i)
            out[i] = slice(start, start + size)
    return out


def start_from_initial(mbs) -> None:
    """Make the initial configuration (a settled start) the current one."""
    sd = mbs.systemData
    sd.SetSystemState(sd.GetSystemState(exu.ConfigurationType.Initial),
                      configuration=exu.ConfigurationType.Current)


def hold_tires(system, Q0, *, release_spin: bool) -> None:
    """Tyre elements of ``system`` as the constant generalized forces ``Q0`` (4, 8); with
    ``release_spin`` no torque on the spin coordinates (no brake)."""
    mbs = system.mbs
    zero = np.zeros((8, 8))
    for i, elem in enumerate(system.tire_elem):
        mbs.SetObjectParameter(elem, "dampingMatrix", zero)
        mbs.SetObjectParameter(elem, "stiffnessMatrix", zero)
        mbs.SetObjectParameter(elem, "forceVector", [float(x) for x in Q0[i]])
        if release_spin:
            mbs.SetLoadParameter(system.load_spin[i], "load", 0.0)


def coordinate_derivatives(mbs, columns, fn, *, eps_q: float = EPS_Q,
                           eps_v: float = EPS_V, rates_only: bool = False):
    """Central differences of ``fn() -> (p,)`` with respect to the current coordinates and
    velocities at the ODE2 indices ``columns``: ``(dfn/dq, dfn/dv)``, each (p, len);
    ``rates_only``: by the velocities only (``dfn/dq`` is None).  The state is restored
    afterwards."""
    sd = mbs.systemData
    q0 = np.array(sd.GetODE2Coordinates(), dtype=float)
    v0 = np.array(sd.GetODE2Coordinates_t(), dtype=float)
    dq, dv = [], []
    kinds = ((eps_v, dv, 1),) if rates_only else ((eps_q, dq, 0), (eps_v, dv, 1))
    for j in columns:
        for eps, out, which in kinds:
            vals = []
            for sgn in (1.0, -1.0):
                q, v = q0.copy(), v0.copy()
                (q, v)[which][j] += sgn * eps
                sd.SetODE2Coordinates(list(q))
                sd.SetODE2Coordinates_t(list(v))
                vals.append(np.asarray(fn(), dtype=float))
            out.append((vals[0] - vals[1]) / (2.0 * eps))
    sd.SetODE2Coordinates(list(q0))
    sd.SetODE2Coordinates_t(list(v0))
    return (None if rates_only else np.array(dq).T), np.array(dv).T


def object_node(mbs, obj) -> int:
    """The node of a single-node object."""
    return int(mbs.GetObject(obj)["nodeNumber"])


def node_reference(mbs, node) -> np.ndarray:
    """A node's reference coordinates."""
    return np.atleast_1d(np.asarray(mbs.GetNodeOutput(
        node, exu.OutputVariableType.Coordinates,
        configuration=exu.ConfigurationType.Reference), dtype=float))
