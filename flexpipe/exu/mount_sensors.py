"""Per-mount and hub forces of a linkage car recorded by Exudyn sensors.

Everything :meth:`flexpipe.exu.linkage.LinkageModel.mount_forces` reads per step (the
force of every joint, link, bushing and force element at a body mount, the marker frames
it is given in, and the body frame) and everything
:meth:`~flexpipe.exu.linkage.LinkageModel.hub_forces` reads (the corner parts'
centre-of-mass accelerations, the forces and ends of the links to the rack and the
anti-roll bars) is stored by Exudyn after every output step; the histories are turned
into forces after the run (:func:`history`, :func:`hub_history`)"""

from __future__ import annotations

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

from flexpipe.exu.output_sensors import stored_reader

OV = exu.OutputVariableType


def add(model, body_node) -> None:
    """Sensors (stored in memory) for everything the per-mount forces need, plus the body
    node's rotation, on the linkage ``model``: Exudyn records them after every output step
    (reading them from Python every step cost about 1 ms per step under cProfile for the
    30 mounts of ``cars/sedan_linkage.toml``).  Call before the system is assembled; read
    with :func:`history`."""
    mbs = model.mbs

    def sensor(item):
        return mbs.AddSensor(item(storeInternal=True, writeToFile=False))

    def obj(co, ov):
        return sensor(lambda **k: eii.SensorObject(objectNumber=co, outputVariableType=ov,
                                                   **k))

    def mark(m, ov):
        return sensor(lambda **k: eii.SensorMarker(markerNumber=m, outputVariableType=ov,
                                                   **k))

    model._sensors = []
    for _mount, co, kind, (m0, m1), _A in model.body_links:
        if kind == "distance":
            s = (obj(co, OV.Force), mark(m0, OV.Position), mark(m1, OV.Position))
        elif kind.startswith("vector"):
            s = (obj(co, OV.Force),)
        else:
            s = (obj(co, OV.ForceLocal), mark(m0, OV.RotationMatrix))
        model._sensors.append(s)
    model._body_sensor = sensor(lambda **k: eii.SensorNode(
        nodeNumber=body_node, outputVariableType=OV.RotationMatrix, **k))
    # the corners' hub forces (LinkageModel.hub_forces): each part's centre-of-mass
    # acceleration and the links from a corner to the rack or an anti-roll-bar arm
    def acc(o, cm):
        return sensor(lambda **k: eii.SensorBody(bodyNumber=o, localPosition=cm,
                                                 outputVariableType=OV.Acceleration, **k))

    model._bushing_sensors = [(m, obj(co, OV.DisplacementLocal), obj(co, OV.Rotation))
                              for m, co in model.bushings]
    model._hub_sensors = (
        [[(acc(o, cm), m) for o, m, cm in parts] for parts in model.part_nodes],
        [(i, obj(co, OV.Force), mark(ma, OV.Position), mark(mb, OV.Position))
         for i, co, mb, ma in model.to_other])


def _reader(model, t):
    """``(data, ok)`` for the times ``t``: ``data(sensor, width)`` reads a sensor's
    values (n, width) at the samples nearest ``t`` (all NaN when nothing was recorded);
    ``ok`` where a sample lies within 1e-9 s of ``t``
    (:func:`flexpipe.exu.output_sensors.stored_reader`, clocked by the body sensor)."""
    got = stored_reader(model.mbs, model._body_sensor, t)
    if got is None:
        n = len(np.atleast_1d(t))
        return (lambda sid, width: np.full((n, width), np.nan)), np.zeros(n, dtype=bool)
    read, ok = got
    return (lambda sid, width: read(sid)[:, :width]), ok


def hub_history(model, t: np.ndarray, F_tire: np.ndarray):
    """The corners' hub forces (n, 4, 3, global, N) at the times ``t`` from the sensors of
    :func:`add` and the tyre forces ``F_tire`` (n, 4, 3) applied at those times, as
    :meth:`flexpipe.exu.linkage.LinkageModel.hub_forces` computes them from Python
    reads; rows NaN where no sensor sample lies within 1e-9 s of ``t``."""
    data, ok = _reader(model, t)
    parts, links = model._hub_sensors
    out = np.array(F_tire, dtype=float)
    g = np.asarray(model.g, dtype=float)
    for i, corner in enumerate(parts):
        for sid, m in corner:
            out[:, i] += m * (g - data(sid, 3))
    for i, sF, sa, sb in links:
        d = data(sa, 3) - data(sb, 3)
        out[:, i] -= data(sF, 1) * d / np.linalg.norm(d, axis=1, keepdims=True)
    out[~ok] = np.nan
    return out


def history(model, t: np.ndarray):
    """Per-mount forces (body axes, N) at the times ``t`` from the sensors of
    :func:`add`: ``{mount: (n, 3)}``, rows NaN where no sensor sample
    lies within 1e-9 s of ``t`` (None without sensors)."""
    if not getattr(model, "_sensors", None):
        return None
    data, ok = _reader(model, t)
    Rb = data(model._body_sensor, 9).reshape(-1, 3, 3)
    out = {}
    for (mount, _co, kind, _m, A), sens in zip(model.body_links, model._sensors, strict=True):
        if kind == "distance":
            d = data(sens[2], 3) - data(sens[1], 3)
            F = data(sens[0], 1) * d / np.linalg.norm(d, axis=1, keepdims=True)
        elif kind.startswith("vector"):
            F = data(sens[0], 3)
        else:
            R0 = data(sens[1], 9).reshape(-1, 3, 3)
            F = np.einsum("nij,jk,nk->ni", R0, A, data(sens[0], 3))
        if kind.endswith("-"):
            F = -F
        out[mount] = out.get(mount, 0.0) + F
    for mount in out:
        F = np.einsum("nji,nj->ni", Rb, out[mount])  # global -> body axes
        F[~ok] = np.nan
        out[mount] = F
    return out


def bushing_history(model, t: np.ndarray):
    """Per body-mount bushing deflections (displacement m, rotation rad, bushing frame) at
    the times ``t`` from the sensors of :func:`add`: ``{mount: (n, 6)}``, rows NaN where
    no sensor sample lies within 1e-9 s of ``t``."""
    data, ok = _reader(model, t)
    out = {}
    for mount, sd, sr in model._bushing_sensors:
        d = np.c_[data(sd, 3), data(sr, 3)]
        d[~ok] = np.nan
        out[mount] = d
    return out
