"""Lumped (diagonal) element mass matrices, Nastran's default mass (PARAM COUPMASS -1).

Each element's translational mass is lumped per component onto the diagonal: the row
sums of the consistent matrix when all are positive (linear elements: the
equal-distribution lumping Nastran uses), else the diagonal scaled to the element's
total mass (Hinton-Rock-Zienkiewicz, for quadratic elements whose corner row sums are
negative).  Rotational DOF get no mass, as in Nastran's lumped formulation of shells and
bars; concentrated masses (CONM1/CONM2) are unaffected.
"""

from __future__ import annotations

import numpy as np


def lump(Me: np.ndarray, dofs_per_node: int) -> np.ndarray:
    """Lumped version (ne, nd, nd) of consistent element masses ``Me``."""
    ne, nd, _ = Me.shape
    nn = nd // dofs_per_node
    out = np.zeros_like(Me)
    for c in range(3):
        idx = np.arange(nn) * dofs_per_node + c
        sub = Me[:, idx[:, None], idx]                      # (ne, nn, nn)
        rows = sub.sum(axis=2)
        total = rows.sum(axis=1)
        diag = np.einsum("eii->ei", sub)
        hrz = diag * (total / np.where(diag.sum(axis=1) > 0, diag.sum(axis=1), 1.0))[:, None]
        m = np.where((rows >= 0).all(axis=1)[:, None], rows, hrz)
        out[:, idx, idx] = m
    return out
