"""Generate ``hertz/_coefficients.h``: every constant the C kernel uses.

Run from the repository root (needs mpmath only)::

    python tools/generate_coefficients.py

The header is committed; re-running this script must reproduce it byte for
byte.  All values are computed at 50 significant digits and rounded once to
the nearest double.

What is generated (notation of ``hertz/_kernel.c``):

* ``BD_SMALL_B``, ``BD_SMALL_D`` -- Maclaurin coefficients of Fukushima's
  associate integrals B(m) = (pi/4) 2F1(1/2, 1/2; 2; m) and
  D(m) = (pi/4) 2F1(1/2, 3/2; 2; m), used after two Landen steps have
  reduced the parameter below ``LANDEN_M2_MAX``.
* ``BD_LOG_*`` -- near m = 1 (p = 1 - m < ``P_LOG_MAX``) the products
  mB = E - pK and mD = K - E are written as Q(p) L + P(p) and
  Q(p) (L - 1) + P(p) with L = ln(4 / sqrt(p)) (DLMF 19.12.1-2); the four
  analytic functions Q, P are Chebyshev interpolants in p on
  [0, ``P_LOG_MAX``].
* ``START_R`` -- the start of the root solve: r(alpha) = (h - 1)/(alpha - 1)
  with h = lambda**2 / alpha, one degree-5 Chebyshev interpolant per quarter
  binade of alpha on [1, 2**64) (256 pieces, chosen from the bits of alpha
  without a logarithm).
"""

from __future__ import annotations

import pathlib

import mpmath as mp

mp.mp.dps = 50

OUT = pathlib.Path(__file__).resolve().parents[1] / "hertz" / "_coefficients.h"

# Region split of the B, D evaluation (see hertz/_kernel.c).
M_LANDEN_MAX = mp.mpf("0.95")  # m <= 0.95: two Landen steps, then Maclaurin series
P_LOG_MAX = mp.mpf("0.05")  # p < 0.05: logarithmic series in p
SMALL_DEGREE = 8
LOG_DEGREE = 7
# Start: r(alpha) on quarter binades of alpha in [1, 2**START_BINADES).
START_BINADES = 64
START_SPLIT = 4
START_DEGREE = 5


def hyp_taylor(a, b, c, n, scale):
    """Maclaurin coefficients of ``scale * 2F1(a, b; c; m)`` up to m**n."""
    coeffs, term = [], mp.mpf(scale)
    for k in range(n + 1):
        coeffs.append(term)
        term = term * (a + k) * (b + k) / ((c + k) * (k + 1))
    return coeffs


def landen_m2(m):
    """Parameter after two descending Landen steps (B, D recursion in the kernel)."""
    kp = mp.sqrt(1 - m)
    k1 = m / (1 + kp) ** 2
    kp1 = 2 * mp.sqrt(kp) / (1 + kp)
    k2 = k1**2 / (1 + kp1) ** 2
    return k2**2


def log_series(nterms=160):
    """Series in p of Q_K, P_K, Q_E, P_E with K = Q_K L + P_K, E = Q_E L + P_E."""
    qk, pk, qe, pe = [], [], [mp.mpf(0)], [mp.mpf(1)]
    ln4 = 2 * mp.log(2)
    for j in range(nterms):
        a2 = (mp.rf(mp.mpf(1) / 2, j) / mp.factorial(j)) ** 2
        d = mp.digamma(1 + j) - mp.digamma(mp.mpf(1) / 2 + j) - ln4
        qk.append(a2)
        pk.append(a2 * d)
        c = mp.rf(mp.mpf(1) / 2, j) * mp.rf(mp.mpf(3) / 2, j) / (mp.rf(2, j) * mp.factorial(j))
        qe.append(c / 2)
        pe.append(c / 2 * (d - mp.mpf(1) / ((2 * j + 1) * (2 * j + 2))))
    return qk, pk, qe[:nterms], pe[:nterms]


def cheb_interp(f, a, b, n):
    """Monomial coefficients (in x) of the degree-n interpolant of f at Chebyshev nodes."""
    nodes = [mp.cos(mp.pi * (k + mp.mpf(1) / 2) / (n + 1)) for k in range(n + 1)]
    xs = [(a + b) / 2 + (b - a) / 2 * z for z in nodes]
    vander = mp.matrix([[x**j for j in range(n + 1)] for x in xs])
    coeffs = mp.lu_solve(vander, mp.matrix([f(x) for x in xs]))
    return [coeffs[i] for i in range(n + 1)]


def series_fn(coeffs):
    return lambda x: mp.fsum(c * x**i for i, c in enumerate(coeffs))


def bd(m):
    """B(m), D(m) from mpmath's K and E with enough guard digits."""
    with mp.workdps(mp.mp.dps + 40):
        k, e = mp.ellipk(m), mp.ellipe(m)
        return (e - (1 - m) * k) / m, (k - e) / m


def root_x(t):
    """x = ln p at the root of alpha = B / (p D), alpha = exp(t) > 1."""

    def f(x):
        b, d = bd(1 - mp.exp(x))
        return mp.log(b / d) - x - t

    x0 = -4 * t / 3 if t < 2 else -t - mp.log(mp.log(4) - 1 + t / 2)
    return mp.findroot(f, (x0 * mp.mpf("1.02"), x0 * mp.mpf("0.98")), solver="secant",
                       tol=mp.mpf(10) ** -45, maxsteps=200)


def start_r(alpha):
    t = mp.log(alpha)
    x = root_x(t)
    return (mp.exp(-x - t) - 1) / (alpha - 1)


def c_array(name, rows, comment):
    lines = [f"/* {comment} */"]
    if isinstance(rows[0], list):
        lines.append(f"static const double {name}[{len(rows)}][{len(rows[0])}] = {{")
        for row in rows:
            lines.append("    {" + ", ".join(f"{float(v):.17g}" for v in row) + "},")
    else:
        lines.append(f"static const double {name}[{len(rows)}] = {{")
        lines.extend(f"    {float(v):.17g}," for v in rows)
    lines.append("};")
    return "\n".join(lines)


def main():
    small_b = hyp_taylor(mp.mpf(1) / 2, mp.mpf(1) / 2, 2, SMALL_DEGREE, mp.pi / 4)
    small_d = hyp_taylor(mp.mpf(1) / 2, mp.mpf(3) / 2, 2, SMALL_DEGREE, mp.pi / 4)
    m2_max = landen_m2(M_LANDEN_MAX)
    # Truncation error of the Maclaurin series at the largest reduced parameter.
    tail = max(
        mp.fsum(abs(c) * m2_max**i for i, c in enumerate(
            hyp_taylor(mp.mpf(1) / 2, b, 2, 60, mp.pi / 4)) if i > SMALL_DEGREE)
        for b in (mp.mpf(1) / 2, mp.mpf(3) / 2))

    qk, pk, qe, pe = log_series()
    n = len(qk)
    q_d = [qk[i] - qe[i] for i in range(n)]  # mD = K - E = Q_D (L - 1) + (P_D + Q_D)
    p_d = [pk[i] - pe[i] + q_d[i] for i in range(n)]
    q_b = [qe[i] - (qk[i - 1] if i else 0) for i in range(n)]  # mB = E - pK = Q_B L + P_B
    p_b = [pe[i] - (pk[i - 1] if i else 0) for i in range(n)]
    series = (("Q_D", q_d), ("P_D", p_d), ("Q_B", q_b), ("P_B", p_b))
    log_polys = {name: cheb_interp(series_fn(c), 0, P_LOG_MAX, LOG_DEGREE)
                 for name, c in series}
    # Q_B(0) = 0 must hold exactly: it multiplies L, which reaches 350 as p -> 0.
    log_polys["Q_B"] = [mp.mpf(0)] + cheb_interp(series_fn(q_b[1:]), 0, P_LOG_MAX, LOG_DEGREE - 1)
    grid = [P_LOG_MAX * k / 200 for k in range(201)]
    log_err = max(abs(series_fn(log_polys[name])(x) - series_fn(c)(x))
                  for name, c in series for x in grid)

    start = []
    nodes = [mp.cos(mp.pi * (k + mp.mpf(1) / 2) / (START_DEGREE + 1))
             for k in range(START_DEGREE + 1)]
    vander = mp.matrix([[z**i for i in range(START_DEGREE + 1)] for z in nodes])
    for e in range(START_BINADES):
        for k in range(START_SPLIT):
            lo = mp.mpf(2) ** e * (1 + mp.mpf(k) / START_SPLIT)
            hi = mp.mpf(2) ** e * (1 + mp.mpf(k + 1) / START_SPLIT)
            vals = [start_r((lo + hi) / 2 + (hi - lo) / 2 * z) for z in nodes]
            c = mp.lu_solve(vander, mp.matrix(vals))
            start.append([c[i] for i in range(START_DEGREE + 1)])

    header = f"""\
/* Generated by tools/generate_coefficients.py -- do not edit by hand. */
#ifndef HERTZ_COEFFICIENTS_H
#define HERTZ_COEFFICIENTS_H

#define M_LANDEN_MAX {float(M_LANDEN_MAX):.17g}
#define P_LOG_MAX {float(P_LOG_MAX):.17g}
#define SMALL_DEGREE {SMALL_DEGREE}
#define LOG_DEGREE {LOG_DEGREE}
#define START_BINADES {START_BINADES}
#define START_SPLIT {START_SPLIT}
#define START_DEGREE {START_DEGREE}
#define PI_2 {float(mp.pi / 2):.17g}
#define PI_4 {float(mp.pi / 4):.17g}
#define LN4 {float(mp.log(4)):.17g}
#define LN4_MINUS_1 {float(mp.log(4) - 1):.17g}

/* Largest parameter after two Landen steps from m = M_LANDEN_MAX: {float(m2_max):.6g};
   truncation error of the Maclaurin series there: {float(tail):.2g}. */
{c_array("BD_SMALL_B", small_b, f"B(m) = (pi/4) 2F1(1/2, 1/2; 2; m), m^0 .. m^{SMALL_DEGREE}")}
{c_array("BD_SMALL_D", small_d, f"D(m) = (pi/4) 2F1(1/2, 3/2; 2; m), m^0 .. m^{SMALL_DEGREE}")}

/* Near m = 1, p = 1 - m, L = ln(4 / sqrt(p)):
     m D = BD_LOG_QD(p) (L - 1) + BD_LOG_PD(p),   m B = BD_LOG_QB(p) L + BD_LOG_PB(p).
   Coefficients of p^0 .. p^{LOG_DEGREE}; largest error on [0, P_LOG_MAX]: {float(log_err):.2g}. */
{c_array("BD_LOG_QD", log_polys["Q_D"], "Q_D = Q_K - Q_E")}
{c_array("BD_LOG_PD", log_polys["P_D"], "P_D = P_K - P_E + Q_D")}
{c_array("BD_LOG_QB", log_polys["Q_B"], "Q_B = Q_E - p Q_K")}
{c_array("BD_LOG_PB", log_polys["P_B"], "P_B = P_E - p P_K")}

/* r(alpha) = (lambda^2/alpha - 1)/(alpha - 1) on alpha = 2^e f, f in [1 + k/4, 1 + (k + 1)/4),
   as a polynomial in z = 8 f - 9 - 2 k. */
{c_array("START_R", start, f"row 4 e + k: coefficients of z^0 .. z^{START_DEGREE}")}

#endif
"""
    OUT.write_text(header)
    print(f"wrote {OUT} (log-series error {float(log_err):.2g}, Maclaurin tail {float(tail):.2g})")


if __name__ == "__main__":
    main()
