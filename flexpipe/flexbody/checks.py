"""Consistency checks of a FlexBody read from a file (:func:`check_body_arrays`).

A body file can be damaged or edited so that it still parses; these checks reject what
no reduction can produce, each error naming the file and the entry:

* every array has the shape implied by the node and mode counts, and is finite;
* mass > 0, inertia symmetric and positive semi-definite, ``inertia_origin`` equal to
  ``inertia`` moved to the origin (parallel-axis theorem) -- a scaled inertia fails;
* frequencies non-negative and ascending, ``M = I`` and ``K = diag((2 pi f)^2)`` (the
  modal normalisation :class:`~flexpipe.flexbody.FlexBody` documents) -- a scaled or
  NaN-corrupted ``K`` fails; damping ratios >= 0;
* triangle and interface node indices inside ``[0, n_nodes)``, interface shapes 6 x m,
  and the tied nodes of each interface moving rigidly with its hardpoint in every mode
  (``u = u_h + theta_h x (x - x_h)``, the RBE2 constraint) -- scaled modes fail.
"""

from __future__ import annotations

import numpy as np

from flexpipe.errors import InputError

#: relative tolerance of the identities M = I, K = diag(omega^2), parallel-axis inertia
REL_TOL = 1e-6


def _fail(path, key, message):
    raise InputError(message, file=path, key=key)


def check_body_arrays(path, header: dict, arrays: dict, inv, interfaces) -> None:
    """Raise :class:`~flexpipe.errors.InputError` naming ``path`` and the entry at fault."""
    n = len(arrays["nodes"]) if arrays["nodes"].ndim >= 1 else -1
    m = len(arrays["frequencies_hz"]) if arrays["frequencies_hz"].ndim == 1 else -1
    shapes = {"nodes": (n, 3), "modes": (n, 3, m), "frequencies_hz": (m,), "M": (m, m),
              "K": (m, m), "D": (m, m), "damping_ratio": (m,), "center_of_mass": (3,),
              "inertia": (3, 3), "inertia_origin": (3, 3)}
    if n < 1 or m < 1:
        _fail(path, "nodes" if n < 1 else "frequencies_hz",
              "empty or malformed: a body needs at least one node and one mode")
    for key, shape in shapes.items():
        a = arrays[key]
        if a.shape != shape:
            _fail(path, key, f"shape {a.shape}, expected {shape} for {n} nodes and {m} modes")
        if not np.all(np.isfinite(a)):
            bad = np.argwhere(~np.isfinite(a))[0].tolist()
            _fail(path, key, f"non-finite value at index {bad}; every entry must be finite")
    tri = arrays["triangles"]
    if tri.size and (tri.ndim != 2 or tri.shape[1] != 3):
        _fail(path, "triangles", f"shape {tri.shape}, expected (t, 3)")
    if tri.size and (tri.min() < 0 or tri.max() >= n):
        _fail(path, "triangles", f"node index {int(tri.max() if tri.max() >= n else tri.min())}"
              f" outside [0, {n}); the file's triangles do not belong to its nodes")
    mass = header["mass"]
    if not (np.isfinite(mass) and mass > 0):
        _fail(path, "header.mass", f"mass = {mass!r} kg; it must be a positive finite number")
    n_rigid = header["n_rigid"]
    if not 0 <= n_rigid <= m:
        _fail(path, "header.n_rigid", f"n_rigid = {n_rigid} outside [0, {m}]")
    J = arrays["inertia"]
    scale = max(float(np.abs(J).max()), 1e-300)
    if np.abs(J - J.T).max() > REL_TOL * scale or np.linalg.eigvalsh(J).min() < -REL_TOL * scale:
        _fail(path, "inertia", "not a symmetric positive semi-definite inertia tensor")
    c = arrays["center_of_mass"]
    Jo = J + mass * (c @ c * np.eye(3) - np.outer(c, c))
    if np.abs(Jo - arrays["inertia_origin"]).max() > REL_TOL * max(float(np.abs(Jo).max()),
                                                                   1e-300):
        _fail(path, "inertia_origin", "differs from inertia + mass (|c|^2 I - c c^T) (parallel "
              "axis theorem): inertia, mass or centre of mass were changed")
    f = arrays["frequencies_hz"]
    fmax = max(float(np.abs(f).max()), 1.0)
    if f.min() < -REL_TOL * fmax:
        k = int(np.argmin(f))
        _fail(path, "frequencies_hz", f"negative frequency {f[k]:.6g} Hz at mode {k}; natural "
              "frequencies are >= 0")
    if np.any(np.diff(f) < -REL_TOL * fmax):
        k = int(np.flatnonzero(np.diff(f) < -REL_TOL * fmax)[0])
        _fail(path, "frequencies_hz", f"not ascending at mode {k + 1} ({f[k]:.6g} > "
              f"{f[k + 1]:.6g} Hz)")
    if n_rigid < m and f[n_rigid] <= 0:
        _fail(path, "frequencies_hz", f"elastic mode {n_rigid} has frequency {f[n_rigid]:.6g} "
              "Hz; elastic modes have positive frequencies")
    if np.abs(arrays["M"] - np.eye(m)).max() > REL_TOL:
        _fail(path, "M", "the reduced mass matrix must be the identity (mass-normalised modes)")
    K, w2 = arrays["K"], (2 * np.pi * f) ** 2
    if np.abs(K - np.diag(w2)).max() > REL_TOL * max(float(w2.max()), 1.0):
        _fail(path, "K", "the reduced stiffness must be diag((2 pi f)^2) of frequencies_hz: "
              "K was changed or scaled")
    zeta = arrays["damping_ratio"]
    if zeta.min() < 0:
        _fail(path, "damping_ratio", f"negative damping ratio {zeta.min():.6g}")
    for name, a in inv.as_dict().items():
        if not np.all(np.isfinite(np.asarray(a, dtype=float))):
            _fail(path, f"invariants.{name}", "non-finite value")
    for j, itf in enumerate(interfaces):
        if itf.nodes.size and (itf.nodes.min() < 0 or itf.nodes.max() >= n):
            _fail(path, f"interface.{j}.nodes", f"interface '{itf.name}': node index outside "
                  f"[0, {n})")
        if itf.shapes.shape != (6, m) or not np.all(np.isfinite(itf.shapes)):
            _fail(path, f"interface.{j}.shapes", f"interface '{itf.name}': shapes must be "
                  f"6 x {m} finite numbers")
        if not np.all(np.isfinite(itf.point)):
            _fail(path, f"interface.{j}.point", "non-finite hardpoint")
        _check_spider(path, j, itf, arrays["nodes"], arrays["modes"])


def _check_spider(path, j, itf, nodes, modes) -> None:
    """The tied nodes move rigidly with the hardpoint: ``u = u_h + theta_h x (x - x_h)``
    in every mode (exact for the RBE2 elimination; a scaled ``modes`` or ``shapes`` fails)."""
    if not itf.nodes.size or itf.dofs != 6 or itf.kind not in ("rbe2", "node"):
        return  # a 3-DOF interface ties translations only: no rigid rotation to check
    S = itf.shapes  # (6, m)
    r = nodes[itf.nodes] - itf.point  # (k, 3)
    rigid = S[None, :3, :] + np.cross(np.broadcast_to(S[3:].T[None], (len(r), S.shape[1], 3)),
                                      r[:, None, :]).transpose(0, 2, 1)
    U = modes[itf.nodes]  # (k, 3, m)
    scale = max(float(np.abs(U).max()), float(np.abs(rigid).max()), 1e-300)
    if np.abs(U - rigid).max() > 1e-6 * scale:
        _fail(path, f"interface.{j}.shapes", f"interface '{itf.name}': the mode shapes at its "
              "tied nodes do not follow the hardpoint's rigid motion (modes or interface "
              "shapes were changed or scaled)")
