"""Step convergence of the linkage car in compliant mode (``[suspension] mode``).

The sample's time runs use the kinematic mode (each bushing replaced by the joint it
surrounds, ``cars/sedan_linkage.toml``); a car in compliant mode (every bushing as given)
runs at a finer default step (:data:`~flexpipe.vehicle.run_inputs.COMPLIANT_STEP`, 0.25 ms,
against :data:`~flexpipe.vehicle.run_inputs.DEFAULT_STEP`, 1.25 ms), and
``docs/car-file.md`` states what each mode costs in step error.  This bench measures it:
the sample in both modes, rigid body, ISO 8608 class C, 70 km/h, 4 s, at the default
step and at half of it against h/8, the compliant mode also at its own default and half
of it against h/8 of that; printed per axis is the worst corner's RMS difference after
0.5 s in percent of the fluctuating part of the reference, as in
:mod:`bench.bench_convergence`, and the CPU time of each run.
"""

from __future__ import annotations

from pathlib import Path

from flexpipe.scenarios.runner import _straight_road
from flexpipe.vehicle import load_car
from flexpipe.vehicle.convergence import check_step
from flexpipe.vehicle.run_inputs import COMPLIANT_STEP, DEFAULT_STEP

ROOT = Path(__file__).resolve().parents[1]
T_RUN = 4.0


def run() -> dict:
    """Run the study; returns a flat dict of figures (percent)."""
    out = {"h_s": DEFAULT_STEP, "compliant_h_s": COMPLIANT_STEP, "t_run_s": T_RUN}
    path = ROOT / "cars" / "sedan_linkage.toml"
    studies = (("compliant", COMPLIANT_STEP, (2, 8)), ("compliant", DEFAULT_STEP, (8,)),
               ("kinematic", DEFAULT_STEP, (2, 8)))
    for mode, h, refinements in studies:
        car = load_car(path, overrides={"suspension.mode": mode})
        c = check_step(car, h=h, refinements=refinements, t_end=T_RUN, body="rigid",
                       t_from=0.5, road=_straight_road(), speed=70 / 3.6)
        for i, hh in enumerate(c.steps[:-1]):
            label = f"{1e3 * hh:g}ms"
            cells = []
            for k in "xyz":
                w = 100 * max(c.rel_dynamic[i, j] for j, ch in enumerate(c.channels)
                              if ch.endswith(k))
                out[f"{mode}_{label}_{k}_pct"] = round(w, 2)
                cells.append(f"{k} {w:5.2f} %")
            print(f"{mode:9s} h = {label:7s} vs {1e3 * c.steps[-1]:g} ms: "
                  + "  ".join(cells) + f"   CPU {c.cpu_time[i]:.2f} s", flush=True)
            out[f"{mode}_{label}_cpu_s"] = round(c.cpu_time[i], 2)
    return out


if __name__ == "__main__":
    run()
