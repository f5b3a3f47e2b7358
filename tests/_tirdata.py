"""Tire test data shared by the tire test modules: file locations and a raw reader.

``raw_numbers`` reads ``KEY = number`` lines straight from a ``.tir`` text with a regular
expression, independently of :func:`flexpipe.tires.read_tir`, so that tests can compare
the model against the file itself.
"""

from __future__ import annotations

import re
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
SAMPLE = REPO / "tires" / "sedan_205_55R16.tir"
REFERENCE_TIRS = ["Sedan_Pac02Tire.tir", "mf_185_80R14.tir", "HMMWV_Pac02Tire.tir"]


def raw_numbers(path: Path) -> dict[str, float]:
    """KEY -> number straight from the text (keys are unique across sections in these files)."""
    out = {}
    for line in path.read_text(errors="replace").splitlines():
        m = re.match(r"\s*([A-Z][A-Z0-9_]*)\s*=\s*([-+0-9.eE]+)\s*(\$.*)?$", line.strip())
        if m:
            out[m.group(1)] = float(m.group(2))
    return out
