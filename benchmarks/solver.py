"""Accuracy and speed of hertz.ellipticity and hertz.contact: the README's solver tables.

    python benchmarks/solver.py [--n 1000000] [--repeats 11] [--readme]

Accuracy: maximum relative error against the 50-digit mpmath table
tests/data/reference_lambda.csv (regenerate with tests/make_reference_table.py), of
the solver (hertz.ellipticity) and of hertz.contact's ellipse.
Speed: N alphas log-uniform in [1, 1e6] (and N contacts); every contender
is timed once per round, rounds interleaved, and the ratio to one
scipy.special.ellipk + ellipe pass over N parameters is taken within each
round (the machine's speed drifts between rounds); medians over the rounds
are reported.  Times are the process's CPU time (time.process_time, one
BLAS thread), so that other work on the machine does not count.  Scalar
calls are timed the same way against one scalar ellipk(m) + ellipe(m)
pair.  Two contact workloads: a ball on a race (a sphere in a groove, the
bearing case) and two general bodies (both convex with distinct principal
radii, 1-100 mm log-uniform, steel on aluminium), each at random angles and
at angle 0.  The tables are printed (with the processor's name); --readme
also writes them into the solver section of README.md.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # no spinning BLAS threads in CPU time

import numpy as np
from scipy import special

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

from _common import describe, replace_readme_section  # noqa: E402

import hertz  # noqa: E402
from hertz._ellipse import solve_ellipse  # noqa: E402


def accuracy() -> dict[str, float]:
    import mpmath as mp
    from reference import load_table

    rows = load_table()
    alpha = np.array([r["alpha"] for r in rows])
    out = {}
    for iterations in (1, 0):
        sol = solve_ellipse(alpha, iterations)
        err = {}
        for name, values in (("lambda", sol.ellipticity), ("m", sol.m), ("K", sol.K),
                             ("E", sol.E)):
            err[name] = np.array([float(abs((mp.mpf(v) - r[name]) / r[name])) if r[name] else 0.0
                                  for v, r in zip(values, rows, strict=True)])
        in_range = np.array([r["group"].removeprefix("recip-") in ("main", "wide", "near1")
                             for r in rows])
        tag = "" if iterations == 1 else " (iterations=0)"
        out[f"lambda, 1/1e15 <= alpha <= 1e15{tag}"] = err["lambda"][in_range].max()
        out[f"lambda, all {len(rows)} table points up to 1.8e308{tag}"] = err["lambda"].max()
        if iterations == 1:
            for name in ("m", "K", "E"):
                out[f"{name} at the root, all table points"] = err[name].max()
    # hertz.contact's own lambda, K, E (the piecewise-polynomial table below 2^64, the
    # solver above): a body (1, alpha) on a plane has rho_x / rho_y = alpha exactly.
    rows = [r for r in rows if 1.0 <= r["alpha"] <= 2.0**200]
    alpha = np.array([r["alpha"] for r in rows])
    steel = (210e9, 0.3)
    c = hertz.contact(hertz.Body(1.0, alpha, *steel), hertz.Body.plane(*steel), load=1.0)
    for name, values in (("lambda", c.ellipticity), ("K", c.K), ("E", c.E)):
        out[f"hertz.contact's {name}, the {len(rows)} table points in [1, 2^200]"] = max(
            float(abs((mp.mpf(v) - r[name]) / r[name])) for v, r in zip(values, rows, strict=True))
    return out


def vector_units() -> str:
    """The vector instructions the contact kernel can pick on this processor (its AVX-512
    and AVX2 clones differ: gathers on one, loads and shuffles on the other)."""
    try:
        with open("/proc/cpuinfo") as f:
            flags = next((line.split(":", 1)[1].split() for line in f
                          if line.startswith("flags")), [])
    except OSError:
        return "vector units unknown"
    if "avx512f" in flags:
        return "AVX-512"
    if "avx2" in flags:
        return "AVX2" + ("+FMA" if "fma" in flags else "") + ", no AVX-512"
    return "no AVX2"


def _rounds(contenders: dict, repeats: int, calls: int = 1) -> dict[str, np.ndarray]:
    """CPU seconds per call of each contender, one entry per round, rounds interleaved."""
    times = {k: [] for k in contenders}
    for f in contenders.values():  # warm-up
        f()
    for _ in range(repeats):
        for name, f in contenders.items():
            t0 = time.process_time()
            for _ in range(calls):
                f()
            times[name].append((time.process_time() - t0) / calls)
    return {k: np.array(v) for k, v in times.items()}


def speed(n: int, repeats: int) -> dict[str, tuple[float, float]]:
    rng = np.random.default_rng(0)
    alpha = np.exp(rng.uniform(0.0, np.log(1e6), n))
    m = rng.uniform(0.0, 1.0, n)
    ball, race = hertz.Body.sphere(6e-3, 210e9, 0.3), hertz.Body(-6.2e-3, 40e-3, 210e9, 0.3)
    loads = rng.uniform(1.0, 2000.0, n)
    angles = rng.uniform(-np.pi, np.pi, n)
    balls = hertz.Body.sphere(rng.uniform(2e-3, 2e-2, n), 210e9, 0.3)
    races = hertz.Body(-rng.uniform(2.05e-2, 3e-2, n), rng.uniform(2e-2, 1e-1, n), 70e9, 0.33)
    # two general bodies: both convex, four distinct radii log-uniform in [1, 100] mm
    radii = np.exp(rng.uniform(np.log(1e-3), np.log(1e-1), (4, n)))
    steel = hertz.Body(radii[0], radii[1], 210e9, 0.3)
    aluminium = hertz.Body(radii[2], radii[3], 70e9, 0.33)
    contenders = {
        "scipy ellipk + ellipe (reference)": lambda: (special.ellipk(m), special.ellipe(m)),
        "hertz.ellipticity": lambda: hertz.ellipticity(alpha),
        "hertz.ellipticity, iterations=0": lambda: hertz.ellipticity(alpha, iterations=0),
        "lambda, m, K, E (solve_ellipse)": lambda: solve_ellipse(alpha),
        "hertz.contact, ball on race, N geometries at random angles, two materials, N loads":
            lambda: hertz.contact(balls, races, load=loads, angle=angles),
        "hertz.contact, ball on race, the same at angle 0":
            lambda: hertz.contact(balls, races, load=loads),
        "hertz.contact, two general convex bodies at random angles, steel on aluminium, "
        "N loads": lambda: hertz.contact(steel, aluminium, load=loads, angle=angles),
        "hertz.contact, two general convex bodies, the same at angle 0":
            lambda: hertz.contact(steel, aluminium, load=loads),
        "hertz.contact, one geometry, N loads": lambda: hertz.contact(ball, race, load=loads),
    }
    times = _rounds(contenders, repeats)
    ref = times["scipy ellipk + ellipe (reference)"]
    return {k: (np.median(v) / n * 1e9, np.median(v / ref)) for k, v in times.items()}


def scalar_speed(repeats: int, calls: int = 5000) -> dict[str, tuple[float, float]]:
    ball, race = hertz.Body.sphere(6e-3, 210e9, 0.3), hertz.Body(-6.2e-3, 40e-3, 210e9, 0.3)
    contenders = {
        "scipy ellipk(m) + ellipe(m), one scalar pair (reference)":
            lambda: (special.ellipk(0.5), special.ellipe(0.5)),
        "hertz.ellipticity(10.0)": lambda: hertz.ellipticity(10.0),
        "hertz.contact, existing bodies": lambda: hertz.contact(ball, race, load=1500.0),
        "hertz.contact with two new Body objects": lambda: hertz.contact(
            hertz.Body(6e-3, 6e-3, 210e9, 0.3), hertz.Body(-6.2e-3, 40e-3, 210e9, 0.3),
            load=1500.0),
        "hertz.Body(...)": lambda: hertz.Body(6e-3, 6e-3, 210e9, 0.3),
    }
    times = _rounds(contenders, repeats, calls)
    ref = times["scipy ellipk(m) + ellipe(m), one scalar pair (reference)"]
    return {k: (np.median(v) * 1e9, np.median(v / ref)) for k, v in times.items()}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--repeats", type=int, default=11)
    ap.add_argument("--readme", action="store_true",
                    help="also write the tables into README.md's solver section")
    ap.add_argument("--speed-only", action="store_true",
                    help="only the array timings (no accuracy table, no scalar calls)")
    args = ap.parse_args()
    if args.speed_only and args.readme:
        ap.error("--readme needs the full tables (drop --speed-only)")
    lines = [f"{describe()} with {vector_units()}, {time.strftime('%Y-%m-%d')}; "
             "`python benchmarks/solver.py`", ""]
    if not args.speed_only:
        lines += ["| maximum relative error against mpmath (50 digits) | value |", "|---|---|"]
        lines += [f"| {name} | {value:.2e} |" for name, value in accuracy().items()]
        lines += [""]
    lines += [f"| N = {args.n:.0e}, alpha log-uniform in [1, 1e6] | ns per element (median) "
              f"| time / (ellipk + ellipe), median of {args.repeats} rounds |", "|---|---|---|"]
    lines += [f"| {name} | {ns:.1f} | {ratio:.2f} |"
              for name, (ns, ratio) in speed(args.n, args.repeats).items()]
    if args.speed_only:
        print("\n".join(lines))
        return
    lines += ["", "| one call with Python floats | ns per call (median) | time / (scalar "
              f"ellipk + ellipe pair), median of {args.repeats} rounds |", "|---|---|---|"]
    lines += [f"| {name} | {ns:.0f} | {ratio:.2f} |"
              for name, (ns, ratio) in scalar_speed(args.repeats).items()]
    text = "\n".join(lines)
    print(text)
    if args.readme:
        replace_readme_section("solver-table", text)


if __name__ == "__main__":
    main()
