"""Cost of the sliding-traction stress (hertz/_friction.py) against the normal field, and
against another checkout's hertz/_friction.py side by side.

    python benchmarks/friction.py [--n 20000] [--repeats 7] [--baseline /work/main]
                                  [--direction 0.5 --maxima-repeats 1]

Times sliding_stress and the C kernel's point_stress (Contact.stress without the checks)
at the same N random points below an ellipse b/a = 0.5 (depths log-uniform 1e-3 a to 3 a),
CPU time, interleaved rounds; prints the medians per point and their ratio, and the
machine. Also times a call at one point (the cost per call of the search for the maxima)
and sliding_maxima for one contact (partial slip, traction along the major axis unless
--direction says otherwise).

With --baseline DIR, DIR/hertz/_friction.py (e.g. the integration branch's) is loaded
beside this checkout's (with this checkout's C kernels) and timed in the same rounds;
the largest difference of the two fields over the N points is printed too.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import describe  # noqa: E402

import hertz._friction as friction  # noqa: E402
from hertz._stress import point_stress  # noqa: E402


def _baseline(path):
    """DIR/hertz/_friction.py as a module of the hertz package (hertz._friction_baseline)."""
    name = "hertz._friction_baseline"
    spec = importlib.util.spec_from_file_location(name, Path(path) / "hertz" / "_friction.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def _cpu(f, scale=1.0):
    t = time.process_time()
    f()
    return (time.process_time() - t) / scale


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=20000)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--maxima-repeats", type=int, default=3)
    ap.add_argument("--baseline", metavar="DIR", help="a checkout to compare with")
    ap.add_argument("--direction", type=float, default=0.0,
                    help="direction of the traction for sliding_maxima [rad]; off the axes "
                         "the search covers the half-space (about 20 times longer)")
    args = ap.parse_args(argv)
    rng = np.random.default_rng(0)
    x = rng.uniform(-1.5, 1.5, args.n)
    y = rng.uniform(-0.75, 0.75, args.n)
    z = np.exp(rng.uniform(np.log(1e-3), np.log(3.0), args.n))
    modules = {"this": friction}
    if args.baseline:
        modules["baseline"] = _baseline(args.baseline)
    runs = {}
    for k, m in modules.items():
        runs[f"sliding_stress ({k})"] = (lambda m=m: m.sliding_stress(
            1.0, 0.5, 1.0, 0.3, 0.3, x, y, z), args.n)
    runs["point_stress (normal)"] = (lambda: point_stress(1.0, 0.5, 1.0, 0.3, x, y, z), args.n)
    for k, m in modules.items():
        runs[f"one point ({k})"] = (lambda m=m: [m.sliding_stress(
            1.0, 0.5, 1.0, 0.3, 0.3, x[i], y[i], z[i]) for i in range(100)], 100)
    times = {k: [] for k in runs}
    for _ in range(args.repeats):
        for k, (f, n) in runs.items():
            times[k].append(_cpu(f, n))
    maxima = {k: [] for k in modules}
    for _ in range(args.maxima_repeats):
        for k, m in modules.items():
            maxima[k].append(_cpu(lambda m=m: m.sliding_maxima(
                1.0, 0.5, 1.0, 0.4, 0.3, args.direction, 0.8)))
    print(describe())
    med = {k: float(np.median(v)) for k, v in times.items()}
    for k, v in med.items():
        print(f"{k:30s} {v * 1e6:8.2f} us per point (median of {args.repeats})")
    ratio = med["sliding_stress (this)"] / med["point_stress (normal)"]
    print(f"sliding_stress / normal field: {ratio:.1f}x")
    for k, v in maxima.items():
        print(f"sliding_maxima ({k}; b/a = 0.5, mu = 0.4, c/a = 0.8, direction "
              f"{args.direction:g}): "
              f"{np.median(v):.2f} s CPU (median of {args.maxima_repeats})")
    if args.baseline:
        base = modules["baseline"]
        print(f"speed-up against the baseline: bulk "
              f"{med['sliding_stress (baseline)'] / med['sliding_stress (this)']:.2f}x, "
              f"one point {med['one point (baseline)'] / med['one point (this)']:.2f}x, "
              f"maxima {np.median(maxima['baseline']) / np.median(maxima['this']):.2f}x")
        diff = np.abs(friction.sliding_stress(1.0, 0.5, 1.0, 1.0, 0.3, x, y, z)
                      - base.sliding_stress(1.0, 0.5, 1.0, 1.0, 0.3, x, y, z)).max()
        print(f"largest difference of the fields: {diff:.3g} mu p0")


if __name__ == "__main__":
    main()
