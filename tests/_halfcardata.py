"""The paper's half-car parameter file and edited copies of it (shared by the tests)."""

from __future__ import annotations

from pathlib import Path

DATA = Path(__file__).resolve().parents[1] / "cars" / "halfcar_paper.toml"


def variant(tmp_path, *edits, name="variant.toml") -> Path:
    """The paper's parameter file with ``(old, new)`` text replacements."""
    text = DATA.read_text()
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    path = tmp_path / name
    path.write_text(text)
    return path
