"""hertz.ellipticity against the 50-digit table, on hard cases, and its invariants."""

import math

import mpmath as mp
import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st
from reference import ellipse_ref, load_table

import hertz
from hertz._ellipse import solve_ellipse

TABLE = load_table()
ALPHA = np.array([r["alpha"] for r in TABLE])
GROUPS = np.array([r["group"] for r in TABLE])


def rel_err(values, refs):
    return np.array([float(abs((mp.mpf(v) - r) / r)) if r else abs(float(v))
                     for v, r in zip(values, refs, strict=True)])


def test_table_covers_the_required_range():
    core = ALPHA[np.isin(GROUPS, ["main", "wide", "near1"])]
    assert core.min() == 1.0 and core.max() == 1e15
    assert (ALPHA < 1).sum() == (ALPHA > 1).sum()


@pytest.mark.parametrize("group", ["main", "wide", "near1", "huge"])
def test_lambda_to_2e_15_against_mpmath(group):
    """Issue 2: max relative error <= 2e-15 in lambda on [1, 1e15] and the reciprocal range."""
    sel = np.char.endswith(GROUPS.astype(str), group)  # the group and recip-<group>
    lam = hertz.ellipticity(ALPHA[sel])
    err = rel_err(lam, [r["lambda"] for r, s in zip(TABLE, sel, strict=True) if s])
    assert err.max() <= 2e-15, (ALPHA[sel][err.argmax()], err.max())


def test_m_and_integrals_at_the_root_against_mpmath():
    sol = solve_ellipse(ALPHA)
    for name, values in (("m", sol.m), ("K", sol.K), ("E", sol.E)):
        err = rel_err(values, [r[name] for r in TABLE])
        assert err.max() <= 2e-15, (name, ALPHA[err.argmax()], err.max())


def test_loose_setting_is_the_start_accurate_to_5e_8():
    lam = hertz.ellipticity(ALPHA, iterations=0)
    err = rel_err(lam, [r["lambda"] for r in TABLE])
    assert err.max() <= 5e-8
    assert err.max() > 1e-12  # it really is the start, not the converged value


@pytest.mark.parametrize("iterations", [2, 3])
def test_more_steps_stay_converged(iterations):
    lam = hertz.ellipticity(ALPHA, iterations=iterations)
    assert rel_err(lam, [r["lambda"] for r in TABLE]).max() <= 2e-15


def test_exact_special_values():
    assert hertz.ellipticity(1.0) == 1.0
    assert hertz.ellipticity(np.inf) == np.inf
    sol = solve_ellipse(np.array([1.0, np.inf]))
    assert sol.m.tolist() == [0.0, 1.0]
    assert sol.K[0] == sol.E[0] == math.pi / 2 and sol.K[1] == np.inf and sol.E[1] == 1.0


@pytest.mark.parametrize("alpha", [1 + 2**-52, 1 - 2**-53, 1 + 1e-12, 1 + 1e-8, 1 + 1e-3,
                                   1e6, 1e12, 1e15, 2.0**64 * (1 - 2**-53), 2.0**64, 1e19, 1e25,
                                   1e300, 1.7976931348623157e308, 1e-300, 5e-324])
def test_hard_cases_live(alpha):
    lam_ref, m_ref, *_ = ellipse_ref(alpha)
    sol = solve_ellipse(np.array(alpha))
    assert float(abs((mp.mpf(float(sol.ellipticity)) - lam_ref) / lam_ref)) <= 2e-15
    if alpha < 1e300:  # m = 1 - O(1e-300) is 1.0 in double precision
        assert float(abs((mp.mpf(float(sol.m)) - m_ref) / m_ref)) <= 2e-15


def test_lambda_minus_one_keeps_relative_precision_near_one():
    """lambda - 1 ~ 2(alpha - 1)/3 is resolved, not rounded away."""
    for k in range(4, 16):
        alpha = 1 + 10.0**-k
        lam_ref = ellipse_ref(alpha)[0]
        got = hertz.ellipticity(alpha) - 1
        assert abs(got / float(lam_ref - 1) - 1) < 2e-16 / float(lam_ref - 1) + 1e-15


def test_continuity_across_internal_boundaries():
    """No jumps where the kernel switches start pieces, B/D regions or to the asymptotic form."""
    edges = [2.0**e * (1 + k / 4) for e in range(64) for k in range(4)] + [2.0**64]
    for edge in edges[1:]:
        x = np.array([np.nextafter(edge, 0), edge, np.nextafter(edge, np.inf)])
        lam = hertz.ellipticity(x)
        assert abs(lam[2] / lam[0] - 1) < 1e-15 and abs(lam[1] / lam[0] - 1) < 1e-15


@given(st.floats(min_value=1e-300, max_value=1e300))
def test_reciprocal_symmetry(alpha):
    inv = 1.0 / alpha
    # 1/alpha is rounded: lambda changes by at most (2/3 + tiny) of its 1.1e-16 error
    assert abs(hertz.ellipticity(alpha) * hertz.ellipticity(inv) - 1) <= 8e-16


@given(st.lists(st.floats(min_value=1e-300, max_value=1e300), min_size=2, max_size=50))
def test_monotone_in_alpha(values):
    """Increasing, up to the few-ulp accuracy for neighbouring doubles."""
    alpha = np.sort(np.array(values))
    lam = hertz.ellipticity(alpha)
    assert np.all(lam[1:] >= lam[:-1] * (1 - 1e-15))
    assert np.all((lam >= 1) == (alpha >= 1))


def test_shapes_and_types():
    assert isinstance(hertz.ellipticity(3), float)
    assert isinstance(hertz.ellipticity(np.float64(3)), float)
    assert isinstance(hertz.ellipticity(np.array(3.0)), float)
    out = hertz.ellipticity(np.full((2, 3, 4), 5.0))
    assert out.shape == (2, 3, 4) and out.dtype == np.float64
    assert hertz.ellipticity([]).shape == (0,)
    non_contiguous = np.linspace(1, 100, 20)[::3]
    np.testing.assert_array_equal(hertz.ellipticity(non_contiguous),
                                  hertz.ellipticity(non_contiguous.copy()))
    assert hertz.ellipticity([[2.0], [3.0]]).shape == (2, 1)


def test_float32_and_integer_input_match_float64():
    a32 = np.array([1.5, 3.0, 10.0, 1e6], dtype=np.float32)
    out = hertz.ellipticity(a32)
    assert out.dtype == np.float64
    np.testing.assert_array_equal(out, hertz.ellipticity(a32.astype(np.float64)))
    assert hertz.ellipticity(np.int32(7)) == hertz.ellipticity(7.0)


def test_large_arrays_are_solved_in_place_without_growing_temporaries():
    alpha = np.geomspace(1, 1e6, 200_001)
    lam = hertz.ellipticity(alpha)
    np.testing.assert_array_equal(lam[::1000], hertz.ellipticity(alpha[::1000]))


@pytest.mark.parametrize("bad", [0.0, -1.0, np.nan, -np.inf, -0.0])
def test_bad_alpha_scalar(bad):
    with pytest.raises(ValueError, match=r"alpha must be a positive number.*got"):
        hertz.ellipticity(bad)


def test_bad_alpha_reports_value_and_index():
    with pytest.raises(ValueError, match=r"got -3\.0 at index 2"):
        hertz.ellipticity([1.0, 2.0, -3.0, np.nan])
    with pytest.raises(ValueError, match=r"got nan at index \(1, 0\)"):
        hertz.ellipticity([[1.0, 2.0], [np.nan, 4.0]])


@pytest.mark.parametrize("bad", ["3", 1j, True, None, [1, "a"], object()])
def test_non_numeric_alpha(bad):
    with pytest.raises(TypeError, match="alpha"):
        hertz.ellipticity(bad)


@pytest.mark.parametrize("bad, exc", [(-1, ValueError), (4, ValueError), (1.0, TypeError),
                                      (True, TypeError)])
def test_bad_iterations(bad, exc):
    with pytest.raises(exc, match="iterations"):
        hertz.ellipticity(2.0, iterations=bad)


def test_vector_start_path_gives_the_same_bits():
    """The AVX2 start-only path (where the CPU has it) against the scalar code."""
    from hertz import _ufuncs

    rng = np.random.default_rng(5)
    alpha = np.concatenate([ALPHA, np.exp(rng.uniform(-50, 50, 10_001)),
                            [1.0, 2.0**64, np.nextafter(2.0**64, 0), np.inf, 5e-324]])
    before = _ufuncs.simd()
    try:
        _ufuncs.simd(True)
        fast = hertz.ellipticity(alpha, iterations=0)
        _ufuncs.simd(False)
        assert not _ufuncs.simd()
        scalar = hertz.ellipticity(alpha, iterations=0)
    finally:
        _ufuncs.simd(before)
    np.testing.assert_array_equal(fast, scalar)
    for bad in ([2.0, 3.0, 4.0, 5.0, 6.0, -1.0], [np.nan] * 9):
        with pytest.raises(ValueError, match="alpha"):
            hertz.ellipticity(bad, iterations=0)


def test_ufunc_conventions():
    """Any real dtype in, float64 out, out=, broadcasting; bool and complex refused."""
    alpha = np.array([[1, 10], [100, 1000]], dtype=np.int32)
    expected = hertz.ellipticity(alpha.astype(float))
    for dtype in (np.int16, np.uint32, np.int64, np.float16, np.float32, np.longdouble):
        got = hertz.ellipticity(alpha.astype(dtype))
        assert got.dtype == np.float64
        np.testing.assert_array_equal(got, hertz.ellipticity(alpha.astype(dtype).astype(float)))
    out = np.empty((2, 2))
    assert hertz.ellipticity(alpha, out=out) is out
    np.testing.assert_array_equal(out, expected)
    assert isinstance(hertz.ellipticity(10), float)
    for bad in (True, np.array([True]), 1j, np.array([1 + 1j])):
        with pytest.raises(TypeError, match="alpha must be a real number"):
            hertz.ellipticity(bad)
    with pytest.raises(ValueError, match=r"alpha must be a positive number.*got -1\.0 at index "
                                         r"\(1, 0\)"):
        hertz.ellipticity(np.array([[1.0, 2.0], [-1.0, 3.0]]))
