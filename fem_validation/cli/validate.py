"""python -m fem_validation: validate hertz against finite elements, grade other codes.

    python -m fem_validation --help                # every mode, with an example each
    python -m fem_validation validate --out DIR    # the five default scenes, level 4 (minutes)
    python -m fem_validation --alpha 2 7 --level 2 # equal steel bodies, alpha = 2 and 7
    python -m fem_validation --scene crossed-30deg --out DIR
    python -m fem_validation --study alpha-3 --levels 1 2 3 4 5
    python -m fem_validation --curved --out DIR    # a ball on a plane and in a groove
    python -m fem_validation --curved --level 2 --a-over-r 0.01 0.2 --out DIR
    python -m fem_validation --curved --levels 3 4 --out DIR  # two levels, one table
    python -m fem_validation grade RESULT --scene FILE.toml --out DIR   # another code's result
    python -m fem_validation deck --scene FILE.toml --format calculix --out DIR  # a deck for one
    python -m fem_validation friction --out DIR   # Coulomb friction against Cattaneo-Mindlin

A bare ``python -m fem_validation`` prints the help (exit 0) rather than start the
default validation, which ``validate`` (or any of its options) runs.

Writes DIR/report.json, DIR/report.md, <scene>_body1.vtu, <scene>_body2.vtu and
<scene>_pressure.png per scene (a study writes study.json, study.md and
study.png; --curved writes curved.json, curved.md and curved.png, at the
levels 0-4 of fem_validation.solvers.curved_mesh, default 3); with --readme also the
tables of the documentation (docs/explanation/fem-model.md, curved-bodies.md)
and docs/fem/*.png.  Errors (usage, conflicting flags, an
--out that cannot be written or is not empty without --overwrite, an alpha the
meshes do not support, --readme outside a checkout, a missing optional package)
print one line on stderr and exit with status 2, before anything runs; an internal
error prints one line and exits 3 (``--debug``: its traceback; see
:mod:`fem_validation.cli.common`).  ``grade``: see :mod:`fem_validation.cli.grade`;
``deck``: :mod:`fem_validation.decks`; ``friction``: :mod:`fem_validation.cli.friction`.
Every mode runs with numpy and scipy alone as far as ``--help``; a run that needs the
fem extra says which package is missing.
"""

from __future__ import annotations

import json
import logging
import time
from os import cpu_count
from pathlib import Path

from ..reports.docs import publish, readme_section
from ..scenes import MAX_ALPHA, NAMED, equal_steel
from .common import (
    FEM_RUN,
    OneLineParser,
    Unknown,
    UsageError,
    add_overwrite,
    choices,
    fem_constants,
    out_dir,
    positive,
    require,
)

log = logging.getLogger("fem_validation")


def _alpha(alpha: float, what: str = "--alpha") -> float:
    """An alpha the block meshes support, else a one-line ValueError saying the range."""
    if not 1 <= alpha <= MAX_ALPHA:
        raise ValueError(f"{what} {alpha:g}: the block meshes support 1 <= alpha <= "
                         f"{MAX_ALPHA:g} (see fem_validation.scenes.MAX_ALPHA)")
    return alpha


def _scene(name: str):
    if name.startswith("alpha-"):
        try:
            alpha = float(name.removeprefix("alpha-"))
        except ValueError:
            raise ValueError(f"scene {name!r}: alpha-<A> needs a number A") from None
        return equal_steel(_alpha(alpha, f"scene {name!r}: alpha"))
    if name in NAMED:
        return NAMED[name]()
    raise ValueError(f"unknown scene {name!r}: use alpha-<A>, {', '.join(NAMED)}")


#: Every mode with one example, the end of ``python -m fem_validation --help``.
MODES = """\
modes (python -m fem_validation MODE --help for each):
  validate        the five default scenes on block meshes at level 4 (a few minutes
                  on two cores, up to 2.5 GB; a bare python -m fem_validation only
                  prints this help)
                    python -m fem_validation validate --out DIR
  --alpha/--scene chosen scenes (the options above, with or without 'validate')
                    python -m fem_validation --alpha 3 --level 0 --out DIR
  --study         a mesh-refinement study of one scene
                    python -m fem_validation --study alpha-3 --levels 1 2 3 --out DIR
  --curved        true curved bodies: a ball on a plane and in a groove
                    python -m fem_validation --curved --level 2 --out DIR
  grade           grade another code's result (or a DEM force-approach curve)
                    python -m fem_validation grade RESULT --scene FILE.toml --out DIR
  deck            write a benchmark deck (CalculiX, Abaqus, meshes) for another code
                    python -m fem_validation deck --scene FILE.toml --format calculix --out DIR
  friction        Coulomb friction on the blocks against Cattaneo-Mindlin
                    python -m fem_validation friction --alpha 3 --level 2 --out DIR

exit status: 0 done, 1 a check failed, 2 bad input (one line), 3 internal error
(one line; --debug for the traceback), 130 interrupted."""


def _parser(prog: str = "python -m fem_validation") -> OneLineParser:
    c, note = fem_constants({
        "solvers.mesh": ("DEFAULT_LEVEL", "LEVEL_RATIO", "LEVEL_SCALE"),
        "solvers.curved_mesh": ("DEFAULT_CURVED_LEVEL",), "runs.curved": ("A_OVER_R",),
        "solvers.solve": ("INITIAL_ACTIVE", "REBUILD_FRACTION"),
        "runs.study": ("DEFAULT_LEVELS",),
        "runs.validate": ("NESTED_REBUILD_FRACTION",)})

    def listed(values) -> str:
        return " ".join(map(str, values)) if isinstance(values, list | tuple) else "?"

    initial = c["INITIAL_ACTIVE"]
    p = OneLineParser(prog=prog, epilog=MODES,
                      description="Finite-element validation of hertz, and graders and decks "
                                  "for other codes." + note)
    p.add_argument("--alpha", type=float, nargs="+", metavar="A",
                   help="equal steel bodies with curvature ratio A (repeatable)")
    p.add_argument("--scene", nargs="+", metavar="NAME", default=[],
                   help=f"named scenes: alpha-<A>, {', '.join(NAMED)}")
    p.add_argument("--level", type=int, default=None, choices=choices(c["LEVEL_SCALE"]),
                   help=f"mesh level (default {c['DEFAULT_LEVEL']}; with --curved 0-4, "
                        f"default {c['DEFAULT_CURVED_LEVEL']}); each level divides every "
                        f"element size by {c['LEVEL_RATIO']:.3g}")
    p.add_argument("--curved", action="store_true",
                   help="true curved bodies: a steel ball on a flat block and in a groove "
                        "(R_g = 1.04 R) at several loads; curved.json, .md, .png")
    p.add_argument("--a-over-r", type=positive, nargs="+", default=None, metavar="X",
                   help="with --curved: target Hertz semi-major axis over the ball radius "
                        f"(default {listed(c['A_OVER_R'])})")
    p.add_argument("--study", metavar="NAME", help="mesh-refinement study of one scene")
    p.add_argument("--levels", type=int, nargs="+", default=None,
                   help=f"consecutive levels of the study (default "
                        f"{listed(c['DEFAULT_LEVELS'])}); with --curved, the levels "
                        f"to run (instead of --level)")
    p.add_argument("--initial-active", default="hertz",
                   choices=None if isinstance(initial, Unknown) else (*initial, "nested"),
                   help="first active set of the contact iteration (default: Hertz's ellipse)")
    p.add_argument("--amg-rebuild", type=float, default=None, metavar="FRACTION",
                   help="rebuild the AMG preconditioner when more than FRACTION of the active "
                        f"pairs changed since its setup (default {c['REBUILD_FRACTION']}, "
                        f"{c['NESTED_REBUILD_FRACTION']} for a nested start's fine solve; "
                        "inf: once)")
    p.add_argument("--out", type=Path, default=Path("fem_out"), help="output directory")
    add_overwrite(p)
    p.add_argument("--readme", action="store_true",
                   help="also put the table (or the study) into its documentation page and "
                        "the plots into docs/fem/ (run from the repository root)")
    p.add_argument("--quiet", action="store_true", help="log warnings only")
    return p


def _conflicts(args) -> None:
    """Refuse flags that the chosen run would silently ignore."""
    given = {"--curved": args.curved, "--study": args.study is not None,
             "--alpha": args.alpha is not None, "--scene": bool(args.scene),
             "--a-over-r": args.a_over_r is not None, "--level": args.level is not None,
             "--levels": args.levels is not None,
             "--initial-active": args.initial_active != "hertz",
             "--amg-rebuild": args.amg_rebuild is not None}
    pairs = [("--curved", "--study"), ("--curved", "--alpha"), ("--curved", "--scene"),
             ("--study", "--alpha"), ("--study", "--scene"), ("--study", "--level"),
             ("--curved", "--initial-active"), ("--curved", "--amg-rebuild"),
             ("--level", "--levels")]
    for a, b in pairs:
        if given[a] and given[b]:
            raise UsageError(f"{a} and {b} cannot be combined")
    if given["--a-over-r"] and not args.curved:
        raise UsageError("--a-over-r applies to --curved only")
    if given["--levels"] and not (args.curved or args.study):
        raise UsageError("--levels applies to --study and --curved only (use --level)")
    if given["--amg-rebuild"] and not args.amg_rebuild > 0:  # NaN fails too
        raise UsageError(f"--amg-rebuild must be a fraction > 0 (inf: build once), got "
                         f"{args.amg_rebuild!r}")


def _validate(argv: list[str], prog: str = "python -m fem_validation") -> int:
    """The validation modes (default scenes, --alpha/--scene, --study, --curved)."""
    args = _parser(prog).parse_args(argv)
    _conflicts(args)
    require(FEM_RUN, "the finite-element validation")
    from ..reports.blocks import report_markdown, write_reports
    from ..runs.curved import A_OVER_R, run_curved
    from ..runs.study import DEFAULT_LEVELS, refinement_study
    from ..runs.validate import validate
    from ..scenes import default_scenes
    from ..solvers.curved_mesh import CURVED_LEVELS, DEFAULT_CURVED_LEVEL
    from ..solvers.mesh import DEFAULT_LEVEL, LEVEL_H0

    for alpha in args.alpha or []:
        _alpha(alpha)
    if args.curved:
        levels = ([DEFAULT_CURVED_LEVEL] if args.level is None and args.levels is None
                  else args.levels or [args.level])
        bad = [x for x in levels if x not in CURVED_LEVELS]
        if bad:
            raise UsageError(f"--curved: levels must be in {list(CURVED_LEVELS)}, got {bad}")
        if args.readme:
            raise UsageError("--readme does not apply to --curved: merge curved.md and "
                             "curved.png by hand")
    scenes = None
    if not args.curved and not args.study:
        scenes = [equal_steel(a) for a in args.alpha or []] + [_scene(n) for n in args.scene]
    elif args.study:
        study_scene = _scene(args.study)
    if args.readme:
        readme_section("fem-study" if args.study else "fem-validation")
    out_dir(args.out, args.overwrite)
    logging.basicConfig(level=logging.WARNING if args.quiet else logging.INFO,
                        format="%(asctime)s %(message)s", datefmt="%H:%M:%S")
    logging.getLogger("skfem").setLevel(logging.ERROR)
    command = " ".join([prog, *argv])
    if args.curved:
        _, json_path, md_path, png_path = run_curved(
            args.out, levels, A_OVER_R if args.a_over_r is None else args.a_over_r, command)
        print(md_path.read_text())
        log.info("wrote %s, %s and %s", json_path, md_path, png_path)
        return 0
    if args.level is None:
        args.level = DEFAULT_LEVEL
    if args.levels is None:
        args.levels = list(DEFAULT_LEVELS)
    if args.study:
        study = refinement_study(study_scene, args.levels, args.out, command=command)
        print(json.dumps({k: study[k] for k in ("rates", "extrapolated", "three_level")},
                         indent=1))
        if args.readme:
            publish("fem-study", study["readme"],
                    [(args.out / "study.png", f"{study['scene']}_study.png")])
        return 0
    if not scenes:
        scenes = default_scenes()
        log.info("the default validation: %d scenes at level %d (a few minutes at level 4)",
                 len(scenes), args.level)
    t0 = time.perf_counter()
    results = [validate(s, args.level, args.out, initial_active=args.initial_active,
                        rebuild_fraction=args.amg_rebuild) for s in scenes]
    header = (f"Level {args.level} (grid spacing {LEVEL_H0[args.level]:.3g} b at the "
              f"contact); {time.perf_counter() - t0:.0f} s in all on {cpu_count()} cores; "
              f"`{command}`.\n")
    json_path, md_path = write_reports(results, args.out, header)
    print(report_markdown(results, header))
    if args.readme:
        publish("fem-validation", report_markdown(results, header),
                [(args.out / f"{r.scene}_pressure.png", f"{r.scene}_pressure.png")
                 for r in results])
    log.info("wrote %s, %s and the VTU/PNG files in %s", json_path, md_path, args.out)
    return 0
