"""Cost of the vectorised DEM tangential laws per contact-step, against one scipy
ellipk + ellipe pass per contact.

    python benchmarks/dem_laws.py [--n 1000000] [--repeats 7] [--steps 4] [--write]

N contacts (a sphere of radius 10 mm on a plane, steel, loads uniform in [1, 100] N,
mu = 0.3) advanced together; times are CPU time in interleaved rounds: each round runs
the reference, then ``steps`` consecutive steps of a law (timed together, divided by the
steps), for each law in turn, and the table gives the medians of the times and of the
ratios of each law's time to the reference pass just before it:

* the reference: scipy.special.ellipk(m) + ellipe(m) over N values of m in [0, 1);
* ``TangentialSpring``, a DEM fretting path: each contact's tangential displacement a
  sinusoid of period 200 steps, random phase, amplitude 1.5 delta_s (delta_s =
  3 mu P / (2 k)), so that every contact slides for part of each half cycle and reverses
  every 100 steps, after 150 steps of warm-up;
* ``TangentialSpring``, a random walk: increments normal with deviation 0.3 delta_s, a
  reversal at every other step on average (the worst case of the masks numpy branches
  on);
* ``LoadPathSpring``, the same fretting path with the normal force varying too (a
  sinusoid of period 170 steps between 40 and 100 per cent of the contact's load).

Issue 26's target: a contact-step within 2x one ellipk + ellipe pass per contact.
``--write`` puts the table in docs/explanation/load-paths.md (the dem-laws section).
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
from _common import describe, replace_readme_section  # noqa: E402

import hertz  # noqa: E402

MU = 0.3
PERIOD = 200
WARM_UP = 150


class Fretting:
    """A tangential spring driven along sinusoids of random phase (increments on the fly)."""

    def __init__(self, n, rng, walk=False):
        self.ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
        self.plane = hertz.Body.plane(E=210e9, nu=0.3)
        self.load = rng.uniform(1.0, 100.0, n)
        contact = hertz.contact(self.ball, self.plane, load=self.load)
        self.spring = hertz.TangentialSpring(contact, MU)
        reach = 1.5 * MU * self.load / contact.tangential_stiffness()
        self.reach, self.walk, self.rng, self.k = reach, walk, rng, 0
        self.phase = rng.uniform(0.0, 2.0 * np.pi, n)

    def increment(self):
        if self.walk:
            return self.rng.normal(0.0, 0.3, self.reach.size) * self.reach
        w, k = 2.0 * np.pi / PERIOD, self.k
        self.k += 1
        return 1.5 * self.reach * (np.sin(w * (k + 1) + self.phase) - np.sin(w * k + self.phase))

    def step(self, inc):
        return self.spring.step(inc)


class VaryingLoad(Fretting):
    """LoadPathSpring on the same fretting path, the normal force a sinusoid as well."""

    def __init__(self, n, rng):
        super().__init__(n, rng)
        self.spring = hertz.LoadPathSpring(self.ball, self.plane, MU, size=n)

    def normal(self):
        return self.load * (0.7 + 0.3 * np.sin(2.0 * np.pi * self.k / 170.0 + self.phase))

    def step(self, inc):
        return self.spring.step(self._p, inc)

    def increment(self):
        self._p = self.normal()
        return super().increment()


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=1_000_000)
    parser.add_argument("--repeats", type=int, default=7)
    parser.add_argument("--steps", type=int, default=4)
    parser.add_argument("--only", choices=["tangential", "load-path"], default=None)
    parser.add_argument("--write", action="store_true",
                        help="write the table into the docs (the dem-laws section)")
    args = parser.parse_args(argv)
    n = args.n
    rng = np.random.default_rng(1)
    m = rng.uniform(0.0, 1.0, n)
    laws = {}
    if args.only in (None, "tangential"):
        laws["TangentialSpring, fretting"] = Fretting(n, rng)
        laws["TangentialSpring, random walk"] = Fretting(n, rng, walk=True)
    if args.only in (None, "load-path"):
        laws["LoadPathSpring, fretting, P varying"] = VaryingLoad(n, rng)
    for law in laws.values():
        for _ in range(WARM_UP):
            law.step(law.increment())
    ref_label = "ellipk + ellipe (scipy)"
    times = {ref_label: [], **{k: [] for k in laws}}
    ratios = {ref_label: [], **{k: [] for k in laws}}
    for _ in range(args.repeats):
        for label, law in laws.items():  # each law right after a reference pass
            t0 = time.process_time()
            special.ellipk(m)
            special.ellipe(m)
            ref = time.process_time() - t0
            times[ref_label].append(ref)
            ratios[ref_label].append(1.0)
            spent = 0.0
            for _ in range(args.steps):
                inc = law.increment()
                t0 = time.process_time()
                law.step(inc)
                spent += time.process_time() - t0
            times[label].append(spent / args.steps)
            ratios[label].append(spent / args.steps / ref)
    lines = [f"{describe()}; N = {n}, {args.repeats} interleaved rounds of {args.steps} "
             "steps, CPU time:", "",
             "| case | ns per contact-step (median) | time / (ellipk + ellipe), median of "
             "rounds |", "|---|---|---|"]
    for label, v in times.items():
        lines.append(f"| {label} | {np.median(v) / n * 1e9:.0f} | "
                     f"{np.median(ratios[label]):.2f} |")
    text = "\n".join(lines)
    print(text)
    if args.write:
        print(f"wrote {replace_readme_section('dem-laws', text)}")


if __name__ == "__main__":
    main()
