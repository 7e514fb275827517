"""``grade RESULT --scene S --model plane-strain|axisymmetric``: a 2-D result against Hertz.

    python -m fem_validation grade RUN/cyl.frd --scene roller.toml --out DIR
    python -m fem_validation grade line.csv --scene sphere.toml --model axisymmetric --out DIR

The mode is taken where ``--model`` is given, and found without it where the result is a
.frd whose deck (beside it) has CPE/CPS/CAX elements, a CSV with a ``# model`` line, or the
scene is a line contact (``load_per_length``, or both bodies cylinders along y).  Reading:
:mod:`fem_validation.readers.plane`; grading: :mod:`fem_validation.grading.plane`; files:
:mod:`fem_validation.reports.plane` (grade.json, grade.md, grade.png).  Exit status 0
passed, 1 a check failed, 2 bad input (one line).
"""

from __future__ import annotations

import re
from pathlib import Path

from ..results.plane import MODELS
from .common import UsageError, out_dir, require

__all__ = ["add_options", "plane_mode", "run_plane"]

#: Options of the 3-D grade that a 2-D one does not take.
_NOT_PLANE = (("force_approach", "--force-approach"), ("tangential", "--tangential"),
              ("symmetry", "--symmetry"), ("origin", "--origin"), ("normal", "--normal"),
              ("x_axis", "--x-axis"), ("normal_force_field", "--normal-force-field"),
              ("reaction_field", "--reaction-field"), ("stress_field", "--stress-field"))


def add_options(p) -> None:
    """``--model`` on the grade's parser."""
    p.add_argument("--model", choices=MODELS,
                   help="a 2-D result: plane strain (line contact; force per unit length) or "
                        "axisymmetric (point contact of bodies of revolution; x the radius). "
                        "Default: found from a .frd's deck (CPE/CPS/CAX), a CSV's '# model' "
                        "line or a line-contact scene")


def _csv_model(path: Path) -> str | None:
    """The ``# model = ...`` line of a CSV's first 50 lines, if any."""
    try:
        with open(path, encoding="utf-8-sig", errors="replace") as f:
            for _, line in zip(range(50), f, strict=False):
                m = re.match(r"^\s*\"?#\s*model\s*[=:]\s*([\w-]+)", line, re.IGNORECASE)
                if m:
                    return m.group(1).lower()
    except OSError:
        return None
    return None


def plane_mode(args) -> str | None:
    """The 2-D model of this grade, or None (a 3-D grade)."""
    if getattr(args, "model", None) is not None:
        return args.model
    result = getattr(args, "result", None)
    if result is None or getattr(args, "tangential", None) is not None:
        return None
    suffix = result.suffix.lower()
    if suffix == ".frd" and result.with_suffix(".inp").is_file():
        from ..readers.calculix_plane import element_model

        try:
            kind, _ = element_model(result.with_suffix(".inp"))
        except (OSError, ValueError):
            kind = None
        if kind is not None:
            return "plane-strain" if kind == "plane-stress" else kind
    if suffix == ".csv":
        found = _csv_model(result)
        if found in MODELS:
            return found
    scene = getattr(args, "scene", None)
    if scene is not None:
        try:
            from hertz._scene import read_scene

            data = read_scene(scene)
        except (OSError, ValueError):
            return None
        if "load_per_length" in data:
            return "plane-strain"
        radii = [(data.get(b, {}).get("Rx"), data.get(b, {}).get("Ry")) for b in
                 ("body1", "body2")]
        parallel = data.get("angle_deg", 0.0) == 0.0  # crossed cylinders touch at a point
        if parallel and all(ry == float("inf") for _, ry in radii) and any(
                rx is not None and rx != float("inf") for rx, _ in radii):
            return "plane-strain"
    return None


def run_plane(args, argv, model: str, tolerances_from, grade_files) -> int:
    """Read, grade and write a 2-D result; the exit status."""
    given = [flag for attr, flag in _NOT_PLANE if getattr(args, attr, None) is not None]
    if getattr(args, "semi_axes", "auto") != "auto":
        given.append("--semi-axes")
    if given:
        raise UsageError(f"python -m fem_validation grade --model {model}: "
                         f"{', '.join(given)} do(es) not apply to a 2-D result")
    if args.result is None:
        raise UsageError(f"python -m fem_validation grade --model {model}: give the RESULT "
                         f"file (.frd, .csv or a meshio 2-D mesh)")
    from ..grading.plane import DEFAULT_TOLERANCES, METRICS, grade_plane
    from ..readers.plane import read_plane_result
    from ..reports.plane import write_plane_grade
    from ..results.plane import plane_scene_from_toml

    command = " ".join(["python -m fem_validation grade", *argv])
    tol = tolerances_from(args, DEFAULT_TOLERANCES[model], METRICS[model])
    scene = plane_scene_from_toml(args.scene, model)
    fields = {}
    if getattr(args, "pressure_field", None) is not None:
        fields["pressure"] = args.pressure_field
    if getattr(args, "columns", None) is not None:
        if args.result.suffix.lower() != ".csv":
            raise UsageError(f"--columns applies to a .csv result, not {args.result.name}")
        from ..readers.csv_file import parse_columns

        fields |= parse_columns(args.columns)
    body1 = getattr(args, "body1", None)
    if body1 is not None and args.result.suffix.lower() != ".frd":
        raise UsageError(f"--body1 applies to a .frd (CalculiX) result, not "
                         f"{args.result.name}")
    result = read_plane_result(args.result, model=model, units=args.units, force=args.force,
                               fields=fields, radii=(scene.body1.Rx, scene.body2.Rx),
                               body1=body1)
    require(["matplotlib"], "grade (its grade.png)")
    out = out_dir(args.out, args.overwrite, grade_files)
    g = grade_plane(result, scene, tol)
    json_path, md_path, png_path = write_plane_grade(g, out, command)
    print(f"{g.summary}; wrote {json_path}, {md_path}, {png_path}")
    return 0 if g.passed else 1
