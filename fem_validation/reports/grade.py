"""A graded result as files: grade.json, grade.md and grade.png, for every grade type
(one table, one bar chart of the checks)."""

from __future__ import annotations

import contextlib
import json
import math
import warnings
from pathlib import Path

import numpy as np

SIGN_CONVENTION = ("Errors are (result - Hertz) / Hertz, Hertz evaluated at the force the "
                   "result reached (matched force); RMS values are fractions of Hertz's p0.")


def grade_json(row: dict) -> str:
    """The text of grade.json: strict JSON (no NaN, no Infinity; a metric that is not
    defined is null, :func:`fem_validation.grading.contact.nan_to_none`).

    Raises
    ------
    RuntimeError
        Where a number is not finite: a grader let an overflow through, a defect (exit
        status 3), never a file that other tools cannot read.
    """
    try:
        return json.dumps(row, indent=1, default=float, allow_nan=False)
    except ValueError as exc:
        raise RuntimeError(f"grade.json would hold a non-finite number ({exc}); the grader "
                           f"should have refused the input or reported null") from None


@contextlib.contextmanager
def quiet_figure():
    """Draw a figure without warnings on stderr (a context manager and a decorator).

    The numbers a figure shows are the grade's, checked finite; what matplotlib or numpy
    may still say while scaling axes over a wide range (ticks near the largest float, a
    layout that does not fit) concerns the picture only, and a command prints one line.
    """
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        yield


def _fmt(name: str, value: float) -> str:
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    if name == "angle_err_deg":
        return f"{value:+.2f} deg"
    if name == "exponent_err":
        return f"{value:+.4f}"
    if name.startswith(("rms_", "stress_rms_", "force_rel_err_rms")):
        return f"{value:.2%}"
    return f"{value:+.2%}"


def _tol(name: str, tol) -> str:
    if tol is None:
        return "-"
    if name == "exponent_err":
        return f"{tol:.4f}"
    return f"{tol:.2f} deg" if name == "angle_err_deg" else f"{tol:.2%}"


def checks_table(checks, metrics_doc, fmt=None) -> list[str]:
    """Markdown rows of a grade's checks: metric, meaning, value, tolerance, status
    (``fmt(name, value)``: the text of a value, default this module's)."""
    fmt = _fmt if fmt is None else fmt
    lines = ["| check | what it measures | value | tolerance | status |", "|---|---|---|---|---|"]
    for ch in checks:
        header, meaning = metrics_doc.get(ch.name, (ch.name, ""))
        status = ch.status.upper() if ch.passed is not None else ch.status
        meaning = meaning.replace("|", "\\|")
        lines.append(f"| {header} (`{ch.name}`) | {meaning} | {fmt(ch.name, ch.value)} | "
                     f"{_tol(ch.name, ch.tolerance)} | {status} |")
    return lines


def grade_markdown(g, command: str = "") -> str:
    """grade.md: what was graded, the method, every check with its tolerance, the verdict."""
    from ..grading.contact import CURVE_METRICS, METRICS

    curve = g.details.get("kind") == "force-approach"
    h = g.hertz
    failed = [c.name for c in g.checks if c.status == "fail"]
    lines = [f"# Grade against Hertz: {'PASSED' if g.passed else 'FAILED'}", ""]
    if g.hint:
        lines += [f"> {g.hint}", ""]
    lines += ["## What was graded", ""]
    if command:
        lines.append(f"- command: `{command}`")
    lines += [f"- result: `{g.source or '-'}`", f"- scene: {g.scene}"]
    if curve:
        lines += [f"- a normal force against approach curve, {g.details['points']} points with "
                  f"a positive approach; Hertz's force F(delta) of the scene's bodies at each "
                  f"approach (`hertz.contact(..., approach=delta)`)",
                  f"- largest force {g.force:.6g} N; Hertz there: a {h['a']:.6g} m, "
                  f"b {h['b']:.6g} m, p0 {h['p0']:.6g} Pa, alpha {h['alpha']:.4g}"]
    else:
        d = g.details
        method = ("second moments of the nodal forces" if g.semi_axes == "moments"
                  else "least-squares fit of p^2")
        lines += [f"- force (whole model, Hertz evaluated there): {g.force:.6g} N; symmetry "
                  f"of the model: {g.symmetry} (forces of a quarter model x4, half x2)",
                  f"- reader: {d.get('reader', '-')}, units of the file: {d.get('units', 'SI')}",
                  f"- Hertz at that force: a {h['a']:.6g} m, b {h['b']:.6g} m, p0 "
                  f"{h['p0']:.6g} Pa, delta {h['delta']:.6g} m, alpha {h['alpha']:.4g}, major "
                  f"axis at {h['major_axis_angle_deg']:.3g} deg from body 1's x axis",
                  f"- result: a {g.fem['a']:.6g} m, b {g.fem['b']:.6g} m (semi-axes from the "
                  f"{method}), "
                  f"p0 {g.fem['p0']:.6g} Pa (fit of p^2 above 20% of the largest pressure), "
                  f"largest nodal pressure {g.fem['peak_nodal_pressure']:.6g} Pa"]
        v = h.get("validity") or {}
        if v:
            dep = v["departure"]
            lines.append(f"- Hertz's validity: a/R = {v['a_over_r']:.4g} (R the smallest "
                         f"radius; hertz.A_OVER_R_LIMIT = {v['limit']:.3g}), conformity "
                         f"{v['conformity']:.2f}; true curved bodies depart from the theory "
                         f"there by a {dep['a']:+.2%}, b {dep['b']:+.2%}, p0 {dep['p0']:+.2%}, "
                         f"approach {dep['delta']:+.2%} ("
                         + ("extrapolated from " if v["departure_extrapolated"] else "")
                         + f"{v['departure_from']})")
    convention = ("Errors are (result - Hertz) / Hertz, Hertz's force taken at the same "
                  "approach." if curve else SIGN_CONVENTION)
    lines += ["", "## Sign convention", "", convention, "",
              "## Checks", "",
              "Status: PASS / FAIL against the tolerance (|value| at most the tolerance); "
              "*information*: reported, not checked (the edge of the pressed region moves "
              "with how a code spreads pressure past the edge: 6-12% for CalculiX); *by "
              "construction*: holds by the way the result was made, so it checks nothing; "
              "*not available*: the result does not hold what it needs.", ""]
    lines += checks_table(g.checks, {**METRICS, **CURVE_METRICS})
    lines += ["", "## Verdict", "",
              ("PASSED: every checked metric is within its tolerance." if g.passed else
               f"FAILED: {', '.join(failed)} outside the tolerance.")]
    notes = getattr(g, "notes", ())
    if notes:
        lines += ["", "## Notes", ""] + [f"- {n}" for n in notes]
    if not curve:
        lines += ["", "## Method", "", "See `fem_validation.grading.contact`: a, b from the second "
                  "moments of the nodal forces (sum f x^2 = P a^2/5 for Hertz's pressure) or "
                  "from the p^2 fit; p0 from the fit; profiles: the nodal pressure "
                  "interpolated on the surface triangles along Hertz's axes to 1.2 semi-axes; "
                  "von Mises: the vertex of a parabola through the 5 axis nodes around the "
                  "largest value; stress RMS: the nodal stress interpolated in the "
                  "tetrahedra, 0.05 b to 3 b deep."]
    return "\n".join(lines) + "\n"


#: Bars of the checks chart stop at this |value| / tolerance (the value is written beside).
CHECKS_CLIP = 3.0


def source_name(g) -> str:
    """The graded result's file name without its directories (else the scene's name)."""
    return Path(g.source).name if g.source else g.scene


def figure_title(fig, lines, width: int = 78) -> None:
    """A figure's title: each line wrapped to ``width`` characters, at a size that reads at
    page width."""
    import textwrap

    fig.suptitle("\n".join(textwrap.fill(line, width) for line in lines if line),
                 fontsize=11)


def plot_checks(ax, checks, metrics_doc: dict, fmt=None, tol=None) -> None:
    """The checks of a grade as horizontal bars of |value| / tolerance (green pass, red
    fail), one per checked metric, labelled with its short name, its value and tolerance
    beside the bar; bars stop at :data:`CHECKS_CLIP` (the value says how far beyond).

    Parameters
    ----------
    ax : matplotlib Axes
    checks : sequence of Check
        Those without a tolerance or a pass/fail status are left out.
    metrics_doc : dict
        Metric name -> (short name, meaning), e.g. ``fem_validation.grading.contact.METRICS``.
    fmt, tol : callable, optional
        (name, value) -> text of a value and of a tolerance (default: this module's).
    """
    fmt = _fmt if fmt is None else fmt
    tol = _tol if tol is None else tol
    checked = [c for c in checks if c.tolerance is not None and c.passed is not None]
    ratio = np.array([abs(c.value) / c.tolerance for c in checked])
    shown = np.minimum(ratio, CHECKS_CLIP)
    y = np.arange(len(checked))
    ax.barh(y, shown, color=["C2" if c.passed else "C3" for c in checked], height=0.6)
    ax.axvline(1.0, color="k", lw=1)
    right = max(1.2, float(shown.max()) if len(shown) else 1.0)
    for k, c in enumerate(checked):
        ax.text(shown[k] + 0.02 * right, k, f"{fmt(c.name, c.value)} (tol "
                f"{tol(c.name, c.tolerance)})" + (" >>" if ratio[k] > CHECKS_CLIP else ""),
                va="center", fontsize=9,
                bbox={"facecolor": "white", "edgecolor": "none", "pad": 1})
    ax.set_xlim(0, 1.75 * right)
    ax.set_yticks(y)
    ax.set_yticklabels([metrics_doc.get(c.name, (c.name,))[0] for c in checked], fontsize=10)
    ax.invert_yaxis()
    ax.set_xlabel("|value| / tolerance (1 = the limit)", fontsize=10)
    ax.set_title("checks (green pass, red fail)", fontsize=10)


@quiet_figure()
def plot_grade(g, path: Path) -> Path:
    """grade.png: the pressure along Hertz's axes (or, for a force-approach curve, the
    force and its error) above the checks; titled with the result's file name, the verdict
    and the unit hint, sized to read at page width (8 inches)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ..grading.contact import CURVE_METRICS, METRICS

    curve = g.details.get("kind") == "force-approach"
    fig = plt.figure(figsize=(8, 8.2))
    grid = fig.add_gridspec(2, 2, height_ratios=[1, 0.9])
    axes = [fig.add_subplot(grid[0, 0]), fig.add_subplot(grid[0, 1]),
            fig.add_subplot(grid[1, :])]
    h = g.hertz
    if curve:
        d, f, ref = (np.asarray(g.fem[k]) for k in ("approach", "force", "hertz_force"))
        axes[0].loglog(d * 1e6, ref, "-", color="k", label="Hertz F(delta)")
        axes[0].loglog(d * 1e6, f, "o", ms=3, color="C3", label="result")
        axes[0].set_xlabel("approach delta [um]")
        axes[0].set_ylabel("normal force [N]")
        axes[0].set_title("force against approach", fontsize=10)
        axes[1].plot(d * 1e6, 100 * np.asarray(g.fem["rel_err"]), "o-", ms=3, color="C3",
                     label="(F - F_Hertz) / F_Hertz")
        limit = g.check("force_rel_err_max").tolerance
        if limit is not None:
            for s in (-1, 1):
                axes[1].axhline(100 * s * limit, color="0.5", ls=":",
                                label="tolerance" if s > 0 else None)
        axes[1].set_xlabel("approach delta [um]")
        axes[1].set_ylabel("force error [%]")
        axes[1].set_title("error along the curve", fontsize=10)
    else:
        for ax, name, semi in zip(axes[:2], ("major", "minor"), (h["a"], h["b"]), strict=True):
            d = g.profiles[name]
            ax.plot(d["s"] / semi, d["hertz"] / h["p0"], "-", color="k", label="Hertz")
            ax.plot(d["s"] / semi, d["fem"] / h["p0"], "o", ms=2.5, color="C3",
                    label="result")
            ax.set_xlabel(f"along Hertz's {name} axis / {'a' if name == 'major' else 'b'}")
            ax.set_title(f"pressure, {name} axis", fontsize=10)
        axes[0].set_ylabel("pressure / Hertz's p0")
    for ax in axes[:2]:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=9, loc="best")
    plot_checks(axes[2], g.checks, {**METRICS, **CURVE_METRICS})
    figure_title(fig, [
        f"{source_name(g)} against Hertz: {'PASSED' if g.passed else 'FAILED'}",
        f"{g.scene}; force {g.force:.5g} N"
        + ("" if curve else f" (whole contact, {g.symmetry} model)")
        + "; errors (result - Hertz) / Hertz at "
        + ("the same approach" if curve else "the same force"),
        g.hint])
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_grade_files(row: dict, out, command: str, markdown: str,
                      plot) -> tuple[Path, Path, Path]:
    """DIR/grade.json (``row`` and the command), DIR/grade.md (``markdown``) and
    DIR/grade.png (``plot(path)``), DIR created: the three files of every grade type."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    paths = out / "grade.json", out / "grade.md", out / "grade.png"
    if command:
        row["command"] = command
    paths[0].write_text(grade_json(row))
    paths[1].write_text(markdown)
    plot(paths[2])
    return paths


def write_grade(g, out: Path, command: str = "") -> tuple[Path, Path, Path]:
    """DIR/grade.json, DIR/grade.md and DIR/grade.png of a Grade."""
    row = g.to_dict()
    if g.details.get("kind") == "force-approach":
        row["fem"] = {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in g.fem.items()}
    return write_grade_files(row, out, command, grade_markdown(g, command),
                             lambda path: plot_grade(g, path))


def series_markdown(s, grades, command: str = "") -> str:
    """grade.md of a mesh series: each mesh's size and verdict, then per metric its values,
    observed order, extrapolated value and uncertainty."""
    from ..grading.contact import METRICS
    from ..grading.series import SAFETY_FACTOR

    lines = [f"# Mesh series against Hertz: {'PASSED' if all(s.passed) else 'FAILED'}", ""]
    if command:
        lines.append(f"- command: `{command}`")
    lines += [f"- scene: {s.scene}", "",
              "| mesh | result | h [m] | force [N] | grade |", "|---|---|---|---|---|"]
    by_source = {g.source: g for g in grades}
    for k, (src, h, ok) in enumerate(zip(s.sources, s.h, s.passed, strict=True), start=1):
        g = by_source.get(src)
        force = f"{g.force:.6g}" if g is not None else "-"
        lines.append(f"| {k} | `{Path(src).name}` | {h:.4g} | {force} | "
                     f"{'PASSED' if ok else 'FAILED'} |")
    lines += ["", "## Convergence", "",
              "Observed order p from the three finest meshes (Roache's grid convergence "
              "study); the value extrapolated to h -> 0 (Richardson) and its uncertainty, "
              f"the finest mesh's grid convergence index ({SAFETY_FACTOR} |e3 - e2| / "
              "((h2/h3)^p - 1)).  Values are relative errors against Hertz at each "
              "mesh's own force."
              + (f"  Expected order: {s.expected_order:g}." if s.expected_order else ""), "",
              "| metric | " + " | ".join(f"mesh {k}" for k in range(1, len(s.h) + 1))
              + " | order | extrapolated | uncertainty | behaviour |",
              "|---" * (len(s.h) + 5) + "|"]
    for name, c in s.metrics.items():
        vals = " | ".join(_fmt(name, v) for v in c.values)
        order = "-" if math.isnan(c.order) else f"{c.order:.2f}"
        lines.append(f"| {METRICS.get(name, (name,))[0]} | {vals} | {order} | "
                     f"{_fmt(name, c.extrapolated)} | "
                     f"{'-' if math.isnan(c.uncertainty) else f'{c.uncertainty:.2%}'} | "
                     f"{c.behaviour} |")
    return "\n".join(lines) + "\n"


@quiet_figure()
def plot_series(s, path: Path) -> Path:
    """grade.png of a mesh series: |error| against the mesh size, log-log, per metric."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(8, 5.5))
    h = np.asarray(s.h)
    for name in ("a_rel_err", "b_rel_err", "p0_rel_err", "rms_major", "von_mises_rel_err"):
        c = s.metrics.get(name)
        if c is None:
            continue
        v = np.abs(np.asarray(c.values, dtype=float))
        if not (np.isfinite(v) & (v > 0)).any():
            continue
        label = name + ("" if math.isnan(c.order) else f" (p = {c.order:.2f})")
        ax.loglog(h * 1e3, v, "o-", ms=4, label=label)
    ax.set_xlabel("mesh size h [mm]")
    ax.set_ylabel("|relative error| against Hertz")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=9)
    figure_title(fig, [f"mesh series against Hertz: {'PASSED' if all(s.passed) else 'FAILED'}",
                       f"{s.scene}; {len(h)} meshes"])
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_series(s, grades, out: Path, command: str = "") -> tuple[Path, Path, Path]:
    """DIR/grade.json, DIR/grade.md and DIR/grade.png of a mesh series
    (:class:`fem_validation.grading.series.Series`), each mesh's grade in grade.json."""
    row = s.to_dict()
    row["passed_all"] = all(s.passed)
    row["grades"] = [{k: v for k, v in g.to_dict().items() if k != "stress"} for g in grades]
    return write_grade_files(row, out, command, series_markdown(s, grades, command),
                             lambda path: plot_series(s, path))
