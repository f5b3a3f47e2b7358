"""Half-car assembly: beam body (FE stage) + body basis (reduction stage) + corners.

Generalized coordinates ``q = [q_B, z_wf, z_wr]``: the body coordinates ``q_B`` (the
22 nodal DOF of the beam for the complete model, the Ritz coordinates of ``x_B = Psi
q_B`` otherwise) followed by the vertical displacements of the front and rear wheels,
all measured from static equilibrium.  With

* ``y = D^T q``: suspension extension (body attachment minus wheel; > 0 in rebound),
* ``delta = s(t) - E^T q``: tire compression (road height minus wheel),

the linear equations of motion are ``M q'' + C q' + K q = E k_t s(t)``, in which ``K``
holds the suspension springs ``D k_s D^T`` and the tires ``E k_t E^T`` and ``C`` the
body damping and the linear suspension dampers ``D c D^T``.  Nonlinear laws add
``B g`` with ``B = [-D, E]`` (see :mod:`flexpipe.halfcar.elements`).
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from flexpipe._arrays import readonly
from flexpipe.errors import InputError
from flexpipe.fem.beam2d import PlanarBeam, assemble_beam, rigid_body_modes, uniform_nodes
from flexpipe.halfcar.params import HalfCarParams, load_params

VARIANTS = ("complete", "reduced", "truncated", "rigid")


@dataclass(frozen=True, eq=False)
class HalfCarModel:
    """Linear half-car matrices and corner data of one model variant (SI units).

    Attributes
    ----------
    variant : str
        ``"complete"``, ``"reduced"``, ``"truncated"`` or ``"rigid"``.
    params : HalfCarParams
    beam : PlanarBeam
        The FE body (always the complete beam).
    Psi : ndarray, shape (22, n_B)
        Body Ritz basis, ``x_B = Psi q_B``.
    M, K, C_body : ndarray, shape (n, n)
        Mass, stiffness (springs and tires included) and body damping matrices.
    D, E : ndarray, shape (n, 2)
        Suspension-extension and wheel-displacement operators (front, rear).
    a_A : ndarray, shape (n,)
        Row giving the vertical displacement of point A (rear body attachment).
    k_s, k_t, k_t3, m_s, c_lin, c_jounce, c_rebound : ndarray, shape (2,)
        Spring and tire rates, cubic tire rates, static sprung mass per corner and
        damper coefficients for zeta, zeta_jounce and zeta_rebound.
    static_tire_force : ndarray, shape (2,)
        Static tire loads (N), the preload that unilateral contact can lose.
    x_attach : ndarray, shape (2,)
        Abscissae of the attachments (m from the front end of the body).
    """

    variant: str
    params: HalfCarParams
    beam: PlanarBeam
    Psi: np.ndarray
    M: np.ndarray
    K: np.ndarray
    C_body: np.ndarray
    D: np.ndarray
    E: np.ndarray
    a_A: np.ndarray
    k_s: np.ndarray
    k_t: np.ndarray
    k_t3: np.ndarray
    m_s: np.ndarray
    c_lin: np.ndarray
    c_jounce: np.ndarray
    c_rebound: np.ndarray
    static_tire_force: np.ndarray
    x_attach: np.ndarray

    def __post_init__(self):
        # read-only copies: build_model caches one model per variant, which every caller
        # shares (a caller scaling model.K in place changed every later result)
        for f in dataclasses.fields(self):
            value = getattr(self, f.name)
            if isinstance(value, np.ndarray):
                object.__setattr__(self, f.name, readonly(value))

    @property
    def n_dof(self) -> int:
        """Number of generalized coordinates."""
        return self.M.shape[0]

    @property
    def wheelbase_m(self) -> float:
        """Distance between the front and rear attachments."""
        return float(self.x_attach[1] - self.x_attach[0])

    @property
    def B(self) -> np.ndarray:
        """Input matrix of the nonlinear forces ``[damper front, rear, tire front, rear]``."""
        return np.hstack([-self.D, self.E])

    def damping_matrix(self, c) -> np.ndarray:
        """Body damping plus suspension dampers of coefficients ``c`` (front, rear)."""
        c = np.asarray(c, dtype=float)
        return self.C_body + (self.D * c) @ self.D.T

    @property
    def C(self) -> np.ndarray:
        """Damping matrix with the linear dampers (``zeta``)."""
        return self.damping_matrix(self.c_lin)


def body_beam(params: HalfCarParams) -> PlanarBeam:
    """The FE model of the body: a uniform free–free beam."""
    x = uniform_nodes(params.body_length_m, params.n_elements)
    return assemble_beam(x, params.bending_stiffness_N_m2,
                         params.body_mass_kg / params.body_length_m)


def body_basis(variant: str, beam: PlanarBeam, params: HalfCarParams) -> np.ndarray:
    """Ritz basis of the body for one model variant (reduction stage).

    ``reduced``: 2 rigid-body + ``free_interface_modes`` elastic free-interface modes +
    one residual-flexibility attachment mode per boundary DOF (the vertical displacement
    at each suspension attachment), orthonormalized (same subspace, so the same reduced
    model, expressed in its own modal coordinates).  ``truncated``: the ``truncated_modes`` lowest
    free–free modes.  ``rigid``: heave and pitch only.
    """
    if variant == "complete":
        return np.eye(beam.n_dof)
    if variant == "rigid":
        return rigid_body_modes(beam.x, x_ref=0.5 * beam.x[-1])
    from flexpipe.reduction.cms import (
        modal_truncation_basis,
        orthonormalize,
        residual_flexibility_basis,
    )

    if variant == "reduced":
        boundary = [beam.w_dof(c.attachment_node) for c in params.corners]
        Psi = residual_flexibility_basis(beam.M, beam.K, boundary,
                                         params.free_interface_modes, n_rigid=2)
        # same subspace, modal coordinates: well-conditioned reduced matrices
        return orthonormalize(beam.M, beam.K, Psi)[0]
    if variant == "truncated":
        return modal_truncation_basis(beam.M, beam.K, params.truncated_modes)
    raise InputError(f"unknown half-car variant {variant!r}; valid: {', '.join(VARIANTS)}",
                     key="variant")


def _first_bending(beam: PlanarBeam) -> float:
    lam = sla.eigh(beam.K.toarray(), beam.M.toarray(), eigvals_only=True)
    return float(np.sqrt(lam[2]))


@functools.lru_cache(maxsize=32)
def build_model(variant: str, params: HalfCarParams | None = None) -> HalfCarModel:
    """Assemble the linear half-car of one variant.

    Parameters
    ----------
    variant : {"complete", "reduced", "truncated", "rigid"}
    params : HalfCarParams, optional
        Defaults to the documented parameter set (:func:`load_params`).

    Returns
    -------
    HalfCarModel

    Raises
    ------
    InputError
        Unknown variant.
    """
    if variant not in VARIANTS:
        raise InputError(f"unknown half-car variant {variant!r}; valid: {', '.join(VARIANTS)}",
                         key="variant")
    p = params if params is not None else load_params()
    beam = body_beam(p)
    Psi = body_basis(variant, beam, p)
    MB, KB = beam.M.toarray(), beam.K.toarray()
    beta = 2.0 * p.structural_damping_ratio / _first_bending(beam)
    nb = Psi.shape[1]
    n = nb + 2
    M = np.zeros((n, n))
    K = np.zeros((n, n))
    Cb = np.zeros((n, n))
    M[:nb, :nb] = Psi.T @ MB @ Psi
    K[:nb, :nb] = Psi.T @ KB @ Psi
    Cb[:nb, :nb] = beta * K[:nb, :nb]
    D = np.zeros((n, 2))
    E = np.zeros((n, 2))
    for j, corner in enumerate(p.corners):
        D[:nb, j] = Psi[beam.w_dof(corner.attachment_node)]
        D[nb + j, j] = -1.0
        E[nb + j, j] = 1.0
    k_s = np.array([c.spring_rate_N_per_m for c in p.corners])
    k_t = np.array([c.tire_rate_N_per_m for c in p.corners])
    m_w = np.array([c.wheel_mass_kg for c in p.corners])
    M[nb:, nb:] = np.diag(m_w)
    K += (D * k_s) @ D.T + (E * k_t) @ E.T
    # static sprung load per corner: the body on two supports (lever rule about its CG)
    x_att = beam.x[[c.attachment_node for c in p.corners]]
    heave = rigid_body_modes(beam.x)
    m_body = heave[:, 0] @ beam.M @ heave[:, 0]
    x_cg = (heave[:, 0] @ beam.M @ heave[:, 1]) / m_body
    m_front = m_body * (x_att[1] - x_cg) / (x_att[1] - x_att[0])
    m_s = np.array([m_front, m_body - m_front])
    crit = 2.0 * np.sqrt(k_s * m_s)
    a_A = D[:, 1].copy()
    a_A[nb + 1] = 0.0
    return HalfCarModel(
        variant=variant, params=p, beam=beam, Psi=Psi, M=M, K=K, C_body=Cb, D=D, E=E,
        a_A=a_A,
        k_s=k_s, k_t=k_t, k_t3=np.array([c.tire_cubic_rate_N_per_m3 for c in p.corners]),
        m_s=m_s, c_lin=p.zeta * crit, c_jounce=p.zeta_jounce * crit,
        c_rebound=p.zeta_rebound * crit,
        static_tire_force=(m_s + m_w) * p.gravity_m_per_s2, x_attach=x_att,
    )


def natural_frequencies(variant: str, params: HalfCarParams | None = None) -> np.ndarray:
    """Undamped natural frequencies of a half-car variant.

    Parameters
    ----------
    variant : {"complete", "reduced", "truncated", "rigid"}
    params : HalfCarParams, optional
        Defaults to the documented parameter set.

    Returns
    -------
    ndarray
        Frequencies in Hz, ascending (24 for the complete model, 8 for the reduced and
        truncated ones, 4 for the rigid one).
    """
    model = build_model(variant, params)
    lam = sla.eigh(model.K, model.M, eigvals_only=True)
    return np.sqrt(np.clip(lam, 0.0, None)) / (2.0 * np.pi)
