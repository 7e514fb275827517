"""Benchmark decks (fem_validation.decks): the model, the .inp, the meshes, problem.json.

Checked against geometry and closed forms, not against the writer's own output:
mid-side nodes in the middle of their edges (or on the sphere), element faces
whose outward normals point out of their body, the paraboloid faces'
heights, the sets on their planes, meshio reading the groups back, and
problem.json's Hertz values against the closed forms of a sphere on a plane.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from fem_extra import require

require("skfem", "meshio", "gmsh")

from fem_validation.decks import read_scene, write_deck  # noqa: E402
from fem_validation.decks.model import TET_FACES, build_model, face_nodes  # noqa: E402
from fem_validation.scenes import Scene  # noqa: E402

pytest.importorskip("gmsh")

SPHERE = """name = "ball 10 mm"
load = 800.0
[body1]
Rx = 0.01
Ry = 0.01
E = 200e9
nu = 0.3
[body2]
Rx = "inf"
Ry = "inf"
E = 200e9
nu = 0.3
"""

ELLIPSOIDS = """name = "ellipsoids"
load = 50.0
angle_deg = 0
[body1]
Rx = 0.008
Ry = 0.02
E = 210e9
nu = 0.3
[body2]
Rx = 0.03
Ry = "inf"
E = 110e9
nu = 0.34
"""


@pytest.fixture(scope="module")
def sphere(tmp_path_factory):
    path = tmp_path_factory.mktemp("scene") / "sphere.toml"
    path.write_text(SPHERE)
    scene = read_scene(path)
    return scene, build_model(scene, level=0)


@pytest.fixture(scope="module")
def blocks(tmp_path_factory):
    path = tmp_path_factory.mktemp("scene") / "ellipsoids.toml"
    path.write_text(ELLIPSOIDS)
    scene = read_scene(path)
    return scene, build_model(scene, level=0)


def _volumes(nodes, tets):
    v = nodes[tets[:, :4]]
    return np.einsum("ij,ij->i", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0]),
                     v[:, 3] - v[:, 0]) / 6


def _face_normals(model, name):
    elem, face = model.surfaces[name]
    six = face_nodes(model.elements[elem], face)
    v = model.nodes[six[:, :3]]
    n = np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0])
    return six, n / np.linalg.norm(n, axis=1)[:, None]


def test_read_scene_errors(tmp_path):
    bad = {"missing.toml": (SPHERE.replace("nu = 0.3\n[body2]", "[body2]"),
                            r"missing\.toml.*\[body1\].*missing nu"),
           "both.toml": (SPHERE.replace("load = 800.0", "load = 800.0\napproach = 1e-6"),
                         "one of load"),
           "none.toml": (SPHERE.replace("load = 800.0", ""), "a deck needs the target"),
           "word.toml": (SPHERE.replace("load = 800.0", "load = 'heavy'"),
                         "load must be a number, got 'heavy'"),
           "extra.toml": ("colour = 1\n" + SPHERE, "unknown key.*colour"),
           "concave.toml": (SPHERE.replace('Rx = "inf"', "Rx = -0.005"), r"\[body|contact")}
    for name, (text, message) in bad.items():
        path = tmp_path / name
        path.write_text(text)
        with pytest.raises(ValueError, match=message):
            read_scene(path)
    with pytest.raises(ValueError, match="cannot read scene file"):
        read_scene(tmp_path / "absent.toml")


def test_approach_scene_gives_its_hertz_load(tmp_path):
    path = tmp_path / "approach.toml"
    path.write_text(SPHERE.replace("load = 800.0", "approach = 2e-5"))
    scene = read_scene(path)
    e_star = 1 / (2 * (1 - 0.3**2) / 200e9)
    # sphere on a plane: delta = a^2 / R, P = 4/3 E* sqrt(R) delta^(3/2)
    assert scene.load == pytest.approx(4 / 3 * e_star * math.sqrt(0.01) * 2e-5**1.5, rel=1e-12)


def test_curved_model_geometry(sphere):
    scene, m = sphere
    r = 0.01
    assert m.geometry == "sphere-plane" and m.quarter
    assert np.all(_volumes(m.nodes, m.elements) > 0)
    # every mid-side node is the middle of its edge, to the sphere's sagitta at most
    for k, (i, j) in enumerate(((0, 1), (1, 2), (2, 0), (0, 3), (1, 3), (2, 3))):
        mid = 0.5 * (m.nodes[m.elements[:, i]] + m.nodes[m.elements[:, j]])
        length = np.linalg.norm(m.nodes[m.elements[:, i]] - m.nodes[m.elements[:, j]], axis=1)
        off = np.linalg.norm(m.nodes[m.elements[:, 4 + k]] - mid, axis=1)
        assert np.all(off <= length**2 / (8 * r) * 1.01 + 1e-15)
    # the ball's contact faces lie on the sphere (all six nodes); the right-hand normal of
    # an S1..S4 vertex triple points into the element: up, into the ball
    six, normal = _face_normals(m, "CONTACT1")
    dist = np.linalg.norm(m.nodes[six] - [0, 0, r], axis=2)
    np.testing.assert_allclose(dist, r, rtol=1e-12)
    assert np.all(normal[:, 2] > 0)
    # the block's contact faces on z = 0, normals into the block
    six, normal = _face_normals(m, "CONTACT2")
    assert np.all(m.nodes[six, 2] == 0) and np.all(normal[:, 2] < -0.999)
    # the slave faces reach past Hertz's contact, not across the whole ball
    xy = np.linalg.norm(m.nodes[m.node_sets["SLAVE"], :2], axis=1)
    assert 1.5 * scene.hertz().a < xy.max() < 4 * scene.hertz().a
    # sets on their planes
    assert np.all(np.abs(m.nodes[m.node_sets["SYMX"], 0]) < 1e-15)
    assert np.all(np.abs(m.nodes[m.node_sets["SYMY"], 1]) < 1e-15)
    np.testing.assert_allclose(m.nodes[m.node_sets["MOVED"], 2], r, rtol=1e-12)
    assert np.all(m.nodes[m.node_sets["FIXED"], 2] == -2 * r)
    # the approach aims at the target load: Hertz's delta less a positive settlement
    assert 0.9 * scene.hertz().delta < m.approach < scene.hertz().delta


def test_block_model_geometry(blocks):
    scene, m = blocks
    assert m.geometry == "paraboloid-blocks" and m.quarter
    assert np.all(_volumes(m.nodes, m.elements) > 0)
    b1, b2 = scene.body1, scene.body2
    for name, sign, body in (("CONTACT1", 1, b1), ("CONTACT2", -1, b2)):
        six, normal = _face_normals(m, name)
        x, y, z = m.nodes[six].transpose(2, 0, 1)
        h = x**2 / (2 * body.Rx) + (y**2 / (2 * body.Ry) if math.isfinite(body.Ry) else 0)
        np.testing.assert_allclose(z, sign * h, atol=1e-15)
        assert np.all(sign * normal[:, 2] > 0)  # into body 1 is up, into body 2 down
    depth = m.info["block_depth"]
    np.testing.assert_allclose(m.nodes[m.node_sets["MOVED"], 2], depth, rtol=1e-12)
    np.testing.assert_allclose(m.nodes[m.node_sets["FIXED"], 2], -depth, rtol=1e-12)
    # the initial gap between the faces is Hertz's: x^2 (1/2R1x + 1/2R2x) + y^2/(2 R1y)
    c = scene.hertz()
    assert c.ellipticity > 1.5 and abs(math.degrees(c.major_axis_angle) - 90) < 1e-9


def test_whole_model_without_symmetry():
    import hertz

    b = hertz.Body(0.01, 0.02, 210e9, 0.3)
    scene = Scene("crossed", b, b, 30.0, math.radians(30))
    with pytest.raises(ValueError, match="no quarter symmetry"):
        build_model(scene, 0, model="quarter")
    m = build_model(scene, 0)
    assert not m.quarter and "SYMX" not in m.node_sets
    assert m.nodes[:, 0].min() < 0 and m.nodes[:, 1].min() < 0
    # body 2's face follows its own paraboloid, turned by 30 degrees
    six, _ = _face_normals(m, "CONTACT2")
    x, y, z = m.nodes[six].transpose(2, 0, 1)
    c, s = math.cos(scene.angle), math.sin(scene.angle)
    u, v = x * c + y * s, -x * s + y * c
    np.testing.assert_allclose(z, -(u**2 / 0.02 + v**2 / 0.04), atol=1e-15)


def test_calculix_and_abaqus_decks(sphere, tmp_path):
    scene, _ = sphere
    decks = {}
    for fmt in ("calculix", "abaqus"):
        m, paths = write_deck(scene, fmt, tmp_path / fmt, level=0)
        decks[fmt] = paths[0].read_text()
    ccx, abq = decks["calculix"], decks["abaqus"]
    for text in (ccx, abq):
        assert text.count("*ELEMENT, TYPE=C3D10") == 2
        assert "*CONTACT PAIR, INTERACTION=HERTZ, TYPE=SURFACE TO SURFACE\nCONTACT1, CONTACT2" \
            in text
        assert "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR" in text
        # the element faces of the surfaces, numbered as in *ELEMENT
        faces = len(m.surfaces["CONTACT1"][0]) + len(m.surfaces["CONTACT2"][0])
        assert len([ln for ln in text.splitlines() if ln.endswith((", S1", ", S2", ", S3",
                                                                   ", S4"))]) == faces
        # mm, MPa: the modulus and the approach
        assert "\n200000, 0.3\n" in text
        assert f"MOVED, 3, 3, {-m.approach * 1e3:.12g}" in text
    assert "*NODE FILE" in ccx and "*CONTACT FILE" in ccx and "ITERATIVE CHOLESKY" in ccx
    assert "*CONTACT OUTPUT" in abq and "*NODE FILE" not in abq and "CHOLESKY" not in abq
    # penalty stated: slope = 10 E*/h0 in MPa/mm
    slope = 10 * scene.hertz().e_star / m.h0 * 1e-9
    assert f"\n{slope:.12g}\n*CONTACT PAIR" in ccx


def test_problem_json_against_closed_forms(sphere, tmp_path):
    scene, _ = sphere
    _, paths = write_deck(scene, "calculix", tmp_path, units="mm", level=0)
    prob = json.loads(paths[1].read_text())
    e_star = 1 / (2 * (1 - 0.3**2) / 200e9)
    a = (3 * 800 * 0.01 / (4 * e_star)) ** (1 / 3)
    exp = prob["expected"]
    assert prob["units"] == {"length": "mm", "force": "N", "stress": "MPa"}
    assert exp["a"] == pytest.approx(a * 1e3, rel=1e-12)
    assert exp["b"] == pytest.approx(a * 1e3, rel=1e-12)
    assert exp["p0"] == pytest.approx(3 * 800 / (2 * math.pi * a**2) * 1e-6, rel=1e-12)
    assert exp["approach"] == pytest.approx(a**2 / 0.01 * 1e3, rel=1e-12)
    # von Mises maximum 0.6200 p0 at 0.4809 a below a circle (nu = 0.3), both bodies
    for body in (1, 2):
        assert exp[f"von_mises_max_body{body}"] / exp["p0"] == pytest.approx(0.6200, abs=1e-4)
        assert exp[f"von_mises_depth_body{body}"] / exp["a"] == pytest.approx(0.4809, abs=1e-4)
    assert prob["materials"]["body1"] == {"E": 200000.0, "nu": 0.3}
    assert prob["model"]["symmetry"] == "quarter" and prob["model"]["force_multiplier"] == 4
    assert prob["contact"]["slave"] == "CONTACT1"


@pytest.mark.parametrize("fmt", ["msh", "med", "exodus", "xdmf"])
def test_meshes_read_back_with_groups(blocks, tmp_path, fmt):
    meshio = pytest.importorskip("meshio")
    if fmt == "med":
        pytest.importorskip("h5py")
    if fmt == "exodus":
        pytest.importorskip("netCDF4")
    scene, _ = blocks
    m, paths = write_deck(scene, fmt, tmp_path, units="SI", level=0)
    mesh = meshio.read(paths[0])
    np.testing.assert_allclose(mesh.points, m.nodes, rtol=1e-12, atol=1e-15)
    tets = sum(len(c.data) for c in mesh.cells if c.type == "tetra10")
    assert tets == len(m.elements)
    n_contact = len(m.surfaces["CONTACT1"][0])
    if fmt == "msh":
        assert {"BODY1", "BODY2", "CONTACT1", "CONTACT2", "MOVED", "FIXED", "SYMX",
                "SYMY"} <= set(mesh.field_data)
        tag = mesh.field_data["CONTACT1"][0]
        assert sum(int(np.sum(d == tag)) for d in mesh.cell_data["gmsh:physical"]) == n_contact
    elif fmt == "med":
        names = {tuple(v)[0]: k for k, v in mesh.cell_tags.items()}
        assert {"BODY1", "CONTACT1", "SYMX"} <= set(names)
        tags = np.concatenate(mesh.cell_data["cell_tags"])
        assert np.sum(tags == names["CONTACT1"]) == n_contact
    elif fmt == "exodus":
        for name in ("MOVED", "FIXED", "SYMX", "SLAVE", "MASTER"):
            np.testing.assert_array_equal(np.sort(mesh.point_sets[name]), m.node_sets[name])
        import netCDF4
        with netCDF4.Dataset(paths[0]) as nc:
            names = list(netCDF4.chartostring(nc.variables["eb_names"][:]))
        assert names[:4] == ["BODY1", "BODY2", "CONTACT1", "CONTACT2"]
    else:
        for name in ("MOVED", "SLAVE", "SYMY"):
            np.testing.assert_array_equal(np.nonzero(mesh.point_data[name])[0],
                                          m.node_sets[name])
    assert json.loads(paths[1].read_text())["files"]["format"] == fmt


def test_face_numbering_matches_tetrahedra():
    """S1..S4 of C3D10: the faces opposite nodes 4, 3, 1, 2 (1-based), whose vertex triples'
    right-hand normals point into a positive tetrahedron."""
    p = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1.0]])
    centroid = p.mean(axis=0)
    for face in TET_FACES:
        v = p[list(face)]
        n = np.cross(v[1] - v[0], v[2] - v[0])
        assert n @ (v.mean(axis=0) - centroid) < 0
    assert [set(range(4)) - set(f) for f in TET_FACES] == [{3}, {2}, {0}, {1}]


def test_cli_deck(tmp_path, capsys):
    from fem_validation.__main__ import main

    scene = tmp_path / "s.toml"
    scene.write_text(SPHERE)
    assert main(["deck", "--scene", str(scene), "--format", "abaqus", "--out",
                 str(tmp_path / "o"), "--level", "0", "--units", "SI"]) == 0
    assert "wrote" in capsys.readouterr().out
    assert (tmp_path / "o" / "hertz.inp").is_file()
    assert main(["deck", "--scene", str(tmp_path / "nope.toml"), "--format", "calculix",
                 "--out", str(tmp_path / "p")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "nope.toml" in err
    assert main(["deck", "--scene", str(scene), "--format", "calculix", "--out",
                 str(tmp_path / "q"), "--level", "7"]) == 2
    assert "level must be one of" in capsys.readouterr().err
