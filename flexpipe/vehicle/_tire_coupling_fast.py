"""Compiled (Numba) corrector and predictor of :mod:`flexpipe.vehicle.tire_coupling`.

A transcription of :meth:`ImplicitTires.correct` and :meth:`ImplicitTires.predict` for
one group of wheels with the same PAC2002 tyre: the perturbed rows are built and the
compiled wheel kernel (:func:`flexpipe.tires._fast.wheel_kernel`) evaluated inside one
compiled call, so a car step pays Python's per-call overhead once per group instead of
for every array operation.  The NumPy methods stay the reference:
``tests/test_tire_coupling_fast.py`` checks both against each other.
"""

from __future__ import annotations

import numpy as np

from flexpipe.tires import _fast
from flexpipe.tires._fast import _cross3, _jit, drop_stale_caches, wheel_kernel

#: columns of the wheel kernel's output
_NOUT = 31


@_jit
def _own(out, CC, j, Y):
    """Force at the contact point and the tyre's own moment of row ``j`` into ``Y[j]``."""
    r0, r1, r2 = out[j, 6] - CC[j, 0], out[j, 7] - CC[j, 1], out[j, 8] - CC[j, 2]
    m0, m1, m2 = _cross3(r0, r1, r2, out[j, 0], out[j, 1], out[j, 2])
    Y[j, 0], Y[j, 1], Y[j, 2] = out[j, 0], out[j, 1], out[j, 2]
    Y[j, 3], Y[j, 4], Y[j, 5] = out[j, 3] - m0, out[j, 4] - m1, out[j, 5] - m2


@_jit
def correct_group(qa, C, s, v, w, om, h_road, n_road, pC, ps, pv, pw, pom, ph, pn,
                  has_prev, mirror, kappa, tan_a, relax, h, force, Fxyz):
    """Advance the slip state (``kappa``, ``tan_a``, in place) over the step with every
    input at the mean of its two ends; the force now into ``force`` (m, 3) and
    ``Fxyz`` (m, 3: Fx, Fy, Fz).  Returns the first bad row or -1."""
    m = C.shape[0]
    mu = np.ones(m)
    out = np.empty((m, _NOUT))
    if has_prev and relax:
        mC, ms, mv, mw = 0.5 * (C + pC), 0.5 * (s + ps), 0.5 * (v + pv), 0.5 * (w + pw)
        mom, mh, mn = 0.5 * (om + pom), 0.5 * (h_road + ph), 0.5 * (n_road + pn)
        bad = wheel_kernel(qa, mC, ms, mn, mom, mv, mw, True, mh, mirror, mu, kappa, tan_a,
                           True, h, out)
        if bad >= 0:
            return bad
        for i in range(m):
            kappa[i], tan_a[i] = out[i, 29], out[i, 30]
    bad = wheel_kernel(qa, C, s, n_road, om, v, w, True, h_road, mirror, mu, kappa, tan_a,
                       relax, 0.0, out)
    if bad >= 0:
        return bad
    for i in range(m):
        for k in range(3):
            force[i, k] = out[i, k]
            Fxyz[i, k] = out[i, 18 + k]
    return -1


@_jit
def predict_group(qa, C, s, v, w, om, n_road, road_ahead, mirror, kappa, tan_a, relax, h,
                  DV, DW, DZ, DTH, F0, Dv, dw, A, S, r, M):
    """Force and own moment predicted for the end of the step and their finite-difference
    derivatives (outputs as :meth:`ImplicitTires.predict`, rows of this group: ``Dv``,
    ``S`` (m, 6, 3), ``dw``, ``A`` (m, 6)).  Returns the first bad row or -1."""
    m = C.shape[0]
    R = 9 * m
    CC, SS, VV, WW, NN = (np.empty((R, 3)), np.empty((R, 3)), np.empty((R, 3)),
                          np.empty((R, 3)), np.empty((R, 3)))
    OM, RH, SK, ST, MU = np.empty(R), np.empty(R), np.empty(R), np.empty(R), np.ones(R)
    MI = np.empty(R, dtype=np.bool_)
    for b in range(9):
        for i in range(m):
            j = b * m + i
            for k in range(3):
                CC[j, k], SS[j, k], VV[j, k] = C[i, k], s[i, k], v[i, k]
                WW[j, k], NN[j, k] = w[i, k], n_road[i, k]
            OM[j], RH[j], MI[j] = om[i], road_ahead[i], mirror[i]
            SK[j], ST[j] = kappa[i], tan_a[i]
    dz = np.empty(m)
    for i in range(m):
        VV[m + i, 0] += DV
        VV[2 * m + i, 1] += DV
        VV[3 * m + i, 2] += DV
        OM[4 * m + i] += DW
        d = h * v[i, 2]
        dz[i] = d if abs(d) > DZ else DZ
        CC[5 * m + i, 2] += dz[i]
        for k in range(3):  # the carrier turned by DTH about global x, y, z
            e0, e1, e2 = (DTH if k == 0 else 0.0), (DTH if k == 1 else 0.0), \
                (DTH if k == 2 else 0.0)
            c0, c1, c2 = _cross3(e0, e1, e2, s[i, 0], s[i, 1], s[i, 2])
            j = (6 + k) * m + i
            SS[j, 0] += c0
            SS[j, 1] += c1
            SS[j, 2] += c2
    out = np.empty((R, _NOUT))
    bad = wheel_kernel(qa, CC, SS, NN, OM, VV, WW, True, RH, MI, MU, SK, ST, relax,
                       h if relax else 0.0, out)
    if bad >= 0:
        return bad
    Y = np.empty((R, 6))
    for j in range(R):
        _own(out, CC, j, Y)
    G = Y
    if relax:  # the direct part: perturbed inputs with the slip state held
        for b in range(9):
            for i in range(m):
                SK[b * m + i], ST[b * m + i] = out[i, 29], out[i, 30]
        out2 = np.empty((R, _NOUT))
        bad = wheel_kernel(qa, CC, SS, NN, OM, VV, WW, True, RH, MI, MU, SK, ST, True, 0.0,
                           out2)
        if bad >= 0:
            return bad
        Yd = np.empty((R, 6))
        for j in range(R):
            _own(out2, CC, j, Yd)
        G = Yd + 0.5 * (Y - Yd)
    for i in range(m):
        for c in range(6):
            yb = Y[i, c]
            for k in range(3):
                Dv[i, c, k] = (G[(1 + k) * m + i, c] - yb) / DV
                S[i, c, k] = (G[(6 + k) * m + i, c] - yb) / DTH
            dw[i, c] = (G[4 * m + i, c] - yb) / DW
            A[i, c] = (G[5 * m + i, c] - yb) / dz[i]
        for k in range(3):
            F0[i, k] = Y[i, k]
            r[i, k] = out[i, 6 + k] - C[i, k]
            M[i, k] = Y[i, 3 + k]
    return -1


@_jit
def applied_force(F0, Dv, dw, A, S, r, s0, w0, v0, om0, z0, R0, s, w, v, om, z, R):
    """Compiled ``CarController._applied_tire_force``: the linearized tyre force (n, 3)
    at the new state (``s``, ``w``, ``v``, ``om``, ``z``, ``R``: spin axis, angular
    velocity, velocity, spin rate, height and rotation of each carrier) from the
    linearization made at the old one (``s0`` ... ``R0``)."""
    n = F0.shape[0]
    out = np.empty((n, 3))
    for i in range(n):
        a = w[i, 0] * s[i, 0] + w[i, 1] * s[i, 1] + w[i, 2] * s[i, 2]
        a0 = w0[i, 0] * s0[i, 0] + w0[i, 1] * s0[i, 1] + w0[i, 2] * s0[i, 2]
        c0, c1, c2 = w[i, 0] - a * s[i, 0], w[i, 1] - a * s[i, 1], w[i, 2] - a * s[i, 2]
        d0, d1, d2 = w0[i, 0] - a0 * s0[i, 0], w0[i, 1] - a0 * s0[i, 1], \
            w0[i, 2] - a0 * s0[i, 2]
        x0, x1, x2 = _cross3(c0, c1, c2, r[i, 0], r[i, 1], r[i, 2])
        y0, y1, y2 = _cross3(d0, d1, d2, r[i, 0], r[i, 1], r[i, 2])
        dvP = (v[i, 0] + x0 - v0[i, 0] - y0, v[i, 1] + x1 - v0[i, 1] - y1,
               v[i, 2] + x2 - v0[i, 2] - y2)
        # rotation of the carrier over the step (small angles): dR = R R0^T
        dR = np.empty((3, 3))
        for j in range(3):
            for k in range(3):
                dR[j, k] = R[i, j, 0] * R0[i, k, 0] + R[i, j, 1] * R0[i, k, 1] \
                    + R[i, j, 2] * R0[i, k, 2]
        th = (0.5 * (dR[2, 1] - dR[1, 2]), 0.5 * (dR[0, 2] - dR[2, 0]),
              0.5 * (dR[1, 0] - dR[0, 1]))
        dom, dz = om[i] - om0[i], z[i] - z0[i]
        for j in range(3):
            out[i, j] = (F0[i, j] + Dv[i, j, 0] * dvP[0] + Dv[i, j, 1] * dvP[1]
                         + Dv[i, j, 2] * dvP[2] + dw[i, j] * dom + A[i, j] * dz
                         + S[i, j, 0] * th[0] + S[i, j, 1] * th[1] + S[i, j, 2] * th[2])
    return out


# these kernels compile the wheel kernel of flexpipe/tires/_fast.py into themselves
drop_stale_caches((_own, correct_group, predict_group, applied_force), _fast.__file__)
