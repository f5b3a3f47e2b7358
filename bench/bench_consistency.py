"""Consistency checks of the car model that the README quotes (issues "Suspension as
vehicle engineers model it" and "Numbers that converge").

Three studies, each printed as it finishes::

    python -m bench consistency          # all three, in a child process
    python bench/bench_consistency.py twin parked start   # any subset, in this process

* ``twin``: the linkage car's flexible body with every elastic mode switched off
  (``max_mode_hz=0``) and a body 100x stiffer (stiffness x 100, damping x 10) against
  the rigid car, on ISO 8608 class C at 70 and 100 km/h and on the slalom, 4 s; worst
  corner's RMS difference after 0.5 s in percent of the rigid hub force's fluctuating
  part, per axis (targets 2 % and 5 %; ``tests/test_linkage_car.py`` holds them on
  shorter runs).
* ``parked``: both cars, rigid and flexible, 60 s at rest on a flat road: the largest
  deviation of any hub force over 50-60 s from its mean over 5-10 s (target 5 N), and
  the largest peak-to-peak range of any hub force over 5-15 s and over 50-60 s (an
  oscillation that grows shows as a larger late range).
* ``start``: both cars, rigid and flexible, parked 6 s from the settled start: the
  largest difference of any hub force at t = 0 and at any later output from its mean
  over 5-6 s, per axis, with the mean vertical wheel load for scale.
"""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

import numpy as np

import flexpipe as fp
from flexpipe.scenarios.runner import _slalom_path, _slalom_road, _straight_road
from flexpipe.vehicle.simulation import prepare

ROOT = Path(__file__).resolve().parents[1]
CARS = (("prismatic", ROOT / "cars" / "sedan.toml"),
        ("linkage", ROOT / "cars" / "sedan_linkage.toml"))
CORNERS = ("fl", "fr", "rl", "rr")


def _cases():
    return (("iso_c_70", dict(road=_straight_road(), speed=70 / 3.6)),
            ("iso_c_100", dict(road=_straight_road(), speed=100 / 3.6)),
            ("slalom_60", dict(road=_slalom_road(), path=_slalom_path(), speed=60 / 3.6)))


def twin(out: dict, *, t_end: float = 4.0) -> None:
    """Modes off and a 100x stiffer body against the rigid twin (see module)."""
    car = fp.load_car(CARS[1][1])
    for name, kw in _cases():
        prep = prepare(car, body="flexible", speed=kw["speed"], road=kw["road"])
        fb = prep["flexbody"]
        stiff = dataclasses.replace(fb, K=fb.K * 100.0, D=fb.D * 10.0,
                                    frequencies_hz=fb.frequencies_hz * 10.0)
        rigid = fp.simulate(car, body="rigid", t_end=t_end, **kw)
        runs = (("modes_off", fp.simulate(car, body="flexible", max_mode_hz=0, prepared=prep,
                                          t_end=t_end, **kw)),
                ("stiff_100x", fp.simulate(car, body="flexible", t_end=t_end,
                                           prepared=dict(prep, flexbody=stiff), **kw)))
        for tag, r in runs:
            d = fp.compare(rigid, r, t_from=0.5)
            w = {a: 100 * max(v["rel_rms_diff_dynamic"] for k, v in d.items()
                              if k.startswith("hub_") and k.endswith("_" + a)) for a in "xyz"}
            for a in "xyz":
                out[f"twin_{name}_{tag}_{a}_pct"] = round(w[a], 3)
            print(f"twin  {name:10s} {tag:10s} worst corner x / y / z "
                  f"{w['x']:.3f} / {w['y']:.3f} / {w['z']:.3f} %", flush=True)


def _parked_runs(t_end: float):
    """``(car tag, body, result, t, {corner_axis: hub force})`` of both cars, rigid and
    flexible, parked on a flat road for ``t_end``."""
    for tag, path in CARS:
        car = fp.load_car(path)
        for body in ("rigid", "flexible"):
            r = fp.simulate(car, speed=0.0, t_end=t_end, body=body)
            hubs = {f"{c}_{a}": np.asarray(r[f"hub_{c}_{a}"]) for c in CORNERS for a in "xyz"}
            yield tag, body, r, np.asarray(r.t), hubs


def parked(out: dict, *, t_end: float = 60.0) -> None:
    """Both cars, rigid and flexible, at rest for ``t_end`` (see module)."""
    for tag, body, r, t, hubs in _parked_runs(t_end):
        worst = early = late = 0.0
        for x in hubs.values():
            static = x[(t > 5) & (t < 10)].mean()
            worst = max(worst, float(np.abs(x[t > t_end - 10] - static).max()))
            early = max(early, float(np.ptp(x[(t > 5) & (t < 15)])))
            late = max(late, float(np.ptp(x[t > t_end - 10])))
        out[f"parked_{tag}_{body}_max_dev_N"] = round(worst, 4)
        out[f"parked_{tag}_{body}_ptp_early_N"] = round(early, 4)
        out[f"parked_{tag}_{body}_ptp_late_N"] = round(late, 4)
        print(f"parked {tag:9s} {body:8s} {r.message}; max |hub - static| over the last "
              f"10 s {worst:.3f} N; largest peak-to-peak 5-15 s {early:.4f} N, last 10 s "
              f"{late:.4f} N", flush=True)


def start(out: dict, *, t_end: float = 6.0) -> None:
    """Both cars, rigid and flexible, parked from the settled start (see module)."""
    for tag, body, _r, t, h in _parked_runs(t_end):
        cells = []
        for a in "xyz":
            x = [h[f"{c}_{a}"] for c in CORNERS]
            ref = [v[t > t_end - 1].mean() for v in x]
            at0 = max(abs(v[0] - m) for v, m in zip(x, ref, strict=True))
            peak = max(float(np.abs(v - m).max()) for v, m in zip(x, ref, strict=True))
            out[f"start_{tag}_{body}_{a}_t0_N"] = round(float(at0), 3)
            out[f"start_{tag}_{body}_{a}_max_N"] = round(peak, 3)
            cells.append(f"{a}: t=0 {at0:.2f} N, max {peak:.2f} N")
        fz = np.mean([h[f"{c}_z"][t > t_end - 1].mean() for c in CORNERS])
        print(f"start  {tag:9s} {body:8s} " + "; ".join(cells)
              + f" (static z ~{fz:.0f} N)", flush=True)


STUDIES = {"twin": twin, "parked": parked, "start": start}


def run(names=tuple(STUDIES)) -> dict:
    """Run the studies ``names``; returns a flat dict of figures."""
    out: dict = {}
    for name in names:
        STUDIES[name](out)
    return out


if __name__ == "__main__":
    bad = [a for a in sys.argv[1:] if a not in STUDIES]
    if bad:
        raise SystemExit(f"unknown study {bad}; valid: {list(STUDIES)}")
    run(tuple(sys.argv[1:]) or tuple(STUDIES))
