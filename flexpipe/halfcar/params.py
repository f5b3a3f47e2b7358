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
    road_amplitude_m, road_wavelength_m, irregularity_cycles
        Harmonic road and isolated irregularity ``s0 sin(2 pi z / lambda)``.
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
        Unreadable file, TOML syntax error, missing table/key, wrong type or a value out
        of range; the message names the file, line and key.
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
        raise InputError(f"invalid TOML: {exc}", file=path,
                         line=int(m.group(1)) if m else None) from None
    except RecursionError:
        raise InputError("invalid TOML: nested too deeply", file=path, line=1) from None
    r = _Reader(path, text, data)
    n_el = r.get("body", "n_elements", kind=int)
    front, rear = _corner(r, "front", n_el), _corner(r, "rear", n_el)
    if front.attachment_node >= rear.attachment_node:
        raise r.error("rear", "attachment_node",
                      f"rear attachment node ({rear.attachment_node}) must lie behind the "
                      f"front one ({front.attachment_node}); nodes count from the front")
    zeta_B = r.get("body", "structural_damping_ratio", allow_zero=True)
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
        free_interface_modes=r.get("reduction", "free_interface_modes", kind=int,
                                   allow_zero=True),
        truncated_modes=r.get("reduction", "truncated_modes", kind=int),
        table1_complete_Hz=r.get("table1", "complete_Hz", kind=tuple),
        table1_reduced_Hz=r.get("table1", "reduced_Hz", kind=tuple),
        table1_rigid_Hz=r.get("table1", "rigid_Hz", kind=tuple),
        source=path,
    )
