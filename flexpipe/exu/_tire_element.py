"""The tyre's linear element on a wheel carrier, compiled (Numba): D, K, f per wheel.

:meth:`flexpipe.exu.car.CarSystem.tire_matrices` maps the per-step linearization of the
tyre force and moment (:class:`flexpipe.vehicle.tire_coupling.TireStep`) onto the eight
coordinates of a wheel: the carrier node's position and Euler parameters and the spin
coordinate.  With ``Y = (F, M)`` (force at the contact point, the tyre's own moment),

    Y = Y0 + DY (v_P - v_P,n) + dY (omega - omega_n) + AY (z - z_n) + SY G (e - e_n)

and ``JY`` the map from coordinate rates to (contact-point velocity of the wheel, the
rotation the moment works on), the element is ``D = -JY^T (DY Jc + dY Jw)``,
``K[:, z] = -JY^T AY``, ``K[:, e] = -JY^T SY G`` and ``f = JY^T (Y0 - DY v_P,n - ...)``.
The spin coordinate is the wheel's absolute rotation about its axis: the wheel turns on
a bearing, so the carrier's rotation about that axis neither turns the wheel nor takes a
moment about it.  The moments' parts about the spin axis (of the contact force and the
tyre's own) go to the spin coordinate, the rest to the carrier.

The wheel's spin momentum ``J omega s`` turns with the carrier: the bearing applies
``J omega (w_c x s)`` to the wheel, so the carrier carries the gyroscopic moment
``M_g = J omega (s x w_c)`` (``w_c = G de/dt``), linearized in the step as a damping
(``-J omega_n G^T [s]x G`` on the carrier's rates, ``-J G^T (s x w_c,n)`` on the spin)
plus ``-J omega_n G^T (s x w_c,n)`` in ``f``.  It does no work (``M_g . w_c = 0``).
``tests/test_tire_element.py`` checks the compiled kernel against the NumPy formulation
(:func:`element_numpy`), and a spinning wheel on a free carrier conserves its angular
momentum.
"""

from __future__ import annotations

import numpy as np

from flexpipe.flexbody.invariants import skew
from flexpipe.tires._fast import _jit


def _g_matrix(e):
    """Global G of Euler parameters: omega = G de/dt, (3, 4)."""
    e0, e1, e2, e3 = e
    return 2.0 * np.array([[-e1, e0, -e3, e2], [-e2, e3, e0, -e1], [-e3, -e2, e1, e0]])


def element_numpy(ep, r, s, qt, q, Y0, DY, dY, AY, SY, J):
    """Reference formulation, one wheel at a time with NumPy (see module docstring)."""
    n = ep.shape[0]
    D, K, f = np.zeros((n, 8, 8)), np.zeros((n, 8, 8)), np.zeros((n, 8))
    for i in range(n):
        G = _g_matrix(ep[i])
        rx = skew(r[i])
        P = np.eye(3) - np.outer(s[i], s[i])
        JY = np.zeros((6, 8))
        JY[:3, :3] = np.eye(3)
        JY[:3, 3:7] = -rx @ P @ G
        JY[:3, 7] = -rx @ s[i]
        JY[3:, 3:7] = P @ G
        JY[3:, 7] = s[i]
        Jc = np.zeros((3, 8))
        Jc[:, :3] = np.eye(3)
        Jc[:, 3:7] = -rx @ P @ G
        Jw = np.zeros(8)
        Jw[7] = 1.0  # the spin coordinate is the wheel's absolute spin
        vP, om = Jc @ qt[i], Jw @ qt[i]
        SG = SY[i] @ G
        D[i] = -JY.T @ (DY[i] @ Jc + np.outer(dY[i], Jw))
        K[i, :, 2] = -JY.T @ AY[i]
        K[i, :, 3:7] = -JY.T @ SG
        rhs = Y0[i] - DY[i] @ vP - dY[i] * om - AY[i] * q[i, 2] - SG @ q[i, 3:7]
        f[i] = JY.T @ rhs
        # the spin momentum's gyroscopic moment on the carrier
        sx = skew(s[i])
        sw = sx @ (G @ qt[i, 3:7])
        D[i, 3:7, 3:7] -= J[i] * om * G.T @ sx @ G
        D[i, 3:7, 7] -= J[i] * G.T @ sw
        f[i, 3:7] -= J[i] * om * G.T @ sw
    return D, K, f


@_jit
def element(ep, r, s, qt, q, Y0, DY, dY, AY, SY, J):
    """Compiled :func:`element_numpy` (explicit loops over the small matrices)."""
    n = ep.shape[0]
    D = np.zeros((n, 8, 8))
    K = np.zeros((n, 8, 8))
    f = np.zeros((n, 8))
    G = np.zeros((3, 4))
    JY = np.zeros((6, 8))
    Jc = np.zeros((3, 8))
    PG = np.zeros((3, 4))
    for i in range(n):
        e0, e1, e2, e3 = ep[i, 0], ep[i, 1], ep[i, 2], ep[i, 3]
        G[0, 0], G[0, 1], G[0, 2], G[0, 3] = -2 * e1, 2 * e0, -2 * e3, 2 * e2
        G[1, 0], G[1, 1], G[1, 2], G[1, 3] = -2 * e2, 2 * e3, 2 * e0, -2 * e1
        G[2, 0], G[2, 1], G[2, 2], G[2, 3] = -2 * e3, -2 * e2, 2 * e1, 2 * e0
        r0, r1, r2 = r[i, 0], r[i, 1], r[i, 2]
        s0, s1, s2 = s[i, 0], s[i, 1], s[i, 2]
        sv = (s0, s1, s2)
        JY[:, :] = 0.0
        Jc[:, :] = 0.0
        for a in range(3):
            JY[a, a] = 1.0
            Jc[a, a] = 1.0
        # P G (the carrier's rotation without its part about the spin axis)
        for c in range(4):
            sg = s0 * G[0, c] + s1 * G[1, c] + s2 * G[2, c]
            for a in range(3):
                PG[a, c] = G[a, c] - sv[a] * sg
        for c in range(4):
            # -r x (PG col): rows of -rx @ P G
            p0, p1, p2 = PG[0, c], PG[1, c], PG[2, c]
            Jc[0, 3 + c] = -(r1 * p2 - r2 * p1)
            Jc[1, 3 + c] = -(r2 * p0 - r0 * p2)
            Jc[2, 3 + c] = -(r0 * p1 - r1 * p0)
            JY[0, 3 + c], JY[1, 3 + c], JY[2, 3 + c] = Jc[0, 3 + c], Jc[1, 3 + c], \
                Jc[2, 3 + c]
            JY[3, 3 + c], JY[4, 3 + c], JY[5, 3 + c] = p0, p1, p2
        JY[0, 7] = -(r1 * s2 - r2 * s1)
        JY[1, 7] = -(r2 * s0 - r0 * s2)
        JY[2, 7] = -(r0 * s1 - r1 * s0)
        JY[3, 7], JY[4, 7], JY[5, 7] = s0, s1, s2
        vP = np.zeros(3)
        om = qt[i, 7]  # Jw = e_7: the spin coordinate is the wheel's absolute spin
        for c in range(8):
            for a in range(3):
                vP[a] += Jc[a, c] * qt[i, c]
        # B = DY Jc + dY e_7^T (6, 8); SG = SY G (6, 4); rhs (6)
        rhs = np.zeros(6)
        for k in range(6):
            acc = Y0[i, k] - dY[i, k] * om - AY[i, k] * q[i, 2]
            for a in range(3):
                acc -= DY[i, k, a] * vP[a]
            for c in range(4):
                sgk = SY[i, k, 0] * G[0, c] + SY[i, k, 1] * G[1, c] + SY[i, k, 2] * G[2, c]
                acc -= sgk * q[i, 3 + c]
                for j in range(8):
                    K[i, j, 3 + c] -= JY[k, j] * sgk
            rhs[k] = acc
            for c in range(8):
                b = dY[i, k] if c == 7 else 0.0
                for a in range(3):
                    b += DY[i, k, a] * Jc[a, c]
                for j in range(8):
                    D[i, j, c] -= JY[k, j] * b
            for j in range(8):
                K[i, j, 2] -= JY[k, j] * AY[i, k]
                f[i, j] += JY[k, j] * rhs[k]
        # the spin momentum's gyroscopic moment on the carrier: s x (G col) per column
        w0 = w1 = w2 = 0.0
        for c in range(4):
            w0 += G[0, c] * qt[i, 3 + c]
            w1 += G[1, c] * qt[i, 3 + c]
            w2 += G[2, c] * qt[i, 3 + c]
        sw0, sw1, sw2 = s1 * w2 - s2 * w1, s2 * w0 - s0 * w2, s0 * w1 - s1 * w0
        Jw = J[i]
        for c in range(4):
            g0, g1, g2 = G[0, c], G[1, c], G[2, c]
            x0, x1, x2 = s1 * g2 - s2 * g1, s2 * g0 - s0 * g2, s0 * g1 - s1 * g0
            for a in range(4):
                D[i, 3 + a, 3 + c] -= Jw * om * (G[0, a] * x0 + G[1, a] * x1
                                                  + G[2, a] * x2)
            gsw = G[0, c] * sw0 + G[1, c] * sw1 + G[2, c] * sw2
            D[i, 3 + c, 7] -= Jw * gsw
            f[i, 3 + c] -= Jw * om * gsw
    return D, K, f
