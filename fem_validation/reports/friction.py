"""The frictional runs as a report: the table of several runs (``friction --collect``)
and the figure of a refinement study."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def plot_study(rows: list[dict], path: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    h = np.array([r["h0_over_b"] for r in rows])
    fig, ax = plt.subplots(figsize=(6, 4))
    for key, header in COLUMNS[:7]:
        err = np.array([abs(r["metrics"].get(key, np.nan)) for r in rows])
        ax.loglog(h, 100 * err, "o-", label=header)
    ax.set_xlabel("grid spacing h0 / b")
    ax.set_ylabel("|error| [%] (RMS: % of mu p0)")
    ax.set_title(f"{rows[0]['scene']}, load along the {rows[0]['axis']} axis")
    ax.legend(fontsize=7)
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


#: Metrics of the summary table: (key, header).
COLUMNS = (("stick_a_rel_err", "stick a"), ("stick_b_rel_err", "stick b"),
           ("force_rel_err_max", "Q(delta) ramp"), ("branch_err_max", "Q(delta) loop"),
           ("loop_energy_rel_err", "loop energy"), ("traction_rms_major", "q RMS major"),
           ("traction_rms_minor", "q RMS minor"), ("transverse_shear_max", "q transverse"))


RELATIVE = {"stick_a_rel_err", "stick_b_rel_err", "force_rel_err_max", "branch_err_max",
            "loop_energy_rel_err"}


def _cell(key: str, value) -> str:
    if value is None or not np.isfinite(value):
        return "-"
    return f"{100 * value:+.2f}%" if key in RELATIVE else f"{100 * value:.2f}%"


def table(rows: list[dict]) -> str:
    """The summary table of report rows (markdown)."""
    head = ["scene", "level", "load along", "P [N]", "Q*/(mu P)",
            *[h for _, h in COLUMNS], "dofs", "solves", "s"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for r in rows:
        cells = [r["scene"], str(r["level"]), r["axis"], f"{r['load']:.4g}",
                 f"{r['ratio']:.3f}", *[_cell(k, r["metrics"].get(k)) for k, _ in COLUMNS],
                 *[("-" if r.get(k) is None else f"{r[k]:.0f}")
                   for k in ("dofs", "iterations", "seconds")]]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


LEGEND = (
    "Errors are (FEM - reference)/reference, the reference being Cattaneo-Mindlin and "
    "Mindlin-Deresiewicz (hertz) at the normal force P the FEM reached.  stick a, b: the "
    "stick ellipse's semi-axes from a fit of (mu p - q)^2 at the end of the ramp (tolerance "
    "2%); Q(delta) ramp: largest relative error of the force at the displacement on the "
    "ramp (1%); Q(delta) loop: largest error on the unloading and reloading branches over "
    "Q* (1%); loop energy: the trapezoid area of the loop against Mindlin-Deresiewicz's "
    "energy per cycle (3%); q RMS: the shear along the load on the major and minor axes "
    "against Cattaneo-Mindlin, over mu p0 (3%); q transverse: the largest shear across "
    "the load over mu p0 (information: Mindlin's solution has none); solves: linear "
    "solves over the whole path.")
