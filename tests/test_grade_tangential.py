"""The tangential grader (fem_validation.grading.tangential), its result type, reader and CLI.

The synthetic results are written out here from the closed forms, independently of the
grader: Hertz's pressure, Cattaneo-Mindlin's traction mu p0 [sqrt(1 - r^2) - s sqrt(1 -
r^2/s^2)] with s = (1 - Q/(mu P))^(1/3), and a force-controlled path (ramp to Q*, down to
-Q*, up again) whose displacement follows Mindlin's virgin curve delta = 3 mu P/(2 k) [1 -
(1 - Q/(mu P))^(2/3)] and Masing's rule, with only k = Contact.tangential_stiffness taken
from the library (checked against Cerruti quadrature in tests/test_tangential.py).  The
grader inverts hertz.tangential_history by bisection at the displacements instead.

Mutation tests: the data built with mu, the stick-ratio exponent 1/3 or the no-slip
stiffness 1-2% off (the same as a reference that far off) fail the checks that look at them.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("scipy")

from fem_extra import require  # noqa: E402

require("skfem", "meshio", "matplotlib")

import fem_validation.grading.tangential as gt  # noqa: E402
import fem_validation.reports.tangential as rt  # noqa: E402
import hertz  # noqa: E402
from fem_validation.cli import grade as grade_cli  # noqa: E402
from fem_validation.readers.tangential_csv import read_tangential  # noqa: E402
from fem_validation.results.contact import ContactFrame, ResultError  # noqa: E402
from fem_validation.results.tangential import TangentialResult, path_reversals  # noqa: E402
from fem_validation.scenes import Scene, crossed_30deg, equal_steel  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
MU = 0.3
CHECKED = ("stick_a_rel_err", "stick_b_rel_err", "force_rel_err_max", "branch_err_max",
           "loop_energy_rel_err", "traction_rms_major", "traction_rms_minor")


def force_path(q_star, steps, reload_to=None):
    """0 -> Q* in `steps`, Q* -> -Q* and -Q* -> reload_to (default Q*) in 2 steps each."""
    reload_to = q_star if reload_to is None else reload_to
    up = np.linspace(0.0, q_star, steps + 1)
    down = np.linspace(q_star, -q_star, 2 * steps + 1)[1:]
    n_re = int(round(2 * steps * (reload_to + q_star) / (2 * q_star)))
    re = np.linspace(-q_star, reload_to, n_re + 1)[1:]
    return np.concatenate([up, down, re])


def masing_displacement(forces, limit, reach, exponent=1 / 3):
    """Displacements of a force path ramp -> one reversal -> another (and past the first
    reversal's force: the virgin curve again), Masing's rule written out."""
    def f(x):  # the odd virgin curve
        return np.sign(x) * reach * (1 - (1 - np.abs(x) / limit) ** (2 * exponent))

    rev = path_reversals(forces)
    out = np.empty_like(forces)
    q1 = forces[rev[0]] if rev else None
    q2 = forces[rev[1]] if len(rev) > 1 else None
    for i, q in enumerate(forces):
        if not rev or i <= rev[0]:
            out[i] = f(q)
        elif len(rev) < 2 or i <= rev[1]:
            out[i] = f(q1) - 2 * f((q1 - q) / 2)
        elif q <= q1:
            out[i] = f(q1) - 2 * f((q1 - q2) / 2) + 2 * f((q - q2) / 2)
        else:  # the loop has closed: back on the virgin curve (memory)
            out[i] = f(q)
    return out


def grid_triangles(nx, ny):
    """Two triangles per cell of an nx x ny grid of nodes (row-major in x)."""
    i, j = np.meshgrid(np.arange(nx - 1), np.arange(ny - 1), indexing="ij")
    a = (i * ny + j).ravel()
    b, c, d = a + ny, a + 1, a + ny + 1
    return np.concatenate([np.column_stack([a, b, d]), np.column_stack([a, d, c])])


def synthetic(scene, q_ratio=0.8, steps=16, h_over_b=0.05, symmetry="whole", axis="major",
              turn=0.0, mu_data=MU, exponent=1 / 3, stiffness=1.0, reload_to=None,
              forces=None, triangles=True, **kw):
    """A TangentialResult of exact Cattaneo-Mindlin / Masing data (see the module docstring).

    ``turn``: the model's coordinates are turned by this [rad] from the contact frame
    (body 1's x axis lies at ``turn`` from the model's x axis; the frame says so).
    ``mu_data``, ``exponent``, ``stiffness``: the data's own, to mutate them.
    """
    c = scene.hertz()
    P, theta = c.load, c.major_axis_angle
    along = 0.0 if axis == "major" else math.pi / 2
    direction = along + theta  # from the frame's x axis, body 1's
    limit = mu_data * P
    q_star = q_ratio * MU * P
    if forces is None:
        forces = force_path(q_star, steps, None if reload_to is None else reload_to * MU * P)
    k = c.tangential_stiffness(along) * stiffness
    disp = masing_displacement(forces, limit, 1.5 * limit / k, exponent)
    r = 1.5 * c.a
    h = h_over_b * c.b
    lo = {"whole": (-r, -r), "half": (-r, 0.0), "quarter": (0.0, 0.0)}[symmetry]
    xs, ys = np.arange(lo[0], r + 1e-9 * r, h), np.arange(lo[1], r + 1e-9 * r, h)
    x, y = (g.ravel() for g in np.meshgrid(xs, ys, indexing="ij"))
    t = theta  # the major axis's angle in the frame
    u, v = x * math.cos(t) + y * math.sin(t), -x * math.sin(t) + y * math.cos(t)
    r2 = (u / c.a) ** 2 + (v / c.b) ** 2
    p = c.p0 * np.sqrt(np.clip(1 - r2, 0.0, None))
    snap = path_reversals(forces)[0] if path_reversals(forces) else len(forces) - 1
    s = (1 - forces[snap] / limit) ** exponent
    inner = np.where(r2 < s * s, s * np.sqrt(np.clip(1 - r2 / (s * s), 0.0, None)), 0.0)
    q = mu_data * (p - c.p0 * inner)
    shear = np.column_stack([q * math.cos(direction), q * math.sin(direction)])
    frame = ContactFrame(x_axis=[math.cos(turn), math.sin(turn), 0.0])
    pts = np.column_stack([x, y, np.zeros_like(x)])
    pts = pts @ frame.rotation  # frame coordinates -> model coordinates
    args = dict(points=pts, pressure=p, shear=shear, normal_force=P, mu=MU,
                direction=direction, displacement=disp, force=forces, symmetry=symmetry,
                frame=frame, stick=(r2 < s * s) & (p > 0),
                triangles=grid_triangles(len(xs), len(ys)) if triangles else None)
    args.update(kw)
    return c, TangentialResult(**args)


# --- exact data -------------------------------------------------------------------------

CASES = [(equal_steel(1), "quarter", "major", 0.0), (equal_steel(3), "whole", "major", 0.0),
         (equal_steel(3), "quarter", "minor", 0.0), (equal_steel(3), "half", "major", 0.0),
         (equal_steel(10), "quarter", "major", 0.0),
         (crossed_30deg(), "whole", "minor", 0.4)]


@pytest.mark.parametrize("scene,symmetry,axis,turn", CASES)
def test_exact_data_is_graded_exact(scene, symmetry, axis, turn):
    """The stick fit and the force along the path are exact on exact data (observed below
    2e-15); the loop energy errs by the trapezoid rule's -1.1 / m^2 (m = 32 force steps per
    branch: -0.11%); the traction RMS is the linear interpolation across the kinks at the
    stick and contact edges, observed 0.07-1.34% of mu p0 at h = 0.05 b."""
    c, r = synthetic(scene, symmetry=symmetry, axis=axis, turn=turn,
                     h_over_b=0.05,
                     triangles=symmetry != "half")
    g = gt.grade_tangential(r, scene)
    m = g.metrics
    for name in ("stick_a_rel_err", "stick_b_rel_err", "force_rel_err_max", "branch_err_max"):
        assert abs(m[name]) < 1e-12, (name, m[name])
    assert -1.3e-3 < m["loop_energy_rel_err"] < -0.9e-3
    assert m["traction_rms_major"] < 0.02 and m["traction_rms_minor"] < 0.02
    assert m["transverse_shear_max"] < 1e-12
    assert abs(m["pressure_integral_rel_err"]) < 0.005
    assert abs(m["shear_integral_rel_err"]) < 0.01
    assert g.passed and not g.failed and not g.notes
    assert all(g.check(n).status == "pass" for n in CHECKED)
    # the stick fit reproduces Cattaneo-Mindlin's ellipse
    t = c.tangential(r.force[r.snapshot], MU, 0.0 if axis == "major" else math.pi / 2)
    assert g.reference["stick_a"] == t.stick_a
    assert g.fem["stick_fit"]["stick_a"] == pytest.approx(t.stick_a, rel=1e-12)


def test_trapezoid_error_of_the_loop_energy():
    """The loop energy of exact data by the trapezoid rule: -1.1 / m^2 with m equal force
    steps per branch (Q* = 0.8 mu P), second order: m = 8 -> -1.8%, 64 -> -0.03%."""
    scene = equal_steel(3)
    errors = {}
    for steps in (4, 32):
        _, r = synthetic(scene, symmetry="quarter", steps=steps, h_over_b=0.1)
        errors[2 * steps] = gt.grade_tangential(r, scene).metrics["loop_energy_rel_err"]
    assert errors[8] * 64 == pytest.approx(-1.14, abs=0.03)
    assert errors[64] * 64**2 == pytest.approx(-1.14, abs=0.03)


def test_reference_branches_are_the_fretting_loop():
    """masing_force inverts tangential_history; on a symmetric loop its branches are
    FrettingLoop.unloading and reloading, and its virgin curve the closed form."""
    c = equal_steel(3).hertz()
    limit = MU * c.load
    q_star = 0.7 * limit
    loop = c.fretting(q_star, MU, 0.0)
    forces = np.linspace(-q_star, q_star, 41)
    down = gt.masing_force(c, MU, 0.0, loop.unloading(forces), [q_star])
    up = gt.masing_force(c, MU, 0.0, loop.reloading(forces), [q_star, -q_star])
    assert np.abs(down - forces).max() < 1e-12 * q_star
    assert np.abs(up - forces).max() < 1e-12 * q_star
    k = c.tangential_stiffness(0.0)
    delta = np.linspace(0.0, 1.5 * limit / k, 30)  # up to the onset of sliding
    virgin = limit * (1 - (1 - delta * 2 * k / (3 * limit)) ** 1.5)
    assert np.abs(gt.masing_force(c, MU, 0.0, delta) - virgin).max() < 1e-12 * limit
    assert gt.masing_force(c, MU, 0.0, [2.0 * delta[-1]])[0] == pytest.approx(limit, rel=1e-15)


# --- mutations --------------------------------------------------------------------------

@pytest.mark.parametrize("q_ratio,mutation,failing", [
    (0.9, {"mu_data": MU * 1.02}, {"stick_a_rel_err", "stick_b_rel_err",
                                   "loop_energy_rel_err"}),
    (0.9, {"mu_data": MU * 0.99}, {"stick_a_rel_err", "stick_b_rel_err",
                                   "loop_energy_rel_err"}),
    (0.8, {"mu_data": MU * 1.02}, {"loop_energy_rel_err"}),
    (0.8, {"exponent": 1.02 / 3}, {"force_rel_err_max", "branch_err_max",
                                   "loop_energy_rel_err"}),
    (0.5, {"exponent": 1.02 / 3}, {"force_rel_err_max", "branch_err_max"}),
    (0.8, {"stiffness": 1.02}, {"force_rel_err_max", "branch_err_max"}),
    (0.8, {"stiffness": 0.98}, {"force_rel_err_max", "branch_err_max"}),
])
def test_a_wrong_reference_fails(q_ratio, mutation, failing):
    """Data made with mu 1-2% off, the stick-ratio exponent 1/3 2% off or the no-slip
    stiffness 2% off (as if the reference were that far off) fail exactly the checks that
    look at them (observed: mu +2% at Q* = 0.9 mu P: stick +4.5%, energy -6.9%; mu -1%:
    stick -2.6%, energy +3.8%; mu +2% at 0.8: energy -5.0% (stick +1.8% passes); exponent
    +2% at 0.8: force -1.9%, branches 1.03%, energy -3.1%; stiffness +-2%: force +-1.98%,
    branches 1.4%); the exact data pass (test_exact_data_is_graded_exact)."""
    scene = equal_steel(3)
    _, r = synthetic(scene, q_ratio=q_ratio, symmetry="quarter", h_over_b=0.06, **mutation)
    g = gt.grade_tangential(r, scene)
    assert not g.passed
    assert {c.name for c in g.checks if c.status == "fail"} == failing


def test_a_one_percent_error_fails_a_tighter_tolerance():
    """The stiffness 1% off gives a 0.99% force error (inside 1%), which a 0.5% tolerance
    fails; and a reference contact at a normal force 3% off fails the stick zone."""
    scene = equal_steel(3)
    _, r = synthetic(scene, symmetry="quarter", h_over_b=0.06, stiffness=1.01)
    g = gt.grade_tangential(r, scene)
    assert g.metrics["force_rel_err_max"] == pytest.approx(0.0099, abs=2e-4)
    tight = {**gt.DEFAULT_TOLERANCES, "force_rel_err_max": 0.005}
    assert gt.grade_tangential(r, scene, tight).check("force_rel_err_max").status == "fail"
    _, exact = synthetic(scene, q_ratio=0.9, symmetry="quarter", h_over_b=0.06)
    g = gt.grade_tangential(exact, scene, hertz_at=lambda load: scene.hertz(1.03 * load))
    assert not g.passed
    assert g.check("stick_a_rel_err").status == "fail"


def test_a_wrong_traction_fails_the_profiles():
    """The shear 8% too large everywhere fails both traction profiles (observed RMS 3.9%
    and 4.0% of mu p0 against 0.9% and 1.2% for the exact shear; it fails the stick zone
    too); a transverse shear of 5% of mu p0 is reported as information and fails nothing.
    (A 2% error in the shear raises the RMS from 0.9% to 1.3% (minor: 1.2% to 1.5%) of mu
    p0: the 3% tolerance, to be retuned from FEM runs, does not see it; mu, the exponent
    and the stiffness are caught by the other checks, test_a_wrong_reference_fails.)"""
    scene = equal_steel(3)
    c, r = synthetic(scene, symmetry="quarter", h_over_b=0.05)
    big = TangentialResult(**{**_fields(r), "shear": r.shear * 1.08})
    g = gt.grade_tangential(big, scene)
    assert g.check("traction_rms_major").status == "fail"
    assert g.check("traction_rms_minor").status == "fail"
    perp = np.array([-math.sin(r.direction), math.cos(r.direction)])
    across = r.shear + 0.05 * MU * r.pressure[:, None] * perp
    g = gt.grade_tangential(TangentialResult(**{**_fields(r), "shear": across}), scene)
    assert g.check("transverse_shear_max").status == "information"
    assert g.metrics["transverse_shear_max"] == pytest.approx(0.05, rel=1e-9)
    assert g.passed
    assert "coulomb" not in " ".join(gt.METRICS).lower()


def _fields(r):
    return {k: getattr(r, k) for k in ("points", "pressure", "shear", "normal_force", "mu",
                                       "direction", "displacement", "force", "snapshot",
                                       "symmetry", "frame", "triangles", "stick", "source",
                                       "details")}


# --- paths that hold less ---------------------------------------------------------------

def test_paths_that_hold_less_are_graded_as_far_as_they_go():
    """No reversal: the ramp and the stick zone only; one reversal: no loop energy; a
    reloading that stops short: no loop energy; one past the first reversal's displacement
    continues on the virgin curve and is graded so (exactly); each says why in the notes."""
    scene = equal_steel(3)
    c, full = synthetic(scene, symmetry="quarter", steps=8, h_over_b=0.08)
    k = len(full.force)

    def cut(n, **kw):
        return TangentialResult(**{**_fields(full), "displacement": full.displacement[:n],
                                   "force": full.force[:n], "snapshot": None, **kw})

    g = gt.grade_tangential(cut(9), scene)  # the ramp only
    assert g.passed and g.fem["reversals"] == []
    assert {n for n in CHECKED if g.check(n).status == "not available"} == {
        "branch_err_max", "loop_energy_rel_err"}
    assert "never turns back" in g.notes[0]
    g = gt.grade_tangential(cut(20), scene)  # ramp and part of the unloading
    assert abs(g.metrics["branch_err_max"]) < 1e-12
    assert g.check("loop_energy_rel_err").status == "not available"
    g = gt.grade_tangential(cut(k - 3), scene)  # the reloading stops short
    assert g.check("loop_energy_rel_err").status == "not available"
    assert any("not closed" in n for n in g.notes)
    _, past = synthetic(scene, symmetry="quarter", steps=8, h_over_b=0.08, reload_to=0.95)
    assert past.force.max() > full.force.max()
    g = gt.grade_tangential(past, scene)
    assert g.passed and abs(g.metrics["branch_err_max"]) < 1e-12
    # the same loop, its last segment cut at the first reversal's displacement
    assert -0.006 < g.metrics["loop_energy_rel_err"] < -0.003
    g = gt.grade_tangential(cut(k, snapshot=12), scene)  # a snapshot on the unloading
    assert g.check("stick_a_rel_err").status == "not available"
    assert any("after the first reversal" in n for n in g.notes)


def test_a_third_reversal_is_not_graded():
    scene = equal_steel(1)
    c, r = synthetic(scene, symmetry="quarter", steps=8, h_over_b=0.08)
    d = np.concatenate([r.displacement, r.displacement[-2:-5:-1]])
    q = np.concatenate([r.force, r.force[-2:-5:-1]])
    g = gt.grade_tangential(TangentialResult(**{**_fields(r), "displacement": d, "force": q}),
                            scene)
    assert g.passed and any("third time" in n for n in g.notes)
    assert g.path["branch"][-1] == "beyond"


# --- bad input --------------------------------------------------------------------------

def _bad(r, **kw):
    return {**_fields(r), **kw, "source": "run.csv"}


@pytest.mark.parametrize("change,words", [
    (lambda r: {"shear": np.where(np.arange(len(r.shear))[:, None] == 3, np.nan, r.shear)},
     ("run.csv", "'shear'", "non-finite", "(3, 0)")),
    (lambda r: {"shear": r.shear[:, 0]}, ("'shear'", "must have shape (121, 2)")),
    (lambda r: {"pressure": -r.pressure}, ("'pressure'", "empty")),
    (lambda r: {"mu": 0.0}, ("'mu'", "> 0", "0.0")),
    (lambda r: {"normal_force": math.nan}, ("'normal_force'", "nan")),
    (lambda r: {"direction": math.inf}, ("'direction'", "inf")),
    (lambda r: {"displacement": r.displacement + 1e-6}, ("'displacement'", "start at 0")),
    (lambda r: {"displacement": -r.displacement, "force": -r.force},
     ("'displacement'", "rise first", "index 1")),
    (lambda r: {"displacement": r.displacement[:1], "force": r.force[:1]},
     ("'displacement'", "2 or more")),
    (lambda r: {"force": r.force[:-1]}, ("'force'", "shape")),
    (lambda r: {"snapshot": 0}, ("'snapshot'", "1..", "got 0")),
    (lambda r: {"snapshot": 99}, ("'snapshot'", "got 99")),
    (lambda r: {"snapshot": True}, ("'snapshot'", "int")),
    (lambda r: {"symmetry": "eighth"}, ("'symmetry'", "eighth")),
    (lambda r: {"direction": r.direction + 0.3}, ("'direction'", "quarter", "frame axis")),
    (lambda r: {"stick": r.stick[:-1]}, ("'stick'", "shape")),
    (lambda r: {"triangles": r.triangles + len(r.points)}, ("'triangles'", "index")),
])
def test_bad_results_are_refused_naming_the_field(change, words):
    _, r = synthetic(equal_steel(1), symmetry="quarter", steps=4, h_over_b=0.15)
    with pytest.raises(ResultError) as err:
        TangentialResult(**_bad(r, **change(r)))
    for w in words:
        assert w in str(err.value), (w, str(err.value))


@pytest.mark.parametrize("change,words", [
    (lambda r: {"pressure": r.pressure * 1e6}, ("pressure integral", "factor")),
    (lambda r: {"force": r.force * 4}, ("exceeds mu P", "index")),
    (lambda r: {"symmetry": "whole"}, ("pressure integral",)),
    (lambda r: {"symmetry": "whole", "pressure": r.pressure * 4},
     ("does not match", "semi-major axis")),
])
def test_results_that_contradict_the_scene_are_bad_input(change, words):
    """Units, symmetry or a scene that does not match: a ResultError, not a failed grade.
    (The last: a scene with 4 times the radii at the same load, a 1.59 times larger.)"""
    scene = equal_steel(1)
    _, r = synthetic(scene, symmetry="quarter", steps=4, h_over_b=0.1)
    if "pressure" in change(r) and "symmetry" in change(r):
        ball = hertz.Body(0.04, 0.04, E=210e9, nu=0.3)
        scene = Scene("big", ball, ball, scene.load)
    with pytest.raises(ResultError) as err:
        gt.grade_tangential(TangentialResult(**_bad(r, **change(r))), scene)
    assert "run.csv" in str(err.value)
    for w in words:
        assert w in str(err.value), (w, str(err.value))


def test_bad_tolerances_are_refused():
    _, r = synthetic(equal_steel(1), symmetry="quarter", steps=4, h_over_b=0.15)
    with pytest.raises(ValueError, match="unknown metric 'a_rel_err'"):
        gt.grade_tangential(r, equal_steel(1), {"a_rel_err": 0.01})
    with pytest.raises(ValueError, match="stick_a_rel_err must be a finite number > 0"):
        gt.grade_tangential(r, equal_steel(1), {"stick_a_rel_err": -1.0})


# --- files, report, command line -------------------------------------------------------

SCENE_TOML = """name = "alpha 3"
load = {load!r}
[body1]
Rx = 0.01
Ry = 0.03
E = 210e9
nu = 0.3
[body2]
Rx = 0.01
Ry = 0.03
E = 210e9
nu = 0.3
"""


def write_csvs(tmp_path, r, units="SI", meta=True, quarter_forces=True, stick=True):
    """The result as the two CSV files of a quarter model (its own forces), SI or mm."""
    length, stress = (1e3, 1e-6) if units == "mm" else (1.0, 1.0)
    mult = r.multiplicity if quarter_forces else 1
    surface, history = tmp_path / "surface.csv", tmp_path / "history.csv"
    lines = []
    if meta:
        lines += [f"# mu = {r.mu!r}", f"# direction_deg = {math.degrees(r.direction)!r}",
                  f"# normal_force = {float(r.normal_force) / mult!r}", f"# units = {units}"]
    x_unit = "mm" if units == "mm" else "m"  # a column's unit must agree with the file's
    lines.append(f"x [{x_unit}],y,z,p,qx,qy" + (",stick" if stick else ""))
    for pt, p, q, s in zip(r.points, r.pressure, r.shear, r.stick, strict=True):
        row = [*(pt * length), p * stress, *(q * stress)] + ([int(s)] if stick else [])
        lines.append(",".join(repr(float(v)) for v in row))
    surface.write_text("\n".join(lines) + "\n")
    rows = [f"# units = {units}", "displacement,force"]
    rows += [f"{float(d) * length!r},{float(f) / mult!r}" for d, f in zip(r.displacement, r.force,
                                                             strict=True)]
    history.write_text("\n".join(rows) + "\n")
    return surface, history


def test_the_reader_gives_back_the_result(tmp_path):
    """SI and mm files give the same result: forces of the quarter model x4, frame and
    symmetry detected, shear in the frame; the grade equals the in-memory one."""
    scene = equal_steel(3)
    _, r = synthetic(scene, symmetry="quarter", steps=8, h_over_b=0.08, triangles=False)
    g0 = gt.grade_tangential(r, scene)
    for units in ("SI", "mm"):
        (tmp_path / units).mkdir()
        s, h = write_csvs(tmp_path / units, r, units)
        back = read_tangential(s, h)
        assert back.symmetry == "quarter" and back.frame.is_standard
        assert back.normal_force == pytest.approx(r.normal_force, rel=1e-14)
        np.testing.assert_allclose(back.force, r.force, rtol=1e-14, atol=1e-14 * r.force.max())
        np.testing.assert_allclose(back.shear, r.shear, rtol=1e-12, atol=1e-6)
        np.testing.assert_allclose(back.displacement, r.displacement, rtol=1e-12, atol=1e-20)
        assert back.direction == pytest.approx(r.direction, abs=1e-15)
        np.testing.assert_array_equal(back.stick, r.stick)
        g = gt.grade_tangential(back, scene)
        for name in CHECKED:
            assert g.metrics[name] == pytest.approx(g0.metrics[name], rel=1e-6, abs=1e-12)


def test_the_report_files(tmp_path):
    """grade.json is strict JSON holding every metric and check with its meaning; grade.md
    names the verdict, every check and the notes; grade.png is written."""
    scene = equal_steel(3)
    _, r = synthetic(scene, symmetry="quarter", steps=8, h_over_b=0.08, mu_data=MU * 1.02,
                     q_ratio=0.9)
    g = gt.grade_tangential(r, scene)
    paths = rt.write_grade(g, tmp_path, "python -m fem_validation grade ...")
    row = json.loads(paths[0].read_text(), parse_constant=lambda c: pytest.fail(c))
    assert row["passed"] is False and row["kind"] == "tangential"
    assert {c["name"] for c in row["checks"]} == set(gt.METRICS)
    assert all(c["meaning"] for c in row["checks"])
    assert row["stick_a_rel_err"] == pytest.approx(g.metrics["stick_a_rel_err"])
    md = paths[1].read_text()
    assert "FAILED" in md and "stick_a_rel_err" in md and "| information |" in md
    assert "by construction" in md  # the Coulomb condition is said not to be a check
    assert paths[2].stat().st_size > 10_000


def test_command_line(tmp_path, capsys):
    """Exit 0 on exact data, 1 with mu 2% off (--mu), 2 with one line for bad input."""
    scene = equal_steel(3)
    c, r = synthetic(scene, symmetry="quarter", steps=8, h_over_b=0.08, q_ratio=0.9)
    toml = tmp_path / "scene.toml"
    toml.write_text(SCENE_TOML.format(load=c.load))
    s, h = write_csvs(tmp_path, r)
    base = ["--tangential", str(s), "--history", str(h), "--scene", str(toml)]
    assert grade_cli.main(base + ["--out", str(tmp_path / "ok")]) == 0
    assert capsys.readouterr().out.startswith("PASSED")
    assert (tmp_path / "ok" / "grade.png").is_file()
    assert grade_cli.main(base + ["--mu", str(MU * 0.98), "--out", str(tmp_path / "f")]) == 1
    assert "stick_a_rel_err" in capsys.readouterr().out
    bare, hb = write_csvs(tmp_path / "f", r, meta=False)
    ok = ["--tangential", str(bare), "--history", str(hb), "--scene", str(toml),
          "--mu", str(MU), "--direction-deg", str(math.degrees(r.direction)),
          "--symmetry", "quarter", "--out", str(tmp_path / "bare")]
    assert grade_cli.main(ok) == 0  # the normal force from the scene
    capsys.readouterr()
    bad = [(["--tangential", str(s), "--scene", str(toml)], "--history"),
           (base + ["--force", "3"], "--force"),
           (base + ["--mu", "-1"], "--mu"),
           (base + ["--snapshot", "0"], "--snapshot"),
           (base + ["--tolerance", "a_rel_err=0.1"], "a_rel_err"),
           (["--tangential", str(bare), "--history", str(hb), "--scene", str(toml)], "mu"),
           (base + ["--normal-force", "1e6"], "pressure integral"),
           (["--tangential", str(h), "--history", str(h), "--scene", str(toml)], "column"),
           ([str(s), "--scene", str(toml), "--mu", "0.3"], "only apply to --tangential")]
    for argv, word in bad:
        assert grade_cli.main(argv + ["--out", str(tmp_path / "bad")]) == 2, argv
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and word in err, (argv, err)


def test_python_m_fem_validation_grade_tangential(tmp_path):
    """The documented command, end to end in a subprocess."""
    scene = equal_steel(3)
    c, r = synthetic(scene, symmetry="quarter", steps=8, h_over_b=0.1)
    toml = tmp_path / "scene.toml"
    toml.write_text(SCENE_TOML.format(load=c.load))
    s, h = write_csvs(tmp_path, r)
    run = subprocess.run([sys.executable, "-m", "fem_validation", "grade", "--tangential",
                          str(s), "--history", str(h), "--scene", str(toml), "--out",
                          str(tmp_path / "out")], capture_output=True, text=True, cwd=ROOT,
                         timeout=300)
    assert run.returncode == 0, run.stderr
    assert json.loads((tmp_path / "out" / "grade.json").read_text())["passed"] is True


def test_docstring_examples():
    """The modules' examples run (pytest's --doctest-modules covers hertz/ only)."""
    import doctest

    import fem_validation.results.tangential as tr

    for module in (gt, tr):
        failures, tried = doctest.testmod(module, optionflags=doctest.ELLIPSIS)
        assert tried > 0 and failures == 0, module.__name__
