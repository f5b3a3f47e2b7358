"""Element stress operators: linear maps from element DOF (global axes) to stresses.

For every element family, :func:`operators` returns ``S`` (ne, nc, nd) with
``sigma_e = S_e @ u_e``, where ``u_e`` is the element's DOF vector in global axes,
node-major (as the assembler orders it).  They are evaluated where the element is most
accurate and where durability codes report it:

* shells (quad4, tri3) - at the element centroid, in the element's local frame
  ``(e1, e2, n)`` (:func:`flexpipe.fem._shell.local_frame`): membrane stresses
  ``m_xx, m_yy, m_xy`` (force per thickness) and bending stresses at the top surface
  ``b_xx, b_yy, b_xy`` (``z = +t/2``); the top surface carries ``m + b``, the bottom
  ``m - b``.  Quad: Allman membrane field and bilinear plate curvature at the centre;
  triangle: Allman (LST) membrane and DKT curvature at the centroid.
* solids (tet4, tet10, hex8) - the six stresses ``xx, yy, zz, yz, xz, xy`` (global axes)
  at the element centroid (hex8: its incompatible modes have zero gradient there), and at
  the element's nodes (:func:`solid_nodal`; hex8 extrapolates from its Gauss points with
  the incompatible modes recovered).
* beams - at both ends, axial stress ``E du/dx`` and the extreme-fibre bending stresses
  ``E c_y v''`` (bending in the local x-y plane) and ``E c_z w''`` (x-z plane), with
  ``c = sqrt(3 I / A)`` (exact for a solid rectangle; a section carries no fibre
  distance); torsion is not included.

All operators are vectorised over the batch of elements.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _shell, _solid, beam3d, hex8, shell_quad4, shell_tri3, tet4, tet10

#: stress components per family kind
COMPONENTS = {
    "shell": ("m_xx", "m_yy", "m_xy", "b_xx", "b_yy", "b_xy"),
    "solid": ("xx", "yy", "zz", "yz", "xz", "xy"),
    "beam": ("axial_1", "bend_y_1", "bend_z_1", "axial_2", "bend_y_2", "bend_z_2"),
}
KIND = {"quad": "shell", "triangle": "shell", "tetra": "solid", "tetra10": "solid",
        "hexahedron": "solid", "line": "beam"}


def _plane_stress_unit(E, nu):
    """Plane-stress elasticity (ne, 3, 3) per unit thickness."""
    return _shell.plane_stress(E, nu, np.ones_like(E))


def _shell_global(Lm, Lb, R, h, E, nu, t):
    """Assemble membrane (ne,3,3nn on u,v,tz) and curvature (ne,3,3nn on w,tx,ty) rows
    into a global-axes operator (ne, 6, 6 nn), with warping offsets and rotation."""
    ne, _, k = Lm.shape
    nn = k // 3
    C = _plane_stress_unit(E, nu)
    node = 6 * np.arange(nn)
    im = (node[:, None] + np.array([0, 1, 5])).ravel()
    ib = (node[:, None] + np.array([2, 3, 4])).ravel()
    L = np.zeros((ne, 6, 6 * nn))
    L[:, :3, im] = np.matmul(C, Lm)
    L[:, 3:, ib] = np.matmul(C, Lb) * (0.5 * t)[:, None, None]
    warped = np.any(h != 0, axis=1)
    if warped.any():  # u_p = u - h theta_y, v_p = v + h theta_x (local, per node)
        L[:, :, node + 4] -= h[:, None, :] * L[:, :, node + 0]
        L[:, :, node + 3] += h[:, None, :] * L[:, :, node + 1]
    # local DOF = R @ global per node triple: S = L blockdiag(R)
    return np.matmul(L.reshape(ne, 6, 2 * nn, 3), R[:, None]).reshape(ne, 6, 6 * nn)


def quad4(X, *, E, nu, thickness, **_):
    """Centroid shell stress operator of quad4 elements, (ne, 6, 24), and frames (ne, 3, 3)."""
    R, xy, h = _shell.local_frame(np.asarray(X, dtype=float))
    q = shell_quad4
    zero = np.zeros((1, 2))
    _, _, inv = q._jacobian(q._shape(zero)[1], xy)                 # (ne, 1, 2, 2)
    dq8 = q._grad(inv, q._q8_gradients(zero))                       # (ne, 1, 8, 2)
    Lm = np.matmul(_shell.membrane_B(dq8)[:, 0], q._allman_map(xy))  # (ne, 3, 12)
    dN = q._grad(inv, q._shape(zero)[1])                            # (ne, 1, 4, 2)
    Lb = _shell.curvature_B(dN)[:, 0]                               # (ne, 3, 12)
    return _shell_global(Lm, Lb, R, h, E, nu, thickness), R


def tri3(X, *, E, nu, thickness, **_):
    """Centroid shell stress operator of tri3 elements, (ne, 6, 18), and frames."""
    R, xy, h = _shell.local_frame(np.asarray(X, dtype=float))
    t3 = shell_tri3
    x, y = xy[..., 0], xy[..., 1]
    b = np.roll(y, -1, axis=1) - np.roll(y, -2, axis=1)
    c = np.roll(x, -2, axis=1) - np.roll(x, -1, axis=1)
    two_area = b[:, 0] * c[:, 1] - b[:, 1] * c[:, 0]
    gradL = np.stack([b, c], axis=-1) / two_area[:, None, None]
    d6 = t3._dT6_dL(np.full((1, 3), 1.0 / 3.0))[0]                  # (6, 3)
    dN6 = np.einsum("ki,eic->ekc", d6, gradL)                       # (ne, 6, 2)
    Bq = np.zeros((len(xy), 3, 12))
    Bq[:, 0, 0::2] = dN6[..., 0]
    Bq[:, 1, 1::2] = dN6[..., 1]
    Bq[:, 2, 0::2] = dN6[..., 1]
    Bq[:, 2, 1::2] = dN6[..., 0]
    Lb = np.matmul(Bq, t3._dkt_map(xy))                              # (ne, 3, 9)
    Lm = np.matmul(_shell.membrane_B(dN6), t3._allman_map(xy))      # (ne, 3, 9)
    return _shell_global(Lm, Lb, R, h, E, nu, thickness), R


def _solid_centroid(X, dN, E, nu):
    J = np.einsum("ai,eaj->eij", dN, X)
    _, inv = _solid.det_inv3(J)
    G = np.einsum("eji,ai->eaj", inv, dN)                           # (ne, nn, 3)
    from flexpipe.fem._element import isotropic_D

    return np.matmul(isotropic_D(E, nu), tet4.strain_displacement(G))


def solid(cell_type, X, *, E, nu, **_):
    """Centroid stress operator (ne, 6, 3 nn) of a solid family, global axes."""
    X = np.asarray(X, dtype=float)
    if cell_type == "tetra":
        dN = tet4._DN
    elif cell_type == "tetra10":
        dN = tet10.shape(np.full((1, 3), 0.25))[1][0]
    else:
        dN = hex8.shape(np.zeros(3))[1][0]
    return _solid_centroid(X, dN, np.asarray(E, float), np.asarray(nu, float))


def _hex8_nodal(X, E, nu):
    """Hex8 corner stresses (ne, 8, 6, 24): Gauss-point stresses with the incompatible
    modes recovered by the same static condensation as the stiffness, extrapolated
    trilinearly from the 2x2x2 points to the corners."""
    det, inv = hex8._jacobian(hex8._DNK, X)
    G = np.einsum("eqji,qai->eqaj", inv, hex8._DNK)            # (ne, 8, 8, 3)
    det0, inv0 = hex8._jacobian(hex8._DN0, X)
    Gi = np.einsum("eji,qki->eqkj", inv0[:, 0], hex8._DP)
    Gi = Gi * (det0[:, 0][:, None] / det)[:, :, None, None]
    Gall = np.concatenate([G, Gi], axis=2)                      # (ne, 8, 11, 3)
    lam, mu = _solid.lame(E, nu)
    K = _solid.isotropic_stiffness(Gall, det * hex8._WK, lam, mu)
    amp = -np.linalg.solve(K[:, 24:, 24:], K[:, 24:, :24])      # (ne, 9, 24)
    ne = len(X)
    B = tet4.strain_displacement(Gall.reshape(ne * 8, 11, 3)).reshape(ne, 8, 6, 33)
    Bu = B[..., :24] + np.matmul(B[..., 24:], amp[:, None])     # (ne, 8, 6, 24)
    from flexpipe.fem._element import isotropic_D

    Sg = np.matmul(isotropic_D(E, nu)[:, None], Bu)
    # Gauss point g sits at sign(P_g) / sqrt(3): trilinear extrapolation to the corners
    node_of_g = [int(np.flatnonzero((hex8.XI == np.sign(p)).all(axis=1))[0])
                 for p in hex8._PK]
    ext = hex8.shape(np.sqrt(3.0) * hex8.XI)[0][:, node_of_g]   # (corner, gauss point)
    return np.einsum("ag,egcd->eacd", ext, Sg)


def solid_nodal(cell_type, X, *, E, nu, **_):
    """Stress operators at the element's nodes (ne, nn, 6, 3 nn), global axes.

    tet4: the constant stress; tet10: the stress field at its ten nodes; hex8: Gauss-point
    stresses (incompatible modes included) extrapolated to the corners.
    """
    X = np.asarray(X, dtype=float)
    E, nu = np.asarray(E, float), np.asarray(nu, float)
    if cell_type == "tetra":
        S = _solid_centroid(X, tet4._DN, E, nu)
        return np.repeat(S[:, None], 4, axis=1)
    if cell_type == "hexahedron":
        return _hex8_nodal(X, E, nu)
    verts = tet10._VERTS
    P = np.vstack([verts, 0.5 * (verts[tet10.EDGES[:, 0]] + verts[tet10.EDGES[:, 1]])])
    dNs = tet10.shape(P)[1]
    return np.stack([_solid_centroid(X, dN, E, nu) for dN in dNs], axis=1)


def beam(X, *, E, A, Iy, Iz, orientation=None, **_):
    """End stress operator of 3D beams (ne, 6, 12): axial and extreme-fibre bending."""
    X = np.asarray(X, dtype=float)
    ne = len(X)
    E, A, Iy, Iz = (np.broadcast_to(np.asarray(v, float), (ne,)) for v in (E, A, Iy, Iz))
    if orientation is None:
        orientation = np.full((ne, 3), np.nan)
    R, L = beam3d._frames(X, orientation)
    cy = np.sqrt(3.0 * Iz / A)
    cz = np.sqrt(3.0 * Iy / A)
    # local DOF per node: u v w tx ty tz; v'' from (v1, tz1, v2, tz2), w'' from
    # (w1, -ty1, w2, -ty2) (theta_y = -dw/dx)
    S = np.zeros((ne, 6, 12))
    S[:, 0, 0], S[:, 0, 6] = -E / L, E / L
    S[:, 3] = S[:, 0]
    L2 = L**2
    h0 = np.stack([-6 / L2, -4 / L, 6 / L2, -2 / L], axis=1)         # v''(0)
    h1 = np.stack([6 / L2, 2 / L, -6 / L2, 4 / L], axis=1)           # v''(L)
    for row, hh in ((1, h0), (4, h1)):
        S[:, row, [1, 5, 7, 11]] = (E * cy)[:, None] * hh
        S[:, row + 1, [2, 4, 8, 10]] = (E * cz)[:, None] * hh * np.array([1, -1, 1, -1])
    # local = R @ global per node triple
    return np.matmul(S.reshape(ne, 6, 4, 3), R[:, None]).reshape(ne, 6, 12)


def operators(cell_type: str, X, **props):
    """Stress operator of ``cell_type`` cells; returns ``(S, frames or None)``.

    ``props`` are the assembler's per-cell properties (``E``, ``nu``, ``thickness`` or
    ``A, Iy, Iz, orientation``).
    """
    if cell_type == "quad":
        return quad4(X, **props)
    if cell_type == "triangle":
        return tri3(X, **props)
    if cell_type == "line":
        return beam(X, **props), None
    return solid(cell_type, X, **props), None
