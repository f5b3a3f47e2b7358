"""Durability on the sample car: recorded body motion, ``make straight`` outputs (hot spots,
animation folder), ``flexpipe animate`` frames checked with meshio against the hardpoint
motion, ``flexpipe stress``, equivalent stresses against NumPy eigenvalues."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import meshio
import numpy as np
import pytest

from flexpipe.cli import main
from flexpipe.durability.recover import plane_equivalent, solid_equivalent

ROOT = Path(__file__).resolve().parents[1]
T_END = 0.2


@pytest.fixture(scope="module")
def straight(tmp_path_factory):
    """The straight scenario of ``make straight``, shortened to 0.2 s."""
    from flexpipe.scenarios.runner import run_scenario

    d = tmp_path_factory.mktemp("straight")
    mp = pytest.MonkeyPatch()
    mp.setenv("FLEXPIPE_CACHE", str(d / "cache"))
    out = d / "out"
    summary = run_scenario("straight", out=out, t_end=T_END, log=lambda *a: None)
    yield out, summary
    mp.undo()


def _csv(path):
    header = path.read_text().splitlines()[0].split(",")
    values = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {h.split(" [")[0]: values[:, i] for i, h in enumerate(header)}, header


def test_straight_run_writes_hotspots_and_animation(straight):
    out, summary = straight
    assert summary["status"] == 0
    for name in ("hotspots.csv", "stress_max.vtu", "stress_max.png", "stress_histories.csv"):
        assert (out / "stress" / name).is_file()
    assert (out / "animation" / "animation.pvd").is_file()
    assert (out / "animation" / "preview.png").read_bytes()[:4] == b"\x89PNG"
    desc = summary["file_descriptions"]
    for name in ("flexible.csv", "motion_flexible.npz", "stress/hotspots.csv",
                 "animation/body.pvd", "summary.json"):
        assert name in desc and desc[name]
    # each run's ride comfort and tyre loads (closed forms: tests/test_scenario_comfort.py)
    assert set(summary["ride_comfort"]) == set(summary["dynamic_load_coefficient"]) \
        == set(summary["cpu_time_s"])
    on_disk = json.loads((out / "summary.json").read_text())
    assert on_disk["file_descriptions"] == desc
    text = (out / "stress" / "hotspots.csv").read_text().splitlines()
    header = text[0].split(",")
    for col in ("element_id", "location", "max_von_mises [MPa]", "time_of_max [s]",
                "damage [-]", "damage_per_km [1/km]", "most_correlated_channel",
                "rank_damage"):
        assert col in header
    first = dict(zip(header, text[1].split(","), strict=True))
    assert first["rank_von_mises"] == "1"
    assert first["most_correlated_channel"].startswith(("hub_", "tire_"))
    assert 0.0 <= float(first["time_of_max [s]"]) <= T_END + 1e-9


def test_animate_frames_match_output_steps_nodes_and_hardpoint_motion(straight, tmp_path):
    from flexpipe.durability.rundir import load_run

    out, _ = straight
    dest = tmp_path / "anim"
    assert main(["animate", str(out), "--dest", str(dest)]) == 0
    run = load_run(out)
    body = run.body()
    ch, _ = _csv(out / "flexible.csv")
    steps = len(ch["t"])
    frames = ET.parse(dest / "body.pvd").getroot().findall("./Collection/DataSet")
    assert len(frames) == steps
    times = np.array([float(f.get("timestep")) for f in frames])
    np.testing.assert_allclose(times, ch["t"], atol=1e-9)
    hp, _ = _csv(out / "hardpoints.csv")
    checked = 0
    for k in (1, steps // 2, steps - 1):
        m = meshio.read(dest / frames[k].get("file"))
        assert len(m.points) == body.n_nodes
        assert sum(len(c) for c in m.cell_data["von_mises [Pa]"]) == body.stress.n_elements
        d = m.point_data["elastic_displacement [m]"]
        R = run.motion.rotation[k]
        # the frame's origin placement agrees with the body channels of the CSV
        x0 = m.points - d - body.nodes @ R.T
        np.testing.assert_allclose(x0, np.broadcast_to([ch["x"][k], ch["y"][k], ch["z"][k]],
                                                       x0.shape), atol=2e-4)
        for itf in body.interfaces:
            u = np.array([hp[f"hardpoint_{itf.name}_u{a}"][k] for a in "xyz"])
            th = np.array([hp[f"hardpoint_{itf.name}_r{a}"][k] for a in "xyz"])
            r = (body.nodes[itf.nodes] - itf.point) @ R.T
            want = u + np.cross(th, r)  # the rigid spider: u_s = u_h + theta_h x r
            np.testing.assert_allclose(d[itf.nodes], want, rtol=0, atol=1e-6)
            assert np.abs(want).max() > 1e-6  # the interface does move
            checked += 1
    assert checked == 3 * len(body.interfaces) >= 12  # every mount, three frames


def test_stress_command_and_result_motion(straight, capsys):
    out, _ = straight
    assert main(["stress", str(out), "--top", "5", "--no-fatigue"]) == 0
    text = (out / "stress" / "hotspots.csv").read_text().splitlines()
    assert len(text) == 6  # header + 5 hot spots (no damage ranking)
    assert "stress:" in capsys.readouterr().out or True


def test_stress_command_errors_in_one_line(tmp_path, capsys):
    (tmp_path / "summary.json").write_text("{}")
    assert main(["stress", str(tmp_path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("flexpipe stress: error:") and "motion_flexible.npz" in err


def test_equivalent_stresses_against_eigenvalues():
    rng = np.random.default_rng(4)
    s = rng.normal(size=(6, 200)) * 1e8
    vm, sp = solid_equivalent(s)
    T = np.zeros((200, 3, 3))
    for (i, j), k in zip([(0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1)], range(6),
                         strict=True):
        T[:, i, j] = T[:, j, i] = s[k]
    p = np.linalg.eigvalsh(T)
    vm_ref = np.sqrt(0.5 * ((p[:, 0] - p[:, 1]) ** 2 + (p[:, 1] - p[:, 2]) ** 2
                            + (p[:, 2] - p[:, 0]) ** 2))
    sp_ref = np.where(np.abs(p[:, 2]) >= np.abs(p[:, 0]), p[:, 2], p[:, 0])
    np.testing.assert_allclose(vm, vm_ref, rtol=1e-9)
    np.testing.assert_allclose(sp, sp_ref, rtol=1e-7, atol=1e-3)
    T2 = T.copy()
    T2[:, 2, :] = T2[:, :, 2] = 0.0
    vm2, sp2 = plane_equivalent(T2[:, 0, 0], T2[:, 1, 1], T2[:, 0, 1])
    vm2_ref, sp2_ref = solid_equivalent(np.stack([T2[:, 0, 0], T2[:, 1, 1], T2[:, 2, 2],
                                                  T2[:, 1, 2], T2[:, 0, 2], T2[:, 0, 1]]))
    np.testing.assert_allclose(vm2, vm2_ref, rtol=1e-9)
    np.testing.assert_allclose(sp2, sp2_ref, rtol=1e-7, atol=1e-3)


def test_readme_durability_example_runs(straight, capsys):
    import re

    text = (ROOT / "README.md").read_text()
    block = re.search(r"## Durability.*?```python\n(.*?)```", text, flags=re.S).group(1)
    out, _ = straight
    block = block.replace('"out/straight"', repr(str(out)))
    exec(compile(block, "README.md", "exec"), {})
    printed = capsys.readouterr().out.split()
    hot = (out / "stress" / "hotspots.csv").read_text().splitlines()[1].split(",")
    assert printed[0] == hot[2]  # the same top element as the hot-spot table


def test_recovery_of_a_single_mode_sine_equals_closed_form():
    """q = a cos(2 pi f t) in one mode: max von Mises = |a| vm(mode), Miner damage of
    n cycles of signed von Mises with amplitude |a| vm(mode) (Basquin closed form)."""
    import flexpipe as fp
    from flexpipe.durability.fatigue import FatigueMaterial
    from flexpipe.durability.recover import equivalents, recover_stress
    from flexpipe.mesh.generate import plate
    from flexpipe.vehicle.result import BodyMotion

    fe = fp.assemble(plate(0.4, 0.2, 8, 4), fp.Material(210e9, 0.3, 7850.0), thickness=0.002)
    body = fp.reduce(fe, [fp.Interface((0.0, 0.1, 0.0), radius=0.05, name="a")], n_modes=3,
                     stress="all")
    k, a, cycles = 2, 1.5e-3, 20
    t = np.linspace(0.0, 1.0, 40 * cycles + 1)
    q = np.zeros((len(t), body.n_elastic))
    q[:, k] = a * np.cos(2 * np.pi * cycles * t)
    n = len(t)
    motion = BodyMotion(t, q, np.column_stack([10 * t, np.zeros(n), np.zeros(n)]),
                        np.broadcast_to(np.eye(3), (n, 3, 3)), body.n_rigid + np.arange(
                            body.n_elastic))
    mat = FatigueMaterial(sigma_f=1e9, b=-0.1)
    sr = recover_stress(motion, body, fatigue=mat)
    # the stored (single-precision) stress mode, evaluated in double precision
    vm_mode, _ = equivalents("shell", body.stress.blocks[0].modes[:, :, k:k + 1].astype(float))
    amp = a * vm_mode[:, :, 0].max(axis=1)
    np.testing.assert_allclose(sr.max_von_mises, amp, rtol=1e-12)
    assert set(np.round(sr.time_of_max * cycles, 9)) <= set(np.arange(cycles + 1.0))
    counted = np.isfinite(sr.damage)  # elements whose damage bound is not negligible
    assert counted[amp >= 0.3 * amp.max()].all()
    N = 0.5 * (amp[counted] / mat.sigma_f) ** (1 / mat.b)
    np.testing.assert_allclose(sr.damage[counted], cycles / N, rtol=1e-9)
    assert sr.distance_km == pytest.approx(0.01)


def test_fast_recovery_agrees_with_generic_equivalents(straight):
    from flexpipe.durability.recover import recover_stress
    from flexpipe.durability.rundir import load_run

    run = load_run(straight[0])
    sr = recover_stress(run.motion, run.body())
    rng = np.random.default_rng(0)
    for i in list(sr.top(5)) + list(rng.choice(len(sr.element_id), 20, replace=False)):
        vm, sp = sr.history(int(i))  # generic path: every location, eigenvalue formulas
        assert vm.max() == pytest.approx(sr.max_von_mises[i], rel=1e-12)
        j = int(np.argmin(np.abs(sr.t - sr.time_of_max[i])))
        assert sp[j] == pytest.approx(sr.principal_at_max[i], rel=1e-9)


def test_solid_body_nodal_recovery_and_report(tmp_path):
    """A hex8 bar bent by one mode: element, nodal and report outputs agree."""
    import flexpipe as fp
    from flexpipe.durability.recover import recover_stress, solid_equivalent
    from flexpipe.durability.report import write_vtu
    from flexpipe.mesh.generate import box
    from flexpipe.vehicle.result import BodyMotion

    fe = fp.assemble(box(1.0, 0.1, 0.1, 10, 1, 1, cell="hexahedron"),
                     fp.Material(210e9, 0.3, 7850.0))
    body = fp.reduce(fe, [fp.Interface((0.0, 0.05, 0.05), radius=0.08, name="l"),
                          fp.Interface((1.0, 0.05, 0.05), radius=0.08, name="r")],
                     n_modes=2, stress="all")
    t = np.linspace(0.0, 1.0, 11)
    n = len(t)
    q = np.outer(np.sin(np.pi * t), np.linspace(1.0, 2.0, body.n_elastic)) * 1e-3
    motion = BodyMotion(t, q, np.zeros((n, 3)), np.broadcast_to(np.eye(3), (n, 3, 3)),
                        body.n_rigid + np.arange(body.n_elastic))
    sr = recover_stress(motion, body)
    blk = body.stress.blocks[0]
    vm, _ = solid_equivalent(np.einsum("kcm,nm->ckn", blk.nodal, q))
    np.testing.assert_allclose(sr.nodal_max_von_mises[blk.nodes], vm.max(axis=1), rtol=1e-12)
    m = meshio.read(write_vtu(tmp_path / "s.vtu", body, sr))
    np.testing.assert_allclose(m.point_data["max_von_mises_nodal [Pa]"][blk.nodes],
                               vm.max(axis=1), rtol=1e-12)
    assert len(m.cell_data["max_von_mises [Pa]"][0]) == len(blk)


def test_matrix_csv_writes_what_the_generic_writer_writes(tmp_path):
    """The per-row formatter of the stress histories against the per-value one it replaced
    (first column ``%.12g``, the others ``%.7g``, non-finite values empty)."""
    from flexpipe._io import write_matrix_csv
    from flexpipe.durability.report import _write_csv

    rng = np.random.default_rng(2)
    data = rng.standard_normal((50, 6)) * 10.0 ** rng.integers(-8, 9, (50, 6))
    data[:, 0] = np.arange(50) * 1e-3
    data[3, 2], data[7, 5], data[9, 1] = np.nan, np.inf, -np.inf
    header = ["t [s]"] + [f"c{i} [Pa]" for i in range(5)]
    _write_csv(tmp_path / "a.csv", header, [[f"{r[0]:.12g}"] + list(r[1:]) for r in data])
    write_matrix_csv(tmp_path / "b.csv", header, data)
    a, b = (tmp_path / "a.csv").read_text(), (tmp_path / "b.csv").read_text()
    assert a == b and ",," in a  # the non-finite values are empty in both


# --------------------------------------------------------------- newcomer audit findings
def test_stress_png_states_element_kinds_clipping_max_and_hot_spots(straight, tmp_path,
                                                                     monkeypatch):
    """The figure says which element kinds it draws, where its colour scale is clipped,
    the max with its element id and kind, and marks the top hot spots by id."""
    import matplotlib.pyplot as plt
    from PIL import Image

    from flexpipe.durability.recover import recover_stress
    from flexpipe.durability.report import write_png
    from flexpipe.durability.rundir import load_run
    from flexpipe.fem.stress import KIND

    run = load_run(straight[0])
    body = run.body()
    sr = recover_stress(run.motion, body, fatigue=run.car().body.fatigue)
    figs = []
    close = plt.close
    monkeypatch.setattr(plt, "close", lambda fig=None: (figs.append(fig), close(fig)))
    write_png(tmp_path / "s.png", body, sr, title="a scenario title")
    fig = figs[-1]
    i = int(np.argmax(sr.max_von_mises))
    eid, kind, vmax = int(sr.element_id[i]), KIND[sr.cell_type[i]], sr.max_von_mises[i] / 1e6
    assert kind == "beam"  # the sample's peak is in a beam, which the old figure left out
    clip = np.percentile(sr.max_von_mises / 1e6, 99.5)
    title = fig._suptitle.get_text()
    assert title.startswith("a scenario title")
    assert f"max {vmax:.1f} MPa at element {eid} (beam" in title
    assert f"99.5th percentile, {clip:.1f} MPa" in title
    assert "shells as faces" in title and "beams as lines" in title
    label = fig.axes[-1].get_xlabel()  # the colour bar (horizontal)
    assert "shell" in label and "beam" in label
    assert f"{clip:.1f} MPa" in label and f"max {vmax:.1f} MPa" in label
    # the views carry short numbers (near-coincident hot spots share one label "1,3")...
    numbers = {n for ax in fig.axes[:2] for t in ax.texts for n in t.get_text().split(",")}
    assert {"1", "2", "3", "4", "5"} <= numbers
    # ...and the table beside them lists number, element id and max von Mises in MPa
    table = fig.axes[2].tables[0]
    cells = {(r, c): cell.get_text().get_text() for (r, c), cell in table.get_celld().items()}
    for k, j in enumerate(sr.top(5)):
        assert cells[(k + 1, 0)] == str(k + 1)
        assert cells[(k + 1, 1)] == str(int(sr.element_id[j]))
        assert cells[(k + 1, 3)] == f"{sr.max_von_mises[j] / 1e6:.1f}"
    assert "[MPa]" in cells[(0, 3)]
    view_names = {t.get_text() for t in fig.texts}
    assert any(n.startswith("isometric view") for n in view_names)
    assert any(n.startswith("top view") for n in view_names)
    assert sr.damage is not None
    if np.nanmax(sr.damage) > 0:  # the fatigue hot spot is marked D and listed
        d = int(np.nanargmax(sr.damage))
        assert "D" in {t.get_text() for ax in fig.axes[:2] for t in ax.texts}
        assert cells[(6, 0)] == "D" and cells[(6, 1)] == str(int(sr.element_id[d]))
        assert "fatigue hot spot D" in title
    assert Image.open(tmp_path / "s.png").text["Title"] == title
    desc = straight[1]["file_descriptions"]["stress/stress_max.png"]
    assert "element" in desc and "99.5th percentile" in desc and "beams as lines" in desc


def test_animation_folder_is_replaced_as_a_whole(straight, tmp_path, monkeypatch):
    """A sparser animation leaves no frames of a denser one; an interrupted one leaves the
    previous animation and no staging folder; a folder of other files is refused."""
    import flexpipe.durability.animate as A
    from flexpipe.durability.pipeline import animate_outputs
    from flexpipe.errors import InputError

    out, _ = straight
    dest = tmp_path / "anim"

    def frames():
        pvd = ET.parse(dest / "body.pvd").getroot().findall("./Collection/DataSet")
        return sorted(f.get("file") for f in pvd), sorted(p.name for p in
                                                          dest.glob("body_*.vtu"))

    assert main(["animate", str(out), "--dest", str(dest), "--every", "10"]) == 0
    listed, on_disk = frames()
    assert len(listed) > 5 and listed == on_disk
    assert main(["animate", str(out), "--dest", str(dest), "--every", "50"]) == 0
    listed, on_disk = frames()
    assert len(listed) < 6 and listed == on_disk
    before = sorted(p.name for p in dest.iterdir())
    calls = []

    def interrupted(path, mesh):
        calls.append(path)
        if len(calls) > 4:
            raise KeyboardInterrupt
        write(path, mesh)

    write = A._write
    monkeypatch.setattr(A, "_write", interrupted)
    with pytest.raises(KeyboardInterrupt):
        animate_outputs(out, dest=dest, every=2, scale=100.0, log=lambda *a: None)
    monkeypatch.undo()
    assert sorted(p.name for p in dest.iterdir()) == before
    assert frames()[0] == frames()[1]
    assert not list(tmp_path.glob(".anim.staging-*"))
    other = tmp_path / "mine"
    other.mkdir()
    (other / "notes.txt").write_text("keep")
    with pytest.raises(InputError) as e:
        animate_outputs(out, dest=other, log=lambda *a: None)
    assert str(other) in str(e.value) and "dest" in str(e.value)
    assert "notes.txt" in str(e.value) and (other / "notes.txt").read_text() == "keep"


def test_animation_folder_with_hidden_files_of_others_is_refused(tmp_path):
    """Only the animation's own temporary files may be hidden: a folder holding ``.git``
    and ``.env`` is refused (replacing it would delete them), one holding a temporary
    frame of :func:`flexpipe._io.atomic_path` is accepted."""
    from flexpipe.durability.animate import stage_animation
    from flexpipe.errors import InputError

    dest = tmp_path / "repo"
    (dest / ".git").mkdir(parents=True)
    (dest / ".env").write_text("SECRET=1")
    with pytest.raises(InputError) as e:
        stage_animation(dest)
    assert str(dest) in str(e.value) and "dest" in str(e.value)
    assert ".git" in str(e.value) and (dest / ".env").read_text() == "SECRET=1"
    anim = tmp_path / "anim"
    anim.mkdir()
    for name in ("animation.pvd", "body_00001.vtu", ".body_00002.vtu.k3_9xq0a.vtu"):
        (anim / name).write_text("")
    stage = stage_animation(anim)
    assert stage.is_dir() and stage.name.startswith(".anim.staging-")


def _copy_run(out, dest):
    import shutil

    shutil.copytree(out, dest)
    return dest


def test_summary_describes_what_stress_and_animate_rewrote(straight, tmp_path):
    out = _copy_run(straight[0], tmp_path / "run")
    assert main(["animate", str(out), "--scale", "100", "--every", "50"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    n = len(ET.parse(out / "animation" / "body.pvd").getroot().findall(
        "./Collection/DataSet"))
    desc = summary["file_descriptions"]["animation/body.pvd"]
    assert desc.startswith(f"{n} frames") and "deformation x 100" in desc
    assert "animation/body.pvd" in summary["files"]
    assert main(["stress", str(out), "--top", "3", "--no-fatigue"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["file_descriptions"]["stress/hotspots.csv"].startswith("top 3 elements")
    assert summary["file_descriptions"]["animation/body.pvd"] == desc  # the rest kept
    assert not list(out.glob(".summary.json.*"))  # the temp file was renamed


def test_interrupted_stress_report_leaves_the_previous_one(straight, tmp_path, monkeypatch):
    """``stress/`` is replaced as a whole: an error after some files of the new report are
    written leaves the previous report (files and stress_summary.json) and no staging
    folder."""
    import flexpipe.durability.report as R
    from flexpipe.durability.pipeline import stress_outputs

    out = _copy_run(straight[0], tmp_path / "run")
    before = {p.name: p.read_bytes() for p in (out / "stress").iterdir()}
    assert "hotspots.csv" in before and "stress_summary.json" in before

    def broken(*a, **k):
        raise RuntimeError("injected")

    monkeypatch.setattr(R, "write_png", broken)
    with pytest.raises(RuntimeError, match="injected"):
        stress_outputs(out, top=2, fatigue=False, log=lambda *a: None)
    assert {p.name: p.read_bytes() for p in (out / "stress").iterdir()} == before
    assert not list(out.glob(".stress.*"))


@pytest.fixture(scope="module")
def short_runs(straight, tmp_path_factory):
    """Short runs that reuse the reduced body cached by ``straight`` (its FLEXPIPE_CACHE):
    the flexible body alone with and without progress bars (stderr and log lines kept),
    and the rigid body alone."""
    import contextlib
    import io

    from flexpipe.scenarios.runner import DEFAULT_CAR, SCENARIOS, run_pair

    d = tmp_path_factory.mktemp("short")
    sc = SCENARIOS["straight"]
    runs = {}
    for name, bodies, progress in (("flex_progress", ("flexible",), True),
                                   ("flex_quiet", ("flexible",), False),
                                   ("rigid", ("rigid",), False)):
        log, err = [], io.StringIO()
        with contextlib.redirect_stderr(err):
            run_pair(DEFAULT_CAR, road=sc.road(), path=None, speed=sc.speed_kmh / 3.6,
                     t_end=0.1, out=d / name, title=sc.title, bodies=bodies,
                     progress=progress, log=log.append)
        runs[name] = (d / name, log, err.getvalue())
    return runs


def test_scenario_run_prints_final_paths(short_runs):
    out, log, _ = short_runs["flex_quiet"]
    line = next(m for m in log if m.startswith("animation:"))
    assert f"{out}/animation/animation.pvd" in line and "staging" not in line
    assert not any("staging" in m for m in log)


def test_scenario_durability_shows_progress_unless_quiet(short_runs):
    _, _, err = short_runs["flex_progress"]
    assert "stress recovery" in err and "animation frames" in err
    _, _, err = short_runs["flex_quiet"]
    assert "stress recovery" not in err and "animation frames" not in err


def test_stress_and_animate_of_a_rigid_only_run_say_so(short_runs, capsys):
    out, _, _ = short_runs["rigid"]
    for cmd in ("stress", "animate"):
        assert main([cmd, str(out)]) == 2
        err = capsys.readouterr().err
        assert str(out) in err and "motion_flexible.npz" in err
        assert "rigid body model" in err and "--body flexible" in err


def test_stress_and_animate_find_the_car_from_any_folder_and_name_a_moved_one(
        straight, tmp_path, monkeypatch, capsys):
    """summary.json names the car file by its absolute path: ``stress`` works from
    another folder; a car file that has moved (or an earlier run's relative path looked
    up from another folder) is a one-line error naming summary.json, 'car_file', the path
    and what to do, before any work."""
    out = _copy_run(straight[0], tmp_path / "run")
    summary = json.loads((out / "summary.json").read_text())
    assert Path(summary["car_file"]).is_absolute() and Path(summary["car_file"]).is_file()
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    monkeypatch.chdir(elsewhere)
    assert main(["stress", str(out), "--top", "2", "--no-fatigue"]) == 0
    capsys.readouterr()
    for car_file, words in ((str(tmp_path / "moved" / "car.toml"), ["moved or deleted"]),
                            ("cars/sedan_linkage.toml", ["relative", str(elsewhere)])):
        summary["car_file"] = car_file
        (out / "summary.json").write_text(json.dumps(summary))
        for cmd in ("stress", "animate"):
            assert main([cmd, str(out)]) == 2
            err = capsys.readouterr().err.strip()
            assert err.startswith(f"flexpipe {cmd}: error:") and "\n" not in err
            for w in [str(out / "summary.json"), "'car_file'", car_file, *words]:
                assert w in err, err
        assert not (out / "animation.failed").exists()
