"""Subframes on bushings (``[subframe.<name>]`` of a linkage car).

References: the linear statics of a rigid body on springs (the subframe's mount forces
under its weight and the forces of the suspension mounts it carries, from the 6x6
stiffness of its bushings solved with NumPy); consistency (a light subframe on very stiff
bushings reproduces the car whose mounts sit on the body); conservation (the tyres carry
the whole car's weight, the subframe's included).
"""

from pathlib import Path

import numpy as np
import pytest

from flexpipe.errors import InputError
from flexpipe.scenarios.runner import _straight_road
from flexpipe.vehicle import load_car, simulate
from flexpipe.vehicle.linkage_setup import GRAVITY
from tests._carfiles import absolute_text
from tests._mountstatics import mount_forces

ROOT = Path(__file__).resolve().parents[1]
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"
CARRIED = ["front_lower_arm_front_l", "front_lower_arm_rear_l", "front_lower_arm_front_r",
           "front_lower_arm_rear_r", "front_rack_mount_l", "front_rack_mount_r",
           "front_arb_bushing_l", "front_arb_bushing_r"]
MOUNTS = {"cradle_front_l": [0.35, 0.442, 0.19], "cradle_front_r": [0.35, -0.442, 0.19],
          "cradle_rear_l": [-0.5, 0.45, 0.25], "cradle_rear_r": [-0.5, -0.45, 0.25]}
SOFT = dict(mass=20.0, k=[2e6, 2e6, 2e6, 2e3, 2e3, 2e3], c=[2e3, 2e3, 2e3, 2.0, 2.0, 2.0])
STIFF = dict(mass=2.0, k=[5e7, 5e7, 5e7, 5e5, 5e5, 5e5], c=[5e3, 5e3, 5e3, 5.0, 5.0, 5.0])


def subframe_text(*, mass, k, c, carried=CARRIED, mounts=MOUNTS, extra="") -> str:
    """``[body.mounts]`` and ``[subframe.front]`` tables of a front cradle on bushings."""
    q = lambda v: str(list(v)).replace("'", '"')  # noqa: E731 - TOML lists of strings
    out = "".join(f"[body.mounts.{n}]\npoint_m = {p}\nradius_m = 0.06\n\n"
                  for n, p in mounts.items())
    out += (f"[subframe.front]\nmass_kg = {mass}\ncenter_of_mass_m = [-0.05, 0.0, 0.2]\n"
            f"inertia_kg_m2 = [1.5, 0.8, 2.2]\nmounts = {q(mounts)}\ncarries = {q(carried)}\n"
            + extra + "\n")
    for n in mounts:
        out += f"[subframe.front.bushings.{n}]\nstiffness = {list(k)}\ndamping = {list(c)}\n\n"
    return out


def car_file(tmp_path, name="car_subframe.toml", **kw) -> Path:
    text = absolute_text(LINKAGE)
    text = text.replace("\n[drive]\n", "\n" + subframe_text(**{**SOFT, **kw}) + "[drive]\n")
    path = tmp_path / name
    path.write_text(text)
    return path


def test_car_reads_the_subframe(tmp_path):
    car = load_car(car_file(tmp_path))
    (sf,) = car.subframes
    assert sf.name == "subframe.front" and sf.carries == tuple(CARRIED)
    assert car.carrier_of("front_rack_mount_l") is sf and car.carrier_of("rear_spring_upper_l") \
        is None
    assert car.mounted_mass == SOFT["mass"]


@pytest.mark.parametrize("kw, match, key", [
    (dict(carried=[*CARRIED, "rear_lower_arm_x"]), "no mount of this car's suspension",
     "subframe.front.carries"),
    (dict(carried=[*CARRIED, CARRIED[0]]), "more than once", "subframe.front.carries"),
    (dict(mounts={"cradle_front_l": [0.35, 0.442, 0.19],
                  "rear_spring_upper_l": [-2.569, 0.491, 0.4113]}), "is a suspension mount",
     "subframe.front.mounts"),
    (dict(extra="spare = 1\n"), "unknown key", "subframe.front.spare"),
])
def test_bad_subframe_names_file_and_key(tmp_path, kw, match, key):
    path = car_file(tmp_path, **kw)
    with pytest.raises(InputError, match=match) as err:
        load_car(path)
    assert err.value.key == key
    assert str(path) in str(err.value)


def test_carried_mount_cannot_be_tied_to_the_body(tmp_path):
    path = car_file(tmp_path)
    path.write_text(path.read_text().replace(
        "\n[drive]\n", "\n[body.mounts.front_rack_mount_l]\nradius_m = 0.02\n\n[drive]\n"))
    with pytest.raises(InputError, match="on the subframe, not on the body") as err:
        load_car(path)
    assert err.value.key == "subframe.front.carries"


@pytest.mark.parametrize("body", ["rigid", "flexible"])
def test_parked_subframe_holds_what_it_carries(tmp_path, body):
    car = load_car(car_file(tmp_path))
    (sf,) = car.subframes
    r = simulate(car, speed=0.0, t_end=2.0, body=body, output_step=0.01)
    assert r.status == 0, r.message
    sel = r.t > 1.0

    def mean(names):
        return np.array([[r[f"mount_{n}_{a}"][sel].mean() for a in "xyz"] for n in names])

    f, carried = mean(sf.mounts), mean(sf.carries)  # on the body / on the subframe
    points = car.suspension.mounts()
    F = carried.sum(axis=0) + np.array([0.0, 0.0, -sf.mass * GRAVITY])
    M = np.cross(np.array([points[n] for n in sf.carries]) - sf.center_of_mass,
                 carried).sum(axis=0)
    # the subframe passes its load to the body whole (Newton, at rest)
    np.testing.assert_allclose(f.sum(axis=0), F, atol=1e-3 * np.abs(F).max())
    if body == "rigid":  # the bushings share it as the linear statics say
        ref = mount_forces(sf, np.concatenate([F, M]))
        assert np.abs(f - ref).max() <= 1e-3 * np.abs(f).max()
    # the tyres carry the whole car, the subframe included
    from flexpipe.vehicle import bodymodel
    from flexpipe.vehicle.suspension.statics import point_masses, with_wheels

    m = bodymodel.rigid_properties(car).mass + sf.mass + sum(
        mp for mp, _ in point_masses(with_wheels(car.suspension, car.suspension.wheels)))
    Fz = sum(r[f"tire_{c}_Fz"][sel].mean() for c in ("fl", "fr", "rl", "rr"))
    assert Fz == pytest.approx(m * GRAVITY, rel=1e-3)


def test_stiff_light_subframe_is_the_car_with_mounts_on_the_body(tmp_path):
    road = _straight_road()
    runs = [simulate(load_car(p), road=road, speed=70 / 3.6, t_end=3.0, body="rigid")
            for p in (LINKAGE, car_file(tmp_path, **STIFF))]
    a, b = runs
    assert a.status == 0 and b.status == 0
    sel = a.t > 0.5
    for c in ("fl", "fr", "rl", "rr"):
        for ax in "xyz":
            k = f"hub_{c}_{ax}"
            fluct = np.std(a[k][sel])
            assert np.sqrt(np.mean((a[k][sel] - b[k][sel]) ** 2)) <= 0.03 * fluct, k
