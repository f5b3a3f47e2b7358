"""Nastran coordinate systems: ``CORD1R/1C/1S`` and ``CORD2R/2C/2S``.

A system is an origin ``o`` and a rotation ``R`` (columns = local axes in basic).
Rectangular systems map local ``(x1, x2, x3)`` to ``o + R x``; cylindrical ones read
``(r, theta [deg], z)``, spherical ones ``(r, theta [deg], phi [deg])`` with
``x = r sin(theta) cos(phi)``, ``y = r sin(theta) sin(phi)``, ``z = r cos(theta)``.
The displacement directions of a grid whose ``CD`` is cylindrical or spherical are the
local unit vectors ``(e_r, e_theta, e_z)`` / ``(e_r, e_theta, e_phi)`` at the grid, as in
Nastran.  ``CORD1*`` systems are defined by three grids and resolved once those grids
have basic positions (a ``CORD1`` may use grids given in another system).
"""

from __future__ import annotations

import numpy as np

from flexpipe.mesh._bulk import Card

KINDS = {"CORD1R": "R", "CORD1C": "C", "CORD1S": "S",
         "CORD2R": "R", "CORD2C": "C", "CORD2S": "S"}


class Systems:
    """Resolves coordinate systems by id; errors name the card that refers to them."""

    def __init__(self, cards: dict[int, Card], grid_xyz=None):
        self.cards = cards
        self.cache: dict = {0: (np.zeros(3), np.eye(3), "R")}
        #: callable(grid id, user card) -> basic position (for CORD1*)
        self.grid_xyz = grid_xyz

    def get(self, cid: int, user: Card, _stack=()):
        """``(origin, R, kind)`` of system ``cid``."""
        if cid in self.cache:
            return self.cache[cid]
        card = self.cards.get(cid)
        if card is None:
            raise user.error(f"refers to coordinate system {cid}, which is not defined "
                             "(no CORD1R/1C/1S/2R/2C/2S card with that CID)")
        if cid in _stack:
            raise card.error("coordinate systems refer to each other in a loop")
        kind = KINDS[card.name]
        if card.name.startswith("CORD2"):
            rid = card.int(1, "RID", 0)
            pts = np.array([[card.real(2 + 3 * p + k, "A/B/C", 0.0) for k in range(3)]
                            for p in range(3)])
            A, B, C = (self.to_basic(rid, pts[i:i + 1], card, _stack + (cid,))[0]
                       for i in range(3))
        else:
            if self.grid_xyz is None:
                raise card.error("CORD1 systems need their grids first")
            g = [card.int(1 + k, f"G{k + 1}") for k in range(3)]
            A, B, C = (self.grid_xyz(gi, card, _stack + (cid,)) for gi in g)
        ez = B - A
        ey = np.cross(ez, C - A)
        if not (np.linalg.norm(ez) > 0 and np.linalg.norm(ey) > 0):
            raise card.error("points A, B, C (or grids G1, G2, G3) are collinear or coincide")
        ez = ez / np.linalg.norm(ez)
        ey = ey / np.linalg.norm(ey)
        self.cache[cid] = (A, np.column_stack([np.cross(ey, ez), ey, ez]), kind)
        return self.cache[cid]

    def to_basic(self, cid: int, x: np.ndarray, user: Card, _stack=()) -> np.ndarray:
        """Basic positions of local coordinates ``x`` (n, 3) given in system ``cid``."""
        o, R, kind = self.get(cid, user, _stack)
        x = np.asarray(x, dtype=float).reshape(-1, 3)
        if kind == "C":
            t = np.radians(x[:, 1])
            x = np.column_stack([x[:, 0] * np.cos(t), x[:, 0] * np.sin(t), x[:, 2]])
        elif kind == "S":
            t, p = np.radians(x[:, 1]), np.radians(x[:, 2])
            x = x[:, :1] * np.column_stack([np.sin(t) * np.cos(p), np.sin(t) * np.sin(p),
                                             np.cos(t)])
        return o + x @ R.T

    def frames(self, cid: int, X: np.ndarray, user: Card) -> np.ndarray:
        """Displacement frames (n, 3, 3) of system ``cid`` at basic points ``X`` (n, 3).

        Columns are the component directions 1, 2, 3 in basic.
        """
        o, R, kind = self.get(cid, user)
        X = np.asarray(X, dtype=float).reshape(-1, 3)
        n = len(X)
        if kind == "R":
            return np.broadcast_to(R, (n, 3, 3)).copy()
        loc = (X - o) @ R
        if kind == "C":
            t = np.arctan2(loc[:, 1], loc[:, 0])
            c, s = np.cos(t), np.sin(t)
            z, o1 = np.zeros(n), np.ones(n)
            F = np.stack([np.stack([c, s, z], 1), np.stack([-s, c, z], 1),
                          np.stack([z, z, o1], 1)], axis=2)
        else:
            r = np.linalg.norm(loc, axis=1)
            t = np.arccos(np.clip(loc[:, 2] / np.where(r > 0, r, 1.0), -1, 1))
            p = np.arctan2(loc[:, 1], loc[:, 0])
            st, ct, sp, cp = np.sin(t), np.cos(t), np.sin(p), np.cos(p)
            F = np.stack([np.stack([st * cp, st * sp, ct], 1),
                          np.stack([ct * cp, ct * sp, -st], 1),
                          np.stack([-sp, cp, np.zeros(n)], 1)], axis=2)
        return np.einsum("ij,njk->nik", R, F)
