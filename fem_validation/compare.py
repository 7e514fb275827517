"""Compare a finite-element contact solution with Hertz.

Method (stated in every report):

* **Force**: the contact force the run reached, P = sum of the penalty forces;
  Hertz is evaluated at that P ("matched force").
* **Semi-axes**: from the second moments of the nodal contact forces f_i,
  M = sum f_i (x_i, y_i)^T (x_i, y_i) / P, which for Hertz's pressure equal
  diag(a**2, b**2)/5 in the ellipse's frame: a, b are sqrt(5 eig(M)).  An
  integral over all nodes, insensitive to the nodal noise of the pressure.
* **Peak pressure**: p0 of a least-squares fit of the Hertz profile
  p**2 = p0**2 - (x, y) Q (x, y)^T to the nodal pressures above 0.2 max(p).
  The largest nodal pressure is reported beside it.
* **Profiles**: the nodal pressure interpolated linearly on the contact face
  along the Hertz ellipse's major and minor axes, up to 1.2 semi-axes; RMS
  difference from Hertz's pressure, over p0.
* **Edge of the active set**: an ellipse fitted (least squares on
  x**2/a**2 + y**2/b**2 = 1, with the mixed term where the model is whole) to
  the midpoints of the contact face's edges that join an active and an
  inactive pair; its semi-axes against Hertz's.  Independent of the pressures.
* **Force against approach**: the approach of the far faces plus the
  Boussinesq settlement of a half-space at the blocks' depth (which clamped
  blocks do not show), against Hertz's delta at the force reached.
* **Orientation**: the major axis of the moment ellipse against Hertz's, only
  where the model is whole (a quarter model has the axes by construction).

Errors are (FEM - Hertz) / Hertz.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass, field

import numpy as np

from .elasticity import element_stress, nodal_average
from .mesh import BlockMesh
from .scenes import Scene
from .solve import ContactSolution, boussinesq_settlement

PROFILE_EXTENT = 1.2  # profiles run to 1.2 semi-axes
FIT_THRESHOLD = 0.2  # fit on nodes with p > 0.2 max(p)

#: The targets of the default level (issue 9): |error| at most these.
TARGETS = {"a_rel_err": 0.005, "b_rel_err": 0.005, "p0_rel_err": 0.005, "rms_major": 0.015,
           "rms_minor": 0.015}


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
    peak_memory_mb : peak resident memory of the process during the run [MB]
        (NaN where not measurable)
    hertz, fem, solver : details
    axis_stress : dict
        The FEM stress on the z axis of each body, for comparison with Hertz's
        subsurface stresses: ``{"body1": {"depth": (n,) [m], "stress": (n, 3, 3) [Pa]},
        "body2": ...}``, nodal (volume-averaged) values at the mesh nodes on
        the axis, in the Hertz ellipse's frame (x along the major axis, y along
        the minor axis, z into the body; tension positive).  Not in the report
        rows (:meth:`to_dict`).
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
    peak_memory_mb: float = float("nan")
    hertz: dict = field(default_factory=dict)
    fem: dict = field(default_factory=dict)
    solver: dict = field(default_factory=dict)
    axis_stress: dict = field(default_factory=dict, repr=False)

    def to_dict(self) -> dict:
        """The report row: every attribute but ``axis_stress``; NaN becomes None."""
        row = asdict(self)
        del row["axis_stress"]
        return _nan_to_none(row)


def _nan_to_none(value):
    if isinstance(value, dict):
        return {k: _nan_to_none(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_nan_to_none(v) for v in value]
    if isinstance(value, float) and math.isnan(value):
        return None
    return value


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


def _axis_angle(v: np.ndarray, major: int) -> float:
    """Angle of eigenvector ``major`` from the x axis, in (-90, 90] degrees."""
    angle = math.degrees(math.atan2(v[1, major], v[0, major]))
    return angle - 180 if angle > 90 else angle + 180 if angle <= -90 else angle


def moment_ellipse(xy: np.ndarray, force: np.ndarray, quarter: bool) -> dict:
    """Semi-axes a >= b and major-axis angle from the second moments of nodal forces.

    Parameters
    ----------
    xy : ndarray, shape (n, 2)
        Positions [m].
    force : ndarray, shape (n,)
        Nodal forces [N] (any consistent unit).
    quarter : bool
        The forces are those of a quarter model: the mixed moment of the whole
        contact is zero by symmetry.

    Returns
    -------
    dict
        a, b [m] and major_axis_angle_deg.
    """
    total = force.sum()
    mxx, myy = (force * xy[:, 0] ** 2).sum(), (force * xy[:, 1] ** 2).sum()
    mxy = 0.0 if quarter else (force * xy[:, 0] * xy[:, 1]).sum()
    w, v = np.linalg.eigh(np.array([[mxx, mxy], [mxy, myy]]) / total)
    return {"a": math.sqrt(5 * w[1]), "b": math.sqrt(5 * w[0]),
            "major_axis_angle_deg": _axis_angle(v, 1)}


def fit_ellipse(xy: np.ndarray, p: np.ndarray) -> dict:
    """Least-squares fit of p**2 = c0 - (x, y) Q (x, y)^T on nodes above FIT_THRESHOLD max(p).

    Returns p0, the semi-axes a >= b and the major axis's angle from the x axis
    in (-90, 90] degrees.
    """
    sel = p > FIT_THRESHOLD * p.max()
    x, y = xy[sel, 0], xy[sel, 1]
    design = np.column_stack([np.ones(sel.sum()), -x * x, -x * y, -y * y])
    (c0, qxx, qxy, qyy), *_ = np.linalg.lstsq(design, p[sel] ** 2, rcond=None)
    w, v = np.linalg.eigh(np.array([[qxx, qxy / 2], [qxy / 2, qyy]]))
    return {"p0": math.sqrt(c0), "a": math.sqrt(c0 / w[0]), "b": math.sqrt(c0 / w[1]),
            "major_axis_angle_deg": _axis_angle(v, 0), "fit_nodes": int(sel.sum())}


def active_edge_points(xy: np.ndarray, tri: np.ndarray, active: np.ndarray) -> np.ndarray:
    """Midpoints of the face's edges that join an active and an inactive pair, (k, 2) [m]."""
    edges = np.sort(np.concatenate([tri[:, [0, 1]], tri[:, [1, 2]], tri[:, [2, 0]]]), axis=1)
    edges = np.unique(edges, axis=0)
    cut = edges[active[edges[:, 0]] != active[edges[:, 1]]]
    return 0.5 * (xy[cut[:, 0]] + xy[cut[:, 1]])


def edge_ellipse(points: np.ndarray, quarter: bool) -> dict:
    """Ellipse through points (k, 2) centred at the origin, by least squares.

    Fits u x**2 + v x y + w y**2 = 1 (v = 0 for a quarter model).

    Returns
    -------
    dict
        a >= b [m], major_axis_angle_deg and the number of points.

    Raises
    ------
    ValueError
        If fewer than 3 points are given or the fit is not an ellipse.
    """
    if len(points) < 3:
        raise ValueError(f"points must hold 3 or more points, got {len(points)}")
    x, y = points[:, 0], points[:, 1]
    cols = [x * x, y * y] if quarter else [x * x, y * y, x * y]
    coef, *_ = np.linalg.lstsq(np.column_stack(cols), np.ones(len(x)), rcond=None)
    u, w = coef[0], coef[1]
    v = 0.0 if quarter else coef[2]
    eig, vec = np.linalg.eigh(np.array([[u, v / 2], [v / 2, w]]))
    if not eig[0] > 0:
        raise ValueError(f"the points do not lie on an ellipse (quadratic form {coef})")
    return {"a": 1 / math.sqrt(eig[0]), "b": 1 / math.sqrt(eig[1]),
            "major_axis_angle_deg": _axis_angle(vec, 0), "points": len(points)}


def interpolate_on_face(xy: np.ndarray, tri: np.ndarray, values: np.ndarray,
                        points: np.ndarray) -> np.ndarray:
    """Piecewise-linear interpolation on the triangulated contact face (NaN outside)."""
    a, b, c = xy[tri[:, 0]], xy[tri[:, 1]], xy[tri[:, 2]]
    det = (b[:, 0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (b[:, 1] - a[:, 1])
    out = np.full(len(points), np.nan)
    for i, q in enumerate(points):
        l1 = ((q[0] - a[:, 0]) * (c[:, 1] - a[:, 1]) - (c[:, 0] - a[:, 0]) * (q[1] - a[:, 1])) / det
        l2 = ((b[:, 0] - a[:, 0]) * (q[1] - a[:, 1]) - (q[0] - a[:, 0]) * (b[:, 1] - a[:, 1])) / det
        inside = np.nonzero((l1 >= -1e-12) & (l2 >= -1e-12) & (l1 + l2 <= 1 + 1e-12))[0]
        if inside.size:
            t = inside[0]
            out[i] = ((1 - l1[t] - l2[t]) * values[tri[t, 0]] + l1[t] * values[tri[t, 1]]
                      + l2[t] * values[tri[t, 2]])
    return out


def profiles(scene: Scene, mesh: BlockMesh, sol: ContactSolution, n: int = 121,
             reference=None) -> dict:
    """FEM and Hertz pressure along the Hertz ellipse's major and minor axes.

    ``reference`` is the Hertz contact to compare with (default: the scene's at
    the force reached).
    """
    c = scene.hertz(sol.force) if reference is None else reference
    xy = mesh.bodies[0].p[:2, mesh.pairs[:, 0]].T
    theta = c.major_axis_angle
    out = {}
    for name, semi, direction in (("major", c.a, (math.cos(theta), math.sin(theta))),
                                  ("minor", c.b, (-math.sin(theta), math.cos(theta)))):
        lo = 0.0 if mesh.quarter else -PROFILE_EXTENT * semi
        s = np.linspace(lo, PROFILE_EXTENT * semi, n)
        pts = np.outer(s, direction)
        if mesh.quarter:  # the quarter model holds the positive half-axes
            pts = np.abs(pts)
        fem = interpolate_on_face(xy, mesh.triangles, sol.pressure, pts)
        hz = c.pressure(s if name == "major" else 0.0, s if name == "minor" else 0.0)
        out[name] = {"s": s, "fem": fem, "hertz": np.asarray(hz, dtype=float),
                     "rms": float(np.sqrt(np.nanmean((fem - hz) ** 2)) / c.p0)}
    return out


def axis_stress(scene: Scene, mesh: BlockMesh, sol: ContactSolution) -> dict:
    """The FEM stress at the nodes on the z axis of each body (see Comparison.axis_stress).

    Element stresses averaged to the nodes by volume; in a quarter model the
    nodes on the axis see a quarter of their neighbourhood, which by symmetry
    gives the same normal stresses as the whole.
    """
    theta = scene.hertz().major_axis_angle
    c, s = math.cos(theta), math.sin(theta)
    out = {}
    for i, (m, u, body) in enumerate(zip(mesh.bodies, (sol.u1, sol.u2),
                                         (scene.body1, scene.body2), strict=True)):
        nodes = mesh.axis[i]
        near = np.any(np.isin(m.t, nodes), axis=0)
        stress = nodal_average(m.p, m.t[:, near], element_stress(m.p, m.t[:, near], u, body.E,
                                                                 body.nu))[nodes]
        flip = 1.0 if i == 0 else -1.0  # z into the body
        rot = np.array([[c, s, 0.0], [-s, c, 0.0], [0.0, 0.0, flip]])
        out[f"body{i + 1}"] = {"depth": np.abs(m.p[2, nodes]),
                               "stress": np.einsum("ij,njk,lk->nil", rot, stress, rot)}
    return out


def compare_with_hertz(scene: Scene, mesh: BlockMesh, sol: ContactSolution, level: int,
                       seconds: float, prof: dict | None = None,
                       hertz_at: Callable | None = None) -> Comparison:
    """Errors of the finite-element solution against Hertz at the force it reached.

    Parameters
    ----------
    scene, mesh, sol : the run
    level : int
        Its mesh level (reported).
    seconds : float
        Wall time so far [s] (reported).
    prof : dict, optional
        The result of :func:`profiles`, computed here if not given.
    hertz_at : callable, optional
        load [N] -> the Hertz contact to compare with; default ``scene.hertz``.
        (A deliberately wrong reference must make the comparison fail.)
    """
    c = (scene.hertz if hertz_at is None else hertz_at)(sol.force)
    xy = mesh.bodies[0].p[:2, mesh.pairs[:, 0]].T
    fit = fit_ellipse(xy, sol.pressure)
    moments = moment_ellipse(xy, sol.pressure * mesh.pair_area, mesh.quarter)
    edge = edge_ellipse(active_edge_points(xy, mesh.triangles, sol.active), mesh.quarter)
    prof = profiles(scene, mesh, sol, reference=c) if prof is None else prof
    settlement = sum(boussinesq_settlement(sol.force, b.E, b.nu, mesh.depth)
                     for b in (scene.body1, scene.body2))
    approach = sol.approach + settlement
    hertz_angle = math.degrees(c.major_axis_angle)
    d_angle = (moments["major_axis_angle_deg"] - hertz_angle + 90) % 180 - 90
    no_angle = c.alpha < 1 + 1e-9 or mesh.quarter
    return Comparison(
        scene=scene.name, level=level, alpha=float(c.alpha), load=sol.force, dofs=sol.dofs,
        seconds=seconds,
        a_rel_err=moments["a"] / c.a - 1, b_rel_err=moments["b"] / c.b - 1,
        p0_rel_err=fit["p0"] / c.p0 - 1, peak_nodal_rel_err=float(sol.pressure.max() / c.p0 - 1),
        rms_major=prof["major"]["rms"], rms_minor=prof["minor"]["rms"],
        force_rel_err=sol.force / sol.top_reaction - 1,
        approach_rel_err=approach / c.delta - 1,
        angle_err_deg=float("nan") if no_angle else d_angle,
        max_penetration_over_delta=float(np.max(-sol.gap[sol.active]) / c.delta),
        edge_a_rel_err=edge["a"] / c.a - 1, edge_b_rel_err=edge["b"] / c.b - 1,
        hertz={"a": c.a, "b": c.b, "p0": c.p0, "delta": c.delta,
               "major_axis_angle_deg": hertz_angle, "target_load": scene.load},
        fem={**moments, "p0": fit["p0"], "fit": fit, "edge": edge,
             "peak_nodal_pressure": float(sol.pressure.max()), "approach": approach,
             "imposed_approach": sol.approach, "settlement_correction": settlement,
             "top_reaction": sol.top_reaction},
        solver={"h0_over_b": mesh.h0 / scene.hertz().b, "block_over_a": mesh.extent / c.a,
                "quarter_model": mesh.quarter, "penalty_Pa_per_m": sol.penalty,
                "active_pairs": int(sol.active.sum()), "contact_pairs": len(mesh.pairs),
                "elements": int(mesh.bodies[0].nelements + mesh.bodies[1].nelements),
                "active_set_iterations": sol.active_set_iterations,
                "cg_iterations": sol.cg_iterations, "amg_setups": sol.amg_setups,
                "stage_seconds": sol.seconds},
        axis_stress=axis_stress(scene, mesh, sol))
