"""Card bookkeeping of the Nastran reader (:mod:`flexpipe.mesh.nastran`): which cards
are read, dropped or refused, the :class:`Deck` that sorts them by kind (duplicate ids are
errors), and the whole-deck checks - a deck with no element, elements whose property card
is missing, the materials (MAT1/MAT8) the model uses (for :mod:`flexpipe.mesh.units`'
plausibility check of E / RHO)."""

from __future__ import annotations

import difflib
import warnings
from collections import Counter, defaultdict
from collections.abc import Mapping
from pathlib import Path

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.mesh import _nastran_props as nprops
from flexpipe.mesh._bulk import Card, FastLines
from flexpipe.mesh._nastran_coords import KINDS as CORD_CARDS
from flexpipe.mesh._nastran_elements import ELEMENTS
from flexpipe.mesh.validate import MeshWarning

SUPPORTED = tuple(ELEMENTS) + ("CELAS1", "CELAS2", "CBUSH", "CONM1", "CONM2", "RBE2", "RBE3",
                               "RBAR")
UNSUPPORTED_ELEMENTS = {
    "CQUADR", "CTRIAR", "CQUAD", "CTRIAX", "CTRIAX6", "CQUADX", "CTUBE", "CELAS3", "CELAS4",
    "CBUSH1D", "CBUSH2D", "CBEND", "CSHEAR", "CGAP", "CWELD", "CFAST", "CSEAM", "CDAMP1",
    "CDAMP2", "CVISC", "CMASS1", "CMASS2", "RBE1", "RBAR1", "RROD", "RTRPLT", "RSPLINE",
    "MPC", "GENEL", "DMIG", "CBEAM3", "CSPOT", "GRDSET", "CONM3",
}
UNSUPPORTED_PROPERTIES = {"PSHEAR", "PGAP", "PWELD", "PFAST", "PBEAM3",
                          "PBUSH1D", "PCOMPLS", "PLPLANE"}
#: cards that do not change M or K (loads, output, other solutions): listed as ignored
NOT_STRUCTURAL = {
    "FORCE", "FORCE1", "FORCE2", "MOMENT", "MOMENT1", "MOMENT2", "PLOAD", "PLOAD1", "PLOAD2",
    "PLOAD4", "GRAV", "LOAD", "TEMP", "TEMPD", "DLOAD", "RLOAD1", "RLOAD2", "TLOAD1",
    "TLOAD2", "FREQ", "FREQ1", "FREQ2", "TSTEP", "EIGR", "EIGRL", "DAREA", "TABDMP1",
    "TABLED1", "TABLED2", "TABLEM1", "PLOTEL", "ASET", "ASET1", "QSET1", "BSET1", "CSET1",
    "SUPORT", "SUPORT1", "SPOINT", "NLPARM", "DESVAR", "DRESP1", "DCONSTR", "MAT4",
    "PARAM", "SPC", "SPC1", "SPCADD", "SPCD", "MPCADD", "ENDDATA", "DTI", "MDLPRM",
    "PBUSHT", "PELAST",
}
_KNOWN = set(ELEMENTS) | set(SUPPORTED) | UNSUPPORTED_ELEMENTS | UNSUPPORTED_PROPERTIES | \
    set(nprops.PROPERTIES) | {"MAT1", "GRID", "SET1"} | nprops.OTHER_MATERIALS | set(CORD_CARDS)
#: names a misspelling is checked against (element, property, material, grid cards)
_SPELLED = sorted(set(SUPPORTED) | set(nprops.PROPERTIES) | {"MAT1", "GRID", "MAT8"})


class Deck:
    """Cards sorted by kind, with duplicate-id checks per kind."""

    def __init__(self):
        self.grids: list[Card] = []
        self.elements: dict = defaultdict(list)      # card name -> cards
        self.props: dict[int, Card] = {}
        self.mats: dict[int, Card] = {}
        self.coords: dict[int, Card] = {}
        self.eigrl: dict[int, Card] = {}
        self.spc: dict = defaultdict(list)
        self.params: dict[str, Card] = {}
        self.sets: dict[int, Card] = {}
        self.dropped: Counter = Counter()
        self.first: dict[str, Card] = {}

    @staticmethod
    def unique(table: dict, key: int, card: Card, what: str):
        old = table.get(key)
        if old is not None:
            raise MeshError(
                f"{what} id {key} is defined twice: {old.name} at {Path(old.file).name} line "
                f"{old.line} and {card.name} at {Path(card.file).name} line {card.line}; ids "
                "must be unique", file=card.file, line=card.line)
        table[key] = card

    def add(self, c: Card) -> None:
        n = c.name
        if n == "GRID":
            self.grids.append(c)
        elif n in ELEMENTS or n in SUPPORTED:
            self.elements[n].append(c)
        elif n in nprops.PROPERTIES or n in UNSUPPORTED_PROPERTIES:
            self.unique(self.props, c.int(0, "PID"), c, "property")
            if n == "PELAS" and c.raw(4):
                self.unique(self.props, c.int(4, "PID2"), c, "property")
        elif n == "MAT1" or n in nprops.OTHER_MATERIALS:
            self.unique(self.mats, c.int(0, "MID"), c, "material")
        elif n in CORD_CARDS:
            self.unique(self.coords, c.int(0, "CID"), c, "coordinate system")
        elif n == "EIGRL":
            self.unique(self.eigrl, c.int(0, "SID"), c, "EIGRL")
        elif n in ("SPC", "SPC1", "SPCADD"):
            self.spc[n].append(c)
        elif n == "SET1":
            self.unique(self.sets, c.int(0, "SID"), c, "SET1")
        elif n == "PARAM":
            self.params[c.raw(0).upper()] = c
        elif n in UNSUPPORTED_ELEMENTS:
            raise c.error(f"{n} is not supported; supported element cards: "
                          f"{', '.join(SUPPORTED)}. Remove or convert it")
        else:
            if n not in NOT_STRUCTURAL and n not in _KNOWN:
                close = difflib.get_close_matches(n, _SPELLED, n=1, cutoff=0.7)
                if close:
                    raise c.error(f"unknown card '{n}': a misspelt {close[0]}? (an element "
                                  "or property card that is not read would change the "
                                  "structure)")
            self.dropped[n] += 1
            self.first.setdefault(n, c)


def check_unique(ids: np.ndarray, cards: list[Card], what: str) -> None:
    order = np.argsort(ids, kind="stable")
    s = ids[order]
    dup = np.flatnonzero(s[1:] == s[:-1])
    if dup.size:
        a, b = cards[order[dup[0]]], cards[order[dup[0] + 1]]
        raise MeshError(
            f"{what} id {int(s[dup[0]])} is defined twice: {a.name} at {Path(a.file).name} "
            f"line {a.line} and {b.name} at {Path(b.file).name} line {b.line}; ids must be "
            "unique", file=b.file, line=b.line)


#: element cards that give stiffness (a deck needs at least one)
STRUCTURAL = tuple(ELEMENTS) + ("CELAS1", "CELAS2", "CBUSH")


def require_elements(deck: Deck, fast: FastLines, cards: list[Card], path) -> None:
    """A :class:`MeshError` naming the file, the last card and its line when the deck has
    no element card (an empty or cut-short deck: nothing to assemble)."""
    if any(deck.elements.get(n) for n in STRUCTURAL) or fast.lines["CQUAD4"] \
            or fast.lines["CTRIA3"]:
        return
    last = max([(c.seq, c) for c in cards[-1:]]
               + [(w[-1][2], fast.card(n, len(w) - 1)) for n, w in fast.where.items() if w],
               key=lambda t: t[0])[1]
    n_grid = len(deck.grids) + len(fast.lines["GRID"])
    raise MeshError(
        f"no element card: the deck has {n_grid} GRID(s) but no {', '.join(STRUCTURAL)}; "
        f"its last card is {last.name}" + (f" {last.label()}" if last.fields else "")
        + f" (line {last.line}) - is the file cut short?", file=str(last.file or path),
        line=last.line)


def missing_property(pid: int, user: Card, cell_type: str, props: dict) -> dict:
    """Warn that element ``user`` refers to property ``pid``, which no card defines, and
    return the note (``"text"``) that the model-building error repeats (see
    :func:`flexpipe.mesh.validate.missing_property_note`)."""
    want = [n for n, kinds in nprops.KIND.items() if cell_type in kinds]
    have = sorted(k for k, c in props.items() if cell_type in nprops.KIND.get(c.name, ()))
    want = ", ".join(want[:-1]) + " or " + want[-1] if len(want) > 1 else want[0]
    text = (f"element {user.label()} ({user.name}, {Path(user.file).name} line {user.line}) "
            f"refers to PID {pid}, which has no property card (expected a {want} card with "
            f"PID {pid}; " + (f"{cell_type} property ids defined: {', '.join(map(str, have))})"
                              if have else f"no {cell_type} property is defined)"))
    warnings.warn(MeshWarning(f"{user.file}: {text}; its elements get no section or "
                              "material"), stacklevel=4)
    return {"text": text, "element": int(user.int(0, "EID")), "line": user.line}


class Looked(Mapping):
    """Read-only view of ``table`` that records the keys looked up (the cards in use)."""

    def __init__(self, table: Mapping):
        self.table, self.used = table, set()

    def __getitem__(self, key):
        value = self.table[key]
        self.used.add(key)
        return value

    def __iter__(self):
        return iter(self.table)

    def __len__(self):
        return len(self.table)


def material_records(mats: Looked) -> dict:
    """``{"MAT1 <mid>": (E, RHO, file, line)}`` of the MAT1/MAT8 cards the model uses
    (MAT8: E1), file units, for the E / RHO plausibility check
    (:func:`flexpipe.mesh.units.check_wave_speeds`)."""
    out = {}
    for mid in sorted(mats.used):
        c = mats.table[mid]
        if c.name == "MAT8":
            E, rho = c.real(1, "E1", None), c.real(7, "RHO", None)
        elif c.name == "MAT1":
            E, G, nu, rho = (c.real(k, n, None) for k, n in ((1, "E"), (2, "G"), (3, "NU"),
                                                             (4, "RHO")))
            if E is None and G is not None and nu is not None:
                E = 2.0 * (1.0 + nu) * G
        else:
            continue
        if E and rho:
            out[f"{c.name} {mid}"] = (float(E), float(rho), c.file, c.line)
    return out
