"""The kernel's own B(m), D(m), V(m) against mpmath, on both sides of its region split."""

import mpmath as mp
import numpy as np
import reference  # noqa: F401  (sets 50-digit precision)

from hertz import _ufuncs


def bdv_ref(m, p):
    """B, D, V with m = 1 - p exact; give the small one of them (the other None)."""
    tiny = p if m is None else m
    with mp.workdps(80 + int(-mp.log10(tiny))):
        m = 1 - mp.mpf(p) if m is None else mp.mpf(m)
        k, e = mp.ellipk(m), mp.ellipe(m)
        b, d = (e - (1 - m) * k) / m, (k - e) / m
        return b, d, (b - (1 - m) * d) / m


def evaluate(m, p):
    return _ufuncs.associate_integrals(np.asarray(m, float), np.asarray(p, float))


def test_against_mpmath_to_a_few_ulp():
    rng = np.random.default_rng(7)
    small = np.concatenate([10.0 ** rng.uniform(-16, np.log10(0.5), 300),
                            rng.uniform(0.5, 0.95, 300), [0.95, np.nextafter(0.95, 1)]])
    tiny_p = np.concatenate([10.0 ** rng.uniform(-300, np.log10(0.05), 300), [0.05, 0.0499]])
    # m primary where it is small, p primary where it is small; the other is 1 - x
    m = np.concatenate([small, 1 - tiny_p])
    p = np.concatenate([1 - small, tiny_p])
    exact = [(x, None) for x in small] + [(None, x) for x in tiny_p]
    got = evaluate(m, p)
    worst = [0.0, 0.0, 0.0]
    for i, (mm, pp) in enumerate(exact):
        for j, ref in enumerate(bdv_ref(mm, pp)):
            worst[j] = max(worst[j], float(abs((mp.mpf(got[j][i]) - ref) / ref)))
    assert max(worst) <= 4 * 2.0**-52, worst


def test_complete_integrals_are_recovered():
    """K = B + D and E = B + pD against scipy-independent closed values."""
    B, D, _ = evaluate([0.5], [0.5])
    K, E = B + D, B + 0.5 * D
    assert abs(K[0] / float(mp.ellipk(0.5)) - 1) < 4e-16
    assert abs(E[0] / float(mp.ellipe(0.5)) - 1) < 4e-16
