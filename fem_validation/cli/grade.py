"""``python -m fem_validation grade``: grade another code's result file against Hertz.

    python -m fem_validation grade RESULT --scene FILE.toml [--units mm]
        [--symmetry quarter] [--force N] [--tolerance NAME=VALUE ...] --out DIR
    python -m fem_validation grade --force-approach CURVE.csv --scene FILE.toml --out DIR
    python -m fem_validation grade --tangential SURFACE.csv --history PATH.csv --mu 0.3
        --scene FILE.toml [--direction-deg 0] [--normal-force N] [--symmetry quarter]
        [--snapshot INDEX] --out DIR
    python -m fem_validation grade --tangential RUN/hertz.frd --scene FILE.toml --out DIR
    python -m fem_validation grade --history PATH.csv --scene FILE.toml [--mu MU] [--law LAW]
        [--driven auto] --out DIR     (a DEM history alone: cli/grade_history.py)
    python -m fem_validation grade --impact RUN.csv --scene FILE.toml --mass M --speed V
        [--damping LAW:VALUE] [--mu MU --angle-deg A] --out DIR  (cli/grade_impact.py)

Writes DIR/grade.json, DIR/grade.md and DIR/grade.png (``--tangential``: a frictional
result against Cattaneo-Mindlin and Mindlin-Deresiewicz,
:mod:`fem_validation.grading.tangential`; a CalculiX .frd of a ``deck --friction`` run
is read by :mod:`fem_validation.readers.calculix_friction`, path and all).  Exit status 0 when every
check passes, 1 when one fails, 2 for bad input (one line on stderr naming the
file and the field), 3 for an internal error (a defect: one line, ``--debug`` for the
traceback), so that other projects can run it in their CI.  A re-run replaces an
earlier grade in DIR; a DIR holding other files needs ``--overwrite``.
"""

from __future__ import annotations

import math
import re
import sys
import tomllib
import warnings
from pathlib import Path

from ..grading.contact import CURVE_METRICS, CURVE_TOLERANCES, DEFAULT_TOLERANCES, METRICS
from ..limits import read_small_text
from .common import (
    OneLineParser,
    UsageError,
    add_overwrite,
    direction,
    finite,
    guarded,
    index,
    out_dir,
    positive,
    require,
    small_input,
    vector,
)

__all__ = ["OneLineParser", "UsageError", "main", "parser", "run", "tolerances_from"]

#: The files a grade writes: an earlier grade's are replaced without --overwrite.
GRADE_FILES = ("grade.json", "grade.md", "grade.png")


def parser() -> OneLineParser:
    p = OneLineParser(prog="python -m fem_validation grade",
                      description="Grade a contact result of any finite-element code (or a "
                                  "DEM force-approach curve) against Hertz.",
                      epilog="examples:\n"
                             "  python -m fem_validation grade RUN/hertz.frd --scene FILE.toml "
                             "--units mm --out DIR\n"
                             "  python -m fem_validation grade --force-approach CURVE.csv "
                             "--scene FILE.toml --out DIR\n"
                             "  python -m fem_validation grade --tangential SURFACE.csv "
                             "--history PATH.csv --mu 0.3 --scene FILE.toml --out DIR\n\n"
                             "exit status: 0 every check passed, 1 one failed, 2 bad input "
                             "(one line), 3 internal error (one line; --debug for the "
                             "traceback)")
    p.add_argument("result", nargs="?", type=Path,
                   help="result file: .csv (x, y, p), .frd (CalculiX), or any meshio format "
                        "(.vtu, .xdmf, .exo, .med, ...)")
    p.add_argument("--scene", type=Path, required=True, metavar="FILE.toml",
                   help="the two bodies: a hertz TOML scene file (SI)")
    p.add_argument("--force-approach", type=Path, metavar="CURVE.csv",
                   help="grade a normal force against approach curve (columns approach, "
                        "force) instead of a result file")
    t = p.add_argument_group("a frictional result (--tangential)")
    t.add_argument("--tangential", type=Path, metavar="SURFACE.csv|RUN.frd",
                   help="grade a frictional result against Cattaneo-Mindlin and "
                        "Mindlin-Deresiewicz: the contact surface at one state (columns x, y, "
                        "z, p, qx, qy[, stick]; needs --history), or the .frd of a CalculiX "
                        "run of 'deck --friction' (its .inp and problem.json beside it; the "
                        "path is read from the increments)")
    t.add_argument("--history", type=Path, metavar="PATH.csv",
                   help="the tangential path (columns displacement, force), from the "
                        "unloaded state: ramp, unloading, reloading; alone (without "
                        "--tangential): a DEM code's history graded by itself (columns "
                        "displacement, force[, normal_force]; --law, --driven)")
    t.add_argument("--mu", type=positive, help="coefficient of friction (default: the "
                                                "surface file's '# mu' line)")
    t.add_argument("--direction-deg", type=finite, metavar="DEG",
                   help="the load's angle from body 1's x axis [deg] (default: the file's "
                        "'# direction_deg' line, else 0)")
    t.add_argument("--normal-force", type=positive, metavar="N",
                   help="normal force of the model in the file (a quarter model's own), in "
                        "the file's force unit (default: the file's '# normal_force' line, "
                        "else the scene's load, whole contact)")
    t.add_argument("--snapshot", type=index, metavar="INDEX",
                   help="path index of the surface's state (default: the file's '# "
                        "snapshot' line, else the first reversal)")
    p.add_argument("--units", choices=("SI", "m", "mm"),
                   help="units of the file: SI (m, N, Pa) or mm (mm, N, MPa); default SI or "
                        "the CSV's '# units' line")
    p.add_argument("--symmetry", choices=("whole", "half", "quarter"),
                   help="the model in the file (default: detected)")
    p.add_argument("--force", type=positive, metavar="N",
                   help="total normal force of the model in the file (a quarter model's own "
                        "reaction), in the file's force unit; default from the file")
    for role in ("pressure", "normal-force", "reaction", "stress"):
        p.add_argument(f"--{role}-field", metavar="NAME[:COMPONENT]",
                       help=f"name of the {role.replace('-', ' ')} field (default: recognised)")
    p.add_argument("--columns", metavar="ROLE=NAME,...",
                   help="a CSV's columns by role: x, y, z, p, f, active (e.g. "
                        "x=x_m,y=y_m,p=p_pa; a unit in the name sets the units)")
    p.add_argument("--body1", metavar="NAME",
                   help="a .frd's body 1: an element set or material of the deck (default: "
                        "two materials, else the mesh's two connected parts)")
    p.add_argument("--origin", type=vector, metavar="X,Y,Z",
                   help="contact point in the file's coordinates, in --units (default: found; "
                        "what is not given of origin, normal, x axis is found)")
    p.add_argument("--normal", type=direction, metavar="X,Y,Z",
                   help="contact normal pointing into body 1 (default: found, along +z)")
    p.add_argument("--x-axis", type=direction, metavar="X,Y,Z",
                   help="body 1's x axis in the contact plane (default: the file's x axis)")
    p.add_argument("--semi-axes", choices=("auto", "moments", "fit"), default="auto",
                   help="a, b from the moments of the nodal forces or from the p^2 fit "
                        "(default: moments where nodal forces are given, else the fit)")
    p.add_argument("--tolerance", action="append", default=[], metavar="NAME=VALUE",
                   help="override a tolerance (repeatable), e.g. p0_rel_err=0.01")
    p.add_argument("--tolerances", type=Path, metavar="FILE.toml",
                   help="tolerances from a TOML file (NAME = VALUE lines)")
    # mode hooks (parser): each grade mode in its own module adds its options here
    from .grade_history import add_options as _history_options  # --history alone

    _history_options(p)
    from .grade_impact import add_arguments as _impact_options  # --impact

    _impact_options(p)
    from .grade_series import add_options as _series_options  # --series RUN1 RUN2 ...

    _series_options(p)
    from .grade_plane import add_options as _plane_options  # --model plane-strain|axisymmetric

    _plane_options(p)
    p.add_argument("--out", type=Path, default=Path("grade_out"), help="output directory")
    add_overwrite(p, "an earlier grade's grade.json, .md and .png are replaced without it")
    return p


def tolerances_from(args, defaults: dict, metrics: dict) -> dict:
    """The defaults, then the TOML file, then --tolerance NAME=VALUE."""
    tol = dict(defaults)
    if args.tolerances is not None:
        text = read_small_text(args.tolerances, "tolerances file")
        try:
            table = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            raise UsageError(f"tolerances file {str(args.tolerances)!r} is not valid TOML: "
                             f"{exc}") from None
        except RecursionError:
            raise UsageError(f"tolerances file {str(args.tolerances)!r} is nested too deeply "
                             "to read") from None
        except ValueError:  # an integer beyond Python's limit on digits (4300)
            raise UsageError(_long_integer(text, args.tolerances)) from None
        for name, value in table.items():
            if isinstance(value, bool) or not isinstance(value, int | float):
                raise UsageError(f"tolerances file {str(args.tolerances)!r}: {name} must be "
                                 f"a number, got {value!r}")
            try:
                tol[name] = float(value)
            except OverflowError:  # an int beyond the largest float
                raise UsageError(f"tolerances file {str(args.tolerances)!r}: {name} must be a "
                                 f"finite number > 0, got an integer of about "
                                 f"{int(value.bit_length() * math.log10(2)) + 1} digits, "
                                 f"beyond the range of floating-point numbers") from None
    for item in args.tolerance:
        name, sep, value = item.partition("=")
        try:
            tol[name.strip()] = float(value)
        except ValueError:
            raise UsageError(f"--tolerance {item!r}: expected NAME=VALUE with a number") from None
        if not sep:
            raise UsageError(f"--tolerance {item!r}: expected NAME=VALUE")
    for name, value in tol.items():
        if name not in metrics:
            raise UsageError(f"tolerance {name!r}: unknown metric; known: "
                             f"{', '.join(sorted(metrics))}")
        if not (math.isfinite(value) and value > 0):
            raise UsageError(f"tolerance {name}: must be a finite number > 0, got {value!r}")
    return tol


def _long_integer(text: str, path) -> str:
    """The message for a TOML file that tomllib cannot read because an integer in it has
    more digits than Python converts (4300): the file, the line and the key."""
    limit = sys.get_int_max_str_digits() or 4300
    m = re.search(r"\d[\d_]{" + str(limit) + ",}", text)
    if m is None:
        return (f"tolerances file {str(path)!r}: a number too long to read (more than "
                f"{limit} digits)")
    start = text.rfind("\n", 0, m.start()) + 1
    line = text.count("\n", 0, m.start()) + 1
    key = text[start:m.start()].partition("=")[0].strip() or "?"
    digits = sum(ch.isdigit() for ch in m.group())
    return (f"tolerances file {str(path)!r}, line {line}: {key[:60]} = an integer of "
            f"{digits} digits, more than the {limit} a number may have: give a finite "
            f"number > 0")


def run(argv: list[str]) -> int:
    """Parse, grade, write; return the exit status (errors are raised as ValueError)."""
    args = parser().parse_args(argv)
    from ..grading.contact import grade, grade_force_approach
    from ..readers import read_result
    from ..readers.csv_file import read_force_approach
    from ..reports.grade import write_grade
    from ..scenes import scene_from_toml

    command = " ".join(["python -m fem_validation grade", *argv])
    # mode hooks (run): a mode in its own module returns its exit status here
    from .grade_history import history_only, run_history  # --history alone

    if history_only(args):
        return run_history(args, argv, tolerances_from, GRADE_FILES)
    if args.impact is not None:  # --impact
        from .grade_impact import run as run_impact

        return run_impact(args, argv, tolerances_from)
    from .grade_series import run_series, series_mode  # --series RUN1 RUN2 ...

    if series_mode(args):
        return run_series(args, argv, tolerances_from, GRADE_FILES, _analyst_fields,
                          _read_framed)
    from .grade_plane import plane_mode, run_plane  # --model plane-strain|axisymmetric

    plane = plane_mode(args)
    if plane is not None:
        return run_plane(args, argv, plane, tolerances_from, GRADE_FILES)
    inputs = [x for x in (args.result, args.force_approach, args.tangential) if x is not None]
    if len(inputs) != 1:
        raise UsageError("python -m fem_validation grade: give a RESULT file, "
                         "--force-approach CURVE.csv or --tangential SURFACE.csv (one of them)")
    friction = {"--history": args.history, "--mu": args.mu,
                "--direction-deg": args.direction_deg, "--normal-force": args.normal_force,
                "--snapshot": args.snapshot}
    frd = args.tangential is not None and args.tangential.suffix.lower() == ".frd"
    if frd:
        given = [k for k, v in (("--history", args.history), ("--direction-deg",
                                                             args.direction_deg),
                                ("--normal-force", args.normal_force)) if v is not None]
        if given:
            raise UsageError(f"python -m fem_validation grade: {', '.join(given)} do(es) not "
                             f"apply to --tangential RUN.frd (the .frd holds the path, the "
                             f"direction and the normal force)")
    if args.tangential is not None:
        if args.history is None and not frd:
            raise UsageError("python -m fem_validation grade: --tangential needs --history "
                             "PATH.csv (columns displacement, force)")
        normal_only = {"--force": args.force, "--pressure-field": args.pressure_field,
                       "--normal-force-field": args.normal_force_field,
                       "--reaction-field": args.reaction_field,
                       "--stress-field": args.stress_field}
        given = [k for k, v in normal_only.items() if v is not None]
        if args.semi_axes != "auto":
            given.append("--semi-axes")
        if given:
            raise UsageError(f"python -m fem_validation grade: {', '.join(given)} do(es) not "
                             f"apply to --tangential (the normal force: --normal-force)")
    else:
        given = [k for k, v in friction.items() if v is not None]
        if given:
            raise UsageError(f"python -m fem_validation grade: {', '.join(given)} only apply "
                             f"to --tangential SURFACE.csv")
    if args.force_approach is not None:
        small_input(args.force_approach, "--force-approach")
    require(["matplotlib"], "grade (its grade.png)")
    out = out_dir(args.out, args.overwrite, GRADE_FILES)
    import hertz

    with warnings.catch_warnings():
        # the scene's own load is only a default: a grade evaluates Hertz at the result's
        # force and notes there whether the contact is within Hertz's validity
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        scene = scene_from_toml(args.scene)
    if args.tangential is not None:
        from ..grading import tangential as gt
        from ..readers.tangential_csv import read_tangential
        from ..reports.tangential import write_grade as write_tangential_grade

        tol = tolerances_from(args, gt.DEFAULT_TOLERANCES, gt.METRICS)
        if frd:
            from ..readers.calculix_friction import read_calculix_tangential

            def read(frame):
                return read_calculix_tangential(args.tangential, units=args.units, mu=args.mu,
                                                symmetry=args.symmetry,
                                                snapshot=args.snapshot, frame=frame)
        else:
            def read(frame):
                return read_tangential(args.tangential, args.history, units=args.units,
                                       symmetry=args.symmetry, normal_force=args.normal_force,
                                       mu=args.mu, direction_deg=args.direction_deg,
                                       snapshot=args.snapshot, frame=frame,
                                       default_normal_force=scene.load)
        g = gt.grade_tangential(_read_framed(read, args, args.tangential), scene, tol)
        json_path, md_path, png_path = write_tangential_grade(g, out, command)
        print(f"{g.summary}; wrote {json_path}, {md_path}, {png_path}")
        return 0 if g.passed else 1
    if args.force_approach is not None:
        tol = tolerances_from(args, CURVE_TOLERANCES, CURVE_METRICS)
        approach, force, _ = read_force_approach(args.force_approach, args.units)
        g = grade_force_approach(approach, force, scene, tol, source=str(args.force_approach))
    else:
        tol = tolerances_from(args, DEFAULT_TOLERANCES, METRICS)
        fields = {k: v for k, v in (("pressure", args.pressure_field),
                                    ("normal_force", args.normal_force_field),
                                    ("reaction", args.reaction_field),
                                    ("stress", args.stress_field)) if v is not None}
        fields |= _analyst_fields(args)  # --columns (a CSV's), --body1 (a .frd's)

        def read(frame):
            return read_result(args.result, units=args.units, symmetry=args.symmetry,
                               force=args.force, frame=frame, fields=fields)
        g = grade(_read_framed(read, args, args.result), scene, tol, semi_axes=args.semi_axes)
    json_path, md_path, png_path = write_grade(g, out, command)
    print(f"{g.summary}; wrote {json_path}, {md_path}, {png_path}")
    return 0 if g.passed else 1


def _analyst_fields(args) -> dict:
    """``--columns`` (a CSV's columns by role) and ``--body1`` (a .frd's body 1) as the
    readers' ``fields``; each refused for a file it does not apply to."""
    from ..readers.csv_file import parse_columns

    suffix = args.result.suffix.lower()
    out = {}
    if args.columns is not None:
        if suffix != ".csv":
            raise UsageError(f"--columns applies to a .csv result, not {args.result.name}")
        try:
            out |= parse_columns(args.columns)
        except ValueError as exc:
            raise UsageError(str(exc)) from None
    if args.body1 is not None:
        if suffix != ".frd":
            raise UsageError(f"--body1 applies to a .frd (CalculiX) result, not "
                             f"{args.result.name}")
        out["body1"] = args.body1
    return out


def _frame(args, units: str | None, source) -> dict:
    """The frame given on the command line (a dict of the parts given, SI), the origin read
    in the length unit of ``units`` (the file's)."""
    from ..readers.common import units_of

    length = units_of(units or "SI")[0]
    return {k: v for k, v in (("origin", args.origin and [length * x for x in args.origin]),
                              ("normal", args.normal), ("x_axis", args.x_axis)) if v}


def _read_framed(read, args, source):
    """``read(frame)`` with the command line's frame; where ``--origin`` was given without
    ``--units`` and the file named its own units (a ``# units`` line, units in the column
    names, problem.json), read again with the origin in those units."""
    result = read(_frame(args, args.units, source))
    resolved = result.details.get("units")
    if args.origin and args.units is None and resolved not in (None, "SI"):
        result = read(_frame(args, resolved, source))
    return result


def main(argv=None) -> int:
    """Entry point of ``python -m fem_validation grade``: the exit status (0 passed, 1 a
    check failed, 2 bad input, 3 an internal error; :func:`fem_validation.cli.common.guarded`)."""
    argv = sys.argv[1:] if argv is None else list(argv)
    return guarded("fem_validation grade", run, argv)
