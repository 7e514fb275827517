"""``python -m fem_validation deck``: a Hertz benchmark as input for another code."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..decks import DEFAULT_DECK_LEVEL, FORMATS, check_deck, read_scene, write_deck
from ..decks.inp import (
    DEFAULT_FRICTION_INCREMENTS,
    FRICTION_MU_RANGE,
    MAX_FRICTION_INCREMENTS,
    MIN_FRICTION_RATIO,
    UNITS,
    check_increments,
    check_mu,
    check_ratio,
)
from ..decks.model import PENALTY_FACTOR, PENALTY_FACTOR_RANGE, check_penalty_factor
from .common import OneLineParser, add_overwrite, finite, out_dir, positive, require


def _checked(parse, check):
    """An option type: ``parse`` the text, then ``check`` the value (its ValueError becomes
    argparse's one line, which names the option)."""
    def option_type(text: str):
        value = parse(text)
        try:
            return check(value)
        except ValueError as exc:
            raise argparse.ArgumentTypeError(str(exc)) from None
    option_type.__name__ = getattr(check, "__name__", "value")
    return option_type


def _integer(text: str) -> int:
    """An integer of at most 18 digits (an option type; the line never echoes thousands)."""
    shown = text if len(text) <= 40 else text[:37] + "..."
    if len(text.strip().lstrip("+-")) > 18:
        raise argparse.ArgumentTypeError(f"not an integer of at most 18 digits: {shown!r}")
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"not an integer: {shown!r}") from None


def _level(value: int) -> int:
    if value < 0:
        raise ValueError(f"level must be >= 0 (0 coarse), got {value!r}")
    return value


def _deck(argv: list[str]) -> int:
    """``python -m fem_validation deck ...``: a benchmark deck for another code."""
    if any(a == "--code" or a.startswith("--code=") for a in argv):  # a DEM code's input
        from .lammps import main as dem_deck

        return dem_deck(argv)
    p = OneLineParser(prog="python -m fem_validation deck",
                      description="Write a Hertz benchmark as input for another "
                                  "finite-element code (fem_validation.decks).",
                      epilog="example: python -m fem_validation deck --scene FILE.toml "
                             "--format calculix --out DIR\n"
                             "a DEM code's input (LAMMPS): python -m fem_validation deck "
                             "--code lammps --help")
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
    parser.add_argument("--level", type=_checked(_integer, _level), default=DEFAULT_DECK_LEVEL,
                        help=f"mesh level, 0 coarse: 0-4 for a true ball on a plane or in a "
                             f"groove, 0-5 for paraboloid-faced blocks (default "
                             f"{DEFAULT_DECK_LEVEL})")
    parser.add_argument("--model", choices=("auto", "quarter", "half", "whole",
                                             "plane-strain", "axisymmetric"),
                        default="auto",
                        help="quarter, half (y >= 0) or whole model (default: quarter where "
                             "the scene allows; half with --friction; plane-strain for a "
                             "line-contact scene, load_per_length); plane-strain or "
                             "axisymmetric: a 2-D deck (fem_validation.decks.plane)")
    parser.add_argument("--slave", type=int, choices=(1, 2), default=1,
                        help="body whose contact face is the slave surface (default 1)")
    low, high = PENALTY_FACTOR_RANGE
    parser.add_argument("--penalty-factor", type=_checked(positive, check_penalty_factor),
                        default=PENALTY_FACTOR,
                        help=f"penalty slope over E*/h0, in [{low:g}, {high:g}]: below, the "
                             f"overclosure exceeds Hertz's approach; above, the contact swamps "
                             f"the elements' stiffness (default {PENALTY_FACTOR:g})")
    f = parser.add_argument_group(
        "Coulomb friction (--format calculix)",
        "After the normal step, body 1's far face moves along x to the displacement at which "
        "Cattaneo-Mindlin gives Q = RATIO mu P (less what the clamped blocks miss), back to "
        "minus that and forward again, with output at every increment; half model (y >= 0) "
        "of paraboloid-faced blocks; stick slope = the normal penalty slope. Grade the run "
        "with: python -m fem_validation grade --tangential DIR/hertz.frd --scene FILE")
    f.add_argument("--friction", type=_checked(finite, check_mu), metavar="MU",
                   help="coefficient of friction, in [{:g}, {:g}] (those of solids): write a "
                        "frictional deck".format(*FRICTION_MU_RANGE))
    f.add_argument("--friction-ratio", type=_checked(finite, check_ratio), default=0.8,
                   metavar="RATIO",
                   help=f"Q*/(mu P) at the end of the ramp, in [{MIN_FRICTION_RATIO:g}, 1): 1 "
                        f"is gross sliding, below {MIN_FRICTION_RATIO:g} the slip annulus is "
                        f"far below an element (default 0.8)")
    f.add_argument("--friction-increments", type=_checked(_integer, check_increments),
                   default=DEFAULT_FRICTION_INCREMENTS, metavar="N",
                   help=f"increments of the ramp, 1 to {MAX_FRICTION_INCREMENTS}; unloading "
                        f"takes 2N, reloading 2N + 1 (one past the peak, so that the loop "
                        f"closes): 5N + 1 increments of ccx, each about 100 s of CPU at level "
                        f"0 (default {DEFAULT_FRICTION_INCREMENTS})")


def _line_scene(scene) -> bool:
    """Whether the scene file is a line contact (``load_per_length``)."""
    try:
        from hertz._scene import read_scene as read_toml

        return "load_per_length" in read_toml(scene)
    except (OSError, ValueError, TypeError):
        return False  # a named scene, or refused below with its own message


def run(args: argparse.Namespace, command: str | None = None) -> int:
    """Run the ``deck`` subcommand; ValueError / FEMValidationError propagate to the caller.

    The scene is read (at most 1 MiB, :func:`fem_validation.limits.read_small_text`), the
    packages a deck needs are looked up, every option is checked against the scene
    (:func:`fem_validation.decks.check_deck`: the level of its geometry, the friction
    options' model and format) and ``--out`` is checked (new or empty, unless
    ``--overwrite``), in that order, before anything is meshed or written.
    """
    if args.model == "auto" and _line_scene(args.scene):  # load_per_length: plane strain
        args.model = "plane-strain"
    if args.model in ("plane-strain", "axisymmetric"):  # a 2-D deck: decks/plane.py
        from ..decks.plane import plane_deck

        require(("gmsh",), f"deck --model {args.model}")
        if args.deck_format not in ("calculix", "abaqus") or args.friction is not None:
            raise ValueError(f"--model {args.model} writes a frictionless CalculiX or Abaqus "
                             f"deck (--format calculix or abaqus, no --friction)")
        out_dir(args.out, args.overwrite)
        print(plane_deck(args.scene, args.model, args.deck_format, args.out, args.units,
                         args.level, args.penalty_factor, command))
        return 0
    scene = read_scene(args.scene)
    if args.friction is None and (args.friction_ratio != 0.8 or
                                  args.friction_increments != DEFAULT_FRICTION_INCREMENTS):
        raise ValueError("--friction-ratio and --friction-increments need --friction MU")
    require(("gmsh", "skfem", "pyamg", *(() if args.deck_format in ("calculix", "abaqus")
                                         else ("meshio",))),
            f"deck --format {args.deck_format}")
    check_deck(scene, args.deck_format, args.units, args.level, args.model, args.slave,
               args.penalty_factor, args.friction, args.friction_ratio,
               args.friction_increments)
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
