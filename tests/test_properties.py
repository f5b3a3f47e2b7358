"""Property-based tests (hypothesis) of the readers: a mutated valid file loads to the
same model or raises a flexpipe error - never any other exception.

Two kinds of mutation of each valid file:

* arbitrary byte edits (flip, delete, insert, duplicate a span, truncate): the reader
  must answer with a :class:`~flexpipe.errors.FlexpipeError` or a model;
* meaning-preserving edits (comment and blank lines, spacing, member order): the reader
  must return the same model as for the original file.
"""

from __future__ import annotations

import io
import warnings
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from flexpipe.errors import FlexpipeError
from tests.badinput import gen_body, gen_cars, gen_meshes, runner

SETTINGS = settings(max_examples=40, deadline=None, derandomize=True,
                    suppress_health_check=[HealthCheck.function_scoped_fixture,
                                           HealthCheck.too_slow])
SPEC = (b'# spec\nradius = 0.05\n\n[[interface]]\nname = "a"\npoint = [0.0, 0.0, 0.0]\n\n'
        b'[[interface]]\nname = "b"\npoint = [1.0, 0.5, 0.0]\nnodes = [1, 2, 3]\n\n'
        b'[[interface]]\nname = "c"\npoint = [2.0, 0.0, 0.0]\nnode_set = "tow"\n')


def _valid():
    files = gen_meshes.valid_files()
    out = {"interfaces.toml": SPEC, "car.toml": gen_cars.base_text().encode(),
           "body.npz": gen_body.npz(gen_body.valid())}
    for name in ("msh22", "msh41", "vtu", "vtk", "stl", "stl-bin", "obj", "off"):
        fname, data = files[name]
        out[f"{name}:{fname}"] = data
    return out


VALID = _valid()


@st.composite
def byte_edits(draw, data: bytes):
    data = bytearray(data)
    for _ in range(draw(st.integers(1, 4))):
        if not data:
            break
        op = draw(st.sampled_from(["flip", "delete", "insert", "duplicate", "truncate"]))
        i = draw(st.integers(0, len(data) - 1))
        if op == "flip":
            data[i] ^= draw(st.integers(1, 255))
        elif op == "delete":
            del data[i:i + draw(st.integers(1, 16))]
        elif op == "insert":
            data[i:i] = draw(st.binary(min_size=1, max_size=8))
        elif op == "duplicate":
            j = min(len(data), i + draw(st.integers(1, 64)))
            data[i:i] = data[i:j]
        else:
            del data[i:]
    return bytes(data)


def _load(tmp_path, key: str, content: bytes):
    fname = key.split(":")[-1]
    folder = tmp_path / f"case{abs(hash(content)) % 10**9}"
    folder.mkdir(exist_ok=True)
    path = folder / fname
    path.write_bytes(content)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return runner.load(runner.kind_of(fname), path)


@pytest.mark.parametrize("key", sorted(VALID))
def test_valid_file_loads(tmp_path, key):
    assert _load(tmp_path, key, VALID[key]) is not None


@pytest.mark.parametrize("key", sorted(VALID))
def test_byte_edits_give_a_model_or_a_flexpipe_error(tmp_path, key):
    @SETTINGS
    @given(content=byte_edits(VALID[key]))
    def check(content):
        try:
            _load(tmp_path, key, content)
        except FlexpipeError as exc:
            assert Path(key.split(":")[-1]).name in str(exc)

    check()


def _comment_edits(text: str, positions, style: str) -> str:
    lines = text.splitlines()
    for p in sorted(positions, reverse=True):
        k = p % (len(lines) + 1)
        # only between tables/entries: before a line that starts a table or a key
        if k < len(lines) and lines[k].strip().startswith(("[", "#")) or k == len(lines):
            lines.insert(k, style)
    return "\n".join(lines) + "\n"


@pytest.mark.parametrize("key", ["interfaces.toml", "car.toml"])
def test_comments_and_blank_lines_keep_the_model(tmp_path, key):
    ref = _load(tmp_path, key, VALID[key])

    @SETTINGS
    @given(positions=st.lists(st.integers(0, 10**6), min_size=1, max_size=6),
           style=st.sampled_from(["", "# a comment", "   ", "#[[interface]]", "\t# x = 1"]))
    def check(positions, style):
        got = _load(tmp_path, key, _comment_edits(VALID[key].decode(), positions,
                                                  style).encode())
        if key == "interfaces.toml":
            assert got == ref
        else:
            assert _car_equal(got, ref)

    check()


def _car_equal(a, b) -> bool:
    """Every field but the file's own path, compared through repr (arrays included)."""
    from dataclasses import fields

    with np.printoptions(precision=17, threshold=10**6):
        return all(repr(getattr(a, f.name)) == repr(getattr(b, f.name))
                   for f in fields(a) if f.name != "file")


@SETTINGS
@given(order=st.permutations(sorted(k for k in gen_body.valid())))
def test_member_order_keeps_the_body(tmp_path, order):
    v = gen_body.valid()
    ref = _load(tmp_path, "body.npz", gen_body.npz(v))
    got = _load(tmp_path, "body.npz", gen_body.npz({k: v[k] for k in order}))
    assert got == ref


@SETTINGS
@given(spaces=st.lists(st.sampled_from([" ", "  ", "\t"]), min_size=1, max_size=3),
       scale=st.sampled_from([1.0, 1.0 + 1e-15]))
def test_stl_spacing_keeps_the_mesh(tmp_path, spaces, scale):
    tris = gen_meshes._square()
    text = gen_meshes.ascii_stl(tris)
    sep = "".join(spaces)
    spaced = "\n".join(sep + ln.replace(" ", sep) for ln in text.splitlines()) + "\n"
    ref = _load(tmp_path, "mesh.stl", text.encode())
    got = _load(tmp_path, "mesh.stl", spaced.encode())
    np.testing.assert_array_equal(got.nodes, ref.nodes)
    assert (got.K != ref.K).nnz == 0


def test_obj_comments_keep_the_mesh(tmp_path):
    _, data = gen_meshes.valid_files()["obj"]
    ref = _load(tmp_path, "mesh.obj", data)
    commented = b"# header\n" + data.replace(b"\nf", b"\n# face follows\nf")
    got = _load(tmp_path, "mesh.obj", commented)
    np.testing.assert_array_equal(got.nodes, ref.nodes)
    assert (got.K != ref.K).nnz == 0


def test_npz_is_not_loaded_with_pickles(tmp_path):
    """A body file holding an object array is refused without numpy's allow_pickle hint."""
    v = gen_body.valid()
    buf = io.BytesIO()
    np.savez(buf, **{**v, "K": np.array([object()], dtype=object)})
    with pytest.raises(FlexpipeError) as info:
        _load(tmp_path, "body.npz", buf.getvalue())
    assert "allow_pickle" not in str(info.value)
