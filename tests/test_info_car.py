"""``flexpipe info CAR.toml`` of a linkage car: the corner mass (wheel and every part of
the linkage) is labelled for what it is, and the conventional unsprung estimate (wheel +
knuckle + half of each arm or link between body and knuckle) is printed beside it."""

import re
import tomllib
from pathlib import Path

import pytest

from flexpipe.cli import main

ROOT = Path(__file__).resolve().parents[1]
CAR = ROOT / "cars" / "sedan_linkage.toml"


def _values(line: str) -> dict:
    return {k: float(v) for k, v in re.findall(r"\b(fl|fr|rl|rr) ([0-9.]+)", line)}


def test_linkage_corner_masses_are_labelled_and_estimated(capsys):
    """By hand from the car file: front (double wishbone) 22.0 kg wheel, 2.5 kg knuckle,
    arms 1.611 + 1.032 kg: 27.14 kg whole, 22 + 2.5 + (1.611 + 1.032) / 2 = 25.82 kg
    unsprung; rear (multi-link) knuckle 4.304, upper arm 4.744, trailing link 15.204 kg
    (both between body and knuckle): 46.25 kg whole, 36.28 kg unsprung."""
    doc = tomllib.loads(CAR.read_text())
    assert main(["info", str(CAR)]) == 0
    out = capsys.readouterr().out
    whole = next(line for line in out.splitlines() if "knuckle and arms/links, whole" in line)
    est = next(line for line in out.splitlines() if "unsprung mass estimate" in line)
    assert "unsprung (per corner" not in out
    assert "half of each arm/link between body and knuckle" in est
    for axle, corners in (("front", ("fl", "fr")), ("rear", ("rl", "rr"))):
        parts = {k: v["mass_kg"] for k, v in doc["suspension"][axle]["parts"].items()}
        for c in corners:
            wheel = doc["corners"][c]["wheel_mass_kg"]
            arms = sum(m for k, m in parts.items() if k != "knuckle")
            assert _values(whole)[c] == pytest.approx(wheel + sum(parts.values()), abs=0.006)
            assert _values(est)[c] == pytest.approx(wheel + parts["knuckle"] + arms / 2,
                                                    abs=0.006)
    assert _values(est)["fl"] == pytest.approx(25.82, abs=0.006)
    assert _values(est)["rl"] == pytest.approx(36.28, abs=0.006)


def test_prismatic_car_keeps_its_unsprung_masses(capsys):
    """cars/sedan.toml gives unsprung_mass_kg per corner: printed as such."""
    doc = tomllib.loads((ROOT / "cars" / "sedan.toml").read_text())
    assert main(["info", str(ROOT / "cars" / "sedan.toml")]) == 0
    out = capsys.readouterr().out
    line = next(line for line in out.splitlines() if "unsprung (per corner, kg)" in line)
    for c in ("fl", "fr", "rl", "rr"):
        assert _values(line)[c] == pytest.approx(doc["corners"][c]["unsprung_mass_kg"],
                                                 abs=0.006)
    assert "estimate" not in out


def test_unsprung_estimate_shares():
    """A part joined to the body only (a rocker) is sprung, one hung on the knuckle only
    is unsprung, one between both counts half: wheel 20 + knuckle 3 + 4/2 + 0 + 1."""
    import numpy as np

    from flexpipe.vehicle.describe import unsprung_estimate
    from flexpipe.vehicle.suspension.model import Joint, Part

    class Corner:
        knuckle = "knuckle"
        parts = (Part("knuckle", 3.0, np.zeros(3)), Part("arm", 4.0, np.zeros(3)),
                 Part("rocker", 5.0, np.zeros(3)), Part("hub_bit", 1.0, np.zeros(3)))
        joints = (Joint("a1", "spherical", "arm", "body", np.zeros(3), mount="m1"),
                  Joint("a2", "spherical", "knuckle", "arm", np.zeros(3)),
                  Joint("r1", "spherical", "rocker", "body", np.zeros(3), mount="m2"),
                  Joint("h1", "spherical", "hub_bit", "knuckle", np.zeros(3)))
        links = ()

    total = 20.0 + 3.0 + 4.0 + 5.0 + 1.0
    assert unsprung_estimate(Corner, total) == pytest.approx(20 + 3 + 2 + 0 + 1, rel=1e-14)
