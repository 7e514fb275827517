"""hertz.impact (elastic normal Hertz impact) and rigid bodies (E = inf), against mpmath.

References: tests/reference_impact.py (50 digits: K from tests/reference.py's contact at
1 N, delta_max and F_max from the energy, t_c with T1 by quadrature; the history by
quadrature of the energy equation, inverted) and Chung & Ooi's (2011) published Test 1.
"""

import math

import mpmath as mp
import numpy as np
import pytest
from reference import contact_ref
from reference_impact import elastic_ref, history_ref, t1_gamma, t1_quad

import hertz
from hertz._impact import T1

pytestmark = pytest.mark.filterwarnings("ignore::hertz.HertzValidityWarning")

INF = math.inf
GLASS_MASS = 2800 * 4 / 3 * math.pi * 0.01**3
# name: (body1, body2, speed [m/s], reduced mass [kg], angle [rad])
SCENES = {
    # Chung & Ooi Test 1: two glass spheres head-on at +-10 m/s
    "glass spheres": ((0.01, 0.01, 48e9, 0.2), (0.01, 0.01, 48e9, 0.2), 20.0,
                      GLASS_MASS / 2, 0.0),
    # aluminium alloy sphere (R 0.1 m, Chung & Ooi Test 2's) on a rigid wall at 0.2 m/s
    "aluminium on rigid wall": ((0.1, 0.1, 70e9, 0.33), (INF, INF, INF, 0.3), 0.2,
                                2700 * 4 / 3 * math.pi * 0.1**3, 0.0),
    "aluminium on steel wall": ((0.1, 0.1, 70e9, 0.33), (INF, INF, 210e9, 0.3), 0.2,
                                2700 * 4 / 3 * math.pi * 0.1**3, 0.0),
    "ellipsoids at an angle": ((0.01, 0.03, 200e9, 0.3), (0.02, 0.05, 110e9, 0.34), 1.5,
                               0.01, 0.7),
    "ball in a groove": ((6e-3, 6e-3, 210e9, 0.3), (-6.2e-3, 40e-3, 210e9, 0.3), 0.5,
                         1e-3, 0.0),
    "micro-sphere on glass": ((1e-6, 1e-6, 3e9, 0.35), (INF, INF, 70e9, 0.22), 1.0,
                              1050 * 4 / 3 * math.pi * 1e-18, 0.0),
}


def _rel(x, ref):
    return float(abs((mp.mpf(x) - ref) / ref))


def test_t1_constant():
    """T1 = Gamma(7/5) Gamma(1/2) / Gamma(9/10) = int_0^1 (1 - x^(5/2))^(-1/2) dx."""
    assert abs(t1_quad() - t1_gamma()) < mp.mpf(10) ** -30  # observed 1e-32
    assert abs(mp.mpf(T1) - t1_gamma()) <= mp.mpf(2) ** -52 * T1


@pytest.mark.parametrize("name", SCENES)
def test_elastic_impact_against_mpmath(name):
    b1, b2, V, m, angle = SCENES[name]
    hit = hertz.impact(hertz.Body(*b1), hertz.Body(*b2), speed=V, mass=m, angle=angle)
    K, dmax, fmax, tc = elastic_ref(b1, b2, V, m, angle)
    worst = max(_rel(hit.max_approach, dmax), _rel(hit.max_force, fmax),
                _rel(hit.duration, tc), _rel(hit.stiffness_coefficient, K))
    assert worst < 1e-13, worst  # observed <= 3e-15
    assert hit.restitution == 1.0
    p0 = contact_ref(b1, b2, fmax, angle).p0
    assert _rel(hit.max_pressure, p0) < 1e-13
    assert hit.time_to_max == hit.duration / 2


def test_chung_ooi_test1_published_values():
    b = hertz.Body.sphere(0.01, E=48e9, nu=0.2)
    hit = hertz.impact(b, b, speed=20.0, mass=GLASS_MASS / 2)
    assert f"{hit.max_approach * 1e6:.2f}" == "274.11"
    assert f"{hit.max_force / 1e3:.3f}" == "10.697"
    assert f"{hit.duration * 1e6:.2f}" == "40.34"


def test_sphere_closed_form_stiffness():
    """K = (4/3) E* sqrt(R) for two spheres."""
    b = hertz.Body.sphere(0.01, E=48e9, nu=0.2)
    hit = hertz.impact(b, b, speed=1.0, mass=1.0)
    e_star = 48e9 / (2 * (1 - 0.04))
    assert abs(hit.stiffness_coefficient / (4 / 3 * e_star * math.sqrt(0.005)) - 1) < 1e-15


@pytest.mark.parametrize("name", ["glass spheres", "ellipsoids at an angle"])
def test_history_against_quadrature(name):
    b1, b2, V, m, angle = SCENES[name]
    hit = hertz.impact(hertz.Body(*b1), hertz.Body(*b2), speed=V, mass=m, angle=angle)
    tc = hit.duration
    times = np.array([1e-12, 1e-6, 0.013, 0.17, 0.25, 0.4999, 0.5, 0.5001, 0.61, 0.9,
                      0.999999]) * tc
    h = hit.history(times)
    worst = 0.0
    for k, t in enumerate(times):
        d, f, v = history_ref(V, hit.max_approach, t, h.approach[k] / hit.max_approach)
        if t <= tc / 2:  # relative, early times too
            errors = (h.approach[k] / float(d) - 1, h.force[k] / hit.max_force / float(f) - 1)
        else:  # scaled: a time near t_c fixes the time left only to its own rounding
            errors = (h.approach[k] / hit.max_approach - float(d) / hit.max_approach,
                      h.force[k] / hit.max_force - float(f))
        worst = max(worst, *map(abs, errors), abs(h.speed[k] - float(v)) / V)
    assert worst < 3e-15, worst  # observed 8e-16


def test_history_ends_and_outside():
    b = hertz.Body.sphere(0.01, E=48e9, nu=0.2)
    hit = hertz.impact(b, b, speed=20.0, mass=GLASS_MASS / 2)
    h = hit.history([-1e-6, 0.0, hit.time_to_max, hit.duration, hit.duration + 1e-6])
    np.testing.assert_allclose(h.speed, [20, 20, 0, -20, -20], atol=1e-12)
    np.testing.assert_allclose(h.force, [0, 0, hit.max_force, 0, 0], rtol=1e-15, atol=0)
    np.testing.assert_allclose(h.approach, [-20e-6, 0, hit.max_approach, 0, -20e-6],
                               rtol=1e-12, atol=1e-18)
    # symmetric about the peak; energy conserved
    t = np.linspace(0, hit.duration, 41)[1:-1]
    h1, h2 = hit.history(t), hit.history(hit.duration - t)
    np.testing.assert_allclose(h1.approach, h2.approach, rtol=1e-13)
    energy = 0.5 * hit.mass * h1.speed**2 + 0.4 * h1.force * h1.approach
    np.testing.assert_allclose(energy, 0.5 * hit.mass * 400.0, rtol=1e-13)


def test_yield_speed_and_thornton():
    ball = hertz.Body.sphere(5e-3, E=70e9, nu=0.33)
    wall = hertz.Body.plane(E=INF, nu=0.3)
    m = 2700 * 4 / 3 * math.pi * 5e-3**3
    hit = hertz.impact(ball, wall, speed=5.0, mass=m)
    vy = hit.yield_speed(300e6)
    # at V_y the largest force is the load of first yield
    at_y = hertz.impact(ball, wall, speed=vy, mass=m)
    c = hertz.contact(ball, wall, load=at_y.max_force)
    assert abs(at_y.max_force / c.first_yield_load(300e6) - 1) < 1e-13
    assert hertz.impact(ball, wall, speed=0.3, mass=m).yield_speed(300e6) == pytest.approx(
        vy, rel=1e-14)
    # Thornton: 1 up to V_y, then Thornton's closed form; large V: e ~ (V_y/V)^(1/4) * c
    assert hertz.impact(ball, wall, speed=0.99 * vy, mass=m).plastic_restitution(300e6) == 1.0
    e_just = hertz.impact(ball, wall, speed=vy * (1 + 1e-9), mass=m).plastic_restitution(300e6)
    assert abs(e_just - 1) < 1e-8
    r = vy / 5.0
    thornton = (math.sqrt(6 * math.sqrt(3) / 5) * math.sqrt(1 - r * r / 6)
                * (r / (r + 2 * math.sqrt(6 / 5 - r * r / 5))) ** 0.25)
    assert abs(hit.plastic_restitution(300e6) - thornton) < 1e-15
    big = hertz.impact(ball, wall, speed=1e4 * vy, mass=m).plastic_restitution(300e6)
    c_inf = math.sqrt(6 * math.sqrt(3) / 5) * (1 / (2 * math.sqrt(6 / 5))) ** 0.25
    assert big / (1e-4 ** 0.25 * c_inf) == pytest.approx(1, rel=1e-4)


def test_broadcasting_matches_scalar_calls():
    radii = np.array([[0.005], [0.02]])
    speeds = np.array([0.5, 2.0, 8.0])
    hit = hertz.impact(hertz.Body.sphere(radii, E=210e9, nu=0.3),
                       hertz.Body.plane(E=70e9, nu=0.33), speed=speeds, mass=0.01)
    assert hit.max_force.shape == (2, 3)
    for i in range(2):
        for j in range(3):
            one = hertz.impact(hertz.Body.sphere(float(radii[i, 0]), E=210e9, nu=0.3),
                               hertz.Body.plane(E=70e9, nu=0.33), speed=float(speeds[j]),
                               mass=0.01)
            for k in ("max_approach", "max_force", "duration", "max_pressure", "restitution"):
                assert getattr(hit, k)[i, j] == getattr(one, k), k
    h = hit.history(hit.duration * 0.25)
    assert h.force.shape == (2, 3)
    assert not hit.max_force.flags.writeable


def test_float32_input():
    b = hertz.Body.sphere(np.float32(0.01), E=np.float32(48e9), nu=np.float32(0.2))
    hit = hertz.impact(b, b, speed=np.float32(20.0), mass=np.float32(GLASS_MASS / 2))
    ref = hertz.impact(hertz.Body.sphere(float(np.float32(0.01)), E=float(np.float32(48e9)),
                                         nu=float(np.float32(0.2))),
                       hertz.Body.sphere(float(np.float32(0.01)), E=float(np.float32(48e9)),
                                         nu=float(np.float32(0.2))),
                       speed=20.0, mass=float(np.float32(GLASS_MASS / 2)))
    assert type(hit.max_force) is float
    assert hit.max_force == pytest.approx(ref.max_force, rel=1e-15)


@pytest.mark.parametrize("kwargs, message", [
    (dict(speed=0.0), "speed must be a positive, finite approach speed in m/s, got 0.0"),
    (dict(speed=-1.0), "speed must be a positive"),
    (dict(speed=[1.0, math.nan]), r"speed must be .*, got nan at index 1"),
    (dict(speed=math.inf), "speed must be a positive"),
    (dict(mass=0.0), "mass must be a positive, finite reduced mass in kg, got 0.0"),
    (dict(mass=-2.0), "mass must be"),
])
def test_bad_input(kwargs, message):
    b = hertz.Body.sphere(0.01, E=48e9, nu=0.2)
    args = dict(speed=1.0, mass=1.0) | kwargs
    with pytest.raises(ValueError, match=message):
        hertz.impact(b, b, **args)


def test_bad_history_time_and_types():
    b = hertz.Body.sphere(0.01, E=48e9, nu=0.2)
    hit = hertz.impact(b, b, speed=1.0, mass=1.0)
    with pytest.raises(ValueError, match=r"t must be a finite time in s, got nan at index 1"):
        hit.history([0.0, math.nan])
    with pytest.raises(TypeError, match="speed must be a real number"):
        hertz.impact(b, b, speed="fast", mass=1.0)
    with pytest.raises(TypeError, match="body1 must be a hertz.Body"):
        hertz.impact((0.01, 0.01, 1e9, 0.3), b, speed=1.0, mass=1.0)


def test_pandas_xarray_pint():
    pd = pytest.importorskip("pandas")
    xr = pytest.importorskip("xarray")
    pint = pytest.importorskip("pint")
    b = hertz.Body.sphere(0.01, E=48e9, nu=0.2)
    plain = hertz.impact(b, b, speed=[1.0, 2.0], mass=0.005)
    s = hertz.impact(b, b, speed=pd.Series([1.0, 2.0], index=["a", "b"]), mass=0.005)
    assert list(s.max_force.index) == ["a", "b"] and s.max_force.name == "max_force"
    np.testing.assert_array_equal(s.max_force.to_numpy(), plain.max_force)
    np.testing.assert_array_equal(s.history(1e-6).force, plain.history(1e-6).force)
    x = hertz.impact(b, b, speed=xr.DataArray([1.0, 2.0], dims="v"), mass=0.005)
    assert x.duration.dims == ("v",)
    np.testing.assert_array_equal(x.duration.values, plain.duration)
    u = pint.UnitRegistry()
    q = hertz.impact(b, b, speed=3.6 * u("km/h"), mass=5 * u.g)
    assert q.max_force.to("N").magnitude == pytest.approx(plain.max_force[0], rel=1e-15)
    assert str(q.duration.units) == "second"
    with pytest.raises(TypeError, match="speed must be a speed .*, got a quantity in kilogram"):
        hertz.impact(b, b, speed=2 * u.kg, mass=1.0)
    with pytest.raises(ValueError, match=r"got -2.0 at index 1 \(label 'b'\)"):
        hertz.impact(b, b, speed=pd.Series([1.0, -2.0], index=["a", "b"]), mass=1.0)


# ----------------------------------------------------------------------------- rigid bodies

def test_rigid_body_is_the_limit_of_a_stiff_one():
    """E = inf gives E* = E/(1 - nu^2) of the other body; every field is the E -> 1e300
    limit (closed forms for a sphere on a plane)."""
    ball = hertz.Body.sphere(0.01, E=70e9, nu=0.33)
    rigid = hertz.contact(ball, hertz.Body.plane(E=INF, nu=0.3), load=100.0)
    stiff = hertz.contact(ball, hertz.Body.plane(E=1e300, nu=0.3), load=100.0)
    e_star = 70e9 / (1 - 0.33**2)
    assert rigid.e_star == pytest.approx(e_star, rel=2e-16)
    a = (3 * 100.0 * 0.01 / (4 * e_star)) ** (1 / 3)
    assert rigid.a == pytest.approx(a, rel=1e-15)
    assert rigid.delta == pytest.approx(a * a / 0.01, rel=1e-15)
    for k in ("a", "b", "p0", "delta", "stiffness", "e_star"):
        assert getattr(rigid, k) == pytest.approx(getattr(stiff, k), rel=1e-15), k
    # tangential: a rigid body has 1/G = 0; the ball's 8 a G / (2 - nu) alone
    shear = 70e9 / (2 * 1.33)
    assert rigid.tangential_stiffness() == pytest.approx(8 * rigid.a * shear / (2 - 0.33),
                                                         rel=1e-14)
    assert rigid.tangential_stiffness() == pytest.approx(stiff.tangential_stiffness(),
                                                         rel=1e-14)
    # Dundurs beta: (1 - 2 nu) / (2 (1 - nu)) of the elastic body (sign: body 1 elastic)
    beta = hertz.dundurs_beta(rigid)
    assert abs(beta) == pytest.approx((1 - 2 * 0.33) / (2 * (1 - 0.33)), rel=1e-14)
    assert beta == pytest.approx(hertz.dundurs_beta(stiff), rel=1e-14)
    assert math.isfinite(rigid.first_yield_load(300e6, body=2))
    m1 = rigid.subsurface(body=1)
    assert m1.tau_max == pytest.approx(stiff.subsurface(body=1).tau_max, rel=1e-14)
    line = hertz.line_contact(hertz.Body.cylinder(0.01, E=INF, nu=0.3),
                              hertz.Body.plane(E=200e9, nu=0.3), 1e4)
    assert line.e_star == pytest.approx(200e9 / 0.91, rel=2e-16)


def test_rigid_arrays_and_both_rigid_refused():
    bodies = hertz.Body.sphere([0.01, 0.02], E=[70e9, INF], nu=0.3)
    c = hertz.contact(bodies, hertz.Body.plane(E=[1e9, 2e9], nu=0.3), load=[1.0, 2.0])
    np.testing.assert_allclose(c.e_star, [1 / (0.91 / 70e9 + 0.91 / 1e9), 2e9 / 0.91],
                               rtol=2e-16)
    with pytest.raises(ValueError, match=r"body1.E and body2.E must not both be inf.*"
                                         r"at index 1"):
        hertz.contact(bodies, hertz.Body.plane(E=[1e9, INF], nu=0.3), load=1.0)
    with pytest.raises(ValueError, match="must not both be inf"):
        hertz.contact(hertz.Body.sphere(0.01, E=INF, nu=0.3), hertz.Body.plane(E=INF, nu=0.3),
                      load=1.0)
    with pytest.raises(ValueError, match="must not both be inf"):
        hertz.impact(hertz.Body.sphere(0.01, E=INF, nu=0.3), hertz.Body.plane(E=INF, nu=0.3),
                     speed=1.0, mass=1.0)
    with pytest.raises(ValueError, match=r"E must be a positive Young's modulus in Pa \(inf "
                                         r"for a rigid body\), got nan"):
        hertz.Body.plane(E=math.nan, nu=0.3)


def test_a_rigid_wall_needs_no_poisson_ratio():
    """Body.plane(E=inf), as a DEM user writes a wall: nu plays no part in E* = E/(1 - nu^2)
    of the other body; an elastic body must still give nu."""
    import math

    wall = hertz.Body.plane(E=math.inf)
    ball = hertz.Body.sphere(0.01, 70e9, 0.33)
    c = hertz.contact(ball, wall, load=10.0)
    e_star = 70e9 / (1 - 0.33 ** 2)
    assert c.e_star == pytest.approx(e_star, rel=1e-15)
    assert hertz.contact(ball, hertz.Body.plane(math.inf, 0.45), load=10.0).a == c.a
    with pytest.raises(TypeError, match="nu .* is required for an elastic body"):
        hertz.Body.sphere(0.01, 70e9)
