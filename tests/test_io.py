"""Atomic writes leave either the old file or the complete new one, never a half."""

import pytest

from flexpipe._io import atomic_path, write_text_atomic
from flexpipe.errors import InputError, SolverError


def test_atomic_write_replaces_complete(tmp_path):
    p = tmp_path / "a.txt"
    write_text_atomic(p, "one")
    write_text_atomic(p, "two")
    assert p.read_text() == "two"
    assert list(tmp_path.iterdir()) == [p]


def test_failed_write_keeps_old_file_and_no_temp(tmp_path):
    p = tmp_path / "a.txt"
    p.write_text("old")
    with pytest.raises(RuntimeError), atomic_path(p) as tmp:
        tmp.write_text("half")
        raise RuntimeError("writer crashed")
    assert p.read_text() == "old"
    assert list(tmp_path.iterdir()) == [p]


def test_error_messages_name_where():
    e = InputError("must be > 0", file="car.toml", line=3, key="mass_kg")
    assert "car.toml" in str(e) and "line 3" in str(e) and "mass_kg" in str(e)
    s = SolverError("Newton did not converge", time=1.25)
    assert "1.25" in str(s) and s.time == 1.25
