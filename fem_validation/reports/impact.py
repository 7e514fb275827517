"""An impact grade as files: grade.json, grade.md and grade.png
(:func:`fem_validation.grading.impact.grade_impact`)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..grading.impact import METRICS
from .grade import figure_title, plot_checks, quiet_figure, write_grade_files

__all__ = ["impact_markdown", "plot_impact", "write_impact_grade"]


def _fmt(name: str, value) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if name == "rebound_angle_err_deg":
        return f"{value:+.3f} deg"
    if name == "restitution_err" or name == "tangential_restitution_err":
        return f"{value:+.2e}"
    if name.endswith("_rms"):
        return f"{value:.3%}"
    return f"{value:+.3%}"


def _tol(name: str, tol) -> str:
    if tol is None:
        return "-"
    if name == "rebound_angle_err_deg":
        return f"{tol:.3f} deg"
    if name in ("restitution_err", "tangential_restitution_err"):
        return f"{tol:.2e}"
    return f"{tol:.3%}"


def _num(x, unit: str = "") -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "-"
    return f"{x:.6g}{(' ' + unit) if unit else ''}"


def impact_markdown(g, command: str = "") -> str:
    """grade.md: what was graded, the reference and the record side by side, every check
    with its tolerance and how the tolerance was derived, the verdict."""
    ref, mea = g.reference, g.measured
    lines = [f"# Impact graded against Hertz: {'PASSED' if g.passed else 'FAILED'}", ""]
    if g.hint:
        lines += [f"> {g.hint}", ""]
    lines += ["## What was graded", ""]
    if command:
        lines.append(f"- command: `{command}`")
    lines += [f"- trajectory: `{g.source or '-'}` ({mea['rows_in_contact']} rows in contact, "
              f"output step dt = {mea['dt']:.6g} s, units {g.details.get('units', 'SI')})",
              f"- scene: {g.scene}; reduced mass {g.mass:.6g} kg, approach speed "
              f"{g.speed:.6g} m/s",
              f"- reference: {ref['source']}", "",
              "| quantity | reference | record |", "|---|---|---|",
              f"| max overlap [m] | {_num(ref['max_approach'])} | {_num(mea['max_overlap'])} |",
              f"| max force [N] | {_num(ref['max_force'])} | {_num(mea['max_force'])} |",
              f"| duration [s] | {_num(ref['duration'])} | {_num(mea['duration'])} "
              f"({_num(mea['t_start'])} to {_num(mea['t_end'])}) |",
              f"| restitution | {_num(ref['restitution'])} | {_num(mea['restitution'])} |"]
    o = ref.get("oblique") or {}
    for key, label in (("tangential_restitution", "tangential restitution"),
                       ("rebound_angle_deg", "rebound angle [deg]"),
                       ("spin", "spin after [rad/s]")):
        mine = mea.get("omega_after") if key == "spin" else mea.get(key)
        if key in o or mine is not None:
            lines.append(f"| {label} | {_num(o.get(key))} | {_num(mine)} |")
    rule = ("the force may pull (--damping-attractive): the contact lasts until the overlap "
            "returns to 0" if mea.get("attractive") else
            "the contact lasts while the force is positive")
    lines += ["", f"Restitution from {mea['restitution_method']}. Contact: {rule}; start at "
              f"{mea.get('start_method') or '-'}, end at {mea.get('end_method') or '-'}.", "",
              "## Checks", "",
              "Errors are (record - reference) / reference (restitution: record - "
              "reference); RMS values are fractions of the reference's F_max. Each tolerance "
              "is a floor for the DEM integrator's own error plus what the output sampling "
              "allows (the last column). *not available*: the reference or the record lacks "
              "what the metric needs.", ""]
    lines += ["| check | what it measures | value | tolerance | tolerance from | status |",
              "|---|---|---|---|---|---|"]
    for c in g.checks:
        short, meaning = METRICS[c.name]
        meaning = meaning.replace("|", "\\|")
        status = c.status.upper() if c.passed is not None else c.status
        lines.append(f"| {short} (`{c.name}`) | {meaning} | {_fmt(c.name, c.value)} | "
                     f"{_tol(c.name, c.tolerance)} | "
                     f"{g.tolerance_basis.get(c.name, '-').replace('|', chr(92) + '|')} | "
                     f"{status} |")
    failed = [c.name for c in g.checks if c.status == "fail"]
    lines += ["", "## Verdict", "",
              ("PASSED: every checked metric is within its tolerance." if g.passed else
               f"FAILED: {', '.join(failed) or 'nothing could be checked'}.")]
    if g.notes:
        lines += ["", "## Notes", ""] + [f"- {n}" for n in g.notes]
    lines += ["", "## Method", "", "See `fem_validation.grading.impact`: peaks are the largest "
              "samples (bound |f''| dt^2 / 8 at the peak); the contact's start and end are "
              "F^(2/3) extrapolated to 0 from the two rows next to each end (at most one step "
              "off); F(t) is compared with the reference's history started at the start "
              "found, refined within one step."]
    return "\n".join(lines) + "\n"


@quiet_figure()
def plot_impact(g, path: Path) -> Path:
    """grade.png: F(t) and F(delta) of the record over the reference's, above the checks."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    c = g.curves
    fig = plt.figure(figsize=(8, 8.2))
    grid = fig.add_gridspec(2, 2, height_ratios=[1, 0.9])
    axes = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1]),
            fig.add_subplot(grid[1, :])]
    t, d, f = (np.asarray(c[k], dtype=float) for k in ("t", "overlap", "force"))
    ft, fd = (np.asarray(c[k], dtype=float) for k in ("reference_force_time",
                                                      "reference_force_overlap"))
    t0 = c["t_start"]
    span = max(c["t_end"] - t0, 1e-300)
    shown = (t >= t0 - 0.1 * span) & (t <= c["t_end"] + 0.1 * span)
    tu = (t[shown] - t0) * 1e6
    if np.isfinite(ft[shown]).any():
        axes[0].plot(tu, ft[shown] / 1e3, "-", color="k", label="reference")
    axes[0].plot(tu, f[shown] / 1e3, "o", ms=2.5, color="C3", label="record")
    axes[0].set_xlabel("time since contact [us]")
    axes[0].set_ylabel("normal force [kN]")
    axes[0].set_title("force against time", fontsize=10)
    inside = f > 0
    order = np.argsort(d[inside])
    if np.isfinite(fd[inside]).any():
        axes[1].plot(d[inside][order] * 1e6, fd[inside][order] / 1e3, "-", color="k",
                     label="Hertz F(delta)")
    axes[1].plot(d[inside] * 1e6, f[inside] / 1e3, "o", ms=2.5, color="C3", label="record")
    axes[1].set_xlabel("overlap [um]")
    axes[1].set_ylabel("normal force [kN]")
    axes[1].set_title("force against overlap", fontsize=10)
    for ax in axes[:2]:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=9, loc="best")
    plot_checks(axes[2], g.checks, METRICS, _fmt, _tol)
    figure_title(fig, [f"{Path(g.source).name if g.source else g.scene} against Hertz: "
                       f"{'PASSED' if g.passed else 'FAILED'}",
                       f"{g.scene}; M {g.mass:.4g} kg, V {g.speed:.4g} m/s; reference "
                       f"{g.reference['source']}"])
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_impact_grade(g, out: Path, command: str = "") -> tuple[Path, Path, Path]:
    """DIR/grade.json, DIR/grade.md and DIR/grade.png of an ImpactGrade."""
    return write_grade_files(g.to_dict(), out, command, impact_markdown(g, command),
                             lambda path: plot_impact(g, path))
