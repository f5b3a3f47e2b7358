"""Eight-node hexahedron with incompatible modes (Wilson-Taylor, "QM6" in 3D).

The trilinear displacement field is enriched with Wilson's nine incompatible modes
``(1 - xi^2) a_1 + (1 - eta^2) a_2 + (1 - zeta^2) a_3`` (three vector amplitudes), which
makes the element exact in pure bending of rectangular blocks and free of shear and
volumetric locking in bending.  Following Taylor, Beresford & Wilson (1976) the mode
derivatives use the Jacobian at the element centre, scaled by ``det J0 / det J``, so
that their volume integral vanishes on any shape: the constant-strain patch test is
passed on distorted meshes.  The nine internal amplitudes are condensed statically,
``K = Kcc - Kci Kii^-1 Kic``, for the whole batch at once (batched solves).

Integration: 2x2x2 Gauss for stiffness, 3x3x3 for the consistent (trilinear) mass.
Node order: meshio/VTK hexahedron (bottom face 0-3 counter-clockwise seen from the top
face 4-7).
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _solid
from flexpipe.fem._element import BadElements
from flexpipe.fem.quadrature import gauss_hex

TYPE = "hexahedron"
DOFS_PER_NODE = 3

#: natural coordinates of the nodes
XI = np.array([[-1, -1, -1], [1, -1, -1], [1, 1, -1], [-1, 1, -1],
               [-1, -1, 1], [1, -1, 1], [1, 1, 1], [-1, 1, 1]], dtype=float)


def shape(P: np.ndarray):
    """Trilinear N (np, 8) and dN/dxi (np, 8, 3) at natural points P (np, 3)."""
    P = np.atleast_2d(np.asarray(P, dtype=float))
    f = 1.0 + P[:, None, :] * XI[None, :, :]                # (np, 8, 3)
    N = 0.125 * f.prod(axis=2)
    dN = np.empty(f.shape)
    dN[..., 0] = 0.125 * XI[:, 0] * f[..., 1] * f[..., 2]
    dN[..., 1] = 0.125 * XI[:, 1] * f[..., 0] * f[..., 2]
    dN[..., 2] = 0.125 * XI[:, 2] * f[..., 0] * f[..., 1]
    return N, dN


_PK, _WK = gauss_hex(2)
_PM, _WM = gauss_hex(3)
_NK, _DNK = shape(_PK)
_NM, _DNM = shape(_PM)
_DN0 = shape(np.zeros(3))[1]
_DNC = shape(XI)[1]
# derivatives of the incompatible modes 1 - xi_k^2 at the stiffness points: (nq, 3, 3)
_DP = np.zeros((len(_PK), 3, 3))
for _k in range(3):
    _DP[:, _k, _k] = -2.0 * _PK[:, _k]


def _jacobian(dN, X):
    return _solid.det_inv3(np.einsum("qai,eaj->eqij", dN, X))


def stiffness(X, E, nu, *, incompatible: bool = True, taylor: bool = True) -> np.ndarray:
    """Stiffness (ne, 24, 24).

    ``incompatible=False`` gives the plain trilinear element (locks in bending);
    ``taylor=False`` uses each point's own Jacobian for the incompatible modes (Wilson's
    original form, which fails the patch test on distorted elements).  Both switches
    exist for verification only.
    """
    X = np.asarray(X, dtype=float)
    det, inv = _jacobian(_DNK, X)
    G = np.einsum("eqji,qai->eqaj", inv, _DNK)              # (ne, 8, 8, 3)
    lam, mu = _solid.lame(E, nu)
    wdet = det * _WK
    if not incompatible:
        return _solid.isotropic_stiffness(G, wdet, lam, mu)
    if taylor:
        det0, inv0 = _jacobian(_DN0, X)
        Gi = np.einsum("eji,qki->eqkj", inv0[:, 0], _DP)
        Gi = Gi * (det0[:, 0][:, None] / det)[:, :, None, None]
    else:
        Gi = np.einsum("eqji,qki->eqkj", inv, _DP)
    K = _solid.isotropic_stiffness(np.concatenate([G, Gi], axis=2), wdet, lam, mu)
    Kcc, Kci, Kii = K[:, :24, :24], K[:, :24, 24:], K[:, 24:, 24:]
    return Kcc - Kci @ np.linalg.solve(Kii, Kci.transpose(0, 2, 1))


def matrices(X, *, E, nu, rho, **_):
    """Stiffness and consistent mass of hex8 elements, see :mod:`flexpipe.fem._element`."""
    X = np.asarray(X, dtype=float)
    detK, _ = _jacobian(_DNK, X)
    detM, _ = _jacobian(_DNM, X)
    detC, _ = _jacobian(_DNC, X)
    bad = _solid.bad_jacobian(np.hstack([detK, detC]), X)
    if bad.any():
        raise BadElements(np.flatnonzero(bad), "inverted or badly distorted "
                          "(det J <= 0 at a corner or integration point; check node order)")
    Ke = stiffness(X, E, nu)
    Me = _solid.consistent_mass(_NM, detM * _WM, rho)
    return Ke, Me
