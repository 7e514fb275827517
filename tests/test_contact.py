"""hertz.contact against the seed's formulas in mpmath, closed forms and invariants."""

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from reference import contact_ref

import hertz

# scenes far outside Hertz's a << R on purpose (ranges, extremes): the warning is tested
# in tests/test_newcomer.py
pytestmark = pytest.mark.filterwarnings("ignore::hertz.HertzValidityWarning")

STEEL = dict(E=210e9, nu=0.3)
SCENES = {
    "sphere on plane": ((0.01, 0.01, 210e9, 0.3), (math.inf, math.inf, 210e9, 0.3), 100.0, 0.0),
    "ball in conforming groove": ((6e-3, 6e-3, 210e9, 0.3), (-6.2e-3, 40e-3, 210e9, 0.3),
                                  1500.0, 0.0),
    "crossed cylinders at 30 deg": ((0.01, math.inf, 210e9, 0.3), (0.02, math.inf, 210e9, 0.3),
                                    200.0, math.radians(30)),
    "wheel on rail": ((0.46, math.inf, 210e9, 0.3), (math.inf, 0.3, 210e9, 0.3), 1e5, 0.0),
    "two ellipsoids, steel on aluminium": ((0.02, 0.05, 210e9, 0.3), (0.03, 0.01, 70e9, 0.33),
                                           50.0, 0.4),
}


def rand_scenes(n=40, seed=11):
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        r1 = 10 ** rng.uniform(-4, 0, 2)
        r2 = 10 ** rng.uniform(-4, 0, 2)
        b1 = (r1[0], r1[1], 10 ** rng.uniform(9, 12), rng.uniform(-0.9, 0.5))
        b2 = (r2[0], r2[1], 10 ** rng.uniform(9, 12), rng.uniform(-0.9, 0.5))
        out.append((b1, b2, 10 ** rng.uniform(-3, 5), rng.uniform(-math.pi, math.pi)))
    return out


def ours(scene):
    b1, b2, load, angle = scene
    return hertz.contact(hertz.Body(*b1), hertz.Body(*b2), load=load, angle=angle)


def check_against_reference(scene, tol=4e-15):
    c, ref = ours(scene), contact_ref(*scene)
    for name in ("a", "b", "p0", "delta"):
        err = float(abs((mp.mpf(getattr(c, name)) - getattr(ref, name)) / getattr(ref, name)))
        assert err <= tol, (name, err)


@pytest.mark.parametrize("name", SCENES)
def test_named_scenes_against_mpmath(name):
    check_against_reference(SCENES[name])


def test_random_scenes_against_mpmath():
    for scene in rand_scenes():
        check_against_reference(scene)


def test_arrays_match_scalar_calls():
    scenes = rand_scenes(12, seed=3)
    cols = list(zip(*[(*s[0], *s[1], s[2], s[3]) for s in scenes], strict=True))
    b1 = hertz.Body(*map(np.array, cols[0:4]))
    b2 = hertz.Body(*map(np.array, cols[4:8]))
    batch = hertz.contact(b1, b2, load=np.array(cols[8]), angle=np.array(cols[9]))
    for i, scene in enumerate(scenes):
        single = ours(scene)
        for name in ("a", "b", "p0", "delta", "major_axis_angle", "stiffness"):
            # numpy's vector and scalar loops may round cbrt and ** differently by an ulp
            assert getattr(batch, name)[i] == pytest.approx(getattr(single, name), rel=5e-16)


def test_sphere_closed_forms():
    R1, R2, P = 0.01, 0.025, 300.0
    c = hertz.contact(hertz.Body.sphere(R1, **STEEL), hertz.Body.sphere(R2, 70e9, 0.33), load=P)
    R = 1 / (1 / R1 + 1 / R2)
    e_star = 1 / ((1 - 0.3**2) / 210e9 + (1 - 0.33**2) / 70e9)
    a = (3 * P * R / (4 * e_star)) ** (1 / 3)
    assert c.alpha == 1 and c.ellipticity == 1 and c.m == 0
    np.testing.assert_allclose([c.a, c.b, c.p0, c.delta, c.e_star],
                               [a, a, 3 * P / (2 * math.pi * a * a), a * a / R, e_star],
                               rtol=2e-15)


@given(st.floats(1e-3, 1e6), st.floats(0.05, 20.0))
def test_scaling_and_equilibrium(load, factor):
    ball, race = hertz.Body.sphere(6e-3, **STEEL), hertz.Body(-6.2e-3, 40e-3, **STEEL)
    c1 = hertz.contact(ball, race, load=load)
    c2 = hertz.contact(ball, race, load=load * factor)
    np.testing.assert_allclose(2 / 3 * math.pi * c1.a * c1.b * c1.p0, load, rtol=4e-15)
    np.testing.assert_allclose([c2.a / c1.a, c2.b / c1.b, c2.delta / c1.delta, c2.p0 / c1.p0],
                               [factor ** (1 / 3)] * 2 + [factor ** (2 / 3), factor ** (1 / 3)],
                               rtol=4e-15)
    assert c1.ellipticity == c2.ellipticity


@given(st.floats(1e-9, 1e-4))
def test_stiffness_is_the_derivative_and_the_inverse_round_trips(delta):
    ball, race = hertz.Body.sphere(6e-3, **STEEL), hertz.Body(-6.2e-3, 40e-3, **STEEL)
    c = hertz.contact(ball, race, approach=delta)
    h = 1e-4
    lo, hi = (hertz.contact(ball, race, approach=delta * (1 + s)).load for s in (-h, h))
    assert c.stiffness == pytest.approx((hi - lo) / (2 * h * delta), rel=1e-7)
    assert c.stiffness == pytest.approx(1.5 * c.load / c.delta, rel=1e-14)
    back = hertz.contact(ball, race, load=c.load)
    assert back.delta == pytest.approx(delta, rel=4e-15)
    assert back.a == pytest.approx(c.a, rel=4e-15)


@given(st.floats(0.01, 1.0), st.floats(0.01, 1.0), st.floats(0.01, 1.0), st.floats(0.01, 1.0),
       st.floats(-3.0, 3.0))
def test_swapping_the_bodies_changes_nothing(r1x, r1y, r2x, r2y, psi):
    b1, b2 = hertz.Body(r1x, r1y, **STEEL), hertz.Body(r2x, r2y, 70e9, 0.33)
    c = hertz.contact(b1, b2, load=10.0, angle=psi)
    s = hertz.contact(b2, b1, load=10.0, angle=-psi)
    for name in ("a", "b", "p0", "delta", "alpha"):
        assert getattr(s, name) == pytest.approx(getattr(c, name), rel=2e-13)
    if c.alpha > 1 + 1e-6:  # the axis direction is defined
        diff = (s.major_axis_angle - (c.major_axis_angle - psi)) % math.pi
        assert min(diff, math.pi - diff) < 1e-9


@given(st.floats(0.01, 1.0), st.floats(0.01, 1.0), st.floats(0.01, 1.0), st.floats(0.01, 1.0),
       st.floats(-3.0, 3.0))
def test_curvatures_and_orientation_match_an_eigendecomposition(r1x, r1y, r2x, r2y, psi):
    c = hertz.contact(hertz.Body(r1x, r1y, **STEEL), hertz.Body(r2x, r2y, **STEEL), load=1.0,
                      angle=psi)
    rot = np.array([[math.cos(psi), -math.sin(psi)], [math.sin(psi), math.cos(psi)]])
    tensor = np.diag([1 / r1x, 1 / r1y]) + rot @ np.diag([1 / r2x, 1 / r2y]) @ rot.T
    w, v = np.linalg.eigh(tensor)
    np.testing.assert_allclose([c.rho_y, c.rho_x], w, rtol=1e-12)
    if w[1] / w[0] > 1 + 1e-6:
        axis = np.array([math.cos(c.major_axis_angle), math.sin(c.major_axis_angle)])
        assert abs(abs(axis @ v[:, 0]) - 1) < 1e-9  # along the smaller curvature
    assert -math.pi / 2 < c.major_axis_angle <= math.pi / 2


def test_orientation_of_an_aligned_scene():
    """Smaller relative curvature along body 1's x axis: the major axis lies along x."""
    ball, race = hertz.Body.sphere(6e-3, **STEEL), hertz.Body(-6.2e-3, 40e-3, **STEEL)
    assert hertz.contact(ball, race, load=1.0).major_axis_angle == 0.0
    race_turned = hertz.Body(40e-3, -6.2e-3, **STEEL)
    assert hertz.contact(ball, race_turned, load=1.0).major_axis_angle == pytest.approx(math.pi / 2)


def test_pressure_field():
    c = ours(SCENES["two ellipsoids, steel on aluminium"])
    assert c.pressure(0.0, 0.0) == c.p0
    assert c.pressure(c.a, 0.0) == 0.0 and c.pressure(0.0, 1.01 * c.b) == 0.0
    np.testing.assert_allclose(c.pressure(0.6 * c.a, 0.0), c.p0 * 0.8, rtol=1e-15)
    np.testing.assert_allclose(c.pressure(0.0, 0.6 * c.b), c.p0 * 0.8, rtol=1e-15)
    # the pressure integrates to the load (midpoint rule on a fine grid)
    n = 1600
    x = (np.arange(n) + 0.5) / n * 2 * c.a - c.a
    y = (np.arange(n) + 0.5) / n * 2 * c.b - c.b
    total = c.pressure(x[:, None], y[None, :]).sum() * (2 * c.a / n) * (2 * c.b / n)
    assert total == pytest.approx(c.load, rel=1e-4)


def test_zero_load_gives_zero_contact_without_warnings():
    with np.errstate(all="raise"):
        c = hertz.contact(hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL),
                          load=[0.0, 1.0])
        for name in ("a", "b", "p0", "p_mean", "area", "delta", "stiffness"):
            assert getattr(c, name)[0] == 0.0 and getattr(c, name)[1] > 0
        assert c.pressure(0.0, 0.0)[0] == 0.0


def test_broadcasting_shapes():
    radii = np.array([[0.01], [0.02]])
    c = hertz.contact(hertz.Body.sphere(radii, **STEEL), hertz.Body.plane(**STEEL),
                      load=[1.0, 2.0, 3.0])
    assert c.a.shape == (2, 3) and c.major_axis_angle.shape == (2, 3)
    with pytest.raises(ValueError, match=r"do not broadcast.*body1.Rx \(2,\).*load \(3,\)"):
        hertz.contact(hertz.Body.sphere(radii[:, 0], **STEEL), hertz.Body.plane(**STEEL),
                      load=[1.0, 2.0, 3.0])


def test_float32_inputs():
    c32 = hertz.contact(hertz.Body.sphere(np.float32(0.01), np.float32(2e11), np.float32(0.25)),
                        hertz.Body.plane(2e11, 0.25), load=np.float32(10))
    r, e, nu = (float(np.float32(x)) for x in (0.01, 2e11, 0.25))
    c64 = hertz.contact(hertz.Body.sphere(r, e, nu), hertz.Body.plane(2e11, 0.25), load=10.0)
    assert c32.a == c64.a and isinstance(c32.a, float)


def test_line_contact_closed_forms():
    e_star = 210e9 / (2 * (1 - 0.3**2))
    lc = hertz.line_contact(hertz.Body.cylinder(0.01, **STEEL), hertz.Body.cylinder(0.02, **STEEL),
                            1e5)
    R = 1 / (1 / 0.01 + 1 / 0.02)
    b = math.sqrt(4 * 1e5 * R / (math.pi * e_star))
    np.testing.assert_allclose([lc.half_width, lc.p0, lc.e_star], [b, 2e5 / (math.pi * b), e_star],
                               rtol=2e-15)
    assert lc.pressure(0.0) == lc.p0 and lc.pressure(b) == 0.0


def test_parallel_cylinders_point_to_line_contact():
    cyl = hertz.Body.cylinder(0.01, **STEEL)
    with pytest.raises(ValueError, match=r"line contact.*hertz\.line_contact"):
        hertz.contact(cyl, cyl, load=1.0)
    with pytest.raises(ValueError, match=r"^at index 1: the bodies make a line contact"):
        hertz.contact(cyl, cyl, load=1.0, angle=[0.3, 0.0])
    with pytest.raises(ValueError, match=r"not a line contact.*hertz\.contact"):
        hertz.line_contact(cyl, cyl.sphere(0.01, **STEEL), 1.0)


@pytest.mark.parametrize("b1, b2, match", [
    (hertz.Body.plane(**STEEL), hertz.Body.plane(**STEEL), "plane on plane"),
    (hertz.Body.sphere(0.01, **STEEL), hertz.Body.sphere(-0.005, **STEEL), "must both be positive"),
    (hertz.Body.sphere(0.01, **STEEL), hertz.Body.sphere(-0.01, **STEEL), "fit each other exactly"),
    (hertz.Body(0.01, 0.02, **STEEL), hertz.Body(-0.02, -0.01, **STEEL), "must both be positive"),
])
def test_no_hertz_contact(b1, b2, match):
    with pytest.raises(ValueError, match=match):
        hertz.contact(b1, b2, load=1.0)


@pytest.mark.parametrize("kwargs, match", [
    (dict(Rx=0.0, Ry=1.0, E=1e9, nu=0.3), r"Rx must be a nonzero radius.*got 0\.0"),
    (dict(Rx=1.0, Ry=np.nan, E=1e9, nu=0.3), r"Ry must be a nonzero radius.*got nan"),
    (dict(Rx=1.0, Ry=1.0, E=0.0, nu=0.3),
     r"E must be a positive Young's modulus in Pa \(inf for a rigid"),
    (dict(Rx=1.0, Ry=1.0, E=-1e9, nu=0.3), r"E must be .*got -1000000000\.0"),
    (dict(Rx=1.0, Ry=1.0, E=-np.inf, nu=0.3), r"E must be .*got -inf"),
    (dict(Rx=1.0, Ry=1.0, E=np.nan, nu=0.3), r"E must be .*got nan"),
    (dict(Rx=1.0, Ry=1.0, E=1e9, nu=0.6), r"nu must be a Poisson's ratio in \(-1, 0\.5\]"),
    (dict(Rx=1.0, Ry=1.0, E=1e9, nu=-1.0), r"nu must be"),
    (dict(Rx=[1.0, 0.0], Ry=1.0, E=1e9, nu=0.3), r"Rx must be .*at index 1"),
])
def test_bad_body(kwargs, match):
    with pytest.raises(ValueError, match=match):
        hertz.Body(**kwargs)


@pytest.mark.parametrize("kwargs", [dict(Rx="1", Ry=1.0, E=1e9, nu=0.3),
                                    dict(Rx=1.0, Ry=1.0, E=1e9 + 0j, nu=0.3),
                                    dict(Rx=1.0, Ry=None, E=1e9, nu=0.3)])
def test_non_numeric_body(kwargs):
    with pytest.raises(TypeError, match="must be a real number"):
        hertz.Body(**kwargs)


@pytest.mark.parametrize("kwargs, exc, match", [
    (dict(load=-5.0), ValueError, r"load must be a finite value >= 0 in N, got -5\.0"),
    (dict(load=np.nan), ValueError, r"load must be"),
    (dict(load=np.inf), ValueError, r"load must be"),
    (dict(load=[1.0, -2.0]), ValueError, r"load .*at index 1"),
    (dict(approach=-1e-6), ValueError, r"approach must be"),
    (dict(load=1.0, angle=np.nan), ValueError, r"angle must be a finite angle"),
    (dict(load="heavy"), TypeError, r"load must be a real number"),
    (dict(), TypeError, r"exactly one of load"),
    (dict(load=1.0, approach=1e-6), TypeError, r"exactly one of load"),
])
def test_bad_contact_arguments(kwargs, exc, match):
    with pytest.raises(exc, match=match):
        hertz.contact(hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL), **kwargs)


def test_bodies_must_be_bodies():
    with pytest.raises(TypeError, match="body2 must be a hertz.Body"):
        hertz.contact(hertz.Body.sphere(0.01, **STEEL), (1.0, 1.0, 1e9, 0.3), load=1.0)


# ------------------------------------------------- a result owns its arrays (issue 18, 3)

def _two_ellipsoids(n=3, seed=5):
    rng = np.random.default_rng(seed)
    return (hertz.Body(rng.uniform(0.01, 0.05, n), 0.05, **STEEL),
            hertz.Body(0.03, rng.uniform(0.005, 0.02, n), 70e9, 0.33),
            rng.uniform(10.0, 100.0, n), rng.uniform(0.1, 1.4, n))


@pytest.mark.parametrize("read_first", [False, True])
def test_changing_the_callers_arrays_afterwards_changes_nothing(read_first):
    """The geometry fields are computed on first access from the inputs: they must be the
    contact's own copies, not the caller's arrays (issue 18, item 3)."""
    b1, b2, load, angle = _two_ellipsoids()
    expected = hertz.contact(b1, b2, load=load.copy(), angle=angle.copy())
    c = hertz.contact(b1, b2, load=load, angle=angle)
    if read_first:
        c.a  # noqa: B018 (the load fields only; the geometry is still deferred)
    angle[:] = [0.0, np.nan, 1e300]
    load[:] = -1.0
    for name in ("a", "b", "load", "p0", "delta", "alpha", "rho_x", "rho_y", "major_axis_angle",
                 "e_star", "K", "E", "m", "ellipticity"):
        np.testing.assert_array_equal(getattr(c, name), getattr(expected, name), err_msg=name)
    assert np.all(c.alpha > 1.0)


def _contacts_of_every_path():
    b1, b2, load, angle = _two_ellipsoids()
    ball = hertz.Body.sphere(0.01, **STEEL)
    yield "fused", hertz.contact(b1, b2, load=load, angle=angle)
    yield "one geometry, many loads", hertz.contact(ball, hertz.Body.plane(**STEEL), load=load)
    yield "approach", hertz.contact(b1, b2, approach=[1e-6, 2e-6, 3e-6], angle=angle)
    yield "p0", hertz.contact(ball, b2, p0=np.array([1e9, 2e9, 3e9]))


@pytest.mark.parametrize("path, c", list(_contacts_of_every_path()))
def test_a_contacts_arrays_are_read_only(path, c):
    names = ("a", "b", "load", "p0", "delta", "stiffness") + tuple(
        n for n in dir(hertz.Contact) if isinstance(getattr(hertz.Contact, n), property)
        and n not in ("rho_sum", "p_mean", "area"))
    assert len(names) == 15
    for name in names:
        value = getattr(c, name)
        assert isinstance(value, np.ndarray) and not value.flags.writeable, (path, name)
        with pytest.raises(ValueError, match="read-only"):
            value[0] = 1.0


def test_a_line_contacts_arrays_are_read_only():
    lc = hertz.line_contact(hertz.Body.cylinder([0.01, 0.02], **STEEL), hertz.Body.plane(**STEEL),
                            np.array([1e4, 1e5]))
    for name in ("half_width", "p0", "e_star", "rho_sum", "load_per_length"):
        value = getattr(lc, name)
        assert isinstance(value, np.ndarray) and not value.flags.writeable, name
        with pytest.raises(ValueError, match="read-only"):
            value[0] = 1.0


# ------------------------------------------- ints beyond the doubles, masked arrays (item 9)

BIG = "must be within the range of a double \\(magnitude at most 1.7976931348623157e308\\)"


@pytest.mark.parametrize("call, match", [
    (lambda: hertz.Body.sphere(10**309, **STEEL), rf"^Rx {BIG}, got the int 1\.000e\+309$"),
    (lambda: hertz.Body(1.0, 1.0, -(10**400), 0.3), rf"^E {BIG}, got the int -1\.000e\+400$"),
    (lambda: hertz.Body.sphere([0.1, 3 * 10**5000], **STEEL),
     rf"^Rx {BIG}, got the int 3\.000e\+5000 at index 1$"),
    (lambda: hertz.contact(hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL),
                           load=10**309), rf"^load {BIG}, got the int 1\.000e\+309$"),
    (lambda: hertz.contact(hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL),
                           load=1.0, angle=2**1024), rf"^angle {BIG}, got the int 1\.798e\+308$"),
    (lambda: hertz.contact(hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL),
                           approach=[[1e-6], [10**309]]),
     rf"^approach {BIG}, got the int 1\.000e\+309 at index \(1, 0\)$"),
    (lambda: hertz.line_contact(hertz.Body.cylinder(0.01, **STEEL), hertz.Body.plane(**STEEL),
                                10**320), rf"^load_per_length {BIG}, got the int 1\.000e\+320$"),
    (lambda: hertz.contact(hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL),
                           load=1.0).stress(0.0, 0.0, [0, 10**309]), rf"^z {BIG}.* at index 1$"),
])
def test_ints_beyond_the_double_range_are_named(call, match):
    with pytest.raises(ValueError, match=match):
        call()


def test_ints_of_more_than_64_bits_within_the_double_range_are_numbers():
    ball, plane = hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL)
    c = hertz.contact(ball, plane, load=[1, 10**20, 2**70])
    np.testing.assert_array_equal(c.load, [1.0, 1e20, 2.0**70])
    assert c.a[1] == hertz.contact(ball, plane, load=1e20).a
    assert hertz.Body.sphere([10**30], **STEEL).Rx[0] == 1e30
    with pytest.raises(TypeError, match="load must be a real number"):
        hertz.contact(ball, plane, load=[True, 10**20])


@pytest.mark.parametrize("make", [
    lambda m: hertz.Body(m, 0.01, **STEEL),
    lambda m: hertz.contact(hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL), load=m),
    lambda m: hertz.contact(hertz.Body(0.01, 0.02, **STEEL), hertz.Body.plane(**STEEL), load=1.0,
                            angle=m),
    lambda m: hertz.line_contact(hertz.Body.cylinder(0.01, **STEEL), hertz.Body.plane(**STEEL), m),
    lambda m: hertz.contact(hertz.Body.sphere(0.01, **STEEL), hertz.Body.plane(**STEEL),
                            load=1.0).pressure(m, 0.0),
])
def test_masked_arrays_are_refused_not_unmasked_silently(make):
    masked = np.ma.masked_array([0.01, -1.0], mask=[False, True])
    with pytest.raises(TypeError, match=r"masked array.*\.filled\(value\).*\.compressed"):
        make(masked)
