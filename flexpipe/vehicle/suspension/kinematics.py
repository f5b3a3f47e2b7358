"""Pose of a corner linkage: Newton on the joint/link constraints, body fixed.

The unknowns are the 6-DOF poses of the linkage's parts (position of the centre of mass
and rotation matrix, updated by exponential-map increments) and, in compliance
analyses with a compliant steering column, the rack travel.  Kinematic analyses impose
every joint and link; compliance analyses replace body-side joints that carry a bushing
(and links with an axial stiffness) by those elements and solve the equilibrium with
Lagrange multipliers for the remaining constraints.

In both cases one extra equation fixes the wheel centre height (wheel travel ``s`` from
the design position); its multiplier is the vertical force (N) the rig applies there.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexpipe.errors import ModelError, SolverError
from flexpipe.vehicle.suspension.carrier import CARRIER, FREE, carried_corner
from flexpipe.vehicle.suspension.model import BODY, RACK, CornerLinkage

G = 9.81


def skew(v) -> np.ndarray:
    """Cross-product matrix: ``skew(a) @ b == cross(a, b)``."""
    return np.array([[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]])


def expm_so3(w) -> np.ndarray:
    """Rotation matrix of the rotation vector ``w`` (Rodrigues)."""
    t = float(np.linalg.norm(w))
    if t < 1e-14:
        return np.eye(3) + skew(w)
    k = skew(np.asarray(w) / t)
    return np.eye(3) + np.sin(t) * k + (1 - np.cos(t)) * (k @ k)


def rotvec(R) -> np.ndarray:
    """Rotation vector of the rotation matrix ``R``."""
    c = np.clip((np.trace(R) - 1) / 2, -1.0, 1.0)
    t = np.arccos(c)
    w = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]])
    return w / 2 if t < 1e-8 else w * t / (2 * np.sin(t))


def _perp(axis):
    a = np.asarray(axis, float)
    t = np.array([1.0, 0, 0]) if abs(a[0]) < 0.9 else np.array([0, 1.0, 0])
    n1 = np.cross(a, t)
    n1 /= np.linalg.norm(n1)
    return n1, np.cross(a, n1)


@dataclass
class Pose:
    """Poses of a linkage's parts: ``r`` (n, 3) centres of mass, ``R`` (n, 3, 3), rack (m)."""

    r: np.ndarray
    R: np.ndarray
    rack: float = 0.0
    force: float = 0.0  # vertical rig force at the wheel centre (N), compliance solves

    def copy(self) -> Pose:
        return Pose(self.r.copy(), self.R.copy(), self.rack, self.force)


class Linkage:
    """A :class:`CornerLinkage` compiled for the solver.

    Parameters
    ----------
    corner : CornerLinkage
        The linkage.
    rack_axis : array of 3
        Direction of the rack's travel (body axes).
    carrier : Carrier, optional
        The subframe half the corner rests on in the K&C rig
        (:func:`~flexpipe.vehicle.suspension.carrier.half_carrier`): one more part, on its
        bushings, carrying the corner's carried mounts.
    mode : {"symmetric", "antisymmetric"}, optional
        The motions the subframe keeps in compliance solves
        (:data:`~flexpipe.vehicle.suspension.carrier.FREE`); held otherwise.

    Attributes
    ----------
    rack_free : bool
        Rack travel is an unknown (compliance with a compliant column).
    """

    def __init__(self, corner: CornerLinkage, *, rack_axis=(0.0, 1.0, 0.0), carrier=None,
                 mode: str | None = None):
        if carrier is not None:
            corner = carried_corner(corner, carrier)
        self.carrier, self.mode = carrier, mode
        self.c = corner
        self.names = [p.name for p in corner.parts]
        self.idx = {n: i for i, n in enumerate(self.names)}
        self.cm0 = np.array([p.cm for p in corner.parts])
        self.n = len(self.names)
        self.rack_axis = np.asarray(rack_axis, float)
        self.rack_free = False
        # the subframe's index, and the rack's carrier when its housing is on it
        self.k_carrier = self.idx[CARRIER] if carrier is not None else None
        self.k_rack = self.k_carrier if carrier is not None and carrier.rack else None

    # ----------------------------------------------------------------- primitives
    @property
    def nx(self) -> int:
        return 6 * self.n + (1 if self.rack_free else 0)

    def design(self) -> Pose:
        """The design pose."""
        return Pose(self.cm0.copy(), np.repeat(np.eye(3)[None], self.n, axis=0))

    def _owner(self, name):
        if name in (BODY, RACK):
            return name
        if name not in self.idx:
            raise ModelError(f"corner {self.c.corner}: unknown part {name!r}; parts: "
                             f"{', '.join(self.names)}")
        return self.idx[name]

    def point(self, pose: Pose, owner, p0):
        """World position of design point ``p0`` attached to ``owner`` and its Jacobian."""
        J = np.zeros((3, self.nx))
        o = self._owner(owner)
        if o == BODY:
            return np.asarray(p0, float), J
        if o == RACK:
            p = np.asarray(p0, float) + pose.rack * self.rack_axis
            if self.k_rack is None:
                if self.rack_free:
                    J[:, -1] = self.rack_axis
                return p, J
            o, p0 = self.k_rack, p            # the housing moves with the subframe
            if self.rack_free:
                J[:, -1] = pose.R[o] @ self.rack_axis
        s = pose.R[o] @ (np.asarray(p0) - self.cm0[o])
        J[:, 6 * o:6 * o + 3] = np.eye(3)
        J[:, 6 * o + 3:6 * o + 6] = -skew(s)
        return pose.r[o] + s, J

    def vector(self, pose: Pose, owner, v0):
        """World direction of design vector ``v0`` fixed in ``owner`` and its Jacobian."""
        J = np.zeros((3, self.nx))
        o = self._owner(owner)
        if o == RACK and self.k_rack is not None:
            o = self.k_rack
        if o in (BODY, RACK):
            return np.asarray(v0, float), J
        v = pose.R[o] @ v0
        J[:, 6 * o + 3:6 * o + 6] = -skew(v)
        return v, J

    def step(self, pose: Pose, dx) -> Pose:
        """``pose`` advanced by the increment ``dx`` (translations, rotation vectors)."""
        out = pose.copy()
        d = np.asarray(dx[:6 * self.n]).reshape(self.n, 6)
        out.r += d[:, :3]
        for i in range(self.n):
            out.R[i] = expm_so3(d[i, 3:]) @ pose.R[i]
        if self.rack_free:
            out.rack += dx[-1]
        return out

    # ----------------------------------------------------------------- constraints
    def constraints(self, pose: Pose, *, compliant=False):
        """Constraint residuals ``g`` and Jacobian ``G`` with the name of each row."""
        rows, jac, names = [], [], []

        def add(name, g, J):
            rows.append(np.atleast_1d(g))
            jac.append(np.atleast_2d(J))
            names.extend([name] * np.atleast_1d(g).size)

        for j in self.c.joints:
            if compliant and j.bushing is not None:
                continue
            label = f"joint '{j.name}' ({j.kind})"
            pa, Ja = self.point(pose, j.a, j.point)
            pb, Jb = self.point(pose, j.b, j.point)
            if j.kind in ("spherical", "revolute", "universal"):
                add(label, pa - pb, Ja - Jb)
            if j.kind == "revolute":
                va, Jva = self.vector(pose, j.a, j.axis)
                for n0 in _perp(j.axis):
                    nb, Jnb = self.vector(pose, j.b, n0)
                    add(label, va @ nb, va @ Jnb + nb @ Jva)
            elif j.kind == "universal":
                va, Jva = self.vector(pose, j.a, j.axis)
                vb, Jvb = self.vector(pose, j.b, j.axis_b)
                add(label, va @ vb, va @ Jvb + vb @ Jva)
            elif j.kind == "inline":
                w, Jw = pb - pa, Jb - Ja
                for n0 in _perp(j.axis):
                    na, Jna = self.vector(pose, j.a, n0)
                    add(label, na @ w, na @ Jw + w @ Jna)
        for lk in self.c.links:
            if compliant and lk.axial_stiffness is not None:
                continue
            pa, Ja = self.point(pose, lk.a, lk.point_a)
            pb, Jb = self.point(pose, lk.b, lk.point_b)
            d = pa - pb
            L = np.linalg.norm(d)
            add(f"link '{lk.name}'", L - lk.length, (d / L) @ (Ja - Jb))
        if self.k_carrier is not None:
            self._carrier_rows(pose, compliant, add)
        w, Jw = self.point(pose, self.c.knuckle, self.c.wheel_center)
        add("wheel travel", w[2], Jw[2])
        return np.concatenate(rows), np.vstack(jac), names

    def _carrier_rows(self, pose: Pose, compliant: bool, add) -> None:
        """The subframe held (kinematic analyses) or kept to the motions of the
        analysis's symmetry (compliance: :data:`~flexpipe.vehicle.suspension.carrier.FREE`)."""
        o = self.k_carrier
        free = FREE[self.mode] if compliant and self.mode is not None else ()
        label = f"subframe ({self.mode or 'held'})"
        e = np.eye(3)
        for k in range(3):
            if k not in free:
                J = np.zeros(self.nx)
                J[6 * o + k] = 1.0
                add(label, pose.r[o][k] - self.cm0[o][k], J)
        for k, (i, j) in enumerate(((1, 2), (2, 0), (0, 1))):   # about x, y, z
            if 3 + k not in free:
                v, Jv = self.vector(pose, CARRIER, e[i])
                add(label, v @ e[j], e[j] @ Jv)

    # ----------------------------------------------------------------- forces
    def forces(self, pose: Pose, *, patch_force=None, rack_stiffness=None,
               gravity=False) -> np.ndarray:
        """Generalised applied forces (elastic elements, external, gravity) on the unknowns."""
        Q = np.zeros(self.nx)
        for j in self.c.joints:
            b = j.bushing
            if b is None:
                continue
            ground = j.a if j.a in (BODY, CARRIER) else j.b   # the body or the subframe
            part = j.b if ground == j.a else j.a
            if j.kind == "inline" and j.a == part:
                Q += self._sliding_bushing(pose, j)
                continue
            self._bushing(Q, pose, b, part, ground, j.point)
        for lk in self.c.links:
            if lk.axial_stiffness is None:
                continue
            pa, Ja = self.point(pose, lk.a, lk.point_a)
            pb, Jb = self.point(pose, lk.b, lk.point_b)
            d = pa - pb
            L = np.linalg.norm(d)
            Q += (Ja - Jb).T @ (-lk.axial_stiffness * (L - lk.length) * d / L)
        for fe in self.c.forces:
            p, Jp = self.point(pose, fe.part, fe.point)
            q, Jq = self.point(pose, fe.body_part, fe.body_point)
            d = p - q
            L = np.linalg.norm(d)
            Q += (Jp - Jq).T @ (fe.static_force(L) * d / L)
        if self.k_carrier is not None:
            Q += self._carrier_bushings(pose)
        if patch_force is not None:
            p, Jp = self.point(pose, self.c.knuckle, self.contact_patch0())
            Q += Jp.T @ np.asarray(patch_force, float)
        if gravity:
            for i, part in enumerate(self.c.parts):
                Q[6 * i + 2] -= part.mass * G
        if self.rack_free and rack_stiffness is not None:
            Q[-1] -= rack_stiffness * pose.rack
        return Q

    def _R(self, pose: Pose, owner) -> np.ndarray:
        """Rotation of ``owner`` (identity for the body)."""
        return np.eye(3) if owner == BODY else pose.R[self.idx[owner]]

    def _torque(self, Q, part, ground, T) -> None:
        """Add the bushing torque ``T`` (world axes) on ``part``, its reaction on ``ground``."""
        o = self.idx[part]
        Q[6 * o + 3:6 * o + 6] += T
        if ground != BODY:
            g = self.idx[ground]
            Q[6 * g + 3:6 * g + 6] -= T

    def _sliding_bushing(self, pose: Pose, j) -> np.ndarray:
        """Bushing of an in-line joint whose line is fixed in the part ``j.a`` (strut top
        mount) on the body or the subframe ``j.b``: it resists the mount point's offset
        from the line and the tilt of the line, not the slide along it or the spin about
        it."""
        b, o = j.bushing, self.idx[j.a]
        u, _ = self.vector(pose, j.a, j.axis)
        m, Jm = self.point(pose, j.b, j.point)             # the mount point, where it is
        p0, _ = self.point(pose, j.a, j.point)
        q_world = p0 + ((m - p0) @ u) * u              # point of the line nearest the mount
        q_design = pose.R[o].T @ (q_world - pose.r[o]) + self.cm0[o]
        q, Jq = self.point(pose, j.a, q_design)
        perp = np.eye(3) - np.outer(u, u)
        rel = rotvec(pose.R[o] @ self._R(pose, j.b).T)
        f = b.force(np.concatenate([b.frame.T @ (perp @ (q - m)), b.frame.T @ (perp @ rel)]))
        F = perp @ (b.frame @ f[:3])
        Q = (Jq - Jm).T @ F
        self._torque(Q, j.a, j.b, perp @ (b.frame @ f[3:]))
        return Q

    def _bushing(self, Q, pose: Pose, b, part, ground, point, weight: float = 1.0) -> None:
        """Add bushing ``b`` at ``point`` between ``part`` and ``ground`` (the body or the
        subframe), its forces scaled by ``weight``: deflection in the bushing's frame,
        the force on ``part`` and its reaction on ``ground``."""
        p, Jp = self.point(pose, part, point)
        q, Jq = self.point(pose, ground, point)
        rot = rotvec(pose.R[self.idx[part]] @ self._R(pose, ground).T)
        f = weight * b.force(np.concatenate([b.frame.T @ (p - q), b.frame.T @ rot]))
        Q += (Jp - Jq).T @ (b.frame @ f[:3])
        self._torque(Q, part, ground, b.frame @ f[3:])

    def _carrier_bushings(self, pose: Pose) -> np.ndarray:
        """Forces of the subframe's bushings (its half on the corner's side) on it."""
        cr = self.carrier
        Q = np.zeros(self.nx)
        for p0, b, w in zip(cr.points, cr.bushings, cr.weights, strict=True):
            self._bushing(Q, pose, b, CARRIER, BODY, p0, w)
        return Q

    def contact_patch0(self) -> np.ndarray:
        """Contact patch at the design position (point fixed in the knuckle)."""
        a = self.c.spin_axis
        down = np.array([0.0, 0, -1]) + a[2] * a
        return self.c.wheel_center + self.c.wheel_radius * down / np.linalg.norm(down)


def _newton(lk: Linkage, pose, residual, n_unknown, *, tol=1e-11, max_iter=60, what=""):
    for _ in range(max_iter):
        r, J, names = residual(pose)
        if np.max(np.abs(r)) < tol:
            return pose
        dz = np.linalg.lstsq(J, -r, rcond=None)[0]
        scale = min(1.0, 0.2 / max(np.max(np.abs(dz[:n_unknown])), 1e-300))
        pose = lk.step(pose, dz * scale)
    r, J, names = residual(pose)
    if np.max(np.abs(r)) < 1e-8:
        return pose
    k = int(np.argmax(np.abs(r)))
    raise ModelError(f"corner {lk.c.corner}: {what} the linkage cannot be assembled: "
                     f"{names[k]} fails with residual {r[k]:.3g} (m or rad) after "
                     f"{max_iter} Newton iterations; check the hardpoints of that joint")


def solve_kinematics(lk: Linkage, travel: float, *, rack: float = 0.0,
                     pose: Pose | None = None) -> Pose:
    """Pose with the wheel centre ``travel`` (m) above design and the rack at ``rack`` (m).

    Raises
    ------
    ModelError
        The linkage cannot be assembled; names the failing constraint and its residual.
    """
    lk.rack_free = False
    pose = lk.design() if pose is None else pose.copy()
    pose.rack = rack
    z0 = lk.c.wheel_center[2] + travel

    def residual(p):
        g, Gm, names = lk.constraints(p)
        g[-1] -= z0
        return g, Gm, names

    return _newton(lk, pose, residual, lk.nx, what=f"at wheel travel {travel * 1e3:.1f} mm")


def solve_compliance(lk: Linkage, travel: float, *, rack: float = 0.0, patch_force=None,
                     rack_stiffness=None, gravity=False, pose: Pose | None = None) -> Pose:
    """Static equilibrium with bushings, compliant links, spring and stops.

    The wheel centre is held at ``travel`` (m); ``patch_force`` (N, body axes) acts at the
    contact patch (a point of the knuckle); ``rack_stiffness`` (N/m) lets the rack move
    against the held steering wheel.  ``Pose.force`` returns the vertical force (N) the
    rig applies at the wheel centre.
    """
    lk.rack_free = rack_stiffness is not None
    pose = lk.design() if pose is None else pose.copy()
    pose.rack = rack if not lk.rack_free else pose.rack
    z0 = lk.c.wheel_center[2] + travel
    nx = lk.nx
    g0, _, _ = lk.constraints(pose, compliant=True)
    lam = np.zeros(len(g0))

    def kkt(p, lam):
        g, Gm, names = lk.constraints(p, compliant=True)
        g[-1] -= z0
        F = lk.forces(p, patch_force=patch_force, rack_stiffness=rack_stiffness,
                      gravity=gravity) + Gm.T @ lam
        return F, g, Gm, names

    h = 1e-7
    for _ in range(80):
        F, g, Gm, names = kkt(pose, lam)
        res = np.concatenate([F, g])
        if np.max(np.abs(g)) < 1e-11 and np.max(np.abs(F)) < 1e-7 * (1 + np.max(np.abs(lam))):
            pose.force = float(lam[-1])
            lk.rack_free = False
            return pose
        K = np.empty((nx, nx))
        for i in range(nx):
            e = np.zeros(nx)
            e[i] = h
            K[:, i] = (kkt(lk.step(pose, e), lam)[0] - kkt(lk.step(pose, -e), lam)[0]) / (2 * h)
        m = len(g)
        A = np.block([[K, Gm.T], [Gm, np.zeros((m, m))]])
        try:
            dz = np.linalg.solve(A, -res)
        except np.linalg.LinAlgError:
            dz = np.linalg.lstsq(A, -res, rcond=1e-14)[0]
        scale = min(1.0, 0.05 / max(np.max(np.abs(dz[:nx])), 1e-300))
        pose = lk.step(pose, dz[:nx] * scale)
        lam = lam + dz[nx:] * scale
    k = int(np.argmax(np.abs(g))) if np.max(np.abs(g)) > 1e-8 else None
    lk.rack_free = False
    where = f"{names[k]} residual {g[k]:.3g}" if k is not None else \
        f"force residual {np.max(np.abs(F)):.3g} N"
    raise SolverError(f"corner {lk.c.corner}: compliance solve at wheel travel "
                      f"{travel * 1e3:.1f} mm did not converge ({where}); with the joints "
                      "rigid the corner is checked at load to have one degree of freedom, "
                      "so look at the bushings and compliant links (a stiffness of zero or "
                      "a few N/m in a direction a joint does not hold) and at the hardpoints "
                      "that place that joint")


def travel_velocity(lk: Linkage, pose: Pose):
    """d(unknowns)/d(travel) at a kinematic ``pose`` (implicit differentiation)."""
    lk.rack_free = False
    _, Gm, _ = lk.constraints(pose)
    rhs = np.zeros(Gm.shape[0])
    rhs[-1] = 1.0
    return np.linalg.lstsq(Gm, rhs, rcond=None)[0]


def rack_velocity(lk: Linkage, pose: Pose):
    """d(unknowns)/d(rack travel) at a kinematic ``pose`` with the wheel centre held."""
    lk.rack_free = True
    _, Gm, _ = lk.constraints(pose)
    lk.rack_free = False
    A = np.vstack([Gm, np.eye(Gm.shape[1])[-1]])
    rhs = np.zeros(A.shape[0])
    rhs[-1] = 1.0
    return np.linalg.lstsq(A, rhs, rcond=None)[0][:-1]
