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

import numpy as np

from .elasticity import von_mises

if TYPE_CHECKING:
    from .compare import Comparison
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
    from .compare import ellipse_rotation

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

    from .compare import recovered_stress

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


def write_reports(results: list[Comparison], out: Path, header: str = "",
                  targets: dict | None = None) -> tuple[Path, Path]:
    """report.json (a list, one object per scene; NaN as null) and report.md.

    report.md stands alone (:func:`report_document`); the README's table is
    :func:`report_markdown` of the same results.
    """
    from .compare import TARGETS

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

SIGN_CONVENTION = ("Errors are (result - Hertz) / Hertz, Hertz evaluated at the force the "
                   "result reached (matched force); RMS values are fractions of Hertz's p0.")


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
    from .grade import CURVE_METRICS, METRICS

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
    if not curve:
        lines += ["", "## Method", "", "See `fem_validation.grade`: a, b from the second "
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
        Metric name -> (short name, meaning), e.g. ``fem_validation.grade.METRICS``.
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


def plot_grade(g, path: Path) -> Path:
    """grade.png: the pressure along Hertz's axes (or, for a force-approach curve, the
    force and its error) above the checks; titled with the result's file name, the verdict
    and the unit hint, sized to read at page width (8 inches)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from .grade import CURVE_METRICS, METRICS

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
        + f"; errors (result - Hertz) / Hertz at "
        + ("the same approach" if curve else "the same force"),
        g.hint])
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path


def write_grade(g, out: Path, command: str = "") -> tuple[Path, Path, Path]:
    """DIR/grade.json, DIR/grade.md and DIR/grade.png of a Grade."""
    out = Path(out)
    paths = out / "grade.json", out / "grade.md", out / "grade.png"
    row = g.to_dict()
    if command:
        row["command"] = command
    if g.details.get("kind") == "force-approach":
        row["fem"] = {k: (v.tolist() if hasattr(v, "tolist") else v) for k, v in g.fem.items()}
    paths[0].write_text(json.dumps(row, indent=1, default=float))
    paths[1].write_text(grade_markdown(g, command))
    plot_grade(g, paths[2])
    return paths


def prepare_out(path) -> Path:
    """The output directory, created; ValueError (one line) where it cannot be written.

    Refused: an existing file, a directory that cannot be created, one where no file
    can be written (probed by creating and removing a temporary file).
    """
    import tempfile

    path = Path(path)
    if path.exists() and not path.is_dir():
        raise ValueError(f"--out {str(path)!r} exists and is not a directory")
    try:
        path.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=path, prefix=".probe"):
            pass
    except OSError as exc:
        raise ValueError(f"--out {str(path)!r} cannot be written: "
                         f"{exc.strerror or exc}") from None
    return path
