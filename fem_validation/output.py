"""What a run writes: VTU files for ParaView, pressure plots, report.md and report.json."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .compare import Comparison
from .elasticity import element_stress, nodal_average, von_mises
from .mesh import BlockMesh
from .scenes import Scene
from .solve import ContactSolution


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
        vm = von_mises(nodal_average(m.p, m.t, element_stress(m.p, m.t, u, body.E, body.nu)))
        data = {"displacement": u, "von_mises": vm,
                "contact_pressure_fem": p_fem, "contact_pressure_hertz": p_hertz,
                "contact_pressure_difference": p_fem - p_hertz}
        path = out / f"{scene.name}_body{i + 1}.vtu"
        meshio.write(path, meshio.Mesh(m.p.T, [("tetra", m.t.T)], point_data=data))
        paths.append(path)
    return paths


def plot_profiles(scene: Scene, prof: dict, result: Comparison, path: Path) -> Path:
    """PNG of the pressure along both axes (``prof`` from compare.profiles), FEM against Hertz."""
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
                 f"{result.dofs} dofs; p0 {result.p0_rel_err:+.2%}, a {result.a_rel_err:+.2%}, "
                 f"b {result.b_rel_err:+.2%}", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


COLUMNS = [("scene", "{}"), ("level", "{}"), ("alpha", "{:.3g}"), ("load", "{:.4g}"),
           ("a_rel_err", "{:+.2%}"), ("b_rel_err", "{:+.2%}"), ("p0_rel_err", "{:+.2%}"),
           ("peak_nodal_rel_err", "{:+.2%}"), ("rms_major", "{:.2%}"), ("rms_minor", "{:.2%}"),
           ("edge_a_rel_err", "{:+.2%}"), ("edge_b_rel_err", "{:+.2%}"),
           ("approach_rel_err", "{:+.2%}"), ("angle_err_deg", "{:+.2f}"),
           ("max_penetration_over_delta", "{:.1e}"), ("dofs", "{}"), ("seconds", "{:.0f}"),
           ("peak_memory_mb", "{:.0f}")]
HEADERS = {"load": "P [N]", "a_rel_err": "a", "b_rel_err": "b", "p0_rel_err": "p0 (fit)",
           "peak_nodal_rel_err": "peak node", "rms_major": "RMS major", "rms_minor": "RMS minor",
           "edge_a_rel_err": "edge a", "edge_b_rel_err": "edge b",
           "approach_rel_err": "approach", "angle_err_deg": "axis angle [deg]",
           "max_penetration_over_delta": "penetration/delta", "seconds": "s",
           "peak_memory_mb": "MB"}


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
    """report.json (a list, one object per scene; NaN as null) and report.md."""
    json_path, md_path = out / "report.json", out / "report.md"
    json_path.write_text(json.dumps([r.to_dict() for r in results], indent=1, default=float))
    md_path.write_text(report_markdown(results, header) + "\n")
    return json_path, md_path
