"""The drive torque's reaction through powertrain mounts (``[drive] reaction_mounts``).

References: statics (the mount forces have zero resultant and the couple's moment; the
least-norm solution of those six equations by SciPy's/NumPy's least squares, another
method than the closed form of :class:`CoupleSplit`); the reduced body's own statics (in
steady acceleration the mount forces deflect the flexible body by ``K^-1 Psi^T f`` more
than the same couple on its reference frame, which no elastic mode sees); conservation
(a load system with zero resultant moves neither the car's speed nor its axle loads).
"""

from pathlib import Path

import numpy as np
import pytest

from flexpipe.driver import OpenLoopTorque
from flexpipe.errors import InputError
from flexpipe.vehicle import bodymodel, load_car, simulate
from flexpipe.vehicle.reaction_mounts import CoupleSplit
from flexpipe.vehicle.simulation import default_driver
from tests._carfiles import absolute_text

ROOT = Path(__file__).resolve().parents[1]
LINKAGE = ROOT / "cars" / "sedan_linkage.toml"
SEDAN = ROOT / "cars" / "sedan.toml"
NAMES = ("engine_mount_r", "gearbox_mount_l", "roll_restrictor")
POINTS = ((0.20, -0.55, 0.55), (0.20, 0.55, 0.55), (-0.20, 0.0, 0.153))


def _car_file(tmp_path, *, mounts=NAMES, points=POINTS, drive_extra="", src=LINKAGE,
              reaction=None):
    """The sample car with powertrain mounts ``[body.mounts.<name>]`` at ``points`` and
    ``[drive] reaction_mounts = mounts`` (None: key left out)."""
    text = absolute_text(src)
    tables = "".join(f"[body.mounts.{n}]\npoint_m = {list(p)}\nradius_m = 0.05\n\n"
                     for n, p in zip(NAMES, points, strict=False)
                     if mounts is None or n in mounts)
    keys = drive_extra
    if reaction is not None:
        keys += f"reaction_mounts = {reaction!r}\n".replace("'", '"')
    elif mounts is not None:
        keys += "reaction_mounts = [" + ", ".join(f'"{n}"' for n in mounts) + "]\n"
    text = text.replace("\n[drive]\n", "\n" + tables + "[drive]\n" + keys)
    path = tmp_path / "car_powertrain.toml"
    path.write_text(text)
    return path


# ----------------------------------------------------------------------------- statics
def test_forces_are_the_least_norm_statically_equivalent_set():
    rng = np.random.default_rng(7)
    for n in (3, 4, 6):
        for _ in range(5):
            p = rng.normal(size=(n, 3))
            tau = rng.normal(size=3) * 1e3
            f = CoupleSplit(tuple(f"m{i}" for i in range(n)), p).forces(tau)
            r = p - p.mean(axis=0)
            assert np.abs(f.sum(axis=0)).max() < 1e-9 * np.abs(tau).max()
            np.testing.assert_allclose(np.cross(r, f).sum(axis=0), tau, atol=1e-9 * 1e3)
            # the six equilibrium equations, solved for the least-norm forces
            A = np.zeros((6, 3 * n))
            for j in range(n):
                A[:3, 3 * j:3 * j + 3] = np.eye(3)
                x, y, z = r[j]
                A[3:, 3 * j:3 * j + 3] = [[0, -z, y], [z, 0, -x], [-y, x, 0]]
            ref = np.linalg.lstsq(A, np.concatenate([np.zeros(3), tau]), rcond=None)[0]
            np.testing.assert_allclose(f.ravel(), ref, atol=1e-8 * np.abs(ref).max())


def test_rotated_body_gives_the_rotated_forces():
    split = CoupleSplit(NAMES, np.array(POINTS))
    c, s = np.cos(0.3), np.sin(0.3)
    R = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]]) @ np.array(
        [[1.0, 0.0, 0.0], [0.0, np.cos(0.1), -np.sin(0.1)], [0.0, np.sin(0.1), np.cos(0.1)]])
    tau = np.array([100.0, -1500.0, 40.0])
    F = split.rotated(R, tau)
    r_global = split.arms @ R.T
    np.testing.assert_allclose(np.cross(r_global, F).sum(axis=0), tau, atol=1e-9)
    np.testing.assert_allclose(F.sum(axis=0), 0.0, atol=1e-9)


@pytest.mark.parametrize("points", [((0, 0, 0), (1, 0, 0), (2, 0, 0)),
                                    ((0, 0, 0.5), (0, 1, 0.5))])
def test_mounts_on_one_line_are_refused(points):
    with pytest.raises(InputError, match="not on one line"):
        CoupleSplit(tuple(f"m{i}" for i in range(len(points))), np.array(points, float))


# ----------------------------------------------------------------------------- car file
def test_car_file_reads_the_mounts(tmp_path):
    car = load_car(_car_file(tmp_path))
    assert car.drive.reaction_mounts == NAMES
    np.testing.assert_allclose(car.drive.reaction_points, POINTS)


@pytest.mark.parametrize("kw, match", [
    (dict(drive_extra='drive_reaction = "knuckle"\n'), "in-wheel motors"),
    (dict(mounts=NAMES[:2]), "at least three"),
    (dict(mounts=(*NAMES, "engine_mount_r")), "more than once"),
    (dict(mounts=(*NAMES, "oil_pan")), r"no \[body.mounts.oil_pan\] table"),
    (dict(mounts=(*NAMES, "front_spring_upper_l")), "is a suspension mount"),
    (dict(reaction="engine_mount_r"), "expected a list of mount names"),
    (dict(points=((0.2, -0.55, 0.55), (0.2, 0.55, 0.55), (0.2, 0.0, 0.55))),
     "not on one line"),
])
def test_bad_reaction_mounts_name_file_and_key(tmp_path, kw, match):
    path = _car_file(tmp_path, **kw)
    with pytest.raises(InputError, match=match) as err:
        load_car(path)
    assert err.value.key == "drive.reaction_mounts"
    assert str(path) in str(err.value)


def test_powertrain_tables_without_reaction_mounts_are_refused(tmp_path):
    with pytest.raises(InputError, match="nor a mount of \\[powertrain\\]") as err:
        load_car(_car_file(tmp_path, mounts=None))
    assert err.value.key == f"body.mounts.{NAMES[0]}"


def test_prismatic_car_has_no_powertrain_mounts(tmp_path):
    text = absolute_text(SEDAN).replace(
        "\n[drive]\n", '\n[drive]\nreaction_mounts = ["a", "b", "c"]\n')
    path = tmp_path / "sedan.toml"
    path.write_text(text)
    with pytest.raises(InputError, match="linkage suspension") as err:
        load_car(path)
    assert err.value.key == "drive.reaction_mounts"


# ----------------------------------------------------------------------------- runs
TORQUE = 1500.0  # N m at the front wheels, held


def _run(car, monkeypatch=None):
    steer, _ = default_driver(car, bodymodel.rigid_properties(car).mass)
    speed = OpenLoopTorque.from_table([0.0], [TORQUE])
    r = simulate(car, speed=15.0, t_end=2.0, body="flexible", driver=(steer, speed),
                 output_step=0.01)
    assert r.status == 0, r.message
    return r


def test_flexible_body_takes_the_couple_at_its_mounts(tmp_path, monkeypatch):
    from flexpipe.exu.linkage_car import LinkageCarSystem
    from flexpipe.vehicle.linkage_setup import reduce_car_body

    car = load_car(_car_file(tmp_path))
    mounts = _run(car)
    # the same body with the couple on its reference frame (no elastic mode sees it)
    monkeypatch.setattr(LinkageCarSystem, "_add_reaction_mounts", lambda *a: None)
    frame = _run(car)
    sel = mounts.t > 1.2  # steady acceleration
    # conservation: the car's motion and axle loads are the couple's, not the mounts'
    assert mounts["speed"][sel].mean() == pytest.approx(frame["speed"][sel].mean(), rel=1e-4)
    for c in ("fl", "rl"):
        assert mounts[f"tire_{c}_Fz"][sel].mean() == pytest.approx(
            frame[f"tire_{c}_Fz"][sel].mean(), rel=1e-3)
    # the recorded mount forces: zero resultant, the couple's moment (body axes: the
    # spin axes are +y up to camber and toe)
    split = CoupleSplit(NAMES, np.array(POINTS))
    f = np.stack([np.column_stack([mounts[f"mount_{n}_{a}"] for a in "xyz"])
                  for n in NAMES], axis=1)[sel]  # (t, mount, 3)
    assert np.abs(f.sum(axis=1)).max() < 1e-6 * TORQUE
    moment = np.cross(split.arms[None], f).sum(axis=1).mean(axis=0)
    assert moment[1] == pytest.approx(-TORQUE, rel=0.01)
    assert np.hypot(moment[0], moment[2]) < 0.05 * TORQUE
    # the reduced body's statics: the mount forces deflect it by K^-1 Psi^T f more
    body, _ = reduce_car_body(car, f_max=mounts.info["band_hz"])
    shapes = {i.name: i.shapes[:3, body.n_rigid:] for i in body.interfaces}
    m = mounts.motion.q.shape[1]
    gen = sum(shapes[n][:, :m].T @ f.mean(axis=0)[j] for j, n in enumerate(NAMES))
    K = body.K[body.n_rigid:body.n_rigid + m, body.n_rigid:body.n_rigid + m]
    predicted = np.linalg.solve(K, gen)
    dq = mounts.motion.q[sel].mean(axis=0) - frame.motion.q[sel].mean(axis=0)
    assert np.linalg.norm(predicted) > 0
    assert np.linalg.norm(dq - predicted) <= 0.02 * np.linalg.norm(predicted)
