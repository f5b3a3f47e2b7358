"""``flexpipe info BODY.npz``: the reduced-vs-full table pairs a reduced mode with a full
mode only when their shapes agree (MAC at least 0.5), says so in its header, gives the
damping column its unit and counts interface nodes in the singular when there is one."""

import re
from pathlib import Path

import pytest

from flexpipe.cli import main

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def plate_body(tmp_path_factory):
    """The audit's body: the 63-node plate, 2 mm steel, Craig-Bampton on its four
    interfaces (fixed-interface modes up to 42 kHz; the full check stops far lower)."""
    out = tmp_path_factory.mktemp("body") / "plate.npz"
    code = main(["reduce", str(ROOT / "meshes" / "plate_quad.msh"), "--interfaces",
                 str(ROOT / "meshes" / "plate_quad_interfaces.toml"), "--material", "steel",
                 "--thickness", "0.002", "-o", str(out), "-q"])
    assert code == 0
    return out


def _rows(text):
    """``{mode: fields}`` of the frequency table."""
    start = text.index("damping ratio [-]")
    rows = {}
    for line in text[start:].splitlines()[1:]:
        if not line.strip():
            break
        fields = line.split()
        rows[int(fields[0])] = fields
    return rows


def test_modes_without_a_counterpart_print_no_match(plate_body, capsys):
    """Each elastic row: the full mode of largest MAC (read from the file's checks here)
    with 100 (f / f_full - 1) % when that MAC is at least 0.5, else "no match" and no
    frequency or difference.  The audit's rows 12-22 (MAC 0.25 .. 0.000, "diffs" of 105 to
    63432 %) have no match; rows 7 and 8 pair with full modes 7 and 8 (66.7, 89.7 Hz)."""
    import numpy as np

    from flexpipe.reduction import load_body

    capsys.readouterr()
    assert main(["info", str(plate_body)]) == 0
    text = capsys.readouterr().out
    assert "'no match' when that MAC is below 0.5" in text
    body = load_body(plate_body)
    mac = body.checks["mac"]
    f_full = body.checks["full_frequencies_hz"]
    r = body.n_rigid
    rows = _rows(text)
    assert len(rows) == body.n_modes
    for k in range(r, body.n_modes):
        fields = rows[k + 1]
        j = r + int(np.argmax(mac[k, r:]))
        best = mac[k, j]
        if best >= 0.5:
            assert fields[2] == str(j + 1)
            assert float(fields[3]) == pytest.approx(f_full[j], rel=1e-5)
            diff = 100 * (body.frequencies_hz[k] / f_full[j] - 1)
            assert float(fields[4]) == pytest.approx(diff, abs=1e-4)
        else:
            assert fields[2:4] == ["no", "match"] and fields[4:6] == ["-", "-"], fields
        assert float(fields[-2]) == pytest.approx(best, abs=5e-4)
    assert rows[7][2] == "7" and rows[8][2] == "8"
    for k in range(12, 23):
        assert rows[k][2:4] == ["no", "match"], rows[k]
    printed = [float(f[4]) for f in rows.values() if len(f) > 4 and f[2] != "no"
               and re.fullmatch(r"-?[0-9.]+", f[4])]
    assert max(abs(d) for d in printed) < 20.0      # no 6070 % .. 63432 % any more


def test_damping_column_and_node_count(plate_body, capsys):
    """The damping ratio is dimensionless ("[-]"): 0.010 below 100 Hz (Adams/Flex default
    1 %); the one-node corner interface reads "1 node", the others "N nodes"."""
    capsys.readouterr()
    assert main(["info", str(plate_body)]) == 0
    text = capsys.readouterr().out
    header = next(line for line in text.splitlines() if "reduced [Hz]" in line)
    assert header.rstrip().endswith("damping ratio [-]")
    assert _rows(text)[7][-1] == "0.010"
    assert "corner (node, 6 DOF, 1 node at" in text and "1 nodes" not in text
    assert "edge (rbe2, 6 DOF, 7 nodes at" in text
