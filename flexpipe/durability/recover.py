"""Modal stress recovery: ``sigma(t) = S q(t)`` from a run's modal coordinates.

:func:`recover_stress` multiplies the body's stress modes (:mod:`flexpipe.flexbody.stress`)
by the elastic modal coordinates a run recorded (``Result.motion``), block by block in
element chunks that keep the temporaries near 64 MB, and reduces each element's history
to its maximum von Mises stress, the time and location (shell surface, beam end) of that
maximum and the signed maximum principal stress there.  With a fatigue material it also
counts rainflow cycles of each element's signed von Mises stress (von Mises with the sign
of the principal stress of largest magnitude) at its critical location and sums Miner
damage (:mod:`flexpipe.durability.fatigue`).  Element stresses of a floating-frame body
are those of the elastic deformation: the frame's rigid motion causes none.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from flexpipe.durability.fatigue import FatigueMaterial, damage_bound, miner_damage
from flexpipe.errors import InputError

#: bytes of one stress-component history array of a chunk (cache-sized temporaries)
CHUNK_BYTES = 2**20
#: damage is counted exactly for every element whose upper bound reaches this fraction of
#: the largest exact damage (the rest cannot matter for the ranking)
DAMAGE_RTOL = 1e-6
LOCATIONS = {"shell": ("top", "bottom"), "beam": ("end 1", "end 2"), "solid": ("centroid",)}


# --------------------------------------------------------------------------- equivalents
def plane_equivalent(sx, sy, txy):
    """Von Mises and signed max-magnitude principal stress of plane stress states."""
    vm = np.sqrt(np.maximum(sx * sx - sx * sy + sy * sy + 3.0 * txy * txy, 0.0))
    c = 0.5 * (sx + sy)
    r = np.sqrt(0.25 * (sx - sy) ** 2 + txy * txy)
    p1, p2 = c + r, c - r
    return vm, np.where(np.abs(p1) >= np.abs(p2), p1, p2)


def solid_equivalent(s):
    """Von Mises and signed max-magnitude principal stress; ``s`` (6, ...) Voigt
    ``xx, yy, zz, yz, xz, xy``.  Principal stresses in closed form (trigonometric)."""
    xx, yy, zz, yz, xz, xy = s
    vm = np.sqrt(np.maximum(0.5 * ((xx - yy) ** 2 + (yy - zz) ** 2 + (zz - xx) ** 2)
                            + 3.0 * (yz * yz + xz * xz + xy * xy), 0.0))
    m = (xx + yy + zz) / 3.0
    a, b, c = xx - m, yy - m, zz - m
    J2 = (a * a + b * b + c * c) / 2.0 + xy * xy + yz * yz + xz * xz
    J3 = a * b * c + 2 * xy * yz * xz - a * yz * yz - b * xz * xz - c * xy * xy
    with np.errstate(invalid="ignore", divide="ignore"):
        arg = np.where(J2 > 0, 1.5 * np.sqrt(3.0) * J3 / np.maximum(J2, 1e-300) ** 1.5, 0.0)
    th = np.arccos(np.clip(arg, -1.0, 1.0)) / 3.0
    rr = 2.0 * np.sqrt(J2 / 3.0)
    p1 = m + rr * np.cos(th)
    p3 = m + rr * np.cos(th + 2.0 * np.pi / 3.0)
    return vm, np.where(np.abs(p1) >= np.abs(p3), p1, p3)


def equivalents(kind: str, sig: np.ndarray):
    """``(vm, sp)`` of shape (ne, n_loc, n) from components ``sig`` (ne, 6, n)."""
    if kind == "shell":
        m, b = sig[:, :3], sig[:, 3:]
        top = plane_equivalent(*(m + b).transpose(1, 0, 2))
        bot = plane_equivalent(*(m - b).transpose(1, 0, 2))
        return np.stack([top[0], bot[0]], axis=1), np.stack([top[1], bot[1]], axis=1)
    if kind == "beam":
        vms, sps = [], []
        for end in (0, 3):
            a, by, bz = sig[:, end], sig[:, end + 1], sig[:, end + 2]
            hi = a + np.abs(by) + np.abs(bz)
            lo = a - np.abs(by) - np.abs(bz)
            sp = np.where(np.abs(hi) >= np.abs(lo), hi, lo)
            vms.append(np.abs(sp))
            sps.append(sp)
        return np.stack(vms, axis=1), np.stack(sps, axis=1)
    vm, sp = solid_equivalent(sig.transpose(1, 0, 2))
    return vm[:, None], sp[:, None]


def _critical(kind, sig, want_signed):
    """Max von Mises over time and locations of a chunk ``sig`` (ne, 6, n).

    Returns ``(vmax, k, loc, sp, signed)``: max von Mises (ne,), its time index and
    location index, the signed principal stress there and, if ``want_signed``, the signed
    von Mises history (ne, n) at that location.  Shells use ``vm^2 = A +- B`` for the top
    and bottom surfaces (``A = Q(m) + Q(b)``, ``B = 2 Q(m, b)`` with ``Q`` the plane von
    Mises form), so the larger surface is ``A + |B|``; the principal stress of largest
    magnitude has the sign of ``sx + sy`` (plane stress) or of the axial stress (beams).
    """
    ne, _, n = sig.shape
    r = np.arange(ne)
    if kind == "shell":
        m1, m2, m3, b1, b2, b3 = (sig[:, i] for i in range(6))
        A = m1 * m1 - m1 * m2 + m2 * m2 + 3.0 * m3 * m3 + b1 * b1 - b1 * b2 + b2 * b2 \
            + 3.0 * b3 * b3
        B = 2.0 * (m1 * b1 + m2 * b2) - m1 * b2 - m2 * b1 + 6.0 * m3 * b3
        k = np.argmax(A + np.abs(B), axis=1)
        s = np.where(B[r, k] >= 0.0, 1.0, -1.0)
        c = sig[r, :, k]                                       # (ne, 6) at the max
        v, sp = plane_equivalent(*(c[:, :3] + s[:, None] * c[:, 3:]).T)
        loc = (s < 0).astype(np.int64)
        signed = None
        if want_signed:
            signed = np.sqrt(np.maximum(A + s[:, None] * B, 0.0))
            signed *= np.where(m1 + m2 + s[:, None] * (b1 + b2) >= 0.0, 1.0, -1.0)
        return v, k, loc, sp, signed
    if kind == "beam":
        vm = [np.abs(sig[:, e]) + np.abs(sig[:, e + 1]) + np.abs(sig[:, e + 2]) for e in (0, 3)]
        both = np.maximum(vm[0], vm[1])
        k = np.argmax(both, axis=1)
        loc = (vm[1][r, k] > vm[0][r, k]).astype(np.int64)
        axial = np.where(loc[:, None] == 1, sig[:, 3], sig[:, 0])
        sgn = np.where(axial >= 0.0, 1.0, -1.0)
        v = both[r, k]
        signed = np.where(loc[:, None] == 1, vm[1], vm[0]) * sgn if want_signed else None
        return v, k, loc, v * sgn[r, k], signed
    vm, sp = solid_equivalent(sig.transpose(1, 0, 2))
    k = np.argmax(vm, axis=1)
    return vm[r, k], k, np.zeros(ne, np.int64), sp[r, k], \
        (vm * np.sign(sp) if want_signed else None)


# --------------------------------------------------------------------------- result
@dataclass(eq=False)
class StressResult:
    """Per-element outcome of :func:`recover_stress` (arrays over all selected elements).

    Attributes
    ----------
    t : ndarray (n,)
        Times, s.
    element_id : ndarray of int
        Element ids of the mesh file.
    cell_type : ndarray of str
    centroid : ndarray (ne, 3)
        Body coordinates, m.
    max_von_mises : ndarray
        Largest von Mises stress over time and locations, Pa.
    time_of_max : ndarray
        When it occurs, s.
    location : ndarray of str
        ``top``/``bottom`` (shells), ``end 1``/``end 2`` (beams), ``centroid`` (solids).
    principal_at_max : ndarray
        Signed principal stress of largest magnitude at that time and location, Pa.
    nodal_max_von_mises : ndarray (n_nodes,) or None
        Solids: max von Mises over time of the nodal (averaged) stresses, Pa; NaN at nodes
        of no solid; None when the body has no solids with stresses.
    damage : ndarray or None
        Miner damage of the run (NaN where the upper bound is negligible, see
        :data:`DAMAGE_RTOL`); None without fatigue material.
    distance_km : float
        Distance travelled by the body origin, km.
    """

    t: np.ndarray
    element_id: np.ndarray
    cell_type: np.ndarray
    centroid: np.ndarray
    max_von_mises: np.ndarray
    time_of_max: np.ndarray
    location: np.ndarray
    principal_at_max: np.ndarray
    damage: np.ndarray | None = None
    distance_km: float = 0.0
    nodal_max_von_mises: np.ndarray | None = None
    material: FatigueMaterial | None = None
    _ref: dict = field(default_factory=dict, repr=False)

    @property
    def damage_per_km(self):
        """Damage per km driven (None without fatigue)."""
        if self.damage is None or self.distance_km <= 0:
            return None
        return self.damage / self.distance_km

    def history(self, index: int):
        """``(von_mises, signed_principal)`` time histories (Pa) of element ``index`` (a
        position in these arrays) at its critical location."""
        blk, row, loc = self._ref["where"][index]
        sig = self._ref["sigma"](blk, np.array([row]))
        vm, sp = equivalents(self._ref["kinds"][blk], sig)
        return vm[0, loc], sp[0, loc]

    def top(self, n: int = 20, *, by: str = "von_mises") -> np.ndarray:
        """Positions of the ``n`` elements with the highest max von Mises (or damage)."""
        key = self.max_von_mises if by == "von_mises" else np.nan_to_num(self.damage, nan=-1.0)
        return np.argsort(-key, kind="stable")[:n]


def _modal_columns(body, motion):
    sm = body.stress
    pos = {int(k): j for j, k in enumerate(sm.mode_index)}
    try:
        return np.array([pos[int(k)] for k in motion.mode_index], dtype=np.int64)
    except KeyError as exc:
        raise InputError(f"the run's mode {exc.args[0]} has no stress mode in this body "
                         "(body file from another reduction?)", key="body") from None


def recover_stress(result, body, *, fatigue: FatigueMaterial | None = None,
                   progress: bool = False) -> StressResult:
    """Modal stress recovery of a run (see module docstring).

    Parameters
    ----------
    result : Result or BodyMotion
        A flexible-body run with ``result.motion`` (or the motion itself).
    body : FlexBody
        The body of that run, reduced with stress modes (``reduce(..., stress="all")``).
    fatigue : FatigueMaterial, optional
        Basquin S-N data: also count rainflow cycles and Miner damage per element.
    progress : bool
        Show a progress bar over element chunks.

    Returns
    -------
    StressResult
    """
    motion = getattr(result, "motion", result)
    if motion is None or not hasattr(motion, "q"):
        raise InputError("the result holds no body motion (modal coordinates); run a "
                         "flexible body with this flexpipe version", key="result")
    if body.stress is None:
        raise InputError("the body has no stress modes; reduce it with stress='all' or a "
                         "cell set", key="body")
    if motion.n_modes == 0:
        raise InputError("the run has no elastic modal coordinates (rigid body)", key="result")
    cols = _modal_columns(body, motion)
    q = np.ascontiguousarray(motion.q.T)  # (m, n)
    n = q.shape[1]
    blocks = body.stress.blocks
    kinds = [b.kind for b in blocks]
    # the run's modes only, one (ne * 6, m) matrix per block: one GEMM per chunk
    S = [np.ascontiguousarray(b.modes[:, :, cols]).reshape(-1, len(cols)) for b in blocks]

    def sigma(bi, rows):
        idx = (6 * np.asarray(rows)[:, None] + np.arange(6)).ravel()
        return (S[bi][idx] @ q).reshape(len(rows), 6, n)

    chunk = max(4, int(CHUNK_BYTES // (8 * max(n, 1))))
    jobs = [(bi, np.arange(s, min(s + chunk, len(b)))) for bi, b in enumerate(blocks)
            for s in range(0, len(b), chunk)]
    it = jobs
    if progress:
        from tqdm import tqdm

        it = tqdm(jobs, desc="stress recovery", unit="chunk")
    vmax, imax, loc, spmax, smax, smin, nrev = ([] for _ in range(7))
    for bi, rows in it:
        sig = (S[bi][6 * rows[0]:6 * (rows[-1] + 1)] @ q).reshape(len(rows), 6, n)
        v, k, lo, sp, signed = _critical(kinds[bi], sig, fatigue is not None)
        vmax.append(v)
        imax.append(k)
        loc.append(lo)
        spmax.append(sp)
        if signed is not None:
            smax.append(signed.max(axis=1))
            smin.append(signed.min(axis=1))
            d = np.sign(np.diff(signed, axis=1))
            nrev.append(2 + np.count_nonzero(d[:, 1:] * d[:, :-1] < 0, axis=1))
    where = [(bi, int(j), int(lc)) for (bi, rows), lcs in zip(jobs, loc, strict=True)
             for j, lc in zip(rows, lcs, strict=True)]
    cat = np.concatenate
    loc_names = np.array([LOCATIONS[kinds[bi]][lc] for bi, _, lc in where], dtype=object)
    p = motion.position
    dist = float(np.sum(np.linalg.norm(np.diff(p[:, :2], axis=0), axis=1))) / 1000.0
    out = StressResult(
        t=motion.t, element_id=cat([b.ids for b in blocks]),
        cell_type=np.array([b.cell_type for b in blocks for _ in range(len(b))], dtype=object),
        centroid=cat([b.centroids for b in blocks]), max_von_mises=cat(vmax),
        time_of_max=motion.t[cat(imax)], location=loc_names, principal_at_max=cat(spmax),
        distance_km=dist, material=fatigue,
        _ref={"where": where, "sigma": sigma, "kinds": kinds})
    out.nodal_max_von_mises = _nodal_max(blocks, cols, q, len(body.nodes))
    if fatigue is not None:
        out.damage = _damage(out, fatigue, cat(smax), cat(smin), cat(nrev), progress=progress)
    return out


def _nodal_max(blocks, cols, q, n_nodes):
    """Max von Mises over time of the solids' nodal stress modes (None without solids)."""
    out = None
    n = q.shape[1]
    chunk = max(4, int(CHUNK_BYTES // (8 * max(n, 1))))
    for b in blocks:
        if not len(b.nodes):
            continue
        if out is None:
            out = np.full(n_nodes, np.nan)
        Sn = np.ascontiguousarray(b.nodal[:, :, cols]).reshape(-1, len(cols))
        for s in range(0, len(b.nodes), chunk):
            e = min(s + chunk, len(b.nodes))
            vm, _ = solid_equivalent((Sn[6 * s:6 * e] @ q).reshape(e - s, 6, n)
                                     .transpose(1, 0, 2))
            out[b.nodes[s:e]] = np.fmax(out[b.nodes[s:e]], vm.max(axis=1))
    return out


def _damage(out: StressResult, material, smax, smin, nrev, *, progress=False) -> np.ndarray:
    """Exact Miner damage in decreasing order of its upper bound, until negligible."""
    bound = damage_bound(smax, smin, nrev, material)
    damage = np.full(len(bound), np.nan)
    best = 0.0
    bar = None
    if progress:
        from tqdm import tqdm

        bar = tqdm(desc="rainflow", unit="element")
    for i in np.argsort(-bound, kind="stable"):
        if bound[i] <= 0 or (best > 0 and bound[i] < DAMAGE_RTOL * best):
            break
        vm, sp = out.history(int(i))
        damage[i] = miner_damage(vm * np.sign(sp), material)
        best = max(best, damage[i])
        if bar is not None:
            bar.update(1)
    if bar is not None:
        bar.close()
    return damage
