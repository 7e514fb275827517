"""Tangential.stress and Tangential.maxima: the frictionless field of the contact plus the
Cattaneo-Mindlin traction's field of hertz/_friction.py (itself checked against an mpmath
quadrature of Cerruti's solution in tests/test_friction.py), on the right body with the
right sign.  Independent checks: the frictionless limit, the surface shear against the
closed-form traction (equilibrium of the surface, opposite in the two bodies)."""

import math

import numpy as np
import pytest

import hertz
from hertz._friction import partial_slip_stress, sliding_maxima

# dissimilar bodies (nu1 != nu2: the body's own nu must reach the field), b/a about 0.6
BALL = hertz.Body(0.01, 0.03, E=210e9, nu=0.3)
BLOCK = hertz.Body.plane(E=70e9, nu=0.22)
CONTACT = hertz.contact(BALL, BLOCK, load=100.0)
NU = {1: 0.3, 2: 0.22}
MU = 0.4
LIMIT = MU * CONTACT.load
# points below and on the surface, inside and outside the contact, in the stick zone
# (r < 0.79 for Q/(mu P) = 1/2) and the slip annulus
A, B = CONTACT.a, CONTACT.b
X = np.array([0.0, 0.3, -0.5, 0.9, -0.95, 1.4, 0.2, -0.6]) * A
Y = np.array([0.0, 0.2, 0.3, -0.1, 0.0, 0.5, -0.9, 0.4]) * B
Z = np.array([0.5, 0.0, 0.1, 0.0, 0.3, 0.0, 0.05, 1.2]) * A


def test_the_frictionless_limit_is_the_normal_field():
    for force, mu in ((0.0, MU), (1e-15 * LIMIT, MU), (1e-16 * CONTACT.load, 1e-16)):
        t = CONTACT.tangential(force, mu, direction=0.7)
        for body in (1, 2):
            diff = t.stress(X, Y, Z, body=body) - CONTACT.stress(X, Y, Z, body=body)
            assert np.abs(diff).max() <= 1e-15 * CONTACT.p0


@pytest.mark.parametrize("force", [0.3 * LIMIT, 0.5 * LIMIT, LIMIT])
@pytest.mark.parametrize("direction", [0.0, 0.7, -2.1])
def test_it_is_the_normal_field_plus_the_partial_slip_field(force, direction):
    t = CONTACT.tangential(force, MU, direction)
    ratio = t.stick_a / CONTACT.a
    # the stick ratio handed on is Cattaneo-Mindlin's (1 - Q/(mu P))^(1/3)
    assert ratio == pytest.approx(np.cbrt(1.0 - force / LIMIT), rel=2e-16, abs=1e-300)
    for body, sign in ((1, -1.0), (2, 1.0)):
        friction = partial_slip_stress(CONTACT.a, CONTACT.b, CONTACT.p0, MU, NU[body], X, Y,
                                       Z, ratio, direction)
        expected = CONTACT.stress(X, Y, Z, body=body) + sign * friction
        assert np.array_equal(t.stress(X, Y, Z, body=body), expected)
    # body 1's field is the one of the traction reversed (direction + pi, as _friction has it)
    reversed_ = partial_slip_stress(CONTACT.a, CONTACT.b, CONTACT.p0, MU, NU[1], X, Y, Z,
                                    ratio, direction + math.pi)
    diff = t.stress(X, Y, Z, body=1) - CONTACT.stress(X, Y, Z, body=1) - reversed_
    assert np.abs(diff).max() <= 1e-15 * CONTACT.p0


@pytest.mark.parametrize("q", [0.25, 0.5, 0.9, 1.0])
@pytest.mark.parametrize("direction", [0.0, 0.7])
def test_surface_shear_is_the_traction_opposite_in_the_two_bodies(q, direction):
    t = CONTACT.tangential(q * LIMIT, MU, direction)
    # on the surface, inside the contact, in the stick zone and in the slip annulus
    r = np.array([0.0, 0.3, 0.55, 0.75, 0.85, 0.95])
    angle = np.array([0.0, 1.0, 2.5, -0.4, 4.0, 2.0])
    x, y = r * np.cos(angle) * A, r * np.sin(angle) * B
    traction = t.traction(x, y)
    assert np.all(traction > 0.01 * MU * CONTACT.p0)
    unit = np.array([math.cos(direction), math.sin(direction)])
    # the traction on body 2 is along the force (body 1 is pushed along it, body 2 dragged);
    # z is the depth into the body, whose outward normal is -z: sigma_iz = -t_i
    for body, on_body in ((2, 1.0), (1, -1.0)):
        s = t.stress(x, y, 0.0, body=body)
        for i in (0, 1):
            expected = -on_body * traction * unit[i]
            assert np.abs(s[:, i, 2] - expected).max() <= 1e-12 * CONTACT.p0
        assert np.abs(s[:, 2, 2] + CONTACT.pressure(x, y)).max() <= 1e-12 * CONTACT.p0


def test_a_one_percent_error_in_the_traction_fails():
    t = CONTACT.tangential(0.5 * LIMIT, MU, 0.0)
    x = np.array([0.3, 0.9]) * A
    err = np.abs(t.stress(x, 0.0, 0.0, body=2)[:, 0, 2] + 1.01 * t.traction(x, 0.0)).max()
    assert err > 100 * 1e-12 * CONTACT.p0


def test_maxima_at_full_sliding_are_sliding_maxima():
    direction = 0.0  # along an axis: the search stays in the plane of symmetry (fast)
    t = CONTACT.tangential(LIMIT, MU, direction)
    assert t.sliding
    m2 = t.maxima(body=2)
    assert m2 == sliding_maxima(CONTACT.a, CONTACT.b, CONTACT.p0, MU, NU[2], direction)
    m1 = t.maxima(body=1)
    assert m1 == sliding_maxima(CONTACT.a, CONTACT.b, CONTACT.p0, MU, NU[1],
                                direction + math.pi)


def test_maxima_in_partial_slip_and_of_similar_bodies():
    similar = hertz.contact(hertz.Body.sphere(0.01, E=210e9, nu=0.3),
                            hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
    t = similar.tangential(0.5 * MU * similar.load, MU, 0.0)
    ratio = np.cbrt(0.5)
    m2 = t.maxima(body=2)
    ref = sliding_maxima(similar.a, similar.b, similar.p0, MU, 0.3, 0.0, stick_ratio=ratio)
    assert m2.von_mises == pytest.approx(ref.von_mises, rel=1e-12)
    assert m2.tensile == pytest.approx(ref.tensile, rel=1e-12)
    # the same material, the traction reversed: the same maxima, mirrored through the z axis
    m1 = t.maxima(body=1)
    for name in ("von_mises", "tau_max", "tensile"):
        assert getattr(m1, name) == pytest.approx(getattr(m2, name), rel=1e-9)
    assert m1.x_tensile == pytest.approx(-m2.x_tensile, abs=1e-6 * similar.a)
    # a tangential force raises the largest surface tension above the frictionless one
    assert m2.tensile > 1.5 * similar.subsurface().tensile


def test_maxima_and_stress_refuse_a_bad_body():
    # (arrays of contacts: tests/test_tangential_api.py)
    with pytest.raises(ValueError, match="body must be 1 or 2"):
        CONTACT.tangential(10.0, MU).maxima(body=3)
    with pytest.raises(ValueError, match="body must be 1 or 2"):
        CONTACT.tangential(10.0, MU).stress(0.0, 0.0, 0.0, body=0)
