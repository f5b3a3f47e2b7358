"""Helpers shared by the mesh test modules: write a text file, wrap Nastran cards."""

from __future__ import annotations

from flexpipe.fem import Material

STEEL = Material(210e9, 0.3, 7850.0)


def write(tmp_path, name, text):
    """Write ``text`` to ``tmp_path / name`` and return the path."""
    p = tmp_path / name
    p.write_text(text)
    return p


def deck(*cards):
    """A bulk-data deck of ``cards`` between BEGIN BULK and ENDDATA."""
    return "BEGIN BULK\n" + "\n".join(cards) + "\nENDDATA\n"
