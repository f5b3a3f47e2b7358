"""Accuracy of a reduced body at its interfaces against the unreduced FE model.

Static check: the body is held at a statically determinate set of interface translations
(``support``: ``[(interface name, components)]``, e.g. 3-2-1) and loaded by a unit force
at every interface translation in turn; the deflections of every interface translation
form the supported flexibility matrix ``G`` (3 k x 3 k, m/N).  For Craig-Bampton the
reduced ``G`` is exact (the static solution of boundary loads lies in the span of the
constraint modes); interface reduction loses part of it.

Dynamic check: free-free frequencies of the reduced body against the lowest eigenvalues
of the full model with its interface spiders.
"""

from __future__ import annotations

import numpy as np

from flexpipe.errors import InputError


def _support_rows(names, support):
    rows = []
    for name, comps in support:
        if name not in names:
            raise InputError(f"support names unknown interface {name!r}; valid: {names}",
                             key="support")
        rows += [3 * names.index(name) + int(c) for c in comps]
    if len(rows) != 6:
        raise InputError(f"a statically determinate support holds 6 translations, got "
                         f"{len(rows)}", key="support")
    return np.array(rows)


def supported_flexibility_full(fe, interfaces, support, *, backend=None):
    """``G`` of the unreduced model (see the module docstring)."""
    from flexpipe.reduction.eigen import factor_spd
    from flexpipe.reduction.interface import interface_system, resolve_interfaces

    resolved = resolve_interfaces(fe, interfaces)
    system = interface_system(fe, resolved)
    names = [r.name for r in resolved]
    tr = np.concatenate([b[:3] for b in system.boundary])
    pinned = tr[_support_rows(names, support)]
    K = system.K.tocsc()
    free = np.setdiff1d(np.arange(K.shape[0]), pinned)
    fac = factor_spd(K[free][:, free], backend=backend)
    F = np.zeros((K.shape[0], tr.size))
    F[tr, np.arange(tr.size)] = 1.0
    u = np.zeros_like(F)
    u[free] = fac.solve(F[free])
    return u[tr]


def supported_flexibility_reduced(body, support):
    """``G`` of a reduced :class:`~flexpipe.flexbody.FlexBody` (every mode, rigid ones
    included, with the support as Lagrange constraints)."""
    names = list(body.interface_names)
    rows = _support_rows(names, support)
    S = np.vstack([i.shapes[:3] for i in body.interfaces])
    m = body.n_modes
    A = np.block([[np.asarray(body.K), S[rows].T], [S[rows], np.zeros((6, 6))]])
    rhs = np.vstack([S.T, np.zeros((6, S.shape[0]))])
    return S @ np.linalg.solve(A, rhs)[:m]


def block_errors(G, G_ref, *, skip=()):
    """Per interface: ``||G_ii - G_ref_ii|| / ||G_ref_ii||`` of its 3 x 3 driving-point
    block (interfaces listed in ``skip``, by index, are left out: fully supported ones)."""
    k = G.shape[0] // 3
    out = []
    for i in range(k):
        if i in skip:
            continue
        b = slice(3 * i, 3 * i + 3)
        out.append(np.linalg.norm(G[b, b] - G_ref[b, b]) / np.linalg.norm(G_ref[b, b]))
    return np.array(out)


def full_frequencies(fe, interfaces, n: int, *, backend=None):
    """Lowest ``n`` free-free frequencies (Hz) of the full model with its spiders."""
    from flexpipe.reduction.eigen import lowest_modes
    from flexpipe.reduction.interface import interface_system, resolve_interfaces

    system = interface_system(fe, resolve_interfaces(fe, interfaces))
    lam, _ = lowest_modes(system.K, system.M, n, backend=backend)
    return np.sqrt(np.clip(lam, 0.0, None)) / (2 * np.pi)


__all__ = ["block_errors", "full_frequencies", "supported_flexibility_full",
           "supported_flexibility_reduced"]
