"""The examples of README.md and docs/*.md work from a fresh clone, as written.

* Every ````python`` block runs, in a scratch folder that links the repository's data
  folders (so ``out/...`` is written there).
* Every ``flexpipe ...`` line of a ````sh`` block parses with that command's own options,
  names only input files that ship with the repository (outputs: ``out/...`` or the value
  of ``-o``/``--out``/``--dest``/``--vtu``; a file the user brings is named ``your_*``),
  and has no placeholder (``...``, ``MESH``); every ``flexpipe run`` line passes the run's
  argument checks (road and path long enough for ``--t-end`` at ``--speed``) without
  running; the quick commands (``modes``, ``reduce``, ``info``) run, in the order the text
  gives them.
* Every inline ```flexpipe CMD ... --option``` names a command and options that exist.
* The interface spec of docs/interfaces.md ships (``meshes/plate_quad_interfaces.toml``)
  and reduces to the interfaces its comments describe; the sweep spec of docs/sweeps.md
  passes every check a sweep makes before its first run.

Marker convention: an HTML comment on the line right before a code fence,
``<!-- docs-test: skip (REASON) -->``, keeps a Python block out of these runs (a run of
minutes, or a block another test runs with checks of its own); ``<!-- docs-test: slow -->``
runs it as a ``slow`` test.
"""

from __future__ import annotations

import argparse
import importlib
import re
import shlex
from pathlib import Path

import pytest

from flexpipe.cli import COMMANDS, main

REPO = Path(__file__).resolve().parents[1]
DOCS = [REPO / "README.md", *sorted((REPO / "docs").glob("*.md"))]
DATA = ("cars", "meshes", "paths", "roads", "sweeps", "tires")
FENCE = re.compile(r"^(?P<indent> *)```(?P<lang>\w*)\n(?P<body>.*?)^(?P=indent)```", re.M | re.S)
MARKER = re.compile(r"<!--\s*docs-test:\s*(?P<what>\w+)(?P<reason>.*?)-->")
INLINE = re.compile(r"`(flexpipe [a-z/][^`]*)`")
OUTPUT_OPTIONS = ("-o", "--out", "--dest", "--vtu")
FILE_SUFFIX = re.compile(r"\.(toml|crg|csv|bdf|nas|dat|msh|inp|vtu|vtk|stl|obj|ply|npz|tir)$")
QUICK = ("modes", "reduce", "info")
MODULES = {name: module for name, module, _ in COMMANDS}


def _blocks(lang):
    """``(where, code, marker)`` of every fenced block in ``lang``, in reading order."""
    out = []
    for doc in DOCS:
        text = doc.read_text()
        for m in FENCE.finditer(text):
            if m["lang"] != lang:
                continue
            line = text.count("\n", 0, m.start()) + 1
            before = text[: m.start()].rstrip().rsplit("\n", 1)[-1]
            indent = len(m["indent"])
            code = "\n".join(s[indent:] for s in m["body"].splitlines()) + "\n"
            out.append((f"{doc.name}:{line}", code, MARKER.search(before)))
    return out


def _python_params():
    params = []
    for where, code, mark in _blocks("python"):
        marks = []
        if mark is not None and mark["what"] == "skip":
            marks.append(pytest.mark.skip(reason=f"{where}: {mark['reason'].strip(' ()')}"))
        elif mark is not None and mark["what"] == "slow":
            marks.append(pytest.mark.slow)
        params.append(pytest.param(where, code, marks=marks, id=where))
    return params


def _commands():
    """``(where, argv)`` of every ``flexpipe`` line of the shell blocks (argv after
    ``flexpipe``; leading ``VAR=value`` assignments dropped)."""
    out = []
    for where, code, _ in _blocks("sh"):
        doc, first = where.rsplit(":", 1)
        for k, line in enumerate(code.replace("\\\n", " ").splitlines()):
            words = shlex.split(line, comments=True)
            while words and re.fullmatch(r"[A-Za-z_]\w*=\S*", words[0]):
                words.pop(0)
            if words and words[0] == "flexpipe":
                out.append((f"{doc}:{int(first) + 1 + k}", words[1:]))
    return out


def _parser(name):
    assert name in MODULES, f"no command {name!r}; valid: {sorted(MODULES)}"
    p = argparse.ArgumentParser(prog=f"flexpipe {name}")
    importlib.import_module(MODULES[name]).add_arguments(p)
    return p


def _parse(where, argv):
    try:
        return _parser(argv[0]).parse_args(argv[1:])
    except SystemExit:
        pytest.fail(f"{where}: 'flexpipe {shlex.join(argv)}' does not parse (argparse's "
                    "message above)")


@pytest.fixture
def scratch(tmp_path, monkeypatch):
    """A folder with the repository's data folders linked in: a fresh clone's files,
    outputs kept out of the repository."""
    for name in DATA:
        (tmp_path / name).symlink_to(REPO / name, target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path / "cache"))
    return tmp_path


def test_the_docs_have_examples_to_check():
    assert len(_blocks("python")) >= 4 and len(_commands()) >= 20


def test_every_skip_marker_gives_a_reason():
    for where, _, mark in _blocks("python"):
        if mark is not None:
            assert mark["what"] in ("skip", "slow"), f"{where}: unknown marker {mark[0]}"
            if mark["what"] == "skip":
                assert mark["reason"].strip(" ():"), f"{where}: a skip marker needs a reason"


@pytest.mark.parametrize("where, code", _python_params())
def test_python_block_runs(where, code, scratch):
    exec(compile(code, where, "exec"), {"__name__": "__main__"})


@pytest.mark.parametrize("where, argv", _commands(), ids=[w for w, _ in _commands()])
def test_command_parses_and_names_shipped_files(where, argv):
    assert "..." not in argv, f"{where}: placeholder '...' in 'flexpipe {shlex.join(argv)}'"
    _parse(where, argv)
    for before, word in zip(argv, argv[1:], strict=False):
        if word.startswith("-") or before in OUTPUT_OPTIONS or "://" in word:
            continue
        assert not re.fullmatch(r"[A-Z][A-Z_]*(\.\w+)?", word), (
            f"{where}: placeholder {word} in 'flexpipe {shlex.join(argv)}'")
        if "/" not in word and not FILE_SUFFIX.search(word):
            continue                                      # a value, not a file
        if word.startswith("out/") or Path(word).name.startswith("your_"):
            continue                                      # an output, or the user's file
        assert (REPO / word).exists(), (
            f"{where}: 'flexpipe {shlex.join(argv)}' names {word}, which does not ship with "
            "the repository; point to a shipped file or call it your_<name>")


@pytest.mark.parametrize("where, argv", [c for c in _commands() if c[1][0] == "run"],
                         ids=[w for w, a in _commands() if a[0] == "run"])
def test_run_command_fits_its_road(where, argv):
    """The checks ``flexpipe run`` makes before it starts (road and path long enough)."""
    from flexpipe.vehicle.run_inputs import check_run

    a = _parse(where, argv)
    if any(Path(f).name.startswith("your_") for f in (a.car, a.road or "", a.path or "")):
        pytest.skip(f"{where}: the user's own file")
    try:
        speed = float(a.speed) / 3.6  # km/h, or a speed profile file
    except ValueError:
        speed = REPO / a.speed
    check_run(REPO / a.car, road=None if a.road is None else REPO / a.road,
              path=a.path if a.path in (None, "road", "straight") else REPO / a.path,
              speed=speed, t_end=a.t_end, body=a.body.split(",")[0],
              h=a.h or 1e-3)


def test_quick_commands_run_in_order(scratch, capsys):
    """``flexpipe modes / reduce / info`` lines run as written (the ``reduce`` output feeds
    the ``info`` line after it)."""
    ran = []
    for where, argv in _commands():
        if argv[0] in QUICK:
            assert main(argv) == 0, f"{where}: 'flexpipe {shlex.join(argv)}' failed"
            ran.append(argv[0])
    assert set(ran) == set(QUICK)
    assert "wrote out/" in capsys.readouterr().out


def test_inline_commands_name_existing_options():
    for doc in DOCS:
        text = doc.read_text()
        for m in INLINE.finditer(text):
            span = " ".join(m[1].split())
            words = span.split()
            names = [n for n in words[1].split("/") if n]
            where = f"{doc.name}:{text.count(chr(10), 0, m.start()) + 1}"
            options = {o for a in _parser(names[0])._actions for o in a.option_strings}
            for name in names[1:]:
                _parser(name)
            for w in words[2:]:
                if w.startswith("-"):
                    assert w in options, f"{where}: '{span}': no option {w}; valid: " \
                                         f"{sorted(options)}"


def test_interface_spec_example_ships_and_reduces_as_annotated(tmp_path):
    """docs/interfaces.md's annotated spec is the shipped file, and each interface ties the
    nodes its comments say."""
    from flexpipe.reduction import load_body

    shipped = REPO / "meshes" / "plate_quad_interfaces.toml"
    toml = [code for where, code, _ in _blocks("toml") if where.startswith("interfaces.md")]
    assert toml and toml[0] == shipped.read_text()
    out = tmp_path / "plate.npz"
    assert main(["reduce", str(REPO / "meshes" / "plate_quad.msh"), "--interfaces",
                 str(shipped), "--material", "steel", "--thickness", "0.002", "-o", str(out),
                 "-q", "--no-check"]) == 0
    got = {i.name: (i.kind, i.dofs, len(i.nodes)) for i in load_body(out).interfaces}
    assert got == {"edge": ("rbe2", 6, 7), "centre": ("rbe2", 6, 5), "tab": ("rbe2", 3, 2),
                   "corner": ("node", 6, 1)}


def test_every_interface_snippet_reads_and_resolves(tmp_path):
    """Every ````toml`` block of docs/interfaces.md is a valid spec for the plate mesh."""
    import flexpipe as fp
    from flexpipe.reduction.interface import resolve_interfaces
    from flexpipe.reduction.spec import read_interfaces

    mesh = fp.read_mesh(REPO / "meshes" / "plate_quad.msh")
    fe = fp.assemble(mesh, fp.Material(E=210e9, nu=0.3, rho=7850.0), thickness=0.002)
    blocks = [(w, c) for w, c, _ in _blocks("toml") if w.startswith("interfaces.md")]
    assert len(blocks) >= 2
    for k, (_, code) in enumerate(blocks):
        spec = tmp_path / f"spec{k}.toml"
        spec.write_text(code)
        assert resolve_interfaces(fe, read_interfaces(spec, node_ids=mesh.node_ids))


def test_sweep_spec_example_passes_the_sweep_checks(tmp_path):
    """docs/sweeps.md's spec, saved as sweeps/study.toml of a clone, passes every check
    ``fp.sweep`` makes before its first run (settings, overrides, road and path lengths,
    plot metrics)."""
    from flexpipe.sweeps.checks import check_plot_metrics, check_runs
    from flexpipe.sweeps.spec import load_sweep
    from flexpipe.vehicle.spec import load_car

    for name in DATA:
        if name != "sweeps":
            (tmp_path / name).symlink_to(REPO / name, target_is_directory=True)
    (tmp_path / "sweeps").mkdir()
    (code,) = [c for w, c, _ in _blocks("toml") if w.startswith("sweeps.md")]
    (tmp_path / "sweeps" / "study.toml").write_text(code)
    spec = load_sweep(tmp_path / "sweeps" / "study.toml")
    runs = spec.runs()
    cars = {}
    for r in runs:
        key = (str(r.car_file), repr(sorted(r.car_overrides.items())))
        cars.setdefault(key, load_car(r.car_file, overrides=r.car_overrides))
    per_run = [cars[(str(r.car_file), repr(sorted(r.car_overrides.items())))] for r in runs]
    check_runs(spec, runs, per_run)
    check_plot_metrics(spec, per_run)
