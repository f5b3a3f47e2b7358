"""Isotropic linear-elastic materials."""

from __future__ import annotations

from dataclasses import dataclass

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

    def __post_init__(self):
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


LIBRARY = {
    "steel": Material(210e9, 0.3, 7850.0, "steel"),
    "aluminium": Material(70e9, 0.33, 2700.0, "aluminium"),
    "aluminum": Material(70e9, 0.33, 2700.0, "aluminium"),
    "magnesium": Material(45e9, 0.35, 1800.0, "magnesium"),
}
