"""The graders say when a result looks off by a power of 1000 (issue 22 item 12).

Each result here is Hertz's own contact (the pressure p0 sqrt(1 - r^2/a^2) on a grid,
Hertz's law F = (4/3) E* sqrt(R) delta^(3/2), Cattaneo-Mindlin's tractions of
tests/test_grade_tangential.py) with one unit mistake made on purpose: lengths, pressures
or forces multiplied by 1000, a file in mm, N, MPa read as SI, a DEM overlap in mm read as
metres.  The hint must name the quantity that was scaled; the exact result and one 2% off
(a poor model, not a unit mistake) must get none.
"""

import doctest
import json
import math
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("scipy")

import fem_validation.grading.contact as fg  # noqa: E402
import fem_validation.grading.tangential as gt  # noqa: E402
import fem_validation.reports.tangential as rt  # noqa: E402
import hertz  # noqa: E402
from fem_validation.reports import grade as grade_files  # noqa: E402
from fem_validation.results.contact import ContactResult, ResultError  # noqa: E402
from fem_validation.results.tangential import TangentialResult  # noqa: E402
from fem_validation.scenes import Scene, equal_steel  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
BALL = Scene("ball on plane", hertz.Body.sphere(0.01, E=210e9, nu=0.3),
             hertz.Body.plane(E=210e9, nu=0.3), 100.0)
E_STAR = 1 / (2 * (1 - 0.3**2) / 210e9)  # the ball's contact modulus, written out


@pytest.fixture(autouse=True)
def _quiet():
    """A result graded at 1000 times its force has a/R far above Hertz's range: the
    validity warning is expected, not the subject here."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        yield


def hertz_result(length=1.0, pressure=1.0, force=1.0, nodal_forces=False):
    """The ball's contact as a quarter model, Hertz's pressure on a grid, its lengths,
    pressures and force multiplied by the factors given (a unit mistake)."""
    a = (3 * BALL.load * 0.01 / (4 * E_STAR)) ** (1 / 3)  # Hertz's radius, written out
    p0 = 3 * BALL.load / (2 * math.pi * a * a)
    xs = np.arange(0.0, 1.5 * a, 0.04 * a)
    x, y = (g.ravel() for g in np.meshgrid(xs, xs, indexing="ij"))
    p = p0 * np.sqrt(np.clip(1 - (x * x + y * y) / (a * a), 0.0, None))
    pts = np.column_stack([x, y, np.zeros_like(x)])
    kw = {}
    if nodal_forces:
        f = p * fg.lumped_area(pts[:, :2], fg.surface_triangles(pts[:, :2]))
        kw["normal_force"] = f * force
    return ContactResult(points=pts * length, pressure=p * pressure, force=BALL.load * force,
                         symmetry="quarter", source="/some/where/run.csv", **kw)


# --- the detector --------------------------------------------------------------------------

def test_detector_names_each_mistake_and_nothing_else():
    """Ratios as a unit mistake scales them (a ~ L / F^(1/3), p0 ~ S / F^(1/3), the pressure
    integral over the force S L^2 / F, F(delta) ~ F / L^1.5)."""
    hint = fg.unit_hint
    assert "--units mm" in hint([("semi_axes", 1e3), ("peak_pressure", 1e-6),
                                 ("pressure_integral", 1.0)])
    assert "pressures 1000x too large" in hint([("semi_axes", 1.0), ("peak_pressure", 1e3),
                                                ("pressure_integral", 1e3)])
    assert "lengths in mm read as m" in hint([("semi_axes", 1e3), ("peak_pressure", 1.0),
                                              ("pressure_integral", 1e6)])
    assert "forces 1000x too large" in hint([("semi_axes", 0.1), ("peak_pressure", 0.1),
                                             ("pressure_integral", 1e-3)])
    assert "lengths in mm read as m" in hint([("curve_force", 1e3 ** -1.5)])
    # a scene whose E was typed in GPa: Hertz's a is 1000x, p0 1e-6x the model's
    assert "E in GPa" in hint([("semi_axes", 1e-3), ("peak_pressure", 1e6)])
    # without the approach, a file in SI read as mm looks the same: both are named
    both = hint([("semi_axes", 1e-3), ("peak_pressure", 1e6)])
    assert "read as mm, N, MPa" in both and "; or " in both
    for ok in (1.0, 1.02, 0.98, 1.3, 0.5, 50.0):
        assert hint([("semi_axes", ok), ("peak_pressure", ok)]) == "", ok
        assert hint([("curve_force", ok)]) == "", ok
    assert hint([("semi_axes", math.nan), ("peak_pressure", 0.0)]) == ""


def test_docstring_examples():
    failures, tried = doctest.testmod(fg, optionflags=doctest.ELLIPSIS)
    assert tried > 0 and failures == 0


# --- a contact result ------------------------------------------------------------------------

@pytest.mark.parametrize("scale", [1.0, 1.02, 0.98])
def test_a_right_or_two_percent_off_result_gets_no_hint(tmp_path, scale):
    g = fg.grade(hertz_result(pressure=scale, nodal_forces=True), BALL)
    assert g.hint == "" and g.to_dict()["hint"] == ""
    assert g.summary in ("PASSED", "FAILED: p0_rel_err")
    g = fg.grade(hertz_result(length=scale), BALL)
    assert g.hint == ""
    grade_files.write_grade(g, tmp_path)
    assert "units?" not in (tmp_path / "grade.md").read_text()


def test_pressure_1000x_is_graded_with_the_hint(tmp_path):
    """Nodal forces right, pressures 1000x (kPa written where MPa is read): the grade
    fails on p0 and says why, in the grade, grade.json, grade.md and the summary line."""
    g = fg.grade(hertz_result(pressure=1e3, nodal_forces=True), BALL)
    assert not g.passed and g.check("p0_rel_err").status == "fail"
    assert "pressures 1000x too large" in g.hint
    assert g.hint in g.summary and g.summary.startswith("FAILED: p0_rel_err")
    grade_files.write_grade(g, tmp_path)
    assert json.loads((tmp_path / "grade.json").read_text())["hint"] == g.hint
    assert g.hint in (tmp_path / "grade.md").read_text()


@pytest.mark.parametrize("scaling,words", [
    ({"pressure": 1e3}, "pressures 1000x too large"),
    ({"pressure": 1e-3}, "pressures 1/1000"),
    ({"length": 1e3}, "lengths in mm read as m"),
    ({"length": 1e-3}, "lengths in m read as mm"),
    ({"force": 1e3}, "forces 1000x too large"),
    ({"force": 1e-3}, "forces 1/1000"),
    ({"length": 1e3, "pressure": 1e-6}, "a file in mm, N, MPa read as SI"),
])
def test_a_result_off_by_1000_is_refused_with_the_hint(scaling, words):
    """The result contradicts itself or the scene (bad input, one line): the line ends
    with the hint naming what was scaled."""
    with pytest.raises(ResultError) as err:
        fg.grade(hertz_result(**scaling), BALL)
    message = str(err.value)
    assert words in message and "units?" in message, message
    assert "\n" not in message and message.startswith("/some/where/run.csv: ")


# --- a force-approach curve -------------------------------------------------------------

def curve():
    delta = np.linspace(1e-7, 5e-6, 40)
    return delta, 4 / 3 * E_STAR * math.sqrt(0.01) * delta**1.5


@pytest.mark.parametrize("d_scale,f_scale,words", [
    (1e3, 1.0, "lengths in mm read as m"),
    (1.0, 1e3, "forces 1000x too large"),
    (1.0, 1e-3, "forces 1/1000"),
    (1.0, 1.0, ""),
    (1.0, 1.02, ""),
    (1.0, 0.98, ""),
])
def test_force_approach_names_the_unit(d_scale, f_scale, words):
    """An overlap in mm read as metres gives forces 1000^-1.5 of Hertz's at the approach
    read: the fitted scale of Hertz's law says so."""
    delta, force = curve()
    g = fg.grade_force_approach(delta * d_scale, force * f_scale, BALL)
    assert g.fem["scale_of_hertz_law"] == pytest.approx(f_scale / d_scale**1.5, rel=1e-9)
    if words:
        assert not g.passed and words in g.hint and g.hint in g.summary
    else:
        assert g.hint == ""


def test_force_approach_of_a_scene_in_gpa():
    """E typed in GPa in the scene: Hertz's force is 1e-9 of the curve's."""
    gpa = Scene("GPa", hertz.Body.sphere(0.01, E=210.0, nu=0.3),
                hertz.Body.plane(E=210.0, nu=0.3), 100.0)
    g = fg.grade_force_approach(*curve(), gpa)
    assert "E in GPa" in g.hint


def test_cli_dem_csv_in_mm_read_as_metres(tmp_path):
    """The issue's reproducer: a DEM CSV whose overlap is in mm, without a units line,
    graded at -100%: grade.json and grade.md now say why."""
    delta, force = curve()
    path = tmp_path / "dem.csv"
    rows = "".join(f"{float(d) * 1e3!r},{float(f)!r}\n" for d, f in zip(delta, force,
                                                                          strict=True))
    path.write_text("overlap,force\n" + rows)
    scene = tmp_path / "ball.toml"
    scene.write_text('name = "ball"\nload = 100.0\n[body1]\nRx = 0.01\nRy = 0.01\n'
                     'E = 210e9\nnu = 0.3\n[body2]\nRx = "inf"\nRy = "inf"\nE = 210e9\n'
                     'nu = 0.3\n')
    done = subprocess.run([sys.executable, "-m", "fem_validation", "grade", "--force-approach",
                           str(path), "--scene", str(scene), "--out", str(tmp_path / "o")],
                          capture_output=True, text=True, timeout=300, cwd=tmp_path,
                          env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin",
                               "MPLBACKEND": "Agg", "HOME": str(tmp_path)})
    assert done.returncode == 1, done.stderr
    row = json.loads((tmp_path / "o" / "grade.json").read_text())
    assert row["force_rel_err_max"] < -0.99
    assert "lengths in mm read as m" in row["hint"]
    assert row["hint"] in (tmp_path / "o" / "grade.md").read_text()


# --- a frictional result ---------------------------------------------------------------

def tangential(pressure=1.0, displacement=1.0):
    """Cattaneo-Mindlin's exact data (tests/test_grade_tangential.py's synthetic), the
    pressure or the displacement path scaled."""
    sys.path.insert(0, str(Path(__file__).parent))
    from test_grade_tangential import _fields, synthetic

    _, r = synthetic(equal_steel(1), symmetry="quarter", steps=6, h_over_b=0.1)
    fields = _fields(r)
    fields.update(pressure=r.pressure * pressure, shear=r.shear * pressure,
                  displacement=r.displacement * displacement, source="run.csv")
    return TangentialResult(**fields)


@pytest.mark.parametrize("scale", [1.0, 1.02])
def test_tangential_right_or_two_percent_off_gets_no_hint(scale):
    g = gt.grade_tangential(tangential(displacement=scale), equal_steel(1))
    assert g.hint == "" and g.to_dict()["hint"] == ""


def test_tangential_pressure_1000x_is_refused_with_the_hint():
    with pytest.raises(ResultError) as err:
        gt.grade_tangential(tangential(pressure=1e3), equal_steel(1))
    assert "pressures 1000x too large" in str(err.value), str(err.value)


def test_tangential_displacement_1000x_is_graded_with_the_hint(tmp_path):
    """The history's displacement in mm read as metres, the surface right: no single unit
    explains it, so the hint names the displacement itself."""
    g = gt.grade_tangential(tangential(displacement=1e3), equal_steel(1))
    assert not g.passed
    assert "tangential displacement at the first reversal 1000x" in g.hint
    assert g.hint in g.summary
    rt.write_grade(g, tmp_path)
    assert g.hint in (tmp_path / "grade.md").read_text()
