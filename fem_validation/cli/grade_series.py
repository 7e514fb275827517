"""``python -m fem_validation grade --series RUN1 RUN2 RUN3 ... --scene S``: a mesh series.

    python -m fem_validation grade --series COARSE.frd MEDIUM.frd FINE.frd --scene FILE.toml
        [--units mm] [--symmetry quarter] [--expected-order P] --out DIR

Each result is read and graded as ``grade RESULT`` grades it (the same options apply to
every one); then each metric's observed order of convergence, its Richardson-extrapolated
value and the uncertainty of that value (:mod:`fem_validation.grading.series`) go to
DIR/grade.json (``"kind": "mesh series"``), grade.md and grade.png.  The mesh size of each
result is measured on its contact surface (:func:`fem_validation.grading.series.mesh_size`).
Exit status 0 where every result's own grade passed, 1 where one failed, 2 bad input.
"""

from __future__ import annotations

from pathlib import Path

from .common import UsageError, finite, out_dir, require

__all__ = ["add_options", "run_series", "series_mode"]

#: grade.py's options that mean nothing for a series.
NOT_FOR_SERIES = {"result": "a RESULT file", "force_approach": "--force-approach",
                  "tangential": "--tangential", "history": "--history", "force": "--force"}


def add_options(p) -> None:
    """The options of the series mode, on grade's parser."""
    s = p.add_argument_group("a mesh series (--series)")
    s.add_argument("--series", nargs="+", type=Path, metavar="RUN",
                   help="grade several results of one scene on finer and finer meshes "
                        "(at least 3 for an order): observed orders, Richardson "
                        "extrapolation and its uncertainty")
    s.add_argument("--expected-order", type=finite, metavar="P",
                   help="the order the method should reach (reported beside the observed)")


def series_mode(args) -> bool:
    """Whether the command line asks for a series; refuses its options elsewhere and
    the others' options with it."""
    if getattr(args, "series", None) is None:
        if getattr(args, "expected_order", None) is not None:
            raise UsageError("python -m fem_validation grade: --expected-order only applies "
                             "to --series")
        return False
    given = [words for key, words in NOT_FOR_SERIES.items()
             if getattr(args, key, None) is not None]
    if given:
        raise UsageError(f"python -m fem_validation grade: {', '.join(given)} do(es) not "
                         f"apply to --series RUN1 RUN2 ... (each run's force is its own)")
    if len(args.series) < 2:
        raise UsageError("python -m fem_validation grade: --series needs at least 2 results "
                         "(3 for an order)")
    if len({str(p.resolve()) for p in args.series}) != len(args.series):
        raise UsageError("python -m fem_validation grade: --series names a result twice")
    return True


def run_series(args, argv, tolerances_from, grade_files, analyst_fields, read_framed) -> int:
    """Read, grade, write the series; the exit status.  grade.py's own helpers come as
    arguments (this module is imported by grade.py, so it does not import it back)."""
    from ..grading.contact import DEFAULT_TOLERANCES, METRICS, grade
    from ..grading.series import grade_series, mesh_size
    from ..readers import read_result
    from ..reports.grade import write_series
    from ..results.contact import ResultError
    from ..scenes import scene_from_toml

    require(["matplotlib"], "grade --series (its grade.png)")
    out = out_dir(args.out, args.overwrite, grade_files)
    import warnings

    import hertz

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        scene = scene_from_toml(args.scene)
    tol = tolerances_from(args, DEFAULT_TOLERANCES, METRICS)
    grades, sizes = [], []
    for path in args.series:
        args.result = path
        fields = {k: v for k, v in (("pressure", args.pressure_field),
                                    ("normal_force", args.normal_force_field),
                                    ("reaction", args.reaction_field),
                                    ("stress", args.stress_field)) if v is not None}
        fields |= analyst_fields(args)

        def read(frame, path=path, fields=fields):
            return read_result(path, units=args.units, symmetry=args.symmetry, force=None,
                               frame=frame, fields=fields)
        result = read_framed(read, args, path)
        weight = result.pressure if result.pressure is not None else result.normal_force
        try:
            sizes.append(mesh_size(result.xy, result.triangles, weight))
        except ValueError as exc:
            raise ResultError(f"{path}: {exc}") from None
        grades.append(grade(result, scene, tol, semi_axes=args.semi_axes))
    args.result = None
    if len(set(sizes)) != len(sizes):
        raise UsageError(f"--series: two results have the same mesh size ({sizes}): a "
                         f"series needs different meshes")
    s = grade_series(grades, sizes, getattr(scene, "name", ""), args.expected_order)
    command = " ".join(["python -m fem_validation grade", *argv])
    json_path, md_path, png_path = write_series(s, grades, out, command)
    ok = all(s.passed)
    orders = ", ".join(f"{k} {c.order:.2f}" for k, c in s.metrics.items()
                       if k in ("a_rel_err", "p0_rel_err") and c.behaviour == "monotone")
    print(f"{'PASSED' if ok else 'FAILED'}: {len(grades)} meshes"
          + (f"; observed orders: {orders}" if orders else "")
          + f"; wrote {json_path}, {md_path}, {png_path}")
    return 0 if ok else 1
