"""Cost of the sliding-traction stress (hertz/_friction.py) against the normal field.

    python benchmarks/friction.py [--n 20000] [--repeats 7]

Times sliding_stress and the C kernel's point_stress (Contact.stress without the checks)
at the same N random points below an ellipse b/a = 0.5 (depths log-uniform 1e-3 a to 3 a),
CPU time, interleaved rounds; prints the medians per point and their ratio, and the
machine. Also times sliding_maxima for one contact.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import describe  # noqa: E402

from hertz._friction import sliding_maxima, sliding_stress  # noqa: E402
from hertz._stress import point_stress  # noqa: E402


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=20000)
    ap.add_argument("--repeats", type=int, default=7)
    args = ap.parse_args(argv)
    rng = np.random.default_rng(0)
    x = rng.uniform(-1.5, 1.5, args.n)
    y = rng.uniform(-0.75, 0.75, args.n)
    z = np.exp(rng.uniform(np.log(1e-3), np.log(3.0), args.n))
    runs = {"sliding_stress": lambda: sliding_stress(1.0, 0.5, 1.0, 0.3, 0.3, x, y, z),
            "point_stress (normal)": lambda: point_stress(1.0, 0.5, 1.0, 0.3, x, y, z)}
    times = {k: [] for k in runs}
    for _ in range(args.repeats):
        for k, f in runs.items():
            t = time.process_time()
            f()
            times[k].append((time.process_time() - t) / args.n)
    print(describe())
    med = {k: float(np.median(v)) for k, v in times.items()}
    for k, v in med.items():
        print(f"{k:24s} {v * 1e6:8.2f} us per point (median of {args.repeats})")
    print(f"ratio {med['sliding_stress'] / med['point_stress (normal)']:.1f}x")
    t = time.process_time()
    sliding_maxima(1.0, 0.5, 1.0, 0.25, 0.3)
    print(f"sliding_maxima (b/a = 0.5, mu = 0.25): {time.process_time() - t:.2f} s CPU")


if __name__ == "__main__":
    main()
