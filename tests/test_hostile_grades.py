"""Hostile input to the graders (issue 22's audit, findings 7, 8, 9, 11 and 14): finite but
extreme numbers are refused in one line naming the file and what is out of range, or graded
to finite numbers; grade.json is strict JSON; no raw warning reaches stderr; a --tolerances
file with an over-long integer names the file, the line and the key.

Each test is built from the audit's reproducer and failed before its fix (a
ZeroDivisionError, Infinity in grade.json, dozens of warning lines, a message without the
file).
"""

from __future__ import annotations

import copy
import dataclasses
import json
import math
import shutil
import warnings
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("scipy")

from fem_extra import require  # noqa: E402

require("skfem", "meshio", "matplotlib")

from test_grade_tangential import SCENE_TOML, synthetic, write_csvs  # noqa: E402
from test_hostile_frd import CUBES_SCENE, DATA  # noqa: E402

import fem_validation.grading.contact as fg  # noqa: E402
import fem_validation.grading.tangential as gt  # noqa: E402
import hertz  # noqa: E402
from fem_validation.cli import grade as grade_cli  # noqa: E402
from fem_validation.cli.common import EXIT_FAILED, EXIT_USAGE, guarded  # noqa: E402
from fem_validation.reports.grade import grade_json  # noqa: E402
from fem_validation.results.contact import ContactResult, ResultError  # noqa: E402
from fem_validation.scenes import Scene, equal_steel  # noqa: E402

BALL = Scene("ball on plane", hertz.Body.sphere(0.01, E=210e9, nu=0.3),
             hertz.Body.plane(E=210e9, nu=0.3), 1000.0)
BALL_TOML = ('name = "ball"\nload = 1000.0\n[body1]\nRx = 0.01\nRy = 0.01\nE = 210e9\n'
             'nu = 0.3\n[body2]\nRx = "inf"\nRy = "inf"\nE = 210e9\nnu = 0.3\n')


def grade(argv) -> int:
    """``python -m fem_validation grade ARGV`` in this process; no Python warning may escape
    it (pytest would otherwise collect what reached stderr in a real run)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        status = grade_cli.main([str(a) for a in argv])
    assert [f"{w.category.__name__}: {w.message}" for w in caught] == []
    return status


def strict_json(path: Path) -> dict:
    """grade.json read as strict JSON: NaN or Infinity fail the test."""
    return json.loads(path.read_text(), parse_constant=lambda c: pytest.fail(f"{c} in {path}"))


def one_line(capsys, *words) -> str:
    """stderr holds exactly one line, with every word in it; stdout is ignored."""
    err = capsys.readouterr().err
    assert err.count("\n") == 1, err
    for word in words:
        assert word in err, (word, err)
    return err


def silent(capsys) -> str:
    """Nothing on stderr (no warning); stdout returned."""
    captured = capsys.readouterr()
    assert captured.err == "", captured.err
    return captured.out


# --- finding 7: a tangential history scaled by 1e-300 ------------------------------------

@pytest.fixture(scope="module")
def friction_files(tmp_path_factory):
    """docs/howto/grade-friction.md's files: exact Cattaneo-Mindlin data, a quarter model."""
    tmp = tmp_path_factory.mktemp("friction")
    scene = equal_steel(3)
    c, r = synthetic(scene, symmetry="quarter", steps=8, h_over_b=0.1, q_ratio=0.8)
    toml = tmp / "scene.toml"
    toml.write_text(SCENE_TOML.format(load=c.load))
    surface, history = write_csvs(tmp, r)
    return scene, r, surface, history, toml


def test_history_scaled_by_1e_minus_300_is_refused_naming_the_history(friction_files, tmp_path,
                                                                     capsys):
    """Both columns x 1e-300: Mindlin's loop energy underflowed to 0 and the grade divided
    by it (ZeroDivisionError, exit 3).  Now: exit 2, one line naming the history file."""
    _, _, surface, history, toml = friction_files
    lines = history.read_text().splitlines()
    rows = [",".join(repr(float(v) * 1e-300) for v in line.split(","))
            for line in lines[2:]]
    tiny = tmp_path / "history.csv"
    tiny.write_text("\n".join([*lines[:2], *rows]) + "\n")
    argv = ["--tangential", str(surface), "--history", str(tiny), "--scene", str(toml),
            "--out", str(tmp_path / "g")]
    assert grade(argv) == EXIT_USAGE
    one_line(capsys, str(tiny), "too small", "mu P")


@pytest.mark.parametrize("factor", [1e-300, 1e-9])
def test_tiny_tangential_forces_are_refused_by_the_grader(friction_files, factor):
    """The Python API: a ResultError, not a ZeroDivisionError."""
    scene, r, *_ = friction_files
    small = dataclasses.replace(r, force=r.force * factor, displacement=r.displacement * factor,
                                details={"history": "h.csv"})
    with pytest.raises(ResultError, match="h.csv: the tangential force never exceeds"):
        gt.grade_tangential(small, scene)


def test_mu_out_of_range_is_refused_without_warnings(friction_files, tmp_path, capsys):
    """--mu 1e300 (or '# mu = 1e300'): mu p overflowed in the stick fit (RuntimeWarnings,
    then exit 1).  Now one line, saying mu."""
    _, _, surface, history, toml = friction_files
    for mu in ("1e300", "1e308"):
        argv = ["--tangential", str(surface), "--history", str(history), "--scene", str(toml),
                "--mu", mu, "--out", str(tmp_path / "g")]
        assert grade(argv) == EXIT_USAGE
        one_line(capsys, "mu")


# --- finding 8: an approach of 1e308 from problem.json -----------------------------------

PROBLEM = {"units": {"length": "mm", "force": "N", "stress": "MPa"},
           "frame": {"origin": [0.0, 0.0, 1.0], "normal_into_body1": [0.0, 0.0, 1.0],
                     "body1_x_axis": [1.0, 0.0, 0.0]},
           "model": {"geometry": "two cubes", "level": 0, "far_face_depths": [1.0, 1.0]},
           "loads": {"approach": 0.01},
           "materials": {"body1": {"E": 210000.0, "nu": 0.3},
                         "body2": {"E": 210000.0, "nu": 0.3}},
           "contact": {"slave": "CONTACT1", "penalty_factor": 1.0}}


def test_approach_1e308_is_refused_not_infinity(tmp_path, capsys):
    """loads.approach = 1e308 (mm): approach_rel_err was Infinity in grade.json (exit 1).
    Now exit 2, one line naming the .frd and the approach; a sane approach still grades."""
    run = tmp_path / "run"
    run.mkdir()
    shutil.copy(DATA / "tet_cubes.frd", run / "hertz.frd")
    shutil.copy(DATA / "tet_cubes.inp", run / "hertz.inp")
    scene = tmp_path / "scene.toml"
    scene.write_text(CUBES_SCENE)
    problem = copy.deepcopy(PROBLEM)
    problem["loads"]["approach"] = 1e308
    (run / "problem.json").write_text(json.dumps(problem))
    argv = [str(run / "hertz.frd"), "--scene", str(scene), "--out", str(tmp_path / "g")]
    assert grade(argv) == EXIT_USAGE
    one_line(capsys, str(run / "hertz.frd"), "approach", "out of range")
    problem["loads"]["approach"] = 0.01
    (run / "problem.json").write_text(json.dumps(problem))
    assert grade(argv + ["--overwrite"]) in (0, EXIT_FAILED)
    silent(capsys)
    row = strict_json(tmp_path / "g" / "grade.json")
    assert math.isfinite(row["approach_rel_err"])


def test_approach_out_of_range_python_api():
    """The grader itself refuses an approach whose ratio to Hertz's overflows."""
    c = BALL.hertz()
    xs = np.arange(0.0, 1.5 * c.a, 0.05 * c.a)
    x, y = (g.ravel() for g in np.meshgrid(xs, xs, indexing="ij"))
    p = c.pressure(x, y)
    kw = dict(points=np.column_stack([x, y, 0 * x]), pressure=p, force=c.load,
              symmetry="quarter", source="run.csv")
    assert math.isfinite(fg.grade(ContactResult(**kw, approach=c.delta), BALL).approach_rel_err)
    with pytest.raises(ResultError, match="run.csv: the approach 1e[+]305 m is out of range"):
        fg.grade(ContactResult(**kw, approach=1e305), BALL)


# --- finding 9 (and 11): a force-approach curve with extreme finite values ----------------

def tutorial_curve():
    """A DEM contact of the ball: Hertz's law, 20 points from 1 um."""
    delta = np.linspace(1e-6, 2e-5, 20)
    e_star = 1 / (2 * (1 - 0.3**2) / 210e9)
    return delta, 4 / 3 * e_star * math.sqrt(0.01) * delta**1.5 * 1.03


@pytest.mark.parametrize("label,transform,outcome", [
    ("approach x1e300", lambda d, f: (d * 1e300, f), "overflows"),
    ("force x1e300", lambda d, f: (d, f * 1e300), EXIT_FAILED),
    ("force 1.7e308", lambda d, f: (d, np.full_like(f, 1.7e308)), "beyond the range"),
    ("both x1e-300", lambda d, f: (d * 1e-300, f * 1e-300), "underflows"),
    ("approach x1e-318", lambda d, f: (d * 1e-318, f), "underflows"),
    ("approach in mm", lambda d, f: (d * 1e3, f), EXIT_FAILED),
])
def test_extreme_force_approach_curves(tmp_path, capsys, label, transform, outcome):
    """Each gave Infinity or NaN in grade.json and 4 to 42 raw warning lines (exit 1).  Now
    either exit 2 with one line naming the file and what is out of range, or a grade of
    finite numbers in strict JSON (exit 1: the checks fail) with nothing on stderr."""
    d, f = transform(*tutorial_curve())
    curve = tmp_path / "curve.csv"
    curve.write_text("approach,force\n" + "".join(f"{float(a)!r},{float(b)!r}\n"
                                                  for a, b in zip(d, f, strict=True)))
    scene = tmp_path / "ball.toml"
    scene.write_text(BALL_TOML)
    status = grade(["--force-approach", str(curve), "--scene", str(scene),
                             "--out", str(tmp_path / "g")])
    if isinstance(outcome, str):
        assert status == EXIT_USAGE, label
        one_line(capsys, str(curve), outcome)
    else:
        assert status == outcome, label
        silent(capsys)
        row = strict_json(tmp_path / "g" / "grade.json")
        assert all(math.isfinite(row[k]) for k in fg.CURVE_METRICS)


def test_force_approach_evaluates_hertz_once_and_notes_its_validity():
    """An overlap in mm read as metres: hertz.contact warned once per row (38 lines on
    stderr).  Now no warning; the grade's notes hold Hertz's validity message once."""
    d, f = tutorial_curve()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        g = fg.grade_force_approach(d * 1e3, f, BALL)
    assert [str(w.message) for w in caught] == []
    assert len(g.notes) == 1 and g.notes[0].startswith("Hertz's validity: ")
    assert "lengths in mm read as m" in g.hint
    assert g.to_dict()["notes"] == list(g.notes)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        g = fg.grade_force_approach(d, f, BALL)
    assert caught == [] and g.notes == ()
    assert math.isfinite(g.force_rel_err_rms)


def test_validity_note_reaches_the_grade_files(tmp_path, capsys):
    """The CLI prints one line on stdout and nothing on stderr; grade.json and grade.md
    carry the note."""
    d, f = tutorial_curve()
    curve = tmp_path / "curve.csv"
    curve.write_text("overlap,force\n" + "".join(f"{float(a) * 1e3!r},{float(b)!r}\n"
                                                 for a, b in zip(d, f, strict=True)))
    scene = tmp_path / "ball.toml"
    scene.write_text(BALL_TOML)
    assert grade(["--force-approach", str(curve), "--scene", str(scene),
                           "--out", str(tmp_path / "g")]) == EXIT_FAILED
    assert silent(capsys).count("\n") == 1
    row = strict_json(tmp_path / "g" / "grade.json")
    assert row["notes"] and row["notes"][0].startswith("Hertz's validity")
    assert "## Notes" in (tmp_path / "g" / "grade.md").read_text()


# --- finding 11: other warnings that leaked ----------------------------------------------

def test_scene_load_1e300_grades_without_warnings(tmp_path, capsys):
    """A scene whose own load is 1e300 (not the force graded): 2 warning lines, exit 0."""
    c = BALL.hertz()
    xs = np.arange(0.0, 1.5 * c.a, 0.05 * c.a)
    x, y = (g.ravel() for g in np.meshgrid(xs, xs, indexing="ij"))
    result = tmp_path / "result.csv"
    result.write_text(f"# force = {c.load / 4!r}\n# symmetry = quarter\nx,y,p\n" + "".join(
        f"{float(a)!r},{float(b)!r},{float(p)!r}\n"
        for a, b, p in zip(x, y, c.pressure(x, y), strict=True)))
    scene = tmp_path / "s.toml"
    scene.write_text(BALL_TOML.replace("load = 1000.0", "load = 1e300"))
    assert grade([str(result), "--scene", str(scene), "--out",
                           str(tmp_path / "g")]) == 0
    silent(capsys)
    for force in ("1e308",):  # --force 1e308: refused, one line (it was 3)
        assert grade([str(result), "--scene", str(scene), "--force", force,
                               "--out", str(tmp_path / "g")]) == EXIT_USAGE
        one_line(capsys, str(result))


def test_contact_grade_notes_hertz_validity_instead_of_warning():
    """grade(): Hertz at the result's force evaluated quietly, the validity in notes."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        c, notes = fg.hertz_quietly(BALL.hertz, 1e12)
    assert caught == [] and len(notes) == 1 and "Hertz's validity" in notes[0]
    assert c.load == 1e12


def test_guarded_holds_stray_warnings_to_one_line(capsys):
    """The backstop: any warning left becomes at most one `warning:` line after a run;
    after an error, only the error's line."""
    def body(_):
        for k in range(5):
            warnings.warn(f"stray {k}", RuntimeWarning, stacklevel=1)
        print("done")
        return 0

    assert guarded("cmd", body, []) == 0
    captured = capsys.readouterr()
    assert captured.out == "done\n"
    assert captured.err == "cmd: warning: RuntimeWarning: stray 0 (and 4 more warning(s))\n"

    def failing(_):
        warnings.warn("stray", RuntimeWarning, stacklevel=1)
        raise ValueError("bad input")

    assert guarded("cmd", failing, []) == EXIT_USAGE
    assert capsys.readouterr().err == "cmd: error: bad input\n"


def test_grade_json_is_strict():
    """A non-finite number reaching grade.json is a defect (exit 3), never written."""
    assert json.loads(grade_json({"a": None, "b": 1.0})) == {"a": None, "b": 1.0}
    with pytest.raises(RuntimeError, match="non-finite"):
        grade_json({"a": math.inf})
    with pytest.raises(RuntimeError, match="non-finite"):
        grade_json({"a": [math.nan]})


# --- finding 14: a --tolerances file with an over-long integer ----------------------------

@pytest.mark.parametrize("value,words", [
    ("9" * 5000, ["line 2", "a_rel_err", "5000 digits"]),
    ("1" + "0" * 400, ["a_rel_err", "finite number > 0"]),
])
def test_tolerances_file_with_a_huge_integer(tmp_path, capsys, value, words):
    """5000 digits: 'Exceeds the limit (4300 digits)...' without the file; 400 digits:
    an OverflowError (exit 3).  Now one line naming the file (and line, key)."""
    tol = tmp_path / "tol.toml"
    tol.write_text(f"# tolerances\na_rel_err = {value}\n")
    scene = tmp_path / "ball.toml"
    scene.write_text(BALL_TOML)
    argv = [str(tmp_path / "nowhere.csv"), "--scene", str(scene), "--tolerances", str(tol),
            "--out", str(tmp_path / "g")]
    assert grade(argv) == EXIT_USAGE
    one_line(capsys, str(tol), *words)


def test_tolerances_python_api_huge_integer():
    """The Python API: a ValueError naming the key (an OverflowError before)."""
    with pytest.raises(ValueError, match="force_rel_err_max must be a finite number > 0, "
                                         "got an integer of about 401 digits"):
        fg.grade_force_approach(*tutorial_curve(), BALL, {"force_rel_err_max": 10**400})
