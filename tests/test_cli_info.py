"""``flexpipe info`` on a mesh: the counts it prints are those of the file itself."""

import re
from pathlib import Path

import pytest

from flexpipe.cli import main

BRACKET = Path(__file__).resolve().parents[1] / "meshes" / "bracket.bdf"


def test_info_mesh_counts_match_the_deck(capsys):
    text = BRACKET.read_text()
    n_grid = len(re.findall(r"^GRID", text, flags=re.M))
    n_quad = len(re.findall(r"^CQUAD4", text, flags=re.M))
    assert main(["info", str(BRACKET)]) in (0, None)
    out = capsys.readouterr().out
    assert f"{n_grid} nodes" in out
    assert re.search(rf"quad\s+{n_quad} elements", out)


def test_info_missing_body_is_a_one_line_error(capsys, tmp_path):
    assert main(["info", str(tmp_path / "nope.npz")]) == 2
    err = capsys.readouterr().err
    assert "nope.npz" in err and "Traceback" not in err


def test_info_on_a_cut_deck_is_a_one_line_error(capsys, tmp_path):
    p = tmp_path / "cut.bdf"
    p.write_bytes(BRACKET.read_bytes()[:2000])
    assert main(["info", str(p)]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err
    assert "cut.bdf, line 41: GRID* 20" in err and "cut short" in err


def test_info_text_of_an_empty_mesh():
    import numpy as np

    from flexpipe.cli.info import mesh_text
    from flexpipe.mesh import Mesh

    text = mesh_text(Mesh(points=np.zeros((0, 3)), blocks=(), source="empty.msh"))
    assert text.startswith("empty.msh: 0 nodes") and "empty mesh" in text


def test_info_warns_about_a_missing_property(capsys, tmp_path):
    p = tmp_path / "pid7.bdf"
    p.write_text(BRACKET.read_text().replace(f"{'CQUAD4':<8}{1:>8}{1:>8}",
                                             f"{'CQUAD4':<8}{1:>8}{7:>8}"))
    assert main(["info", str(p)]) in (0, None)
    cap = capsys.readouterr()
    assert "PID7" in cap.out
    assert "element 1 (CQUAD4" in cap.err and "PID 7" in cap.err and "PSHELL" in cap.err


def test_info_reads_a_deck_in_its_units(capsys, tmp_path):
    text = BRACKET.read_text()
    mm = tmp_path / "mm.bdf"     # an mm-t-s material: read with --units
    mm.write_text(text.replace("210000000000.0", "      210000.0").replace(
        f"{'*':<8}{'7850.0':>16}", f"{'*':<8}{'7.85e-09':>16}"))
    assert main(["info", str(mm)]) == 2
    assert "units='mm-t-s'" in capsys.readouterr().err
    assert main(["info", str(mm), "--units", "mm-t-s"]) in (0, None)
    assert "rho=7850" in capsys.readouterr().out


ROOT = BRACKET.parents[1]


def test_info_describes_a_road_file(capsys):
    """``flexpipe info roads/iso_c_200m.toml``: a road, with its length, samples, track
    width and track heights (those of the road the runs load), not a car error.  The RMS
    is that of the profile the car drives (linear between samples) over the length: the
    reference integrates it numerically on a grid ten times finer than the samples."""
    import numpy as np

    from flexpipe.roads import load_road

    road = load_road(ROOT / "roads" / "iso_c_200m.toml")
    assert main(["info", str(ROOT / "roads" / "iso_c_200m.toml")]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"{ROOT / 'roads' / 'iso_c_200m.toml'}: road iso8608")
    assert f"{road.length:.6g} m long" in out
    assert f"{road.x.size} samples, uniform, every 0.05 m" in out
    assert "track width 1.5 m" in out and "road_class = 'C'" in out
    xf = np.linspace(road.x[0], road.x[-1], 10 * (road.x.size - 1) + 1)
    zf = np.interp(xf, road.x, road.left)
    mean = np.trapezoid(zf, xf) / road.length
    rms = np.sqrt(np.trapezoid((zf - mean) ** 2, xf) / road.length)
    got = float(re.search(r"left track height \(mm\):.*RMS about the mean ([0-9.]+)",
                          out).group(1))
    assert got == pytest.approx(1e3 * rms, abs=0.006)


def test_info_describes_a_path_file(capsys):
    from flexpipe.driver import read_path

    path = read_path(ROOT / "paths" / "slalom_18m.toml")
    assert main(["info", str(ROOT / "paths" / "slalom_18m.toml")]) == 0
    out = capsys.readouterr().out
    assert ": path slalom(" in out and f"{path.s[-1]:.6g} m long" in out
    assert f"y {path.y.min():.4g} .. {path.y.max():.4g} m" in out


def test_info_describes_a_driver_file(capsys):
    """The gains and the neuromuscular lag as the file gives them."""
    from flexpipe.roads._tables import read_toml

    f = ROOT / "paths" / "driver.toml"
    raw = read_toml(f)
    assert main(["info", str(f)]) == 0
    out = capsys.readouterr().out
    st, sp = raw["steering"], raw["speed"]
    assert f"preview {st['lookahead_base_m']:g} m + {st['lookahead_time_s']:g} s x speed" in out
    assert f"kp {sp['kp_Nm_s_per_m']:.4g} N m s/m, ki {sp['ki_Nm_per_m']:.4g} N m/m" in out
    assert out.count(f"neuromuscular lag {st['neuromuscular_lag_s']:g} s") == 2


@pytest.mark.parametrize("name, words", [
    ("sweeps/sample.toml", ["is a sweep file", "flexpipe sweep"]),
    ("cars/halfcar_paper.toml", ["is a half-car parameter file"]),
    ("other.toml", ["not a car, road or path file", "['x']"]),
])
def test_info_on_another_toml_file_says_what_it_is(capsys, tmp_path, name, words):
    """A TOML file info does not describe is a one-line error naming the file, what it
    is and what info takes, not "missing required key 'car'"."""
    (tmp_path / "other.toml").write_text("x = 1\n")
    path = tmp_path / name if name == "other.toml" else ROOT / name
    assert main(["info", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"flexpipe info: error: {path}: ") and "\n" not in err
    for w in [*words, "flexpipe info takes", ".npz", "[car]", "[road]", "[path]", ".bdf"]:
        assert w in err, err
    assert "missing required key" not in err


def test_info_on_a_list_design_sweep_says_it_is_a_sweep(capsys, tmp_path):
    """Finding: a list-design sweep ([sweep] design = "list", [road], [[runs]], no
    [parameters]) was taken for a road file ("key 'runs': expected a single [road]
    table"); any file with a [sweep] table is a sweep."""
    path = tmp_path / "list_sweep.toml"
    path.write_text(f"""[sweep]
car = "{(ROOT / 'cars' / 'sedan.toml').as_posix()}"
design = "list"

[road]
type = "iso8608"
road_class = "C"

[[runs]]
speed_kmh = 50.0

[[runs]]
speed_kmh = 80.0
""")
    assert main(["info", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"flexpipe info: error: {path}: ") and "\n" not in err
    assert "is a sweep file" in err and "flexpipe sweep" in err, err
    assert "expected a single [road] table" not in err


def test_info_help_lists_every_kind_of_file_it_takes(capsys):
    """``info`` takes a reduced body, a car, road or path file and a mesh; its help says
    so (and that --vtu and --mac-size are for reduced bodies)."""
    assert main(["info", "--help"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "reduced body" in out and ".npz" in out and "(FlexBody files)" in out
    assert "car file (.toml" in out and "road" in out and ".crg" in out and "path" in out
    for suffix in (".msh", ".inp", ".bdf", ".vtu"):
        assert suffix in out


TIR = Path(__file__).resolve().parents[1] / "tires" / "sedan_205_55R16.tir"


def _tir_numbers(path):
    """Raw keys of a .tir file (key = value lines), read here without flexpipe."""
    out = {}
    for line in Path(path).read_text().splitlines():
        line = line.split("$", 1)[0]
        if "=" in line:
            k, v = (t.strip() for t in line.split("=", 1))
            try:
                out[k.upper()] = float(v)
            except ValueError:
                pass
    return out


def test_info_tir_prints_the_magic_formula_at_the_nominal_load(capsys):
    """At Fz = FNOMIN (dfz = 0, no camber) PAC2002 gives mu_y = PDY1 LMUY, mu_x = PDX1 LMUX
    and a cornering stiffness PKY1 FNOMIN sin(2 atan(1/PKY2)) LKY (the MF 5.2 formulas);
    the loaded radius is within 1 mm of R0 - FNOMIN / Kz."""
    import math

    k = _tir_numbers(TIR)
    assert main(["info", str(TIR)]) == 0
    out = capsys.readouterr().out
    mux = float(re.search(r"mu_x ([0-9.]+)", out).group(1))
    muy = float(re.search(r"mu_y ([0-9.]+)", out).group(1))
    ky = float(re.search(r"cornering stiffness ([0-9.e+]+) N/deg", out).group(1))
    r = float(re.search(r"loaded radius at FNOMIN ([0-9.]+) mm", out).group(1))
    assert mux == pytest.approx(k["PDX1"] * k.get("LMUX", 1.0), abs=5e-4)
    assert muy == pytest.approx(k["PDY1"] * k.get("LMUY", 1.0), abs=5e-4)
    want = (k["PKY1"] * k["FNOMIN"] * math.sin(2 * math.atan(1 / k["PKY2"]))
            * k.get("LKY", 1.0) * math.pi / 180)
    assert ky == pytest.approx(abs(want), rel=1e-3)
    linear = 1e3 * (k["UNLOADED_RADIUS"] - k["FNOMIN"] / k["VERTICAL_STIFFNESS"])
    assert abs(r - linear) < 1.0 and r < 1e3 * k["UNLOADED_RADIUS"]


def test_info_csv_road_and_path(capsys, tmp_path):
    road = tmp_path / "road.csv"
    road.write_text("distance_m,left_m,right_m\n0,0,0\n10,0.01,0.02\n20,0,0\n")
    assert main(["info", str(road)]) == 0
    out = capsys.readouterr().out
    assert "20 m long" in out and "max 20.00" in out
    path = tmp_path / "path.csv"
    path.write_text("x_m,y_m\n0,0\n10,0\n20,5\n30,5\n")
    assert main(["info", str(path)]) == 0
    length = 10.0 + (10.0 ** 2 + 5.0 ** 2) ** 0.5 + 10.0  # the three segments
    out = capsys.readouterr().out
    assert ": path " in out and f"{length:.6g} m long, 4 points" in out
    bad = tmp_path / "bad.csv"
    bad.write_text("distance_m,left_m,right_m\n0,0,0\n0,0,0\n")
    assert main(["info", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "bad.csv" in err and "Traceback" not in err


def test_info_warns_of_what_run_would_refuse(capsys, tmp_path):
    """A prismatic car whose wheel-centre height is off its tyre's loaded radius: info
    still describes it, with the run's error as a warning."""
    root = Path(__file__).resolve().parents[1]
    text = (root / "cars" / "sedan.toml").read_text().replace('"../', f'"{root}/')
    car = tmp_path / "car.toml"
    car.write_text(text.replace("wheel_center_m = [0.0, 0.775, 0.2983]",
                                "wheel_center_m = [0.0, 0.775, 0.33]"))
    assert main(["info", str(car)]) == 0
    cap = capsys.readouterr()
    assert "static wheel loads" in cap.out
    assert "warning: flexpipe run refuses this car" in cap.err
    assert "corners.fl.wheel_center_m z = 0.3300 m" in cap.err
    assert main(["info", str(root / "cars" / "sedan.toml")]) == 0
    assert "warning" not in capsys.readouterr().err


def test_info_sample_path_csv_behind_a_comment_is_a_path(capsys):
    """paths/sample_xy.csv starts with a '#' comment: the header on the next line tells
    the path (it was read as a road and failed).  Length from the file's points by hand."""
    import numpy as np

    root = Path(__file__).resolve().parents[1]
    sample = root / "paths" / "sample_xy.csv"
    xy = np.loadtxt(sample, delimiter=",", comments="#", skiprows=2)
    length = float(np.hypot(*np.diff(xy, axis=0).T).sum())
    assert main(["info", str(sample)]) == 0
    out = capsys.readouterr().out
    assert ": path " in out and f"{length:.6g} m long, {len(xy)} points" in out


@pytest.mark.parametrize("text, kind, words", [
    ("# lane change\nx_m,y_m\n0,0\n10,0\n20,1.75\n30,3.5\n40,3.5\n", "path",
     ["y 0 .. 3.5 m", "5 points"]),
    ("y_m,x_m\n0,0\n0,10\n3.5,20\n", "path", ["y 0 .. 3.5 m", "to (20, 3.5) m"]),
    ("0,0\n10,0\n10,5\n5,8\n", "path", ["4 points"]),             # x goes back: no road
    ("0,0,0\n10,0.01,0.02\n20,0,0\n", "road", ["20 m long", "max 20.00"]),
    ("distance_mm,height_mm\n0,0\n10000,20\n20000,0\n", "road", ["20 m long", "max 20.00"]),
])
def test_info_csv_is_told_by_header_or_by_what_it_can_be(capsys, tmp_path, text, kind, words):
    f = tmp_path / "f.csv"
    f.write_text(text)
    assert main(["info", str(f)]) == 0
    out = capsys.readouterr().out
    assert f": {kind} " in out, out
    for w in words:
        assert w in out, out


def test_info_csv_that_can_be_road_or_path_asks_for_a_header(capsys, tmp_path):
    f = tmp_path / "two.csv"
    f.write_text("0,0\n10,0\n20,1.75\n30,3.5\n")
    assert main(["info", str(f)]) == 2
    err = capsys.readouterr().err
    assert "two.csv, line 1" in err and "road (distance, height) or a path (x, y)" in err
    assert "'x_m,y_m'" in err and "Traceback" not in err


def test_info_tir_without_width_and_warnings_once(capsys, tmp_path):
    """A .tir without [DIMENSION] WIDTH (runs accept it) is described, 'width not given';
    the file is read once, so its ANGLE = 'deg' warning shows once."""
    import warnings

    lines = TIR.read_text().splitlines()
    no_width = tmp_path / "no_width.tir"
    no_width.write_text("\n".join(t for t in lines if not t.startswith("WIDTH ")) + "\n")
    assert main(["info", str(no_width)]) == 0
    out = capsys.readouterr().out
    r0 = _tir_numbers(TIR)["UNLOADED_RADIUS"]
    assert "width not given" in out and f"unloaded radius {r0 * 1e3:.1f} mm" in out
    deg = tmp_path / "deg.tir"
    deg.write_text("\n".join(t.replace("'radian'", "'deg'") if t.startswith("ANGLE ") else t
                             for t in lines) + "\n")
    with warnings.catch_warnings():
        warnings.simplefilter("always")      # (each warning call shows, none is merged)
        assert main(["info", str(deg)]) == 0
    cap = capsys.readouterr()
    assert sum("ANGLE" in t for t in cap.err.splitlines()) == 1, cap.err
    assert f"width {_tir_numbers(TIR)['WIDTH'] * 1e3:.0f} mm" in cap.out
