"""How far Mindlin's slip-annulus traction is from Coulomb's law: the misalignment of slip and
traction, by a quadrature of Cerruti's solution (tests/reference_tangential.py, mpmath).

    python benchmarks/tangential_slip.py [--dps 20] [--ring 16]

Mindlin's partial-slip solution (and hertz.Contact.tangential) takes the traction in the
slip annulus along the force.  The slip it produces there is not exactly parallel to that
traction (a Poisson effect: none at nu = 0).  For a steel pair (nu = 0.3) at
Q/(mu P) = 0.5 this prints, per ellipse and force direction, the largest and the mean angle
between slip and force line over points of the mid-annulus ring (r = (1 + c)/2 of the
contact ellipse's radius, c the stick ratio) at --ring angles, and the same at nu = 0.5.
Slow: about a minute per line on a shared 2-core machine.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import reference_tangential as ref  # noqa: E402


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dps", type=int, default=20)
    parser.add_argument("--ring", type=int, default=16)
    args = parser.parse_args(argv)
    ref.DPS = args.dps
    q = 0.5
    c = (1 - q) ** (1 / 3)
    r = (1 + c) / 2
    print("| b/a | nu | force direction | largest misalignment [deg] | mean [deg] |")
    print("|---|---|---|---|---|")
    for nu in (0.3, 0.5):
        bodies = [(1.0, nu), (1.0, nu)]
        for ratio in (1.0, 0.2):
            for direction in (0.0, math.pi / 4, math.pi / 2):
                if ratio == 1.0 and direction:
                    continue  # a circle has no preferred axis
                points = [(r * math.cos(2 * math.pi * (k + 0.5) / args.ring),
                           ratio * r * math.sin(2 * math.pi * (k + 0.5) / args.ring))
                          for k in range(args.ring)]
                angles = [float(x) for x in
                          ref.slip_misalignment(1.0, ratio, bodies, q, direction, points)]
                print(f"| {ratio:g} | {nu:g} | {math.degrees(direction):.0f} deg | "
                      f"{max(angles):.2f} | {sum(angles) / len(angles):.2f} |", flush=True)


if __name__ == "__main__":
    main()
