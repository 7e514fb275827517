"""hertz.contact on hard scenes against mpmath, and its invariants to a few ulp.

Hard scenes: nearly conforming bodies at an angle (a ball in a groove, an
ellipsoid in a cup), a saddle contact whose curvature determinant cancels,
extreme loads, radii and moduli, curvature ratios near the double range.  Invariants (hypothesis):
swapping the bodies, turning both by 90 degrees, circles at any angle,
scaling the load, and the load -> approach -> load and load -> p0 -> load
round trips.
"""

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

STEEL = (210e9, 0.3)


def rel_err(value, ref) -> float:
    return float(abs((mp.mpf(value) - ref) / ref))


def ulps(value, ref) -> float:
    """|value - ref| in units of the last place of value (ref may be mpf)."""
    return float(abs(mp.mpf(value) - mp.mpf(ref)) / mp.mpf(np.spacing(abs(value))))


def groove(g):
    return (6e-3, 6e-3, *STEEL), (-6e-3 * (1 + g), 40e-3, *STEEL)


SADDLE = ((0.08073941314545452, 0.02745196686562482, *STEEL),
          (-0.029033934600377176, 0.08262373225124177, 70e9, 0.33))

HARD = {
    "groove conforming to 1e-6 at 0.3 rad": (*groove(1e-6), 1500.0, 0.3),
    "groove conforming to 1e-10 at 0.3 rad": (*groove(1e-10), 1500.0, 0.3),
    "groove conforming to 1e-14 at 0.3 rad": (*groove(1e-14), 1500.0, 0.3),
    "groove conforming to 1e-14, swapped": (*groove(1e-14)[::-1], 1500.0, -0.3),
    "load 1e300": ((1.0, 1.0, 1.0, 0.0), (math.inf, math.inf, 1.0, 0.0), 1e300, 0.0),
    "load 1e-300": ((1.0, 1.0, 1.0, 0.0), (math.inf, math.inf, 1.0, 0.0), 1e-300, 0.0),
    "load 1e-162": ((1.0, 1.0, 1.0, 0.0), (math.inf, math.inf, 1.0, 0.0), 1e-162, 0.0),
    "largest load": ((6e-3, 6e-3, *STEEL), (-6.2e-3, 40e-3, *STEEL), 1.7976931348623157e308,
                     0.0),
    "radius 1e-160": ((1e-160, 1e-160, 1e9, 0.0), (math.inf, math.inf, 1e9, 0.0), 1e-3, 0.0),
    "radius 1e-310 (subnormal)": ((1e-310, 1e-310, 1e9, 0.3), (math.inf, math.inf, 1e9, 0.3),
                                  1.0, 0.0),
    "radii 1e300": ((1e300, 2e300, 1e9, 0.3), (math.inf, math.inf, 1e9, 0.3), 1e10, 0.0),
    "E 1e-300 on 1e300": ((0.01, 0.02, 1e-300, 0.3), (0.03, 0.01, 1e300, 0.1), 1.0, 1.0),
    "subnormal moduli": ((1e-310, 1e-310, 5e-324, 0.3), (math.inf, math.inf, 5e-324, 0.3),
                         1e-300, 0.0),
    "crossed cylinders at 1e-150 rad": ((1e-2, math.inf, *STEEL), (1e-2, math.inf, *STEEL), 1.0,
                                        1e-150),
    "angle 1e6 rad": ((0.01, 0.03, *STEEL), (0.02, -0.5, 70e9, 0.33), 10.0, 1e6),
    "nu near -1": ((0.01, 0.03, 1e9, -0.999999), (0.02, 0.5, 70e9, 0.5), 10.0, 0.7),
    # A body concave across at an angle: rho_x rho_y = Sx Sy + g1 g2 sin^2(psi) is a
    # difference (28x and 1e6x below its terms; the double formula was off by 1.2e-14 and
    # 3.2e-10 in alpha), and so is rho_x + rho_y = Sx + Sy (Sx < 0).
    # An ellipsoid in a nearly conforming cup at a small angle: g1 and -g2 nearly cancel
    # (g1 + g2 is taken as Sx - Sy). Before, a was off by 4.6e-11, 7.0e-9 and 2.7e-5.
    "ellipsoid in a cup conforming to 1e-6 at 1e-8 rad": (
        (0.01, 0.02, *STEEL), (-0.01000001, -0.02000002, *STEEL), 100.0, 1e-8),
    "ellipsoid in a cup conforming to 1e-9 at 1e-10 rad": (
        (0.01, 0.02, *STEEL), (-0.010000000010000001, -0.020000000020000002, *STEEL), 100.0,
        1e-10),
    "cup conforming to 1e-12 at 4e-13 rad": (
        (-0.009400108878343976, -0.14727022485818647, 137693728064.38263, 0.12444941718478869),
        (0.009400108878332794, 0.14727022485650926, 67234607041.65486, 0.19542136368757212),
        303.7397198152371, 3.9843224812260383e-13),
    "saddle at an angle, det 28x below its terms": (*SADDLE, 10.0, 1.4756902810579353),
    "saddle at an angle, det 1e6x below its terms": (*SADDLE, 10.0, 1.3608494129183655),
}


@pytest.mark.parametrize("name", HARD)
def test_hard_scenes_against_mpmath(name):
    b1, b2, load, angle = HARD[name]
    c = hertz.contact(hertz.Body(*b1), hertz.Body(*b2), load=load, angle=angle)
    ref = contact_ref(b1, b2, load, angle)
    for field in ("a", "b", "p0", "delta"):
        value, exact = getattr(c, field), getattr(ref, field)
        # observed at most 4.4e-16 (2 ulp) over these scenes
        assert rel_err(value, exact) <= 6e-16, (field, value, exact)
    # observed at most 3.4e-16 (E 1e-300 on 1e300)
    assert rel_err(c.alpha, ref.alpha) <= 5e-16


def test_conforming_groove_at_an_angle_matches_angle_zero():
    """With a sphere the angle cannot matter: same results at 0 and 0.3 rad."""
    for g in (1e-6, 1e-10, 1e-14):
        b1, b2 = (hertz.Body(*b) for b in groove(g))
        at0, at3 = (hertz.contact(b1, b2, load=1500.0, angle=t) for t in (0.0, 0.3))
        for field in ("a", "b", "p0", "delta"):
            assert ulps(getattr(at3, field), getattr(at0, field)) <= 1


def test_sphere_on_saddle_is_a_line_contact_at_any_angle():
    sphere, saddle = hertz.Body.sphere(1.0, 1e5, 0.0), hertz.Body(4.0, -1.0, 1e5, 0.0)
    for b1, b2, angle in ((sphere, saddle, 3.0), (saddle, sphere, -3.0), (sphere, saddle, 0.0)):
        with pytest.raises(ValueError, match="line contact"):
            hertz.contact(b1, b2, load=1.0, angle=angle)


def test_circular_contact_at_an_angle_keeps_its_promises():
    c = hertz.contact(hertz.Body.sphere(596.1349776173041, 1e5, 0.0), hertz.Body.plane(1e5, 0.0),
                      load=1.0, angle=1.0)
    assert c.alpha == 1.0 and c.a == c.b and c.major_axis_angle == 0.0


def test_beyond_the_double_range_is_an_error_not_nan():
    cyl = hertz.Body.cylinder(1e-2, *STEEL)
    with pytest.raises(ValueError, match="within rounding of a line contact.*line_contact"):
        hertz.contact(cyl, cyl, load=1.0, angle=1e-154)
    with pytest.raises(ValueError, match=r"^at index 1: the bodies are within rounding"):
        hertz.contact(cyl, cyl, load=1.0, angle=[1e-150, 1e-154])


def test_the_largest_and_smallest_values_are_finite_or_named():
    ball, race = hertz.Body.sphere(6e-3, *STEEL), hertz.Body(-6.2e-3, 40e-3, *STEEL)
    with np.errstate(all="raise"):
        c = hertz.contact(ball, race, load=[5e-324, 1e-310, 1e308, 1.7976931348623157e308])
    assert np.all(np.isfinite([c.a, c.b, c.p0, c.delta, c.stiffness]))
    assert np.all(c.a > 0)


def test_batch_scalar_and_one_geometry_paths_give_the_same_bits():
    rng = np.random.default_rng(4)
    n = 300
    b1 = hertz.Body(rng.uniform(1e-3, 1e-1, n), rng.uniform(1e-3, 1e-1, n), 210e9, 0.3)
    b2 = hertz.Body(-rng.uniform(0.11, 0.2, n), rng.uniform(1e-3, 1e-1, n), 70e9, 0.33)
    angle, load = rng.uniform(-3, 3, n), 10 ** rng.uniform(-3, 5, n)
    batch = hertz.contact(b1, b2, load=load, angle=angle)
    fields = ("a", "b", "p0", "delta", "stiffness", "ellipticity", "alpha", "K", "E", "m",
              "rho_x", "rho_y", "e_star", "major_axis_angle")
    for i in range(0, n, 37):
        one = hertz.contact(hertz.Body(b1.Rx[i], b1.Ry[i], 210e9, 0.3),
                            hertz.Body(b2.Rx[i], b2.Ry[i], 70e9, 0.33), load=float(load[i]),
                            angle=float(angle[i]))
        many = hertz.contact(hertz.Body(b1.Rx[i], b1.Ry[i], 210e9, 0.3),
                             hertz.Body(b2.Rx[i], b2.Ry[i], 70e9, 0.33), load=load[i:i + 3],
                             angle=float(angle[i]))
        for field in fields:
            assert getattr(batch, field)[i] == getattr(one, field) == getattr(many, field)[0]


# ---------------------------------------------------------------- invariants

radius = st.floats(1e-3, 1.0) | st.floats(-1.0, -1e-3) | st.just(math.inf)
positive_radius = st.floats(1e-3, 1.0)
poisson = st.floats(-0.9, 0.5)
modulus = st.floats(1e9, 1e12)
angle_st = st.floats(-3.2, 3.2)


def scene(r1x, r1y, r2x, r2y):
    return hertz.Body(r1x, r1y, 210e9, 0.3), hertz.Body(r2x, r2y, 70e9, 0.33)


@given(positive_radius, positive_radius, radius, radius, angle_st, st.floats(1e-3, 1e5))
def test_swapping_the_bodies_gives_the_same_bits(r1x, r1y, r2x, r2y, psi, load):
    b1, b2 = scene(r1x, r1y, r2x, r2y)
    try:
        c = hertz.contact(b1, b2, load=load, angle=psi)
    except ValueError:
        return  # no point contact: checked elsewhere
    s = hertz.contact(b2, b1, load=load, angle=-psi)
    for field in ("a", "b", "p0", "delta", "stiffness", "alpha", "ellipticity", "e_star"):
        assert getattr(s, field) == getattr(c, field), field


@given(positive_radius, positive_radius, positive_radius, positive_radius, angle_st)
def test_turning_both_bodies_by_90_degrees_moves_only_the_axis(r1x, r1y, r2x, r2y, psi):
    c = hertz.contact(*scene(r1x, r1y, r2x, r2y), load=10.0, angle=psi)
    t = hertz.contact(*scene(r1y, r1x, r2y, r2x), load=10.0, angle=psi)
    for field in ("a", "b", "p0", "delta", "alpha"):
        assert ulps(getattr(t, field), getattr(c, field)) <= 4, field
    if c.alpha > 1 + 1e-6:  # the axis direction is defined
        diff = (t.major_axis_angle - c.major_axis_angle - math.pi / 2) % math.pi
        assert min(diff, math.pi - diff) < 1e-9


@given(st.floats(1e-4, 1.0), st.floats(1e-4, 1.0) | st.just(math.inf), angle_st, modulus,
       poisson)
def test_a_circular_contact_at_any_angle(r1, r2, psi, e2, nu2):
    c = hertz.contact(hertz.Body.sphere(r1, 210e9, 0.3), hertz.Body.sphere(r2, e2, nu2),
                      load=3.0, angle=psi)
    assert c.alpha == 1.0 and c.ellipticity == 1.0 and c.major_axis_angle == 0.0
    assert c.a == c.b


@given(positive_radius, positive_radius, positive_radius, positive_radius, angle_st,
       st.floats(1e-3, 1e5), st.floats(1e-3, 1e3))
def test_scaling_the_load(r1x, r1y, r2x, r2y, psi, load, factor):
    b1, b2 = scene(r1x, r1y, r2x, r2y)
    c1 = hertz.contact(b1, b2, load=load, angle=psi)
    c2 = hertz.contact(b1, b2, load=load * factor, angle=psi)
    s = mp.mpf(load * factor) / mp.mpf(load)  # the factor actually applied
    # observed at most 1.4 ulp over 2e4 random scenes (the issue asks for 4)
    assert ulps(c2.a, mp.mpf(c1.a) * mp.cbrt(s)) <= 2
    assert ulps(c2.b, mp.mpf(c1.b) * mp.cbrt(s)) <= 2
    assert ulps(c2.p0, mp.mpf(c1.p0) * mp.cbrt(s)) <= 2
    assert ulps(c2.delta, mp.mpf(c1.delta) * mp.cbrt(s) ** 2) <= 2
    assert c1.ellipticity == c2.ellipticity


@given(positive_radius, positive_radius, positive_radius, positive_radius, angle_st,
       st.floats(1e-3, 1e5))
def test_round_trips_through_approach_and_p0(r1x, r1y, r2x, r2y, psi, load):
    b1, b2 = scene(r1x, r1y, r2x, r2y)
    c = hertz.contact(b1, b2, load=load, angle=psi)
    # observed over 2e4 random scenes: 1 ulp through the approach, 3 through p0
    back = hertz.contact(b1, b2, approach=c.delta, angle=psi)
    assert ulps(back.load, load) <= 2 and ulps(back.a, c.a) <= 2
    back = hertz.contact(b1, b2, p0=c.p0, angle=psi)
    assert ulps(back.load, load) <= 4 and ulps(back.a, c.a) <= 4


@given(st.floats(1e-9, 1e-4))
def test_stiffness_is_the_derivative(delta):
    ball, race = hertz.Body.sphere(6e-3, *STEEL), hertz.Body(-6.2e-3, 40e-3, *STEEL)
    c = hertz.contact(ball, race, approach=delta)
    h = 1e-4
    lo, hi = (hertz.contact(ball, race, approach=delta * (1 + s)).load for s in (-h, h))
    assert c.stiffness == pytest.approx((hi - lo) / (2 * h * delta), rel=1e-7)
    # three rounded outputs: observed at most 5 ulp over 2e4 approaches
    assert ulps(c.stiffness, 1.5 * mp.mpf(c.load) / mp.mpf(c.delta)) <= 8


# ---------------------------------------------------------------- own data

def test_bodies_and_contacts_keep_their_own_data():
    E = np.array([210e9, 210e9])
    body = hertz.Body(np.array([0.01, 0.02]), 0.01, E, 0.3)
    E[1] = -210e9  # the caller's array, not the body's
    assert body.E[1] == 210e9
    with pytest.raises(ValueError):
        body.E[1] = -1.0  # read-only
    load = np.array([1.0, 2.0])
    c = hertz.contact(body, hertz.Body.plane(*STEEL), load=load)
    assert not np.shares_memory(c.load, load)
    load[0] = -5.0
    assert c.load[0] == 1.0 and np.all(np.isfinite(c.p0))


def test_out_of_range_errors_name_the_users_parameter():
    with pytest.raises(ValueError, match=r"body2\.nu must be a Poisson's ratio.*got 0\.7"):
        hertz._ufuncs.contact(0, 1.0, 1.0, 1.0, 1.0, 0.0, 1e9, 0.3, 1e9, 0.7, 1.0)
    with pytest.raises(ValueError, match=r"E must be .*got 0\.0"):
        hertz.Body(1.0, 1.0, 0.0, 0.3)


def test_contact_ellipse_against_the_50_digit_table():
    """lambda, K, E of hertz.contact (the piecewise-polynomial table for 1 <= alpha < 2^64,
    the solver beyond) at every alpha in [1, 2^200] of tests/data/reference_lambda.csv.

    A body (1, alpha) on a plane has rho_x / rho_y = alpha exactly (products with 1)."""
    from reference import load_table

    # (up to 2^200: radii beyond 2^240 take the scalar geometry, where 1/alpha rounds)
    rows = [r for r in load_table() if 1.0 <= r["alpha"] <= 2.0**200]
    alpha = np.array([r["alpha"] for r in rows])
    c = hertz.contact(hertz.Body(1.0, alpha, *STEEL), hertz.Body.plane(*STEEL), load=1.0)
    np.testing.assert_array_equal(c.alpha, alpha)
    worst = {}
    for name, values in (("lambda", c.ellipticity), ("K", c.K), ("E", c.E)):
        worst[name] = max(rel_err(v, r[name]) for v, r in zip(values, rows, strict=True))
    # observed over 1658 alphas: lambda 1.27e-16, K 1.22e-16, E 1.11e-16 (the solver of
    # hertz.ellipticity: 3.7e-16, 7.0e-16, 6.5e-16)
    assert worst["lambda"] <= 1.9e-16, worst
    assert worst["K"] <= 1.9e-16, worst
    assert worst["E"] <= 1.7e-16, worst
    assert np.all(c.ellipticity >= 1.0)
    assert c.ellipticity[0] == 1.0 and c.K[0] == c.E[0] == np.pi / 2  # alpha = 1 exactly


def test_fast_and_exact_output_scaling_agree():
    """A block (64 elements) with one load of 1e300 is redone with the exact scaling; the
    ordinary loads in it must keep the bits they have in a block of ordinary loads."""
    rng = np.random.default_rng(5)
    n = 256
    ball = hertz.Body.sphere(rng.uniform(2e-3, 2e-2, n), *STEEL)
    race = hertz.Body(-rng.uniform(2.05e-2, 3e-2, n), rng.uniform(2e-2, 1e-1, n), 70e9, 0.33)
    angle = rng.uniform(-3, 3, n)
    for name in ("load", "approach", "p0"):
        value = {"load": rng.uniform(1, 2e3, n), "approach": rng.uniform(1e-7, 1e-5, n),
                 "p0": rng.uniform(1e8, 3e9, n)}[name]
        extreme = value.copy()
        extreme[::64] = {"load": 1e300, "approach": 1e200, "p0": 1e250}[name]
        plain = hertz.contact(ball, race, angle=angle, **{name: value})
        mixed = hertz.contact(ball, race, angle=angle, **{name: extreme})
        keep = np.ones(n, bool)
        keep[::64] = False
        for field in ("a", "b", "load", "p0", "delta", "stiffness"):
            np.testing.assert_array_equal(getattr(plain, field)[keep],
                                          getattr(mixed, field)[keep], err_msg=f"{name} {field}")


@pytest.mark.parametrize("angle", [1.4756902810579353, 1.3608494129183655, -1.5, 1.7])
def test_saddle_swapped_and_in_an_array(angle):
    """The double-double path of cancelling scenes is symmetric in the bodies, and a scene
    in an array (block code, flagged to the scalar path) has the bits of a single call."""
    b1, b2 = SADDLE
    one = hertz.contact(hertz.Body(*b1), hertz.Body(*b2), load=10.0, angle=angle)
    swapped = hertz.contact(hertz.Body(*b2), hertz.Body(*b1), load=10.0, angle=-angle)
    mixed = hertz.contact(hertz.Body([b1[0], 0.01, b1[0]], [b1[1], 0.01, b1[1]], b1[2], b1[3]),
                          hertz.Body([b2[0], 0.02, b2[0]], [b2[1], 0.03, b2[1]], b2[2], b2[3]),
                          load=[10.0, 5.0, 10.0], angle=[angle, 0.3, angle])
    for field in ("a", "b", "p0", "delta", "alpha", "rho_x", "rho_y"):
        assert getattr(one, field) == getattr(swapped, field), field
        assert getattr(mixed, field)[0] == getattr(one, field), field
        assert getattr(mixed, field)[2] == getattr(one, field), field
