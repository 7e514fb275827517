"""Mesh-refinement study: the errors against Hertz as the contact-zone element size halves."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from .compare import Comparison, report_markdown
from .mesh import LEVEL_H0
from .scenes import Scene

QUANTITIES = ("a_rel_err", "b_rel_err", "p0_rel_err", "rms_major", "rms_minor")


def observed_rates(h: np.ndarray, results: list[Comparison]) -> dict[str, float]:
    """Slope of log|error| against log h (least squares) for each quantity."""
    rates = {}
    for q in QUANTITIES:
        err = np.abs([getattr(r, q) for r in results])
        rates[q] = float(np.polyfit(np.log(h), np.log(err), 1)[0])
    return rates


def refinement_study(scene: Scene, levels, out: Path) -> dict:
    """Run ``scene`` at each mesh level; write study.json, study.md and study.png in ``out``."""
    from . import validate

    levels = sorted(set(levels))
    if len(levels) < 3:
        raise ValueError(f"a refinement study needs 3 or more levels, got {levels}")
    results = [validate(scene, level) for level in levels]
    h = np.array([LEVEL_H0[level] for level in levels])
    rates = observed_rates(h, results)
    study = {"scene": scene.name, "levels": levels, "h0_over_b": h.tolist(), "rates": rates,
             "results": [r.to_dict() for r in results]}
    (out / "study.json").write_text(json.dumps(study, indent=1, default=float))
    rate_line = ", ".join(f"{q.removesuffix('_rel_err')} {rate:.2f}" for q, rate in rates.items())
    (out / "study.md").write_text(
        report_markdown(results, f"Refinement study of {scene.name}, levels {levels}; observed "
                        f"rates (slope of log|error| against log h): {rate_line}.\n") + "\n")
    _plot(scene, h, results, rates, out / "study.png")
    return study


def _plot(scene, h, results, rates, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for q, marker in zip(QUANTITIES, "osD^v", strict=True):
        err = np.abs([getattr(r, q) for r in results])
        ax.loglog(h, err, marker + "-", label=f"{q} (rate {rates[q]:.2f})")
    ax.set_xlabel("element size in the contact zone / b")
    ax.set_ylabel("|error| against Hertz")
    ax.set_title(f"{scene.name}: refinement study", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
