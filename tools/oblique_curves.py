"""Oblique impact curves and the integration's error (hertz.oblique_impact).

    python tools/oblique_curves.py                 # table: Chung & Ooi's alumina, 5-85 deg
    python tools/oblique_curves.py --convergence   # psi2 against the number of steps
    python tools/oblique_curves.py --plot FILE.png # the table's curves as a figure

The table and the figure are those of docs/explanation/oblique-impact.md.  The
convergence study integrates Maw's normalised equations (chi of a solid alumina ball,
nu = 0.23) at n = 50 ... 3200 steps and compares psi2 and Richardson's (4 psi2(n) -
psi2(n/2)) / 3 with Richardson's value at the finest n.
"""

from __future__ import annotations

import argparse
import math
import sys
import time

import numpy as np

import hertz
from hertz._oblique import _gross_end, _nodes, _normalised

R, E, NU, RHO, SPEED, MU = 2.5e-3, 380e9, 0.23, 4000.0, 3.9, 0.092


def alumina():
    ball = hertz.Body.sphere(R, E=E, nu=NU)
    block = hertz.Body.plane(E=E, nu=NU)
    return ball, block, RHO * 4.0 / 3.0 * math.pi * R ** 3


def table(degrees):
    ball, block, m = alumina()
    hit = hertz.oblique_impact(ball, block, SPEED, np.radians(degrees), m, MU)
    rows = ["| theta [deg] | psi1 | psi2 | e_t | rebound [deg] | centre [deg] | spin [rad/s] "
            "| J_t/J_n | gross |",
            "|---|---|---|---|---|---|---|---|---|"]
    for i, d in enumerate(degrees):
        rows.append(
            f"| {d:g} | {hit.normalised_incidence[i]:.4f} | {hit.normalised_rebound[i]:.5f} "
            f"| {hit.tangential_restitution[i]:.5f} "
            f"| {math.degrees(hit.rebound_angle[i]):.3f} "
            f"| {math.degrees(hit.centre_rebound_angle[i]):.3f} | {hit.spin[i]:.2f} "
            f"| {hit.impulse_ratio[i]:.5f} | {'yes' if hit.gross_slip[i] else 'no'} |")
    print(f"chi = {hit.chi:.6f}, c = {hit.compliance_ratio:.6f}, gross slip above "
          f"{math.degrees(hit.gross_slip_angle[0]):.4f} deg, Coulomb's rigid-body v_t = 0 "
          f"at {math.degrees(math.atan(2 * MU * 3.5)):.4f} deg")
    print("\n".join(rows))
    return hit


def convergence():
    ball, block, m = alumina()
    hit = hertz.impact(ball, block, speed=SPEED, mass=m)
    chi = (1 - NU) / (2 - NU) * 3.5
    finest = 3200
    ns = [50, 100, 200, 400, 800, 1600, finest]
    for psi1 in (0.5, 1.5, 3.0, 4.5):
        raw = {}
        start = time.perf_counter()
        for n in ns:
            raw[n] = _normalised(psi1, chi, _nodes(hit, n, _gross_end(psi1, chi)))[0]
        ref = (4 * raw[finest] - raw[finest // 2]) / 3
        print(f"psi1 = {psi1}: reference psi2 = {ref:.12f} ({time.perf_counter() - start:.1f} s)")
        print("      n   psi2 - ref   Richardson - ref   estimate |psi2(n) - psi2(n/2)|/3")
        for a, b in zip(ns[:-2], ns[1:-1], strict=True):
            rich = (4 * raw[b] - raw[a]) / 3
            print(f"  {b:5d}  {raw[b] - ref: .3e}   {rich - ref: .3e}        "
                  f"{abs(raw[b] - raw[a]) / 3:.3e}")


def plot(path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    degrees = np.arange(1.0, 90.0, 1.0)
    ball, block, m = alumina()
    hit = hertz.oblique_impact(ball, block, SPEED, np.radians(degrees), m, MU, steps=200)
    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6))
    axes[0].plot(degrees, hit.tangential_restitution)
    axes[0].axvline(math.degrees(hit.gross_slip_angle[0]), ls=":", c="k")
    axes[0].set(xlabel="incidence [deg]", ylabel="tangential restitution")
    axes[1].plot(degrees, hit.spin)
    axes[1].set(xlabel="incidence [deg]", ylabel="spin after [rad/s]")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--convergence", action="store_true")
    parser.add_argument("--plot", metavar="FILE")
    args = parser.parse_args(argv)
    if args.convergence:
        convergence()
    elif args.plot:
        plot(args.plot)
    else:
        table([5, 10, 15, 20, 25, 28, 28.5, 30, 32.5, 35, 45, 60, 75, 85])
    return 0


if __name__ == "__main__":
    sys.exit(main())
