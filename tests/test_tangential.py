"""Tangential contact (Cattaneo-Mindlin, Mindlin-Deresiewicz) against an mpmath quadrature of
Cerruti's solution (tests/reference_tangential.py) and physical invariants.

The reference is computed once per module at DPS = 20 (about 1e-19 relative, far below the
tolerances) for held-out ellipses b/a = 1 to 1e-3 with dissimilar materials; it integrates
the tractions, never the closed forms of hertz/_tangential.py.
"""

import math

import mpmath as mp
import numpy as np
import pytest
import reference_tangential as ref

import hertz

ref.DPS = 20

STEEL = dict(E=210e9, nu=0.3)
GLASS = dict(E=70e9, nu=0.22)
POLYMER = dict(E=3e9, nu=0.45)
LOAD, MU = 20.0, 0.375  # mu P = 7.5 exactly: q = 1 is the same number here and in mpmath

# Ry/Rx of body 1 on a plane of body 2: b/a = 1, 0.48, 0.095, 0.012, 9e-4
SCENES = [(1.0, STEEL, GLASS), (3.0, GLASS, STEEL), (40.0, STEEL, POLYMER),
          (1500.0, POLYMER, STEEL), (1.5e5, STEEL, GLASS)]

# Observed agreement with the quadrature, relative, worst over the scenes, both axes and the
# forces below (AMD EPYC, numpy 2.4): compliance 2.9e-16, displacement 5.6e-16, stick
# semi-axes 7.1e-16, tangent stiffness 9.8e-16, loop energy 7.7e-16, Masing branch 6.3e-16
# (of delta*).  The issue asks for 1e-13; the tolerances sit 1.5x above what is observed.
TOL = 1e-15
TOL_COMPLIANCE = 4.5e-16
TOL_DISPLACEMENT = 9e-16
TOL_STICK = 1.1e-15
TOL_STIFFNESS = 1.5e-15
TOL_ENERGY = 1.2e-15
TOL_BRANCH = 1e-15


def _contact(ratio, m1, m2, load=LOAD):
    return hertz.contact(hertz.Body(5e-3, 5e-3 * ratio, **m1), hertz.Body.plane(**m2),
                         load=load)


def _bodies(m1, m2):
    return [(m["E"] / (2 * (1 + m["nu"])), m["nu"]) for m in (m1, m2)]


def _rel(actual, expected):
    return abs(mp.mpf(float(actual)) - expected) / abs(expected)


@pytest.fixture(scope="module")
def scenes():
    """Each scene's contact and the quadrature's compliances and sliding displacements."""
    out = []
    for ratio, m1, m2 in SCENES:
        c = _contact(ratio, m1, m2)
        bodies = _bodies(m1, m2)
        refs = {axis: (ref.no_slip_compliance(c.a, c.b, bodies, axis),
                       ref.sliding_displacement(c.a, c.b, LOAD, MU, bodies, axis))
                for axis in "xy"}
        out.append((c, bodies, refs))
    return out


def test_scenes_span_the_ellipses(scenes):
    ratios = [c.b / c.a for c, _, _ in scenes]
    assert ratios[0] == 1.0 and min(ratios) < 1.05e-3


def test_no_slip_compliance_along_both_axes(scenes):
    worst = 0.0
    for c, _, refs in scenes:
        compliance = hertz.tangential_compliance(c)
        assert compliance[0, 1] == compliance[1, 0] == 0.0
        for i, axis in enumerate("xy"):
            worst = max(worst, _rel(compliance[i, i], refs[axis][0]))
            direction = 0.0 if axis == "x" else math.pi / 2
            worst = max(worst, _rel(1.0 / c.tangential_stiffness(direction), refs[axis][0]))
    assert worst < TOL_COMPLIANCE, worst


def test_stiffness_in_any_direction(scenes):
    c, _, refs = scenes[2]
    cx, cy = refs["x"][0], refs["y"][0]
    for t in (0.3, 1.0, -2.0, 7.0):
        expected = 1 / (cx * mp.cos(t) ** 2 + cy * mp.sin(t) ** 2)
        assert _rel(c.tangential_stiffness(t), expected) < TOL_COMPLIANCE
    k = c.tangential_stiffness(np.array([0.0, 0.3, math.pi / 2]))
    assert k.shape == (3,) and k[0] < k[1] < k[2]  # the minor axis is the stiffer


def test_the_quadrature_confirms_mindlin_uniform_displacement():
    """The reference's own premise, checked once at an off-centre point: the no-slip
    traction moves the ellipse rigidly (no transverse part), and Mindlin's partial-slip
    traction moves the stick ellipse rigidly."""
    a, b = 1.0, 0.2
    bodies = _bodies(STEEL, POLYMER)
    centre = ref.displacement_no_slip(a, b, bodies, 0, 0, "y")
    off = ref.displacement_no_slip(a, b, bodies, 0.6 * a, -0.5 * b, "y")
    assert abs(off[0] / centre[0] - 1) < 1e-17 and abs(off[1] / centre[0]) < 1e-17
    c = mp.cbrt(mp.mpf(1) - mp.mpf(0.3) / mp.mpf(0.5))  # stick ratio at Q / (mu P) = 0.6
    x0, y0 = 0.5 * c * a, 0.6 * c * b  # a point of the stick ellipse
    u0 = ref.displacement_hertz_traction(a, b, bodies, 0, 0, "x")[0]
    u1 = ref.displacement_hertz_traction(a, b, bodies, x0, y0, "x")[0]
    u2 = ref.displacement_hertz_traction(a, b, bodies, x0 / c, y0 / c, "x")[0]
    # full traction minus the stick ellipse's (c^2 times the full one's at (x0, y0)/c)
    assert abs((u1 - c * c * u2) / (u0 * (1 - c * c)) - 1) < 1e-17


@pytest.mark.parametrize("q", [1e-6, 0.1, 0.5, 0.9, 0.99, 1.0])
def test_partial_slip_displacement_and_stick_zone(scenes, q):
    worst = 0.0
    for c, _, refs in scenes:
        force = q * MU * LOAD
        with mp.workdps(ref.DPS):
            ratio = mp.cbrt(1 - mp.mpf(force) / (mp.mpf(MU) * LOAD))
        for axis, direction in (("x", 0.0), ("y", math.pi / 2)):
            t = c.tangential(force, MU, direction)
            expected = ref.virgin(refs[axis][1], LOAD, MU, force)
            worst = max(worst, _rel(t.displacement, expected))
            if q < 1.0:
                assert _rel(t.stick_a, c.a * ratio) < TOL_STICK
                assert _rel(t.stick_b, c.b * ratio) < TOL_STICK
                assert _rel(t.stiffness, ratio / refs[axis][0]) < TOL_STIFFNESS
            else:
                assert t.stick_a == t.stick_b == t.stiffness == 0.0 and t.sliding
    assert worst < TOL_DISPLACEMENT, worst


def test_masing_unloading_branch(scenes):
    worst = 0.0
    for c, _, refs in scenes:
        amplitude = 0.8 * MU * LOAD
        forces = np.array([0.8, 0.5, 0.0, -0.3, -0.79]) * MU * LOAD
        for axis, direction in (("x", 0.0), ("y", math.pi / 2)):
            expected = ref.masing_unloading(refs[axis][1], LOAD, MU, amplitude, forces)
            got = c.fretting(amplitude, MU, direction).unloading(forces)
            path = np.concatenate([[amplitude], forces])
            hist = hertz.tangential_history(c, path, MU, direction)[1:]
            scale = abs(expected[0])  # the branch crosses zero: errors relative to delta*
            for g, h, e in zip(got, hist, expected, strict=True):
                worst = max(worst, abs(mp.mpf(float(g)) - e) / scale,
                            abs(mp.mpf(float(h)) - e) / scale)
    assert worst < TOL_BRANCH, worst


@pytest.mark.parametrize("q", [1e-6, 1e-4, 0.3, 0.99, 1.0])
def test_loop_energy(scenes, q):
    worst = 0.0
    for c, _, refs in scenes[::2]:
        amplitude = q * MU * LOAD
        for axis, direction in (("x", 0.0), ("y", math.pi / 2)):
            expected = ref.loop_energy(refs[axis][1], LOAD, MU, amplitude)
            worst = max(worst, _rel(c.fretting(amplitude, MU, direction).energy, expected))
    assert worst < TOL_ENERGY, worst


def test_a_one_percent_error_in_the_reference_fails(scenes):
    """The tolerances can fail: a 1% error in any reference quantity is caught."""
    c, _, refs = scenes[3]
    assert _rel(1.0 / c.tangential_stiffness(), refs["x"][0] * 1.01) > 100 * TOL
    t = c.tangential(0.99 * MU * LOAD, MU)
    assert _rel(t.displacement, ref.virgin(refs["x"][1] * 1.01, LOAD, MU, t.force)) > 100 * TOL
    e = ref.loop_energy(refs["x"][1] * 0.99, LOAD, MU, 0.5 * MU * LOAD)
    assert _rel(c.fretting(0.5 * MU * LOAD, MU).energy, e) > 100 * TOL


# ----------------------------------------------------------------------------- circle
def test_circle_limit_is_smooth():
    """alpha = 1 exactly and 1 + 1 ulp give the classic 8 a / sum (2 - nu)/G."""
    eps = 2.0 ** -52
    g1 = STEEL["E"] / (2 * 1.3)
    g2 = GLASS["E"] / (2 * 1.22)
    for ry in (5e-3, 5e-3 * (1 + eps), 5e-3 * (1 + 2 * eps), 5e-3 * (1 + 1e-9)):
        c = hertz.contact(hertz.Body(5e-3, ry, **STEEL), hertz.Body.plane(**GLASS), load=LOAD)
        classic = 8 * c.a / ((2 - 0.3) / g1 + (2 - 0.22) / g2)
        for t in (0.0, 1.0):
            assert abs(c.tangential_stiffness(t) / classic - 1) < 3e-16 + 1e-9 * (ry != 5e-3)
    assert _contact(1.0, STEEL, GLASS).alpha == 1.0


# ----------------------------------------------------------------------------- invariants
def test_stiffness_falls_to_zero_at_the_limit_of_friction():
    c = _contact(40.0, STEEL, GLASS)
    q = 1 - np.logspace(-1, -12, 12)
    t = c.tangential(q * MU * LOAD, MU, 0.4)
    k0 = c.tangential_stiffness(0.4)
    assert np.all(np.diff(t.stiffness) < 0)
    np.testing.assert_allclose(t.stiffness / k0, np.cbrt(1 - q), rtol=1e-4)
    assert t.stiffness[-1] < 1e-3 * k0
    assert c.tangential(MU * LOAD, MU, 0.4).stiffness == 0.0


def test_energy_goes_as_amplitude_cubed():
    c = _contact(3.0, GLASS, STEEL)
    amplitudes = np.logspace(-9, -3, 7) * MU * LOAD
    loop = c.fretting(amplitudes, MU)
    small = 2 * amplitudes ** 3 / (9 * MU * LOAD * c.tangential_stiffness())
    q = amplitudes / (MU * LOAD)
    # W = 2 Q*^3 / (9 mu P k) (1 + 2q/3 + O(q^2)): no cancellation down to q = 1e-9
    assert np.all(np.abs(loop.energy / small - (1 + 2 * q / 3)) < 2e-15 + q * q)
    assert abs(loop.energy[0] / small[0] - (1 + 2 * q[0] / 3)) < 3e-15


def test_loop_is_symmetric_and_closed():
    c = _contact(1500.0, POLYMER, STEEL)
    loop = c.fretting(0.7 * MU * LOAD, MU, 0.2)
    forces = np.linspace(-1, 1, 41) * loop.amplitude
    np.testing.assert_allclose(loop.unloading(forces), -loop.reloading(-forces),
                               rtol=0, atol=1e-15 * loop.displacement_amplitude)
    f, d = loop.loop(51)
    assert f[0] == f[-1] and abs(d[0] - d[-1]) < 1e-15 * loop.displacement_amplitude
    assert np.all(loop.unloading(forces) >= loop.reloading(forces) - 1e-16)
    # the loop's area by the trapezoid rule
    F, D = loop.loop(20001)
    area = 0.5 * abs(np.sum((D[1:] + D[:-1]) * np.diff(F)))
    assert abs(area / loop.energy - 1) < 1e-6


def test_history_with_memory_and_the_virgin_curve():
    c = _contact(40.0, STEEL, POLYMER)
    lim = MU * LOAD
    path = np.array([0.5, -0.2, 0.3, -0.2, 0.6, -0.6, 0.6, 0.9, -0.9]) * lim
    d = hertz.tangential_history(c, path, MU)
    virgin = [c.tangential(f, MU).displacement for f in (0.5 * lim, 0.6 * lim, 0.9 * lim)]
    assert d[0] == virgin[0]
    assert abs(d[3] - d[1]) < 1e-22  # the small loop -0.2 -> 0.3 -> -0.2 closed
    assert abs(d[4] - virgin[1]) < 1e-15 * virgin[1]  # back on the virgin curve past 0.5
    assert abs(d[5] + virgin[1]) < 1e-15 * virgin[1]  # Masing: the branch ends at -delta*
    assert abs(d[6] - virgin[1]) < 1e-15 * virgin[1]
    assert abs(d[7] - virgin[2]) < 1e-15 * virgin[2]
    assert abs(d[8] + virgin[2]) < 1e-15 * virgin[2]


def test_history_is_vectorised_over_contacts():
    c = hertz.contact(hertz.Body(5e-3, 5e-3 * np.array([1.0, 3.0, 40.0]), **STEEL),
                      hertz.Body.plane(**GLASS), load=np.array([5.0, 20.0, 50.0]))
    rng = np.random.default_rng(7)
    path = rng.uniform(-1, 1, (40, 3)) * MU * c.load
    d = hertz.tangential_history(c, path, MU)
    for i, ratio in enumerate((1.0, 3.0, 40.0)):
        one = hertz.contact(hertz.Body(5e-3, 5e-3 * ratio, **STEEL), hertz.Body.plane(**GLASS),
                            load=float(c.load[i]))
        np.testing.assert_array_equal(d[:, i], hertz.tangential_history(one, path[:, i], MU))


def test_oblique_force_displacement_vector():
    c = _contact(40.0, STEEL, GLASS)
    compliance = hertz.tangential_compliance(c)
    t = c.tangential(0.6 * MU * LOAD, MU, 0.7)
    ux = c.tangential(0.6 * MU * LOAD, MU, 0.0).displacement * math.cos(0.7)
    uy = c.tangential(0.6 * MU * LOAD, MU, math.pi / 2).displacement * math.sin(0.7)
    along = ux * math.cos(0.7) + uy * math.sin(0.7)
    across = -ux * math.sin(0.7) + uy * math.cos(0.7)
    assert abs(t.displacement / along - 1) < 1e-15
    assert abs(t.displacement_transverse / across - 1) < 1e-14
    assert t.displacement_transverse < 0  # towards the major axis, the compliant one
    assert compliance[0, 0] > compliance[1, 1]


def test_traction_integrates_to_the_force():
    c = _contact(3.0, STEEL, GLASS)
    t = c.tangential(0.6 * MU * LOAD, MU)
    # polar map x = a r cos p, y = b r sin p; Gauss-Legendre in r on each side of the stick
    # edge r = s (where the traction has a square-root kink), trapezoid in p
    s = t.stick_a / c.a
    r, w = np.polynomial.legendre.leggauss(200)
    r = np.concatenate([(r + 1) * s / 2, s + (r + 1) * (1 - s) / 2])
    w = np.concatenate([w * s / 2, w * (1 - s) / 2])
    p = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    R, P = np.meshgrid(r, p)
    q = t.traction(c.a * R * np.cos(P), c.b * R * np.sin(P))
    total = np.sum(q * R * w) * (2 * np.pi / 64) * c.a * c.b
    assert abs(total / t.force - 1) < 1e-6
    assert t.traction(0.0, 0.0) < MU * c.p0 and t.traction(c.a, 0.0) == 0.0
    edge = 0.5 * (t.stick_a + c.a)  # the slip annulus carries mu p
    assert abs(t.traction(edge, 0.0) / (MU * c.pressure(edge, 0.0)) - 1) < 1e-12


def test_proportional_loading():
    c = _contact(40.0, STEEL, GLASS)
    d = hertz.proportional_loading(c, 0.2 * LOAD, MU, 0.5)
    # no slip, compliance growing as P^(-1/3): 3 Q / (2 k) at the final load
    assert abs(d * c.tangential_stiffness(0.5) / (1.5 * 0.2 * LOAD) - 1) < 1e-15
    # the integral of dQ / k(P) along the path Q = 0.2 P, P = LOAD t^3 (midpoint rule in t)
    t = (np.arange(2000) + 0.5) / 2000
    k = hertz.contact(hertz.Body(5e-3, 0.2, **STEEL), hertz.Body.plane(**GLASS),
                      load=LOAD * t ** 3).tangential_stiffness(0.5)
    assert abs(np.sum(0.2 * 3 * LOAD * t * t / 2000 / k) / d - 1) < 1e-6
    with pytest.raises(ValueError, match="slides from the start"):
        hertz.proportional_loading(c, MU * LOAD, MU)


# ----------------------------------------------------------------------------- DEM spring
def test_spring_follows_the_virgin_curve_and_slides():
    c = _contact(3.0, STEEL, GLASS)
    spring = hertz.TangentialSpring(c, MU, 0.3)
    reach = 1.5 * MU * LOAD / c.tangential_stiffness(0.3)
    for target in np.linspace(0.05, 0.95, 10) * reach:
        spring.step(target - spring.displacement)
        expected_disp = c.tangential(spring.force, MU, 0.3).displacement
        assert abs(expected_disp / target - 1) < 1e-12
    assert spring.step(reach) == MU * LOAD and spring.sliding
    assert spring.step(10 * reach) == MU * LOAD
    # reversal from sliding: Masing branch from the sliding point, the opposite limit after
    # 2 delta_s
    down = spring.step(-reach)
    # Masing from the sliding point: mu P - 2 g(delta_s / 2), g the virgin curve's inverse,
    # g(delta_s / 2) = mu P (1 - (1/2)^(3/2))
    assert abs(down / (MU * LOAD) - (2 * 0.5 ** 1.5 - 1)) < 1e-14 and not spring.sliding
    assert spring.step(-0.999999 * reach) > -MU * LOAD
    assert spring.step(-1e-3 * reach) == -MU * LOAD and spring.sliding


def test_spring_reversal_matches_the_force_history():
    c = _contact(40.0, GLASS, POLYMER)
    lim = MU * LOAD
    forces = np.array([0.5, -0.2, 0.3, -0.2, 0.6, -0.6]) * lim
    disp = hertz.tangential_history(c, forces, MU)
    spring = hertz.TangentialSpring(c, MU)
    previous = 0.0
    for f, d in zip(forces, disp, strict=True):
        got = spring.step(d - previous)
        previous = d
        assert abs(got - f) < 1e-12 * lim


def test_spring_is_vectorised():
    c = hertz.contact(hertz.Body.sphere(5e-3, **STEEL), hertz.Body.plane(**GLASS),
                      load=np.array([1.0, 10.0, 100.0]))
    spring = hertz.TangentialSpring(c, MU)
    f = spring.step(np.array([1e-10, 1e-8, 1e-3]))
    assert f.shape == (3,) and f[2] == MU * 100.0 and spring.sliding.tolist() == [0, 0, 1]


# ----------------------------------------------------------------------------- errors
def test_errors_name_the_parameter():
    c = _contact(3.0, STEEL, GLASS)
    with pytest.raises(ValueError, match=r"mu must be a positive.*got 0\.0"):
        c.tangential(1.0, 0.0)
    with pytest.raises(ValueError, match=r"mu must be .*got -0\.1 at index 1"):
        c.tangential(1.0, [0.3, -0.1])
    with pytest.raises(ValueError, match="mu must be"):
        c.fretting(1.0, float("nan"))
    with pytest.raises(ValueError, match=r"force must be a non-negative.*got -1\.0"):
        c.tangential(-1.0, MU)
    with pytest.raises(ValueError, match=r"force must be at most mu \* load = 7\.5 N.*slides"):
        c.tangential(7.6, MU)
    with pytest.raises(ValueError, match=r"amplitude must be at most"):
        c.fretting(7.6, MU)
    with pytest.raises(ValueError, match="direction must be a finite"):
        c.tangential_stiffness(math.inf)
    with pytest.raises(TypeError, match="force must be a real number"):
        c.tangential("1", MU)
    with pytest.raises(ValueError, match=r"forces must be at most"):
        hertz.tangential_history(c, [1.0, -7.6], MU)
    zero = _contact(3.0, STEEL, GLASS, load=0.0)
    assert zero.tangential_stiffness() == 0.0  # no load, no stiffness (not NaN)
    with pytest.raises(ValueError, match="contact.load must be positive"):
        zero.tangential(0.0, MU)
    with pytest.raises(ValueError, match="contact.load must be positive"):
        hertz.TangentialSpring(zero, MU)


def test_sliding_onset_is_a_result_without_nan():
    c = _contact(1500.0, STEEL, GLASS)
    t = c.tangential(np.array([0.0, MU * LOAD]), MU)
    for name in ("stick_a", "stick_b", "displacement", "stiffness", "slip_area"):
        assert np.all(np.isfinite(getattr(t, name)))
    assert t.sliding.tolist() == [False, True]
    assert t.displacement[0] == 0.0 and t.stick_a[0] == c.a
    assert np.all(np.isfinite(t.traction(0.0, 0.0)))
    loop = c.fretting(MU * LOAD, MU)
    assert math.isfinite(loop.energy) and loop.energy > 0


def test_dundurs_beta():
    assert hertz.dundurs_beta(_contact(1.0, STEEL, STEEL)) == 0.0
    b = hertz.dundurs_beta(_contact(1.0, STEEL, POLYMER))
    g1, g2 = 210e9 / 2.6, 3e9 / 2.9
    assert abs(b - (0.4 / g1 - 0.1 / g2) / (2 * (0.7 / g1 + 0.55 / g2))) < 1e-15
    assert hertz.dundurs_beta(_contact(1.0, POLYMER, STEEL)) == -b
    assert _contact(1.0, STEEL, POLYMER).tangential(1.0, MU).dundurs_beta == b


# ----------------------------------------------------------------------------- annulus
def test_reference_outside_the_ellipse():
    """The reference's field outside the loaded ellipse (needed for the slip annulus) is
    continuous across the edge and tends to Cerruti's point force far away."""
    a, b, bodies = 1.0, 0.3, [(1.0, 0.3)]
    t, h = 0.6, 1e-7
    inside = ref.displacement_hertz_traction(a, b, bodies, (1 - h) * a * math.cos(t),
                                             (1 - h) * b * math.sin(t), "y")
    outside = ref.displacement_hertz_traction(a, b, bodies, (1 + h) * a * math.cos(t),
                                              (1 + h) * b * math.sin(t), "y")
    # observed 5.2e-7 and 4.1e-7, linear in h (5.2e-4 at h = 1e-4): the field's gradient
    # times 2h; a wrong outside formula would be off by O(1)
    assert abs(outside[0] / inside[0] - 1) < 8e-7 and abs(outside[1] / inside[1] - 1) < 8e-7
    x0, y0 = 2000.0, 1300.0
    far = ref.displacement_hertz_traction(a, b, bodies, x0, y0, "x")
    force = 2 * mp.pi * a * b / 3  # the traction's resultant
    r = math.hypot(x0, y0)
    cerruti = force / (2 * mp.pi * r) * ((1 - 0.3) + 0.3 * (x0 / r) ** 2)
    assert abs(far[0] / cerruti - 1) < 1.5e-8  # observed 8.8e-9: terms of order (a/r)^2


def test_slip_annulus_misalignment_is_a_poisson_effect():
    """Mindlin's approximation: slip in the annulus not parallel to the traction. None at
    nu = 0 (for any direction), degrees at nu = 0.3 (figures: benchmarks/tangential_slip.py)."""
    point = [(0.92 * math.cos(0.5), 0.2 * 0.92 * math.sin(0.5))]
    dps, ref.DPS = ref.DPS, 15  # angles in degrees: 15 digits are plenty
    try:
        zero = ref.slip_misalignment(1.0, 0.2, [(1.0, 0.0)], 0.5, 0.7, point)[0]
        steel = ref.slip_misalignment(1.0, 0.2, [(1.0, 0.3)], 0.5, 0.7, point)[0]
    finally:
        ref.DPS = dps
    assert zero < 1e-12 and 1.0 < steel < 15.0


def test_stiffness_on_dask_is_lazy_and_the_same_bits():
    da = pytest.importorskip("dask.array")
    loads = np.linspace(1.0, 100.0, 10)
    body1, body2 = hertz.Body(5e-3, 0.02, **STEEL), hertz.Body.plane(**GLASS)
    lazy = hertz.contact(body1, body2, load=da.from_array(loads, chunks=5))
    k = lazy.tangential_stiffness(0.3)
    assert isinstance(k, da.Array)
    np.testing.assert_array_equal(k.compute(),
                                  hertz.contact(body1, body2, load=loads).tangential_stiffness(0.3))


def test_spring_and_force_history_agree_on_a_random_path():
    """Displacement-driven (the spring) and force-driven (tangential_history) Masing with
    memory are inverse to each other while nothing slides: 300 steps, 154 reversals."""
    c = _contact(3.0, STEEL, POLYMER)
    reach = 1.5 * MU * LOAD / c.tangential_stiffness()
    rng = np.random.default_rng(3)
    path = np.cumsum(rng.normal(0, 0.15 * reach, 300))
    path = 0.95 * reach * np.tanh(path / reach)  # stays below sliding
    spring = hertz.TangentialSpring(c, MU)
    forces = np.array([spring.step(d) for d in np.diff(path, prepend=0.0)])
    assert not np.any(np.abs(forces) >= MU * LOAD)
    back = hertz.tangential_history(c, forces, MU)
    assert np.max(np.abs(back - path)) < 5e-16 * reach  # observed 3.5e-16


def test_per_contact_moduli():
    moduli = np.array([210e9, 70e9, 3e9])
    nu1 = np.array([0.3, 0.22, 0.45])
    c = hertz.contact(hertz.Body(5e-3, 0.02, E=moduli, nu=nu1), hertz.Body.plane(**STEEL),
                      load=10.0)
    k = c.tangential_stiffness(0.4)
    for i in range(3):
        one = hertz.contact(hertz.Body(5e-3, 0.02, E=float(moduli[i]), nu=float(nu1[i])),
                            hertz.Body.plane(**STEEL), load=10.0)
        assert k[i] == one.tangential_stiffness(0.4)


def test_partial_slip_on_dask_is_lazy_the_same_bits_and_names_a_bad_element():
    da = pytest.importorskip("dask.array")
    loads = np.linspace(1.0, 100.0, 10)
    body1, body2 = hertz.Body(5e-3, 0.02, **STEEL), hertz.Body.plane(**GLASS)
    lazy = hertz.contact(body1, body2, load=da.from_array(loads, chunks=4))
    eager = hertz.contact(body1, body2, load=loads)
    force = 0.2 * loads * np.linspace(0.0, 1.0, 10)
    t, ref = lazy.tangential(force, 0.2, 0.7), eager.tangential(force, 0.2, 0.7)
    assert isinstance(t.stick_a, da.Array)
    for name in ("stick_a", "stick_b", "slip_area", "displacement", "displacement_transverse",
                 "stiffness", "no_slip_stiffness", "sliding"):
        np.testing.assert_array_equal(np.asarray(getattr(t, name)), getattr(ref, name),
                                      err_msg=name)
    assert t.sliding.dtype == bool and bool(t.sliding[-1].compute())
    bad = force.copy()
    bad[6] = 0.21 * loads[6]
    with pytest.raises(ValueError, match=r"^force must be at most mu \* load = .* N \(the "
                                         r"limit of friction.*, got .* at index 6$"):
        lazy.tangential(bad, 0.2).stick_a.compute()
    # numpy input: the same check, before any result
    with pytest.raises(ValueError, match=r"^force must be at most mu \* load .* at index 6$"):
        eager.tangential(bad, 0.2)


def test_kernel_cube_root_and_angles_against_mpmath():
    """The compiled kernel computes (1 - q)^(1/3), cos 2t and sin 2t itself (vectorised):
    within 1 ulp of mpmath for the cube root (glibc's cbrt: 3), the stiffness within 4e-16
    and the transverse displacement within 2e-17 of the one along the force, for angles
    up to the reduction's limit (|2t| = 1e5) and beyond it (libm)."""
    from hertz import _ufuncs

    rng = np.random.default_rng(11)
    q = np.concatenate([rng.uniform(0, 1, 300), 1 - 10 ** rng.uniform(-16, 0, 300),
                        10 ** rng.uniform(-300, 0, 100), [0.0, 1.0, 0.5, 1 - 2 ** -53]])
    # a = b = 1: stick_a is the cube root itself
    s = _ufuncs.partial_slip(1.5, 1.0, 1.0, 1.0, 1.0, 1.0, 0.3, 0.3, 1.0, 1.0, q, 1.0, 0.3)[0]
    ref_s = np.array([float(mp.cbrt(1 - mp.mpf(float(v)))) for v in q])
    assert np.all(np.abs(s - ref_s) <= np.spacing(ref_s))  # observed: 1 ulp, 89% exact

    K, alpha, lam, nu1, nu2, e1, e2 = 2.1, 7.0, 3.0, 0.3, 0.22, 210e9, 70e9
    t = np.concatenate([rng.uniform(-4, 4, 200), rng.uniform(-5e4, 5e4, 100),
                        [4.9999e4, -4.9999e4, 5.0001e4, 1e6, -3e9, math.pi / 4]])
    out = _ufuncs.partial_slip(K, alpha, lam, 1.0, 1.0 / lam, 1.0, nu1, nu2, e1, e2, 0.5, 1.0,
                               t)
    k = _ufuncs.tangential_stiffness(K, alpha, lam, 1.0, nu1, nu2, e1, e2, t)
    w1, w2 = (1 + mp.mpf(nu1)) / e1, (1 + mp.mpf(nu2)) / e2
    w, wn = w1 + w2, w1 * nu1 + w2 * nu2
    d = K / (1 + mp.mpf(alpha) / lam ** 2)
    worst_k = worst_across = 0.0
    for i, angle in enumerate(t):
        c2, s2 = mp.cos(2 * mp.mpf(float(angle))), mp.sin(2 * mp.mpf(float(angle)))
        along = w * K - wn * (K / 2 + (K / 2 - d) * c2)  # pi a / k
        across = wn * (K / 2 - d) * s2
        worst_k = max(worst_k, abs(float(k[i] * along / mp.pi - 1)))
        assert out[6][i] == k[i]  # one formula, one kernel
        # the transverse displacement (3 mu P / 2)(1 - s^2) across / (pi a), a = 1,
        # absolute against the along-force compliance (sin 2t may vanish)
        scale = 1.5 * (1 - mp.cbrt(mp.mpf(0.5)) ** 2) / mp.pi  # mu = P = 1, q = 0.5
        worst_across = max(worst_across, abs(float((out[4][i] - scale * across)
                                                   / (scale * along))))
    assert worst_k < 4e-16 and worst_across < 2e-17  # observed 2.2e-16, 9.8e-18
