"""Ride comfort and road holding of a scenario's runs, for its ``summary.json``.

Per body model and named body point (channels ``acc_<p>_x|y|z``, body axes): the ISO
2631-1 weighted RMS ``a_w`` (Wd fore-aft and lateral, Wk vertical), the vertical VDV, the
comfort total value ``a_v = sqrt(a_wx^2 + a_wy^2 + a_wz^2)`` (multiplying factors 1,
ISO 2631-1 8.2.3) and its reaction (Annex C); per tyre the dynamic load coefficient, the
standard deviation of the vertical tyre force over its mean.  From the same samples as
the hub-force comparison (after its start time), so rigid and flexible compare alike,
and with the linear model's prediction (:func:`flexpipe.ride_response`).  A seat
(:mod:`flexpipe.vehicle.seats`) is a point too, with its SEAT value: its vertical ``a_w``
over its floor point's, in %.
"""

from __future__ import annotations

import math

import numpy as np

CORNERS = ("fl", "fr", "rl", "rr")


def ride_summary(results: dict, *, t_from: float) -> dict:
    """``{"ride_comfort": {body: {point: {...}}}, "dynamic_load_coefficient": {body:
    {corner: value}}}`` of the runs ``results`` (body -> Result), samples from
    ``t_from`` on; runs that stopped early are left out."""
    from flexpipe.sweeps.iso2631 import comfort_reaction
    from flexpipe.sweeps.metrics import run_metrics
    from flexpipe.vehicle.seats import seat_value

    comfort, load = {}, {}
    for body, r in results.items():
        if r.status != 0:
            continue
        m = run_metrics(r.t, r.channels, settle=t_from)
        points = {}
        for key in m:
            if key.startswith("av_"):
                p = key[3:-len("_m_per_s2")]
                aw = {k: m[f"aw_{p}_{k}_m_per_s2"] for k in "xyz"}
                a_v = math.sqrt(sum(v**2 for v in aw.values()))
                points[p] = {**{f"aw_{k}_m/s^2": round(v, 4) for k, v in aw.items()},
                             "vdv_z_m/s^1.75": round(m[f"vdv_{p}_z_m_per_s1.75"], 4),
                             "a_v_m/s^2": round(a_v, 4), "reaction": comfort_reaction(a_v)}
        seats = (getattr(r, "info", None) or {}).get("seats") or {}
        for seat, floor in seats.items():  # flexpipe.vehicle.seats
            if seat in points and floor in points:
                v = seat_value(points[seat]["aw_z_m/s^2"], points[floor]["aw_z_m/s^2"])
                points[seat]["SEAT_%"] = round(v, 2) if math.isfinite(v) else None  # JSON
                points[seat]["floor_point"] = floor
        comfort[body] = points
        keep = r.t >= t_from - 1e-12
        load[body] = {c: round(float(np.std(r[f"tire_{c}_Fz"][keep])
                                     / np.mean(r[f"tire_{c}_Fz"][keep])), 5)
                      for c in CORNERS if f"tire_{c}_Fz" in r.channels}
    return {"ride_comfort": comfort, "dynamic_load_coefficient": load}
