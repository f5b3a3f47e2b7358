"""Nastran materials and properties -> flexpipe section dictionaries.

``MAT1`` (``E, G, NU, RHO``; two of E, G, NU suffice), ``PSHELL`` (``T``, ``MID1``,
``MID2`` with ``12I/T^3``: bending rigidity scale ``12I/T^3 * E(MID2) / E(MID1)``,
blank MID2 = membrane only, ``NSM`` added as ``NSM / T`` to the density), ``PSOLID``,
``PBAR`` (``A, I1, I2, J, NSM``, ``K1, K2`` shear area factors - blank = no shear
flexibility - and ``I12``), ``PBEAM`` (end A; ``K1, K2`` default 1.0 as in Nastran),
``PBARL``/``PBEAML`` (standard shapes of :mod:`flexpipe.fem.sections`, end A),
``PROD`` / ``CONROD`` (``A, J``: axial + torsion only), ``PELAS``, ``PBUSH`` (``K``,
``B``; ``GE`` ignored).  A section with ``I12 != 0`` is turned to its principal axes
(``theta``).  ``PARAM, WTMASS`` multiplies every density, NSM and mass.  Shell material
orientation (``THETA`` angle or ``MCID`` system): :func:`shell_orientation`.
"""

from __future__ import annotations

import numpy as np

from flexpipe.fem.sections import N_DIMS, principal, standard_section
from flexpipe.mesh._bulk import Card

#: property card -> cell types it may be used by
KIND = {"PSHELL": ("triangle", "quad"), "PCOMP": ("triangle", "quad"),
        "PCOMPG": ("triangle", "quad"),
        "PSOLID": ("tetra", "tetra10", "hexahedron", "wedge", "pyramid"),
        "PBAR": ("line",), "PBEAM": ("line",), "PBARL": ("line",), "PBEAML": ("line",),
        "PROD": ("line",), "PELAS": ("spring", "spring1"), "PBUSH": ("spring", "spring1")}
PROPERTIES = tuple(KIND)
OTHER_MATERIALS = {"MAT2", "MAT8", "MAT9", "MAT3", "MATS1"}
#: largest accepted modulus / density magnitude in any unit system
_HUGE = 1e20


def material(card: Card, wtmass: float = 1.0) -> dict:
    """``E, nu, rho`` of a MAT1 card, range-checked (errors name file, line and MID)."""
    E = card.real(1, "E", None)
    G = card.real(2, "G", None)
    nu = card.real(3, "NU", None)
    rho = card.real(4, "RHO", None)
    if E is None and G is not None and nu is not None:
        E = 2.0 * (1.0 + nu) * G
    if nu is None and E is not None and G is not None and G != 0:
        nu = E / (2.0 * G) - 1.0
    if E is None or nu is None:
        raise card.error("needs E and NU (or two of E, G, NU)")
    if not (np.isfinite(E) and 0 < E < _HUGE):
        raise card.error(f"Young's modulus E = {E:g}; valid: 0 < E < {_HUGE:g} (file units)")
    if not (np.isfinite(nu) and -1.0 < nu < 0.5):
        raise card.error(f"Poisson's ratio NU = {nu:g}; valid: -1 < NU < 0.5")
    if rho is None:
        import warnings

        from flexpipe.mesh.validate import MeshWarning
        warnings.warn(MeshWarning(f"{card.file} line {card.line}: MAT1 {card.label()} has no "
                                  "RHO: its elements are massless"), stacklevel=5)
        rho = 0.0
    if not (np.isfinite(rho) and 0 <= rho < _HUGE):
        raise card.error(f"density RHO = {rho:g}; valid: 0 <= RHO < {_HUGE:g}")
    return {"E": E, "nu": nu, "rho": rho * wtmass}


def _positive(card: Card, values: dict, *, allow_zero=()):
    for name, v in values.items():
        ok = np.isfinite(v) and (v >= 0 if name in allow_zero else v > 0)
        if not ok:
            raise card.error(f"{name} = {v:g}; valid: a finite value "
                             f"{'>= 0' if name in allow_zero else '> 0'}")


def _beam(out: dict, A, I1, I2, I12, J, K1, K2, nsm, rho_mat):
    Ip1, Ip2, theta = principal(I1, I2, I12)
    out.update(A=A, Iz=Ip1, Iy=Ip2, J=J, k1=K1, k2=K2, theta=theta)
    if nsm and "rho" in out:
        out["rho"] = out["rho"] + nsm / A
    return out


def _tapered(card: Card) -> None:
    import warnings

    from flexpipe.mesh.validate import MeshWarning
    warnings.warn(MeshWarning(f"{card.file} line {card.line}: {card.name} {card.label()} is "
                              "tapered; flexpipe uses the mean of the end A and end B "
                              "section properties along each element"), stacklevel=5)


def _dims(card: Card, start: int, n: int) -> list[float]:
    return [card.real(start + k, f"DIM{k + 1}") for k in range(n)]


def section(card: Card, mats: dict, wtmass: float = 1.0) -> dict:
    """Section dictionary of property ``card`` (materials from ``mats``: MID -> Card)."""
    out: dict = {}
    name = card.name
    if name in ("PELAS", "PBUSH"):
        return out
    mid_field = {"PSHELL": 1, "PSOLID": 1, "PBAR": 1, "PBEAM": 1, "PBARL": 1, "PBEAML": 1,
                 "PROD": 1}[name]
    mid = card.int(mid_field, "MID", None)
    mid2 = card.int(3, "MID2", None) if name == "PSHELL" else None
    if name == "PSHELL" and mid is None:
        mid = mid2
    if mid is None:     # geometry only: the material comes from assemble(material=...)
        if name == "PSHELL" and card.raw(2):
            out["thickness"] = card.real(2, "T")
            _positive(card, {"T": out["thickness"]})
        return out
    mcard = mats.get(mid)
    if mcard is None:
        raise card.error(f"refers to material MID {mid}, which has no MAT1 card")
    if mcard.name != "MAT1":
        raise card.error(f"material {mid} is {mcard.name} (line {mcard.line}); only isotropic "
                         "MAT1 is supported")
    out.update(material(mcard, wtmass))
    if name == "PSHELL":
        if card.raw(10):
            raise card.error("MID4 (membrane-bending coupling) is not supported; leave it "
                             "blank or use a symmetric PCOMP")
        t = card.real(2, "T", None)
        if t is not None:
            _positive(card, {"T": t})
            out["thickness"] = t
        ratio = card.real(4, "12I/T**3", 1.0)
        if mid2 is None:
            out["bending"] = 0.0
        else:
            if mid2 not in mats or mats[mid2].name != "MAT1":
                raise card.error(f"MID2 = {mid2} has no MAT1 card")
            out["bending"] = ratio * material(mats[mid2])["E"] / out["E"]
        _positive(card, {"12I/T**3": ratio}, allow_zero=("12I/T**3",))
        nsm = card.real(7, "NSM", 0.0) * wtmass
        if nsm and t:
            out["rho"] += nsm / t
    elif name == "PBAR":
        A, I1, I2, J = (card.real(k, n, 0.0) for k, n in ((2, "A"), (3, "I1"), (4, "I2"),
                                                          (5, "J")))
        _positive(card, {"A": A, "I1": I1, "I2": I2, "J": J}, allow_zero=("I1", "I2", "J"))
        K1, K2 = card.real(16, "K1", 0.0), card.real(17, "K2", 0.0)
        I12 = card.real(18, "I12", 0.0)
        if I1 * I2 < I12**2:
            raise card.error(f"I1 I2 = {I1 * I2:g} < I12^2 = {I12**2:g}; valid: I1 I2 > I12^2")
        _positive(card, {"K1": K1, "K2": K2}, allow_zero=("K1", "K2"))
        _beam(out, A, I1, I2, I12, J, K1, K2, card.real(6, "NSM", 0.0) * wtmass, out["rho"])
    elif name == "PBEAM":
        A, I1, I2, I12, J = (card.real(k, n, 0.0) for k, n in
                             ((2, "A"), (3, "I1"), (4, "I2"), (5, "I12"), (6, "J")))
        _positive(card, {"A": A, "I1": I1, "I2": I2, "J": J}, allow_zero=("J",))
        k, last = 16, None
        while card.raw(k).upper() in ("YES", "YESA", "NO"):
            last = k
            k += 16
        if last is not None:    # end B (blank values: those of end A)
            B = [card.real(last + 2 + j, n, v) for j, (n, v) in enumerate(
                (("A", A), ("I1", I1), ("I2", I2), ("I12", I12), ("J", J)))]
            if not np.allclose(B, [A, I1, I2, I12, J], rtol=1e-9, atol=0):
                _tapered(card)
                A, I1, I2, I12, J = ((a + b) / 2 for a, b in zip((A, I1, I2, I12, J), B,
                                                                strict=True))
        K1, K2 = card.real(k, "K1", 1.0), card.real(k + 1, "K2", 1.0)
        _positive(card, {"K1": K1, "K2": K2}, allow_zero=("K1", "K2"))
        _beam(out, A, I1, I2, I12, J, K1, K2, card.real(7, "NSM", 0.0) * wtmass, out["rho"])
    elif name in ("PBARL", "PBEAML"):
        shape = card.raw(3).upper()
        if shape not in N_DIMS:
            raise card.error(f"section TYPE '{card.raw(3)}' is not supported; valid: "
                             f"{', '.join(N_DIMS)}")
        n = N_DIMS[shape]
        dims = _dims(card, 8, n)
        try:
            s = standard_section(shape, dims, out["nu"])
            k, last = 9 + n, None          # PBEAML stations: SO, X/XB, DIM1..n, NSM
            while name == "PBEAML" and card.raw(k).upper() in ("YES", "YESA", "NO"):
                last = k
                k += n + 3
            if last is not None:
                dims_b = [card.real(last + 2 + j, f"DIM{j + 1}(B)", dims[j])
                          for j in range(n)]
                if not np.allclose(dims_b, dims, rtol=1e-9, atol=0):
                    _tapered(card)
                    sb = standard_section(shape, dims_b, out["nu"])
                    s = {key: (s[key] + sb[key]) / 2 for key in s}
        except ValueError as exc:
            raise card.error(str(exc)) from None
        _beam(out, s["A"], s["I1"], s["I2"], s["I12"], s["J"], s["K1"], s["K2"],
              card.real(8 + n, "NSM", 0.0) * wtmass, out["rho"])
    elif name == "PROD":
        A, J = card.real(2, "A"), card.real(3, "J", 0.0)
        _positive(card, {"A": A, "J": J}, allow_zero=("J",))
        _beam(out, A, 0.0, 0.0, 0.0, J, 0.0, 0.0, card.real(5, "NSM", 0.0) * wtmass, out["rho"])
    return out


def conrod_section(card: Card, mats: dict, wtmass: float = 1.0) -> dict:
    """Section of a CONROD (EID G1 G2 MID A J C NSM): the PROD fields inline."""
    mid = card.int(3, "MID")
    mcard = mats.get(mid)
    if mcard is None or mcard.name != "MAT1":
        raise card.error(f"refers to material MID {mid}, which has no MAT1 card")
    out = material(mcard, wtmass)
    A, J = card.real(4, "A"), card.real(5, "J", 0.0)
    _positive(card, {"A": A, "J": J}, allow_zero=("J",))
    return _beam(out, A, 0.0, 0.0, 0.0, J, 0.0, 0.0, card.real(7, "NSM", 0.0) * wtmass, None)


def pelas(card: Card) -> dict:
    """PID -> stiffness of a PELAS card (two properties per card allowed)."""
    out = {}
    for base in (0, 4):
        if card.raw(base):
            k = card.real(base + 1, "K")
            if not np.isfinite(k):
                raise card.error(f"K = {k}; valid: a finite stiffness")
            out[card.int(base, "PID")] = k
    return out


def pbush(card: Card) -> dict:
    """``{"K": (6,), "B": (6,)}`` of a PBUSH card (flag lines K, B, GE, RCV, M)."""
    out = {"K": np.zeros(6), "B": np.zeros(6)}
    k = 1
    while k < len(card.fields):
        flag = card.raw(k).upper()
        if flag in ("K", "B"):
            vals = [card.real(k + 1 + j, f"{flag}{j + 1}", 0.0) for j in range(6)]
            if not all(np.isfinite(v) and v >= 0 for v in vals):
                raise card.error(f"{flag} values {vals}; valid: finite and >= 0")
            out[flag] = np.array(vals)
        elif flag not in ("GE", "RCV", "M", ""):
            raise card.error(f"unknown flag '{card.raw(k)}'; valid: K, B, GE, RCV, M")
        k += 8
    return out


def _ply_material(card: Card, mats: dict, mid: int):
    """``(Q, G_transverse, rho)`` of ply material ``mid`` (MAT8 or MAT1)."""
    from flexpipe.fem.laminate import ply_q

    m = mats.get(mid)
    if m is None:
        raise card.error(f"ply material MID {mid} has no MAT1 or MAT8 card")
    if m.name == "MAT1":
        p = material(m)
        G = p["E"] / (2 * (1 + p["nu"]))
        return ply_q(p["E"], p["E"], p["nu"], G), G, p["rho"]
    if m.name != "MAT8":
        raise card.error(f"ply material {mid} is {m.name}; valid: MAT1 or MAT8")
    E1, E2, nu12, G12 = (m.real(k, n) for k, n in ((1, "E1"), (2, "E2"), (3, "NU12"),
                                                   (4, "G12")))
    G1z = m.real(5, "G1Z", G12)
    rho = m.real(7, "RHO", 0.0)
    for n, v in (("E1", E1), ("E2", E2), ("G12", G12), ("G1Z", G1z)):
        if not (np.isfinite(v) and 0 < v < _HUGE):
            raise m.error(f"{n} = {v:g}; valid: 0 < {n} < {_HUGE:g}")
    if not (np.isfinite(rho) and 0 <= rho < _HUGE):
        raise m.error(f"RHO = {rho:g}; valid: >= 0")
    if not (np.isfinite(nu12) and nu12**2 * E2 / E1 < 1):
        raise m.error(f"NU12 = {nu12:g}; valid: NU12^2 E2 / E1 < 1")
    return ply_q(E1, E2, nu12, G12), G1z, rho


def composite(card: Card, mats: dict, wtmass: float = 1.0) -> dict:
    """Section of a PCOMP/PCOMPG: laminate rigidities by classical lamination.

    Keys ``A11 .. A66`` and ``D11 .. D66`` (upper triangles), ``Gt`` (transverse shear
    ``sum G1Z t``), ``thickness``, mean ``rho`` (with NSM) and, for the assembler's
    material check, an equivalent ``E``, ``nu``.  ``LAM = SYM`` mirrors the plies; an
    unsymmetric laminate (``B != 0``) or an offset ``Z0`` raises an error.
    """
    from flexpipe.fem.laminate import section as lam_section

    g = card.name == "PCOMPG"
    lam = card.raw(7).upper()
    if lam not in ("", "SYM"):
        raise card.error(f"LAM = {lam} is not supported; valid: blank or SYM")
    plies, k, last = [], 8, (None, None)
    while k < len(card.fields):
        off = k + (1 if g else 0)
        mid = card.int(off, "MID", last[0])
        t = card.real(off + 1, "T", last[1])
        theta = card.real(off + 2, "THETA", 0.0)
        if mid is None or t is None:
            raise card.error(f"ply {len(plies) + 1}: MID and T are needed (blank only after "
                             "a ply that gives them)")
        if not (np.isfinite(t) and t > 0) or not np.isfinite(theta):
            raise card.error(f"ply {len(plies) + 1}: T = {t:g}, THETA = {theta:g}; valid: "
                             "T > 0, THETA finite")
        plies.append((mid, t, theta))
        last = (mid, t)
        k += 8 if g else 4
    if not plies:
        raise card.error("has no plies")
    if lam == "SYM":
        plies = plies + plies[::-1]
    mat = {mid: _ply_material(card, mats, mid) for mid in {p[0] for p in plies}}
    T = sum(p[1] for p in plies)
    z0 = card.real(1, "Z0", -T / 2)
    if abs(z0 + T / 2) > 1e-9 * T:
        raise card.error(f"Z0 = {z0:g} offsets the laminate (Z0 != -T/2 = {-T / 2:g}); "
                         "give the offset as ZOFFS on the elements instead")
    try:
        out = lam_section([(mat[m][0], t, th, mat[m][1], mat[m][2]) for m, t, th in plies],
                          card.real(2, "NSM", 0.0))
    except ValueError as exc:
        raise card.error(str(exc)) from None
    out["rho"] *= wtmass
    return out


def shell_orientation(theta, conn, X, systems, user_of):
    """Material orientation of shells: THETA (degrees from the element x axis) or MCID
    (x axis of that coordinate system, projected onto the element)."""
    n = len(theta)
    ang = np.zeros(n)
    ref = np.full((n, 3), np.nan)
    for j in np.flatnonzero(np.array([bool(t) for t in theta])):
        s = theta[j]
        if s.lstrip("+-").isdigit():
            c = user_of(int(j))
            ref[j] = systems.frames(int(s), X[conn[j]].mean(axis=0)[None], c)[0][:, 0]
        else:
            from flexpipe.mesh._bulk import parse_real

            v = parse_real(s)
            if v is None or not np.isfinite(v):
                raise user_of(int(j)).error(f"THETA = '{s}' is not a number (or MCID id)")
            ang[j] = np.radians(v)
    return ang, ref
