"""``reduce(fe, interfaces, ...)``: component mode synthesis of an FE model into a FlexBody.

Pipeline: interfaces -> rigid spiders on the independent DOF (6 boundary DOF each) ->
Ritz basis of the chosen method -> orthonormalization (the reduced eigenproblem, as
Adams/Flex does before it writes its modal neutral file) -> expansion to nodal
translations -> mass properties, FFRF invariants, interface shapes, modal damping.

Mode selection
--------------
``n_modes`` counts normal modes: fixed-interface modes for Craig-Bampton, elastic
free-interface modes for residual flexibility and elastic free-free modes for modal
truncation (the rigid-body modes and the 6 static/attachment modes per interface come
on top).  Alternatively ``f_max`` (Hz) is the top of the frequency band the body must
reproduce: free-interface methods keep every mode up to ``f_max``; Craig-Bampton keeps
fixed-interface modes up to ``CB_FACTOR * f_max`` (3x; with 1.5x and 2x the free-free
frequencies below ``f_max`` of a stubby test bar were still 2% and 0.7% high, with 3x
0.25%, see tests/test_reduction.py).  With neither given,
``f_max = DEFAULT_F_MAX_HZ`` = 2 x 25 Hz: twice the top of the 0-25 Hz ride band
(Gillespie; the paper's section 3).

Many interfaces
---------------
Interfaces with ``dofs=3`` add 3 boundary DOF instead of 6.  Craig-Bampton with
``interface_f_max`` (Hz) replaces the static constraint modes by the characteristic
constraint modes up to that frequency (:mod:`flexpipe.reduction.ccmodes`), which keeps
the number of body modes in check when the body has tens of interfaces; with ``f_max``
given, the interior static responses to the inertia loads of the CC modes up to
``INERTIA_FACTOR * f_max`` are added (they restore the band's accuracy, see ccmodes).
"""

from __future__ import annotations

import time

import numpy as np
import scipy.sparse as sp

from flexpipe.errors import InputError, ModelError
from flexpipe.fem.mechanism import (
    count_zero_modes,
    describe_motion,
    extra_directions,
    likely_cause,
    node_amplitude,
    thickness_note,
)
from flexpipe.fem.model import FEModel
from flexpipe.fem.modes import check_mass
from flexpipe.flexbody.body import BodyInterface, FlexBody
from flexpipe.flexbody.invariants import (
    ffrf_invariants,
    mass_properties,
    rigid_body_vectors,
    translational_block,
)
from flexpipe.flexbody.surface import mesh_hash, surface_triangles
from flexpipe.reduction import cms
from flexpipe.reduction._threads import dense_single_threaded
from flexpipe.reduction.interface import interface_system, resolve_interfaces

#: default top of the frequency band, Hz: twice the 25 Hz top of the ride band
DEFAULT_F_MAX_HZ = 50.0
#: Craig-Bampton keeps fixed-interface modes up to this multiple of f_max
CB_FACTOR = 3.0
#: with interface reduction: inertia vectors for the CC modes up to this multiple of f_max
INERTIA_FACTOR = 3.0
METHODS = {
    "craig-bampton": "craig-bampton", "cb": "craig-bampton",
    "hurty-craig-bampton": "craig-bampton",
    "residual-flexibility": "residual-flexibility", "rf": "residual-flexibility",
    "modal-truncation": "modal-truncation", "mt": "modal-truncation",
}


def adams_damping(frequencies_hz) -> np.ndarray:
    """Adams/Flex default modal damping ratio (CRATIO): 1% below 100 Hz, 10% from 100 Hz to
    1 kHz, critical (100%) above."""
    f = np.asarray(frequencies_hz, dtype=float)
    return np.where(f < 100.0, 0.01, np.where(f < 1000.0, 0.10, 1.0))


def _damping_ratios(damping, f_hz, n_rigid):
    m = len(f_hz)
    if damping is None:
        zeta = adams_damping(f_hz)
    elif callable(damping):
        zeta = np.asarray([float(damping(f)) for f in f_hz])
    else:
        zeta = np.broadcast_to(np.asarray(damping, dtype=float), (m,)).copy() \
            if np.ndim(damping) == 0 else np.asarray(damping, dtype=float)
        if zeta.shape != (m,):
            raise InputError(f"damping must be a ratio, a function of frequency or {m} ratios",
                             key="damping")
    zeta = np.array(zeta, dtype=float)
    if np.any(zeta < 0) or not np.all(np.isfinite(zeta)):
        raise InputError("damping ratios must be finite and >= 0", key="damping")
    zeta[:n_rigid] = 0.0
    return zeta


def reduce(fe: FEModel, interfaces, method: str = "craig-bampton", n_modes: int | None = None,
           f_max: float | None = None, *, damping=None, check: bool = False,
           backend: str | None = None, tol: float | None = None,
           cb_factor: float = CB_FACTOR, stress: str | None = None,
           interface_f_max: float | None = None, log=None) -> FlexBody:
    """Reduce an FE model to a :class:`FlexBody` by component mode synthesis.

    Parameters
    ----------
    fe : FEModel
        Free (unsupported) structure.
    interfaces : Interface or list of Interface
    method : {"craig-bampton", "residual-flexibility", "modal-truncation"}
    n_modes : int, optional
        Normal modes to keep (see module docstring).
    f_max : float, optional
        Top of the frequency band in Hz (see module docstring).
    damping : float, array_like, callable, optional
        Modal damping ratio: one for all modes, one per mode, or ``f(f_hz) -> ratio``;
        default :func:`adams_damping`.
    check : bool
        Also solve the full model's free-free eigenproblem and store the frequency
        comparison and MAC matrix in ``body.checks``.
    backend : {"pardiso", "superlu"}, optional
        Sparse factorization backend.
    tol : float, optional
        Shift-invert residual tolerance of the eigensolver (default 1e-6: eigenvalues
        to ~1e-12).
    cb_factor : float
        Craig-Bampton with ``f_max``: keep fixed-interface modes up to
        ``cb_factor * f_max`` (default :data:`CB_FACTOR`).
    stress : {None, "none", "all"} or str
        Stress modes to store with the body (:mod:`flexpipe.flexbody.stress`): none
        (default), every element, or the elements of the named cell set of the mesh.
    interface_f_max : float, optional
        Craig-Bampton only: interface reduction, keeping the characteristic constraint
        modes up to this frequency (Hz) instead of every static constraint mode, plus
        (with ``f_max``) the inertia vectors of those up to ``INERTIA_FACTOR * f_max``;
        each interface's ``residual_compliance`` holds the static flexibility dropped.
    log : callable, optional
        ``log(line)`` as each stage ends (its name, seconds and the time so far): the
        progress of a reduction that takes minutes.

    Returns
    -------
    FlexBody
    """
    with dense_single_threaded():
        return _reduce(fe, interfaces, method, n_modes, f_max, damping=damping, check=check,
                       backend=backend, tol=tol, cb_factor=cb_factor, stress=stress,
                       interface_f_max=interface_f_max, log=log)


#: what each stage of :func:`reduce` did (its ``timings`` key -> words for the log)
_STAGES = {"interfaces_s": "interfaces resolved", "partition_s": "matrices partitioned",
           "factor_s": "K_ii factorized", "static_s": "static (constraint) modes",
           "eigen_s": "fixed-interface normal modes", "basis_s": "basis complete",
           "expand_s": "modes orthonormalized and expanded", "check_s": "full-model check",
           "stress_s": "stress modes"}


class _Timings(dict):
    """The stage timings of :func:`reduce`, logging each as it is set."""

    def __init__(self, log):
        super().__init__()
        self._log, self._t0 = log, time.perf_counter()

    def __setitem__(self, key, seconds):
        super().__setitem__(key, seconds)
        if self._log is not None:
            self._log(f"{_STAGES.get(key, key)}: {seconds:.1f} s "
                      f"({time.perf_counter() - self._t0:.1f} s so far)")


def _reduce(fe, interfaces, method, n_modes, f_max, *, damping, check, backend, tol,
            cb_factor, stress=None, interface_f_max=None, log=None):
    t0 = time.perf_counter()
    timings = _Timings(log)
    if not isinstance(fe, FEModel):
        raise InputError(f"fe must be an FEModel (flexpipe.assemble), got {type(fe).__name__}")
    key = str(method).strip().lower()
    if key not in METHODS:
        raise InputError(f"unknown method {method!r}; valid: craig-bampton, "
                         "residual-flexibility, modal-truncation", key="method")
    method = METHODS[key]
    if interface_f_max is not None and method != "craig-bampton":
        raise InputError("interface_f_max (interface reduction) applies to Craig-Bampton "
                         f"only, not {method}", key="interface_f_max")
    if n_modes is not None and f_max is not None:
        raise InputError("give n_modes or f_max, not both", key="n_modes")
    if n_modes is None and f_max is None:
        f_max = DEFAULT_F_MAX_HZ
    f_max, cb_factor, tol, interface_f_max = _check_arguments(
        n_modes=n_modes, f_max=f_max, cb_factor=cb_factor, tol=tol,
        interface_f_max=interface_f_max, damping=damping, backend=backend, check=check,
        stress=stress, log=log)
    check_mass(fe)   # as eigenmodes: names the file, not LAPACK's words
    resolved = resolve_interfaces(fe, interfaces)
    system = interface_system(fe, resolved)
    b = np.concatenate(system.active)
    timings["interfaces_s"] = time.perf_counter() - t0

    t = time.perf_counter()
    factor_out = []
    try:
        Psi, n_rigid_hint = _basis(method, system, b, n_modes, f_max, backend=backend, tol=tol,
                                   timings=timings, cb_factor=cb_factor, factor_out=factor_out)
        n_constraint, n_inertia, C_res = b.size, 0, np.zeros((b.size, b.size))
        if interface_f_max is not None and b.size:
            from flexpipe.reduction.ccmodes import reduce_interface

            Psi, n_constraint, n_inertia, C_res = reduce_interface(
                system.M, system.K, Psi, b, interface_f_max=interface_f_max,
                inertia_f_max=None if f_max is None else INERTIA_FACTOR * f_max,
                factor=factor_out[0] if factor_out else None)
    except ModelError as exc:
        raise ModelError(_explain(fe, system, exc)) from None
    timings["basis_s"] = time.perf_counter() - t
    t = time.perf_counter()
    Psi, omega = cms.orthonormalize(system.M, system.K, Psi)
    try:
        n_rigid = cms.detect_rigid_modes(omega) if n_rigid_hint is None else n_rigid_hint
    except ModelError as exc:
        raise ModelError(_explain(fe, system, exc)) from None
    f_hz = omega / (2 * np.pi)
    f_hz[:n_rigid] = np.where(f_hz[:n_rigid] < 1e-300, 0.0, f_hz[:n_rigid])

    dpn, n = fe.dofs_per_node, fe.n_nodes
    trans = (np.arange(n)[:, None] * dpn + np.arange(3)).ravel()
    Et = sp.csr_matrix(system.E[trans])
    U = np.asarray(Et @ Psi)  # (3 n, m) nodal translations
    shapes = []  # (6, m) hardpoint motion per interface (no rotation rows: zero)
    for bj in system.boundary:
        S = np.zeros((6, Psi.shape[1]))
        S[:len(bj)] = Psi[bj]
        shapes.append(S)

    mass, com, J_com, J_origin = mass_properties(fe.M, fe.nodes, dpn)
    Mt = translational_block(fe.M, dpn)
    inv = ffrf_invariants(fe.nodes, Mt, U[:, n_rigid:])
    R = rigid_body_vectors(fe.nodes, dpn)
    MR = fe.M @ R
    C = Psi.T @ (system.E.T @ MR)  # modal content of the six rigid-body motions
    checks = {"rigid_mass_matrix_full": R.T @ MR, "rigid_mass_matrix_reduced": C.T @ C}
    timings["expand_s"] = time.perf_counter() - t
    if check:
        t = time.perf_counter()
        checks.update(_full_model_checks(fe, system, U, len(f_hz), backend=backend))
        timings["check_s"] = time.perf_counter() - t

    smodes = None
    if stress is not None and str(stress).lower() != "none":
        from flexpipe.flexbody.stress import stress_modes

        t = time.perf_counter()
        smodes = stress_modes(fe, np.asarray(system.E @ Psi[:, n_rigid:]),
                              np.arange(n_rigid, Psi.shape[1]), selection=stress)
        timings["stress_s"] = time.perf_counter() - t
    zeta = _damping_ratios(damping, f_hz, n_rigid)
    m = len(f_hz)
    ends = np.cumsum([len(a) for a in system.active])
    offsets = [np.arange(e - len(a), e) for a, e in zip(system.active, ends, strict=True)]
    mesh = fe.mesh
    triangles = surface_triangles(mesh) if mesh is not None else np.zeros((0, 3), np.int64)
    from flexpipe import __version__

    meta = {
        "flexpipe_version": __version__, "n_dof": int(fe.n_dof), "n_nodes": int(n),
        "dofs_per_node": int(dpn), "n_modes_requested": None if n_modes is None else int(n_modes),
        "f_max_hz": None if f_max is None else float(f_max), "source": mesh.source if mesh else "",
        "n_boundary_dof": int(b.size), "n_constraint_modes": int(n_constraint),
        "n_inertia_vectors": int(n_inertia),
        "interface_f_max_hz": None if interface_f_max is None else float(interface_f_max),
        **{k: round(v, 4) for k, v in timings.items()},
        "total_s": round(time.perf_counter() - t0, 4),
    }
    return FlexBody(
        nodes=fe.nodes, triangles=triangles, modes=U.reshape(n, 3, m), frequencies_hz=f_hz,
        n_rigid=n_rigid, M=np.eye(m), K=np.diag(omega**2), D=np.diag(2 * zeta * omega),
        damping_ratio=zeta, mass=mass, center_of_mass=com, inertia=J_com,
        inertia_origin=J_origin, invariants=inv,
        interfaces=tuple(BodyInterface(name=r.name, point=r.point, nodes=r.nodes, shapes=s,
                                       kind=r.kind, dofs=r.dofs,
                                       residual_compliance=C_res[np.ix_(o, o)])
                         for r, s, o in zip(resolved, shapes, offsets, strict=True)),
        method=method, source_hash=mesh_hash(mesh) if mesh is not None else "",
        meta=meta, checks=checks, stress=smodes,
    )


def _check_arguments(*, n_modes, f_max, cb_factor, tol, interface_f_max, damping, backend,
                     check, stress, log):
    """Every argument of :func:`reduce` by its own name, before any work: returns the
    numbers as floats (``f_max, cb_factor, tol, interface_f_max``; None stays None)."""
    from flexpipe._args import checked_bool, checked_int, checked_number
    from flexpipe.fem.solver import available_backends

    if n_modes is not None:
        checked_int(n_modes, "n_modes", lo=0)
    if f_max is not None:
        f_max = checked_number(f_max, "f_max", lo=0.0, unit="Hz")
    cb_factor = checked_number(cb_factor, "cb_factor", lo=0.0)
    if tol is not None:  # eigenvalue errors ~ tol^2: beyond 0.1 they exceed 1 %
        tol = checked_number(tol, "tol", lo=0.0, hi=0.1)
    if interface_f_max is not None and not (  # inf keeps every characteristic mode
            isinstance(interface_f_max, (int, float, np.number)) and interface_f_max == np.inf):
        interface_f_max = checked_number(interface_f_max, "interface_f_max", lo=0.0,
                                         unit="Hz")
    if damping is not None and not callable(damping):
        try:
            zeta = np.asarray(damping, dtype=float)
        except (TypeError, ValueError):
            zeta = None
        if zeta is None or zeta.ndim > 1 or zeta.size == 0:
            raise InputError("damping must be a ratio (e.g. 0.02), one ratio per mode or a "
                             f"function f(f_hz) -> ratio, got {damping!r}", key="damping")
        if not np.all(np.isfinite(zeta)) or np.any(zeta < 0):
            raise InputError(f"damping ratios must be finite and >= 0, got {damping!r}",
                             key="damping")
    valid = available_backends()
    if backend is not None and backend not in valid:
        known = "'pardiso', 'superlu'"
        raise InputError(f"backend must be None (default) or one of {known} (available "
                         f"here: {', '.join(map(repr, valid))}), got {backend!r}",
                         key="backend")
    checked_bool(check, "check")
    if stress is not None and not isinstance(stress, str):
        raise InputError("stress must be None, 'none', 'all' or the name of a cell set of "
                         f"the mesh, got {type(stress).__name__} {stress!r}", key="stress")
    if log is not None and not callable(log):
        raise InputError(f"log must be a function log(line) or None, got {log!r}", key="log")
    return f_max, cb_factor, tol, interface_f_max


def _basis(method, system, b, n_modes, f_max, *, backend, tol, timings, cb_factor,
           factor_out=None):
    """Ritz basis of ``method`` on the interface system, and the rigid count if known."""
    if method == "craig-bampton":
        f_cb = None if f_max is None else cb_factor * f_max
        Psi, _ = cms._craig_bampton(system.M, system.K, b, n_modes, f_max=f_cb,
                                    backend=backend, tol=tol, timings=timings,
                                    factor_out=factor_out)
        return Psi, None
    if method == "residual-flexibility":
        Psi, _, n_rigid = cms._residual_flexibility(system.M, system.K, b, n_modes, f_max=f_max,
                                                    backend=backend, tol=tol)
        return Psi, n_rigid
    _, Psi, n_rigid, _, _, _ = cms._free_modes(system.M, system.K, n_modes, f_max=f_max,
                                               backend=backend, tol=tol)
    return Psi, n_rigid


def _explain(fe, system, exc) -> str:
    """The message of a failed basis: the mesh file, the error, and the diagnosis (extra
    zero-energy modes and where they move, or the shells' ``--thickness``)."""
    msg = str(exc)
    src = fe.mesh.source if fe.mesh is not None and fe.mesh.source else ""
    diag = _diagnose(fe, system)
    if not diag:
        thin = thickness_note(fe)
        diag = f"; check the shell thickness: {thin}" if thin else ""
    return f"{src + ': ' if src and not msg.startswith(src) else ''}{msg}{diag}"


def _diagnose(fe, system) -> str:
    """Where is the structure singular?  Zero-energy modes beyond the six rigid ones
    (the test and words :func:`flexpipe.fem.eigenmodes` warns with)."""
    try:
        from flexpipe.reduction.eigen import lowest_modes

        lam, X = lowest_modes(system.K, system.M, min(19, system.K.shape[0]))
        n_zero = count_zero_modes(np.sqrt(np.clip(lam, 0, None)))
        if n_zero <= 6:
            return ""
        # the zero-energy motions M-orthogonal to the six exact rigid-body motions
        MR = system.E.T @ (fe.M @ rigid_body_vectors(fe.nodes, fe.dofs_per_node))
        Z = X[:, :n_zero]
        U = np.asarray(system.E @ (Z @ extra_directions(MR, Z)))
        moved = describe_motion(fe, node_amplitude(fe, U))
    except Exception:  # noqa: BLE001 - the diagnosis must never hide the original error
        return ""
    return (f". Diagnosis: {n_zero} zero-energy modes where a free body has 6; "
            f"the extra motion is {moved}; likely cause: {likely_cause(fe)}")


def mac(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """Modal assurance criterion ``|a_i . b_j|^2 / (|a_i|^2 |b_j|^2)`` of columns."""
    num = (A.T @ B) ** 2
    den = np.outer(np.einsum("ij,ij->j", A, A), np.einsum("ij,ij->j", B, B))
    return num / np.where(den > 0, den, 1.0)


def _full_model_checks(fe, system, U, m, *, backend=None):
    """Free-free modes of the full model *with its interface spiders* (the model the
    reduction approximates) and the MAC of the reduced modes against them."""
    from flexpipe.reduction.eigen import lowest_modes

    k = min(m + 4, system.K.shape[0] - 1)
    lam, X = lowest_modes(system.K, system.M, k, backend=backend)
    f_full = np.sqrt(np.clip(lam, 0.0, None)) / (2 * np.pi)
    trans = (np.arange(fe.n_nodes)[:, None] * fe.dofs_per_node + np.arange(3)).ravel()
    shapes = np.asarray(sp.csr_matrix(system.E[trans]) @ X)
    return {"full_frequencies_hz": f_full, "mac": mac(U, shapes)}
