"""``flexpipe`` command line: the ``modes`` command against rod theory, error handling
(one line, exit code 2) and the lazy subcommand registry."""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import meshio
import numpy as np
import pytest

from flexpipe import cli
from flexpipe.mesh import write_mesh
from flexpipe.mesh.generate import box, plate

E, RHO, L = 210e9, 7850.0, 1.0


@pytest.fixture(scope="module")
def bar(tmp_path_factory):
    """A 1 m x 0.1 m x 0.1 m tet4 bar as a Gmsh file (face node sets xmin, xmax, ...)."""
    p = tmp_path_factory.mktemp("bar") / "bar.msh"
    write_mesh(box(L, 0.1, 0.1, 20, 2, 2), p)
    return p


def _table(out: str) -> np.ndarray:
    rows = [ln.split() for ln in out.splitlines()]
    return np.array([float(r[1]) for r in rows if len(r) == 2 and r[0].isdigit()])


def test_modes_axial_mode_of_clamped_rod(bar, tmp_path, capsys):
    out = tmp_path / "modes"
    code = cli.main(["modes", str(bar), "--material", "steel", "--nu", "0", "--n", "10",
                     "--fixed", "xmin", "-o", str(out), "-q"])
    assert code == 0
    printed = _table(capsys.readouterr().out)
    m = meshio.read(out / "modes.vtu")
    f = m.field_data["frequency_hz"]
    np.testing.assert_allclose(printed, f, rtol=1e-5)       # table shows 6 digits
    assert len(f) == 10 and np.all(np.diff(f) >= 0) and f[0] > 1.0   # clamped: no rigid modes
    fixed = np.isclose(m.points[:, 0], 0.0)
    x_share = []
    for k in range(10):
        u = m.point_data[f"mode_{k + 1:02d}"]
        assert np.abs(u[fixed]).max() == 0.0                  # clamped face does not move
        x_share.append(np.sum(u[:, 0] ** 2) / np.sum(u**2))
    axial = int(np.argmax(x_share))
    assert x_share[axial] > 0.99
    # nu = 0: the first axial mode of a clamped-free rod, f = c / (4 L), c = sqrt(E / rho)
    assert f[axial] == pytest.approx(np.sqrt(E / RHO) / (4 * L), rel=5e-3)
    csv = np.loadtxt(out / "frequencies.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(csv[:, 1], f, rtol=1e-9)


def test_modes_free_body_has_six_rigid_modes(bar, tmp_path, capsys):
    out = tmp_path / "free"
    assert cli.main(["modes", str(bar), "--E", "70e9", "--nu", "0.33", "--rho", "2700",
                     "--n", "8", "-o", str(out), "-q", "--per-mode"]) == 0
    f = _table(capsys.readouterr().out)
    assert np.all(f[:6] < 1e-3 * f[6]) and f[6] > 100.0
    one = meshio.read(out / "mode_07.vtu")
    assert one.field_data["frequency_hz"][0] == pytest.approx(f[6], rel=1e-5)
    assert one.point_data["displacement"].shape == (one.points.shape[0], 3)


def test_modes_shell_mesh_with_thickness(tmp_path, capsys):
    p = tmp_path / "plate.msh"
    write_mesh(plate(0.4, 0.3, 8, 6), p)
    assert cli.main(["modes", str(p), "--material", "steel", "--thickness", "0.002",
                     "--n", "7", "--fixed", "xmin", "-o", str(tmp_path / "o"), "-q"]) == 0
    f = _table(capsys.readouterr().out)
    # cantilever plate strip, first bending: f = 1.875^2 / (2 pi L^2) sqrt(D / (rho t))
    D = E * 0.002**3 / (12 * (1 - 0.3**2))
    f_ref = 1.875104**2 / (2 * np.pi * 0.4**2) * np.sqrt(D / (RHO * 0.002))
    assert f[0] == pytest.approx(f_ref, rel=0.03)
    m = meshio.read(tmp_path / "o" / "modes.vtu")
    assert "mode_01_rotation" in m.point_data


@pytest.mark.parametrize("args,expect", [
    (["missing.msh", "--material", "steel"], "missing.msh: file not found"),
    (["{bar}"], "no material in the file"),
    (["{bar}", "--material", "steel", "--fixed", "nowhere"], "no node set or cell set 'nowhere'"),
    (["{bar}", "--material", "unobtainium"], "unknown material 'unobtainium'"),
    (["{bar}", "--E", "1e9"], "missing --nu, --rho"),
    (["{plate}", "--material", "steel"], "plate.msh: 48 shell (quad) element(s) have no"),
])
def test_errors_are_one_line_with_exit_code_2(bar, tmp_path, capsys, monkeypatch, args, expect):
    monkeypatch.chdir(tmp_path)
    write_mesh(plate(0.4, 0.3, 8, 6), tmp_path / "plate.msh")
    argv = ["modes"] + [a.format(bar=bar, plate=tmp_path / "plate.msh") for a in args] + ["-q"]
    assert cli.main(argv) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("flexpipe modes: error: ")
    assert expect in err[0]


def test_console_entry_point_without_traceback(tmp_path):
    r = subprocess.run([sys.executable, "-m", "flexpipe.cli", "modes", str(tmp_path / "x.bdf")],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 2
    assert "Traceback" not in r.stderr and "x.bdf: file not found" in r.stderr
    r = subprocess.run([sys.executable, "-m", "flexpipe.cli", "--help"], capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0 and "modes" in r.stdout


def test_registry_loads_commands_lazily(tmp_path, monkeypatch, capsys):
    (tmp_path / "fp_echo_cmd.py").write_text(textwrap.dedent("""
        def add_arguments(p):
            p.add_argument("--times", type=int, default=1)

        def run(args):
            print("echo " * args.times)
            return 3
    """))
    monkeypatch.syspath_prepend(str(tmp_path))
    monkeypatch.setattr(cli, "COMMANDS", cli.COMMANDS + (
        ("echo", "fp_echo_cmd", "test command"), ("ghost", "fp_not_installed", "absent")))
    assert cli.main(["--help"]) == 0
    listing = capsys.readouterr().out
    assert "echo" in listing and "ghost" not in listing
    assert "fp_echo_cmd" not in sys.modules            # --help did not import it
    assert cli.main(["echo", "--times", "2"]) == 3
    assert capsys.readouterr().out.split() == ["echo", "echo"]
    assert cli.main(["ghost"]) == 2                     # unknown command: argparse error


def test_a_reader_that_closes_the_pipe_is_no_error(tmp_path):
    """``flexpipe info ... | head -1``: when the reader leaves, the command stops quietly
    with the shell's code for SIGPIPE (141), not with an "error: Broken pipe" line."""
    (tmp_path / "fp_chatty_cmd.py").write_text(textwrap.dedent("""
        def add_arguments(p):
            pass

        def run(args):
            for i in range(200000):
                print("line", i)
    """))
    script = textwrap.dedent(f"""
        import sys
        sys.path.insert(0, {str(tmp_path)!r})
        from flexpipe import cli
        cli.COMMANDS = cli.COMMANDS + (("chatty", "fp_chatty_cmd", "many lines"),)
        raise SystemExit(cli.main(["chatty"]))
    """)
    p = subprocess.Popen([sys.executable, "-c", script], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    assert p.stdout.readline() == "line 0\n"
    p.stdout.close()                                     # the reader leaves
    err = p.stderr.read()
    assert p.wait(timeout=120) == cli.EXIT_BROKEN_PIPE
    assert err == ""


SAMPLES = Path(__file__).resolve().parents[1] / "meshes"


def test_acceptance_command_on_the_sample_plate(tmp_path, capsys):
    """``flexpipe modes meshes/plate_quad.msh --material steel --thickness 0.002 --n 20``:
    the table, progress messages on stderr, and a .vtu that meshio reads back with one
    translation and one rotation array per mode; the six ~0 Hz modes written are rigid
    motions (u = t + theta x X, rotations = theta) and the printed mass is rho a b t."""
    out = tmp_path / "plate"
    assert cli.main(["modes", str(SAMPLES / "plate_quad.msh"), "--material", "steel",
                     "--thickness", "0.002", "--n", "20", "-o", str(out)]) == 0
    cap = capsys.readouterr()
    for step in ("reading", "assembling", "solving for 20 modes"):
        assert step in cap.err
    assert cap.err.count("done in") == 3
    f = _table(cap.out)
    assert len(f) == 20 and np.all(f[:6] < 1e-4 * f[6]) and f[6] > 1.0
    mass = float(cap.out.split("mass ")[1].split()[0])
    assert mass == pytest.approx(RHO * 0.4 * 0.3 * 0.002, rel=1e-5)    # 6 digits printed
    m = meshio.read(out / "modes.vtu")
    modes = sorted(k for k in m.point_data if k.startswith("mode_"))
    assert modes == sorted([f"mode_{k:02d}" for k in range(1, 21)]
                           + [f"mode_{k:02d}_rotation" for k in range(1, 21)])
    assert set(m.point_data) - set(modes) == {"node_id"}       # file node ids (Gmsh tags)
    assert m.point_data["node_id"].ravel().tolist() == list(range(1, 64))
    assert all(m.point_data[k].shape == (63, 3) for k in modes)
    assert m.cells_dict["quad"].shape == (48, 4)
    np.testing.assert_allclose(m.field_data["frequency_hz"], f, rtol=1e-5)
    X = m.points
    for k in range(1, 7):
        u, rot = m.point_data[f"mode_{k:02d}"], m.point_data[f"mode_{k:02d}_rotation"]
        theta = rot.mean(axis=0)
        assert np.abs(rot - theta).max() < 1e-6 * np.abs(u).max()
        t = (u - np.cross(theta, X)).mean(axis=0)
        assert np.abs(u - t - np.cross(theta, X)).max() < 1e-6 * np.abs(u).max()


def test_corrupt_mesh_is_a_one_line_error(tmp_path, capsys):
    bad = tmp_path / "broken.vtu"
    bad.write_text("<VTKFile type='UnstructuredGrid'")
    assert cli.main(["modes", str(bad), "--material", "steel", "-q"]) == 2
    cap = capsys.readouterr()
    err = cap.err.strip().splitlines()
    assert len(err) == 1 and "broken.vtu, line 1: not well-formed XML" in err[0]
    assert cap.out == ""


def test_modes_names_the_missing_property_card(tmp_path, capsys):
    text = (SAMPLES / "bracket.bdf").read_text().replace(f"{'CQUAD4':<8}{1:>8}{1:>8}",
                                                         f"{'CQUAD4':<8}{1:>8}{7:>8}")
    p = tmp_path / "pid7.bdf"
    p.write_text(text)
    assert cli.main(["modes", str(p), "-q", "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err and not (tmp_path / "out").exists()
    (line,) = [ln for ln in err.splitlines() if "error:" in ln]
    assert "pid7.bdf" in line and "element 1 (CQUAD4" in line and "PID 7" in line
    assert "PSHELL" in line and "property ids defined: 1, 2" in line


def _never(*a, **k):
    raise AssertionError("the analysis ran before the output path was checked")


@pytest.mark.parametrize("argv, patched, words", [
    (["modes", "{mesh}", "--material", "steel", "-o", "{file}", "-q"],
     "flexpipe.mesh.read_mesh", ["'-o'", "takes a folder"]),
    (["modes", "{mesh}", "--material", "steel", "-o", "{file}/sub", "-q"],
     "flexpipe.mesh.read_mesh", ["'-o'", "is a file"]),
    (["kc", "{car}", "-o", "{file}"], "flexpipe.vehicle.suspension.kc.kc",
     ["'-o'", "takes a folder"]),
    (["linear", "{car}", "-o", "{file}"], "flexpipe.vehicle.linear.linear_modes",
     ["'-o'", "takes a folder"]),
    (["reduce", "{mesh}", "--interfaces", "x.toml", "-o", "{dir}.npz"],
     "flexpipe.mesh.read_mesh", ["'-o'", "takes a file name"]),
    (["reduce", "{mesh}", "--interfaces", "x.toml", "-o", "b.npz", "--vtu", "{file}/m.vtu"],
     "flexpipe.mesh.read_mesh", ["'--vtu'", "is a file"]),
    (["info", "body.npz", "--vtu", "{file}/m.vtu"], "flexpipe.reduction.load_body",
     ["'--vtu'", "is a file"]),
    (["animate", "{dir}", "--dest", "{file}"], "flexpipe.durability.pipeline.animate_outputs",
     ["'--dest'", "takes a folder"]),
    (["run", "{car}", "--speed", "10", "--check-step", "--out", "{file}"],
     "flexpipe.vehicle.convergence.check_step", ["'--out'", "takes a folder"]),
    (["run", "{car}", "--speed", "10", "--out", "{file}"],
     "flexpipe.vehicle.simulation.simulate", ["'--out'", "takes a folder"]),
])
def test_output_paths_are_checked_before_the_analysis(tmp_path, capsys, monkeypatch, argv,
                                                      patched, words):
    """An output path that cannot be written (a file where a folder is needed, a folder
    where a file is needed, a file on the way) is a one-line error naming the option,
    given before any analysis runs (the analysis is replaced by one that fails)."""
    import importlib

    monkeypatch.chdir(tmp_path)
    module, name = patched.rsplit(".", 1)  # the module, also where a package re-exports
    monkeypatch.setattr(importlib.import_module(module), name, _never)  # a same-named name
    (tmp_path / "taken").write_text("")
    (tmp_path / "dir.npz").mkdir()
    root = Path(__file__).resolve().parents[1]
    fill = {"mesh": str(root / "meshes" / "bracket.bdf"), "file": str(tmp_path / "taken"),
            "dir": str(tmp_path / "dir"), "car": str(root / "cars" / "sedan_linkage.toml")}
    assert cli.main([a.format(**fill) for a in argv]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"flexpipe {argv[0]}: error: ")
    assert str(tmp_path / "taken") in err[0] or str(tmp_path / "dir") in err[0]
    for w in words:
        assert w in err[0], err[0]
