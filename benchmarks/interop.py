"""What pandas, xarray and pint inputs cost against the same numbers as numpy arrays.

    python benchmarks/interop.py [--rounds 15]

hertz.contact of N spheres on a race (radii, loads and angles given as numpy
arrays, pandas Series, xarray DataArrays or pint Quantities), the median of
interleaved rounds and its ratio to numpy; for N = 1 the numpy case is the
scalar path (Python floats).  The wrappers cost a fixed time per call (the
unwrapping, the second Body check and the wrapping of fifteen fields, the
geometry ones computed at once), which a large batch hides.  Prints a
markdown table; nothing is written.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import timeit
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import describe  # noqa: E402

import hertz  # noqa: E402


def cases(n: int):
    import pandas as pd
    import pint
    import xarray as xr

    ureg = pint.UnitRegistry()
    rng = np.random.default_rng(0)
    radius, load, angle = rng.uniform(2e-3, 2e-2, n), rng.uniform(1, 2e3, n), rng.uniform(-3, 3, n)
    race = hertz.Body(-0.03, 0.05, 70e9, 0.33)
    if n == 1:
        plain = (float(radius[0]), float(load[0]), float(angle[0]))
    else:
        plain = (radius, load, angle)
    index = pd.RangeIndex(n)
    series = tuple(pd.Series(x, index=index) for x in (radius, load, angle))
    arrays = tuple(xr.DataArray(x, dims="case") for x in (radius, load, angle))
    quantities = (plain[0] * ureg.m, plain[1] * ureg.N, plain[2] * ureg.rad)

    def run(r, p, a):
        return lambda: hertz.contact(hertz.Body.sphere(r, 210e9, 0.3), race, load=p, angle=a)

    return {"numpy" if n > 1 else "floats": run(*plain), "pandas": run(*series),
            "xarray": run(*arrays), "pint": run(*quantities)}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--rounds", type=int, default=15)
    args = ap.parse_args()
    print(f"{describe()}; `python benchmarks/interop.py`\n")
    print("| N | " + " | ".join(("plain", "pandas", "xarray", "pint")) + " |")
    print("|---|---|---|---|---|")
    for n in (1, 1_000, 100_000):
        funcs = cases(n)
        number = max(1, 500 // n)
        times = {k: [] for k in funcs}
        for _ in range(args.rounds):
            for k, f in funcs.items():
                times[k].append(timeit.timeit(f, number=number) / number)
        med = {k: statistics.median(v) for k, v in times.items()}
        base = next(iter(med.values()))
        cells = [f"{base * 1e6:.1f} us"] + [f"{v * 1e6:.1f} us ({v / base:.1f}x)"
                                            for v in list(med.values())[1:]]
        print(f"| {n:.0e} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
