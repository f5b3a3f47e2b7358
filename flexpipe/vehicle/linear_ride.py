"""Ride on a random road from the linear model: output spectra, RMS values and ISO 2631-1
weighted accelerations without a time run.

The road is an ISO 8608 class (displacement PSD ``Gd(n) = Gd(n0) (n / n0)^-2`` over the
classification band of spatial frequencies ``n``, as :func:`flexpipe.roads.iso8608`
synthesises it).  At speed ``V`` one track's height has the one-sided temporal PSD
``G(f) = Gd(f / V) / V`` (m^2/Hz).  The two tracks, a distance ``B`` apart, share the PSD
and have the coherence ``gamma(n)`` (the cross-spectrum ``gamma G`` is real): the
isotropic-surface model ``gamma = x K1(x)``, ``x = 2 pi n B``, or a constant.  Their
mean ``(L + R) / 2`` and half difference ``(L - R) / 2`` are then uncorrelated with the
PSDs ``G (1 + gamma) / 2`` and ``G (1 - gamma) / 2``, and they are what
:meth:`~flexpipe.vehicle.linear.LinearModes.track_response` answers with ``"same"`` and
``"opposite"`` tracks (each wheel meeting the profile at its place, the rear ones a
wheelbase later).  So every output has the PSD

    S(f) = G(f) [ |H_same(f)|^2 (1 + gamma) / 2 + |H_opposite(f)|^2 (1 - gamma) / 2 ]

and its RMS is ``sqrt(int S df)``.  The accelerations' ISO 2631-1 weighted RMS
``a_w = sqrt(int |W(f)|^2 S df)`` uses Wk vertically and Wd fore-aft and laterally
(:mod:`flexpipe.sweeps.iso2631`); each body point's total value
``a_v = sqrt(a_wx^2 + a_wy^2 + a_wz^2)`` (comfort, multiplying factors 1, ISO 2631-1
8.2.3) with the standard's comfort reaction (Annex C).  The vertical tyre forces' RMS over
their static value is the dynamic load coefficient (road holding, road damage).

Checks (``tests/test_linear_ride.py``): a quarter car against the covariance of its state
equations (Lyapunov), and the sample car's linear model run in time over roads
synthesised with the same spectrum.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from flexpipe.errors import InputError
from flexpipe.sweeps.iso2631 import comfort_reaction
from flexpipe.vehicle.seats import seat_value, with_seats

#: frequency samples of the spectra (log spaced over the road's band at the speed): a
#: step of 0.2 % resolves a resonance of damping ratio 0.01 with 10 samples per
#: half-power band
N_FREQ = 4000
def road_psd(f_hz, *, road_class: str, speed: float, n_band=None) -> np.ndarray:
    """One-sided temporal PSD ``G(f) = Gd(f / V) / V`` (m^2/Hz) of one track of an ISO 8608
    class-``road_class`` road met at ``speed`` (m/s), zero outside ``n_band`` (cycles/m;
    default the classification band, as :func:`flexpipe.roads.iso8608`)."""
    from flexpipe.roads import ISO8608_BAND, iso8608_psd

    if not (np.isfinite(speed) and speed > 0.0):
        raise InputError(f"a road spectrum needs a speed > 0 m/s, got {speed!r}: at rest "
                         "the road does not move under the wheels", key="speed")
    n = np.asarray(f_hz, dtype=float) / speed
    return iso8608_psd(road_class, n, n_band=ISO8608_BAND if n_band is None else n_band,
                       what="ride") / speed


def output_psd(road, H_same, H_opposite, gamma) -> np.ndarray:
    """PSD of every output, ``road (|H_same|^2 (1 + gamma) + |H_opposite|^2 (1 - gamma))
    / 2`` (module notes).

    Parameters
    ----------
    road : array_like (f,)
        One track's PSD (m^2/Hz).
    H_same, H_opposite : array_like (f, outputs), complex
        Responses per metre of road height on both tracks, and on the left with its
        negative on the right.
    gamma : array_like (f,) or float
        Coherence of the two tracks (cross-spectrum over PSD), in [-1, 1].
    """
    g = np.asarray(gamma, dtype=float)
    if np.any(np.abs(g) > 1.0):
        raise InputError("track coherence must be in [-1, 1]", key="coherence")
    g = np.broadcast_to(g, np.shape(road))[:, None]
    return np.asarray(road, dtype=float)[:, None] * 0.5 * (
        np.abs(H_same) ** 2 * (1.0 + g) + np.abs(H_opposite) ** 2 * (1.0 - g))


@dataclass(frozen=True)
class RideResponse:
    """Response of a linearized car to an ISO 8608 road.

    Attributes
    ----------
    f_hz : ndarray (f,)
        Frequencies (Hz) of the spectra, log spaced over the road's band at the speed.
    road_psd : ndarray (f,)
        One track's height PSD (m^2/Hz).
    coherence : ndarray (f,)
        The tracks' coherence.
    psd : ndarray (f, outputs)
        Output PSDs, (unit)^2/Hz, ``outputs`` as the linear model's.
    rms : ndarray (outputs,)
        RMS of each output about its value at the linearization state (N, m, m/s^2).
    weighted_rms : ndarray (outputs,)
        ISO 2631-1 weighted RMS of the accelerations (Wk for z, Wd for x and y; NaN for
        the tyre forces), m/s^2.
    points : dict
        Per body point: ``"a_v_m/s^2"``, the total comfort value, and its ``"reaction"``
        (ISO 2631-1 Annex C).
    dynamic_load : dict
        Per tyre: RMS of the vertical force over its static value (-).
    difference_rms, difference_psd : ndarray (outputs,) and (f, outputs), or None
        With a ``reference`` model: RMS and PSD of this model's outputs minus the
        reference's on the same road (e.g. flexible minus rigid hub forces), free of any
        time step.
    """

    car: str
    body: str
    speed: float
    road_class: str
    track_width: float
    f_hz: np.ndarray
    road_psd: np.ndarray
    coherence: np.ndarray
    outputs: tuple
    psd: np.ndarray
    rms: np.ndarray
    weighted_rms: np.ndarray
    points: dict
    dynamic_load: dict
    difference_rms: np.ndarray | None = None
    difference_psd: np.ndarray | None = None
    info: dict = field(default_factory=dict)

    def rows(self) -> list[dict]:
        """One dict per output (the CSV's columns, units in the keys)."""
        from flexpipe.vehicle.linear import output_unit

        out = []
        for j, name in enumerate(self.outputs):
            row = {"output": name, "unit": output_unit(name), "rms": float(self.rms[j])}
            row["iso2631_weighting"] = _weighting(name) or ""
            row["weighted_rms"] = float(self.weighted_rms[j])
            if self.difference_rms is not None:
                row["difference_rms"] = float(self.difference_rms[j])
            out.append(row)
        return out


def ride_response(modes, road_class: str = "C", *, coherence="isotropic",
                  track_width: float | None = None, n_band=None, n_freq: int = N_FREQ,
                  reference=None) -> RideResponse:
    """Spectra, RMS and ISO 2631-1 values of a linearized car on an ISO 8608 road.

    Parameters
    ----------
    modes : LinearModes
        The car linearized at a speed > 0 (:func:`flexpipe.linear_modes`).
    road_class : str
        ISO 8608 class, ``"A"`` .. ``"H"``.
    coherence : "isotropic" or float
        The tracks' coherence: the isotropic-surface model, or a constant in [0, 1]
        (1: both tracks the same; 0: independent), as :func:`flexpipe.roads.iso8608`.
    track_width : float, optional
        Distance between the tracks (m); default the car's mean track.
    n_band : (float, float), optional
        Spatial-frequency band (cycles/m); default the ISO 8608 classification band.
    n_freq : int
        Frequency samples (default :data:`N_FREQ`).
    reference : LinearModes, optional
        The same car's model at the same speed with another body (e.g. rigid): the RMS
        of the outputs' difference on the same road (``difference_rms``).

    Raises
    ------
    InputError
        A model linearized at rest, an unknown road class, a coherence outside [0, 1], a
        band that is not ``0 < n_lo < n_hi``, fewer than 100 samples, a reference of
        other outputs or speed.
    """
    from flexpipe.roads import ISO8608_BAND, checked_coherence, track_coherence
    from flexpipe.sweeps.iso2631 import response

    if modes.speed <= 0.0:
        raise InputError("the ride response needs the car linearized at a speed > 0 "
                         "(linear_modes(..., speed=...), flexpipe linear --speed): at rest "
                         "the road does not move under the wheels", key="speed")
    n_lo, n_hi = ISO8608_BAND if n_band is None else (float(n_band[0]), float(n_band[1]))
    if not (0.0 < n_lo < n_hi < np.inf):
        raise InputError(f"n_band must be 0 < n_lo < n_hi cycles/m, got {n_band!r}",
                         key="n_band")
    if not (isinstance(n_freq, int) and n_freq >= 100):
        raise InputError(f"n_freq must be an integer >= 100, got {n_freq!r}", key="n_freq")
    if track_width is None:
        y = np.asarray(modes.info["wheel_y_m"], dtype=float)
        track_width = float(np.mean(np.abs(y[0::2] - y[1::2])))
    elif not (np.isfinite(track_width) and track_width > 0.0):
        raise InputError(f"track_width must be > 0 m, got {track_width!r}",
                         key="track_width")
    v = modes.speed
    f = np.geomspace(v * n_lo, v * n_hi, n_freq)
    coherence = checked_coherence(coherence, what="ride")
    gamma = track_coherence(coherence, f / v, track_width)
    G = road_psd(f, road_class=road_class, speed=v, n_band=(n_lo, n_hi))
    H = modes.frequency_response(f)
    H_same = modes.track_response(f, tracks="same", H=H)
    H_opposite = modes.track_response(f, tracks="opposite", H=H)
    outputs, H_same, H_opposite = with_seats(modes, f, H_same, H_opposite)
    S = output_psd(G, H_same, H_opposite, gamma)
    rms = np.sqrt(np.trapezoid(S, f, axis=0))
    difference = S_d = None
    if reference is not None:  # the two models' outputs on the same road, subtracted
        if tuple(reference.outputs) != tuple(modes.outputs) \
                or not abs(reference.speed - v) <= 1e-9 * v:
            raise InputError(f"the reference must be the same car's linear model at the "
                             f"same speed ({v:g} m/s, outputs {len(modes.outputs)}); got "
                             f"{reference.speed:g} m/s, {len(reference.outputs)} outputs",
                             key="reference")
        H_ref = reference.frequency_response(f)
        _, R_same, R_opposite = with_seats(
            reference, f, reference.track_response(f, tracks="same", H=H_ref),
            reference.track_response(f, tracks="opposite", H=H_ref))
        S_d = output_psd(G, H_same - R_same, H_opposite - R_opposite, gamma)
        difference = np.sqrt(np.trapezoid(S_d, f, axis=0))
    w_rms = np.full(rms.shape, np.nan)
    for j, name in enumerate(outputs):
        if (wk := _weighting(name)) is not None:
            w_rms[j] = np.sqrt(np.trapezoid(np.abs(response(f, wk)) ** 2 * S[:, j], f))
    points = {}
    for name in outputs:
        if name.startswith("acc_") and name.endswith("_z"):
            point = name[4:-2]
            idx = [outputs.index(f"acc_{point}_{ax}") for ax in "xyz"]
            a_v = float(np.sqrt(np.sum(w_rms[idx] ** 2)))
            points[point] = {"a_v_m/s^2": a_v, "reaction": comfort_reaction(a_v)}
    for fields in modes.info.get("seats", ()):
        seat, floor = fields["name"], fields["floor_point"]
        if seat in points:  # SEAT value: the seat's weighted vertical RMS over the floor's
            points[seat]["SEAT_%"] = seat_value(w_rms[outputs.index(f"acc_{seat}_z")],
                                                w_rms[outputs.index(f"acc_{floor}_z")])
    # the tyres' static loads are in the outputs' order (tire_<corner>_Fz, corners fl..rr)
    static = modes.info.get("tire_Fz_N")
    tyres = [j for j, name in enumerate(modes.outputs) if name.endswith("_Fz")]
    dynamic = {} if static is None else {
        modes.outputs[j][5:-3]: float(rms[j] / load)
        for j, load in zip(tyres, static, strict=True)}
    return RideResponse(car=modes.car, body=modes.body, speed=v,
                        road_class=str(road_class).upper(), track_width=track_width,
                        f_hz=f, road_psd=G, coherence=gamma, outputs=outputs,
                        psd=S, rms=rms, weighted_rms=w_rms, points=points,
                        dynamic_load=dynamic,
                        difference_rms=difference, difference_psd=S_d,
                        info={"n_band_cycles/m": [n_lo, n_hi],
                              "coherence_model": coherence,
                              "road_rms_m": float(np.sqrt(np.trapezoid(G, f))),
                              **({"reference_body": reference.body}
                                 if reference is not None else {})})


def _weighting(name: str) -> str | None:
    """ISO 2631-1 weighting of an acceleration output (None for other outputs)."""
    from flexpipe.sweeps.iso2631 import AXIS_WEIGHTING

    if name.startswith("acc_") and name[-2:] in ("_x", "_y", "_z"):
        return AXIS_WEIGHTING[name[-1]]
    return None


def ride_vs_speed(car, speeds, road_class: str = "C", *, body: str = "flexible",
                  coherence="isotropic", f_max=None, reference: str | None = None,
                  progress: bool = True) -> list:
    """The ride on one ISO 8608 road at several speeds: the car linearized at each
    (:func:`flexpipe.linear_modes`) and answered by :func:`ride_response`.

    Parameters
    ----------
    car : Car or str or Path
        A car with linkage suspensions.
    speeds : sequence of float
        Speeds, m/s, each in (0, 300 km/h]; at least one, no repeats.
    road_class, coherence
        As :func:`ride_response`.
    body, f_max
        As :func:`flexpipe.linear_modes`.
    reference : str, optional
        Another body (``"rigid"``, ``"flexible"`` or ``"full"``): the car is linearized
        with it too at each speed and each response carries the RMS of the outputs'
        difference on the same road (``difference_rms``, e.g. flexible minus rigid hub
        forces against speed).
    progress : bool
        Show a progress bar (tqdm) over the speeds.

    Returns
    -------
    list of RideResponse
        One per speed, in the order given.

    Raises
    ------
    InputError
        No speeds, a repeated or non-positive speed, a reference that is not another
        body, or anything :func:`~flexpipe.vehicle.linear.linear_modes` or
        :func:`ride_response` refuses (checked for the road before the first
        linearization).
    """
    from tqdm import tqdm

    from flexpipe.roads import checked_coherence
    from flexpipe.vehicle.linear import linear_modes
    from flexpipe.vehicle.run_inputs import BODIES
    from flexpipe.vehicle.spec import Car, load_car

    try:
        v = [float(s) for s in speeds]
    except (TypeError, ValueError) as err:
        raise InputError(f"speeds must be numbers (m/s), got {speeds!r}", key="speeds") \
            from err
    if not v or any(not (np.isfinite(s) and 0.0 < s <= 300 / 3.6) for s in v) \
            or len(set(v)) != len(v):
        raise InputError(f"speeds must be distinct, in (0, {300 / 3.6:.2f}] m/s, at least "
                         f"one; got {speeds!r}", key="speeds")
    road_psd([1.0], road_class=road_class, speed=v[0])  # the class, before any work
    checked_coherence(coherence, what="ride")
    if reference is not None:
        ref = str(reference).strip().lower()
        if ref not in BODIES or ref == str(body).strip().lower():
            raise InputError(f"reference must be another body than {body!r} "
                             f"({', '.join(BODIES)}), got {reference!r}", key="reference")
    if not isinstance(car, Car):
        from flexpipe._args import as_path

        car = load_car(as_path(car, "car"))
    out = []
    for s in tqdm(v, desc="ride: speeds", unit="speed", disable=not progress):
        modes = linear_modes(car, body=body, speed=s, f_max=f_max)
        ref_modes = None if reference is None else linear_modes(car, body=ref, speed=s,
                                                                f_max=f_max)
        out.append(ride_response(modes, road_class, coherence=coherence,
                                 reference=ref_modes))
    return out
