"""The Abaqus ``.inp`` writer's history data: a deck's SPC set and EIGRL written as
``*BOUNDARY`` and a ``*FREQUENCY`` step read back as the same DOF set and set-up, with the
same constrained frequencies (the closed-form simply supported plate and the Nastran deck
of :mod:`test_abaqus_decks` as references), and what an ``.inp`` cannot hold named."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from test_abaqus_decks import F11, _abaqus_plate, _cli_modes, _nastran_plate, _read

from flexpipe.mesh import MeshWarning, read_mesh


def test_spc_set_and_eigrl_survive_the_inp_writer(tmp_path):
    """A Nastran SOL 103 deck's SPC = 1 set and EIGRL written as *BOUNDARY and a *FREQUENCY
    step, read back as the same DOF set and set-up; the constrained frequencies equal the
    Nastran deck's and the closed-form simply supported plate's."""
    from flexpipe.mesh import write_mesh

    a = _read(tmp_path, "p.bdf", _nastran_plate())
    with warnings.catch_warnings():
        warnings.simplefilter("error", MeshWarning)     # nothing is lost: no warning
        text = write_mesh(a, tmp_path / "w.inp").read_text()
        b = read_mesh(tmp_path / "w.inp")               # *HEADING is not warned about
    assert "*BOUNDARY" in text and "*FREQUENCY, EIGENSOLVER=LANCZOS" in text
    assert b.info["dropped"] == {"HEADING": 1}
    assert sorted(b.dof_sets["SPC1"].tolist()) == sorted(a.dof_sets["SPC1"].tolist())
    assert b.solution["spc"] == "SPC1" and b.solution["n_modes"] == 8
    f = _cli_modes(tmp_path, tmp_path / "w.inp")
    np.testing.assert_allclose(f, _cli_modes(tmp_path, tmp_path / "p.bdf"), rtol=1e-9)
    assert f[0] == pytest.approx(F11, rel=2e-3)


def test_frequency_range_survives_the_inp_writer(tmp_path):
    a = _read(tmp_path, "rng.inp", _abaqus_plate(["*BOUNDARY", "EDGE, 1, 3", "*STEP",
                                                  "*FREQUENCY", ", 200., 450.", "*END STEP"]))
    from flexpipe.mesh import write_mesh

    b = read_mesh(write_mesh(a, tmp_path / "w.inp"))
    assert dict(b.solution) == {"spc": "SPC1", "f_min": 200.0, "f_max": 450.0}
    np.testing.assert_allclose(_cli_modes(tmp_path, tmp_path / "w.inp"),
                               [247.949, 247.949, 396.773], rtol=1e-5)


def test_inp_writer_names_what_an_inp_cannot_hold(tmp_path):
    """A second SPC set the solution does not use, and Nastran's default lumped mass (no
    PARAM,COUPMASS in a SOL deck), are named in the writer's warning, not dropped silently."""
    from flexpipe.mesh import write_mesh

    text = _nastran_plate(extra=["SPC1,7,3,221"]).replace("PARAM,COUPMASS,1\n", "")
    a = _read(tmp_path, "p2.bdf", text)
    with pytest.warns(MeshWarning) as got:
        write_mesh(a, tmp_path / "w2.inp")
    msg = " ".join(str(w.message) for w in got)
    assert "constraint set(s) SPC7, which the solution does not use" in msg
    assert "lumped mass of the Nastran solution" in msg
