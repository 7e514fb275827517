"""Generate ``hertz/_ellipse_table.h``: lambda, K and E of the contact ellipse as
piecewise polynomials in alpha, for the contact kernel (hertz/_ellipse_table.c).

Run from the repository root (needs mpmath only; about a minute on two cores)::

    python tools/generate_ellipse_table.py

The header is committed; re-running this script reproduces it byte for byte.

alpha in [1, 2**TABLE_BINADES) is cut into pieces read from its bits: the
binade e (alpha = 2**e f, f in [1, 2)) and the next TABLE_SPLIT_BITS bits of
f, k.  On piece (e, k) the local variable

    z = 2**(S + 1) f - (2**(S + 1) + 2 k + 1),   S = TABLE_SPLIT_BITS,

runs over [-1, 1) and is exact in double arithmetic.  Each of lambda, K, E is
its degree-TABLE_DEGREE interpolant at Chebyshev nodes in z, stored as
(c0_hi, c0_lo, c1, ..., c_d) and evaluated as

    c0_hi + (c0_lo + z (c1 + z (c2 + ... + z c_d))),

so that the leading coefficient carries 106 bits and the rounding of the
small tail stays below a tenth of an ulp.  The values at the nodes are the
root of alpha = B(m) / ((1 - m) D(m)) (Fukushima's associate integrals from
mpmath's K and E, hertz/_kernel.c eq. (1)) at 50 significant digits.  The
script ends by evaluating every piece in double arithmetic, as the C code
does, at both ends and INNER_CHECKS inner points, against fresh mpmath roots, and
writes the largest error into the header.
"""

from __future__ import annotations

import multiprocessing
import pathlib
import random

import mpmath as mp

mp.mp.dps = 50

OUT = pathlib.Path(__file__).resolve().parents[1] / "hertz" / "_ellipse_table.h"

TABLE_BINADES = 64
TABLE_SPLIT_BITS = 4
TABLE_DEGREE = 8
TABLE_STRIDE = TABLE_DEGREE + 2  # c0_hi, c0_lo, c1 .. c_d
NAMES = ("lambda", "K", "E")
INNER_CHECKS = 14  # random points checked per piece, besides both ends


def bd(m, p):
    """B(m), D(m) from mpmath's K and E with guard digits; p = 1 - m given exactly."""
    with mp.workdps(mp.mp.dps + 40):
        k, e = mp.ellipk(m), mp.ellipe(m)
        return (e - p * k) / m, (k - e) / m


def lam_k_e(alpha):
    """(lambda, K, E) at the root for alpha > 1 (mpf), solved in x = ln p."""
    t = mp.log(alpha)

    def f(x):
        with mp.workdps(mp.mp.dps + 40):
            p = mp.exp(x)
            b, d = bd(1 - p, p)
            return mp.log(b / d) - x - t

    x0 = -4 * t / 3 if t < 2 else -t - mp.log(mp.log(4) - 1 + t / 2)
    x = mp.findroot(f, (x0 * mp.mpf("1.02"), x0 * mp.mpf("0.98")), solver="secant",
                    tol=mp.mpf(10) ** -45, maxsteps=200)
    with mp.workdps(mp.mp.dps + 40):
        p = mp.exp(x)
        b, d = bd(1 - p, p)
        return mp.exp(-x / 2), b + d, b + p * d


def piece_bounds(e, k):
    width = mp.mpf(2) ** -TABLE_SPLIT_BITS
    return mp.ldexp(1 + k * width, e), mp.ldexp(1 + (k + 1) * width, e)


def fit_piece(index):
    """Coefficients (c0_hi, c0_lo, c1 .. c_d) of lambda, K, E on one piece."""
    e, k = divmod(index, 2**TABLE_SPLIT_BITS)
    lo, hi = piece_bounds(e, k)
    n = TABLE_DEGREE + 1
    nodes = [mp.cos(mp.pi * (j + mp.mpf(1) / 2) / n) for j in range(n)]
    values = [lam_k_e((lo + hi) / 2 + (hi - lo) / 2 * z) for z in nodes]
    vander = mp.matrix([[z**i for i in range(n)] for z in nodes])
    rows = []
    for fn in range(3):
        c = mp.lu_solve(vander, mp.matrix([v[fn] for v in values]))
        c0_hi = float(c[0])
        rows.append([c0_hi, float(c[0] - c0_hi)] + [float(c[i]) for i in range(1, n)])
    return rows


def evaluate(row, z):
    """The C evaluation, in double arithmetic (no fused multiply-add)."""
    r = row[-1]
    for c in reversed(row[2:-1]):
        r = r * z + c
    return row[0] + (row[1] + z * r)


def local_z(alpha):
    """Piece index and z of a double alpha in [1, 2**TABLE_BINADES), as the C code does."""
    import math

    f, e = math.frexp(alpha)  # alpha = f 2**e, f in [0.5, 1)
    f, e = 2 * f, e - 1
    s = 2**TABLE_SPLIT_BITS
    k = int((f - 1) * s)
    return e * s + k, 2 * s * f - (2 * s + 2 * k + 1)


def check_piece(args):
    """Largest relative error (in units of 2**-53) of the stored piece at its checkpoints."""
    index, rows, seed = args
    e, k = divmod(index, 2**TABLE_SPLIT_BITS)
    lo, hi = piece_bounds(e, k)
    rng = random.Random(seed)
    points = [float(lo), float(hi) * (1 - 2**-53)]
    points += [float(lo + (hi - lo) * rng.random()) for _ in range(INNER_CHECKS)]
    worst = [0.0, 0.0, 0.0]
    for alpha in points:
        if alpha == 1.0:
            continue
        j, z = local_z(alpha)
        assert j == index, (alpha, j, index)
        truth = lam_k_e(mp.mpf(alpha))
        for fn in range(3):
            err = abs((evaluate(rows[fn], z) - truth[fn]) / truth[fn]) * 2**53
            worst[fn] = max(worst[fn], float(err))
    return worst


def main():
    count = TABLE_BINADES * 2**TABLE_SPLIT_BITS
    with multiprocessing.Pool() as pool:
        table = pool.map(fit_piece, range(count), chunksize=8)
        worst = pool.map(check_piece, [(i, table[i], i) for i in range(count)], chunksize=8)
    err = [max(w[fn] for w in worst) for fn in range(3)]
    lines = [
        "/* Generated by tools/generate_ellipse_table.py -- do not edit by hand. */",
        "#ifndef HERTZ_ELLIPSE_TABLE_H",
        "#define HERTZ_ELLIPSE_TABLE_H",
        "",
        f"#define TABLE_BINADES {TABLE_BINADES}",
        f"#define TABLE_SPLIT_BITS {TABLE_SPLIT_BITS}",
        f"#define TABLE_DEGREE {TABLE_DEGREE}",
        f"#define TABLE_STRIDE {TABLE_STRIDE}",
        "",
        "/* lambda, K, E on piece e 2^TABLE_SPLIT_BITS + k of alpha in [1, 2^TABLE_BINADES):",
        "   c0_hi + (c0_lo + z (c1 + ... + z c_d)), see the script.  Largest relative error",
        f"   of the double evaluation at both ends and {INNER_CHECKS} inner points of every"
        " piece, in",
        "   units of 2^-53: "
        + ", ".join(f"{n} {e:.2f}" for n, e in zip(NAMES, err, strict=True)) + ". */",
        f"static const double ELLIPSE_TABLE[{count}][3][{TABLE_STRIDE}] = {{",
    ]
    for rows in table:
        lines.append("    {" + ", ".join(
            "{" + ", ".join(f"{v:.17g}" for v in row) + "}" for row in rows) + "},")
    lines += ["};", "", "#endif", ""]
    OUT.write_text("\n".join(lines))
    print(f"wrote {OUT}; largest errors (2^-53): {dict(zip(NAMES, err, strict=True))}")


if __name__ == "__main__":
    main()
