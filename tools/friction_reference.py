"""Write tests/data/friction_reference.csv: the stress of a sliding traction, by mpmath.

    python tools/friction_reference.py            # about 20 min on two cores
    python tools/friction_reference.py --check    # recompute every entry at dps 40, tol 1e-22
    python tools/friction_reference.py --maxima   # tests/data/friction_maxima.csv, ~10 min

--maxima: for a few sliding contacts, where hertz's sliding_maxima puts the von Mises and
the tau1 maximum, and the total stress there from mpmath (Boussinesq's solution integrated by
tests/reference_stress.py plus Cerruti's by tests/reference_friction.py): the test compares
the maximum values with the von Mises and tau1 of that reference stress (at a maximum the
value is stationary, so the position needs only moderate accuracy).

Each row is one field point (x, y, z) under the ellipse of semi-axes a = 1, b (b/a = 1, 0.5,
0.2) loaded by q = sqrt(1 - x^2 - y^2/b^2) along +x (p0 = mu = 1), from
tests/reference_friction.py (Cerruti's solution integrated over the ellipse, dps 25,
tol 1e-17): the twelve numbers A, B with stress = A + (1 - 2 nu) B, components sxx, syy, szz,
syz, sxz, sxy, as float.hex. The points: inside and outside the contact, on and off the axes,
near the trailing and the leading edge, depths 0.01 a to 3 a, and the surface z = 0 outside
the contact (where the quadrature is regular; on the surface inside and at the edge it is
not, and no points are taken there). The seconds each point took are written too, so that
a test can recompute the cheapest ones.
"""

from __future__ import annotations

import csv
import multiprocessing
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from reference_friction import friction_ref12  # noqa: E402

TABLE = ROOT / "tests" / "data" / "friction_reference.csv"
MAXIMA = ROOT / "tests" / "data" / "friction_maxima.csv"
# (b/a, mu, nu)
MAXIMA_CASES = ((1.0, 0.2, 0.3), (0.5, 0.25, 0.25))
MAXIMA_HEADER = ["b", "mu", "nu", "criterion", "value", "x", "y", "z", "sxx", "syy", "szz",
                 "syz", "sxz", "sxy"]
RATIOS = (1.0, 0.5, 0.2)
# (x/a, y/b, z/a)
POINTS = (
    (0.0, 0.0, 0.5),       # on the axis
    (0.3, 0.4, 0.25),      # inside, off the axes
    (-0.95, 0.0, 0.01),    # below the trailing edge, shallow
    (0.97, 0.0, 0.02),     # below the leading edge, shallow
    (0.6, 0.78, 0.02),     # near the edge off the axes, shallow
    (-1.1, 0.0, 0.0),      # on the surface behind the contact
    (0.8, 0.75, 0.0),      # on the surface outside, off the axes
    (1.2, 0.9, 0.3),       # outside, at depth
    (-0.5, 0.3, 1.0),
    (0.4, -0.5, 3.0),      # deep
    (0.2, -0.3, 0.05),     # inside, shallow
)
HEADER = ["b", "x", "y", "z", "seconds"] + [f"{p}_{c}" for p in "AB"
                                           for c in ("sxx", "syy", "szz", "syz", "sxz", "sxy")]


def rows():
    return [(b, xa, yb * b, z) for b in RATIOS for xa, yb, z in POINTS]


def _one(args, dps=25, tol=1e-17):
    b, x, y, z = args
    t = time.perf_counter()
    v = friction_ref12(1.0, b, x, y, z, dps=dps, tol=tol)
    return args, time.perf_counter() - t, [float(e) for e in v]


def _check(args):
    return _one(args, dps=40, tol=1e-22)


def _maximum_row(args):
    from reference_stress import stress_ref6
    b, mu, nu, criterion, value, x, y, z = args
    normal = stress_ref6(1.0, b, nu, x, y, z, dps=25, tol=1e-17)
    fr = friction_ref12(1.0, b, x, y, z)
    k = 1 - 2 * nu
    total = [float(normal[i]) + mu * (float(fr[i]) + k * float(fr[i + 6])) for i in range(6)]
    return [v.hex() for v in (b, mu, nu)] + [criterion] + [v.hex() for v in (value, x, y, z)] \
        + [v.hex() for v in total]


def maxima(pool):
    sys.path.insert(0, str(ROOT))
    from hertz._friction import sliding_maxima
    jobs = []
    for b, mu, nu in MAXIMA_CASES:
        m = sliding_maxima(1.0, b, 1.0, mu, nu)
        jobs.append((b, mu, nu, "von_mises", m.von_mises, m.x_von_mises, m.y_von_mises,
                     m.z_von_mises))
        jobs.append((b, mu, nu, "tau_max", m.tau_max, m.x_tau_max, m.y_tau_max, m.z_tau_max))
    out = pool.map(_maximum_row, jobs)
    with MAXIMA.open("w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(MAXIMA_HEADER)
        w.writerows(out)


def main(argv):
    with multiprocessing.Pool(2) as pool:
        if "--maxima" in argv:
            maxima(pool)
            return
        if "--check" in argv:
            table = {tuple(float.fromhex(r[k]) for k in "bxyz"): r
                     for r in csv.DictReader(TABLE.open())}
            worst = 0.0
            for args, _, vals in pool.imap_unordered(_check, list(table)):
                row = table[args]
                stored = [float.fromhex(row[h]) for h in HEADER[5:]]
                err = max(abs(p - q) for p, q in zip(vals, stored, strict=True))
                worst = max(worst, err)
                print(args, f"{err:.2e}", flush=True)
            print(f"largest difference {worst:.2e}")
            return
        out = []
        for args, sec, vals in pool.imap(_one, rows()):
            print(args, f"{sec:.1f} s", flush=True)
            out.append([v.hex() for v in args] + [f"{sec:.1f}"] + [v.hex() for v in vals])
    with TABLE.open("w", newline="") as fh:
        w = csv.writer(fh, lineterminator="\n")
        w.writerow(HEADER)
        w.writerows(out)


if __name__ == "__main__":
    main(sys.argv[1:])
