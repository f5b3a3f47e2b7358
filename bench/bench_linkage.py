"""Full car on linkage suspensions (``cars/sedan_linkage.toml``): speed and profile.

Targets (issue "Numbers that converge"): the flexible car at the default step at least 3x
faster than real time, flexible/rigid CPU at most 2, with the linkage suspension.  The
same run is made with the prismatic-corner sample (``cars/sedan.toml``) as the peer: the
ratios are against it and against the rigid car, all measured in this run.  The profile
splits each run's CPU time into the Python step (tyre model, linearization, driver,
recording) and Exudyn's own work (the rest); a separate 2 s run of the linkage car with
Exudyn's timers on (``simulate(profile=True)``) splits Exudyn's part further.  Only
Exudyn's range-checked module has those timers, so that run is made in a process of its
own on it (``FLEXPIPE_EXUDYN=checked``; its total, printed too, is that module's); the
timed runs use the module flexpipe loads by default (``exudyn_module`` in the output).  The
linkage car is also run at 1 ms (the default until 2026-12-04) and at 2 ms (the default
before the step was halved for convergence) as the peers of the default step, on
``make slalom``'s run (60 km/h, ISO B, 8 cones): a turning car, whose Newton Jacobian
the time loop renews as the body turns, and on two of Exudyn's threads against one
(``threads*`` keys: wall-clock time, its peer the one-thread run made alternately in the
same bench).

This virtual machine's speed changes by 20-55 % from minute to minute (other machines
share its cores and caches), and a slow spell hits the flexible car's run harder than
the rigid one's (single runs on 2026-12-02 gave ratios of 1.76 to 2.27 within
five minutes).  The linkage car at the default step, the figure the targets are about,
is therefore run :data:`REPEATS` times, rigid and flexible alternating; each run's CPU
time is printed, and the figures are the best of the runs (as ``timeit`` takes them:
the machine's noise only ever adds time), their ratio, and the range of the ratios of
adjacent pairs.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

from flexpipe.exu import compiled_module
from flexpipe.scenarios.runner import _slalom_path, _slalom_road, _straight_road
from flexpipe.vehicle import load_car, simulate
from flexpipe.vehicle.simulation import DEFAULT_STEP, prepare

ROOT = Path(__file__).resolve().parents[1]
SPEED = 70.0 / 3.6
SLALOM_SPEED = 60.0 / 3.6  # make slalom's
T_RUN = 10.0
T_PROFILE = 2.0
#: alternating runs of the linkage car at the default step (best of them is the figure)
REPEATS = 3


def run() -> dict:
    """Run the benchmark; returns a flat dict of figures."""
    road = _straight_road()
    out = {"t_run_s": T_RUN, "speed_kmh": 70.0, "h_s": DEFAULT_STEP}
    linkage, prismatic = ROOT / "cars" / "sedan_linkage.toml", ROOT / "cars" / "sedan.toml"
    runs = [("linkage", linkage, DEFAULT_STEP, "", REPEATS),
            ("prismatic", prismatic, DEFAULT_STEP, "", 1),
            ("linkage", linkage, 1e-3, "_at_1ms", 1),
            ("linkage", linkage, 2e-3, "_at_2ms", 1)]
    preps = {}  # (car file, body) -> (car, prepared run): set up once, used by every run
    for tag, path, h, suffix, repeats in runs:
        cpu = {"rigid": [], "flexible": []}
        for _ in range(repeats):
            for body in ("rigid", "flexible"):
                if (path, body) not in preps:
                    car = load_car(path)
                    preps[path, body] = car, prepare(car, body=body, speed=SPEED, road=road)
                car, prep = preps[path, body]
                r = simulate(car, road=road, speed=SPEED, t_end=T_RUN, body=body,
                             prepared=prep, h=h)
                cpu[body].append(r.cpu_time)
                key = f"{tag}_{body}{suffix}"
                out[f"{key}_status"] = min(out.get(f"{key}_status", 0), r.status)  # worst
                if r.cpu_time > min(cpu[body]):
                    continue  # the figures are the best run's
                py = r.info.get("cpu_python_step_s", 0.0)
                out[f"{key}_cpu_s"] = round(r.cpu_time, 3)
                out[f"{key}_realtime_factor"] = round(r.realtime_factor, 3)
                out[f"{key}_cpu_python_step_s"] = round(py, 3)
                out[f"{key}_cpu_exudyn_s"] = round(r.cpu_time - py, 3)
                out[f"{key}_ms_per_step"] = round(1e3 * r.cpu_time / (T_RUN / h), 4)
                out[f"{key}_newton_iterations_per_step"] = r.info.get(
                    "newton_iterations_per_step")
                out[f"{key}_newton_jacobians"] = r.info.get("newton_jacobians")
                if body == "flexible":
                    out[f"{key}_modes"] = r.info.get("n_elastic_modes")
        out[f"{tag}_cpu_ratio_flexible_to_rigid{suffix}"] = round(
            out[f"{tag}_flexible{suffix}_cpu_s"] / out[f"{tag}_rigid{suffix}_cpu_s"], 3)
        if repeats > 1:
            for body, times in cpu.items():
                out[f"{tag}_{body}{suffix}_cpu_s_runs"] = [round(c, 2) for c in times]
            pairs = [f / r for r, f in zip(cpu["rigid"], cpu["flexible"], strict=True)]
            out[f"{tag}_cpu_ratio_flexible_to_rigid{suffix}_pairs"] = [
                round(min(pairs), 3), round(max(pairs), 3)]
    _slalom(out, linkage)
    _two_threads(out, preps, linkage, road)
    out["linkage_over_prismatic_cpu_flexible"] = round(
        out["linkage_flexible_cpu_s"] / out["prismatic_flexible_cpu_s"], 3)
    out["target_flexible_rtf_at_least_3"] = out["linkage_flexible_realtime_factor"] >= 3.0
    out["target_ratio_at_most_2"] = out["linkage_cpu_ratio_flexible_to_rigid"] <= 2.0
    out["exudyn_module"] = compiled_module()
    # the profile: Exudyn's own timers and the Python step, ms per step, linkage car at the
    # default step (T_PROFILE s; the timers cost a little themselves, so not in the table)
    for body, prof in _checked_profile().items():
        for part, ms in prof.items():
            out[f"profile_linkage_{body}_{part}_ms"] = ms
    for k, v in out.items():
        print(f"{k:44s} {v}")
    return out


def _slalom(out: dict, path) -> None:
    """The linkage car on ``make slalom``'s run (a turning car: the time loop renews its
    Newton Jacobian as the body turns, flexpipe.exu.timeloop.JACOBIAN_RENEW_DEG)."""
    car = load_car(path)
    for body in ("rigid", "flexible"):
        r = simulate(car, road=_slalom_road(), path=_slalom_path(), speed=SLALOM_SPEED,
                     t_end=T_RUN, body=body)
        key = f"slalom_{body}"
        out[f"{key}_status"] = r.status
        out[f"{key}_cpu_s"] = round(r.cpu_time, 3)
        out[f"{key}_realtime_factor"] = round(r.realtime_factor, 3)
        out[f"{key}_newton_iterations_per_step"] = r.info.get("newton_iterations_per_step")
        out[f"{key}_newton_jacobians"] = r.info.get("newton_jacobians")
    out["slalom_cpu_ratio_flexible_to_rigid"] = round(
        out["slalom_flexible_cpu_s"] / out["slalom_rigid_cpu_s"], 3)


def _two_threads(out: dict, preps: dict, path, road) -> None:
    """The linkage car at the default step on one and on two of Exudyn's threads
    (``simulate(threads=...)``, :mod:`flexpipe.exu.threads`), alternating, best of
    :data:`REPEATS` (the rigid car once): wall-clock time, the real-time factor on it, and
    the two-thread run's CPU (both threads, the second spinning while it waits)."""
    for body, repeats in (("flexible", REPEATS), ("rigid", 1)):
        car, prep = preps[path, body]
        wall = {1: [], 2: []}
        for _ in range(repeats):
            for n in (1, 2):
                r = simulate(car, road=road, speed=SPEED, t_end=T_RUN, body=body,
                             prepared=prep, threads=n)
                key = f"threads{n}_{body}"
                out[f"{key}_status"] = min(out.get(f"{key}_status", 0), r.status)
                out[f"{key}_threads_used"] = r.info.get("threads")
                wall[n].append(r.wall_time)
                if r.wall_time <= min(wall[n]):
                    out[f"{key}_wall_s"] = round(r.wall_time, 3)
                    out[f"{key}_wall_realtime_factor"] = round(r.wall_realtime_factor, 3)
                    out[f"{key}_cpu_s"] = round(r.cpu_time, 3)
        for n in (1, 2):
            out[f"threads{n}_{body}_wall_s_runs"] = [round(w, 2) for w in wall[n]]
        out[f"threads_{body}_wall_2_over_1"] = round(
            out[f"threads2_{body}_wall_s"] / out[f"threads1_{body}_wall_s"], 3)


PROFILE_RUN = """
import json, sys
from flexpipe.scenarios.runner import _straight_road
from flexpipe.vehicle import load_car, simulate
car, road = load_car(sys.argv[1]), _straight_road()
print(json.dumps({f"{body}{tag}": simulate(
    car, road=road, speed=float(sys.argv[2]), t_end=float(sys.argv[3]), body=body,
    profile=True, threads=n).info["profile_ms_per_step"]
    for body, n, tag in (("rigid", 1, ""), ("flexible", 1, ""), ("flexible", 2, "_2threads"))}))
"""


def _checked_profile() -> dict:
    """Exudyn's part timers for both bodies, from a run on its range-checked module."""
    p = subprocess.run([sys.executable, "-c", PROFILE_RUN,
                        str(ROOT / "cars" / "sedan_linkage.toml"), str(SPEED), str(T_PROFILE)],
                       capture_output=True, text=True, cwd=ROOT, check=True,
                       env=dict(os.environ, FLEXPIPE_EXUDYN="checked"))
    return json.loads(p.stdout.strip().splitlines()[-1])


if __name__ == "__main__":
    run()
