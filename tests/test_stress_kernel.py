"""The C stress kernel (hertz/_stress_kernel.c) through ctypes, against the mpmath
quadrature of Boussinesq's and Flamant's solutions (tests/reference_stress.py), published
values and physical invariants. The kernel is compiled here into a temporary shared
library with the C compiler Python was built with; hertz itself is not imported."""

import ctypes
import math
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import mpmath as mp
import numpy as np
import pytest
from reference_stress import axis_maxima_ref, axis_stress_ref, line_stress_ref4, stress_ref6

SOURCE = Path(__file__).resolve().parent.parent / "hertz" / "_stress_kernel.c"
D = ctypes.c_double
P = ctypes.POINTER(D)


def build(tmp_path_factory, *defines):
    cc = (sysconfig.get_config_var("CC") or "cc").split()
    if shutil.which(cc[0]) is None:
        pytest.skip(f"no C compiler ({cc[0]}) to build {SOURCE.name}")
    suffix = ".dll" if sys.platform == "win32" else ".so"
    so = tmp_path_factory.mktemp("stress_kernel") / ("stress_kernel" + suffix)
    subprocess.run([*cc, "-std=c99", "-O2", "-fPIC", "-shared", "-fno-math-errno",
                    "-fno-trapping-math", "-ffp-contract=off", *(f"-D{d}" for d in defines),
                    str(SOURCE), "-o", str(so), "-lm"], check=True)
    lib = ctypes.CDLL(str(so))
    lib.hertz_point_stress.argtypes = [D] * 6 + [P]
    lib.hertz_subsurface.argtypes = [D] * 3 + [P]
    lib.hertz_line_stress.argtypes = [D] * 4 + [P]
    lib.hertz_line_subsurface.argtypes = [D] * 2 + [P]
    for f in (lib.hertz_point_stress, lib.hertz_subsurface, lib.hertz_line_stress,
              lib.hertz_line_subsurface):
        f.restype = ctypes.c_int
    return lib


@pytest.fixture(scope="module")
def lib(tmp_path_factory):
    return build(tmp_path_factory)


@pytest.fixture(scope="module")
def search_lib(tmp_path_factory):
    """The kernel with the general search of the axis maxima everywhere (no fitted depths)."""
    return build(tmp_path_factory, "HERTZ_STRESS_SEARCH_ONLY")


def call(fn, n, *args):
    out = (D * n)()
    rc = fn(*args, out)
    return np.array(out[:]), rc


def point(lib, a, b, nu, x, y, z):
    out, rc = call(lib.hertz_point_stress, 6, a, b, nu, x, y, z)
    assert rc == 0
    return out


def ref6(*args, **kw):
    return np.array([float(v) for v in stress_ref6(*args, **kw)])


# ------------------------------------------------------------------ against the quadrature
# (a, b, nu, x, y, z): deep and shallow, inside and outside, on the surface and at its
# edge, a near circle and a long ellipse; chosen for the speed of the quadrature. The same
# comparison over 173 points (b/a = 1, 1/1.0001, 0.5, 0.1, 1e-3, 1e-6; on and near the
# edge; z from 0 to 1e3 a) gave at most 1.5e-15, except at points 1e-16 from the edge on
# the surface, where the quadrature is not to be trusted.
QUADRATURE_POINTS = [
    (2.0, 1.0, 0.25, 0.6, 0.4, 0.8),             # b/a = 0.5, deep, off the axes
    (1.0, 1 / 1.0001, 0.3, 0.3, 0.4, 0.2),       # a/b = 1.0001
    (1.0, 0.5, 0.0, 0.3, 0.2, 0.0),              # on the surface, inside
    (1.0, 0.1, 0.3, 1.2, 0.005, 0.0),            # on the surface, outside
    (1.0, 0.5, -0.5, 0.3, 0.2, 1e-3),            # just below the surface
    (1.0, 0.5, 0.3, 1.3, -0.6, 0.2),             # outside the contact, below the surface
    (1.0, 0.25, 0.3, 0.5, 0.1, 0.05),            # a/b = 4
]

@pytest.mark.parametrize("pt", QUADRATURE_POINTS)
def test_point_stress_against_boussinesq_quadrature(lib, pt):
    ours = point(lib, *pt)
    ref = ref6(*pt, dps=20, tol=1e-15)
    np.testing.assert_allclose(ours, ref, rtol=0, atol=1e-13)


def test_axis_closed_form_against_quadrature():
    # the reference's own axis formulas (used for the maxima below) agree with Boussinesq
    for a, b, nu, z in ((1.0, 0.4, 0.3, 0.3),):
        sxx, syy, szz = axis_stress_ref(a, b, nu, z)
        q = ref6(a, b, nu, 0.0, 0.0, z, dps=20, tol=1e-15)
        np.testing.assert_allclose([float(sxx), float(syy), float(szz)], q[:3], atol=1e-14)


LINE_POINTS = [(0.0, 0.0), (0.5, 0.0), (1.0, 0.0), (1.3, 0.0), (0.0, 0.786), (0.3, 0.4),
               (-0.7, 0.2), (0.99, 1e-6), (1.2, 1e-3), (0.866, 0.5), (5.0, 3.0), (0.0, 100.0),
               (1e3, 1e3)]


@pytest.mark.parametrize("nu", [0.3, -0.5])
def test_line_stress_against_flamant_quadrature(lib, nu):
    for x, z in LINE_POINTS:
        ours, rc = call(lib.hertz_line_stress, 4, 2.0, nu, 2 * x, 2 * z)
        assert rc == 0
        ref = [float(v) for v in line_stress_ref4(nu, x, z)]
        np.testing.assert_allclose(ours, ref, rtol=0, atol=2e-15, err_msg=f"{x}, {z}")


# ------------------------------------------------------------------ published values
def test_published_values_circle_and_line(lib):
    nu = 0.3
    out, rc = call(lib.hertz_subsurface, 12, 1.0, 1.0, nu)
    assert rc == 0
    assert out[0] == pytest.approx(0.310, abs=5e-4) and out[1] == pytest.approx(0.481, abs=5e-4)
    assert out[2] == pytest.approx(0.620, abs=5e-4) and out[3] == pytest.approx(0.481, abs=5e-4)
    assert out[4] == pytest.approx(0.2139, abs=5e-5)
    assert out[5] == pytest.approx(0.848, abs=5e-4) and out[6] == pytest.approx(0.351, abs=5e-4)
    assert out[7] == pytest.approx((1 - 2 * nu) / 3, rel=1e-15)
    # the radial stress at the edge of a circle, from the field
    s = point(lib, 1.0, 1.0, nu, 1.0, 0.0, 0.0)
    assert s[0] == pytest.approx((1 - 2 * nu) / 3, rel=1e-15)
    line, rc = call(lib.hertz_line_subsurface, 7, 1.0, nu)
    assert rc == 0
    assert line[0] == pytest.approx(0.300, abs=5e-4) and line[1] == pytest.approx(0.786, abs=5e-4)
    assert line[4:] == pytest.approx([0.25, math.sqrt(3) / 2, 0.5], rel=1e-15)


def test_circle_axis_closed_forms(lib):
    # Johnson eq. 3.45: sr = -(1+nu)(1 - z atan(1/z)) + 1/(2(1+z^2)), szz = -1/(1+z^2)
    for nu in (0.0, 0.3, 0.5):
        for z in (0.0, 0.1, 0.48, 2.0, 50.0):
            s = point(lib, 1.0, 1.0, nu, 0.0, 0.0, z)
            sr = -(1 + nu) * (1 - z * math.atan2(1.0, z)) + 0.5 / (1 + z * z)
            assert s[0] == pytest.approx(sr, abs=1e-15)
            assert s[1] == s[0]
            assert s[2] == pytest.approx(-1 / (1 + z * z), rel=1e-15)


# ------------------------------------------------------------------ maxima
@pytest.mark.parametrize("b,nu", [(1.0, 0.3), (0.5, -0.5), (0.2, 0.3), (1e-3, 0.0),
                                  (0.05, 0.45), (1e-3, 0.25), (0.97, 0.5)])
def test_axis_maxima_against_mpmath(lib, b, nu):
    out, rc = call(lib.hertz_subsurface, 12, 2.0, 2.0 * b, nu)
    assert rc == 0
    ref = axis_maxima_ref(2.0, 2.0 * b, nu, dps=20, npts=60)
    pairs = zip((out[0:2], out[2:4]), (ref["tau"], ref["von_mises"]), strict=True)
    for (val, z), (rv, rz) in pairs:
        assert val == pytest.approx(float(rv), rel=1e-12)
        assert z == pytest.approx(float(rz), rel=1e-8, abs=1e-300)


def test_direct_axis_maxima_agree_with_the_search(lib, search_lib):
    # 0.25 <= nu <= 0.5, 1e-3 <= b/a <= 1: the maxima start from fitted depths (one exact
    # evaluation and a Halley step); elsewhere, and in search_lib everywhere, the general
    # search runs. Both converge to the same maxima: values to rounding, depths far
    # within 1e-8 (measured: 2e-15 and 4e-11, the search being the less accurate).
    rng = np.random.default_rng(8)
    n = 300
    ks = np.r_[10 ** rng.uniform(-3, 0, n), rng.uniform(1e-3, 1, n), 1e-3, 1.0, 1 - 1e-12,
               1 - 1e-6, 0.5, 0.999, 1e-3 * (1 - 1e-15), 0.3]
    nus = np.r_[rng.uniform(0.25, 0.5, 2 * n), 0.25, 0.5, 0.3, 0.25, 0.5, 0.3, 0.3,
                0.25 - 1e-15]
    nus[:40] = 0.25
    nus[40:80] = 0.5
    for k, nu in zip(ks, nus, strict=True):
        fast, rc = call(lib.hertz_subsurface, 12, 2.0, 2.0 * k, nu)
        ref, rc2 = call(search_lib.hertz_subsurface, 12, 2.0, 2.0 * k, nu)
        assert rc == rc2 == 0
        np.testing.assert_allclose(fast[[0, 2]], ref[[0, 2]], rtol=1e-14, err_msg=f"{k}, {nu}")
        np.testing.assert_allclose(fast[[1, 3]], ref[[1, 3]], rtol=1e-9, err_msg=f"{k}, {nu}")
        np.testing.assert_array_equal(fast[4:10], ref[4:10])


@pytest.mark.parametrize("b", [1.0, 0.5, 0.1, 1e-3])
def test_orthogonal_shear_is_the_largest_syz_in_x_0(lib, b):
    out, _ = call(lib.hertz_subsurface, 12, 1.0, b, 0.3)
    tau, y0, z0 = out[4:7]
    s = point(lib, 1.0, b, 0.3, 0.0, y0, z0)
    assert abs(s[3]) == pytest.approx(tau, rel=1e-14)
    for dy, dz in ((1, 0), (-1, 0), (0, 1), (0, -1), (1, 1), (-1, 1)):
        q = point(lib, 1.0, b, 0.3, 0.0, y0 + 1e-4 * b * dy, z0 + 1e-4 * b * dz)
        assert abs(q[3]) < tau
    # a coarse scan finds nothing larger
    ys, zs = np.meshgrid(np.linspace(0.0, 2.0, 41) * b, np.linspace(0.01, 1.5, 31) * b)
    scan = max(abs(point(lib, 1.0, b, 0.3, 0.0, y, z)[3])
               for y, z in zip(ys.ravel(), zs.ravel(), strict=True))
    assert scan <= tau


def principal_max_surface(lib, a, b, nu, x, y):
    s = point(lib, a, b, nu, x, y, 0.0)
    return 0.5 * (s[0] + s[1]) + math.hypot(0.5 * (s[0] - s[1]), s[5])


@pytest.mark.parametrize("b,nu", [(1.0, 0.3), (0.9, -0.9), (0.5, 0.0), (0.1, 0.3),
                                  (1e-3, 0.45)])
def test_surface_tension_is_at_the_end_of_the_major_axis(lib, b, nu):
    out, _ = call(lib.hertz_subsurface, 12, 1.0, b, nu)
    tens, x, y = out[7:10]
    assert (x, y) == (1.0, 0.0)
    assert principal_max_surface(lib, 1.0, b, nu, 1.0, 0.0) == pytest.approx(tens, rel=1e-14)
    # largest principal stress on the surface, inside and outside the contact
    worst = -1.0
    for r in (0.0, 0.3, 0.6, 0.9, 0.99, 1.0, 1.001, 1.05, 1.3, 2.0):
        for t in np.linspace(0.0, math.pi / 2, 25):
            worst = max(worst, principal_max_surface(lib, 1.0, b, nu, r * math.cos(t),
                                                     r * b * math.sin(t)))
    assert worst <= tens * (1 + 1e-12) + 1e-15


# ------------------------------------------------------------------ invariants
@pytest.mark.parametrize("b", [1.0, 0.5, 0.1])
def test_equilibrium(lib, b):
    # div sigma = 0 by fourth-order central differences, step 1e-3 of the depth
    nu = 0.3
    comp = {(0, 0): 0, (1, 1): 1, (2, 2): 2, (1, 2): 3, (0, 2): 4, (0, 1): 5}
    for p0 in ((0.3, 0.2 * b, 0.4 * b), (0.9, 0.3 * b, 0.05 * b), (1.2, 0.9 * b, 0.3 * b),
               (0.0, 0.5 * b, 0.01 * b)):
        h = 1e-3 * p0[2]
        w = np.array([1.0, -8.0, 0.0, 8.0, -1.0]) / (12 * h)
        terms = np.zeros((3, 3))           # d sigma_ij / d x_j
        for j in range(3):
            for m, wm in zip(range(-2, 3), w, strict=True):
                p = list(p0)
                p[j] += m * h
                s = point(lib, 1.0, b, nu, *p)
                terms[:, j] += [wm * s[comp[(min(i, j), max(i, j))]] for i in range(3)]
        div = terms.sum(axis=1)
        assert np.abs(div).max() < 1e-9 * np.abs(terms).max(), (p0, div, terms)


def test_surface_traction(lib):
    for b, nu in ((1.0, 0.3), (0.3, 0.0), (1e-4, 0.5)):
        for x, y in ((0.0, 0.0), (0.5, 0.3 * b), (0.95, 0.2 * b), (0.0, 0.999 * b)):
            s = point(lib, 1.0, b, nu, x, y, 0.0)
            p = math.sqrt(1 - x * x - (y / b) ** 2)
            assert s[2] == pytest.approx(-p, rel=1e-14) and s[3] == 0.0 and s[4] == 0.0
        for x, y in ((1.0, 0.0), (0.0, b), (1.1, 0.0), (0.6, 0.9 * b), (3.0, 2.0)):
            s = point(lib, 1.0, b, nu, x, y, 0.0)
            assert s[2] == 0.0 and s[3] == 0.0 and s[4] == 0.0


def test_symmetry(lib):
    sign_x = np.array([1, 1, 1, 1, -1, -1])
    sign_y = np.array([1, 1, 1, -1, 1, -1])
    for b in (1.0, 0.6, 1e-3):
        for x, y, z in ((0.3, 0.2, 0.4), (1.3, 0.5, 0.0), (0.5, 0.9, 0.01)):
            y *= b
            z *= b
            s = point(lib, 1.0, b, 0.3, x, y, z)
            np.testing.assert_array_equal(point(lib, 1.0, b, 0.3, -x, y, z), sign_x * s)
            np.testing.assert_array_equal(point(lib, 1.0, b, 0.3, x, -y, z), sign_y * s)


def test_far_field_is_a_point_force(lib):
    # Boussinesq for the total force P = (2/3) pi a b p0, at R = 1e4 a: relative 1e-7
    a, b, nu = 1.0, 0.4, 0.3
    force = 2 * math.pi * a * b / 3
    for x, y, z in ((6e3, 3e3, 7e3), (0.0, 0.0, 1e4), (1e4, 0.0, 0.0)):
        s = point(lib, a, b, nu, x, y, z)
        q = force * np.array([float(v) for v in _boussinesq(nu, x, y, z)])
        np.testing.assert_allclose(s, q, rtol=1e-7, atol=1e-7 * np.abs(q).max())


def _boussinesq(nu, x, y, z):
    """Unit normal force at the origin (the kernel of reference_stress), exact."""
    with mp.workdps(30):
        x, y, z, nu = mp.mpf(x), mp.mpf(y), mp.mpf(z), mp.mpf(nu)
        r2 = x * x + y * y
        R = mp.sqrt(r2 + z * z)
        k = 1 - 2 * nu
        if r2 == 0:
            c2 = s2 = cs = mp.mpf(0)
            sx2 = sy2 = mp.mpf(1) / 2
        else:
            c2, s2, cs = (x * x - y * y) / r2, 2 * x * y / r2, x * y / r2
            sx2, sy2 = y * y / r2, x * x / r2
        t = 1 / (R * (R + z))
        return [(k * (c2 * t + z * sx2 / R ** 3) - 3 * z * x * x / R ** 5) / (2 * mp.pi),
                (k * (-c2 * t + z * sy2 / R ** 3) - 3 * z * y * y / R ** 5) / (2 * mp.pi),
                -3 * z ** 3 / R ** 5 / (2 * mp.pi),
                -3 * y * z * z / R ** 5 / (2 * mp.pi),
                -3 * x * z * z / R ** 5 / (2 * mp.pi),
                (k * (s2 * t - z * cs / R ** 3) - 3 * x * y * z / R ** 5) / (2 * mp.pi)]


def test_scaling_and_circle_limit(lib):
    s1 = point(lib, 1.0, 0.5, 0.3, 0.3, 0.2, 0.4)
    s2 = point(lib, 3e-3, 1.5e-3, 0.3, 0.9e-3, 0.6e-3, 1.2e-3)
    np.testing.assert_allclose(s1, s2, rtol=0, atol=1e-15)
    # a/b -> 1: no 0/0, the field moves smoothly
    for x, y, z in ((0.3, 0.4, 0.2), (0.7, 0.7, 0.0), (1.5, 0.2, 0.0), (0.0, 0.0, 0.5)):
        c = point(lib, 1.0, 1.0, 0.3, x, y, z)
        for eps in (1e-15, 1e-12, 1e-9):
            n = point(lib, 1.0, 1.0 - eps, 0.3, x, y, z)
            assert np.abs(n - c).max() < 4 * eps + 1e-15


def test_long_ellipse_tends_to_the_line_contact(lib):
    # at x = 0, (y, z) in units of b: syy -> sxx(line), szz -> szz, syz -> sxz, sxx -> syy
    nu = 0.3
    for y, z in ((0.0, 0.786), (0.5, 0.3), (0.9, 0.05), (1.2, 0.0), (0.3, 2.0)):
        s = point(lib, 1e6, 1.0, nu, 0.0, y, z)
        line, _ = call(lib.hertz_line_stress, 4, 1.0, nu, y, z)
        np.testing.assert_allclose(s[[1, 2, 3, 0]], line, rtol=0, atol=2e-5)
    out, _ = call(lib.hertz_subsurface, 12, 1e6, 1.0, nu)
    lo, _ = call(lib.hertz_line_subsurface, 7, 1.0, nu)
    np.testing.assert_allclose(out[[0, 1, 2, 3, 4, 5, 6]], lo, rtol=2e-5)


def test_invalid_input(lib):
    bad = [(1.0, 2.0, 0.3, 0, 0, 1, 1), (1.0, 0.0, 0.3, 0, 0, 1, 1), (1.0, 0.5, 0.6, 0, 0, 1, 2),
           (1.0, 0.5, -1.0, 0, 0, 1, 2), (1.0, 0.5, 0.3, math.nan, 0, 1, 3),
           (1.0, 0.5, 0.3, 0, 0, -1e-300, 4), (math.inf, 0.5, 0.3, 0, 0, 1, 1),
           (1.0, 1e-80, 0.3, 0, 0, 1, 1)]
    for *args, code in bad:
        out, rc = call(lib.hertz_point_stress, 6, *args)
        assert rc == code and np.isnan(out).all(), args
    out, rc = call(lib.hertz_subsurface, 12, 1.0, 1.5, 0.3)
    assert rc == 1 and np.isnan(out).all()
    out, rc = call(lib.hertz_line_stress, 4, 1.0, 0.3, 0.0, -1.0)
    assert rc == 4 and np.isnan(out).all()
    out, rc = call(lib.hertz_line_subsurface, 7, 1.0, 0.51)
    assert rc == 2 and np.isnan(out).all()


def _flamant(x, z):
    """(sxx, szz, sxz) of a unit line force per unit length at the origin, exact
    (Johnson sec. 2.2: sigma_r = -(2/pi) cos(theta) / r)."""
    with mp.workdps(30):
        x, z = mp.mpf(x), mp.mpf(z)
        r4 = (x * x + z * z) ** 2
        return [-2 / mp.pi * x * x * z / r4, -2 / mp.pi * z ** 3 / r4,
                -2 / mp.pi * x * z * z / r4]


FAR_POINTS = [(1e60, 3e59, 2e59), (-1e150, 1e149, 5e149), (0.0, 0.0, 1e200),
              (1e304, -2e303, 1e303), (1.7e308, 1e308, 1.5e308), (1e306, 0.0, 1e-5),
              (0.0, -1.7e308, 0.0), (1e308, 1e308, 1e308)]


@pytest.mark.parametrize("x, y, z", FAR_POINTS)
def test_far_field_to_the_end_of_the_double_range(lib, x, y, z):
    """Issue 18, item 4: NaN at coordinates from 1e306 m (x/a overflowed). Beyond 1e60 a the
    field is Boussinesq's for the total force (relative difference (a/R)^2): to the last bit
    where the stress / p0 is a normal double, to its granularity where it underflows."""
    a, b, nu = 1e-4, 4e-5, 0.3
    s = point(lib, a, b, nu, x, y, z)
    q = 2 * math.pi * a * b / 3 * np.array([float(v) for v in _boussinesq(nu, x, y, z)])
    assert np.isfinite(s).all()
    np.testing.assert_allclose(s, q, rtol=0, atol=2e-15 * np.abs(q).max() + 2e-323)


@pytest.mark.parametrize("x, z", [(1e61, 3e60), (1e308, 1e-5), (-1.7e308, 1.7e308),
                                  (1e200, 1e250), (0.0, 1.7e308), (1e306, 1e306)])
def test_line_far_field_to_the_end_of_the_double_range(lib, x, z):
    """LineContact.stress(1e308, 1e-5) was NaN (x/b overflowed): Flamant's line force
    pi b p0 / 2 beyond 1e60 b, exact up to the granularity of the underflowing values."""
    b, nu = 1e-4, 0.25
    s, rc = call(lib.hertz_line_stress, 4, b, nu, x, z)
    q = math.pi * b / 2 * np.array([float(v) for v in _flamant(x, z)])
    assert rc == 0 and np.isfinite(s).all()
    np.testing.assert_allclose(s[:3], q, rtol=0, atol=2e-15 * np.abs(q).max() + 2e-323)
    assert s[3] == nu * (s[0] + s[1])
