"""``python -m fem_validation grade --history PATH.csv`` without ``--tangential``: a DEM
code's tangential force-displacement history graded from the history alone.

    python -m fem_validation grade --history PATH.csv --scene FILE.toml [--mu MU]
        [--normal-force N] [--law mindlin-deresiewicz|linear-capped|mindlin|
        mindlin_rescale|mindlin/force|mindlin_rescale/force] [--driven auto|displacement|force]
        [--units SI|mm] [--tolerance NAME=VALUE ...] --out DIR

Hooked into :mod:`fem_validation.cli.grade` (its options by :func:`add_options`, its run
by :func:`run_history`); writes DIR/grade.json, .md, .png
(:mod:`fem_validation.reports.tangential_history`).  Exit status 0 every check passed, 1
one failed, 2 bad input (one line naming the file, the line or the option), 3 an
internal error.
"""

from __future__ import annotations

import warnings

from .common import UsageError, out_dir, require, small_input

__all__ = ["add_options", "history_only", "run_history"]

#: grade's options that apply to a history alone; any other given (another mode's) is
#: refused, whichever mode added it.
FOR_HISTORY = {"history", "tangential", "scene", "mu", "normal_force", "law", "driven",
               "units", "tolerance", "tolerances", "out", "overwrite", "debug"}
#: What an option left out reads as (argparse's defaults of grade's options).
UNSET = (None, False, [], "auto")


def add_options(p) -> None:
    """The options of the history-only mode, on grade's parser."""
    from ..grading.tangential_history import LAWS

    h = p.add_argument_group("a DEM history alone (--history without --tangential)")
    h.add_argument("--law", choices=LAWS, metavar="LAW",
                   help="the tangential law the code claims: mindlin-deresiewicz (default, "
                        "the physics), linear-capped (k = 8 G* a, |Q| <= mu P; constant P), "
                        "or LAMMPS's mindlin, mindlin_rescale, mindlin/force, "
                        "mindlin_rescale/force; the verdict is on it, the distance to "
                        "Mindlin-Deresiewicz is reported")
    h.add_argument("--driven", choices=("auto", "displacement", "force"),
                   help="the history's driving quantity (default auto: detected from the "
                        "steps); the reference is taken at it")


def history_only(args) -> bool:
    """Whether the command line asks for the history-only mode; refuses this mode's
    options in another mode."""
    mine = args.history is not None and args.tangential is None
    if not mine:
        given = [f"--{k}" for k in ("law", "driven") if getattr(args, k, None) is not None]
        if given:
            raise UsageError(f"python -m fem_validation grade: {', '.join(given)} only "
                             f"apply to --history PATH.csv without --tangential")
    return mine


def run_history(args, argv, tolerances_from, grade_files) -> int:
    """Read, grade, write; the exit status (errors raised as ValueError).

    ``tolerances_from(args, defaults, metrics)`` and ``grade_files`` (the files an earlier
    grade wrote) are grade's own (:mod:`fem_validation.cli.grade`), handed in so that this
    module does not import it back."""
    given = ["a RESULT file" if k == "result" else "--" + k.replace("_", "-")
             for k, v in sorted(vars(args).items())
             if k not in FOR_HISTORY and not any(v is u or v == u for u in UNSET)]
    if given:
        raise UsageError(f"python -m fem_validation grade: {', '.join(given)} do(es) not "
                         f"apply to --history PATH.csv alone (a DEM history: columns "
                         f"displacement, force[, normal_force])")
    small_input(args.history, "--history", limit=1 << 62)
    require(["matplotlib"], "grade (its grade.png)")
    import hertz

    from ..grading import tangential_history as gh
    from ..readers.history_csv import read_dem_history
    from ..reports.tangential_history import write_grade
    from ..scenes import scene_from_toml

    tol = tolerances_from(args, gh.DEFAULT_TOLERANCES, gh.METRICS)
    out = out_dir(args.out, args.overwrite, grade_files)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        scene = scene_from_toml(args.scene)
    history = read_dem_history(args.history, units=args.units, mu=args.mu,
                               normal_force=args.normal_force, default_normal_force=scene.load)
    driven = None if args.driven in (None, "auto") else args.driven
    g = gh.grade_history(history, scene, tol, law=args.law or "mindlin-deresiewicz",
                         driven=driven)
    command = " ".join(["python -m fem_validation grade", *argv])
    json_path, md_path, png_path = write_grade(g, out, command)
    print(f"{g.summary}; wrote {json_path}, {md_path}, {png_path}")
    return 0 if g.passed else 1
