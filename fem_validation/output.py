"""What a run writes: VTU files for ParaView, pressure plots, report.md and report.json."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .compare import Comparison, ellipse_rotation, recovered_stress
from .elasticity import von_mises
from .mesh import BlockMesh
from .scenes import Scene
from .solve import ContactSolution


def hertz_nodal_stress(c, p: np.ndarray, body: int) -> np.ndarray:
    """Hertz's stress at nodes p (3, n) of body 1 or 2, in the mesh frame, (n, 3, 3) [Pa].

    The nodes are put into the ellipse frame of ``c`` (a ``hertz.Contact``; z is
    the depth into the body: the mesh's z for body 1, -z for body 2),
    ``c.stress`` is evaluated there at once, and the tensors are turned back
    into the mesh frame.
    """
    rot = ellipse_rotation(c.major_axis_angle, body)
    x, y, z = rot @ p
    exact = c.stress(x, y, np.maximum(z, 0.0), body=body)
    return np.einsum("ji,njk,kl->nil", rot, exact, rot)


def _tensor(s: np.ndarray) -> np.ndarray:
    """(n, 3, 3) -> (n, 9), rows xx xy xz yx yy yz zx zy zz (ParaView's tensor layout)."""
    return np.ascontiguousarray(s.reshape(len(s), 9))


def write_vtu(scene: Scene, mesh: BlockMesh, sol: ContactSolution, out: Path,
              nodal_stress: tuple | None = None, reference=None) -> list[Path]:
    """One .vtu per body, for ParaView.

    Point data: ``displacement`` [m]; ``stress_fem`` (the patch-recovered FEM
    stress, :func:`fem_validation.compare.recovered_stress`), ``stress_hertz``
    (``Contact.stress`` at the node) and ``stress_difference`` (FEM - Hertz),
    9-component tensors in the mesh frame [Pa]; ``von_mises`` (of
    ``stress_fem``), ``von_mises_hertz`` and ``von_mises_difference`` [Pa];
    ``contact_pressure_fem``, ``contact_pressure_hertz`` and
    ``contact_pressure_difference`` [Pa] (zero off the contact face).

    Parameters
    ----------
    scene, mesh, sol : the run
    out : Path
        Directory; writes ``<scene>_body1.vtu`` and ``<scene>_body2.vtu``.
    nodal_stress : tuple of two ndarrays, optional
        The bodies' recovered stresses (``Comparison.nodal_stress``), computed
        here if not given.
    reference : hertz.Contact, optional
        The Hertz contact to write (default: the scene's at the force reached).
    """
    import meshio

    c = scene.hertz(sol.force) if reference is None else reference
    theta = c.major_axis_angle
    paths = []
    for i, (m, u) in enumerate(zip(mesh.bodies, (sol.u1, sol.u2), strict=True)):
        nodes = mesh.pairs[:, i]
        p_fem = np.zeros(m.nvertices)
        p_fem[nodes] = sol.pressure
        x, y = m.p[0, nodes], m.p[1, nodes]
        p_hertz = np.zeros(m.nvertices)
        p_hertz[nodes] = c.pressure(x * math.cos(theta) + y * math.sin(theta),
                                    -x * math.sin(theta) + y * math.cos(theta))
        fem = (recovered_stress(scene, mesh, sol, i + 1) if not nodal_stress
               else nodal_stress[i])
        exact = hertz_nodal_stress(c, m.p, i + 1)
        vm, vm_hertz = von_mises(fem), von_mises(exact)
        data = {"displacement": u, "von_mises": vm,
                "contact_pressure_fem": p_fem, "contact_pressure_hertz": p_hertz,
                "contact_pressure_difference": p_fem - p_hertz,
                "stress_fem": _tensor(fem), "stress_hertz": _tensor(exact),
                "stress_difference": _tensor(fem - exact), "von_mises_hertz": vm_hertz,
                "von_mises_difference": vm - vm_hertz}
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
           ("max_penetration_over_delta", "{:.1e}"), ("von_mises_rel_err", "{:+.2%}"),
           ("z_von_mises_rel_err", "{:+.2%}"), ("stress_rms_axis", "{:.2%}"),
           ("stress_rms_major_plane", "{:.2%}"), ("stress_rms_minor_plane", "{:.2%}"),
           ("dofs", "{}"), ("seconds", "{:.0f}"),
           ("peak_memory_mb", "{:.0f}")]
HEADERS = {"load": "P [N]", "a_rel_err": "a", "b_rel_err": "b", "p0_rel_err": "p0 (fit)",
           "peak_nodal_rel_err": "peak node", "rms_major": "RMS major", "rms_minor": "RMS minor",
           "edge_a_rel_err": "edge a", "edge_b_rel_err": "edge b",
           "approach_rel_err": "approach", "angle_err_deg": "axis angle [deg]",
           "max_penetration_over_delta": "penetration/delta", "von_mises_rel_err": "VM max",
           "z_von_mises_rel_err": "VM depth", "stress_rms_axis": "stress RMS axis",
           "stress_rms_major_plane": "RMS major plane",
           "stress_rms_minor_plane": "RMS minor plane", "seconds": "s",
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
