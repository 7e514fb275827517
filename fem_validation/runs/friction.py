"""Coulomb friction end to end: our frictional block run graded against
Cattaneo-Mindlin, and the table of several runs (``friction --collect``)."""

from __future__ import annotations

import json
import time
from pathlib import Path

import numpy as np

from ..limits import read_small_text
from ..reports.friction import COLUMNS

DEFAULT_ALPHAS = (1.0, 3.0, 10.0)


DEFAULT_MU = 0.3


#: Q*/(mu P) at the end of the ramp: the stick zone is then (0.2)^(1/3) = 0.58 of the
#: contact, so that both the stick ellipse and the slip annulus span many nodes.
DEFAULT_RATIO = 0.8


#: Ramp steps; unloading and reloading take twice as many each.  The loop energy's
#: trapezoid rule errs by about -1/m^2 with m steps per branch (-0.4% at 16).
DEFAULT_RAMP_STEPS = 8


DEFAULT_STUDY_LEVELS = (1, 2, 3, 4)


def mesh_axis(scene, axis: str) -> str:
    """The mesh axis ("x" or "y") along the contact's ``axis`` ("major" or "minor")."""
    along_x = abs(np.cos(scene.hertz().major_axis_angle)) > 0.5
    return "x" if (axis == "major") == along_x else "y"


def run(scene, level: int, mu: float, ratio: float, axis: str, ramp_steps: int, out: Path,
        command: str = "") -> dict:
    """Mesh, solve, grade and write one frictional run; its report row."""
    from ..grading.tangential import grade_tangential
    from ..reports.tangential import write_grade
    from ..solvers.friction import friction_mesh, friction_result, solve_friction

    t0 = time.perf_counter()
    mesh = friction_mesh(scene, level)
    sol = solve_friction(scene, mesh, mu, mesh_axis(scene, axis), ratio=ratio,
                         ramp_steps=ramp_steps)
    result = friction_result(scene, mesh, sol)
    g = grade_tangential(result, scene)
    seconds = time.perf_counter() - t0
    write_grade(g, out / f"{scene.name}-{axis}", command)
    c = scene.hertz(sol.normal.force)
    row = {"scene": scene.name, "level": level, "axis": axis, "alpha": float(c.alpha),
            "mu": mu, "load": sol.normal.force,
            "ratio": float(sol.force[sol.snapshot] / (mu * sol.normal.force)),
            "metrics": {k: v for k, v in g.metrics.items()}, "passed": g.passed,
            "failed": [ch.name for ch in g.checks if ch.passed is False],
            "dofs": sol.dofs, "steps": len(sol.steps),
            "iterations": int(sum(s.iterations for s in sol.steps)),
            "cg_iterations": int(sum(sum(s.cg_iterations) for s in sol.steps)),
            "amg_setups": sol.amg_setups, "coupling_pressure_over_p0":
            sol.coupling_pressure / c.p0, "seconds": seconds,
            "h0_over_b": mesh.h0 / scene.hertz().b, "command": command}
    (out / f"{scene.name}-{axis}" / "row.json").write_text(json.dumps(row, indent=1,
                                                                      default=float))
    return row


#: The largest grade.json, row.json or report --collect reads [bytes] (ours hold a few
#: hundred kB).
MAX_COLLECT_BYTES = 64 << 20


def _json(path: Path):
    return json.loads(read_small_text(path, "--collect: file", MAX_COLLECT_BYTES))


def row_from_grade(directory: Path) -> dict:
    """A report row from a run's directory: its grade.json (the metrics, the force, the
    command) and, when the run wrote it, row.json (the solver's counts and time).

    Raises
    ------
    ValueError
        Naming the file: it cannot be read, is larger than MAX_COLLECT_BYTES, is not JSON
        or not the grade of a frictional run.
    """
    directory = Path(directory)
    path = directory / "grade.json"
    try:
        g = _json(path)
    except ValueError as exc:
        raise ValueError(f"--collect: cannot read {path}: {exc}") from None
    if not isinstance(g, dict) or g.get("kind") != "tangential":
        raise ValueError(f"--collect: {path} is not a tangential grade")
    axis = directory.name.rsplit("-", 1)[-1]
    try:
        level = int(g["source"].rsplit("level ", 1)[-1])
        solver = {}
        if (directory / "row.json").is_file():
            path = directory / "row.json"
            solver = _json(path)
        else:  # a run made before rows were kept beside the grade: its report's row
            for report in (directory.parent / "friction.json",
                           directory.parent.parent / "study.json"):
                if report.is_file():
                    path = report
                    solver = next((r for r in _json(report)["rows"]
                                   if (r["scene"], r["axis"], r["level"])
                                   == (g["scene"], axis, level)), {})
                    break
        return {"scene": g["scene"], "level": level, "axis": axis,
                "load": g["normal_force"], "ratio": g["fem"]["snapshot_force_ratio"],
                "metrics": {c["name"]: c["value"] for c in g["checks"]},
                "passed": g["passed"], "command": g.get("command", ""),
                **{k: solver.get(k) for k in ("dofs", "iterations", "seconds")}}
    except (KeyError, TypeError, AttributeError, IndexError, ValueError) as exc:
        raise ValueError(f"--collect: {path} is not what a friction run writes "
                         f"({type(exc).__name__}: {exc})"[:300]) from None


def study_rates(rows: list[dict]) -> dict:
    """Observed rates: slopes of log|error| against log(element size) per metric."""
    h = np.array([r["h0_over_b"] for r in rows])
    rates = {}
    for key, _ in COLUMNS[:7]:
        err = np.array([abs(r["metrics"].get(key, np.nan)) for r in rows])
        ok = np.isfinite(err) & (err > 0)
        if ok.sum() >= 2:
            rates[key] = float(np.polyfit(np.log(h[ok]), np.log(err[ok]), 1)[0])
    return rates
