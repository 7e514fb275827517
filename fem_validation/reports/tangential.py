"""A graded tangential result as files: grade.json, grade.md and grade.png."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from ..grading.contact import FIT_THRESHOLD
from ..grading.tangential import METRICS, TangentialGrade
from .grade import quiet_figure


def _fmt(name: str, value) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if value != 0 and abs(value) < 5e-5:  # exact data: show the rounding, not +0.00%
        return f"{value:+.1e}"
    if name.startswith("traction_rms") or name in ("branch_err_max", "transverse_shear_max"):
        return f"{value:.2%}"
    return f"{value:+.2%}"


def grade_markdown(g: TangentialGrade, command: str = "") -> str:
    """grade.md: what was graded, the method, every check with its tolerance, the verdict."""
    from .grade import checks_table

    r, f = g.reference, g.fem
    failed = [c.name for c in g.checks if c.status == "fail"]
    lines = [f"# Grade against Cattaneo-Mindlin and Mindlin-Deresiewicz: "
             f"{'PASSED' if g.passed else 'FAILED'}", ""]
    if g.hint:
        lines += [f"> {g.hint}", ""]
    lines += ["## What was graded", ""]
    if command:
        lines.append(f"- command: `{command}`")
    lines += [
        f"- result: `{g.source or '-'}`; scene: {g.scene}; symmetry of the model: {g.symmetry}",
        f"- normal force P = {g.normal_force:.6g} N (whole contact), mu = {g.mu:.4g}, load "
        f"at {math.degrees(g.direction):.4g} deg from body 1's x axis = "
        f"{r['direction_in_ellipse_frame_deg']:.4g} deg from Hertz's major axis",
        f"- Hertz at P: a {r['a']:.6g} m, b {r['b']:.6g} m, p0 {r['p0']:.6g} Pa, alpha "
        f"{r['alpha']:.4g}; no-slip stiffness along the load {r['no_slip_stiffness']:.6g} N/m",
        f"- snapshot at path index {f['snapshot']}: Q = {f['snapshot_force']:.6g} N = "
        f"{f['snapshot_force_ratio']:.4g} mu P; Cattaneo-Mindlin's stick semi-axes "
        f"{r['stick_a']:.6g} m, {r['stick_b']:.6g} m; the result's (fit) "
        f"{f['stick_fit']['stick_a']:.6g} m, {f['stick_fit']['stick_b']:.6g} m",
        f"- path: {len(g.path['displacement'])} points, reversals at {f['reversals']}; "
        f"Q* = {f['amplitude']:.6g} N; loop energy {f['loop_energy']:.6g} J, "
        f"Mindlin-Deresiewicz's {r['loop_energy']:.6g} J"]
    if math.isfinite(f["stick_area_fraction"]):
        lines.append(f"- the code's stick flags cover {f['stick_area_fraction']:.4g} of the "
                     f"pressed area (Cattaneo-Mindlin: {r['stick_area_fraction']:.4g})")
    if g.details:
        lines.append("- details: " + ", ".join(f"{k} = {v}" for k, v in g.details.items()))
    lines += ["", "## Sign convention", "",
              "Relative errors are (result - reference) / reference, the reference at the "
              "result's own normal force (and, for the stick zone and the tractions, at its "
              "tangential force at the snapshot); the branch error is |Q - Q_ref| / Q*; "
              "RMS values and the transverse shear are fractions of mu p0.", "",
              "## Checks", "",
              "Status: PASS / FAIL against the tolerance (|value| at most the tolerance); "
              "*information*: reported, not checked; *not available*: the result does not "
              "hold what it needs (see the notes).", ""]
    lines += checks_table(g.checks, METRICS, fmt=_fmt)
    if g.notes:
        lines += ["", "## Notes", ""] + [f"- {n}" for n in g.notes]
    lines += ["", "## Verdict", "",
              ("PASSED: every checked metric is within its tolerance." if g.passed else
               f"FAILED: {', '.join(failed)} outside the tolerance."),
              "", "## Method", "",
              "See `fem_validation.grading.tangential`: the stick semi-axes from a least-squares "
              "fit of (mu p - q)^2 on the nodes where mu p - q exceeds "
              f"{FIT_THRESHOLD:g} of its largest value; the reference force along the "
              "result's displacement path by Masing's rule with memory "
              "(`hertz.tangential_history` inverted by bisection); the loop energy by the "
              "trapezoid rule; the tractions interpolated on the surface triangles along "
              "Hertz's axes. That slipping nodes carry |q| = mu p is not reported: a Coulomb "
              "solver holds it by construction."]
    return "\n".join(lines) + "\n"


@quiet_figure()
def plot_grade(g: TangentialGrade, path: Path) -> Path:
    """grade.png: traction profiles along both axes against Cattaneo-Mindlin, the
    force-displacement loop against Masing, and the checks; titled with the result's file
    name, the verdict and the unit hint, sized to read at page width (8 inches)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .grade import figure_title, plot_checks, source_name

    fig = plt.figure(figsize=(8, 10.5))
    grid = fig.add_gridspec(3, 2, height_ratios=[1, 1, 0.85])
    r = g.reference
    scale = g.mu * r["p0"]
    handles = []
    for col, name, semi in zip((0, 1), ("major", "minor"), (r["a"], r["b"]), strict=True):
        ax = fig.add_subplot(grid[0, col])
        d = g.profiles.get(name)
        if d is not None:
            s = d["s"] / semi
            ax.plot(s, d["hertz"] / scale, "-", color="k",
                    label="Cattaneo-Mindlin at the snapshot's Q")
            ax.plot(s, d["fem"] / scale, "o", ms=2.5, color="C3",
                    label="result, interpolated")
            ax.plot(s, np.sqrt(np.clip(1 - s * s, 0, None)), ":", color="0.5",
                    label="mu p (Hertz): the limit of friction")
            key = "stick_a" if name == "major" else "stick_b"
            ax.axvline(r[key] / semi, color="k", lw=0.8, ls="--",
                       label="stick edge, Cattaneo-Mindlin")
            fitted = g.fem["stick_fit"][key]
            if math.isfinite(fitted):
                ax.axvline(fitted / semi, color="C3", lw=0.8, ls=":",
                           label="stick edge, fit to the result")
            if len(ax.get_lines()) > len(handles):
                handles = ax.get_lines()
        else:
            ax.text(0.5, 0.5, "not graded\n(see the notes)", ha="center",
                    transform=ax.transAxes)
        ax.set_xlabel(f"along Hertz's {name} axis / {'a' if name == 'major' else 'b'}")
        if col == 0:
            ax.set_ylabel("shear along the load / (mu p0)")
        ax.set_title(f"tangential traction, {name} axis", fontsize=10)
        ax.grid(True, alpha=0.3)
    ax = fig.add_subplot(grid[1, 0])
    cd, cq = g.path["reference_curve"]
    ax.plot(np.asarray(cd) * 1e6, np.asarray(cq) / (g.mu * g.normal_force), "-", color="k",
            label="Mindlin-Deresiewicz\n(Masing's rule)")
    ax.plot(np.asarray(g.path["displacement"]) * 1e6,
            np.asarray(g.path["force"]) / (g.mu * g.normal_force), "o-", ms=3, lw=0.8,
            color="C3", label="result")
    ax.set_xlabel("tangential displacement [um]")
    ax.set_ylabel("Q / (mu P)")
    ax.set_title("force against displacement", fontsize=10)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=9)
    key = fig.add_subplot(grid[1, 1])
    key.axis("off")
    if handles:
        key.legend(handles, [h.get_label() for h in handles], loc="center", fontsize=9,
                   title="traction plots", title_fontsize=9)
    plot_checks(fig.add_subplot(grid[2, :]), g.checks, METRICS, fmt=_fmt)
    figure_title(fig, [
        f"{source_name(g)} against Cattaneo-Mindlin / Mindlin-Deresiewicz: "
        f"{'PASSED' if g.passed else 'FAILED'}",
        f"{g.scene}; P = {g.normal_force:.5g} N, mu = {g.mu:.3g}, load at "
        f"{r['direction_in_ellipse_frame_deg']:.3g} deg from the major axis, "
        f"{g.symmetry} model",
        g.hint])
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_grade(g: TangentialGrade, out, command: str = "") -> tuple[Path, Path, Path]:
    """DIR/grade.json, DIR/grade.md and DIR/grade.png of a TangentialGrade (DIR created)."""
    from .grade import write_grade_files

    return write_grade_files(g.to_dict(), out, command, grade_markdown(g, command),
                             lambda path: plot_grade(g, path))
