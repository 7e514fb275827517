"""fem_validation's true curved bodies: the contact search, the meshes, and (slow) Hertz.

Skipped without the ``fem`` extra (scikit-fem, gmsh, pyamg), which the wheel
builds' test runs do not install.  The slow test's tolerances are about 1.5
times the errors observed (``python -m fem_validation --curved --levels 3 4``).
"""

import json
import subprocess
import sys

import numpy as np
import pytest

pytest.importorskip("skfem")
pytest.importorskip("gmsh")
pytest.importorskip("pyamg")

from skfem import MeshTet  # noqa: E402

import fem_validation.fe.contact_search as cs  # noqa: E402
import fem_validation.runs.curved as cvr  # noqa: E402
import fem_validation.solvers.curved as cv  # noqa: E402
import fem_validation.solvers.curved_mesh as cm  # noqa: E402

# --- closest points on triangles -------------------------------------------------------

UNIT = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])


@pytest.mark.parametrize("point, closest, bary", [
    ((0.2, 0.3, 0.5), (0.2, 0.3, 0.0), (0.5, 0.2, 0.3)),      # above the interior
    ((0.2, 0.3, -0.5), (0.2, 0.3, 0.0), (0.5, 0.2, 0.3)),     # below it
    ((2.0, -1.0, 1.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),     # beyond a vertex
    ((1.0, 1.0, -0.3), (0.5, 0.5, 0.0), (0.0, 0.5, 0.5)),     # beyond the hypotenuse
    ((0.25, -2.0, 0.1), (0.25, 0.0, 0.0), (0.75, 0.25, 0.0)),  # beyond the edge y = 0
])
def test_closest_point_on_a_triangle_closed_form(point, closest, bary):
    c, w = cs.closest_point_on_triangles(np.array([point]), UNIT[None])
    np.testing.assert_allclose(c[0], closest, atol=1e-15)
    np.testing.assert_allclose(w[0], bary, atol=1e-15)


def test_closest_point_against_a_dense_sampling():
    """Random triangles and points: the distance found is the minimum over a fine
    barycentric grid of the triangle, to within the grid's resolution."""
    rng = np.random.default_rng(3)
    n = 40
    tri = rng.normal(size=(n, 3, 3))
    pts = rng.normal(size=(n, 3)) * 2
    c, w = cs.closest_point_on_triangles(pts, tri)
    assert np.all(w >= 0) and np.allclose(w.sum(axis=1), 1)
    np.testing.assert_allclose(np.einsum("ij,ijk->ik", w, tri), c, atol=1e-14)
    s = np.linspace(0, 1, 201)
    u, v = np.meshgrid(s, s)
    keep = u + v <= 1
    grid = np.column_stack([1 - u[keep] - v[keep], u[keep], v[keep]])  # (g, 3)
    for i in range(n):
        sample = grid @ tri[i]
        dist = np.linalg.norm(sample - pts[i], axis=1)
        found = np.linalg.norm(c[i] - pts[i])
        spacing = np.linalg.norm(tri[i] - tri[i].mean(axis=0), axis=1).max() * 2 * s[1]
        assert found <= dist.min() + 1e-12
        assert found >= dist.min() - spacing


# --- projection and gaps on known surfaces ---------------------------------------------


def _surface(m: MeshTet, select):
    """Boundary triangles of m whose three nodes satisfy select(p), with outward normals."""
    facets = m.facets[:, m.boundary_facets()].T
    facets = facets[np.all(select(m.p[:, facets]), axis=1)]
    return facets, cs.outward_normals(m.p, m.t, facets)


def test_outward_normals_of_a_box():
    m = MeshTet.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 2, 3), np.linspace(-1, 0, 5))
    for axis, value, sign in ((2, 0.0, 1), (2, -1.0, -1), (0, 0.0, -1), (1, 2.0, 1)):
        facets, normals = _surface(m, lambda p, a=axis, v=value: np.abs(p[a] - v) < 1e-12)
        expected = np.zeros(3)
        expected[axis] = sign
        np.testing.assert_allclose(normals, np.broadcast_to(expected, normals.shape),
                                   atol=1e-14)


def test_gap_of_points_above_a_plane():
    m = MeshTet.init_tensor(np.linspace(0, 1, 6) ** 1.3, np.linspace(0, 1, 5),
                            np.linspace(-1, 0, 3))
    facets, normals = _surface(m, lambda p: np.abs(p[2]) < 1e-12)
    rng = np.random.default_rng(1)
    pts = np.column_stack([rng.uniform(0, 1, 200), rng.uniform(0, 1, 200),
                           rng.uniform(-0.01, 0.05, 200)])
    proj = cs.project(pts, m.p.T, facets, normals)
    np.testing.assert_allclose(proj.gap, pts[:, 2], atol=1e-15)
    np.testing.assert_allclose(proj.closest[:, :2], pts[:, :2], atol=1e-14)
    np.testing.assert_allclose(proj.normal, np.broadcast_to([0, 0, 1], proj.normal.shape))
    # the barycentric coordinates reproduce the point from the triangle's nodes
    corners = m.p.T[facets[proj.triangle]]
    np.testing.assert_allclose(np.einsum("ij,ijk->ik", proj.bary, corners), proj.closest,
                               atol=1e-14)


def test_gap_of_points_above_a_sphere():
    """Points at radius 1 + d outside a triangulated unit ball: the faceted surface lies
    between the facets' smallest distance r_in from the centre and 1, so the distance
    found is within [d, d + 1 - r_in], the gap (along the facet normal) at most that,
    and the closest point is the nearest over all facets (brute force)."""
    m = MeshTet.init_ball(3)
    facets, normals = _surface(m, lambda p: np.ones(p.shape[1:], dtype=bool))
    x = m.p.T[facets]
    r_in = np.abs(np.einsum("ij,ij->i", normals, x[:, 0])).min()
    rng = np.random.default_rng(7)
    direction = rng.normal(size=(300, 3))
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    d = rng.uniform(0.0, 0.1, 300)
    pts = direction * (1 + d)[:, None]
    proj = cs.project(pts, m.p.T, facets, normals, candidates=2)
    slack = 1 - r_in
    assert 0 < slack < 0.02
    assert np.all(proj.distance >= d - 1e-12) and np.all(proj.distance <= d + slack + 1e-12)
    assert np.all(proj.gap <= proj.distance + 1e-12) and np.all(proj.gap >= d - slack)
    for i in range(0, 300, 30):  # certified search against brute force
        c, _ = cs.closest_point_on_triangles(np.repeat(pts[i:i + 1], len(x), 0), x)
        assert proj.distance[i] == pytest.approx(np.linalg.norm(c - pts[i], axis=1).min(),
                                                 abs=1e-14)


def test_gap_operator_of_linear_displacements():
    """g = g0 + C u: a slave translation t changes g by n.t, a linear master field
    u = grad x by -n.(grad x_c) (the triangle's interpolation is exact for linear fields)."""
    m = MeshTet.init_tensor(np.linspace(0, 1, 4), np.linspace(0, 1, 4), np.linspace(-1, 0, 3))
    facets, normals = _surface(m, lambda p: np.abs(p[2]) < 1e-12)
    rng = np.random.default_rng(2)
    slaves = np.column_stack([rng.uniform(0, 1, 20), rng.uniform(0, 1, 20),
                              rng.uniform(0, 0.1, 20)])
    proj = cs.project(slaves, m.p.T, facets, normals)
    ns = len(slaves)
    ndofs = 3 * ns + 3 * m.nvertices
    gap_op = cs.gap_operator(proj, 3 * np.arange(ns), 3 * ns + 3 * facets, ndofs)
    u = np.zeros(ndofs)
    t = np.array([0.1, -0.2, 0.3])
    u[: 3 * ns] = np.tile(t, ns)
    np.testing.assert_allclose(gap_op @ u, proj.normal @ t, atol=1e-15)
    grad = rng.normal(size=(3, 3))
    u = np.zeros(ndofs)
    u[3 * ns:] = (grad @ m.p).T.ravel()
    expected = -np.einsum("ij,ij->i", proj.normal, proj.closest @ grad.T)
    np.testing.assert_allclose(gap_op @ u, expected, atol=1e-14)


def test_surface_lumped_area():
    m = MeshTet.init_tensor(np.linspace(0, 2, 5) ** 1.5, np.linspace(0, 1, 4),
                            np.linspace(0, 1, 3))
    facets, _ = _surface(m, lambda p: np.abs(p[2] - 1) < 1e-12)
    area = cs.surface_lumped_area(m.p.T, facets, m.nvertices)
    assert area.sum() == pytest.approx(2 ** 1.5, rel=1e-12)
    assert np.all(area[np.abs(m.p[2] - 1) > 1e-12] == 0)


# --- meshes ----------------------------------------------------------------------------


@pytest.mark.parametrize("make", [cm.sphere_plane, cm.ball_groove])
def test_curved_meshes_follow_the_real_geometry(make):
    scene = make(0.05)
    assert scene.hertz().a / scene.radius == pytest.approx(0.05, rel=1e-12)
    mesh = cm.build_curved(scene, 0)
    ball, block = mesh.bodies
    R = scene.radius
    slave = ball.p[:, mesh.slave]
    np.testing.assert_allclose(np.linalg.norm(slave - [[0], [0], [R]], axis=0), R,
                               rtol=1e-9)
    nodes = block.p[:, np.unique(mesh.master)]
    if scene.groove_radius is None:
        assert np.all(np.abs(nodes[2]) < 1e-12)
        assert np.all(mesh.master_normals[:, 2] == pytest.approx(1.0))
    else:
        rg = scene.groove_radius
        np.testing.assert_allclose(np.hypot(nodes[1], nodes[2] - rg), rg, rtol=1e-9)
        assert np.all(mesh.master_normals[:, 2] > 0)
    # the undeformed gap against the distance to the true surface
    proj = cs.project(slave.T, block.p.T, mesh.master, mesh.master_normals)
    if scene.groove_radius is None:
        np.testing.assert_allclose(proj.gap, slave[2], atol=1e-15 * R)
    else:
        exact = rg - np.hypot(slave[1], slave[2] - rg)
        x = block.p.T[mesh.master[proj.triangle]]
        edge = np.linalg.norm(x - np.roll(x, 1, axis=1), axis=2).max()
        # facets are chords: the faceted groove lies inside the cylinder by < edge^2/(8 Rg)
        assert np.all(exact - proj.gap >= -1e-12 * R)
        assert np.all(exact - proj.gap <= edge**2 / (8 * rg))
    np.testing.assert_allclose(ball.p[2, mesh.fixed[0]], R, rtol=1e-12)
    np.testing.assert_allclose(block.p[2, mesh.fixed[1]], -mesh.block_depth, rtol=1e-12)
    # the mesh is refined at the contact, about h0 there
    near = slave[:, np.hypot(slave[0], slave[1]) < scene.hertz().b]
    assert near.shape[1] >= 10
    again = cm.build_curved(scene, 0)
    np.testing.assert_array_equal(again.bodies[0].p, ball.p)
    np.testing.assert_array_equal(again.bodies[1].t, block.t)


def test_bad_curved_arguments():
    with pytest.raises(ValueError, match="^level must"):
        cm.level_scale(7)
    with pytest.raises(ValueError, match="^groove_over_r must"):
        cm.ball_groove(0.1, groove_over_r=0.9)
    for bad in (0.0, -0.1, 0.7):
        with pytest.raises(ValueError, match="^a_over_r must"):
            cm.sphere_plane(bad)


def test_cli_curved(tmp_path):
    ok = subprocess.run([sys.executable, "-m", "fem_validation", "--curved", "--level", "0",
                         "--a-over-r", "0.05", "--out", str(tmp_path), "--quiet"],
                        capture_output=True, text=True)
    assert ok.returncode == 0, ok.stderr
    rows = json.loads((tmp_path / "curved.json").read_text())
    assert [r["scene"] for r in rows] == ["sphere-plane", "ball-groove"]
    for r in rows:
        for key in ("load", "a_over_R", "target_a_over_R", "a_rel_err", "b_rel_err",
                    "p0_rel_err",
                    "approach_rel_err", "dofs", "seconds", "peak_memory_mb"):
            assert key in r
        assert r["a_over_R"] == pytest.approx(0.05, rel=0.05)
        assert abs(r["a_rel_err"]) < 0.05  # level 0 is coarse
    assert (tmp_path / "curved.md").exists() and (tmp_path / "curved.png").exists()
    bad = subprocess.run([sys.executable, "-m", "fem_validation", "--curved", "--level", "5",
                          "--out", str(tmp_path)], capture_output=True, text=True)
    assert bad.returncode == 2 and bad.stderr.count("\n") == 1, bad.stderr


# --- slow: Hertz at small a/R, and the trend -------------------------------------------

#: Errors observed (python -m fem_validation --curved --levels 3 4, and
#: python -m fem_validation --curved --level 2 --a-over-r 0.01 0.2): the sphere on a plane
#: at the default level 3, a/R = 0.01.
OBSERVED_SMALL = {"a_rel_err": -0.0032, "b_rel_err": -0.0032, "p0_rel_err": -0.0017}
#: Both scenes at level 2: the errors at a/R = 0.01 and the net errors at 0.2 (the error
#: less that at 0.01 on the same mesh level: Hertz's own error; levels 3 and 4 agree with
#: these to 0.05%).
OBSERVED_L2 = {
    "sphere-plane": {"small": {"a_rel_err": -0.0056, "b_rel_err": -0.0065,
                               "p0_rel_err": -0.0025},
                     "net": {"a_rel_err": -0.0027, "b_rel_err": -0.0031}},
    "ball-groove": {"small": {"a_rel_err": -0.0105, "b_rel_err": -0.0083,
                              "p0_rel_err": 0.0076},
                    "net": {"a_rel_err": -0.0110, "b_rel_err": 0.0049}},
}


def _tolerances(observed):
    """1.5 times the observed errors, and never more than the issue's 1.5%."""
    return {k: min(1.5 * abs(v), 0.015) for k, v in observed.items()}


def _run(make, a_over_r, level):
    scene = make(a_over_r)
    mesh = cm.build_curved(scene, level)
    sol = cv.solve_curved(scene, mesh)
    return scene, mesh, sol, cvr.compare_curved(scene, mesh, sol)


@pytest.fixture(scope="module")
def sphere_small():
    """The sphere on a plane at a/R = 0.01, default level (about 12 s)."""
    return _run(cm.sphere_plane, 0.01, cm.DEFAULT_CURVED_LEVEL)


@pytest.fixture(scope="module")
def level_2():
    """Both scenes at a/R = 0.01 and 0.2, level 2 (about 30 s), with net errors."""
    rows = [_run(make, x, 2)[3] for make in (cm.sphere_plane, cm.ball_groove)
            for x in (0.01, 0.2)]
    return cvr.net_errors(rows)


@pytest.mark.slow
def test_hertz_holds_at_a_over_r_0_01(sphere_small):
    r = sphere_small[3]
    assert r.a_over_r == pytest.approx(0.01, rel=0.02)
    for key, tol in _tolerances(OBSERVED_SMALL).items():
        assert abs(getattr(r, key)) <= tol, (key, getattr(r, key), tol)
    assert r.max_penetration_over_delta < 1e-3
    assert abs(r.force_rel_err) < 1e-6  # solver diagnostic: the CG residual


@pytest.mark.slow
def test_a_wrong_reference_fails_the_curved_comparison(sphere_small):
    """Mutation: Hertz's a 1% too large or too small fails the tolerance above."""
    scene, mesh, sol, right = sphere_small

    class Wrong:
        def __init__(self, contact, scale):
            self._c, self.a = contact, contact.a * scale

        def __getattr__(self, name):
            return getattr(self._c, name)

    for scale in (1.01, 0.99):
        wrong = cvr.compare_curved(scene, mesh, sol,
                                  hertz_at=lambda load, s=scale: Wrong(scene.hertz(load), s))
        assert abs(wrong.a_rel_err) > _tolerances(OBSERVED_SMALL)["a_rel_err"]
        assert wrong.b_rel_err == right.b_rel_err


@pytest.mark.slow
@pytest.mark.parametrize("scene", ["sphere-plane", "ball-groove"])
def test_hertz_error_grows_with_a_over_r(level_2, scene):
    """At a/R = 0.01 both scenes agree with Hertz (coarse level 2); at 0.2 the error of a
    is larger, and the net error (less the mesh's share) is Hertz's own, as observed."""
    small, large = sorted((r for r in level_2 if r.scene == scene), key=lambda r: r.a_over_r)
    assert small.a_over_r == pytest.approx(0.01, rel=0.03)
    assert large.a_over_r == pytest.approx(0.2, rel=0.03)
    for key, tol in _tolerances(OBSERVED_L2[scene]["small"]).items():
        assert abs(getattr(small, key)) <= tol, (key, getattr(small, key), tol)
    assert abs(large.a_rel_err) > abs(small.a_rel_err) + 0.002
    for key, value in OBSERVED_L2[scene]["net"].items():
        net = large.net_of_smallest[key]
        assert np.sign(net) == np.sign(value), (key, net, value)
        assert abs(value) / 1.5 <= abs(net) <= 1.5 * abs(value), (key, net, value)
