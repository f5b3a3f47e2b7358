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

:func:`check_wave_speeds` then checks each material card the model uses (the reader's
``Mesh.info["materials"]``, Nastran MAT1/MAT8): its bar wave speed ``sqrt(E / rho)`` in
the model's SI units should be one of a solid (:data:`WAVE_SPEED_RANGE`).  A card outside
it is a warning (decks use stiff or massless dummy materials for connector bars); every
material outside it on the same side is an error, a unit slip of the whole deck (E or RHO
given in another unit system, a mm-t-s deck read as SI).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from flexpipe.errors import InputError, MeshError

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


#: Bar wave speed sqrt(E / rho) of a solid material, m/s: (lowest, highest) accepted.
#: The softest solids in a vehicle model, rubber bushes and foams (E ~ 1 MPa at
#: rho ~ 1100-1500 kg/m^3, or ~0.1-1 MPa at 30-100 kg/m^3), have c ~ 30 m/s; the stiffest
#: solid, diamond (E ~ 1050 GPa, rho = 3510 kg/m^3), 17-18 km/s (beryllium 12.9 km/s,
#: high-modulus CFRP along the fibres ~14 km/s); metals, glass, wood, plastics and
#: composites lie in between (steel, aluminium, titanium, magnesium: 5.0-5.2 km/s).  The
#: bounds keep a margin of about 3x beyond both ends, while the usual unit slips move c
#: far outside: E in MPa with rho in kg/m^3 gives 5 m/s for any metal (c / 1000), rho in
#: g/cm^3 1.6e5 m/s (c x 31.6), a whole mm-t-s deck read as SI 5.2e6 m/s (c x 1000), rho
#: in t/mm^3 with E in Pa 5.2e9 m/s (c x 1e6).
WAVE_SPEED_RANGE = (10.0, 5.0e4)
#: factor on c of each slip (with SI assumed) -> what it looks like and what to do
_SLIPS = (
    (1e6, "RHO looks like t/mm^3 (an mm-t-s value) while E is in Pa: give RHO in kg/m^3 "
          "(steel: 7850)"),
    (1e3, "E and RHO look like mm-t-s values (MPa, t/mm^3): read the deck with "
          "units='mm-t-s' (option --units mm-t-s; mesh_units in a car file)"),
    (10**1.5, "RHO looks like g/cm^3: give it in kg/m^3 (steel: 7850)"),
    (1e-3, "E looks like MPa (N/mm^2) while RHO is in kg/m^3: give E in Pa (steel: 2.1e11)"),
    (10**-4.5, "E looks like GPa: give it in Pa (steel: 2.1e11)"),
)
_STEEL_C = (210e9 / 7850.0) ** 0.5


def check_wave_speeds(mesh, system: UnitSystem, *, materials: bool) -> None:
    """Check that every material card the model uses has a plausible bar wave speed.

    ``mesh.info["materials"]`` (``{"MAT1 <mid>": (E, RHO, file, line)}``, file units)
    and ``mesh.info["wtmass"]`` (PARAM WTMASS) come from the Nastran reader; E and
    RHO x WTMASS are taken as the model takes them: converted with ``system`` when
    ``materials`` (``units`` was given), as SI otherwise.

    A single card outside :data:`WAVE_SPEED_RANGE` is not certainly wrong: production
    decks use deliberately stiff or nearly massless dummy materials for connector bars
    (e.g. E = 1000 x steel's with steel's density, 1.6e5 m/s).  A unit slip of the whole
    deck, though, moves *every* material's speed the same way.

    Warns
    -----
    MeshWarning
        For each card outside the range that is not part of such a global slip (the
        message names the file, line, card, E, RHO and the speed); with ``units`` or a
        WTMASS (a stated conversion) for every card outside the range (the message says
        when the values look like SI).

    Raises
    ------
    MeshError
        When the deck states no unit conversion (no ``units``, no WTMASS: E and RHO are
        taken as SI) and every material the model uses lies outside the range on the
        same side; the message names the first card, E, RHO, the speed, the other cards
        and the likely unit slip (e.g. read the deck with ``units='mm-t-s'``).
    """
    import warnings

    from flexpipe.mesh.validate import MeshWarning

    lo, hi = WAVE_SPEED_RANGE
    wtmass = float(mesh.info.get("wtmass", 1.0))
    fE = system.factor(SECTION_DIMENSIONS["E"]) if materials else 1.0
    frho = (system.factor(SECTION_DIMENSIONS["rho"]) if materials else 1.0) * wtmass
    speeds = {name: (E, rho, file, line, float(np.sqrt(E * fE / (rho * frho))))
              for name, (E, rho, file, line) in (mesh.info.get("materials") or {}).items()
              if E > 0 and rho > 0}
    out = {name: v for name, v in speeds.items() if not lo <= v[4] <= hi}
    if not out:
        return
    stated = materials or wtmass != 1.0
    taken = ([f"converted from units {system.name!r}"] if materials else
             ["taken as SI (Pa, kg/m^3)" + ("" if wtmass != 1.0 else
                                            ", as no units were given")])
    if wtmass != 1.0:
        taken.append(f"RHO times PARAM WTMASS {wtmass:g}")

    def what(name):
        E, rho, _, _, c = speeds[name]
        return (f"{name}: E = {E:g} and RHO = {rho:g} ({', '.join(taken)}) give a bar wave "
                f"speed sqrt(E/RHO) = {c:.3g} m/s; valid: {lo:g} to {hi:g} m/s, the range "
                "of solid materials (soft rubber ~30, steel 5200, diamond 18000)")

    sides = {v[4] > hi for v in out.values()}
    if not stated and len(out) == len(speeds) and len(sides) == 1:
        # every material off the same way: a unit slip of the whole deck
        name, (_, _, file, line, _) = next(iter(out.items()))
        others = [f"{n} ({v[4]:.3g} m/s)" for n, v in out.items() if n != name]
        also = (f"; so do all the other materials the model uses: {', '.join(others[:5])}"
                f"{', ...' if len(others) > 5 else ''}" if others else "")
        r = float(np.median([np.log10(v[4] / _STEEL_C) for v in out.values()]))
        f, hint = min(_SLIPS, key=lambda fs: abs(np.log10(fs[0]) - r))
        hint = hint if abs(np.log10(f) - r) < 1.0 else "check the units of E and RHO"
        raise MeshError(f"{what(name)}{also}; {hint}", file=file, line=line)
    for name, (E, rho, file, line, c) in out.items():
        if stated:      # a stated conversion: warn, do not overrule
            how = f"units {system.name!r}" if materials else f"WTMASS {wtmass:g}"
            hint = (f"the values look like SI (m-kg-s) ones: check {how}"
                    if lo <= np.sqrt(E / rho) <= hi else f"check E, RHO and {how}")
        else:           # other materials are solid: a deliberate dummy, not a unit slip
            kind = "stiff or light" if c > hi else "soft or heavy"
            hint = (f"accepted as a deliberately {kind} material (e.g. a dummy connector "
                    "bar), since not every material of the model is off the same way (a "
                    "unit slip of the whole deck would move them all); check E and RHO if "
                    "it is not meant to be")
        warnings.warn(MeshWarning(f"{file} line {line}: {what(name)}; {hint}"), stacklevel=3)
