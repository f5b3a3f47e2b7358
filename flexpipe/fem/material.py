"""Isotropic linear-elastic materials."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError


@dataclass(frozen=True)
class Material:
    """Isotropic linear-elastic material in SI units.

    Parameters
    ----------
    E : float
        Young's modulus, Pa.
    nu : float
        Poisson's ratio, -1 < nu < 0.5.
    rho : float
        Density, kg/m^3.
    name : str, optional
    """

    E: float
    nu: float
    rho: float
    name: str = ""
    _checked: bool = dataclasses.field(default=False, repr=False, compare=False)

    def __post_init__(self):
        from flexpipe._args import checked_number

        for key in ("E", "nu", "rho"):  # numbers (a str or None gave a raw TypeError)
            object.__setattr__(self, key, checked_number(getattr(self, key),
                                                         f"Material {self.name!r}: {key}",
                                                         key=key))
        if not (self.E > 0):
            raise InputError(f"Material {self.name!r}: E must be > 0 Pa, got {self.E}", key="E")
        if not (-1.0 < self.nu < 0.5):
            raise InputError(
                f"Material {self.name!r}: nu must lie in (-1, 0.5), got {self.nu}", key="nu"
            )
        if not (self.rho >= 0):
            raise InputError(
                f"Material {self.name!r}: rho must be >= 0 kg/m^3, got {self.rho}", key="rho"
            )
        if self.rho > 0 and not self._checked:  # a unit slip (E in GPa, rho in g/cm^3) is a
            import warnings  # warning in Python; the command line's options refuse it

            try:
                check_plausible(self.E, self.nu, self.rho)
            except InputError as exc:
                warnings.warn(f"Material {self.name!r}: {exc}", UserWarning, stacklevel=3)

    @property
    def G(self) -> float:
        """Shear modulus, Pa."""
        return self.E / (2.0 * (1.0 + self.nu))

    @classmethod
    def named(cls, name: str) -> Material:
        """Return a library material: ``steel``, ``aluminium``/``aluminum``, ``magnesium``."""
        key = name.lower()
        if key not in LIBRARY:
            raise InputError(f"unknown material '{name}'; valid: {sorted(LIBRARY)}")
        return LIBRARY[key]




def check_plausible(E: float, nu: float, rho: float, *, keys=("E", "nu", "rho"),
                    given=None) -> Material:
    """The material, with the checks a Nastran MAT1 card's values get.

    E > 0, -1 < nu < 0.5, rho >= 0, and (for rho > 0) a bar wave speed ``sqrt(E / rho)``
    within :data:`flexpipe.mesh.units.WAVE_SPEED_RANGE`, the range of solid materials
    (soft rubber ~30 m/s, steel 5200, diamond 18000).

    Parameters
    ----------
    E, nu, rho : float
        SI values (Pa, -, kg/m^3).
    keys : tuple of str
        How the user gave E, nu and rho (e.g. ``("--E", "--nu", "--rho")``): the
        messages name them.
    given : set of str, optional
        Which of ``"E"``, ``"nu"``, ``"rho"`` the user gave (the others came from a
        library material); default all.

    Raises
    ------
    InputError
        With ``key`` the offending option and what would be valid (and the likely unit
        slip, e.g. E in MPa or GPa).
    """
    from flexpipe.mesh.units import _SLIPS, _STEEL_C, WAVE_SPEED_RANGE

    key = dict(zip(("E", "nu", "rho"), keys, strict=True))
    for name, value in (("E", E), ("nu", nu), ("rho", rho)):
        if not np.isfinite(value):
            raise InputError(f"{name} must be a finite number, got {value}", key=key[name])
    if not E > 0:
        raise InputError(f"E must be > 0 Pa (steel: 2.1e11), got {E:g}", key=key["E"])
    if not -1.0 < nu < 0.5:
        raise InputError(f"nu must lie in (-1, 0.5) (steel: 0.3), got {nu:g}", key=key["nu"])
    if not rho >= 0:
        raise InputError(f"rho must be >= 0 kg/m^3 (steel: 7850), got {rho:g}",
                         key=key["rho"])
    lo, hi = WAVE_SPEED_RANGE
    c = float(np.sqrt(E / rho)) if rho > 0 else None
    if c is not None and not lo <= c <= hi:
        given = {"E", "nu", "rho"} if given is None else set(given)
        blame = [n for n in ("E", "rho") if n in given] or ["E", "rho"]
        r = float(np.log10(c / _STEEL_C))
        f, hint = min(_SLIPS, key=lambda fs: abs(np.log10(fs[0]) - r))
        hint = hint if abs(np.log10(f) - r) < 1.0 else "check the units of E and rho"
        hint = hint.replace("RHO", "rho")
        if hint.startswith("rho") and "rho" in given:
            blame = ["rho"]
        raise InputError(
            f"{key['E']} {E:g} Pa and {key['rho']} {rho:g} kg/m^3 give a bar wave speed "
            f"sqrt(E/rho) = {c:.3g} m/s; valid: {lo:g} to {hi:g} m/s, the range of solid "
            f"materials (soft rubber ~30, steel 5200, diamond 18000); {hint}",
            key=key[blame[0]])
    return Material(E, nu, rho, _checked=True)


#: library materials
LIBRARY = {
    "steel": Material(210e9, 0.3, 7850.0, "steel"),
    "aluminium": Material(70e9, 0.33, 2700.0, "aluminium"),
    "aluminum": Material(70e9, 0.33, 2700.0, "aluminium"),
    "magnesium": Material(45e9, 0.35, 1800.0, "magnesium"),
}
