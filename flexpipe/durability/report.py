"""Stress and fatigue report of a run: hot-spot table, histories, ``.vtu`` and PNG.

:func:`write_stress_report` writes into a folder

* ``hotspots.csv`` - the ``top`` elements by max von Mises and the ``top`` by damage
  (union), with element id, type, location, centroid, max von Mises and its time, the
  signed principal stress there, damage of the run and per km, both ranks and the load
  channel whose history correlates best with the element's signed principal stress;
* ``stress_histories.csv`` - von Mises and signed principal stress of those elements;
* ``stress_max.vtu`` - the body mesh with the max von Mises, time of max and damage per
  element (cell data) and nodal max von Mises (point data: solids from their nodal
  stress modes, shells and beams the average of their elements' maxima);
* ``stress_max.png`` - the body coloured by max von Mises (headless matplotlib).
"""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import numpy as np

from flexpipe._io import atomic_path, write_matrix_csv, write_text_atomic

#: channels considered as loads for the correlation column
LOAD_PREFIXES = ("hub_", "tire_")


def _correlated(sig, channels):
    best, r_best = "", 0.0
    s = sig - sig.mean()
    ns = np.sqrt(s @ s)
    if ns == 0:
        return best, r_best
    for name, x in channels.items():
        if not name.startswith(LOAD_PREFIXES) or len(x) != len(sig):
            continue
        d = x - x.mean()
        nd = np.sqrt(d @ d)
        if nd == 0:
            continue
        r = float(s @ d / (ns * nd))
        if abs(r) > abs(r_best):
            best, r_best = name, r
    return best, r_best


def hotspots(sr, channels, *, top: int = 20):
    """Rows (dicts) of the hot-spot table (see module docstring)."""
    by_vm = sr.top(top, by="von_mises")
    rank_vm = np.empty(len(sr.max_von_mises), dtype=np.int64)
    rank_vm[np.argsort(-sr.max_von_mises, kind="stable")] = np.arange(1, len(rank_vm) + 1)
    chosen = list(by_vm)
    rank_d = None
    if sr.damage is not None:
        key = np.nan_to_num(sr.damage, nan=-1.0)
        rank_d = np.empty(len(key), dtype=np.int64)
        rank_d[np.argsort(-key, kind="stable")] = np.arange(1, len(key) + 1)
        chosen += [i for i in sr.top(top, by="damage") if i not in chosen]
    per_km = sr.damage_per_km
    rows, hist = [], {}
    for i in chosen:
        vm, sp = sr.history(int(i))
        ch, r = _correlated(sp, channels)
        eid = int(sr.element_id[i])
        hist[eid] = (vm, sp)
        rows.append({
            "rank_von_mises": int(rank_vm[i]),
            "rank_damage": int(rank_d[i]) if rank_d is not None else "",
            "element_id": eid, "cell_type": sr.cell_type[i], "location": sr.location[i],
            "x [m]": sr.centroid[i, 0], "y [m]": sr.centroid[i, 1], "z [m]": sr.centroid[i, 2],
            "max_von_mises [MPa]": sr.max_von_mises[i] / 1e6,
            "time_of_max [s]": sr.time_of_max[i],
            "principal_at_max [MPa]": sr.principal_at_max[i] / 1e6,
            "damage [-]": sr.damage[i] if sr.damage is not None else "",
            "damage_per_km [1/km]": per_km[i] if per_km is not None else "",
            "most_correlated_channel": ch, "correlation [-]": r,
        })
    return rows, hist


def _fmt(v):
    if isinstance(v, (float, np.floating)):
        return "" if not np.isfinite(v) else f"{v:.7g}"
    return str(v)


def _write_csv(path, header, rows):
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(header)
    for r in rows:
        w.writerow([_fmt(v) for v in r])
    write_text_atomic(path, buf.getvalue())


def _cells(body):
    return [(b.cell_type, np.asarray(b.cells)) for b in body.stress.blocks]


def write_vtu(path, body, sr):
    """``stress_max.vtu``: body mesh with per-element and nodal max von Mises."""
    import meshio

    cells = _cells(body)
    sizes = [len(c) for _, c in cells]
    split = np.cumsum(sizes)[:-1]
    cdata = {"max_von_mises [Pa]": sr.max_von_mises, "time_of_max [s]": sr.time_of_max,
             "element_id": sr.element_id.astype(float)}
    if sr.damage is not None:
        cdata["damage [-]"] = np.nan_to_num(sr.damage, nan=0.0)
    cell_data = {k: np.split(np.asarray(v, dtype=float), split) for k, v in cdata.items()}
    nodal = body.stress.nodal_average(np.split(sr.max_von_mises, split), body.n_nodes)
    if sr.nodal_max_von_mises is not None:  # solids: from their nodal stress modes
        have = np.isfinite(sr.nodal_max_von_mises)
        nodal[have] = sr.nodal_max_von_mises[have]
    mesh = meshio.Mesh(np.asarray(body.nodes), cells, cell_data=cell_data,
                       point_data={"max_von_mises_nodal [Pa]": np.nan_to_num(nodal)})
    with atomic_path(path, suffix=".vtu") as tmp:
        meshio.write(tmp, mesh, file_format="vtu")
    return Path(path)


def polygons(body, cells=None):
    """Shell faces (k, nn, 3) in body coordinates and their element positions."""
    polys, index, ofs = [], [], 0
    for b in body.stress.blocks if cells is None else cells:
        if b.cell_type in ("quad", "triangle"):
            polys.extend(list(body.nodes[b.cells]))
            index.extend(range(ofs, ofs + len(b)))
        ofs += len(b)
    return polys, np.asarray(index, dtype=np.int64)


def write_png(path, body, sr, *, title=""):
    """Body coloured by max von Mises, two views (matplotlib, headless)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    polys, idx = polygons(body)
    vals = sr.max_von_mises[idx] / 1e6
    norm = matplotlib.colors.Normalize(vmin=0.0, vmax=max(float(np.percentile(vals, 99.5)),
                                                         1e-9))
    cmap = matplotlib.colormaps["viridis"]
    fig = plt.figure(figsize=(12, 5.5))
    for k, (elev, azim) in enumerate(((25, -60), (90, -90))):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        pc = Poly3DCollection(polys, facecolors=cmap(norm(vals)), edgecolors="none")
        ax.add_collection3d(pc)
        lo, hi = body.nodes.min(axis=0), body.nodes.max(axis=0)
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_box_aspect(hi - lo)
        ax.view_init(elev=elev, azim=azim)
        ax.set_axis_off()
    sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
    fig.colorbar(sm, ax=fig.axes, shrink=0.6, label="max von Mises stress [MPa]")
    fig.suptitle(title or "Max von Mises stress over the run (shell elements)")
    with atomic_path(path, suffix=".png") as tmp:
        fig.savefig(tmp, dpi=110)
    plt.close(fig)
    return Path(path)


def write_stress_report(out, sr, body, channels, *, top: int = 20, title: str = "") -> dict:
    """Write the report files into ``out``; returns ``{file name: description}``."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    rows, hist = hotspots(sr, channels, top=top)
    header = list(rows[0]) if rows else ["element_id"]
    _write_csv(out / "hotspots.csv", header, [list(r.values()) for r in rows])
    h_header = ["t [s]"]
    cols = [sr.t]
    for eid, (vm, sp) in hist.items():
        h_header += [f"von_mises_{eid} [Pa]", f"principal_{eid} [Pa]"]
        cols += [vm, sp]
    write_matrix_csv(out / "stress_histories.csv", h_header, np.column_stack(cols))
    write_vtu(out / "stress_max.vtu", body, sr)
    write_png(out / "stress_max.png", body, sr, title=title)
    files = {
        "hotspots.csv": f"top {top} elements by max von Mises and by fatigue damage: id, "
                        "location, centroid (body axes, m), max von Mises (MPa) and its time "
                        "(s), signed principal stress there (MPa), Miner damage of the run "
                        "and per km, ranks, most correlated load channel (Pearson r)",
        "stress_histories.csv": "von Mises and signed max principal stress (Pa) of the "
                                "hot-spot elements at their critical location vs time (s)",
        "stress_max.vtu": "body mesh (body axes) with max von Mises (Pa), time of max (s), "
                          "damage per element and nodal-averaged max von Mises; ParaView",
        "stress_max.png": "body coloured by max von Mises over the run (MPa)",
    }
    meta = {"elements": int(len(sr.element_id)), "distance_km": sr.distance_km,
            "max_von_mises_MPa": float(sr.max_von_mises.max() / 1e6),
            "hotspot_element": int(sr.element_id[int(np.argmax(sr.max_von_mises))])}
    if sr.damage is not None:
        d = np.nan_to_num(sr.damage, nan=0.0)
        meta.update(max_damage=float(d.max()), max_damage_per_km=float(d.max() /
                    max(sr.distance_km, 1e-12)),
                    damage_element=int(sr.element_id[int(np.argmax(d))]),
                    fatigue_material={"sigma_f_Pa": sr.material.sigma_f, "b": sr.material.b,
                                      "endurance_limit_Pa": sr.material.endurance_limit})
    write_text_atomic(out / "stress_summary.json",
                      json.dumps({"files": files, **meta}, indent=2) + "\n")
    files["stress_summary.json"] = "what each stress file holds and the headline figures"
    return files
