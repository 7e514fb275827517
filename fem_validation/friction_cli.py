"""``python -m fem_validation friction``: Cattaneo-Mindlin and Mindlin-Deresiewicz by FEM.

    python -m fem_validation friction --out DIR            # alpha 1, 3, 10, default level
    python -m fem_validation friction --alpha 3 --axis minor --level 2 --out DIR
    python -m fem_validation friction --study alpha-1 --levels 1 2 3 4 --out DIR

Each run holds the scene's normal load, then moves body 1's loaded face along a
principal axis of the contact: a ramp to the displacement at which
Cattaneo-Mindlin gives Q = RATIO mu P, unloading to minus that and reloading
(:mod:`fem_validation.friction`).  The run becomes a
:class:`~fem_validation.tangential_result.TangentialResult` graded by
:func:`~fem_validation.grade_tangential.grade_tangential`, the grader every
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

from .cli_common import (
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
from .limits import read_small_text
from .scenes import MAX_ALPHA, equal_steel

log = logging.getLogger("fem_validation")

DEFAULT_ALPHAS = (1.0, 3.0, 10.0)
DEFAULT_MU = 0.3
#: Q*/(mu P) at the end of the ramp: the stick zone is then (0.2)^(1/3) = 0.58 of the
#: contact, so that both the stick ellipse and the slip annulus span many nodes.
DEFAULT_RATIO = 0.8
#: Ramp steps; unloading and reloading take twice as many each.  The loop energy's
#: trapezoid rule errs by about -1/m^2 with m steps per branch (-0.4% at 16).
DEFAULT_RAMP_STEPS = 8
DEFAULT_STUDY_LEVELS = (1, 2, 3, 4)
#: Metrics of the summary table: (key, header).
COLUMNS = (("stick_a_rel_err", "stick a"), ("stick_b_rel_err", "stick b"),
           ("force_rel_err_max", "Q(delta) ramp"), ("branch_err_max", "Q(delta) loop"),
           ("loop_energy_rel_err", "loop energy"), ("traction_rms_major", "q RMS major"),
           ("traction_rms_minor", "q RMS minor"), ("transverse_shear_max", "q transverse"))
RELATIVE = {"stick_a_rel_err", "stick_b_rel_err", "force_rel_err_max", "branch_err_max",
            "loop_energy_rel_err"}


def mesh_axis(scene, axis: str) -> str:
    """The mesh axis ("x" or "y") along the contact's ``axis`` ("major" or "minor")."""
    along_x = abs(np.cos(scene.hertz().major_axis_angle)) > 0.5
    return "x" if (axis == "major") == along_x else "y"


def run(scene, level: int, mu: float, ratio: float, axis: str, ramp_steps: int, out: Path,
        command: str = "") -> dict:
    """Mesh, solve, grade and write one frictional run; its report row."""
    from .friction import friction_mesh, friction_result, solve_friction
    from .grade_tangential import grade_tangential, write_grade

    t0 = time.perf_counter()
    mesh = friction_mesh(scene, level)
    sol = solve_friction(scene, mesh, mu, mesh_axis(scene, axis), ratio=ratio,
                         ramp_steps=ramp_steps)
    result = friction_result(scene, mesh, sol)
    g = grade_tangential(result, scene)
    seconds = time.perf_counter() - t0
    write_grade(g, out / f"{scene.name}-{axis}", command)
    c = scene.hertz(sol.normal.force)
    row = {"scene": scene.name, "level": level, "axis": axis, "alpha": float(c.alpha),
            "mu": mu, "load": sol.normal.force,
            "ratio": float(sol.force[sol.snapshot] / (mu * sol.normal.force)),
            "metrics": {k: v for k, v in g.metrics.items()}, "passed": g.passed,
            "failed": [ch.name for ch in g.checks if ch.passed is False],
            "dofs": sol.dofs, "steps": len(sol.steps),
            "iterations": int(sum(s.iterations for s in sol.steps)),
            "cg_iterations": int(sum(sum(s.cg_iterations) for s in sol.steps)),
            "amg_setups": sol.amg_setups, "coupling_pressure_over_p0":
            sol.coupling_pressure / c.p0, "seconds": seconds,
            "h0_over_b": mesh.h0 / scene.hertz().b, "command": command}
    (out / f"{scene.name}-{axis}" / "row.json").write_text(json.dumps(row, indent=1,
                                                                      default=float))
    return row


#: The largest grade.json, row.json or report --collect reads [bytes] (ours hold a few
#: hundred kB).
MAX_COLLECT_BYTES = 64 << 20


def _json(path: Path):
    return json.loads(read_small_text(path, "--collect: file", MAX_COLLECT_BYTES))


def row_from_grade(directory: Path) -> dict:
    """A report row from a run's directory: its grade.json (the metrics, the force, the
    command) and, when the run wrote it, row.json (the solver's counts and time).

    Raises
    ------
    ValueError
        Naming the file: it cannot be read, is larger than MAX_COLLECT_BYTES, is not JSON
        or not the grade of a frictional run.
    """
    directory = Path(directory)
    path = directory / "grade.json"
    try:
        g = _json(path)
    except ValueError as exc:
        raise ValueError(f"--collect: cannot read {path}: {exc}") from None
    if not isinstance(g, dict) or g.get("kind") != "tangential":
        raise ValueError(f"--collect: {path} is not a tangential grade")
    axis = directory.name.rsplit("-", 1)[-1]
    try:
        level = int(g["source"].rsplit("level ", 1)[-1])
        solver = {}
        if (directory / "row.json").is_file():
            path = directory / "row.json"
            solver = _json(path)
        else:  # a run made before rows were kept beside the grade: its report's row
            for report in (directory.parent / "friction.json",
                           directory.parent.parent / "study.json"):
                if report.is_file():
                    path = report
                    solver = next((r for r in _json(report)["rows"]
                                   if (r["scene"], r["axis"], r["level"])
                                   == (g["scene"], axis, level)), {})
                    break
        return {"scene": g["scene"], "level": level, "axis": axis,
                "load": g["normal_force"], "ratio": g["fem"]["snapshot_force_ratio"],
                "metrics": {c["name"]: c["value"] for c in g["checks"]},
                "passed": g["passed"], "command": g.get("command", ""),
                **{k: solver.get(k) for k in ("dofs", "iterations", "seconds")}}
    except (KeyError, TypeError, AttributeError, IndexError, ValueError) as exc:
        raise ValueError(f"--collect: {path} is not what a friction run writes "
                         f"({type(exc).__name__}: {exc})"[:300]) from None


def _cell(key: str, value) -> str:
    if value is None or not np.isfinite(value):
        return "-"
    return f"{100 * value:+.2f}%" if key in RELATIVE else f"{100 * value:.2f}%"


def table(rows: list[dict]) -> str:
    """The summary table of report rows (markdown)."""
    head = ["scene", "level", "load along", "P [N]", "Q*/(mu P)",
            *[h for _, h in COLUMNS], "dofs", "solves", "s"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        cells = [r["scene"], str(r["level"]), r["axis"], f"{r['load']:.4g}",
                 f"{r['ratio']:.3f}", *[_cell(k, r["metrics"].get(k)) for k, _ in COLUMNS],
                 *[("-" if r.get(k) is None else f"{r[k]:.0f}")
                   for k in ("dofs", "iterations", "seconds")]]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


LEGEND = (
    "Errors are (FEM - reference)/reference, the reference being Cattaneo-Mindlin and "
    "Mindlin-Deresiewicz (hertz) at the normal force P the FEM reached.  stick a, b: the "
    "stick ellipse's semi-axes from a fit of (mu p - q)^2 at the end of the ramp (tolerance "
    "2%); Q(delta) ramp: largest relative error of the force at the displacement on the "
    "ramp (1%); Q(delta) loop: largest error on the unloading and reloading branches over "
    "Q* (1%); loop energy: the trapezoid area of the loop against Mindlin-Deresiewicz's "
    "energy per cycle (3%); q RMS: the shear along the load on the major and minor axes "
    "against Cattaneo-Mindlin, over mu p0 (3%); q transverse: the largest shear across "
    "the load over mu p0 (information: Mindlin's solution has none); solves: linear "
    "solves over the whole path.")


def study_rates(rows: list[dict]) -> dict:
    """Observed rates: slopes of log|error| against log(element size) per metric."""
    h = np.array([r["h0_over_b"] for r in rows])
    rates = {}
    for key, _ in COLUMNS[:7]:
        err = np.array([abs(r["metrics"].get(key, np.nan)) for r in rows])
        ok = np.isfinite(err) & (err > 0)
        if ok.sum() >= 2:
            rates[key] = float(np.polyfit(np.log(h[ok]), np.log(err[ok]), 1)[0])
    return rates


def plot_study(rows: list[dict], path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    h = np.array([r["h0_over_b"] for r in rows])
    fig, ax = plt.subplots(figsize=(6, 4))
    for key, header in COLUMNS[:7]:
        err = np.array([abs(r["metrics"].get(key, np.nan)) for r in rows])
        ax.loglog(h, 100 * err, "o-", label=header)
    ax.set_xlabel("grid spacing h0 / b")
    ax.set_ylabel("|error| [%] (RMS: % of mu p0)")
    ax.set_title(f"{rows[0]['scene']}, load along the {rows[0]['axis']} axis")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _parser() -> OneLineParser:
    c, note = fem_constants({"mesh": ("DEFAULT_LEVEL", "LEVEL_SCALE")})
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
    from .mesh import LEVEL_SCALE

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
    check failed, 2 bad input, 3 an internal error; :func:`fem_validation.cli_common.guarded`)."""
    return guarded("fem_validation friction", _main, list(argv))


def _main(argv: list[str]) -> int:
    from .__main__ import publish, readme_section

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
    from .mesh import DEFAULT_LEVEL, LEVEL_H0, LEVEL_RATIO

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
