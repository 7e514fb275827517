"""Batch cost of the tangential contact against one scipy ellipk + ellipe pass over N.

    python benchmarks/tangential.py [--n 1000000] [--repeats 7]

N contacts (an ellipsoid on a plane, Ry/Rx log-uniform in [1, 1e4], dissimilar materials,
random loads); times, as CPU time in interleaved rounds (medians of the per-round ratios):

* the reference: scipy.special.ellipk(m) + ellipe(m) over the same N;
* Contact.tangential_stiffness(direction) and Contact.tangential(force, mu, direction)
  (the monotonic Cattaneo-Mindlin state, all fields) on contacts whose geometry fields
  (K, alpha) have been read once ("warm"), and on fresh contacts, whose first read of K
  runs the library's second compiled pass over the geometry ("cold": that pass is the
  contact's own cost, shared with anything else that reads m, K, E);
* Contact.fretting(amplitude, mu) (warm).

Issue 17's target: the stiffness and the monotonic partial slip within 2x one
ellipk + ellipe pass.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402
from scipy import special  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import describe  # noqa: E402

import hertz  # noqa: E402


def scene(n, seed=1):
    rng = np.random.default_rng(seed)
    ratio = 10.0 ** rng.uniform(0, 4, n)
    body1 = hertz.Body(5e-3, 5e-3 * ratio, E=210e9, nu=0.3)
    body2 = hertz.Body.plane(E=70e9, nu=0.22)
    load = rng.uniform(1.0, 100.0, n)
    direction = rng.uniform(0, np.pi, n)
    mu = 0.3
    force = rng.uniform(0, 1, n) * mu * load
    return body1, body2, load, direction, mu, force


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1_000_000)
    parser.add_argument("--repeats", type=int, default=7)
    args = parser.parse_args(argv)
    n = args.n
    body1, body2, load, direction, mu, force = scene(n)
    warm = hertz.contact(body1, body2, load=load)
    m = np.ascontiguousarray(warm.m)  # reads the geometry once: K, alpha are now stored

    def reference():
        special.ellipk(m)
        special.ellipe(m)

    def fresh():
        return hertz.contact(body1, body2, load=load)

    cases = {
        "ellipk + ellipe (scipy)": (reference, None),
        "tangential_stiffness, warm": (lambda: warm.tangential_stiffness(direction), None),
        "tangential (partial slip), warm": (lambda: warm.tangential(force, mu, direction),
                                            None),
        "fretting (loop energy), warm": (lambda: warm.fretting(force, mu, direction), None),
        "tangential_stiffness, cold": (lambda c: c.tangential_stiffness(direction), fresh),
        "tangential (partial slip), cold": (lambda c: c.tangential(force, mu, direction),
                                            fresh),
    }
    times = {k: [] for k in cases}
    for _ in range(args.repeats):
        for label, (run, setup) in cases.items():
            arg = setup() if setup else None
            t0 = time.process_time()
            run(arg) if setup else run()
            times[label].append(time.process_time() - t0)
    ref = np.array(times["ellipk + ellipe (scipy)"])
    print(describe())
    print(f"N = {n}, {args.repeats} interleaved rounds, CPU time\n")
    print("| case | ns per contact (median) | time / (ellipk + ellipe), median of rounds |")
    print("|---|---|---|")
    for label, v in times.items():
        print(f"| {label} | {np.median(v) / n * 1e9:.0f} | {np.median(np.array(v) / ref):.2f} |")


if __name__ == "__main__":
    main()
