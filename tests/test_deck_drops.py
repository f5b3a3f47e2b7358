"""Deck input that used to be dropped without a word: CQUAD8/CTRIA6 ZOFFS and THETA/MCID
(now applied to the four shells each is split into), Abaqus ``*COUPLING, INFLUENCE
RADIUS=`` (applied: only the surface nodes within the radius are coupled),
``*CONNECTOR MOTION`` / ``*CONNECTOR STOP`` (real keywords, reported as not used - not
taken for a misspelt ``*CONNECTOR SECTION``) and ``*TRANSVERSE SHEAR STIFFNESS`` (the
report says flexpipe's own transverse shear replaces the values).

References: the same models written with the split CQUAD4/CTRIA3 shells (and centre grids)
by hand, an MCID system along the THETA direction, distances counted by hand."""

from __future__ import annotations

import re
import warnings

import numpy as np
import pytest
from _meshdata import write as _write

from flexpipe.errors import MeshError
from flexpipe.fem import assemble
from flexpipe.mesh import MeshWarning, read_mesh

N, A = 3, 0.3                       # CQUAD8 plate: N x N elements, side A
MAT8 = "MAT8,2,140.+9,10.+9,0.3,5.+9,5.+9,4.+9,1600."
PCOMP = ["PCOMP,1,,,,,,,,+", "+,2,0.002,0."]
PSHELL = ["MAT1,2,2.1+11,,0.3,7850.", "PSHELL,1,2,0.002,2"]


def _read(path):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", MeshWarning)
        return read_mesh(path)


def _gid(i, j):
    return 1 + i + (2 * N + 1) * j


def _grid(i, j):
    return f"GRID,{_gid(i, j)},,{A * i / (2 * N)!r},{A * j / (2 * N)!r},0."


def _quad8_deck(theta="", zoffs="", extra=()):
    lines = ["BEGIN BULK"]
    lines += [_grid(i, j) for j in range(2 * N + 1) for i in range(2 * N + 1)
              if not (i % 2 and j % 2)]
    for j in range(N):
        for i in range(N):
            a, b = 2 * i, 2 * j
            g = [_gid(a, b), _gid(a + 2, b), _gid(a + 2, b + 2), _gid(a, b + 2),
                 _gid(a + 1, b), _gid(a + 2, b + 1), _gid(a + 1, b + 2), _gid(a, b + 1)]
            lines += [f"CQUAD8,{1 + i + N * j},1,{','.join(map(str, g[:6]))},+",
                      f"+,{g[6]},{g[7]},,,,,{theta},{zoffs}"]
    return "\n".join(lines + list(extra) + ["ENDDATA"]) + "\n"


def _split_quad4_deck(zoffs, extra=()):
    """The CQUAD8 plate as its split: four CQUAD4 through the mid-side and centre grids."""
    lines = ["BEGIN BULK"] + [_grid(i, j) for j in range(2 * N + 1) for i in range(2 * N + 1)]
    eid = 0
    for j in range(N):
        for i in range(N):
            a, b = 2 * i, 2 * j
            for di, dj in ((0, 0), (1, 0), (1, 1), (0, 1)):
                x, y = a + di, b + dj
                eid += 1
                g = (_gid(x, y), _gid(x + 1, y), _gid(x + 1, y + 1), _gid(x, y + 1))
                lines.append(f"CQUAD4,{eid},1,{','.join(map(str, g))},,{zoffs}")
    return "\n".join(lines + list(extra) + ["ENDDATA"]) + "\n"


def _by_position(model):
    """K and M with the nodes sorted by position (decks number the centre grids apart)."""
    X = np.asarray(model.nodes)
    order = np.lexsort(np.round(X, 9).T[::-1])
    dpn = model.dofs_per_node
    dofs = (order[:, None] * dpn + np.arange(dpn)).ravel()
    return (model.K.toarray()[np.ix_(dofs, dofs)], model.M.toarray()[np.ix_(dofs, dofs)])


# ---------------------------------------------------------------- 1. CQUAD8/CTRIA6
def test_cquad8_zoffs_is_applied_as_on_the_split_cquad4(tmp_path):
    """ZOFFS = 3 mm on every CQUAD8 = the split CQUAD4 plate with ZOFFS = 3 mm (K and M);
    without ZOFFS K differs (the old reader dropped the field)."""
    z = _read(_write(tmp_path, "z.bdf", _quad8_deck(zoffs="0.003", extra=PSHELL)))
    quads = [b for b in z.blocks if b.type == "quad"]
    assert len(quads) == 1 and np.all(quads[0].data["zoffset"] == 0.003)
    Kz, Mz = _by_position(assemble(z))
    Kq, Mq = _by_position(assemble(_read(_write(tmp_path, "q.bdf",
                                                _split_quad4_deck("0.003", PSHELL)))))
    K0, _ = _by_position(assemble(_read(_write(tmp_path, "n.bdf",
                                               _quad8_deck(extra=PSHELL)))))
    scale = abs(Kq).max()
    assert abs(Kz - Kq).max() < 1e-9 * scale
    assert abs(Mz - Mq).max() < 1e-9 * abs(Mq).max()
    assert abs(Kz - K0).max() > 1e-3 * scale


def test_ctria6_zoffs_reaches_all_four_sub_triangles(tmp_path):
    text = "\n".join(["BEGIN BULK", "GRID,1,,0.,0.,0.", "GRID,2,,1.,0.,0.", "GRID,3,,0.,1.,0.",
                      "GRID,4,,.5,0.,0.", "GRID,5,,.5,.5,0.", "GRID,6,,0.,.5,0.",
                      "CTRIA6,7,1,1,2,3,4,5,6,+", "+,,-0.004", *PSHELL, "ENDDATA"]) + "\n"
    m = _read(_write(tmp_path, "t6.bdf", text))
    (tri,) = [b for b in m.blocks if b.type == "triangle"]
    assert len(tri) == 4 and np.all(tri.data["zoffset"] == -0.004)


def test_cquad8_theta_is_the_mcid_direction_on_an_orthotropic_laminate(tmp_path):
    """THETA = 30 on CQUAD8 with a MAT8 ply = MCID of a system turned 30 deg about z (both
    applied to the split shells); K differs from THETA blank."""
    c, s = float(np.cos(np.radians(30))), float(np.sin(np.radians(30)))
    cord = ["CORD2R,7,,0.,0.,0.,0.,0.,1.,+", f"+,{c!r},{s!r},0."]
    lam = [MAT8, *PCOMP, *cord]
    models = {k: _read(_write(tmp_path, f"{k}.bdf", _quad8_deck(theta=t, extra=lam)))
              for k, t in (("theta", "30."), ("mcid", "7"), ("none", ""))}
    quad = [b for b in models["theta"].blocks if b.type == "quad"][0]
    assert np.allclose(quad.data["mat_ref"], [c, s, 0.0]) and not quad.data["mat_theta"].any()
    K = {k: assemble(m).K.toarray() for k, m in models.items()}
    scale = abs(K["none"]).max()
    assert abs(K["theta"] - K["mcid"]).max() < 1e-9 * scale
    assert abs(K["theta"] - K["none"]).max() > 1e-3 * scale


def test_ctria6_theta_turns_the_parent_x_axis_not_each_sub_triangle(tmp_path):
    """A CTRIA6 G1 -> G2 along y, THETA = 90: the material axis is -x on all four parts
    (the middle part's own x axis runs from mid-side 4 to mid-side 5)."""
    text = "\n".join(["BEGIN BULK", "GRID,1,,0.,0.,0.", "GRID,2,,0.,1.,0.", "GRID,3,,-1.,0.,0.",
                      "GRID,4,,0.,.5,0.", "GRID,5,,-.5,.5,0.", "GRID,6,,-.5,0.,0.",
                      "CTRIA6,7,1,1,2,3,4,5,6,+", "+,90.", MAT8, *PCOMP, "ENDDATA"]) + "\n"
    m = _read(_write(tmp_path, "t6.bdf", text))
    (tri,) = [b for b in m.blocks if b.type == "triangle"]
    assert np.allclose(tri.data["mat_ref"], [-1.0, 0.0, 0.0], atol=1e-12)


def test_second_order_shell_bad_theta_is_an_error_naming_the_line(tmp_path):
    p = _write(tmp_path, "bad.bdf", _quad8_deck(theta="abc", extra=PSHELL))
    with pytest.raises(MeshError, match=r"bad.bdf, line \d+: CQUAD8 .*THETA = 'abc'"):
        read_mesh(p)


# ---------------------------------------------------------------- Abaqus
MAT = ["*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1E11, 0.3", "*DENSITY", "7850."]


def _abaqus(after):
    """A 4 x 4 S4R plate (0.1 m grid), reference node 100 above node 13 (the centre)."""
    lines = ["*HEADING", "plate", "*NODE"]
    lines += [f"{1 + i + 5 * j}, {0.1 * i!r}, {0.1 * j!r}, 0." for j in range(5)
              for i in range(5)]
    lines += ["100, 0.2, 0.2, 0.05", "*ELEMENT, TYPE=S4R, ELSET=PLATE"]
    lines += [f"{1 + i + 4 * j}, {1 + i + 5 * j}, {2 + i + 5 * j}, {7 + i + 5 * j}, "
              f"{6 + i + 5 * j}" for j in range(4) for i in range(4)]
    lines += ["*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL", "0.002, 5", *MAT]
    return "\n".join(lines + after) + "\n"


def _coupling(radius, kind="DISTRIBUTING"):
    r = f", INFLUENCE RADIUS={radius}" if radius is not None else ""
    return ["*SURFACE, TYPE=NODE, NAME=ALLN", *(str(k) for k in range(1, 26)),
            f"*COUPLING, CONSTRAINT NAME=C1, REF NODE=100, SURFACE=ALLN{r}", f"*{kind}"]


@pytest.mark.parametrize("kind", ["DISTRIBUTING", "KINEMATIC"])
def test_coupling_influence_radius_keeps_the_nodes_within_it(tmp_path, kind):
    """Radius 0.12 around (0.2, 0.2, 0.05): the centre node (0.05 away) and its four
    neighbours at 0.1 in plane (sqrt(0.01 + 0.0025) = 0.112); not the diagonal ones
    (sqrt(0.02 + 0.0025) = 0.150)."""
    m = _read(_write(tmp_path, "r.inp", _abaqus(_coupling("0.12", kind))))
    if kind == "DISTRIBUTING":
        (c,) = m.interpolations
        nodes = c.nodes
    else:
        (c,) = m.rigid_links
        nodes = c.slaves
    assert sorted(np.asarray(m.node_ids)[nodes].tolist()) == [8, 12, 13, 14, 18]
    full = _read(_write(tmp_path, "f.inp", _abaqus(_coupling(None, kind))))
    (cf,) = full.interpolations if kind == "DISTRIBUTING" else full.rigid_links
    assert len(cf.nodes if kind == "DISTRIBUTING" else cf.slaves) == 25


@pytest.mark.parametrize(("radius", "why"), [("-1.", "valid: a distance > 0"),
                                             ("abc", "valid: a distance > 0"),
                                             ("0.01", "none of the 25 nodes")])
def test_coupling_influence_radius_errors_name_file_line_and_parameter(tmp_path, radius, why):
    text = _abaqus(_coupling(radius))
    line = text.splitlines().index(next(t for t in text.splitlines()
                                        if t.startswith("*COUPLING"))) + 1
    with pytest.raises(MeshError, match=rf"bad.inp, line {line}: \*COUPLING INFLUENCE "
                                        rf"RADIUS=.*{why}"):
        read_mesh(_write(tmp_path, "bad.inp", text))


def _not_used(tmp_path, after):
    text = _abaqus(after)
    with warnings.catch_warnings(record=True) as rec:
        warnings.simplefilter("always")
        m = read_mesh(_write(tmp_path, "d.inp", text), prune_unreferenced=True)
    msgs = [str(w.message) for w in rec if "not used for M and K" in str(w.message)]
    assert len(msgs) == 1
    return m, msgs[0], text.splitlines()


@pytest.mark.parametrize("kw", ["CONNECTOR MOTION", "CONNECTOR STOP"])
def test_connector_motion_and_stop_are_reported_not_used_not_a_typo(tmp_path, kw):
    after = [f"*{kw}", "1, 0.01"] if kw == "CONNECTOR STOP" else [f"*{kw}", "100, 1, 0.01"]
    m, msg, lines = _not_used(tmp_path, after)
    line = lines.index(f"*{kw}") + 1
    assert re.search(rf"\*{kw} x1 - .*\(first at \S*d.inp line {line}\)", msg)
    assert m.info["dropped"][kw] == 1


def test_connector_stop_keeps_the_connector_behavior_open(tmp_path):
    """*CONNECTOR STOP between *CONNECTOR ELASTICITY and *CONNECTOR DAMPING: the damping
    still belongs to the behaviour (it was an error 'outside a *CONNECTOR BEHAVIOR')."""
    after = ["*NODE", "101, 0.2, 0.2, 0.", "*ELEMENT, TYPE=CONN3D2, ELSET=C", "50, 101, 13",
             "*CONNECTOR SECTION, ELSET=C, BEHAVIOR=B", "CARTESIAN",
             "*CONNECTOR BEHAVIOR, NAME=B", "*CONNECTOR ELASTICITY, COMPONENT=1", "1000.",
             "*CONNECTOR STOP", "1, -0.01, 0.01", "*CONNECTOR DAMPING, COMPONENT=1", "5."]
    m, msg, _ = _not_used(tmp_path, after)
    assert "*CONNECTOR STOP x1" in msg and "CONNECTOR STOP" in m.info["dropped"]


def test_transverse_shear_stiffness_report_says_flexpipe_replaces_it(tmp_path):
    after = ["*TRANSVERSE SHEAR STIFFNESS", "1.e6, 1.e6"]
    _, msg, lines = _not_used(tmp_path, after)
    line = lines.index("*TRANSVERSE SHEAR STIFFNESS") + 1
    assert re.search(r"\*TRANSVERSE SHEAR STIFFNESS x1 - the given transverse shear stiffness "
                     rf"values are replaced by flexpipe's own .*d.inp line {line}\)", msg)
