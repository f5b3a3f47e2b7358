"""Tyre forces inside the implicit step: a linearization per step, corrected every step.

The tyre model (:meth:`flexpipe.tires.contact.TireModel.wheel_forces`) is nonlinear and
has a slip-relaxation state.  Holding its force constant over a step (operator
splitting) makes the longitudinal and lateral hub forces first-order accurate in the step
(measured on the prismatic sample, ISO C, 70 km/h, before this coupling: x and y hub
forces 52-57 % of their fluctuation off at 2 ms against 0.125 ms, issue "Numbers that
converge").  Instead, per step,
the force on each wheel at the *end* of the step is written as

    F(v_P, omega, z, theta) = F0 + D_v (v_P - v_P,n) + d_w (omega - omega_n) + A (z - z_n)
                              + S theta

(contact-point velocity of the wheel carrier ``v_P``, spin rate ``omega``, wheel-centre
height ``z``, small rotation ``theta`` of the carrier over the step: steer, toe and camber
changes turn the contact frame and the slip velocities) and handed to the implicit
integrator as a linear force element, so the integrator balances it at the end of the
step like any spring or damper.  The tyre's own moments (aligning, overturning, rolling
resistance) are linearized the same way and enter the same element.  ``F0`` is the force
predicted for the end of the step with the inputs held (road height taken under the wheel
where it will be); the derivatives come from batched evaluations of the tyre model with
perturbed inputs.

Relaxation (first-order, slip-velocity form) is integrated with the inputs varying
linearly over the step: at the start of the next step the state is *corrected* with every
input (velocities, spin, wheel position and axis, road height and normal) at the mean of
its values at the two ends of the step (trapezoidal input in the exact exponential update,
second order).  Each input therefore acts on the end-of-step force directly (load,
contact frame: full sensitivity) and through the relaxed slips (half): the predictor
separates the two by evaluating the perturbed inputs once with the slip state advanced
and once with it held.

Low speed: the slip velocities are regularised at ``VXLOW`` by the tyre model; at
standstill the relaxation state is a spring (``du/dt = w``) that is now implicit, so a
parked car no longer winds up (``tests/test_rollout.py``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexpipe.tires import _fast
from flexpipe.tires.contact import SlipState, _cross
from flexpipe.vehicle._tire_coupling_fast import correct_group, predict_group

#: finite-difference steps: velocity (m/s), spin rate (rad/s), height (m), rotation (rad)
DV, DW, DZ, DTH = 1e-3, 1e-2, 1e-5, 1e-5
#: wheel inputs the corrector averages over the step
_TRACKED = ("C", "s", "v", "w", "omega", "h_road", "n_road")


@dataclass
class TireStep:
    """What the integrator needs for one step (arrays over the 4 wheels)."""

    F0: np.ndarray  # (n, 3) force at the contact point predicted for the end of the step
    Dv: np.ndarray  # (n, 3, 3) dF/dv_P
    dw: np.ndarray  # (n, 3) dF/domega
    A: np.ndarray  # (n, 3) dF/dz (wheel-centre height)
    r: np.ndarray  # (n, 3) contact point - wheel centre, global
    moment: np.ndarray  # (n, 3) tyre moments (Mx, My, Mz; not the moment of F), global
    spin_axis: np.ndarray  # (n, 3)
    S: np.ndarray  # (n, 3, 3) dF/dtheta, small global rotation of the carrier
    #: force and own moment together (Y0 (n, 6), dY/dv_P (n, 6, 3), dY/domega (n, 6),
    #: dY/dz (n, 6), dY/dtheta (n, 6, 3)): the tyre element's input, as one block each;
    #: rows 3: are the own moment's (``moment`` and its derivatives), rows :3 the force's
    lin6: tuple


def _force_and_moment(out, C, rows, m):
    """(rows, m, 6): the force at the contact point and the tyre's own moment (not the
    moment of the force about the wheel centre ``C``)."""
    own = out.moment - _cross(out.contact_point - C, out.force)
    return np.concatenate([out.force, own], axis=1).reshape(rows, m, 6)


def _rows(ix):
    """Wheel indices ``ix`` (ascending) of a group: a slice when consecutive (the group's
    rows are views of the car's arrays, read and written in place), else an index array
    (read as a copy, written back by index)."""
    if ix == list(range(ix[0], ix[-1] + 1)):
        return slice(ix[0], ix[-1] + 1)
    return np.array(ix)


class ImplicitTires:
    """Per-step linearization of the tyre forces of a car (see module docstring).

    Parameters
    ----------
    tires : list of TireModel
        One per wheel (identical objects are evaluated together).
    mirror : ndarray of bool
        Mirrored characteristic per wheel.
    """

    def __init__(self, tires, mirror):
        groups = {}
        for i, t in enumerate(tires):
            groups.setdefault(id(t), (t, []))[1].append(i)
        #: (tyre, its wheels: a slice when consecutive, else an index array; see _rows)
        self.groups = [(t, _rows(ix)) for t, ix in groups.values()]
        self.mirror = np.asarray(mirror, dtype=bool)
        self._mirror = {id(t): self.mirror[ix].copy() for t, ix in self.groups}
        n = len(tires)
        self.state = {id(t): SlipState.zeros(len(ix)) for t, ix in groups.values()}
        #: groups evaluated by the compiled corrector and predictor (PAC2002 tyres)
        self.compiled = {id(t) for t, _ in self.groups
                         if _fast.enabled() and hasattr(t, "_packed")}
        self.n = n
        self._prev = None  # inputs of the last step, for the corrector

    @staticmethod
    def _take(a, ix):
        """``a[ix]`` as a contiguous float array (a view for a slice ``ix`` of a contiguous
        float array, else a copy: read only)."""
        return np.ascontiguousarray(a[ix], dtype=float)

    @staticmethod
    def _stack(x, k):
        return np.concatenate([x] * k, axis=0)

    def correct(self, kin, h: float):
        """Advance the relaxation state over the step just taken; return the tyre forces
        at its end (``WheelForces``-like dict of arrays over the wheels)."""
        out = {k: np.zeros(self.n) for k in ("Fx", "Fy", "Fz")}
        out["force"] = np.zeros((self.n, 3))
        prev = self._prev
        for tire, ix in self.groups:
            st = self.state[id(tire)]
            if id(tire) in self.compiled:
                self._correct_compiled(tire, ix, kin, prev, h, out)
                continue
            if prev is not None and tire.relaxation:
                # the relaxation over the step: every input (velocities and geometry) at
                # the mean of its values at the two ends (trapezoidal, second order)
                mid = {k: 0.5 * (kin[k][ix] + prev[k][ix]) for k in _TRACKED}
                st = tire.wheel_forces(mid["C"], mid["s"], mid["omega"], mid["v"],
                                       road_height=mid["h_road"], road_normal=mid["n_road"],
                                       angular_velocity=mid["w"], mirror=self.mirror[ix],
                                       state=st, dt=h).state
                self.state[id(tire)] = st
            # the force now: the new state, nothing advanced
            wf = tire.wheel_forces(kin["C"][ix], kin["s"][ix], kin["omega"][ix], kin["v"][ix],
                                   road_height=kin["h_road"][ix],
                                   road_normal=kin["n_road"][ix], angular_velocity=kin["w"][ix],
                                   mirror=self.mirror[ix], state=st if tire.relaxation else None,
                                   dt=0.0 if tire.relaxation else None)
            out["Fx"][ix], out["Fy"][ix], out["Fz"][ix] = wf.Fx, wf.Fy, wf.Fz
            out["force"][ix] = wf.force
        return out

    def _correct_compiled(self, tire, ix, kin, prev, h, out):
        st = self.state[id(tire)]
        kappa, tan_a = st.kappa.astype(float), st.tan_alpha.astype(float)
        a = [self._take(kin[k], ix) for k in _TRACKED]
        p = a if prev is None else [self._take(prev[k], ix) for k in _TRACKED]
        m = len(a[0])
        force, Fxyz = np.empty((m, 3)), np.empty((m, 3))
        bad = correct_group(tire._packed(), a[0], a[1], a[2], a[3], a[4], a[5], a[6],
                            p[0], p[1], p[2], p[3], p[4], p[5], p[6], prev is not None,
                            self._mirror[id(tire)], kappa, tan_a,
                            bool(tire.relaxation), float(h), force, Fxyz)
        _fast.check_rows(bad, a[1])
        self.state[id(tire)] = SlipState(kappa, tan_a)
        out["Fx"][ix], out["Fy"][ix], out["Fz"][ix] = Fxyz.T
        out["force"][ix] = force

    def predict(self, kin, h: float, road_ahead) -> TireStep:
        """Force predicted for the end of the coming step and its derivatives."""
        n = self.n
        F0 = np.zeros((n, 3))
        Dv = np.zeros((n, 6, 3))  # rows: force (3), the tyre's own moment (3)
        dw = np.zeros((n, 6))
        A = np.zeros((n, 6))
        S = np.zeros((n, 6, 3))
        r = np.zeros((n, 3))
        M = np.zeros((n, 3))
        for tire, ix in self.groups:
            if id(tire) in self.compiled:
                self._predict_compiled(tire, ix, kin, h, road_ahead,
                                       (F0, Dv, dw, A, S, r, M))
                continue
            C, s, v = kin["C"][ix], kin["s"][ix], kin["v"][ix]
            m = len(C)
            w, om = kin["w"][ix], kin["omega"][ix]
            rows = 9
            CC = self._stack(C, rows)
            SS = self._stack(s, rows)
            E = np.zeros((3 * m, 3))  # the carrier turned by DTH about global x, y, z
            E[np.arange(3 * m), np.repeat(np.arange(3), m)] = DTH
            SS[6 * m:] += _cross(E, np.concatenate([s] * 3))
            VV = self._stack(v, rows)
            OM = np.concatenate([om] * rows)
            VV[m:2 * m, 0] += DV
            VV[2 * m:3 * m, 1] += DV
            VV[3 * m:4 * m, 2] += DV
            OM[4 * m:5 * m] += DW
            # height slope: the secant to the height predicted for the end of the step
            # (a wheel that lands or lifts off within the step meets the kink of the
            # vertical force there), the tangent when the wheel hardly moves
            dz = h * v[:, 2]
            dz = np.where(np.abs(dz) > DZ, dz, DZ)
            CC[5 * m:6 * m, 2] += dz
            st = self.state[id(tire)]
            relax = bool(tire.relaxation)
            args = dict(road_height=np.concatenate([road_ahead[ix]] * rows),
                        road_normal=self._stack(kin["n_road"][ix], rows),
                        angular_velocity=self._stack(w, rows),
                        mirror=np.concatenate([self.mirror[ix]] * rows))
            wf = tire.wheel_forces(
                CC, SS, OM, VV, **args, dt=h if relax else None,
                state=SlipState(np.tile(st.kappa, rows), np.tile(st.tan_alpha, rows))
                if relax else None)
            # force at the contact point and the tyre's own moments (not the moment of F),
            # one 6-vector per row
            P = wf.contact_point[:m]

            Y = _force_and_moment(wf, CC, rows, m)
            Yb = Y[0]
            G = Y
            if relax:
                # each input acts directly (load, contact frame: full) and through the
                # slip velocities the corrector averages over the step (half): the direct
                # part is the force of the perturbed inputs with the slip state held
                held = SlipState(np.tile(wf.state.kappa[:m], rows),
                                 np.tile(wf.state.tan_alpha[:m], rows))
                Yd = _force_and_moment(tire.wheel_forces(CC, SS, OM, VV, **args, state=held,
                                                         dt=0.0), CC, rows, m)
                G = Yd + 0.5 * (Y - Yd)
            for k in range(3):
                Dv[ix, :, k] = (G[1 + k] - Yb) / DV
                S[ix, :, k] = (G[6 + k] - Yb) / DTH
            dw[ix] = (G[4] - Yb) / DW
            A[ix] = (G[5] - Yb) / dz[:, None]
            F0[ix] = Yb[:, :3]
            r[ix] = P - C
            M[ix] = Yb[:, 3:]
        self._prev = {k: kin[k].copy() for k in _TRACKED}
        return TireStep(F0=F0, Dv=Dv[:, :3], dw=dw[:, :3], A=A[:, :3], r=r, moment=M,
                        spin_axis=kin["s"].copy(), S=S[:, :3],
                        lin6=(np.concatenate([F0, M], axis=1), Dv, dw, A, S))

    def _predict_compiled(self, tire, ix, kin, h, road_ahead, full):
        st = self.state[id(tire)]
        g = {k: self._take(kin[k], ix) for k in ("C", "s", "v", "w", "omega", "n_road")}
        m = len(g["C"])
        # consecutive wheels: the kernel writes the car's rows in place (views); otherwise
        # into the group's own rows, copied to the car's afterwards
        views = isinstance(ix, slice)
        part = tuple(a[ix] if views else np.empty((m,) + a.shape[1:]) for a in full)
        bad = predict_group(tire._packed(), g["C"], g["s"], g["v"], g["w"], g["omega"],
                            g["n_road"], self._take(road_ahead, ix),
                            self._mirror[id(tire)],
                            st.kappa.astype(float), st.tan_alpha.astype(float),
                            bool(tire.relaxation), float(h), DV, DW, DZ, DTH, *part)
        _fast.check_rows(bad, g["s"])
        if not views:
            for dst, src in zip(full, part, strict=True):
                dst[ix] = src


def applied_force_reference(lin, st, s_axis, omega) -> np.ndarray:
    """Tyre force (n, 3) the integrator applied at the end of a step: the linearization
    ``lin = (TireStep, state at the step's start, spin rates there)`` carried to the new
    state ``st`` (spin axes ``s_axis``, spin rates ``omega``).  The NumPy reference of the
    compiled :func:`flexpipe.vehicle._tire_coupling_fast.applied_force`."""
    ts, st0, om0 = lin
    wc = st.wheel_w - np.einsum("ij,ij->i", st.wheel_w, s_axis)[:, None] * s_axis
    wc0 = st0.wheel_w - np.einsum("ij,ij->i", st0.wheel_w, ts.spin_axis)[:, None] \
        * ts.spin_axis
    vP = st.wheel_v + _cross(wc, ts.r)
    vP0 = st0.wheel_v + _cross(wc0, ts.r)
    F = (ts.F0 + np.einsum("nij,nj->ni", ts.Dv, vP - vP0)
         + ts.dw * (omega - om0)[:, None]
         + ts.A * (st.wheel_p[:, 2] - st0.wheel_p[:, 2])[:, None])
    # rotation of the carriers over the step (small angles)
    dR = st.wheel_R @ st0.wheel_R.transpose(0, 2, 1)
    th = 0.5 * np.stack([dR[:, 2, 1] - dR[:, 1, 2], dR[:, 0, 2] - dR[:, 2, 0],
                         dR[:, 1, 0] - dR[:, 0, 1]], axis=1)
    return F + np.einsum("nij,nj->ni", ts.S, th)
