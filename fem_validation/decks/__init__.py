"""Benchmark decks: a Hertz scene as input for another finite-element code.

``python -m fem_validation deck --scene FILE --format calculix --out DIR``
writes DIR/hertz.inp (CalculiX), ``--format abaqus`` DIR/hertz.inp in
Abaqus's dialect, ``--format msh|med|exodus|xdmf`` DIR/mesh.* with named
groups; every format also writes DIR/problem.json (materials, loads, units,
groups, the contact pair and penalty, the Hertz values expected).  The scene
is a ``hertz`` TOML scene file (SI; see :mod:`hertz.cli`).

The model (:mod:`fem_validation.decks.model`): a true ball on a plane or in a
groove where the scene is one (quarter model), paraboloid-faced blocks
otherwise; 10-node tetrahedra; body 1's far face moved down by the approach
that gives the target load, body 2's far face clamped; frictionless
surface-to-surface penalty contact, slave on body 1 unless ``--slave 2``.

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

from ..scenes import Scene, scene_from_toml
from .inp import UNITS, write_inp
from .meshes import write_mesh, write_problem
from .model import PENALTY_FACTOR, DeckModel, build_model

__all__ = ["FORMATS", "DeckModel", "add_arguments", "build_model", "read_scene", "run",
           "write_deck"]

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
        Naming the file and the key (see scene_from_toml), or the missing target.
    """
    scene = scene_from_toml(path)
    if not math.isfinite(scene.load):
        raise ValueError(f"scene file {str(path)!r}: a deck needs the target: give load [N] "
                         f"or approach [m]")
    return scene


def write_deck(scene: Scene, fmt: str, out, units: str = "mm", level: int = DEFAULT_DECK_LEVEL,
               model: str = "auto", slave_body: int = 1,
               penalty_factor: float = PENALTY_FACTOR, command: str | None = None,
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
    model : {"auto", "quarter", "whole"}
    slave_body : {1, 2}
    penalty_factor : float
        Penalty slope over E*/h0.
    command : str, optional
        The command line, recorded in the files.

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
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    m = build_model(scene, level, model, slave_body, penalty_factor)
    if fmt in ("calculix", "abaqus"):
        path = out / "hertz.inp"
        write_inp(m, path, units, fmt, command)
    else:
        path = write_mesh(m, out, fmt, units)
    problem = write_problem(m, out, units, {"deck" if fmt in ("calculix", "abaqus")
                                            else "mesh": path.name, "format": fmt}, command)
    return m, [path, problem]


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The ``deck`` subcommand's options."""
    parser.add_argument("--scene", required=True, type=Path, metavar="FILE",
                        help="hertz TOML scene file (SI)")
    parser.add_argument("--format", required=True, choices=FORMATS, dest="deck_format",
                        help="calculix or abaqus (.inp), or a mesh with named groups")
    parser.add_argument("--out", type=Path, required=True, help="output directory")
    parser.add_argument("--units", choices=sorted(UNITS), default="mm",
                        help="units of the files (default mm: mm, N, MPa)")
    parser.add_argument("--level", type=int, default=DEFAULT_DECK_LEVEL,
                        help=f"mesh level, 0 coarse (default {DEFAULT_DECK_LEVEL})")
    parser.add_argument("--model", choices=("auto", "quarter", "whole"), default="auto",
                        help="quarter or whole model (default: quarter where the scene allows)")
    parser.add_argument("--slave", type=int, choices=(1, 2), default=1,
                        help="body whose contact face is the slave surface (default 1)")
    parser.add_argument("--penalty-factor", type=float, default=PENALTY_FACTOR,
                        help=f"penalty slope over E*/h0 (default {PENALTY_FACTOR:g})")


def run(args: argparse.Namespace, command: str | None = None) -> int:
    """Run the ``deck`` subcommand; ValueError / FEMValidationError propagate to the caller."""
    scene = read_scene(args.scene)
    m, paths = write_deck(scene, args.deck_format, args.out, args.units, args.level,
                          args.model, args.slave, args.penalty_factor, command)
    c = m.contact
    ul = UNITS[args.units]["length"]
    print(f"{scene.name}: {m.geometry}, {'quarter' if m.quarter else 'whole'} model, "
          f"{len(m.nodes)} nodes, {len(m.elements)} elements; Hertz a = {c.a * ul:.5g}, "
          f"b = {c.b * ul:.5g} {UNITS[args.units]['names']['length']} at "
          f"{c.load:.5g} N; wrote {', '.join(str(p) for p in paths)}")
    return 0
