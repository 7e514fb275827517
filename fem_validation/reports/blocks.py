"""What a run writes: VTU files for ParaView, pressure plots, report.md and report.json;
what a grade writes: grade.json, grade.md, grade.png.

The solver's modules (and scikit-fem with them) are imported only by the functions that
write a run, so that grading another code's result needs none of them.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from ..scenes import Scene


def plot_profiles(scene: Scene, prof: dict, result, path: Path) -> Path:
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


def report_markdown(results: list, header: str = "") -> str:
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


#: What each column of report.md, study.md (and, with CURVED_MEANINGS, curved.md) holds.
MEANINGS = {
    "scene": "the scene (alpha-A: equal steel bodies with curvature ratio A)",
    "level": "mesh level (each level divides every element size by sqrt 2)",
    "alpha": "Hertz's curvature ratio rho_x / rho_y",
    "load": "the contact force the run reached [N]; Hertz is evaluated at it",
    "a_rel_err": "semi-major axis from the second moments of the nodal contact forces",
    "b_rel_err": "semi-minor axis, likewise",
    "p0_rel_err": "peak pressure of the least-squares fit of p^2 (nodes above 0.2 max p)",
    "peak_nodal_rel_err": "largest nodal pressure (information)",
    "rms_major": "RMS of (pressure - Hertz) along the major axis to 1.2 a, over p0",
    "rms_minor": "as RMS major, along the minor axis to 1.2 b",
    "edge_a_rel_err": "semi-major axis of the ellipse through the active set's edge "
                      "(information)",
    "edge_b_rel_err": "semi-minor axis of that ellipse (information)",
    "approach_rel_err": "approach plus the blocks' Boussinesq settlement against Hertz's delta "
                        "(information)",
    "angle_err_deg": "major axis against Hertz's [deg], whole models only ('-': a quarter "
                     "model has its axes by construction)",
    "max_penetration_over_delta": "largest penetration of a contact pair over Hertz's delta "
                                  "(penalty diagnostic)",
    "von_mises_rel_err": "largest von Mises stress on the z axis (parabola vertex), the body "
                         "with the larger error",
    "z_von_mises_rel_err": "its depth, likewise",
    "stress_rms_axis": "RMS of the six stress components' difference on the z axis (0.05 b "
                       "to 3 b deep), over p0, the worse body",
    "stress_rms_major_plane": "as stress RMS axis, in the plane through the major axis",
    "stress_rms_minor_plane": "as stress RMS axis, in the plane through the minor axis",
    "dofs": "unknowns of the linear system",
    "seconds": "wall time: mesh, solve, comparison [s]",
    "peak_memory_mb": "peak resident memory of the process during the run [MB]",
}


def _legend(columns, headers: dict, meanings: dict) -> list[str]:
    return [f"- **{headers.get(k, k)}**: {meanings.get(k, k)}" for k in columns]


def report_document(results: list, header: str, title: str, columns, headers: dict,
                    meanings: dict, targets: dict, table: str, note: str = "") -> str:
    """A report that stands alone: what was run, the sign convention, a legend of every
    column, each check's tolerance, the table, and pass/fail per row."""
    lines = [f"# {title}", "", "## What was run", "", header.strip(), "",
             "## Sign convention", "",
             "Errors are (FEM - Hertz) / Hertz, Hertz evaluated at the force the run reached "
             "(matched force); RMS values are fractions of Hertz's p0; '-' where a value "
             "does not apply.", "", "## Columns", ""]
    lines += _legend(columns, headers, meanings)
    lines += ["", "## Checks", "", "Each row passes when every one of these is within its "
              "tolerance (|value| at most):", ""]
    lines += [f"- {headers.get(k, k)} (`{k}`): {v:.2%}" for k, v in targets.items()]
    if note:
        lines += ["", note]
    lines += ["", "## Results", "", table.strip(), "", "## Pass/fail", ""]
    for r in results:
        g = getattr(r, "grade", None)
        failed = ([c.name for c in g.checks if c.status == "fail"] if g is not None else
                  [k for k, v in targets.items() if not abs(getattr(r, k)) <= v])
        label = f"{r.scene}, level {r.level}" + (
            f", a/R {r.a_over_r:.3f}" if hasattr(r, "a_over_r") else "")
        lines.append(f"- {label}: " + ("PASS" if not failed else
                                       "FAIL (" + ", ".join(failed) + ")"))
    return "\n".join(lines) + "\n"


def write_reports(results: list, out: Path, header: str = "",
                  targets: dict | None = None) -> tuple[Path, Path]:
    """report.json (a list, one object per scene; NaN as null) and report.md.

    report.md stands alone (:func:`report_document`); the README's table is
    :func:`report_markdown` of the same results.
    """
    from ..grading.contact import TARGETS

    targets = TARGETS if targets is None else targets
    json_path, md_path = out / "report.json", out / "report.md"
    json_path.write_text(json.dumps([r.to_dict() for r in results], indent=1, default=float))
    md_path.write_text(report_document(
        results, header, "Finite elements against Hertz", [k for k, _ in COLUMNS], HEADERS,
        MEANINGS, targets, report_markdown(results),
        note="These are the targets of the default level (4); coarser levels are expected to "
             "miss some."))
    return json_path, md_path


# --- a graded result: grade.json, grade.md, grade.png -----------------------------------


