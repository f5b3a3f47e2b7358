"""Bad command lines for the ``flexpipe`` CLI, run in-process through ``flexpipe.cli.main``.

Each case is a ``*.cli.json`` document: ``argv``, the small input ``files`` written to
the case folder first (``{dir}`` in argv is that folder) and ``names``, a text the one-line
error must contain (the offending option or file).  A bad command line must exit with
code 2 (argparse usage or a flexpipe error), one ``error:`` line, no traceback.
"""

from __future__ import annotations

import json
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SEDAN = str(ROOT / "cars" / "sedan.toml")
BRACKET = str(ROOT / "meshes" / "bracket.bdf")
PLATE = str(ROOT / "meshes" / "plate_quad.msh")
SPEC = '[[interface]]\nname = "a"\npoint = [0.0, 0.0, 0.0]\nradius = 0.02\n'
BAD_SPEC = '[[interface]]\nname = "a"\npoint = [0.0, 0.0]\nradius = 0.02\n'


def case(argv, names=None, files=None, expect="error"):
    doc = {"argv": argv, "files": files or {}}
    if names is not None:
        doc["names"] = names
    return json.dumps(doc).encode(), expect


def _cases():
    d = "{dir}"
    run = ["run", SEDAN, "--t-end", "0.02", "--body", "rigid", "--out", f"{d}/out"]
    yield "no-command", case([], None)
    yield "unknown-command", case(["simulate"], "simulate")
    yield "unknown-top-option", case(["--frobnicate"], "frobnicate")
    # ---- run: numbers
    for opt, values in {"--speed": ["-5", "nan", "inf", "abc", "", "1e400", "-inf"],
                        "--t-end": ["0", "-1", "nan", "abc", "inf", "1e9"],
                        "--h": ["0", "-1e-3", "1", "nan", "abc", "1e-9", "0.03"]}.items():
        for v in values:
            argv = [a for a in run]
            if opt == "--t-end":
                argv[argv.index("--t-end") + 1] = v
                argv += ["--speed", "30"]
            else:
                argv += ["--speed", "30"] if opt != "--speed" else []
                argv += [opt, v]
            yield f"run{opt}={v or 'empty'}", case(argv, opt.lstrip("-").replace("-", "_")
                                                  if v not in ("", "abc") else opt)
    yield "run-speed-missing", case(run, "--speed")
    for body in ("stiff", "", "RIGID", "rigid,elastic"):
        yield f"run-body={body or 'empty'}", case(
            [*run[:5], body, *run[6:], "--speed", "30"], "--body")
    yield "run-body=rigid,,", case([*run[:5], "rigid,,", *run[6:], "--speed", "30"], "--body",
                                   expect="maybe")
    yield "run-car-missing", case(["run", f"{d}/nope.toml", "--speed", "30"], "nope.toml")
    yield "run-car-not-toml", case(["run", BRACKET, "--speed", "30", "--out", f"{d}/o"],
                                   "bracket.bdf")
    yield "run-car-garbage", case(["run", f"{d}/car.toml", "--speed", "30", "--out", f"{d}/o"],
                                  "car.toml", {"car.toml": "[car\nname = 1\n"})
    yield "run-car-directory", case(["run", d, "--speed", "30"], None)
    yield "run-road-missing", case([*run, "--speed", "30", "--road", f"{d}/nope.crg"],
                                   "nope.crg")
    yield "run-road-garbage-csv", case([*run, "--speed", "30", "--road", f"{d}/road.csv"],
                                       "road.csv", {"road.csv": "x,z\n0,0\n1,abc\n"})
    yield "run-road-unknown-suffix", case([*run, "--speed", "30", "--road", f"{d}/road.xyz"],
                                          "road.xyz", {"road.xyz": "0 0\n"})
    yield "run-path-missing", case([*run, "--speed", "30", "--path", f"{d}/nope.csv"],
                                   "nope.csv")
    yield "run-path-garbage", case([*run, "--speed", "30", "--path", f"{d}/path.csv"],
                                   "path.csv", {"path.csv": "x,y\n0,0\nnan,1\n"})
    yield "run-out-is-file", case([*run[:-2], "--out", f"{d}/file.txt", "--speed", "30"],
                                  "file.txt", {"file.txt": "x"})
    yield "run-out-foreign-folder", case([*run[:-2], "--out", d, "--speed", "30"],
                                         "summary.json", {"keep.me": "x"})
    yield "run-unknown-option", case([*run, "--speed", "30", "--fast"], "--fast")
    yield "run-speed-twice-bad", case([*run, "--speed", "30", "--speed", "x"], "--speed")
    yield "run-ok-quiet", case([*run, "--speed", "30", "-q"], None, expect="ok")
    yield "run-ok", case([*run, "--speed", "20"], None, expect="ok")
    # ---- modes
    modes = ["modes", BRACKET, "-o", f"{d}/m", "-q"]
    for opt, values in {"--n": ["0", "-3", "abc", "1.5", "100000000"],
                        "--E": ["-1", "0", "nan", "abc", "inf"],
                        "--nu": ["0.5", "-1", "0.7", "nan"],
                        "--rho": ["0", "-7850", "nan"],
                        "--thickness": ["0", "-0.002", "nan", "abc"],
                        "--scale": ["0", "-1", "nan", "inf", "abc"]}.items():
        for v in values:
            yield f"modes{opt}={v}", case([*modes, opt, v], None)
    for mat in ("unobtainium", "", "STEEL!"):
        yield f"modes-material={mat or 'empty'}", case([*modes, "--material", mat],
                                                       "--material" if mat else None)
    yield "modes-units-bad", case([*modes, "--units", "furlong"], "furlong")
    yield "modes-fixed-unknown-set", case([*modes, "--fixed", "nosuchset"], "nosuchset")
    yield "modes-keep-bad-type", case(["modes", PLATE, "-o", f"{d}/m", "-q", "--keep",
                                       "octahedron", "--material", "steel", "--thickness",
                                       "0.002"], "octahedron")
    yield "modes-mesh-missing", case(["modes", f"{d}/nope.bdf"], "nope.bdf")
    yield "modes-mesh-unknown-suffix", case(["modes", f"{d}/mesh.xyz"], "mesh.xyz",
                                            {"mesh.xyz": "1 2 3\n"})
    yield "modes-mesh-empty", case(["modes", f"{d}/empty.bdf", "-q"], "empty.bdf",
                                   {"empty.bdf": ""})
    yield "modes-mesh-garbage-msh", case(["modes", f"{d}/g.msh", "-q", "--material", "steel"],
                                         "g.msh", {"g.msh": "$MeshFormat\n2.2 0 8\n$End\n"})
    yield "modes-no-material", case(["modes", PLATE, "-o", f"{d}/m", "-q"], None)
    yield "modes-ok", case([*modes, "--n", "8"], None, expect="ok")
    # ---- reduce
    red = ["reduce", BRACKET, "--interfaces", f"{d}/spec.toml", "-o", f"{d}/b.npz", "-q"]
    files = {"spec.toml": SPEC}
    yield "reduce-ok", case([*red, "--n-modes", "4", "--no-check"], None, files, "ok")
    yield "reduce-out-not-npz", case([*red[:5], f"{d}/b.txt", "-q"], "-o", files)
    yield "reduce-spec-missing", case(red, "spec.toml")
    yield "reduce-spec-bad", case(red, "spec.toml", {"spec.toml": BAD_SPEC})
    yield "reduce-spec-ints", case(red, "spec.toml", {"spec.toml": "interface = [1, 2]\n"})
    yield "reduce-spec-float-nodes", case(red, "spec.toml", {
        "spec.toml": '[[interface]]\nname = "a"\npoint = [0, 0, 0]\nnodes = [4.7]\n'})
    yield "reduce-spec-radius-and-nodes", case(red, "spec.toml", {
        "spec.toml": '[[interface]]\nname = "a"\npoint = [0, 0, 0]\nradius = 0.1\n'
                     'nodes = [1]\n'})
    yield "reduce-spec-far-point", case(red, "spec.toml", {
        "spec.toml": '[[interface]]\nname = "far"\npoint = [9, 9, 9]\nradius = 0.01\n'})
    yield "reduce-spec-unknown-node", case(red, "spec.toml", {
        "spec.toml": '[[interface]]\nname = "a"\npoint = [0, 0, 0]\nnodes = [999999]\n'})
    for opt, values in {"--n-modes": ["-1", "abc", "100000"],
                        "--f-max": ["0", "-10", "nan", "abc", "inf"],
                        "--damping": ["-0.1", "nan", "abc"]}.items():
        for v in values:
            yield f"reduce{opt}={v}", case([*red, opt, v], None, files)
    # Guyan-type body (static modes only) and an overcritical damping ratio are legitimate
    yield "reduce--n-modes=0", case([*red, "--n-modes", "0", "--no-check"], None, files,
                                    "maybe")
    yield "reduce--damping=2.5", case([*red, "--damping", "2.5", "--no-check"], None, files,
                                      "maybe")
    yield "reduce-n-modes-and-f-max", case([*red, "--n-modes", "4", "--f-max", "100"],
                                           "--f-max", files)
    yield "reduce-method-bad", case([*red, "--method", "guyan"], "--method", files)
    yield "reduce-missing-interfaces", case(["reduce", BRACKET, "-o", f"{d}/b.npz"],
                                            "--interfaces")
    # ---- info
    yield "info-missing", case(["info", f"{d}/nope.npz"], "nope.npz")
    yield "info-garbage-npz", case(["info", f"{d}/g.npz"], "g.npz", {"g.npz": "garbage"})
    yield "info-unknown-suffix", case(["info", f"{d}/x.abc"], "x.abc", {"x.abc": "1"})
    yield "info-mesh-garbage", case(["info", f"{d}/m.obj"], "m.obj", {"m.obj": "v 1 2\n"})
    yield "info-mac-size-bad", case(["info", f"{d}/g.npz", "--mac-size", "abc"],
                                    "--mac-size", {"g.npz": "x"})
    yield "info-ok-mesh", case(["info", BRACKET], None, expect="ok")


def cases():
    for cid, (content, expect) in _cases():
        yield cid, "case.cli.json", content, expect
