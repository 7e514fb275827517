"""Mesh-refinement study: the errors against Hertz as every element size shrinks by sqrt 2.

Writes study.json with

* ``levels``: one row per level, as in report.json (plus ``h_over_b``, the
  structured block's spacing in units of b);
* ``rates``: observed rates, the slope of log|error| against log h (least
  squares over all levels; np.polyfit);
* ``extrapolated``: Richardson's extrapolation of a, b and p0 to h = 0 from
  the two finest levels, e0 = e_n - (e_(n-1) - e_n) / (r**p - 1), r = sqrt 2,
  with p the observed rate of that quantity over all levels;
* ``three_level``: the classic three-level variant, whose order comes from the
  three finest levels alone (``orders``); shown beside it because that local
  order is sensitive to the wobble of a sequence (b of alpha-3, levels 3-5:
  the differences do not shrink and it gives NaN, where all levels give a
  rate of 1.71).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from ..grading.contact import TARGETS
from ..reports.blocks import COLUMNS, HEADERS, MEANINGS, report_document, report_markdown
from ..scenes import Scene
from ..solvers.mesh import LEVEL_H0, LEVEL_RATIO
from .validate import Comparison

#: Quantities whose rates are reported.
QUANTITIES = ("a_rel_err", "b_rel_err", "p0_rel_err", "rms_major", "rms_minor",
              "approach_rel_err")
#: Quantities extrapolated to h = 0.
EXTRAPOLATED = ("a_rel_err", "b_rel_err", "p0_rel_err")
#: Levels of a study by default.
DEFAULT_LEVELS = (1, 2, 3, 4, 5)


def observed_rates(h, errors: dict[str, list[float]]) -> dict[str, float]:
    """Slope of log|error| against log h (least squares) for each quantity.

    Parameters
    ----------
    h : array_like
        Element sizes (any unit).
    errors : dict
        Quantity -> its errors at those sizes.
    """
    logh = np.log(np.asarray(h, dtype=float))
    return {q: float(np.polyfit(logh, np.log(np.abs(e)), 1)[0]) for q, e in errors.items()}


def richardson(e1: float, e2: float, e3: float, ratio: float) -> tuple[float, float]:
    """Three-level Richardson extrapolation, refinement by a constant ratio.

    Assumes e(h) = e0 + C h**p; with e1, e2, e3 at h, h / ratio, h / ratio**2,
    p = log((e1 - e2) / (e2 - e3)) / log(ratio) and
    e0 = e3 - (e2 - e3) / (ratio**p - 1).

    Returns
    -------
    (e0, p) : tuple of float
        NaN for both when the differences do not shrink monotonically.

    Raises
    ------
    ValueError
        If ratio <= 1.
    """
    if not ratio > 1:
        raise ValueError(f"ratio must be > 1, got {ratio!r}")
    d1, d2 = e1 - e2, e2 - e3
    if d2 == 0 or d1 / d2 <= 1:
        return math.nan, math.nan
    p = math.log(d1 / d2) / math.log(ratio)
    return richardson_with_order(e2, e3, ratio, p), p


def richardson_with_order(e_coarse: float, e_fine: float, ratio: float, order: float) -> float:
    """Richardson extrapolation of two levels with a known order p > 0.

    e0 = e_fine - (e_coarse - e_fine) / (ratio**p - 1).

    Raises
    ------
    ValueError
        If ratio <= 1 or order <= 0.
    """
    if not ratio > 1:
        raise ValueError(f"ratio must be > 1, got {ratio!r}")
    if not order > 0:
        raise ValueError(f"order must be > 0, got {order!r}")
    return e_fine - (e_coarse - e_fine) / (ratio**order - 1)


def refinement_study(scene: Scene, levels, out: Path, command: str = "") -> dict:
    """Run ``scene`` at each mesh level; write study.json, study.md and study.png in ``out``.

    The returned record also holds ``readme``: the header and table the README shows
    (study.md adds what was run, the legend, the sign convention and the checks).

    Raises
    ------
    ValueError
        If fewer than 3 levels are given, or they are not consecutive (Richardson's
        extrapolation needs a constant refinement ratio).
    """
    from .validate import validate

    levels = sorted(set(levels))
    if len(levels) < 3:
        raise ValueError(f"levels must hold 3 or more levels, got {levels}")
    if levels != list(range(levels[0], levels[-1] + 1)):
        raise ValueError(f"levels must be consecutive, got {levels}")
    results = [validate(scene, level) for level in levels]
    study = study_of(scene.name, levels, results)
    out = Path(out)
    (out / "study.json").write_text(json.dumps(study, indent=1, default=float))
    rate_line = ", ".join(f"{q.removesuffix('_rel_err')} {rate:.2f}"
                          for q, rate in study["rates"].items())
    extra = ", ".join(f"{q.removesuffix('_rel_err')} {v:+.3f}%"
                      for q, v in ((q, 100 * v) for q, v in study["extrapolated"].items()))
    header = (f"Refinement study of {scene.name}, levels {levels} (every "
              f"element size divided by {LEVEL_RATIO:.3g} per level); observed rates "
              f"(slope of log|error| against log h): {rate_line}. Richardson's "
              f"extrapolation to h = 0 (two finest levels, observed rates): "
              f"{extra}.\n")
    table = report_markdown(results, header)
    run = header + (f"\nCommand: `{command}`." if command else "")
    (out / "study.md").write_text(report_document(
        results, run, f"Refinement study of {scene.name}", [k for k, _ in COLUMNS], HEADERS,
        MEANINGS, TARGETS, report_markdown(results),
        note="The targets are those of the default level (4); coarser levels are expected "
             "to miss them: the rates and the extrapolation are the study's result."))
    study["readme"] = table
    _plot(scene, np.array(study["h_over_b"]), results, study["rates"], out / "study.png")
    return study


def study_of(name: str, levels: list[int], results: list[Comparison]) -> dict:
    """The study's record from results at consecutive levels (see the module docstring)."""
    h = [LEVEL_H0[level] for level in levels]
    rows = [{**r.to_dict(), "h_over_b": hb} for r, hb in zip(results, h, strict=True)]
    rates = observed_rates(h, {q: [getattr(r, q) for r in results] for q in QUANTITIES})
    extrapolated, local, orders = {}, {}, {}
    for q in EXTRAPOLATED:
        e1, e2, e3 = (getattr(r, q) for r in results[-3:])
        extrapolated[q] = (richardson_with_order(e2, e3, LEVEL_RATIO, rates[q])
                           if rates[q] > 0 else math.nan)
        local[q], orders[q] = richardson(e1, e2, e3, LEVEL_RATIO)
    return {"scene": name, "level_numbers": levels, "h_over_b": h, "levels": rows,
            "rates": rates, "extrapolated": extrapolated,
            "three_level": {"extrapolated": local, "orders": orders}}


def _plot(scene, h, results, rates, path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4.5))
    for q, marker in zip(QUANTITIES, "osD^v<", strict=True):
        err = np.abs([getattr(r, q) for r in results])
        ax.loglog(h, err, marker + "-", label=f"{q} (rate {rates[q]:.2f})")
    ax.set_xlabel("structured-block spacing / b (every size scales with it)")
    ax.set_ylabel("|error| against Hertz")
    ax.set_title(f"{scene.name}: refinement study", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
