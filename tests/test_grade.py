"""The one grader (fem_validation.grading.contact), its result type, readers and command line.

References are independent of the grader: Hertz's pressure p0 sqrt(1 - x^2/a^2 - y^2/b^2)
evaluated on meshes made here, Hertz's law F = (4/3) E* sqrt(R) delta^(3/2) in closed form
for a sphere, and hand-built files.  Mutation tests: a 1.5% error in the reference or in the
result must fail the checks that look at it.
"""

from __future__ import annotations

import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from scene_files import ball_on_plane

meshio = pytest.importorskip("meshio", reason="needs the fem extra (meshio)")
pytest.importorskip("scipy")

import fem_validation.grading.contact as fg  # noqa: E402
import hertz  # noqa: E402
from fem_validation.readers import read_result  # noqa: E402
from fem_validation.results.contact import (  # noqa: E402
    BodyStress,
    ContactFrame,
    ContactResult,
    ResultError,
    stress_from_voigt,
)
from fem_validation.scenes import Scene, crossed_30deg, equal_steel, scene_from_toml  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
STEEL = {"E": 210e9, "nu": 0.3}
BALL_TOML = ball_on_plane("ball on plane", 100.0)


def exact_pressure(c, x, y):
    """Hertz's pressure at model coordinates (x along body 1's x axis), written out here."""
    t = c.major_axis_angle
    u, v = x * math.cos(t) + y * math.sin(t), -x * math.sin(t) + y * math.cos(t)
    return c.p0 * np.sqrt(np.clip(1 - (u / c.a) ** 2 - (v / c.b) ** 2, 0.0, None))


def grid(c, h_over_b, quarter, extent=1.5):
    r = extent * c.a
    xs = np.arange(0.0 if quarter else -r, r + 1e-12 * r, h_over_b * c.b)
    x, y = (g.ravel() for g in np.meshgrid(xs, xs, indexing="ij"))
    return np.column_stack([x, y, np.zeros_like(x)])


def synthetic(scene, h_over_b=0.04, quarter=False, load=None, **kw):
    c = scene.hertz(load)
    pts = grid(c, h_over_b, quarter)
    p = exact_pressure(c, pts[:, 0], pts[:, 1])
    return c, ContactResult(points=pts, pressure=p, force=c.load,
                            symmetry="quarter" if quarter else "whole", **kw)


class Scaled:
    """A Hertz contact with one attribute scaled (a deliberately wrong reference)."""

    def __init__(self, contact, **scales):
        self._c, self._s = contact, scales

    def __getattr__(self, name):
        value = getattr(self._c, name)
        return value * self._s[name] if name in self._s else value


# --- the grade on exact Hertz data ------------------------------------------------------

@pytest.mark.parametrize("scene,quarter", [(equal_steel(3), False), (equal_steel(3), True),
                                           (crossed_30deg(), False)])
def test_exact_hertz_pressure_is_graded_exact(scene, quarter):
    """a, b, p0 of the p^2 fit are exact on exact data (observed < 1e-12); the profile RMS
    is the linear interpolation of the square-root edge, observed 0.51-0.95% of p0 at
    h = 0.025 b; the pressure integral 0.02%."""
    c, r = synthetic(scene, quarter=quarter)
    g = fg.grade(r, scene)
    assert g.semi_axes == "fit"
    for k in ("a_rel_err", "b_rel_err", "p0_rel_err"):
        assert abs(g.metrics[k]) < 1e-9, (k, g.metrics[k])
    assert g.metrics["rms_major"] < 0.015 and g.metrics["rms_minor"] < 0.015
    assert abs(g.metrics["pressure_integral_rel_err"]) < 0.001
    assert g.passed and not g.failed
    if quarter:
        assert g.check("angle_err_deg").status == "by construction"
    else:
        assert abs(g.metrics["angle_err_deg"]) < 1e-6


def test_moments_of_exact_nodal_forces():
    """Nodal forces = exact pressure x lumped area: the moment ellipse is within 0.05%
    (observed 0.03% at h = 0.025 b: the lumping's quadrature), and 'auto' uses it."""
    scene = equal_steel(3)
    c, r = synthetic(scene)
    f = r.pressure * fg.lumped_area(r.xy, fg.surface_triangles(r.xy))
    r2 = ContactResult(points=r.points, normal_force=f, force=f.sum())
    g = fg.grade(r2, scene)
    assert g.semi_axes == "moments"
    assert abs(g.metrics["a_rel_err"]) < 5e-4 and abs(g.metrics["b_rel_err"]) < 5e-4
    assert g.check("pressure_integral_rel_err").status == "by construction"


@pytest.mark.parametrize("name,scale", [("a", 1.015), ("b", 0.985), ("p0", 1.025)])
def test_a_wrong_reference_fails(name, scale):
    """Mutation: Hertz's a, b (1.5%) or p0 (2.5%, its tolerance is 2%) wrong fails that
    check with the default tolerances, and a 1% error fails a 0.5% tolerance."""
    scene = equal_steel(3)
    _, r = synthetic(scene)
    g = fg.grade(r, scene, hertz_at=lambda load: Scaled(scene.hertz(load), **{name: scale}))
    assert not g.passed
    assert g.check(f"{name}_rel_err").status == "fail"
    small = {name: 1 + (scale - 1) / abs(scale - 1) * 0.01}
    tight = {f"{name}_rel_err": 0.005}
    g = fg.grade(r, scene, tight, hertz_at=lambda load: Scaled(scene.hertz(load), **small))
    assert g.check(f"{name}_rel_err").status == "fail"


def test_a_wrong_result_fails():
    """Mutation of the result: the pressed region 1.5% too wide in x fails a; the
    pressure 2.5% too high fails p0 (and the pressure integral); the true data pass."""
    scene = equal_steel(1)
    c, r = synthetic(scene, quarter=True)
    wide = ContactResult(points=r.points * [1.015, 1.015, 1.0], pressure=r.pressure,
                         force=c.load, symmetry="quarter")
    g = fg.grade(wide, scene)
    assert g.check("a_rel_err").status == "fail"
    assert abs(g.metrics["a_rel_err"] - 0.015) < 1e-9
    high = ContactResult(points=r.points, pressure=r.pressure * 1.025, force=c.load,
                         symmetry="quarter")
    g = fg.grade(high, scene)
    assert g.check("p0_rel_err").status == "fail"
    assert g.check("pressure_integral_rel_err").status == "fail"


def test_smeared_edge_is_information_not_a_failure():
    """Pressure spread past the edge (as CalculiX's): a tail p0 * 0.15 (1 - (r - 1)/0.1)
    out to 1.1 a.  The p^2 fit stays within 0.5%, the edge of the pressed region is >5% too
    large and is reported as information; the second moments are biased by the tail."""
    scene = equal_steel(1)
    c = scene.hertz()
    pts = grid(c, 0.02, True)
    rr = np.hypot(pts[:, 0], pts[:, 1]) / c.a
    p = exact_pressure(c, pts[:, 0], pts[:, 1])
    tail = (rr > 0.98) & (rr < 1.1)
    p[tail] = np.maximum(p[tail], 0.15 * c.p0 * (1 - (rr[tail] - 1) / 0.1).clip(0, 1))
    r = ContactResult(points=pts, pressure=p, force=c.load, symmetry="quarter")
    g = fg.grade(r, scene)
    assert abs(g.metrics["a_rel_err"]) < 0.005 and abs(g.metrics["p0_rel_err"]) < 0.005
    assert g.metrics["edge_a_rel_err"] > 0.05
    assert g.check("edge_a_rel_err").status == "information"
    assert g.metrics["a_moments_rel_err"] > g.metrics["a_fit_rel_err"]


def test_approach_and_reaction():
    scene = equal_steel(1)
    c, r = synthetic(scene)
    from dataclasses import replace

    g = fg.grade(replace(r, approach=c.delta * 1.03, reaction=c.load), scene)
    assert g.check("approach_rel_err").status == "fail"
    assert abs(g.metrics["approach_rel_err"] - 0.03) < 1e-12
    assert g.check("reaction_rel_err").status == "information"


def test_frame_turns_a_result_into_the_contact_plane():
    """The same exact data rotated and moved (normal along -x, say) and given its frame
    grade as the original: a, b, p0 and the angle agree to 1e-9."""
    scene = crossed_30deg()
    c, r = synthetic(scene, h_over_b=0.04)
    rot = np.array([[0.0, 0.0, -1.0], [0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])  # rows: new axes
    origin = np.array([0.1, -0.2, 0.3])
    moved = r.points @ rot + origin
    frame = ContactFrame(origin=origin, normal=rot[2], x_axis=rot[0])
    tri = fg.surface_triangles(r.xy)  # a regular grid's Delaunay ties: the same triangles
    g0 = fg.grade(ContactResult(points=r.points, pressure=r.pressure, force=r.force,
                                triangles=tri), scene)
    g1 = fg.grade(ContactResult(points=moved, pressure=r.pressure, force=r.force, frame=frame,
                                triangles=tri), scene)
    for k in ("a_rel_err", "b_rel_err", "p0_rel_err", "angle_err_deg", "rms_major"):
        assert g1.metrics[k] == pytest.approx(g0.metrics[k], abs=1e-9)


# --- stresses ---------------------------------------------------------------------------

def block_mesh(c, quarter=True, n=(14, 14, 41)):
    """Tetrahedra of a box below the contact (body 2, z <= 0): graded towards the axis
    across, 0.075 b apart in depth (the axis von Mises peak is a parabola through them)."""
    from scipy.spatial import Delaunay

    s = np.linspace(0.0, 1.0, n[0]) ** 1.5
    xs = 2.5 * c.a * s if quarter else 2.5 * c.a * np.concatenate([-s[:0:-1], s])
    zs = -3.0 * c.b * np.linspace(0.0, 1.0, n[2])
    x, y, z = (g.ravel() for g in np.meshgrid(xs, xs, zs, indexing="ij"))
    pts = np.column_stack([x, y, z])
    return pts, Delaunay(pts).simplices


def test_exact_stress_field_is_graded_close():
    """Hertz's own stress at the nodes of a tetrahedral box: the axis von Mises peak is
    within 0.3% (observed 0.1%: the parabola through nodes), its depth within 3%; a stress
    scaled by 1.015 fails a 0.5% von Mises tolerance."""
    scene = equal_steel(1)
    c, r = synthetic(scene, quarter=True)
    pts, tets = block_mesh(c)
    sig = c.stress(pts[:, 0], pts[:, 1], -pts[:, 2], body=2)
    sig = sig * np.array([1, 1, -1])[:, None] * np.array([1, 1, -1])[None, :]  # z -> -depth
    st = BodyStress(body=2, points=pts, stress=sig, tetrahedra=tets)
    from dataclasses import replace

    g = fg.grade(replace(r, stress=(st,)), scene)
    assert abs(g.metrics["von_mises_rel_err"]) < 0.003, g.stress
    assert abs(g.metrics["z_von_mises_rel_err"]) < 0.03
    assert g.metrics["stress_rms_axis"] < 0.01
    wrong = replace(r, stress=(BodyStress(body=2, points=pts, stress=sig * 1.015,
                                          tetrahedra=tets),))
    g = fg.grade(wrong, scene, {"von_mises_rel_err": 0.005})
    assert g.check("von_mises_rel_err").status == "fail"


def test_stress_from_voigt():
    s = stress_from_voigt([[1, 2, 3, 4, 5, 6]], "xx yy zz xy yz xz")[0]
    assert s[0, 1] == s[1, 0] == 4 and s[1, 2] == 5 and s[0, 2] == 6
    with pytest.raises(ValueError, match="permutation"):
        stress_from_voigt([[1, 2, 3, 4, 5, 6]], "xx yy zz xy yz zz")


# --- the result type refuses bad input ----------------------------------------------------

@pytest.mark.parametrize("change,match", [
    ({"points": np.zeros((5, 2))}, r"'points' must have shape \(n, 3\)"),
    ({"force": -1.0}, "'force' must be a finite number > 0"),
    ({"force": float("nan")}, "'force'"),
    ({"pressure": None}, "no contact pressure and no nodal contact force"),
    ({"pressure": np.zeros(5)}, "contact is empty"),
    ({"pressure": np.array([1.0, np.nan, 1.0, 1.0, 1.0])}, r"'pressure'.*index 1"),
    ({"pressure": np.ones(4)}, r"'pressure' must have shape"),
    ({"symmetry": "eighth"}, "'symmetry' must be one of"),
    ({"triangles": [[0, 1, 7]]}, "'triangles' must index the 5 points"),
])
def test_result_names_the_bad_field(change, match):
    args = {"points": np.random.default_rng(0).random((5, 3)), "pressure": np.ones(5),
            "force": 1.0, "source": "model.vtu", **change}
    with pytest.raises(ResultError, match=match) as info:
        ContactResult(**args)
    assert "model.vtu" in str(info.value)


def test_frame_must_be_orthogonal():
    with pytest.raises(ResultError, match="x_axis"):
        ContactFrame(normal=[0, 0, 1], x_axis=[0, 1, 1])


def test_units_and_symmetry_that_contradict_the_force_are_bad_input():
    scene = equal_steel(1)
    c, r = synthetic(scene, quarter=True)
    for force in (c.load * 1e6, c.load / 4):  # MPa read as Pa; a quarter model's own force
        with pytest.raises(ResultError, match="disagree by a factor"):
            fg.grade(ContactResult(points=r.points, pressure=r.pressure, force=force,
                                   symmetry="quarter", source="q.csv"), scene)
    with pytest.raises(ResultError, match="disagree"):  # quarter data called whole
        fg.grade(ContactResult(points=r.points, pressure=r.pressure, force=c.load), scene)


def test_a_scene_that_does_not_match_is_bad_input():
    """The ball's result graded against a ball ten times larger (Hertz's a 2.15 times
    larger): no model of that scene is 50% off in a, so the scene does not match."""
    scene = equal_steel(1)
    _, r = synthetic(scene, quarter=True)
    big = Scene("big", hertz.Body(0.1, 0.1, **STEEL), hertz.Body(0.1, 0.1, **STEEL), 1.0)
    with pytest.raises(ResultError, match="scene does not match"):
        fg.grade(r, big)


# --- readers: round trips ----------------------------------------------------------------

@pytest.fixture
def ball(tmp_path):
    path = tmp_path / "ball.toml"
    path.write_text(BALL_TOML)
    return scene_from_toml(path), path


def write_csv(path, pts, p, header="x [mm],y [mm],p [MPa]", meta=("# force = 25", "# units = mm"),
              scale=(1e3, 1e-6)):
    lines = list(meta) + [header]
    lines += [f"{x * scale[0]:.12g},{y * scale[0]:.12g},{q * scale[1]:.12g}"
              for (x, y, _), q in zip(pts, p, strict=True)]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_csv_round_trip_in_mm(ball, tmp_path):
    """A quarter model in mm, N, MPa with its own force (25 N of 100 N): the symmetry is
    detected, the force multiplied by 4, the units converted; same grade as in SI."""
    scene, _ = ball
    c, r = synthetic(scene, quarter=True, load=100.0)
    res = read_result(write_csv(tmp_path / "q.csv", r.points, r.pressure))
    assert res.symmetry == "quarter" and res.force == pytest.approx(100.0)
    np.testing.assert_allclose(res.points, r.points, rtol=1e-11, atol=1e-18)
    g0, g1 = fg.grade(r, scene), fg.grade(res, scene)
    for k in ("a_rel_err", "b_rel_err", "p0_rel_err", "rms_major"):
        assert g1.metrics[k] == pytest.approx(g0.metrics[k], abs=1e-9)


def test_frame_is_found_for_a_tilted_offset_surface(ball, tmp_path):
    """The ball's whole contact tilted by 30 degrees about x and moved: the frame found
    (normal by PCA, origin at the pressure's centroid) grades it as the flat original."""
    scene, _ = ball
    c, r = synthetic(scene, load=100.0, h_over_b=0.05)
    t = math.radians(30.0)
    rot = np.array([[1.0, 0.0, 0.0], [0.0, math.cos(t), -math.sin(t)],
                    [0.0, math.sin(t), math.cos(t)]])
    moved = r.points @ rot.T + [0.02, -0.01, 0.005]
    path = tmp_path / "tilted.csv"
    path.write_text("# force = 100\nx,y,z,p\n" + "".join(
        f"{x!r},{y!r},{z!r},{q!r}\n" for (x, y, z), q in zip(moved.tolist(), r.pressure.tolist(),
                                                          strict=True)))
    res = read_result(path)
    assert res.symmetry == "whole"
    np.testing.assert_allclose(res.frame.normal, rot[:, 2], atol=1e-9)
    g0, g1 = fg.grade(r, scene), fg.grade(res, scene)
    for k in ("a_rel_err", "b_rel_err", "p0_rel_err"):
        assert g1.metrics[k] == pytest.approx(g0.metrics[k], abs=1e-6)


def test_csv_bad_input(ball, tmp_path):
    scene, _ = ball
    c, r = synthetic(scene, quarter=True, load=100.0)
    p = r.pressure.copy()
    p[7] = np.nan
    with pytest.raises(ResultError, match=r"nan\.csv: column 'p' \(pressure\).*line 11"):
        read_result(write_csv(tmp_path / "nan.csv", r.points, p))
    with pytest.raises(ResultError, match="no contact pressure column"):
        read_result(write_csv(tmp_path / "nop.csv", r.points, r.pressure, header="x,y,q"))
    with pytest.raises(ResultError, match="contact is empty"):
        read_result(write_csv(tmp_path / "zero.csv", r.points, 0 * r.pressure))
    noforce = read_result(write_csv(tmp_path / "noforce.csv", r.points, r.pressure,
                                    meta=("# units = mm",)))  # graded at the integral
    assert "integral" in noforce.details["force_from"]
    bad = write_csv(tmp_path / "text.csv", r.points, r.pressure)
    bad.write_text(bad.read_text().replace("\n0,0,", "\n0,zero,", 1))
    with pytest.raises(ResultError, match=r"line 4, column 'y'"):
        read_result(bad)


def surface_mesh_file(path, r, fields, fmt=None):
    tri = fg.surface_triangles(r.xy)
    meshio.write(path, meshio.Mesh(r.points, [("triangle", tri)], point_data=fields),
                 file_format=fmt)
    return path


@pytest.mark.parametrize("suffix", [".vtu", ".xdmf", ".med", ".exo"])
def test_meshio_round_trip(ball, tmp_path, suffix):
    """A whole contact surface with CPRESS in MPa, in mm, through VTU, XDMF, MED and Exodus:
    the same grade as the data in memory (the force given, as a deck's printed reaction)."""
    if suffix == ".exo":
        pytest.importorskip("netCDF4", reason="meshio writes Exodus with netCDF4")
    if suffix in (".xdmf", ".med"):
        pytest.importorskip("h5py", reason="meshio writes XDMF and MED with h5py")
    scene, _ = ball
    c, r = synthetic(scene, load=100.0, h_over_b=0.05)
    path = surface_mesh_file(tmp_path / f"s{suffix}",
                             ContactResult(points=r.points * 1e3, pressure=r.pressure,
                                           force=1.0),
                             {"CPRESS": r.pressure / 1e6})
    res = read_result(path, units="mm", force=100.0)
    assert res.symmetry == "whole" and res.details["pressure_field"] == "CPRESS"
    g0, g1 = fg.grade(r, scene), fg.grade(res, scene)
    for k in ("a_rel_err", "b_rel_err", "p0_rel_err"):
        assert g1.metrics[k] == pytest.approx(g0.metrics[k], abs=1e-6)


def test_meshio_volume_with_stress_and_reaction(ball, tmp_path):
    """A tetrahedral box (body 2) with CPRESS on its top, S (6 Voigt components) and RF
    (the force on its top and the opposite on its bottom): the contact surface is the
    boundary faces around the pressure, the force comes from RF, the stress is graded."""
    scene, _ = ball
    c = scene.hertz(100.0)
    pts, tets = block_mesh(c)
    top = np.abs(pts[:, 2]) < 1e-15
    bottom = np.abs(pts[:, 2] - pts[:, 2].min()) < 1e-15
    p = np.where(top, exact_pressure(c, pts[:, 0], pts[:, 1]), 0.0)
    rf = np.zeros((len(pts), 3))
    rf[bottom, 2] = 25.0 / bottom.sum()
    rf[top & (p > 0), 2] = -25.0 / (top & (p > 0)).sum()
    sig = c.stress(pts[:, 0], pts[:, 1], -pts[:, 2], body=2)
    sig = sig * np.array([1, 1, -1])[:, None] * np.array([1, 1, -1])[None, :]
    voigt = sig[:, [0, 1, 2, 0, 1, 0], [0, 1, 2, 1, 2, 2]]
    path = tmp_path / "box.vtu"
    meshio.write(path, meshio.Mesh(pts, [("tetra", tets)],
                                   point_data={"CPRESS": p, "S": voigt, "RF": rf}))
    res = read_result(path)
    assert res.symmetry == "quarter" and res.force == pytest.approx(100.0)
    assert [st.body for st in res.stress] == [2]
    g = fg.grade(res, scene)
    assert abs(g.metrics["von_mises_rel_err"]) < 0.003
    assert abs(g.metrics["p0_rel_err"]) < 1e-6


def test_meshio_bad_input(ball, tmp_path):
    scene, _ = ball
    c, r = synthetic(scene, load=100.0, h_over_b=0.1)
    with pytest.raises(ResultError, match=r"nop\.vtu: no contact pressure field.*foo"):
        read_result(surface_mesh_file(tmp_path / "nop.vtu", r, {"foo": r.pressure}),
                    force=100.0)
    p = r.pressure.copy()
    p[3] = np.nan
    with pytest.raises(ResultError, match=r"nan\.vtu: field 'CPRESS' has 1 non-finite"):
        read_result(surface_mesh_file(tmp_path / "nan.vtu", r, {"CPRESS": p}), force=100.0)
    with pytest.raises(ResultError, match=r"zero\.vtu: the contact is empty: field 'CPRESS'"):
        read_result(surface_mesh_file(tmp_path / "zero.vtu", r, {"CPRESS": 0 * r.pressure}),
                    force=100.0)
    with pytest.raises(ResultError, match="no point field 'PRESS'"):
        read_result(surface_mesh_file(tmp_path / "named.vtu", r, {"CPRESS": r.pressure}),
                    force=100.0, fields={"pressure": "PRESS"})
    with pytest.raises(ResultError, match="no total force"):
        read_result(surface_mesh_file(tmp_path / "noforce.vtu", r, {"CPRESS": r.pressure}))
    (tmp_path / "junk.vtu").write_text("not a mesh")
    with pytest.raises(ResultError, match="junk.vtu: meshio cannot read it"):
        read_result(tmp_path / "junk.vtu")


# --- scenes -------------------------------------------------------------------------------

@pytest.mark.parametrize("text,match", [
    ("load = 1.0\n[body1]\nRx = 0.01\nRy = 0.01\nE = 2e11\nnu = 0.3\n", r"\[body2\] table"),
    (BALL_TOML.replace("nu = 0.3\n[body2]", "nu = 0.3\nG = 1\n[body2]"), "unknown G"),
    (BALL_TOML.replace('Ry = "inf"', 'Ry = "wide"', 1), "body2.Ry must be a number"),
    ("colour = 1\n" + BALL_TOML, "unknown key"),
    (BALL_TOML.replace("load = 100.0", "load = 1.0\napproach = 1e-6"), "at most one"),
    ("load = [", "not valid TOML"),
])
def test_scene_file_errors_name_the_key(tmp_path, text, match):
    path = tmp_path / "s.toml"
    path.write_text(text)
    with pytest.raises(ValueError, match=match) as info:
        scene_from_toml(path)
    assert "s.toml" in str(info.value)


# --- force against approach ---------------------------------------------------------------

def test_force_approach_against_hertz_law(ball):
    """Hertz's law for a ball on a plane, written out: F = (4/3) E* sqrt(R) delta^1.5."""
    scene, _ = ball
    e_star = 1 / (2 * (1 - 0.3**2) / 210e9)
    delta = np.linspace(1e-7, 5e-6, 40)
    force = 4 / 3 * e_star * math.sqrt(0.01) * delta**1.5
    g = fg.grade_force_approach(delta, force, scene)
    assert g.passed and abs(g.metrics["force_rel_err_max"]) < 1e-12
    assert abs(g.metrics["exponent_err"]) < 1e-9
    g = fg.grade_force_approach(delta, force * 1.015, scene)
    assert not g.passed and g.check("force_rel_err_max").status == "fail"
    with pytest.raises(ResultError, match="non-finite"):
        fg.grade_force_approach(delta, np.where(delta > 1e-6, np.nan, force), scene)


def test_equivalent_sphere_dem_law_fails_an_elliptical_contact():
    """DEM codes replace an elliptical contact by a sphere of the mean radius: for alpha 10
    (Rx = 10 mm, Ry = 100 mm) that law misses Hertz's force by several percent."""
    scene = equal_steel(10)
    r1, r2 = (1 / scene.body1.Rx + 1 / scene.body2.Rx), (1 / scene.body1.Ry + 1 / scene.body2.Ry)
    r_eq = 1 / math.sqrt(r1 * r2)  # Gaussian-curvature equivalent sphere
    e_star = scene.hertz().e_star
    delta = np.linspace(1e-7, 2e-6, 20)
    g = fg.grade_force_approach(delta, 4 / 3 * e_star * math.sqrt(r_eq) * delta**1.5, scene)
    assert g.check("force_rel_err_max").status == "fail"
    assert abs(g.metrics["exponent_err"]) < 1e-9  # the exponent is right, the constant not


# --- the command line -----------------------------------------------------------------------

def run(*args, cwd=None):
    env_path = str(ROOT)
    return subprocess.run([sys.executable, "-m", "fem_validation", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd, timeout=300,
                          env={"PYTHONPATH": env_path, "PATH": "/usr/bin:/bin",
                               "MPLBACKEND": "Agg", "HOME": str(cwd or ROOT)})


def test_cli_grade_pass_fail_and_bad_input(ball, tmp_path):
    scene, toml = ball
    c, r = synthetic(scene, quarter=True, load=100.0)
    good = write_csv(tmp_path / "q.csv", r.points, r.pressure)
    out = tmp_path / "out"
    done = run("grade", good, "--scene", toml, "--out", out)
    assert done.returncode == 0, done.stderr
    row = json.loads((out / "grade.json").read_text())
    for key in ("force", "a_rel_err", "b_rel_err", "p0_rel_err", "passed", "checks"):
        assert key in row
    assert row["force"] == pytest.approx(100.0) and row["passed"] is True
    check = next(ch for ch in row["checks"] if ch["name"] == "a_rel_err")
    assert set(check) >= {"value", "tolerance", "pass"} and check["pass"] is True
    md = (out / "grade.md").read_text()
    for text in ("## What was graded", "(result - Hertz) / Hertz", "| tolerance |", "PASSED"):
        assert text in md
    assert (out / "grade.png").stat().st_size > 10_000
    # a tolerance tighter than the data's profile RMS fails: exit 1
    done = run("grade", good, "--scene", toml, "--tolerance", "rms_major=0.001", "--out", out)
    assert done.returncode == 1 and "FAILED: rms_major" in done.stdout
    tol = tmp_path / "tol.toml"
    tol.write_text("rms_minor = 0.001\n")
    assert run("grade", good, "--scene", toml, "--tolerances", tol,
               "--out", out).returncode == 1
    # wrong units: the file's MPa read as Pa
    for args, match in [(("--units", "SI"), "--units"),
                        (("--symmetry", "half"), "holds a quarter model"),
                        (("--symmetry", "whole"), "holds a quarter model"),
                        (("--tolerance", "a_err=1"), "unknown metric"),
                        (("--tolerance", "a_rel_err=-1"), "finite number > 0"),
                        (("--force", "nan"), "--force"),
                        (("--bogus",), "unrecognized arguments")]:
        done = run("grade", good, "--scene", toml, *args, "--out", out)
        assert done.returncode == 2, (args, done.stdout, done.stderr)
        assert len(done.stderr.strip().splitlines()) == 1 and match in done.stderr, done.stderr
    done = run("grade", tmp_path / "missing.csv", "--scene", toml, "--out", out)
    assert done.returncode == 2 and "missing.csv: no such file" in done.stderr


def test_cli_force_approach(ball, tmp_path):
    scene, toml = ball
    e_star = 1 / (2 * (1 - 0.3**2) / 210e9)
    delta = np.linspace(1e-4, 5e-3, 30)  # mm
    force = 4 / 3 * e_star * math.sqrt(0.01) * (delta * 1e-3) ** 1.5
    curve = tmp_path / "dem.csv"
    curve.write_text("# units = mm\noverlap,force\n"
                     + "".join(f"{float(d)!r},{float(f)!r}\n" for d, f in zip(delta, force,
                                                                        strict=True)))
    done = run("grade", "--force-approach", curve, "--scene", toml, "--out", tmp_path / "o")
    assert done.returncode == 0, done.stderr
    assert json.loads((tmp_path / "o" / "grade.json").read_text())["passed"] is True
    curve.write_text(curve.read_text().replace("# units = mm\n", ""))  # now metres: wrong
    assert run("grade", "--force-approach", curve, "--scene", toml,
               "--out", tmp_path / "o").returncode == 1
    done = run("grade", curve, "--force-approach", curve, "--scene", toml, "--out", tmp_path)
    assert done.returncode == 2 and "one of them" in done.stderr


@pytest.mark.parametrize("args,match", [
    (("--alpha", "1e9", "--level", "0"), "1 <= alpha <= 1000"),
    (("--alpha", "1e5"), "1 <= alpha <= 1000"),
    (("--scene", "alpha-2000"), "1 <= alpha <= 1000"),
    (("--curved", "--study", "alpha-3"), "--curved and --study cannot be combined"),
    (("--alpha", "3", "--study", "alpha-3"), "--study and --alpha cannot be combined"),
    (("--level", "9"), "invalid choice"),
    (("--curved", "--level", "5"), "levels must be in"),
    (("--nonsense",), "unrecognized arguments"),
    (("--alpha", "three"), "invalid float value"),
    (("--alpha", "2", "--level", "0", "--amg-rebuild", "-1"), "--amg-rebuild must be"),
    (("--alpha", "2", "--level", "0", "--amg-rebuild", "nan"), "--amg-rebuild must be"),
])
def test_cli_hostile_arguments_one_line(tmp_path, args, match):
    done = run(*args, "--out", tmp_path / "o")
    assert done.returncode == 2, done.stderr
    assert len(done.stderr.strip().splitlines()) == 1 and match in done.stderr, done.stderr
    assert not (tmp_path / "o").exists()  # refused before anything ran


def test_cli_out_that_cannot_be_written(tmp_path):
    afile = tmp_path / "file"
    afile.write_text("")
    for out, match in [(afile, "exists and is not a directory"),
                       (afile / "sub", "cannot be written"),
                       (Path("/proc/fem_validation_out"), "cannot be written")]:
        for args in (("--alpha", "3", "--level", "0"),
                     ("grade", tmp_path / "x.csv", "--scene", tmp_path / "s.toml")):
            done = run(*args, "--out", out)
            assert done.returncode == 2 and match in done.stderr, done.stderr
            assert len(done.stderr.strip().splitlines()) == 1


def test_cli_readme_outside_a_checkout_is_refused_before_the_run(tmp_path):
    done = run("--alpha", "3", "--level", "0", "--readme", "--out", tmp_path / "o",
               cwd=tmp_path)
    assert done.returncode == 2 and "fem-validation" in done.stderr
    assert not (tmp_path / "o").exists()


def test_our_own_vtu_graded_through_the_reader_reproduces_the_report(tmp_path):
    """End to end, one grading path: a level-0 run of alpha 3 writes its VTU; the meshio
    reader and the grader, given only that file, the scene and the quarter's force,
    reproduce the run's own a (moments of pressure x lumped area on the same triangles),
    p0 and body 1's axis von Mises error to 1e-9."""
    pytest.importorskip("gmsh", reason="needs the fem extra (gmsh)")
    import fem_validation as fv

    scene = equal_steel(3)
    run_ = fv.validate(scene, level=0, out=tmp_path)
    res = read_result(tmp_path / "alpha-3_body1.vtu", force=run_.load / 4)
    assert res.symmetry == "quarter" and res.force == pytest.approx(run_.load, rel=1e-12)
    g = fg.grade(res, scene)
    assert g.metrics["a_moments_rel_err"] == pytest.approx(run_.a_rel_err, abs=1e-9)
    assert g.metrics["b_moments_rel_err"] == pytest.approx(run_.b_rel_err, abs=1e-9)
    assert g.metrics["p0_rel_err"] == pytest.approx(run_.p0_rel_err, abs=1e-9)
    assert g.stress["body1"]["von_mises_rel_err"] == pytest.approx(
        run_.stress["body1"]["von_mises_rel_err"], abs=1e-9)


def test_cli_origin_is_in_the_files_units(ball, tmp_path):
    """--origin is in the file's length unit: a whole model in mm (``# units = mm``), moved
    by (5, -3, 0) mm, graded with ``--origin 5 -3 0`` and no --units grades as with
    ``--units mm`` (the origin was read as metres, 1000 times too far)."""
    scene, toml = ball
    _, r = synthetic(scene, load=100.0)
    moved = r.points + [5e-3, -3e-3, 0.0]
    path = write_csv(tmp_path / "w.csv", moved, r.pressure, meta=("# force = 100", "# units = mm"))
    rows = []
    for extra in ((), ("--units", "mm")):
        out = tmp_path / f"out{len(extra)}"
        done = run("grade", path, "--scene", toml, "--origin", "5", "-3", "0", *extra,
                   "--out", out)
        assert done.returncode == 0, done.stdout + done.stderr
        rows.append(json.loads((out / "grade.json").read_text()))
    for key in ("a_rel_err", "b_rel_err", "p0_rel_err"):
        assert rows[0][key] == rows[1][key]


def test_a_hertz_scene_with_its_tangential_keys_is_a_fem_validation_scene(tmp_path):
    """One scene format, one parser (hertz._scene): what ``hertz --print-scene`` writes,
    tangential keys included, is read by fem_validation as the same contact (it was
    refused: "unknown key(s) direction_deg, mu, tangential")."""
    done = subprocess.run([sys.executable, "-m", "hertz", "--print-scene", "--tangential", "10",
                           "--mu", "0.3"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    path = tmp_path / "s.toml"
    path.write_text(done.stdout)
    scene = scene_from_toml(path)
    c = scene.hertz()
    import tomllib

    data = tomllib.loads(done.stdout)
    assert data["mu"] == 0.3 and data["tangential"] == 10
    ref = hertz.contact(hertz.Body(**data["body1"]), hertz.Body(**data["body2"]),
                        load=data["load"], angle=math.radians(data.get("angle_deg", 0.0)))
    assert (c.a, c.b, c.p0) == (ref.a, ref.b, ref.p0)
