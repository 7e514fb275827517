"""Hostile scenes for the deck writer and the meshes behind it (issue 22, items 5 and 11).

* A target load of 0 ended in a ZeroDivisionError; a load of 1e-300 N, or E = 1e300 Pa on
  both bodies, made gmsh mesh until it was killed (~23 GB): the contact, 1e-103 of the
  ball's radius, was far below gmsh's tolerance.  Such scenes, and meshes whose estimated
  size exceeds the cap, are refused before gmsh runs (the ``no_gmsh`` fixture makes any
  gmsh call fail the test, so a test cannot pass by meshing, nor hang).
* The scene's name went into hertz.inp verbatim: a name holding a line break and
  ``*INCLUDE, INPUT=...`` wrote a live keyword line.
"""

from __future__ import annotations

import dataclasses
import json
import math
import re

import numpy as np
import pytest

import hertz

pytest.importorskip("gmsh")
pytest.importorskip("skfem")

from fem_validation.decks.inp import write_inp  # noqa: E402
from fem_validation.decks.meshes import write_mesh, write_problem  # noqa: E402
from fem_validation.decks.model import (  # noqa: E402
    build_model,  # noqa: E402
    check_scene,  # noqa: E402
)
from fem_validation.scenes import Scene, equal_steel  # noqa: E402
from fem_validation.solvers import curved_mesh, mesh  # noqa: E402

E, NU, R = 200e9, 0.3, 0.01
BALL = hertz.Body(R, R, E, NU)
PLANE = hertz.Body(math.inf, math.inf, E, NU)
ELLIPSOID = hertz.Body(0.008, 0.02, 210e9, 0.3)
CYLINDER = hertz.Body(0.03, math.inf, 110e9, 0.34)


def _e_star(e1, nu1, e2, nu2):
    return 1.0 / ((1 - nu1 ** 2) / e1 + (1 - nu2 ** 2) / e2)


def _sphere_plane_load(a_over_r: float) -> float:
    """Hertz's closed form for a ball on a plane: a**3 = 3 P R / (4 E*)."""
    return 4 * _e_star(E, NU, E, NU) * (a_over_r * R) ** 3 / (3 * R)


@pytest.fixture
def no_gmsh(monkeypatch):
    """Any call into gmsh fails the test: the guards must refuse before meshing."""
    import gmsh

    def refuse(*args, **kwargs):
        raise AssertionError("gmsh ran")

    monkeypatch.setattr(gmsh, "initialize", refuse)


@pytest.mark.parametrize("load", [0.0, -1.0, math.nan, math.inf])
def test_target_load_must_be_positive(no_gmsh, load):
    """load = 0 ended in a ZeroDivisionError in block_extent."""
    for body2 in (PLANE, CYLINDER):
        scene = Scene("zero", BALL if body2 is PLANE else ELLIPSOID, body2, load)
        with pytest.raises(ValueError, match=r"^scene 'zero': load must be a finite number "
                                             r"> 0 \[N\].*got " + re.escape(repr(load))):
            build_model(scene, 0)


@pytest.mark.parametrize("body1, body2, load", [
    (BALL, PLANE, 1e-300),                                     # issue's reproducer
    (hertz.Body(R, R, 1e300, NU), hertz.Body(math.inf, math.inf, 1e300, NU), 800.0),
    (ELLIPSOID, CYLINDER, 1e-300),                             # paraboloid-faced blocks
    (BALL, PLANE, _sphere_plane_load(0.5e-5)),                 # just below the range
])
def test_tiny_contact_refused_before_meshing(no_gmsh, body1, body2, load):
    scene = Scene("tiny", body1, body2, load)
    for model in ("auto", "whole", "half"):
        with pytest.raises(ValueError, match=r"^scene 'tiny': the contact is too small for "
                                             r"the meshes: .* a/R_min >= 1e-05"):
            build_model(scene, 0, model)


def test_contact_size_range_ends():
    """The range's lower end, 1e-5 R, against Hertz's closed form for a ball on a plane."""
    ok = Scene("ok", BALL, PLANE, _sphere_plane_load(1.01e-5))
    assert check_scene(ok).a / R == pytest.approx(1.01e-5, rel=1e-9)
    with pytest.raises(ValueError, match="too small"):
        check_scene(Scene("low", BALL, PLANE, _sphere_plane_load(0.99e-5)))
    # the blocks' upper end: a <= 0.0375 R_min (a larger contact on a ball in a groove of
    # another material, so no true-geometry model)
    soft = hertz.Body(math.inf, math.inf, 70e9, 0.33)
    big = Scene("big", BALL, soft, 4 * _e_star(E, NU, 70e9, 0.33) * (0.04 * R) ** 3 / (3 * R))
    with pytest.raises(ValueError, match=r"too large for the radii.*a/R_min <= 0.0375"):
        build_model(big, 0)


def test_curved_lower_end_meshes():
    """The smallest a/R allowed meshes (the limit is not a guess at gmsh's tolerance)."""
    m = curved_mesh.build_curved(curved_mesh.sphere_plane(curved_mesh.MIN_A_OVER_R), 0)
    assert min(b.p.shape[1] for b in m.bodies) > 100 and len(m.slave) >= 10


@pytest.mark.parametrize("a_over_r", [1e-100, 0.99e-5, 0.0, math.nan])
def test_curved_scene_range(no_gmsh, a_over_r):
    """The validation's curved scenes (--curved --a-over-r) share the cause."""
    with pytest.raises(ValueError, match=r"^a_over_r must be in \[1e-05, 0.5\]"):
        curved_mesh.sphere_plane(a_over_r)


def test_mesh_node_estimate_against_gmsh():
    """estimate_nodes within a factor 2 of gmsh's count, for a round and an elongated contact."""
    for scene in (equal_steel(1), equal_steel(100)):
        params = mesh.mesh_parameters(scene, 0)
        built = mesh.build(scene, 0)
        count = sum(b.p.shape[1] for b in built.bodies) - len(built.pairs)
        assert 0.5 < mesh.estimate_nodes(params) / count < 2.0


def test_huge_mesh_refused_before_meshing(no_gmsh):
    """A needle-like contact at the finest level: refused, naming the count and the cap."""
    needle = Scene("needle", hertz.Body(0.01, 100.0, E, NU), PLANE, 1e-3)  # a/b = 242
    with pytest.raises(ValueError, match=r"^scene 'needle' at level 4: the blocks' mesh "
                                         r"would have about .* vertices, more than the 2e\+06"):
        build_model(needle, 4)
    # the validation's own meshes share the check: alpha = 1000 at level 5 (4 million)
    with pytest.raises(ValueError, match="vertices, more than"):
        mesh.build(equal_steel(1000), 5)


@pytest.mark.parametrize("factor", [math.inf, math.nan, 0.0, -1.0, "10", True])
def test_penalty_factor_refused_before_meshing(no_gmsh, factor):
    """--penalty-factor inf was accepted: the deck said inf, problem.json Infinity."""
    with pytest.raises(ValueError, match=r"^penalty_factor must be a finite number > 0"):
        build_model(Scene("ball", BALL, PLANE, 800.0), 0, penalty_factor=factor)


HOSTILE = ["ball\n*INCLUDE, INPUT=/etc/passwd", "x\r*STEP\r\n*END STEP",
           "a\u2028*INCLUDE, INPUT=y", "*HEADING", "** *\t*", "\x00\x1b[31m\x7f",
           "Kugel \u00f8 10 mm", "n" * 500]


@pytest.fixture(scope="module")
def ball_model():
    return build_model(Scene("benign", BALL, PLANE, 800.0), 0)


def _keyword_lines(text):
    return [ln for ln in text.splitlines() if ln.startswith("*") and not ln.startswith("**")]


@pytest.mark.parametrize("dialect", ["calculix", "abaqus"])
def test_hostile_name_writes_no_keyword(ball_model, tmp_path, dialect):
    """No line of the deck other than its own keyword lines starts with '*', whatever the
    name or the command line; problem.json stays valid JSON and keeps the name."""
    write_inp(ball_model, tmp_path / "benign.inp", dialect=dialect, command="deck")
    benign = (tmp_path / "benign.inp").read_text()
    for k, name in enumerate(HOSTILE):
        model = dataclasses.replace(ball_model, scene=dataclasses.replace(ball_model.scene,
                                                                          name=name))
        path = tmp_path / f"{k}.inp"
        write_inp(model, path, dialect=dialect, command=f"deck --out '{name}'")
        raw = path.read_bytes()
        assert all(32 <= c < 127 or c == 10 for c in raw), name  # printable ASCII lines
        text = raw.decode("ascii")
        assert _keyword_lines(text) == _keyword_lines(benign), name
        assert len(text.splitlines()) == len(benign.splitlines()), name
        assert max(len(ln) for ln in text.splitlines()[:2]) <= 120
        out = tmp_path / f"p{k}"
        out.mkdir()
        problem = json.loads(write_problem(model, out, command=name).read_text(),
                             parse_constant=lambda c: pytest.fail(f"{c} in problem.json"))
        assert problem["scene"]["name"] == name and problem["command"] == name


def test_hostile_name_meshes_stay_valid(ball_model, tmp_path):
    meshio = pytest.importorskip("meshio")
    model = dataclasses.replace(ball_model, scene=dataclasses.replace(ball_model.scene,
                                                                      name=HOSTILE[0]))
    path = write_mesh(model, tmp_path, "msh")
    back = meshio.read(path)
    np.testing.assert_allclose(back.points, model.nodes * 1e3)
    assert set(back.field_data) >= {"BODY1", "BODY2", "CONTACT1", "CONTACT2"}

