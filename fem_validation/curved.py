"""True curved bodies against Hertz: where the small-contact assumption stops holding.

``python -m fem_validation --curved --out DIR`` meshes a steel ball (radius R)
on a flat steel block and in a steel groove (R_g = 1.04 R) with their real
geometry (:mod:`fem_validation.curved_mesh`), presses them together at loads
whose Hertz semi-major axis is a/R = 0.01 to 0.2, and compares a, b and p0
with ``hertz.contact`` at the force each run reached.  Hertz's theory replaces
the bodies by half-spaces and their surfaces by paraboloids, an assumption of
order a/R: the errors measured here are that assumption's cost plus the
discretisation's (the latter is what remains at a/R = 0.01).

Model.  Linear tetrahedra, small strain (elasticity.stiffness).  Contact:
frictionless node-to-surface penalty between non-matching meshes
(:mod:`fem_validation.contact_search`): the ball's surface nodes are the
slaves, the block's surface triangles the master; the gap is linearised about
the undeformed geometry, g = g0 + C u, and an active slave node (g < 0)
carries the force k (-g) along the master normal, k = kappa E* A / h0 (A its
lumped area on the sphere, h0 the element size at the contact), i.e. the
pressure kappa E* (-g) / h0.  The active set is iterated until it stops
changing; linear solves by AMG-preconditioned conjugate gradients with the
settings of :mod:`fem_validation.solve`.  The ball's equator is moved down
rigidly by the imposed approach, the block's bottom is clamped, x = 0 and
y = 0 are planes of symmetry (quarter model; forces are multiplied by 4).

Comparison (as :mod:`fem_validation.compare`, at the force reached): the load
P is the vertical resultant of the contact forces; a, b from the second
moments of the nodal vertical contact forces over the slave nodes' positions
projected on the plane z = 0 (and, as a (arc) and b (arc), over their
geodesic distances on the ball: Hertz does not distinguish the two, which
differ by order (a/R)**2); p0 from the least-squares fit of p**2 to the
nodal pressures above 0.2 max(p); edge a, b from an ellipse through the
midpoints of the sphere's surface edges that join an active and an inactive
node.  Each error less the same scene's at the smallest a/R on the same mesh
level (:func:`net_errors`) is Hertz's own error: the mesh scales with the
Hertz contact, so the discretisation's share is nearly the same at every
load (levels 3 and 4 give the same net errors in a and b to 0.05%, in p0 to
0.17%, where their raw errors differ by up to 0.3%).

The approach (the equator's displacement) is corrected by the Boussinesq
settlement of a half-space at the depth of each far face (R for the ball, 2R
for the block), which these finite bodies do not show; for the hemisphere
that correction is itself only right to order a/R, so the approach error
mixes Hertz's error with the model's truncation and is reported as an
indication.
"""

from __future__ import annotations

import json
import logging
import math
import os
import time
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np
from scipy import sparse

from . import memory
from .contact_search import gap_operator, project
from .curved_mesh import (
    DEFAULT_CURVED_LEVEL,
    CurvedMesh,
    CurvedScene,
    ball_groove,
    build_curved,
    sphere_plane,
)
from .curved_output import curved_document, plot_curved
from .elasticity import rigid_body_modes, stiffness
from .errors import FEMValidationError
from .grade import grade, moment_ellipse, nan_to_none
from .result import ContactResult
from .solve import (
    AMG_MODES,
    KAPPA,
    REBUILD_FRACTION,
    boussinesq_settlement,
    iterate_active_set,
)

log = logging.getLogger("fem_validation")

#: Target a/R of the curved runs (Hertz's semi-major axis over the ball radius).
A_OVER_R = (0.01, 0.02, 0.05, 0.1, 0.2)


def curved_scenes(a_over_r=A_OVER_R) -> list[CurvedScene]:
    """The sphere on a plane and the ball in a groove at each target a/R."""
    return [f(x) for f in (sphere_plane, ball_groove) for x in a_over_r]


@dataclass
class CurvedSolution:
    """Displacements and contact state of one curved run (forces of the whole contact).

    Attributes
    ----------
    u1, u2 : ndarray, shape (n1, 3), (n2, 3)
        Displacements of the ball and the block [m].
    gap : ndarray
        Gap of each slave node [m] (negative: penetration).
    pressure : ndarray
        Contact pressure at each slave node [Pa], zero where inactive.
    active : ndarray of bool
    vertical_force : ndarray
        Vertical contact force on each slave node of the quarter model [N].
    force : float
        Total vertical contact force [N] (quarter model times 4).
    equator_reaction : float
        Vertical force on the ball's equator [N]: equal to ``force`` up to the
        CG residual (a solver diagnostic).
    approach : float
        Imposed approach of the far faces [m].
    penalty : float
        kappa E* / h0 [Pa/m].
    dofs, active_set_iterations, cg_iterations, amg_setups, seconds : solver statistics
    """

    u1: np.ndarray
    u2: np.ndarray
    gap: np.ndarray
    pressure: np.ndarray
    active: np.ndarray
    vertical_force: np.ndarray
    force: float
    equator_reaction: float
    approach: float
    penalty: float
    dofs: int
    active_set_iterations: int
    cg_iterations: list[int] = field(default_factory=list)
    amg_setups: int = 0
    seconds: dict[str, float] = field(default_factory=dict)


def settlement(scene: CurvedScene, mesh: CurvedMesh, load: float) -> float:
    """Boussinesq settlement of half-spaces at the far faces' depths (R and the block's) [m]."""
    m = scene.material
    return (boussinesq_settlement(load, m["E"], m["nu"], scene.radius)
            + boussinesq_settlement(load, m["E"], m["nu"], mesh.block_depth))


def imposed_approach(scene: CurvedScene, mesh: CurvedMesh) -> float:
    """Approach of the far faces aimed at the target load: Hertz's delta less the settlement."""
    return scene.hertz().delta - settlement(scene, mesh, scene.load)


def solve_curved(scene: CurvedScene, mesh: CurvedMesh, approach: float | None = None,
                 kappa: float = KAPPA, rebuild_fraction: float = REBUILD_FRACTION,
                 ) -> CurvedSolution:
    """Solve the curved contact at an imposed approach (active set from Hertz's ellipse).

    Parameters
    ----------
    scene : CurvedScene
    mesh : CurvedMesh
    approach : float, optional
        Downward displacement of the ball's equator [m]; default :func:`imposed_approach`.
    kappa : float
        Penalty factor (stiffness kappa E*/h0 per unit area).
    rebuild_fraction : float
        Rebuild the AMG preconditioner when more than this fraction of the
        active nodes changed state since its setup.

    Raises
    ------
    FEMValidationError
        If a slave node lies on the far faces, the active set does not settle
        or cycles, or conjugate gradients do not converge.
    """
    if not kappa > 0:
        raise ValueError(f"kappa must be > 0, got {kappa!r}")
    t0 = time.perf_counter()
    seconds = {}
    if approach is None:
        approach = imposed_approach(scene, mesh)
    ball, block = mesh.bodies
    n1 = 3 * ball.nvertices
    n = n1 + 3 * block.nvertices
    m = scene.material
    k_ball = stiffness(ball.p, ball.t, m["E"], m["nu"])
    K = sparse.block_diag([k_ball, stiffness(block.p, block.t, m["E"], m["nu"])], format="csr")
    B = np.vstack([rigid_body_modes(ball.p), rigid_body_modes(block.p)])[:, :AMG_MODES]

    fixed = [3 * mesh.fixed[0][:, None] + np.arange(3),
             n1 + 3 * mesh.fixed[1][:, None] + np.arange(3)]
    for nodes, comp in ((mesh.sym_x, 0), (mesh.sym_y, 1)):
        fixed += [3 * nodes[0] + comp, n1 + 3 * nodes[1] + comp]
    fixed = np.unique(np.concatenate([f.ravel() for f in fixed]))
    values = np.zeros(n)
    values[3 * mesh.fixed[0] + 2] = -approach
    keep = np.ones(n)
    keep[fixed] = 0.0

    proj = project(ball.p[:, mesh.slave].T, block.p.T, mesh.master, mesh.master_normals)
    gap_op = gap_operator(proj, 3 * mesh.slave, n1 + 3 * mesh.master, n)
    if np.any(np.abs(gap_op) @ np.abs(values) != 0):
        raise FEMValidationError(f"{scene.name}: a contact node lies on a moved face")
    gap_op = (gap_op @ sparse.diags(keep)).tocsr()  # symmetry dofs are zero: drop their columns
    g0 = proj.gap

    load = -keep * (K @ values)
    rows = np.repeat(np.arange(n), np.diff(K.indptr))
    K.data *= keep[rows] * keep[K.indices]
    K = (K + sparse.diags(1.0 - keep)).tocsr()
    seconds["assembly"] = time.perf_counter() - t0

    penalty = kappa * scene.e_star / mesh.h0
    k_all = penalty * mesh.slave_area
    c = scene.hertz()
    along_x = abs(math.cos(c.major_axis_angle)) >= 0.5
    ax, ay = (c.a, c.b) if along_x else (c.b, c.a)
    xy = ball.p[:2, mesh.slave].T
    active = (xy[:, 0] / ax) ** 2 + (xy[:, 1] / ay) ** 2 < 1.0

    x = np.zeros(n)
    x[fixed] = values[fixed]

    def system_for(act):
        k = np.where(act, k_all, 0.0)
        A = (K + gap_op.T @ sparse.diags(k) @ gap_op).tocsr()
        b = load - gap_op.T @ (k * g0)
        b[fixed] = values[fixed]
        return A, b

    run = iterate_active_set(scene.name, system_for, lambda u: g0 + gap_op @ u, active, x, B,
                             rebuild_fraction, True, seconds, what="nodes")
    x, gap, active = run.x, run.gap, run.active
    normal_force = np.where(active, k_all * -gap, 0.0)
    vertical = normal_force * proj.normal[:, 2]
    reaction = k_ball @ x[:n1]
    seconds["solve"] = time.perf_counter() - t0
    return CurvedSolution(
        u1=x[:n1].reshape(-1, 3), u2=x[n1:].reshape(-1, 3), gap=gap,
        pressure=np.where(active, penalty * -gap, 0.0), active=active,
        vertical_force=vertical, force=4.0 * float(vertical.sum()),
        equator_reaction=-4.0 * float(reaction[3 * mesh.fixed[0] + 2].sum()),
        approach=approach, penalty=penalty, dofs=n, active_set_iterations=run.iterations,
        cg_iterations=run.cg_iterations, amg_setups=run.amg_setups, seconds=seconds)


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


def arc_positions(xyz: np.ndarray, radius: float) -> np.ndarray:
    """Points of the ball's surface mapped to the plane at their geodesic distance.

    Parameters
    ----------
    xyz : ndarray, shape (n, 3)
        Points on the sphere of radius ``radius`` centred at (0, 0, radius) [m].
    radius : float
        Ball radius [m].

    Returns
    -------
    ndarray, shape (n, 2)
        (x, y) scaled to length R theta, theta the angle from the contact point
        seen from the centre [m].
    """
    r = np.hypot(xyz[:, 0], xyz[:, 1])
    theta = np.arctan2(r, radius - xyz[:, 2])
    scale = np.divide(radius * theta, r, out=np.ones_like(r), where=r > 0)
    return xyz[:, :2] * scale[:, None]


#: Tolerances of the curved runs' checks: the issue's target for the discretisation error
#: at the smallest a/R.  At larger a/R a miss is Hertz's own error, which is the finding.
CURVED_TARGETS = {"a_rel_err": 0.015, "b_rel_err": 0.015, "p0_rel_err": 0.015}


def curved_result(scene: CurvedScene, mesh: CurvedMesh, sol: CurvedSolution) -> ContactResult:
    """A curved run as a :class:`~fem_validation.result.ContactResult` (what the grader sees).

    Points: the ball's slave nodes (undeformed); nodal normal forces: their vertical
    contact forces (quarter model); force: the vertical resultant of the whole
    contact; reaction: the equator's; approach: the imposed one plus the Boussinesq
    settlement of both far faces (an indication, see the module docstring).
    """
    corrected = sol.approach + settlement(scene, mesh, sol.force)
    return ContactResult(
        points=mesh.bodies[0].p[:, mesh.slave].T, force=sol.force, pressure=sol.pressure,
        normal_force=sol.vertical_force, symmetry="quarter", triangles=mesh.slave_triangles,
        active=sol.active, approach=corrected, reaction=sol.equator_reaction,
        source=f"fem_validation curved {scene.name}, a/R {scene.a_over_r:g}, level "
               f"{mesh.level}",
        details={"imposed_approach": sol.approach,
                 # The equator's reaction equals the contact force up to the CG residual.
                 "by_construction": ["reaction_rel_err"]})


def compare_curved(scene: CurvedScene, mesh: CurvedMesh, sol: CurvedSolution,
                   seconds: float = 0.0, hertz_at=None,
                   targets: dict[str, float] = CURVED_TARGETS) -> CurvedComparison:
    """Errors of a curved run against Hertz at the force it reached.

    The run becomes a ContactResult (:func:`curved_result`) graded by
    :func:`fem_validation.grade.grade` against ``targets``; a (arc), b (arc) are
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
    memory.reset_peak()
    t0 = time.perf_counter()
    mesh = build_curved(scene, level)
    sol = solve_curved(scene, mesh, kappa=kappa)
    r = compare_curved(scene, mesh, sol, time.perf_counter() - t0)
    r.peak_memory_mb = memory.peak_mb()
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
        Mesh levels (see :mod:`fem_validation.curved_mesh`).
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
