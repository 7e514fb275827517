"""The random-angle batch of benchmarks/solver.py in a loop, for a profiler.

    perf record -o /tmp/contact.perf python benchmarks/profile_contact.py [--general]
    perf report -i /tmp/contact.perf --sort symbol

--general times the two general convex bodies of benchmarks/solver.py instead
of the ball on race.

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
    parser.add_argument("--general", action="store_true",
                        help="two general convex bodies (steel on aluminium), not a ball on race")
    args = parser.parse_args()
    rng = np.random.default_rng(0)
    loads = rng.uniform(1.0, 2000.0, args.n)
    angles = rng.uniform(-np.pi, np.pi, args.n)
    balls = hertz.Body.sphere(rng.uniform(2e-3, 2e-2, args.n), 210e9, 0.3)
    races = hertz.Body(-rng.uniform(2.05e-2, 3e-2, args.n), rng.uniform(2e-2, 1e-1, args.n),
                       70e9, 0.33)
    if args.general:
        radii = np.exp(rng.uniform(np.log(1e-3), np.log(1e-1), (4, args.n)))
        balls = hertz.Body(radii[0], radii[1], 210e9, 0.3)
        races = hertz.Body(radii[2], radii[3], 70e9, 0.33)
    for _ in range(args.calls):
        hertz.contact(balls, races, load=loads, angle=angles)


if __name__ == "__main__":
    main()
