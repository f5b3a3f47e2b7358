"""Parameter set of the half-car study, read from a TOML data file.

The numbers live in ``cars/halfcar_paper.toml`` (see its comments for the reasoning
behind each value); this module only validates and types them.
"""

from __future__ import annotations

import math
import re
import tomllib
from dataclasses import dataclass
from pathlib import Path

from flexpipe.errors import InputError

#: the documented parameter set reproducing Table 1 of the paper
DEFAULT_PARAMS = Path(__file__).resolve().parents[2] / "cars" / "halfcar_paper.toml"


@dataclass(frozen=True)
class Corner:
    """One suspension corner: attachment node, spring, damper ratio, wheel and tire."""

    attachment_node: int
    spring_rate_N_per_m: float
    wheel_mass_kg: float
    tire_rate_N_per_m: float
    tire_cubic_rate_N_per_m3: float


@dataclass(frozen=True)
class HalfCarParams:
    """Typed contents of a half-car TOML file (SI units).

    Attributes
    ----------
    body_length_m, body_mass_kg, n_elements, bending_stiffness_N_m2
        Uniform Euler–Bernoulli beam of the vehicle body.
    structural_damping_ratio
        Body damping ratio at the first free–free bending mode; the body damping matrix
        is stiffness-proportional, ``C_B = beta K_B``.
    front, rear : Corner
    zeta, zeta_jounce, zeta_rebound
        Suspension damping ratios ``c / (2 sqrt(k_s m_s))`` with ``m_s`` the static
        sprung mass carried by the corner (linear, dual-rate jounce and rebound).
    gravity_m_per_s2
    reference_speed_m_per_s, reference_frequency_Hz
        ``[road] reference_speed_km_per_h`` (in m/s) and ``reference_frequency_Hz``:
        the speed of the transient study (Figs 4 and 5; the paper's 150 km/h) and the
        forcing frequency it gives on the road.
    road_amplitude_m, road_wavelength_m, irregularity_cycles
        Harmonic road and isolated irregularity ``s0 sin(2 pi z / lambda)``; the
        wavelength is ``reference_speed / reference_frequency`` (section 4 of the paper).
    sweep_f_min_Hz, sweep_f_max_Hz, sweep_n_points, harmonics, time_samples
        Response-spectrum sweep and harmonic-balance resolution.
    refine_band_Hz, refine_points
        Extra sweep points across the body-bending resonance (figures).
    free_interface_modes, truncated_modes
        Elastic free-interface modes of the reduced body; body modes of the truncated one.
    table1_complete_Hz, table1_reduced_Hz, table1_rigid_Hz
        Published Table 1 (used by the parameter fit and printed alongside results).
    source : Path
        File the values came from.
    """

    body_length_m: float
    body_mass_kg: float
    n_elements: int
    bending_stiffness_N_m2: float
    structural_damping_ratio: float
    front: Corner
    rear: Corner
    zeta: float
    zeta_jounce: float
    zeta_rebound: float
    gravity_m_per_s2: float
    reference_speed_m_per_s: float
    reference_frequency_Hz: float
    road_amplitude_m: float
    road_wavelength_m: float
    irregularity_cycles: int
    sweep_f_min_Hz: float
    sweep_f_max_Hz: float
    sweep_n_points: int
    refine_band_Hz: tuple[float, ...]
    refine_points: int
    harmonics: int
    time_samples: int
    free_interface_modes: int
    truncated_modes: int
    table1_complete_Hz: tuple[float, ...]
    table1_reduced_Hz: tuple[float, ...]
    table1_rigid_Hz: tuple[float, ...]
    source: Path

    @property
    def corners(self) -> tuple[Corner, Corner]:
        """``(front, rear)``."""
        return (self.front, self.rear)

    @property
    def body_dof(self) -> int:
        """DOF of the FE body: ``(n_elements + 1)`` nodes x (w, theta)."""
        return body_dof(self.n_elements)


def body_dof(n_elements: int) -> int:
    """DOF of a beam of ``n_elements`` cubic elements: 2 per node."""
    return 2 * (n_elements + 1)


class _Reader:
    """Typed access to a parsed TOML document that reports file, line and key."""

    def __init__(self, path: Path, text: str, data: dict):
        self.path, self.lines, self.data = path, text.splitlines(), data

    def line_of(self, section: str, key: str) -> int | None:
        header = re.compile(r"^\s*\[\s*" + re.escape(section) + r"\s*\]")
        keyline = re.compile(r"^\s*" + re.escape(key) + r"\s*=")
        inside = False
        for i, line in enumerate(self.lines, start=1):
            if line.lstrip().startswith("["):
                inside = bool(header.match(line))
            elif inside and keyline.match(line):
                return i
        return None

    def error(self, section, key, message):
        return InputError(message, file=self.path, line=self.line_of(section, key),
                          key=f"{section}.{key}")

    def get(self, section, key, *, kind=float, positive=True, allow_zero=False):
        table = self.data.get(section)
        if not isinstance(table, dict):
            raise InputError(f"missing table [{section}]", file=self.path, key=section)
        if key not in table:
            raise InputError(f"missing key '{key}' in table [{section}]", file=self.path,
                             key=f"{section}.{key}")
        value = table[key]
        if kind is int:
            if isinstance(value, bool) or not isinstance(value, int):
                raise self.error(section, key, f"must be an integer, got {value!r}")
        elif kind is float:
            if isinstance(value, bool) or not isinstance(value, (int, float)):
                raise self.error(section, key, f"must be a number, got {value!r}")
            value = float(value)
            if not math.isfinite(value):
                raise self.error(section, key, f"must be finite, got {value!r}")
        elif kind is tuple:
            if not isinstance(value, list) or not all(
                    isinstance(v, (int, float)) and not isinstance(v, bool) for v in value):
                raise self.error(section, key, f"must be a list of numbers, got {value!r}")
            return tuple(float(v) for v in value)
        if positive and (value < 0 or (value == 0 and not allow_zero)):
            valid = ">= 0" if allow_zero else "> 0"
            raise self.error(section, key, f"must be {valid}, got {value!r}")
        return value


def _corner(r: _Reader, section: str, n_elements: int) -> Corner:
    node = r.get(section, "attachment_node", kind=int, allow_zero=True)
    if not 0 <= node <= n_elements:
        raise r.error(section, "attachment_node",
                      f"node {node} is not on the beam; valid nodes are 0..{n_elements}")
    return Corner(
        attachment_node=node,
        spring_rate_N_per_m=r.get(section, "spring_rate_N_per_m"),
        wheel_mass_kg=r.get(section, "wheel_mass_kg"),
        tire_rate_N_per_m=r.get(section, "tire_rate_N_per_m"),
        tire_cubic_rate_N_per_m3=r.get(section, "tire_cubic_rate_N_per_m3", allow_zero=True),
    )


#: tables only a half-car parameter file has (a car, road or sweep file has none of them)
_HALF_CAR_TABLES = ("front", "rear", "reduction", "table1")


def _check_kind(path: Path, data: dict) -> None:
    """Refuse a TOML file of another kind (a car, road or sweep file) in one line."""
    if any(t in data for t in _HALF_CAR_TABLES):
        return
    found = ", ".join(f"[{k}]" for k in data) or "none"
    what = " (a car file for flexpipe run)" if "car" in data else ""
    raise InputError(
        f"not a half-car parameter file{what}: it has none of the tables "
        f"{', '.join(f'[{t}]' for t in _HALF_CAR_TABLES)} (its tables: {found}); a half-car "
        f"parameter file looks like {DEFAULT_PARAMS}", file=path)


def _frequencies(r: _Reader, key: str, n_max: int, what: str) -> tuple[float, ...]:
    """A ``[table1]`` list of published frequencies: 1..n_max positive numbers."""
    values = r.get("table1", key, kind=tuple)
    if not 1 <= len(values) <= n_max:
        raise r.error("table1", key,
                      f"the {what} has {n_max} natural frequencies: give 1 to {n_max} "
                      f"published values (Hz, ascending), got {len(values)}")
    if not all(math.isfinite(v) and v > 0 for v in values):
        raise r.error("table1", key, f"frequencies must be finite and > 0 Hz, got "
                                     f"{list(values)}")
    return values


def _mode_counts(r: _Reader, n_el: int) -> tuple[int, int]:
    """``[reduction]`` mode counts, checked against the DOF of the beam."""
    n = body_dof(n_el)
    fi = r.get("reduction", "free_interface_modes", kind=int, allow_zero=True)
    if fi > n - 4:
        raise r.error(
            "reduction", "free_interface_modes",
            f"{fi} elastic modes do not fit the body: body.n_elements = {n_el} gives a beam "
            f"of {n} DOF, and the reduced body keeps 2 rigid-body + free_interface_modes "
            f"elastic + 2 residual-flexibility modes, so valid values are 0..{n - 4}")
    tr = r.get("reduction", "truncated_modes", kind=int)
    if not 2 <= tr <= n:
        raise r.error(
            "reduction", "truncated_modes",
            f"must lie in 2..{n}, got {tr}: the truncated body keeps its 2 rigid-body "
            f"modes (heave, pitch) and at most all {n} modes of the beam (body.n_elements "
            f"= {n_el})")
    return fi, tr


def load_params(path=None) -> HalfCarParams:
    """Read and validate a half-car parameter file.

    Parameters
    ----------
    path : str or Path, optional
        TOML file; defaults to :data:`DEFAULT_PARAMS`.

    Returns
    -------
    HalfCarParams

    Raises
    ------
    InputError
        Unreadable file, TOML syntax error, a file of another kind (e.g. a car file),
        missing table/key, wrong type, a value out of range, mode counts the beam cannot
        hold or more published frequencies than a model has; the message names the
        file, line and key and what would be valid.
    """
    path = Path(path) if path is not None else DEFAULT_PARAMS
    try:
        text = path.read_text(encoding="utf-8")
    except OSError as exc:
        raise InputError(f"cannot read half-car parameter file ({exc.strerror})",
                         file=path) from None
    except UnicodeDecodeError as exc:
        raise InputError(f"not UTF-8 text ({exc.reason}); a parameter file is TOML text",
                         file=path) from None
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        m = re.search(r"line (\d+)", str(exc))
        line = int(m.group(1)) if m else None
        if line is None and "end of document" in str(exc):
            line = max(len(text.splitlines()), 1)
        raise InputError(f"invalid TOML: {exc}", file=path, line=line) from None
    except RecursionError:
        raise InputError("invalid TOML: nested too deeply", file=path, line=1) from None
    _check_kind(path, data)
    r = _Reader(path, text, data)
    n_el = r.get("body", "n_elements", kind=int)
    front, rear = _corner(r, "front", n_el), _corner(r, "rear", n_el)
    if front.attachment_node >= rear.attachment_node:
        raise r.error("rear", "attachment_node",
                      f"rear attachment node ({rear.attachment_node}) must lie behind the "
                      f"front one ({front.attachment_node}); nodes count from the front")
    zeta_B = r.get("body", "structural_damping_ratio", allow_zero=True)
    fi, n_trunc = _mode_counts(r, n_el)
    # section 4 of the paper: the wavelength makes the reference speed (150 km/h) give
    # the reference forcing frequency (20 Hz); the transients run at that speed
    speed = r.get("road", "reference_speed_km_per_h") / 3.6
    f_ref = r.get("road", "reference_frequency_Hz")
    f_min = r.get("sweep", "frequency_min_Hz")
    f_max = r.get("sweep", "frequency_max_Hz")
    if f_min >= f_max:
        raise r.error("sweep", "frequency_max_Hz",
                      f"must exceed frequency_min_Hz = {f_min}, got {f_max}")
    band = r.get("sweep", "refine_band_Hz", kind=tuple)
    if len(band) != 2 or not f_min <= band[0] < band[1] <= f_max:
        raise r.error("sweep", "refine_band_Hz",
                      f"must be [low, high] with {f_min} <= low < high <= {f_max}, got "
                      f"{list(band)}")
    n_h = r.get("sweep", "harmonics", kind=int)
    n_t = r.get("sweep", "time_samples", kind=int)
    if n_t < 4 * n_h:
        raise r.error("sweep", "time_samples",
                      f"must be >= 4 * harmonics = {4 * n_h} to avoid aliasing, got {n_t}")
    return HalfCarParams(
        body_length_m=r.get("body", "length_m"),
        body_mass_kg=r.get("body", "mass_kg"),
        n_elements=n_el,
        bending_stiffness_N_m2=r.get("body", "bending_stiffness_N_m2"),
        structural_damping_ratio=zeta_B,
        front=front,
        rear=rear,
        zeta=r.get("damping", "zeta"),
        zeta_jounce=r.get("damping", "zeta_jounce"),
        zeta_rebound=r.get("damping", "zeta_rebound"),
        gravity_m_per_s2=r.get("environment", "gravity_m_per_s2"),
        reference_speed_m_per_s=speed,
        reference_frequency_Hz=f_ref,
        road_amplitude_m=r.get("road", "amplitude_m"),
        road_wavelength_m=speed / f_ref,
        irregularity_cycles=r.get("road", "irregularity_cycles", kind=int),
        sweep_f_min_Hz=f_min,
        sweep_f_max_Hz=f_max,
        sweep_n_points=r.get("sweep", "n_points", kind=int),
        refine_band_Hz=band,
        refine_points=r.get("sweep", "refine_points", kind=int, allow_zero=True),
        harmonics=n_h,
        time_samples=n_t,
        free_interface_modes=fi,
        truncated_modes=n_trunc,
        table1_complete_Hz=_frequencies(r, "complete_Hz", body_dof(n_el) + 2,
                                        f"complete model (body.n_elements = {n_el})"),
        # the paper's reduced model may differ from this file's (free_interface_modes):
        # Table 1 leaves the cells of modes it does not have blank
        table1_reduced_Hz=_frequencies(r, "reduced_Hz", body_dof(n_el) + 2,
                                       f"complete model (body.n_elements = {n_el}), the "
                                       "bound of any reduced one,"),
        table1_rigid_Hz=_frequencies(r, "rigid_Hz", 4, "rigid model"),
        source=path,
    )
