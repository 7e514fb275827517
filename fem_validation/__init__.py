"""Finite-element validation of hertz, and graders of other codes' results against Hertz.

Run ``python -m fem_validation validate`` (``python -m fem_validation --help`` lists every
mode), or from Python::

    import fem_validation as fv
    result = fv.validate(fv.equal_steel(3), level=2, out="fem_out")
    result.a_rel_err, result.p0_rel_err

Any other code's result: read a file with :func:`fem_validation.readers.read_result` (or
fill a :class:`ContactResult`) and grade it with
:func:`fem_validation.grading.contact.grade` (a scene: :func:`scene_from_toml`);
``python -m fem_validation grade RESULT --scene FILE --out DIR`` does both and writes
grade.json, grade.md and grade.png.  Our own blocks and curved bodies go through the
same grade.  The finite elements need the ``fem`` extra (scikit-fem, meshio, gmsh,
pyamg, matplotlib); the graders need numpy and scipy (and matplotlib for the figure).

The layers (one way through: sources -> results -> grading -> reports -> runs -> cli; a
module imports its own folder and the layers below, never a sibling folder of its layer
nor one above; tests/test_layers.py enforces it on every import, function-level and
TYPE_CHECKING ones included)::

    L7  __main__        picks the mode
    L6  cli/            argument parsing and exit statuses, one module a mode
    L5  runs/           our runs end to end (blocks, curved bodies, friction, the study)
        decks/          a scene as input for another code
    L4  reports/        tables, figures and grade files from what they are handed
    L3  solvers/        our sources (block meshes and solve, curved bodies, friction)
        readers/        other codes' files (one dispatch: readers.read_result)
        grading/        a result against Hertz (never imports a source)
    L2  results/        ContactResult, TangentialResult: where sources meet graders
        fe/             finite-element numerics that know no scene
    L1  errors, memory, limits, scenes, halfspace  (and hertz)

This face only re-exports (lazily, so that ``import fem_validation`` needs no solver); no
module of the package imports it.  The old module paths (``fem_validation.grade``,
``.result``, ``.output``, ...) still import for one release, with a DeprecationWarning.
"""

from __future__ import annotations

import importlib
import importlib.util
import logging
from typing import TYPE_CHECKING

from .errors import FEMValidationError

if TYPE_CHECKING:
    from .runs.validate import Comparison
    from .scenes import Scene

#: Where each public name lives: imported on first use (PEP 562), so that
#: ``import fem_validation``, ``python -m fem_validation --help`` and the graders work with
#: numpy and scipy alone, and only what a name needs (scikit-fem, gmsh, pyamg: the ``fem``
#: extra) is imported when it is used.
_LAZY = {
    "grading.contact": ("DEFAULT_TOLERANCES", "TARGETS", "Grade"),
    "grading.tangential": ("TangentialGrade",),
    "reports.blocks": ("plot_profiles", "write_reports"),
    "results.contact": ("BodyStress", "ContactFrame", "ContactResult", "ResultError"),
    "results.tangential": ("TangentialResult",),
    "runs.curved": ("A_OVER_R", "CurvedComparison", "compare_curved", "run_curved",
                    "validate_curved"),
    "runs.validate": ("NESTED_REBUILD_FRACTION", "Comparison", "check", "compare_with_hertz",
                      "profiles", "validate"),
    "scenes": ("Scene", "crossed_30deg", "default_scenes", "equal_steel", "scene_from_toml",
               "steel_on_aluminium"),
    "solvers.curved": ("solve_curved",),
    "solvers.curved_mesh": ("DEFAULT_CURVED_LEVEL", "CurvedScene", "ball_groove",
                            "build_curved", "sphere_plane"),
    "solvers.friction": ("FrictionSolution", "friction_result", "solve_friction"),
    "solvers.mesh": ("DEFAULT_LEVEL", "LEVEL_H0", "LEVEL_SCALE", "BlockMesh", "build",
                     "mirrored"),
    "solvers.solve": ("KAPPA", "REBUILD_FRACTION", "ContactSolution", "solve_contact",
                      "transferred_active_set"),
    "solvers.vtu": ("write_vtu",),
}
_WHERE = {name: module for module, names in _LAZY.items() for name in names}

__all__ = [
    "A_OVER_R",
    "DEFAULT_CURVED_LEVEL",
    "DEFAULT_LEVEL",
    "DEFAULT_TOLERANCES",
    "KAPPA",
    "LEVEL_H0",
    "LEVEL_SCALE",
    "NESTED_REBUILD_FRACTION",
    "TARGETS",
    "BlockMesh",
    "BodyStress",
    "Comparison",
    "ContactFrame",
    "ContactResult",
    "ContactSolution",
    "CurvedComparison",
    "CurvedScene",
    "FEMValidationError",
    "FrictionSolution",
    "Grade",
    "ResultError",
    "Scene",
    "TangentialGrade",
    "TangentialResult",
    "ball_groove",
    "build",
    "build_curved",
    "check",
    "compare_curved",
    "compare_with_hertz",
    "crossed_30deg",
    "default_scenes",
    "equal_steel",
    "friction_result",
    "mirrored",
    "run_curved",
    "scene_from_toml",
    "solve_contact",
    "solve_curved",
    "solve_friction",
    "sphere_plane",
    "steel_on_aluminium",
    "validate",
    "validate_curved",
]

log = logging.getLogger("fem_validation")


def __getattr__(name: str):
    """A public name (or a submodule) imported on first use."""
    if name in _WHERE:
        value = getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
    elif not name.startswith("__") and importlib.util.find_spec(f"{__name__}.{name}"):
        value = importlib.import_module(f".{name}", __name__)  # a submodule, as before
    else:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(__all__))


