"""Constant inertia coupling of a floating-frame body (Adams/Flex's "constant coupling").

Exudyn's ``ObjectFFRFreducedOrder`` evaluates the complete floating-frame mass matrix and
quadratic velocity vector at every Newton iteration: the rigid-body inertia, the modal
mass and every deformation-dependent coupling block (inertia invariants 3, 4, 5, 8 and 9
in Adams/Flex's numbering), a dense (7 + m) x (7 + m) matrix for m elastic modes.  When
the elastic modes are orthogonal to the rigid-body motion in the mass metric (mean axes:
``sum m Phi = 0`` and ``sum m (x - c) x Phi = 0``, which free-free modes of the reduced
body satisfy), the couplings that are linear in the modal coordinates vanish and what
is left is of second order in the deformation: the centrifugal and Coriolis loads of the
frame's rotation on the modes and the deformation's change of the body's inertia.
Adams/Flex calls the model without them *constant coupling*: the rigid body's inertia
plus the constant modal mass.

:func:`add_constant_coupling` builds it from Exudyn items, leaving the FFRF object to
carry only the kinematics (markers at ``p + A (x + Phi q)``, ``computeFFRFterms=False``):
an ``ObjectRigidBody`` on the frame node and an ``ObjectGenericODE2`` with the modal
mass, stiffness and damping on the modal node.  Both have small, mostly constant mass
matrices; :func:`check_mean_axes` refuses bodies whose modes are not mean-axis modes.
The modal matrices of a reduced body are diagonal; :func:`compact` hands them to Exudyn
as their diagonal entries instead of dense m x m matrices, which Exudyn adds entry by
entry into the system matrices at every Newton iteration.  On the flexible linkage car
(75 modes; ISO C 70 km/h, 2 s, Exudyn's timers on its range-checked module, two
simultaneous pairs of runs, 2026-12-02) the mass-matrix timer fell from 0.099 / 0.138 to
0.070 / 0.075 ms per step and the body-and-force timer from 0.211 / 0.253 to 0.187 /
0.198 ms; the hub forces are bitwise the same.
"""

from __future__ import annotations

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

from flexpipe.errors import InputError
from flexpipe.flexbody.invariants import MAX_MEAN_AXIS_COSINE, mean_axis_cosine

#: inertia coupling models of :func:`flexpipe.exu.body.add_flexible_body`
COUPLINGS = ("full", "constant")


def dense(A) -> exu.MatrixContainer:
    """Exudyn matrix container holding ``A`` as a dense matrix."""
    c = exu.MatrixContainer()
    c.SetWithDenseMatrix(np.ascontiguousarray(A, dtype=float), useDenseMatrix=True)
    return c


def compact(A) -> exu.MatrixContainer:
    """Exudyn matrix container holding ``A``: sparse (its non-zero entries only) when
    ``A`` is diagonal, as modal matrices are, else dense."""
    A = np.ascontiguousarray(A, dtype=float)
    if A.ndim != 2 or A.shape[0] != A.shape[1] or np.any(A - np.diag(np.diag(A))):
        return dense(A)
    i = np.flatnonzero(np.diag(A))
    c = exu.MatrixContainer()
    c.SetWithSparseMatrix(np.column_stack([i, i, A[i, i]]).astype(float),
                          numberOfRows=A.shape[0], numberOfColumns=A.shape[1],
                          useDenseMatrix=False)
    return c


def inertia6(J) -> list:
    """Exudyn's six-component inertia ``[Jxx, Jyy, Jzz, Jyz, Jxz, Jxy]`` of a 3 x 3 tensor."""
    J = np.asarray(J, dtype=float)
    return [J[0, 0], J[1, 1], J[2, 2], J[1, 2], J[0, 2], J[0, 1]]


def check_mean_axes(body, n_modes: int | None = None) -> None:
    """Raise :class:`InputError` unless the elastic modes are mean-axis modes."""
    cos, j = mean_axis_cosine(body, n_modes)
    if cos > MAX_MEAN_AXIS_COSINE:
        raise InputError(
            f"inertia_coupling='constant' needs elastic modes orthogonal to the rigid-body "
            f"motion (mean axes), but elastic mode {j + 1} "
            f"({body.frequencies_hz[body.n_rigid + j]:.1f} Hz) has a mass-metric cosine "
            f"of {cos:.3g} with it (limit {MAX_MEAN_AXIS_COSINE:g}); use "
            "inertia_coupling='full' or a body whose modes are free-free modes of the "
            "reduced model",
            key="inertia_coupling")


def add_constant_coupling(mbs, body, n_frame, n_modal, M, K, D):
    """Rigid inertia on ``n_frame`` and the modal mass ``M``, stiffness ``K`` and damping
    ``D`` (m x m) on ``n_modal``; returns the rigid body's object index (for
    mass-proportional loads such as gravity)."""
    if M.shape[0]:
        mbs.AddObject(eii.ObjectGenericODE2(
            nodeNumbers=[n_modal], massMatrix=compact(M), stiffnessMatrix=compact(K),
            dampingMatrix=compact(D)))
    return mbs.AddObject(eii.ObjectRigidBody(
        nodeNumber=n_frame, mass=body.mass, inertia=inertia6(body.inertia_origin),
        centerOfMass=list(map(float, body.center_of_mass)),
        visualization=eii.VObjectRigidBody(show=False)))
