"""``python -m fem_validation grade --impact``: grade a DEM code's impact trajectory.

    python -m fem_validation grade --impact TRAJECTORY.csv --scene FILE.toml --mass M
        --speed V [--damping LAW:VALUE [--damping-attractive]] [--mu MU --angle-deg A]
        [--units SI|mm] [--tolerance NAME=VALUE ...] --out DIR

The trajectory (columns t, overlap, normal_force; optionally v_n; for an oblique impact
tangential_force, v_t, omega: :mod:`fem_validation.readers.impact_csv`) is graded by
:func:`fem_validation.grading.impact.grade_impact` against the exact impact of the
scene's bodies (:func:`fem_validation.grading.impact.impact_reference`), and
DIR/grade.json, grade.md and grade.png are written
(:mod:`fem_validation.reports.impact`).  Exit status 0 when every check passes, 1 when
one fails, 2 for bad input (one line), 3 for an internal error.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

from .common import UsageError, finite, out_dir, positive, require

__all__ = ["add_arguments", "run"]

#: The files a grade writes (an earlier grade's are replaced without --overwrite).
GRADE_FILES = ("grade.json", "grade.md", "grade.png")


def add_arguments(p) -> None:
    """The options of ``grade --impact`` (``--mu``, ``--units``, ``--tolerance``,
    ``--out``, ``--overwrite`` are the grade command's own)."""
    g = p.add_argument_group("a DEM impact (--impact)")
    g.add_argument("--impact", type=Path, metavar="TRAJECTORY.csv",
                   help="grade a DEM impact: columns t, overlap, normal_force [, v_n] "
                        "[, tangential_force, v_t, omega], from before the contact to after "
                        "it; needs --mass and --speed")
    g.add_argument("--mass", type=positive, metavar="M",
                   help="reduced mass m1 m2 / (m1 + m2) [kg] (m1 against a rigid wall)")
    g.add_argument("--speed", type=positive, metavar="V",
                   help="normal approach speed of the bodies [m/s] (the relative one)")
    g.add_argument("--damping", metavar="LAW:VALUE",
                   help="a damped contact, graded against hertz.damped_impact (default: "
                        "elastic): a hertz law and its coefficient (velocity, "
                        "mass_velocity, viscoelastic, kuwabara_kono, tsuji, "
                        "coeff_restitution), or LAMMPS's 'damping tsuji E' as "
                        "lammps_tsuji:E (LAMMPS up to 22 Jul 2025: alpha = poly(E)) or "
                        "lammps_tsuji_sqrt2:E (LAMMPS development since mid-2026: "
                        "sqrt(2) poly(E))")
    g.add_argument("--damping-attractive", action="store_true",
                   help="the damped force may pull (LAMMPS without limit_damping): the "
                        "contact ends when the overlap returns to 0; default: the force is "
                        "cut off at 0 (limit_damping) and the contact ends where it "
                        "reaches 0")
    g.add_argument("--angle-deg", type=finite, metavar="A",
                   help="incidence of an oblique impact from the normal [deg] (with --mu)")


def _radius(scene) -> float | None:
    """Body 1's radius where it is a sphere (the rebound angle of the contact point)."""
    b = scene.body1
    return float(b.Rx) if b.Rx == b.Ry and math.isfinite(b.Rx) and b.Rx > 0 else None


def run(args, argv, tolerances_from) -> int:
    """Grade ``args.impact``; return the exit status (errors are raised as ValueError).
    ``tolerances_from`` is grade.py's reader of --tolerance and --tolerances (passed in:
    grade.py imports this module)."""
    other = {"RESULT": args.result, "--force-approach": args.force_approach,
             "--tangential": args.tangential, "--history": getattr(args, "history", None)}
    given = [k for k, v in other.items() if v is not None]
    if given:
        raise UsageError(f"python -m fem_validation grade: --impact grades a trajectory "
                         f"alone; {', '.join(given)} do(es) not go with it")
    for name, what in (("mass", "the reduced mass [kg]"),
                       ("speed", "the normal approach speed [m/s]")):
        if getattr(args, name) is None:
            raise UsageError(f"python -m fem_validation grade: --impact needs --{name} "
                             f"({what})")
    if args.angle_deg is not None and not -90 < args.angle_deg < 90:
        raise UsageError(f"python -m fem_validation grade: --angle-deg must lie in (-90, 90) "
                         f"(the incidence from the normal), got {args.angle_deg!r}")
    if args.damping_attractive and args.damping is None:
        raise UsageError("python -m fem_validation grade: --damping-attractive needs "
                         "--damping LAW:VALUE")
    from ..grading.impact import METRICS, grade_impact, impact_reference
    from ..readers.impact_csv import read_impact
    from ..reports.impact import write_impact_grade
    from ..scenes import scene_from_toml

    tol = tolerances_from(args, {}, METRICS)
    require(["matplotlib", "scipy"], "grade --impact (its grade.png, the reference)")
    out = out_dir(args.out, args.overwrite, GRADE_FILES)
    import hertz

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        scene = scene_from_toml(args.scene)
    trajectory = read_impact(args.impact, args.units)
    try:
        ref = impact_reference(scene, args.mass, args.speed, damping=args.damping, mu=args.mu,
                               angle_deg=args.angle_deg or 0.0,
                               cutoff=not args.damping_attractive)
    except ValueError as exc:
        raise UsageError(f"python -m fem_validation grade: {exc}") from None
    g = grade_impact(trajectory, ref, mass=args.mass, speed=args.speed, radius=_radius(scene),
                     scene=scene.name, tolerances=tol,
                     details={"damping": args.damping, "mu": args.mu,
                              "angle_deg": args.angle_deg},
                     attractive=args.damping_attractive)
    command = " ".join(["python -m fem_validation grade", *argv])
    json_path, md_path, png_path = write_impact_grade(g, out, command)
    print(f"{g.summary}; wrote {json_path}, {md_path}, {png_path}")
    return 0 if g.passed else 1
