"""Load one corpus case with the reader its file name selects, and classify the outcome."""

from __future__ import annotations

import contextlib
import importlib
import io
import json
import re
import signal
import warnings
from dataclasses import dataclass
from pathlib import Path

from flexpipe.errors import FlexpipeError

HERE = Path(__file__).resolve().parent
TIME_LIMIT_S = 20
MESH_SUFFIXES = {".bdf", ".nas", ".dat", ".inp", ".msh", ".vtu", ".vtk", ".stl", ".obj",
                 ".ply", ".off"}
#: a location in a message: line, key, card, element/node/material/property id, entry
_LOCATION = re.compile(
    r"line \d+|key '|\bkeys? \w|card|\b(element|elem|node|vertex|facet|cell|material|"
    r"property|mid|pid|eid|nid|grid|id|set|interface|entry|mode|column|row|argument|option|"
    r"record|channel|header|data block|section)"
    r"\b|--\w", re.IGNORECASE)


def generators():
    """``{name: module}`` of every ``gen_*.py`` next to this file."""
    out = {}
    for p in sorted(HERE.glob("gen_*.py")):
        out[p.stem] = importlib.import_module(f"tests.badinput.{p.stem}")
    return out


def kind_of(filename: str) -> str:
    name = Path(filename).name.lower()
    suffix = Path(name).suffix
    if name.endswith(".cli.json"):
        return "cli"
    if suffix in MESH_SUFFIXES:
        return "mesh"
    if suffix == ".tir":
        return "tire"
    if suffix == ".npz":
        return "body"
    if suffix in (".crg", ".rdf"):
        return "road"
    for prefix, kind in (("road", "road"), ("path", "path"), ("driver", "driver"),
                         ("speed", "speed"),
                         ("car", "car"), ("interface", "interfaces"), ("spec", "interfaces"),
                         ("halfcar", "halfcar")):
        if name.startswith(prefix):
            return kind
    if suffix == ".csv":
        return "road"
    raise ValueError(f"corpus file name {filename!r} maps to no reader (see README.md)")


def load(kind: str, path: Path):
    """Read ``path`` with the reader of ``kind``; returns what it produced."""
    if kind == "mesh":
        from flexpipe.fem import Material, assemble
        from flexpipe.mesh import read_mesh

        mesh = read_mesh(path)
        if path.suffix.lower() in (".bdf", ".nas", ".dat", ".inp"):
            return assemble(mesh)
        return assemble(mesh, Material(E=210e9, nu=0.3, rho=7850.0), thickness=0.002)
    if kind == "tire":
        from flexpipe.tires import tire_from_file

        return tire_from_file(path)
    if kind == "body":
        from flexpipe.flexbody import load_body

        return load_body(path)
    if kind == "road":
        from flexpipe.roads import load_road

        return load_road(path)
    if kind == "path":
        from flexpipe.driver import read_path

        return read_path(path)
    if kind == "driver":
        from flexpipe.driver import read_driver

        return read_driver(path)
    if kind == "speed":
        from flexpipe.driver import read_speed_profile
        from flexpipe.vehicle.run_inputs import SPEED_MAX

        return read_speed_profile(path, speed_max=SPEED_MAX)
    if kind == "car":
        from flexpipe.vehicle import load_car

        return load_car(path)
    if kind == "interfaces":
        from flexpipe.reduction.spec import read_interfaces

        return read_interfaces(path)
    if kind == "halfcar":
        from flexpipe.halfcar.params import load_params

        return load_params(path)
    raise ValueError(kind)


@dataclass
class Outcome:
    generator: str
    case_id: str
    filename: str
    expect: str
    category: str  # clear, vague, raw, accepted-wrong, ok, rejected-valid
    message: str


class _Timeout(BaseException):
    pass


def _alarm(signum, frame):
    raise _Timeout()


def _run_cli(spec: dict, folder: Path):
    from flexpipe.cli import main

    for name, text in spec.get("files", {}).items():
        (folder / name).write_text(text)
    argv = [a.replace("{dir}", str(folder)) for a in spec["argv"]]
    err, out = io.StringIO(), io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
        try:
            code = main(argv)
        except SystemExit as exc:
            code = exc.code if isinstance(exc.code, int) else 2
    return code, err.getvalue()


def run_case(generator: str, case, folder: Path, loader=None) -> Outcome:
    """Write the case into the empty ``folder``, load it, classify the result.

    ``loader(path)`` is the generator's own ``load`` function when it defines one;
    otherwise the file name selects the reader (:func:`kind_of`)."""
    case_id, filename, content, expect = case
    path = folder / filename
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(TIME_LIMIT_S)
    try:
        if kind_of(filename) == "cli":
            return _classify_cli(generator, case, json.loads(content), folder)
        path.write_bytes(content)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            if loader is not None:
                loader(path)
            else:
                load(kind_of(filename), path)
    except _Timeout:
        return Outcome(generator, case_id, filename, expect, "raw",
                       f"no answer within {TIME_LIMIT_S} s (hang)")
    except FlexpipeError as exc:
        msg = " ".join(str(exc).split())
        if expect == "ok":
            return Outcome(generator, case_id, filename, expect, "rejected-valid", msg)
        named = Path(filename).name in msg
        located = expect == "error:file" or _located(exc, msg)
        return Outcome(generator, case_id, filename, expect,
                       "clear" if named and located else "vague", msg)
    except Exception as exc:  # noqa: BLE001 - the point of the corpus: any other exception
        return Outcome(generator, case_id, filename, expect, "raw",
                       f"{type(exc).__name__}: {' '.join(str(exc).split())[:300]}")
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    return Outcome(generator, case_id, filename, expect,
                   "ok" if expect in ("ok", "maybe") else "accepted-wrong", "loaded")


def _located(exc: FlexpipeError, msg: str) -> bool:
    if getattr(exc, "line", None) is not None or getattr(exc, "key", None) is not None:
        return True
    return bool(_LOCATION.search(msg))


def _classify_cli(generator, case, spec, folder) -> Outcome:
    case_id, filename, _, expect = case
    try:
        code, err = _run_cli(spec, folder)
    except FlexpipeError as exc:  # main() must catch these itself
        return Outcome(generator, case_id, filename, expect, "raw",
                       f"escaped main(): {type(exc).__name__}: {exc}")
    text = " ".join(err.split())
    if expect == "ok":
        return Outcome(generator, case_id, filename, expect,
                       "ok" if code == 0 else "rejected-valid", f"exit {code}: {text[:300]}")
    if code == 0:
        if expect == "maybe":
            return Outcome(generator, case_id, filename, expect, "ok", "exit 0")
        return Outcome(generator, case_id, filename, expect, "accepted-wrong", "exit 0")
    if "Traceback" in err or code not in (1, 2):
        return Outcome(generator, case_id, filename, expect, "raw",
                       f"exit {code}: {text[:300]}")
    lines = [ln for ln in err.splitlines() if ": error:" in ln or ln.startswith("error:")]
    names = spec.get("names")
    clear = len(lines) == 1 and (names is None or names in lines[0])
    return Outcome(generator, case_id, filename, expect, "clear" if clear else "vague",
                   f"exit {code}: {text[:300]}")
