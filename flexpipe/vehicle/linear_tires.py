"""The tyres of a linearized car (:mod:`flexpipe.vehicle.linear`): central differences of
the tyre model a run uses.

Per wheel, the tyre's force at the contact point and its own moments, as generalized
forces on the carrier's seven coordinates and its spin coordinate (the run's tyre
element's map, :func:`flexpipe.exu._tire_element.element_numpy`), the rates of the relaxed
slips (kappa', tan alpha') and the vertical force, as functions of the carrier's
coordinates and velocities, the slips and the road (height and longitudinal slope under
the wheel).
"""

from __future__ import annotations

import numpy as np

#: step of the slip state's advance used for its rate (s), and the central differences of
#: the tyre's inputs: coordinates (m, Euler parameters), velocities (m/s, rad/s), slips
DT_SLIP, EPS_Q, EPS_V, EPS_S = 1e-6, 1e-7, 1e-6, 1e-7
#: central-difference step of the road inputs (m and rad)
EPS_ROAD = 1e-6


class TireLinearization:
    """The tyres' generalized forces on the wheel coordinates and their slip states'
    rates, as functions of the Exudyn state and the relaxed slips, and their derivatives."""

    def __init__(self, system, ctrl, slices):
        self.system, self.ctrl = system, ctrl
        n = len(system.wheel_node)
        self.kappa, self.tan_alpha = np.zeros(n), np.zeros(n)
        relax = np.zeros(n, dtype=bool)
        for tire, ix in ctrl.tires.groups:
            st = ctrl.tires.state[id(tire)]
            self.kappa[ix], self.tan_alpha[ix] = st.kappa, st.tan_alpha
            relax[ix] = bool(tire.relaxation)
        #: slip states: (wheel, 0 = kappa' / 1 = tan alpha') of the relaxing tyres
        self.states = [(i, c) for i in range(n) if relax[i] for c in (0, 1)]
        #: the 8 ODE2 indices of each wheel: carrier node (7), spin coordinate (1)
        self.idx = [np.r_[np.arange(slices[int(w)].start, slices[int(w)].stop),
                          slices[int(s)].start]
                    for w, s in zip(system.wheel_node, system.spin_node, strict=True)]

    def generalized(self, road=None):
        """(Q (4, 8), slip rates (4, 2), Fz (4,), F (4, 3): the force at the contact
        point, global) at the current Exudyn state and slips;
        ``road``: (4, 3) offsets of the road height (m) and of its longitudinal and
        lateral slopes (rad: dh/dx along the body's x axis, dh/dy along its y axis, to
        the left) under each wheel."""
        from flexpipe.exu._tire_element import element_numpy
        from flexpipe.tires.contact import SlipState
        from flexpipe.vehicle.tire_coupling import _force_and_moment

        sy, ctrl = self.system, self.ctrl
        st = sy.state(0.0)
        s_axis = st.wheel_R[:, :, 1]
        omega = st.spin_rate  # the wheels' absolute spin, as a run's
        h_road, n_road = ctrl.road_contact(st.wheel_p)
        if road is not None:  # the road raised and tilted under each wheel
            up = np.array([0.0, 0.0, 1.0])
            fwd = st.body_R[:, 0] - st.body_R[2, 0] * up
            fwd /= np.linalg.norm(fwd)
            left = np.cross(up, fwd)
            h_road = h_road + road[:, 0]
            n_road = n_road - road[:, 1:2] * fwd[None, :] - road[:, 2:3] * left[None, :]
            n_road /= np.linalg.norm(n_road, axis=1)[:, None]
        w = st.wheel_w + st.spin_rate[:, None] * s_axis
        n = len(omega)
        Y, r, rate = np.zeros((n, 6)), np.zeros((n, 3)), np.zeros((n, 2))
        Fz = np.zeros(n)
        for tire, ix in ctrl.tires.groups:
            relax = bool(tire.relaxation)
            args = (st.wheel_p[ix], s_axis[ix], omega[ix], st.wheel_v[ix])
            kw = dict(road_height=h_road[ix], road_normal=n_road[ix],
                      angular_velocity=w[ix], mirror=ctrl.tires.mirror[ix])
            state = SlipState(self.kappa[ix].copy(), self.tan_alpha[ix].copy())
            wf = tire.wheel_forces(*args, **kw, state=state if relax else None,
                                   dt=0.0 if relax else None)
            m = len(omega[ix])
            Y[ix] = _force_and_moment(wf, st.wheel_p[ix], 1, m)[0]
            Fz[ix] = wf.Fz
            r[ix] = wf.contact_point - st.wheel_p[ix]
            if relax:
                adv = tire.wheel_forces(*args, **kw, state=state, dt=DT_SLIP).state
                rate[ix, 0] = (adv.kappa - self.kappa[ix]) / DT_SLIP
                rate[ix, 1] = (adv.tan_alpha - self.tan_alpha[ix]) / DT_SLIP
        ep = sy.wheel_ref[:, 3:] + st.wheel_q[:, 3:]
        qt = np.concatenate([st.wheel_qt, st.spin_rate[:, None]], axis=1)
        z6, z63 = np.zeros((n, 6)), np.zeros((n, 6, 3))
        D, _, f = element_numpy(ep, r, s_axis, qt, st.wheel_q, Y, z63, z6, z6, z63,
                                np.asarray(sy.spec.spin_inertia, dtype=float))
        Q = f - np.einsum("nij,nj->ni", D, qt)  # with the wheels' gyroscopic moments
        return Q, rate, Fz, Y[:, :3]

    def _flat(self, size: int, road=None):
        """(Q over all ODE2 coordinates (size,), rates of the slip states), Fz (4,), the
        force vectors (12,: wheel by wheel, global x, y, z) as one vector."""
        Q, rate, Fz, F = self.generalized(road)
        out = np.zeros(size)
        for i, ix in enumerate(self.idx):
            out[ix] += Q[i]
        return np.concatenate([out, [rate[i, c] for i, c in self.states], Fz, F.ravel()])

    def derivatives(self, size: int):
        """``K_t, D_t`` (size, size): minus the tyre force's derivatives by coordinates and
        velocities; ``B`` (size, s): by the slips; ``E_q, E_v`` (s, size) and ``A_s``
        (s, s): the slips' rates by coordinates, velocities and slips; ``U`` (size + s, 8):
        force and slip rates by the road inputs (height, slopes under each wheel); ``F``:
        the derivatives (``q``, ``v``, slips, road inputs) of the vertical tyre forces
        (4 rows) and of the tyre force vectors (12 rows, global, wheel by wheel)."""
        from flexpipe.exu.linearize import coordinate_derivatives

        cols = np.concatenate(self.idx)
        ns = len(self.states)
        n_w = len(self.idx)
        dq, dv = coordinate_derivatives(self.system.mbs, cols, lambda: self._flat(size),
                                        eps_q=EPS_Q, eps_v=EPS_V)
        Kt, Dt = np.zeros((size, size)), np.zeros((size, size))
        Eq, Ev = np.zeros((ns, size)), np.zeros((ns, size))
        Fq, Fv = np.zeros((4 * n_w, size)), np.zeros((4 * n_w, size))
        Kt[:, cols], Dt[:, cols] = -dq[:size], -dv[:size]
        Eq[:, cols], Ev[:, cols] = dq[size:size + ns], dv[size:size + ns]
        Fq[:, cols], Fv[:, cols] = dq[size + ns:], dv[size + ns:]
        d_slip = np.zeros((size + ns + 4 * n_w, ns))
        for k, (i, c) in enumerate(self.states):
            slip = (self.kappa, self.tan_alpha)[c]
            vals = []
            for sgn in (1.0, -1.0):
                slip[i] += sgn * EPS_S
                vals.append(self._flat(size))
                slip[i] -= sgn * EPS_S
            d_slip[:, k] = (vals[0] - vals[1]) / (2.0 * EPS_S)
        d_road = np.zeros((size + ns + 4 * n_w, 3 * n_w))
        for j in range(3 * n_w):
            vals = []
            for sgn in (1.0, -1.0):
                road = np.zeros((n_w, 3))
                road[j % n_w, j // n_w] = sgn * EPS_ROAD
                vals.append(self._flat(size, road))
            d_road[:, j] = (vals[0] - vals[1]) / (2.0 * EPS_ROAD)
        B, As = d_slip[:size], d_slip[size:size + ns]
        F = (Fq, Fv, d_slip[size + ns:], d_road[size + ns:])
        return Kt, Dt, B, Eq, Ev, As, d_road[:size + ns], F
