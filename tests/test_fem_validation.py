"""fem_validation: the model's pieces, a fast end-to-end run, and (slow) the targets.

Needs the ``fem`` extra; deliberately not skipped without it, so that a CI run
cannot pass without running the finite elements.
"""

import json
import math
import subprocess
import sys

import meshio
import numpy as np
import pytest
from skfem import Basis, ElementTetP1, ElementVector, asm

import fem_validation as fv
import fem_validation.compare as fvc
import fem_validation.mesh as fvm
import fem_validation.solve as fvs
import hertz


@pytest.fixture(scope="module")
def coarse():
    """alpha = 3 at mesh level 0: mesh, solution and comparison (a few seconds)."""
    scene = fv.equal_steel(3)
    mesh = fvm.build(scene, 0)
    sol = fvs.solve_contact(scene, mesh)
    return scene, mesh, sol, fvc.compare_with_hertz(scene, mesh, sol, 0, 0.0)


def test_rigid_body_modes_are_the_stiffness_nullspace(coarse):
    _, mesh, _, _ = coarse
    m = mesh.bodies[0]
    mu, lmbda = fvs.lame(210e9, 0.3)
    K = asm(fvs.elasticity, Basis(m, ElementVector(ElementTetP1()), intorder=1), mu=mu,
            lmbda=lmbda)
    modes = fvs.rigid_body_modes(m.p)
    assert np.abs(K @ modes).max() <= 1e-6 * abs(K).max() * np.abs(modes).max()


def test_two_bodies_with_matching_contact_faces(coarse):
    scene, mesh, _, _ = coarse
    m1, m2 = mesh.bodies
    assert m1.p[2].min() >= 0 and m2.p[2].max() <= 0
    np.testing.assert_array_equal(m1.p[:, mesh.pairs[:, 0]], m2.p[:, mesh.pairs[:, 1]])
    assert np.all(m1.p[2, mesh.pairs[:, 0]] == 0)
    assert mesh.quarter and scene.symmetric
    assert mesh.pair_area.sum() == pytest.approx(mesh.extent**2, rel=1e-9)
    assert mesh.extent >= 10 * scene.hertz().a


def test_gap_is_the_relative_curvature_quadratic():
    scene = fv.crossed_30deg()
    c = scene.hertz()
    t = c.major_axis_angle
    along_major = np.array([[math.cos(t), math.sin(t)]]) * 1e-4
    along_minor = np.array([[-math.sin(t), math.cos(t)]]) * 1e-4
    assert fvs.gap0(scene, along_major)[0] == pytest.approx(0.5 * c.rho_y * 1e-8, rel=1e-12)
    assert fvs.gap0(scene, along_minor)[0] == pytest.approx(0.5 * c.rho_x * 1e-8, rel=1e-12)


def test_post_processing_recovers_an_exact_hertz_field():
    rng = np.random.default_rng(4)
    a, b, p0, theta = 2.0, 1.0, 3.0, math.radians(-75)
    xy = rng.uniform(-2.2, 2.2, (20000, 2))
    u = xy @ np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
    r2 = (u[:, 0] / a) ** 2 + (u[:, 1] / b) ** 2
    p = p0 * np.sqrt(np.clip(1 - r2, 0, None))
    fit = fvc.fit_ellipse(xy, p)
    assert (fit["p0"], fit["a"], fit["b"]) == pytest.approx((p0, a, b), rel=1e-10)
    assert fit["major_axis_angle_deg"] == pytest.approx(-75, abs=1e-8)
    mom = fvc.moment_ellipse(xy, p * (4.4**2 / len(p)), quarter=False)
    assert (mom["a"], mom["b"]) == pytest.approx((a, b), rel=0.01)
    assert mom["major_axis_angle_deg"] == pytest.approx(-75, abs=0.5)


def test_interpolation_on_the_face_is_exact_for_linear_fields():
    xy = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    tri = np.array([[0, 1, 2], [1, 3, 2]])
    values = 2 + 3 * xy[:, 0] - xy[:, 1]
    pts = np.array([[0.25, 0.25], [0.9, 0.8], [2.0, 2.0]])
    out = fvc.interpolate_on_face(xy, tri, values, pts)
    np.testing.assert_allclose(out[:2], 2 + 3 * pts[:2, 0] - pts[:2, 1], rtol=1e-14)
    assert np.isnan(out[2])


def test_coarse_end_to_end_is_roughly_hertz(coarse):
    """Loose tolerances that still catch a wrong sign or a factor of 2 (E' for E*: 26% in a)."""
    scene, mesh, sol, r = coarse
    assert abs(r.a_rel_err) < 0.06 and abs(r.b_rel_err) < 0.06
    assert abs(r.p0_rel_err) < 0.10
    assert r.rms_major < 0.10 and r.rms_minor < 0.10
    assert abs(r.force_rel_err) < 1e-5
    assert 0.8 < sol.force / scene.load < 1.2
    assert r.max_penetration_over_delta < 0.01
    assert sol.active.sum() > 10 and not sol.active.all()


def test_vtu_round_trip_and_reports(coarse, tmp_path):
    scene, mesh, sol, r = coarse
    paths = fvc.write_vtu(scene, mesh, sol, tmp_path)
    for i, path in enumerate(paths):
        back = meshio.read(path)
        body = mesh.bodies[i]
        np.testing.assert_array_equal(back.points, body.p.T)
        np.testing.assert_array_equal(back.cells_dict["tetra"], body.t.T)
        u = (sol.u1, sol.u2)[i]
        np.testing.assert_array_equal(back.point_data["displacement"], u)
        assert set(back.point_data) == {"displacement", "von_mises", "contact_pressure_fem",
                                        "contact_pressure_hertz", "contact_pressure_difference"}
        assert np.all(back.point_data["von_mises"] >= 0)
        p = back.point_data["contact_pressure_fem"][mesh.pairs[:, i]]
        np.testing.assert_array_equal(p, sol.pressure)
    json_path, md_path = fvc.write_reports([r], tmp_path)
    row = json.loads(json_path.read_text())[0]
    for key in ("alpha", "a_rel_err", "b_rel_err", "p0_rel_err", "force_rel_err", "seconds",
                "dofs"):
        assert key in row
    assert "alpha-3" in md_path.read_text()


def test_cli(tmp_path):
    ok = subprocess.run([sys.executable, "-m", "fem_validation", "--scene", "alpha-1.5",
                         "--level", "0", "--out", str(tmp_path), "--quiet"],
                        capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    assert (tmp_path / "report.json").exists() and (tmp_path / "alpha-1.5_body2.vtu").exists()
    assert (tmp_path / "alpha-1.5_pressure.png").exists()
    bad = subprocess.run([sys.executable, "-m", "fem_validation", "--scene", "nope"],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1 and "Traceback" not in bad.stderr


def test_scene_loads_keep_the_contact_small():
    for scene in fv.default_scenes():
        c = scene.hertz()
        radii = [abs(r) for b in (scene.body1, scene.body2) for r in (b.Rx, b.Ry)
                 if math.isfinite(r)]
        assert c.a / min(radii) <= 0.05
    assert fv.crossed_30deg().hertz().major_axis_angle == pytest.approx(math.radians(-75))
    assert not fv.crossed_30deg().symmetric
    with pytest.raises(ValueError, match="alpha"):
        fv.equal_steel(0.5)
    assert isinstance(fv.equal_steel(2).body1, hertz.Body)


TARGETS = {"a_rel_err": 0.02, "b_rel_err": 0.02, "p0_rel_err": 0.03, "rms_major": 0.03,
           "rms_minor": 0.03, "force_rel_err": 0.005}


@pytest.mark.slow
@pytest.mark.parametrize("alpha", [1, 3, 10])
def test_targets_at_the_default_mesh(alpha):
    r = fv.validate(fv.equal_steel(alpha))
    for key, limit in TARGETS.items():
        assert abs(getattr(r, key)) <= limit, (key, getattr(r, key))
    assert r.max_penetration_over_delta <= 0.01


@pytest.mark.slow
def test_orientation_of_the_crossed_scene():
    r = fv.validate(fv.crossed_30deg(), level=2)
    assert abs(r.angle_err_deg) < 1.0
    assert abs(r.a_rel_err) < 0.02 and abs(r.b_rel_err) < 0.02


@pytest.mark.slow
def test_refinement_rates(tmp_path):
    from fem_validation.study import refinement_study

    study = refinement_study(fv.equal_steel(3), [0, 1, 2, 3], tmp_path)
    errors = {q: [abs(r[q]) for r in study["results"]] for q in study["rates"]}
    for q, values in errors.items():
        assert values[-1] < values[0] / 2, (q, values)
    rates = study["rates"]
    assert rates["a_rel_err"] > 0.3 and rates["b_rel_err"] > 0.8
    assert rates["p0_rel_err"] > 0.5 and min(rates["rms_major"], rates["rms_minor"]) > 0.4
