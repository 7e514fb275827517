"""Contact.stress / subsurface / first_yield_load and the line contact's, through the API.

References: published values (Johnson, Contact Mechanics; Harris), the closed forms on
the z axis (the ellipsoidal potential of Thomas & Hoersch 1930 and Johnson 1985 sec. 3.5,
written with Carlson's R_D) and of the orthogonal shear stress (Lundberg & Palmgren 1947)
evaluated here with mpmath (the works: docs/bibliography.md), and physical invariants
(equilibrium, surface traction, symmetry, the line-contact limit).
"""

import json
import math
from dataclasses import fields

import mpmath as mp
import numpy as np
import pytest
from reference import contact_ref, curvatures_ref, ellipse_ref
from reference_stress import axis_maxima_ref

import hertz
from hertz._stress import load_for_p0
from hertz.cli import main

# scenes far outside Hertz's a << R on purpose (ranges, extremes): the warning is tested
# in tests/test_newcomer.py
pytestmark = pytest.mark.filterwarnings("ignore::hertz.HertzValidityWarning")

STEEL = (210e9, 0.3)


def point_contact(ratio=1.0, nu=0.3, load=100.0):
    """A contact with a / b close to ``ratio`` (ellipsoid on a plane) and p0 ~ GPa."""
    if ratio == 1.0:
        b1 = hertz.Body.sphere(0.01, 210e9, nu)
    else:  # a/b ~ alpha**(2/3) (Greenwood), good enough to place the ratio
        b1 = hertz.Body(0.01, 0.01 * ratio ** 1.5, 210e9, nu)
    return hertz.contact(b1, hertz.Body.plane(210e9, nu), load=load)


# ------------------------------------------------------------ published values

def test_circle_published_values():
    c = point_contact()
    m = c.subsurface()
    assert m.tau_max / c.p0 == pytest.approx(0.3100, abs=5e-5)
    assert m.z_tau_max / c.a == pytest.approx(0.4809, abs=5e-5)
    assert m.von_mises / c.p0 == pytest.approx(0.6200, abs=5e-5)
    assert m.tau_orthogonal / c.p0 == pytest.approx(0.2139, abs=5e-5)
    assert m.y_tau_orthogonal / c.b == pytest.approx(0.848, abs=5e-4)
    assert m.z_tau_orthogonal / c.b == pytest.approx(0.351, abs=5e-4)
    assert m.tensile / c.p0 == pytest.approx((1 - 2 * 0.3) / 3, rel=1e-12)


def test_line_contact_published_values():
    lc = hertz.line_contact(hertz.Body.cylinder(0.01, *STEEL), hertz.Body.plane(*STEEL), 1e5)
    m = lc.subsurface()
    assert m.tau_max / lc.p0 == pytest.approx(0.3004, abs=5e-4)
    assert m.z_tau_max / lc.half_width == pytest.approx(0.7861, abs=5e-4)
    assert m.tau_orthogonal / lc.p0 == pytest.approx(0.25, rel=1e-12)
    assert m.z_tau_orthogonal / lc.half_width == pytest.approx(0.5, rel=1e-12)
    assert m.x_tau_orthogonal / lc.half_width == pytest.approx(math.sqrt(3) / 2, rel=1e-12)



@pytest.mark.parametrize("nu", [0.0, 0.1, 0.2, 0.3, 0.45])
def test_line_contact_shear_counts_the_out_of_plane_stress(nu):
    """(s1 - s3)/2 over all three principal stresses: McEwen's axis stresses
    s_xx = -p0 ((1 + 2 t^2)/sqrt(1 + t^2) - 2 t), s_zz = -p0/sqrt(1 + t^2) (t = z/b),
    s_yy = nu (s_xx + s_zz) in plane strain, maximised with mpmath."""
    lc = hertz.line_contact(hertz.Body.cylinder(0.01, 210e9, nu), hertz.Body.plane(210e9, nu),
                            1e5)
    m = lc.subsurface()
    with mp.workdps(30):
        def tau(t):
            r = mp.sqrt(1 + t * t)
            sxx, szz = -((1 + 2 * t * t) / r - 2 * t), -1 / r
            syy = nu * (sxx + szz)
            return (max(sxx, syy, szz) - min(sxx, syy, szz)) / 2
        ts = [mp.mpf(k) / 400 for k in range(0, 801)]
        t0 = max(ts, key=tau)
        if t0 > 0:  # refine the interior maximum
            t0 = mp.findroot(lambda t: mp.diff(tau, t), t0)
        ref_tau, ref_z = tau(t0), t0
    assert m.tau_max / lc.p0 == pytest.approx(float(ref_tau), rel=1e-12)
    assert m.z_tau_max / lc.half_width == pytest.approx(float(ref_z), rel=1e-8, abs=1e-300)


# ------------------------------------------------- closed forms on the z axis

def axis_reference(a, b, nu, z):
    """sigma_x, sigma_y, sigma_z / p0 on the z axis (Johnson 1985 sec. 3.5 with Carlson's
    R_D; docs/bibliography.md), 40 digits."""
    with mp.workdps(40):
        a, b, nu, z = (mp.mpf(v) for v in (a, b, nu, z))
        s = z * z
        A, B = a * a + s, b * b + s
        rd = mp.elliprd
        sz = -a * b / mp.sqrt(A * B)
        if a == b:
            tail_x = tail_y = (1 - 2 * nu) / (2 * A)
        else:
            tail_x = (1 - 2 * nu) * (1 - mp.sqrt(B / A)) / (a * a - b * b)
            tail_y = (1 - 2 * nu) * (mp.sqrt(A / B) - 1) / (a * a - b * b)
        sx = a * b * (2 * (1 - nu) / 3 * z * rd(s, B, A) - 2 * nu / 3 * z * rd(A, B, s) - tail_x)
        sy = a * b * (2 * (1 - nu) / 3 * z * rd(s, A, B) - 2 * nu / 3 * z * rd(A, B, s) - tail_y)
        return sx, sy, sz


@pytest.mark.parametrize("ratio, nu", [(1.0, 0.3), (1.0001, 0.25), (2.0, 0.3), (9.0, 0.5),
                                       (30.0, 0.0), (3.0, -0.5)])
def test_axis_stresses_against_closed_forms(ratio, nu):
    c = point_contact(ratio, nu)
    a, b = c.a, c.b
    for depth in (1e-3, 0.1, 0.48, 1.0, 3.0, 30.0):
        z = depth * b
        s = c.stress(0.0, 0.0, z) / c.p0
        ref = axis_reference(a, b, nu, z)
        for got, exact in zip((s[0, 0], s[1, 1], s[2, 2]), ref, strict=True):
            assert abs(got - float(exact)) <= 1e-12, (depth, got, exact)
        assert np.max(np.abs([s[0, 1], s[0, 2], s[1, 2]])) <= 1e-13  # principal on the axis


def test_orthogonal_shear_closed_form():
    for ratio in (1.0, 2.0, 5.0, 20.0):
        c = point_contact(ratio)
        m = c.subsurface()
        with mp.workdps(40):
            k2 = (mp.mpf(c.b) / mp.mpf(c.a)) ** 2
            t = mp.findroot(lambda t, k2=k2: (t * t - 1) * (2 * t - 1) - k2, 1 + k2)
            tau = mp.sqrt(2 * t - 1) / (2 * t * (t + 1))
            z0 = 1 / ((t + 1) * mp.sqrt(2 * t - 1))
        assert m.tau_orthogonal / c.p0 == pytest.approx(float(tau), rel=1e-12)
        assert m.z_tau_orthogonal / c.b == pytest.approx(float(z0), rel=1e-8)


# ------------------------------------------------------------------ invariants

@pytest.mark.parametrize("ratio", [1.0, 3.0, 12.0])
def test_equilibrium_by_finite_differences(ratio):
    c = point_contact(ratio, 0.28)
    rng = np.random.default_rng(2)
    h = 1e-4 * c.b
    for _ in range(12):
        x, y = rng.uniform(-1.5, 1.5) * c.a, rng.uniform(-1.5, 1.5) * c.b
        z = rng.uniform(0.05, 2.0) * c.b
        div = np.zeros(3)
        for axis in range(3):
            step = np.zeros(3)
            step[axis] = h
            plus = c.stress(*(np.array([x, y, z]) + step))
            minus = c.stress(*(np.array([x, y, z]) - step))
            div += (plus[axis, :] - minus[axis, :]) / (2 * h)
        assert np.max(np.abs(div)) * c.b / c.p0 <= 1e-6


def test_surface_traction_and_symmetry():
    c = point_contact(4.0, 0.3)
    x = np.array([0.0, 0.3, -0.7, 0.99, 1.2, 3.0]) * c.a
    y = np.array([0.0, 0.2, 0.5, 0.0, 0.0, -1.0]) * c.b
    s = c.stress(x, y, 0.0)
    p = c.pressure(x, y)
    np.testing.assert_allclose(s[:, 2, 2], -p, atol=1e-12 * c.p0)
    np.testing.assert_allclose(s[:, 0, 2], 0.0, atol=1e-12 * c.p0)
    np.testing.assert_allclose(s[:, 1, 2], 0.0, atol=1e-12 * c.p0)
    pts = (0.4 * c.a, 0.7 * c.b, 0.3 * c.b)
    base = c.stress(*pts)
    mirror_x = c.stress(-pts[0], pts[1], pts[2])
    np.testing.assert_allclose(mirror_x * np.array([[1, -1, -1], [-1, 1, 1], [-1, 1, 1]]), base,
                               atol=1e-14 * c.p0)


def test_point_contact_tends_to_the_line_contact():
    lc = hertz.line_contact(hertz.Body.cylinder(0.01, *STEEL), hertz.Body.plane(*STEEL), 1e5)
    line = lc.subsurface()
    ratios = [10.0, 100.0, 1000.0]
    gaps = []
    for ratio in ratios:
        c = point_contact(ratio)
        m = c.subsurface()
        gaps.append(abs(m.tau_max / c.p0 - line.tau_max / lc.p0))
        assert m.z_tau_max / c.b == pytest.approx(line.z_tau_max / lc.half_width, rel=0.05)
    assert gaps[0] > gaps[1] > gaps[2] and gaps[2] < 1e-3


def test_stresses_at_the_end_of_the_double_range():
    """NaN from 1e306 m (issue 18, item 4): the far field is Boussinesq's (Flamant's) force,
    p0 (a/R)**2 (p0 b/R), here far below the smallest double or, for the line contact at
    R = 1.4e300 m, Flamant's -(2 P'/pi) cos(theta)/R with P' = pi b p0 / 2."""
    c = point_contact(2.0)
    for point in ((1e306, 0.0, 1e-5), (1.7e308, -1.7e308, 1.7e308), (0.0, 0.0, 1e308)):
        s = c.stress(*point)
        assert np.all(s == 0.0), point
    lc = hertz.line_contact(hertz.Body.cylinder(0.01, *STEEL), hertz.Body.plane(*STEEL), 1e5)
    assert np.all(lc.stress(1e308, 1e-5) == 0.0)
    s = lc.stress(1e300, 1e300)
    # sigma_r at theta = 45 degrees; sxx = szz = sxz = sigma_r / 2, syy = nu sigma_r
    radial = -mp.mpf(lc.half_width) * lc.p0 * mp.sqrt(0.5) / (mp.sqrt(2) * mp.mpf(1e300))
    ref = [float(radial / 2)] * 3 + [float(radial * mp.mpf(0.3))]
    ours = [s[0, 0], s[2, 2], s[0, 2], s[1, 1]]
    np.testing.assert_allclose(ours, ref, rtol=7e-16)  # observed 4.3e-16


# ----------------------------------------------------------- API and first yield

def test_shapes_and_bodies():
    balls = hertz.Body.sphere(np.array([0.01, 0.02]), 210e9, 0.3)
    plane = hertz.Body.plane(70e9, 0.45)
    c = hertz.contact(balls, plane, load=100.0)
    assert c.stress(0.0, 0.0, np.zeros((4, 1, 1)) + c.b[0]).shape == (4, 1, 2, 3, 3)
    m1, m2 = c.subsurface(1), c.subsurface(2)
    assert m1.tau_max.shape == (2,) and not np.allclose(m1.von_mises, m2.von_mises)
    one = hertz.contact(hertz.Body.sphere(0.02, 210e9, 0.3), plane, load=100.0).subsurface(2)
    assert one.von_mises == m2.von_mises[1]
    with pytest.raises(ValueError, match="body must be 1 or 2"):
        c.subsurface(3)
    with pytest.raises(ValueError, match="z must be a depth >= 0"):
        c.stress(0.0, 0.0, -1e-6)
    # b/a = 5e-153: the kernel's range ends at 1e-70, so it names the line contact
    cylinder = hertz.contact(hertz.Body(1e-2, 1e300, *STEEL), plane, load=1.0)
    for call in (cylinder.subsurface, lambda: cylinder.stress(0.0, 0.0, cylinder.b)):
        with pytest.raises(ValueError, match=r"b/a >= 1e-70 .*use hertz.line_contact"):
            call()


def test_a_contact_without_load_has_no_stresses():
    """A zero load is a valid contact (a = b = p0 = 0): every stress is 0 and the maxima
    are 0 at the origin (the limit of a vanishing load), not a 'line contact' error."""
    ball, plane = hertz.Body.sphere(0.01, *STEEL), hertz.Body.plane(*STEEL)
    pair = hertz.contact(ball, plane, load=[0.0, 100.0])
    one = hertz.contact(ball, plane, load=100.0)
    zero = hertz.contact(ball, plane, load=0.0)
    points = (np.array([0.0, 1e-4, -3e-4]), 2e-5, np.array([[0.0], [5e-5]]))
    with np.errstate(all="raise"):
        assert np.all(zero.stress(*points) == 0.0) and zero.stress(0.0, 0.0, 0.0).shape == (3, 3)
        assert zero.pressure(0.0, 0.0) == 0.0 and zero.pressure(1, np.inf) == 0.0
        s = pair.stress(*(np.asarray(v)[..., None] for v in points))
        assert np.all(s[..., 0, :, :] == 0.0)
        np.testing.assert_array_equal(s[..., 1, :, :], one.stress(*points))
        for m in (zero.subsurface(), zero.subsurface(2)):
            assert all(getattr(m, f.name) == 0.0 for f in fields(m))
        m = pair.subsurface()
        for f in fields(m):
            assert getattr(m, f.name)[0] == 0.0
            assert getattr(m, f.name)[1] == getattr(one.subsurface(), f.name), f.name
    lc = hertz.line_contact(hertz.Body.cylinder(0.01, *STEEL), plane, [0.0, 1e5])
    lc1 = hertz.line_contact(hertz.Body.cylinder(0.01, *STEEL), plane, 1e5)
    with np.errstate(all="raise"):
        lc0 = hertz.line_contact(hertz.Body.cylinder(0.01, *STEEL), plane, 0.0)
        assert lc0.pressure(0.0) == 0.0 and np.all(lc0.stress(0.0, 0.0) == 0.0)
        s = lc.stress(np.array([[0.0], [3e-5]]), 4e-5)
        assert np.all(s[:, 0] == 0.0)
        np.testing.assert_array_equal(s[:, 1], lc1.stress(np.array([0.0, 3e-5]), 4e-5))
        m = lc.subsurface()
        for f in fields(m):
            assert getattr(m, f.name)[0] == 0.0
            assert getattr(m, f.name)[1] == getattr(lc1.subsurface(), f.name), f.name


@pytest.mark.parametrize("call, match", [
    (lambda c, lc: c.stress([0.0, np.nan], 0.0, 0.0),
     r"^x must be a finite coordinate in m, got nan at index 1$"),
    (lambda c, lc: c.stress(0.0, [[0.0, 1.0], [np.inf, 0.0]], 0.0),
     r"^y must be a finite coordinate in m, got inf at index \(1, 0\)$"),
    (lambda c, lc: c.stress(0.0, 0.0, [0.0, 1e-6, -1e-6]),
     r"^z must be a depth >= 0 in m \(finite\), got -1e-06 at index 2$"),
    (lambda c, lc: c.stress(0.0, 0.0, np.inf), r"^z must be a depth >= 0 .*got inf$"),
    (lambda c, lc: c.pressure(np.nan, 0.0), r"^x must be a coordinate in m \(not NaN\), got nan$"),
    (lambda c, lc: c.pressure(0.0, [1.0, np.nan]), r"^y must be .*got nan at index 1$"),
    (lambda c, lc: lc.pressure([np.nan]), r"^x must be a coordinate .*got nan at index 0$"),
    (lambda c, lc: lc.stress([1.0, -np.inf], 0.0), r"^x must be .*got -inf at index 1$"),
    (lambda c, lc: lc.stress(0.0, [0.0, -2.0]), r"^z must be .*got -2.0 at index 1$"),
    (lambda c, lc: c.stress(0.0, 0.0, 0.0, body=1.0), r"^body must be 1 or 2, got 1.0$"),
    (lambda c, lc: c.subsurface(body=True), r"^body must be 1 or 2, got True$"),
    (lambda c, lc: lc.subsurface(body="2"), r"^body must be 1 or 2, got '2'$"),
    (lambda c, lc: c.first_yield_load(1e9, body=2.0), r"^body must be 1 or 2, got 2.0$"),
    (lambda c, lc: c.first_yield_load([1e9, np.nan]), r"yield_strength .*got nan at index 1$"),
])
def test_bad_points_and_bodies_name_the_parameter_value_and_index(call, match):
    c = point_contact()
    lc = hertz.line_contact(hertz.Body.cylinder(0.01, *STEEL), hertz.Body.plane(*STEEL), 1e5)
    with pytest.raises(ValueError, match=match):
        call(c, lc)


def test_pressure_at_infinity_is_zero_and_bodies_may_be_numpy_integers():
    c = point_contact()
    assert c.pressure(np.inf, 0.0) == 0.0 and c.pressure(0.0, -np.inf) == 0.0
    np.testing.assert_array_equal(c.stress(0.0, 0.0, c.a, body=np.int64(2)),
                                  c.stress(0.0, 0.0, c.a, body=2))


def test_a_contact_beyond_the_stress_kernels_range_is_named_by_its_index():
    plane = hertz.Body.plane(*STEEL)
    c = hertz.contact(hertz.Body([1e-2, 1e-2], [1e-2, 1e300], *STEEL), plane, load=1.0)
    for call in (c.subsurface, lambda: c.stress(0.0, 0.0, 1e-6)):
        with pytest.raises(ValueError, match=r"b/a >= 1e-70 .*line_contact.*at index 1$"):
            call()


@pytest.mark.parametrize("criterion", ["von_mises", "tresca"])
def test_first_yield_load_reaches_the_yield_strength(criterion):
    ball, race = hertz.Body.sphere(6e-3, *STEEL), hertz.Body(-6.2e-3, 40e-3, *STEEL)
    c = hertz.contact(ball, race, load=1500.0)
    load = c.first_yield_load(1.2e9, criterion=criterion)
    m = hertz.contact(ball, race, load=load).subsurface()
    reached = m.von_mises if criterion == "von_mises" else 2 * m.tau_max
    assert reached == pytest.approx(1.2e9, rel=1e-13)
    with pytest.raises(ValueError, match="yield_strength must be a positive"):
        c.first_yield_load(-1.0)
    with pytest.raises(ValueError, match="criterion must be one of"):
        c.first_yield_load(1e9, criterion="rankine")


def test_first_yield_load_does_not_depend_on_the_contacts_own_load():
    """Issue 18, item 4: inf at a load of 1e-310, NaN from approach=1e308. The first-yield
    load of the default scene (1.5 GPa) against mpmath: the ellipse, E*, the curvatures and
    the largest von Mises stress on the axis (reference.py, reference_stress.py), then
    P = (8 pi/3) lambda (E(m) p0 / (E* rho_sum))**2 p0. Observed error 8.2e-16."""
    ball, race = (6e-3, 6e-3, *STEEL), (-6.2e-3, 40e-3, *STEEL)
    rho_x, rho_y = curvatures_ref(6e-3, 6e-3, -6.2e-3, 40e-3, 0.0)
    lam, _, _, ellip_e = ellipse_ref(rho_x / rho_y)
    e_star = 1 / (2 * (1 - mp.mpf(0.3) ** 2) / mp.mpf(210e9))
    p0 = mp.mpf(1.5e9) / axis_maxima_ref(1, 1 / lam, 0.3, dps=25, npts=40)["von_mises"][0]
    expected = 8 * mp.pi / 3 * lam * (ellip_e * p0 / (e_star * (rho_x + rho_y))) ** 2 * p0
    assert float(expected) == pytest.approx(2969.17, abs=0.005)
    b1, b2 = hertz.Body(*ball), hertz.Body(*race)
    contacts = [hertz.contact(b1, b2, load=load) for load in (5e-324, 1e-310, 0.0, 1.0, 1500.0,
                                                              1e300)]
    contacts += [hertz.contact(b1, b2, approach=1e308), hertz.contact(b1, b2, p0=1e-300)]
    with np.errstate(all="raise"):
        loads = [c.first_yield_load(1.5e9) for c in contacts]
    assert len(set(loads)) == 1
    assert abs(loads[0] - expected) <= 1.2e-15 * expected
    batch = hertz.contact(b1, b2, load=[0.0, 1e-310, 1e300]).first_yield_load([1.5e9, 3e9, 1e8])
    assert batch[0] == loads[0] and batch[1] == pytest.approx(8 * loads[0], rel=2e-15)


def test_load_for_a_peak_pressure_against_mpmath():
    """The geometry-only load of first yield, P(p0), gives back p0 through the seed's
    contact formulas in mpmath (reference.py), for random bodies, angles and pressures,
    and for curvatures and pressures far from the usual: tiny or huge radii and p0."""
    rng = np.random.default_rng(3)
    scenes = []
    for _ in range(40):
        r1, r2 = 10 ** rng.uniform(-4, 0, 2), 10 ** rng.uniform(-4, 0, 2)
        scenes.append(((r1[0], r1[1], 10 ** rng.uniform(9, 12), rng.uniform(-0.9, 0.5)),
                       (r2[0], r2[1], 10 ** rng.uniform(9, 12), rng.uniform(-0.9, 0.5)),
                       rng.uniform(-math.pi, math.pi), 10 ** rng.uniform(5, 11)))
    # P ~ (p0 / (E* rho))**2 p0: these give 0.1 N, 1e168 N, 1e-298 N and 1e212 N
    scenes += [((1e-200, 2e-200, *STEEL), (math.inf, math.inf, *STEEL), 0.3, 1e140),
               ((1e200, 3e200, *STEEL), (-5e200, 1e201, *STEEL), 0.0, 1e-70),
               ((1e-3, 2e-3, *STEEL), (math.inf, math.inf, *STEEL), 1.0, 1e-90),
               ((1e-3, 2e-3, *STEEL), (math.inf, math.inf, *STEEL), 1.0, 1e80)]
    worst = 0.0
    for b1, b2, angle, p0 in scenes:
        c = hertz.contact(hertz.Body(*b1), hertz.Body(*b2), load=0.0, angle=angle)
        load = load_for_p0(p0, c.ellipticity, c.E, c.e_star, c.rho_sum)
        assert 0.0 < load < math.inf
        ref = contact_ref(b1, b2, load, angle)
        worst = max(worst, float(abs(ref.p0 - p0) / p0))
    assert worst <= 4e-16   # observed 2.6e-16 (the load within 3x that)


def test_load_for_a_peak_pressure_round_trips():
    ball, race = hertz.Body.sphere(6e-3, *STEEL), hertz.Body(-6.2e-3, 40e-3, *STEEL)
    for p0 in (1e6, 2e9, 4.5e9):
        back = hertz.contact(ball, race, p0=hertz.contact(ball, race, p0=p0).p0)
        assert back.p0 == p0
        c = hertz.contact(ball, race, p0=p0)
        assert hertz.contact(ball, race, load=c.load).p0 == pytest.approx(p0, rel=4e-15)


# ------------------------------------------------------------------------ CLI

def test_cli_prints_the_maxima(capsys):
    assert main(["--yield-strength", "1.5e9"]) == 0
    out = capsys.readouterr().out
    assert "largest von Mises stress" in out and "first yield, von Mises" in out
    assert main(["--json", "--yield-strength", "1.5e9"]) == 0
    data = json.loads(capsys.readouterr().out)
    c = hertz.contact(hertz.Body(6e-3, 6e-3, *STEEL), hertz.Body(-6.2e-3, 40e-3, *STEEL),
                      load=1500.0)
    assert data["stresses"]["body1"]["von_mises"] == c.subsurface(1).von_mises
    assert data["stresses"]["body2"]["first_yield_load_tresca"] == pytest.approx(
        c.first_yield_load(1.5e9, body=2, criterion="tresca"), rel=1e-15)
    assert main(["--yield-strength", "-1"]) == 2
    assert "yield_strength must be a positive" in capsys.readouterr().err


def test_cli_plot(tmp_path, capsys):
    pytest.importorskip("matplotlib")
    path = tmp_path / "stress.png"
    assert main(["--plot", str(path)]) == 0
    assert path.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(["--plot", str(tmp_path / "no" / "such" / "dir.png")]) == 2
    assert "cannot write the plot" in capsys.readouterr().err
