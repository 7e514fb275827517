"""A graded DEM history as files: grade.json, grade.md and grade.png
(:class:`fem_validation.grading.tangential_history.HistoryGrade`)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..grading.tangential_history import LAMMPS_LAWS, METRICS, STIFFNESS_WINDOW, HistoryGrade
from .grade import quiet_figure

__all__ = ["grade_markdown", "plot_grade", "write_grade"]


def _fmt(name: str, value) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if value != 0 and abs(value) < 5e-5:
        return f"{value:+.1e}"
    if name in ("branch_err_max", "path_force_err_max", "law_force_err_max"):
        return f"{value:.2%}"
    return f"{value:+.2%}"


def _reference_words(g: HistoryGrade) -> str:
    at = ("the history's own displacements (the same displacement amplitude): the reference "
          "force at each row" if g.driven == "displacement" else
          "the history's own forces (the same force amplitude): the reference displacement "
          "at each row")
    return f"{g.reference['model']} at {at}"


def grade_markdown(g: HistoryGrade, command: str = "") -> str:
    """grade.md: what was graded, the story in words, the checks, the states, the notes."""
    from .grade import checks_table

    r, m = g.reference, g.measured
    p = np.asarray(g.path["normal_force"])
    failed = [c.name for c in g.checks if c.status == "fail"]
    lines = [f"# Grade of a tangential history against Mindlin-Deresiewicz"
             f"{'' if g.law == 'mindlin-deresiewicz' else f' and the law claimed, {g.law}'}: "
             f"{'PASSED' if g.passed else 'FAILED'}", ""]
    if g.hint:
        lines += [f"> {g.hint}", ""]
    lines += ["## In words", ""] + [f"- {line}" for line in g.diagnosis] + [""]
    lines += ["## What was graded", ""]
    if command:
        lines.append(f"- command: `{command}`")
    lines += [
        f"- history: `{g.source or '-'}`, {m['rows']} rows, reversals at rows "
        f"{m['reversals'] or 'none'}; scene: {g.scene}",
        (f"- normal force P from {p.min():.6g} to {p.max():.6g} N (varying)" if g.varying
         else f"- normal force P = {g.normal_force:.6g} N (constant)")
        + f", mu = {g.mu:.4g}, mu P = {r['mu_P']:.6g} N",
        f"- law claimed: {g.law}; driving quantity: {g.driven} ({g.driven_how})",
        f"- reference: {_reference_words(g)}",
        f"- Hertz at P = {g.normal_force:.6g} N: a = {r['a']:.6g} m; Mindlin's no-slip "
        f"stiffness k = {r['no_slip_stiffness']:.6g} N/m (8 G* a for spheres, "
        f"1 / hertz.tangential_compliance); sliding displacement 3 mu P / (2 k) = "
        f"{r['sliding_displacement']:.6g} m",
        f"- measured: initial stiffness {m['initial_stiffness']:.6g} N/m (from "
        f"{m['stiffness_window_points']} points within {STIFFNESS_WINDOW:.0%} mu P), "
        f"Mindlin's there {r['initial_no_slip_stiffness']:.6g} N/m"
        + (f"; after the reversals {', '.join(f'{k:.6g}' for k in m['reversal_stiffness'])} "
           f"N/m" if m["reversal_stiffness"] else ""),
    ]
    if math.isfinite(m["loop_energy"]):
        lines.append(f"- loop energy {m['loop_energy']:.6g} J; Mindlin-Deresiewicz's "
                     f"{r['loop_energy']:.6g} J ({r['loop_energy_from']})")
    if g.details:
        lines.append("- details: " + ", ".join(f"{k} = {v}" for k, v in g.details.items()))
    lines += ["", "## Sign convention", "",
              "The force is the one that drives the displacement (body 1 on body 2, the "
              "displacement's sign on the ramp), both projected on the contact plane. "
              "Relative errors are (history - reference) / reference; the branch error is "
              "|Q - Q_ref| / Q*, the path errors |Q - Q_ref| / (mu P_max).", "",
              "## Checks", "",
              "Status: PASS / FAIL against the tolerance; *information*: reported, not "
              "checked" + ("" if g.law == "mindlin-deresiewicz" else
                           f" (with --law {g.law} the Mindlin-Deresiewicz metrics are the "
                           f"distance to the physics)")
              + "; *not available*: see the notes.", ""]
    lines += checks_table(g.checks, METRICS, fmt=_fmt)
    if g.states:
        lines += ["", "## States along the path (where the laws part)", "",
                  "| state | row | P [N] | displacement [m] | Q [N] | Mindlin-Deresiewicz "
                  "[N] | error | " + " | ".join(f"`{v}` [N]" for v in LAMMPS_LAWS) + " |",
                  "|---" * (7 + len(LAMMPS_LAWS)) + "|"]
        for s in g.states:
            err = s["rel_err"]
            lines.append(
                f"| {s['state']}{' (parts)' if s['parts'] else ''} | {s['line']} | "
                f"{s['normal_force']:.6g} | {s['displacement']:.6g} | {s['force']:.6g} | "
                f"{s['reference_force']:.6g} | "
                f"{'-' if not math.isfinite(err) else f'{err:+.2%}'} | "
                + " | ".join(f"{s[v]:.6g}" for v in LAMMPS_LAWS) + " |")
    if g.notes:
        lines += ["", "## Notes", ""] + [f"- {n}" for n in g.notes]
    lines += ["", "## Verdict", "",
              ("PASSED: every checked metric is within its tolerance." if g.passed else
               f"FAILED: {', '.join(failed)} outside the tolerance."),
              "", "## Method", "",
              "See `fem_validation.grading.tangential_history`: the stiffness from a line "
              "fit of the compliance delta / Q against Q over the points within "
              f"{STIFFNESS_WINDOW:.0%} mu P of the start (and of each reversal), taken at "
              "Q = 0; the reference stepped along the history's driving quantity; the loop "
              "energy by the trapezoid rule against Mindlin-Deresiewicz's closed form at the "
              "reference's amplitude; LAMMPS's linear laws stepped as pair_style granular "
              "computes them (no damping)."]
    return "\n".join(lines) + "\n"


@quiet_figure()
def plot_grade(g: HistoryGrade, path: Path) -> Path:
    """grade.png: the force against the displacement with the reference at the driving
    quantity (and the law claimed), the start of the ramp against Mindlin's k (or, where P
    varies, both forces along the path), the checks."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .grade import figure_title, plot_checks, source_name

    d = np.asarray(g.path["displacement"])
    q = np.asarray(g.path["force"])
    p = np.asarray(g.path["normal_force"])
    ref = np.asarray(g.path["reference"])
    law = g.path.get("law")
    scale = g.reference["mu_P"]
    fig = plt.figure(figsize=(8, 9.5))
    grid = fig.add_gridspec(2, 2, height_ratios=[1, 0.8])
    ax = fig.add_subplot(grid[0, 0])
    style = {"ms": 2.5, "lw": 0.8} if len(d) <= 400 else {"ms": 0, "lw": 1.0}
    if g.driven == "displacement":
        ax.plot(d * 1e6, ref / scale, "-", color="k", lw=1.2,
                label="Mindlin-Deresiewicz\nat the same displacements")
    else:
        ax.plot(ref * 1e6, q / scale, "-", color="k", lw=1.2,
                label="Mindlin-Deresiewicz\nat the same forces")
    if law is not None and g.law != "mindlin-deresiewicz":
        ax.plot(d * 1e6, np.asarray(law) / scale, "--", color="C0", lw=1.0,
                label=f"law claimed: {g.law}")
    ax.plot(d * 1e6, q / scale, "o-", color="C3", label="history", **style)
    ax.set_xlabel("tangential displacement [um]")
    ax.set_ylabel("Q / (mu P_max)")
    ax.set_title("force against displacement", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    ax2 = fig.add_subplot(grid[0, 1])
    if g.varying:
        rows = np.arange(len(d))
        ax2.plot(rows, q / scale, "-", color="C3", label="history Q / (mu P_max)")
        if g.driven == "displacement":
            ax2.plot(rows, ref / scale, "-", color="k", lw=1.0,
                     label="Mindlin-Deresiewicz Q / (mu P_max)")
        ax2.plot(rows, p / p.max(), ":", color="0.4", label="P / P_max")
        for s in g.states:
            ax2.axvline(s["row"], color="C1" if s["parts"] else "0.8", lw=0.8)
        ax2.set_xlabel("row")
        ax2.set_title("along the path (orange: the laws part)", fontsize=10)
    else:
        k = g.reference["initial_no_slip_stiffness"]
        rev = g.measured["reversals"]
        end = rev[0] if rev else len(d) - 1
        sel = np.arange(0, end + 1)
        sel = sel[np.abs(q[sel]) <= 4 * STIFFNESS_WINDOW * scale]
        ax2.plot(d[sel] * 1e9, q[sel] / scale, "o", ms=3, color="C3", label="history")
        ax2.plot(d[sel] * 1e9, k * d[sel] / scale, "-", color="k", lw=1.0,
                 label="Mindlin's no-slip k")
        ax2.axhline(STIFFNESS_WINDOW, color="0.5", ls=":", label="fit window")
        ax2.set_xlabel("tangential displacement [nm]")
        ax2.set_title("start of the ramp: the stiffness", fontsize=10)
    ax2.grid(True, alpha=0.3)
    ax2.legend(fontsize=8)
    plot_checks(fig.add_subplot(grid[1, :]), g.checks, METRICS, fmt=_fmt)
    figure_title(fig, [
        f"{source_name(g)} against Mindlin-Deresiewicz"
        + ("" if g.law == "mindlin-deresiewicz" else f" (law claimed: {g.law})")
        + f": {'PASSED' if g.passed else 'FAILED'}",
        f"{g.scene}; mu = {g.mu:.3g}, P "
        + (f"{p.min():.4g}..{p.max():.4g} N" if g.varying else f"= {g.normal_force:.5g} N")
        + f"; {g.driven}-driven: the reference at the same {g.driven}s",
        "; ".join(g.diagnosis[:2]), g.hint])
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def write_grade(g: HistoryGrade, out, command: str = "") -> tuple[Path, Path, Path]:
    """DIR/grade.json, DIR/grade.md and DIR/grade.png of a HistoryGrade (DIR created)."""
    from .grade import write_grade_files

    return write_grade_files(g.to_dict(), out, command, grade_markdown(g, command),
                             lambda path: plot_grade(g, path))
