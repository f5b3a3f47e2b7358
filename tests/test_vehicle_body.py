"""The sample body-in-white: file reproducible from its generator, size, mass, dimensions and
first global modes against the ranges published for steel passenger-car bodies.

Published ranges used (see meshes/make_sedan_biw.py): first global torsion of a steel
sedan body-in-white ~25-45 Hz, first vertical bending ~30-50 Hz; steel mid-size sedan
BIW mass ~250-400 kg.
"""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pytest

from flexpipe.fem import assemble
from flexpipe.mesh import read_mesh
from flexpipe.vehicle.bodymodel import global_modes

ROOT = Path(__file__).resolve().parents[1]
BDF = ROOT / "meshes" / "sedan_biw.bdf"


def _generator():
    spec = importlib.util.spec_from_file_location("make_sedan_biw",
                                                  ROOT / "meshes" / "make_sedan_biw.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def mesh():
    return read_mesh(BDF)


def test_committed_file_is_what_the_generator_writes(tmp_path):
    gen = _generator()
    info = gen.write_bdf(gen.build(), tmp_path / "biw.bdf")
    assert (tmp_path / "biw.bdf").read_bytes() == BDF.read_bytes()
    assert info["bytes"] < 10e6
    assert 20_000 <= info["dof"] <= 60_000  # "a few tens of thousands of DOF"


def test_dimensions_mass_and_hardpoints(mesh):
    ext = np.ptp(mesh.points, axis=0)
    assert 4.4 <= ext[0] <= 4.8  # length of the structure
    assert 1.4 <= ext[1] <= 1.9  # width over the sills
    assert 1.1 <= ext[2] + 0.2 <= 1.5  # roof height above ground (floor at z = 0.2 m)
    fe = assemble(mesh)
    assert 250.0 <= fe.total_mass <= 400.0
    # the mass read back equals the geometric mass of the generator's parts (plus CONM2)
    gen = _generator()
    B = gen.build()
    assert fe.total_mass == pytest.approx(gen.structural_mass(B) + gen.NONSTRUCTURAL_KG,
                                          rel=2e-3)
    for p in gen.HARDPOINTS.values():  # every suspension mount lies on the structure
        assert np.linalg.norm(mesh.points - np.asarray(p), axis=1).min() < 1e-6


def test_first_torsion_and_bending_in_published_ranges(mesh):
    g = global_modes(assemble(mesh), 14)
    assert g["torsion_hz"] is not None and 25.0 <= g["torsion_hz"] <= 45.0
    assert g["bending_hz"] is not None and 30.0 <= g["bending_hz"] <= 50.0
    # the lowest elastic mode is global, not a local panel mode
    assert g["labels"][0] in ("torsion", "bending", "lateral")
