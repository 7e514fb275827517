"""Benchmark decks: a Hertz scene as input for another finite-element code.

``python -m fem_validation deck --scene FILE --format calculix --out DIR``
writes DIR/hertz.inp (CalculiX), ``--format abaqus`` DIR/hertz.inp in
Abaqus's dialect, ``--format msh|med|exodus|xdmf`` DIR/mesh.* with named
groups; every format also writes DIR/problem.json (materials, loads, units,
groups, the contact pair and penalty, the Hertz values expected).  The scene
is a ``hertz`` TOML scene file (SI; see :mod:`hertz.cli`).  DIR must be new or
empty (``--overwrite`` writes into a folder that holds files: a new deck beside
an earlier run's results would be graded against the wrong problem.json).

The model (:mod:`fem_validation.decks.model`): a true ball on a plane or in a
groove where the scene is one (quarter model), paraboloid-faced blocks
otherwise; 10-node tetrahedra; body 1's far face moved down by the approach
that gives the target load, body 2's far face clamped; frictionless
surface-to-surface penalty contact, slave on body 1 unless ``--slave 2``.

``--friction MU`` (CalculiX) adds Coulomb friction and a tangential path
after the normal step: body 1's far face moves along x to the displacement
at which Cattaneo-Mindlin gives Q = ``--friction-ratio`` mu P, back to minus
that and forward again (a fretting loop), on the half model y >= 0 of
paraboloid-faced blocks; :mod:`fem_validation.readers.calculix_friction`
reads the run back for the tangential grader.

Examples
--------
>>> from fem_validation.decks import FORMATS
>>> sorted(FORMATS)
['abaqus', 'calculix', 'exodus', 'med', 'msh', 'xdmf']
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path

from ..cli_common import add_overwrite, finite, out_dir, positive, require
from ..scenes import Scene, scene_from_toml
from .inp import DEFAULT_FRICTION_INCREMENTS, UNITS, friction_path, write_inp
from .meshes import write_mesh, write_problem
from .model import PENALTY_FACTOR, DeckModel, build_model

__all__ = ["FORMATS", "DeckModel", "add_arguments", "build_model", "friction_path",
           "read_scene", "run", "write_deck"]

FORMATS = ("calculix", "abaqus", "msh", "med", "exodus", "xdmf")
#: Default mesh level of a deck: coarse enough for a laptop (the curved levels are 0-4,
#: the block levels 0-5).
DEFAULT_DECK_LEVEL = 1


def read_scene(path) -> Scene:
    """A :class:`Scene` with its target load from a ``hertz`` TOML scene file (SI units).

    :func:`fem_validation.scenes.scene_from_toml`, which also needs one of
    ``load`` [N] or ``approach`` [m] here: a deck prescribes the approach that
    reaches the target load.

    Raises
    ------
    ValueError
        Naming the file and the key (see scene_from_toml), or the missing or zero target.
    """
    scene = scene_from_toml(path)
    if not math.isfinite(scene.load):
        raise ValueError(f"scene file {str(path)!r}: a deck needs the target: give load [N] "
                         f"or approach [m]")
    if not scene.load > 0:
        raise ValueError(f"scene file {str(path)!r}: load must be > 0 for a deck (the "
                         f"approach that reaches it is prescribed), got {scene.load!r}")
    return scene


def write_deck(scene: Scene, fmt: str, out, units: str = "mm", level: int = DEFAULT_DECK_LEVEL,
               model: str = "auto", slave_body: int = 1,
               penalty_factor: float = PENALTY_FACTOR, command: str | None = None,
               friction: float | None = None, friction_ratio: float = 0.8,
               friction_increments: int = DEFAULT_FRICTION_INCREMENTS,
               ) -> tuple[DeckModel, list[Path]]:
    """Write the benchmark deck of a scene.

    Parameters
    ----------
    scene : Scene
    fmt : str
        One of :data:`FORMATS`.
    out : path-like
        Output directory (created).
    units : {"mm", "SI"}
        mm, N, MPa or m, N, Pa (the files and problem.json).
    level : int
        Mesh level (0 coarse).
    model : {"auto", "quarter", "half", "whole"}
        With ``friction``, "auto" is the half model.
    slave_body : {1, 2}
    penalty_factor : float
        Penalty slope over E*/h0.
    command : str, optional
        The command line, recorded in the files.
    friction : float, optional
        Coefficient of friction: a frictional CalculiX deck (the normal step,
        then the tangential path of :func:`friction_path` along x).
    friction_ratio : float
        Q*/(mu P) at the end of the ramp (Cattaneo-Mindlin), in (0, 1).
    friction_increments : int
        Increments of the ramp (unloading 2n, reloading 2n + 1: one past the peak).

    Returns
    -------
    model : DeckModel
    paths : list of Path
        The files written (the deck or mesh, then problem.json).
    """
    if fmt not in FORMATS:
        raise ValueError(f"format must be one of {', '.join(FORMATS)}, got {fmt!r}")
    if units not in UNITS:
        raise ValueError(f"units must be one of {', '.join(UNITS)}, got {units!r}")
    if friction is not None:
        if fmt != "calculix":
            raise ValueError(f"friction decks are written for format calculix only, got "
                             f"{fmt!r}")
        if model not in ("auto", "half", "whole"):
            raise ValueError(f"a frictional deck is a half or whole model (the load along x "
                             f"breaks the symmetry in x = 0), got model {model!r}")
        model = "half" if model == "auto" else model
    out = Path(out)
    m = build_model(scene, level, model, slave_body, penalty_factor)
    path_ = None if friction is None else friction_path(m, friction, friction_ratio,
                                                        friction_increments)
    out.mkdir(parents=True, exist_ok=True)
    if fmt in ("calculix", "abaqus"):
        path = out / "hertz.inp"
        write_inp(m, path, units, fmt, command, path_)
    else:
        path = write_mesh(m, out, fmt, units)
    problem = write_problem(m, out, units, {"deck" if fmt in ("calculix", "abaqus")
                                            else "mesh": path.name, "format": fmt}, command,
                            path_)
    return m, [path, problem]


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
