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

from scene_files import ball_on_plane

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
    big = Scene("big", BALL, soft, 4 * _e_star(E, NU, 70e9, 0.33) * (0.21 * R) ** 3 / (3 * R))
    with pytest.raises(ValueError, match=r"too large for the radii.*a/R_min <= 0.2 "):
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



# --- audit finding 16: options that wrote an unrunnable or meaningless deck ----------------

BALL_TOML = ball_on_plane("ball", 100.0)


@pytest.mark.parametrize("options, option, message", [
    # *STATIC increments of 5e-10 (5e-6) under *STEP, INC=1000: ccx cannot finish
    (["--friction", "0.3", "--friction-increments", "1000000000"], "--friction-increments",
     r"friction increments must be an integer from 1 to 100 .*got 1000000000"),
    (["--friction", "0.3", "--friction-increments", "100000"], "--friction-increments",
     r"from 1 to 100 .*got 100000"),
    (["--friction", "0.3", "--friction-increments", "1" * 5000], "--friction-increments",
     r"at most 18 digits"),
    # a penalty slope of 6.7e-318 MPa/mm
    (["--penalty-factor", "5e-324"], "--penalty-factor",
     r"penalty_factor must be a finite number > 0 in \[0\.1, 1e\+06\] .*got 5e-324"),
    (["--penalty-factor", "1e7"], "--penalty-factor", r"in \[0\.1, 1e\+06\].*got 10000000"),
    # *FRICTION 4.9e-324
    (["--friction", "5e-324"], "--friction", r"mu must be a finite number in \[0\.001, 10\] "
                                             r".*got 5e-324"),
    (["--friction", "1e300"], "--friction", r"in \[0\.001, 10\].*got 1e\+300"),
    # peak_displacement 0.0
    (["--friction", "0.3", "--friction-ratio", "5e-324"], "--friction-ratio",
     r"friction ratio must be in \(0, 1\), at least 0\.001 .*got 5e-324"),
    (["--level", "-1"], "--level", r"level must be >= 0.*got -1"),
    (["--level", "5"], "", r"level must be one of \[0, 1, 2, 3, 4\] .*sphere-plane.*got 5"),
    (["--level", "9" * 5000], "--level", r"at most 18 digits"),
    (["--friction", "0.3", "--model", "quarter"], "", r"half or whole model"),
])
def test_deck_options_out_of_range_refused_in_one_line(no_gmsh, capsys, tmp_path, options,
                                                       option, message):
    """One line naming the option, the range and the value, exit 2, and no --out folder:
    every option is checked before anything is meshed or written."""
    from fem_validation.__main__ import main

    scene = tmp_path / "ball.toml"
    scene.write_text(BALL_TOML)
    out = tmp_path / "deck"
    assert main(["deck", "--scene", str(scene), "--format", "calculix", "--out", str(out),
                 *options]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and len(err) < 400, err
    assert re.search(message, err), err
    assert f"argument {option}:" in err if option else "level" in err or "model" in err
    assert not out.exists()


@pytest.fixture(scope="module")
def half_ball():
    return build_model(Scene("half", BALL, PLANE, 100.0), 0, "half")


def test_friction_options_range_in_the_api(half_ball):
    """friction_path (and write_deck through check_deck) refuses what the CLI refuses."""
    from fem_validation.decks.inp import MAX_FRICTION_INCREMENTS, friction_path

    for kwargs, message in [({"mu": 5e-324}, r"^mu must be a finite number in \[0\.001, 10\]"),
                            ({"mu": 11.0}, r"^mu must be"),
                            ({"mu": True}, r"^mu must be"),
                            ({"ratio": 5e-324}, r"^friction ratio must be in \(0, 1\), at "
                                                r"least 0\.001"),
                            ({"ratio": 1.0}, r"^friction ratio"),
                            ({"increments": 10 ** 9}, r"^friction increments must be an "
                                                      r"integer from 1 to 100"),
                            ({"increments": MAX_FRICTION_INCREMENTS + 1}, r"from 1 to 100")]:
        args = {"mu": 0.3, "ratio": 0.8, "increments": 2, **kwargs}
        with pytest.raises(ValueError, match=message):
            friction_path(half_ball, args["mu"], args["ratio"], args["increments"])
    # the range's ends write a runnable path: a positive peak, increments INC holds
    for mu, ratio in ((1e-3, 1e-3), (10.0, 0.999)):
        fp = friction_path(half_ball, mu, ratio, MAX_FRICTION_INCREMENTS)
        assert math.isfinite(fp.peak) and fp.peak > 0


def test_friction_increments_fit_the_step(half_ball, tmp_path):
    """The largest ramp writes increments every *STEP's INC holds (ccx stops at INC)."""
    from fem_validation.decks.inp import (
        FRICTION_STEP_INC,
        MAX_FRICTION_INCREMENTS,
        friction_path,
    )

    assert 2 * MAX_FRICTION_INCREMENTS + 1 <= FRICTION_STEP_INC
    path = tmp_path / "f.inp"
    write_inp(half_ball, path, friction=friction_path(half_ball, 0.3, 0.8,
                                                      MAX_FRICTION_INCREMENTS))
    steps = re.findall(r"\*STEP, INC=(\d+)\n\*STATIC, DIRECT\n([^,]+), 1\.", path.read_text())
    assert len(steps) == 3
    for inc, dt in steps:
        assert 1 / float(dt) <= int(inc) + 1e-9
    # a FrictionPath built by hand past the cap is refused, not written
    fp = dataclasses.replace(friction_path(half_ball, 0.3), increments=10 ** 6)
    with pytest.raises(ValueError, match=r"at most 499 .*INC=1000"):
        write_inp(half_ball, tmp_path / "g.inp", friction=fp)
    assert not (tmp_path / "g.inp").exists()


@pytest.mark.parametrize("factor", [5e-324, 0.09, 1.01e6, 1e300])
def test_penalty_factor_range(no_gmsh, factor):
    with pytest.raises(ValueError, match=r"^penalty_factor must be a finite number > 0 in "
                                         r"\[0\.1, 1e\+06\]"):
        build_model(Scene("ball", BALL, PLANE, 800.0), 0, penalty_factor=factor)


def test_write_deck_checks_before_meshing(no_gmsh, tmp_path):
    """write_deck's own checks (the API path) run before gmsh and before --out is made."""
    from fem_validation.decks import write_deck

    scene = Scene("ball", BALL, PLANE, 100.0)
    for kwargs, message in [({"level": 5}, r"^level must be one of \[0, 1, 2, 3, 4\]"),
                            ({"level": 6, "model": "whole"}, r"^level must be one of \[0, 1, "
                                                             r"2, 3, 4, 5\]"),
                            ({"level": True}, r"^level must be"),
                            ({"friction": 0.3, "friction_increments": 10 ** 9},
                             r"^friction increments"),
                            ({"friction": 5e-324}, r"^mu must be"),
                            ({"penalty_factor": 5e-324}, r"^penalty_factor")]:
        with pytest.raises(ValueError, match=message):
            write_deck(scene, "calculix", tmp_path / "d", **kwargs)
        assert not (tmp_path / "d").exists()
