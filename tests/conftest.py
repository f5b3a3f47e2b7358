"""Shared pytest fixtures."""

from __future__ import annotations

import os
from pathlib import Path

import matplotlib
import pytest

import flexpipe.exu  # noqa: F401  (chooses Exudyn's compiled module before any test imports it)

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")

REPO = Path(__file__).resolve().parents[1]
REFERENCE = REPO.parent / "shared" / "reference"


@pytest.fixture
def reference_dir() -> Path:
    """``../shared/reference`` (real third-party files); skips when a clone has none."""
    if not REFERENCE.is_dir():
        pytest.skip("../shared/reference is not present next to this clone")
    return REFERENCE
