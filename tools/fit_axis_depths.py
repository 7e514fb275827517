"""Fit of the depths of the axis maxima used by axis_maxima_direct in hertz/_stress_kernel.c,
and the checks of the structure that the direct path relies on.

    python tools/fit_axis_depths.py [--kernel hertz/_stress_kernel.c] [--val 3000]

Compiles the kernel into a temporary shared library (axis_targets made public), and for
every (b/a, nu) of a training grid and of random validation points in 1e-3 <= b/a <= 1,
0.25 <= nu <= 0.5:
  * finds every stationary point of the three axis targets, (sxx - szz)/2, (syy - szz)/2
    and von Mises^2, on a table of depths (z/b from 0 to about 200) refined by Newton's
    method with the exact derivatives, and checks that (syy - szz)/2 and von Mises^2 have
    exactly one interior maximum each and that any interior maximum of (sxx - szz)/2 is
    below the larger of that of (syy - szz)/2 and the surface values (printing the margin);
  * fits z/b of the two maxima by least squares: Chebyshev polynomials in x = 2 b/a - 1 and
    y = (nu - 0.375)/0.125 plus (b/a)^2j ln(b/a) times Chebyshev polynomials in y;
  * prints the largest relative error on both sets and the C tables.
"""

import argparse
import ctypes
import subprocess
import tempfile
from pathlib import Path

import numpy as np
from numpy.polynomial import chebyshev

DK, DN, DL = 8, 5, 3  # table sizes in the C code
DEGREES = {"tau": (7, 3, 2), "vm": (8, 5, 3)}  # (x degree, y degree, log terms)


def build(kernel):
    src = Path(kernel).read_text().replace("static void axis_targets", "void axis_targets")
    src = src.replace(
        '#include "_stress_kernel.h"',
        f'#include "{(Path(kernel).resolve().parent / "_stress_kernel.h")}"',
    )
    tmp = Path(tempfile.mkdtemp())
    (tmp / "k.c").write_text(src)
    subprocess.run(
        [
            "cc",
            "-O2",
            "-fPIC",
            "-shared",
            "-ffp-contract=off",
            "-DHERTZ_STRESS_SEARCH_ONLY",
            str(tmp / "k.c"),
            "-o",
            str(tmp / "k.so"),
            "-lm",
        ],
        check=True,
    )
    return ctypes.CDLL(str(tmp / "k.so"))


def make_targets(lib):
    D = ctypes.c_double

    def targets(k, nu, zs):
        z = np.ascontiguousarray(zs, float)
        out = np.zeros((len(z), 3, 4))
        for i0 in range(0, len(z), 16):
            m = min(16, len(z) - i0)
            lib.axis_targets(
                D(k),
                D(nu),
                ctypes.c_int(m),
                z[i0:].ctypes.data_as(ctypes.c_void_p),
                out[i0:].ctypes.data_as(ctypes.c_void_p),
                D(1e-2),
            )
        return out

    return targets


U = np.concatenate([np.linspace(0, 4, 801)[1:], 4 * 1.02 ** np.arange(1, 200)])


def stationary(targets, k, nu):
    f = targets(k, nu, U * k)
    res = []
    for i in range(3):
        d = f[:, i, 1]
        found = []
        for j in np.nonzero(np.sign(d[:-1]) != np.sign(d[1:]))[0]:
            z = U[j] * k
            for _ in range(50):
                g = targets(k, nu, [z])[0, i]
                step = -g[1] / g[2]
                z += step
                if abs(step) < 1e-15 * z:
                    break
            found.append(("max" if d[j] > 0 else "min", z / k, targets(k, nu, [z])[0, i, 0]))
        res.append(found)
    return res, targets(k, nu, [0.0])[0]


def dataset(targets, pts):
    rows = []
    for k, nu in pts:
        (r0, r1, r2), s = stationary(targets, k, nu)
        m0, m1, m2 = ([x for x in r if x[0] == "max"] for r in (r0, r1, r2))
        assert len(m1) == 1 and len(m2) == 1 and len(m0) <= 1, (k, nu, r0, r1, r2)
        assert len(r1) == 1 and len(r2) <= 2, (k, nu, r1, r2)
        tau = max(m1[0][2], s[0][0], s[1][0])
        margin = (tau - m0[0][2]) / tau if m0 else 1.0
        assert k == 1.0 or margin > 0, (k, nu, margin)
        rows.append((k, nu, m1[0][1], m2[0][1], margin))
    return np.array(rows)


def basis(k, nu, dk, dn, dl):
    x, y = 2 * k - 1, (nu - 0.375) / 0.125
    cols = [chebyshev.chebvander2d(x, y, [dk, dn])]
    for j in range(1, dl + 1):
        for m in range(dn + 1):
            cols.append((k ** (2 * j) * np.log(k) * chebyshev.chebval(y, [0] * m + [1]))[:, None])
    return np.hstack(cols)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--kernel", default="hertz/_stress_kernel.c")
    ap.add_argument("--val", type=int, default=3000)
    args = ap.parse_args()
    targets = make_targets(build(args.kernel))
    ks = np.r_[
        np.geomspace(1e-3, 0.05, 21)[:-1], np.linspace(0.05, 1, 61), 1 - np.geomspace(1e-6, 1e-2, 5)
    ]
    train = dataset(targets, [(k, nu) for nu in np.linspace(0.25, 0.5, 26) for k in ks])
    rng = np.random.default_rng(1)
    n = args.val
    kv = np.where(rng.random(n) < 0.5, 10 ** rng.uniform(-3, 0, n), rng.uniform(1e-3, 1, n))
    val = dataset(targets, list(zip(kv, rng.uniform(0.25, 0.5, n), strict=True)))
    for name, rows in (("train", train), ("validation", val)):
        m = rows[:, 0] < 1
        print(
            f"{name}: {len(rows)} points, smallest margin of (sxx - szz)/2 "
            f"{rows[m, 4].min():.2e} at {rows[m][np.argmin(rows[m, 4]), :2]}"
        )
    for name, col in (("tau", 2), ("vm", 3)):
        dk, dn, dl = DEGREES[name]
        c, *_ = np.linalg.lstsq(
            basis(train[:, 0], train[:, 1], dk, dn, dl), train[:, col], rcond=None
        )
        for set_name, rows in (("train", train), ("validation", val)):
            err = np.abs(basis(rows[:, 0], rows[:, 1], dk, dn, dl) @ c / rows[:, col] - 1)
            print(f"{name}: largest relative error of z/b, {set_name}: {err.max():.2e}")
        nc = (dk + 1) * (dn + 1)
        c2 = np.zeros((DK + 1, DN + 1))
        c2[: dk + 1, : dn + 1] = c[:nc].reshape(dk + 1, dn + 1)
        d2 = np.zeros((DL, DN + 1))
        d2[:dl, : dn + 1] = c[nc:].reshape(dl, dn + 1)
        print(f"static const double fit_{name}_c[{DK + 1}][{DN + 1}] = {{")
        for row in c2:
            print("    {" + ", ".join(f"{v:.17g}" for v in row) + "},")
        print("};")
        print(f"static const double fit_{name}_d[{DL}][{DN + 1}] = {{")
        for row in d2:
            print("    {" + ", ".join(f"{v:.17g}" for v in row) + "},")
        print("};")


if __name__ == "__main__":
    main()
