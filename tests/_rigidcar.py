"""The sample sedan as a car without mesh: ``[body.rigid]`` mass properties of its
trimmed body (values from ``cars/sedan.toml``'s FE model, rounded), so tests of the
machinery around a run need no FE assembly or reduction."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

RIGID = """[body]
[body.rigid]
mass_kg = 1324.14
cg_m = [-1.2363, 0.0, 0.5790]
inertia_kg_m2 = [421.17, 2132.08, 2299.63, 0.0, -18.43, 0.0]

[body.points]
driver_floor = [-1.55, 0.40, 0.20]
rear_floor = [-2.20, 0.40, 0.20]
"""


def rigid_sedan(folder) -> Path:
    """Write ``sedan_rigid.toml`` into ``folder`` and return its path."""
    text = (ROOT / "cars" / "sedan.toml").read_text()
    start = text.index("[body]")
    end = text.index("[corners.fl]")
    # keep the corner comment block out; tyre paths become absolute
    text = text[:start] + RIGID + "\n" + text[end:]
    tire = (ROOT / "tires" / "sedan_205_55R16.tir").as_posix()
    text = re.sub(r'tire = "[^"]*"', f'tire = "{tire}"', text)
    text = text.replace('name = "sedan"', 'name = "sedan_rigid"')
    path = Path(folder) / "sedan_rigid.toml"
    path.write_text(text)
    return path
