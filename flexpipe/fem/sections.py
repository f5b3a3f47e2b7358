"""Standard beam cross-sections (Nastran PBARL/PBEAML, Abaqus *BEAM SECTION).

:func:`standard_section` turns a shape name and its dimensions into ``A``, ``I1``, ``I2``,
``I12``, ``J`` and the transverse-shear area factors ``K1``, ``K2``, in the Nastran
section frame: ``y`` (plane 1, ``I1 = int y^2 dA``) is the section's *height* direction,
``z`` (plane 2, ``I2 = int z^2 dA``) its *width*; ``I12 = int y z dA``.  Dimensions
follow the MSC/NX Nastran PBARL figures:

=====  ==========================================================================
ROD    DIM1 radius
TUBE   DIM1 outer radius, DIM2 inner radius
BAR    DIM1 width (z), DIM2 height (y)
BOX    DIM1 width, DIM2 height, DIM3 top/bottom wall thickness, DIM4 side walls
I      DIM1 height, DIM2 bottom flange width, DIM3 top flange width, DIM4 web,
       DIM5 bottom flange thickness, DIM6 top flange thickness
T      DIM1 flange width, DIM2 height, DIM3 flange thickness, DIM4 web thickness
L      DIM1 width, DIM2 height, DIM3 horizontal leg thickness, DIM4 vertical leg
CHAN   DIM1 width, DIM2 height, DIM3 web thickness, DIM4 flange thickness
HAT    DIM1 height, DIM2 wall thickness, DIM3 crown width, DIM4 brim width (each side)
=====  ==========================================================================

Properties are about the centroid (the beam nodes are taken on the centroidal axis; as
in Nastran's PBARL the offset of the shear centre of open unsymmetric sections is not
modelled).  Torsion: exact for ROD and TUBE, Saint-Venant series (Roark) for BAR,
Bredt for BOX, ``sum b t^3 / 3`` for open thin-walled shapes.  Shear factors: Cowper
(1966) for ROD (``6(1+nu)/(7+6nu)``), TUBE and BAR (``10(1+nu)/(12+11nu)``); for
thin-walled shapes the area of the walls parallel to the shear over the total area.
"""

from __future__ import annotations

import numpy as np

#: number of dimensions of each shape
N_DIMS = {"ROD": 1, "TUBE": 2, "BAR": 2, "BOX": 4, "I": 6, "T": 4, "L": 4, "CHAN": 4,
          "HAT": 4}


def _rects(shape: str, d) -> list[tuple[float, float, float, float]]:
    """Rectangles ``(z_centre, y_centre, width_z, height_y)`` making up a thin-walled shape."""
    if shape == "BOX":
        b, h, t1, t2 = d
        return [(-(b - t2) / 2, 0.0, t2, h), ((b - t2) / 2, 0.0, t2, h),
                (0.0, (h - t1) / 2, b - 2 * t2, t1), (0.0, -(h - t1) / 2, b - 2 * t2, t1)]
    if shape == "I":
        h, wb, wt, tw, tb, tt = d
        hw = h - tb - tt
        return [(0.0, tb / 2, wb, tb), (0.0, h - tt / 2, wt, tt), (0.0, tb + hw / 2, tw, hw)]
    if shape == "T":
        bf, h, tf, tw = d
        return [(0.0, h - tf / 2, bf, tf), (0.0, (h - tf) / 2, tw, h - tf)]
    if shape == "L":
        b, h, th, tv = d
        return [(tv / 2, h / 2, tv, h), (tv + (b - tv) / 2, th / 2, b - tv, th)]
    if shape == "CHAN":
        b, h, tw, tf = d
        return [(tw / 2, h / 2, tw, h), (tw + (b - tw) / 2, tf / 2, b - tw, tf),
                (tw + (b - tw) / 2, h - tf / 2, b - tw, tf)]
    if shape == "HAT":
        h, t, wc, wb = d
        return [(0.0, h - t / 2, wc, t),
                (-(wc - t) / 2, (h - t) / 2, t, h - t), ((wc - t) / 2, (h - t) / 2, t, h - t),
                (-(wc / 2 + wb / 2), t / 2, wb, t), (wc / 2 + wb / 2, t / 2, wb, t)]
    raise KeyError(shape)


def _check(shape: str, d) -> str | None:
    """Why the dimensions do not make a section, or None."""
    if shape == "TUBE" and not d[1] < d[0]:
        return "inner radius DIM2 must be smaller than the outer radius DIM1"
    if shape == "BOX" and not (2 * d[3] < d[0] and 2 * d[2] < d[1]):
        return "walls too thick: need 2 DIM4 < DIM1 and 2 DIM3 < DIM2"
    if shape == "I" and not (d[4] + d[5] < d[0] and d[3] <= min(d[1], d[2])):
        return "need DIM5 + DIM6 < DIM1 and DIM4 <= DIM2, DIM3"
    if shape == "T" and not (d[2] < d[1] and d[3] <= d[0]):
        return "need DIM3 < DIM2 and DIM4 <= DIM1"
    if shape in ("L", "CHAN") and not (d[3 if shape == "L" else 2] < d[0]
                                       and d[2 if shape == "L" else 3] < d[1]):
        return "wall thicknesses must be smaller than the width and the height"
    if shape == "HAT" and not (2 * d[1] < d[0] and 2 * d[1] < d[2]):
        return "need 2 DIM2 < DIM1 and 2 DIM2 < DIM3"
    return None


def standard_section(shape: str, dims, nu: float = 0.3) -> dict:
    """Section properties of a standard shape.

    Parameters
    ----------
    shape : str
        One of :data:`N_DIMS` (case-insensitive).
    dims : sequence of float
        The shape's dimensions (lengths, > 0), see the module table.
    nu : float
        Poisson's ratio (Cowper shear factors of solid shapes).

    Returns
    -------
    dict
        ``A, I1, I2, I12, J, K1, K2``.

    Raises
    ------
    ValueError
        Unknown shape, wrong number of dimensions, or dimensions that make no section
        (the message says what is valid).
    """
    shape = shape.upper()
    if shape not in N_DIMS:
        raise ValueError(f"section type '{shape}' is not supported; valid: "
                         f"{', '.join(N_DIMS)}")
    d = [float(x) for x in dims]
    if len(d) != N_DIMS[shape]:
        raise ValueError(f"{shape} needs {N_DIMS[shape]} dimensions, got {len(d)}")
    if not all(np.isfinite(x) and x > 0 for x in d):
        raise ValueError(f"{shape} dimensions must be finite and > 0, got {d}")
    why = _check(shape, d)
    if why:
        raise ValueError(f"{shape} dimensions {d}: {why}")
    if shape == "ROD":
        r = d[0]
        I = np.pi * r**4 / 4
        k = 6 * (1 + nu) / (7 + 6 * nu)
        return dict(A=np.pi * r**2, I1=I, I2=I, I12=0.0, J=2 * I, K1=k, K2=k)
    if shape == "TUBE":
        ro, ri = d
        I = np.pi * (ro**4 - ri**4) / 4
        m2 = (ri / ro) ** 2
        k = 6 * (1 + nu) * (1 + m2) ** 2 / ((7 + 6 * nu) * (1 + m2) ** 2 + (20 + 12 * nu) * m2)
        return dict(A=np.pi * (ro**2 - ri**2), I1=I, I2=I, I12=0.0, J=2 * I, K1=k, K2=k)
    if shape == "BAR":
        b, h = d
        a, c = max(b, h), min(b, h)
        J = a * c**3 * (1 / 3 - 0.21 * c / a * (1 - c**4 / (12 * a**4)))
        k = 10 * (1 + nu) / (12 + 11 * nu)
        return dict(A=b * h, I1=b * h**3 / 12, I2=h * b**3 / 12, I12=0.0, J=J, K1=k, K2=k)
    R = np.array(_rects(shape, d))
    z, y, w, h = R.T
    a = w * h
    A = a.sum()
    zc, yc = (a * z).sum() / A, (a * y).sum() / A
    I1 = (w * h**3 / 12 + a * (y - yc) ** 2).sum()
    I2 = (h * w**3 / 12 + a * (z - zc) ** 2).sum()
    I12 = (a * (y - yc) * (z - zc)).sum()
    if shape == "BOX":
        b, hh, t1, t2 = d
        line = 2 * (b - t2) / t1 + 2 * (hh - t1) / t2
        J = 4 * ((b - t2) * (hh - t1)) ** 2 / line
    else:
        J = (np.maximum(w, h) * np.minimum(w, h) ** 3 / 3).sum()
    vertical = h >= w
    K1 = a[vertical].sum() / A
    K2 = a[~vertical].sum() / A
    return dict(A=A, I1=I1, I2=I2, I12=I12 if abs(I12) > 1e-12 * max(I1, I2) else 0.0,
                J=J, K1=K1, K2=K2)


def principal(I1: float, I2: float, I12: float) -> tuple[float, float, float]:
    """Principal second moments and the angle (rad) from the section y axis to the first.

    Returns ``(I1p, I2p, alpha)`` with ``I1p`` about the axis nearest to the original
    plane-1 axis: the rotated section axes are ``y' = cos(a) y + sin(a) z``,
    ``z' = -sin(a) y + cos(a) z``.
    """
    if I12 == 0.0:
        return I1, I2, 0.0
    lam, V = np.linalg.eigh(np.array([[I1, I12], [I12, I2]]))
    k = int(np.argmax(np.abs(V[0])))                       # eigenvector nearest to y
    u = V[:, k] * np.sign(V[0, k])
    return float(lam[k]), float(lam[1 - k]), float(np.arctan2(u[1], u[0]))
