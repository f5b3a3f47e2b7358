"""Sweep specification: a TOML file (or the same structure as a dict) naming the base
car, road and settings once, and the parameters to vary as a grid, a list or a Latin
hypercube.  See ``docs/sweeps.md`` for the format; the short version::

    [sweep]
    car = "../cars/sedan.toml"      # paths relative to this file
    road = "../roads/iso_c_200m.toml"  # or an inline [road] table (below), or omitted: flat
    path = "straight"               # or a path file
    body = "rigid"                  # rigid | flexible | full
    speed_kmh = 60.0                # or speed_profile = "../paths/speed_brake_100_40.toml"
    driver = "../paths/driver_step_steer.toml"   # default: the car's own driver
    t_end_s = 10.0
    h_s = 0.00125                   # time step (default: simulate's for the car, 1.25 ms
                                    # or 0.25 ms for a compliant linkage suspension)
    output_step_s = 0.0025          # default: h_s (every step)
    settle_s = 0.0                  # metrics leave out samples before this time
    design = "grid"                 # grid | list | lhs
    samples = 16                    # lhs only
    seed = 0                        # lhs only
    out = "../out/sweep"            # default output folder (flexpipe sweep --out overrides)

    [parameters]                    # grid: lists; lhs: {min, max} ranges or lists (levels)
    speed_kmh = [40, 70, 100]
    "road.road_class" = ["A", "B", "C"]
    body = ["rigid", "flexible"]
    "car.corners.fl.spring_rate_N_per_m" = [25000.0, 30000.0]

    [[runs]]                        # list design: one table per run
    speed_kmh = 50

    [plots]
    metrics = ["aw_driver_floor_z_m_per_s2", "hub_fl_z_std_N"]

Parameter names: ``speed_kmh``, ``speed_profile`` (a speed-profile file used instead of
``speed_kmh``), ``driver`` (a driver file, or "default"), ``t_end_s``, ``h_s``, ``body``,
``path`` (file or "straight"), ``car`` (a car file replacing the base car, e.g. a
variant naming it as its ``base``), ``road`` (a road file replacing the base road),
``road.<key>`` (a key of the base road's ``[road]`` table, e.g. ``road.road_class``) and
``car.<dotted key>`` (any key of the car file, e.g. ``car.corners.fl.spring_rate_N_per_m``).
"""

from __future__ import annotations

import hashlib
import itertools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from flexpipe.errors import InputError
from flexpipe.sweeps import manoeuvres
from flexpipe.sweeps.metrics import MIN_SAMPLES
from flexpipe.vehicle.run_inputs import H_MAX, H_MIN, SPEED_MAX, T_END_MAX, default_step
from flexpipe.vehicle.spec import load_car

SETTINGS = ("speed_kmh", "t_end_s", "h_s", "body", "path", "road", "driver", "speed_profile",
            "car")
DESIGNS = ("grid", "list", "lhs")
BODIES = ("rigid", "flexible", "full")
_SWEEP_KEYS = ("car", "road", "path", "body", "speed_kmh", "t_end_s", "h_s", "output_step_s",
               "settle_s", "design", "samples", "seed", "out", "driver", "speed_profile")


@dataclass(frozen=True)
class RunSpec:
    """One run of a sweep, fully resolved.

    ``params`` holds the swept values (names as in the spec), ``car_overrides`` the
    dotted car keys, ``road`` a road file (Path), a ``[road]`` table (dict; ``road_base``
    is the file it came from, for relative ``file`` keys and messages) or None (flat),
    ``key`` the parameter key.  ``speed`` is m/s: the constant speed, or for a run with a
    ``speed_profile`` (its file, absolute) the profile's highest speed (what the flexible
    body's band is chosen for, as simulate() does); ``driver`` a driver file or None.
    """

    key: str
    index: int
    params: dict
    car_file: Path
    car_overrides: dict
    road: object
    road_base: Path | None
    path: str
    body: str
    speed: float
    t_end: float
    h: float
    output_step: float
    settle: float
    driver: str | None = None
    speed_profile: str | None = None


@dataclass(frozen=True)
class SweepSpec:
    """A parsed sweep (see the module docstring)."""

    file: Path | None
    car: Path
    road: object  # Path, dict (inline table) or None
    road_base: Path | None
    base: dict
    design: str
    parameters: dict
    runs_list: tuple = ()
    samples: int = 0
    seed: int = 0
    out: Path | None = None
    plots: tuple = ()
    extra: dict = field(default_factory=dict)

    # ------------------------------------------------------------------ expansion
    def points(self) -> list[dict]:
        """Swept values of every run, in run order."""
        if self.design == "list":
            return [dict(r) for r in self.runs_list]
        names = list(self.parameters)
        if self.design == "grid":
            return [dict(zip(names, combo, strict=True))
                    for combo in itertools.product(*(self.parameters[n] for n in names))]
        from scipy.stats import qmc

        u = qmc.LatinHypercube(d=len(names), seed=self.seed).random(self.samples)
        out = []
        for row in u:
            point = {}
            for name, ui in zip(names, row, strict=True):
                v = self.parameters[name]
                if isinstance(v, list):  # levels, stratified over their index
                    point[name] = v[min(int(ui * len(v)), len(v) - 1)]
                elif isinstance(v[0], int) and isinstance(v[1], int):
                    point[name] = min(v[0] + int(ui * (v[1] - v[0] + 1)), v[1])
                else:
                    point[name] = float(v[0] + ui * (v[1] - v[0]))
            out.append(point)
        return out

    def runs(self) -> list[RunSpec]:
        """Every run, resolved and keyed; each run's settings are checked here (ranges,
        the settle window), naming the spec file and key.  Duplicates (e.g. Latin
        hypercube samples of a small integer range) keep their first position."""
        from flexpipe.vehicle._car_base import car_files

        shas = {}

        def car_sha(car):   # the car file with its base files (variants)
            if car not in shas:
                shas[car] = "".join(_sha(f) for f in car_files(car))
            return shas[car]
        road_desc = _describe_road(self.road)
        out, seen = [], set()
        for i, point in enumerate(self.points()):
            r = self._resolve(i, point, car_sha, road_desc)
            if r.key not in seen:
                seen.add(r.key)
                out.append(r)
        return out

    def _key(self, name: str, point: dict, index: int) -> str:
        """Key of the spec that gave setting ``name`` of a run: ``parameters.NAME``,
        ``runs[I].NAME`` (list design) or ``sweep.NAME`` (the base value)."""
        if name in point:
            return f"runs[{index}].{name}" if self.design == "list" else f"parameters.{name}"
        return f"sweep.{name}"

    def _resolve(self, index, point, car_sha, road_desc) -> RunSpec:
        where = self.file

        def key(name):
            return self._key(name, point, index)
        s = dict(self.base)
        car_over, road_over = {}, {}
        road, car = self.road, self.car
        for name, value in point.items():
            if name.startswith("car."):
                car_over[name[4:]] = value
            elif name.startswith("road."):
                road_over[name[5:]] = value
            elif name in SETTINGS:
                s[name] = value
            else:
                raise InputError(f"unknown parameter {name!r}; valid: {', '.join(SETTINGS)}, "
                                 "road.<key of the [road] table>, car.<dotted key of the car "
                                 "file>", file=where, key=key(name))
        road_base = self.road_base
        if "car" in point:   # a car file (e.g. a variant of the base car) for this run
            car = _file(point["car"], self.file, key("car"))
        if "road" in point:
            road = _file(point["road"], self.file, key("road"))
            road_base = road
        if road_over:
            if not isinstance(road, dict):
                raise InputError("road.<key> parameters need a base road given as a .toml "
                                 "[road] table (file or inline); got "
                                 f"{road if road is not None else 'a flat road'}",
                                 file=where, key=key(f"road.{next(iter(road_over))}"))
            road = {**road, **road_over}
        body = s["body"]
        if body not in BODIES:
            raise InputError(f"body {body!r}; valid: {', '.join(BODIES)}", file=where,
                             key=key("body"))
        path = s["path"]
        if path != "straight":
            path = str(_file(path, self.file, key("path")))
        # the ranges simulate() accepts (flexpipe.vehicle.run_inputs), in the spec's units
        extra, profile, driver = {}, None, None
        if manoeuvres.speed_setting(point, self.base, where=where, key=key) == "speed_kmh":
            speed = _num(s["speed_kmh"], key("speed_kmh"), where, lo=0.0,
                         hi=round(SPEED_MAX * 3.6, 6), unit="km/h") / 3.6
        else:  # read now: a bad profile is named before any run
            p = _file(s["speed_profile"], self.file, key("speed_profile"))
            profile, sha = str(p), _sha(p)
            speed = manoeuvres.speed_profile(p, sha, where=where,
                                             key=key("speed_profile")).maximum
            extra.update(speed_profile=profile, speed_profile_sha=sha)
        if s.get("driver") not in (None, "default"):
            p = _file(s["driver"], self.file, key("driver"))
            driver, sha = str(p), _sha(p)
            manoeuvres.driver(p, sha, where=where, key=key("driver"))
            extra.update(driver=driver, driver_sha=sha)
        t_end = _num(s["t_end_s"], key("t_end_s"), where, lo=0.0, open_=True, hi=T_END_MAX,
                     unit="s")
        if s["h_s"] is None:  # the run's car's default step (compliant suspensions: finer)
            h = default_step(load_car(car, overrides=car_over or None))
        else:
            h = _num(s["h_s"], key("h_s"), where, lo=H_MIN, hi=H_MAX, unit="s")
        if h > t_end:
            raise InputError(f"h_s = {h:g} s is longer than t_end_s = {t_end:g} s "
                             f"({key('t_end_s')}); choose h_s <= t_end_s", file=where,
                             key=key("h_s"))
        output_step = h if s["output_step_s"] is None else _num(
            s["output_step_s"], key("output_step_s"), where, lo=0.0, open_=True, hi=1.0,
            unit="s")
        settle = _num(s["settle_s"], key("settle_s"), where, lo=0.0, unit="s")
        _check_window(settle, t_end, h, output_step, where=where,
                      keys=(key("settle_s"), key("t_end_s")))
        ident = {"car": str(car), "car_sha": car_sha(car), "car_overrides": car_over,
                 "road": road_desc if road is self.road else _describe_road(road),
                 "path": path, "path_sha": _sha(Path(path)) if path != "straight" else "",
                 "body": body, "speed_kmh": None if profile else float(s["speed_kmh"]),
                 "t_end_s": t_end, "h_s": h, "output_step_s": output_step}
        ident.update(extra)  # (nothing for a run without driver or profile: same keys)
        key = hashlib.sha256(json.dumps(ident, sort_keys=True, default=str).encode())
        return RunSpec(key=key.hexdigest()[:16], index=index, params=dict(point),
                       car_file=car, car_overrides=car_over, road=road,
                       road_base=road_base, path=path, body=body, speed=speed, t_end=t_end,
                       h=h, output_step=output_step, settle=settle, driver=driver,
                       speed_profile=profile)


# --------------------------------------------------------------------------- helpers
def _sha(path: Path) -> str:
    try:
        return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]
    except OSError:
        return ""


def _describe_road(road):
    if road is None:
        return "flat"
    if isinstance(road, dict):
        return {"table": road}
    return {"file": str(road), "sha": _sha(road)}


def _file(value, base_file, key) -> Path:
    if not isinstance(value, str | Path):
        raise InputError(f"expected a file name, got {value!r}", file=base_file, key=key)
    base = Path(base_file).parent if base_file is not None else Path.cwd()
    p = (base / value).resolve()
    if not p.is_file():
        raise InputError(f"file {p} does not exist (paths are relative to the sweep file)",
                         file=base_file, key=key)
    return p


def _num(v, key, where, *, lo=None, open_=False, hi=None, unit="") -> float:
    u = f" {unit}" if unit else ""
    if isinstance(v, bool) or not isinstance(v, int | float) or not math.isfinite(v):
        raise InputError(f"expected a finite number{u}, got {v!r}", file=where, key=key)
    if (lo is not None and (v < lo or (open_ and v == lo))) or (hi is not None and v > hi):
        if hi is None:
            rng = f"{'>' if open_ else '>='} {lo:g}{u}"
        else:
            rng = f"in {'(' if open_ else '['}{lo:g}, {hi:g}]{u}"
        raise InputError(f"must be {rng}, got {v!r}{u}", file=where, key=key)
    return float(v)


def _check_window(settle, t_end, h, output_step, *, where, keys) -> None:
    """The metrics need samples after ``settle``: at least :data:`MIN_SAMPLES` of the
    output times ``j * dt``, ``j = 0 .. n_out`` (``dt`` the output step as simulate()
    rounds it to whole steps ``h``; the t = 0 sample included) up to ``t_end``, counted
    as :func:`flexpipe.sweeps.metrics.run_metrics` selects them (``t >= settle - 1e-12``)."""
    every = max(1, int(round(output_step / h)))
    dt = every * h
    n_out = int(round(t_end / h)) // every
    first = max(0, math.ceil((settle - 1e-12) / dt))
    n = max(0, n_out - first + 1)
    if n < MIN_SAMPLES:
        latest = (n_out - MIN_SAMPLES + 1) * dt
        fix = f"choose settle_s <= {latest:.6g} s or " if latest >= 0 else "choose "
        raise InputError(
            f"settle_s = {settle:g} s ({keys[0]}) with t_end_s = {t_end:g} s ({keys[1]}) "
            f"leaves {n} output sample(s) (every {dt:g} s) for the metrics, which need at "
            f"least {MIN_SAMPLES}; {fix}a longer t_end_s", file=where, key=keys[0])


def _duplicates(values) -> tuple | None:
    """``(i, j, value)`` of the first value ``values[j]`` equal to an earlier ``values[i]``
    (50 and 50.0 are equal: they make the same run; true and 1 are not)."""
    for j, v in enumerate(values):
        for i in range(j):
            if isinstance(values[i], bool) == isinstance(v, bool) and values[i] == v:
                return i, j, v
    return None


def _parameters(raw, design, where) -> dict:
    if not isinstance(raw, dict):
        raise InputError("expected a [parameters] table", file=where, key="parameters")
    out = {}
    for name, v in raw.items():
        key = f"parameters.{name}"
        if design == "lhs" and isinstance(v, dict):
            if set(v) != {"min", "max"}:
                raise InputError(f"a Latin-hypercube range is {{min = ..., max = ...}}, got "
                                 f"{v!r}", file=where, key=key)
            lo, hi = _num(v["min"], key + ".min", where), _num(v["max"], key + ".max", where)
            if not hi >= lo:
                raise InputError(f"max {hi:g} < min {lo:g}", file=where, key=key)
            out[name] = (v["min"], v["max"]) if all(
                isinstance(x, int) for x in (v["min"], v["max"])) else (lo, hi)
        elif isinstance(v, list) and v:
            dup = _duplicates(v)
            if dup is not None:  # a repeated value would silently run once
                i, j, value = dup
                raise InputError(f"value {value!r} appears twice (positions {i} and {j}); each "
                                 "value of a sweep axis runs once: remove the repeat",
                                 file=where, key=key)
            out[name] = list(v)
        else:
            what = "a non-empty list of values" + (" or {min, max}" if design == "lhs" else "")
            raise InputError(f"expected {what}, got {v!r}", file=where, key=key)
    return out


def load_sweep(spec, *, base_dir=None) -> SweepSpec:
    """Read a sweep from a TOML file or a dict of the same structure.

    Parameters
    ----------
    spec : str, Path or dict
    base_dir : str or Path, optional
        Folder that relative paths of a dict spec are relative to (default: cwd).

    Raises
    ------
    InputError
        Unknown keys, bad values or missing files, naming the sweep file and key.
    """
    if isinstance(spec, SweepSpec):
        return spec
    if isinstance(spec, dict):
        doc, file = spec, None
        anchor = Path(base_dir or Path.cwd()) / "sweep.toml"
    else:
        from flexpipe.vehicle._toml import parse

        file = Path(spec)
        if file.suffix.lower() != ".toml":
            raise InputError("a sweep spec is a .toml file", file=file)
        if not file.is_file():
            raise InputError("sweep file does not exist", file=file)
        doc, _ = parse(file)
        anchor = file.resolve()
    where = file
    unknown = sorted(set(doc) - {"sweep", "parameters", "runs", "road", "plots"})
    if unknown:
        raise InputError(f"unknown table [{unknown[0]}]; valid: [sweep], [parameters], "
                         "[[runs]], [road], [plots]", file=where, key=unknown[0])
    sw = doc.get("sweep")
    if not isinstance(sw, dict):
        raise InputError("missing [sweep] table (car = ..., speed_kmh = ...)", file=where,
                         key="sweep")
    bad = sorted(set(sw) - set(_SWEEP_KEYS))
    if bad:
        raise InputError(f"unknown key; valid keys in [sweep]: {', '.join(_SWEEP_KEYS)}",
                         file=where, key=f"sweep.{bad[0]}")
    if "car" not in sw:
        raise InputError("missing required key 'car' (the base car file)", file=where,
                         key="sweep.car")
    car = _file(sw["car"], anchor, "sweep.car")
    road, road_base = None, None
    if "road" in doc and "road" in sw:
        raise InputError("give the base road once: sweep.road (a file) or a [road] table",
                         file=where, key="road")
    if "road" in doc:
        if not isinstance(doc["road"], dict):
            raise InputError("expected a [road] table", file=where, key="road")
        road, road_base = dict(doc["road"]), anchor
    elif "road" in sw:
        road = _file(sw["road"], anchor, "sweep.road")
        road_base = road
        if road.suffix.lower() == ".toml":  # keep the table so road.<key> can vary
            from flexpipe.roads._tables import read_toml

            road = dict(read_toml(road).get("road", {})) or road
    design = sw.get("design", "grid")
    if design not in DESIGNS:
        raise InputError(f"design {design!r}; valid: {', '.join(DESIGNS)}", file=where,
                         key="sweep.design")
    if "speed_kmh" in sw and "speed_profile" in sw:
        raise InputError("speed_kmh and speed_profile both in [sweep]; give one (a speed "
                         "profile replaces the constant speed)", file=where,
                         key="sweep.speed_profile")
    base = {"speed_kmh": sw.get("speed_kmh", None if "speed_profile" in sw else 60.0),
            "speed_profile": sw.get("speed_profile"), "driver": sw.get("driver"),
            "t_end_s": sw.get("t_end_s", 10.0),
            "h_s": sw.get("h_s"), "output_step_s": sw.get("output_step_s"),
            "settle_s": sw.get("settle_s", 0.0), "body": sw.get("body", "rigid"),
            "path": sw.get("path", "straight")}
    params = _parameters(doc.get("parameters", {}), design, where)
    runs_list = doc.get("runs", [])
    if design == "list":
        if not isinstance(runs_list, list) or not runs_list or not all(
                isinstance(r, dict) for r in runs_list):
            raise InputError("design = 'list' needs [[runs]] tables, one per run",
                             file=where, key="runs")
        if params:
            raise InputError("design = 'list' takes [[runs]], not [parameters]", file=where,
                             key="parameters")
    elif runs_list:
        raise InputError(f"[[runs]] needs design = 'list' (got {design!r})", file=where,
                         key="runs")
    elif not params:
        raise InputError("no [parameters] to sweep", file=where, key="parameters")
    samples = sw.get("samples", 0)
    if design == "lhs" and (isinstance(samples, bool) or not isinstance(samples, int)
                            or samples < 1):
        raise InputError(f"design = 'lhs' needs samples = a positive integer, got {samples!r}",
                         file=where, key="sweep.samples")
    seed = sw.get("seed", 0)
    if isinstance(seed, bool) or not isinstance(seed, int):
        raise InputError(f"seed must be an integer, got {seed!r}", file=where, key="sweep.seed")
    plots = doc.get("plots", {})
    metrics = plots.get("metrics", []) if isinstance(plots, dict) else None
    if not isinstance(metrics, list) or not all(isinstance(m, str) for m in metrics):
        raise InputError("[plots] metrics must be a list of metric column names", file=where,
                         key="plots.metrics")
    out = sw.get("out")
    spec_obj = SweepSpec(file=file, car=car, road=road, road_base=road_base, base=base,
                         design=design, parameters=params, runs_list=tuple(runs_list),
                         samples=int(samples), seed=seed,
                         out=(anchor.parent / out).resolve() if out else None,
                         plots=tuple(metrics))
    spec_obj.runs()  # validate every run's parameters now, before anything runs
    return spec_obj


__all__ = ["DESIGNS", "RunSpec", "SweepSpec", "load_sweep"]
