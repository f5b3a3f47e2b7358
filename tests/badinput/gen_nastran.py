"""Bad (and tolerated) Nastran decks, generated from one valid SOL 103 body deck.

``cases()`` yields ``(case_id, filename, content, expect)``: ``expect == "error"`` means
reading (:func:`flexpipe.read_mesh`) and assembling must raise a
:class:`~flexpipe.errors.FlexpipeError` whose message names the file; ``"ok"`` means the
deck must load and assemble (warnings allowed).
"""

from __future__ import annotations

HEAD = ["SOL 103", "CEND", "SPC = 1", "METHOD = 2", "BEGIN BULK"]
BULK = [
    "PARAM,WTMASS,1.0",
    "MAT1,1,2.1+11,,0.3,7850.",
    "PSOLID,1,1",
    "PSHELL,2,1,0.01,1",
    "PBARL,3,1,,ROD",
    ",0.05",
    "PBUSH,41,K,1.+6,1.+6,1.+6,1.+3,1.+3,1.+3",
    "CORD2R,7,,0.,0.,0.,0.,0.,1.,+",
    "+,1.,0.,0.",
    "GRID,1,,0.,0.,0.",
    "GRID,2,,1.,0.,0.",
    "GRID,3,,1.,1.,0.",
    "GRID,4,,0.,1.,0.",
    "GRID,5,,0.,0.,1.",
    "GRID,6,,1.,0.,1.",
    "GRID,7,,1.,1.,1.",
    "GRID,8,,0.,1.,1.",
    "GRID,9,,2.,0.,0.",
    "GRID,10,,2.,0.,1.",
    "GRID,11,7,0.,1.,2.",
    "GRID,12,,3.,0.,0.",
    "GRID,13,,0.5,0.5,-0.5",
    "GRID,14,,0.5,0.5,1.5",
    "CHEXA,1,1,1,2,3,4,5,6,+",
    "+,7,8",
    "CPENTA,2,1,2,9,3,6,10,7",
    "CQUAD4,3,2,5,6,7,8",
    "CBAR,4,3,8,11,1.,0.,0.",
    "CBUSH,40,41,9,12,0.,0.,1.",
    "CONM2,50,11,,2.0",
    "CONM2,51,12,,3.0",
    "CONM2,52,14,,1.0",
    "RBE2,60,13,123,1,2,3,4",
    "RBE3,61,,14,123456,1.0,123,5,6,7,8",
    "SPC1,1,123456,13",
    "EIGRL,2,,,6",
]
TAIL = ["ENDDATA"]


def _deck(bulk, head=HEAD) -> bytes:
    return ("\n".join(list(head) + list(bulk) + TAIL) + "\n").encode()


def _replace(prefix: str, new: str | None, bulk=BULK) -> list[str]:
    """``bulk`` with the first line starting with ``prefix`` replaced (None: deleted)."""
    out, done = [], False
    for ln in bulk:
        if not done and ln.startswith(prefix):
            done = True
            if new is not None:
                out.append(new)
            continue
        out.append(ln)
    if not done:
        raise KeyError(prefix)
    return out


def cases():
    """Yield ``(case_id, filename, content, expect)``."""
    yield "base", "base.bdf", _deck(BULK), "ok"
    text = _deck(BULK)
    # ---- truncations inside element and property cards (the rest of the deck lost)
    for k, prefix in enumerate(("CHEXA,1", "CPENTA", "CQUAD4", "CBAR", "CBUSH", "RBE3",
                                "PBARL", "MAT1", "CONM2,50", "SPC1")):
        i = next(j for j, ln in enumerate(BULK) if ln.startswith(prefix))
        cut = BULK[i][:BULK[i].index(",", len(prefix) - 1 if "," in prefix else len(prefix))
                      + 2]
        yield f"truncate_{k}_{prefix.split(',')[0]}", f"trunc{k}.bdf", _deck(
            BULK[:i] + [cut]), "error"
    for k, frac in enumerate((0.05, 0.2, 0.5)):
        yield f"truncate_bytes_{k}", f"cut{k}.bdf", text[:int(len(text) * frac)], "error"
    yield "empty", "empty.bdf", b"", "error"
    yield "only_head", "head.bdf", _deck([]), "error"
    # ---- garbage
    yield "binary", "binary.bdf", bytes(range(256)) * 8, "error"
    yield "nul_in_text", "nul.bdf", text[:200] + b"\x00\x00" + text[200:], "error"
    yield "random_text", "words.bdf", b"hello world\nthis is not a deck\n" * 20, "error"
    yield "utf16", "utf16.bdf", "\n".join(HEAD + BULK + TAIL).encode("utf-16"), "error"
    # ---- non-finite numbers
    for name, prefix, new in (
            ("nan_grid", "GRID,2,", "GRID,2,,nan,0.,0."),
            ("inf_grid", "GRID,3,", "GRID,3,,1.,inf,0."),
            ("nan_E", "MAT1", "MAT1,1,nan,,0.3,7850."),
            ("inf_rho", "MAT1", "MAT1,1,2.1+11,,0.3,inf"),
            ("nan_nu", "MAT1", "MAT1,1,2.1+11,,nan,7850."),
            ("nan_thickness", "PSHELL", "PSHELL,2,1,nan,1"),
            ("inf_thickness", "PSHELL", "PSHELL,2,1,inf,1"),
            ("nan_pbarl", ",0.05", ",nan"),
            ("nan_mass", "CONM2,50", "CONM2,50,11,,nan"),
            ("inf_bush", "PBUSH", "PBUSH,41,K,inf,1.,1.,1.,1.,1."),
            ("nan_rbe3_weight", "RBE3", "RBE3,61,,14,123456,nan,123,5,6,7,8"),
            ("nan_cord", "+,1.,0.,0.", "+,nan,0.,0.")):
        yield name, f"{name}.bdf", _deck(_replace(prefix, new)), "error"
    # ---- zero or negative physical values
    for name, prefix, new in (
            ("E_zero", "MAT1", "MAT1,1,0.,,0.3,7850."),
            ("E_negative", "MAT1", "MAT1,1,-2.1+11,,0.3,7850."),
            ("E_huge", "MAT1", "MAT1,1,1.+300,,0.3,7850."),
            ("nu_half", "MAT1", "MAT1,1,2.1+11,,0.5,7850."),
            ("nu_below_minus_one", "MAT1", "MAT1,1,2.1+11,,-1.5,7850."),
            ("rho_negative", "MAT1", "MAT1,1,2.1+11,,0.3,-7850."),
            ("E_and_nu_missing", "MAT1", "MAT1,1,,,,7850."),
            ("thickness_zero", "PSHELL", "PSHELL,2,1,0.,1"),
            ("thickness_negative", "PSHELL", "PSHELL,2,1,-0.01,1"),
            ("rod_radius_zero", ",0.05", ",0."),
            ("rod_radius_negative", ",0.05", ",-0.05"),
            ("pbarl_unknown_shape", "PBARL", "PBARL,3,1,,ZED"),
            ("pbar_negative_area", "PBARL", "PBAR,3,1,-1.-4,1.-8,1.-8,2.-8"),
            ("pbar_zero_area", "PBARL", "PBAR,3,1,0.,1.-8,1.-8,2.-8"),
            ("pbar_i12_too_big", "PBARL", "PBAR,3,1,1.-4,1.-8,1.-8,2.-8,,,+"),
            ("mass_negative", "CONM2,50", "CONM2,50,11,,-2.0"),
            ("bush_negative", "PBUSH", "PBUSH,41,K,-1.+6,1.,1.,1.,1.,1."),
            ("rbe3_weight_zero", "RBE3", "RBE3,61,,14,123456,0.,123,5,6,7,8"),
            ("wtmass_zero", "PARAM,WTMASS", "PARAM,WTMASS,0."),
            ("eigrl_nd_zero", "EIGRL", "EIGRL,2,,,0"),
            ("eigrl_range_inverted", "EIGRL", "EIGRL,2,100.,10.")):
        bulk = _replace(prefix, new)
        if name == "pbarl_unknown_shape":
            bulk = _replace(",0.05", ",1.,2.", bulk)
        if name.startswith("pbar_"):
            bulk = _replace(",0.05", None, bulk)
            if name == "pbar_i12_too_big":
                bulk = _replace("PBAR,", "PBAR,3,1,1.-4,1.-8,1.-8,2.-8", bulk)
                i = bulk.index("PBAR,3,1,1.-4,1.-8,1.-8,2.-8")
                bulk[i + 1:i + 1] = [",,,,,,,,", ",,,5.-8"]
        yield name, f"{name}.bdf", _deck(bulk), "error"
    # ---- inverted and degenerate elements
    for name, prefix, new in (
            ("hex_inverted", "CHEXA", "CHEXA,1,1,5,6,7,8,1,2,+\n+,3,4"),
            ("wedge_inverted", "CPENTA", "CPENTA,2,1,6,10,7,2,9,3"),
            ("hex_repeated_node", "CHEXA", "CHEXA,1,1,1,2,3,3,5,6,+"),
            ("quad_repeated_node", "CQUAD4", "CQUAD4,3,2,5,6,6,8"),
            ("bar_zero_length", "CBAR", "CBAR,4,3,8,8,1.,0.,0."),
            ("bar_orientation_parallel", "CBAR", "CBAR,4,3,8,11,0.,0.,1."),
            ("bush_no_orientation", "CBUSH", "CBUSH,40,41,9,12"),
            ("hex_corner_blank", "CHEXA", "CHEXA,1,1,1,2,3,,5,6,+"),
            ("penta_corner_zero", "CPENTA", "CPENTA,2,1,2,9,3,6,0,7,+")):
        bulk = [x for ln in _replace(prefix, new) for x in ln.split("\n")]
        if name == "hex_inverted":
            bulk = _replace("+,7,8", None, bulk)
        if name == "hex_corner_blank":
            bulk = _replace("+,7,8", "+,7,8,9,10,11,12", bulk)
        if name == "penta_corner_zero":
            i = bulk.index("CPENTA,2,1,2,9,3,6,0,7,+")
            bulk.insert(i + 1, "+,11,12,13,14,1,4,5,8,+")
            bulk.insert(i + 2, "+,10")
        yield name, f"{name}.bdf", _deck(bulk), "error"
    # ---- duplicate ids
    for name, extra in (("dup_grid", "GRID,5,,0.,0.,3."), ("dup_element", "CQUAD4,1,2,5,6,7,8"),
                        ("dup_mat1", "MAT1,1,7.+10,,0.3,2700."), ("dup_psolid", "PSOLID,1,1"),
                        ("dup_pshell_vs_psolid", "PSHELL,1,1,0.01,1"),
                        ("dup_cord", "CORD2R,7,,0.,0.,0.,0.,0.,1.,+\n+,0.,1.,0."),
                        ("dup_eigrl", "EIGRL,2,,,8"), ("dup_conm2_vs_rbe", "CONM2,60,12,,1.0")):
        yield name, f"{name}.bdf", _deck(BULK + extra.split("\n")), "error"
    # ---- dangling references
    for name, prefix, new in (
            ("undefined_grid", "CQUAD4", "CQUAD4,3,2,5,6,7,99"),
            ("undefined_property", "CQUAD4", "CQUAD4,3,9,5,6,7,8"),
            ("undefined_material", "PSHELL", "PSHELL,2,9,0.01,9"),
            ("undefined_cord", "GRID,11,", "GRID,11,8,0.,1.,2."),
            ("undefined_pbush", "CBUSH", "CBUSH,40,42,9,12,0.,0.,1."),
            ("undefined_rbe3_ref", "RBE3", "RBE3,61,,99,123456,1.0,123,5,6,7,8"),
            ("undefined_rbe2_slave", "RBE2", "RBE2,60,13,123,1,2,3,99"),
            ("undefined_conm2_grid", "CONM2,51", "CONM2,51,99,,3.0"),
            ("undefined_spc_grid", "SPC1", "SPC1,1,123456,99"),
            ("wrong_property_kind", "CQUAD4", "CQUAD4,3,1,5,6,7,8"),
            ("rbe3_um", "RBE3", "RBE3,61,,14,123456,1.0,123,5,6,7,8,+\n+,UM,5,1"),
            ("rbe3_ref_is_independent", "RBE3", "RBE3,61,,14,123456,1.0,123,5,6,7,14"),
            ("rbe3_bad_components", "RBE3", "RBE3,61,,14,123789,1.0,123,5,6,7,8"),
            ("rbe3_collinear_rotation", "RBE3", "RBE3,61,,14,123456,1.0,123,5,6"),
            ("bar_pin_flag_digit_7", "CBAR", "CBAR,4,3,8,11,1.,0.,0.,,+\n+,457"),
            ("rbar_unusual", "RBE2", "RBAR,60,13,1,123,123")):
        bulk = [x for ln in _replace(prefix, new) for x in ln.split("\n")]
        yield name, f"{name}.bdf", _deck(bulk), "error"
    yield ("case_spc_undefined", "spc9.bdf",
           _deck(BULK, ["SOL 103", "CEND", "SPC = 9", "METHOD = 2", "BEGIN BULK"]), "error")
    yield ("case_method_undefined", "method9.bdf",
           _deck(BULK, ["SOL 103", "CEND", "SPC = 1", "METHOD = 9", "BEGIN BULK"]), "error")
    yield "spcadd_undefined", "spcadd.bdf", _deck(BULK + ["SPCADD,5,1,8"]), "error"
    # ---- unknown, misspelt, unsupported cards
    for name, extra, expect in (
            ("unknown_card", "FOOBAR,1,2,3", "ok"), ("load_cards", "FORCE,1,12,,1.,1.,0.,0.",
                                                     "ok"),
            ("typo_cquad4", "CQAUD4,70,2,5,6,7,8", "error"),
            ("typo_chexa", "CHEXX,71,1,1,2,3,4,5,6", "error"),
            ("typo_pshell", "PSHEL,72,1,0.01,1", "error"),
            ("typo_grid", "GIRD,73,,0.,0.,0.", "error"),
            ("unsupported_cgap", "CGAP,74,1,1,2", "error"),
            ("unsymmetric_pcomp", "PCOMP,2,,,,,,,,+\n+,8,0.005,0.,,8,0.005,90.\n"
             "MAT8,8,140.+9,10.+9,0.3,5.+9,,,1600.", "error"),
            ("symmetric_pcomp", "PCOMP,2,,,,,,,SYM,+\n+,8,0.005,0.,,8,0.005,90.\n"
             "MAT8,8,140.+9,10.+9,0.3,5.+9,,,1600.", "ok"),
            ("pcomp_with_element_theta", "PCOMP,2,,,,,,,SYM,+\n+,8,0.005,0.\n"
             "MAT8,8,140.+9,10.+9,0.3,5.+9,,,1600.\nCQUAD4,90,2,5,6,7,8,30.", "ok"),
            ("pcomp_element_theta_text", "PCOMP,2,,,,,,,SYM,+\n+,8,0.005,0.\n"
             "MAT8,8,140.+9,10.+9,0.3,5.+9,,,1600.\nCQUAD4,90,2,5,6,7,8,abc", "error"),
            ("pcomp_element_mcid_undefined", "PCOMP,2,,,,,,,SYM,+\n+,8,0.005,0.\n"
             "MAT8,8,140.+9,10.+9,0.3,5.+9,,,1600.\nCQUAD4,90,2,5,6,7,8,77", "error"),
            ("pcomp_ply_material_missing", "PCOMP,2,,,,,,,SYM,+\n+,9,0.005,0.", "error"),
            ("mat8_negative_e2", "PCOMP,2,,,,,,,SYM,+\n+,8,0.005,0.\n"
             "MAT8,8,140.+9,-10.+9,0.3,5.+9,,,1600.", "error"),
            ("unsupported_cquadr", "CQUADR,75,2,5,6,7,8", "error"),
            ("unsupported_mpc", "MPC,1,1,1,1.,2,1,-1.", "error")):
        bulk = BULK + extra.split("\n")
        if "pcomp" in name or "mat8" in name:
            bulk = _replace("PSHELL", None, bulk)
        yield name, f"{name}.bdf", _deck(bulk), expect
    # ---- typos in fields
    for name, prefix, new in (
            ("letter_in_coordinate", "GRID,2,", "GRID,2,,1.O,0.,0."),
            ("real_element_id", "CQUAD4", "CQUAD4,3.5,2,5,6,7,8"),
            ("text_node_id", "CQUAD4", "CQUAD4,3,2,5,6,7,eight"),
            ("bad_component", "SPC1", "SPC1,1,1237,13"),
            ("bad_pbush_flag", "PBUSH", "PBUSH,41,X,1.,1.,1.,1.,1.,1."),
            ("blank_grid_id", "GRID,4,", "GRID,,,0.,1.,0."),
            ("thru_inverted", "RBE2", "RBE2,60,13,123,4,THRU,1")):
        yield name, f"{name}.bdf", _deck(_replace(prefix, new)), "error"
    # ---- tolerated input: loads and still equal structures
    yield "bar_pin_flags", "pins.bdf", _deck([x for ln in _replace(
        "CBAR", "CBAR,4,3,8,11,1.,0.,0.,,+\n+,456") for x in ln.split("\n")]), "ok"
    yield "unreferenced_grid", "orphan.bdf", _deck(BULK + ["GRID,99,,9.,9.,9."]), "ok"
    yield "comments_and_blank", "comments.bdf", _deck(
        [x for ln in BULK for x in ("$ comment", ln, "")]), "ok"
    yield "tabs", "tabs.bdf", _deck([ln.replace("GRID,1,", "GRID,1,") for ln in BULK]), "ok"
    yield "no_case_control", "bulkonly.bdf", _deck(BULK, ["BEGIN BULK"]), "ok"
    yield "wtmass", "wtmass.bdf", _deck(_replace("PARAM,WTMASS", "PARAM,WTMASS,0.00259")), "ok"
    yield "coupmass", "coupmass.bdf", _deck(BULK + ["PARAM,COUPMASS,1"]), "ok"
    yield "cquad8", "cquad8.bdf", _deck(_replace("CQUAD4", "CQUAD8,3,2,5,6,7,8,15,16,+\n"
                                                 "+,17,18") + [
        "GRID,15,,0.5,0.,1.", "GRID,16,,1.,0.5,1.", "GRID,17,,0.5,1.,1.",
        "GRID,18,,0.,0.5,1."]), "ok"
    yield "cylindrical_cd", "cyl.bdf", _deck(BULK + [
        "CORD2C,8,,0.,0.,0.,0.,0.,1.,+", "+,1.,0.,0.", "GRID,20,8,1.,30.,0.,8",
        "CELAS2,80,1000.,20,1,12,2", "CONM2,81,20,,1.0"]), "ok"
    yield "large_field", "large.bdf", _deck(_replace("GRID,2,", "GRID*,2,,1.,0.,+\n*,0.")), "ok"
