"""Nastran reader benchmark: a 1,000,000-node shell body deck with the new cards.

The deck (written once into a temporary directory, small-field format as
pre-processors write it) holds 1,000,000 GRIDs (a 1000 x 1000 grid, every 500th
point with ``CP``/``CD`` in a CORD2R system), 998,001 CQUAD4/CTRIA3 (1 % with ZOFFS),
CBAR stiffeners with PBARL ``BOX`` (Timoshenko), CBUSH/PBUSH and CELAS2 mounts, RBE3
spiders, CONM2 masses, SPC1/EIGRL and case control.

Targets: ``read_mesh`` under 20 s and under 4 GB peak resident memory.  Peer, timed in
the same run: the floor of any pure-Python reader - reading the text and cutting every
line into its 8-character fields (``text_split_s``); the figure to watch is the ratio
``read_over_split``.  The read runs in a child process so that its peak memory
(``ru_maxrss``) is its own.  ``python -m bench.bench_nastran`` runs it alone.
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
N = 1000                    # grid points per side: N^2 = 1,000,000 GRIDs


def _f8(x) -> str:
    """A coordinate in [-0.2, 1.2] as an 8-character small field."""
    return f"{x:.5f}"


def write_deck(path: Path, n: int = N) -> dict:
    """Write the benchmark deck; return its card counts."""
    h = 1.0 / (n - 1)
    lines = ["SOL 103", "CEND", "SPC = 1", "METHOD = 1", "BEGIN BULK",
             "MAT1           1  2.1+11              .3   7850.",
             "PSHELL         1       1   .0015       1",
             "PBARL          2       1             BOX", "             .03     .03    .002    .002",
             "PBUSH          3       K   1.+6    1.+6    1.+6    1.+3    1.+3    1.+3",
             "CORD2R         5              0.      0.      0.      0.      0.      1.",
             "              1.      0.      0.",
             "EIGRL          1                      20"]
    ids = np.arange(1, n * n + 1)
    x = ((ids - 1) % n) * h
    y = ((ids - 1) // n) * h
    z = 0.1 * np.sin(np.pi * x) * np.sin(np.pi * y)
    sys5 = (ids % 500) == 0
    for i, xi, yi, zi, c in zip(ids, x, y, z, sys5, strict=True):
        cp = "       5" if c else "        "
        cd = "       5" if c else ""
        lines.append(f"GRID    {i:>8d}{cp}{_f8(xi):>8}{_f8(yi):>8}{_f8(zi):>8}{cd}")
    eid = 0
    for j in range(n - 1):
        for i in range(n - 1):
            a = j * n + i + 1
            eid += 1
            if (i + j) % 97 == 0:   # some triangles
                lines.append(f"CTRIA3  {eid:>8d}       1{a:>8d}{a + 1:>8d}{a + n + 1:>8d}")
                eid += 1
                lines.append(f"CTRIA3  {eid:>8d}       1{a:>8d}{a + n + 1:>8d}{a + n:>8d}")
            elif eid % 100 == 0:
                lines.append(f"CQUAD4  {eid:>8d}       1{a:>8d}{a + 1:>8d}{a + n + 1:>8d}"
                             f"{a + n:>8d}            .002")
            else:
                lines.append(f"CQUAD4  {eid:>8d}       1{a:>8d}{a + 1:>8d}{a + n + 1:>8d}"
                             f"{a + n:>8d}")
    n_shell = eid
    for j in range(0, n, 50):          # stiffeners along x every 50 rows
        for i in range(n - 1):
            a = j * n + i + 1
            eid += 1
            lines.append(f"CBAR    {eid:>8d}       2{a:>8d}{a + 1:>8d}      0.      0.      1.")
    nid = n * n
    extra = []
    for corner in (1, n, n * n - n + 1, n * n):                  # mounts and spiders
        nid += 1
        extra.append(f"GRID    {nid:>8d}        " + "".join(
            f"{_f8(v):>8}" for v in (x[corner - 1], y[corner - 1], z[corner - 1] - 0.05)))
        eid += 1
        extra.append(f"CBUSH   {eid:>8d}       3{corner:>8d}{nid:>8d}                        0")
        eid += 1
        extra.append(f"CELAS2  {eid:>8d}    1.+5{nid:>8d}       3")
        extra.append(f"SPC1           1  123456{nid:>8d}")
        nid += 1
        c = corner - 1
        extra.append(f"GRID    {nid:>8d}        " + "".join(
            f"{_f8(v):>8}" for v in (x[c], y[c], z[c] + 0.1)))
        eid += 1
        row = [g for g in (corner, corner + 1, corner - 1, corner + n, corner - n)
               if 1 <= g <= n * n][:4]
        extra.append(f"RBE3    {eid:>8d}        {nid:>8d}  123456     1.0     123"
                     + "".join(f"{g:>8d}" for g in row[:2]))
        extra.append("        " + "".join(f"{g:>8d}" for g in row[2:]))
        eid += 1
        extra.append(f"CONM2   {eid:>8d}{nid:>8d}             25.")
    lines += extra + ["ENDDATA"]
    path.write_text("\n".join(lines) + "\n")
    return {"grids": nid, "shells": n_shell, "cards": len(lines)}


_CHILD = """
import json, resource, sys, time, warnings
sys.path.insert(0, sys.argv[3])
t0 = time.perf_counter()
from flexpipe.mesh import read_mesh
with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    mesh = read_mesh(sys.argv[1])
t = time.perf_counter() - t0
json.dump({"read_s": t, "peak_GB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20,
           "nodes": int(mesh.n_nodes), "cells": int(sum(len(b) for b in mesh.blocks)),
           "interpolations": len(mesh.interpolations), "spc": mesh.solution.get("spc")},
          open(sys.argv[2], "w"))
"""


def _split_floor(path: Path) -> float:
    """Seconds to read the text and cut every line into 8-character fields."""
    t0 = time.perf_counter()
    text = path.read_text(encoding="latin-1")
    cuts = tuple(slice(8 + 8 * k, 16 + 8 * k) for k in range(8))
    n = 0
    for ln in text.splitlines():
        n += len([ln[s].strip() for s in cuts])
    return time.perf_counter() - t0


def run() -> dict:
    """Write the deck, time the reader (child process) and the split floor."""
    with tempfile.TemporaryDirectory() as tmp:
        deck = Path(tmp) / "body_1M.bdf"
        t0 = time.perf_counter()
        counts = write_deck(deck)
        res = {"deck_write_s": time.perf_counter() - t0, "deck_MB": deck.stat().st_size / 1e6,
               **{f"deck_{k}": v for k, v in counts.items()}}
        out = Path(tmp) / "res.json"
        subprocess.run([sys.executable, "-c", _CHILD, str(deck), str(out), str(ROOT)],
                       check=True, cwd=ROOT)
        child = json.loads(out.read_text())
        res.update({f"read_{k}" if not k.startswith("read") else k: v
                    for k, v in child.items()})
        res["text_split_s"] = _split_floor(deck)
    res["read_over_split"] = res["read_s"] / res["text_split_s"]
    res["target_read_s"] = 20.0
    res["target_peak_GB"] = 4.0
    res["meets_targets"] = bool(res["read_s"] < 20.0 and res["read_peak_GB"] < 4.0)
    res["parent_peak_GB"] = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20
    return res


if __name__ == "__main__":
    for key, value in run().items():
        print(f"{key:28s} {value:.4g}" if isinstance(value, float) else f"{key:28s} {value}")
