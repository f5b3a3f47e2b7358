"""Hub forces as outputs of the linearized car (:mod:`flexpipe.vehicle.linear`).

A run's hub force ``hub_<corner>_<x|y|z>`` is what the corner applies to the body through
its own mounts, in body axes: Newton's law of the corner's parts,

    h = R^T H,   H = F_tyre + sum m (g - a_cm) + sum F_link u_link,

with the tyre force at the contact point, the parts' centre-of-mass accelerations and the
pulls of the links to the rack and the anti-roll bars (tension ``F_link`` along
``u_link``), as :meth:`flexpipe.exu.linkage.LinkageModel.hub_forces` computes it.  Its
linearization about the state:

- the body's rotation ``R``, the links' directions and a spring link's force, by central
  differences of ``R(q)^T (H_0 + sum (F_link(q, v) u_link(q) - F_0 u_0))``;
- the tyre force, by the tyre's own derivatives (:mod:`flexpipe.vehicle.linear_tires`);
- ``m a_cm``, by the parts' momenta's velocity Jacobian times the accelerations of the
  linear model;
- a constraint link's tension, its multiplier: from the full linear equations
  ``M dq'' + K dq + D dq' - B s - U u + C^T dlambda = 0`` along the nullspace solution
  (least squares in ``C^T``; the right-hand side lies in its range).
"""

from __future__ import annotations

import numpy as np


def hub_rows(system, lin, *, N, A, Bx, K, D, B_slip, Ur, F_tire, T_d, R):
    """``C`` and ``D`` rows (12,) of ``hub_<corner>_<x|y|z>`` and their names.

    Parameters
    ----------
    system : LinkageCarSystem
        At the linearization state.
    lin : Linearized
        :func:`flexpipe.exu.linearize.linearize` of the state.
    N, A, Bx : ndarray
        Nullspace basis, state matrix and input matrix of the linear model.
    K, D, B_slip, Ur : ndarray
        Stiffness and damping over all coordinates (tyres included), the tyre forces by the
        slip states and by the road inputs (generalized, first ``size`` rows).
    F_tire : ndarray (4, 3)
        The tyre forces at the state (global).
    T_d : tuple
        Derivatives of the tyre force vectors (12 rows, global, wheel by wheel) by
        coordinates, velocities, slips and road inputs.
    R : ndarray (3, 3)
        The body's rotation at the state.
    """
    from flexpipe.exu.linearize import coordinate_derivatives

    model = system.linkage
    size = lin.q.size
    k = N.shape[1]
    n_w = F_tire.shape[0]
    H0 = model.hub_forces(F_tire)
    links0 = model.links_to_other()

    def frozen():  # R(q)^T H with the constraint links' tensions and the tyres held
        H = H0.copy()
        for (i, u, F, ae), (_, u0, F0, _) in zip(model.links_to_other(), links0,
                                                  strict=True):
            H[i] += (F0 if ae is not None else F) * u - F0 * u0
        return (H @ system.state(0.0).body_R).ravel()

    Pq, Pv = coordinate_derivatives(system.mbs, np.arange(size), frozen)
    _, Jm = coordinate_derivatives(system.mbs, np.arange(size),
                                   lambda: (model.corner_momenta() @ R).ravel(),
                                   rates_only=True)
    Rt = np.kron(np.eye(n_w), R.T)  # the tyre forces into body axes, wheel by wheel
    Tq, Tv, Ts, Tu = (Rt @ t for t in T_d)
    acc_x, acc_u = A[k:2 * k], Bx[k:2 * k]  # nullspace accelerations y''
    C = (np.hstack([(Pq + Tq) @ N, (Pv + Tv) @ N, Ts]) - (Jm @ N) @ acc_x)
    Dm = Tu - (Jm @ N) @ acc_u
    # the constraint links' tensions: C^T dlambda = -K dq - D dq' + B s + U u - M dq''
    ae = [(i, u, a) for i, u, _, a in links0 if a is not None]
    if ae:
        MN = lin.M @ N
        G_x = np.hstack([-K @ N, -D @ N, B_slip]) - MN @ acc_x
        G_u = Ur - MN @ acc_u
        P = np.linalg.pinv(lin.C.T)[[a for _, _, a in ae]]  # rows of the links' multipliers
        L_x, L_u = P @ G_x, P @ G_u
        for j, (i, u, _) in enumerate(ae):
            pull = R.T @ u  # body axes
            C[3 * i:3 * i + 3] += np.outer(pull, L_x[j])
            Dm[3 * i:3 * i + 3] += np.outer(pull, L_u[j])
    from flexpipe.vehicle.linear import CORNERS

    names = [f"hub_{c}_{ax}" for c in CORNERS[:n_w] for ax in "xyz"]
    return C, Dm, names
