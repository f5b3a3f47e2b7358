"""Zero-energy modes beyond the rigid-body ones: how many, where they move, why.

A free body has six zero-frequency (rigid-body) modes; a supported one has as many as
its supports leave free.  More are a *mechanism*: a node hung on rods only, a part held
by one node or a hinge, a part no element connects, or stiffness that has all but
vanished (a shell thickness of 1e-9 m: bending goes with ``t^3``).  The same test and
the same words serve :func:`flexpipe.fem.eigenmodes` (which warns) and
:func:`flexpipe.reduce` (which explains a singular interior stiffness).
"""

from __future__ import annotations

import numpy as np

#: a mode is zero-frequency when it lies below this fraction of the first elastic one
ZERO_RATIO = 1e-3
#: without a gap in the modes found: zero when below this fraction of
#: :func:`element_scale_hz`: exact zeros only (round-off ones lie near 1e-8 of it, a
#: stiff body's first mode at 1e-4, a nearly massless rod's with a point mass lower)
ABS_ZERO_RATIO = 1e-10
#: shells thinner than this fraction of the model's size are reported as the likely cause
THIN_RATIO = 1e-5


class MechanismWarning(UserWarning):
    """More zero-frequency modes than the supports leave rigid-body motions."""


def count_zero_modes(omega, *, ratio: float = ZERO_RATIO) -> int:
    """Number of leading zero-frequency modes in ascending circular frequencies ``omega``.

    The count ``r`` is the largest one for which every one of the first ``r``
    frequencies lies below ``ratio`` times the frequency of mode ``r`` (the first elastic
    mode).  0 when no such gap is seen among the values given.
    """
    w = np.sqrt(np.clip(np.asarray(omega, dtype=float) ** 2, 0.0, None))
    r = 0
    for k in range(1, len(w)):
        if w[k] > 0 and w[:k].max() < ratio * w[k]:
            r = k
    return r


def extra_directions(MR, Z) -> np.ndarray:
    """Combinations of the zero modes ``Z`` that are M-orthogonal to the rigid motions.

    Parameters
    ----------
    MR : ndarray, shape (n, r0)
        Mass matrix times the rigid-body motions left free (any coordinates).
    Z : ndarray, shape (n, r)
        The zero-frequency modes, same coordinates.

    Returns
    -------
    ndarray, shape (r, r - rank)
        Coefficients: ``Z @ C`` are the zero-energy motions that are not rigid.
    """
    Z = np.asarray(Z)
    if MR is None or np.shape(MR)[1] == 0:
        return np.eye(Z.shape[1])
    _, s, Vt = np.linalg.svd(np.asarray(MR).T @ Z)
    rank = int(np.count_nonzero(s > 1e-6 * max(s.max(initial=0.0), 1e-300)))
    return Vt[rank:].T


def node_amplitude(fe, U) -> np.ndarray:
    """Root-sum-square nodal translation of the all-DOF motions ``U`` (n_dof, k)."""
    U = np.asarray(U).reshape(fe.n_nodes, fe.dofs_per_node, -1)[:, :3]
    return np.sqrt((U ** 2).sum(axis=(1, 2)))


def describe_motion(fe, amp) -> str:
    """``"largest at node 500 at (0.3, 0.075, 0) m (1 nodes move with it)"``."""
    amp = np.asarray(amp, dtype=float)
    if not amp.size or not np.isfinite(amp).all() or amp.max() <= 0:
        return ""
    order = np.argsort(-amp)
    i = int(order[0])
    moving = int((amp > 0.5 * amp[i]).sum())
    name = (lambda k: fe.mesh.describe_node(k)) if fe.mesh is not None else \
        (lambda k: f"node index {k}")
    text = f"largest at {name(i)} ({moving} nodes move with it"
    if moving > 1:
        text += ", e.g. " + ", ".join(name(int(k)).split(" at ")[0] for k in order[1:3])
    return text + ")"


def thickness_note(fe, option: str = "--thickness") -> str:
    """What to check when shells take their thickness from ``read_mesh(thickness=)`` (the
    command line's ``--thickness``): the value, and whether it is the likely cause."""
    from flexpipe.mesh.read import DEFAULT_THICKNESS_SET

    mesh = fe.mesh
    props = {} if mesh is None else mesh.sections.get(DEFAULT_THICKNESS_SET, {})
    if "thickness" not in props:
        return ""
    t = float(props["thickness"])
    n = sum(len(v) for v in mesh.cell_sets.get(DEFAULT_THICKNESS_SET, {}).values())
    size = float(np.linalg.norm(np.ptp(fe.nodes, axis=0))) if fe.n_nodes else 0.0
    text = (f"{n} shell element(s) without a thickness in the file take {option} {t:g} m "
            "(read_mesh thickness=)")
    if size > 0 and t < THIN_RATIO * size:
        text += (f", {t / size:.1e} of the model's size {size:.3g} m: their bending "
                 "stiffness (~ t^3) is lost in round-off, the likely cause; give the real "
                 "thickness, e.g. 0.002 for 2 mm")
    return text


def likely_cause(fe, *, option: str = "--thickness") -> str:
    """The likely causes of extra zero-energy modes, as words for a message."""
    thin = thickness_note(fe, option)
    causes = ("a part held by a single node or a hinge (e.g. a node on rods or springs "
              "only) or a missing connection (a disconnected part, elements with zero "
              "stiffness)")
    if "likely cause" in thin:
        return thin.replace(", the likely cause", "")
    return f"{causes}; also check: {thin}" if thin else causes


def n_parts(fe) -> int:
    """Connected parts of the model: nodes joined by stiffness or rigid links."""
    import scipy.sparse as sp
    from scipy.sparse.csgraph import connected_components

    d = fe.dofs_per_node
    A = sp.csr_matrix((np.ones(fe.n_dof), (np.arange(fe.n_dof), np.arange(fe.n_dof) // d)),
                      shape=(fe.n_dof, fe.n_nodes))
    K, T = abs(sp.csr_matrix(fe.K)), abs(sp.csr_matrix(fe.T))
    G = A.T @ K @ A + (A.T @ T) @ (T.T @ A)
    used = np.asarray(G.diagonal()) > 0
    G = G[used][:, used]
    return int(connected_components(G, directed=False)[0]) if used.any() else 1


def element_scale_hz(fe) -> float:
    """Typical element-level frequency of the translations, Hz (0 if none).

    ``sqrt(median(K_jj / M_jj)) / 2 pi`` over the translational DOF: about the
    wave speed over the element size, whatever the shell thickness.  Round-off zeros lie
    near 1e-8 of it; a 10 um foil's first bending mode near 1e-5.
    """
    d = fe.dofs_per_node
    dK = fe.K.diagonal().reshape(-1, d)[:, :3].ravel()
    dM = fe.M.diagonal().reshape(-1, d)[:, :3].ravel()
    pos = (dK > 0) & (dM > 0)
    return float(np.sqrt(np.median(dK[pos] / dM[pos])) / (2 * np.pi)) if pos.any() else 0.0


def zero_mode_warning(fe, freqs_hz, n_expected: int, *, supported: bool,
                      extra_motion=None, scale_hz: float = 0.0) -> str:
    """Warning text when ``freqs_hz`` (ascending) hold more zero modes than expected.

    Parameters
    ----------
    fe : FEModel
    freqs_hz : ndarray
        The lowest natural frequencies found, Hz.
    n_expected : int
        Rigid-body motions the supports leave free (6 for a free body).
    supported : bool
        Whether the model is held by supports (changes the words only).
    extra_motion : callable, optional
        ``extra_motion(r) -> (n_dof, k)``: the zero-energy motions among the first ``r``
        modes that are not rigid-body ones, for naming the nodes that move most.
    scale_hz : float
        :func:`element_scale_hz` of the model: when every frequency found lies below
        :data:`ABS_ZERO_RATIO` times it (no elastic mode found to compare with), they
        all count as zero.

    Returns
    -------
    str
        Empty when the count is as expected.
    """
    f = np.asarray(freqs_hz, dtype=float)
    r = count_zero_modes(f)
    all_zero = (r <= n_expected and scale_hz > 0 and len(f) > n_expected
                and bool((f < ABS_ZERO_RATIO * scale_hz).all()))
    if r <= n_expected and not all_zero:
        return ""
    if all_zero:
        r = len(f)
        how = (f"all {r} modes computed are zero-frequency (at most {f.max():.3g} Hz; ask "
               "for more modes to see the first elastic one)")
    else:
        how = (f"{r} zero-frequency modes (below {ZERO_RATIO:g} x the first elastic "
               f"frequency {f[r]:.4g} Hz)")
    where = f"{fe.mesh.source}: " if fe.mesh is not None and fe.mesh.source else ""
    held = (f"the supports leave {n_expected} rigid-body motion(s) free" if supported
            else "a free body has 6 (rigid-body motions)")
    text = (f"{where}{how} where {held}: {'at least ' if all_zero else ''}"
            f"{r - n_expected} extra zero-energy motion(s), a mechanism")
    if extra_motion is not None:
        try:
            amp = node_amplitude(fe, extra_motion(r))
        except (ValueError, np.linalg.LinAlgError):   # naming nodes is a bonus
            amp = None
        moved = describe_motion(fe, amp) if amp is not None else ""
        if moved:
            text += f"; the extra motion is {moved}"
    return f"{text}; likely cause: {likely_cause(fe)}"
