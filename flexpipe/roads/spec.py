"""Road specifications: ``load_road`` dispatches on a file suffix or a TOML table.

A road TOML file holds a ``[road]`` table whose ``type`` selects the generator; keys carry
their unit::

    [road]
    type = "iso8608"          # flat | harmonic | irregularity | iso8608 | csv | crg
    road_class = "C"
    length_m = 200.0
    dx_m = 0.05
    seed = 1
    track_width_m = 1.5       # optional, all types
    coherence = "isotropic"   # optional: "isotropic" or a number in [0, 1]
    fade_m = 5.0              # optional

Other types: ``flat`` (length_m, dx_m), ``harmonic`` (wavelength_m, amplitude_m, length_m,
dx_m, phase_right_rad), ``irregularity`` (s0_m, wavelength_m, n_periods, start_m, length_m,
dx_m, tracks), ``csv`` / ``crg`` (``file``, relative to the TOML file).
"""

from __future__ import annotations

import pathlib

import numpy as np

from flexpipe._args import as_path, checked_number
from flexpipe.errors import InputError
from flexpipe.roads import generators
from flexpipe.roads._plausible import check_heights
from flexpipe.roads._tables import TableReader, read_toml
from flexpipe.roads.crg import read_crg
from flexpipe.roads.road import Road, read_csv

ROAD_TYPES = ("flat", "harmonic", "irregularity", "iso8608", "csv", "crg")


def road_from_spec(table: dict, *, file=None, name: str = "road") -> Road:
    """Build a road from a TOML-style table (see the module notes).

    Parameters
    ----------
    table : dict
        The ``[road]`` table.
    file : str or pathlib.Path, optional
        File the table came from; relative ``file`` keys are resolved against its folder.
    name : str
        Name of the table, for error messages.
    """
    t = TableReader(table, file=file, name=name)
    kind = t.str("type", choices=ROAD_TYPES)
    tw = t.float("track_width_m", 1.5, positive=True)
    base = pathlib.Path(file).parent if file is not None else pathlib.Path.cwd()
    try:
        if kind == "flat":
            road = generators.flat(t.float("length_m", positive=True),
                                   dx=t.float("dx_m", 1.0, positive=True), track_width=tw)
        elif kind == "harmonic":
            road = generators.harmonic(
                wavelength=t.float("wavelength_m", positive=True),
                amplitude=t.float("amplitude_m"), length=t.float("length_m", positive=True),
                dx=t.float("dx_m", positive=True),
                phase_right=t.float("phase_right_rad", 0.0), track_width=tw)
        elif kind == "irregularity":
            road = generators.irregularity(
                s0=t.float("s0_m"), wavelength=t.float("wavelength_m", positive=True),
                n_periods=t.int("n_periods", 10, lo=1),
                start=t.float("start_m", 20.0, nonnegative=True),
                length=t.float("length_m", None, positive=True),
                dx=t.float("dx_m", 0.01, positive=True),
                tracks=t.str("tracks", "both", choices=("both", "left", "right")),
                track_width=tw)
        elif kind == "iso8608":
            coherence = t.raw("coherence", "isotropic")
            if not (coherence == "isotropic" or (isinstance(coherence, int | float)
                                                 and not isinstance(coherence, bool)
                                                 and 0.0 <= coherence <= 1.0)):
                raise t.error("coherence", f"got {coherence!r}; valid: 'isotropic' or a "
                                           "number in [0, 1]")
            road = generators.iso8608(
                t.str("road_class", choices=tuple("ABCDEFGH")),
                t.float("length_m", positive=True), t.float("dx_m", positive=True),
                t.int("seed"), track_width=tw, coherence=coherence,
                n_min=t.float("n_min_cycles_per_m", generators.ISO8608_BAND[0], positive=True),
                n_max=t.float("n_max_cycles_per_m", generators.ISO8608_BAND[1], positive=True),
                fade=t.float("fade_m", 0.0, nonnegative=True))
        else:
            rel = t.str("file")
            target = (base / rel).resolve()
            if not target.is_file():
                raise t.error("file", f"road file {target} does not exist")
            reader = read_csv if kind == "csv" else read_crg
            road = reader(target, track_width=tw)
    except InputError as exc:
        if exc.file is not None or file is None:
            raise
        raise InputError(str(exc), file=file, key=name) from None
    t.finish()
    height_key = {"harmonic": "amplitude_m", "irregularity": "s0_m"}.get(kind)
    if height_key is not None:   # csv/crg files are checked by their readers
        check_heights(road.x, np.column_stack([road.left, road.right]), file=file,
                      labels=("left track", "right track"), key=f"{name}.{height_key}",
                      cause=f"{height_key} = {t.table[height_key]!r} looks like millimetres; "
                            "the key's unit is metres")
    return road


def load_road(spec, *, track_width: float | None = None) -> Road:
    """Load a road from a file (``.crg``, ``.csv``, ``.rdf``, ``.toml``) or a specification
    table.

    Parameters
    ----------
    spec : str, pathlib.Path or dict
        A file name, or a ``[road]``-style table (see :func:`road_from_spec`).
    track_width : float, optional
        Wheel-track distance for ``.crg``/``.csv``/``.rdf`` files (default 1.5 m); a TOML spec
        gives its own ``track_width_m``.

    Returns
    -------
    Road
    """
    if track_width is not None:
        track_width = checked_number(track_width, "track_width", lo=0.0, unit="m")
    if isinstance(spec, dict):
        return road_from_spec(spec)
    if not isinstance(spec, (str, pathlib.Path)) and not hasattr(spec, "__fspath__"):
        raise InputError("spec must be a road file (str or pathlib.Path: .crg, .csv, .rdf, "
                         ".toml) "
                         f"or a [road] table (dict), got {type(spec).__name__} {spec!r:.60}",
                         key="spec")
    path = as_path(spec, "spec")
    suffix = path.suffix.lower()
    if suffix not in (".crg", ".csv", ".rdf", ".toml"):
        raise InputError(f"unknown road file type {path.suffix!r}; valid: .crg (OpenCRG), "
                         ".csv, .rdf (Adams 2D road), .toml",
                         file=path, key="file suffix")
    if not path.is_file():
        raise InputError("road file does not exist", file=path)
    tw = 1.5 if track_width is None else track_width
    if suffix == ".crg":
        return read_crg(path, track_width=tw)
    if suffix == ".csv":
        return read_csv(path, track_width=tw)
    if suffix == ".rdf":
        from flexpipe.roads.rdf import read_rdf

        return read_rdf(path, track_width=tw)
    doc = read_toml(path)
    if set(doc) != {"road"}:
        extra = sorted(set(doc) - {"road"})
        raise InputError(f"expected a single [road] table, found {sorted(doc)}", file=path,
                         key=extra[0] if extra else "road")
    return road_from_spec(doc["road"], file=path, name="road")
