"""Speed against error of every method for lambda(alpha), measured in one run.

    python benchmarks/speed_vs_error.py [--out DIR] [--rounds 7] [--readme]

Error: relative error in lambda and in the contact outputs a, b, p0, delta
against the committed 50-digit table tests/data/reference_lambda.csv, on
alpha in [1, 1e6] (1000 log-uniform points plus 53 hard cases just above 1),
on (1e6, 1e15] (600 points), and on the hard cases alone.  Methods that give
only lambda get exact K(m), E(m) (scipy) for a, b, p0, delta; Hamrock & Brewe
and Hamrock 1994 use their own approximations of K and E.

Speed: nanoseconds per contact on N alphas log-uniform in [1, 1e6] (N = 1e6,
fewer for the slow iterative methods: the table says), median of --rounds
rounds with all methods interleaved in each round, single-threaded; and
microseconds for one call with a Python float.

Prints the table and writes OUT/speed_vs_error.json (raw numbers),
OUT/speed_vs_error.md (the table and the conclusions) and
OUT/speed_vs_error.png (error against time, log-log; needs matplotlib, the
``plot`` extra); OUT defaults to the current folder.  With --readme, OUT is
docs/ and the table also replaces the speed-vs-error section of the
documentation (docs/explanation/speed-vs-error.md).
"""

from __future__ import annotations

import argparse
import json
import math
import sys
import time
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from scipy import special

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(ROOT / "benchmarks"))

import mpmath as mp  # noqa: E402
from _common import describe, replace_readme_section  # noqa: E402
from reference import load_table  # noqa: E402

import hertz  # noqa: E402
from hertz import methods  # noqa: E402

MACHINE_PRECISION = 1e-15  # "machine precision" for the comparison: 4.5 ulp (also shown: 2e-15)


@dataclass
class Method:
    name: str
    family: str
    fn: object  # alpha array -> lambda, or (lambda, K, E)
    n_time: int = 1_000_000
    note: str = ""
    result: dict = field(default_factory=dict)



def with_integrals(fn, integrals):
    return lambda a: (fn(a), *integrals(a))


def first(fn, **kw):
    return lambda a: fn(a, **kw)[0]


def build_methods() -> list[Method]:
    ms = [
        Method("ours, iterations=1 (default)", "ours", hertz.ellipticity),
        Method("ours, iterations=0", "ours", lambda a: hertz.ellipticity(a, iterations=0)),
        Method("Hamrock & Brewe 1983", "closed form",
               with_integrals(methods.hamrock_brewe_1983, methods.hamrock_brewe_1983_integrals),
               note="own K, E"),
        Method("Hamrock 1994", "closed form",
               with_integrals(methods.hamrock_1994, methods.hamrock_1994_integrals),
               note="own K, E"),
        Method("Greenwood 1985", "closed form", methods.greenwood_1985),
        Method("Antoine et al. 2006", "closed form", methods.antoine_2006),
        Method("Hamrock & Anderson 1973, rtol 1e-13", "iterative",
               first(methods.hamrock_anderson_1973), n_time=100_000),
        Method("Dyson, Evans & Snidle 1992, rtol 1e-14", "iterative",
               first(methods.dyson_evans_snidle_1992), n_time=100_000),
    ]
    for corrected, label in ((False, "seed as printed"), (True, "seed, c3 corrected")):
        for n in range(4):
            ms.append(Method(f"{label}, n = {n}", "seed",
                             lambda a, n=n, c=corrected: methods.seed_hokada_2025(a, n, c)))
    for kind in ("linear", "cubic"):
        for size in (1_000, 10_000, 100_000):
            table = methods.TableLookup(size, kind)
            ms.append(Method(f"table, {kind}, {size:.0e} nodes", "table", table,
                             note=f"{table.nbytes / 1e3:.0f} kB"))
    ms.append(Method("bracketing reference (toms748)", "reference",
                     methods.bracketing_reference, n_time=2_000))
    return ms


def unit_contact(lam, K, E):
    """a, b, p0, delta of a unit scene (P = E* = rho_+ = 1) from lambda, K, E."""
    b = np.cbrt(3 * E / (np.pi * lam))
    a = lam * b
    return a, b, 3 / (2 * np.pi * a * b), 0.5 * K * np.cbrt(9 / (E * (np.pi * lam) ** 2))


def reference_sets():
    rows = load_table()
    sets = {"main": [r for r in rows if r["group"] in ("main", "near1")],
            "wide": [r for r in rows if r["group"] == "wide"],
            "near1": [r for r in rows if r["group"] == "near1"]}
    out = {}
    for name, rs in sets.items():
        alpha = np.array([r["alpha"] for r in rs])
        lam = [r["lambda"] for r in rs]
        with mp.workdps(60):
            contact = [[float(v) for v in (
                (3 * r["E"] / (mp.pi * r["lambda"])) ** (mp.mpf(1) / 3) * r["lambda"],
                (3 * r["E"] / (mp.pi * r["lambda"])) ** (mp.mpf(1) / 3),
                3 / (2 * mp.pi * r["lambda"] * (3 * r["E"] / (mp.pi * r["lambda"]))
                     ** (mp.mpf(2) / 3)),
                r["K"] / 2 * (9 / (r["E"] * (mp.pi * r["lambda"]) ** 2)) ** (mp.mpf(1) / 3))]
                for r in rs]
        out[name] = (alpha, lam, np.array(contact).T)
    return out


def rel_err(values, refs) -> np.ndarray:
    """|v - r|/r with mpmath references; NaN and inf count as infinite error."""
    err = np.array([float(abs((mp.mpf(v) - r) / r)) if math.isfinite(v) else math.inf
                    for v, r in zip(np.asarray(values, dtype=float), refs, strict=True)])
    return err


def measure_errors(m: Method, sets) -> None:
    for name, (alpha, lam_ref, contact_ref) in sets.items():
        with np.errstate(all="ignore"):
            out = m.fn(alpha)
            if isinstance(out, tuple):
                lam, K, E = out
            else:
                lam = np.asarray(out, dtype=float)
                p = 1 / lam**2
                K, E = special.ellipkm1(p), special.ellipe(1 - p)
            contact = unit_contact(lam, K, E)
        err = rel_err(lam, lam_ref)
        c_err = np.max([np.where(np.isfinite(c), np.abs(c / r - 1), np.inf)
                        for c, r in zip(contact, contact_ref, strict=True)], axis=0)
        finite = np.isfinite(err)
        m.result[name] = {
            "lambda_max": float(err.max()),  # inf if any element failed (NaN/inf)
            "lambda_max_finite": float(err[finite].max()) if finite.any() else math.inf,
            "lambda_median": float(np.median(err)),
            "contact_max": float(c_err.max()),
            "contact_max_finite": float(c_err[np.isfinite(c_err)].max())
            if np.isfinite(c_err).any() else math.inf,
            "failures": int(np.sum(~finite))}


def measure_speed(ms: list[Method], rounds: int) -> None:
    rng = np.random.default_rng(1)
    big = np.exp(rng.uniform(0.0, np.log(1e6), 1_000_000))
    ref = lambda a: (special.ellipk(a), special.ellipe(a))  # noqa: E731
    m_uniform = rng.uniform(0, 1, 1_000_000)
    times = {m.name: [] for m in ms}
    times["scipy ellipk + ellipe"] = []
    for m in ms:  # warm-up
        m.fn(big[:1000])
    for _ in range(rounds):
        t0 = time.perf_counter()
        ref(m_uniform)
        times["scipy ellipk + ellipe"].append((time.perf_counter() - t0) / 1e6)
        for m in ms:
            a = big[: m.n_time]
            with np.errstate(all="ignore"):
                t0 = time.perf_counter()
                m.fn(a)
                times[m.name].append((time.perf_counter() - t0) / m.n_time)
    ke = np.array(times["scipy ellipk + ellipe"])
    for m in ms:
        t = np.array(times[m.name])
        m.result["ns_per_contact"] = float(np.median(t) * 1e9)
        m.result["ns_per_round"] = [float(x * 1e9) for x in t]
        m.result["ratio_to_ellipk_ellipe"] = float(np.median(t / ke))
        m.result["n_timed"] = m.n_time
        calls = []
        for _ in range(5 if m.family == "reference" else 200):
            t0 = time.perf_counter()
            m.fn(3.7)
            calls.append(time.perf_counter() - t0)
        m.result["us_per_scalar_call"] = float(np.median(calls) * 1e6)
    return float(np.median(ke) * 1e9)


def accuracy(m: Method) -> float:
    """The accuracy used for the comparisons: max lambda error on [1, 1e6] with the hard cases."""
    return m.result["main"]["lambda_max"]


def time_ratio(m1: Method, m2: Method) -> float:
    """Median over the rounds of time(m1)/time(m2), both measured in the same round."""
    return float(np.median(np.array(m1.result["ns_per_round"]) / m2.result["ns_per_round"]))


def conclusions(ms: list[Method]) -> list[str]:
    """Comparisons use time ratios taken within each round (robust to the machine's drift)."""
    out = []
    ours = [m for m in ms if m.family == "ours"]
    others = [m for m in ms if m.family != "ours"]
    t = lambda m: m.result["ratio_to_ellipk_ellipe"]  # noqa: E731
    for o in ours:
        better = [m.name for m in others if time_ratio(m, o) < 1 and accuracy(m) < accuracy(o)]
        out.append(f"- **{o.name}** ({accuracy(o):.1e}, {o.result['ns_per_contact']:.1f} ns): "
                   + ("on the Pareto front: no method is both faster and more accurate."
                      if not better else f"NOT on the Pareto front: {', '.join(better)} "
                      "are both faster and more accurate."))
    for threshold in (MACHINE_PRECISION, 2 * MACHINE_PRECISION):
        exact = sorted((m for m in ms if accuracy(m) <= threshold), key=t)
        out.append(f"- At max error <= {threshold:.0e} on [1, 1e6]: "
                   + ", ".join(f"{m.name} ({t(m):.2f} x ellipk+ellipe)" for m in exact)
                   + f"; the fastest is **{exact[0].name}**.")
    closed = [m for m in ms if m.family == "closed form"]
    quick = min(closed, key=t)
    loose = next(m for m in ours if "iterations=0" in m.name)
    best_closed = min(closed, key=accuracy)
    out.append(f"- Loose setting: {loose.name} has error {accuracy(loose):.1e}, below every "
               f"closed form (best: {best_closed.name}, {accuracy(best_closed):.1e})"
               if accuracy(loose) < accuracy(best_closed) else
               f"- Loose setting: {loose.name} ({accuracy(loose):.1e}) does NOT beat "
               f"{best_closed.name} ({accuracy(best_closed):.1e}) on error")
    ratio = time_ratio(loose, quick)
    out[-1] += (f", at {ratio:.2f} times the time of the fastest closed form "
                f"({quick.name}, {quick.result['ns_per_contact']:.1f} ns)"
                + (" (goal: at most 2)." if ratio <= 2 else " -- ABOVE the goal of 2."))
    faster_than_ours = [m for m in others if time_ratio(m, ours[0]) < 1]
    if faster_than_ours:
        out.append("- Faster than ours at its default, and less accurate: " + ", ".join(
            f"{m.name} ({m.result['ns_per_contact']:.1f} ns, {fmt(accuracy(m))})"
            for m in sorted(faster_than_ours, key=t)) + ".")
    tables = [m for m in ms if m.family == "table"]
    floor = min(tables, key=accuracy)
    out.append(f"- The most accurate table ({floor.name}, {floor.note}) reaches "
               f"{accuracy(floor):.1e} ({floor.result['wide']['lambda_max']:.1e} up to 1e15): "
               "the rounding of ln(alpha), which it needs to find its interval, sets that floor; "
               "it is built with hertz.ellipticity.")
    return out


def fmt(x: float) -> str:
    return "-" if math.isinf(x) or math.isnan(x) else f"{x:.1e}"


def fmt_err(r: dict, key: str) -> str:
    """Max error over the elements that gave a number, and how many did not."""
    text = fmt(r[f"{key}_finite"])
    return text + (f" ({r['failures']} NaN)" if r["failures"] else "")


def markdown(ms: list[Method], ke_ns: float, header: str) -> str:
    lines = [header, "",
             "| method | lambda max, [1, 1e6] | lambda median | lambda max, (1e6, 1e15] "
             "| lambda max, 53 hard cases 1 < alpha <= 1.5 | a, b, p0, delta max, [1, 1e6] "
             "| ns / contact (N) | x ellipk+ellipe | us / scalar call | note |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for m in ms:
        r = m.result
        lines.append(
            f"| {m.name} | {fmt_err(r['main'], 'lambda_max')} | {fmt(r['main']['lambda_median'])} "
            f"| {fmt_err(r['wide'], 'lambda_max')} | {fmt_err(r['near1'], 'lambda_max')} "
            f"| {fmt(r['main']['contact_max_finite'])} "
            f"| {r['ns_per_contact']:.1f} ({r['n_timed']:.0e}) "
            f"| {r['ratio_to_ellipk_ellipe']:.2f} | {r['us_per_scalar_call']:.1f} | {m.note} |")
    lines += ["", f"One scipy.special.ellipk + ellipe pass: {ke_ns:.1f} ns per element.", ""]
    lines += conclusions(ms)
    return "\n".join(lines)


def plot(ms: list[Method], path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(9, 6.5))
    styles = {"ours": ("*", "C3", 220), "closed form": ("o", "C0", 60),
              "iterative": ("s", "C1", 60), "seed": ("^", "C2", 60), "table": ("D", "C4", 50),
              "reference": ("P", "C5", 70)}
    for fam, (marker, color, size) in styles.items():
        pts = [m for m in ms if m.family == fam]
        for m in pts:
            x = m.result["ns_per_contact"]
            y = min(max(m.result["main"]["lambda_max_finite"], 1e-17), 10.0)
            fails = m.result["main"]["failures"]
            ax.scatter([x], [y], marker=marker, s=size, zorder=3,
                       facecolors="none" if fails else color, edgecolors=color,
                       label=fam if m is pts[0] else None)
            ax.annotate(m.name + (f" ({fails} NaN)" if fails else ""), (x, y), fontsize=6,
                        xytext=(4, 3), textcoords="offset points")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per contact [ns] (N = 1e6, alpha log-uniform in [1, 1e6])")
    ax.set_ylabel("max relative error in lambda on [1, 1e6] (with alpha -> 1)\n"
                  "hollow: the method returned NaN for some inputs (max over the rest)")
    ax.axhline(MACHINE_PRECISION, color="0.6", lw=0.8, ls="--")
    ax.grid(True, which="major", alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    ax.set_title("lambda(alpha): error against time, all methods measured in one run")
    fig.tight_layout()
    fig.savefig(path, dpi=130)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", type=Path, default=None,
                    help="folder for the .json, .md and .png (default: here; docs/ with --readme)")
    ap.add_argument("--rounds", type=int, default=7)
    ap.add_argument("--readme", action="store_true",
                    help="write into docs/ and the documentation's speed-vs-error section")
    args = ap.parse_args()
    if args.out is None:
        args.out = ROOT / "docs" if args.readme else Path(".")
    args.out.mkdir(parents=True, exist_ok=True)
    t_start = time.time()
    ms = build_methods()
    sets = reference_sets()
    for m in ms:
        measure_errors(m, sets)
    ke_ns = measure_speed(ms, args.rounds)
    header = (f"{describe()}; {time.strftime('%Y-%m-%d')}; median of {args.rounds} interleaved "
              f"rounds; `python benchmarks/speed_vs_error.py`.")
    md = markdown(ms, ke_ns, header)
    (args.out / "speed_vs_error.md").write_text(md + "\n")
    (args.out / "speed_vs_error.json").write_text(json.dumps(
        {"machine": describe(), "date": time.strftime("%Y-%m-%d"), "ellipk_ellipe_ns": ke_ns,
         "methods": [{k: v for k, v in asdict(m).items() if k != "fn"} for m in ms]}, indent=1))
    try:
        plot(ms, args.out / "speed_vs_error.png")
    except ImportError:
        print("matplotlib missing (pip install '.[plot]'): no PNG written", file=sys.stderr)
    print(md)
    if args.readme:
        print(f"wrote {replace_readme_section('speed-vs-error', md)}")
    print(f"\n({time.time() - t_start:.0f} s)")


if __name__ == "__main__":
    main()
