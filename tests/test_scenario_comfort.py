"""The ride summary of a scenario (flexpipe.scenarios.comfort) against closed forms: a sine
acceleration's ISO 2631-1 weighted RMS is its amplitude / sqrt(2) times the weighting's
gain at its frequency, the comfort value the root sum of squares of the axes; a sine tyre
load's dynamic load coefficient is its amplitude / sqrt(2) over its mean."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest

from flexpipe.scenarios.comfort import ride_summary
from flexpipe.sweeps.iso2631 import comfort_reaction, response


class _Result(SimpleNamespace):
    """What the summary reads of a Result: t, channels, status, result[name]."""

    def __getitem__(self, name):
        return self.channels[name]


def _run(status=0):
    t = np.arange(0.0, 60.0, 1e-3)
    ch = {"acc_seat_x": 0.3 * np.sin(2 * np.pi * 1.0 * t),
          "acc_seat_y": 0.2 * np.sin(2 * np.pi * 2.0 * t),
          "acc_seat_z": 1.2 * np.sin(2 * np.pi * 5.0 * t),
          "tire_fl_Fz": 4000.0 + 600.0 * np.sin(2 * np.pi * 12.0 * t),
          "tire_rr_Fz": 3500.0 + 0.0 * t}
    return _Result(t=t, channels=ch, status=status)


def test_ride_summary_equals_closed_forms():
    out = ride_summary({"rigid": _run(), "flexible": _run(status=-1)}, t_from=2.0)
    assert set(out["ride_comfort"]) == {"rigid"}  # a run that stopped early is left out
    seat = out["ride_comfort"]["rigid"]["seat"]
    aw = {k: a / math.sqrt(2) * abs(response(f, w))
          for k, a, f, w in (("x", 0.3, 1.0, "Wd"), ("y", 0.2, 2.0, "Wd"),
                             ("z", 1.2, 5.0, "Wk"))}
    for k in "xyz":
        # the weighting's start-up at the record's start: under 0.5 % of 58 s
        assert seat[f"aw_{k}_m/s^2"] == pytest.approx(aw[k], rel=5e-3)
    a_v = math.sqrt(sum(v**2 for v in aw.values()))
    assert seat["a_v_m/s^2"] == pytest.approx(a_v, rel=5e-3)
    assert seat["reaction"] == comfort_reaction(seat["a_v_m/s^2"])
    # VDV of a sine: (3/8 a^4 T)^(1/4), T = 58 s
    assert seat["vdv_z_m/s^1.75"] == pytest.approx((3 / 8 * aw["z"] ** 4 * 4 * 58.0)
                                                   ** 0.25, rel=5e-3)
    load = out["dynamic_load_coefficient"]["rigid"]
    assert load["fl"] == pytest.approx(600.0 / math.sqrt(2) / 4000.0, rel=1e-4)
    assert load["rr"] == 0.0 and set(load) == {"fl", "rr"}


def test_spectra_plot_marks_where_the_runs_differ(tmp_path, monkeypatch):
    """spectra.png of a scenario: the difference's PSD peaks where the runs differ (a
    5 % extra 22 Hz line in the flexible run's hub force), read back from the figure's
    data; written as a PNG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flexpipe.vehicle import plots

    t = np.arange(0.0, 12.0, 1e-3)
    base = 3500.0 + 400.0 * np.sin(2 * np.pi * 1.5 * t) + 80.0 * np.sin(2 * np.pi * 22.0 * t)
    acc = np.sin(2 * np.pi * 1.5 * t)
    runs = {"rigid": _Result(t=t, status=0, channels={"hub_fl_z": base, "acc_seat_x": acc,
                                                      "acc_seat_y": acc, "acc_seat_z": acc}),
            "flexible": _Result(t=t, status=0, channels={
                "hub_fl_z": base + 4.0 * np.sin(2 * np.pi * 22.0 * t), "acc_seat_x": acc,
                "acc_seat_y": acc, "acc_seat_z": 1.1 * acc})}
    captured = {}
    save = plots._save

    def keep(plt_, fig, path):
        captured["lines"] = [(ln.get_label(), ln.get_xdata(), ln.get_ydata())
                             for ln in fig.axes[0].get_lines()]
        return save(plt_, fig, path)

    monkeypatch.setattr(plots, "_save", keep)
    path = plots.spectra(runs, tmp_path / "spectra.png", t_from=0.5)
    plt.close("all")
    assert path.read_bytes()[:4] == b"\x89PNG"
    (f, p), = [(x, y) for label, x, y in captured["lines"] if label == "rigid - flexible"]
    assert f[np.argmax(p)] == pytest.approx(22.0, abs=0.5)


def test_spectra_plot_shows_the_seat_under_its_floor(tmp_path, monkeypatch):
    """With a seat, spectra.png gets a third panel: the seat's vertical PSD, which over
    its floor point's is the seat's |T|^2 in closed form (broadband floor motion)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from flexpipe.vehicle import plots
    from flexpipe.vehicle.seats import Seat

    t = np.arange(0.0, 60.0, 1e-3)
    floor = np.random.default_rng(3).standard_normal(t.size)
    seat = Seat("driver_seat", "floor", 4.0, 0.3).acceleration(t, floor)
    ch = {"hub_fl_z": 3500.0 + floor, **{f"acc_floor_{k}": floor for k in "xyz"},
          "acc_driver_seat_x": floor, "acc_driver_seat_y": floor, "acc_driver_seat_z": seat}
    info = {"seats": {"driver_seat": "floor"}}
    runs = {"rigid": _Result(t=t, status=0, channels=ch, info=info),
            "flexible": _Result(t=t, status=0, channels=ch, info=info)}
    captured = {}
    save = plots._save

    def keep(plt_, fig, path):
        captured["axes"] = [(ax.get_ylabel(), {ln.get_label(): (ln.get_xdata(), ln.get_ydata())
                                               for ln in ax.get_lines()}) for ax in fig.axes]
        return save(plt_, fig, path)

    monkeypatch.setattr(plots, "_save", keep)
    plots.spectra(runs, tmp_path / "spectra.png", t_from=0.5)
    plt.close("all")
    (_, floor_lines), (label, seat_lines) = captured["axes"][1], captured["axes"][2]
    assert "driver_seat (seat on floor)" in label
    f, p_floor = floor_lines["rigid body"]
    _, p_seat = seat_lines["rigid body"]
    r = f / 4.0
    T2 = (1 + (0.6 * r) ** 2) / ((1 - r * r) ** 2 + (0.6 * r) ** 2)
    band = (f >= 1.0) & (f <= 20.0)
    # the plot's 0.5 Hz Welch bins smear |T|^2 where it turns fast, at 3.5-6 Hz by up
    # to 6.5 % on this record, within 3 % elsewhere
    np.testing.assert_allclose(p_seat[band] / p_floor[band], T2[band], rtol=0.1)
