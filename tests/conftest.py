"""Shared pytest fixtures."""

from __future__ import annotations

import os
import resource
from pathlib import Path

import matplotlib
import pytest

import flexpipe.exu  # noqa: F401  (chooses Exudyn's compiled module before any test imports it)

matplotlib.use("Agg")
os.environ.setdefault("MPLBACKEND", "Agg")

#: address space of a test process (GiB): a test that allocates without bound (a damaged
#: road that once asked for 27 GB) fails with MemoryError, naming itself, instead of the
#: kernel's OOM killer taking a pytest-xdist worker down and leaving the run hanging
MEMORY_CAP_GB = float(os.environ.get("FLEXPIPE_TEST_MEMORY_GB", "10"))


def _cap_memory(gib: float) -> None:
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    cap = int(gib * 2**30)
    if hard != resource.RLIM_INFINITY:
        cap = min(cap, hard)
    if soft == resource.RLIM_INFINITY or soft > cap:
        resource.setrlimit(resource.RLIMIT_AS, (cap, hard))


if MEMORY_CAP_GB > 0:
    _cap_memory(MEMORY_CAP_GB)

REPO = Path(__file__).resolve().parents[1]
REFERENCE = REPO.parent / "shared" / "reference"


@pytest.fixture
def reference_dir() -> Path:
    """``../shared/reference`` (real third-party files); skips when a clone has none."""
    if not REFERENCE.is_dir():
        pytest.skip("../shared/reference is not present next to this clone")
    return REFERENCE
