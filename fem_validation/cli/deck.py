"""``python -m fem_validation deck``: a Hertz benchmark as input for another code."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..decks import DEFAULT_DECK_LEVEL, FORMATS, read_scene, write_deck
from ..decks.inp import DEFAULT_FRICTION_INCREMENTS, UNITS
from ..decks.model import PENALTY_FACTOR
from .common import OneLineParser, add_overwrite, finite, out_dir, positive, require


def _deck(argv: list[str]) -> int:
    """``python -m fem_validation deck ...``: a benchmark deck for another code."""
    p = OneLineParser(prog="python -m fem_validation deck",
                      description="Write a Hertz benchmark as input for another "
                                  "finite-element code (fem_validation.decks).",
                      epilog="example: python -m fem_validation deck --scene FILE.toml "
                             "--format calculix --out DIR")
    add_arguments(p)
    args = p.parse_args(argv)
    return run(args, command=" ".join(["python -m fem_validation deck", *argv]))


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The ``deck`` subcommand's options."""
    parser.add_argument("--scene", required=True, type=Path, metavar="FILE",
                        help="hertz TOML scene file (SI)")
    parser.add_argument("--format", required=True, choices=FORMATS, dest="deck_format",
                        help="calculix or abaqus (.inp), or a mesh with named groups")
    parser.add_argument("--out", type=Path, required=True,
                        help="output directory (new or empty: a deck beside another run's "
                             "files would be graded against the wrong problem.json)")
    add_overwrite(parser)
    parser.add_argument("--units", choices=sorted(UNITS), default="mm",
                        help="units of the files (default mm: mm, N, MPa)")
    parser.add_argument("--level", type=int, default=DEFAULT_DECK_LEVEL,
                        help=f"mesh level, 0 coarse (default {DEFAULT_DECK_LEVEL})")
    parser.add_argument("--model", choices=("auto", "quarter", "half", "whole"),
                        default="auto",
                        help="quarter, half (y >= 0) or whole model (default: quarter where "
                             "the scene allows; half with --friction)")
    parser.add_argument("--slave", type=int, choices=(1, 2), default=1,
                        help="body whose contact face is the slave surface (default 1)")
    parser.add_argument("--penalty-factor", type=positive, default=PENALTY_FACTOR,
                        help=f"penalty slope over E*/h0 (default {PENALTY_FACTOR:g})")
    f = parser.add_argument_group(
        "Coulomb friction (--format calculix)",
        "After the normal step, body 1's far face moves along x to the displacement at which "
        "Cattaneo-Mindlin gives Q = RATIO mu P (less what the clamped blocks miss), back to "
        "minus that and forward again, with output at every increment; half model (y >= 0) "
        "of paraboloid-faced blocks; stick slope = the normal penalty slope. Grade the run "
        "with: python -m fem_validation grade --tangential DIR/hertz.frd --scene FILE")
    f.add_argument("--friction", type=finite, metavar="MU",
                   help="coefficient of friction: write a frictional deck")
    f.add_argument("--friction-ratio", type=finite, default=0.8, metavar="RATIO",
                   help="Q*/(mu P) at the end of the ramp, in (0, 1) (default 0.8)")
    f.add_argument("--friction-increments", type=int, default=DEFAULT_FRICTION_INCREMENTS,
                   metavar="N", help="increments of the ramp; unloading takes 2N, reloading "
                                     "2N + 1 (one past the peak, so that the loop closes) "
                                     f"(default {DEFAULT_FRICTION_INCREMENTS})")


def run(args: argparse.Namespace, command: str | None = None) -> int:
    """Run the ``deck`` subcommand; ValueError / FEMValidationError propagate to the caller.

    The scene is read (at most 1 MiB, :func:`fem_validation.limits.read_small_text`), the
    packages a deck needs are looked up and ``--out`` is checked (new or empty, unless
    ``--overwrite``) before anything is meshed.
    """
    scene = read_scene(args.scene)
    if args.friction is None and (args.friction_ratio != 0.8 or
                                  args.friction_increments != DEFAULT_FRICTION_INCREMENTS):
        raise ValueError("--friction-ratio and --friction-increments need --friction MU")
    require(("gmsh", "skfem", "pyamg", *(() if args.deck_format in ("calculix", "abaqus")
                                         else ("meshio",))),
            f"deck --format {args.deck_format}")
    out_dir(args.out, args.overwrite)
    m, paths = write_deck(scene, args.deck_format, args.out, args.units, args.level,
                          args.model, args.slave, args.penalty_factor, command,
                          args.friction, args.friction_ratio, args.friction_increments)
    c = m.contact
    ul = UNITS[args.units]["length"]
    print(f"{scene.name}: {m.geometry}, {m.symmetry} model, "
          f"{len(m.nodes)} nodes, {len(m.elements)} elements; Hertz a = {c.a * ul:.5g}, "
          f"b = {c.b * ul:.5g} {UNITS[args.units]['names']['length']} at "
          f"{c.load:.5g} N; wrote {', '.join(str(p) for p in paths)}")
    return 0
