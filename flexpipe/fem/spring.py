"""Springs and dampers (Nastran CELAS1/2, CBUSH/PBUSH; Abaqus *SPRING, *CONNECTOR).

The reader computes the element matrices once, in global 6-DOF-per-node components, and
stores them in ``block.data`` (``"K"``, optional ``"B"`` for viscous damping); cells
``spring`` join two nodes (12 x 12), ``spring1`` tie one node to ground (6 x 6).

* **Scalar spring** (CELAS): ``k (g . u)^2`` with ``g = (e_a, -e_b)``, ``e`` the unit
  vector of the component ``C`` at the node, in the node's displacement system (``CD``).
* **Bush** (CBUSH): stiffness ``K1..K6`` along the axes of the element system; the
  spring sits at ``P = A + S (B - A)`` and both nodes reach it by rigid offsets, so the
  element is free of stress under rigid motion (Nastran's formulation):
  ``d = R (u_B - S(P - B)^T theta_B - u_A + ...)`` see :func:`bush`.
"""

from __future__ import annotations

import numpy as np

TYPE = "spring"
DOFS_PER_NODE = 6
#: properties come from ``block.data``, not from materials
FROM_DATA = True
#: the reader's matrices are symmetric bit for bit
SYMMETRIC = True


def matrices(X, *, K, **_):
    """Stiffness (from the block data) and zero mass."""
    K = np.asarray(K, dtype=float)
    return K, np.zeros_like(K)


def damping(X, *, B=None, K=None, **_):
    """Viscous damping matrices (zero when the block carries none)."""
    return np.zeros_like(np.asarray(K, dtype=float)) if B is None else np.asarray(B, float)


def unit_dof(frames: np.ndarray, comp: np.ndarray) -> np.ndarray:
    """6-vectors (n, 6) of component ``comp`` (0..5) in displacement frames (n, 3, 3)."""
    n = len(comp)
    e = np.zeros((n, 6))
    c = np.asarray(comp) % 3
    rot = np.asarray(comp) >= 3
    d = frames[np.arange(n), :, c]               # column c of each frame
    e[~rot, :3] = d[~rot]
    e[rot, 3:] = d[rot]
    return e


def scalar(k: np.ndarray, ea: np.ndarray, eb: np.ndarray | None = None) -> np.ndarray:
    """Scalar spring matrices ``k g g^T``: (n, 12, 12), or (n, 6, 6) when grounded."""
    g = ea if eb is None else np.hstack([ea, -eb])
    return np.asarray(k, dtype=float)[:, None, None] * g[:, :, None] * g[:, None, :]


def _skew(w):
    S = np.zeros(w.shape[:-1] + (3, 3))
    S[..., 0, 1], S[..., 0, 2], S[..., 1, 2] = -w[..., 2], w[..., 1], -w[..., 0]
    S[..., 1, 0], S[..., 2, 0], S[..., 2, 1] = w[..., 2], -w[..., 1], w[..., 0]
    return S


def bush(XA, XB, R, k, s=0.5):
    """CBUSH matrices (n, 12, 12) for diagonal values ``k`` (n, 6) in element axes.

    ``R`` (n, 3, 3): rows are the element axes in basic.  Relative motion at the spring
    point ``P``: ``u_B + theta_B x (P - B) - u_A - theta_A x (P - A)``, rotations
    ``theta_B - theta_A``; both in element axes.
    """
    XA, XB = np.asarray(XA, float), np.asarray(XB, float)
    n = len(XA)
    P = XA + np.asarray(s, float).reshape(-1, 1) * (XB - XA)
    D = np.zeros((n, 6, 12))
    eye = np.eye(3)
    D[:, :3, 0:3] = -eye
    D[:, :3, 3:6] = _skew(P - XA)               # -(theta x r) = r x theta = S(r) theta
    D[:, :3, 6:9] = eye
    D[:, :3, 9:12] = -_skew(P - XB)
    D[:, 3:, 3:6] = -eye
    D[:, 3:, 9:12] = eye
    T = np.zeros((n, 6, 6))
    T[:, :3, :3] = R
    T[:, 3:, 3:] = R
    Dl = np.matmul(T, D)
    out = np.einsum("eki,ek,ekj->eij", Dl, np.asarray(k, float), Dl)
    return 0.5 * (out + out.transpose(0, 2, 1))        # symmetric bit for bit


def grounded_bush(R, k):
    """CBUSH to ground (n, 6, 6): ``k`` (n, 6) along the element axes ``R`` (n, 3, 3)."""
    n = len(R)
    T = np.zeros((n, 6, 6))
    T[:, :3, :3] = R
    T[:, 3:, 3:] = R
    out = np.einsum("eki,ek,ekj->eij", T, np.asarray(k, float), T)
    return 0.5 * (out + out.transpose(0, 2, 1))
