"""``flexpipe reduce`` and the body summary of ``flexpipe info``; the interface spec file."""

from __future__ import annotations

import argparse

import meshio
import numpy as np
import pytest

from flexpipe.cli import main
from flexpipe.cli import reduce as cli_reduce
from flexpipe.errors import InputError
from flexpipe.mesh.generate import box
from flexpipe.mesh.write import write_mesh
from flexpipe.reduction import load_body
from flexpipe.reduction.spec import read_interfaces

SPEC = """radius = 0.07
[[interface]]
name = "a"
point = [0.0, 0.1, 0.05]

[[interface]]
name = "b"
point = [1.0, 0.1, 0.05]
node_set = "xmax"
"""


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    d = tmp_path_factory.mktemp("cli")
    write_mesh(box(1.0, 0.2, 0.1, 12, 3, 2), d / "bar.msh")
    (d / "spec.toml").write_text(SPEC)
    return d


def test_reduce_writes_body_and_vtu(files, capsys):
    out, vtu = files / "bar.npz", files / "bar.vtu"
    code = main(["reduce", str(files / "bar.msh"), "--interfaces", str(files / "spec.toml"),
                 "-o", str(out), "--material", "steel", "--n-modes", "4", "--vtu", str(vtu),
                 "-q"])
    assert code == 0
    text = capsys.readouterr().out
    body = load_body(out)
    assert body.interface_names == ("a", "b") and body.n_modes == 12 + 4  # static + fixed
    assert body.mass == pytest.approx(7850 * 1.0 * 0.2 * 0.1, rel=1e-12)
    assert "mass [kg]" in text and "MAC" in text and "rigid" in text
    m = meshio.read(vtu)
    assert len(m.point_data) == body.n_modes
    first_elastic = [k for k in m.point_data if k.startswith("mode_07_")][0]
    np.testing.assert_array_equal(m.point_data[first_elastic], body.modes[:, :, 6])


def test_info_prints_the_stored_checks(files, capsys):
    out = files / "info.npz"
    assert main(["reduce", str(files / "bar.msh"), "--interfaces", str(files / "spec.toml"),
                 "-o", str(out), "--material", "steel", "--n-modes", "4", "-q"]) == 0
    capsys.readouterr()
    p = argparse.ArgumentParser()
    cli_reduce.add_info_arguments(p)
    assert cli_reduce.run_info(p.parse_args([str(out)])) == 0
    text = capsys.readouterr().out
    body = load_body(out)
    f_full = body.checks["full_frequencies_hz"]
    # the first elastic row pairs reduced and full mode 7 and shows both frequencies
    row = next(line for line in text.splitlines() if line.strip().startswith("7 "))
    assert f"{body.frequencies_hz[6]:.6g}" in row and f"{f_full[6]:.6g}" in row


def test_bad_spec_and_bad_output_give_one_line_errors(files, capsys):
    bad = files / "bad.toml"
    bad.write_text('[[interface]]\nname = "a"\npoint = [0.0, 0.1]\n')
    with pytest.raises(InputError, match=r"bad.toml, line 1, key 'interface\[0\].point'"):
        read_interfaces(bad)
    code = main(["reduce", str(files / "bar.msh"), "--interfaces", str(bad), "-o",
                 str(files / "x.npz"), "--material", "steel", "-q"])
    assert code == 2
    assert "point must be [x, y, z]" in capsys.readouterr().err
    far = files / "far.toml"
    far.write_text('[[interface]]\nname = "far"\npoint = [5.0, 0.0, 0.0]\nradius = 0.01\n')
    code = main(["reduce", str(files / "bar.msh"), "--interfaces", str(far), "-o",
                 str(files / "x.npz"), "--material", "steel", "-q"])
    assert code == 2
    err = capsys.readouterr().err
    assert "'far'" in err and "no mesh node within radius" in err
    assert not (files / "x.npz").exists()


def test_spec_node_ids_are_file_ids(files):
    spec = files / "ids.toml"
    spec.write_text('[[interface]]\nname = "p"\npoint = [0.0, 0.0, 0.0]\nnodes = [1, 2, 5]\n')
    itf = read_interfaces(spec, node_ids=np.array([1, 2, 3, 4, 5]))
    assert itf[0].nodes == (0, 1, 4)
    with pytest.raises(InputError, match="not in the mesh"):
        read_interfaces(spec, node_ids=np.array([7, 8]))


def test_missing_node_ids_name_the_valid_ids_and_the_nearest(files):
    spec = files / "missing.toml"
    spec.write_text('[[interface]]\nname = "p"\npoint = [0.0, 0.0, 0.0]\nnodes = [1, 99, 0, 12]\n')
    with pytest.raises(InputError) as e:
        read_interfaces(spec, node_ids=np.array([1, 2, 3, 10, 11, 40]))
    msg = str(e.value)
    assert "missing.toml, line 1, key 'interface[0].nodes'" in msg
    assert "[99, 0, 12]" in msg and "6 node ids" in msg and "1 and 40" in msg  # range, count
    assert "99 -> 40" in msg and "0 -> 1" in msg and "12 -> 11 or 40" in msg  # nearest ids


def test_overlapping_interfaces_name_the_key_once(files, capsys):
    spec = files / "overlap.toml"
    spec.write_text('[[interface]]\nname = "a"\npoint = [0.0, 0.1, 0.05]\nradius = 0.3\n\n'
                    '[[interface]]\nname = "tab"\npoint = [0.1, 0.1, 0.05]\nradius = 0.3\n')
    code = main(["reduce", str(files / "bar.msh"), "--interfaces", str(spec), "-o",
                 str(files / "x.npz"), "--material", "steel", "-q"])
    assert code == 2
    err = capsys.readouterr().err
    assert "overlap.toml, line 6, key 'interface[1]': interfaces 'a' and 'tab' overlap" in err
    assert err.count("key ") == 1 and "key 'tab'" not in err


def test_reduce_stores_stress_modes_on_request(files, capsys):
    out = files / "stress.npz"
    assert main(["reduce", str(files / "bar.msh"), "--interfaces", str(files / "spec.toml"),
                 "-o", str(out), "--material", "steel", "--n-modes", "4", "--stress", "all",
                 "--no-check", "-q"]) == 0
    body = load_body(out)
    assert body.stress.n_elements == 12 * 3 * 2 * 6  # every tetra of the Kuhn split
    assert body.stress.blocks[0].modes.shape[1:] == (6, body.n_elastic)
    assert "stress modes (all)" in capsys.readouterr().out
