"""Abaqus history data: the ``*STEP`` keywords :func:`flexpipe.mesh.abaqus.read_abaqus`
reads (``*BOUNDARY``, ``*FREQUENCY``), and the set-up ``flexpipe modes`` takes from them.

The constraints in effect in the first ``*FREQUENCY`` step (the model data's, then the
steps' up to it, ``OP=NEW`` removing what came before) become the DOF set :data:`BC_SET`
held fixed, and that step's number of eigenvalues and frequency range the modes to
compute, as a Nastran deck's ``SPC =`` set and EIGRL.  A keyword close to one this reader
acts on is taken as a typo (:func:`near_miss`); other history data is listed as not used.
"""

from __future__ import annotations

import warnings

import numpy as np

from flexpipe.errors import MeshError
from flexpipe.mesh._abaqus_deck import _Deck
from flexpipe.mesh._bulk import parse_real
from flexpipe.mesh.validate import MeshWarning


def near_miss(kw, known, f, ln):
    """A keyword that is not read but close to one that is: taken as a typo (an error)."""
    import difflib

    close = difflib.get_close_matches(kw, known, n=1, cutoff=0.8)
    if close:
        raise MeshError(f"unknown keyword *{kw}: a misspelt *{close[0]}? (a keyword that is "
                        "not read could change the structure)", file=f, line=ln)



#: name of the DOF set of the deck's *BOUNDARY constraints: a Nastran SPC set's name, so
#: that ``flexpipe modes`` applies it and the .bdf writer writes it (SPC = 1, SPC1 cards)
BC_SET = "SPC1"
#: keywords read inside a step (the rest of a step is listed as not used)
STEP_KEYWORDS = ("STEP", "END STEP", "BOUNDARY", "FREQUENCY")


def _step_keyword(deck: _Deck, kw: str, p, lines, f, ln) -> None:
    """One keyword of history data: ``*BOUNDARY`` and ``*FREQUENCY`` are read."""
    if kw == "STEP":
        if deck.step is not None:
            raise MeshError(f"*STEP inside the step that starts at line {deck.step['line']}: "
                            "that step has no *END STEP", file=f, line=ln)
        deck.steps += 1
        if deck.bc_active is None:
            deck.bc_active = list(deck.bc_model)
        deck.step = {"new": False, "freq": None, "file": f, "line": ln}
        for _ in lines.data():              # the step's description line
            pass
    elif kw == "END STEP":
        _end_step(deck)
    elif kw == "BOUNDARY":
        rows, op_new = _boundary(deck, p, lines, f, ln)
        if op_new and not deck.step["new"]:  # OP=NEW: the step's first one removes all
            deck.bc_active, deck.step["new"] = [], True
        deck.bc_active += rows
    elif kw == "FREQUENCY":
        deck.step["freq"] = _frequency(p, list(lines.data()), f, ln)
    elif kw == "MODEL CHANGE":
        raise MeshError("*MODEL CHANGE is not supported (it removes or adds elements in a "
                        "step); write the deck with the elements of the frequency step only",
                        file=f, line=ln)
    else:
        near_miss(kw, STEP_KEYWORDS, f, ln)
        deck.dropped[kw] = deck.dropped.get(kw, 0) + 1
        deck.dropped_at.setdefault(kw, (f, ln))
        for _ in lines.data():
            pass


def _end_step(deck: _Deck) -> None:
    if deck.step is None:
        return
    step, deck.step = deck.step, None
    if deck.steps == 1:
        deck.bc_first = list(deck.bc_active)
    if step["freq"] is not None:            # the first frequency step: its set-up is used
        deck.bc_used, deck.frequency, deck.done = list(deck.bc_active), step["freq"], True


#: named *BOUNDARY types and the DOF they hold (Abaqus conventions)
BC_TYPES = {"ENCASTRE": "123456", "PINNED": "123", "XSYMM": "156", "YSYMM": "246",
            "ZSYMM": "345", "XASYMM": "234", "YASYMM": "135", "ZASYMM": "126"}
_BC_PARAMS = ("OP", "TYPE", "AMPLITUDE", "FIXED")


def _boundary(deck, p, lines, f, ln):
    """Rows ``(node id or node set key, dofs "123", file, line)`` of a ``*BOUNDARY``
    block, and whether it has ``OP=NEW``.  A non-zero value is held at zero with a
    warning: a natural-frequency analysis (as Abaqus's ``*FREQUENCY`` step) fixes the DOF."""
    bad = [k for k in p if k not in _BC_PARAMS]
    if bad:
        raise MeshError(f"*BOUNDARY parameter {bad[0]} is not supported; valid: OP=MOD|NEW, "
                        "TYPE=DISPLACEMENT, AMPLITUDE, FIXED", file=f, line=ln)
    op = p.get("OP", "MOD").upper()
    if op not in ("MOD", "NEW"):
        raise MeshError(f"*BOUNDARY OP={p['OP']}; valid: MOD, NEW", file=f, line=ln)
    kind = p.get("TYPE", "DISPLACEMENT").upper()
    if kind != "DISPLACEMENT":
        raise MeshError(f"*BOUNDARY TYPE={p['TYPE']} is not supported; valid: DISPLACEMENT "
                        "(zero displacements and rotations held fixed)", file=f, line=ln)
    ctx = deck.ctx()
    rows, nonzero = [], []
    for lf, lln, t in lines.data():
        tok = [x.strip() for x in t.split(",")]
        tok += [""] * (4 - len(tok))
        if not tok[0] or not tok[1]:
            raise MeshError("*BOUNDARY line needs 'node or node set, first DOF[, last DOF[, "
                            "value]]' or 'node or node set, type' (ENCASTRE, PINNED, XSYMM, ...)",
                            file=lf, line=lln)
        if not tok[1].isdigit():
            dofs = BC_TYPES.get(tok[1].upper())
            if dofs is None:
                raise MeshError(f"*BOUNDARY type '{tok[1]}' is not known; valid: a DOF number "
                                f"1..6 or {', '.join(BC_TYPES)}", file=lf, line=lln)
        else:
            first = int(tok[1])
            last = int(tok[2]) if tok[2].isdigit() else first
            if tok[2] and not tok[2].isdigit():
                raise MeshError(f"*BOUNDARY last DOF '{tok[2]}'; valid: an integer 1..6",
                                file=lf, line=lln)
            if not 1 <= first <= last <= 6:
                raise MeshError(f"*BOUNDARY DOF {first}..{last}; valid: first <= last within "
                                "1..6 (displacements 1-3, rotations 4-6)", file=lf, line=lln)
            dofs = "".join(str(d) for d in range(first, last + 1))
            if tok[3]:
                v = parse_real(tok[3])
                if v is None or not np.isfinite(v):
                    raise MeshError(f"*BOUNDARY value '{tok[3]}' is not a number", file=lf,
                                    line=lln)
                if v:
                    nonzero.append((lf, lln, tok[0], tok[3]))
        rows.append((deck.node_ref(tok[0], ctx), dofs, lf, lln))
    if nonzero:
        lf, lln, what, v = nonzero[0]
        warnings.warn(MeshWarning(
            f"{lf} line {lln}: *BOUNDARY prescribes non-zero values ({len(nonzero)} line(s), "
            f"e.g. {what} = {v}); the natural modes hold these DOF fixed (as a *FREQUENCY "
            "step does), the values are not used"), stacklevel=5)
    return rows, op == "NEW"


def _frequency(p, rows, f, ln):
    """``(n, f_min, f_max, file, line)`` of a ``*FREQUENCY`` step (None where blank)."""
    solver = p.get("EIGENSOLVER", "LANCZOS").upper()
    if solver not in ("LANCZOS", "AMS", "SUBSPACE"):
        raise MeshError(f"*FREQUENCY EIGENSOLVER={p['EIGENSOLVER']}; valid: LANCZOS, AMS, "
                        "SUBSPACE", file=f, line=ln)
    if not rows:
        raise MeshError("*FREQUENCY needs a data line (number of eigenvalues, frequency range)",
                        file=f, line=ln)
    lf, lln, t = rows[0]
    tok = [x.strip() for x in t.split(",")] + [""] * 3
    n = None
    if tok[0]:
        if not tok[0].isdigit() or int(tok[0]) < 1:
            raise MeshError(f"*FREQUENCY number of eigenvalues '{tok[0]}'; valid: an integer "
                            ">= 1 or blank", file=lf, line=lln)
        n = int(tok[0])
    fields = (None, tok[1]) if solver == "SUBSPACE" else (tok[1], tok[2])
    rng = []
    for what, s in zip(("minimum", "maximum"), fields, strict=True):
        v = parse_real(s) if s else None
        if s and (v is None or not np.isfinite(v) or v < 0):
            raise MeshError(f"*FREQUENCY {what} frequency '{s}'; valid: a frequency >= 0 "
                            "(cycles per time) or blank", file=lf, line=lln)
        rng.append(v)
    f_min, f_max = rng
    if n is None and f_max is None:
        raise MeshError("*FREQUENCY gives neither the number of eigenvalues nor a maximum "
                        "frequency", file=lf, line=lln)
    if f_min is not None and f_max is not None and f_min >= f_max:
        raise MeshError(f"*FREQUENCY range {f_min:g}..{f_max:g}; valid: minimum < maximum",
                        file=lf, line=lln)
    return n, f_min, f_max, lf, lln


def _solution(deck: _Deck, index):
    """``Mesh.dof_sets`` / ``Mesh.solution`` from ``*BOUNDARY`` and ``*FREQUENCY``: the
    constraints in effect in the first ``*FREQUENCY`` step (model data, then the steps up
    to it, ``OP=NEW`` removing what was before) - else at the end of the first step, else
    the model data's - as the DOF set :data:`BC_SET` that ``flexpipe modes`` holds fixed
    (``solution["spc"]``, as a Nastran ``SPC = 1``), and that step's number of
    eigenvalues and frequency range (``n_modes``, ``f_min``, ``f_max``, as an EIGRL)."""
    rows = deck.bc_used if deck.bc_used is not None else (
        deck.bc_first if deck.bc_first is not None else deck.bc_model)
    dof_sets, solution = {}, {}
    pairs = []
    for ref, dofs, f, ln in rows:
        ids = deck.nodes_of(ref, "*BOUNDARY", f, ln)
        idx = index(ids, lambda _, f=f, ln=ln: (f, ln), "*BOUNDARY")
        cc = np.array([int(ch) - 1 for ch in dofs])
        pairs.append(np.column_stack([np.repeat(idx, len(cc)), np.tile(cc, len(idx))]))
    if pairs:
        dof_sets[BC_SET] = np.unique(np.vstack(pairs), axis=0)
        solution["spc"] = BC_SET
    if deck.frequency is not None:
        n, f_min, f_max = deck.frequency[:3]
        solution.update({k: v for k, v in (("n_modes", n), ("f_min", f_min),
                                            ("f_max", f_max)) if v is not None})
    return dof_sets, solution


def warn_dropped(path, deck: _Deck, notes: dict, silent) -> None:
    """One warning naming the keywords not used for M and K (with what they would do, for
    those in ``notes``, and where the first is), leaving out the ``silent`` ones."""
    told = {k: n for k, n in deck.dropped.items() if k not in silent}
    if told:
        where = {k: f" (first at {f} line {ln})" for k, (f, ln) in deck.dropped_at.items()}
        warnings.warn(MeshWarning(
            f"{path}: keywords not used for M and K: "
            + ", ".join(f"*{k} x{n}" + (f" - {notes[k]}{where.get(k, '')}" if k in notes
                                        else "")
                        for k, n in told.items())), stacklevel=4)
