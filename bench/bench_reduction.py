"""Reduction benchmarks: flexpipe's Craig-Bampton against Exudyn's, and large bodies.

Cases (each in its own process, so that its peak memory is its own):

``cb_vs_exudyn``
    The same >= 50k-DOF tet4 block, the same four interface node sets (RBE2) and ten
    fixed-interface modes, reduced side by side by
    ``exudyn.FEM.FEMinterface.ComputeHurtyCraigBamptonModes`` (RBE2 mode) and by
    ``flexpipe.reduce(..., method="craig-bampton")``.  Target: flexpipe >= 10x faster,
    reduced free-free frequencies equal to 1e-6 relative.  Exudyn's basis has no
    rigid-body modes (its floating frame adds them), so its free-free frequencies are
    those of ``[rigid-body modes, Exudyn basis]``, which spans the same space as the
    full Craig-Bampton basis.
``shell_500k``
    A closed box-shaped shell body (car-body-like, 4.6 x 1.5 x 1.2 m, quad shells,
    ~500k DOF) reduced to 30 modes (24 static + 6 fixed-interface) with 4 interfaces.
``solid_200k``
    A ~200k-DOF tet4 block reduced likewise.  Target for both: < 2 min, < 12 GB.

``python -m bench.bench_reduction [case ...]`` runs a subset.
"""

from __future__ import annotations

import json
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
STEEL = dict(E=210e9, nu=0.3, rho=7850.0)
CASES = ("cb_vs_exudyn", "shell_500k", "solid_200k")


def _peak_rss_gb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20


def _corner_interfaces(points, corners, radius):
    import flexpipe

    return [flexpipe.Interface(c, radius=radius, name=f"mount{k + 1}")
            for k, c in enumerate(corners)]


def _solid(L, b, h, nx, ny, nz):
    from flexpipe.fem import Material, assemble
    from flexpipe.mesh.generate import box

    mesh = box(L, b, h, nx, ny, nz)
    return assemble(mesh, Material(**STEEL))


def _rigid_vectors(nodes):
    from flexpipe.flexbody.invariants import rigid_body_vectors

    return rigid_body_vectors(nodes, 3)


def case_cb_vs_exudyn(n_modes: int = 10) -> dict:
    """flexpipe vs Exudyn Craig-Bampton on the same matrices and node sets."""
    import exudyn.FEM as efem

    import flexpipe
    from flexpipe.reduction.cms import orthonormalize

    fe = _solid(3.0, 0.75, 1.0, 60, 15, 20)  # 61,488 DOF
    corners = [(0.3, 0.0, 0.0), (0.3, 0.75, 0.0), (2.7, 0.0, 0.0), (2.7, 0.75, 0.0)]
    itfs = _corner_interfaces(fe.nodes, corners, 0.12)
    node_sets = [np.flatnonzero(np.linalg.norm(fe.nodes - c, axis=1) <= 0.12 + 1e-12)
                 for c in corners]
    # flexpipe gets the very same node sets (hardpoint = their centroid, as Exudyn's)
    itfs = [flexpipe.Interface(tuple(fe.nodes[s].mean(axis=0)), nodes=s, name=i.name)
            for s, i in zip(node_sets, itfs, strict=True)]
    fem = efem.FEMinterface()
    fem.nodes = {"Position": np.array(fe.nodes)}
    fem.stiffnessMatrix = fe.K.tocsr()
    fem.massMatrix = fe.M.tocsr()

    times_fp = []
    body = None
    for _ in range(2):
        t = time.perf_counter()
        body = flexpipe.reduce(fe, itfs, method="craig-bampton", n_modes=n_modes)
        times_fp.append(time.perf_counter() - t)
    t = time.perf_counter()
    fem.ComputeHurtyCraigBamptonModes(boundaryNodesList=[list(s) for s in node_sets],
                                      nEigenModes=n_modes, useSparseSolver=True,
                                      computationMode=efem.HCBstaticModeSelection.RBE2)
    t_exu = time.perf_counter() - t
    t = time.perf_counter()
    body = flexpipe.reduce(fe, itfs, method="craig-bampton", n_modes=n_modes)
    times_fp.append(time.perf_counter() - t)

    basis = np.hstack([_rigid_vectors(fe.nodes), fem.modeBasis["matrix"]])
    _, omega_exu = orthonormalize(fe.M, fe.K, basis)
    f_exu = omega_exu[6:] / (2 * np.pi)
    f_fp = body.frequencies_hz[6:]
    rel = np.abs(f_fp / f_exu - 1.0)
    t_fp = float(np.median(times_fp))
    return {
        "cb_dof": int(fe.n_dof), "cb_interfaces": 4, "cb_fixed_modes": n_modes,
        "cb_exudyn_s": round(t_exu, 2), "cb_flexpipe_s_median": round(t_fp, 2),
        "cb_flexpipe_s_runs": [round(v, 2) for v in times_fp],
        "cb_speedup": round(t_exu / t_fp, 1),
        "cb_target_10x_met": bool(t_exu / t_fp >= 10.0),
        "cb_freq_max_rel_diff": float(rel.max()),
        "cb_freq_target_1e-6_met": bool(rel.max() <= 1e-6),
        "cb_first_elastic_hz": round(float(f_fp[0]), 3),
        "cb_flexpipe_stage_s": {k: v for k, v in body.meta.items() if k.endswith("_s")},
        "cb_peak_rss_gb": round(_peak_rss_gb(), 2),
    }


def closed_box_shell(L, b, h, nx, ny, nz, *, thickness=1.0e-3):
    """Quad-shell surface of the block [0, L] x [0, b] x [0, h] (a closed box body)."""
    from flexpipe.mesh.generate import box
    from flexpipe.mesh.mesh import CellBlock, Mesh

    hexes = box(L, b, h, nx, ny, nz, cell="hexahedron")
    from flexpipe.flexbody.surface import _HEX_QUADS, _unique_faces

    q = hexes.blocks[0].cells[:, np.array(_HEX_QUADS)].reshape(-1, 4)
    q = q[_unique_faces(q)]
    used, inv = np.unique(q, return_inverse=True)
    mesh = Mesh(points=hexes.points[used], blocks=(CellBlock("quad", inv.reshape(-1, 4)),),
                cell_sets={"skin": {0: np.arange(len(q))}},
                sections={"skin": {"thickness": thickness}})
    return mesh


def _scale_case(prefix, build_fe, corners, radius) -> dict:
    """Assemble a body, reduce it to 30 modes with 4 corner interfaces, time both."""
    import flexpipe

    t = time.perf_counter()
    fe = build_fe()
    t_asm = time.perf_counter() - t
    itfs = _corner_interfaces(fe.nodes, corners, radius)
    t = time.perf_counter()
    body = flexpipe.reduce(fe, itfs, method="craig-bampton", n_modes=6)
    t_red = time.perf_counter() - t
    rss = _peak_rss_gb()
    return {
        f"{prefix}_dof": int(fe.n_dof), f"{prefix}_assemble_s": round(t_asm, 1),
        f"{prefix}_reduce_s": round(t_red, 1), f"{prefix}_modes_total": body.n_modes,
        f"{prefix}_first_elastic_hz": round(float(body.frequencies_hz[6]), 3),
        f"{prefix}_peak_rss_gb": round(rss, 2),
        f"{prefix}_target_met": bool(t_red < 120 and rss < 12),
    }


def case_shell_500k() -> dict:
    from flexpipe.fem import Material, assemble

    def build():
        mesh = closed_box_shell(4.6, 1.5, 1.2, 250, 82, 66)
        return assemble(mesh, Material(**STEEL), thickness=1.0e-3)

    corners = [(0.4, 0.0, 0.0), (0.4, 1.5, 0.0), (4.2, 0.0, 0.0), (4.2, 1.5, 0.0)]
    return _scale_case("shell", build, corners, 0.06)


def case_solid_200k() -> dict:
    corners = [(0.3, 0.0, 0.0), (0.3, 1.0, 0.0), (2.7, 0.0, 0.0), (2.7, 1.0, 0.0)]
    return _scale_case("solid", lambda: _solid(3.0, 1.0, 0.5, 120, 40, 13), corners, 0.08)


def _run_case(name: str) -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "r.json"
        code = ("import json, sys; from bench import bench_reduction as b; "
                f"json.dump(b.case_{name}(), open(sys.argv[1], 'w'), default=str)")
        proc = subprocess.run([sys.executable, "-c", code, str(out)], cwd=ROOT)
        if proc.returncode != 0 or not out.exists():
            return {f"{name}_status": f"failed (exit code {proc.returncode})"}
        return json.loads(out.read_text())


def run(cases=CASES) -> dict:
    """Run the cases, each in a child process; return their figures in one dict."""
    res = {}
    for name in cases:
        res.update(_run_case(name))
    return res


if __name__ == "__main__":
    names = sys.argv[1:] or list(CASES)
    print(json.dumps(run(names), indent=2, default=str))
