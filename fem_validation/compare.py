"""Compare a finite-element contact solution with Hertz, and write what was found.

Method (stated in every report):

* **Force**: the contact force the run reached, P = sum of the penalty forces;
  Hertz is evaluated at that P ("matched force").  Force balance compares it
  with the reaction on body 1's loaded face.
* **Semi-axes and orientation**: from the second moments of the nodal contact
  forces f_i, M = sum f_i (x_i, y_i)^T (x_i, y_i) / P, which for Hertz's
  pressure equal diag(a**2, b**2)/5 in the ellipse's frame: a, b are
  sqrt(5 eig(M)) and the major axis is the eigenvector of the larger
  eigenvalue.  An integral over all nodes, insensitive to the nodal noise of
  the pressure.
* **Peak pressure**: p0 of a least-squares fit of the Hertz profile
  p**2 = p0**2 - (x, y) Q (x, y)^T to the nodal pressures above 0.2 max(p)
  (the fit's own semi-axes are reported too).  The largest nodal pressure is
  reported beside it.
* **Profiles**: the nodal pressure interpolated linearly on the contact face
  along the Hertz ellipse's major and minor axes, up to 1.2 semi-axes; RMS
  difference from Hertz's pressure, over p0.
* **Approach**: the imposed approach of the far faces plus the Boussinesq
  settlement of a half-space at the blocks' depth (which clamped blocks do
  not show), against Hertz's delta.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np
from skfem import Basis, ElementTetP1, ElementVector

from .mesh import BlockMesh
from .scenes import Scene
from .solve import ContactSolution, boussinesq_settlement, lame

PROFILE_EXTENT = 1.2  # profiles run to 1.2 semi-axes
FIT_THRESHOLD = 0.2  # fit on nodes with p > 0.2 max(p)


@dataclass
class Comparison:
    """One scene's finite-element result against Hertz at matched force.

    Relative errors are (FEM - Hertz)/Hertz; rms_major and rms_minor are the
    RMS pressure differences along the axes over Hertz's p0; force_rel_err is
    the force balance (contact force against the loaded face's reaction).
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
    hertz: dict = field(default_factory=dict)
    fem: dict = field(default_factory=dict)
    solver: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        return asdict(self)


def _axis_angle(w: np.ndarray, v: np.ndarray, major: int) -> float:
    """Angle of eigenvector ``major`` from the x axis, in (-90, 90] degrees."""
    angle = math.degrees(math.atan2(v[1, major], v[0, major]))
    return angle - 180 if angle > 90 else angle + 180 if angle <= -90 else angle


def moment_ellipse(xy: np.ndarray, force: np.ndarray, quarter: bool) -> dict:
    """Semi-axes a >= b and major-axis angle from the second moments of nodal forces.

    For the quarter model the mixed moment of the whole contact is zero by symmetry.
    """
    total = force.sum()
    mxx, myy = (force * xy[:, 0] ** 2).sum(), (force * xy[:, 1] ** 2).sum()
    mxy = 0.0 if quarter else (force * xy[:, 0] * xy[:, 1]).sum()
    w, v = np.linalg.eigh(np.array([[mxx, mxy], [mxy, myy]]) / total)
    return {"a": math.sqrt(5 * w[1]), "b": math.sqrt(5 * w[0]),
            "major_axis_angle_deg": _axis_angle(w, v, 1)}


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
            "major_axis_angle_deg": _axis_angle(w, v, 0), "fit_nodes": int(sel.sum())}


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


def profiles(scene: Scene, mesh: BlockMesh, sol: ContactSolution, n: int = 121) -> dict:
    """FEM and Hertz pressure along the Hertz ellipse's major and minor axes."""
    c = scene.hertz(sol.force)
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


def compare_with_hertz(scene: Scene, mesh: BlockMesh, sol: ContactSolution, level: int,
                       seconds: float, prof: dict | None = None) -> Comparison:
    """Errors of the finite-element solution against Hertz at the force it reached.

    ``prof`` is the result of :func:`profiles`, computed here if not given.
    """
    c = scene.hertz(sol.force)
    xy = mesh.bodies[0].p[:2, mesh.pairs[:, 0]].T
    fit = fit_ellipse(xy, sol.pressure)
    moments = moment_ellipse(xy, sol.pressure * mesh.pair_area, mesh.quarter)
    prof = profiles(scene, mesh, sol) if prof is None else prof
    settlement = sum(boussinesq_settlement(sol.force, b.E, b.nu, mesh.depth)
                     for b in (scene.body1, scene.body2))
    approach = sol.approach + settlement
    hertz_angle = math.degrees(c.major_axis_angle)
    d_angle = (moments["major_axis_angle_deg"] - hertz_angle + 90) % 180 - 90
    circular = c.alpha < 1 + 1e-9
    return Comparison(
        scene=scene.name, level=level, alpha=float(c.alpha), load=sol.force, dofs=sol.dofs,
        seconds=seconds,
        a_rel_err=moments["a"] / c.a - 1, b_rel_err=moments["b"] / c.b - 1,
        p0_rel_err=fit["p0"] / c.p0 - 1, peak_nodal_rel_err=float(sol.pressure.max() / c.p0 - 1),
        rms_major=prof["major"]["rms"], rms_minor=prof["minor"]["rms"],
        force_rel_err=sol.force / sol.top_reaction - 1,
        approach_rel_err=approach / c.delta - 1,
        angle_err_deg=float("nan") if circular else d_angle,
        max_penetration_over_delta=float(np.max(-sol.gap[sol.active]) / c.delta),
        hertz={"a": c.a, "b": c.b, "p0": c.p0, "delta": c.delta,
               "major_axis_angle_deg": hertz_angle, "target_load": scene.load},
        fem={**moments, "p0": fit["p0"], "fit": fit,
             "peak_nodal_pressure": float(sol.pressure.max()), "approach": approach,
             "imposed_approach": sol.approach, "settlement_correction": settlement,
             "top_reaction": sol.top_reaction},
        solver={"h0_over_b": mesh.h0 / scene.hertz().b, "block_over_a": mesh.extent / c.a,
                "quarter_model": mesh.quarter, "penalty_Pa_per_m": sol.penalty,
                "active_pairs": int(sol.active.sum()), "contact_pairs": len(mesh.pairs),
                "active_set_iterations": sol.active_set_iterations,
                "cg_iterations": sol.cg_iterations, "stage_seconds": sol.seconds})


def nodal_von_mises(mesh, u: np.ndarray, E: float, nu: float) -> np.ndarray:
    """Von Mises stress of a P1 displacement, averaged to the nodes by element volume [Pa]."""
    basis = Basis(mesh, ElementVector(ElementTetP1()), intorder=1)
    grad = basis.interpolate(u.ravel()).grad[..., 0]  # (3, 3, elements), constant per element
    eps = 0.5 * (grad + grad.transpose(1, 0, 2))
    mu, _ = lame(E, nu)
    tr = np.trace(eps)
    dev = 2 * mu * (eps - tr / 3 * np.eye(3)[..., None])
    vm = np.sqrt(1.5 * np.einsum("ije,ije->e", dev, dev))
    vol = basis.dx[:, 0]
    total = np.zeros(mesh.nvertices)
    weight = np.zeros(mesh.nvertices)
    np.add.at(total, mesh.t.ravel(), np.repeat((vm * vol)[None, :], 4, axis=0).ravel())
    np.add.at(weight, mesh.t.ravel(), np.repeat(vol[None, :], 4, axis=0).ravel())
    return total / weight


def write_vtu(scene: Scene, mesh: BlockMesh, sol: ContactSolution, out: Path) -> list[Path]:
    """One .vtu per body: displacement, von Mises stress, FEM and Hertz contact pressure."""
    import meshio

    c = scene.hertz(sol.force)
    theta = c.major_axis_angle
    paths = []
    for i, (m, u, body) in enumerate(zip(mesh.bodies, (sol.u1, sol.u2),
                                         (scene.body1, scene.body2), strict=True)):
        nodes = mesh.pairs[:, i]
        p_fem = np.zeros(m.nvertices)
        p_fem[nodes] = sol.pressure
        x, y = m.p[0, nodes], m.p[1, nodes]
        p_hertz = np.zeros(m.nvertices)
        p_hertz[nodes] = c.pressure(x * math.cos(theta) + y * math.sin(theta),
                                    -x * math.sin(theta) + y * math.cos(theta))
        data = {"displacement": u, "von_mises": nodal_von_mises(m, u, body.E, body.nu),
                "contact_pressure_fem": p_fem, "contact_pressure_hertz": p_hertz,
                "contact_pressure_difference": p_fem - p_hertz}
        path = out / f"{scene.name}_body{i + 1}.vtu"
        meshio.write(path, meshio.Mesh(m.p.T, [("tetra", m.t.T)], point_data=data))
        paths.append(path)
    return paths


def plot_profiles(scene: Scene, prof: dict, result: Comparison, path: Path) -> Path:
    """PNG of the pressure along both axes (``prof`` from :func:`profiles`), FEM against Hertz."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c = scene.hertz(result.load)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, name, semi in zip(axes, ("major", "minor"), (c.a, c.b), strict=True):
        d = prof[name]
        ax.plot(d["s"] / semi, d["hertz"] / c.p0, "-", color="k", label="Hertz")
        ax.plot(d["s"] / semi, d["fem"] / c.p0, "o", ms=3, color="C3",
                label=f"FEM (RMS {d['rms']:.1%} of p0)")
        ax.set_xlabel(f"distance along the {name} axis / semi-axis")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=8)
    axes[0].set_ylabel("pressure / Hertz p0")
    fig.suptitle(f"{scene.name}: alpha = {c.alpha:.3g}, P = {result.load:.4g} N, "
                 f"{result.dofs} dofs; p0 {result.p0_rel_err:+.1%}, a {result.a_rel_err:+.1%}, "
                 f"b {result.b_rel_err:+.1%}", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


COLUMNS = [("scene", "{}"), ("level", "{}"), ("alpha", "{:.3g}"), ("load", "{:.4g}"),
           ("a_rel_err", "{:+.2%}"),
           ("b_rel_err", "{:+.2%}"), ("p0_rel_err", "{:+.2%}"), ("peak_nodal_rel_err", "{:+.2%}"),
           ("rms_major", "{:.2%}"), ("rms_minor", "{:.2%}"), ("force_rel_err", "{:+.1e}"),
           ("approach_rel_err", "{:+.2%}"), ("angle_err_deg", "{:+.2f}"),
           ("max_penetration_over_delta", "{:.1e}"), ("dofs", "{}"), ("seconds", "{:.0f}")]
HEADERS = {"load": "P [N]", "a_rel_err": "a", "b_rel_err": "b", "p0_rel_err": "p0 (fit)",
           "peak_nodal_rel_err": "peak node", "rms_major": "RMS major", "rms_minor": "RMS minor",
           "force_rel_err": "force balance", "approach_rel_err": "approach",
           "angle_err_deg": "axis angle [deg]", "max_penetration_over_delta": "penetration/delta",
           "seconds": "s"}


def report_markdown(results: list[Comparison], header: str = "") -> str:
    """The validation table: errors of the finite elements relative to Hertz."""
    lines = [header] if header else []
    lines.append("| " + " | ".join(HEADERS.get(k, k) for k, _ in COLUMNS) + " |")
    lines.append("|" + "---|" * len(COLUMNS))
    for r in results:
        cells = []
        for key, fmt in COLUMNS:
            value = getattr(r, key)
            cells.append("-" if isinstance(value, float) and math.isnan(value)
                         else fmt.format(value))
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def write_reports(results: list[Comparison], out: Path, header: str = "") -> tuple[Path, Path]:
    """report.json (a list, one object per scene) and report.md."""
    json_path, md_path = out / "report.json", out / "report.md"
    json_path.write_text(json.dumps([r.to_dict() for r in results], indent=1, default=float))
    md_path.write_text(report_markdown(results, header) + "\n")
    return json_path, md_path
