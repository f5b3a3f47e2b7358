"""Linear modes of the whole car (Adams/Linear): frequencies, damping, energy by part.

The car (rigid or flexible body, linkage suspensions, tyres) is assembled as for a run,
settled at rest (:mod:`flexpipe.vehicle.settle`) or, at a speed, run straight on a flat
road until it is steady, and linearized there:

- the multibody part (body, its elastic modes, every link, bushing, spring, damper, stop,
  anti-roll bar, rack, subframe and powertrain) by :func:`flexpipe.exu.linearize.linearize`:
  central differences of Exudyn's equations, including the constraint forces' geometric
  stiffness, reduced to the constraints' nullspace.  A dual-rate damper enters with the
  mean of its two slopes at zero velocity (the central difference of its table); a bump
  stop in contact with its slope;
- the tyres by central differences of the tyre model the run uses: its force and own
  moment on each wheel carrier and spin coordinate as functions of the carrier's position,
  attitude, velocities and spin rate, and of the relaxed slips (kappa', tan alpha'), whose
  first-order relaxation ``sigma s' ' + |Vx| s' = w`` adds two states per tyre.  At rest
  the relaxation is the tyre's horizontal spring; no brake acts (the car may roll: one
  free mode of body and wheels together).

The driver and the speed controller are not part of the linear model (controls fixed).
The state ``x = (y, y', s')`` (nullspace coordinates, their rates, relaxed slips) gives
``x' = A x``; its eigenvalues are the car's modes.  Each mode's kinetic energy is split
over the parts (body frame and its six motions, body elastic, each corner's parts, wheel
spin, steering, the rest).  ``tests/test_linear.py`` checks the modes against the
nonlinear run of the same car released from a disturbed state.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from flexpipe.errors import InputError
from flexpipe.vehicle.dynamics import ROAD_NORMAL_HALF_BASE_M

#: an eigenvalue below this (rad/s) is a free motion (the car rolling away, at rest the
#: relaxed slips' anchors): counted in ``info["free_modes"]``, not listed
FREE_RAD_S = 1e-3
CORNERS = ("fl", "fr", "rl", "rr")
BODY_MOTIONS = ("x", "y", "z", "roll", "pitch", "yaw")
_BODY_LABEL = {"x": "body fore-aft", "y": "body lateral", "z": "body bounce",
               "roll": "body roll", "pitch": "body pitch", "yaw": "body yaw"}
#: seconds a car is run straight before it is linearized at a speed
STEADY_S = 2.0


@dataclass(frozen=True)
class LinearModes:
    """Modes of a linearized car, sorted by natural frequency.

    Attributes
    ----------
    eigenvalues : ndarray, complex (k,)
        One of each conjugate pair (imaginary part >= 0), 1/s; the free motions (zero
        eigenvalues) are left out and counted in ``info["free_modes"]``.
    frequency_hz, damped_frequency_hz, damping_ratio : ndarray (k,)
        ``|lambda| / 2 pi``, ``Im(lambda) / 2 pi`` and ``-Re(lambda) / |lambda|`` (1 for a
        real, overdamped eigenvalue).
    energy : ndarray (k, len(groups))
        Each mode's kinetic energy split over ``groups`` (rows sum to 1).
    body_motion : ndarray (k, 6)
        The body frame's share of kinetic energy split over its motions x, y, z, roll,
        pitch, yaw (body axes, at its centre of mass; rows sum to 1 or are 0).
    label : tuple of str
        Dominant motion of each mode ("tyre relaxation" when the slip states take more
        than half of its participation).
    slip_participation : ndarray (k,)
        Share of the tyre slip states in each mode's participation factors (left times
        right eigenvector, summed over the states; 0: a purely mechanical mode).
    shapes : ndarray, complex (k, n)
        Mode shapes in Exudyn's coordinates (displacements).
    A : ndarray
        The state matrix of ``x = (y, y', s')``: ``x' = A x``.
    N : ndarray (n, k)
        Orthonormal basis of the constraints' nullspace: Exudyn's coordinates are
        ``q + N y``, their rates ``N y'``.
    q : ndarray (n,)
        Exudyn's coordinates at the linearization state.
    residual_N : float
        Largest force out of balance at the linearization state (N or N m).
    B, C, D : ndarray
        ``x' = A x + B u``, ``y = C x + D u``: ``inputs`` ``u`` are the road height (m)
        and its longitudinal and lateral slopes dh/dx, dh/dy (rad, body axes, y to the
        left) under each wheel (``road_<corner>_z``, ``road_<corner>_slope_x``,
        ``road_<corner>_slope_y``); ``outputs`` ``y`` the vertical tyre forces
        (``tire_<corner>_Fz``, N), the suspension travel (``travel_<corner>``, m, jounce
        along the body's z axis), the hub forces (``hub_<corner>_<x|y|z>``, N, body axes,
        :mod:`flexpipe.vehicle.linear_hub`) and the accelerations of the car's named body
        points in body axes (``acc_<point>_<x|y|z>``, m/s^2), as a run's channels name
        them.
    """

    car: str
    body: str
    speed: float
    eigenvalues: np.ndarray
    frequency_hz: np.ndarray
    damped_frequency_hz: np.ndarray
    damping_ratio: np.ndarray
    energy: np.ndarray
    groups: tuple
    body_motion: np.ndarray
    label: tuple
    slip_participation: np.ndarray
    shapes: np.ndarray
    A: np.ndarray
    N: np.ndarray
    q: np.ndarray
    residual_N: float
    B: np.ndarray
    C: np.ndarray
    D: np.ndarray
    inputs: tuple
    outputs: tuple
    info: dict = field(default_factory=dict)
    #: the body at the linearization state (for :func:`~flexpipe.vehicle.linear_output.
    #: write_shapes`): its frame's and modal node's coordinate slices, frame position,
    #: rotation and Euler parameters, modal coordinates, and the FlexBody (None if rigid)
    body_state: dict | None = None

    def frequency_response(self, f_hz) -> np.ndarray:
        """``H`` (len(f_hz), outputs, inputs), complex: the steady response ``y = H u`` to
        harmonic inputs at the frequencies ``f_hz`` (Hz)."""
        f = np.atleast_1d(np.asarray(f_hz, dtype=float))
        eye = np.eye(self.A.shape[0])
        out = np.empty((f.size, *self.D.shape), dtype=complex)
        for i in range(0, f.size, 256):  # batched solves, 256 frequencies at a time
            s = 2j * np.pi * f[i:i + 256, None, None]
            out[i:i + 256] = self.C @ np.linalg.solve(s * eye - self.A, self.B) + self.D
        return out

    def track_response(self, f_hz, *, tracks: str = "same", H=None) -> np.ndarray:
        """``H`` (len(f_hz), outputs), complex: the response to a road profile per unit of
        its height: on both tracks (``tracks="same"``), or on the left track and its
        negative on the right (``"opposite"``: a roll and warp input; the road's
        cross-section straight between the wheels, so each axle also meets the lateral
        slope ``2 / track`` times the height).  At a speed each wheel meets the profile
        at its own place (the rear ``wheelbase / V`` later) with its longitudinal slope as
        a run's tyre meets it, the central difference over ``+-e`` (``e`` =
        :data:`~flexpipe.vehicle.dynamics.ROAD_NORMAL_HALF_BASE_M`): ``j sin(k e) / e``
        times the height at the wavenumber ``k = omega / V``; at rest all four wheels
        move in phase (a four-post rig's heave, or its roll with ``"opposite"``).
        ``H``: the :meth:`frequency_response` at ``f_hz`` if already at hand."""
        from flexpipe._args import checked_choice

        checked_choice(tracks, "tracks", ("same", "opposite"))
        f = np.atleast_1d(np.asarray(f_hz, dtype=float))
        H = self.frequency_response(f) if H is None else H
        n_w = len(self.inputs) // 3
        w = 2 * np.pi * f[:, None]
        if self.speed > 0.0:
            x = np.asarray(self.info["wheel_x_m"], dtype=float)
            gain = np.exp(-1j * w * ((x.max() - x) / self.speed)[None, :])
            e = ROAD_NORMAL_HALF_BASE_M
            slope_x = 1j * np.sin(w / self.speed * e) / e * gain
        else:
            gain, slope_x = np.ones((len(f), n_w)), np.zeros((len(f), n_w))
        slope_y = np.zeros_like(gain)
        if tracks == "opposite":
            y = np.asarray(self.info["wheel_y_m"], dtype=float)
            side = np.where(y > 0.0, 1.0, -1.0)
            track = np.empty(n_w)
            for i in range(0, n_w, 2):  # the axles: (fl, fr), (rl, rr)
                track[i:i + 2] = abs(y[i] - y[i + 1])
            slope_y = (2.0 / track)[None, :] * gain  # the same under both wheels
            gain, slope_x = gain * side, slope_x * side
        return (np.einsum("fow,fw->fo", H[:, :, :n_w], gain)
                + np.einsum("fow,fw->fo", H[:, :, n_w:2 * n_w], slope_x)
                + np.einsum("fow,fw->fo", H[:, :, 2 * n_w:], slope_y))

    def rows(self) -> list[dict]:
        """One dict per mode (the CSV's columns, units in the keys)."""
        out = []
        for k, lam in enumerate(self.eigenvalues):
            row = {"mode": k + 1, "frequency_Hz": float(self.frequency_hz[k]),
                   "damped_frequency_Hz": float(self.damped_frequency_hz[k]),
                   "damping_ratio": float(self.damping_ratio[k]),
                   "real_1/s": float(lam.real), "imag_1/s": float(lam.imag),
                   "label": self.label[k],
                   "tyre_slip_participation": float(self.slip_participation[k])}
            row.update({f"energy_{g.replace(' ', '_')}": float(e)
                        for g, e in zip(self.groups, self.energy[k], strict=True)})
            row.update({f"body_{m}": float(e)
                        for m, e in zip(BODY_MOTIONS, self.body_motion[k], strict=True)})
            out.append(row)
        return out


def linear_modes(car, *, body: str = "flexible", speed: float = 0.0, road=None,
                 f_max=None, max_mode_hz=None, cache: bool = True, log=None) -> LinearModes:
    """Linearize the car at rest (or in steady straight running) and return its modes.

    Parameters
    ----------
    car : Car or str or Path
        A car with linkage suspensions (:func:`flexpipe.load_car`).
    body : {"flexible", "rigid", "full"}
        Body model, as :func:`flexpipe.simulate`.
    speed : float
        0 (default): parked, settled; > 0: run straight at this speed (m/s) for
        :data:`STEADY_S` on ``road`` and linearized there.
    road : Road, str, Path or None
        The road the car settles or runs on before it is linearized (default flat; the
        linear model holds at the state reached there).
    f_max, max_mode_hz, cache, log
        As :func:`flexpipe.simulate`.

    Raises
    ------
    InputError
        A car without linkage suspensions, a speed outside 0-300 km/h, an unknown body.
    """
    from flexpipe._args import as_path, checked_choice, checked_number
    from flexpipe.vehicle.simulation import simulate
    from flexpipe.vehicle.spec import Car, load_car

    speed = checked_number(speed, "speed", lo=0.0, hi=300 / 3.6, lo_closed=True,
                           unit="m/s")
    body = checked_choice(body, "body", ("flexible", "rigid", "full"))
    if not isinstance(car, Car):
        car = load_car(as_path(car, "car"))
    if car.suspension is None:
        raise InputError("this car has prismatic corners, no [suspension.*] tables; the "
                         "linear analysis needs a linkage car (e.g. "
                         "cars/sedan_linkage.toml): the prismatic corners' anti-roll bars "
                         "act outside the implicit equations", file=car.file, key="car")
    # the run's assembly, settled, handed to the analysis instead of the run; the body
    # with its own modal masses and damping (a run fits them to its step: prewarp)
    modes = simulate(car, road=road, speed=speed, t_end=1.0, body=body, f_max=f_max,
                     max_mode_hz=max_mode_hz, cache=cache, log=log, prewarp=False,
                     probe=lambda system, ctrl: _analyse(system, ctrl, speed=speed))
    modes["info"]["seats"] = [asdict(s) for s in car.body.seats]  # ride_response
    return LinearModes(car=car.name, body=body, speed=float(speed), **modes)


# ---------------------------------------------------------------------------- analysis
def _analyse(system, ctrl, *, speed: float) -> dict:
    from scipy.linalg import eig

    from flexpipe.exu.linearize import (
        hold_tires,
        linearize,
        node_slices,
        start_from_initial,
        steady_translation,
    )
    from flexpipe.vehicle.linear_hub import hub_rows
    from flexpipe.vehicle.linear_tires import TireLinearization
    from flexpipe.vehicle.simulation import SPECTRAL_RADIUS

    start_from_initial(system.mbs)
    if speed > 0.0:
        ok, t, *_ = system.run(ctrl, t_end=STEADY_S, h=ctrl.h, spectral_radius=SPECTRAL_RADIUS)
        if not ok or ctrl.status < 0:
            raise RuntimeError(f"the run to a steady state at {speed:g} m/s stopped at "
                               f"t = {t:.3f} s: {ctrl.message}")
        # the state reached, its decaying transients' velocities removed: the whole car
        # translating along the road, the wheels spinning as they do
        st = system.state(0.0)
        n = np.mean(ctrl.road_contact(st.wheel_p)[1], axis=0)
        n /= np.linalg.norm(n)
        steady_translation(system.mbs, st.body_v - (st.body_v @ n) * n,
                           keep=system.spin_node)
    st = system.state(0.0)
    loads = ctrl(st)
    if loads is None:
        raise RuntimeError(f"the car's state cannot be linearized: {ctrl.message}")
    system.apply(loads, st.mount_R, st)
    slices = node_slices(system.mbs)
    tires = TireLinearization(system, ctrl, slices)
    # the tyres' force at the state as a constant force in Exudyn's element: their
    # derivatives come from tires.derivatives; at rest no brake holds the wheels
    Q, _, Fz, F_tire = tires.generalized()
    hold_tires(system, Q, release_spin=speed == 0.0)
    # the spin torques' reactions follow the wheels' spin axes (as a run sets them)
    lin = linearize(system.mbs, follow=lambda: system.set_spin_reactions(
        loads.spin_torque, loads.drive_torque, system.state(0.0)))
    Kt, Dt, B, Eq, Ev, Az, Ur, Fz_d = tires.derivatives(lin.q.size)
    K, D, N = lin.K + Kt, lin.D + Dt, lin.N
    Mr, Kr, Dr = N.T @ lin.M @ N, N.T @ K @ N, N.T @ D @ N
    k, ns = N.shape[1], Az.shape[0]
    Minv = np.linalg.inv(Mr)
    A = np.zeros((2 * k + ns, 2 * k + ns))
    A[:k, k:2 * k] = np.eye(k)
    A[k:2 * k, :k] = -Minv @ Kr
    A[k:2 * k, k:2 * k] = -Minv @ Dr
    A[k:2 * k, 2 * k:] = Minv @ (N.T @ B)
    A[2 * k:, :k] = Eq @ N
    A[2 * k:, k:2 * k] = Ev @ N
    A[2 * k:, 2 * k:] = Az
    body = _body_state(system, slices, lin.q)
    io = _io_matrices(system, lin, N, A, Minv, Ur, Fz_d, k, R=body["rotation"])
    n_w = Fz.size
    Ch, Dh, hub = hub_rows(system, lin, N=N, A=A, Bx=io["B"], K=K, D=D, B_slip=B,
                           Ur=Ur[:lin.q.size], F_tire=F_tire,
                           T_d=tuple(d[n_w:] for d in Fz_d), R=body["rotation"])
    io.update(C=np.vstack([io["C"], Ch]), D=np.vstack([io["D"], Dh]),
              outputs=io["outputs"] + tuple(hub))
    lam, L, X = eig(A, left=True, right=True)
    # participation of the tyre slip states in each mode (unit-free: left times right
    # eigenvector, summed over the slip states, as a share of the sum over all states)
    p = np.abs(np.real(np.conj(L) * X))
    slip_part = p[2 * k:].sum(axis=0) / np.maximum(p.sum(axis=0), 1e-300)
    tol = 1e-9 * np.maximum(1.0, np.abs(lam))
    keep = lam.imag >= -tol
    lam, X, slip_part = lam[keep], X[:, keep], slip_part[keep]
    lam = np.where(np.abs(lam.imag) < tol[keep], lam.real + 0j, lam)
    order = np.lexsort((np.abs(lam.imag), np.abs(lam)))
    lam, X, slip_part = lam[order], X[:, order], slip_part[order]
    # free: the car rolling away; at rest also each relaxed slip's anchor (a constant of
    # the motion: s' integrates the slip velocity).  Counted, not listed
    free = np.abs(lam) < FREE_RAD_S
    n_free = int(np.count_nonzero(free))
    lam, X, slip_part = lam[~free], X[:, ~free], slip_part[~free]
    phi = (N @ X[:k]).T  # displacement shapes (modes, n)
    u = (N @ X[k:2 * k]).T  # velocity shapes
    groups, energy = _energy(system, slices, lin.M, u)
    motion = _body_motion(system.spec, body, u)
    mag = np.abs(lam)
    zeta = -lam.real / mag
    labels = tuple(("tyre relaxation" if sp > 0.5 else _label(groups, e, m))
                   + (" (overdamped)" if lam_k.imag == 0 else "")
                   for e, m, lam_k, sp in zip(energy, motion, lam, slip_part, strict=True))
    return dict(eigenvalues=lam, frequency_hz=mag / (2 * np.pi),
                damped_frequency_hz=np.abs(lam.imag) / (2 * np.pi), damping_ratio=zeta,
                energy=energy, groups=groups, body_motion=motion, label=labels,
                slip_participation=slip_part,
                shapes=phi, A=A, N=N, q=lin.q, residual_N=lin.residual_N,
                body_state=body, **io,
                info={"n_coordinates": int(lin.q.size), "n_dof": int(k),
                      "n_slip_states": int(ns), "n_constraints": int(lin.C.shape[0]),
                      "free_modes": n_free,
                      "drive_torque_Nm": float(getattr(ctrl, "torque", 0.0)),
                      "tire_Fz_N": [float(x) for x in Fz],
                      **_wheel_xy(system, body)})


def _io_matrices(system, lin, N, A, Minv, Ur, Fz_d, k, *, R) -> dict:
    """Road inputs (height, slopes under each wheel) and outputs (vertical tyre forces,
    suspension travel, body-point accelerations in the axes of the body rotated by ``R``) of
    ``x' = A x + B u``, ``y = C x + D u``."""
    from flexpipe.exu.linearize import coordinate_derivatives

    size = lin.q.size
    n_w = Ur.shape[1] // 3
    Bx = np.zeros((A.shape[0], 3 * n_w))
    Bx[k:2 * k] = Minv @ (N.T @ Ur[:size])
    Bx[2 * k:] = Ur[size:]
    Fq, Fv, Fs, Fu = (d[:n_w] for d in Fz_d)  # the vertical forces' rows
    C = [np.hstack([Fq @ N, Fv @ N, Fs])]
    D = [Fu]
    names = [f"tire_{c}_Fz" for c in CORNERS[:n_w]]
    # suspension travel (jounce of each wheel centre along the body's z axis, as a run's
    # travel_<corner> channel): a function of the coordinates only
    Jq, _ = coordinate_derivatives(system.mbs, np.arange(size),
                                   lambda: system.state(0.0).jounce)
    C.append(np.hstack([Jq @ N, np.zeros((n_w, k + Fs.shape[1]))]))
    D.append(np.zeros((n_w, 3 * n_w)))
    names += [f"travel_{c}" for c in CORNERS[:n_w]]
    points = list(system.points)
    if points:
        _, Jv = coordinate_derivatives(system.mbs, np.arange(size),
                                       lambda: np.concatenate(
                                           [v @ R for v in system.point_velocities().values()]),
                                       rates_only=True)
        acc = Jv @ N  # (3 points, k): body-axes acceleration per nullspace acceleration
        C.append(acc @ A[k:2 * k])
        D.append(acc @ Bx[k:2 * k])
        names += [f"acc_{p}_{ax}" for p in points for ax in "xyz"]
    inputs = tuple(f"road_{c}_{kind}" for kind in ("z", "slope_x", "slope_y")
                   for c in CORNERS[:n_w])
    return {"B": Bx, "C": np.vstack(C), "D": np.vstack(D), "inputs": inputs,
            "outputs": tuple(names)}


def output_unit(name: str) -> str:
    """SI unit of a linear model's output, by its (run channel) name."""
    if name.startswith(("tire_", "hub_")):
        return "N"
    return "m" if name.startswith("travel_") else "m/s^2"


def _wheel_xy(system, body) -> dict:
    """Wheel centres' positions along the body's x and y axes (m, from the body origin)."""
    r = (system.state(0.0).wheel_p - body["position"]) @ body["rotation"]
    return {"wheel_x_m": r[:, 0].tolist(), "wheel_y_m": r[:, 1].tolist()}


def _body_state(system, slices, q) -> dict:
    from flexpipe.exu.linearize import node_reference

    sl = slices[int(system.body_node)]
    modal = getattr(system, "modal_node", None)
    ms = slices[int(modal)] if modal is not None else None
    st = system.state(0.0)
    e = node_reference(system.mbs, system.body_node)[3:7] + q[sl][3:7]
    return {"frame": sl, "modal": ms, "position": st.body_p.copy(),
            "rotation": st.body_R.copy(), "euler": e / np.linalg.norm(e),
            "modal_q": q[ms].copy() if ms is not None else None,
            "flexbody": system.spec.flexbody if ms is not None else None}


# ---------------------------------------------------------------------------- energy
def _groups(system, slices):
    """``[(name, ODE2 indices)]``: body frame, body elastic, corners, spin, steering, rest."""
    from flexpipe.exu.linearize import object_node

    mbs = system.mbs
    named = {}

    def put(name, node):
        if node is not None and int(node) in slices:
            named.setdefault(name, []).append(int(node))

    put("body frame", system.body_node)
    put("body elastic", getattr(system, "modal_node", None))
    lk = system.linkage
    for cn, parts in zip(CORNERS, lk.part_nodes, strict=True):
        for obj, *_ in parts:
            put(f"corner {cn}", object_node(mbs, obj))
    for node in system.spin_node:
        put("wheel spin", node)
    if lk.rack is not None:
        put("steering", lk.rack["node"])
    used = {n for nodes in named.values() for n in nodes}
    for node in slices:
        if node not in used:
            put("other parts", node)
    return [(name, np.concatenate([np.arange(slices[n].start, slices[n].stop)
                                   for n in nodes])) for name, nodes in named.items()]


def _energy(system, slices, M, u):
    """Each mode's kinetic energy share per group (rows sum to 1)."""
    groups = _groups(system, slices)
    Mu = u @ M.T  # (modes, n): M u for each mode
    total = np.real(np.einsum("kn,kn->k", u.conj(), Mu))
    total = np.where(total > 0, total, 1.0)
    E = np.array([np.real(np.einsum("kn,kn->k", u[:, ix].conj(), Mu[:, ix]))
                  for _, ix in groups]).T / total[:, None]
    return tuple(name for name, _ in groups), E


def _body_motion(spec, body, u):
    """The body frame's kinetic energy per motion (x, y, z, roll, pitch, yaw; body axes,
    at its centre of mass), normalized per mode (``body``: :func:`_body_state`)."""
    from flexpipe.exu._tire_element import _g_matrix

    sl, R = body["frame"], body["rotation"]
    G = _g_matrix(body["euler"])
    m = float(spec.mass)
    c = np.asarray(spec.center_of_mass, float)
    J_o = np.asarray(spec.inertia_origin, float)
    J = J_o - m * (c @ c * np.eye(3) - np.outer(c, c))
    ub = u[:, sl]
    w = (R.T @ (G @ ub[:, 3:7].T)).T  # body-axes angular velocity shapes
    v = (R.T @ ub[:, :3].T).T + np.cross(w, c)
    out = np.column_stack([m * np.abs(v) ** 2, np.real(w.conj() * (w @ J.T))])
    tot = out.sum(axis=1)
    return np.where(tot[:, None] > 0, out / np.where(tot > 0, tot, 1.0)[:, None], 0.0)


def _label(groups, energy, motion) -> str:
    """Dominant motion of a mode."""
    share = dict(zip(groups, energy, strict=True))
    body = share.get("body frame", 0.0)
    elastic = share.get("body elastic", 0.0)
    front = share.get("corner fl", 0.0) + share.get("corner fr", 0.0)
    rear = share.get("corner rl", 0.0) + share.get("corner rr", 0.0)
    cands = {"body": body, "body elastic": elastic, "front axle": front,
             "rear axle": rear, "wheel spin": share.get("wheel spin", 0.0),
             "steering": share.get("steering", 0.0),
             "other parts": share.get("other parts", 0.0)}
    top = max(cands, key=cands.get)
    if cands[top] <= 0.0:
        return "tyre relaxation"
    if top == "body":
        return _BODY_LABEL[BODY_MOTIONS[int(np.argmax(motion))]]
    return top
