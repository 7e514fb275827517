"""Peak memory of hertz.contact: a 1e7-contact batch, and 4e7 contacts through dask.

    python benchmarks/memory.py [--n 10000000] [--dask-n 40000000] [--readme]

Each case runs in a fresh Python process and reads the kernel's high-water
mark of resident memory (VmHWM, Linux).  The batch case reports the peak
above the memory held before the call (inputs included) against the bytes
of the arrays the call returns; the dask case reports the whole process's
peak while it computes summary statistics of 4e7 contacts in chunks of 1e6
(inputs generated lazily, nothing held but the chunks in flight).  It
prints the table; with --readme it also replaces the memory-table section
of the documentation (docs/explanation/contact-kernel.md).
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
import textwrap
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import describe, replace_readme_section  # noqa: E402

BATCH = """
import json, numpy as np, hertz
def status(key):
    for line in open('/proc/self/status'):
        if line.startswith(key):
            return int(line.split()[1]) * 1024
n = {n}
rng = np.random.default_rng(0)
balls = hertz.Body.sphere(rng.uniform(2e-3, 2e-2, n), 210e9, 0.3)
races = hertz.Body(-rng.uniform(2.05e-2, 3e-2, n), rng.uniform(2e-2, 1e-1, n), 70e9, 0.33)
loads, angles = rng.uniform(1.0, 2000.0, n), rng.uniform(-3.0, 3.0, n)
before = status('VmRSS')
c = hertz.contact(balls, races, load=loads, angle=angles)
peak = status('VmHWM')
held = sum(getattr(c, k).nbytes for k in ('a', 'b', 'load', 'p0', 'delta', 'stiffness'))
print(json.dumps(dict(before=before, peak=peak, results=held)))
"""

DASK = """
import json, dask, dask.array as da, hertz
def status(key):
    for line in open('/proc/self/status'):
        if line.startswith(key):
            return int(line.split()[1]) * 1024
n, chunk = {n}, 1_000_000
rs = da.random.default_rng(0)
radius = rs.uniform(2e-3, 2e-2, n, chunks=chunk)
load = rs.uniform(1.0, 2000.0, n, chunks=chunk)
angle = rs.uniform(-3.0, 3.0, n, chunks=chunk)
c = hertz.contact(hertz.Body.sphere(radius, 210e9, 0.3),
                  hertz.Body(-0.03, 0.05, 70e9, 0.33), load=load, angle=angle)
with dask.config.set(scheduler="threads", num_workers=2):
    p0_max, a_mean, over = da.compute(c.p0.max(), c.a.mean(), (c.p0 > 2e9).sum())
print(json.dumps(dict(peak=status('VmHWM'), p0_max=float(p0_max), a_mean=float(a_mean),
                      over=int(over))))
"""


def run(code: str) -> tuple[dict, float]:
    t0 = time.perf_counter()
    out = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True,
                         text=True, check=True)
    return json.loads(out.stdout), time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=10_000_000)
    ap.add_argument("--dask-n", type=int, default=40_000_000)
    ap.add_argument("--readme", action="store_true",
                    help="also write the table into the documentation's memory-table section")
    args = ap.parse_args()
    batch, _ = run(BATCH.format(n=args.n))
    extra = batch["peak"] - batch["before"]
    mb = 1024.0**2
    lines = [f"{describe()}, {time.strftime('%Y-%m-%d')}; `python benchmarks/memory.py`", "",
             "| case | peak memory | against |", "|---|---|---|",
             f"| hertz.contact, N = {args.n:.0e} distinct geometries at random angles | "
             f"{extra / mb:.0f} MB above the inputs | results {batch['results'] / mb:.0f} MB "
             f"(ratio {extra / batch['results']:.3f}) |"]
    if args.dask_n:
        dask_run, seconds = run(DASK.format(n=args.dask_n))
        lines.append(f"| {args.dask_n:.0e} contacts through dask, chunks of 1e6, 2 threads "
                     f"(p0 max, a mean, count p0 > 2 GPa) | {dask_run['peak'] / mb:.0f} MB "
                     f"whole process | {seconds:.0f} s in all |")
    text = "\n".join(lines)
    print(text)
    if args.readme:
        print(f"wrote {replace_readme_section('memory-table', text)}")


if __name__ == "__main__":
    main()
