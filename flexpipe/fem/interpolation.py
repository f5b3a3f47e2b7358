"""Interpolation constraints (Nastran RBE3, Abaqus distributing coupling), exact.

Nastran's RBE3 makes the reference node's components ``REFC`` follow the weighted
least-squares rigid-body fit of the independent nodes' components ``Ci``:

``q_ref = argmin_q sum_i sum_{c in Ci} W_ic (u_ic - (G_i q)_c)^2``

with ``G_i = [I, -[r_i]x ; 0, I]`` the rigid motion of node ``i`` at ``r_i = x_i - x_ref``
and ``W = w_i`` for translations, ``w_i Lc^2`` for rotations (``Lc`` the mean distance of
the independent nodes from the reference node, as in MSC Nastran), i.e.
``q = A^-1 sum_i G_i^T W_i u_i``, ``A = sum_i G_i^T W_i G_i``.  Each REFC component of
the reference node is eliminated through that linear equation (no penalty), so a force
``F`` and moment ``M`` at the reference node are distributed to the independent nodes as
``f_i = W_i G_i A^-1 (F, M)`` - the RBE3 load distribution (forces proportional to the
weights for a load at the weighted centroid, moments as a linear force field).  The
reference node adds no stiffness: components of it not in REFC stay free.
"""

from __future__ import annotations

import numpy as np

from flexpipe.errors import ModelError


def _skew(r):
    return np.array([[0, -r[2], r[1]], [r[2], 0, -r[0]], [-r[1], r[0], 0]])


def rows(it, points: np.ndarray, node_ids=None):
    """Dependent rows of one interpolation constraint.

    Returns ``(ref_components, columns, coefficients)``: for each REFC component ``c``
    (0..5), the node-component pairs ``columns`` (k, 2) and the coefficients (len(REFC), k)
    with ``u_ref,c = coefficients[c] @ u[columns]``.
    """
    xr = points[it.ref]
    nodes = np.asarray(it.nodes, dtype=np.int64)
    r = points[nodes] - xr
    Lc = float(np.mean(np.linalg.norm(r, axis=1))) if len(nodes) else 0.0
    g_rows, w_rows, cols = [], [], []
    for k, nd in enumerate(nodes):
        comps = it.node_dofs[k] if it.node_dofs else "123"
        G = np.zeros((6, 6))
        G[:3, :3] = np.eye(3)
        G[:3, 3:] = -_skew(r[k])
        G[3:, 3:] = np.eye(3)
        for ch in comps:
            c = int(ch) - 1
            g_rows.append(G[c])
            w_rows.append(float(it.weights[k]) * (1.0 if c < 3 else max(Lc, 1e-300) ** 2))
            cols.append((int(nd), c))
    Gm = np.array(g_rows).reshape(-1, 6)
    W = np.array(w_rows)
    A = Gm.T @ (W[:, None] * Gm)
    ref = [int(ch) - 1 for ch in it.ref_dofs]
    lam, V = np.linalg.eigh(A)
    ok = lam > 1e-10 * max(lam.max(initial=0.0), 1e-300)
    Ainv = (V[:, ok] / lam[ok]) @ V[:, ok].T
    P = Ainv @ A                              # projector onto the determined directions
    name = f"node {int(node_ids[it.ref])}" if node_ids is not None else f"index {it.ref}"
    for c in ref:
        if abs(P[c, c] - 1.0) > 1e-8:
            raise ModelError(
                f"RBE3 {it.id}: reference {name} component {c + 1} is not determined by the "
                "independent nodes (too few nodes or components, e.g. rotations of "
                "collinear points); add independent nodes/components or drop it from REFC")
    coef = (Ainv @ (Gm.T * W))[ref]
    return ref, np.array(cols, dtype=np.int64).reshape(-1, 2), coef
