"""Named-point accelerations and the body's motion recorded by Exudyn sensors.

A car run records, at every output row, the global acceleration of each named body point
(``acc_<point>_<axis>``) and, for durability, the body's motion (elastic modal
coordinates, frame position and rotation; ``Result.motion``).  Read from Python in the
step, that is one Exudyn call per point plus three for the motion and a list of every
modal coordinate turned into an array, every output row; on a flexible body the point
call evaluates the super element's acceleration at a mesh node.  Stored by Exudyn's own
sensors after every output step instead, the same values cost no Python at all and are
turned into the channels after the run (:func:`history`).  The first row (t = 0) has no
sensor sample (sensors store after a step) and keeps the Python reads.
``tests/test_linkage_car.py`` checks the sensor channels against the Python reads.
"""

from __future__ import annotations

import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np

OV = exu.OutputVariableType


def add(system) -> None:
    """Sensors (stored in memory) for the named points' accelerations and the body's
    motion of the car ``system`` (a :class:`flexpipe.exu.car.CarSystem` whose
    ``points``, ``body_obj``, ``body_node`` and ``modal_node`` are set).  Call before the
    system is assembled."""
    mbs = system.mbs
    kw = dict(storeInternal=True, writeToFile=False)
    points = {}
    for name, (kind, where) in system.points.items():
        if kind == "node":
            item = eii.SensorSuperElement(bodyNumber=system.body_obj, meshNodeNumber=where,
                                          outputVariableType=OV.Acceleration, **kw)
        else:
            item = eii.SensorBody(bodyNumber=system.body_obj, localPosition=where,
                                  outputVariableType=OV.Acceleration, **kw)
        points[name] = mbs.AddSensor(item)
    node = system.body_node
    modal = None if system.modal_node is None else mbs.AddSensor(eii.SensorNode(
        nodeNumber=system.modal_node, outputVariableType=OV.Coordinates, **kw))
    # a linkage car's mount sensors already record the body node's rotation: shared
    rotation = getattr(getattr(system, "linkage", None), "_body_sensor", None)
    if rotation is None:
        rotation = mbs.AddSensor(eii.SensorNode(
            nodeNumber=node, outputVariableType=OV.RotationMatrix, **kw))
    system._output_sensors = (points, modal, mbs.AddSensor(eii.SensorNode(
        nodeNumber=node, outputVariableType=OV.Position, **kw)), rotation)


def stored_reader(mbs, clock, t):
    """``(data, ok)`` for the output times ``t`` (n,) from sensors stored in memory:
    ``data(sensor)`` gives a sensor's values (n, width) at the samples nearest ``t``
    (the sample times read from the sensor ``clock``); ``ok`` (n,) is True where a
    sample lies within 1e-9 s of ``t``.  None when nothing was recorded."""
    get = mbs.GetSensorStoredData
    raw = np.atleast_2d(np.asarray(get(clock), dtype=float))
    if not raw.size:
        return None
    ts = raw[:, 0]
    t = np.asarray(t, dtype=float)
    j = np.clip(np.searchsorted(ts, t - 1e-9), 0, len(ts) - 1)
    ok = np.abs(ts[j] - t) < 1e-9

    def data(sensor):
        return np.asarray(get(sensor), dtype=float).reshape(len(ts), -1)[j, 1:]

    return data, ok


def history(system, t: np.ndarray) -> dict:
    """The recorded values at the times ``t`` (n,): ``{"points": {name: (n, 3) global
    acceleration}, "q": (n, modes), "p": (n, 3), "R": (n, 3, 3)}``, rows NaN where no
    sample lies within 1e-9 s of ``t``; None when nothing was recorded."""
    points, modal, s_p, s_R = system._output_sensors
    got = stored_reader(system.mbs, s_R, t)
    if got is None:
        return None
    read, ok = got

    def data(sensor):
        out = np.array(read(sensor), dtype=float)
        out[~ok] = np.nan
        return out

    q = data(modal) if modal is not None else np.zeros((len(ok), 0))
    return {"points": {name: data(s) for name, s in points.items()}, "q": q,
            "p": data(s_p), "R": data(s_R).reshape(-1, 3, 3)}


__all__ = ["add", "history", "stored_reader"]
