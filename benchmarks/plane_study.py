"""Refinement study of our own 2-D Hertz models (fem_validation.solvers.plane).

    python benchmarks/plane_study.py [--divisions 4 8 16 32] [--docs]

Plane strain and axisymmetric: a rigid parabolic indenter (R 10 mm) on a steel
half-space (E 210 GPa, nu 0.3), 1e5 N/m and 100 N; cells of Hertz's size / n over the
contact.  Prints, per model and n, the unknowns, the errors of the half-width or contact
radius (second moment of the nodal forces) and of p0 (recovered from the nodal forces),
the observed orders (slope of log |err| against log h over the series) and p0
extrapolated by Richardson from the two finest meshes at the observed order; ``--docs``
writes the table into docs/explanation/plane-models.md between its markers.
"""

from __future__ import annotations

import argparse
import platform
import re
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from fem_validation.solvers.plane import refinement_study  # noqa: E402

CASES = {"plane-strain": 1e5, "axisymmetric": 100.0}
PAGE = ROOT / "docs" / "explanation" / "plane-models.md"


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--divisions", type=int, nargs="+", default=[4, 8, 16, 32])
    p.add_argument("--docs", action="store_true")
    args = p.parse_args()
    lines = [f"{platform.processor() or platform.machine()}, Python "
             f"{platform.python_version()}; `python benchmarks/plane_study.py`", "",
             "| model | cells over the contact (size / h) | unknowns | seconds | size error "
             "| p0 error |", "|---|---|---|---|---|---|"]
    summary = []
    for model, force in CASES.items():
        t0 = time.perf_counter()
        runs, rates = refinement_study(model, 0.01, 210e9, 0.3, force,
                                       divisions=tuple(args.divisions))
        seconds = (time.perf_counter() - t0) / len(runs)
        for n, s in zip(args.divisions, runs, strict=True):
            lines.append(f"| {model} | {n} | {s.dofs} | {seconds:.0f} (mean) | "
                         f"{s.size_rel_err:+.2e} | {s.p0_rel_err:+.2e} |")
        order = rates["p0"]
        coarse, fine = runs[-2], runs[-1]
        extrapolated = fine.p0 + (fine.p0 - coarse.p0) / (2 ** order - 1)
        summary.append(f"* {model}: observed order of the p0 error {order:.2f} (size "
                       f"error {rates['size']:.2f}: at its floor, the finite domain's); "
                       f"p0 extrapolated from the two finest meshes "
                       f"{extrapolated / fine.p0_hertz - 1:+.1e} from Hertz")
    text = "\n".join(lines + [""] + summary)
    print(text)
    if args.docs:
        page = PAGE.read_text()
        new = re.sub(r"(<!-- plane-study -->\n).*?(\n<!-- /plane-study -->)",
                     lambda m: m.group(1) + text + m.group(2), page, flags=re.S)
        PAGE.write_text(new)


if __name__ == "__main__":
    main()
