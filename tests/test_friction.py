"""The stress of a sliding (frictional) traction: hertz/_friction.py against an mpmath
quadrature of Cerruti's solution (tests/reference_friction.py, table written by
tools/friction_reference.py), closed forms on the surface of a circle, and invariants."""

import csv
from pathlib import Path

import numpy as np
import pytest

from hertz._friction import (
    partial_slip_stress,
    sliding_maxima,
    sliding_stress,
    surface_von_mises_mu,
)
from hertz._stress import point_stress

DATA = Path(__file__).parent / "data"
NUS = (0.25, 0.3, 0.5)
COMPONENTS = ((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))
# largest difference from the mpmath table observed: 6.7e-16 p0 (33 points x 3 nu)
TABLE_TOL = 1e-15


def _table():
    with (DATA / "friction_reference.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    names = list(rows[0])[5:]
    return [({k: float.fromhex(r[k]) for k in "bxyz"}, float(r["seconds"]),
             np.array([float.fromhex(r[k]) for k in names])) for r in rows]


def _reference(vals, nu):
    return vals[:6] + (1 - 2 * nu) * vals[6:]


def _six(s):
    return np.stack([s[..., i, j] for i, j in COMPONENTS], axis=-1)


def _errors(scale_ref=1.0):
    rows = _table()
    out = []
    for nu in NUS:
        p = {k: np.array([r[0][k] for r in rows]) for k in "bxyz"}
        mine = _six(sliding_stress(1.0, p["b"], 1.0, 1.0, nu, p["x"], p["y"], p["z"]))
        ref = np.array([_reference(r[2], nu) for r in rows]) * scale_ref
        out.append(np.abs(mine - ref).max())
    return max(out)


def test_field_agrees_with_cerruti_quadrature():
    assert _errors() <= TABLE_TOL


def test_a_one_percent_error_in_the_reference_fails():
    assert _errors(1.01) > 100 * TABLE_TOL
    assert _errors(0.99) > 100 * TABLE_TOL


def test_units_scale():
    # a = 2 mm, p0 = 1.5 GPa, mu = 0.3: stress scales with mu p0, positions with a
    rows = _table()[:6]
    for (pt, _, vals) in rows:
        a, p0, mu = 2e-3, 1.5e9, 0.3
        s = sliding_stress(a, pt["b"] * a, p0, mu, 0.3, pt["x"] * a, pt["y"] * a, pt["z"] * a)
        ref = _reference(vals, 0.3) * mu * p0
        assert np.abs(_six(s) - ref).max() <= TABLE_TOL * mu * p0


def test_table_script_reproduces_entries():
    # the cheapest row (on the surface outside the contact), recomputed at lower precision
    from reference_friction import friction_ref12
    rows = sorted(_table(), key=lambda r: r[1])[:1]
    for pt, _, vals in rows:
        got = np.array([float(v) for v in friction_ref12(1.0, pt["b"], pt["x"], pt["y"],
                                                          pt["z"], dps=20, tol=1e-15)])
        assert np.abs(got - vals).max() < 1e-14


@pytest.mark.parametrize("nu", NUS)
def test_circle_surface_closed_forms(nu):
    # Inside a circle, z = 0 (Johnson, Contact Mechanics, sec. 7.2; Hamilton 1983):
    # sxx = -pi (4 + nu) q0 x / (8a), syy = -3 pi nu q0 x / (8a),
    # sxy = -pi (2 - nu) q0 y / (8a), sxz = -q0 sqrt(1 - r^2/a^2)
    a, q0 = 1.5e-3, 2e8
    rng = np.random.default_rng(3)
    r, t = np.sqrt(rng.random(50)) * a, rng.random(50) * 2 * np.pi
    x, y = r * np.cos(t), r * np.sin(t)
    s = sliding_stress(a, a, q0, 1.0, nu, x, y, 0.0)
    np.testing.assert_allclose(s[:, 0, 0], -np.pi * (4 + nu) * q0 * x / (8 * a),
                               rtol=0, atol=3e-15 * q0)
    np.testing.assert_allclose(s[:, 1, 1], -3 * np.pi * nu * q0 * x / (8 * a),
                               rtol=0, atol=3e-15 * q0)
    np.testing.assert_allclose(s[:, 0, 1], -np.pi * (2 - nu) * q0 * y / (8 * a),
                               rtol=0, atol=3e-15 * q0)
    np.testing.assert_allclose(s[:, 0, 2], -q0 * np.sqrt(1 - (r / a) ** 2),
                               rtol=0, atol=3e-15 * q0)
    assert np.all(s[:, 2, 2] == 0) and np.all(s[:, 1, 2] == 0)


@pytest.mark.parametrize("ratio", [1.0, 0.2])
def test_surface_is_the_limit_from_below(ratio):
    # z = 0 has its own limits (inside: l = 0; outside: z J1 -> e1); the field is continuous
    # (the stresses change like sqrt(z) at the edge, like z elsewhere)
    t = np.linspace(0, 2 * np.pi, 13)
    for r in (0.3, 0.9, 1.1, 1.7):
        x, y = r * np.cos(t), ratio * r * np.sin(t)
        s0 = sliding_stress(1.0, ratio, 1.0, 1.0, 0.3, x, y, 0.0)
        s1 = sliding_stress(1.0, ratio, 1.0, 1.0, 0.3, x, y, 1e-10)
        assert np.abs(s0 - s1).max() < 1e-8


def test_surface_traction_is_the_applied_one():
    # sxz = -q on the surface (z into the body), for the sliding and the partial-slip traction
    a, b, p0, mu, c = 1e-3, 0.4e-3, 1e9, 0.3, 0.6
    rng = np.random.default_rng(5)
    r, t = np.sqrt(rng.random(40)) * 0.999, rng.random(40) * 2 * np.pi
    x, y = a * r * np.cos(t), b * r * np.sin(t)
    q = mu * p0 * np.sqrt(1 - r * r)
    s = sliding_stress(a, b, p0, mu, 0.3, x, y, 0.0)
    np.testing.assert_allclose(s[:, 0, 2], -q, rtol=0, atol=1e-14 * p0)
    stick = np.maximum(1 - r * r / (c * c), 0)
    qp = q - c * mu * p0 * np.sqrt(stick)
    s = partial_slip_stress(a, b, p0, mu, 0.3, x, y, 0.0, c)
    np.testing.assert_allclose(s[:, 0, 2], -qp, rtol=0, atol=1e-14 * p0)
    # along y
    s = sliding_stress(a, b, p0, mu, 0.3, x, y, 0.0, direction=np.pi / 2)
    np.testing.assert_allclose(s[:, 1, 2], -q, rtol=0, atol=1e-14 * p0)
    np.testing.assert_allclose(s[:, 0, 2], 0, rtol=0, atol=1e-14 * p0)


@pytest.mark.parametrize("ratio", [1.0, 0.5, 0.2])
def test_equilibrium_of_a_plane(ratio):
    # int sxz dA over z = h is -Q = -mu (2/3) pi a b p0; int syz = int szz = 0. Polar grid to
    # r = 1000 a, Cerruti's point-force tail beyond it added in closed form.
    h, rmax = 0.6, 1000.0
    nodes, weights = np.polynomial.legendre.leggauss(20)
    edges = np.concatenate([[0], np.geomspace(0.05, rmax, 30)])
    pieces = list(zip(edges[:-1], edges[1:], strict=True))
    r = np.concatenate([(hi - lo) / 2 * nodes + (hi + lo) / 2 for lo, hi in pieces])
    wr = np.concatenate([(hi - lo) / 2 * weights for lo, hi in pieces])
    t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    R, th = np.meshgrid(r, t, indexing="ij")
    s = sliding_stress(1.0, ratio, 1.0, 1.0, 0.3, R * np.cos(th), R * np.sin(th), h)
    w = (wr * r)[:, None] * (2 * np.pi / t.size)
    force = 2 / 3 * np.pi * ratio
    u = rmax ** 2 + h * h   # tail of -3 Q x^2 z / (2 pi R^5) over r > rmax
    tail = -3 * force * h / 2 * (u ** -0.5 - h * h * u ** -1.5 / 3)
    # observed: 1.6e-10 to 2.7e-10 relative (the tail's own error, (a/r)^2 of it), syz
    # 5e-15, szz 5e-17
    assert abs(np.sum(w * s[..., 0, 2]) + tail + force) < 4e-10 * force
    assert abs(np.sum(w * s[..., 1, 2])) < 1e-14
    # szz: odd in x, cancels over the plane
    assert abs(np.sum(w * s[..., 2, 2])) < 1e-12 * force


def test_far_field_is_cerruti_point_force():
    nu, ratio = 0.3, 0.5
    force = 2 / 3 * np.pi * ratio
    for d in (50.0, 200.0):
        x, y, z = 0.6 * d, -0.3 * d, 0.74 * d
        s = sliding_stress(1.0, ratio, 1.0, 1.0, nu, x, y, z)
        R = np.sqrt(x * x + y * y + z * z)
        k = 1 - 2 * nu
        sxx = x / (2 * np.pi * R ** 3) * (-3 * x * x / R ** 2 + k / (R + z) ** 2 * (
            R * R - y * y - 2 * R * y * y / (R + z)))
        sxz = -3 * x * x * z / (2 * np.pi * R ** 5)
        for got, point in ((s[0, 0], sxx), (s[0, 2], sxz)):
            assert abs(got / (force * point) - 1) < 2 / d ** 2


def test_symmetries_and_zero_friction():
    rng = np.random.default_rng(7)
    x, y, z = rng.normal(size=30), 0.5 * rng.normal(size=30), rng.random(30)
    s = sliding_stress(1.0, 0.5, 1.0, 0.4, 0.3, x, y, z)
    mx = sliding_stress(1.0, 0.5, 1.0, 0.4, 0.3, -x, y, z)
    my = sliding_stress(1.0, 0.5, 1.0, 0.4, 0.3, x, -y, z)
    odd_x = np.array([[1, -1, -1], [-1, 1, 1], [-1, 1, 1]])   # xx yy zz yz odd in x
    odd_y = np.array([[1, -1, 1], [-1, 1, -1], [1, -1, 1]])   # xy, yz odd in y
    np.testing.assert_allclose(mx, -odd_x * s, rtol=0, atol=1e-15)
    np.testing.assert_allclose(my, odd_y * s, rtol=0, atol=1e-15)
    assert np.all(sliding_stress(1.0, 0.5, 1.0, 0.0, 0.3, x, y, z) == 0)
    # reversing the traction reverses the field; any direction is the sum of the two axes
    np.testing.assert_allclose(sliding_stress(1.0, 0.5, 1.0, 0.4, 0.3, x, y, z, np.pi), -s,
                               rtol=0, atol=1e-15)
    th = 0.7
    sy = sliding_stress(1.0, 0.5, 1.0, 0.4, 0.3, x, y, z, np.pi / 2)
    np.testing.assert_allclose(sliding_stress(1.0, 0.5, 1.0, 0.4, 0.3, x, y, z, th),
                               np.cos(th) * s + np.sin(th) * sy, rtol=0, atol=1e-15)
    # traction along y on (a, b) is traction along x on (b, a) with the axes exchanged
    swap = sliding_stress(0.5, 1.0, 1.0, 0.4, 0.3, y, x, z)[..., [1, 0, 2], :][..., [1, 0, 2]]
    np.testing.assert_allclose(sy, swap, rtol=0, atol=1e-15)
    # partial slip: no tangential force, full sliding
    np.testing.assert_allclose(partial_slip_stress(1.0, 0.5, 1.0, 0.4, 0.3, x, y, z, 1.0), 0,
                               atol=1e-15)
    np.testing.assert_array_equal(partial_slip_stress(1.0, 0.5, 1.0, 0.4, 0.3, x, y, z, 0.0), s)


def test_rotated_frame():
    # the field of traction along x on an ellipse with its major axis along y (b/a = 2) is
    # that of traction along -y' in the frame x' = y, y' = -x (a' = 2 along x'); an mpmath
    # spot check of b/a = 2 at (0.3, 0.5, 0.4) agreed to 1.4e-16
    rng = np.random.default_rng(11)
    x, y, z = rng.normal(size=20), rng.normal(size=20), rng.random(20)
    s = sliding_stress(1.0, 2.0, 1.0, 0.3, 0.3, x, y, z)
    s2 = sliding_stress(2.0, 1.0, 1.0, 0.3, 0.3, y, -x, z, direction=-np.pi / 2)
    rot = np.array([[0, 1, 0], [-1, 0, 0], [0, 0, 1]])
    np.testing.assert_allclose(rot.T @ s2 @ rot, s, rtol=0, atol=1e-15)


def _maxima_table():
    with (DATA / "friction_maxima.csv").open() as fh:
        rows = list(csv.DictReader(fh))
    out = []
    for r in rows:
        v = {k: (r[k] if k == "criterion" else float.fromhex(r[k])) for k in r}
        sxx, syy, szz, syz, sxz, sxy = (v[k] for k in ("sxx", "syy", "szz", "syz", "sxz", "sxy"))
        e = np.linalg.eigvalsh(np.array([[sxx, sxy, sxz], [sxy, syy, syz], [sxz, syz, szz]]))
        vm = np.sqrt(((e[0] - e[1]) ** 2 + (e[1] - e[2]) ** 2 + (e[2] - e[0]) ** 2) / 2)
        v["reference"] = vm if v["criterion"] == "von_mises" else (e[2] - e[0]) / 2
        out.append(v)
    return out


def test_maxima_agree_with_mpmath():
    # the value of each maximum against von Mises / tau1 of the mpmath stress (Boussinesq +
    # Cerruti quadratures) at the position found; observed 4.4e-16 p0
    seen = {}
    for v in _maxima_table():
        key = (v["b"], v["mu"], v["nu"])
        if key not in seen:
            seen[key] = sliding_maxima(1.0, v["b"], 1.0, v["mu"], v["nu"])
        m = seen[key]
        c = v["criterion"]
        pos = np.array([getattr(m, f"{axis}_{c}") for axis in "xyz"])
        assert np.abs(pos - [v["x"], v["y"], v["z"]]).max() < 1e-6   # the table is current
        assert abs(getattr(m, c) - v["reference"]) < 7e-16
        assert abs(getattr(m, c) * 1.01 - v["reference"]) > 1e-3
        assert v["z"] > 0.1        # below the surface at these mu
        # and it is a maximum: the field is lower 1e-3 a away in every direction
        d = 1e-3 * np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1],
                             [0, 0, -1]])
        p = pos + d
        s = point_stress(1.0, v["b"], 1.0, v["nu"], *p.T) + sliding_stress(
            1.0, v["b"], 1.0, v["mu"], v["nu"], *p.T)
        e = np.linalg.eigvalsh(s)
        near = (np.sqrt(((e[:, 0] - e[:, 1]) ** 2 + (e[:, 1] - e[:, 2]) ** 2
                         + (e[:, 2] - e[:, 0]) ** 2) / 2) if c == "von_mises"
                else (e[:, 2] - e[:, 0]) / 2)
        assert np.all(near < getattr(m, c))


def test_maxima_without_friction_and_trailing_edge_tension():
    m = sliding_maxima(2e-3, 2e-3, 1e9, 0.0, 0.3)
    # frictionless circle, nu = 0.3 (Johnson 1985 sec. 3.4, to four digits as in
    # tests/test_stress.py): 0.6200 p0 and 0.3100 p0 at 0.4809 a
    assert abs(m.von_mises / 1e9 - 0.62004) < 1e-5 and abs(m.z_von_mises / 2e-3 - 0.48086) < 1e-5
    assert abs(m.tau_max / 1e9 - 0.31002) < 1e-5
    assert abs(m.tensile / 1e9 - 0.4 / 3) < 1e-14
    for mu in (0.1, 0.4):
        m = sliding_maxima(2e-3, 2e-3, 1e9, mu, 0.3)
        # Hamilton 1983: p0 [(1 - 2 nu)/3 + mu pi (4 + nu)/8] at the trailing edge x = -a
        assert abs(m.tensile / 1e9 - (0.4 / 3 + mu * np.pi * 4.3 / 8)) < 1e-14
        assert abs(m.x_tensile + 2e-3) < 1e-12 and abs(m.y_tensile) < 1e-12


def test_partial_slip_maxima():
    # no tangential force (stick ratio 1): the frictionless maxima
    m0 = sliding_maxima(1.0, 0.5, 1.0, 0.0, 0.3)
    m1 = sliding_maxima(1.0, 0.5, 1.0, 0.4, 0.3, stick_ratio=1.0)
    assert abs(m1.von_mises - m0.von_mises) < 1e-14 and abs(m1.tensile - m0.tensile) < 1e-14
    # between no slip and full sliding, at the position found: the partial-slip field's value
    m = sliding_maxima(1.0, 0.5, 1.0, 0.4, 0.3, stick_ratio=0.7)
    ms = sliding_maxima(1.0, 0.5, 1.0, 0.4, 0.3)
    assert m0.von_mises < m.von_mises < ms.von_mises
    s = point_stress(1.0, 0.5, 1.0, 0.3, m.x_von_mises, m.y_von_mises, m.z_von_mises) + \
        partial_slip_stress(1.0, 0.5, 1.0, 0.4, 0.3, m.x_von_mises, m.y_von_mises,
                            m.z_von_mises, 0.7)
    e = np.linalg.eigvalsh(s)
    vm = np.sqrt(((e[0] - e[1]) ** 2 + (e[1] - e[2]) ** 2 + (e[2] - e[0]) ** 2) / 2)
    assert abs(vm - m.von_mises) < 1e-15
    with pytest.raises(ValueError, match="stick_ratio must be one c/a in"):
        sliding_maxima(1.0, 0.5, 1.0, 0.4, 0.3, stick_ratio=-0.1)


def test_maxima_along_the_minor_axis_are_those_of_the_turned_ellipse():
    # traction along y on (a, b) searched in the plane x = 0; along x on (b, a) in y = 0
    m = sliding_maxima(1.0, 0.5, 1.0, 0.3, 0.3, direction=np.pi / 2)
    t = sliding_maxima(0.5, 1.0, 1.0, 0.3, 0.3)
    for name in ("von_mises", "tau_max"):
        assert abs(getattr(m, name) - getattr(t, name)) < 1e-14
        assert abs(getattr(m, f"y_{name}") - getattr(t, f"x_{name}")) < 1e-6
        assert abs(getattr(m, f"z_{name}") - getattr(t, f"z_{name}")) < 1e-6
    assert abs(m.tensile - t.tensile) < 1e-14 and abs(m.y_tensile + 0.5) < 1e-12


def test_von_mises_maximum_reaches_the_surface_near_mu_03():
    # Hamilton 1983: for a sliding sphere the largest von Mises stress is on the surface for
    # mu above about 0.3 (nu = 0.3); here 0.3047
    mu = surface_von_mises_mu(1.0, 0.3)
    assert 0.29 < mu < 0.32
    assert sliding_maxima(1.0, 1.0, 1.0, mu - 0.01, 0.3).z_von_mises > 0.3
    assert sliding_maxima(1.0, 1.0, 1.0, mu + 0.01, 0.3).z_von_mises == 0


def test_sliding_adds_to_the_normal_field_at_the_maximum():
    # the maxima are those of normal + sliding: at mu = 0 the field is the normal one
    s = sliding_stress(1.0, 0.5, 1.0, 0.0, 0.3, 0.1, 0.2, 0.3) + point_stress(
        1.0, 0.5, 1.0, 0.3, 0.1, 0.2, 0.3)
    np.testing.assert_array_equal(s, point_stress(1.0, 0.5, 1.0, 0.3, 0.1, 0.2, 0.3))


@pytest.mark.parametrize("kwargs, match", [
    (dict(mu=-0.1), "mu must be a finite friction coefficient >= 0, got -0.1"),
    (dict(z=[0.1, -1.0]), "z must be a finite depth >= 0 in m, got -1.0 at index 1"),
    (dict(nu=0.6), "nu must be a Poisson's ratio"),
    (dict(a=0.0), "a must be a positive"),
    (dict(x=float("nan")), "x must be a finite coordinate"),
])
def test_bad_input(kwargs, match):
    args = dict(a=1.0, b=0.5, p0=1.0, mu=0.3, nu=0.3, x=0.1, y=0.1, z=0.1)
    args.update(kwargs)
    with pytest.raises(ValueError, match=match):
        sliding_stress(**args)


def test_bad_input_partial_slip_and_maxima():
    with pytest.raises(ValueError, match=r"stick_ratio must be c/a in \[0, 1\], got 1.5"):
        partial_slip_stress(1.0, 0.5, 1.0, 0.3, 0.3, 0.1, 0.1, 0.1, 1.5)
    with pytest.raises(TypeError, match="mu must be a scalar"):
        sliding_maxima(1.0, 0.5, 1.0, [0.1, 0.2], 0.3)
    with pytest.raises(TypeError, match="x must be a real number"):
        sliding_stress(1.0, 0.5, 1.0, 0.3, 0.3, "a", 0.1, 0.1)
