"""FE benchmarks: assembly, eigenmodes and sparse direct solvers on large models.

Targets (2 cores):

* assembly of a 1,000,000-DOF tet4 mesh in under 30 s and 8 GB peak;
* lowest 20 modes of a 150,000-DOF solid block in under 30 s;
* lowest 20 modes of a 500,000-DOF shell structure in under 60 s;
* SciPy SuperLU against MKL PARDISO (pypardiso) on the same >= 100k-DOF shifted
  stiffness: factorization time and peak memory decide the default backend.

Every case runs in its own process so that its peak resident memory (``ru_maxrss``) is
its own.  ``python -m bench.bench_fem [case ...]`` runs a subset.
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


def _peak_rss_gb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 2**20   # KiB -> GiB


def _rss_gb() -> float:
    with open("/proc/self/statm") as fh:
        return int(fh.read().split()[1]) * resource.getpagesize() / 2**30


def _material():
    from flexpipe.fem import Material

    return Material(**STEEL)


class _Counting:
    """Wrap ``factorize`` to time the factorization and count the solves."""

    def __init__(self):
        self.factor_s = 0.0
        self.solves = 0
        self.solve_s = 0.0

    def __enter__(self):
        from flexpipe.fem import modes

        self._modes = modes
        self._orig = modes.factorize

        def factorize(A, **kw):
            t0 = time.perf_counter()
            fac = self._orig(A, **kw)
            self.factor_s += time.perf_counter() - t0
            inner = fac.solve

            def solve(b):
                t1 = time.perf_counter()
                x = inner(b)
                self.solve_s += time.perf_counter() - t1
                self.solves += 1 if np.ndim(b) == 1 else np.shape(b)[1]
                return x

            fac.solve = solve
            return fac

        modes.factorize = factorize
        return self

    def __exit__(self, *exc):
        self._modes.factorize = self._orig


# ----------------------------------------------------------------------------- cases
def case_assembly_1m() -> dict:
    """tet4 block with 70 x 70 x 69 nodes = 1,014,300 DOF."""
    from flexpipe.fem import assemble
    from flexpipe.mesh.generate import box

    t0 = time.perf_counter()
    mesh = box(2.0, 2.0, 2.0, 69, 69, 68, cell="tetra")
    t_mesh = time.perf_counter() - t0
    rss0 = _rss_gb()
    t0 = time.perf_counter()
    fe = assemble(mesh, _material())
    t_asm = time.perf_counter() - t0
    return {
        "assembly_tet4_dof": fe.n_dof,
        "assembly_tet4_elements": len(mesh.blocks[0]),
        "assembly_tet4_nnz_K": int(fe.K.nnz),
        "assembly_tet4_mesh_s": t_mesh,
        "assembly_tet4_s": t_asm,
        "assembly_tet4_peak_rss_GB": _peak_rss_gb(),
        "assembly_tet4_rss_before_GB": rss0,
        "assembly_tet4_target_30s_8GB": bool(t_asm < 30.0 and _peak_rss_gb() < 8.0),
    }


def _eigen_case(prefix: str, fe, n: int, target_s: float) -> dict:
    from flexpipe.fem import eigenmodes

    rss0 = _rss_gb()
    with _Counting() as cnt:
        t0 = time.perf_counter()
        f, _ = eigenmodes(fe, n)
        t_eig = time.perf_counter() - t0
    return {
        f"{prefix}_dof": fe.n_dof,
        f"{prefix}_modes": n,
        f"{prefix}_eigenmodes_s": t_eig,
        f"{prefix}_factor_s": cnt.factor_s,
        f"{prefix}_solves": cnt.solves,
        f"{prefix}_solve_total_s": cnt.solve_s,
        f"{prefix}_f7_Hz": float(f[6]),
        f"{prefix}_f{n}_Hz": float(f[-1]),
        f"{prefix}_max_rigid_Hz": float(f[:6].max()),
        f"{prefix}_peak_rss_GB": _peak_rss_gb(),
        f"{prefix}_rss_before_GB": rss0,
        f"{prefix}_target_{target_s:.0f}s": bool(t_eig < target_s),
    }


def case_eigen_solid_150k() -> dict:
    """Lowest 20 modes of a 2 m x 1 m x 0.5 m steel block, tet4, 153,957 DOF."""
    from flexpipe.fem import assemble
    from flexpipe.mesh.generate import box

    fe = assemble(box(2.0, 1.0, 0.5, 72, 36, 18, cell="tetra"), _material())
    return _eigen_case("eigen_solid", fe, 20, 30.0)


def tube_mesh(width: float, height: float, length: float, n_w: int, n_h: int, n_l: int):
    """Quad shell mesh of an open rectangular tube along x (closed cross-section)."""
    from flexpipe.mesh import CellBlock, Mesh

    def side(a, b, n):
        t = np.linspace(0.0, 1.0, n, endpoint=False)[:, None]
        return a + t * (b - a)

    c = np.array([[0.0, 0.0], [width, 0.0], [width, height], [0.0, height]])
    ring = np.vstack([side(c[0], c[1], n_w), side(c[1], c[2], n_h),
                      side(c[2], c[3], n_w), side(c[3], c[0], n_h)])
    n_r = len(ring)
    x = np.linspace(0.0, length, n_l + 1)
    pts = np.column_stack([np.repeat(x, n_r), np.tile(ring[:, 0], n_l + 1),
                           np.tile(ring[:, 1], n_l + 1)])
    i, j = np.meshgrid(np.arange(n_r), np.arange(n_l), indexing="ij")
    i, j = i.ravel(), j.ravel()
    ip = (i + 1) % n_r
    cells = np.column_stack([j * n_r + i, j * n_r + ip, (j + 1) * n_r + ip, (j + 1) * n_r + i])
    return Mesh(pts, (CellBlock("quad", cells),), cell_sets={"wall": {0: np.arange(len(cells))}})


def case_eigen_shell_500k() -> dict:
    """Lowest 20 modes of a 0.4 m x 0.2 m x 3 m steel box beam, t = 2 mm, 501,120 DOF."""
    from flexpipe.fem import assemble

    t0 = time.perf_counter()
    fe = assemble(tube_mesh(0.4, 0.2, 3.0, 64, 32, 434), _material(), thickness=0.002)
    t_asm = time.perf_counter() - t0
    res = _eigen_case("eigen_shell", fe, 20, 60.0)
    res["eigen_shell_assembly_s"] = t_asm
    return res


def _factor_case(backend: str) -> dict:
    """Factor K - sigma M of a 4:2:1 tet4 block, 109,395 DOF, and solve once."""
    from flexpipe.fem import assemble
    from flexpipe.fem.modes import DEFAULT_SIGMA
    from flexpipe.fem.solver import factorize
    from flexpipe.mesh.generate import box

    fe = assemble(box(2.0, 1.0, 0.5, 64, 32, 16, cell="tetra"), _material())
    A = (fe.Kr - DEFAULT_SIGMA * fe.Mr).tocsr()
    b = fe.Mr @ np.ones(A.shape[0])
    del fe
    rss0 = _rss_gb()
    t0 = time.perf_counter()
    fac = factorize(A, backend=backend)
    t_fac = time.perf_counter() - t0
    t0 = time.perf_counter()
    x = fac.solve(b)
    t_sol = time.perf_counter() - t0
    res = float(np.linalg.norm(A @ x - b) / np.linalg.norm(b))
    p = f"factor_{backend}"
    return {
        f"{p}_dof": A.shape[0],
        f"{p}_nnz_A": int(A.nnz),
        f"{p}_s": t_fac,
        f"{p}_solve_s": t_sol,
        f"{p}_relative_residual": res,
        f"{p}_peak_rss_GB": _peak_rss_gb(),
        f"{p}_rss_before_GB": rss0,
    }


def case_factor_pardiso() -> dict:
    return _factor_case("pardiso")


def case_factor_superlu() -> dict:
    return _factor_case("superlu")


CASES = {
    "assembly_1m": case_assembly_1m,
    "eigen_solid_150k": case_eigen_solid_150k,
    "eigen_shell_500k": case_eigen_shell_500k,
    "factor_pardiso": case_factor_pardiso,
    "factor_superlu": case_factor_superlu,
}
TIMEOUT_S = 1800


def _run_case(name: str) -> dict:
    """Run one case in a child process; failures become a status entry."""
    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "case.json"
        t0 = time.perf_counter()
        try:
            proc = subprocess.run([sys.executable, "-m", "bench.bench_fem", "--child", name,
                                   str(out)], cwd=ROOT, timeout=TIMEOUT_S)
        except subprocess.TimeoutExpired:
            return {f"{name}_status": f"timeout after {TIMEOUT_S} s"}
        if proc.returncode != 0 or not out.exists():
            return {f"{name}_status": f"failed (exit code {proc.returncode}) after "
                                      f"{time.perf_counter() - t0:.0f} s"}
        return json.loads(out.read_text())


def run(cases=None) -> dict:
    """Run the cases (default: all) and return their figures in one dict."""
    res: dict = {}
    for name in cases or CASES:
        print(f"--- bench_fem: {name}", flush=True)
        figures = _run_case(name)
        for key, value in figures.items():
            print(f"{key:44s} {value:.4g}" if isinstance(value, float) and
                  not isinstance(value, bool) else f"{key:44s} {value}", flush=True)
        res.update(figures)
    if "factor_pardiso_s" in res and "factor_superlu_s" in res:
        res["factor_speedup_pardiso_over_superlu"] = (res["factor_superlu_s"]
                                                      / res["factor_pardiso_s"])
        res["factor_memory_ratio_superlu_to_pardiso"] = (
            (res["factor_superlu_peak_rss_GB"] - res["factor_superlu_rss_before_GB"])
            / (res["factor_pardiso_peak_rss_GB"] - res["factor_pardiso_rss_before_GB"]))
    return res


def main(argv: list[str]) -> None:
    if argv[:1] == ["--child"]:
        name, out = argv[1], argv[2]
        figures = CASES[name]()
        Path(out).write_text(json.dumps(figures))
        return
    unknown = [a for a in argv if a not in CASES]
    if unknown:
        raise SystemExit(f"unknown case(s) {unknown}; valid: {list(CASES)}")
    run(argv or None)


if __name__ == "__main__":
    main(sys.argv[1:])
