"""Step convergence of the linkage car in compliant mode (``[suspension] mode``).

The sample's time runs use the kinematic mode (each bushing replaced by the joint it
surrounds, ``cars/sedan_linkage.toml``); ``docs/car-file.md`` states what the compliant
mode (every bushing as given) costs in step error.  This bench measures it: the sample
with ``suspension.mode = "compliant"``, rigid body, ISO 8608 class C, 70 km/h, 4 s,
at the default step (1 ms) and at 0.5 ms, each against h/8 of the default (0.125 ms);
printed per axis is the worst corner's RMS difference after 0.5 s in percent of the
fluctuating part of the reference, as in :mod:`bench.bench_convergence`.  The kinematic
sample is the peer, measured in the same run.
"""

from __future__ import annotations

from pathlib import Path

from flexpipe.scenarios.runner import _straight_road
from flexpipe.vehicle import load_car
from flexpipe.vehicle.convergence import check_step
from flexpipe.vehicle.simulation import DEFAULT_STEP

ROOT = Path(__file__).resolve().parents[1]
T_RUN = 4.0


def run() -> dict:
    """Run the study; returns a flat dict of figures (percent)."""
    out = {"h_s": DEFAULT_STEP, "t_run_s": T_RUN}
    path = ROOT / "cars" / "sedan_linkage.toml"
    for mode in ("compliant", "kinematic"):
        car = load_car(path, overrides={"suspension.mode": mode})
        c = check_step(car, h=DEFAULT_STEP, refinements=(2, 8), t_end=T_RUN, body="rigid",
                       t_from=0.5, road=_straight_road(), speed=70 / 3.6)
        for i, label in enumerate(("1ms", "0.5ms")):
            cells = []
            for k in "xyz":
                w = 100 * max(c.rel_dynamic[i, j] for j, ch in enumerate(c.channels)
                              if ch.endswith(k))
                out[f"{mode}_{label}_{k}_pct"] = round(w, 2)
                cells.append(f"{k} {w:5.2f} %")
            print(f"{mode:9s} h = {label:5s} vs h/8: " + "  ".join(cells), flush=True)
        out[f"{mode}_cpu_s"] = [round(t, 2) for t in c.cpu_time]
    return out


if __name__ == "__main__":
    run()
