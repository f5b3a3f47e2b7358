"""Shared kinematics of the flat shell elements :mod:`shell_tri3` and :mod:`shell_quad4`.

Each element is treated in its own flat local frame ``(e1, e2, n)``:

* **frame** - triangles: ``e1`` along edge 1-2, ``n`` the triangle normal.  Quads:
  ``n`` is the normal of the two diagonals (the mean plane of a warped quad),
  ``e1`` the mean direction of edges 1-2 and 4-3 projected onto that plane.
* **warping** - the corners of a warped quad lie at heights ``h_a`` (alternately
  ``+h``/``-h``) above the mean plane.  The flat element is built on the projected
  corners and joined to the true nodes by rigid offsets ``u_p = u + theta x (-h n)``,
  which keeps rigid-body motion strain-free (the same idea as the MSC Nastran warping
  correction).  A quad whose ``|h| / sqrt(area)`` exceeds :data:`WARP_LIMIT` is rejected.
* **local DOF** - per node ``u, v, w, theta_x, theta_y, theta_z`` (rotation-vector
  components).  Through-thickness kinematics ``u(z) = z theta_y``, ``v(z) = -z theta_x``,
  i.e. section rotations ``beta_x = theta_y``, ``beta_y = -theta_x``.
* **drilling** - both families use an Allman-type membrane, in which the drilling
  rotation ``theta_z`` shapes the in-plane field (mid-side displacements), plus a
  penalty ``1/2 sum_a k_d (theta_z,a - omega_a)^2`` tying it to the rotation
  ``omega = (dv/dx - du/dy) / 2`` of that field at each corner (Hughes-Brezzi type,
  ``k_d = alpha G t area / n_nodes``, ``alpha`` set per family).  The penalty vanishes
  for rigid rotation and constant strain, so it spoils neither rigid modes nor the
  membrane patch test.
* **mass** - consistent (quad: bilinear, 2x2 Gauss; triangle: linear) translational
  mass ``rho t`` and rotary inertia ``rho t^3 / 12`` on all three rotations (the drilling
  share is negligible, ``t^2 / 12`` of the in-plane inertia, and keeps M definite).
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem._element import BadElements

DOFS_PER_NODE = 6
#: transverse shear correction factor of Reissner-Mindlin plates
SHEAR_FACTOR = 5.0 / 6.0
#: largest accepted quad warp, max corner distance from the mean plane / sqrt(area)
#: (0.1 twists opposite edges by about 23 degrees)
WARP_LIMIT = 0.1
#: elements per vectorized sub-batch inside a family call (keeps temporaries in cache)
SUB_BATCH = 2048


def _unit(v):
    n = np.linalg.norm(v, axis=-1, keepdims=True)
    return v / np.where(n > 0, n, 1.0), n[..., 0]


def local_frame(X: np.ndarray):
    """Local frames of a batch of flat (or mildly warped) shell elements.

    Parameters
    ----------
    X : ndarray, shape (ne, nn, 3)
        Node coordinates, ``nn`` = 3 (triangle) or 4 (quad).

    Returns
    -------
    R : ndarray, shape (ne, 3, 3)
        Rows ``e1, e2, n``; local = ``R @ global``.
    xy : ndarray, shape (ne, nn, 2)
        In-plane local coordinates of the nodes (projected onto the mean plane).
    h : ndarray, shape (ne, nn)
        Height of the nodes above the mean plane (zero for triangles).
    """
    nn = X.shape[1]
    c = X.mean(axis=1)
    if nn == 3:
        a = X[:, 1] - X[:, 0]
        b = X[:, 2] - X[:, 0]
        n, two_area = _unit(np.cross(a, b))
        e1 = a
        size2 = np.maximum(np.einsum("ei,ei->e", a, a), np.einsum("ei,ei->e", b, b))
    else:
        d1 = X[:, 2] - X[:, 0]
        d2 = X[:, 3] - X[:, 1]
        n, two_area = _unit(np.cross(d1, d2))
        e1 = X[:, 1] + X[:, 2] - X[:, 0] - X[:, 3]
        size2 = np.maximum(np.einsum("ei,ei->e", d1, d1), np.einsum("ei,ei->e", d2, d2))
    bad = ~(two_area > 1e-10 * size2)
    if bad.any():
        raise BadElements(np.flatnonzero(bad), "degenerate (zero area or collinear nodes)")
    e1 = e1 - np.einsum("ei,ei->e", e1, n)[:, None] * n
    e1, _ = _unit(e1)
    e2 = np.cross(n, e1)
    R = np.stack([e1, e2, n], axis=1)
    loc = np.einsum("eij,eaj->eai", R, X - c[:, None, :])
    h = loc[..., 2]
    if nn == 4:
        warp = np.abs(h).max(axis=1) / np.sqrt(0.5 * two_area)
        h = np.where((warp > 1e-10)[:, None], h, 0.0)  # round-off of flat quads
        bad = warp > WARP_LIMIT
        if bad.any():
            raise BadElements(
                np.flatnonzero(bad),
                f"warped (out-of-plane corner distance up to {warp.max():.3g} x "
                f"sqrt(area), limit {WARP_LIMIT}; split them into triangles or remesh)",
            )
    else:
        h = np.zeros_like(h)
    return R, loc[..., :2], h


def plane_stress(E, nu, t):
    """Membrane rigidity matrices ``t * C`` (ne, 3, 3), Voigt xx, yy, xy (engineering)."""
    f = E * t / (1 - nu**2)
    C = np.zeros(np.shape(E) + (3, 3))
    C[:, 0, 0] = C[:, 1, 1] = f
    C[:, 0, 1] = C[:, 1, 0] = f * nu
    C[:, 2, 2] = f * (1 - nu) / 2
    return C


def bending_rigidity(E, nu, t):
    """Plate bending rigidity matrices ``t^3 / 12 * C`` (ne, 3, 3)."""
    return plane_stress(E, nu, t) * (t**2 / 12.0)[:, None, None]


def membrane_B(dN: np.ndarray) -> np.ndarray:
    """Membrane strain rows (..., 3, 2 nn) from shape gradients dN (..., nn, 2)."""
    nn = dN.shape[-2]
    B = np.zeros(dN.shape[:-2] + (3, 2 * nn))
    B[..., 0, 0::2] = dN[..., 0]
    B[..., 1, 1::2] = dN[..., 1]
    B[..., 2, 0::2] = dN[..., 1]
    B[..., 2, 1::2] = dN[..., 0]
    return B


def curvature_B(dN: np.ndarray) -> np.ndarray:
    """Curvature rows (..., 3, 3 nn) on DOF ``w, theta_x, theta_y`` per node."""
    nn = dN.shape[-2]
    B = np.zeros(dN.shape[:-2] + (3, 3 * nn))
    B[..., 0, 2::3] = dN[..., 0]            # beta_x,x = theta_y,x
    B[..., 1, 1::3] = -dN[..., 1]           # beta_y,y = -theta_x,y
    B[..., 2, 2::3] = dN[..., 1]
    B[..., 2, 1::3] = -dN[..., 0]
    return B


def btdb(B, D, w):
    """``sum_g w_g B_g^T D B_g`` for B (ne, ng, nr, nd), D (ne, nr, nr), w (ne, ng)."""
    ne, ng, nr, nd = B.shape
    DB = np.matmul(D[:, None], B) * w[:, :, None, None]
    return np.matmul(B.reshape(ne, ng * nr, nd).transpose(0, 2, 1), DB.reshape(ne, ng * nr, nd))


def add_drilling(Km: np.ndarray, omega: np.ndarray, k_drill: np.ndarray) -> np.ndarray:
    """Add the drilling penalty ``1/2 sum_a k_d (theta_z,a - omega_a)^2`` to a membrane matrix.

    ``Km`` (ne, 3 nn, 3 nn) acts on ``u, v, theta_z`` per node; ``omega`` (ne, nn, 3 nn)
    gives, in the same DOF, the in-plane rotation ``(v,x - u,y) / 2`` of the membrane
    field at each node ``a``.
    """
    nn = omega.shape[1]
    g = -omega.copy()
    g[:, np.arange(nn), 3 * np.arange(nn) + 2] += 1.0
    return Km + np.matmul(g.transpose(0, 2, 1), g) * k_drill[:, None, None]


def combine(Km: np.ndarray, Kb: np.ndarray) -> np.ndarray:
    """Local 6-DOF element matrix from membrane and plate parts.

    Parameters
    ----------
    Km : (ne, 3 nn, 3 nn)
        Membrane stiffness (incl. drilling) on ``u, v, theta_z`` per node.
    Kb : (ne, 3 nn, 3 nn)
        Bending + transverse shear stiffness on ``w, theta_x, theta_y`` per node.
    """
    ne, nm, _ = Km.shape
    nn = nm // 3
    node = np.arange(nn)
    im = (6 * node[:, None] + np.array([0, 1, 5])).ravel()
    ib = (6 * node[:, None] + 2 + np.arange(3)).ravel()
    K = np.zeros((ne, 6 * nn, 6 * nn))
    K[:, im[:, None], im] = Km
    K[:, ib[:, None], ib] = Kb
    return K


def consistent_mass(NN, rho, t):
    """Local 6-DOF mass (ne, 6 nn, 6 nn) from ``NN = int N_a N_b dA`` (ne, nn, nn)."""
    ne, nn, _ = NN.shape
    diag = np.concatenate([np.repeat((rho * t)[:, None], 3, axis=1),
                           np.repeat((rho * t**3 / 12.0)[:, None], 3, axis=1)], axis=1)
    M = np.zeros((ne, nn, 6, nn, 6))
    for c in range(6):
        M[:, :, c, :, c] = NN * diag[:, c, None, None]
    return M.reshape(ne, 6 * nn, 6 * nn)


def to_global(K: np.ndarray, R: np.ndarray, h: np.ndarray, *,
              isotropic: bool = False) -> np.ndarray:
    """Apply the warping offsets and rotate local element matrices to global axes.

    ``isotropic``: every 3x3 node block of ``K`` is a multiple of the identity (the
    shell mass), which rotation leaves unchanged; only warped elements are transformed.
    """
    ne, nd, _ = K.shape
    nn = nd // 6
    warped = np.any(h != 0, axis=1)
    if isotropic:
        if warped.any():
            K = K.copy()
            K[warped] = to_global(K[warped], R[warped], h[warped])
        return K
    if warped.any():
        K = K.copy()
        node = 6 * np.arange(nn)
        # u_p = u - h theta_y, v_p = v + h theta_x  (columns, then rows)
        K[:, :, node + 4] -= h[:, None, :] * K[:, :, node + 0]
        K[:, :, node + 3] += h[:, None, :] * K[:, :, node + 1]
        K[:, node + 4, :] -= h[:, :, None] * K[:, node + 0, :]
        K[:, node + 3, :] += h[:, :, None] * K[:, node + 1, :]
    # K <- T^T K T with T = blockdiag(R, ..., R): right then left, as batched 3x3 matmuls
    KR = np.matmul(K.reshape(ne, nd, 2 * nn, 3), R[:, None])
    out = np.empty_like(K)
    np.matmul(R.transpose(0, 2, 1)[:, None], KR.reshape(ne, 2 * nn, 3, nd),
              out=out.reshape(ne, 2 * nn, 3, nd))
    return out


def rigidities(E, nu, t, bend, lam):
    """Membrane ``C_m`` (ne, 3, 3), bending ``D`` (ne, 3, 3) and shear ``G t`` (ne,).

    ``lam`` is None (isotropic: plane stress from ``E, nu, t``, bending scaled by
    ``bend``) or a laminate ``(A, D, Gt)`` from :mod:`flexpipe.fem.laminate`.
    """
    if lam is None:
        return (plane_stress(E, nu, t), bending_rigidity(E, nu, t) * bend[:, None, None],
                E / (2 * (1 + nu)) * t)
    return lam


def material_angle(R: np.ndarray, ref: np.ndarray, theta: np.ndarray) -> np.ndarray:
    """Angle (rad) of the material x axis from the element x axis ``e1``: ``theta`` plus,
    where ``ref`` (ne, 3) is finite, the angle of ``ref`` projected onto the element
    plane (global Z instead when ``ref`` is within 0.1 degree of the normal, as Abaqus)."""
    phi = np.array(theta, dtype=float, copy=True)
    has = np.isfinite(ref).all(axis=1)
    if has.any():
        v = np.einsum("eij,ej->ei", R[has], ref[has])
        along_n = np.hypot(v[:, 0], v[:, 1]) < 1.75e-3 * np.linalg.norm(v, axis=1)
        if along_n.any():
            v[along_n] = R[has][along_n][:, :, 2]
        phi[has] += np.arctan2(v[:, 1], v[:, 0])
    return phi


def oriented(lam, R):
    """Laminate ``(A, D, Gt[, ref, theta])`` turned into each element's axes."""
    if lam is None or len(lam) == 3:
        return lam
    from flexpipe.fem.laminate import rotate_batch

    A, D, Gt, ref, theta = lam
    phi = material_angle(R, ref, theta)
    if not phi.any():
        return A, D, Gt
    return rotate_batch(A, phi), rotate_batch(D, phi), Gt


def in_sub_batches(fn, geometry, E, nu, rho, t, *, bending=1.0, laminate=None,
                   size: int = SUB_BATCH):
    """Run ``fn(R, xy, h, E, nu, rho, t, bending, lam) -> (K, M)`` over sub-batches.

    ``bending`` scales the plate bending rigidity (Nastran PSHELL ``12I/T^3`` times
    ``E(MID2) / E(MID1)``; 0 = membrane only).  Element matrices are written into
    preallocated outputs, so the temporaries stay small (a few MB) whatever the batch
    size handed over by the assembler.
    """
    ne, nn = geometry[1].shape[:2]
    E, nu, rho, t, bending = (np.broadcast_to(np.asarray(v, dtype=float), (ne,))
                              for v in (E, nu, rho, t, bending))
    K = np.empty((ne, 6 * nn, 6 * nn))
    M = np.empty((ne, 6 * nn, 6 * nn))
    for s in range(0, ne, size):
        sl = slice(s, s + size)
        lam = None if laminate is None else tuple(np.asarray(a)[sl] for a in laminate)
        K[sl], M[sl] = fn(*(g[sl] for g in geometry), E[sl], nu[sl], rho[sl], t[sl],
                          bending[sl], lam)
    return K, M


def offset_heights(h: np.ndarray, zoffset) -> np.ndarray:
    """Heights of the nodes above the element's mid-surface: warping ``h`` minus the
    shell offset ``zoffset`` (Nastran ZOFFS: mid-surface at ``node + zoffs n``)."""
    if zoffset is None:
        return h
    z = np.asarray(zoffset, dtype=float).reshape(-1)
    return h - z[:, None] if np.any(z) else h
