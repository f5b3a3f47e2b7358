"""Bad (and tolerated) Abaqus decks, generated from one valid body deck.

``cases()`` yields ``(case_id, filename, content, expect)``: ``expect == "error"`` means
reading (:func:`flexpipe.read_mesh`) and assembling must raise a
:class:`~flexpipe.errors.FlexpipeError` whose message names the file; ``"ok"`` means the
deck must load and assemble (warnings allowed).
"""

from __future__ import annotations

NODES = ["1, 0., 0., 0.", "2, 1., 0., 0.", "3, 1., 1., 0.", "4, 0., 1., 0.",
         "5, 0., 0., 1.", "6, 1., 0., 1.", "7, 1., 1., 1.", "8, 0., 1., 1.",
         "9, 2., 0., 0.", "10, 2., 0., 1.", "11, 0., 1., 2.", "12, 3., 0., 0.",
         "13, 0.5, 0.5, -0.5", "14, 0.5, 0.5, 1.5", "15, 3., 0., 0."]
BASE = ["*HEADING", "flexpipe bad-input base deck", "*NODE", *NODES,
        "*ELEMENT, TYPE=C3D8, ELSET=SOLID", "1, 1, 2, 3, 4, 5, 6, 7, 8",
        "*ELEMENT, TYPE=C3D6, ELSET=SOLID", "2, 2, 9, 3, 6, 10, 7",
        "*ELEMENT, TYPE=S4, ELSET=SHELL", "3, 5, 6, 7, 8",
        "*ELEMENT, TYPE=B31, ELSET=BEAM", "4, 8, 11",
        "*ELEMENT, TYPE=SPRING2, ELSET=SPR", "5, 9, 12",
        "*ELEMENT, TYPE=MASS, ELSET=M1", "6, 11",
        "*ELEMENT, TYPE=MASS, ELSET=M2", "7, 12",
        "*ELEMENT, TYPE=MASS, ELSET=M3", "8, 14",
        "*ELEMENT, TYPE=CONN3D2, ELSET=CONN", "9, 12, 15",
        "*ELEMENT, TYPE=MASS, ELSET=M4", "10, 15",
        "*NSET, NSET=TOP", "5, 6, 7, 8", "*NSET, NSET=BOT, GENERATE", "1, 4, 1",
        "*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL",
        "*SHELL SECTION, ELSET=SHELL, MATERIAL=STEEL", "0.01",
        "*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL, SECTION=I",
        "0.05, 0.1, 0.05, 0.05, 0.005, 0.005, 0.004", "1., 0., 0.",
        "*SPRING, ELSET=SPR", "1, 1", "1.E6",
        "*MASS, ELSET=M1", "2.0", "*MASS, ELSET=M2", "3.0", "*MASS, ELSET=M3", "1.0",
        "*MASS, ELSET=M4", "4.0",
        "*CONNECTOR SECTION, ELSET=CONN, BEHAVIOR=BUSH", "BUSHING,",
        "*CONNECTOR BEHAVIOR, NAME=BUSH", "*CONNECTOR ELASTICITY, COMPONENT=1", "1.E5,",
        "*CONNECTOR ELASTICITY, COMPONENT=2", "2.E5,", "*CONNECTOR DAMPING, COMPONENT=1",
        "10.,",
        "*KINEMATIC COUPLING, REF NODE=13", "BOT, 1, 3",
        "*SURFACE, TYPE=NODE, NAME=TOPS", "TOP, 1.0",
        "*COUPLING, REF NODE=14, SURFACE=TOPS", "*DISTRIBUTING", "1, 6",
        "*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1E11, 0.3", "*DENSITY", "7850.",
        "*STEP", "*FREQUENCY", "10", "*END STEP"]


def _deck(lines) -> bytes:
    return ("\n".join(lines) + "\n").encode()


def _replace(old: str, new, lines=BASE) -> list[str]:
    """``lines`` with the first line equal to ``old`` replaced by ``new`` (str, list or None)."""
    i = lines.index(old)
    new = [] if new is None else [new] if isinstance(new, str) else list(new)
    return list(lines[:i]) + new + list(lines[i + 1:])


def cases():
    """Yield ``(case_id, filename, content, expect)``."""
    yield "base", "base.inp", _deck(BASE), "ok"
    text = _deck(BASE)
    # ---- truncations
    for k, frac in enumerate((0.03, 0.1, 0.2, 0.35, 0.5, 0.65)):
        yield f"truncate_bytes_{k}", f"cut{k}.inp", text[:int(len(text) * frac)], "error"
    for name, old, new in (
            ("element_missing_last_node", "1, 1, 2, 3, 4, 5, 6, 7, 8", "1, 1, 2, 3, 4, 5, 6, 7"),
            ("wedge_missing_node", "2, 2, 9, 3, 6, 10, 7", "2, 2, 9, 3, 6, 10"),
            ("shell_missing_node", "3, 5, 6, 7, 8", "3, 5, 6, 7"),
            ("node_missing_coordinate", "5, 0., 0., 1.", "5, 0., 0."),
            ("beam_section_one_dim", "0.05, 0.1, 0.05, 0.05, 0.005, 0.005, 0.004", "0.05"),
            ("spring_missing_dof", "1, 1", "1"),
            ("elastic_missing_nu", "2.1E11, 0.3", "2.1E11")):
        yield name, f"{name}.inp", _deck(_replace(old, new)), "error"
    # elements run together: the next element's id read as the last node, then lost
    yield "elements_run_together", "runon.inp", _deck(_replace(
        "3, 5, 6, 7, 8", ["3, 5, 6, 7", "9, 5, 6, 7, 8"])), "error"
    yield "empty", "empty.inp", b"", "error"
    # ---- garbage
    yield "binary", "binary.inp", bytes(range(256)) * 8, "error"
    yield "nul_in_text", "nul.inp", text[:150] + b"\x00" + text[150:], "error"
    yield "random_text", "words.inp", b"hello world\nnot a deck at all\n" * 20, "error"
    yield "utf16", "utf16.inp", "\n".join(BASE).encode("utf-16"), "error"
    yield "data_before_keyword", "data.inp", _deck(["1, 2, 3"] + BASE), "error"
    # ---- non-finite numbers
    for name, old, new in (
            ("nan_node", "6, 1., 0., 1.", "6, nan, 0., 1."),
            ("inf_node", "7, 1., 1., 1.", "7, 1., inf, 1."),
            ("nan_E", "2.1E11, 0.3", "nan, 0.3"),
            ("nan_nu", "2.1E11, 0.3", "2.1E11, nan"),
            ("inf_density", "7850.", "inf"),
            ("nan_thickness", "0.01", "nan"),
            ("nan_mass", "2.0", "nan"),
            ("inf_spring", "1.E6", "inf"),
            ("nan_beam_dim", "0.05, 0.1, 0.05, 0.05, 0.005, 0.005, 0.004",
             "0.05, nan, 0.05, 0.05, 0.005, 0.005, 0.004"),
            ("nan_surface_weight", "TOP, 1.0", "TOP, nan")):
        yield name, f"{name}.inp", _deck(_replace(old, new)), "error"
    # ---- zero or negative physical values
    for name, old, new in (
            ("E_zero", "2.1E11, 0.3", "0., 0.3"),
            ("E_negative", "2.1E11, 0.3", "-2.1E11, 0.3"),
            ("E_huge", "2.1E11, 0.3", "1.E300, 0.3"),
            ("nu_half", "2.1E11, 0.3", "2.1E11, 0.5"),
            ("nu_below_minus_one", "2.1E11, 0.3", "2.1E11, -1.5"),
            ("density_negative", "7850.", "-7850."),
            ("thickness_zero", "0.01", "0."),
            ("thickness_negative", "0.01", "-0.01"),
            ("mass_negative", "2.0", "-2.0"),
            ("i_section_zero_height", "0.05, 0.1, 0.05, 0.05, 0.005, 0.005, 0.004",
             "0.05, 0., 0.05, 0.05, 0.005, 0.005, 0.004"),
            ("i_section_flanges_too_thick", "0.05, 0.1, 0.05, 0.05, 0.005, 0.005, 0.004",
             "0.05, 0.1, 0.05, 0.05, 0.06, 0.06, 0.004"),
            ("surface_weight_zero", "TOP, 1.0", "TOP, 0."),
            ("distributing_dof_7", "1, 6", "1, 7"),
            ("kinematic_dof_inverted", "BOT, 1, 3", "BOT, 3, 1")):
        yield name, f"{name}.inp", _deck(_replace(old, new)), "error"
    for name, sec, dims in (("rect_zero", "RECT", "0., 0."), ("rect_negative", "RECT", "-1., 1."),
                            ("circ_zero", "CIRC", "0."), ("pipe_wall_too_thick", "PIPE",
                                                          "0.05, 0.06"),
                            ("box_unequal_walls", "BOX", "0.1, 0.1, 0.01, 0.02, 0.01, 0.01"),
                            ("l_too_thick", "L", "0.05, 0.05, 0.06, 0.005"),
                            ("hex_section", "HEX", "0.05, 0.01"),
                            ("box_too_thick", "BOX", "0.1, 0.1, 0.06, 0.06, 0.06, 0.06")):
        lines = _replace("*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL, SECTION=I",
                         f"*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL, SECTION={sec}")
        lines = _replace("0.05, 0.1, 0.05, 0.05, 0.005, 0.005, 0.004", dims, lines)
        yield name, f"{name}.inp", _deck(lines), "error"
    # ---- keywords without their data line
    for name, kw, data in (("elastic_no_data", "*ELASTIC", "2.1E11, 0.3"),
                           ("density_no_data", "*DENSITY", "7850."),
                           ("mass_no_data", "*MASS, ELSET=M1", "2.0"),
                           ("shell_section_no_data", "*SHELL SECTION, ELSET=SHELL, "
                            "MATERIAL=STEEL", "0.01"),
                           ("spring_no_stiffness", "*SPRING, ELSET=SPR", "1.E6")):
        lines = list(BASE)
        i = lines.index(kw)
        j = lines.index(data, i)
        del lines[j]
        yield name, f"{name}.inp", _deck(lines), "error"
    # ---- GENERATE
    for name, data in (("generate_step_zero", "1, 4, 0"), ("generate_huge", "1, 2000000000, 1"),
                       ("generate_inverted", "4, 1, 1"), ("generate_text", "1, four"),
                       ("generate_negative_step", "1, 4, -1")):
        yield name, f"{name}.inp", _deck(_replace("1, 4, 1", data)), "error"
    # ---- inverted and degenerate elements
    for name, old, new in (
            ("hex_inverted", "1, 1, 2, 3, 4, 5, 6, 7, 8", "1, 5, 6, 7, 8, 1, 2, 3, 4"),
            ("wedge_inverted", "2, 2, 9, 3, 6, 10, 7", "2, 6, 10, 7, 2, 9, 3"),
            ("hex_repeated_node", "1, 1, 2, 3, 4, 5, 6, 7, 8", "1, 1, 2, 3, 3, 5, 6, 7, 8"),
            ("beam_zero_length", "4, 8, 11", "4, 8, 8"),
            ("beam_n1_parallel", "1., 0., 0.", "0., 0., 1.")):
        yield name, f"{name}.inp", _deck(_replace(old, new)), "error"
    # ---- duplicate ids
    yield "dup_node", "dupnode.inp", _deck(_replace("14, 0.5, 0.5, 1.5", [
        "14, 0.5, 0.5, 1.5", "5, 9., 9., 9."])), "error"
    yield "dup_element", "dupel.inp", _deck(_replace("3, 5, 6, 7, 8", ["3, 5, 6, 7, 8",
                                                                       "1, 5, 6, 7, 8"])), "error"
    # ---- dangling references
    for name, old, new in (
            ("undefined_node", "3, 5, 6, 7, 8", "3, 5, 6, 7, 99"),
            ("undefined_elset", "*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL",
             "*SOLID SECTION, ELSET=NOPE, MATERIAL=STEEL"),
            ("undefined_material", "*SOLID SECTION, ELSET=SOLID, MATERIAL=STEEL",
             "*SOLID SECTION, ELSET=SOLID, MATERIAL=ALU"),
            ("undefined_nset_in_coupling", "BOT, 1, 3", "NOPE, 1, 3"),
            ("undefined_surface", "*COUPLING, REF NODE=14, SURFACE=TOPS",
             "*COUPLING, REF NODE=14, SURFACE=NOPE"),
            ("undefined_ref_node", "*COUPLING, REF NODE=14, SURFACE=TOPS",
             "*COUPLING, REF NODE=99, SURFACE=TOPS"),
            ("undefined_kinematic_ref", "*KINEMATIC COUPLING, REF NODE=13",
             "*KINEMATIC COUPLING, REF NODE=99"),
            ("element_surface", "*SURFACE, TYPE=NODE, NAME=TOPS", "*SURFACE, NAME=TOPS"),
            ("coupling_without_ref", "*COUPLING, REF NODE=14, SURFACE=TOPS",
             "*COUPLING, SURFACE=TOPS"),
            ("spring_undefined_elset", "*SPRING, ELSET=SPR", "*SPRING, ELSET=NOPE"),
            ("spring_orientation", "*SPRING, ELSET=SPR", "*SPRING, ELSET=SPR, ORIENTATION=O1"),
            ("weighted_distributing", "*DISTRIBUTING", "*DISTRIBUTING, WEIGHTING METHOD=CUBIC"),
            ("undefined_nset_in_surface", "TOP, 1.0", "NOPE, 1.0"),
            ("ref_node_on_surface", "TOP, 1.0", ["TOP, 1.0", "14, 1.0"]),
            ("nset_with_elset", "*NSET, NSET=TOP", "*NSET, NSET=TOP, ELSET=SHELL")):
        yield name, f"{name}.inp", _deck(_replace(old, new)), "error"
    # ---- connectors
    for name, old, new in (
            ("connector_undefined_behavior", "*CONNECTOR SECTION, ELSET=CONN, BEHAVIOR=BUSH",
             "*CONNECTOR SECTION, ELSET=CONN, BEHAVIOR=NOPE"),
            ("connector_unknown_type", "BUSHING,", "HINGE,"),
            ("connector_orientation", "BUSHING,", ["BUSHING,", "ORI1,"]),
            ("connector_nonlinear", "*CONNECTOR ELASTICITY, COMPONENT=1",
             "*CONNECTOR ELASTICITY, COMPONENT=1, NONLINEAR"),
            ("connector_component_7", "*CONNECTOR ELASTICITY, COMPONENT=1",
             "*CONNECTOR ELASTICITY, COMPONENT=7"),
            ("connector_negative_k", "1.E5,", "-1.E5,"),
            ("connector_nan_damping", "10.,", "nan,"),
            ("connector_component_not_available", "BUSHING,", "CARDAN,"),
            ("connector_nodes_apart", "15, 3., 0., 0.", "15, 3., 1., 0."),
            ("connector_no_elasticity_data", "1.E5,", None),
            ("connector_outside_behavior", "*CONNECTOR BEHAVIOR, NAME=BUSH", None)):
        yield name, f"{name}.inp", _deck(_replace(old, new)), "error"
    yield "coupling_without_distributing", "nodist.inp", _deck([
        ln for ln in BASE if ln not in ("*DISTRIBUTING", "1, 6")]), "error"
    yield "connector_elasticity_after_material", "late.inp", _deck(_replace(
        "*STEP", ["*CONNECTOR ELASTICITY, COMPONENT=3", "3.E5,", "*STEP"])), "error"
    yield "connector_without_section", "noconn.inp", _deck([ln for ln in BASE if ln not in (
        "*CONNECTOR SECTION, ELSET=CONN, BEHAVIOR=BUSH", "BUSHING,")]), "error"
    yield "connector_cartesian_cardan", "cc.inp", _deck(_replace(
        "BUSHING,", "CARTESIAN, CARDAN")), "ok"
    yield "spring_without_section", "nospring.inp", _deck([ln for ln in BASE if ln not in (
        "*SPRING, ELSET=SPR", "1, 1", "1.E6")]), "error"
    # ---- unknown, misspelt and unsupported keywords / element types
    for name, lines, expect in (
            ("unknown_keyword", _replace("*STEP", ["*FOOBAR, X=1", "1, 2", "*STEP"]), "ok"),
            ("boundary_before_step", _replace("*STEP", ["*BOUNDARY", "13, 1, 6", "*STEP"]),
             "ok"),
            ("typo_element", _replace("*ELEMENT, TYPE=S4, ELSET=SHELL",
                                      "*ELEMNT, TYPE=S4, ELSET=SHELL"), "error"),
            ("typo_node", _replace("*NODE", "*NODES"), "error"),
            ("typo_density", _replace("*DENSITY", "*DENSTY"), "error"),
            ("unknown_element_type", _replace("*ELEMENT, TYPE=S4, ELSET=SHELL",
                                              "*ELEMENT, TYPE=S8R, ELSET=SHELL"), "error"),
            ("c3d20", _replace("*ELEMENT, TYPE=C3D8, ELSET=SOLID",
                               "*ELEMENT, TYPE=C3D20, ELSET=SOLID"), "error"),
            ("tie", _replace("*STEP", ["*TIE, NAME=T1", "A, B", "*STEP"]), "error"),
            ("mpc", _replace("*STEP", ["*MPC", "BEAM, 1, 2", "*STEP"]), "error"),
            ("equation", _replace("*STEP", ["*EQUATION", "2", "1, 1, 1., 2, 1, -1.",
                                            "*STEP"]), "error"),
            ("transform", _replace("*STEP", ["*TRANSFORM, NSET=TOP, TYPE=C", "0,0,0,0,0,1",
                                             "*STEP"]), "error"),
            ("ngen", _replace("*STEP", ["*NGEN, NSET=X", "1, 4", "*STEP"]), "error"),
            ("composite_shell", _replace("*SHELL SECTION, ELSET=SHELL, MATERIAL=STEEL",
                                         "*SHELL SECTION, ELSET=SHELL, COMPOSITE"), "error"),
            ("orthotropic_elastic", _replace("*ELASTIC", "*ELASTIC, TYPE=ENGINEERING CONSTANTS"),
             "error"),
            ("two_instances", _replace("*STEP", ["*INSTANCE, NAME=A, PART=P", "*END INSTANCE",
                                                 "*INSTANCE, NAME=B, PART=P", "*END INSTANCE",
                                                 "*STEP"]), "error")):
        yield name, f"{name}.inp", _deck(lines), expect
    # ---- typos in fields
    for name, old, new in (
            ("letter_in_coordinate", "6, 1., 0., 1.", "6, 1.O, 0., 1."),
            ("real_element_id", "3, 5, 6, 7, 8", "3.5, 5, 6, 7, 8"),
            ("text_node_id", "3, 5, 6, 7, 8", "3, 5, 6, 7, eight"),
            ("text_thickness", "0.01", "thin"),
            ("text_mass", "2.0", "heavy")):
        yield name, f"{name}.inp", _deck(_replace(old, new)), "error"
    # ---- tolerated input
    yield "unreferenced_node", "orphan.inp", _deck(_replace("14, 0.5, 0.5, 1.5", [
        "14, 0.5, 0.5, 1.5", "99, 9., 9., 9."])), "error"
    yield "comments", "comments.inp", _deck([x for ln in BASE for x in ("** note", ln)]), "ok"
    yield "lowercase", "lower.inp", _deck([ln.lower() if ln.startswith("*") else ln
                                           for ln in BASE]), "ok"
    yield "continued_element", "cont.inp", _deck(_replace("1, 1, 2, 3, 4, 5, 6, 7, 8", [
        "1, 1, 2, 3, 4,", "5, 6, 7, 8"])), "ok"
    yield "generate_with_step", "gen2.inp", _deck(_replace("1, 4, 1", "1, 4")), "ok"
    yield "rect_beam", "rect.inp", _deck(_replace(
        "0.05, 0.1, 0.05, 0.05, 0.005, 0.005, 0.004", "0.02, 0.04", _replace(
            "*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL, SECTION=I",
            "*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL, SECTION=RECT"))), "ok"
    yield "l_beam", "lbeam.inp", _deck(_replace(
        "0.05, 0.1, 0.05, 0.05, 0.005, 0.005, 0.004", "0.05, 0.04, 0.005, 0.004", _replace(
            "*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL, SECTION=I",
            "*BEAM SECTION, ELSET=BEAM, MATERIAL=STEEL, SECTION=L"))), "ok"
    yield "kinematic_coupling_keyword_pair", "kin.inp", _deck(_replace(
        "*DISTRIBUTING", "*KINEMATIC")), "ok"
    yield "no_step", "nostep.inp", _deck(BASE[:BASE.index("*STEP")]), "ok"
    comp = ["*SHELL SECTION, ELSET=SHELL, COMPOSITE, SYMMETRIC", "0.001, 3, CF, 0.",
            "0.001, 3, CF, 45."]
    lamina = ["*MATERIAL, NAME=CF", "*ELASTIC, TYPE=LAMINA",
              "140.E9, 10.E9, 0.3, 5.E9, 5.E9, 4.E9", "*DENSITY", "1600.", "*STEP"]
    base = _replace("0.01", None, _replace("*SHELL SECTION, ELSET=SHELL, MATERIAL=STEEL", comp))
    yield "composite_lamina", "comp.inp", _deck(_replace("*STEP", lamina, base)), "ok"
    for name, old, new in (
            ("composite_named_orientation", "0.001, 3, CF, 45.", "0.001, 3, CF, ORI1"),
            ("composite_zero_ply", "0.001, 3, CF, 45.", "0., 3, CF, 45."),
            ("composite_undefined_material", "0.001, 3, CF, 45.", "0.001, 3, GF, 45."),
            ("lamina_negative_e2", "140.E9, 10.E9, 0.3, 5.E9, 5.E9, 4.E9",
             "140.E9, -10.E9, 0.3, 5.E9, 5.E9, 4.E9"),
            ("composite_unsymmetric", "*SHELL SECTION, ELSET=SHELL, COMPOSITE, SYMMETRIC",
             "*SHELL SECTION, ELSET=SHELL, COMPOSITE")):
        lines = _replace("*STEP", lamina, base)
        yield name, f"{name}.inp", _deck(_replace(old, new, lines)), "error"
