"""The curved-bodies table (curved.md) and figure (curved.png) of ``--curved``."""

from __future__ import annotations

import math
from pathlib import Path

COLUMNS = [("scene", "{}"), ("level", "{}"), ("load", "{:.4g}"), ("a_over_r", "{:.3f}"),
           ("a_rel_err", "{:+.2%}"), ("b_rel_err", "{:+.2%}"), ("p0_rel_err", "{:+.2%}"),
           ("a_arc_rel_err", "{:+.2%}"), ("b_arc_rel_err", "{:+.2%}"),
           ("approach_rel_err", "{:+.2%}"), ("max_penetration_over_delta", "{:.1e}"),
           ("dofs", "{}"), ("seconds", "{:.0f}"), ("peak_memory_mb", "{:.0f}")]
HEADERS = {"load": "P [N]", "a_over_r": "a/R", "a_rel_err": "a", "b_rel_err": "b",
           "p0_rel_err": "p0 (fit)", "a_arc_rel_err": "a (arc)", "b_arc_rel_err": "b (arc)",
           "approach_rel_err": "approach*", "max_penetration_over_delta": "penetration/delta",
           "seconds": "s", "peak_memory_mb": "MB"}


#: What each column of curved.md holds.
CURVED_MEANINGS = {
    "scene": "sphere-plane: a steel ball on a flat steel block; ball-groove: the ball in a "
             "groove of radius 1.04 R",
    "level": "mesh level (0-4; each divides every element size by sqrt 2)",
    "load": "vertical contact force reached [N]; Hertz is evaluated at it",
    "a_over_r": "Hertz's semi-major axis at that force over the ball radius",
    "a_rel_err": "semi-major axis from the second moments of the vertical nodal forces, "
                 "nodes projected on z = 0",
    "b_rel_err": "semi-minor axis, likewise",
    "p0_rel_err": "peak pressure of the least-squares fit of p^2",
    "a_arc_rel_err": "as a, nodes at their geodesic distance on the ball",
    "b_arc_rel_err": "as b, likewise",
    "approach_rel_err": "equator approach plus the Boussinesq settlement of both far faces "
                        "against Hertz's delta (an indication: the correction is approximate)",
    "max_penetration_over_delta": "largest penetration over Hertz's delta (penalty "
                                  "diagnostic)",
    "dofs": "unknowns of the linear system",
    "seconds": "wall time: mesh, solve, comparison [s]",
    "peak_memory_mb": "peak resident memory during the run [MB]",
    "net a": "a less the same scene's a at the smallest a/R on the same level (Hertz's own "
             "error, the mesh's share removed)",
    "net b": "likewise for b", "net p0 (fit)": "likewise for p0",
    "net a (arc)": "likewise for a (arc)",
}


def curved_document(results: list, header: str, targets: dict) -> str:
    """curved.md: what was run, the legend, the sign convention, the checks, the table."""
    from .blocks import report_document

    columns = [k for k, _ in COLUMNS] + ["net a", "net b", "net p0 (fit)", "net a (arc)"]
    return report_document(
        results, header, "True curved bodies against Hertz", columns, HEADERS,
        CURVED_MEANINGS, targets, curved_markdown(results),
        note="The tolerance is the issue's target for the discretisation error, met at the "
             "smallest a/R; at larger a/R a miss measures Hertz's own error (small-contact "
             "assumption), which is what this run is for: read the net columns.")


def curved_markdown(results: list, header: str = "") -> str:
    """The curved-bodies table (errors relative to Hertz at the force reached)."""
    lines = [header] if header else []
    shown = ("a_rel_err", "b_rel_err", "p0_rel_err", "a_arc_rel_err")
    net = [f"net {HEADERS.get(k, k)}" for k in shown]
    lines.append("| " + " | ".join([HEADERS.get(k, k) for k, _ in COLUMNS] + net) + " |")
    lines.append("|" + "---|" * (len(COLUMNS) + len(net)))
    for r in results:
        cells = []
        for key, fmt in COLUMNS:
            value = getattr(r, key)
            cells.append("-" if isinstance(value, float) and math.isnan(value)
                         else fmt.format(value))
        for key in shown:
            value = r.net_of_smallest.get(key, math.nan)
            cells.append("-" if math.isnan(value) else f"{value:+.2%}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def plot_curved(results: list, path: Path) -> Path:
    """PNG: the errors of a, b, p0 (and the approach) against a/R, one column per scene.

    Top: the errors of a, b, p0 and the approach; bottom: a, b, p0 and a (arc)
    net of the smallest a/R's errors (``net_of_smallest``, see
    :func:`net_errors`).  With several mesh levels, the finest is drawn solid
    and the coarser ones faded and dashed: the gap between them is the
    discretisation error.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = list(dict.fromkeys(r.scene for r in results))
    levels = sorted({r.level for r in results})
    fig, axes = plt.subplots(2, len(names), figsize=(5.5 * len(names), 8), sharex=True,
                             squeeze=False)
    top = (("a_rel_err", "a", "o", "C0"), ("b_rel_err", "b", "s", "C1"),
           ("p0_rel_err", "p0", "^", "C2"), ("approach_rel_err", "approach*", "x", "C3"))
    bottom = top[:3] + (("a_arc_rel_err", "a (arc)", "D", "C4"),)
    for col, name in enumerate(names):
        for level in levels:
            rows = sorted((r for r in results if r.scene == name and r.level == level),
                          key=lambda r: r.a_over_r)
            if not rows:
                continue
            finest = level == levels[-1]
            x = [r.a_over_r for r in rows]
            for row, quantities in ((0, top), (1, bottom)):
                for key, label, marker, color in quantities:
                    y = [100 * (getattr(r, key) if row == 0
                                else r.net_of_smallest.get(key, math.nan)) for r in rows]
                    axes[row, col].plot(x, y, marker=marker, color=color,
                                        ls="-" if finest else "--",
                                        alpha=1.0 if finest else 0.4,
                                        label=f"{label}, level {level}")
        alpha = results[[r.scene for r in results].index(name)].hertz.get("alpha", math.nan)
        axes[0, col].set_title(f"{name} (Hertz alpha = {alpha:.3g})", fontsize=10)
        axes[1, col].set_xlabel("a / R (Hertz semi-major axis over ball radius)")
        for ax in axes[:, col]:
            ax.axhline(0, color="k", lw=0.8)
            ax.set_xscale("log")
            ax.grid(True, which="both", alpha=0.3)
        for lim in (-1.5, 1.5):
            axes[0, col].axhline(lim, color="0.6", lw=0.8, ls=":")
        for ax in axes[:, col]:
            ax.legend(fontsize=7, ncol=2)
    lows, highs = zip(*(ax.get_ylim() for ax in axes[1]), strict=True)
    for ax in axes[1]:  # one scale: the scenes' own errors side by side
        ax.set_ylim(min(lows), max(highs))
    axes[0, 0].set_ylabel("(FEM - Hertz) / Hertz [%]")
    axes[1, 0].set_ylabel("Hertz's own error: the same less its value at a/R = 0.01 [%]")
    fig.suptitle("A real ball against Hertz at matched force (top); net of the mesh's share "
                 "(bottom). *approach: indicative, see the text", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
    return path
