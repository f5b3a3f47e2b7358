"""Five-node pyramid (Nastran CPYRAM) as a collapsed trilinear hexahedron.

The four top nodes of a hex8 are merged into the apex: ``N_apex = N_5 + ... + N_8``.
The field stays isoparametric, so rigid motion and constant strain are exact (patch
test), it is bilinear on the quadrilateral base (conforming with hex8 faces) and linear
on the triangular faces (conforming with tet4 faces).  Integration: 2x2x2 Gauss for the
stiffness, 3x3x3 for the consistent mass (points are interior, where the Jacobian of the
collapsed map is regular).  No incompatible modes (they are not defined on the collapsed
shape).  Node order: base G1-G4 counter-clockwise seen from the apex G5.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem import _solid, hex8
from flexpipe.fem._element import BadElements

TYPE = "pyramid"
DOFS_PER_NODE = 3
_HEX = np.array([0, 1, 2, 3, 4, 4, 4, 4])
#: collapse map: hex DOF (24) -> pyramid DOF (15)
_C = np.zeros((24, 15))
for _a, _p in enumerate(_HEX):
    for _j in range(3):
        _C[3 * _a + _j, 3 * _p + _j] = 1.0


def matrices(X, *, E, nu, rho, **_):
    """Stiffness and consistent mass of pyramid5 elements, see :mod:`flexpipe.fem._element`."""
    X = np.asarray(X, dtype=float)
    Xh = X[:, _HEX]
    detK, _ = hex8._jacobian(hex8._DNK, Xh)
    detM, _ = hex8._jacobian(hex8._DNM, Xh)
    base = np.einsum("eij,ej->ei", np.cross(X[:, 1] - X[:, 0], X[:, 3] - X[:, 0])[:, None],
                     X[:, 4] - X[:, 0])[:, 0]
    base2 = np.einsum("ej,ej->e", np.cross(X[:, 3] - X[:, 2], X[:, 1] - X[:, 2]),
                      X[:, 4] - X[:, 2])
    bad = _solid.bad_jacobian(np.column_stack([detK, detM, base, base2]), X)
    if bad.any():
        raise BadElements(np.flatnonzero(bad), "inverted or degenerate (apex G5 on the wrong "
                          "side of the base G1-G4, or det J <= 0 inside)")
    Kh = hex8.stiffness(Xh, E, nu, incompatible=False)
    Mh = _solid.consistent_mass(hex8._NM, detM * hex8._WM, rho)
    return _C.T @ Kh @ _C, _C.T @ Mh @ _C
