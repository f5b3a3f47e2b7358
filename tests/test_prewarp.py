"""Pre-warped modal inertia (flexpipe/exu/prewarp.py) against Exudyn and the closed form.

References: Exudyn's own generalized-alpha step on a one-coordinate system, and the exact
free vibration of a damped oscillator.
"""
import exudyn as exu
import exudyn.itemInterface as eii
import numpy as np
import pytest

from flexpipe.exu.prewarp import _amplification, discrete_mode, prewarp_modes


def _exudyn_free(omega, zeta, *, h, rho, t_end, mass=1.0, stiffness=None, x0=1e-3):
    """Free vibration of m q'' + c q' + k q = 0 integrated by Exudyn (q at every step)."""
    k = omega**2 * mass if stiffness is None else stiffness
    c = 2.0 * zeta * np.sqrt(k * mass)
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    n = mbs.AddNode(eii.NodeGenericODE2(numberOfODE2Coordinates=1, referenceCoordinates=[0.0],
                                        initialCoordinates=[x0], initialCoordinates_t=[0.0]))
    mbs.AddObject(eii.ObjectGenericODE2(nodeNumbers=[n], massMatrix=np.array([[mass]]),
                                        stiffnessMatrix=np.array([[k]]),
                                        dampingMatrix=np.array([[c]])))
    s = mbs.AddSensor(eii.SensorNode(nodeNumber=n, storeInternal=True, writeToFile=False,
                                     outputVariableType=exu.OutputVariableType.Coordinates))
    mbs.Assemble()
    st = exu.SimulationSettings()
    st.timeIntegration.numberOfSteps = int(round(t_end / h))
    st.timeIntegration.endTime = t_end
    st.timeIntegration.generalizedAlpha.spectralRadius = rho
    st.timeIntegration.verboseMode = 0
    st.solution.file.write = False
    st.solution.sensors.writePeriod = h
    exu.SolveDynamic(mbs, st)
    d = mbs.GetSensorStoredData(s)
    return d[:, 0], d[:, 1]


def _exact_free(t, omega, zeta, x0=1e-3):
    wd = omega * np.sqrt(1.0 - zeta**2)
    return x0 * np.exp(-zeta * omega * t) * (np.cos(wd * t) + zeta / np.sqrt(1 - zeta**2)
                                            * np.sin(wd * t))


@pytest.mark.parametrize("f_hz,zeta,rho", [(25.0, 0.02, 0.5), (60.0, 0.1, 0.8)])
def test_recurrence_is_exudyns_step(f_hz, zeta, rho):
    """The step matrix the pre-warp is solved on reproduces Exudyn's generalized-alpha."""
    h, w = 2e-3, 2 * np.pi * f_hz
    _, q = _exudyn_free(w, zeta, h=h, rho=rho, t_end=0.2)
    A = _amplification(w, zeta, h, rho)
    x = np.array([1e-3, 0.0, -w * w * 1e-3, -w * w * 1e-3])  # Exudyn's initial acceleration
    mine = [x[0]]
    for _ in range(len(q) - 1):
        x = A @ x
        mine.append(x[0])
    assert np.max(np.abs(np.array(mine) - q)) < 1e-9 * 1e-3 * 1e3


@pytest.mark.parametrize("f_hz,zeta", [(25.0, 0.02), (50.0, 0.02), (80.0, 0.02),
                                       (130.0, 0.10)])
def test_prewarped_mode_rings_at_its_own_frequency_and_damping(f_hz, zeta):
    """Exudyn at h = 2 ms with the pre-warped mass and damping follows the exact free
    vibration of the continuous mode; the plain mode drifts away from it."""
    h, rho, w, t_end = 2e-3, 0.5, 2 * np.pi * f_hz, 0.4
    factor, zp, matched = prewarp_modes([w], [zeta], h=h, spectral_radius=rho)
    assert matched[0] == 2
    m2 = factor[0]
    t, q = _exudyn_free(w, zp[0], h=h, rho=rho, t_end=t_end, mass=m2, stiffness=w * w)
    err = np.max(np.abs(q - _exact_free(t, w, zeta)))
    t, q0 = _exudyn_free(w, zeta, h=h, rho=rho, t_end=t_end)
    err_plain = np.max(np.abs(q0 - _exact_free(t, w, zeta)))
    # eigenvalues exact: what is left is the start-up of the scheme (the spurious roots and
    # the principal root's amplitude), growing with (omega h)^2
    assert err < 0.05 * (w * h) ** 2 * 1e-3, (err, err_plain)
    assert err_plain > 5 * err
    wd, zd = discrete_mode(w / np.sqrt(m2), zp[0], h=h, spectral_radius=rho)
    assert wd == pytest.approx(w, rel=1e-9) and zd == pytest.approx(zeta, abs=1e-9)


def test_prewarp_vanishes_with_the_step():
    """As h -> 0 the fitted masses and damping ratios tend to the continuous ones."""
    w = 2 * np.pi * np.array([22.0, 80.0, 300.0])
    zeta = np.array([0.02, 0.02, 0.10])
    f1, z1, m1 = prewarp_modes(w, zeta, h=1e-5, spectral_radius=0.5)
    assert np.all(m1 == 2)
    assert np.max(np.abs(f1 - 1.0)) < 1e-3 and np.max(np.abs(z1 - zeta)) < 1e-4
    f2, _, _ = prewarp_modes(w, zeta, h=2e-3, spectral_radius=0.5)
    assert np.all(np.abs(f2[:2] - 1) > 100 * np.abs(f1[:2] - 1))


def test_modes_near_nyquist_are_left_alone():
    """A mode the step cannot ring at its frequency keeps its mass and damping; where the
    damping cannot be matched with c' >= 0 only the frequency is."""
    h = 2e-3
    f, z, m = prewarp_modes(2 * np.pi * np.array([90.0, 240.0]), [0.02, 0.10], h=h,
                            spectral_radius=0.5)
    assert m[0] == 1 and z[0] == 0.0 and f[0] < 1.0
    wd, zd = discrete_mode(2 * np.pi * 90.0 / np.sqrt(f[0]), 0.0, h=h, spectral_radius=0.5)
    assert wd == pytest.approx(2 * np.pi * 90.0, rel=1e-9) and zd > 0.02
    assert m[1] == 0 and f[1] == 1.0 and z[1] == 0.10
    # critically damped (Adams/Flex default above 1 kHz): nothing rings, nothing to match
    f, z, m = prewarp_modes([2 * np.pi * 1200.0], [1.0], h=1e-4, spectral_radius=0.5)
    assert m[0] == 0 and f[0] == 1.0 and z[0] == 1.0


def test_bad_arguments():
    with pytest.raises(ValueError, match="h must be"):
        prewarp_modes([100.0], [0.02], h=0.0, spectral_radius=0.5)
    with pytest.raises(ValueError, match="spectral_radius"):
        prewarp_modes([100.0], [0.02], h=1e-3, spectral_radius=1.5)


def _free_body_response(body, *, h, t_end, prewarp):
    """Free flexible body (ObjectFFRFreducedOrder, 2 % modal damping), z pulse at 'b':
    elastic deflection of 'b' along z at every step."""
    from flexpipe.exu.body import add_flexible_body

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    hb = add_flexible_body(mbs, body, gravity=(0, 0, 0), damping=0.02,
                           prewarp=(h, 0.5) if prewarp else None)
    pulse = 0.5e-3
    load = mbs.AddLoad(eii.LoadForceVector(markerNumber=hb.position_markers["b"],
                                           loadVector=[0.0, 0.0, 0.0]))
    mbs.SetLoadParameter(load, "loadVectorUserFunction", lambda m, t, v: [
        0.0, 0.0, 400.0 * np.sin(np.pi * t / pulse) if t < pulse else 0.0])
    s = mbs.AddSensor(eii.SensorNode(nodeNumber=hb.modal_node, storeInternal=True,
                                     writeToFile=False,
                                     outputVariableType=exu.OutputVariableType.Coordinates))
    mbs.Assemble()
    st = exu.SimulationSettings()
    st.timeIntegration.numberOfSteps = int(round(t_end / h))
    st.timeIntegration.endTime = t_end
    st.timeIntegration.generalizedAlpha.spectralRadius = 0.5
    st.timeIntegration.verboseMode = 0
    st.solution.file.write = False
    st.solution.sensors.writePeriod = h
    exu.SolveDynamic(mbs, st)
    d = mbs.GetSensorStoredData(s)
    itf = next(i for i in body.interfaces if i.name == "b")
    sel = slice(body.n_rigid, body.n_rigid + d.shape[1] - 1)
    return d[:, 0], d[:, 1:] @ itf.shapes[2, sel]


def test_prewarp_on_a_floating_frame_body():
    """A free FFRF beam rung by a pulse, 2 % modal damping, step omega_1 h = 0.6 (the first
    body mode of the sample car at 2 ms is 0.28): against the solution at h/16, the plain
    body's tip deflection is off by 93 % of its RMS after 15 periods (phase drift), the
    pre-warped one by 12 % (measured), what is left coming from the modes above the first
    that the step cannot ring."""
    import flexpipe
    from flexpipe.fem import Material, assemble
    from flexpipe.mesh.generate import box

    fe = assemble(box(1.0, 0.2, 0.1, 16, 3, 2), Material(210e9, 0.3, 7850.0))
    body = flexpipe.reduce(fe, [flexpipe.Interface((0.0, 0.1, 0.05), radius=0.07, name="a"),
                                flexpipe.Interface((1.0, 0.1, 0.05), radius=0.07, name="b")],
                           method="craig-bampton", n_modes=8)
    w1 = 2 * np.pi * body.frequencies_hz[body.n_rigid]
    h, t_end = 0.6 / w1, 0.02
    t_ref, z_ref = _free_body_response(body, h=h / 16, t_end=t_end, prewarp=False)
    z_ref = z_ref[::16]
    err = {}
    for pw in (False, True):
        _, z = _free_body_response(body, h=h, t_end=t_end, prewarp=pw)
        n = min(len(z), len(z_ref))
        err[pw] = np.sqrt(np.mean((z[:n] - z_ref[:n]) ** 2)) / np.std(z_ref[:n])
    assert err[True] < 0.15 and err[True] < 0.2 * err[False], err


def test_simulate_rejects_a_non_boolean_prewarp():
    from pathlib import Path

    from flexpipe.errors import InputError
    from flexpipe.vehicle.simulation import simulate

    car = Path(__file__).resolve().parents[1] / "cars" / "sedan.toml"
    with pytest.raises(InputError, match="prewarp must be True or False"):
        simulate(car, speed=10.0, t_end=0.1, body="rigid", prewarp="yes")
