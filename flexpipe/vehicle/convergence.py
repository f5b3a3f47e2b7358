"""Step-convergence study of a run: the same run at ``h``, ``h/2``, ``h/4`` (or any list).

``check_step`` runs :func:`~flexpipe.vehicle.simulation.simulate` once per step size and
compares every requested channel with the finest run: the RMS difference after
``t_from`` relative to the fluctuating part (standard deviation) of the finest run, the
figure the README's accuracy statements quote.  ``flexpipe run ... --check-step`` prints
the table and writes it as ``step_check.csv``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError

DEFAULT_CHANNELS = tuple(f"hub_{c}_{k}" for c in ("fl", "fr", "rl", "rr") for k in "xyz")


@dataclass(frozen=True)
class StepCheck:
    """Result of :func:`check_step`.

    Attributes
    ----------
    steps : tuple of float
        Step sizes, coarsest first; the last is the reference.
    channels : tuple of str
    rms_diff : ndarray (n_steps - 1, n_channels)
        RMS of (run - reference) after ``t_from``, in the channel's unit.
    rel_dynamic : ndarray (n_steps - 1, n_channels)
        ``rms_diff`` / standard deviation of the reference (fluctuating part).
    std_ref : ndarray (n_channels,)
    cpu_time : tuple of float
        CPU seconds of each run.
    """

    steps: tuple
    channels: tuple
    rms_diff: np.ndarray
    rel_dynamic: np.ndarray
    std_ref: np.ndarray
    cpu_time: tuple

    def table(self) -> str:
        """Plain-text table: one row per channel, one column per coarse step."""
        ref = self.steps[-1]
        head = f"{'channel':<14}" + "".join(f"{f'h={h:g} vs {ref:g}':>26}"
                                             for h in self.steps[:-1])
        rows = [head]
        for j, ch in enumerate(self.channels):
            cells = "".join(f"{self.rms_diff[i, j]:>12.3g} ({100 * self.rel_dynamic[i, j]:5.1f} %)"
                            .rjust(26) for i in range(len(self.steps) - 1))
            rows.append(f"{ch:<14}{cells}")
        rows.append("RMS difference after t_from (percent of the finest run's fluctuating "
                    "part); CPU s: " + ", ".join(f"{c:.1f}" for c in self.cpu_time))
        return "\n".join(rows)

    def worst(self, i: int = 0) -> float:
        """Largest relative difference of row ``i`` (default: the coarsest step)."""
        return float(np.nanmax(self.rel_dynamic[i]))


def check_step(car, *, h: float | None = None, refinements=(2, 4), channels=DEFAULT_CHANNELS,
               t_from: float = 0.5, progress: bool = False, **simulate_kw) -> StepCheck:
    """Run ``simulate(car, h=h / r, ...)`` for ``r`` in ``(1, *refinements)`` and compare.

    Parameters
    ----------
    car : Car or path
    h : float, optional
        Coarsest step, s (default: :data:`~flexpipe.vehicle.simulation.DEFAULT_STEP`,
        the default of ``simulate``).
    refinements : sequence of int
        Divisors of ``h``, increasing; the largest gives the reference run.
    channels : sequence of str
        Channels to compare (default: every hub force component).
    t_from : float
        Start of the comparison window, s (skips the start transient).
    **simulate_kw
        Passed to :func:`~flexpipe.vehicle.simulation.simulate` (road, path, speed,
        t_end, body, ...); ``output_step`` defaults to ``h`` so every run samples alike.
    """
    from flexpipe.vehicle.simulation import DEFAULT_STEP, simulate

    h = DEFAULT_STEP if h is None else h
    refinements = tuple(int(r) for r in refinements)
    if not refinements or any(r < 2 for r in refinements) or list(refinements) != sorted(
            set(refinements)):
        raise InputError(f"refinements must be increasing integers >= 2, got {refinements}",
                         key="refinements")
    steps = (float(h),) + tuple(float(h) / r for r in refinements)
    simulate_kw.setdefault("output_step", float(h))
    runs = []
    for hh in steps:
        r = simulate(car, h=hh, progress=progress, **simulate_kw)
        if r.status != 0:
            raise InputError(f"the run at h = {hh:g} s did not complete: {r.message}", key="h")
        runs.append(r)
    ref = runs[-1]
    channels = tuple(channels)
    sel = ref.t >= t_from
    if not np.any(sel):
        raise InputError(f"no output after t_from = {t_from} s", key="t_from")
    std = np.array([np.std(ref[c][sel]) for c in channels])
    rms = np.zeros((len(steps) - 1, len(channels)))
    for i, r in enumerate(runs[:-1]):
        for j, c in enumerate(channels):
            d = np.interp(ref.t[sel], r.t, r[c]) - ref[c][sel]
            rms[i, j] = np.sqrt(np.mean(d ** 2))
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(std > 0, rms / std, np.nan)
    return StepCheck(steps=steps, channels=channels, rms_diff=rms, rel_dynamic=rel,
                     std_ref=std, cpu_time=tuple(r.cpu_time for r in runs))
