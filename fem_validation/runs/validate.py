"""The block validation end to end: solve a scene on block meshes, grade it against
Hertz as any other result (:mod:`fem_validation.grading.contact`), and write its
VTU files, figure and report row (:class:`Comparison`)."""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

from ..grading import contact as _grade
from ..grading.contact import FIELD_SETS, TARGETS, Grade, nan_to_none, pressure_profiles
from ..scenes import Scene
from ..solvers.blocks import block_result
from ..solvers.mesh import BlockMesh
from ..solvers.solve import ContactSolution

log = logging.getLogger("fem_validation")

@dataclass
class Comparison:
    """One scene's finite-element result against Hertz at matched force.

    Relative errors are (FEM - Hertz)/Hertz.

    Attributes
    ----------
    scene, level, alpha, load : name, mesh level, Hertz's alpha, force reached [N]
    dofs, seconds : unknowns and wall time (mesh, solve, comparison) [s]
    a_rel_err, b_rel_err : semi-axes from the moments of the contact forces
    p0_rel_err : peak pressure of the fitted Hertz profile
    peak_nodal_rel_err : largest nodal pressure
    rms_major, rms_minor : RMS pressure difference along the axes, over Hertz's p0
    edge_a_rel_err, edge_b_rel_err : semi-axes of the ellipse fitted to the
        active set's edge
    approach_rel_err : approach (corrected by the blocks' settlement) against
        Hertz's delta at the force reached
    angle_err_deg : major axis against Hertz's [deg]; NaN for quarter models and circles
    max_penetration_over_delta : largest penetration of a pair over Hertz's delta
    force_rel_err : contact force over the reaction of body 1's loaded face, minus 1.
        Zero by construction up to the CG residual (the z translation is in the
        stiffness's null space): a solver diagnostic, not a check of the model.
    von_mises_rel_err, z_von_mises_rel_err : largest von Mises stress on the z axis
        and its depth against ``Contact.subsurface(body)``: the body with the
        larger |error| of each (signed; both bodies in ``stress``)
    stress_rms_axis, stress_rms_major_plane, stress_rms_minor_plane : RMS difference
        of the six stress components from ``Contact.stress`` over the sample
        points on the z axis, in the plane through the major axis and in the
        plane through the minor axis, over Hertz's p0; the larger of the two
        bodies (see :func:`field_errors`)
    peak_memory_mb : peak resident memory of the process during the run [MB]
        (NaN where not measurable)
    hertz, fem, solver : details
    stress : dict
        Per body (``"body1"``, ``"body2"``): FEM and Hertz von Mises maxima
        [Pa] and depths [m], their errors, and the field RMS of each set.
    axis_stress : dict
        The FEM stress on the z axis of each body, for comparison with Hertz's
        subsurface stresses: ``{"body1": {"depth": (n,) [m], "stress": (n, 3, 3) [Pa]},
        "body2": ...}``, patch-recovered values at the mesh nodes on the axis
        (:func:`recovered_stress`), in the Hertz ellipse's frame (x along the
        major axis, y along the minor axis, z into the body; tension positive).
        Not in the report rows (:meth:`to_dict`).
    nodal_stress : tuple of two ndarrays
        The patch-recovered stress at every node of each body, (n, 3, 3) [Pa],
        in the mesh frame (what :func:`fem_validation.solvers.vtu.write_vtu` writes).
        Not in the report rows.
    """

    scene: str
    level: int
    alpha: float
    load: float
    dofs: int
    seconds: float
    a_rel_err: float
    b_rel_err: float
    p0_rel_err: float
    peak_nodal_rel_err: float
    rms_major: float
    rms_minor: float
    force_rel_err: float
    approach_rel_err: float
    angle_err_deg: float
    max_penetration_over_delta: float
    edge_a_rel_err: float = float("nan")
    edge_b_rel_err: float = float("nan")
    von_mises_rel_err: float = float("nan")
    z_von_mises_rel_err: float = float("nan")
    stress_rms_axis: float = float("nan")
    stress_rms_major_plane: float = float("nan")
    stress_rms_minor_plane: float = float("nan")
    peak_memory_mb: float = float("nan")
    hertz: dict = field(default_factory=dict)
    fem: dict = field(default_factory=dict)
    solver: dict = field(default_factory=dict)
    stress: dict = field(default_factory=dict)
    axis_stress: dict = field(default_factory=dict, repr=False)
    nodal_stress: tuple = field(default=(), repr=False)
    grade: Grade | None = field(default=None, repr=False, compare=False)

    def to_dict(self) -> dict:
        """The report row: every attribute but ``axis_stress``, ``nodal_stress`` and
        ``grade``, plus ``checks`` (the grade's checks against TARGETS) and ``passed``;
        NaN becomes None."""
        skip = ("axis_stress", "nodal_stress", "grade")
        row = {f.name: getattr(self, f.name) for f in fields(self) if f.name not in skip}
        if self.grade is not None:
            row["passed"] = self.grade.passed
            row["checks"] = [c.to_dict() for c in self.grade.checks]
        return nan_to_none(row)


def check(result: Comparison, targets: dict[str, float] = TARGETS) -> list[str]:
    """The targets a result misses, as messages (empty if it meets them all).

    Parameters
    ----------
    result : Comparison
    targets : dict
        Attribute name -> largest allowed |value|.
    """
    missed = []
    for key, limit in targets.items():
        value = getattr(result, key)
        if not abs(value) <= limit:
            missed.append(f"{result.scene}: |{key}| = {abs(value):.3g} > {limit:.3g}")
    return missed


def compare_with_hertz(scene: Scene, mesh: BlockMesh, sol: ContactSolution, level: int,
                       seconds: float, prof: dict | None = None,
                       hertz_at: Callable | None = None,
                       targets: dict[str, float] = TARGETS) -> Comparison:
    """Errors of the finite-element solution against Hertz at the force it reached.

    The run becomes a ContactResult (:func:`block_result`) graded by
    :func:`fem_validation.grading.contact.grade` against ``targets``; the Comparison is the
    report row of that grade plus the solver's own figures.

    Parameters
    ----------
    scene, mesh, sol : the run
    level : int
        Its mesh level (reported).
    seconds : float
        Wall time so far [s] (reported).
    prof : dict, optional
        Unused: the grade computes the profiles (kept for callers that pass it).
    hertz_at : callable, optional
        load [N] -> the Hertz contact to compare with; default ``scene.hertz``.
        (A deliberately wrong reference must make the comparison fail.)
    targets : dict
        The tolerances of the grade's checks.
    """
    result = block_result(scene, mesh, sol)
    g = _grade.grade(result, scene, targets, semi_axes="moments", hertz_at=hertz_at)
    m, h = g.metrics, g.hertz
    fem = {**g.fem["moments"], "p0": g.fem["p0"], "fit": g.fem["fit"], "edge": g.fem["edge"],
           "peak_nodal_pressure": g.fem["peak_nodal_pressure"], "approach": result.approach,
           "imposed_approach": sol.approach,
           "settlement_correction": result.details["settlement_correction"],
           "top_reaction": sol.top_reaction}
    return Comparison(
        scene=scene.name, level=level, alpha=h["alpha"], load=sol.force, dofs=sol.dofs,
        seconds=seconds,
        a_rel_err=m["a_rel_err"], b_rel_err=m["b_rel_err"], p0_rel_err=m["p0_rel_err"],
        peak_nodal_rel_err=m["peak_nodal_rel_err"],
        rms_major=m["rms_major"], rms_minor=m["rms_minor"],
        force_rel_err=m["reaction_rel_err"], approach_rel_err=m["approach_rel_err"],
        angle_err_deg=m["angle_err_deg"],
        max_penetration_over_delta=float(np.max(-sol.gap[sol.active]) / h["delta"]),
        edge_a_rel_err=m["edge_a_rel_err"], edge_b_rel_err=m["edge_b_rel_err"],
        hertz={"a": h["a"], "b": h["b"], "p0": h["p0"], "delta": h["delta"],
               "major_axis_angle_deg": h["major_axis_angle_deg"], "target_load": scene.load},
        fem=fem,
        solver={"h0_over_b": mesh.h0 / scene.hertz().b, "block_over_a": mesh.extent / h["a"],
                "quarter_model": mesh.quarter, "penalty_Pa_per_m": sol.penalty,
                "active_pairs": int(sol.active.sum()), "contact_pairs": len(mesh.pairs),
                "elements": int(mesh.bodies[0].nelements + mesh.bodies[1].nelements),
                "active_set_iterations": sol.active_set_iterations,
                "cg_iterations": sol.cg_iterations, "amg_setups": sol.amg_setups,
                "stage_seconds": sol.seconds},
        von_mises_rel_err=m["von_mises_rel_err"], z_von_mises_rel_err=m["z_von_mises_rel_err"],
        **{f"stress_rms_{name}": m[f"stress_rms_{name}"] for name in FIELD_SETS},
        stress=g.stress, axis_stress=g.axis_stress,
        nodal_stress=tuple(st.stress for st in result.stress), grade=g)


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
        :func:`fem_validation.solvers.solve.initial_active_set`); "nested" solves
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
    from ..memory import peak_mb, reset_peak
    from ..solvers.mesh import DEFAULT_LEVEL, build
    from ..solvers.solve import KAPPA, REBUILD_FRACTION, solve_contact, transferred_active_set
    from .validate import compare_with_hertz, profiles

    level = DEFAULT_LEVEL if level is None else level
    kappa = KAPPA if kappa is None else kappa
    reset_peak()
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
    result.peak_memory_mb = peak_mb()
    log.info("%s: a %+.2f%%, b %+.2f%%, p0 %+.2f%%, RMS %.2f%% / %.2f%% of p0, edge %+.2f%% / "
             "%+.2f%%, approach %+.2f%%, %d dofs, %.1f s, %.0f MB", scene.name,
             100 * result.a_rel_err, 100 * result.b_rel_err, 100 * result.p0_rel_err,
             100 * result.rms_major, 100 * result.rms_minor, 100 * result.edge_a_rel_err,
             100 * result.edge_b_rel_err, 100 * result.approach_rel_err, result.dofs,
             result.seconds, result.peak_memory_mb)
    if out is not None:
        from ..reports.blocks import plot_profiles
        from ..solvers.vtu import write_vtu

        out = Path(out)
        out.mkdir(parents=True, exist_ok=True)
        write_vtu(scene, mesh, sol, out, nodal_stress=result.nodal_stress)
        plot_profiles(scene, prof, result, out / f"{scene.name}_pressure.png")
    return result


def profiles(scene: Scene, mesh: BlockMesh, sol: ContactSolution, n: int = 121,
             reference=None) -> dict:
    """FEM and Hertz pressure along the Hertz ellipse's major and minor axes
    (:func:`fem_validation.grading.contact.pressure_profiles` on the contact face).

    ``reference`` is the Hertz contact to compare with (default: the scene's at
    the force reached).
    """
    c = scene.hertz(sol.force) if reference is None else reference
    xy = mesh.bodies[0].p[:2, mesh.pairs[:, 0]].T
    return pressure_profiles(c, xy, mesh.triangles, sol.pressure,
                             (mesh.quarter, mesh.quarter), n)
