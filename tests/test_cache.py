"""Cache integrity (issue 14): every kind of damaged entry is detected and rebuilt.

The reference is the body/mass properties computed from scratch: a damaged entry must
never be returned; after the rebuild the entry equals a fresh computation.
"""

from __future__ import annotations

import json
import multiprocessing as mp
import os
import time
import zipfile
from pathlib import Path

import numpy as np
import pytest

import flexpipe
from flexpipe.fem import Material, assemble
from flexpipe.mesh.generate import box
from flexpipe.reduction import Interface
from flexpipe.vehicle import _cache

ROOT = Path(__file__).resolve().parents[1]
KEY = "k" * 64


@pytest.fixture(scope="module")
def body():
    fe = assemble(box(1.0, 0.1, 0.1, 8, 2, 2), Material(E=210e9, nu=0.3, rho=7850.0))
    itfs = [Interface((0.0, 0.05, 0.05), radius=0.06, name="a"),
            Interface((1.0, 0.05, 0.05), radius=0.06, name="b")]
    return flexpipe.reduce(fe, itfs, method="craig-bampton", n_modes=4)


def _rewrite(path: Path, **changes):
    """Rewrite the npz with some arrays changed but the header (and its hash) kept."""
    with np.load(path) as d:
        data = {k: d[k] for k in d.files}
    for k, f in changes.items():
        data[k] = f(data[k].copy())
    with open(path, "wb") as fh:
        np.savez(fh, **data)


def _flip_member_byte(path: Path, member: str):
    """Flip one data byte of a stored (uncompressed) zip member: its CRC no longer fits."""
    with zipfile.ZipFile(path) as z:
        info = z.getinfo(member)
    raw = bytearray(path.read_bytes())
    # local header: 30 bytes + name + extra; then the data (the .npy header, then numbers)
    n, e = int.from_bytes(raw[info.header_offset + 26:info.header_offset + 28], "little"), \
        int.from_bytes(raw[info.header_offset + 28:info.header_offset + 30], "little")
    pos = info.header_offset + 30 + n + e + info.compress_size - 3
    raw[pos] ^= 0xFF
    path.write_bytes(bytes(raw))


def _nan_k(K):
    K[-1, -1] = np.nan
    return K


DAMAGE = {
    "crc-corrupt K member": lambda p: _flip_member_byte(p, "K.npy"),
    "NaN in K": lambda p: _rewrite(p, K=_nan_k),
    "K scaled by 1.1": lambda p: _rewrite(p, K=lambda K: 1.1 * K),
    "inertia scaled by 1.1": lambda p: _rewrite(p, inertia=lambda J: 1.1 * J,
                                                inertia_origin=lambda J: 1.1 * J),
    "mode shapes scaled": lambda p: _rewrite(p, modes=lambda X: 2.0 * X),
    "truncated file": lambda p: p.write_bytes(p.read_bytes()[: len(p.read_bytes()) // 2]),
    "zero bytes": lambda p: p.write_bytes(b""),
    "garbage": lambda p: p.write_bytes(os.urandom(4096)),
}


def test_good_entry_round_trips(tmp_path, body):
    path = tmp_path / "body-x.npz"
    saved = _cache.save_cached_body(body, path, KEY)
    back = _cache.load_cached_body(path, KEY)
    assert back == saved
    np.testing.assert_array_equal(back.K, body.K)


@pytest.mark.parametrize("damage", sorted(DAMAGE))
def test_damaged_body_entry_is_rejected_with_warning(tmp_path, body, damage):
    path = tmp_path / "body-x.npz"
    _cache.save_cached_body(body, path, KEY)
    DAMAGE[damage](path)
    with pytest.warns(_cache.CacheWarning, match=str(path.name)):
        assert _cache.load_cached_body(path, KEY) is None


def test_entry_for_other_inputs_is_rejected(tmp_path, body):
    path = tmp_path / "body-x.npz"
    _cache.save_cached_body(body, path, KEY)
    with pytest.warns(_cache.CacheWarning, match="other inputs"):
        assert _cache.load_cached_body(path, "z" * 64) is None


MASS_DAMAGE = {
    "garbage JSON": lambda p: p.write_text("{not json"),
    "zero bytes": lambda p: p.write_text(""),
    "mass doubled": lambda p: p.write_text(json.dumps(
        {**json.loads(p.read_text()), "mass": 2 * json.loads(p.read_text())["mass"]})),
    "inertia scaled": lambda p: p.write_text(json.dumps({
        **json.loads(p.read_text()),
        "inertia": (1.1 * np.array(json.loads(p.read_text())["inertia"])).tolist()})),
    "old layout without hash": lambda p: p.write_text(json.dumps(
        {k: v for k, v in json.loads(p.read_text()).items() if k != "sha256"})),
    "list instead of object": lambda p: p.write_text("[1, 2, 3]"),
}


@pytest.mark.parametrize("damage", sorted(MASS_DAMAGE))
def test_damaged_massprops_entry_is_rejected(tmp_path, damage):
    path = tmp_path / "massprops-x.json"
    J = np.diag([10.0, 20.0, 25.0])
    _cache.save_massprops(path, KEY, 100.0, [0.1, 0.0, 0.3], J)
    m, c, J2 = _cache.load_massprops(path, KEY)
    assert m == 100.0 and np.array_equal(J2, J)
    MASS_DAMAGE[damage](path)
    with pytest.warns(_cache.CacheWarning):
        assert _cache.load_massprops(path, KEY) is None


def test_stale_temp_files_are_cleaned(tmp_path):
    old = tmp_path / ".body-x.npz.abc123.npz"
    old.write_bytes(b"")  # a writer killed mid-write
    fresh = tmp_path / ".body-y.npz.def456.npz"
    fresh.write_bytes(b"")  # a writer at work right now
    t = time.time() - 2 * _cache.STALE_AGE_S
    os.utime(old, (t, t))
    assert _cache.clean_stale(tmp_path) == [old]
    assert not old.exists() and fresh.exists()


def test_rigid_properties_rebuild_a_corrupt_entry(tmp_path, monkeypatch):
    """End to end on the sample car: garbage JSON -> warning, recomputed, same numbers."""
    from flexpipe.vehicle import bodymodel, load_car

    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path))
    car = load_car(ROOT / "cars" / "sedan.toml")
    ref = bodymodel.rigid_properties(car)  # computed from the FE model (empty cache)
    first = bodymodel.rigid_properties(car)  # from the cache
    (entry,) = tmp_path.glob("massprops-*.json")
    entry.write_text('{"mass": 1.0, "cg": [0, 0, 0], "inertia": "garbage"}')
    with pytest.warns(_cache.CacheWarning, match=entry.name):
        again = bodymodel.rigid_properties(car)
    assert again.mass == ref.mass == first.mass
    np.testing.assert_array_equal(again.inertia, ref.inertia)
    assert _cache.load_massprops(entry, json.loads(entry.read_text())["key"]) is not None


def _writer(path, key, body, n, errors):
    try:
        for _ in range(n):
            _cache.save_cached_body(body, path, key)
    except BaseException as exc:  # noqa: BLE001 - reported to the parent
        errors.put(repr(exc))


def test_concurrent_writers_never_corrupt_the_entry(tmp_path, body):
    """Two processes rewrite the same entry while this one reads it: every read that finds
    the file gets the complete, verified body; no temporary file is left."""
    path = tmp_path / "body-x.npz"
    ctx = mp.get_context("fork")
    errors = ctx.Queue()
    procs = [ctx.Process(target=_writer, args=(path, KEY, body, 15, errors)) for _ in range(2)]
    for p in procs:
        p.start()
    reads = 0
    while any(p.is_alive() for p in procs):
        if path.exists():
            got = _cache.load_cached_body(path, KEY)
            assert got is not None and np.array_equal(got.K, body.K)
            reads += 1
    for p in procs:
        p.join()
    assert errors.empty()
    assert reads > 0
    assert _cache.load_cached_body(path, KEY) is not None
    assert [p.name for p in tmp_path.iterdir()] == ["body-x.npz"]


def _reduce_sedan(cache, errors):
    try:
        os.environ["FLEXPIPE_CACHE"] = str(cache)
        from flexpipe.vehicle import bodymodel, load_car

        bodymodel.reduced_body(load_car(ROOT / "cars" / "sedan.toml"), f_max=20.0,
                               log=lambda *a: None)
    except BaseException as exc:  # noqa: BLE001 - reported to the parent
        errors.put(repr(exc))


def test_two_processes_reduce_the_same_body_then_a_damaged_entry_is_rebuilt(tmp_path,
                                                                            monkeypatch):
    from flexpipe.vehicle import bodymodel, load_car

    ctx = mp.get_context("fork")
    errors = ctx.Queue()
    procs = [ctx.Process(target=_reduce_sedan, args=(tmp_path, errors)) for _ in range(2)]
    for p in procs:
        p.start()
    for p in procs:
        p.join(300)
    assert errors.empty()
    assert len(list(tmp_path.glob("body-*.npz"))) == 1
    assert not list(tmp_path.glob(".*"))
    monkeypatch.setenv("FLEXPIPE_CACHE", str(tmp_path))
    car = load_car(ROOT / "cars" / "sedan.toml")
    cached, info = bodymodel.reduced_body(car, f_max=20.0, log=lambda *a: None)
    assert info["cached"]
    entry = Path(info["path"])
    _rewrite(entry, K=lambda K: 1.1 * K)  # a plausible but wrong stiffness
    with pytest.warns(_cache.CacheWarning, match="content hash"):
        fresh, info2 = bodymodel.reduced_body(car, f_max=20.0, log=lambda *a: None)
    assert not info2["cached"]
    np.testing.assert_allclose(fresh.frequencies_hz, cached.frequencies_hz, rtol=1e-9)
    again, info3 = bodymodel.reduced_body(car, f_max=20.0, log=lambda *a: None)
    assert info3["cached"] and again == fresh
