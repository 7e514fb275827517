"""Finite-element validation of hertz: two elastic blocks, penalty contact, scikit-fem.

Run ``python -m fem_validation validate`` (``python -m fem_validation --help`` lists every
mode), or from Python::

    import fem_validation as fv
    result = fv.validate(fv.equal_steel(3), level=2, out="fem_out")
    result.a_rel_err, result.p0_rel_err

The model is Hertz's own: two half-spaces, truncated to blocks, with the
quadratic gap of the scene's curvatures between their flat faces (see
``fem_validation.solve``).  Needs the ``fem`` extra (scikit-fem, meshio, gmsh,
pyamg, matplotlib); the geometry is meshes/blocks.geo (see
``fem_validation.mesh.geometry_file``).

True curved bodies (a ball on a plane and in a groove, node-to-surface contact):
``fem_validation.curved`` (``python -m fem_validation --curved``).

Any other code's result: fill a :class:`ContactResult` (``fem_validation.result``; or
read a file with ``fem_validation.readers.common.read_result``) and grade it with
``fem_validation.grade.grade(result, scene)`` (a scene: ``scene_from_toml``);
``python -m fem_validation grade RESULT --scene FILE --out DIR`` does both and writes
grade.json, grade.md and grade.png.  Our own blocks and curved bodies go through the
same grade.
"""

from __future__ import annotations

import importlib
import importlib.util
import logging
import time
from pathlib import Path
from typing import TYPE_CHECKING

from .errors import FEMValidationError

if TYPE_CHECKING:
    from .compare import Comparison
    from .scenes import Scene

#: Where each public name lives: imported on first use (PEP 562), so that
#: ``import fem_validation``, ``python -m fem_validation --help`` and the graders work with
#: numpy and scipy alone, and only what a name needs (scikit-fem, gmsh, pyamg: the ``fem``
#: extra) is imported when it is used.
_LAZY = {
    "compare": ("TARGETS", "Comparison", "check", "compare_with_hertz", "profiles"),
    "curved": ("A_OVER_R", "CurvedComparison", "compare_curved", "run_curved",
               "solve_curved", "validate_curved"),
    "curved_mesh": ("DEFAULT_CURVED_LEVEL", "CurvedScene", "ball_groove", "build_curved",
                    "sphere_plane"),
    "friction": ("FrictionSolution", "friction_result", "solve_friction"),
    "grade": ("DEFAULT_TOLERANCES", "Grade"),  # the function: fem_validation.grade.grade
    "grade_tangential": ("TangentialGrade",),  # the function: grade_tangential.grade_tangential
    "mesh": ("DEFAULT_LEVEL", "LEVEL_H0", "LEVEL_SCALE", "BlockMesh", "build", "mirrored"),
    "output": ("plot_profiles", "write_reports", "write_vtu"),
    "result": ("BodyStress", "ContactFrame", "ContactResult", "ResultError"),
    "scenes": ("Scene", "crossed_30deg", "default_scenes", "equal_steel", "scene_from_toml",
               "steel_on_aluminium"),
    "solve": ("KAPPA", "REBUILD_FRACTION", "ContactSolution", "solve_contact",
              "transferred_active_set"),
    "tangential_result": ("TangentialResult",),
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


#: A nested start solves this many levels coarser first.
NESTED_LEVELS = 2
#: The AMG rebuild threshold of a nested start's fine solve: the active set transferred from
#: the coarse mesh moves by 1-5% of the pairs in the first solves, below REBUILD_FRACTION, and
#: a preconditioner built before those moves left CG 100 iterations (alpha 3, level 4: 36.6 s
#: with REBUILD_FRACTION, 27.9 s with this).
NESTED_REBUILD_FRACTION = 0.01


def validate(scene: Scene, level: int | None = None, out: str | Path | None = None,
             kappa: float | None = None, initial_active: str = "hertz",
             rebuild_fraction: float | None = None) -> Comparison:
    """Mesh, solve and compare one scene; with ``out``, also write its VTU files and plot.

    Parameters
    ----------
    scene : Scene
        The bodies, target load and angle (see :mod:`fem_validation.scenes`).
    level : int, optional
        Mesh level, 0 (coarse, seconds) to 5 (fine), default DEFAULT_LEVEL; each
        level divides every element size by LEVEL_RATIO (sqrt 2); the element size
        in the contact zone is LEVEL_H0[level] times the Hertz semi-axis b.
    out : path, optional
        Directory for ``<scene>_body1.vtu``, ``<scene>_body2.vtu`` and
        ``<scene>_pressure.png``.
    kappa : float, optional
        Penalty factor (stiffness kappa E*/h0 per unit area), default KAPPA.
    initial_active : {"hertz", "interpenetration", "none", "all", "nested"}
        First active set of the contact iteration (see
        :func:`fem_validation.solve.initial_active_set`); "nested" solves
        NESTED_LEVELS levels coarser from the interpenetration of the
        undeformed bodies first and starts from that solution's active set.
    rebuild_fraction : float, optional
        Rebuild the AMG preconditioner when more than this fraction of the
        active pairs changed state since its setup (``inf``: build it once).
        Default REBUILD_FRACTION, and NESTED_REBUILD_FRACTION for the fine
        solve of a nested start.

    Returns
    -------
    Comparison
        Errors against Hertz at the force the run reached, with timings.
    """
    from . import memory
    from .compare import compare_with_hertz, profiles
    from .mesh import DEFAULT_LEVEL, build
    from .solve import KAPPA, REBUILD_FRACTION, solve_contact, transferred_active_set

    level = DEFAULT_LEVEL if level is None else level
    kappa = KAPPA if kappa is None else kappa
    memory.reset_peak()
    t0 = time.perf_counter()
    mesh = build(scene, level)
    start = initial_active
    fine_rebuild = REBUILD_FRACTION if rebuild_fraction is None else rebuild_fraction
    if initial_active == "nested":
        coarse = build(scene, max(level - NESTED_LEVELS, 0))
        start = transferred_active_set(
            coarse, solve_contact(scene, coarse, kappa=kappa, initial_active="interpenetration",
                                  rebuild_fraction=fine_rebuild), mesh)
        if rebuild_fraction is None:
            fine_rebuild = NESTED_REBUILD_FRACTION
    sol = solve_contact(scene, mesh, kappa=kappa, initial_active=start,
                        rebuild_fraction=fine_rebuild)
    prof = profiles(scene, mesh, sol)
    result = compare_with_hertz(scene, mesh, sol, level, time.perf_counter() - t0, prof)
    result.peak_memory_mb = memory.peak_mb()
    log.info("%s: a %+.2f%%, b %+.2f%%, p0 %+.2f%%, RMS %.2f%% / %.2f%% of p0, edge %+.2f%% / "
             "%+.2f%%, approach %+.2f%%, %d dofs, %.1f s, %.0f MB", scene.name,
             100 * result.a_rel_err, 100 * result.b_rel_err, 100 * result.p0_rel_err,
             100 * result.rms_major, 100 * result.rms_minor, 100 * result.edge_a_rel_err,
             100 * result.edge_b_rel_err, 100 * result.approach_rel_err, result.dofs,
             result.seconds, result.peak_memory_mb)
    if out is not None:
        from .output import plot_profiles, write_vtu

        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        write_vtu(scene, mesh, sol, out, nodal_stress=result.nodal_stress)
        plot_profiles(scene, prof, result, out / f"{scene.name}_pressure.png")
    return result


def reports(results: list[Comparison], out: str | Path, header: str = ""):
    """Write report.json and report.md for a list of results."""
    from .output import write_reports

    return write_reports(results, Path(out), header)
