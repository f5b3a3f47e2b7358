"""Generate ``meshes/sedan_biw.bdf``: a sedan body-in-white concept model (shells + beams).

Run ``python meshes/make_sedan_biw.py`` to rewrite the file, ``--check`` to also assemble
it, print its mass and its free-free modes, and (with ``--car cars/sedan.toml``) the modes
of the trimmed body (the car file's non-structural masses added).

Geometry (ISO 8855 axes: x forward, y left, z up; z = 0 is the ground in the design
position; front axle at x = 0, rear axle at x = -2.75 m; overall 4.60 x 1.50 (body
structure, 1.80 over the tyres) x 1.40 m).  Panels are CQUAD4 shells on a 50 mm grid
(PSHELL), the body-side frame and the rails are CBAR beams (PBAR, thin-walled box
sections) sharing nodes with the panels:

* floor pan with a closed tunnel, heel kick, raised rear floor;
* dash panel (bulkhead), rear seat-back panel, parcel shelf, rear wheelhouse inner walls
  carrying the rear damper mounts;
* front strut towers (wall + top plate) between the front rails and the upper (apron)
  rails, carrying the front strut mounts; the rear (back) panel;
* sills, hinge pillars, A-, B-, C-pillars, roof rails, headers, roof bow, roof panel;
* front rails with kick-down floor longitudinals, rear rails, bumper beams, radiator
  support, floor cross members, cowl beam.

Panels not modelled as structure (outer body side skins, wheelhouse outers, reinforcements,
sealer, spot-weld flanges) are carried as non-structural CONM2 masses on the side frame so
that the BIW mass is realistic (~300 kg for a steel mid-size sedan).

Targets (sources): global first torsion and bending of a steel sedan BIW at roughly
25-45 Hz and 30-50 Hz; once trimmed (powertrain, interior, closures, occupants as
masses) the global modes fall to roughly 15-30 Hz.  BMW's NVH practice (Ludke, quoted in
Crolla (ed.), *Automotive Engineering: Powertrain, Chassis System and Vehicle Body*,
Butterworth-Heinemann 2009, ch. 18.1) puts the complete vehicle's first bending/torsion at
26/29 Hz, in an "idle frequency window" between engine orders.

Suspension mounts: the 30 body-side mounts of a double-wishbone front and a multi-link
rear (:data:`MOUNTS_LEFT`, mirrored to the right; names ``<axle>_<point>_<side>``) are
nodes of the structure: a front engine cradle (closed-section perimeter frame bolted to
the front rails by posts) carries the lower-arm pivots, the rack mounts and the anti-roll
bar bushings; tripod brackets on the strut-tower walls (stiffened by vertical posts) carry
the upper-arm pivots and spring seats; a rear subframe on the rear rails and the rear
floor carries the lateral links, tie rods and anti-roll bar; brackets on the rear floor,
seat-back panel and wheelhouse walls (with a damper-top reinforcement) carry the upper
arms, trailing links, spring and damper tops.  The engine cradle, formerly a 2.5 mm plate
between the front rails, is now this beam frame.  Measured (``--check``): BIW 396.6 kg
(358.1 kg before the mounts), first torsion 42.3 Hz (43.5), bending 46.1 Hz (46.5);
trimmed with ``cars/sedan.toml`` 1335.1 kg (1324.1), torsion 22.8 Hz (23.6), bending
24.0 Hz (23.6) (re-run 2026-12-02).

Every mount and the four legacy corner hardpoints are written as comments
``$ HARDPOINT name x y z`` and as ``SET1`` node lists with a ``$ SET name`` comment (the
mount's own node for the 30 mounts; the nodes within 0.10 m for the legacy four).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

H = 0.05  # grid spacing, m
STEEL = dict(E=210e9, nu=0.3, rho=7850.0)

#: suspension mount points (body coordinates, m)
HARDPOINTS = {
    "strut_fl": (0.00, 0.65, 0.85),
    "strut_fr": (0.00, -0.65, 0.85),
    "damper_rl": (-2.75, 0.55, 0.65),
    "damper_rr": (-2.75, -0.55, 0.65),
}

#: body-side suspension mounts, left side (body coordinates, m); the right side is the
#: mirror image y -> -y.  Front: double wishbone; rear: multi-link.  Names in the body:
#: ``<axle>_<point>_<side>``, e.g. ``front_lower_arm_front_l``.
MOUNTS_LEFT = {
    "front": {
        "lower_arm_front": (0.200, 0.420, 0.148), "lower_arm_rear": (-0.200, 0.470, 0.153),
        "upper_arm_front": (-0.100, 0.470, 0.523), "upper_arm_rear": (-0.250, 0.510, 0.528),
        "spring_upper": (-0.040, 0.520, 0.648), "rack_mount": (-0.200, 0.300, 0.298),
        "arb_bushing": (-0.150, 0.350, 0.220),
    },
    "rear": {
        "upper_arm_front": (-2.690, 0.397, 0.383), "upper_arm_rear": (-2.907, 0.358, 0.363),
        "lateral_link_inner": (-2.714, 0.188, 0.168),
        "trailing_link_front": (-2.027, 0.449, 0.229),
        "tie_rod_inner": (-3.007, 0.170, 0.185), "spring_upper": (-2.569, 0.491, 0.411),
        "damper_upper": (-2.579, 0.478, 0.616), "arb_bushing": (-2.950, 0.350, 0.250),
    },
}
#: a mount's SET1 holds the body nodes within this distance of the mount point, m
MOUNT_SET_RADIUS = 0.01


def mounts() -> dict:
    """Every body-side suspension mount, ``{name: (x, y, z)}`` (30 mounts)."""
    out = {}
    for axle, pts in MOUNTS_LEFT.items():
        for point, (x, y, z) in pts.items():
            out[f"{axle}_{point}_l"] = (x, y, z)
            out[f"{axle}_{point}_r"] = (x, -y, z)
    return out

#: shell properties: name -> (sheet gauge in m, bending factor beta).  Beaded and crowned
#: sheet is modelled as an equivalent flat shell of thickness beta * gauge with E and rho
#: divided by beta: same mass and membrane stiffness as the sheet, bending stiffness
#: raised by beta^2 (beads, crown, local stiffeners), which keeps local panel modes
#: above the global ones as in a real body.
SHELLS = {
    "floor": (0.0007, 8.0), "tunnel": (0.0008, 4.0), "heel_kick": (0.0010, 4.0),
    "rear_floor": (0.0008, 10.0), "dash": (0.0008, 8.0), "seat_back": (0.0007, 8.0),
    "parcel_shelf": (0.0008, 8.0), "wheelhouse": (0.0010, 6.0), "tower": (0.0020, 3.0),
    "roof": (0.0006, 10.0), "rear_panel": (0.0010, 6.0),
}

#: beam properties: name -> thin-walled box (width, height, wall) in m
BEAMS = {
    "sill": (0.10, 0.10, 0.0013), "hinge_pillar": (0.09, 0.11, 0.0015),
    "a_pillar": (0.07, 0.08, 0.0015), "b_pillar": (0.07, 0.10, 0.0014),
    "c_pillar": (0.10, 0.12, 0.0015), "backlight": (0.08, 0.10, 0.0015),
    "roof_rail": (0.06, 0.07, 0.0012), "header": (0.06, 0.07, 0.0012),
    "front_rail": (0.07, 0.09, 0.0015), "upper_rail": (0.06, 0.08, 0.0015),
    "rear_rail": (0.07, 0.09, 0.0015), "cross_member": (0.07, 0.08, 0.0013),
    "bumper": (0.06, 0.10, 0.0018), "cowl": (0.08, 0.10, 0.0015),
    "quarter": (0.06, 0.08, 0.0015),
    "cradle_rail": (0.08, 0.08, 0.0020), "cradle_post": (0.06, 0.06, 0.0015),
    "rear_cradle": (0.07, 0.07, 0.0018), "bracket": (0.05, 0.05, 0.0015),
    "tower_post": (0.06, 0.06, 0.0015),
}
#: non-structural masses (kg) smeared evenly over the nodes of these beam groups: outer
#: body-side skins and reinforcements on the side frame; crash boxes and small brackets
#: on the front structure (the tower posts and suspension brackets are beams)
NONSTRUCTURAL = (
    ("side frame", 60.0, ("sill", "hinge_pillar", "b_pillar", "roof_rail")),
    ("front structure", 15.0, ("front_rail", "upper_rail", "bumper")),
)
NONSTRUCTURAL_KG = sum(m for _, m, _ in NONSTRUCTURAL)


def shell_equivalent(name):
    """(E, rho, thickness) of the equivalent shell of panel ``name``."""
    gauge, beta = SHELLS[name]
    return STEEL["E"] / beta, STEEL["rho"] / beta, gauge * beta


def box_section(b, h, t):
    """Area, I_y (about local y, bending in x-z), I_z (about z), J of a thin box."""
    bi, hi = b - 2 * t, h - 2 * t
    A = b * h - bi * hi
    Iz = (b * h**3 - bi * hi**3) / 12  # height along local y
    Iy = (h * b**3 - hi * bi**3) / 12
    J = 4 * ((b - t) * (h - t)) ** 2 * t / (2 * ((b - t) + (h - t)))
    return A, Iy, Iz, J


class Builder:
    """Accumulates nodes (merged on a 1 µm lattice), quads, bars and point masses."""

    def __init__(self):
        self.key = {}
        self.points = []
        self.quads, self.quad_pid = [], []
        self.bars, self.bar_pid, self.bar_v = [], [], []
        self.pids = {}

    def node(self, p) -> int:
        k = tuple(np.round(np.asarray(p, dtype=float) * 1e6).astype(np.int64))
        if k not in self.key:
            self.key[k] = len(self.points)
            self.points.append(np.asarray(k, dtype=float) * 1e-6)
        return self.key[k]

    def pid(self, name) -> int:
        return self.pids.setdefault(name, len(self.pids) + 1)

    def panel(self, name, origin, u, v):
        """Planar patch origin + a u + b v, a, b in [0, 1], meshed at spacing H."""
        o, u, v = (np.asarray(a, dtype=float) for a in (origin, u, v))
        nu = max(1, round(np.linalg.norm(u) / H))
        nv = max(1, round(np.linalg.norm(v) / H))
        ids = np.empty((nu + 1, nv + 1), dtype=np.int64)
        for i in range(nu + 1):
            for j in range(nv + 1):
                ids[i, j] = self.node(o + u * i / nu + v * j / nv)
        pid = self.pid(name)
        for i in range(nu):
            for j in range(nv):
                self.quads.append((ids[i, j], ids[i + 1, j], ids[i + 1, j + 1], ids[i, j + 1]))
                self.quad_pid.append(pid)

    def beam(self, name, *pts, orient=None):
        """Polyline through ``pts`` split into pieces of about H."""
        pid = self.pid(name)
        pts = [np.asarray(p, dtype=float) for p in pts]
        for a, b in zip(pts[:-1], pts[1:], strict=True):
            n = max(1, round(np.linalg.norm(b - a) / H))
            d = (b - a) / np.linalg.norm(b - a)
            if orient is not None:
                v = np.asarray(orient, dtype=float)
            else:  # vertical-ish members: orientation along x; others: along z
                v = np.array([1.0, 0, 0]) if abs(d[2]) > 0.7 else np.array([0, 0, 1.0])
            ids = [self.node(a + (b - a) * k / n) for k in range(n + 1)]
            for i0, i1 in zip(ids[:-1], ids[1:], strict=True):
                self.bars.append((i0, i1))
                self.bar_pid.append(pid)
                self.bar_v.append(v)


def build():
    """Return the :class:`Builder` holding the body-in-white."""
    B = Builder()
    P = B.panel
    # ---- floor, tunnel, heel kick, rear floor
    P("floor", (-2.40, -0.75, 0.20), (1.90, 0, 0), (0, 1.50, 0))
    for y in (-0.10, 0.10):
        P("tunnel", (-2.40, y, 0.20), (1.90, 0, 0), (0, 0, 0.20))
    P("tunnel", (-2.40, -0.10, 0.40), (1.90, 0, 0), (0, 0.20, 0))
    P("heel_kick", (-2.40, -0.75, 0.20), (0, 1.50, 0), (0, 0, 0.15))
    P("rear_floor", (-3.75, -0.55, 0.35), (1.35, 0, 0), (0, 1.10, 0))
    # ---- bulkheads and rear structure
    P("dash", (-0.50, -0.75, 0.20), (0, 1.50, 0), (0, 0, 0.75))
    P("seat_back", (-2.60, -0.55, 0.35), (0, 1.10, 0), (0, 0, 0.60))
    P("parcel_shelf", (-3.10, -0.55, 0.95), (0.50, 0, 0), (0, 1.10, 0))
    for y in (-0.55, 0.55):  # rear wheelhouse / quarter inner walls
        P("wheelhouse", (-3.75, y, 0.35), (1.35, 0, 0), (0, 0, 0.40))
        P("wheelhouse", (-3.10, y, 0.75), (0.70, 0, 0), (0, 0, 0.20))
    # ---- front strut towers: wall between front rail and apron, top plate to upper rail
    for s in (-1, 1):
        P("tower", (-0.25, 0.55 * s, 0.40), (0.50, 0, 0), (0, 0, 0.45))
        P("tower", (-0.25, 0.55 * s, 0.85), (0.50, 0, 0), (0, 0.20 * s, 0))
    P("roof", (-2.55, -0.65, 1.40), (1.30, 0, 0), (0, 1.30, 0))
    # rear panel (the engine cradle is a beam frame: suspension_mounts)
    P("rear_panel", (-3.75, -0.55, 0.35), (0, 1.10, 0), (0, 0, 0.40))
    # ---- beams
    for s in (-1, 1):
        B.beam("sill", (-2.40, 0.75 * s, 0.20), (-0.50, 0.75 * s, 0.20))
        B.beam("hinge_pillar", (-0.50, 0.75 * s, 0.20), (-0.50, 0.75 * s, 0.95))
        B.beam("a_pillar", (-0.50, 0.75 * s, 0.95), (-1.25, 0.65 * s, 1.40))
        B.beam("b_pillar", (-1.60, 0.75 * s, 0.20), (-1.60, 0.65 * s, 1.40))
        B.beam("roof_rail", (-1.25, 0.65 * s, 1.40), (-2.55, 0.65 * s, 1.40))
        # C-pillar: heel-kick corner up to the roof, with a node at belt height (z 0.95)
        zc = 0.95
        tc = (zc - 0.35) / (1.40 - 0.35)
        pc = np.array([-2.40, 0.75 * s, 0.35]) + tc * np.array([-0.15, -0.10 * s, 1.05])
        B.beam("c_pillar", (-2.40, 0.75 * s, 0.35), pc, (-2.55, 0.65 * s, 1.40))
        B.beam("quarter", pc, (-2.40, 0.55 * s, 0.95))
        B.beam("quarter", (-2.40, 0.75 * s, 0.35), (-2.40, 0.55 * s, 0.35))
        B.beam("backlight", (-2.55, 0.65 * s, 1.40), (-3.10, 0.55 * s, 0.95))
        B.beam("sill", (-2.40, 0.75 * s, 0.20), (-2.40, 0.75 * s, 0.35))
        B.beam("quarter", (-3.10, 0.55 * s, 0.95), (-3.75, 0.55 * s, 0.75),
               (-3.75, 0.55 * s, 0.35))
        # front: rails, kick-down into floor longitudinals, apron upper rails, posts
        B.beam("front_rail", (0.85, 0.55 * s, 0.40), (-0.50, 0.55 * s, 0.40))
        B.beam("front_rail", (-0.50, 0.55 * s, 0.40), (-0.90, 0.55 * s, 0.20),
               (-2.40, 0.55 * s, 0.20))
        B.beam("upper_rail", (0.70, 0.75 * s, 0.85), (-0.50, 0.75 * s, 0.85))
        B.beam("cross_member", (0.70, 0.55 * s, 0.40), (0.70, 0.55 * s, 0.85))
        B.beam("rear_rail", (-2.40, 0.55 * s, 0.35), (-3.75, 0.55 * s, 0.35))
    B.beam("header", (-1.25, -0.65, 1.40), (-1.25, 0.65, 1.40))
    B.beam("header", (-2.55, -0.65, 1.40), (-2.55, 0.65, 1.40))
    B.beam("header", (-1.90, -0.65, 1.40), (-1.90, 0.65, 1.40))
    B.beam("cowl", (-0.50, -0.75, 0.95), (-0.50, 0.75, 0.95))
    B.beam("cross_member", (-1.20, -0.75, 0.20), (-1.20, 0.75, 0.20))
    B.beam("cross_member", (-2.00, -0.75, 0.20), (-2.00, 0.75, 0.20))
    B.beam("cross_member", (0.70, -0.75, 0.85), (0.70, 0.75, 0.85))
    B.beam("bumper", (0.85, -0.55, 0.40), (0.85, 0.55, 0.40))
    B.beam("cross_member", (0.35, -0.55, 0.40), (0.35, 0.55, 0.40))
    B.beam("cross_member", (0.00, -0.55, 0.40), (0.00, 0.55, 0.40))  # suspension cross
    B.beam("cross_member", (-3.10, -0.55, 0.95), (-3.10, 0.55, 0.95))  # backlight lower
    B.beam("cross_member", (-2.90, -0.55, 0.35), (-2.90, 0.55, 0.35))  # rear floor
    B.beam("cross_member", (-3.30, -0.55, 0.35), (-3.30, 0.55, 0.35))
    B.beam("bumper", (-3.75, -0.55, 0.35), (-3.75, 0.55, 0.35))
    B.beam("cross_member", (-3.75, -0.55, 0.75), (-3.75, 0.55, 0.75))
    suspension_mounts(B)
    return B


def _tripod(B, apex, *feet):
    """A bracket: one short beam from the mount point ``apex`` to each body node in ``feet``."""
    for f in feet:
        B.beam("bracket", apex, f)


def suspension_mounts(B):
    """Front engine cradle, rear subframe and brackets carrying every mount of :func:`mounts`.

    Every mount point is a node of the structure (beam end points are exact); brackets end
    on existing panel or rail nodes (50 mm grid).
    """
    F, R = MOUNTS_LEFT["front"], MOUNTS_LEFT["rear"]

    def m(p, s):  # mirror a left-side point to side s (+1 left, -1 right)
        return (p[0], s * p[1], p[2])

    # ---- front cradle: perimeter frame of closed sections, bolted to the front rails
    laf, lar = F["lower_arm_front"], F["lower_arm_rear"]
    rack, arb = F["rack_mount"], F["arb_bushing"]
    B.beam("cradle_rail", (0.35, -laf[1], laf[2]), (0.35, laf[1], laf[2]))
    B.beam("cradle_rail", m(laf, -1), m(laf, 1))
    B.beam("cradle_rail", m(lar, -1), (lar[0], -0.35, lar[2]), (lar[0], -rack[1], lar[2]),
           (lar[0], rack[1], lar[2]), (lar[0], 0.35, lar[2]), m(lar, 1))
    for s in (-1, 1):
        front_end, rear_end = (0.35, s * laf[1], laf[2]), (-0.45, s * lar[1], lar[2])
        B.beam("cradle_rail", front_end, m(laf, s), m(lar, s), rear_end)
        mid = 0.5 * (np.asarray(m(laf, s)) + np.asarray(m(lar, s)))  # a node of the side member
        for foot, top in ((front_end, (0.35, 0.55 * s, 0.40)), (tuple(mid), (0.0, 0.55 * s, 0.40)),
                          (rear_end, (-0.45, 0.55 * s, 0.40))):
            B.beam("cradle_post", foot, top)
        # steering rack post (to the engine-cradle plate) and anti-roll-bar bracket
        B.beam("cradle_post", (lar[0], s * rack[1], lar[2]), m(rack, s),
               (rack[0], 0.55 * s, 0.40))
        side = np.asarray(m(laf, s)) + 0.75 * (np.asarray(m(lar, s)) - np.asarray(m(laf, s)))
        B.beam("bracket", (lar[0], 0.35 * s, lar[2]), m(arb, s), tuple(side))
        # upper-arm and spring brackets on the strut-tower wall (y = 0.55), stiffened by
        # vertical posts from the front rail to the tower top
        w = 0.55 * s
        for x in (-0.25, -0.10, 0.0):
            B.beam("tower_post", (x, w, 0.40), (x, w, 0.85))
        _tripod(B, m(F["upper_arm_front"], s), (-0.15, w, 0.50), (-0.05, w, 0.50),
                (-0.10, w, 0.55))
        _tripod(B, m(F["upper_arm_rear"], s), (-0.25, w, 0.50), (-0.25, w, 0.55),
                (-0.20, w, 0.55))
        _tripod(B, m(F["spring_upper"], s), (-0.10, w, 0.65), (0.0, w, 0.60), (0.0, w, 0.70))
    # ---- rear: floor cross member over the subframe, subframe on the rails and the floor
    B.beam("cross_member", (-2.70, -0.55, 0.35), (-2.70, 0.55, 0.35))
    lat, tie, rarb = R["lateral_link_inner"], R["tie_rod_inner"], R["arb_bushing"]
    B.beam("rear_cradle", m(lat, -1), m(lat, 1))
    B.beam("rear_cradle", m(tie, -1), m(tie, 1))
    for s in (-1, 1):
        corner_f = (-2.70, 0.45 * s, 0.25)
        corner_r = (-2.95, 0.45 * s, 0.30)
        B.beam("rear_cradle", m(lat, s), corner_f, (-2.70, 0.55 * s, 0.35))
        B.beam("rear_cradle", m(tie, s), m(rarb, s), corner_r, (-2.95, 0.55 * s, 0.35))
        B.beam("rear_cradle", m(lat, s), m(tie, s))
        B.beam("rear_cradle", corner_f, corner_r)
        B.beam("cradle_post", m(lat, s), (-2.70, 0.20 * s, 0.35))
        B.beam("cradle_post", m(tie, s), (-3.00, 0.15 * s, 0.35))
        _tripod(B, m(R["upper_arm_front"], s), (-2.65, 0.40 * s, 0.35),
                (-2.70, 0.35 * s, 0.35), (-2.70, 0.45 * s, 0.35))
        _tripod(B, m(R["upper_arm_rear"], s), (-2.90, 0.30 * s, 0.35),
                (-2.90, 0.40 * s, 0.35), (-2.95, 0.35 * s, 0.35))
        _tripod(B, m(R["trailing_link_front"], s), (-2.00, 0.40 * s, 0.20),
                (-2.00, 0.50 * s, 0.20), (-2.10, 0.45 * s, 0.20))
        _tripod(B, m(R["spring_upper"], s), (-2.60, 0.50 * s, 0.40), (-2.60, 0.45 * s, 0.45),
                (-2.55, 0.55 * s, 0.40), (-2.55, 0.50 * s, 0.35))
        # damper-top reinforcement along the wheelhouse inner wall
        B.beam("tower_post", (-2.40, 0.55 * s, 0.60), (-3.10, 0.55 * s, 0.60))
        _tripod(B, m(R["damper_upper"], s), (-2.60, 0.45 * s, 0.60), (-2.55, 0.55 * s, 0.60),
                (-2.60, 0.55 * s, 0.65), (-2.50, 0.55 * s, 0.60), (-2.65, 0.55 * s, 0.60))


def check_connected(B):
    """Raise when a mount is not a node or a beam end hangs free (a bracket foot that
    missed the panel grid)."""
    X = np.array(B.points)
    for name, p in mounts().items():
        if np.linalg.norm(X - np.asarray(p), axis=1).min() > 1e-6:
            raise RuntimeError(f"mount {name} at {p} is not a node of the body")
    deg = np.zeros(len(X), dtype=int)
    for q in B.quads:
        deg[list(q)] += 2
    for a, b in B.bars:
        deg[a] += 1
        deg[b] += 1
    free = np.flatnonzero(deg == 1)
    if free.size:
        raise RuntimeError(f"{free.size} beam ends hang free, e.g. at {X[free[:3]].tolist()}")


def structural_mass(B) -> float:
    """Mass of shells and beams from geometry (independent of the FE assembly)."""
    X = np.array(B.points)
    q = np.array(B.quads)
    d1 = X[q[:, 2]] - X[q[:, 0]]
    d2 = X[q[:, 3]] - X[q[:, 1]]
    area = 0.5 * np.linalg.norm(np.cross(d1, d2), axis=1)
    inv = {v: k for k, v in B.pids.items()}
    t = np.array([SHELLS[inv[p]][0] for p in B.quad_pid])
    b = np.array(B.bars)
    L = np.linalg.norm(X[b[:, 1]] - X[b[:, 0]], axis=1)
    A = np.array([box_section(*BEAMS[inv[p]])[0] for p in B.bar_pid])
    return float(STEEL["rho"] * (area @ t + L @ A))


def nonstructural_masses(B):
    """(node, mass) pairs of the smeared non-structural masses (see NONSTRUCTURAL)."""
    inv = {v: k for k, v in B.pids.items()}
    out = {}
    for _, mass, groups in NONSTRUCTURAL:
        nodes = sorted({n for (a, b), p in zip(B.bars, B.bar_pid, strict=True) if inv[p] in groups
                        for n in (a, b)})
        for n in nodes:
            out[n] = out.get(n, 0.0) + mass / len(nodes)
    return sorted(out.items())


def _importable() -> None:
    """Make the checkout's ``flexpipe`` importable when the script runs outside the venv."""
    root = str(Path(__file__).resolve().parents[1])
    if root not in sys.path:
        sys.path.insert(0, root)


def write_bdf(B, path: Path) -> dict:
    """Write the Nastran bulk-data file (small-field cards); returns a summary dict."""
    _importable()
    from flexpipe.mesh.nastran_write import card

    def _card(name, *fields):
        return card(name, fields, small=True).rstrip("\n")

    X = np.array(B.points)
    ns = nonstructural_masses(B)
    lines = [
        "$ sedan body-in-white concept model, written by meshes/make_sedan_biw.py",
        "$ units: m, kg, s, N, Pa.  Axes ISO 8855 (x forward, y left, z up), z = 0 ground",
    ]
    for name, p in {**HARDPOINTS, **mounts()}.items():
        lines.append(f"$ HARDPOINT {name} {p[0]:.4f} {p[1]:.4f} {p[2]:.4f}")
    lines.append("BEGIN BULK")
    lines.append(_card("MAT1", 1, STEEL["E"], "", STEEL["nu"], STEEL["rho"]))
    inv = {v: k for k, v in B.pids.items()}
    for pid in sorted(inv):
        name = inv[pid]
        lines.append(f"$ property {pid}: {name}")
        if name in SHELLS:
            E, rho, t = shell_equivalent(name)
            mid = 100 + pid
            lines.append(f"$ equivalent sheet: gauge {SHELLS[name][0] * 1e3:.2f} mm, "
                         f"bending factor {SHELLS[name][1]:g}")
            lines.append(_card("MAT1", mid, E, "", STEEL["nu"], rho))
            lines.append(_card("PSHELL", pid, mid, t, mid, "", mid))
        else:
            A, Iy, Iz, J = box_section(*BEAMS[name])
            # PBAR I1 = bending in plane 1 (local x-y, about local z), I2 about local y
            lines.append(_card("PBAR", pid, 1, A, Iz, Iy, J))
    for i, p in enumerate(X):
        lines.append(_card("GRID", i + 1, "", float(p[0]), float(p[1]), float(p[2])))
    eid = 0
    for q, pid in zip(B.quads, B.quad_pid, strict=True):
        eid += 1
        lines.append(_card("CQUAD4", eid, pid, *(int(n) + 1 for n in q)))
    for (a, b), pid, v in zip(B.bars, B.bar_pid, B.bar_v, strict=True):
        eid += 1
        lines.append(_card("CBAR", eid, pid, a + 1, b + 1, float(v[0]), float(v[1]),
                           float(v[2])))
    for label, mass, groups in NONSTRUCTURAL:
        lines.append(f"$ non-structural mass: {label}, {mass:g} kg on the {', '.join(groups)} "
                     "nodes")
    for n, m in ns:
        eid += 1
        lines.append(_card("CONM2", eid, int(n) + 1, 0, round(m, 6)))
    for k, (name, p) in enumerate(HARDPOINTS.items()):
        near = np.flatnonzero(np.linalg.norm(X - np.asarray(p), axis=1) <= 0.10 + 1e-9)
        lines.append(f"$ SET {name}")
        lines.append(_card("SET1", k + 1, *(int(n) + 1 for n in near)))
    for k, (name, p) in enumerate(mounts().items(), start=len(HARDPOINTS) + 1):
        near = np.flatnonzero(np.linalg.norm(X - np.asarray(p), axis=1)
                              <= MOUNT_SET_RADIUS + 1e-9)
        lines.append(f"$ SET {name}")
        lines.append(_card("SET1", k, *(int(n) + 1 for n in near)))
    lines.append("ENDDATA")
    text = "\n".join(lines) + "\n"
    tmp = path.with_suffix(".tmp")
    tmp.write_text(text)
    tmp.replace(path)
    return {"nodes": len(X), "quads": len(B.quads), "bars": len(B.bars),
            "dof": 6 * len(X), "structural_mass_kg": structural_mass(B),
            "nonstructural_mass_kg": NONSTRUCTURAL_KG, "bytes": len(text)}


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default=str(Path(__file__).with_name("sedan_biw.bdf")))
    ap.add_argument("--check", action="store_true", help="assemble and print modes")
    ap.add_argument("--car", default=None, help="car file whose added masses trim the body")
    args = ap.parse_args(argv)
    B = build()
    check_connected(B)
    info = write_bdf(B, Path(args.out))
    print(f"wrote {args.out}: {info['nodes']} nodes ({info['dof']} DOF), {info['quads']} "
          f"CQUAD4, {info['bars']} CBAR, {info['bytes'] / 1e6:.2f} MB; BIW mass "
          f"{info['structural_mass_kg'] + info['nonstructural_mass_kg']:.1f} kg "
          f"(structure {info['structural_mass_kg']:.1f} kg)")
    if args.check:
        _importable()
        from flexpipe.vehicle.bodymodel import describe_modes

        print(describe_modes(Path(args.out), car=args.car))


if __name__ == "__main__":
    main()
