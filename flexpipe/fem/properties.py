"""Per-cell properties: beam sections, and resolution of material, shell thickness and
beam section for every cell of a block.

Explicit arguments come first (a single value, or a mapping from cell-set name to value
with an optional ``"default"``), then the properties the mesh file carried
(:attr:`~flexpipe.mesh.Mesh.sections`, e.g. Nastran PSHELL/PBAR/MAT1).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError, MeshError
from flexpipe.fem.material import Material
from flexpipe.mesh.mesh import Mesh
from flexpipe.mesh.validate import missing_property_note


@dataclass(frozen=True)
class BeamSection:
    """Cross-section of a 3D beam, SI units.

    Parameters
    ----------
    A : float
        Area, m^2.
    Iy, Iz : float
        Second moments of area about the local y and z axes, m^4.
    J : float
        Torsion constant, m^4.
    orientation : (3,) array_like, optional
        Vector lying in the local x-y plane (Nastran CBAR convention); local
        z = x cross v.  Default: global z, or global y for beams parallel to z.
    k1, k2 : float
        Transverse-shear area factors (Nastran PBAR K1, K2): shear stiffness ``k1 G A``
        in the x-y plane (with ``Iz``), ``k2 G A`` in x-z (with ``Iy``).  0 (default):
        no shear deformation, Euler-Bernoulli.
    theta : float
        Angle (rad) of the principal section axes from the local y axis about x.
    """

    A: float
    Iy: float
    Iz: float
    J: float
    orientation: tuple[float, float, float] | None = None
    k1: float = 0.0
    k2: float = 0.0
    theta: float = 0.0

    @classmethod
    def rectangle(cls, b: float, h: float, **kw) -> BeamSection:
        """Solid rectangle: width ``b`` along local z, height ``h`` along local y."""
        a, c = max(b, h), min(b, h)
        J = a * c**3 * (1 / 3 - 0.21 * c / a * (1 - c**4 / (12 * a**4)))
        # Iy = int z^2 dA (z spans the width b), Iz = int y^2 dA (y spans the height h)
        return cls(b * h, h * b**3 / 12, b * h**3 / 12, J, **kw)

    @classmethod
    def circle(cls, d: float, **kw) -> BeamSection:
        """Solid circle of diameter ``d``."""
        I = np.pi * d**4 / 64
        return cls(np.pi * d**2 / 4, I, I, 2 * I, **kw)

    @classmethod
    def box(cls, b: float, h: float, t: float, **kw) -> BeamSection:
        """Thin-walled rectangular tube, outer width ``b`` (local z) x height ``h`` (local
        y), wall ``t`` (Bredt torsion)."""
        bi, hi = b - 2 * t, h - 2 * t
        Iy = (h * b**3 - hi * bi**3) / 12
        Iz = (b * h**3 - bi * hi**3) / 12
        bm, hm = b - t, h - t
        J = 4 * (bm * hm) ** 2 * t / (2 * (bm + hm))
        return cls(b * h - bi * hi, Iy, Iz, J, **kw)


def per_cell(mesh: Mesh, bi: int, n: int, value, name: str, section_keys):
    """Resolve a property (scalar, object or set->value mapping) to one value per cell."""
    out = [None] * n
    if value is not None and not isinstance(value, Mapping):
        return [value] * n
    mapping = dict(value or {})
    default = mapping.pop("default", None)
    if default is not None:
        out = [default] * n
    # properties stored with the mesh (e.g. PSHELL/MAT1), by cell set
    for set_name, props in mesh.sections.items():
        if set_name in mapping or bi not in mesh.cell_sets.get(set_name, {}):
            continue
        val = section_keys(props)
        if val is not None:
            for c in mesh.cell_sets[set_name][bi]:
                if out[c] is None or default is None:
                    out[c] = val
    for set_name, val in mapping.items():
        if set_name not in mesh.cell_sets:
            raise InputError(
                f"{name} given for cell set '{set_name}', which the mesh does not have; "
                f"valid: {sorted(mesh.cell_sets)} or 'default'", file=mesh.source or None,
                key=set_name,
            )
        for c in mesh.cell_sets[set_name].get(bi, ()):
            out[c] = val
    return out


def material_arrays(mesh, bi, block, material):
    def from_section(p):
        if all(k in p for k in ("E", "nu", "rho")):
            return Material(float(p["E"]), float(p["nu"]), float(p["rho"]))
        return None

    mats = per_cell(mesh, bi, len(block), material, "material", from_section)
    if len(set(map(id, mats))) == 1 and mats[0] is not None:  # one material: no loops
        m = mats[0]
        return tuple(np.full(len(mats), float(v)) for v in (m.E, m.nu, m.rho))
    missing = [i for i, m in enumerate(mats) if m is None]
    if missing:
        ids = block.ids[missing[:10]].tolist()
        raise MeshError(
            f"{missing_property_note(mesh, bi, missing)}"
            f"no material for {len(missing)} {block.type} element(s), e.g. ids {ids}; pass "
            "material=Material(E, nu, rho) or a mapping {cell_set: Material, 'default': ...}",
            file=mesh.source or None,
        )
    E = np.array([m.E for m in mats])
    nu = np.array([m.nu for m in mats])
    rho = np.array([m.rho for m in mats])
    return E, nu, rho


def shell_props(mesh, bi, block, thickness):
    def from_section(p):
        return float(p["thickness"]) if "thickness" in p else None

    t = per_cell(mesh, bi, len(block), thickness, "thickness", from_section)
    bad = [i for i, v in enumerate(t) if v is None or not np.isfinite(v) or v <= 0]
    if bad:
        ids = block.ids[bad[:10]].tolist()
        raise MeshError(
            f"{missing_property_note(mesh, bi, bad)}"
            f"{len(bad)} shell ({block.type}) element(s) have no positive thickness, e.g. ids "
            f"{ids}; pass thickness=<m> (or a mapping by cell set) or give PSHELL T",
            file=mesh.source or None,
        )
    def bend(p):
        return float(p["bending"]) if "bending" in p else None

    b = per_cell(mesh, bi, len(block), None, "bending", bend)
    out = {"thickness": np.asarray(t, dtype=float),
           "bending": np.array([1.0 if v is None else v for v in b], dtype=float)}
    if "zoffset" in block.data:
        out["zoffset"] = np.asarray(block.data["zoffset"], dtype=float)

    def lam(p):
        return p if "A11" in p else None

    lams = per_cell(mesh, bi, len(block), None, "laminate", lam)
    if any(v is not None for v in lams):
        out["laminate_rows"] = lams
        n = len(block)
        out["laminate_ref"] = np.asarray(block.data.get("mat_ref", np.full((n, 3), np.nan)),
                                         dtype=float)
        out["laminate_theta"] = np.asarray(block.data.get("mat_theta", np.zeros(n)),
                                           dtype=float)
    return out


_IJ = ((0, 0, "11"), (0, 1, "12"), (0, 2, "16"), (1, 1, "22"), (1, 2, "26"), (2, 2, "66"))


def laminate_arrays(rows, E, nu, t, ref=None, theta=None):
    """``(A, D, Gt, ref, theta)`` arrays of a shell block: laminate sections (PCOMP) where
    given, the isotropic plane-stress values elsewhere; ``ref``/``theta`` orient the
    material axes per cell (see :func:`flexpipe.fem._shell.material_angle`)."""
    from flexpipe.fem import _shell

    n = len(rows)
    ones = np.ones(n)
    A, D, Gt = _shell.rigidities(np.asarray(E, float), np.asarray(nu, float),
                                 np.asarray(t, float), ones, None)
    A, D, Gt = A.copy(), D.copy(), np.array(Gt, dtype=float)
    for c, p in enumerate(rows):
        if p is None:
            continue
        for i, j, ij in _IJ:
            A[c, i, j] = A[c, j, i] = float(p["A" + ij])
            D[c, i, j] = D[c, j, i] = float(p["D" + ij])
        Gt[c] = float(p["Gt"])
    ref = np.full((n, 3), np.nan) if ref is None else ref
    theta = np.zeros(n) if theta is None else theta
    return A, D, Gt, ref, theta


def beam_props(mesh, bi, block, beam_section):
    def from_section(p):
        if all(k in p for k in ("A", "Iy", "Iz", "J")):
            return BeamSection(float(p["A"]), float(p["Iy"]), float(p["Iz"]), float(p["J"]),
                               k1=float(p.get("k1", 0.0)), k2=float(p.get("k2", 0.0)),
                               theta=float(p.get("theta", 0.0)))
        return None

    secs = per_cell(mesh, bi, len(block), beam_section, "beam_section", from_section)
    bad = [i for i, s in enumerate(secs) if s is None]
    if bad:
        ids = block.ids[bad[:10]].tolist()
        raise MeshError(
            f"{missing_property_note(mesh, bi, bad)}"
            f"{len(bad)} beam element(s) have no cross-section, e.g. ids {ids}; pass "
            "beam_section=BeamSection(A, Iy, Iz, J) (or a mapping by cell set) or give PBAR",
            file=mesh.source or None,
        )
    props = {k: np.array([getattr(s, k) for s in secs], dtype=float)
             for k in ("A", "Iy", "Iz", "J", "k1", "k2", "theta")}
    bad = [i for i, s in enumerate(secs)
           if not all(np.isfinite(getattr(s, k)) for k in ("A", "Iy", "Iz", "J", "k1", "k2"))
           or s.A <= 0 or s.Iy < 0 or s.Iz < 0 or s.J < 0 or s.k1 < 0 or s.k2 < 0]
    if bad:
        ids = block.ids[bad[:10]].tolist()
        s = secs[bad[0]]
        raise MeshError(
            f"{len(bad)} beam element(s) have an invalid cross-section, e.g. ids {ids} with "
            f"A={s.A:g}, Iy={s.Iy:g}, Iz={s.Iz:g}, J={s.J:g}, k1={s.k1:g}, k2={s.k2:g}; "
            "valid: A > 0 and Iy, Iz, J, k1, k2 >= 0 (finite)", file=mesh.source or None)
    orient = np.array([s.orientation if s.orientation is not None else (np.nan,) * 3
                       for s in secs], dtype=float)
    if "orientation" in block.data:
        given = np.asarray(block.data["orientation"], dtype=float)
        use = np.isfinite(given).all(axis=1) & np.isnan(orient).any(axis=1)
        orient[use] = given[use]
    props["orientation"] = orient
    for key in ("offset_a", "offset_b"):
        if key in block.data:
            props[key] = np.asarray(block.data[key], dtype=float)
    if "release" in block.data:
        props["release"] = np.asarray(block.data["release"], dtype=np.int64)
    return props
