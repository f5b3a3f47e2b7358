"""The powertrain as a rigid body on mounts (``[powertrain]`` of a linkage car).

References: the linear statics of a rigid body on springs (the mount forces that hold
the powertrain's weight, the bushings' deflections under it, and the forces that pass a
given resultant and moment, from the 6x6 stiffness of the mounts solved with NumPy); a
closed form for the mounts' stiffness and the bounce frequency of a symmetric layout;
conservation (the tyres carry the whole car's weight, the powertrain's included).
"""

from pathlib import Path

import numpy as np
import pytest

from flexpipe.driver import OpenLoopTorque
from flexpipe.errors import InputError
from flexpipe.vehicle import bodymodel, load_car, simulate
from flexpipe.vehicle.export import channel_unit
from flexpipe.vehicle.linkage_setup import GRAVITY
from flexpipe.vehicle.mounted import MountedBody
from flexpipe.vehicle.simulation import default_driver
from flexpipe.vehicle.suspension.model import Bushing
from flexpipe.vehicle.suspension.statics import point_masses, with_wheels
from tests._carfiles import absolute_text
from tests._mountstatics import mount_forces

ROOT = Path(__file__).resolve().parents[1]
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"
MASS = 190.0
MOUNTS = {"engine_mount_r": ([0.20, -0.55, 0.55], [1.5e5, 1.5e5, 2.5e5], [150, 150, 250]),
          "gearbox_mount_l": ([0.20, 0.55, 0.55], [1.5e5, 1.5e5, 2.5e5], [150, 150, 250]),
          "roll_restrictor": ([-0.20, 0.0, 0.153], [3.0e5, 1.0e5, 1.0e5], [300, 100, 100])}
SPREAD = '''[[body.mass]]
name = "powertrain"
mass_kg = 190.0
position_m = [0.10, 0.0, 0.55]
spread_radius_m = 0.35

'''


def powertrain_text(*, mounts=MOUNTS, extra="", bushings=None) -> str:
    """``[body.mounts]`` and ``[powertrain]`` tables for the sample's powertrain."""
    out = "".join(f"[body.mounts.{n}]\npoint_m = {p}\nradius_m = 0.05\n\n"
                  for n, (p, _, _) in mounts.items())
    out += (f"[powertrain]\nmass_kg = {MASS}\ncenter_of_mass_m = [0.10, 0.0, 0.55]\n"
            "inertia_kg_m2 = [8.0, 6.0, 9.0]\nmounts = ["
            + ", ".join(f'"{n}"' for n in mounts) + "]\n" + extra + "\n")
    for n, (_, k, c) in (bushings or mounts).items():
        out += (f"[powertrain.bushings.{n}]\nstiffness = {[*k, 0.0, 0.0, 0.0]}\n"
                f"damping = {[*c, 0, 0, 0]}\n\n")
    return out


def car_file(tmp_path, **kw) -> Path:
    """The linkage sample with its powertrain on mounts in place of the spread mass."""
    text = absolute_text(LINKAGE)
    assert SPREAD in text
    text = text.replace(SPREAD, "").replace("\n[drive]\n",
                                            "\n" + powertrain_text(**kw) + "[drive]\n")
    path = tmp_path / "car_powertrain.toml"
    path.write_text(text)
    return path


# ----------------------------------------------------------------------------- reader
def test_car_reads_the_powertrain(tmp_path):
    car = load_car(car_file(tmp_path))
    pt = car.powertrain
    assert pt.mounts == tuple(MOUNTS)
    assert car.mounted_mass == MASS
    np.testing.assert_allclose(pt.points, [p for p, _, _ in MOUNTS.values()])


def test_symmetric_mounts_bounce_at_the_closed_form_frequency():
    # four equal mounts at the corners of a square around the centre of mass: vertical
    # bounce decoupled, f = sqrt(4 k / m) / (2 pi)
    k = np.array([1e5, 1e5, 2e5, 0.0, 0.0, 0.0])
    pts = np.array([[0.3, 0.3, 0.0], [0.3, -0.3, 0.0], [-0.3, 0.3, 0.0], [-0.3, -0.3, 0.0]])
    pt = MountedBody(150.0, np.zeros(3), np.diag([6.0, 5.0, 7.0]), ("a", "b", "c", "d"), pts,
                    tuple(Bushing(k) for _ in range(4)))
    f, V = pt.frequencies()
    bounce = int(np.argmax(np.abs(V[2])))
    assert f[bounce] == pytest.approx(np.sqrt(4 * 2e5 / 150.0) / (2 * np.pi), rel=1e-9)
    # roll about x: 4 k_z y^2 over I_xx
    roll = int(np.argmax(np.abs(V[3])))
    assert f[roll] == pytest.approx(np.sqrt(4 * 2e5 * 0.09 / 6.0) / (2 * np.pi), rel=1e-9)


@pytest.mark.parametrize("kw, match, key", [
    (dict(extra='mounts_extra = 1\n'), "unknown key", "powertrain.mounts_extra"),
    (dict(bushings={n: v for n, v in list(MOUNTS.items())[:2]}), "has no bushing",
     "powertrain.bushings"),
    (dict(mounts={"a": ([0.2, -0.55, 0.55], [1e5, 1e5, 1e5], [0, 0, 0]),
                  "b": ([0.2, 0.55, 0.55], [1e5, 1e5, 1e5], [0, 0, 0])}),
     "free to move", "powertrain.mounts"),
])
def test_bad_powertrain_names_file_and_key(tmp_path, kw, match, key):
    path = car_file(tmp_path, **kw)
    with pytest.raises(InputError, match=match) as err:
        load_car(path)
    assert err.value.key == key
    assert str(path) in str(err.value)


def test_powertrain_and_reaction_mounts_exclude_each_other(tmp_path):
    path = car_file(tmp_path)
    path.write_text(path.read_text().replace(
        "\n[drive]\n", '\n[drive]\nreaction_mounts = ["engine_mount_r", "gearbox_mount_l", '
                       '"roll_restrictor"]\n'))
    with pytest.raises(InputError, match="remove reaction_mounts") as err:
        load_car(path)
    assert err.value.key == "powertrain"


# ----------------------------------------------------------------------------- runs
@pytest.mark.parametrize("body, tol", [("rigid", 1e-3), ("flexible", 5e-3)])
def test_parked_powertrain_hangs_in_its_mounts(tmp_path, body, tol):
    car = load_car(car_file(tmp_path))
    pt = car.powertrain
    r = simulate(car, speed=0.0, t_end=2.0, body=body, output_step=0.01)
    assert r.status == 0, r.message
    sel = r.t > 1.0
    f = np.array([[r[f"mount_{n}_{a}"][sel].mean() for a in "xyz"] for n in pt.mounts])
    W = MASS * GRAVITY
    ref = mount_forces(pt, np.array([0.0, 0.0, -W, 0.0, 0.0, 0.0]))
    # the flexible body's mounts move under the load: the bushings see that too
    assert np.abs(f - ref).max() <= tol * W
    # each bushing's deflection channels (bushing frame): the same statics, the weight's
    # motion (u, theta) = K^-1 (W_body, 0) of the centre of mass at the mount, with the
    # weight in body axes (the body pitches at rest) the resultant of the mount forces
    u = np.linalg.solve(pt.stiffness_matrix(), np.r_[f.sum(axis=0), 0.0, 0.0, 0.0])
    for n, p, b in zip(pt.mounts, pt.points, pt.bushings, strict=True):
        ref_d = np.r_[b.frame.T @ (u[:3] + np.cross(u[3:], p - pt.center_of_mass)),
                      b.frame.T @ u[3:]]
        got = np.array([r[f"bushing_{n}_{a}"][sel].mean()
                        for a in ("dx", "dy", "dz", "rx", "ry", "rz")])
        # the force criterion above in the softest direction: tol W / k_min
        assert np.abs(got[:3] - ref_d[:3]).max() <= tol * W / min(b.stiffness[:3]), n
        # rotations on the rigid body (a flexible body's mount turns with the shell's local
        # slope under the mount's 750 N, 0.29 mrad here, which the bushing sees too);
        # 3e-3: linear statics against Exudyn's finite rotation (the 1.7 mrad pitch)
        if body == "rigid":
            assert np.abs(got[3:] - ref_d[3:]).max() <= 3e-3 * np.abs(ref_d[3:]).max(), n
    assert (channel_unit(f"bushing_{n}_dz"), channel_unit(f"bushing_{n}_ry")) == ("m", "rad")
    # the powertrain's own motion (its centre of mass, body axes) from the bushings: the
    # same statics u; on the flexible body relative to its mounts as a whole
    got = np.array([r[f"powertrain_{a}"][sel].mean() for a in ("x", "y", "z", "rx", "ry",
                                                                 "rz")])
    assert np.abs(got[:3] - u[:3]).max() <= (2e-3 if body == "rigid" else 0.02) * \
        np.abs(u[:3]).max()
    if body == "rigid":
        assert np.abs(got[3:] - u[3:]).max() <= 3e-3 * np.abs(u[3:]).max()
    assert (channel_unit("powertrain_z"), channel_unit("powertrain_ry")) == ("m", "rad")
    # the tyres carry the whole car, the powertrain on its mounts included
    m = bodymodel.rigid_properties(car).mass + MASS + sum(
        mp for mp, _ in point_masses(with_wheels(car.suspension, car.suspension.wheels)))
    Fz = sum(r[f"tire_{c}_Fz"][sel].mean() for c in ("fl", "fr", "rl", "rr"))
    assert Fz == pytest.approx(m * GRAVITY, rel=1e-3)


@pytest.mark.parametrize("body", ["rigid", "flexible"])
def test_drive_couple_reaches_the_body_through_the_mounts(tmp_path, body):
    torque = 400.0  # N m, small enough that the powertrain's turn on its mounts (0.5 deg)
    car = load_car(car_file(tmp_path))  # keeps the mounts' statics linear
    pt = car.powertrain
    steer, _ = default_driver(car, bodymodel.rigid_properties(car).mass)
    r = simulate(car, speed=15.0, t_end=5.0, body=body, output_step=0.01,
                 driver=(steer, OpenLoopTorque.from_table([0.0], [torque])))
    assert r.status == 0, r.message
    sel = r.t > 3.0
    f = np.array([[r[f"mount_{n}_{a}"][sel].mean() for a in "xyz"] for n in pt.mounts])
    arm = pt.points - pt.center_of_mass
    F, M = f.sum(axis=0), np.cross(arm, f).sum(axis=0)
    # the couple passes whole (the inertia and weight act at the centre of mass)
    assert M[1] == pytest.approx(-torque, rel=0.01)
    # the mounts share the loads as the linear statics of the powertrain on them say
    ref = mount_forces(pt, np.concatenate([F, M]))
    assert np.abs(f - ref).max() <= 0.015 * np.abs(f).max()


def test_sweep_overrides_reach_the_bushings(tmp_path):
    # a sweep's car overrides set the bushings (car.powertrain.bushings.<mount>.<key>):
    # four times every rate, twice every body-held frequency (f ~ sqrt(k / m))
    path = car_file(tmp_path)
    base = load_car(path)
    stiff = load_car(path, overrides={f"powertrain.bushings.{n}.stiffness": [4 * v for v in
                                                                            (*k, 0, 0, 0)]
                                      for n, (_, k, _) in MOUNTS.items()})
    np.testing.assert_allclose(stiff.powertrain.frequencies()[0],
                               2 * base.powertrain.frequencies()[0], rtol=1e-9)
