"""Bad car files (TOML) for ``load_car``, made by mutating the sample sedan key by key.

The sample's mesh and tyre paths are made absolute so that each case loads from its own
folder.  For every distinct key (the first ``[[body.mass]]`` entry stands for all of
them, ``fl`` and ``rr`` for the corners): a typo in the key, a wrong type, NaN and
infinity, a negative value, arrays of the wrong length, and deletion of required keys;
the same for a seat added on the driver floor point, with the seat's own checks.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SEDAN = ROOT / "cars" / "sedan.toml"
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"
#: keys whose deletion must be an error
REQUIRED = {"hardpoint_m", "wheel_center_m", "spring_rate_N_per_m", "unsprung_mass_kg",
            "wheel_radius_m", "wheel_spin_inertia_kg_m2", "tire", "mass_kg", "position_m",
            "ratio", "layout"}
#: mutations that give a valid file (an empty label where the default is empty)
MAY_LOAD = {("body.fatigue", "name", "empty-string")}
KEY_LINE = re.compile(r"^(\s*)([A-Za-z_][A-Za-z0-9_]*)(\s*=\s*)(.*?)(\s*#.*)?$")


def base_text(car: Path = SEDAN) -> str:
    text = car.read_text()
    text = text.replace('"../meshes/', f'"{(ROOT / "meshes").as_posix()}/')
    return text.replace('"../tires/', f'"{(ROOT / "tires").as_posix()}/')


def _key_lines(lines):
    """(index, section, key, value) of the distinct key lines to mutate."""
    section, seen_mass, out = "", 0, []
    for i, line in enumerate(lines):
        s = line.strip()
        if s.startswith("["):
            section = s.strip("[]")
            if section == "body.mass":
                seen_mass += 1
            continue
        m = KEY_LINE.match(line)
        if not m or s.startswith("#"):
            continue
        if section == "body.mass" and seen_mass > 1:
            continue
        if section in ("corners.fr", "corners.rl") or section.startswith("body.points") and \
                m.group(2) != "driver_floor":
            continue
        out.append((i, section, m.group(2), m.group(4)))
    return out


def _variants(key: str, value: str):
    v = value.strip()
    is_array = v.startswith("[")
    is_string = v.startswith('"')
    if not key.endswith("floor"):  # body.points names are the user's own: no typo there
        yield "typo", None
    if is_string:
        yield "number", "5"
        yield "empty-string", '""'
        return
    yield "text", '"oops"'
    yield "bool", "true"
    yield "table", "{a = 1}"
    if is_array:
        items = [x.strip() for x in v.strip("[]").split(",")]
        yield "short", "[" + ", ".join(items[:-1]) + "]"
        yield "long", "[" + ", ".join(items + ["0.0"]) + "]"
        yield "nan-item", "[" + ", ".join(["nan"] + items[1:]) + "]"
        yield "text-item", "[" + ", ".join(['"a"'] + items[1:]) + "]"
        yield "empty", "[]"
        if key.endswith("inertia_kg_m2"):
            yield "negative", "[" + ", ".join(["-1.0"] + items[1:]) + "]"
    else:
        yield "nan", "nan"
        yield "inf", "inf"
        yield "negative", "-" + v if not v.startswith("-") else v[1:]
        yield "array", f"[{v}]"


def _mutations(lines, *, sections=None, required=REQUIRED):
    """Each distinct key of ``lines`` (of ``sections`` only, if given) mutated by
    :func:`_variants`, and deleted where it is required."""
    for i, section, key, value in _key_lines(lines):
        if sections is not None and section not in sections:
            continue
        m = KEY_LINE.match(lines[i])
        for kind, new in _variants(key, value):
            mutated = list(lines)
            if kind == "typo":
                mutated[i] = f"{m.group(1)}{key}x{m.group(3)}{value}"
            else:
                mutated[i] = f"{m.group(1)}{key}{m.group(3)}{new}"
            expect = "maybe" if (section, key, kind) in MAY_LOAD else "error"
            yield f"{section}.{key}-{kind}", "car.toml", "\n".join(mutated).encode(), expect
        if key in required:
            mutated = lines[:i] + lines[i + 1:]
            yield f"{section}.{key}-deleted", "car.toml", "\n".join(mutated).encode(), "error"


#: a seat on the sample's driver floor point (flexpipe.vehicle.seats)
SEAT = ('[body.seats.driver_seat]\nfloor_point = "driver_floor"\n'
        'natural_frequency_hz = 4.0\ndamping_ratio = 0.3\n'
        'fore_aft_frequency_hz = 3.0\nfore_aft_damping_ratio = 0.2\n')


def _seats():
    """The sedan with a seat: each seat key mutated as the sample's are, deleted, and the
    seat's own checks (a floor point that is not a named point, a seat named as a point,
    values past the bounds, a seat that is not a table)."""
    text = base_text() + "\n" + SEAT
    yield "seat-ok", "car.toml", text.encode(), "ok"
    yield from _mutations(text.splitlines(), sections={"body.seats.driver_seat"},
                          required={"floor_point", "natural_frequency_hz", "damping_ratio"})
    base = base_text() + "\n"
    for name, seat in (
            ("floor-point-unknown", SEAT.replace('"driver_floor"', '"nowhere"')),
            ("named-as-a-point", SEAT.replace("driver_seat]", "rear_floor]")),
            ("frequency-above-20-Hz", SEAT.replace("= 4.0", "= 25.0")),
            ("frequency-below-0.5-Hz", SEAT.replace("= 4.0", "= 0.1")),
            ("damping-zero", SEAT.replace("= 0.3", "= 0.0")),
            ("damping-above-2", SEAT.replace("= 0.3", "= 2.5")),
            ("fore-aft-frequency-alone", SEAT.replace("fore_aft_damping_ratio = 0.2\n", "")),
            ("fore-aft-damping-alone", SEAT.replace("fore_aft_frequency_hz = 3.0\n", "")),
            ("not-a-table", "[body.seats]\ndriver_seat = 4.0\n")):
        yield f"seat-{name}", "car.toml", (base + seat).encode(), "error"


def cases():
    text = base_text()
    yield "ok-sedan", "car.toml", text.encode(), "ok"
    yield "ok-crlf", "car.toml", text.replace("\n", "\r\n").encode(), "ok"
    yield "ok-no-comments", "car.toml", "\n".join(
        ln for ln in text.splitlines() if not ln.strip().startswith("#")).encode(), "ok"
    yield from _mutations(text.splitlines())
    # whole-file and structure
    yield "empty", "car.toml", b"", "error"
    yield "binary", "car.toml", bytes(range(256)) * 8, "error"
    yield "latin1", "car.toml", text.replace('name = "sedan"', 'name = "s\xe9dan"').encode(
        "latin-1"), "error"
    yield "utf16", "car.toml", text.encode("utf-16"), "error"
    yield "truncated-half", "car.toml", text.encode()[: len(text) // 2], "error"
    yield "truncated-mid-line", "car.toml", text.encode()[: text.index("spring_rate") + 14], \
        "error"
    yield "deep-nesting", "car.toml", b"a = " + b"[" * 5000 + b"]" * 5000, "error"
    yield "deep-tables", "car.toml", b"a = " + b"{b = " * 3000 + b"1" + b"}" * 3000, "error"
    yield "unknown-section", "car.toml", (text + "\n[suspensionx]\nk = 1\n").encode(), "error"
    yield "duplicate-section", "car.toml", (text + "\n[steering]\nratio = 15.0\n").encode(), \
        "error"
    for sec in ("car", "body", "corners.fl", "steering", "drive"):
        out, skip = [], False
        for ln in text.splitlines():
            if ln.strip().startswith("["):
                skip = ln.strip() == f"[{sec}]"
            if not skip:
                out.append(ln)
        yield f"section-{sec}-missing", "car.toml", "\n".join(out).encode(), "error"
    yield "mesh-missing-file", "car.toml", text.replace("sedan_biw.bdf", "nope.bdf").encode(), \
        "error"
    yield "tire-missing-file", "car.toml", text.replace("sedan_205_55R16.tir", "nope.tir", 1)\
        .encode(), "error"
    yield "mesh-is-directory", "car.toml", text.replace("meshes/sedan_biw.bdf", "meshes")\
        .encode(), "error"
    yield "left-corner-on-right", "car.toml", text.replace(
        "hardpoint_m = [0.0, 0.65, 0.85]", "hardpoint_m = [0.0, -0.65, 0.85]", 1).encode(), \
        "error"
    yield "rear-ahead-of-front", "car.toml", text.replace(
        "wheel_center_m = [0.0, 0.775, 0.2983]", "wheel_center_m = [-3.0, 0.775, 0.2983]", 1)\
        .encode(), "error"
    yield "wheel-under-ground", "car.toml", text.replace(
        "wheel_center_m = [0.0, 0.775, 0.2983]", "wheel_center_m = [0.0, 0.775, -0.3]", 1)\
        .encode(), "error"

    yield from _bounds(text)
    yield from _powertrain()
    yield from _powertrain_body()
    yield from _subframe()
    yield from _variants_of_base()
    yield from _seats()


def _bounds(text: str):
    """Values outside the physical bounds of flexpipe/vehicle/limits.py (one case each, the
    first occurrence of the line), and values at the edge of what is valid."""
    lk = base_text(LINKAGE)
    for car, label, old, new, expect in (
            (text, "spin-inertia-tiny", "wheel_spin_inertia_kg_m2 = 1.0",
             "wheel_spin_inertia_kg_m2 = 1.0e-9", "error"),
            (text, "spin-inertia-kg-cm2", "wheel_spin_inertia_kg_m2 = 1.0",
             "wheel_spin_inertia_kg_m2 = 1.0e4", "error"),
            (text, "spin-inertia-small-wheel", "wheel_spin_inertia_kg_m2 = 1.0",
             "wheel_spin_inertia_kg_m2 = 0.1", "ok"),
            (text, "arb-huge", "rate_N_per_m = 18000.0", "rate_N_per_m = 1.0e12", "error"),
            (text, "arb-n-per-mm", "rate_N_per_m = 18000.0", "rate_N_per_m = 18.0", "error"),
            (text, "arb-none", "rate_N_per_m = 18000.0", "rate_N_per_m = 0.0", "ok"),
            (text, "wheel-center-y-5m", "wheel_center_m = [0.0, 0.775, 0.2983]",
             "wheel_center_m = [0.0, 5.0, 0.2983]", "error"),
            (text, "wheel-center-mm", "wheel_center_m = [0.0, 0.775, 0.2983]",
             "wheel_center_m = [0.0, 775.0, 298.3]", "error"),
            (text, "hardpoint-far-from-wheel", "hardpoint_m = [0.0, 0.65, 0.85]",
             "hardpoint_m = [0.0, 0.65, 2.5]", "error"),
            (text, "unsprung-inertia-triangle", "unsprung_inertia_kg_m2 = [0.9, 1.3, 0.9]",
             "unsprung_inertia_kg_m2 = [0.1, 0.1, 5.0]", "error"),
            (lk, "linkage-spin-inertia-tiny", "wheel_spin_inertia_kg_m2 = 1.0",
             "wheel_spin_inertia_kg_m2 = 1.0e-9", "error"),
            (lk, "linkage-rack-tiny", "travel_per_rev_m = 0.055",
             "travel_per_rev_m = 1.0e-9", "error"),
            (lk, "linkage-rack-mm", "travel_per_rev_m = 0.055", "travel_per_rev_m = 55.0",
             "error"),
            (lk, "linkage-arb-torsion-huge", "torsion_rate_N_m_per_rad = 6300.0",
             "torsion_rate_N_m_per_rad = 1.0e12", "error"),
            (lk, "linkage-bushing-rigid", "stiffness = [8.0e6, 8.0e6, 1.0e6, 500.0, 500.0, 150.0]",
             "stiffness = [1.0e13, 1.0e13, 1.0e13, 1.0e9, 1.0e9, 1.0e9]", "error"),
            (lk, "linkage-bushing-kn-per-mm", "stiffness = [8.0e6, 8.0e6, 1.0e6,",
             "stiffness = [8.0, 8.0, 1.0,", "error"),
            (lk, "linkage-bushing-damping-huge", "damping = [800.0, 800.0, 100.0, 0.5, 0.5, 0.2]",
             "damping = [800.0, 800.0, 100.0, 1.0e6, 0.5, 0.2]", "error"),
            (lk, "linkage-bushing-at-bounds", "stiffness = [8.0e6, 8.0e6, 1.0e6, 500.0, 500.0, "
             "150.0]", "stiffness = [1.0e8, 1.0e8, 1.0e4, 1.0e6, 1.0e6, 1.0e6]", "ok"),
            (lk, "linkage-part-inertia-triangle", "inertia_kg_m2 = [0.0151, 0.0207, 0.0355]",
             "inertia_kg_m2 = [0.0151, 0.0207, 0.0500]", "error"),
            (lk, "linkage-wheel-inertia-triangle", "wheel_inertia_kg_m2 = [0.45, 0.0, 0.45]",
             "wheel_inertia_kg_m2 = [0.45, 0.0, 1.45]", "error")):
        assert old in car, old
        yield f"bound-{label}", "car.toml", car.replace(old, new, 1).encode(), expect


def _powertrain():
    """``[drive] reaction_mounts`` (powertrain mounts on a linkage car): each case one
    mistake in the mount list or its ``[body.mounts]`` tables, and the valid base."""
    tables = "".join(f"[body.mounts.{n}]\npoint_m = {p}\nradius_m = 0.05\n\n" for n, p in (
        ("engine_mount_r", "[0.20, -0.55, 0.55]"), ("gearbox_mount_l", "[0.20, 0.55, 0.55]"),
        ("roll_restrictor", "[-0.20, 0.0, 0.153]")))
    names = '["engine_mount_r", "gearbox_mount_l", "roll_restrictor"]'
    lk = base_text(LINKAGE)
    assert "\n[drive]\n" in lk
    good = lk.replace("\n[drive]\n", f"\n{tables}[drive]\nreaction_mounts = {names}\n")
    for label, old, new, expect in (
            ("ok", "", "", "ok"),
            ("string", f"reaction_mounts = {names}", 'reaction_mounts = "engine_mount_r"',
             "error"),
            ("numbers", f"reaction_mounts = {names}", "reaction_mounts = [1, 2, 3]", "error"),
            ("empty", f"reaction_mounts = {names}", "reaction_mounts = []", "error"),
            ("two", f"reaction_mounts = {names}",
             'reaction_mounts = ["engine_mount_r", "gearbox_mount_l"]', "error"),
            ("twice", f"reaction_mounts = {names}",
             'reaction_mounts = ["engine_mount_r", "gearbox_mount_l", "engine_mount_r"]',
             "error"),
            ("no-table", f"reaction_mounts = {names}",
             'reaction_mounts = ["engine_mount_r", "gearbox_mount_l", "oil_pan"]', "error"),
            ("suspension-mount", f"reaction_mounts = {names}",
             'reaction_mounts = ["engine_mount_r", "gearbox_mount_l", "front_rack_mount_l"]',
             "error"),
            ("no-point", "point_m = [-0.20, 0.0, 0.153]\n", "", "error"),
            ("on-one-line", "point_m = [-0.20, 0.0, 0.153]", "point_m = [0.20, 0.0, 0.55]",
             "error"),
            ("knuckle", f"reaction_mounts = {names}",
             f'drive_reaction = "knuckle"\nreaction_mounts = {names}', "error"),
            ("table-without-list", f"reaction_mounts = {names}\n", "", "error")):
        assert old in good, old
        yield f"powertrain-{label}", "car.toml", good.replace(old, new, 1).encode(), expect


def _powertrain_body():
    """``[powertrain]`` (a rigid powertrain on mounts of a linkage car): one mistake each
    in its table, its mounts or their bushings, and the valid base."""
    from tests.test_powertrain import SPREAD, powertrain_text

    lk = base_text(LINKAGE)
    assert SPREAD in lk
    good = lk.replace(SPREAD, "").replace("\n[drive]\n", "\n" + powertrain_text() + "[drive]\n")
    names = '["engine_mount_r", "gearbox_mount_l", "roll_restrictor"]'
    for label, old, new in (
            ("ok", "", ""),
            ("mass-zero", "mass_kg = 190.0", "mass_kg = 0.0"),
            ("mass-missing", "mass_kg = 190.0\n", ""),
            ("cm-two", "center_of_mass_m = [0.10, 0.0, 0.55]", "center_of_mass_m = [0.1, 0.0]"),
            ("inertia-triangle", "inertia_kg_m2 = [8.0, 6.0, 9.0]",
             "inertia_kg_m2 = [8.0, 6.0, 30.0]"),
            ("mounts-string", f"mounts = {names}", 'mounts = "engine_mount_r"'),
            ("mounts-twice", f"mounts = {names}",
             'mounts = ["engine_mount_r", "engine_mount_r", "roll_restrictor"]'),
            ("mount-no-table", f"mounts = {names}",
             'mounts = ["engine_mount_r", "gearbox_mount_l", "oil_pan"]'),
            ("mount-suspension", f"mounts = {names}",
             'mounts = ["engine_mount_r", "gearbox_mount_l", "front_rack_mount_l"]'),
            ("bushing-missing", "[powertrain.bushings.roll_restrictor]",
             "[powertrain.bushings_spare.roll_restrictor]"),
            ("bushing-stray", "[powertrain.bushings.roll_restrictor]",
             "[powertrain.bushings.oil_pan]\nstiffness = [1e5, 1e5, 1e5, 0, 0, 0]\n\n"
             "[powertrain.bushings.roll_restrictor]"),
            ("bushing-n-per-mm", "stiffness = [150000.0, 150000.0, 250000.0,",
             "stiffness = [150.0, 150.0, 250.0,"),
            ("bushing-negative", "stiffness = [150000.0, 150000.0, 250000.0,",
             "stiffness = [-150000.0, 150000.0, 250000.0,"),
            ("no-linkage-drive-reaction", "\n[drive]\n",
             f"\n[drive]\nreaction_mounts = {names}\n")):
        assert old in good, old
        yield (f"powertrain-body-{label}", "car.toml", good.replace(old, new, 1).encode(),
               "ok" if label == "ok" else "error")


def _subframe():
    """``[subframe.<name>]`` (a cradle on bushings carrying suspension mounts): one mistake
    each, and the valid base."""
    from tests.test_subframe import CARRIED, SOFT, subframe_text

    lk = base_text(LINKAGE)
    good = lk.replace("\n[drive]\n", "\n" + subframe_text(**SOFT) + "[drive]\n")
    carried = str(CARRIED).replace("'", '"')
    for label, old, new in (
            ("ok", "", ""),
            ("carries-string", f"carries = {carried}", 'carries = "front_rack_mount_l"'),
            ("carries-unknown", f"carries = {carried}", 'carries = ["oil_pan"]'),
            ("carries-twice", f"carries = {carried}",
             'carries = ["front_rack_mount_l", "front_rack_mount_l"]'),
            ("carries-missing", f"carries = {carried}\n", ""),
            ("carried-tied", "\n[drive]\n",
             "\n[body.mounts.front_rack_mount_l]\nradius_m = 0.02\n\n[drive]\n"),
            ("mass-negative", "mass_kg = 20.0", "mass_kg = -20.0"),
            ("mount-untied", "[body.mounts.cradle_rear_r]", "[body.mounts.cradle_rear_x]"),
            ("bushing-stray", "[subframe.front.bushings.cradle_rear_r]",
             "[subframe.front.bushings.cradle_x]"),
            ("prismatic", "", "")):
        if label == "prismatic":
            text = base_text().replace("\n[drive]\n",
                                       "\n[subframe.front]\nmass_kg = 20.0\n\n[drive]\n")
            yield "subframe-prismatic", "car.toml", text.encode(), "error"
            continue
        assert old in good, old
        yield (f"subframe-{label}", "car.toml", good.replace(old, new, 1).encode(),
               "ok" if label == "ok" else "error")


def _variants_of_base():
    """Car variants (``base = ...``): the valid variant, and one mistake each."""
    base = f'base = "{LINKAGE}"\n'
    for label, text, expect in (
            ("ok", base + "[suspension.front.spring]\nrate_N_per_m = 95000.0\n", "ok"),
            ("ok-no-change", base, "ok"),
            ("number", "base = 3\n", "error"),
            ("empty", 'base = ""\n', "error"),
            ("missing", 'base = "nowhere.toml"\n', "error"),
            ("not-toml", f'base = "{ROOT / "tires" / "sedan_205_55R16.tir"}"\n', "error"),
            ("self", 'base = "car.toml"\n', "error"),
            ("table-for-value", base + "[car.name]\nx = 1\n", "error"),
            ("value-for-table", base + "corners = 3\n", "error"),
            ("bad-value", base + "[suspension.front.spring]\nrate_N_per_m = -1.0\n", "error"),
            ("unknown-key", base + "[suspension.front.spring]\nrate = 1.0\n", "error"),
            ("after-table", "[car]\nname = \"x\"\n" + base, "error"),
            ("tire-missing", base + '[corners.fl]\ntire = "nope.tir"\n', "error")):
        yield f"variant-{label}", "car.toml", text.encode(), expect
