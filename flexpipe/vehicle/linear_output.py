"""Files of a linear analysis (:func:`flexpipe.vehicle.linear.linear_modes`): the modes as
CSV (units in the headers) and JSON, and a PNG of damping against frequency; each file is
written to a temporary name and renamed into place."""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import numpy as np

from flexpipe._io import atomic_path, write_text_atomic

#: what the modes are (the JSON's and the printout's notes)
NOTES = (
    "controls fixed: the driver and speed controller are not part of the linear model",
    "a dual-rate damper enters with the mean of its two slopes at zero velocity",
    "at rest no brake acts: the car may roll (a free mode); each tyre's relaxed slips are "
    "its horizontal springs",
    "free motions (zero eigenvalues) are counted, not listed",
)


def table_text(modes, *, f_max: float | None = None) -> str:
    """The modes as a text table (up to ``f_max`` Hz)."""
    lines = [f"{'mode':>4}  {'f (Hz)':>9}  {'fd (Hz)':>9}  {'zeta':>6}  dominant motion "
             "(share of kinetic energy)"]
    for k, row in enumerate(modes.rows()):
        if f_max is not None and row["frequency_Hz"] > f_max:
            break
        if row["label"].startswith("tyre relaxation"):
            share = f"slip states {modes.slip_participation[k]:.0%} of the participation"
        else:
            share = f"{float(np.max(modes.energy[k])):.0%}"
        lines.append(f"{row['mode']:>4}  {row['frequency_Hz']:9.3f}  "
                     f"{row['damped_frequency_Hz']:9.3f}  {row['damping_ratio']:6.3f}  "
                     f"{row['label']} ({share})")
    return "\n".join(lines)


def write_modes(modes, out) -> list[Path]:
    """Write ``linear_modes.csv``, ``linear_modes.json`` and ``linear_modes.png`` into
    ``out`` (created if needed); returns their paths."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    rows = modes.rows()
    buf = io.StringIO()
    if rows:
        w = csv.DictWriter(buf, fieldnames=list(rows[0]), lineterminator="\n")
        w.writeheader()
        for r in rows:
            w.writerow({k: (f"{v:.9g}" if isinstance(v, float) else v) for k, v in r.items()})
    paths = [out / "linear_modes.csv", out / "linear_modes.json", out / "linear_modes.png"]
    write_text_atomic(paths[0], buf.getvalue())
    doc = {"car": modes.car, "body": modes.body, "speed_m_per_s": modes.speed,
           "residual_N": modes.residual_N, **modes.info, "groups": list(modes.groups),
           "notes": list(NOTES), "modes": rows}
    write_text_atomic(paths[1], json.dumps(doc, indent=1) + "\n")
    _plot(modes, paths[2])
    return paths


#: frequencies of the written track response (Hz)
FRF_HZ = np.geomspace(0.3, 50.0, 240)


def write_track_response(modes, out, *, f_hz=FRF_HZ, tracks: str = "same") -> list[Path]:
    """``linear_frf.csv`` and ``linear_frf.png`` (``tracks="same"``) or
    ``linear_frf_opposite.*``: the response to a road profile on both tracks, or on the
    left one and its negative on the right
    (:meth:`~flexpipe.vehicle.linear.LinearModes.track_response`), per metre of its
    height: magnitude (output unit per m) and phase (deg) of every output."""
    out = Path(out)
    H = modes.track_response(f_hz, tracks=tracks)
    from flexpipe.vehicle.linear import output_unit

    units = {name: f"{output_unit(name)}/m" for name in modes.outputs}
    head = ["f_Hz"] + [c for name in modes.outputs
                       for c in (f"{name}_gain_{units[name]}", f"{name}_phase_deg")]
    lines = [",".join(head)]
    for i, f in enumerate(f_hz):
        vals = [f"{f:.6g}"]
        for j in range(len(modes.outputs)):
            vals += [f"{abs(H[i, j]):.7g}", f"{np.degrees(np.angle(H[i, j])):.3f}"]
        lines.append(",".join(vals))
    stem = "linear_frf" if tracks == "same" else "linear_frf_opposite"
    paths = [out / f"{stem}.csv", out / f"{stem}.png"]
    write_text_atomic(paths[0], "\n".join(lines) + "\n")
    fig, axes = _figure(2, 1, figsize=(8, 7), sharex=True)
    for j, name in enumerate(modes.outputs):
        if name.endswith("_Fz") or (name.startswith("hub_") and name.endswith("_z")):
            axes[0].loglog(f_hz, np.abs(H[:, j]), label=name,
                           ls="--" if name.startswith("hub_") else "-")
        elif name.startswith("acc_") and name.endswith("_z"):
            axes[1].loglog(f_hz, np.abs(H[:, j]), label=name)
    axes[0].set_ylabel("vertical tyre and hub forces\nper road height (N/m)")
    axes[1].set_ylabel("vertical floor acceleration\nper road height (m/s^2 / m)")
    axes[1].set_xlabel("frequency (Hz)")
    if modes.speed > 0:
        where = (f"{'both tracks' if tracks == 'same' else 'opposite tracks'}, "
                 f"{modes.speed * 3.6:g} km/h")
    else:
        where = f"four-post {'heave' if tracks == 'same' else 'roll'}, at rest"
    axes[0].set_title(f"{modes.car}, {modes.body} body: {where}")
    for ax in axes:
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    _save(fig, paths[1])
    return paths


def write_state_space(modes, path) -> Path:
    """``linear_state_space.mat`` (MATLAB level 5, :func:`scipy.io.savemat`): the state
    matrices ``A``, ``B``, ``C``, ``D`` of ``x' = A x + B u``, ``y = C x + D u`` (SI units;
    ``ss(A, B, C, D)`` in MATLAB), ``inputs``, ``outputs`` and ``states`` as cell arrays of
    names, the eigenvalues and the linearization's ``speed_m_per_s``, ``car``, ``body``
    and ``info`` (JSON text).  States: the constraints' nullspace coordinates ``y_k`` (m
    or rad along :attr:`~flexpipe.vehicle.linear.LinearModes.N`), their rates ``ydot_k``
    and the tyres' relaxed slips ``slip_<k>``."""
    from scipy.io import savemat

    k = modes.N.shape[1]
    n_slip = modes.A.shape[0] - 2 * k
    states = ([f"y_{i + 1}" for i in range(k)] + [f"ydot_{i + 1}" for i in range(k)]
              + [f"slip_{i + 1}" for i in range(n_slip)])

    def cells(names):
        out = np.empty((len(names), 1), dtype=object)
        out[:, 0] = list(names)
        return out

    data = {"A": modes.A, "B": modes.B, "C": modes.C, "D": modes.D,
            "inputs": cells(modes.inputs), "outputs": cells(modes.outputs),
            "states": cells(states), "eigenvalues": modes.eigenvalues[:, None],
            "speed_m_per_s": float(modes.speed), "car": modes.car, "body": modes.body,
            "info": json.dumps(modes.info, default=str)}
    path = Path(path)
    with atomic_path(path, suffix=".mat") as tmp:
        savemat(tmp, data, do_compression=True)
    return path


def _plot(modes, path) -> None:
    import matplotlib.pyplot as plt

    fig, ax = _figure(figsize=(8, 5))
    f, z = modes.frequency_hz, modes.damping_ratio
    kinds = sorted(set(modes.label))
    cmap = plt.get_cmap("tab10")
    for i, kind in enumerate(kinds):
        sel = np.array([lab == kind for lab in modes.label])
        ax.scatter(f[sel], z[sel], s=28, color=cmap(i % 10), label=kind)
    ax.set_xscale("log")
    ax.set_xlabel("natural frequency |lambda| / 2 pi (Hz)")
    ax.set_ylabel("damping ratio (-)")
    ax.set_ylim(-0.05, 1.05)
    ax.grid(True, which="both", alpha=0.3)
    ax.set_title(f"{modes.car}: linear modes, {modes.body} body, "
                 f"{modes.speed * 3.6:g} km/h")
    ax.legend(fontsize=7, loc="upper right", ncol=2)
    _save(fig, path)


def _figure(*args, **kwargs):
    """A matplotlib figure on the Agg backend (no display needed)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt.subplots(*args, **kwargs)


def _save(fig, path) -> None:
    """Write ``fig`` as a PNG (temporary name, renamed into place) and close it."""
    import matplotlib.pyplot as plt

    fig.tight_layout()
    with atomic_path(path, suffix=".png") as tmp:
        fig.savefig(tmp, dpi=120)
    plt.close(fig)


def shape_fields(modes, index) -> tuple:
    """Mesh nodes of the flexible body at the linearization state (global, m) and the
    complex displacement field (n, 3, len(index)) of the modes ``index`` (global axes;
    frame motion plus elastic deformation, each mode scaled to a largest node
    displacement of 1)."""
    from flexpipe.exu._tire_element import _g_matrix

    b = modes.body_state
    fb = b["flexbody"]
    R, p = b["rotation"], b["position"]
    cols = fb.n_rigid + np.arange(b["modal"].stop - b["modal"].start)
    phi = fb.modes[:, :, cols]  # (n, 3, m) in body axes
    x_body = fb.nodes + phi @ b["modal_q"]
    X = x_body @ R.T + p
    G = _g_matrix(b["euler"])
    U = np.empty((len(X), 3, len(index)), dtype=complex)
    for j, k in enumerate(index):
        sh = modes.shapes[k]
        dp, de = sh[b["frame"]][:3], sh[b["frame"]][3:7]
        dth = G @ de
        u = dp + np.cross(dth, x_body @ R.T) + (phi @ sh[b["modal"]]) @ R.T
        U[:, :, j] = u / max(np.max(np.linalg.norm(u, axis=1)), 1e-300)
    return X, U


def write_shapes(modes, path, *, f_max: float) -> Path | None:
    """``linear_modes.vtu``: the flexible body's mesh at the linearization state with the
    modes up to ``f_max`` as point data ``mode_NN_re`` / ``mode_NN_im`` (complex
    displacement, global axes, largest node displacement 1; ParaView: Warp By Vector)
    and field data ``frequency_Hz`` / ``damping_ratio``.  None for a rigid body."""
    import meshio
    from meshio.vtu import write as write_vtu

    from flexpipe.durability.animate import body_cells

    if modes.body_state is None or modes.body_state["flexbody"] is None:
        return None
    index = [k for k, f in enumerate(modes.frequency_hz) if f <= f_max]
    X, U = shape_fields(modes, index)
    data = {}
    for j, k in enumerate(index):
        data[f"mode_{k + 1:03d}_re"] = U[:, :, j].real
        data[f"mode_{k + 1:03d}_im"] = U[:, :, j].imag
    mesh = meshio.Mesh(X, body_cells(modes.body_state["flexbody"]), point_data=data,
                       field_data={"frequency_Hz": modes.frequency_hz[index],
                                   "damping_ratio": modes.damping_ratio[index]})
    path = Path(path)
    with atomic_path(path, suffix=".vtu") as tmp:
        write_vtu(tmp, mesh, binary=True, compression=None)
    return path
