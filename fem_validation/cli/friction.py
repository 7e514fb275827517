"""``python -m fem_validation friction``: Cattaneo-Mindlin and Mindlin-Deresiewicz by FEM.

    python -m fem_validation friction --out DIR            # alpha 1, 3, 10, default level
    python -m fem_validation friction --alpha 3 --axis minor --level 2 --out DIR
    python -m fem_validation friction --study alpha-1 --levels 1 2 3 4 --out DIR

Each run holds the scene's normal load, then moves body 1's loaded face along a
principal axis of the contact: a ramp to the displacement at which
Cattaneo-Mindlin gives Q = RATIO mu P, unloading to minus that and reloading
(:mod:`fem_validation.solvers.friction`).  The run becomes a
:class:`~fem_validation.results.tangential.TangentialResult` graded by
:func:`~fem_validation.grading.tangential.grade_tangential`, the grader every
other source goes through.  Writes DIR/<scene>-<axis>/grade.{json,md,png} per
run and DIR/friction.{json,md} (a study: study.{json,md,png}); with --readme
also the table of docs/explanation/fem-friction.md and docs/fem/*.png.
Usage errors exit 2 with one line, before anything runs; a failed grade exits 1; an
internal error exits 3 with one line (``--debug``: its traceback).  A non-empty --out
is refused unless ``--overwrite``.
"""

from __future__ import annotations

import json
import logging
import time
from os import cpu_count
from pathlib import Path

import numpy as np

from ..reports.friction import COLUMNS, LEGEND, plot_study, table
from ..runs.friction import (
    DEFAULT_ALPHAS,
    DEFAULT_MU,
    DEFAULT_RAMP_STEPS,
    DEFAULT_RATIO,
    DEFAULT_STUDY_LEVELS,
    row_from_grade,
    run,
    study_rates,
)
from ..scenes import MAX_ALPHA, equal_steel
from .common import (
    FEM_RUN,
    OneLineParser,
    UsageError,
    add_overwrite,
    choices,
    fem_constants,
    guarded,
    out_dir,
    require,
)

log = logging.getLogger("fem_validation")


def _parser() -> OneLineParser:
    c, note = fem_constants({"solvers.mesh": ("DEFAULT_LEVEL", "LEVEL_SCALE")})
    p = OneLineParser(prog="python -m fem_validation friction",
                      description="Coulomb friction on the blocks against Cattaneo-Mindlin "
                                  "and Mindlin-Deresiewicz." + note,
                      epilog="example: python -m fem_validation friction --alpha 3 --level 2 "
                             "--out DIR")
    p.add_argument("--alpha", type=float, nargs="+", metavar="A",
                   help=f"equal steel bodies with curvature ratio A (default "
                        f"{' '.join(f'{a:g}' for a in DEFAULT_ALPHAS)})")
    p.add_argument("--axis", choices=("major", "minor"), nargs="+", default=["major"],
                   help="principal axis of the contact along which the load moves "
                        "(default major)")
    p.add_argument("--mu", type=float, default=DEFAULT_MU,
                   help=f"coefficient of friction (default {DEFAULT_MU})")
    p.add_argument("--ratio", type=float, default=DEFAULT_RATIO,
                   help=f"Q*/(mu P) at the end of the ramp, in (0, 1) (default "
                        f"{DEFAULT_RATIO})")
    p.add_argument("--ramp-steps", type=int, default=DEFAULT_RAMP_STEPS,
                   help=f"steps of the ramp; unloading and reloading take twice as many "
                        f"(default {DEFAULT_RAMP_STEPS})")
    p.add_argument("--level", type=int, default=None, choices=choices(c["LEVEL_SCALE"]),
                   help=f"mesh level (default {c['DEFAULT_LEVEL']})")
    p.add_argument("--study", metavar="NAME",
                   help="refinement study of one scene (alpha-<A>) at --levels")
    p.add_argument("--levels", type=int, nargs="+", default=None,
                   help=f"levels of the study (default "
                        f"{' '.join(map(str, DEFAULT_STUDY_LEVELS))})")
    p.add_argument("--collect", type=Path, nargs="+", metavar="RUN",
                   help="no run: one table from earlier runs' directories (DIR/<scene>-<axis>, "
                        "each with its grade.json), e.g. to join runs made in parallel")
    p.add_argument("--out", type=Path, default=Path("fem_out"), help="output directory")
    add_overwrite(p)
    p.add_argument("--readme", action="store_true",
                   help="also put the table into docs/explanation/fem-friction.md and the "
                        "plots into docs/fem/ (run from the repository root)")
    p.add_argument("--quiet", action="store_true", help="log warnings only")
    return p


def _scene_of(name: str):
    if not name.startswith("alpha-"):
        raise UsageError(f"--study {name!r}: use alpha-<A> (equal steel bodies)")
    try:
        alpha = float(name.removeprefix("alpha-"))
    except ValueError:
        raise UsageError(f"--study {name!r}: alpha-<A> needs a number A") from None
    return alpha


def _check(args) -> list[float]:
    from ..solvers.mesh import LEVEL_SCALE

    if args.study and args.alpha:
        raise UsageError("--study and --alpha cannot be combined")
    if args.study and args.level is not None:
        raise UsageError("--study and --level cannot be combined (use --levels)")
    if args.levels is not None and not args.study:
        raise UsageError("--levels applies to --study only (use --level)")
    alphas = [_scene_of(args.study)] if args.study else list(args.alpha or DEFAULT_ALPHAS)
    for a in alphas:
        if not 1 <= a <= MAX_ALPHA:
            raise UsageError(f"alpha {a:g}: the block meshes support 1 <= alpha <= "
                             f"{MAX_ALPHA:g}")
    if not (args.mu > 0 and np.isfinite(args.mu)):
        raise UsageError(f"--mu must be a finite number > 0, got {args.mu!r}")
    if not 0 < args.ratio < 1:
        raise UsageError(f"--ratio must be in (0, 1), got {args.ratio!r}")
    if not args.ramp_steps >= 2:
        raise UsageError(f"--ramp-steps must be >= 2, got {args.ramp_steps!r}")
    levels = args.levels or list(DEFAULT_STUDY_LEVELS)
    bad = [x for x in levels if x not in LEVEL_SCALE]
    if bad:
        raise UsageError(f"--levels must be in {sorted(LEVEL_SCALE)}, got {bad}")
    if args.study and len(levels) < 2:
        raise UsageError("--study needs at least two --levels")
    args.levels = levels
    return alphas


def main(argv: list[str]) -> int:
    """Entry point of ``python -m fem_validation friction``: the exit status (0 passed, 1 a
    check failed, 2 bad input, 3 an internal error; :func:`fem_validation.cli.common.guarded`)."""
    return guarded("fem_validation friction", _main, list(argv))


def _main(argv: list[str]) -> int:
    from ..reports.docs import publish, readme_section

    args = _parser().parse_args(argv)
    if args.collect:
        rows = [row_from_grade(d) for d in args.collect]
        commands = list(dict.fromkeys(r["command"] for r in rows if r["command"]))
        text = ("Collected from " + "; ".join(f"`{c}`" for c in commands)
                + f" (`python -m fem_validation friction {' '.join(argv)}`).\n\n"
                + table(rows) + "\n")
        print(text)
        if args.readme:
            publish("fem-friction", text,
                    [(d / "grade.png", f"{r['scene']}-{r['axis']}_friction.png")
                     for d, r in zip(args.collect, rows, strict=True)])
        return 0 if all(r["passed"] for r in rows) else 1
    require(FEM_RUN, "friction")
    from ..solvers.mesh import DEFAULT_LEVEL, LEVEL_H0, LEVEL_RATIO

    alphas = _check(args)
    if args.readme:
        readme_section("fem-friction-study" if args.study else "fem-friction")
    out_dir(args.out, args.overwrite)
    logging.basicConfig(level=logging.WARNING if args.quiet else logging.INFO,
                        format="%(asctime)s %(message)s", datefmt="%H:%M:%S")
    command = " ".join(["python -m fem_validation friction", *argv])
    t0 = time.perf_counter()
    if args.study:
        scene = equal_steel(alphas[0])
        rows = [run(scene, level, args.mu, args.ratio, args.axis[0], args.ramp_steps,
                    args.out / f"level-{level}", command) for level in args.levels]
        rates = study_rates(rows)
        text = (f"Refinement study of {scene.name}, load along the {args.axis[0]} axis, "
                f"mu = {args.mu:g}, Q*/(mu P) = {args.ratio:g}, levels {args.levels} "
                f"(every element size divided by {LEVEL_RATIO:.3g} per level); "
                f"observed rates (slope of log|error| against log h): "
                + ", ".join(f"{dict(COLUMNS)[k]} {v:.2f}" for k, v in rates.items())
                + f"; {time.perf_counter() - t0:.0f} s on {cpu_count()} cores; "
                f"`{command}`.\n\n" + table(rows) + "\n")
        (args.out / "study.json").write_text(json.dumps(
            {"rows": rows, "rates": rates, "command": command}, indent=1, default=float))
        (args.out / "study.md").write_text(text + "\n" + LEGEND + "\n")
        plot_study(rows, args.out / "study.png")
        print(text)
        if args.readme:
            publish("fem-friction-study", text,
                    [(args.out / "study.png", f"{scene.name}_friction_study.png")])
        return 0
    level = DEFAULT_LEVEL if args.level is None else args.level
    rows = [run(equal_steel(a), level, args.mu, args.ratio, axis, args.ramp_steps,
                args.out, command) for a in alphas for axis in args.axis]
    text = (f"Level {level} (grid spacing {LEVEL_H0[level]:.3g} b at the contact), "
            f"mu = {args.mu:g}, Q*/(mu P) = {args.ratio:g}, {args.ramp_steps} ramp steps; "
            f"{time.perf_counter() - t0:.0f} s in all on {cpu_count()} cores; "
            f"`{command}`.\n\n" + table(rows) + "\n")
    (args.out / "friction.json").write_text(json.dumps(
        {"rows": rows, "command": command}, indent=1, default=float))
    (args.out / "friction.md").write_text(text + "\n" + LEGEND + "\n")
    print(text)
    if args.readme:
        publish("fem-friction", text,
                [(args.out / f"{r['scene']}-{r['axis']}" / "grade.png",
                  f"{r['scene']}-{r['axis']}_friction.png") for r in rows])
    failed = [f"{r['scene']} ({', '.join(r['failed'])})" for r in rows if not r["passed"]]
    if failed:
        log.warning("failed: %s", "; ".join(failed))
        return 1
    return 0
