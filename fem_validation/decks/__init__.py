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

import math
from pathlib import Path

from ..scenes import Scene, scene_from_toml
from .inp import DEFAULT_FRICTION_INCREMENTS, UNITS, check_friction, friction_path, write_inp
from .meshes import write_mesh, write_problem
from .model import PENALTY_FACTOR, DeckModel, build_model, check_model

__all__ = ["FORMATS", "DeckModel", "build_model", "check_deck", "friction_path",
           "read_scene", "write_deck"]

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


def check_deck(scene: Scene, fmt: str, units: str = "mm", level: int = DEFAULT_DECK_LEVEL,
               model: str = "auto", slave_body: int = 1,
               penalty_factor: float = PENALTY_FACTOR, friction: float | None = None,
               friction_ratio: float = 0.8,
               friction_increments: int = DEFAULT_FRICTION_INCREMENTS) -> str:
    """Check what :func:`write_deck` is given, before anything is meshed or written.

    The format and units, the friction options (a CalculiX deck of a half or whole
    model; mu, the ratio and the increments in their ranges:
    :func:`fem_validation.decks.inp.check_friction`) and the model's
    (:func:`fem_validation.decks.model.check_model`: the scene, the level of the
    geometry, the penalty factor in [0.1, 1e6]).

    Returns
    -------
    str
        The model to build ("auto" is "half" with friction).

    Raises
    ------
    ValueError
        Naming the parameter, the value and what is allowed.
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
        check_friction(friction, friction_ratio, friction_increments)
    check_model(scene, level, model, slave_body, penalty_factor)
    return model


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
        Mesh level (0 coarse): 0-4 for true curved bodies, 0-5 for paraboloid-faced
        blocks.
    model : {"auto", "quarter", "half", "whole"}
        With ``friction``, "auto" is the half model.
    slave_body : {1, 2}
    penalty_factor : float
        Penalty slope over E*/h0, in [0.1, 1e6]
        (:data:`fem_validation.decks.model.PENALTY_FACTOR_RANGE`: below, the overclosure
        exceeds Hertz's approach; above, the contact swamps the elements' stiffness).
    command : str, optional
        The command line, recorded in the files.
    friction : float, optional
        Coefficient of friction, in [0.001, 10]: a frictional CalculiX deck (the normal
        step, then the tangential path of :func:`friction_path` along x).
    friction_ratio : float
        Q*/(mu P) at the end of the ramp (Cattaneo-Mindlin), in [0.001, 1).
    friction_increments : int
        Increments of the ramp, 1 to 100 (unloading 2n, reloading 2n + 1: one past the
        peak; ccx's ``*STEP, INC=1000`` holds them).

    Every option is checked (:func:`check_deck`) before anything is meshed or written.

    Returns
    -------
    model : DeckModel
    paths : list of Path
        The files written (the deck or mesh, then problem.json).
    """
    model = check_deck(scene, fmt, units, level, model, slave_body, penalty_factor, friction,
                       friction_ratio, friction_increments)
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


