"""The seed's Fig. 4 redone: convergence of the Bailey iteration against alpha.

    python benchmarks/convergence.py [--out DIR] [--readme]

Left panel, as the paper plots it: |nu_n / nu_inf - 1| for n = 0, 1, 2 over
1e-3 <= alpha <= 1e6, with the trial function as printed (c3 = +0.109...)
and corrected (c3 = -0.109..., alpha < 1 by symmetry); nu_inf is the exact
elliptic parameter from the 50-digit table, not the iteration's own limit.
Right panel: the same iterates measured as the relative error in lambda,
the quantity users see, with ours (iterations = 0 and 1) beside them.
Errors below 1e-17 are drawn at 1e-17; the printed method gives NaN for
alpha < 1 (the trial function takes (ln alpha)^(1/2)) and above alpha ~ 100.
Writes OUT/convergence.png (OUT defaults to the current folder; --readme
writes docs/convergence.png, the figure of docs/explanation/solver.md).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT / "tests"))

import mpmath as mp  # noqa: E402
from reference import load_table  # noqa: E402

import hertz  # noqa: E402
from hertz import methods  # noqa: E402

FLOOR = 1e-17


def rel(values, refs):
    out = []
    for v, r in zip(np.asarray(values, dtype=float), refs, strict=True):
        if not np.isfinite(v):
            out.append(np.nan)
        elif r == 0:
            out.append(abs(v))
        else:
            out.append(float(abs((mp.mpf(v) - r) / r)))
    return np.maximum(np.array(out), FLOOR)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--out", type=Path, default=Path("."),
                    help="folder for convergence.png (default: here)")
    ap.add_argument("--readme", action="store_true",
                    help="write docs/convergence.png, the documentation's figure")
    args = ap.parse_args()
    if args.readme:
        args.out = ROOT / "docs"
    args.out.mkdir(parents=True, exist_ok=True)

    rows = sorted((r for r in load_table()
                   if r["group"] in ("main", "recip-main") and 1e-3 <= r["alpha"] <= 1e6),
                  key=lambda r: r["alpha"])
    alpha = np.array([r["alpha"] for r in rows])
    m_ref = [r["m"] for r in rows]
    lam_ref = [r["lambda"] for r in rows]

    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5), sharey=True)
    with np.errstate(all="ignore"):
        for n, color in zip(range(3), ("C0", "C1", "C2"), strict=True):
            variants = ((False, ":", "as printed"), (True, "-", "c3 corrected"))
            for corrected, style, label in variants:
                nu = methods.seed_hokada_2025_nu(alpha, n, corrected)
                lam = methods.seed_hokada_2025(alpha, n, corrected)
                left.plot(alpha, rel(nu, m_ref), style, color=color, lw=1.2,
                          label=f"n = {n}, {label}")
                right.plot(alpha, rel(lam, lam_ref), style, color=color, lw=1.2,
                           label=f"seed n = {n}, {label}")
    for iterations, color in ((0, "C4"), (1, "C3")):
        right.plot(alpha, rel(hertz.ellipticity(alpha, iterations=iterations), lam_ref), "-",
                   color=color, lw=1.6, label=f"ours, iterations = {iterations}")
    left.set_title("as in the paper: |nu_n / nu_inf - 1|")
    right.set_title("what users see: relative error in lambda = a/b")
    for ax in (left, right):
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("alpha = rho_x / rho_y")
        ax.set_ylim(FLOOR / 2, 10)
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="upper left")
    left.set_ylabel("relative error (values below 1e-17 drawn at 1e-17)")
    fig.suptitle("Convergence of the Bailey iteration (Hokada, Iizuka & Takada, Fig. 4) "
                 "against the 50-digit reference")
    fig.tight_layout()
    path = args.out / "convergence.png"
    fig.savefig(path, dpi=130)
    print(f"wrote {path}")


if __name__ == "__main__":
    main()
