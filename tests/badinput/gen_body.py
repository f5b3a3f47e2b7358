"""Bad FlexBody files (.npz) for ``load_body``: damaged archives, headers, arrays, bodies.

Every mutation of an array is made twice: with the stored content hash kept (caught by
the hash) and with the hash removed, as in a file written before hashes existed (caught
by the physical consistency checks).
"""

from __future__ import annotations

import io
import json
import pickle
import zipfile
from functools import lru_cache

import numpy as np

ARRAYS = ("nodes", "triangles", "modes", "frequencies_hz", "M", "K", "D", "damping_ratio",
          "center_of_mass", "inertia", "inertia_origin")


@lru_cache(maxsize=1)
def valid() -> dict:
    """Arrays of a small valid body (Craig-Bampton bar, two interfaces)."""
    import flexpipe
    from flexpipe.fem import Material, assemble
    from flexpipe.mesh.generate import box
    from flexpipe.reduction import Interface

    fe = assemble(box(1.0, 0.1, 0.1, 6, 2, 2), Material(E=210e9, nu=0.3, rho=7850.0))
    body = flexpipe.reduce(fe, [Interface((0.0, 0.05, 0.05), radius=0.06, name="a"),
                                Interface((1.0, 0.05, 0.05), radius=0.06, name="b")],
                           method="craig-bampton", n_modes=4)
    buf = io.BytesIO()
    from flexpipe.flexbody.body import _to_arrays

    np.savez(buf, **_to_arrays(body, with_hash=True))
    with np.load(io.BytesIO(buf.getvalue())) as d:
        return {k: d[k] for k in d.files}


def npz(arrays: dict) -> bytes:
    buf = io.BytesIO()
    np.savez(buf, **arrays)
    return buf.getvalue()


def header(arrays) -> dict:
    return json.loads(str(arrays["header"]))


def with_header(arrays, **changes) -> dict:
    h = header(arrays)
    for k, v in changes.items():
        if v is _DROP:
            h.pop(k, None)
        else:
            h[k] = v
    out = dict(arrays)
    out["header"] = np.array(json.dumps(h))
    return out


_DROP = object()


def nohash(arrays) -> dict:
    return with_header(arrays, content_sha256=_DROP)


def changed(key, f):
    def make(a):
        out = dict(a)
        out[key] = f(np.array(a[key], copy=True))
        return out
    return make


def _nan(a):
    a = a.astype(float)
    a.flat[a.size // 2] = np.nan
    return a


def _inf(a):
    a = a.astype(float)
    a.flat[-1] = np.inf
    return a


def _crc(data: bytes, member: str) -> bytes:
    with zipfile.ZipFile(io.BytesIO(data)) as z:
        info = z.getinfo(member)
    raw = bytearray(data)
    n = int.from_bytes(raw[info.header_offset + 26:info.header_offset + 28], "little")
    e = int.from_bytes(raw[info.header_offset + 28:info.header_offset + 30], "little")
    raw[info.header_offset + 30 + n + e + info.compress_size - 1] ^= 0x5A
    return bytes(raw)


def cases():
    v = valid()
    good = npz(v)
    m = len(v["frequencies_hz"])
    n = len(v["nodes"])
    yield "valid", "body.npz", good, "ok"
    yield "valid-without-hash", "body.npz", npz(nohash(v)), "ok"
    # ---- whole file
    yield "empty", "body.npz", b"", "error:file"
    for size in (1, 10, 100, 4096):
        yield f"random-{size}", "body.npz", np.random.default_rng(size).bytes(size), \
            "error:file"
    yield "text", "body.npz", b"this is not a body\n", "error:file"
    for frac in (0.05, 0.2, 0.4, 0.6, 0.8, 0.95, 0.99):
        yield f"truncated-{frac}", "body.npz", good[: int(len(good) * frac)], "error:file"
    buf = io.BytesIO()
    np.save(buf, np.zeros(3))
    yield "npy-not-npz", "body.npz", buf.getvalue(), "error:file"
    yield "zip-of-text", "body.npz", _zip({"readme.txt": b"hello"}), "error"
    yield "pickled-object-array", "body.npz", npz({**v, "K": np.array([{"a": 1}],
                                                                      dtype=object)}), "error"
    yield "pickle-file", "body.npz", pickle.dumps({"K": [1, 2]}), "error:file"
    for member in ("K.npy", "header.npy", "modes.npy", "interface.0.nodes.npy"):
        yield f"crc-{member}", "body.npz", _crc(good, member), "error"
    # ---- header
    yield "no-header", "body.npz", npz({k: x for k, x in v.items() if k != "header"}), "error"
    yield "header-not-json", "body.npz", npz({**v, "header": np.array("{oops")}), "error"
    yield "header-list", "body.npz", npz({**v, "header": np.array("[1, 2]")}), "error"
    yield "header-number-array", "body.npz", npz({**v, "header": np.zeros(3)}), "error"
    bad_header = {
        "format": ["other", 5, None], "version": [2, "1", None, 0],
        "n_rigid": [-1, m + 1, "6", 2.5, True], "mass": [-1.0, 0.0, "heavy", None],
        "method": [5], "meta": [[1, 2], "x"], "interfaces": ["ab", [{"name": "a"}],
                                                            [{"kind": "rbe2"}], [1, 2]],
        "checks": [["nonexistent"], [1]], "source_hash": [7],
    }
    for key, values in bad_header.items():
        for j, val in enumerate(values):
            yield f"header-{key}-{j}", "body.npz", npz(nohash(with_header(v, **{key: val}))), \
                "error"
    yield "header-mass-nan", "body.npz", npz(nohash(with_header(v, mass=float("nan")))), \
        "error"
    yield "header-mass-changed-hash-kept", "body.npz", \
        npz(with_header(v, mass=2 * header(v)["mass"])), "error"
    for key in ("format", "version", "n_rigid", "mass", "interfaces", "checks"):
        yield f"header-missing-{key}", "body.npz", npz(nohash(with_header(v, **{key: _DROP}))),\
            "error"
    # ---- arrays: missing, NaN, inf, shape, dtype; hash kept and removed
    muts = {}
    for key in ARRAYS:
        muts[f"{key}-missing"] = lambda a, k=key: {x: y for x, y in a.items() if x != k}
        if key != "triangles":
            muts[f"{key}-nan"] = changed(key, _nan)
            muts[f"{key}-inf"] = changed(key, _inf)
        muts[f"{key}-shape"] = changed(key, lambda a: a.reshape(-1)[:-1])
        muts[f"{key}-text"] = changed(key, lambda a: np.array(["x"] * max(a.size, 1)))
    muts.update({
        "K-scaled": changed("K", lambda a: 1.1 * a),
        "K-negative": changed("K", lambda a: -a),
        "M-scaled": changed("M", lambda a: 2.0 * a),
        "inertia-scaled": lambda a: changed("inertia_origin", lambda x: 1.1 * x)(
            changed("inertia", lambda x: 1.1 * x)(a)),
        "inertia-asymmetric": changed("inertia", lambda a: a + np.triu(np.ones((3, 3)), 1)),
        "inertia-negative": changed("inertia", lambda a: -a),
        "com-moved": changed("center_of_mass", lambda a: a + 0.1),
        "frequency-negative": changed("frequencies_hz", _negative_last),
        "frequencies-unsorted": changed("frequencies_hz", lambda a: a[::-1].copy()),
        "frequencies-scaled": changed("frequencies_hz", lambda a: 2 * a),
        "damping-negative": changed("damping_ratio", lambda a: -np.abs(a) - 0.1),
        "triangle-index-too-big": changed("triangles", lambda a: _set_last(a, n + 5)),
        "triangle-index-negative": changed("triangles", lambda a: _set_last(a, -1)),
        "triangles-two-columns": changed("triangles", lambda a: a[:, :2].copy()),
        "interface-node-too-big": changed("interface.0.nodes", lambda a: _set_last(a, n)),
        "interface-node-negative": changed("interface.1.nodes", lambda a: _set_last(a, -3)),
        "interface-shapes-shape": changed("interface.0.shapes", lambda a: a[:, :-1].copy()),
        "interface-shapes-nan": changed("interface.1.shapes", _nan),
        "interface-point-nan": changed("interface.0.point", _nan),
        "interface-point-missing": lambda a: {x: y for x, y in a.items()
                                              if x != "interface.1.point"},
        "invariant-nan": changed("invariants.mPsiTildePsi", _nan),
        "invariant-missing": lambda a: {x: y for x, y in a.items()
                                        if x != "invariants.mPhitTPsi"},
        "modes-scaled": changed("modes", lambda a: 3.0 * a),
        "nodes-empty": changed("nodes", lambda a: np.zeros((0, 3))),
        "frequencies-empty": changed("frequencies_hz", lambda a: np.zeros(0)),
    })
    for name, f in muts.items():
        yield f"{name}-hash-kept", "body.npz", npz(f(v)), "error"
        yield f"{name}-no-hash", "body.npz", npz(f(nohash(v))), "error"
    yield "extra-entry-no-hash", "body.npz", npz({**nohash(v), "notes": np.zeros(2)}), "ok"
    yield "extra-entry-hash-kept", "body.npz", npz({**v, "notes": np.zeros(2)}), "error"


def _negative_last(a):
    a = a.copy()
    a[-1] = -abs(a[-1])
    return a


def _set_last(a, value):
    a = a.copy()
    a.flat[-1] = value
    return a


def _zip(members: dict) -> bytes:
    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as z:
        for k, x in members.items():
            z.writestr(k, x)
    return buf.getvalue()
