"""High-precision references for normal impacts (mpmath), kept apart from hertz's code.

Nothing here imports hertz. The contact coefficient K (F = K delta**(3/2)) comes from
tests/reference.py's 60-digit contact at 1 N; the rest is:

* elastic: delta_max = (5 M V**2 / (4 K))**(2/5), F_max = K delta_max**(3/2),
  t_c = 2 T1 delta_max / V with T1 = int_0^1 dx / sqrt(1 - x**(5/2)) by tanh-sinh
  quadrature (and, separately, the Gamma-function closed form it is checked against);
* the history: tau(x) = int_0^x du / sqrt(1 - u**(5/2)) by quadrature, inverted by a
  root finder, at 40 digits;
* damped: x'' = -(5/4) x**(3/2) - gamma x**p x' integrated by mpmath's Taylor-series
  ODE solver (``mp.odefun``) at 30 digits, in three phases whose right-hand sides are
  analytic (the start and the end in u = x**(1/4), the turn in time), the phase changes
  and the end located by mpmath's root finder.
"""

from __future__ import annotations

import mpmath as mp
from reference import contact_ref

ELASTIC_DPS = 50
DAMPED_DPS = 30


def t1_quad():
    """int_0^1 dx / sqrt(1 - x**(5/2)) by tanh-sinh quadrature, in s = 1 - sqrt(x)
    (x = (1 - s)**2, 1 - x**(5/2) = s (5 - 10 s + 10 s^2 - 5 s^3 + s^4): analytic but for
    the s**(-1/2) at s = 0, with no cancellation); about 32 digits."""
    with mp.workdps(ELASTIC_DPS + 10):
        return +mp.quad(lambda s: 2 * (1 - s) / mp.sqrt(s * (5 - 10 * s + 10 * s**2 - 5 * s**3
                                                             + s**4)), [0, 1])


def t1_gamma():
    """Gamma(7/5) Gamma(1/2) / Gamma(9/10)."""
    with mp.workdps(ELASTIC_DPS + 10):
        return mp.gamma(mp.mpf(7) / 5) * mp.gamma(mp.mpf(1) / 2) / mp.gamma(mp.mpf(9) / 10)


def elastic_ref(body1, body2, speed, mass, angle=0.0):
    """(K, delta_max, F_max, t_c) as mpf; bodies are (Rx, Ry, E, nu) tuples (E may be inf)."""
    c1 = contact_ref(body1, body2, 1.0, angle)
    with mp.workdps(ELASTIC_DPS + 10):
        K = 1 / c1.delta ** mp.mpf(1.5)
        V, m = mp.mpf(speed), mp.mpf(mass)
        dmax = (5 * m * V**2 / (4 * K)) ** (mp.mpf(2) / 5)
        fmax = K * dmax ** mp.mpf(1.5)
        tc = 2 * t1_quad() * dmax / V
        return +K, +dmax, +fmax, +tc


def _tau_from_peak(x):
    """T1 - tau(x) = int_x^1 du / sqrt(1 - u**(5/2)), in s = 1 - sqrt(u) (no cancellation)."""
    top = 1 - mp.sqrt(x)
    if top == 0:
        return mp.mpf(0)
    return mp.quad(lambda s: 2 * (1 - s) / mp.sqrt(s * (5 - 10 * s + 10 * s**2 - 5 * s**3
                                                        + s**4)), [0, top])


def _tau(x):
    """tau(x) = int_0^x du / sqrt(1 - u**(5/2)), in w = sqrt(u) (analytic at 0)."""
    return mp.quad(lambda w: 2 * w / mp.sqrt(1 - w**5), [0, mp.sqrt(x)])


def history_ref(speed, dmax, t, guess):
    """(approach, force / F_max, speed) at time t inside the contact, by quadrature of
    the energy equation, inverted by Newton's method from ``guess`` (x = delta/delta_max
    in double precision: a starting point only)."""
    with mp.workdps(40):
        V, d, t = mp.mpf(speed), mp.mpf(dmax), mp.mpf(t)
        t1 = t1_gamma()
        tau = t * V / d
        rest = abs(t1 - tau)  # T1 - tau(x) for the compression half (x < 1)
        x = mp.mpf(guess)
        for _ in range(30):
            if x >= 1:
                x = 1 - mp.mpf(10) ** -35
            # f(x) = (T1 - tau(x)) - rest, f' = -1/sqrt(1 - x^(5/2))
            f = (_tau_from_peak(x) if x > 0.5 else t1 - _tau(x)) - rest
            step = f * mp.sqrt(1 - x ** mp.mpf(2.5))
            x += step
            if abs(step) < mp.mpf(10) ** -34 * max(x, mp.mpf(10) ** -30):
                break
        sign = 1 if tau <= t1 else -1
        return d * x, x ** mp.mpf(1.5), sign * V * mp.sqrt(1 - x ** mp.mpf(2.5))


def _power(x, a, k, w):
    """The k-th coefficient of x(h)**a from x's and w's lower ones (J. C. P. Miller)."""
    if k == 0:
        return x[0] ** a
    total = mp.mpf(0)
    for j in range(1, k + 1):
        total += ((a + 1) * j - k) * x[j] * w[k - j]
    return total / (k * x[0])


def _series_u(u0, y0, g, q, n):
    """Taylor coefficients in h (u = u0 + h) of (v, tau): v' = -5 u^9/v - 4 g u^(3+q),
    tau' = 4 u^3 / v (the start and the end, x = u^4)."""
    poly = {m: [mp.binomial(m, j) * u0 ** (m - j) for j in range(m + 1)] for m in (3, 9, 3 + q)}
    v, tau, r = [y0[0]], [y0[1]], []
    for k in range(n):
        if k == 0:
            r.append(1 / v[0])
        else:
            r.append(-sum(v[j] * r[k - j] for j in range(1, k + 1)) / v[0])
        p9 = sum(poly[9][j] * r[k - j] for j in range(min(k, 9) + 1))
        p3 = sum(poly[3][j] * r[k - j] for j in range(min(k, 3) + 1))
        pq = poly[3 + q][k] if k <= 3 + q else 0
        v.append((-5 * p9 - 4 * g * pq) / (k + 1))
        tau.append(4 * p3 / (k + 1))
    return [v, tau]


def _series_t(y0, g, q, n):
    """Taylor coefficients in time of (x, v): x' = v, v' = -(5/4) x^(3/2) - g x^(q/4) v."""
    x, v, w, z = [y0[0]], [y0[1]], [], []  # w = x^(1/2), z = x^(q/4)
    a_z = mp.mpf(q) / 4
    for k in range(n):
        w.append(_power(x, mp.mpf(1) / 2, k, w))
        z.append(_power(x, a_z, k, z) if q else (1 if k == 0 else 0))
        x15 = sum(x[j] * w[k - j] for j in range(k + 1))
        zv = sum(z[j] * v[k - j] for j in range(k + 1))
        x.append(v[k] / (k + 1))
        v.append((-mp.mpf(5) / 4 * x15 - g * zv) / (k + 1))
    return [x, v]


def _evaluate(series, h):
    return [mp.polyval(c[::-1], h) for c in series]


def _step_size(series, eps):
    """A step within which the truncated series is accurate to about eps."""
    n = len(series[0]) - 1
    h = mp.inf
    for c in series:
        scale = max(abs(c[0]), mp.mpf(1) / 10)
        for k in range(n - 5, n + 1):  # several: a series may skip powers
            if c[k] != 0:
                h = min(h, (eps * scale / abs(c[k])) ** (mp.mpf(1) / k))
    return h / 2


def _integrate(series_at, t0, y0, t_stop, event, n=32):
    """Taylor steps from t0 (toward t_stop, either side) until ``event(t, y)`` changes
    sign (the root then found on the step's polynomial) or t_stop: (t, y, hit)."""
    eps = mp.mpf(10) ** (-mp.mp.dps - 5)
    t, y = t0, y0
    sign = 1 if t_stop > t0 else -1
    g_old = event(t, y) if event else None
    while True:
        series = series_at(t, y)
        h = _step_size(series, eps)
        last = abs(t_stop - t) <= h
        h = abs(t_stop - t) if last else h
        y_new = _evaluate(series, sign * h)
        if event is not None:
            g_new = event(t + sign * h, y_new)
            if g_old != 0 and g_new * g_old < 0:
                def on_step(s, t=t, series=series):
                    return event(t + sign * s, _evaluate(series, sign * s))

                s = mp.findroot(on_step, (mp.mpf(0), h), solver="anderson")
                return t + sign * s, _evaluate(series, sign * s), True
            g_old = g_new
        t, y = t + sign * h, y_new
        if last:
            return t, y, False


def damped_ref(gamma, p, cutoff):
    """(restitution, duration in delta_max / V) of x'' = -(5/4) x^1.5 - gamma x^p x'
    (p = 0, 1/4 or 1/2), x(0) = 0, x'(0) = 1, with the attractive force cut off or not.

    Three phases with analytic right-hand sides: u = x**(1/4) from 0 until the speed is
    1/2, then time until x is back at that value (or the force is 0, with the cutoff),
    then u back to 0 (or to the zero of the force); each a 32-term Taylor series per step
    at 30 digits.
    """
    with mp.workdps(DAMPED_DPS):
        g, q = mp.mpf(gamma), int(round(4 * p))
        half = mp.mpf(1) / 2
        five4 = mp.mpf(5) / 4

        def in_u(t, y):
            return _series_u(t, y, g, q, 32)

        def in_t(t, y):
            return _series_t(y, g, q, 32)

        u_s, (v_s, tau_a), hit = _integrate(in_u, mp.mpf(0), [mp.mpf(1), mp.mpf(0)], mp.mpf(1),
                                            lambda u, y: y[0] - half)
        assert hit
        x_s = u_s**4

        def back(t, y):  # x back at x_s, on the way out (x - x_s > 0 until then)
            return y[0] - x_s if t > 0 and y[1] < 0 else mp.mpf(1)

        def back_or_zero(t, y):
            if t > 0 and y[1] < 0:
                return min(y[0] - x_s, five4 * y[0] ** mp.mpf(1.5) + g * y[0] ** (mp.mpf(q) / 4)
                           * y[1])
            return mp.mpf(1)

        t_b, (x_b, v_b), hit = _integrate(in_t, mp.mpf(0), [x_s, half], mp.mpf(10 ** 4),
                                          back_or_zero if cutoff else back)
        assert hit
        if cutoff and abs(x_b - x_s) > mp.mpf(10) ** (-20):  # the force vanished first
            return -v_b, tau_a + t_b

        def zero(u, y):
            return five4 * u ** (6 - q) + g * y[0] if u > 0 else mp.mpf(1)

        u_e, (v_e, tau_c), hit = _integrate(in_u, u_s, [v_b, mp.mpf(0)], mp.mpf(0),
                                            zero if cutoff else None)
        return -v_e, tau_a + t_b + tau_c
