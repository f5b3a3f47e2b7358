"""Wheel-road contact kinematics and the common tyre-model interface.

Frames
------
Global frame: ISO 8855 (x forward, y left, z up).  Per wheel the contact (TYDEX/ISO W)
frame is built from the road normal ``n`` and the unit spin axis ``s``:

* ``e_x = (s x n)/|s x n|`` — forward, along the wheel-plane / road-plane intersection;
* ``e_y = n x e_x`` — left, in the road plane;
* ``e_z = n``;
* inclination ``gamma = asin(s . n)`` (top of the wheel towards -y is positive);
* the contact point ``P`` is where the wheel-plane radius through the lowest point,
  direction ``s x e_x``, meets the road plane: loaded radius ``R_l = h / cos(gamma)`` with
  ``h`` the centre height above the plane, deflection ``rho = R0 - R_l``.

``s`` must be the axis about which *forward* rolling is a positive rotation — for a car in
ISO 8855 axes the wheel's +y (left) axis on **both** sides.  ``omega`` is the spin rate about
``s`` (``V = omega R`` when free rolling forward).  Slips (W-axes, see
:mod:`flexpipe.tires.pac2002`): ``kappa = -(Vcx - omega Re)/max(|Vcx|, VXLOW)``,
``tan(alpha) = Vcy / max(|Vcx|, VXLOW)`` — the floor at VXLOW (from the file, default
1 m/s) regularises standstill; the relaxed (transient) slips use the true speed.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError
from flexpipe.tires.relaxation import relax_slip_velocity

#: Bounds of the relaxed slips kept in :class:`SlipState` (beyond full sliding).
KAPPA_STATE_MAX = 1.5
TAN_ALPHA_STATE_MAX = 10.0


@dataclass(frozen=True)
class SlipState:
    """Relaxed slips carried between steps (one entry per wheel).

    Attributes
    ----------
    kappa : ndarray
        Relaxed longitudinal slip kappa'.
    tan_alpha : ndarray
        Tangent of the relaxed slip angle.
    """

    kappa: np.ndarray
    tan_alpha: np.ndarray

    @classmethod
    def zeros(cls, n: int) -> SlipState:
        """Undeformed tyres (no slip) for ``n`` wheels."""
        return cls(np.zeros(n), np.zeros(n))


@dataclass(frozen=True)
class WheelForces:
    """Result of :meth:`TireModel.wheel_forces` for n wheels.

    Attributes
    ----------
    force, moment : ndarray, shape (n, 3)
        Force on the wheel and moment about the wheel centre, global frame (N, N m).
    contact_point : ndarray, shape (n, 3)
        Contact point, global.
    frame : ndarray, shape (n, 3, 3)
        Rows are e_x, e_y, e_z of each contact (W) frame in global coordinates.
    Fx, Fy, Fz, Mx, My, Mz : ndarray, shape (n,)
        Contact forces/moments in the W-axes.
    kappa, alpha, gamma : ndarray, shape (n,)
        Slips used for the forces (relaxed ones when relaxation is active), rad for angles.
    deflection, deflection_rate : ndarray, shape (n,)
        Radial deflection (m, > 0 in contact) and its rate (m/s).
    state : SlipState or None
        Relaxed slips at the end of the step (pass to the next call).
    """

    force: np.ndarray
    moment: np.ndarray
    contact_point: np.ndarray
    frame: np.ndarray
    Fx: np.ndarray
    Fy: np.ndarray
    Fz: np.ndarray
    Mx: np.ndarray
    My: np.ndarray
    Mz: np.ndarray
    kappa: np.ndarray
    alpha: np.ndarray
    gamma: np.ndarray
    deflection: np.ndarray
    deflection_rate: np.ndarray
    state: SlipState | None


def iso_to_sae(Fx, Fy, Fz, Mx, My, Mz, alpha=0.0, gamma=0.0):
    """Convert contact forces/moments and slips from ISO/TYDEX W-axes to SAE tyre axes.

    SAE axes share x (forward) but have y to the right and z down, i.e. a rotation of pi
    about x: components along y and z change sign, the slip angle (measured about z)
    changes sign, the inclination angle (top of wheel towards the right is positive in
    both systems) does not.

    Returns
    -------
    tuple
        ``(Fx, Fy, Fz, Mx, My, Mz, alpha, gamma)`` in SAE axes.
    """
    return (Fx, -np.asarray(Fy), -np.asarray(Fz), Mx, -np.asarray(My), -np.asarray(Mz),
            -np.asarray(alpha), gamma)


def _cross(a, b):
    """Row-wise cross product of (n, 3) arrays (much cheaper than np.cross for small n)."""
    a0, a1, a2 = a[:, 0], a[:, 1], a[:, 2]
    b0, b1, b2 = b[:, 0], b[:, 1], b[:, 2]
    return np.column_stack((a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0))


def _dot(a, b):
    return (a * b).sum(axis=1)


def _unit(v, name):
    v = np.asarray(v, dtype=float)
    norm = np.linalg.norm(v, axis=-1, keepdims=True)
    if np.any(norm == 0) or not np.all(np.isfinite(norm)):
        raise InputError(f"{name} must be non-zero, finite vectors", key=name)
    return v / norm


class TireModel:
    """Common interface of the tyre models (:class:`Pac2002Tire`, :class:`FialaTire`).

    Subclasses provide ``vertical`` (:class:`VerticalModel`), ``unloaded_radius``,
    ``relaxation`` (bool), ``vxlow``, ``tyre_side``, ``mirror_all`` and the methods
    :meth:`slip_forces`, :meth:`relaxation_lengths`, :meth:`effective_rolling_radius`.
    """

    def slip_forces(self, kappa, alpha, Fz, gamma=0.0, *, vx=None, mirror=False,
                    mu_scale=1.0):  # pragma: no cover - interface
        raise NotImplementedError

    def relaxation_lengths(self, Fz, gamma=0.0):  # pragma: no cover - interface
        raise NotImplementedError

    def effective_rolling_radius(self, deflection):  # pragma: no cover - interface
        raise NotImplementedError

    def mirror_for(self, sides) -> np.ndarray:
        """Mirror flags for wheels mounted on ``sides`` (each ``'left'`` or ``'right'``).

        A wheel on the side opposite to the file's TYRESIDE (or every wheel for a negative
        USE_MODE) uses the mirrored characteristic; ``TYRESIDE = 'SYMMETRIC'`` never mirrors.
        """
        flags = []
        for side in sides:
            side = str(side).upper()
            if side not in ("LEFT", "RIGHT"):
                raise InputError(f"wheel side must be 'left' or 'right', got {side!r}", key="side")
            flags.append(self.tyre_side in ("LEFT", "RIGHT") and side != self.tyre_side)
        return np.array(flags, dtype=bool) ^ self.mirror_all

    def wheel_forces(self, center, spin_axis, omega, velocity, *, road_height,
                     road_normal=(0.0, 0.0, 1.0), angular_velocity=None, mirror=False,
                     mu_scale=1.0, state: SlipState | None = None,
                     dt: float | None = None) -> WheelForces:
        """Tyre force and moment on each wheel centre, global ISO 8855 frame.

        Parameters
        ----------
        center : array, shape (n, 3) or (3,)
            Wheel centre positions, m.
        spin_axis : array, shape (n, 3) or (3,)
            Spin axes (normalised here); forward rolling is positive about them.
        omega : float or array, shape (n,)
            Spin rate about ``spin_axis``, rad/s.
        velocity : array, shape (n, 3) or (3,)
            Wheel centre velocities, m/s.
        road_height : float or array, shape (n,)
            Road height z at each wheel centre's (x, y), m; the road is the plane through
            ``(x_c, y_c, road_height)`` with normal ``road_normal``.
        road_normal : array, shape (n, 3) or (3,)
            Upward road normal (normalised here).
        angular_velocity : array, shape (n, 3), optional
            Full wheel angular velocity; its non-spin part moves the contact point.
        mirror : bool or array of bool
            Use the mirrored characteristic (see :meth:`mirror_for`).
        mu_scale : float or array
            Road friction factor.
        state : SlipState, optional
            Relaxed slips from the previous step; relaxation is applied only when the model
            has ``relaxation=True`` and ``state`` and ``dt`` are given (otherwise the returned
            state holds the kinematic slips).  Lifted wheels get a zero state; the state is
            bounded to ``|kappa'| <= 1.5``, ``|tan alpha'| <= 10``.
        dt : float, optional
            Step length, s (needed with ``state``); 0 gives the force of ``state`` as it
            is, without advancing it.

        Returns
        -------
        WheelForces
        """
        C = np.atleast_2d(np.asarray(center, dtype=float))
        v = np.atleast_2d(np.asarray(velocity, dtype=float))
        s = np.atleast_2d(_unit(spin_axis, "spin_axis"))
        n = np.atleast_2d(_unit(road_normal, "road_normal"))
        if n.shape[0] != C.shape[0]:
            n = np.repeat(n, C.shape[0], axis=0)
        if s.shape[0] != C.shape[0]:
            s = np.repeat(s, C.shape[0], axis=0)
        omega = np.asarray(omega, dtype=float)

        h = n[:, 2] * (C[:, 2] - np.asarray(road_height, dtype=float))
        sin_g = np.clip(_dot(s, n), -1.0, 1.0)
        gamma = np.arcsin(sin_g)
        sxn = _cross(s, n)
        cos_g = np.linalg.norm(sxn, axis=1)
        ok = cos_g > 1e-6
        cos_safe = np.where(ok, cos_g, 1.0)
        ex = sxn / cos_safe[:, None]
        ey = _cross(n, ex)
        down = _cross(s, ex)
        Rl = h / cos_safe
        rho = np.where(ok, self.unloaded_radius - Rl, -1.0)
        P = C + Rl[:, None] * down
        rho_dot = -_dot(n, v) / cos_safe
        Fz = self.vertical.force(rho, rho_dot)

        Vc = v
        if angular_velocity is not None:
            w = np.atleast_2d(np.asarray(angular_velocity, dtype=float))
            w_carrier = w - _dot(w, s)[:, None] * s
            Vc = v + _cross(w_carrier, P - C)
        Vcx = _dot(Vc, ex)
        Vcy = _dot(Vc, ey)
        Vsx = Vcx - omega * self.effective_rolling_radius(rho)
        vden = np.maximum(np.abs(Vcx), self.vxlow)
        kappa = -Vsx / vden
        tan_a = Vcy / vden

        new_state = None
        if self.relaxation and state is not None:
            if dt is None or not dt >= 0:
                raise InputError("dt >= 0 is required with a relaxation state (0: the "
                                 "force of the state as it is)", key="dt")
            sk, sa = self.relaxation_lengths(np.maximum(Fz, 1e-3), gamma)
            has_k = sk > 0  # False for nan (no relaxation data)
            has_a = sa > 0
            k_new = relax_slip_velocity(state.kappa, -Vsx, Vcx, np.where(has_k, sk, 1.0), dt)
            t_new = relax_slip_velocity(state.tan_alpha, Vcy, Vcx, np.where(has_a, sa, 1.0), dt)
            # a lifted tyre has no carcass deflection; bound the state so that a wheel
            # spinning at standstill (no decay, |Vx| = 0) cannot wind it up without limit
            touch = Fz > 0.0
            kappa = np.where(has_k, np.where(touch, np.clip(k_new, -KAPPA_STATE_MAX,
                                                            KAPPA_STATE_MAX), 0.0), kappa)
            tan_a = np.where(has_a, np.where(touch, np.clip(t_new, -TAN_ALPHA_STATE_MAX,
                                                            TAN_ALPHA_STATE_MAX), 0.0), tan_a)
            new_state = SlipState(kappa, tan_a)
        elif state is not None:
            new_state = SlipState(kappa, tan_a)
        alpha = np.arctan(tan_a)

        sf = self.slip_forces(kappa, alpha, Fz, gamma, vx=Vcx, mirror=mirror, mu_scale=mu_scale)
        Fx, Fy, Mz, Mx, My = sf.Fx, sf.Fy, sf.Mz, sf.Mx, sf.My
        F = Fx[:, None] * ex + Fy[:, None] * ey + Fz[:, None] * n
        M = _cross(P - C, F) + Mx[:, None] * ex + My[:, None] * ey + Mz[:, None] * n
        return WheelForces(
            force=F, moment=M, contact_point=P, frame=np.stack([ex, ey, n], axis=1),
            Fx=Fx, Fy=Fy, Fz=Fz, Mx=Mx, My=My, Mz=Mz, kappa=kappa, alpha=alpha, gamma=gamma,
            deflection=rho, deflection_rate=rho_dot, state=new_state)
