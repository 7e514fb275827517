"""Stresses below the default scene, and the speed of the stress field and its maxima.

    python benchmarks/stress.py [--n 1000000] [--contacts 100000] [--repeats 7] [--readme]
                                [--out DIR] [--baseline PATH]

Prints the table of subsurface maxima of the ``hertz`` command's default
scene (a bearing ball on its inner race), writes OUT/stress.png (the figure
of ``hertz --plot``; OUT defaults to the current folder), and times Contact.stress at N points and
Contact.subsurface for N contacts against one scipy.special.ellipk + ellipe
pass over N (CPU time, interleaved rounds, medians of the per-round
ratios).  With --readme the tables also replace the stress-table section
of the documentation (docs/explanation/stresses.md) and the figure goes to
docs/stress.png.  --baseline PATH (another build's hertz/_ufuncs*.so, or the
checkout that holds it) adds, in the same interleaved rounds, the bare
subsurface ufunc of that build and of this one on the same contacts, for a
before/after comparison on a busy machine.
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
from scipy import special  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _common import describe, replace_readme_section  # noqa: E402

import hertz  # noqa: E402
from hertz.cli import DEFAULT_SCENE  # noqa: E402

DOCS = Path(__file__).resolve().parents[1] / "docs"


def default_contact():
    b1, b2 = (hertz.Body(**DEFAULT_SCENE[k]) for k in ("body1", "body2"))
    return hertz.contact(b1, b2, load=DEFAULT_SCENE["load"])


def maxima_table(c) -> list[str]:
    m = c.subsurface(1)
    rows = [("largest shear stress tau1 = (s1 - s3)/2", m.tau_max,
             f"z = {m.z_tau_max * 1e6:.2f} um"),
            ("largest von Mises stress", m.von_mises, f"z = {m.z_von_mises * 1e6:.2f} um"),
            ("largest orthogonal shear \\|tau_yz\\| (x = 0)", m.tau_orthogonal,
             f"y = {m.y_tau_orthogonal * 1e6:.2f} um, z = {m.z_tau_orthogonal * 1e6:.2f} um"),
            ("largest surface tension (edge of the ellipse)", m.tensile,
             f"x = {m.x_tensile * 1e6:.1f} um, y = {m.y_tensile * 1e6:.1f} um")]
    lines = [f"Default scene (`hertz`): a = {c.a * 1e3:.4f} mm, b = {c.b * 1e3:.4f} mm, "
             f"p0 = {c.p0 / 1e9:.4f} GPa, both bodies steel (nu = 0.3).", "",
             "| quantity | value | / p0 | where |", "|---|---|---|---|"]
    lines += [f"| {name} | {value / 1e9:.4f} GPa | {value / c.p0:.4f} | {where} |"
              for name, value, where in rows]
    for criterion in ("von_mises", "tresca"):
        load = c.first_yield_load(1.5e9, criterion=criterion)
        lines.append(f"| first yield, {criterion.replace('_', ' ')}, yield strength 1.5 GPa | "
                     f"{load:.1f} N | | load |")
    return lines


def load_baseline(path: str):
    """hertz._ufuncs of another build: the .so itself or a checkout with hertz/_ufuncs*.so."""
    p = Path(path)
    if p.is_dir():
        found = sorted(p.glob("hertz/_ufuncs*.so")) + sorted(p.glob("hertz/_ufuncs*.pyd"))
        if not found:
            raise SystemExit(f"no hertz/_ufuncs*.so in {p} (build it with setup.py build_ext "
                             "--inplace)")
        p = found[0]
    # a name that ends in _ufuncs: the loader calls PyInit__ufuncs
    spec = importlib.util.spec_from_file_location("hertz_baseline._ufuncs", p)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def speed(n: int, contacts: int, repeats: int, baseline=None) -> list[str]:
    rng = np.random.default_rng(0)
    c = default_contact()
    x = rng.uniform(-2 * c.a, 2 * c.a, n)
    y = rng.uniform(-2 * c.b, 2 * c.b, n)
    z = rng.uniform(0.0, 3 * c.b, n)
    m = rng.uniform(0.0, 1.0, n)
    mc = rng.uniform(0.0, 1.0, contacts)
    balls = hertz.Body.sphere(rng.uniform(2e-3, 2e-2, contacts), 210e9, 0.3)
    races = hertz.Body(-rng.uniform(2.05e-2, 3e-2, contacts), rng.uniform(2e-2, 1e-1, contacts),
                       210e9, 0.3)
    batch = hertz.contact(balls, races, load=rng.uniform(1.0, 2000.0, contacts))
    contenders = {
        "points": {"ref": lambda: (special.ellipk(m), special.ellipe(m)),
                   "Contact.stress": lambda: c.stress(x, y, z)},
        "contacts": {"ref": lambda: (special.ellipk(mc), special.ellipe(mc)),
                     "Contact.subsurface": lambda: batch.subsurface(1)},
    }
    if baseline is not None:
        from hertz import _ufuncs

        a, b, nu = np.asarray(batch.a), np.asarray(batch.b), 0.3
        contenders["contacts"]["subsurface ufunc, this build"] = lambda: _ufuncs.subsurface(
            a, b, nu)
        contenders["contacts"]["subsurface ufunc, baseline"] = lambda: baseline.subsurface(
            a, b, nu)
    lines = ["| case | ns per element (median) | time / (ellipk + ellipe) over the same N, "
             f"median of {repeats} rounds |", "|---|---|---|"]
    for group, size in (("points", n), ("contacts", contacts)):
        fs = contenders[group]
        times = {k: [] for k in fs}
        for f in fs.values():
            f()
        for _ in range(repeats):
            for k, f in fs.items():
                t0 = time.process_time()
                f()
                times[k].append(time.process_time() - t0)
        ref = np.array(times["ref"])
        for k, v in times.items():
            if k != "ref":
                label = f"{k}, N = {size:.0e} {'points' if group == 'points' else 'contacts'}"
                lines.append(f"| {label} | {np.median(v) / size * 1e9:.0f} | "
                             f"{np.median(np.array(v) / ref):.1f} |")
    return lines


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--n", type=int, default=1_000_000)
    ap.add_argument("--contacts", type=int, default=100_000)
    ap.add_argument("--repeats", type=int, default=7)
    ap.add_argument("--readme", action="store_true",
                    help="also write the tables into the documentation's stress-table section "
                         "and the figure to docs/stress.png")
    ap.add_argument("--out", type=Path, default=Path("."),
                    help="folder for stress.png without --readme (default: here)")
    ap.add_argument("--baseline", metavar="PATH",
                    help="also time the subsurface ufunc of another build (its _ufuncs .so "
                         "or its checkout), interleaved with this one's")
    args = ap.parse_args()
    if args.baseline and args.readme:
        ap.error("--baseline is for comparisons: drop --readme")
    baseline = load_baseline(args.baseline) if args.baseline else None
    c = default_contact()
    from hertz._plot import stress_figure

    out = DOCS if args.readme else args.out
    out.mkdir(parents=True, exist_ok=True)
    stress_figure(c, title="bearing ball on inner race (default scene)").savefig(
        out / "stress.png", dpi=110)
    lines = [f"{describe()}, {time.strftime('%Y-%m-%d')}; `python benchmarks/stress.py`", "",
             *maxima_table(c), "", *speed(args.n, args.contacts, args.repeats, baseline)]
    text = "\n".join(lines)
    print(text)
    print(f"wrote {out / 'stress.png'}")
    if args.readme:
        print(f"wrote {replace_readme_section('stress-table', text)}")


if __name__ == "__main__":
    main()
