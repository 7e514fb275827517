"""fem_validation: the model's pieces, a fast end-to-end run, and (slow) the targets.

Needs the ``fem`` extra (scikit-fem, meshio, gmsh, pyamg, matplotlib): without it the
module skips with the missing package's name, as tests/test_fem_curved.py does, so that
``pip install -e ".[test]"`` and ``python -m pytest`` run the rest.  A run that must
exercise the finite elements (CI installs ``.[test,fem]``) sets ``HERTZ_REQUIRE_FEM=1``:
then a missing package is a collection error, not a skip.

The slow tests' tolerances are about 1.5 times the errors observed at the
default level (with a floor of 0.05% for errors that happen to be tiny), so
that a Hertz reference 1-2% off fails them (test_a_wrong_reference_fails).
"""

import importlib
import json
import math
import os
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

for _module in ("skfem", "meshio", "gmsh", "pyamg", "matplotlib"):  # the fem extra
    if os.environ.get("HERTZ_REQUIRE_FEM") == "1":
        importlib.import_module(_module)
    else:
        pytest.importorskip(_module, reason=f"{_module} is not installed: the FEM validation "
                            "needs the fem extra (pip install -e '.[test,fem]')")

import meshio  # noqa: E402
from skfem import Basis, BilinearForm, ElementTetP1, ElementVector, MeshTet, asm  # noqa: E402
from skfem.helpers import ddot, sym_grad, trace  # noqa: E402

import fem_validation as fv  # noqa: E402
import fem_validation.fe.elasticity as fve  # noqa: E402
import fem_validation.fe.surface as fvsurf  # noqa: E402
import fem_validation.grading.contact as fvg  # noqa: E402
import fem_validation.reports.blocks as fvo  # noqa: E402
import fem_validation.runs.study as fvst  # noqa: E402
import fem_validation.runs.validate as fvrun  # noqa: E402
import fem_validation.solvers.blocks as fvc  # noqa: E402
import fem_validation.solvers.mesh as fvm  # noqa: E402
import fem_validation.solvers.solve as fvs  # noqa: E402
import fem_validation.solvers.vtu as fvvtu  # noqa: E402
import hertz  # noqa: E402


@pytest.fixture(scope="module")
def coarse():
    """alpha = 3 at mesh level 0: mesh, solution and comparison (a second or two)."""
    scene = fv.equal_steel(3)
    mesh = fvm.build(scene, 0)
    sol = fvs.solve_contact(scene, mesh)
    return scene, mesh, sol, fvrun.compare_with_hertz(scene, mesh, sol, 0, 0.0)


@pytest.fixture(scope="module")
def crossed_coarse():
    """The crossed scene (whole model, rotated ellipse) at level 0: its mesh only."""
    scene = fv.crossed_30deg()
    return scene, fvm.build(scene, 0)


# --- elasticity ------------------------------------------------------------------------


def _distorted_box():
    m = MeshTet.init_tensor(np.linspace(0, 1, 5) ** 1.5, np.linspace(0, 2, 4),
                            np.linspace(0, 1, 4))
    return MeshTet(m.p + 0.02 * np.sin(7 * m.p[[1, 2, 0]]), m.t)


def test_stiffness_matches_scikit_fem():
    @BilinearForm
    def elasticity(u, v, w):
        eu, ev = sym_grad(u), sym_grad(v)
        return 2.0 * w.mu * ddot(eu, ev) + w.lmbda * trace(eu) * trace(ev)

    m = _distorted_box()
    mu, lmbda = fve.lame(210e9, 0.3)
    reference = asm(elasticity, Basis(m, ElementVector(ElementTetP1()), intorder=1), mu=mu,
                    lmbda=lmbda)
    K = fve.stiffness(m.p, m.t, 210e9, 0.3)
    assert abs(K - reference).max() <= 1e-13 * abs(reference).max()


def test_rigid_body_modes_are_the_stiffness_nullspace():
    m = _distorted_box()
    K = fve.stiffness(m.p, m.t, 210e9, 0.3)
    modes = fve.rigid_body_modes(m.p)
    assert np.abs(K @ modes).max() <= 1e-6 * abs(K).max() * np.abs(modes).max()


def test_stress_of_a_linear_displacement_is_exact():
    m = _distorted_box()
    grad = np.array([[1.0, 2.0, 0.5], [-1.0, 0.3, 0.0], [0.2, 0.4, -0.7]]) * 1e-4
    u = (grad @ m.p).T
    E, nu = 70e9, 0.33
    mu, lmbda = fve.lame(E, nu)
    eps = 0.5 * (grad + grad.T)
    expected = 2 * mu * eps + lmbda * np.trace(eps) * np.eye(3)
    stress = fve.element_stress(m.p, m.t, u, E, nu)
    np.testing.assert_allclose(stress, np.broadcast_to(expected, stress.shape),
                               rtol=1e-10, atol=1e-10 * abs(expected).max())
    nodal = fve.nodal_average(m.p, m.t, stress)
    np.testing.assert_allclose(nodal, np.broadcast_to(expected, nodal.shape),
                               rtol=1e-10, atol=1e-10 * abs(expected).max())
    uniaxial = np.zeros((3, 3))
    uniaxial[0, 0] = 5.0
    assert fve.von_mises(uniaxial) == pytest.approx(5.0)


def test_patch_recovery_is_exact_for_linear_fields():
    """Element values sampled from a linear field at the centroids come back exactly at
    every node (the nodal average does not: its patches are not centred on the nodes)."""
    m = _distorted_box()
    centroid = m.p[:, m.t].mean(axis=1)
    coef = np.array([[1.0, 2.0, -3.0, 0.5], [-2.0, 0.0, 1.0, 4.0]])  # two fields
    values = (coef[:, :1] + coef[:, 1:] @ centroid).T  # (m, 2)
    exact = (coef[:, :1] + coef[:, 1:] @ m.p).T
    # the box's corners have 2 or 6 tetrahedra whose centroids are (nearly) coplanar: the
    # fit falls back to the average there
    fitted = np.bincount(m.t.ravel()) > 6
    rec = fve.patch_recovery(m.p, m.t, values)
    np.testing.assert_allclose(rec[fitted], exact[fitted], rtol=0,
                               atol=1e-10 * np.abs(exact).max())
    average = fve.nodal_average(m.p, m.t, values)
    assert np.abs(average - exact)[fitted].max() > 1e-3
    single = np.bincount(m.t.ravel()) <= 2
    np.testing.assert_allclose(rec[single], average[single], rtol=1e-12)
    # a field independent of x, fitted without the x direction: still exact
    values_yz = (coef[:, :1] + coef[:, 2:] @ centroid[1:]).T
    exact_yz = (coef[:, :1] + coef[:, 2:] @ m.p[1:]).T
    rec = fve.patch_recovery(m.p, m.t, values_yz, np.diag([0.0, 1.0, 1.0]))
    np.testing.assert_allclose(rec[fitted], exact_yz[fitted], rtol=0,
                               atol=1e-10 * np.abs(exact).max())


def test_patch_recovery_falls_back_to_the_average_on_thin_patches():
    """A node of a single element has no linear fit: it gets that element's value."""
    p = np.array([[0.0, 1.0, 0.0, 0.0, 1.0], [0.0, 0.0, 1.0, 0.0, 1.0],
                  [0.0, 0.0, 0.0, 1.0, 1.0]])
    t = np.array([[0, 1], [1, 2], [2, 3], [3, 4]])
    rec = fve.patch_recovery(p, t, np.array([1.0, 3.0]))
    assert rec[0] == 1.0 and rec[4] == 3.0
    assert np.all((rec >= 1.0) & (rec <= 3.0))


def test_peak_of_sampled_curve():
    z = np.linspace(0.0, 2.0, 21)  # h = 0.1, the maximum 0.57 between two samples
    f = 1.0 - (z - 0.57) ** 2 + 0.1 * (z - 0.57) ** 3
    top = fvg.peak(z, f)
    assert top["fitted"]
    assert abs(top["depth"] - 0.57) < 3e-3 and abs(top["value"] - 1.0) < 2e-4
    # the largest sample is off by ~h/2 and low by ~(h/2)**2
    assert abs(top["node_depth"] - 0.57) > 0.02 and top["node_value"] < 1 - 5e-4
    edge = fvg.peak(z, z**3)  # largest at the last sample, convex: no vertex to take
    assert not edge["fitted"] and (edge["value"], edge["depth"]) == (8.0, 2.0)
    with pytest.raises(ValueError, match="^points must"):
        fvg.peak(z[:3], f[:3], points=5)


def test_interpolation_in_a_tetrahedral_mesh_is_exact_for_linear_fields():
    m = _distorted_box()
    field = (np.array([[1.0, -2.0, 0.5]]) @ m.p).T[:, 0] + 3.0
    rng = np.random.default_rng(1)
    pts = rng.uniform([0.1, 0.1, 0.1], [0.9, 1.9, 0.9], (200, 3))
    expected = pts @ np.array([1.0, -2.0, 0.5]) + 3.0
    np.testing.assert_allclose(fvc.interpolate(m, field, pts), expected, rtol=1e-12)
    corner = m.p[:, :1].T  # a node itself
    assert fvc.interpolate(m, field, corner)[0] == pytest.approx(field[0], rel=1e-12)
    with pytest.raises(fv.FEMValidationError, match="outside the mesh"):
        fvc.interpolate(m, field, np.array([[0.5, 0.5, 5.0]]))


@pytest.mark.parametrize("E, nu, name", [(0.0, 0.3, "E"), (1e9, 0.5, "nu"), (1e9, -1.0, "nu")])
def test_bad_material_names_the_parameter(E, nu, name):
    with pytest.raises(ValueError, match=f"^{name} must"):
        fve.lame(E, nu)


# --- mesh ------------------------------------------------------------------------------


def test_two_bodies_with_matching_contact_faces(coarse):
    scene, mesh, _, _ = coarse
    m1, m2 = mesh.bodies
    assert m1.p[2].min() >= 0 and m2.p[2].max() <= 0
    np.testing.assert_array_equal(m1.p[:, mesh.pairs[:, 0]], m2.p[:, mesh.pairs[:, 1]])
    assert np.all(m1.p[2, mesh.pairs[:, 0]] == 0)
    assert mesh.quarter and scene.symmetric
    assert mesh.pair_area.sum() == pytest.approx(mesh.extent**2, rel=1e-9)
    assert mesh.extent >= 10 * scene.hertz().a


def test_meshing_is_deterministic(coarse):
    scene, mesh, _, _ = coarse
    again = fvm.build(scene, 0)
    for first, second in zip(mesh.bodies, again.bodies, strict=True):
        np.testing.assert_array_equal(first.p, second.p)
        np.testing.assert_array_equal(first.t, second.t)


def test_levels_scale_every_size():
    scene = fv.equal_steel(3)
    fine, coarse = fvm.mesh_parameters(scene, 4), fvm.mesh_parameters(scene, 3)
    for key in ("hs", "h0", "grade", "hmax"):
        assert coarse[key] == pytest.approx(fvm.LEVEL_RATIO * fine[key], rel=1e-12), key
    for key in ("L", "H", "zone", "zi", "zz", "st", "ea"):
        assert coarse[key] == fine[key], key
    with pytest.raises(ValueError, match="^level must be one of"):
        fvm.mesh_parameters(scene, 9)


def test_anisotropy_grows_with_the_ellipticity_up_to_a_cap():
    assert fvm.anisotropy(1.0) == 1.0
    assert fvm.anisotropy(8.0) == pytest.approx(8.0 / fvm.ANISOTROPY_PER_A)
    assert fvm.anisotropy(100.0) == fvm.MAX_ANISOTROPY
    with pytest.raises(ValueError, match="^ellipticity must"):
        fvm.anisotropy(0.5)


def test_the_contact_zone_is_a_structured_grid(coarse):
    """Near the origin every contact node sits on the grid of spacing hs (st hs along a)."""
    scene, mesh, _, _ = coarse
    params = mesh.parameters
    b = scene.hertz().b
    xy = mesh.bodies[0].p[:2, mesh.pairs[:, 0]].T / b
    inner = np.all(xy < 0.5, axis=1)
    # alpha = 3: the major axis is along y
    steps = {0: params["hs"], 1: params["hs"] * params["st"]}
    for k, h in steps.items():
        n = params["zone"] * (params["eb"] if k == 0 else params["ea"]) / h
        spacing = params["zone"] * (params["eb"] if k == 0 else params["ea"]) / math.ceil(n)
        q = xy[inner, k] / spacing
        np.testing.assert_allclose(q, np.round(q), atol=1e-6)


def test_axis_nodes_lie_on_the_z_axis(coarse, crossed_coarse):
    for _, mesh in (coarse[:2], crossed_coarse):
        for body, nodes in zip(mesh.bodies, mesh.axis, strict=True):
            p = body.p[:, nodes]
            assert len(nodes) >= 5
            np.testing.assert_allclose(p[:2], 0.0, atol=1e-9 * mesh.extent)
            depth = np.abs(p[2])
            assert depth[0] == 0 and np.all(np.diff(depth) > 0)
            assert depth[-1] == pytest.approx(mesh.depth)


def test_geometry_is_found_packaged_first_then_in_the_checkout(tmp_path, monkeypatch):
    source = fvm.geometry_file()
    assert Path(source).name == "blocks.geo" and Path(source).is_file()
    packaged = tmp_path / "fem_validation"
    (packaged / "meshes").mkdir(parents=True)
    (packaged / "meshes" / "blocks.geo").write_text("// packaged copy\n")
    monkeypatch.setattr(fvm.importlib.resources, "files", lambda package: packaged)
    assert Path(fvm.geometry_file()) == packaged / "meshes" / "blocks.geo"
    with pytest.raises(fv.FEMValidationError, match="not found"):
        fvm.geometry_file("no-such.geo")


# --- solver and comparison -------------------------------------------------------------


def test_gap_is_the_relative_curvature_quadratic():
    scene = fv.crossed_30deg()
    c = scene.hertz()
    t = c.major_axis_angle
    along_major = np.array([[math.cos(t), math.sin(t)]]) * 1e-4
    along_minor = np.array([[-math.sin(t), math.cos(t)]]) * 1e-4
    assert fvs.gap0(scene, along_major)[0] == pytest.approx(0.5 * c.rho_y * 1e-8, rel=1e-12)
    assert fvs.gap0(scene, along_minor)[0] == pytest.approx(0.5 * c.rho_x * 1e-8, rel=1e-12)


def test_initial_active_sets(coarse):
    scene, mesh, sol, _ = coarse
    xy = mesh.bodies[0].p[:2, mesh.pairs[:, 0]].T
    hertz_set = fvs.initial_active_set(scene, xy, sol.approach, "hertz")
    overlap = fvs.initial_active_set(scene, xy, sol.approach, "interpenetration")
    assert np.all(overlap[hertz_set]) and overlap.sum() > 1.5 * hertz_set.sum()
    assert not fvs.initial_active_set(scene, xy, sol.approach, "none").any()
    assert fvs.initial_active_set(scene, xy, sol.approach, "all").all()
    with pytest.raises(ValueError, match="^initial_active must be one of"):
        fvs.initial_active_set(scene, xy, sol.approach, "ellipse")
    with pytest.raises(ValueError, match="^kappa must"):
        fvs.solve_contact(scene, mesh, kappa=-1.0)
    with pytest.raises(ValueError, match="^depth must"):
        fvs.boussinesq_settlement(1.0, 1e9, 0.3, 0.0)


def test_a_cold_start_reaches_the_same_solution(coarse):
    """Started from the interpenetration of the undeformed bodies, the active set settles
    where Hertz's start leads, the preconditioner being rebuilt on the way."""
    scene, mesh, sol, _ = coarse
    cold = fvs.solve_contact(scene, mesh, initial_active="interpenetration")
    np.testing.assert_array_equal(cold.active, sol.active)
    np.testing.assert_allclose(cold.pressure, sol.pressure, rtol=0,
                               atol=1e-4 * sol.pressure.max())
    assert cold.amg_setups > 1 and cold.active_set_iterations > sol.active_set_iterations


def test_a_nested_start_reaches_the_hertz_start_solution():
    """validate(initial_active="nested"): coarse solve from the overlap, transfer, fine solve
    with its own rebuild threshold; the same contact as Hertz's start (level 2)."""
    scene = fv.equal_steel(3)
    warm = fv.validate(scene, level=2)
    cold = fv.validate(scene, level=2, initial_active="nested")
    for key in ("a_rel_err", "b_rel_err", "p0_rel_err", "von_mises_rel_err"):
        assert getattr(cold, key) == pytest.approx(getattr(warm, key), abs=1e-6)
    assert cold.solver["amg_setups"] > 1


def test_post_processing_recovers_an_exact_hertz_field():
    rng = np.random.default_rng(4)
    a, b, p0, theta = 2.0, 1.0, 3.0, math.radians(-75)
    xy = rng.uniform(-2.2, 2.2, (20000, 2))
    u = xy @ np.array([[math.cos(theta), -math.sin(theta)], [math.sin(theta), math.cos(theta)]])
    r2 = (u[:, 0] / a) ** 2 + (u[:, 1] / b) ** 2
    p = p0 * np.sqrt(np.clip(1 - r2, 0, None))
    fit = fvg.fit_ellipse(xy, p)
    assert (fit["p0"], fit["a"], fit["b"]) == pytest.approx((p0, a, b), rel=1e-10)
    assert fit["major_axis_angle_deg"] == pytest.approx(-75, abs=1e-8)
    mom = fvg.moment_ellipse(xy, p * (4.4**2 / len(p)), quarter=False)
    assert (mom["a"], mom["b"]) == pytest.approx((a, b), rel=0.01)
    assert mom["major_axis_angle_deg"] == pytest.approx(-75, abs=0.5)


def test_edge_of_the_active_set_on_a_grid():
    """The ellipse through the midpoints of the active-inactive edges of a fine grid."""
    a, b, theta = 2.0, 1.0, math.radians(30)
    g = np.linspace(-3, 3, 241)
    x, y = np.meshgrid(g, g, indexing="ij")
    xy = np.column_stack([x.ravel(), y.ravel()])
    n = len(g)
    idx = np.arange(n * n).reshape(n, n)
    tri = np.concatenate([np.column_stack([idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(),
                                           idx[1:, 1:].ravel()]),
                          np.column_stack([idx[:-1, :-1].ravel(), idx[1:, 1:].ravel(),
                                           idx[:-1, 1:].ravel()])])
    c, s = math.cos(theta), math.sin(theta)
    u, v = xy @ np.array([c, s]), xy @ np.array([-s, c])
    active = (u / a) ** 2 + (v / b) ** 2 < 1
    edge = fvg.edge_ellipse(fvg.active_edge_points(xy, tri, active), quarter=False)
    assert (edge["a"], edge["b"]) == pytest.approx((a, b), rel=2e-3)
    assert edge["major_axis_angle_deg"] == pytest.approx(30, abs=0.5)
    quarter = np.all(xy >= 0, axis=1)
    keep = np.all(quarter[tri], axis=1)
    aligned = (xy[:, 0] / a) ** 2 + (xy[:, 1] / b) ** 2 < 1
    q = fvg.edge_ellipse(fvg.active_edge_points(xy, tri[keep], aligned), quarter=True)
    assert (q["a"], q["b"]) == pytest.approx((a, b), rel=3e-3)
    with pytest.raises(ValueError, match="^points must"):
        fvg.edge_ellipse(np.zeros((2, 2)), quarter=True)


def test_interpolation_on_the_face_is_exact_for_linear_fields():
    xy = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]])
    tri = np.array([[0, 1, 2], [1, 3, 2]])
    values = 2 + 3 * xy[:, 0] - xy[:, 1]
    pts = np.array([[0.25, 0.25], [0.9, 0.8], [2.0, 2.0]])
    out = fvg.interpolate_on_face(xy, tri, values, pts)
    np.testing.assert_allclose(out[:2], 2 + 3 * pts[:2, 0] - pts[:2, 1], rtol=1e-14)
    assert np.isnan(out[2])


def test_coarse_end_to_end_is_roughly_hertz(coarse):
    """Loose tolerances that still catch a wrong sign or a factor of 2 (E' for E*: 26% in a)."""
    scene, mesh, sol, r = coarse
    assert abs(r.a_rel_err) < 0.03 and abs(r.b_rel_err) < 0.03
    assert abs(r.p0_rel_err) < 0.06
    assert r.rms_major < 0.06 and r.rms_minor < 0.06
    assert abs(r.edge_a_rel_err) < 0.05 and abs(r.edge_b_rel_err) < 0.05
    assert abs(r.approach_rel_err) < 0.1
    # stresses below the surface (observed: von Mises -2.7% at -10% depth, RMS <= 1.8%)
    assert abs(r.von_mises_rel_err) < 0.06 and abs(r.z_von_mises_rel_err) < 0.2
    for name in fvg.FIELD_SETS:
        assert getattr(r, f"stress_rms_{name}") < 0.04, name
    assert 0.8 < sol.force / scene.load < 1.2
    assert r.max_penetration_over_delta < 0.01
    assert sol.active.sum() > 10 and not sol.active.all()
    # the reaction equals the contact force by construction (up to the CG residual)
    assert abs(r.force_rel_err) < 1e-6
    assert math.isnan(r.angle_err_deg)  # a quarter model has its axes by construction


def test_axis_stress_is_in_the_ellipse_frame(coarse):
    scene, mesh, sol, r = coarse
    c = scene.hertz(sol.force)
    for name in ("body1", "body2"):
        data = r.axis_stress[name]
        depth, stress = data["depth"], data["stress"]
        assert stress.shape == (len(depth), 3, 3) and depth[0] == 0
        np.testing.assert_allclose(stress, stress.transpose(0, 2, 1), atol=1e-9 * c.p0)
        # compressive below the contact: sigma_zz = -p0 a b / sqrt((a^2 + z^2)(b^2 + z^2))
        z = depth[(depth > 0.5 * c.b) & (depth < 3 * c.a)]
        exact = -c.p0 * c.a * c.b / np.sqrt((c.a**2 + z**2) * (c.b**2 + z**2))
        fem = stress[(depth > 0.5 * c.b) & (depth < 3 * c.a), 2, 2]
        assert np.abs(fem - exact).max() < 0.1 * c.p0


def test_check_names_the_missed_targets(coarse):
    *_, r = coarse
    missed = fv.check(r, {"a_rel_err": 1e-6, "rms_major": 1.0})
    assert len(missed) == 1 and "a_rel_err" in missed[0]


def test_vtu_round_trip_and_reports(coarse, tmp_path):
    scene, mesh, sol, r = coarse
    paths = fvvtu.write_vtu(scene, mesh, sol, tmp_path)
    for i, path in enumerate(paths):
        back = meshio.read(path)
        body = mesh.bodies[i]
        np.testing.assert_array_equal(back.points, body.p.T)
        np.testing.assert_array_equal(back.cells_dict["tetra"], body.t.T)
        u = (sol.u1, sol.u2)[i]
        np.testing.assert_array_equal(back.point_data["displacement"], u)
        assert set(back.point_data) == {
            "displacement", "von_mises", "contact_pressure_fem", "contact_pressure_hertz",
            "contact_pressure_difference", "stress_fem", "stress_hertz", "stress_difference",
            "von_mises_hertz", "von_mises_difference"}
        assert np.all(back.point_data["von_mises"] >= 0)
        p = back.point_data["contact_pressure_fem"][mesh.pairs[:, i]]
        np.testing.assert_array_equal(p, sol.pressure)
        # the analytic field at a few nodes, rebuilt here from Contact.stress
        c = scene.hertz(sol.force)
        t = c.major_axis_angle
        flip = 1.0 if i == 0 else -1.0
        axes = np.array([[math.cos(t), -math.sin(t), 0.0], [math.sin(t), math.cos(t), 0.0],
                         [0.0, 0.0, flip]])  # columns: the ellipse frame's axes
        near = np.nonzero(np.linalg.norm(body.p, axis=0) < 2 * c.a)[0]
        for j in [*mesh.axis[i][1:4], *near[:: max(len(near) // 7, 1)]]:
            x, y, z = axes.T @ body.p[:, j]
            exact = c.stress(x, y, z, body=i + 1)
            hz = back.point_data["stress_hertz"][j].reshape(3, 3)
            np.testing.assert_allclose(hz, axes @ exact @ axes.T, rtol=0, atol=1e-9 * c.p0)
            assert back.point_data["von_mises_hertz"][j] == pytest.approx(
                fve.von_mises(exact), rel=1e-9)
        fem = back.point_data["stress_fem"]
        np.testing.assert_allclose(back.point_data["stress_difference"],
                                   fem - back.point_data["stress_hertz"], rtol=1e-12,
                                   atol=1e-12 * c.p0)
        np.testing.assert_allclose(back.point_data["von_mises"],
                                   fve.von_mises(fem.reshape(-1, 3, 3)), rtol=1e-12)
        np.testing.assert_allclose(fem.reshape(-1, 3, 3), r.nodal_stress[i], rtol=1e-12,
                                   atol=1e-12 * c.p0)
    json_path, md_path = fvo.write_reports([r], tmp_path)
    row = json.loads(json_path.read_text())[0]  # strict JSON: NaN is written as null
    for key in ("alpha", "a_rel_err", "b_rel_err", "p0_rel_err", "force_rel_err", "seconds",
                "dofs", "edge_a_rel_err", "approach_rel_err", "peak_memory_mb",
                "von_mises_rel_err", "z_von_mises_rel_err", "stress_rms_axis",
                "stress_rms_major_plane", "stress_rms_minor_plane"):
        assert key in row
    assert set(row["stress"]) == {"body1", "body2"}
    assert row["angle_err_deg"] is None
    assert "axis_stress" not in row and "nodal_stress" not in row
    assert "alpha-3" in md_path.read_text()


def test_richardson_and_rates_on_a_known_sequence():
    h = np.array([0.4, 0.4 / 2**0.5, 0.2])
    e = 0.001 + 0.05 * h**2
    e0, p = fvst.richardson(*e, 2**0.5)
    assert e0 == pytest.approx(0.001, abs=1e-12) and p == pytest.approx(2.0)
    rates = fvst.observed_rates(h, {"q": 0.05 * h**1.5})
    assert rates["q"] == pytest.approx(1.5)
    assert all(math.isnan(v) for v in fvst.richardson(1.0, 0.5, 0.7, 2**0.5))
    assert fvst.richardson_with_order(e[1], e[2], 2**0.5, 2.0) == pytest.approx(0.001)
    with pytest.raises(ValueError, match="^ratio must"):
        fvst.richardson(1.0, 0.5, 0.2, 1.0)
    with pytest.raises(ValueError, match="^order must"):
        fvst.richardson_with_order(1.0, 0.5, 2.0, 0.0)


def test_cli(tmp_path):
    ok = subprocess.run([sys.executable, "-m", "fem_validation", "--scene", "alpha-1.5",
                         "--level", "0", "--out", str(tmp_path), "--quiet"],
                        capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    assert (tmp_path / "report.json").exists() and (tmp_path / "alpha-1.5_body2.vtu").exists()
    assert (tmp_path / "alpha-1.5_pressure.png").exists()
    for bad in (["--scene", "nope"], ["--study", "alpha-3", "--levels", "0", "2", "3"]):
        out = subprocess.run([sys.executable, "-m", "fem_validation", *bad,
                              "--out", str(tmp_path)], capture_output=True, text=True)
        assert out.returncode == 2 and out.stderr.count("\n") == 1, out.stderr
        assert "Traceback" not in out.stderr


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


# --- slow: the default level against Hertz ---------------------------------------------

#: Errors observed at the default level (python -m fem_validation --alpha 1 3 10 30 100;
#: alpha = 6 was not run before these tests were written).
OBSERVED = {
    1: {"a_rel_err": -0.00104, "b_rel_err": -0.00196, "p0_rel_err": 0.00204,
        "rms_major": 0.01293, "rms_minor": 0.01156, "edge_a_rel_err": 0.00468,
        "edge_b_rel_err": 0.00001, "approach_rel_err": -0.00029,
        "von_mises_rel_err": -0.00495, "z_von_mises_rel_err": 0.01302,
        "stress_rms_axis": 0.00271, "stress_rms_major_plane": 0.00254,
        "stress_rms_minor_plane": 0.00164},
    10: {"a_rel_err": -0.00182, "b_rel_err": -0.00071, "p0_rel_err": 0.00190,
         "rms_major": 0.00650, "rms_minor": 0.01110, "edge_a_rel_err": -0.00135,
         "edge_b_rel_err": 0.00742, "approach_rel_err": -0.00254,
         "von_mises_rel_err": -0.00254, "z_von_mises_rel_err": -0.00557,
         "stress_rms_axis": 0.00209, "stress_rms_major_plane": 0.00143,
         "stress_rms_minor_plane": 0.00156},
}
FLOOR = 0.0005


def _tolerances(observed):
    return {k: max(1.5 * abs(v), FLOOR) for k, v in observed.items()}


@pytest.fixture(scope="module")
def default_level_alpha_1():
    scene = fv.equal_steel(1)
    mesh = fvm.build(scene)
    sol = fvs.solve_contact(scene, mesh)
    return scene, mesh, sol, fvrun.compare_with_hertz(scene, mesh, sol, fvm.DEFAULT_LEVEL, 0.0)


@pytest.mark.slow
def test_alpha_1_at_the_default_level(default_level_alpha_1):
    *_, r = default_level_alpha_1
    assert fv.check(r) == []
    assert fv.check(r, _tolerances(OBSERVED[1])) == []
    assert r.max_penetration_over_delta <= 1e-3


@pytest.mark.slow
def test_a_wrong_reference_fails(default_level_alpha_1):
    """Mutation: Hertz's a made 1.5% too large must fail both the issue's targets and the
    tests' tolerances; the true reference passes (test above)."""
    scene, mesh, sol, _ = default_level_alpha_1

    class Wrong:
        def __init__(self, contact, scale):
            self._c, self.a = contact, contact.a * scale

        def __getattr__(self, name):
            return getattr(self._c, name)

        def pressure(self, x, y):
            r2 = (np.asarray(x) / self.a) ** 2 + (np.asarray(y) / self._c.b) ** 2
            return self._c.p0 * np.sqrt(np.clip(1 - r2, 0, None))

    for scale in (1.01, 1.015, 0.985):
        wrong = fvrun.compare_with_hertz(scene, mesh, sol, fvm.DEFAULT_LEVEL, 0.0,
                                       hertz_at=lambda load, s=scale: Wrong(scene.hertz(load),
                                                                            s))
        assert any("a_rel_err" in m for m in fv.check(wrong, _tolerances(OBSERVED[1])))
        if abs(scale - 1) > 0.01:
            assert any("a_rel_err" in m for m in fv.check(wrong))


@pytest.mark.slow
def test_a_wrong_reference_stress_fails(default_level_alpha_1):
    """Mutation: Hertz's stresses scaled by 1.5% (or the depth of the von Mises maximum
    moved by 3%) must fail the comparison; the true reference passes (test above)."""
    scene, mesh, sol, _ = default_level_alpha_1
    tolerances = _tolerances(OBSERVED[1])

    class Scaled:
        def __init__(self, contact, scale, depth_scale):
            self._c, self._s, self._d = contact, scale, depth_scale

        def __getattr__(self, name):
            return getattr(self._c, name)

        def stress(self, x, y, z, body=1):
            return self._s * self._c.stress(x, y, z, body=body)

        def subsurface(self, body=1):
            exact = self._c.subsurface(body)
            return SimpleNamespace(von_mises=self._s * exact.von_mises,
                                   z_von_mises=self._d * exact.z_von_mises)

    def compared(scale, depth_scale=1.0):
        return fvrun.compare_with_hertz(
            scene, mesh, sol, fvm.DEFAULT_LEVEL, 0.0,
            hertz_at=lambda load: Scaled(scene.hertz(load), scale, depth_scale))

    for scale in (1.01, 1.015, 0.985):
        wrong = compared(scale)
        assert any("von_mises_rel_err" in m for m in fv.check(wrong, tolerances)), scale
        if scale == 1.015:
            assert any("von_mises_rel_err" in m for m in fv.check(wrong))
            assert any("stress_rms" in m for m in fv.check(wrong, tolerances))
    deeper = compared(1.0, 1.03)
    assert any("z_von_mises_rel_err" in m for m in fv.check(deeper))
    assert any("z_von_mises_rel_err" in m for m in fv.check(deeper, tolerances))


#: Largest |sigma_zz - Hertz| on the axis of alpha 1 at the default level, 0.2 a to 3 a deep,
#: over p0, per body: patch recovery, and the volume-weighted nodal average it replaced.
SZZ_RECOVERED = (0.0074, 0.0074)
SZZ_AVERAGE = (0.0088, 0.0135)


@pytest.mark.slow
def test_axis_stress_at_the_default_level(default_level_alpha_1):
    """sigma_zz on the axis against Hertz's closed form (Johnson 1985 sec. 3.5, see
    docs/bibliography.md), 0.2 a to 3 a deep,
    and the recovery against the nodal average on the same solution.

    Observed: sigma_zz within 0.74% of p0 in both bodies, against 0.88% and 1.35% for the
    nodal average; the depth of the von Mises maximum +1.3% / -0.1% off, against +4.7% /
    -3.3% (the average's bias: a node's tetrahedra in the cut grid are not centred on it)."""
    scene, mesh, sol, r = default_level_alpha_1
    c = scene.hertz(sol.force)
    average_depth_errors = []
    for i, name in enumerate(("body1", "body2")):
        depth, stress = r.axis_stress[name]["depth"], r.axis_stress[name]["stress"]
        sel = (depth > 0.2 * c.a) & (depth < 3 * c.a)
        exact = -c.p0 * c.a * c.b / np.sqrt((c.a**2 + depth[sel] ** 2)
                                            * (c.b**2 + depth[sel] ** 2))
        assert np.abs(stress[sel, 2, 2] - exact).max() < 1.5 * SZZ_RECOVERED[i] * c.p0
        m, u, body = mesh.bodies[i], (sol.u1, sol.u2)[i], (scene.body1, scene.body2)[i]
        average = fve.nodal_average(m.p, m.t, fve.element_stress(m.p, m.t, u, body.E, body.nu))
        rot = fvsurf.ellipse_rotation(c.major_axis_angle, i + 1)
        average = np.einsum("ij,njk,lk->nil", rot, average[mesh.axis[i]], rot)
        assert np.abs(average[sel, 2, 2] - exact).max() == pytest.approx(
            SZZ_AVERAGE[i] * c.p0, rel=0.05)
        top = fvg.peak(depth, fve.von_mises(average))
        average_depth_errors.append(top["depth"] / c.subsurface(i + 1).z_von_mises - 1)
    assert max(abs(e) for e in average_depth_errors) > 0.03  # what the recovery removes


@pytest.mark.slow
@pytest.mark.parametrize("alpha", [10])
def test_targets_at_the_default_level(alpha):
    r = fv.validate(fv.equal_steel(alpha))
    assert fv.check(r) == []
    assert fv.check(r, _tolerances(OBSERVED[alpha])) == []


@pytest.mark.slow
def test_an_alpha_not_tuned_on():
    r = fv.validate(fv.equal_steel(6))
    assert fv.check(r) == []
    assert abs(r.approach_rel_err) < 0.005
    assert abs(r.edge_a_rel_err) < 0.01 and abs(r.edge_b_rel_err) < 0.01


@pytest.mark.slow
def test_orientation_of_the_crossed_scene():
    r = fv.validate(fv.crossed_30deg(), level=3)  # observed: a -0.41%, b -0.27%
    assert abs(r.angle_err_deg) < 0.3
    assert abs(r.a_rel_err) < 0.0065 and abs(r.b_rel_err) < 0.0045


@pytest.mark.slow
def test_refinement_study_converges(tmp_path):
    from fem_validation.runs.study import refinement_study

    study = refinement_study(fv.equal_steel(3), [2, 3, 4], tmp_path)
    assert json.loads((tmp_path / "study.json").read_text())["rates"] == study["rates"]
    rows = study["levels"]
    for q in ("a_rel_err", "b_rel_err", "p0_rel_err", "rms_major", "rms_minor"):
        errors = [abs(row[q]) for row in rows]
        assert errors[0] > errors[1] > errors[2], (q, errors)
    for q, value in study["extrapolated"].items():
        assert abs(value) < 0.002, (q, value)
    assert all(rate > 0.8 for rate in study["rates"].values()), study["rates"]
