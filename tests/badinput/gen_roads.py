"""Bad-input corpus for road TOML/CSV, path TOML/CSV and driver TOML files.

Generated from the repository's valid files (``roads/*.toml``, ``roads/bump.csv``,
``paths/*``).  ``cases()`` yields ``(case_id, filename, content, expect)``; the file name
says which loader applies (:func:`load`): ``road_*`` -> ``flexpipe.roads.load_road``,
``path_*`` -> ``flexpipe.driver.read_path``, ``speed_*`` ->
``flexpipe.driver.read_speed_profile``, ``driver_*`` -> ``flexpipe.driver.read_driver``.
"""

from __future__ import annotations

import random
import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]


def load(path):
    """Load a case file with the loader its name selects."""
    path = Path(path)
    if path.name.startswith("road_"):
        from flexpipe.roads import load_road

        return load_road(path)
    if path.name.startswith("path_"):
        from flexpipe.driver import read_path

        return read_path(path)
    if path.name.startswith("speed_"):
        from flexpipe.driver import read_speed_profile
        from flexpipe.vehicle.run_inputs import SPEED_MAX

        return read_speed_profile(path, speed_max=SPEED_MAX)
    from flexpipe.driver import read_driver

    return read_driver(path)


def _set(text: str, key: str, value: str) -> str:
    new, n = re.subn(rf"^({key}\s*=\s*).*$", lambda m: m.group(1) + value, text, count=1,
                     flags=re.M)
    assert n == 1, key
    return new


def _rename(text: str, key: str, new_key: str) -> str:
    new, n = re.subn(rf"^{key}(\s*=)", rf"{new_key}\1", text, count=1, flags=re.M)
    assert n == 1, key
    return new


def _toml_cases(prefix, name, text, values, typos):
    """Value and key-typo mutations of one TOML file."""
    for key, value, expect in values:
        label = re.sub(r"\W+", "_", value).strip("_") or "empty"
        yield f"{name}_{key}_{label}", f"{prefix}_{name}.toml", _set(text, key, value).encode(), \
            expect
    for key, typo in typos:
        yield f"{name}_typo_{typo}", f"{prefix}_{name}.toml", _rename(text, key, typo).encode(), \
            "error"


def _common_file_cases(prefix, name, text, suffix):
    """Truncation, garbage and encoding cases shared by every file kind."""
    b = text.encode()
    rng = random.Random(len(text))
    yield f"{name}_empty", f"{prefix}_empty{suffix}", b"", "error"
    yield f"{name}_garbage", f"{prefix}_garbage{suffix}", bytes(
        rng.randrange(256) for _ in range(2000)), "error"
    yield f"{name}_utf16", f"{prefix}_utf16{suffix}", text.encode("utf-16"), "error"
    yield f"{name}_latin1", f"{prefix}_latin1{suffix}", b"# \xe9\xe8\xff\n" + b, "error"


def cases():
    """Yield the corpus (about 130 cases)."""
    iso = (REPO / "roads" / "iso_c_200m.toml").read_text()
    flat = (REPO / "roads" / "flat_500m.toml").read_text()
    irr = (REPO / "roads" / "irregularity.toml").read_text()
    harmonic = ('[road]\ntype = "harmonic"\nwavelength_m = 5.0\namplitude_m = 0.01\n'
                'length_m = 100.0\ndx_m = 0.1\n')
    yield "road_iso_ok", "road_iso.toml", iso.encode(), "ok"
    yield "road_flat_ok", "road_flat.toml", flat.encode(), "ok"
    yield "road_irregularity_ok", "road_irr.toml", irr.encode(), "ok"
    yield "road_harmonic_ok", "road_harmonic.toml", harmonic.encode(), "ok"
    yield from _toml_cases("road", "iso", iso, [
        ("type", '"iso8806"', "error"), ("type", "3", "error"), ("road_class", '"Z"', "error"),
        ("road_class", '"c"', "error"), ("length_m", "-200.0", "error"),
        ("length_m", "0.0", "error"), ("length_m", "nan", "error"), ("length_m", "inf", "error"),
        ("length_m", '"200"', "error"), ("length_m", "1e12", "error"),
        ("dx_m", "0.0", "error"), ("dx_m", "-0.05", "error"), ("dx_m", "true", "error"),
        ("dx_m", "500.0", "error"), ("seed", "1.5", "error"), ("seed", '"one"', "error")],
        [("road_class", "road_clas"), ("length_m", "lenght_m"), ("dx_m", "dx")])
    yield from _toml_cases("road", "flat", flat, [
        ("length_m", "-1.0", "error"), ("dx_m", "nan", "error"), ("type", '"flat "', "error"),
        ("length_m", "[500.0]", "error")], [("length_m", "length_km")])
    yield from _toml_cases("road", "irr", irr, [
        ("s0_m", "nan", "error"), ("wavelength_m", "0.0", "error"),
        ("n_periods", "0", "error"), ("n_periods", "2.5", "error"),
        ("tracks", '"middle"', "error"), ("start_m", "-20.0", "error"),
        ("track_width_m", "0.0", "error"), ("track_width_m", "-1.5", "error"),
        ("dx_m", "1e-9", "error")], [("s0_m", "s_0_m")])
    yield from _toml_cases("road", "harmonic", harmonic, [
        ("amplitude_m", "inf", "error"), ("wavelength_m", "-5.0", "error"),
        ("amplitude_m", "10.0", "error"),               # 10 mm written as 10 (metres)
        ("length_m", "-100.0", "error")], [("amplitude_m", "amplitude")])
    extra = iso.replace("[road]", "[road]\ncoherence = 2.0")
    yield "road_iso_coherence_2", "road_coh.toml", extra.encode(), "error"
    yield "road_iso_coherence_word", "road_coh.toml", iso.replace(
        "[road]", '[road]\ncoherence = "iso"').encode(), "error"
    yield "road_iso_fade_negative", "road_fade.toml", iso.replace(
        "[road]", "[road]\nfade_m = -5.0").encode(), "error"
    yield "road_no_road_table", "road_notable.toml", iso.replace("[road]", "[roads]").encode(), \
        "error"
    yield "road_two_tables", "road_two.toml", (iso + "\n[extra]\na = 1\n").encode(), "error"
    yield "road_syntax_error", "road_syntax.toml", iso.replace("type = ", "type == ", 1).encode(), \
        "error"
    yield "road_truncated", "road_trunc.toml", iso[:iso.index("length_m") + 10].encode(), \
        "error"
    yield "road_deep_nesting", "road_deep.toml", ("[road]\na = " + "[" * 5000 + "]" * 5000
                                                  + "\n").encode(), "error"
    yield "road_csv_missing_file", "road_csvref.toml", (REPO / "roads" / "bump_csv.toml") \
        .read_text().encode(), "error"
    yield "road_crg_file_number", "road_crgref.toml", b'[road]\ntype = "crg"\nfile = 3\n', "error"
    yield "road_unknown_suffix", "road_file.txt", iso.encode(), "error"
    yield from _common_file_cases("road", "road_toml", iso, ".toml")
    # ---- road CSV
    csv = (REPO / "roads" / "bump.csv").read_text()
    rows = csv.splitlines()
    data_at = next(i for i, r in enumerate(rows) if r[:1].isdigit())
    yield "road_csv_ok", "road_bump.csv", csv.encode(), "ok"

    def csv_row(i, new):
        out = rows[:]
        out[data_at + i] = new
        return ("\n".join(out) + "\n").encode()

    for label, row in (("nan", "1.0,nan,0.0"), ("inf", "1.0,0.0,inf"), ("text", "1.0,abc,0.0"),
                       ("four_columns", "1.0,0.0,0.0,0.0"), ("one_column", "1.0"),
                       ("semicolons", "1.0;0.0;0.0"), ("unit_suffix", "1.0m,0.0,0.0"),
                       ("decreasing", "-5.0,0.0,0.0"), ("empty_field", "1.0,,0.0")):
        yield f"road_csv_{label}", "road_bad.csv", csv_row(2, row), "error"
    mm = [",".join([r.split(",")[0]] + [f"{float(v) * 1e3:g}" for v in r.split(",")[1:]])
          if r[:1].isdigit() else r for r in rows]
    yield "road_csv_millimetres", "road_mm.csv", ("\n".join(mm) + "\n").encode(), "error"
    yield "road_csv_duplicate_distance", "road_dup.csv", csv_row(2, rows[data_at + 1]), "error"
    yield "road_csv_truncated_line", "road_cut.csv", (csv.rstrip("\n") + "\n40.0,0.0")\
        .encode(), "error"
    yield "road_csv_header_only", "road_head.csv", (rows[data_at - 1] + "\n").encode(), "error"
    yield "road_csv_one_row", "road_one.csv", (rows[data_at - 1] + "\n" + rows[data_at]
                                               + "\n").encode(), "error"
    yield from _common_file_cases("road", "road_csv", csv, ".csv")
    # ---- path CSV
    pcsv = (REPO / "paths" / "sample_xy.csv").read_text()
    prow = pcsv.splitlines()
    p0 = next(i for i, r in enumerate(prow) if r[:1].isdigit())
    yield "path_csv_ok", "path_xy.csv", pcsv.encode(), "ok"

    def path_row(i, new):
        out = prow[:]
        out[p0 + i] = new
        return ("\n".join(out) + "\n").encode()

    for label, row in (("nan", "2.0,nan"), ("inf", "inf,0.0"), ("text", "2.0,zero"),
                       ("three_columns", "2.0,0.0,1.0"), ("one_column", "2.0"),
                       ("repeated_point", prow[p0 + 1]), ("turn_back", "-5.0,0.0")):
        yield f"path_csv_{label}", "path_bad.csv", path_row(2, row), "error"
    yield "path_csv_single_point", "path_one.csv", (prow[p0 - 1] + "\n" + prow[p0]
                                                    + "\n").encode(), "error"
    yield from _common_file_cases("path", "path_csv", pcsv, ".csv")
    # ---- path TOML
    straight = (REPO / "paths" / "straight_500m.toml").read_text()
    sl = (REPO / "paths" / "slalom_18m.toml").read_text()
    points = '[path]\ntype = "points"\nx_m = [0.0, 10.0, 20.0]\ny_m = [0.0, 0.0, 1.0]\n'
    yield "path_straight_ok", "path_straight.toml", straight.encode(), "ok"
    yield "path_slalom_ok", "path_slalom.toml", sl.encode(), "ok"
    yield "path_points_ok", "path_points.toml", points.encode(), "ok"
    yield from _toml_cases("path", "straight", straight, [
        ("length_m", "-500.0", "error"), ("length_m", "nan", "error"), ("ds_m", "0.0", "error"),
        ("type", '"stright"', "error"), ("length_m", '"500 m"', "error")],
        [("length_m", "lenght_m")])
    yield from _toml_cases("path", "slalom", sl, [
        ("n_cones", "0", "error"), ("n_cones", "2.5", "error"), ("cone_spacing_m", "0.0", "error"),
        ("offset_m", "-0.8", "error"), ("offset_m", "inf", "error"), ("first", '"middle"', "error"),
        ("lead_in_m", '"40"', "error")], [("cone_spacing_m", "cone_spacing"), ("first", "frist")])
    yield from _toml_cases("path", "points", points, [
        ("y_m", "[0.0, 0.0]", "error"), ("x_m", "[0.0, 0.0, 20.0]", "error"),
        ("x_m", "[0.0, nan, 20.0]", "error"), ("x_m", '["a", "b", "c"]', "error"),
        ("x_m", "[]", "error"), ("x_m", "[0.0, 10.0, 0.0]", "error")], [("x_m", "x")])
    yield "path_no_table", "path_notable.toml", straight.replace("[path]", "[paths]").encode(), \
        "error"
    yield "path_csv_missing_file", "path_ref.toml", b'[path]\ntype = "csv"\nfile = "gone.csv"\n', \
        "error"
    yield from _common_file_cases("path", "path_toml", straight, ".toml")
    # ---- driver TOML
    drv = (REPO / "paths" / "driver.toml").read_text()
    yield "driver_ok", "driver_gains.toml", drv.encode(), "ok"
    yield from _toml_cases("driver", "gains", drv, [
        ("wheelbase_m", "0.0", "error"), ("wheelbase_m", "-2.7", "error"),
        ("lookahead_base_m", "nan", "error"), ("lookahead_time_s", "-0.2", "error"),
        ("max_steer_rad", "2.0", "error"), ("max_steer_rad", "0.0", "error"),
        ("type", '"stanley"', "error"), ("kp_Nm_s_per_m", "-600.0", "error"),
        ("ki_Nm_per_m", "inf", "error"), ("drive_torque_max_Nm", "0.0", "error"),
        ("brake_torque_max_Nm", '"8000"', "error"), ("integral_band_mps", "0.0", "error"),
        ("rear_axle_offset_m", "nan", "error")],
        [("wheelbase_m", "wheelbase"), ("kp_Nm_s_per_m", "kp"), ("max_steer_rad", "max_steer")])
    # [speed] may be left out (the car's default controller); an unknown table may not
    yield "driver_no_speed_table", "driver_nospeed.toml", drv[:drv.index("[speed]")].encode(), \
        "ok"
    yield "driver_unknown_table", "driver_extra.toml", (drv + "[speeds]\nkp = 1.0\n").encode(), \
        "error"
    step = (REPO / "paths" / "driver_step_steer.toml").read_text()
    yield "driver_open_loop_ok", "driver_step.toml", step.encode(), "ok"
    olt = drv[:drv.index("[speed]")] + ('[speed]\ntype = "open_loop"\ntime_s = [0.0, 2.0, 2.3]\n'
                                        'torque_Nm = [0.0, 0.0, -2500.0]\n')
    yield "driver_open_loop_torque_ok", "driver_olt.toml", olt.encode(), "ok"
    yield from _toml_cases("driver", "olt", olt, [
        ("time_s", "[0.0, 2.0, 1.0]", "error"), ("torque_Nm", "[0.0, nan, 1.0]", "error"),
        ("torque_Nm", "[0.0, 1.0]", "error")], [("torque_Nm", "torque_N_m")])
    swd = (REPO / "paths" / "driver_sine_with_dwell.toml").read_text()
    yield "driver_sine_with_dwell_ok", "driver_swd.toml", swd.encode(), "ok"
    yield from _toml_cases("driver", "step", step, [
        ("steering_wheel_deg", "nan", "error"), ("steering_wheel_deg", '"30"', "error"),
        ("rise_time_s", "0.0", "error"), ("t_start_s", "-1.0", "error"),
        ("input", '"impulse"', "error")], [("steering_wheel_deg", "steering_deg")])
    yield from _toml_cases("driver", "swd", swd, [
        ("amplitude_deg", "-120.0", "error"), ("frequency_hz", "0.0", "error"),
        ("dwell_s", "-0.5", "error"), ("direction", '"up"', "error")], [])
    # ---- speed profiles (TOML, CSV)
    brake = (REPO / "paths" / "speed_brake_100_40.toml").read_text()
    yield "speed_ok", "speed_brake.toml", brake.encode(), "ok"
    yield from _toml_cases("speed", "brake", brake, [
        ("time_s", "[0.0, 1.5, 1.5]", "error"), ("time_s", "[1.0, 1.5, 4.833]", "error"),
        ("time_s", "[0.0, 1.5]", "error"), ("speed_kmh", "[100.0, 100.0, -40.0]", "error"),
        ("speed_kmh", "[100.0, 100.0, 400.0]", "error"),
        ("speed_kmh", "[100.0, nan, 40.0]", "error")], [("speed_kmh", "speed_mph")])
    yield "speed_both_bases", "speed_both.toml", (brake + "distance_m = [0.0, 1.0, 2.0]\n")\
        .encode(), "error"
    yield "speed_no_table", "speed_notable.toml", brake.replace(
        "[speed_profile]", "[speed]").encode(), "error"
    csv = "distance_m,speed_kmh\n0,60\n200,60\n300,100\n"
    yield "speed_csv_ok", "speed_drive.csv", csv.encode(), "ok"
    yield "speed_csv_bad_header", "speed_hdr.csv", csv.replace("speed_kmh", "v").encode(), \
        "error"
    yield "speed_csv_back", "speed_back.csv", csv.replace("300,", "100,").encode(), "error"
    yield "speed_csv_columns", "speed_cols.csv", csv.replace("200,60", "200,60,1").encode(), \
        "error"
    yield "speed_csv_from_rest", "speed_rest.csv", csv.replace("0,60", "0,0").encode(), "error"
    yield from _common_file_cases("speed", "speed", brake, ".toml")
    yield "driver_no_steering_table", "driver_nosteer.toml", drv.replace(
        "[steering]", "[steer]").encode(), "error"
    yield from _common_file_cases("driver", "driver", drv, ".toml")
