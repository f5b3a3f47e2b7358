"""Unit systems of mesh files and the conversion of a :class:`Mesh` to SI.

Two separate knobs exist, because most mesh files carry geometry only while solver
decks (Nastran, Abaqus) also carry materials, masses and inertias:

``scale`` (a length factor, e.g. ``1e-3`` for millimetre meshes)
    multiplies every *purely geometric* quantity: node coordinates, point-mass offsets,
    element offsets (``block.data`` keys ending in ``offset``), shell thickness, beam
    area (``scale**2``) and second moments / torsion constant (``scale**4``).  It does
    **not** touch Young's modulus, density, concentrated masses or rotary inertias: a
    millimetre deck whose MAT1 holds E in MPa and rho in t/mm^3 needs ``units``.
Springs and dampers (``spring`` cells) convert with ``units`` only (force per length,
per radian ...), like the materials.
``units`` (``"SI"``, ``"mm-t-s"``, ``"mm-kg-s"``, ``"mm-kg-ms"``, ``"mm-g-ms"``,
``"cm-g-s"``, ... any ``LENGTH-MASS-TIME`` from the tables below)
    converts everything consistently: lengths as above, E and G by
    ``mass / (length time^2)``, rho by ``mass / length^3``, point masses by ``mass`` and
    rotary inertias by ``mass length^2``.  ``units="mm-t-s"`` therefore turns E = 210000
    (MPa) into 2.1e11 Pa and rho = 7.85e-9 (t/mm^3) into 7850 kg/m^3.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from flexpipe.errors import InputError

LENGTH_M = {"m": 1.0, "cm": 1e-2, "mm": 1e-3, "um": 1e-6}
MASS_KG = {"kg": 1.0, "t": 1e3, "g": 1e-3, "mg": 1e-6}
TIME_S = {"s": 1.0, "ms": 1e-3}
ALIASES = {"si": "m-kg-s", "mks": "m-kg-s", "mmns": "mm-t-s", "cgs": "cm-g-s"}

#: section keys and the power of (length, mass, time) of their unit
SECTION_DIMENSIONS = {
    "thickness": (1, 0, 0), "A": (2, 0, 0), "Iy": (4, 0, 0), "Iz": (4, 0, 0),
    "J": (4, 0, 0), "E": (-1, 1, -2), "G": (-1, 1, -2), "rho": (-3, 1, 0),
    # laminate rigidities (PCOMP): A and Gt force per length, D force times length
    **{f"A{ij}": (0, 1, -2) for ij in ("11", "12", "16", "22", "26", "66")},
    **{f"D{ij}": (2, 1, -2) for ij in ("11", "12", "16", "22", "26", "66")},
    "Gt": (0, 1, -2),
}


@dataclass(frozen=True)
class UnitSystem:
    """Factors that convert one unit of length, mass and time of a file to SI."""

    length: float = 1.0
    mass: float = 1.0
    time: float = 1.0
    name: str = "m-kg-s"

    def factor(self, dims) -> float:
        """SI factor of a quantity with dimensions ``(length, mass, time)`` powers."""
        a, b, c = dims
        return self.length**a * self.mass**b * self.time**c


def unit_system(units) -> UnitSystem:
    """Parse a unit-system name such as ``"mm-t-s"`` (case-insensitive) or ``"SI"``."""
    if isinstance(units, UnitSystem):
        return units
    key = str(units).strip().lower()
    key = ALIASES.get(key, key)
    parts = key.split("-")
    valid = (f"'SI' or LENGTH-MASS-TIME with LENGTH in {sorted(LENGTH_M)}, MASS in "
             f"{sorted(MASS_KG)}, TIME in {sorted(TIME_S)} (e.g. 'mm-t-s')")
    if len(parts) != 3 or parts[0] not in LENGTH_M or parts[1] not in MASS_KG \
            or parts[2] not in TIME_S:
        raise InputError(f"unknown unit system {units!r}; valid: {valid}", key="units")
    return UnitSystem(LENGTH_M[parts[0]], MASS_KG[parts[1]], TIME_S[parts[2]], key)


def resolve(scale=1.0, units=None) -> tuple[UnitSystem, bool]:
    """Combine ``scale`` and ``units`` into one :class:`UnitSystem`.

    Returns ``(system, convert_materials)``: with ``units`` materials and masses are
    converted too; with ``scale`` alone only geometry is.
    """
    try:
        s = float(scale)
    except (TypeError, ValueError):
        raise InputError(f"scale must be a positive number, got {scale!r}", key="scale") from None
    if not (np.isfinite(s) and s > 0):
        raise InputError(f"scale must be a positive number, got {scale!r}", key="scale")
    if units is None:
        return UnitSystem(length=s, name=f"length x {s:g}"), False
    us = unit_system(units)
    if s != 1.0 and not np.isclose(s, us.length, rtol=1e-12):
        raise InputError(
            f"scale={s:g} contradicts units={units!r} (length factor {us.length:g}); give "
            "only units (it sets the length scale) or only scale", key="scale")
    return us, True


def convert(mesh, system: UnitSystem, *, materials: bool):
    """Return ``mesh`` converted to SI with ``system`` (see module docstring).

    Parameters
    ----------
    mesh : Mesh
    system : UnitSystem
    materials : bool
        Also convert E, G, rho, point masses and rotary inertias (``units`` given).
    """
    L = system.length
    if L == 1.0 and (not materials or (system.mass == 1.0 and system.time == 1.0)):
        return mesh
    from flexpipe.mesh.mesh import CellBlock, PointMass

    sections = {}
    for name, props in mesh.sections.items():
        out = dict(props)
        for key, dims in SECTION_DIMENSIONS.items():
            if key in out and (materials or dims[1:] == (0, 0)):
                out[key] = float(out[key]) * system.factor(dims)
        sections[name] = out
    blocks = []
    for b in mesh.blocks:
        data = {k: (np.asarray(v, dtype=float) * L if k.endswith("offset") else v)
                for k, v in b.data.items()}
        if b.type in ("spring", "spring1") and materials:
            # spring matrices: N/m, N/rad, N m/rad blocks; dampers times one time unit
            nn = 2 if b.type == "spring" else 1
            pat = np.kron(np.ones((nn, nn)), np.kron([[1.0, L], [L, L * L]], np.ones((3, 3))))
            f = system.mass / system.time**2
            for key, extra_t in (("K", 1.0), ("B", system.time)):
                if key in data:
                    data[key] = np.asarray(data[key], dtype=float) * pat * f * extra_t
            rot = np.array([1.0, 1.0, 1.0, L * L, L * L, L * L]) * f
            for key, extra_t in (("k6", 1.0), ("b6", system.time)):
                if key in data:
                    data[key] = np.asarray(data[key], dtype=float) * rot * extra_t
        blocks.append(CellBlock(b.type, b.cells, b.ids, b.tags, data))
    mass_f = system.mass if materials else 1.0
    inertia_f = system.factor((2, 1, 0)) if materials else 1.0
    masses = tuple(
        PointMass(pm.node, pm.mass * mass_f, np.asarray(pm.inertia, dtype=float) * inertia_f,
                  np.asarray(pm.offset, dtype=float) * L, pm.id,
                  None if pm.matrix is None else np.asarray(pm.matrix, dtype=float)
                  * np.kron([[1.0, L], [L, L * L]], np.ones((3, 3)))
                  * (mass_f if materials else 1.0))
        for pm in mesh.point_masses
    )
    solution = dict(mesh.solution)
    if materials:   # EIGRL frequency range in 1 / (file time unit)
        for key in ("f_min", "f_max"):
            if solution.get(key) is not None:
                solution[key] = float(solution[key]) / system.time
    return replace(mesh, points=mesh.points * L, blocks=tuple(blocks), sections=sections,
                   point_masses=masses, solution=solution)
