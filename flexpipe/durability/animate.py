"""ParaView animation of a run: the deformed body in global coordinates, wheels, road.

:func:`write_animation` writes into a folder

* ``body.pvd`` + ``body_NNNNN.vtu`` - one frame per selected output step: every mesh node
  of the body at ``p + R (x + scale u(q))`` (global coordinates), point data
  ``elastic_displacement`` (``R u``, global axes, m, unscaled) and, when the body has
  stress modes, cell data ``von_mises`` (Pa, the larger of a shell's two surfaces or a
  beam's two ends);
* ``wheels.pvd`` + ``wheels_NNNNN.vtu`` - the four wheels as cylinders (radius from the
  car file) at the wheel centres (design position moved by the suspension travel,
  steered and spinning);
* ``road.vtu`` - the road surface as a strip along the driven track;
* ``animation.pvd`` - all three as parts of one time series (open this in ParaView);
* ``preview.png`` - one frame rendered headless with matplotlib.

The folder is a transaction: the frames are written into a staging folder
``.NAME.staging-PID`` next to it, which then replaces the folder as a whole, so it always
holds exactly one animation (no frames of an earlier, denser or interrupted one).
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np

from flexpipe._io import atomic_path, commit_directory, write_text_atomic
from flexpipe.errors import InputError

WHEEL_SEGMENTS = 24
WHEEL_HALF_WIDTH = 0.1  # m
_ANIMATION_NAME = (r"((body|wheels)_\d+\.vtu|(body|wheels|animation)\.pvd|"
                   r"road\.vtu|preview\.png)")
#: names of the files an animation folder holds: its own files and the temporary files
#: :func:`flexpipe._io.atomic_path` leaves of them (``.NAME.XXXXXXXX.SUFFIX``, from
#: ``tempfile.mkstemp``); any other hidden entry (``.git``, ``.env``) is not an animation's
_ANIMATION_FILE = re.compile(rf"{_ANIMATION_NAME}|\.{_ANIMATION_NAME}\.\w+\.(vtu|pvd|png)")


def _pvd(path, entries):
    lines = ['<?xml version="1.0"?>',
             '<VTKFile type="Collection" version="0.1" byte_order="LittleEndian">',
             "  <Collection>"]
    for t, part, name in entries:
        lines.append(f'    <DataSet timestep="{t:.12g}" group="" part="{part}" file="{name}"/>')
    lines += ["  </Collection>", "</VTKFile>", ""]
    write_text_atomic(path, "\n".join(lines))


def _write(path, mesh):
    """Binary .vtu, uncompressed: float data hardly compresses and zlib took 3/4 of the
    time of a frame."""
    from meshio.vtu import write as write_vtu

    with atomic_path(path, suffix=".vtu") as tmp:
        write_vtu(tmp, mesh, binary=True, compression=None)


def body_cells(body):
    """meshio cell blocks of the body: its stressed elements, else its surface triangles."""
    if body.stress is not None:
        return [(b.cell_type, np.asarray(b.cells)) for b in body.stress.blocks]
    return [("triangle", np.asarray(body.triangles))]


class _Modes:
    """The body's mode shapes and stress modes restricted to the run's modes (sliced once)."""

    def __init__(self, body, motion):
        from flexpipe.durability.recover import _modal_columns

        self.phi = body.modes[:, :, motion.mode_index]
        self.stress = []
        if body.stress is not None and motion.n_modes:
            cols = _modal_columns(body, motion)
            self.stress = [(b.kind, np.ascontiguousarray(b.modes[:, :, cols]))
                           for b in body.stress.blocks]


def body_frame(body, motion, k: int, *, scale: float = 1.0, modes=None):
    """Global node positions (n, 3) and elastic displacement ``R u`` (n, 3) at step ``k``."""
    modes = modes or _Modes(body, motion)
    R, p, q = motion.rotation[k], motion.position[k], motion.q[k]
    u = modes.phi @ q if motion.n_modes else np.zeros_like(body.nodes)
    x = (body.nodes + scale * u) @ R.T + p
    return x, u @ R.T


def frame_von_mises(body, motion, k: int, *, modes=None):
    """Per-element von Mises stress (Pa) at step ``k`` (concatenated over blocks)."""
    from flexpipe.durability.recover import equivalents

    modes = modes or _Modes(body, motion)
    out = []
    for kind, S in modes.stress:
        vm, _ = equivalents(kind, (S @ motion.q[k])[:, :, None])
        out.append(vm[:, :, 0].max(axis=1))
    return np.concatenate(out)


def wheel_mesh(centers, rotations, radius):
    """Cylinders (points, quads, triangles) for wheels at ``centers`` (k, 3)."""
    a = np.linspace(0, 2 * np.pi, WHEEL_SEGMENTS, endpoint=False)
    pts, quads, tris = [], [], []
    for c, Rw, r in zip(centers, rotations, radius, strict=True):
        base = len(pts) and sum(len(p) for p in pts)
        ring = np.column_stack([r * np.cos(a), np.zeros_like(a), r * np.sin(a)])
        local = np.vstack([ring + [0, WHEEL_HALF_WIDTH, 0], ring - [0, WHEEL_HALF_WIDTH, 0],
                           [[0, WHEEL_HALF_WIDTH, 0], [0, -WHEEL_HALF_WIDTH, 0]]])
        pts.append(local @ Rw.T + c)
        n = WHEEL_SEGMENTS
        j = np.arange(n)
        jn = (j + 1) % n
        quads.append(base + np.column_stack([j, jn, n + jn, n + j]))
        tris.append(base + np.column_stack([np.full(n, 2 * n), jn, j]))
        tris.append(base + np.column_stack([np.full(n, 2 * n + 1), n + j, n + jn]))
    return np.vstack(pts), np.vstack(quads), np.vstack(tris)


def _rz(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _ry(a):
    c, s = np.cos(a), np.sin(a)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def wheel_poses(car, run):
    """Wheel centres (n, 4, 3), rotations (n, 4, 3, 3) from the run's channels."""
    from flexpipe.vehicle.spec import CORNERS

    m, ch, t = run.motion, run.channels, run.motion.t
    n = len(t)
    C = np.zeros((n, 4, 3))
    Rw = np.zeros((n, 4, 3, 3))
    steer = ch.get("steer", np.zeros(n))
    for i, cn in enumerate(CORNERS):
        corner = car.corner(cn)
        travel = ch.get(f"travel_{cn}", np.zeros(n))
        spin = ch.get(f"spin_{cn}", np.zeros(n))
        angle = np.concatenate([[0.0], np.cumsum(0.5 * (spin[1:] + spin[:-1]) * np.diff(t))])
        steered = corner.axle == car.steering.axle
        for k in range(n):
            W = corner.wheel_center + np.array([0.0, 0.0, travel[k]])
            C[k, i] = m.position[k] + m.rotation[k] @ W
            Rw[k, i] = m.rotation[k] @ (_rz(steer[k]) if steered else np.eye(3)) @ _ry(angle[k])
    return C, Rw


def _road_mesh(road):
    X, Y, Z = road
    na, nc = X.shape
    pts = np.column_stack([X.ravel(), Y.ravel(), Z.ravel()])
    i, j = np.meshgrid(np.arange(na - 1), np.arange(nc - 1), indexing="ij")
    a = (i * nc + j).ravel()
    quads = np.column_stack([a, a + nc, a + nc + 1, a + 1])
    return pts, quads


def stage_animation(dest) -> Path:
    """A fresh, empty staging folder ``.NAME.staging-PID`` next to the animation folder.

    ``dest`` must be absent, empty or an animation folder (only the files an animation
    writes), so that replacing it never removes other files.  Staging folders left by
    processes that no longer exist are removed.

    Raises
    ------
    InputError
        ``dest`` is a file, or a folder holding other files.
    """
    from flexpipe._io import staging_folder

    dest = Path(dest)
    if dest.exists():
        if not dest.is_dir():
            raise InputError("the animation folder is an existing file; choose another "
                             "--dest", file=dest, key="dest")
        other = sorted(e.name for e in dest.iterdir() if not _ANIMATION_FILE.fullmatch(e.name))
        if other:
            raise InputError(f"the folder holds files that are not an animation's ({other[:3]});"
                             " the animation replaces its folder as a whole: choose a new, "
                             "empty or animation folder as --dest", file=dest, key="dest")
    return staging_folder(dest)


def write_animation(out, run, body, *, scale: float = 1.0, every: int = 1,
                    stress: bool = True, progress: bool = False, log=None) -> dict:
    """Write the animation folder (see module docstring); returns ``{file: description}``.

    The frames go into a staging folder (:func:`stage_animation`) that replaces ``out``
    as a whole when every file is written; on an error or interrupt it is removed and
    ``out`` keeps its previous animation.

    Parameters
    ----------
    out : path
        Folder to write (absent, empty or a previous animation folder).
    run : RunData
        The run (:func:`flexpipe.durability.rundir.load_run`).
    body : FlexBody
        Its body.
    scale : float
        Deformation scale factor of the body (1: true scale).
    every : int
        Write every ``every``-th output step.
    stress : bool
        Add the von Mises field when the body has stress modes.
    """
    if not (np.isfinite(scale) and scale >= 0):
        raise InputError(f"scale must be a finite number >= 0, got {scale}", key="scale")
    if int(every) < 1:
        raise InputError(f"every must be an integer >= 1, got {every}", key="every")
    stage = stage_animation(out)
    try:
        files = _write_frames(stage, run, body, scale=scale, every=int(every), stress=stress,
                              progress=progress)
        commit_directory(stage, out)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    return files


def _write_frames(out, run, body, *, scale, every, stress, progress) -> dict:
    """The files of :func:`write_animation`, written into the folder ``out``."""
    import meshio

    out = Path(out)
    car = run.car()
    motion = run.motion
    steps = np.arange(0, len(motion.t), int(every))
    cells = [(t, c.astype(np.int32)) for t, c in body_cells(body)]
    split = np.cumsum([len(c) for _, c in cells])[:-1]
    with_stress = stress and body.stress is not None and motion.n_modes > 0
    radius = np.array([c.wheel_radius for c in car.corners])
    C, Rw = wheel_poses(car, run)
    entries, body_entries, wheel_entries = [], [], []
    if run.road is not None:
        rp, rq = _road_mesh(run.road)
        _write(out / "road.vtu", meshio.Mesh(rp, [("quad", rq)]))
    it = steps
    if progress:
        from tqdm import tqdm

        it = tqdm(steps, desc="animation frames", unit="frame")
    modes = _Modes(body, motion)
    for k in it:
        x, d = body_frame(body, motion, int(k), scale=scale, modes=modes)
        cdata = {}
        if with_stress:
            vm = frame_von_mises(body, motion, int(k), modes=modes).astype(np.float32)
            cdata["von_mises [Pa]"] = np.split(vm, split)
        name = f"body_{k:05d}.vtu"
        # float32: 1.5e-5 m resolution at 200 m from the origin, ample for viewing; the
        # displacement field (~1e-4 m) keeps ~1e-11 m
        _write(out / name, meshio.Mesh(x.astype(np.float32), cells, cell_data=cdata,
                                       point_data={"elastic_displacement [m]":
                                                   d.astype(np.float32)}))
        wp, wq, wt = wheel_mesh(C[k], Rw[k], radius)
        wname = f"wheels_{k:05d}.vtu"
        _write(out / wname, meshio.Mesh(wp, [("quad", wq), ("triangle", wt)]))
        tk = float(motion.t[k])
        body_entries.append((tk, 0, name))
        wheel_entries.append((tk, 0, wname))
        entries += [(tk, 0, name), (tk, 1, wname)]
        if run.road is not None:
            entries.append((tk, 2, "road.vtu"))
    _pvd(out / "body.pvd", body_entries)
    _pvd(out / "wheels.pvd", wheel_entries)
    _pvd(out / "animation.pvd", entries)
    k_prev = int(steps[len(steps) // 2])
    write_preview(out / "preview.png", body, run, car, k_prev, C[k_prev], Rw[k_prev], radius,
                  scale=scale, with_stress=with_stress)
    files = {
        "animation.pvd": "ParaView time series: body (part 0), wheels (part 1), road (part 2)",
        "body.pvd": f"{len(steps)} frames body_NNNNN.vtu: deformed body in global "
                    f"coordinates (m, deformation x {scale:g}), elastic_displacement (m, "
                    "global axes, unscaled)" + (", von_mises per element (Pa)"
                                                 if with_stress else ""),
        "wheels.pvd": "wheels as cylinders at the wheel centres (global, m)",
        "preview.png": f"frame at t = {motion.t[k_prev]:.3f} s rendered with matplotlib",
    }
    if run.road is not None:
        files["road.vtu"] = "road surface strip along the driven track (global, m)"
    return files


def write_preview(path, body, run, car, k, centers, rotations, radius, *, scale=1.0,
                  with_stress=True):
    """One frame of the scene as a PNG (headless matplotlib).

    Shells are drawn as faces and beams as lines, both coloured by von Mises stress on
    one scale (0 to the 99th percentile of all their elements, stated on the colour bar
    with the frame's max); axes in global coordinates [m]; the title names the car, the
    run (road, speed) and the time.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    x, _ = body_frame(body, run.motion, k, scale=scale)
    fig = plt.figure(figsize=(10, 6.5))
    ax = fig.add_subplot(projection="3d")
    segs, seg_rows = [], []
    if body.stress is not None:
        verts, rows, ofs = [], [], 0
        for b in body.stress.blocks:
            if b.cell_type in ("quad", "triangle"):
                verts.extend(list(x[b.cells]))
                rows.extend(range(ofs, ofs + len(b)))
            elif b.kind == "beam":
                segs.extend(list(x[b.cells[:, [0, -1]]]))
                seg_rows.extend(range(ofs, ofs + len(b)))
            ofs += len(b)
        rows, seg_rows = np.asarray(rows, dtype=np.int64), np.asarray(seg_rows, dtype=np.int64)
        if with_stress:
            vm = frame_von_mises(body, run.motion, k) / 1e6
            drawn = np.concatenate([vm[rows], vm[seg_rows]])
            vmax = max(float(np.percentile(drawn, 99)), 1e-9) if len(drawn) else 1e-9
            norm = matplotlib.colors.Normalize(0, vmax)
            cmap = matplotlib.colormaps["viridis"]
            colors, seg_colors = cmap(norm(vm[rows])), cmap(norm(vm[seg_rows]))
            kinds = " and ".join(n for n, c in (("shells", len(rows)), ("beams", len(seg_rows)))
                                 if c)
            peak = float(drawn.max()) if len(drawn) else 0.0
            sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
            fig.colorbar(sm, ax=ax, shrink=0.6, pad=0.08,
                         extend="max" if peak > vmax else "neither",
                         label=(f"von Mises stress [MPa] of {kinds}\nscale to the 99th "
                                f"percentile, {vmax:.1f} MPa; max {peak:.1f} MPa"))
        else:
            colors, seg_colors = "0.7", "0.35"
    else:
        verts = list(x[body.triangles])
        colors = "0.7"
    ax.add_collection3d(Poly3DCollection(verts, facecolors=colors, edgecolors="none"))
    if segs:
        ax.add_collection3d(Line3DCollection(segs, colors=seg_colors, linewidths=1.2))
    wp, wq, wt = wheel_mesh(centers, rotations, radius)
    ax.add_collection3d(Poly3DCollection(list(wp[wq]), facecolors="0.15", edgecolors="none"))
    c = x.mean(axis=0)
    if run.road is not None:
        X, Y, Z = run.road
        near = np.abs(X[:, 0] - c[0]) < 4.0
        if near.any():
            ax.plot_surface(X[near], Y[near], Z[near], color="0.55", alpha=0.6, linewidth=0)
    half = 3.0
    ax.set_xlim(c[0] - half, c[0] + half)
    ax.set_ylim(c[1] - half, c[1] + half)
    ax.set_zlim(c[2] - half / 2, c[2] + half / 2)
    ax.set_box_aspect((2, 2, 1))
    ax.view_init(elev=20, azim=-60)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_zlabel("z [m]")
    summary = getattr(run, "summary", None) or {}
    what = summary.get("title") or ""
    ax.set_title(f"{car.name}" + (f", {what}" if what else "")
                 + f"\nt = {run.motion.t[k]:.3f} s, deformation x {scale:g} "
                 "(global coordinates)", fontsize=10)
    with atomic_path(path, suffix=".png") as tmp:
        fig.savefig(tmp, dpi=100)
    plt.close(fig)
