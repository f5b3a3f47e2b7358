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
* ``stress_max.png`` - the body coloured by max von Mises (headless matplotlib): shells,
  beams and solids on one colour scale, the top hot spots marked, the clipping of the
  scale and the largest value with its element stated (:func:`png_text`).

The folder is a transaction, like the animation folder: the files are written into a
staging folder ``.NAME.staging-PID`` next to it, which then replaces the folder as a
whole, so an interrupted report leaves the previous one (and its ``stress_summary.json``)
intact.
"""

from __future__ import annotations

import csv
import io
import json
from pathlib import Path

import numpy as np

from flexpipe._io import (
    atomic_path,
    commit_directory,
    staging_folder,
    write_matrix_csv,
    write_text_atomic,
)
from flexpipe.fem.stress import KIND

#: channels considered as loads for the correlation column
LOAD_PREFIXES = ("hub_", "tire_")
#: the PNG's colour scale ends at this percentile of the max von Mises of all elements, so
#: that a few peak elements do not leave the rest of the body in one colour
CLIP_PERCENTILE = 99.5
#: hot spots (largest max von Mises) marked with their element ids in the PNG
PNG_HOTSPOTS = 5
#: how each element kind is drawn in the PNG
DRAWN_AS = {"shell": "faces", "beam": "lines", "solid": "centroid points"}


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


def _kind_counts(body) -> dict:
    counts: dict = {}
    for b in body.stress.blocks:
        counts[b.kind] = counts.get(b.kind, 0) + len(b)
    return counts


def _damage_hotspot(sr):
    """Position in ``sr`` of the element with the largest fatigue damage, or None."""
    if sr.damage is None:
        return None
    d = np.nan_to_num(np.asarray(sr.damage, dtype=float), nan=-1.0)
    if d.size == 0 or d.max() <= 0.0:
        return None
    return int(np.argmax(d))


def png_text(body, sr, *, title: str = "", hotspots: int = PNG_HOTSPOTS) -> dict:
    """What ``stress_max.png`` shows, in words: its title, colour-bar label, description.

    The figure draws every element with stresses (:data:`DRAWN_AS`) on one colour scale
    ending at the :data:`CLIP_PERCENTILE` th percentile of their max von Mises; the text
    states that clipping, the largest value, its element id and kind, the hot spots
    numbered in the views (listed with their element ids in the table beside them) and
    the fatigue (largest damage) hot spot.

    Returns
    -------
    dict
        ``title``, ``colorbar``, ``description`` (str), ``vmax_MPa`` (end of the colour
        scale), ``hotspots`` (positions of the numbered elements in ``sr``),
        ``damage_hotspot`` (position of the largest damage, or None without fatigue).
    """
    vals = sr.max_von_mises / 1e6
    clip = max(float(np.percentile(vals, CLIP_PERCENTILE)), 1e-9)
    i = int(np.argmax(vals))
    kind = KIND.get(sr.cell_type[i], str(sr.cell_type[i]))
    drawn = ", ".join(f"{n} {k}s as {DRAWN_AS[k]}" for k, n in _kind_counts(body).items())
    top = [int(j) for j in sr.top(hotspots)]
    dmg = _damage_hotspot(sr)
    at_max = (f"max {vals[i]:.1f} MPa at element {int(sr.element_id[i])} ({kind}, "
              f"{sr.location[i]}) at t = {sr.time_of_max[i]:.3f} s")
    if vals[i] > clip:
        scale = (f"colour scale clipped at the {CLIP_PERCENTILE:g}th percentile, "
                 f"{clip:.1f} MPa (higher values in the top colour)")
    else:
        scale = f"colour scale 0 to {clip:.1f} MPa"
    marked = (f"top {len(top)} hot spots numbered 1-{len(top)} (red circles; element ids "
              + ", ".join(str(int(sr.element_id[j])) for j in top) + " in the table)")
    if dmg is not None:
        fatigue = (f"fatigue hot spot D (magenta diamond): element {int(sr.element_id[dmg])}, "
                   f"damage {float(sr.damage[dmg]):.3g}")
    else:
        fatigue = "no fatigue damage computed" if sr.damage is None else "no fatigue damage"
    head = title or "Max von Mises stress over the run"
    return {
        "title": f"{head}\n{drawn}; {at_max}\n{scale}\n{marked}; {fatigue}",
        "colorbar": (f"max von Mises [MPa] of {', '.join(_kind_counts(body))} elements\n"
                     f"scale clipped at {clip:.1f} MPa; max {vals[i]:.1f} MPa"),
        "description": (f"body coloured by max von Mises over the run (MPa), two views "
                        f"({', '.join(name for name, _, _ in VIEWS)}): {drawn}; {scale}; "
                        f"{at_max}; {marked}; {fatigue}"),
        "vmax_MPa": clip, "hotspots": top, "damage_hotspot": dmg,
    }


#: the two views of ``stress_max.png``: name, elevation, azimuth (body axes: x forward,
#: y to the left, z up)
VIEWS = (("isometric view from front right", 25, -60),
         ("top view (front to the right, left side up)", 90, -90))


def _groups(points, tol):
    """Indices of ``points`` grouped greedily: each joins the first group whose first
    point lies within ``tol`` (so labels of near-coincident hot spots are merged)."""
    groups = []
    for k, p in enumerate(points):
        for g in groups:
            if np.linalg.norm(points[g[0]] - p) <= tol:
                g.append(k)
                break
        else:
            groups.append([k])
    return groups


def hotspot_table_rows(sr, text) -> list:
    """Rows of the table beside the views: marker, element id, kind, max von Mises [MPa],
    its time [s] and damage; the fatigue hot spot as marker ``D``."""
    def row(mark, j):
        d = "" if sr.damage is None else f"{float(np.nan_to_num(sr.damage[j])):.2g}"
        return [mark, str(int(sr.element_id[j])), KIND.get(sr.cell_type[j], sr.cell_type[j]),
                f"{sr.max_von_mises[j] / 1e6:.1f}", f"{sr.time_of_max[j]:.3f}", d]
    rows = [row(str(k + 1), j) for k, j in enumerate(text["hotspots"])]
    if text["damage_hotspot"] is not None:
        rows.append(row("D", text["damage_hotspot"]))
    return rows


HOTSPOT_TABLE_HEADER = ["#", "element", "kind", "max vM\n[MPa]", "t of max\n[s]", "damage\n[-]"]


def write_png(path, body, sr, *, title=""):
    """Body coloured by max von Mises, two named views and a hot-spot table (headless).

    Shells are drawn as faces, beams as lines, solids as points at their centroids, all
    on one colour scale.  The top hot spots are numbered (red circles; hot spots closer
    than 2 % of the body's size share one label such as ``1,3``) and listed with their
    element ids and values in a table beside the views, where ``D`` is the fatigue hot
    spot (largest damage, magenta diamond).  The title, colour-bar label and description
    (:func:`png_text`) are also stored as the PNG's ``Title`` and ``Description`` text.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

    text = png_text(body, sr, title=title)
    vals = sr.max_von_mises / 1e6
    norm = matplotlib.colors.Normalize(vmin=0.0, vmax=text["vmax_MPa"])
    cmap = matplotlib.colormaps["viridis"]
    polys, idx = polygons(body)
    segs, sidx, pts, pidx, ofs = [], [], [], [], 0
    for b in body.stress.blocks:
        rows = np.arange(ofs, ofs + len(b))
        if b.kind == "beam":
            segs.extend(list(body.nodes[b.cells[:, [0, -1]]]))
            sidx.extend(rows)
        elif b.kind == "solid":
            pts.append(b.centroids)
            pidx.extend(rows)
        ofs += len(b)
    lo, hi = body.nodes.min(axis=0), body.nodes.max(axis=0)
    size = float(np.linalg.norm(hi - lo))
    top = text["hotspots"]
    groups = _groups(np.asarray([sr.centroid[j] for j in top]).reshape(-1, 3), 0.02 * size)
    dmg = text["damage_hotspot"]
    fig = plt.figure(figsize=(13, 8.2))
    # a 3D axes leaves wide blank margins around its box: the views get rectangles larger
    # than their share of the figure (left column, top and bottom half below the title)
    frames = ([-0.2, 0.3, 1.1, 0.66], [-0.2, -0.17, 1.1, 0.66])
    for k, (name, elev, azim) in enumerate(VIEWS):
        ax = fig.add_axes(frames[k], projection="3d")
        ax.set_facecolor((1, 1, 1, 0))  # transparent: the frames overlap
        ax.computed_zorder = False  # draw order: the hot-spot marks stay on top
        if polys:
            ax.add_collection3d(Poly3DCollection(polys, facecolors=cmap(norm(vals[idx])),
                                                 edgecolors="none"))
        if segs:
            ax.add_collection3d(Line3DCollection(segs, colors=cmap(norm(vals[sidx])),
                                                 linewidths=1.5))
        if pts:
            c = np.vstack(pts)
            ax.scatter(c[:, 0], c[:, 1], c[:, 2], c=cmap(norm(vals[pidx])), s=4)
        for g in groups:
            for m in g:
                ax.scatter(*sr.centroid[top[m]], s=70, facecolors="none", edgecolors="red",
                           linewidths=1.3, zorder=10)
            c = sr.centroid[top[g[0]]]
            ax.text(c[0], c[1], c[2] + 0.04 * size, ",".join(str(m + 1) for m in g),
                    color="red", fontsize=9, fontweight="bold", ha="center", va="bottom",
                    zorder=12, bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="red",
                                         lw=0.6, alpha=0.85))
        if dmg is not None:
            c = sr.centroid[dmg]
            ax.scatter(*c, s=90, marker="D", facecolors="none", edgecolors="magenta",
                       linewidths=1.5, zorder=10)
            ax.text(c[0], c[1], c[2] - 0.04 * size, "D", color="magenta", fontsize=9,
                    fontweight="bold", ha="center", va="top", zorder=12,
                    bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="magenta", lw=0.6,
                              alpha=0.85))
        ax.text(hi[0] + 0.03 * size, 0.5 * (lo[1] + hi[1]), lo[2], "front", color="0.35",
                fontsize=8, ha="left", va="center")
        ax.set_xlim(lo[0], hi[0])
        ax.set_ylim(lo[1], hi[1])
        ax.set_zlim(lo[2], hi[2])
        ax.set_box_aspect(hi - lo, zoom=1.0)
        ax.view_init(elev=elev, azim=azim)
        ax.set_axis_off()
        fig.text(0.35, (0.85, 0.40)[k], name, fontsize=10, ha="center", va="top",
                 fontweight="bold")
    tab_ax = fig.add_axes([0.73, 0.42, 0.25, 0.44])
    tab_ax.set_axis_off()
    rows = hotspot_table_rows(sr, text)
    table = tab_ax.table(cellText=rows, colLabels=HOTSPOT_TABLE_HEADER, loc="upper center",
                         cellLoc="center", colWidths=[0.08, 0.17, 0.15, 0.17, 0.17, 0.17])
    table.auto_set_font_size(False)
    table.set_fontsize(8)
    table.scale(1.0, 1.5)
    for (r, _), cell in table.get_celld().items():
        if r == 0:
            cell.set_height(cell.get_height() * 1.6)
            cell.set_facecolor("0.92")
        elif rows[r - 1][0] == "D":
            cell.get_text().set_color("magenta")
        else:
            cell.get_text().set_color("red")
    tab_ax.set_title("hot spots (# as in the views; D = largest fatigue damage)",
                     fontsize=8.5)
    sm = matplotlib.cm.ScalarMappable(norm=norm, cmap=cmap)
    cax = fig.add_axes([0.75, 0.30, 0.22, 0.025])
    fig.colorbar(sm, cax=cax, orientation="horizontal", label=text["colorbar"],
                 extend="max" if vals.max() > text["vmax_MPa"] else "neither")
    fig.suptitle(text["title"], fontsize=9)
    with atomic_path(path, suffix=".png") as tmp:
        fig.savefig(tmp, dpi=110, metadata={"Title": text["title"],
                                            "Description": text["description"]})
    plt.close(fig)
    return Path(path)


def write_stress_report(out, sr, body, channels, *, top: int = 20, title: str = "") -> dict:
    """Write the report files into ``out``; returns ``{file name: description}``.

    The files go into a staging folder that replaces ``out`` as a whole when every file
    is written; on an error or interrupt it is removed and ``out`` keeps its previous
    report.
    """
    import shutil

    stage = staging_folder(out)
    try:
        files = _write_report_files(stage, sr, body, channels, top=top, title=title)
        commit_directory(stage, out)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise
    return files


def _write_report_files(out, sr, body, channels, *, top, title) -> dict:
    out = Path(out)
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
        "stress_max.png": png_text(body, sr, title=title)["description"],
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
