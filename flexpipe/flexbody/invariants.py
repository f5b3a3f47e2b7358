"""Mass properties and the FFRF inertia invariants of a modally reduced body.

Notation follows Exudyn's ``ObjectFFRFreducedOrder`` (Zwoelfer & Gerstmayr, "The
nodal-based floating frame of reference formulation with modal reduction", 2021):
``M_t`` is the mass matrix of the nodal translations (3 n x 3 n, node-major x, y, z),
``Psi`` (3 n x m) the translational elastic mode shapes, ``Phi_t = [I3; I3; ...]`` the
rigid translations, ``x_ref`` the stacked reference positions and ``~`` the stacked
skew-symmetric (cross-product) matrices, node by node and mode by mode.

How rotational DOF of shell and beam nodes enter
------------------------------------------------
* **Rigid-body mass, centre of mass and inertia** come from the *full* mass matrix
  (translations and nodal rotations, point masses with offsets and rotary inertia) via
  exact rigid-body vectors, so they are the mesh's exact values.  They are what Exudyn
  receives as ``mass``, ``centerOfMass`` and ``inertia``.
* **Mode shapes** given to Exudyn are the nodal translations only; the rotational rows
  are dropped (Exudyn's FFRF body has 3 DOF per mesh node).  The modal coupling
  invariants are built from the translational block ``M_t`` of the consistent mass
  matrix.  The rotary inertia of the shell/beam cross-sections therefore enters the
  rigid-body inertia exactly but is ignored in the (second-order) coupling terms
  between rotation of the frame and elastic deformation; for thin walls it is
  O((t / L)^2) of those terms.
* The reduced modal mass and stiffness (identity and ``diag(omega^2)``) are the full
  ``Psi^T M Psi`` and ``Psi^T K Psi`` including rotational DOF.
"""

from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np
import scipy.sparse as sp


@dataclass(frozen=True, eq=False)
class FFRFInvariants:
    """Constant FFRF terms of the elastic modes, in Exudyn's names.

    Attributes
    ----------
    mPsiTildePsi : ndarray, shape (3 m, m)
    mPsiTildePsiTilde : ndarray, shape (3 m, 3 m)
    mPhitTPsi : ndarray, shape (3, m)
    mPhitTPsiTilde : ndarray, shape (3, 3 m)
    mXRefTildePsi : ndarray, shape (3, m)
    mXRefTildePsiTilde : ndarray, shape (3, 3 m)
    """

    mPsiTildePsi: np.ndarray
    mPsiTildePsiTilde: np.ndarray
    mPhitTPsi: np.ndarray
    mPhitTPsiTilde: np.ndarray
    mXRefTildePsi: np.ndarray
    mXRefTildePsiTilde: np.ndarray

    def as_dict(self) -> dict:
        """Field name -> array."""
        return {f.name: getattr(self, f.name) for f in fields(self)}


def skew(v) -> np.ndarray:
    """Cross-product matrix ``S(v)`` with ``S(v) w = v x w``; ``v`` (..., 3)."""
    v = np.asarray(v, dtype=float)
    S = np.zeros(v.shape[:-1] + (3, 3))
    S[..., 0, 1], S[..., 0, 2] = -v[..., 2], v[..., 1]
    S[..., 1, 0], S[..., 1, 2] = v[..., 2], -v[..., 0]
    S[..., 2, 0], S[..., 2, 1] = -v[..., 1], v[..., 0]
    return S


def stacked_skew(U: np.ndarray) -> np.ndarray:
    """Exudyn's ``ComputeSkewMatrix``: (3 n, m) -> (3 n, 3 m), block (i, j) = S(U[i, :, j])."""
    U = np.asarray(U, dtype=float)
    n3, m = U.shape
    S = skew(U.reshape(n3 // 3, 3, m).transpose(0, 2, 1))  # (n, m, 3, 3)
    return S.transpose(0, 2, 1, 3).reshape(n3, 3 * m)


def rigid_body_vectors(nodes: np.ndarray, dofs_per_node: int) -> np.ndarray:
    """Six rigid-body displacement fields (n_dof, 6) about the origin.

    Columns: unit translations x, y, z, then unit small rotations about x, y, z
    (translations ``e_k x X``, and rotation DOF ``e_k`` when the nodes have them).
    """
    nodes = np.asarray(nodes, dtype=float)
    n = len(nodes)
    R = np.zeros((n, dofs_per_node, 6))
    R[:, 0:3, 0:3] = np.eye(3)
    R[:, 0:3, 3:6] = -skew(nodes)  # e_k x X = -S(X) e_k
    if dofs_per_node == 6:
        R[:, 3:6, 3:6] = np.eye(3)
    return R.reshape(n * dofs_per_node, 6)


def mass_properties(M, nodes: np.ndarray, dofs_per_node: int):
    """Exact rigid-body mass properties of a mass matrix over node-major DOF.

    Returns
    -------
    mass : float
    center_of_mass : ndarray (3,)
    inertia_com : ndarray (3, 3)
        Inertia tensor about the centre of mass, axes of the mesh.
    inertia_origin : ndarray (3, 3)
        Inertia tensor about the origin of the mesh coordinates.
    """
    R = rigid_body_vectors(nodes, dofs_per_node)
    return rigid_mass_properties(R.T @ (M @ R))


def rigid_mass_properties(MR: np.ndarray):
    """Mass, centre of mass, inertia about it and about the origin from the 6 x 6 rigid-body
    mass matrix ``R^T M R`` (translations x, y, z, rotations about x, y, z at the origin)."""
    MR = 0.5 * (np.asarray(MR, dtype=float) + np.asarray(MR, dtype=float).T)
    mass = float(np.mean(np.diag(MR)[:3]))
    # off-diagonal block: R_t^T M R_r = -m S(c)  (translation-rotation coupling)
    Sc = -MR[0:3, 3:6] / mass
    com = np.array([Sc[2, 1], Sc[0, 2], Sc[1, 0]])
    J0 = MR[3:6, 3:6]
    Jc = J0 - mass * (com @ com * np.eye(3) - np.outer(com, com))
    return mass, com, 0.5 * (Jc + Jc.T), J0


def translational_block(M, dofs_per_node: int):
    """The 3 n x 3 n block of ``M`` acting on nodal translations (sparse CSR)."""
    M = sp.csr_matrix(M)
    if dofs_per_node == 3:
        return M
    n = M.shape[0] // dofs_per_node
    idx = (np.arange(n)[:, None] * dofs_per_node + np.arange(3)).ravel()
    return sp.csr_matrix(M[idx][:, idx])


def ffrf_invariants(nodes: np.ndarray, Mt, Psi: np.ndarray) -> FFRFInvariants:
    """FFRF invariants of translational elastic modes ``Psi`` (3 n x m) with mass ``Mt``.

    Equivalent to Exudyn's ``ObjectFFRFreducedOrderInterface`` but vectorized: the
    stacked skew matrices are only formed once, as dense (3 n x 3 m) arrays.
    """
    nodes = np.asarray(nodes, dtype=float)
    Psi = np.asarray(Psi, dtype=float)
    n, m = len(nodes), Psi.shape[1]
    if m == 0:
        z = np.zeros
        return FFRFInvariants(z((0, 0)), z((0, 0)), z((3, 0)), z((3, 0)), z((3, 0)), z((3, 0)))
    Xt = skew(nodes).reshape(3 * n, 3)  # stacked S(x_i): (3 n, 3)
    Pt = stacked_skew(Psi)  # (3 n, 3 m)
    MPsi = Mt @ Psi
    MPt = Mt @ Pt
    phit_M = np.asarray(Mt.T @ np.tile(np.eye(3), (n, 1))).T  # Phi_t^T M: (3, 3 n)
    return FFRFInvariants(
        mPsiTildePsi=Pt.T @ MPsi,
        mPsiTildePsiTilde=Pt.T @ MPt,
        mPhitTPsi=phit_M @ Psi,
        mPhitTPsiTilde=phit_M @ Pt,
        mXRefTildePsi=Xt.T @ MPsi,
        mXRefTildePsiTilde=Xt.T @ MPt,
    )


#: largest cosine (mass metric) between an elastic mode and a rigid-body motion for which
#: a body counts as having mean-axis modes (constant inertia coupling, flexpipe.exu.inertia)
MAX_MEAN_AXIS_COSINE = 1e-2


def mean_axis_cosine(body, n_modes: int | None = None) -> tuple[float, int]:
    """Largest cosine, in the mass metric, between an elastic mode and a rigid-body motion.

    From the body's inertia invariants: per mode ``j`` with modal mass ``m_j``, the
    translation cosine ``|sum m Phi_j| / sqrt(mass m_j)`` and the rotation (about the
    centre of mass) cosine ``sqrt(v_j^T J_c^-1 v_j / m_j)`` with
    ``v_j = sum m (x - c) x Phi_j``, each maximised over the direction; translations
    and rotations about the centre of mass are mass-orthogonal, so the cosine of the
    angle between the mode and the six-dimensional rigid-body subspace is the root sum
    of their squares.

    Returns
    -------
    cosine : float
    mode : int
        Index (0-based, among the elastic modes) of the worst mode, -1 if there is none.
    """
    me = body.n_elastic if n_modes is None else int(n_modes)
    if me == 0:
        return 0.0, -1
    inv = body.invariants
    sel = slice(body.n_rigid, body.n_rigid + me)
    mj = np.diag(body.M[sel, sel])
    t = inv.mPhitTPsi[:, :me]
    Sc = skew(np.asarray(body.center_of_mass, dtype=float)[None])[0]
    v = -inv.mXRefTildePsi[:, :me] - Sc @ t
    cos_t = np.linalg.norm(t, axis=0) / np.sqrt(body.mass * mj)
    cos_r = np.sqrt(np.einsum("ij,ij->j", v, np.linalg.solve(body.inertia, v)) / mj)
    worst = np.hypot(cos_t, cos_r)
    j = int(np.argmax(worst))
    return float(worst[j]), j
