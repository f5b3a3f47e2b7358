"""The Numba kernels of a car run: whether they still need compiling, and compiling them.

A car run calls compiled kernels in every step: the PAC2002 wheel forces
(:mod:`flexpipe.tires._fast`), the implicit tyre coupling's corrector and predictor
(:mod:`flexpipe.vehicle._tire_coupling_fast`), the tyre element
(:mod:`flexpipe.exu._tire_element`) and the node-state reader
(:mod:`flexpipe.exu._node_state`).  Numba compiles them at their first call and keeps the
machine code on disk (``cache=True``: in ``__pycache__`` next to the sources, or under
``NUMBA_CACHE_DIR``), so only the first run after installing or updating flexpipe pays
for it: ``flexpipe run cars/sedan.toml --body rigid --t-end 0.02`` on a fresh clone took
28.0 s with the kernels still to compile and 6.0 s with them cached (empty body cache,
2026-12-02); compiling them with both sample cars took 24 s.

:func:`pending` tells :func:`flexpipe.vehicle.simulate` to say so before such a run
starts; ``python -m flexpipe.vehicle.warmup CAR.toml ...`` compiles them ahead with a
few steps of each car (the Makefile's set-up step does, with the sample cars).
"""

from __future__ import annotations

import importlib
import sys
import time

#: the kernels a car run calls from Python, by module (the rest are compiled into them)
RUN_KERNELS = {"flexpipe.vehicle._tire_coupling_fast": ("correct_group", "predict_group",
                                                        "applied_force"),
               "flexpipe.exu._tire_element": ("element",),
               "flexpipe.exu._node_state": ("node_states",),
               "flexpipe.roads._contact_fast": ("contact",)}
MESSAGE = ("compiling flexpipe's Numba kernels (tyre model and coupling): the first run "
           "after installing or updating takes about 25 s longer; they are cached after it")


def kernels() -> list:
    """The compiled kernels a car run calls (empty when Numba is not used)."""
    from flexpipe.tires._fast import enabled

    if not enabled():
        return []
    return [getattr(importlib.import_module(m), name)
            for m, names in RUN_KERNELS.items() for name in names]


def _ready(kernel) -> bool:
    """Compiled in this process, or machine code for its current source is on disk
    (Numba's cache index, which Numba drops when the kernel's own file changed and
    :func:`flexpipe.tires._fast.drop_stale_caches` when a file it calls changed)."""
    if kernel.signatures:
        return True
    try:
        return bool(kernel._cache._cache_file._load_index())
    except (AttributeError, OSError, ValueError):  # cannot tell: say it may compile
        return False


def pending() -> bool:
    """True when a car run would compile some of its kernels first."""
    return not all(_ready(k) for k in kernels())


def warm_up(cars, *, speed: float = 10.0, steps: int = 5) -> None:
    """Compile the kernels by running each car (a Car or car file; rigid body, flat road)
    a few steps."""
    from flexpipe.vehicle import simulate
    from flexpipe.vehicle.simulation import DEFAULT_STEP

    for car in cars:
        r = simulate(car, speed=speed, t_end=steps * DEFAULT_STEP, body="rigid")
        if r.status != 0:
            raise RuntimeError(f"{car}: the warm-up run failed: {r.message}")


def main(argv=None) -> int:
    from flexpipe.errors import FlexpipeError
    from flexpipe.vehicle import load_car

    files = list(sys.argv[1:] if argv is None else argv)
    if not files:
        print("usage: python -m flexpipe.vehicle.warmup CAR.toml [CAR.toml ...]",
              file=sys.stderr)
        return 2
    try:
        cars = [load_car(f) for f in files]  # bad files are named whatever the cache holds
        if not pending():
            print("flexpipe's Numba kernels are compiled")
            return 0
        print(MESSAGE)
        t0 = time.perf_counter()
        warm_up(cars)
    except (FlexpipeError, RuntimeError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    print(f"compiled in {time.perf_counter() - t0:.0f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main())
