"""Step convergence of the hub forces (issue "Numbers that converge").

For both sample cars (prismatic corners ``cars/sedan.toml`` and linkage suspensions
``cars/sedan_linkage.toml``), rigid and flexible body, on ISO 8608 class C at 70 and
100 km/h and on the slalom (class B, 60 km/h): the run at the default step h = 2 ms
against the same run at h/8, 4 s each.  Printed per case: the worst corner's RMS
difference after 0.5 s in percent of the fluctuating part (standard deviation) of the
h/8 run, for x, y and z.  Target: under 5 % everywhere.  Last line: the flexible linkage
car at 70 km/h with its modes not pre-warped (``simulate(..., prewarp=False)``).
"""

from __future__ import annotations

from pathlib import Path

from flexpipe.scenarios.runner import _slalom_path, _slalom_road, _straight_road
from flexpipe.vehicle.convergence import check_step

ROOT = Path(__file__).resolve().parents[1]
T_RUN = 4.0
CARS = (("prismatic", ROOT / "cars" / "sedan.toml"),
        ("linkage", ROOT / "cars" / "sedan_linkage.toml"))


def _cases():
    return (("iso_c_70", dict(road=_straight_road(), speed=70 / 3.6)),
            ("iso_c_100", dict(road=_straight_road(), speed=100 / 3.6)),
            ("slalom_60", dict(road=_slalom_road(), path=_slalom_path(), speed=60 / 3.6)))


def run() -> dict:
    """Run the study; returns a flat dict of figures (percent)."""
    out = {"h_s": 2e-3, "reference_h_s": 2.5e-4, "t_run_s": T_RUN}
    worst_all = 0.0
    for tag, car in CARS:
        for body in ("rigid", "flexible"):
            for name, kw in _cases():
                key = f"{tag}_{body}_{name}"
                w = _case(out, key, car, body, kw, label=f"{tag:9s} {body:8s} {name:10s}")
                worst_all = max(worst_all, w)
    out["target_all_within_5_pct"] = worst_all <= 0.05
    # the same study without pre-warping the body modes (flexpipe/exu/prewarp.py): the
    # peer of the flexible figures above, measured in the same run
    name, kw = _cases()[0]
    _case(out, f"linkage_flexible_{name}_no_prewarp", CARS[1][1], "flexible",
          dict(kw, prewarp=False),
          label=f"{'linkage':9s} {'flexible':8s} {name:10s}", note="  (modes not pre-warped)")
    return out


def _case(out: dict, key: str, car, body: str, kw: dict, *, label: str, note: str = ""):
    """One case: h against h/8; worst corner per axis into ``out``, one printed line;
    returns the worst fraction over the axes."""
    c = check_step(car, h=2e-3, refinements=(8,), t_end=T_RUN, body=body, t_from=0.5, **kw)
    worst = 0.0
    for k in "xyz":
        w = max(c.rel_dynamic[0, j] for j, ch in enumerate(c.channels) if ch.endswith(k))
        out[f"{key}_{k}_pct"] = round(100 * w, 2)
        worst = max(worst, w)
    out[f"{key}_cpu_s"] = round(c.cpu_time[0], 2)
    print(f"{label} " + "  ".join(f"{k} {out[f'{key}_{k}_pct']:5.1f} %" for k in "xyz") + note,
          flush=True)
    return worst


if __name__ == "__main__":
    run()
