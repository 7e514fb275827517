"""The random-angle batch of benchmarks/solver.py in a loop, for a profiler.

    perf record -o /tmp/contact.perf python benchmarks/profile_contact.py
    perf report -i /tmp/contact.perf --sort symbol

The README's shares of the batch time (solver, geometry stage, load stage, page
faults) are read from that report.
"""

from __future__ import annotations

import argparse

import numpy as np

import hertz


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1_000_000)
    parser.add_argument("--calls", type=int, default=60)
    args = parser.parse_args()
    rng = np.random.default_rng(0)
    loads = rng.uniform(1.0, 2000.0, args.n)
    angles = rng.uniform(-np.pi, np.pi, args.n)
    balls = hertz.Body.sphere(rng.uniform(2e-3, 2e-2, args.n), 210e9, 0.3)
    races = hertz.Body(-rng.uniform(2.05e-2, 3e-2, args.n), rng.uniform(2e-2, 1e-1, args.n),
                       70e9, 0.33)
    for _ in range(args.calls):
        hertz.contact(balls, races, load=loads, angle=angles)


if __name__ == "__main__":
    main()
