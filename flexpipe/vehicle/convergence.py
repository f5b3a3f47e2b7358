"""Step-convergence study of a run: the same run at ``h``, ``h/2``, ``h/4`` (or any list).

``check_step`` runs :func:`~flexpipe.vehicle.simulation.simulate` once per step size and
compares every requested channel with the finest run: the RMS difference after
``t_from`` in the channel's unit, and relative to the fluctuating part (standard
deviation) of the finest run, the figure the README's accuracy statements quote.  Where
that fluctuation is negligible (below :data:`FLUCTUATION_FLOOR` in the channel's unit or
below :data:`RELATIVE_FLOOR` of the channel's mean magnitude, e.g. a lateral hub force
on a straight, flat road) the relative figure divides by numerical noise: it is kept in
the numbers but marked not meaningful, and the table shows the absolute difference.
Every argument (the time window and every step size included) is checked before the
first run.  ``flexpipe run ... --check-step`` prints the table and writes it as
``step_check.csv`` into a run folder (:mod:`flexpipe.scenarios.step_study`).
"""

from __future__ import annotations

import csv
import io
from dataclasses import dataclass

import numpy as np

from flexpipe.errors import InputError

DEFAULT_CHANNELS = tuple(f"hub_{c}_{k}" for c in ("fl", "fr", "rl", "rr") for k in "xyz")
#: start of the comparison window, s: skips the start transient (driver, settling)
DEFAULT_T_FROM = 0.5

#: fluctuation (standard deviation) below which a relative step difference means
#: nothing, per channel unit.  1 N (forces) is 0.03 % of a passenger car's static wheel
#: load (3-4 kN) and far below a wheel-force transducer's resolution (about 0.1 % of a
#: 20-50 kN range); 1 N m likewise for torques; 1 um and 1 urad are below any road
#: profile, suspension travel or attitude that matters; 1e-4 m/s and rad/s below any
#: speed or spin fluctuation; 1e-3 m/s^2 is a tenth of the ISO 2631-1 perception
#: threshold of vibration (about 0.01 m/s^2); 1 kPa is 1e-6 of a steel's fatigue strength.
FLUCTUATION_FLOOR = {"N": 1.0, "N m": 1.0, "m": 1e-6, "rad": 1e-6, "m/s": 1e-4,
                     "rad/s": 1e-4, "m/s^2": 1e-3, "Pa": 1e3}
#: fluctuation below this fraction of the channel's mean magnitude is rounding of a
#: steady value (the solver's own tolerances are coarser), whatever the unit
RELATIVE_FLOOR = 1e-6


def _num(v) -> float | None:
    """A finite float, or None (JSON has no NaN)."""
    v = float(v)
    return v if np.isfinite(v) else None


def _fmt_floors(units) -> str:
    found = [f"{FLUCTUATION_FLOOR[u]:g} {u}" for u in dict.fromkeys(units)
             if u in FLUCTUATION_FLOOR]
    return (", ".join(found) + "; or " if found else "") + \
        f"{RELATIVE_FLOOR:g} of the channel's mean magnitude"


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
        ``rms_diff`` / standard deviation of the reference (fluctuating part); not
        meaningful where :attr:`meaningful` is False.
    std_ref : ndarray (n_channels,)
        Standard deviation of the reference run after ``t_from`` (channel unit).
    cpu_time : tuple of float
        CPU seconds of each run.
    units : tuple of str
        SI unit of each channel (:func:`~flexpipe.vehicle.export.channel_unit`).
    mean_abs_ref : ndarray (n_channels,)
        Mean magnitude of the reference run after ``t_from`` (channel unit).
    floor : ndarray (n_channels,)
        Fluctuation below which ``rel_dynamic`` is not meaningful: the larger of
        :data:`FLUCTUATION_FLOOR` of the unit and :data:`RELATIVE_FLOOR` x
        ``mean_abs_ref``.
    t_from, t_end : float
        Comparison window, s.
    """

    steps: tuple
    channels: tuple
    rms_diff: np.ndarray
    rel_dynamic: np.ndarray
    std_ref: np.ndarray
    cpu_time: tuple
    units: tuple = ()
    mean_abs_ref: np.ndarray | None = None
    floor: np.ndarray | None = None
    t_from: float = DEFAULT_T_FROM
    t_end: float | None = None

    @property
    def meaningful(self) -> np.ndarray:
        """Per channel: the reference's fluctuation reaches the floor, so ``rel_dynamic``
        measures the step error (else it divides by numerical noise)."""
        floor = np.zeros(len(self.channels)) if self.floor is None else self.floor
        return (self.std_ref > 0) & (self.std_ref >= floor)

    def _unit(self, j: int) -> str:
        return self.units[j] if self.units else "-"

    def _why(self, j: int) -> str:
        """Why channel ``j``'s percentage is not meaningful."""
        u = self._unit(j)
        floor = 0.0 if self.floor is None else float(self.floor[j])
        src = ""
        if self.mean_abs_ref is not None and floor > FLUCTUATION_FLOOR.get(u, 0.0):
            src = f" ({RELATIVE_FLOOR:g} of the mean magnitude {self.mean_abs_ref[j]:.4g} {u})"
        return f"n/a: fluctuation {self.std_ref[j]:.3g} {u} below floor {floor:.3g} {u}{src}"

    def header(self) -> str:
        """One line: h, the refinements, t_end and t_from."""
        h = self.steps[0]
        refs = ", ".join(f"{round(h / s):d}" for s in self.steps[1:])
        finer = ", ".join(f"h/{round(h / s):d} = {s:g} s" for s in self.steps[1:])
        end = f"t_end = {self.t_end:g} s, " if self.t_end is not None else ""
        return (f"step convergence: h = {h:g} s, refinements {refs} ({finer}; the finest is "
                f"the reference), {end}compared from t_from = {self.t_from:g} s")

    def table(self) -> str:
        """Plain-text table: a header line (h, refinements, t_end, t_from), one row per
        channel with its unit, the reference's fluctuation and per coarse step the RMS
        difference and its percentage (n/a below the floor), then a footnote."""
        ref = self.steps[-1]
        ok = self.meaningful
        rows = [self.header(),
                f"{'channel':<14}{'unit':<7}{'fluctuation':>12}"
                + "".join(f"{f'h={h:g} vs {ref:g}':>24}" for h in self.steps[:-1])]
        for j, ch in enumerate(self.channels):
            cells = ""
            for i in range(len(self.steps) - 1):
                pct = f"({100 * self.rel_dynamic[i, j]:5.1f} %)" if ok[j] else "(  n/a  )"
                cells += f"{self.rms_diff[i, j]:.3g} {pct}".rjust(24)
            note = "" if ok[j] else f"   {self._why(j)}"
            rows.append(f"{ch:<14}{self._unit(j):<7}{self.std_ref[j]:>12.3g}{cells}{note}")
        rows.append(f"RMS difference from the reference run (h = {ref:g} s) from t_from to "
                    "t_end, in the channel's unit; in parentheses as a percentage of the "
                    "reference run's fluctuating part (its standard deviation, column "
                    "'fluctuation').")
        if not ok.all():
            rows.append(f"n/a: the fluctuation is below the floor ({_fmt_floors(self.units)}),"
                        " so a percentage would divide by numerical noise; the absolute "
                        "difference is what counts there.")
        rows.append("CPU s per run: " + ", ".join(f"{c:.1f}" for c in self.cpu_time))
        return "\n".join(rows)

    def csv_text(self) -> str:
        """The table as CSV, one row per channel, units in the headers: ``std_reference``,
        ``rms_diff`` and ``rel_dynamic`` per coarse step (as before), then ``unit``,
        ``mean_abs_reference``, ``floor`` and ``relative_meaningful`` (1, or 0 where
        ``rel_dynamic`` divides by noise)."""
        units = set(self.units) if self.units else {"-"}
        u = next(iter(units)) if len(units) == 1 else "unit column"
        coarse = self.steps[:-1]
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["channel", f"std_reference [{u}]"]
                   + [f"rms_diff h={x:g} s [{u}]" for x in coarse]
                   + [f"rel_dynamic h={x:g} s [-]" for x in coarse]
                   + ["unit", f"mean_abs_reference [{u}]", f"floor [{u}]",
                      "relative_meaningful [-]"])
        ok = self.meaningful
        nan = np.full(len(self.channels), np.nan)
        mean = nan if self.mean_abs_ref is None else self.mean_abs_ref
        floor = nan if self.floor is None else self.floor
        for j, c in enumerate(self.channels):
            w.writerow([c, f"{self.std_ref[j]:.6g}"]
                       + [f"{v:.6g}" for v in self.rms_diff[:, j]]
                       + [f"{v:.6g}" for v in self.rel_dynamic[:, j]]
                       + [self._unit(j), f"{mean[j]:.6g}", f"{floor[j]:.6g}", int(ok[j])])
        return buf.getvalue()

    def to_dict(self) -> dict:
        """The study as plain numbers for ``summary.json``."""
        ok = self.meaningful
        out = {"steps_s": list(self.steps), "reference_step_s": self.steps[-1],
               "refinements": [round(self.steps[0] / s) for s in self.steps[1:]],
               "t_end_s": self.t_end, "t_from_s": self.t_from,
               "cpu_time_s": [round(c, 3) for c in self.cpu_time], "channels": {}}
        for j, c in enumerate(self.channels):
            d = {"unit": self._unit(j), "std_reference": float(self.std_ref[j]),
                 "rms_diff": {f"{h:g}": float(self.rms_diff[i, j])
                              for i, h in enumerate(self.steps[:-1])},
                 "rel_dynamic": {f"{h:g}": _num(self.rel_dynamic[i, j])
                                 for i, h in enumerate(self.steps[:-1])},
                 "relative_meaningful": bool(ok[j])}
            if self.mean_abs_ref is not None:
                d["mean_abs_reference"] = float(self.mean_abs_ref[j])
                d["floor"] = float(self.floor[j])
            if not ok[j]:
                d["note"] = self._why(j)
            out["channels"][c] = d
        out["worst_rel_dynamic"] = {f"{h:g}": _num(self.worst(i)) for i, h in
                                    enumerate(self.steps[:-1])}
        return out

    def worst(self, i: int = 0) -> float:
        """Largest relative difference of row ``i`` (default: the coarsest step) over the
        channels where it is meaningful (NaN when there is none)."""
        row = np.where(self.meaningful, self.rel_dynamic[i], np.nan)
        return float(np.nanmax(row)) if np.any(np.isfinite(row)) else float("nan")


class StoppedEarly(InputError):
    """A run of the study did not reach ``t_end`` (key ``h``): ``runs`` holds the runs
    that completed before it (finest step last), ``result`` the run that stopped."""

    def __init__(self, message: str, *, runs, result):
        super().__init__(message, key="h")
        self.runs = list(runs)
        self.result = result


def check_step_inputs(car, *, h: float | None = None, refinements=(2, 4),
                      t_from: float = DEFAULT_T_FROM, **simulate_kw) -> tuple:
    """Check every argument of :func:`check_step` without running anything: the
    refinements, the window ``t_from`` .. ``t_end``, and the arguments of every run
    (:func:`~flexpipe.vehicle.run_inputs.check_run` at each step, so a refined step below
    the smallest step is found before the first run).

    Returns
    -------
    tuple of float
        The step sizes, coarsest first.

    Raises
    ------
    InputError
        Naming the argument (``refinements``, ``t_from``, ``h`` with the refined step it
        concerns, or what :func:`check_run` names).
    """
    import inspect

    from flexpipe.vehicle.run_inputs import (
        T_END_MAX,
        as_car,
        check_run,
        checked_number,
        default_step,
    )

    if h is None:
        car = as_car(car)
        h = default_step(car)
    refinements = tuple(int(r) for r in refinements)
    if not refinements or any(r < 2 for r in refinements) or list(refinements) != sorted(
            set(refinements)):
        raise InputError(f"refinements must be increasing integers >= 2, got {refinements}",
                         key="refinements")
    h = checked_number(h, "h", lo=0.0)
    steps = (h,) + tuple(h / r for r in refinements)
    t_from = checked_number(t_from, "t_from", lo=0.0, hi=T_END_MAX, lo_closed=True, unit="s")
    t_end = simulate_kw.get("t_end")
    if isinstance(t_end, (int, float)) and np.isfinite(t_end) and t_from > t_end - h:
        raise InputError(f"t_from = {t_from:g} s leaves no comparison window before t_end = "
                         f"{t_end:g} s (the runs are compared from t_from to t_end); choose "
                         f"t_from <= t_end - h = {t_end - h:g} s or a longer t_end",
                         key="t_from")
    names = set(inspect.signature(check_run).parameters) - {"car", "h"}
    kw = {k: v for k, v in simulate_kw.items() if k in names}
    kw.setdefault("output_step", h)
    for r, hh in zip((1, *refinements), steps, strict=True):
        try:
            car = check_run(car, h=hh, **kw).car
        except InputError as exc:
            if r == 1:
                raise
            raise InputError(f"the step check's run at h/{r} = {hh:g} s: {exc.message}",
                             file=exc.file, line=exc.line, key=exc.key) from None
    return steps


def check_step(car, *, h: float | None = None, refinements=(2, 4), channels=DEFAULT_CHANNELS,
               t_from: float = DEFAULT_T_FROM, progress: bool = False, log=None,
               **simulate_kw) -> StepCheck:
    """Run ``simulate(car, h=h / r, ...)`` for ``r`` in ``(1, *refinements)`` and compare.

    Parameters
    ----------
    car : Car or path
    h : float, optional
        Coarsest step, s (default: the car's
        :func:`~flexpipe.vehicle.run_inputs.default_step`, the default of ``simulate``).
    refinements : sequence of int
        Divisors of ``h``, increasing; the largest gives the reference run.
    channels : sequence of str
        Channels to compare (default: every hub force component).
    t_from : float
        Start of the comparison window, s (skips the start transient); at most
        ``t_end - h``.
    progress : bool
        Progress bar of each run.
    log : callable, optional
        Receives one line per run (default: silent).
    **simulate_kw
        Passed to :func:`~flexpipe.vehicle.simulation.simulate` (road, path, speed,
        t_end, body, ...); ``output_step`` defaults to ``h`` so every run samples alike.

    Raises
    ------
    InputError
        A bad argument, before any run (:func:`check_step_inputs`).
    StoppedEarly
        A run that did not complete (an :class:`InputError` with key ``h`` that keeps the
        runs completed before it).
    """
    from flexpipe.vehicle.export import channel_unit
    from flexpipe.vehicle.run_inputs import as_car
    from flexpipe.vehicle.simulation import simulate

    steps = check_step_inputs(car, h=h, refinements=refinements, t_from=t_from,
                              **simulate_kw)
    car = as_car(car)
    simulate_kw.setdefault("output_step", steps[0])
    runs = []
    for i, hh in enumerate(steps, 1):
        if log is not None:
            log(f"[{i}/{len(steps)}] h = {hh:g} s")
        r = simulate(car, h=hh, progress=progress, **simulate_kw)
        if r.status != 0:
            raise StoppedEarly(f"the run at h = {hh:g} s did not complete: {r.message}",
                               runs=runs, result=r)
        runs.append(r)
    ref = runs[-1]
    channels = tuple(channels)
    sel = ref.t >= t_from
    if not np.any(sel):
        raise InputError(f"no output after t_from = {t_from} s", key="t_from")
    std = np.array([np.std(ref[c][sel]) for c in channels])
    mean_abs = np.array([np.mean(np.abs(ref[c][sel])) for c in channels])
    units = tuple(channel_unit(c) for c in channels)
    floor = np.maximum([FLUCTUATION_FLOOR.get(u, 0.0) for u in units],
                       RELATIVE_FLOOR * mean_abs)
    rms = np.zeros((len(steps) - 1, len(channels)))
    for i, r in enumerate(runs[:-1]):
        for j, c in enumerate(channels):
            d = np.interp(ref.t[sel], r.t, r[c]) - ref[c][sel]
            rms[i, j] = np.sqrt(np.mean(d ** 2))
    with np.errstate(divide="ignore", invalid="ignore"):
        rel = np.where(std > 0, rms / std, np.nan)
    return StepCheck(steps=steps, channels=channels, rms_diff=rms, rel_dynamic=rel,
                     std_ref=std, cpu_time=tuple(r.cpu_time for r in runs), units=units,
                     mean_abs_ref=mean_abs, floor=floor, t_from=float(t_from),
                     t_end=float(ref.info.get("t_end", ref.t[-1])))
