"""A graded 2-D result (:class:`~fem_validation.grading.plane.PlaneGrade`) as files:
grade.json, grade.md and grade.png, as the 3-D grade writes them (:mod:`.grade`)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .grade import (
    SIGN_CONVENTION,
    checks_table,
    figure_title,
    plot_checks,
    quiet_figure,
    source_name,
    write_grade_files,
)

__all__ = ["plane_markdown", "plot_plane", "write_plane_grade"]

_TITLES = {"plane-strain": "plane strain (line contact, per unit length)",
           "axisymmetric": "axisymmetric (point contact, full circle)"}


def _force(g) -> str:
    return f"{g.force:.6g} {'N/m' if g.model == 'plane-strain' else 'N'}"


def plane_markdown(g, command: str = "") -> str:
    """grade.md of a PlaneGrade: verdict, the reference and the result, the checks, the
    stresses, the notes and the method."""
    from ..grading.plane import METRICS

    w = "b" if g.model == "plane-strain" else "a"
    key = "half_width" if w == "b" else "a"
    lines = [f"# {source_name(g)} against Hertz: {'PASSED' if g.passed else 'FAILED'}", "",
             f"- scene: {g.scene}; model: {_TITLES[g.model]}",
             f"- force: {_force(g)} (the result's; Hertz is evaluated there)",
             f"- Hertz: {w} = {g.hertz[key] * 1e3:.6g} mm, p0 = {g.hertz['p0'] / 1e6:.6g} MPa",
             f"- result: {w} = {g.fem[key] * 1e3:.6g} mm, p0 = {g.fem['p0'] / 1e6:.6g} MPa "
             f"(p^2 fit on {g.fem['fit_nodes']} nodes, {g.fem['fit_dropped']} outliers left "
             f"out)"]
    if command:
        lines.append(f"- command: `{command}`")
    lines += ["", SIGN_CONVENTION, "", *checks_table(g.checks, METRICS[g.model])]
    if g.stress:
        lines += ["", "| body | von Mises max [MPa] | Hertz [MPa] | depth [mm] | Hertz [mm] |",
                  "|---|---|---|---|---|"]
        for body, row in g.stress.items():
            lines.append(f"| {body} | {row['von_mises'] / 1e6:.5g} | "
                         f"{row['hertz_von_mises'] / 1e6:.5g} | {row['z_von_mises'] * 1e3:.4g} "
                         f"| {row['hertz_z_von_mises'] * 1e3:.4g} |")
    if g.notes:
        lines += ["", "Notes:", *(f"- {n}" for n in g.notes)]
    if g.details:
        lines += ["", "Read from the file:",
                  *(f"- {k}: {v}" for k, v in g.details.items() if v is not None)]
    lines += ["", "Method: fem_validation.grading.plane (the p^2 fit, moments, edge, profile "
                  "and stresses of the 3-D grade on a line)."]
    return "\n".join(lines) + "\n"


@quiet_figure()
def plot_plane(g, path: Path) -> Path:
    """grade.png: the pressure against Hertz's, the von Mises stress on the axis, the
    checks."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..grading.plane import METRICS

    w = "b" if g.model == "plane-strain" else "a"
    width = g.hertz["half_width" if w == "b" else "a"]
    fig = plt.figure(figsize=(8, 8.2))
    grid = fig.add_gridspec(2, 2, height_ratios=[1, 0.9])
    axes = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1]),
            fig.add_subplot(grid[1, :])]
    prof = g.profile
    axes[0].plot(prof["x"] / width, prof["hertz"] / g.hertz["p0"], "-", color="k",
                 label="Hertz")
    axes[0].plot(prof["x"] / width, prof["fem"] / g.hertz["p0"], "o", ms=2.5, color="C3",
                 label="result")
    axes[0].set_xlabel(f"{'x' if w == 'b' else 'r'} / {w}")
    axes[0].set_ylabel("pressure / Hertz's p0")
    axes[0].set_title("contact pressure", fontsize=10)
    for k, (body, line) in enumerate(g.axis_stress.items()):
        axes[1].plot(line["depth"] / width, line["von_mises"] / g.hertz["p0"], "o", ms=2.5,
                     color=f"C{3 + k}", label=f"result, {body}")
        if k == 0:
            axes[1].plot(line["depth"] / width, np.asarray(line["hertz"]) / g.hertz["p0"],
                         "-", color="k", label="Hertz")
    axes[1].set_xlim(0, 3)
    axes[1].set_xlabel(f"depth on the axis / {w}")
    axes[1].set_ylabel("von Mises / p0")
    axes[1].set_title("von Mises stress on the axis", fontsize=10)
    for ax in axes[:2]:
        ax.grid(True, alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=9, loc="best")
    plot_checks(axes[2], g.checks, METRICS[g.model])
    figure_title(fig, [f"{source_name(g)} against Hertz: {'PASSED' if g.passed else 'FAILED'}",
                       f"{g.scene}; {_TITLES[g.model]}; force {_force(g)}; errors (result - "
                       f"Hertz) / Hertz at the same force"])
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_plane_grade(g, out: Path, command: str = "") -> tuple[Path, Path, Path]:
    """DIR/grade.json, DIR/grade.md and DIR/grade.png of a PlaneGrade."""
    return write_grade_files(g.to_dict(), out, command, plane_markdown(g, command),
                             lambda path: plot_plane(g, path))
