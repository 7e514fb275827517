"""Tangential contact at the ends of the double range (issue 22, item 10): finite, accepted
input gives the right number or one clear error, never NaN; one contact and an array of
them give the same bits.  References: mpmath, closed forms and exact scaling laws."""

import math

import mpmath as mp
import numpy as np
import pytest

import hertz

STEEL = dict(E=210e9, nu=0.3)
GLASS = dict(E=70e9, nu=0.22)
MU, LOAD = 0.3, 100.0
HUGE = [9e307, 1e308, -1.7976931348623157e308, 2.0 ** 1022, float(np.nextafter(2.0 ** 1023, 0)),
        -2.0 ** 1023]


def _contact(load=LOAD):
    """An elliptical contact of dissimilar bodies (b/a about 0.6)."""
    return hertz.contact(hertz.Body(5e-3, 2e-2, **STEEL), hertz.Body.plane(**GLASS), load=load)


# ----------------------------------------------------------------------------- direction
def _cos_sin_twice(t):
    """cos 2t, sin 2t of the double t, exactly reduced by mpmath (2t needs 1030 bits)."""
    with mp.workprec(2400):
        twice = 2 * mp.mpf(t)
        return float(mp.cos(twice)), float(mp.sin(twice))


@pytest.mark.parametrize("t", [0.3, 5e4, 1e300] + HUGE)
def test_any_finite_direction_gives_the_compliance_of_its_angle(t):
    """1/k(t) = (c_x + c_y)/2 + (c_x - c_y)/2 cos 2t and the transverse displacement
    -(c_x - c_y)/2 sin 2t per unit force, cos and sin of 2t from mpmath; beyond
    |t| = 2^1022 (2t overflows) this was NaN."""
    c = _contact()
    cx, cy = 1.0 / c.tangential_stiffness(0.0), 1.0 / c.tangential_stiffness(math.pi / 2)
    cos2, sin2 = _cos_sin_twice(t)
    along = 0.5 * (cx + cy) + 0.5 * (cx - cy) * cos2
    assert abs(c.tangential_stiffness(t) * along - 1.0) < 1e-15
    s = c.tangential(15.0, MU, t)
    across = -0.5 * (cx - cy) * sin2
    assert abs(s.displacement_transverse / s.displacement - across / along) < 1e-15
    assert abs(s.no_slip_stiffness * along - 1.0) < 1e-15
    assert np.isfinite(c.fretting(15.0, MU, t).energy)


def test_huge_directions_in_an_array_are_each_their_own():
    c = _contact()
    t = np.array([0.3] + HUGE)
    got = c.tangential(15.0, MU, t)
    for i, angle in enumerate(t):
        one = c.tangential(15.0, MU, float(angle))
        assert got.displacement[i] == one.displacement
        assert got.displacement_transverse[i] == one.displacement_transverse


# ----------------------------------------------------------------------------- fretting
def _loop_energy_reference(k, limit, q):
    """W = 36 (mu P)^2 / (5 k) [1 - (1-q)^(5/3) - (5q/6)(1 + (1-q)^(2/3))] (the form that
    cancels, so at 3 times the digits the cancellation costs)."""
    with mp.workdps(3 * 60 + 400):
        q = mp.mpf(q)
        w = (36 * mp.mpf(limit) ** 2 / (5 * mp.mpf(k))
             * (1 - (1 - q) ** (mp.mpf(5) / 3) - 5 * q / 6 * (1 + (1 - q) ** (mp.mpf(2) / 3))))
        return w


@pytest.mark.parametrize("mu, q", [(MU, 0.5), (1e-152, 0.5), (1e148, 0.5), (1e152, 0.99),
                                   (1e154, 0.3), (1e155, 1.0), (1e148, 1e-120),
                                   (1e-40, 1e-60), (1e100, 1e-110)])
def test_fretting_energy_against_mpmath_where_powers_leave_the_range(mu, q):
    """mu P up to 1e157 and q down to 1e-120: (mu P)^2 overflows beyond 1.3e154 (was inf
    or NaN), q^3 underflows below 5e-109 (was 0)."""
    c = _contact()
    limit = mu * LOAD
    amplitude = q * limit
    qq = amplitude / limit  # the ratio the function sees
    got = c.fretting(amplitude, mu).energy
    expected = _loop_energy_reference(c.tangential_stiffness(), limit, qq)
    assert 0.0 < got < math.inf
    assert abs(mp.mpf(got) / expected - 1) < 2e-15


def test_fretting_energy_scales_exactly_as_mu_p_squared():
    """mu and the amplitude times 2^j: q is the same double and W = (mu P)^2 / k g(q) is
    W(0) 2^(2j) exactly, through subnormal results (mu P = 1e-150) and overflow to inf
    (beyond W = 1.8e308 J; mu P up to 1e300)."""
    c = _contact()
    amplitudes = np.array([0.5, 1e-3, 0.999, 1.0, 1e-30]) * MU * LOAD
    base = c.fretting(amplitudes, MU).energy
    for j in range(-520, 1000, 7):
        mu = math.ldexp(MU, j)
        if mu * LOAD > 1e300:
            break
        got = c.fretting(np.ldexp(amplitudes, j), mu).energy
        with np.errstate(over="ignore"):
            expected = np.ldexp(base, 2 * j)
        assert np.array_equal(got, expected), j
    assert j > 990  # the loop reached mu P = 1e300


def test_fretting_energy_one_contact_and_many_the_same_bits():
    c = _contact()
    amplitudes = np.random.default_rng(5).uniform(0, MU * LOAD, 1000)
    many = c.fretting(amplitudes, MU).energy
    one = np.array([c.fretting(float(a), MU).energy for a in amplitudes])
    assert np.array_equal(many, one)


def test_mu_times_load_beyond_a_double_is_refused():
    """3 mu P / 2 must be a double: beyond, every displacement was inf and at zero force
    NaN."""
    c = _contact()
    for call in (lambda: c.fretting(0.0, 1.5e306), lambda: c.tangential(0.0, 1.5e306),
                 lambda: hertz.tangential_history(c, [0.0], 1.5e306),
                 lambda: hertz.TangentialSpring(c, 1.5e306)):
        with pytest.raises(ValueError, match=r"^mu \* load must be at most 1e\+308 N .*got "
                                             r"mu = 1\.5e\+306 and load = 100\.0 N$"):
            call()
    t = c.tangential(0.0, 1e306)  # mu P = 1e308: the largest accepted
    assert t.displacement == 0.0 and t.stick_a == c.a


# ----------------------------------------------------------------------------- springs
def test_load_path_spring_slides_any_distance_without_nan():
    """An increment of 1e302 m slides the contact as a whole, as any increment beyond
    2 (3 mu P / (2 k)) does: the same forces afterwards as after 1e-3 m, and those of
    TangentialSpring (was NaN from then on).  The force never exceeds mu P (after a
    return to the limit it was 30.000000000000007 N for mu P = 30 N)."""
    ball = hertz.Body.sphere(0.01, **STEEL)
    plane = hertz.Body.plane(**STEEL)
    c = hertz.contact(ball, plane, load=LOAD)
    huge = hertz.LoadPathSpring(ball, plane, MU)
    moderate = hertz.LoadPathSpring(ball, plane, MU)
    old = hertz.TangentialSpring(c, MU)
    assert huge.step(LOAD, 0.0) == moderate.step(LOAD, 0.0) == 0.0  # pressed first
    steps = [1e-7, 1e302, -1e-7, 1e-7, -1.7e308, 3e-7, -1e-6, 1e-300]
    for k, d in enumerate(steps):
        f = huge.step(LOAD, d)
        g = moderate.step(LOAD, math.copysign(1e-3, d) if abs(d) > 1.0 else d)
        h = old.step(d)
        assert f == g and huge.sliding == moderate.sliding, k
        assert abs(f - h) < 6e-16 * MU * LOAD and huge.sliding == old.sliding, k
        assert abs(f) <= MU * LOAD
    # beyond the range of a double: refused, the state unchanged
    before = (huge.force, huge.displacement)
    with pytest.raises(ValueError, match=r"^increment must keep the accumulated displacement "
                                         r"within the range of a double .*got -1\.7e\+308 m"):
        huge.step(LOAD, -1.7e308)
    assert (huge.force, huge.displacement) == before
    assert huge.step(LOAD, -2e-7) == moderate.step(LOAD, -2e-7)


def test_tangential_spring_overflow_is_refused_and_slides_on():
    """Two steps of 1.7e308 m: the second is refused (was NaN for ever after); a reversal
    after a slide of 1e300 m gives the Masing branch, as after a slide of 1e-3 m (the
    small step was rounded away on the accumulated 1e300 m)."""
    c = _contact()
    spring = hertz.TangentialSpring(c, MU)
    assert spring.step(1.7e308) == MU * LOAD
    with pytest.raises(ValueError, match=r"^increment must keep the accumulated displacement "
                                         r"within the range of a double .*got 1\.7e\+308 m on "
                                         r"1\.7e\+308 m$"):
        spring.step(1.7e308)
    assert spring.force == MU * LOAD and spring.displacement == 1.7e308
    reach = 1.5 * MU * LOAD / c.tangential_stiffness()
    moderate = hertz.TangentialSpring(c, MU)
    moderate.step(1e-3)
    for d in (-0.5 * reach, 0.1 * reach, -3 * reach, 1e-300, 2.5 * reach):
        assert spring.step(d) == moderate.step(d)
        assert spring.sliding == moderate.sliding
    # and against Masing from the sliding point: mu P - 2 mu P (1 - (1 - x/(2 reach))^(3/2))
    spring.step(1e300)
    down = spring.step(-0.5 * reach) / (MU * LOAD)
    assert abs(down - (1 - 2 * (1 - (1 - 0.25) ** 1.5))) < 1e-14


def test_tangential_spring_array_with_huge_steps_stays_within_the_limit():
    c = hertz.contact(hertz.Body.sphere(5e-3, **STEEL), hertz.Body.plane(**GLASS),
                      load=np.array([1.0, 10.0, 100.0]))
    spring = hertz.TangentialSpring(c, MU)
    rng = np.random.default_rng(3)
    for _ in range(40):
        f = spring.step(rng.choice([-1.0, 1.0], 3) * 10.0 ** rng.uniform(-12, 300, 3))
        assert np.all(np.isfinite(f)) and np.all(np.abs(f) <= MU * np.array([1, 10, 100.0]))


# ----------------------------------------------------------------------------- history
def test_history_with_no_instants_is_empty():
    """n = 0 instants: an empty result of shape (0, ...) (was numpy's reshape error)."""
    c = _contact()
    assert hertz.tangential_history(c, [], MU).shape == (0,)
    assert hertz.tangential_history(c, np.zeros((0, 3)), MU).shape == (0, 3)
    many = _contact(np.array([10.0, 20.0]))
    assert hertz.tangential_history(many, np.zeros(0), MU).shape == (0, 2)


def test_history_of_shape_n_drives_every_contact():
    """Forces of shape (n,) on two contacts: each contact the whole history (its trailing
    axes, none, broadcast with the contacts'); at n = 2 the instants were taken as the
    contacts, silently."""
    loads = np.array([10.0, 20.0])
    many = _contact(loads)
    forces = [2.0, -1.0]
    got = hertz.tangential_history(many, forces, MU)
    assert got.shape == (2, 2)
    for j, load in enumerate(loads):
        assert np.array_equal(got[:, j], hertz.tangential_history(_contact(load), forces, MU))
    with pytest.raises(ValueError, match=r"^forces must have the shape \(n, \.\.\.\), its "
                                         r"trailing axes \(3,\) broadcasting with the "
                                         r"contacts' shape \(2,\), got the shape \(4, 3\)$"):
        hertz.tangential_history(many, np.zeros((4, 3)), MU)


def test_history_near_the_largest_double():
    """Forces of +-1e308 N (mu P = 1e308): differences overflow, the displacements do
    not: the memory closes the small loop, as at ordinary forces."""
    c = _contact()
    mu = 1e306
    d = hertz.tangential_history(c, [1e308, -1e308, 0.5e308, -1e308, 1e308], mu)
    assert np.all(np.isfinite(d))
    assert d[1] == d[3] and d[0] == d[4] and d[1] == -d[0]


# ----------------------------------------------------------------------------- far field
def _cerruti(force, nu, x, y, z, angle):
    """Cerruti's stress [Pa] of a point force ``force`` [N] on the surface, along
    ``angle`` from x (Johnson, Contact Mechanics, eq. 2.19), in mpmath."""
    with mp.workdps(40):
        c, s = mp.cos(angle), mp.sin(angle)
        u, v, w = c * x + s * y, -s * x + c * y, mp.mpf(z)  # the force's frame
        r = mp.sqrt(u * u + v * v + w * w)
        k, g = force / (2 * mp.pi), 1 - 2 * mp.mpf(nu)
        sxx = k * (-3 * u ** 3 / r ** 5 + g * (u / r ** 3 - 3 * u / (r * (r + w) ** 2)
                                               + u ** 3 / (r ** 3 * (r + w) ** 2)
                                               + 2 * u ** 3 / (r ** 2 * (r + w) ** 3)))
        syy = k * (-3 * u * v ** 2 / r ** 5 + g * (u / r ** 3 - u / (r * (r + w) ** 2)
                                                    + u * v ** 2 / (r ** 3 * (r + w) ** 2)
                                                    + 2 * u * v ** 2 / (r ** 2 * (r + w) ** 3)))
        sxy = k * (-3 * u ** 2 * v / r ** 5 + g * (-v / (r * (r + w) ** 2)
                                                    + u ** 2 * v / (r ** 3 * (r + w) ** 2)
                                                    + 2 * u ** 2 * v / (r ** 2 * (r + w) ** 3)))
        szz = -3 * k * u * w ** 2 / r ** 5
        sxz = -3 * k * u ** 2 * w / r ** 5
        syz = -3 * k * u * v * w / r ** 5
        local = mp.matrix([[sxx, sxy, sxz], [sxy, syy, syz], [sxz, syz, szz]])
        rot = mp.matrix([[c, -s, 0], [s, c, 0], [0, 0, 1]])
        out = rot * local * rot.T
        return np.array([[float(out[i, j]) for j in range(3)] for i in range(3)])


@pytest.mark.parametrize("radius", [1e3, 1e50, 1e100, 1e150])
@pytest.mark.parametrize("direction", [0.0, math.pi / 2, 0.7])
def test_far_field_is_cerruti_of_the_force(radius, direction):
    """Far from the contact (here 1e7 to 1e154 semi-axes) the tangential field is
    Cerruti's field of the resultant Q (within (a/R)^2 of it); beyond 1e50 m it was NaN
    while the frictionless field is finite.  Body 2 carries the traction along
    ``direction``, body 1 the opposite."""
    c = _contact()
    t = c.tangential(15.0, MU, direction)
    for unit in ([0.6, -0.48, 0.64], [0.8, 0.6, 0.0], [-0.6, 0.0, 0.8]):
        x, y, z = (radius * u for u in unit)
        for body, sign, nu in ((2, 1.0, GLASS["nu"]), (1, -1.0, STEEL["nu"])):
            got = t.stress(x, y, z, body=body)
            assert np.all(np.isfinite(got))
            friction = got - c.stress(x, y, z, body=body)
            expected = sign * _cerruti(15.0, nu, x, y, z, direction)
            scale = np.max(np.abs(expected))
            assert scale > 0
            assert np.max(np.abs(friction - expected)) <= 1e-13 * scale, (body, unit)


def test_stress_one_point_and_many_the_same_bits():
    """Each point's Newton iteration for the ellipsoidal coordinate stops on its own (it
    went on while others in the batch had not converged: 1 ulp apart at 8 of 287 points)."""
    c = _contact()
    t = c.tangential(15.0, MU, 0.4)
    rng = np.random.default_rng(7)
    n = 287
    x = rng.uniform(-2, 2, n) * c.a
    y = rng.uniform(-2, 2, n) * c.b
    z = np.where(rng.uniform(size=n) < 0.2, 0.0, rng.uniform(0, 1.5, n) * c.a)
    x[:20] *= 10.0 ** rng.uniform(3, 8, 20)  # some beyond the switch to the far field
    for body in (1, 2):
        many = t.stress(x, y, z, body=body)
        one = np.array([t.stress(float(p), float(q), float(r), body=body)
                        for p, q, r in zip(x, y, z, strict=True)])
        assert np.array_equal(many, one)
