"""Write tests/data/reference_lambda.csv: lambda(alpha), m, K, E at 50 digits.

    python tests/make_reference_table.py        # about two minutes

Groups of alpha (each value is a double, stored exactly as float.hex):

* ``main``  -- 1000 points log-uniform on [1, 1e6] (both ends included);
* ``wide``  -- 600 points log-uniform on (1e6, 1e15];
* ``near1`` -- 1 + j 2**-52 (j = 1..8), 1 + c 10**-k (c = 1, 2, 5; k = 1..15);
* ``huge``  -- 40 points log-uniform on (1e15, 1e300], and the largest double;
* ``recip-<group>`` -- the double nearest to 1/alpha for every alpha above
  (lambda for it is 1/lambda(1/alpha) with 1/alpha exact, not rounded).

Used by the accuracy tests and by benchmarks/speed_vs_error.py.
"""

from __future__ import annotations

import csv
import sys

import mpmath as mp
import numpy as np
from reference import DIGITS, TABLE, ellipse_ref


def alphas() -> list[tuple[str, float]]:
    out = [("main", float(a)) for a in np.logspace(0, 6, 1000)]
    out += [("wide", float(a)) for a in np.logspace(6, 15, 601)[1:]]
    near = {1 + j * 2.0**-52 for j in range(1, 9)}
    near |= {1 + c * 10.0**-k for k in range(1, 16) for c in (1, 2, 5)}
    out += [("near1", a) for a in sorted(near)]
    out += [("huge", float(a)) for a in np.logspace(15, 300, 41)[1:]]
    out.append(("huge", sys.float_info.max))
    out += [(f"recip-{g}", 1.0 / a) for g, a in list(out) if a != 1.0]
    return out


def main():
    TABLE.parent.mkdir(exist_ok=True)
    rows = alphas()
    with TABLE.open("w", newline="") as f:
        f.write(f"# lambda(alpha) = l_y/l_x, m = 1 - (minor/major)^2, K(m), E(m); "
                f"mpmath, {DIGITS} digits; written by tests/make_reference_table.py\n")
        w = csv.writer(f)
        w.writerow(["group", "alpha_hex", "alpha", "lambda", "m", "K", "E"])
        for i, (group, a) in enumerate(rows):
            lam, m, k, e = ellipse_ref(a)
            w.writerow([group, a.hex(), repr(a)]
                       + [mp.nstr(x, 32, min_fixed=1, max_fixed=0) for x in (lam, m, k, e)])
            if i % 200 == 0:
                print(f"{i}/{len(rows)}", flush=True)
    print(f"wrote {len(rows)} rows to {TABLE}")


if __name__ == "__main__":
    main()
