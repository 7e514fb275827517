"""Finite-element validation of hertz: two elastic blocks, penalty contact, scikit-fem.

Run ``python -m fem_validation`` (see ``--help``), or from Python::

    import fem_validation as fv
    result = fv.validate(fv.equal_steel(3), level=2, out="fem_out")
    result.a_rel_err, result.p0_rel_err

The model is Hertz's own: two half-spaces, truncated to blocks, with the
quadratic gap of the scene's curvatures between their flat faces (see
``fem_validation.solve``).  Needs the ``fem`` extra (scikit-fem, meshio, gmsh,
pyamg, matplotlib) and a source checkout (the geometry is meshes/blocks.geo).
"""

from __future__ import annotations

import logging
import time
from pathlib import Path

from .compare import (
    Comparison,
    compare_with_hertz,
    plot_profiles,
    profiles,
    write_reports,
    write_vtu,
)
from .errors import FEMValidationError
from .mesh import DEFAULT_LEVEL, LEVEL_H0, BlockMesh, build
from .scenes import Scene, crossed_30deg, default_scenes, equal_steel, steel_on_aluminium
from .solve import KAPPA, ContactSolution, solve_contact

__all__ = [
    "DEFAULT_LEVEL",
    "KAPPA",
    "LEVEL_H0",
    "BlockMesh",
    "Comparison",
    "ContactSolution",
    "FEMValidationError",
    "Scene",
    "build",
    "compare_with_hertz",
    "crossed_30deg",
    "default_scenes",
    "equal_steel",
    "solve_contact",
    "steel_on_aluminium",
    "validate",
]

log = logging.getLogger("fem_validation")


def validate(scene: Scene, level: int = DEFAULT_LEVEL, out: str | Path | None = None,
             kappa: float = KAPPA) -> Comparison:
    """Mesh, solve and compare one scene; with ``out``, also write its VTU files and plot.

    Parameters
    ----------
    scene : Scene
        The bodies, target load and angle (see :mod:`fem_validation.scenes`).
    level : int
        Mesh level, 0 (coarse, seconds) to 3 (fine); element size in the
        contact zone LEVEL_H0[level] times the Hertz semi-axis b.
    out : path, optional
        Directory for ``<scene>_body1.vtu``, ``<scene>_body2.vtu`` and
        ``<scene>_pressure.png``.
    kappa : float
        Penalty factor (stiffness kappa E*/h0 per unit area).

    Returns
    -------
    Comparison
        Errors against Hertz at the force the run reached, with timings.
    """
    t0 = time.perf_counter()
    mesh = build(scene, level)
    sol = solve_contact(scene, mesh, kappa=kappa)
    prof = profiles(scene, mesh, sol)
    result = compare_with_hertz(scene, mesh, sol, level, time.perf_counter() - t0, prof)
    log.info("%s: a %+.2f%%, b %+.2f%%, p0 %+.2f%%, RMS %.2f%% / %.2f%% of p0, force balance "
             "%.1e, %d dofs, %.1f s", scene.name, 100 * result.a_rel_err, 100 * result.b_rel_err,
             100 * result.p0_rel_err, 100 * result.rms_major, 100 * result.rms_minor,
             result.force_rel_err, result.dofs, result.seconds)
    if out is not None:
        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        write_vtu(scene, mesh, sol, out)
        plot_profiles(scene, prof, result, out / f"{scene.name}_pressure.png")
    return result


def reports(results: list[Comparison], out: str | Path, header: str = ""):
    """Write report.json and report.md for a list of results."""
    return write_reports(results, Path(out), header)
