"""True curved bodies end to end: a ball on a plane and in a groove at several loads,
solved (:mod:`fem_validation.solvers.curved`), graded as any other result, and
reported (curved.json, .md, .png)."""

from __future__ import annotations

import json
import logging
import os
import time
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from ..grading.contact import grade, moment_ellipse, nan_to_none
from ..memory import peak_mb, reset_peak
from ..reports.curved import curved_document, plot_curved
from ..solvers.curved import CurvedSolution, arc_positions, curved_result, solve_curved
from ..solvers.curved_mesh import (
    DEFAULT_CURVED_LEVEL,
    CurvedMesh,
    CurvedScene,
    ball_groove,
    build_curved,
    sphere_plane,
)
from ..solvers.solve import KAPPA

log = logging.getLogger("fem_validation")

#: Target a/R of the curved runs (Hertz's semi-major axis over the ball radius).
A_OVER_R = (0.01, 0.02, 0.05, 0.1, 0.2)


def curved_scenes(a_over_r=A_OVER_R) -> list[CurvedScene]:
    """The sphere on a plane and the ball in a groove at each target a/R."""
    return [f(x) for f in (sphere_plane, ball_groove) for x in a_over_r]


@dataclass
class CurvedComparison:
    """One curved run against Hertz at the force it reached; errors are (FEM - Hertz)/Hertz.

    Attributes
    ----------
    scene, level : name and mesh level
    target_a_over_r : the a/R the load was chosen for
    load : vertical contact force reached [N]
    a_over_r : Hertz's semi-major axis at that force over the ball radius
    a_rel_err, b_rel_err : semi-axes from the moments of the vertical nodal forces
    p0_rel_err : peak of the fitted Hertz profile
    peak_nodal_rel_err : largest nodal pressure
    edge_a_rel_err, edge_b_rel_err : ellipse through the active set's edge
    approach_rel_err : equator approach plus the settlement correction against
        Hertz's delta (an indication: the correction is approximate, see the module)
    max_penetration_over_delta : largest penetration over Hertz's delta
    force_rel_err : contact force over the equator's reaction, minus 1 (a solver diagnostic)
    a_arc_rel_err, b_arc_rel_err : as a, b, with the slave nodes placed at their geodesic
        distance from the contact point on the undeformed ball instead of their
        projection on z = 0 (:func:`arc_positions`): Hertz does not say which; the
        two differ by order (a/R)**2
    dofs, seconds, peak_memory_mb : size, wall time (mesh, solve, comparison) [s],
        peak resident memory [MB]
    hertz, fem, solver : details
    net_of_smallest : dict
        Filled by :func:`net_errors`: each error less the same scene's at the
        smallest a/R on the same mesh level (keys a_rel_err, b_rel_err,
        p0_rel_err, approach_rel_err): Hertz's own error with the
        discretisation's removed to first order (the meshes are the same in
        units of the Hertz semi-axes).
    """

    scene: str
    level: int
    target_a_over_r: float
    load: float
    a_over_r: float
    a_rel_err: float
    b_rel_err: float
    p0_rel_err: float
    peak_nodal_rel_err: float
    edge_a_rel_err: float
    edge_b_rel_err: float
    approach_rel_err: float
    max_penetration_over_delta: float
    force_rel_err: float
    dofs: int
    seconds: float
    a_arc_rel_err: float = float("nan")
    b_arc_rel_err: float = float("nan")
    peak_memory_mb: float = float("nan")
    hertz: dict = field(default_factory=dict)
    fem: dict = field(default_factory=dict)
    solver: dict = field(default_factory=dict)
    net_of_smallest: dict = field(default_factory=dict)
    grade: object = field(default=None, repr=False, compare=False)

    def to_dict(self) -> dict:
        """The curved.json row (NaN as None; a_over_r spelled a_over_R, as issue 9 asks),
        with the grade's ``checks`` against CURVED_TARGETS and ``passed``."""
        row = {k.replace("a_over_r", "a_over_R"): getattr(self, k) for k in
               (f.name for f in fields(self)) if k != "grade"}
        if self.grade is not None:
            row["passed"] = self.grade.passed
            row["checks"] = [c.to_dict() for c in self.grade.checks]
        return nan_to_none(row)


#: Tolerances of the curved runs' checks: the issue's target for the discretisation error
#: at the smallest a/R.  At larger a/R a miss is Hertz's own error, which is the finding.
CURVED_TARGETS = {"a_rel_err": 0.015, "b_rel_err": 0.015, "p0_rel_err": 0.015}


def compare_curved(scene: CurvedScene, mesh: CurvedMesh, sol: CurvedSolution,
                   seconds: float = 0.0, hertz_at=None,
                   targets: dict[str, float] = CURVED_TARGETS) -> CurvedComparison:
    """Errors of a curved run against Hertz at the force it reached.

    The run becomes a ContactResult (:func:`curved_result`) graded by
    :func:`fem_validation.grading.contact.grade` against ``targets``; a (arc), b (arc) are
    the grade's moment ellipse over the geodesic positions (:func:`arc_positions`).
    ``hertz_at``: load [N] -> the Hertz contact to compare with (default
    ``scene.hertz``; a deliberately wrong one must fail).
    """
    result = curved_result(scene, mesh, sol)
    g = grade(result, scene, targets, semi_axes="moments", hertz_at=hertz_at)
    m, h = g.metrics, g.hertz
    arc = moment_ellipse(arc_positions(mesh.bodies[0].p[:, mesh.slave].T, scene.radius),
                         sol.vertical_force, quarter=True)
    return CurvedComparison(
        scene=scene.name, level=mesh.level, target_a_over_r=scene.a_over_r, load=sol.force,
        a_over_r=h["a"] / scene.radius, a_rel_err=m["a_rel_err"],
        b_rel_err=m["b_rel_err"], p0_rel_err=m["p0_rel_err"],
        peak_nodal_rel_err=m["peak_nodal_rel_err"],
        edge_a_rel_err=m["edge_a_rel_err"], edge_b_rel_err=m["edge_b_rel_err"],
        approach_rel_err=m["approach_rel_err"],
        max_penetration_over_delta=float(np.max(-sol.gap[sol.active]) / h["delta"]),
        force_rel_err=m["reaction_rel_err"], dofs=sol.dofs, seconds=seconds,
        a_arc_rel_err=arc["a"] / h["a"] - 1, b_arc_rel_err=arc["b"] / h["b"] - 1,
        hertz={"a": h["a"], "b": h["b"], "p0": h["p0"], "delta": h["delta"],
               "alpha": h["alpha"], "target_load": scene.load},
        fem={"a": g.fem["moments"]["a"], "b": g.fem["moments"]["b"], "p0": g.fem["p0"],
             "fit": g.fem["fit"], "edge": g.fem["edge"], "imposed_approach": sol.approach,
             "approach": result.approach},
        solver={"h0_over_b": mesh.h0 / scene.hertz().b, "penalty_Pa_per_m": sol.penalty,
                "slave_nodes": len(mesh.slave), "master_triangles": len(mesh.master),
                "active_nodes": int(sol.active.sum()),
                "elements": int(mesh.bodies[0].nelements + mesh.bodies[1].nelements),
                "active_set_iterations": sol.active_set_iterations,
                "cg_iterations": sol.cg_iterations, "amg_setups": sol.amg_setups,
                "stage_seconds": sol.seconds},
        grade=g)


def validate_curved(scene: CurvedScene, level: int = DEFAULT_CURVED_LEVEL,
                    kappa: float = KAPPA) -> CurvedComparison:
    """Mesh, solve and compare one curved scene."""
    reset_peak()
    t0 = time.perf_counter()
    mesh = build_curved(scene, level)
    sol = solve_curved(scene, mesh, kappa=kappa)
    r = compare_curved(scene, mesh, sol, time.perf_counter() - t0)
    r.peak_memory_mb = peak_mb()
    log.info("%s at a/R %.3g: a %+.2f%%, b %+.2f%%, p0 %+.2f%%, approach %+.2f%%, %d dofs, "
             "%.1f s, %.0f MB", r.scene, r.a_over_r, 100 * r.a_rel_err, 100 * r.b_rel_err,
             100 * r.p0_rel_err, 100 * r.approach_rel_err, r.dofs, r.seconds, r.peak_memory_mb)
    return r


NET = ("a_rel_err", "b_rel_err", "p0_rel_err", "approach_rel_err", "a_arc_rel_err",
       "b_arc_rel_err")


def net_errors(results: list[CurvedComparison]) -> list[CurvedComparison]:
    """Fill each result's ``net_of_smallest``: its errors less those of the same scene and
    level at the smallest a/R (the discretisation's share, nearly the same at every load
    because the mesh scales with the Hertz contact).  Returns ``results``."""
    for r in results:
        base = min((q for q in results if q.scene == r.scene and q.level == r.level),
                   key=lambda q: q.a_over_r)
        r.net_of_smallest = {k: getattr(r, k) - getattr(base, k) for k in NET}
        r.net_of_smallest["reference_a_over_r"] = base.a_over_r
    return results


def run_curved(out: str | Path, levels=(DEFAULT_CURVED_LEVEL,), a_over_r=A_OVER_R,
               command: str = "") -> tuple[list[CurvedComparison], Path, Path, Path]:
    """Run every curved scene at each level; write curved.json, curved.md and curved.png.

    Parameters
    ----------
    out : path
        Output directory (created).
    levels : sequence of int
        Mesh levels (see :mod:`fem_validation.solvers.curved_mesh`).
    a_over_r : sequence of float
        Target Hertz semi-major axes over the ball radius.
    command : str
        The command line, quoted in curved.md.

    Returns
    -------
    (results, json_path, md_path, png_path)
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    results = net_errors([validate_curved(s, level) for level in levels
                          for s in curved_scenes(a_over_r)])
    json_path, md_path, png_path = out / "curved.json", out / "curved.md", out / "curved.png"
    json_path.write_text(json.dumps([r.to_dict() for r in results], indent=1))
    header = (f"Curved bodies, level {', '.join(map(str, levels))}; "
              f"{time.perf_counter() - t0:.0f} s in all on {os.cpu_count()} cores"
              + (f"; `{command}`" if command else "") + ".\n")
    md_path.write_text(curved_document(results, header, CURVED_TARGETS))
    plot_curved(results, png_path)
    return results, json_path, md_path, png_path
