"""A 2-D result (:class:`~fem_validation.results.plane.PlaneResult`) against Hertz.

Plane strain is graded against ``hertz.line_contact`` at the result's force per unit
length, axisymmetric against ``hertz.contact`` at its total force (full circle).  The
measures are those of the 3-D grade (:mod:`fem_validation.grading.contact`), on a line:

* **Force**: the result's (a reaction for a displacement-controlled run); Hertz is evaluated
  there.  ``pressure_integral_rel_err``: the nodal pressure integrated by the trapezoidal
  rule (plane strain: over x, times 2 for a half model; axisymmetric: 2 pi r p over r)
  against the force; ``reaction_rel_err`` (information): the force over the other body's
  reaction, minus 1.
* **Half-width b / contact radius a and p0, by the edge-tolerant fit**: least squares of
  p**2 = c0 - q x**2 on the nodes above FIT_THRESHOLD (the 3-D grade's 0.2) of the largest
  pressure, in the model's measure (weight 1 per node in plane strain, r in an axisymmetric
  model, as the area each node stands for, which a 3-D surface's nodes stand for by
  themselves); then once more without the nodes within INNER (half) of the width whose
  pressure lies more than OUTLIER_MADS median absolute deviations (and 1% of p0) off the
  first fit (a code's spike at the axis or at a corner); p0 = sqrt(c0), b (a) =
  sqrt(c0 / q).  Codes that smear the pressure past the edge hardly move it.
* **Moments** (information): b**2 = 4 <x**2> (plane strain), a**2 = 5/2 <r**2>
  (axisymmetric), the means over the pressure in the model's measure: exact for Hertz's
  pressure, biased by a smeared edge.
* **Edge** (information): the middle between the last node in contact (the code's status,
  else p > 0) and the next.
* **Profile**: the nodal pressure, linear between nodes, against Hertz's at 121 points
  out to PROFILE_EXTENT (1.2) half-widths: the RMS of the difference over p0, over the
  contact's area (axisymmetric: each point weighted by its radius, the ring it stands for,
  so that a code's spike at the nodes next to the axis counts for the area it covers).
* **Approach**: only where the result gives one (an axisymmetric model corrected for its
  finite bodies).  A line contact's approach depends on the bodies' sizes (Johnson, ch. 5):
  never checked.
* **Stresses**: the von Mises stress along the axis below the first point of contact, per
  body the file holds, its maximum deeper than SURFACE_SKIP (0.2) half-widths by the 3-D
  grade's local parabola (``peak``), against
  ``LineContact.subsurface`` / ``Contact.subsurface`` (value and depth); the worse body
  is reported.

Errors are (result - Hertz) / Hertz.  Hertz's own range is reported in every grade: b/R or
a/R (R the smallest radius in the plane), with the note of ``hertz``'s validity warning.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from ..results.contact import ResultError
from ..results.plane import PlaneResult, PlaneScene
from .contact import (
    FIT_THRESHOLD,
    PEAK_POINTS,
    PROFILE_EXTENT,
    Check,
    GradeMethods,
    hertz_quietly,
    nan_to_none,
    peak,
)

__all__ = ["DEFAULT_TOLERANCES", "METRICS", "PlaneGrade", "fit_semi_ellipse",
           "grade_plane", "moments_width"]

#: A node whose pressure lies more than this many (scaled) median absolute deviations off
#: the first fit is left out of the second (and at least 1% of p0 off).
OUTLIER_MADS = 5.0
#: Only nodes within this fraction of the fitted width are outliers: a spike inside the
#: contact (at the axis, a corner) is a code's artefact; a node near the edge above Hertz's
#: profile is the smeared edge, which the threshold already keeps out of the fit's way (the
#: 3-D grade keeps it too).
INNER = 0.5
#: Profile points.
PROFILE_POINTS = 121
#: The von Mises maximum on the axis is looked for deeper than this many half-widths (contact
#: radii): Hertz's lies at 0.70 b (line) and 0.48 a (point, nu = 0.3), and its surface value
#: on the axis is far lower (0.4 p0, 0.2 p0); a code's spike at the surface node on the axis
#: (CalculiX's CAX elements at r = 0: 1.4 times Hertz's maximum) is not the subsurface one.
SURFACE_SKIP = 0.2

#: The metrics, per model: (short header, meaning).  ``{w}`` is the width's name.
_COMMON = {
    "p0_rel_err": ("p0 (fit)", "peak pressure of the least-squares fit of p^2"),
    "peak_nodal_rel_err": ("peak node", "largest nodal pressure"),
    "rms_profile": ("RMS profile", f"RMS of (pressure - Hertz) to {PROFILE_EXTENT} {{w}}, "
                                   "over p0"),
    "pressure_integral_rel_err": ("p integral", "integral of the nodal pressure against the "
                                                "force"),
    "reaction_rel_err": ("reaction", "force over the other body's reaction, minus 1"),
    "approach_rel_err": ("approach", "approach against Hertz's delta at the force (where "
                                     "the result gives one)"),
    "von_mises_rel_err": ("VM max", "largest von Mises stress on the axis (worse body)"),
    "z_von_mises_rel_err": ("VM depth", "its depth (worse body)"),
}


def _metrics(model: str) -> dict:
    w, name = (("b", "half_width") if model == "plane-strain" else ("a", "a"))
    width = {f"{name}_rel_err": (w, f"{'half-width' if w == 'b' else 'contact radius'} of "
                                    "the p^2 fit"),
             f"{name}_moments_rel_err": (f"{w} (moments)", "from the second moment of the "
                                                           "pressure (information)"),
             f"{name}_edge_rel_err": (f"edge {w}", "between the last node in contact and "
                                                   "the next (information)")}
    return {**width, **{k: (h, m.replace("{w}", w)) for k, (h, m) in _COMMON.items()}}


#: Every metric of each model: (short header, meaning).
METRICS = {model: _metrics(model) for model in ("plane-strain", "axisymmetric")}

#: Default tolerances (|value| at most this), those of the 3-D grade for the same measures.
DEFAULT_TOLERANCES = {
    "plane-strain": {"half_width_rel_err": 0.01, "p0_rel_err": 0.02, "rms_profile": 0.04,
                     "pressure_integral_rel_err": 0.02, "von_mises_rel_err": 0.05,
                     "z_von_mises_rel_err": 0.10},
    "axisymmetric": {"a_rel_err": 0.01, "p0_rel_err": 0.02, "rms_profile": 0.04,
                     "pressure_integral_rel_err": 0.02, "approach_rel_err": 0.02,
                     "von_mises_rel_err": 0.05, "z_von_mises_rel_err": 0.10},
}


@dataclass(frozen=True)
class PlaneGrade(GradeMethods):
    """A 2-D result graded against Hertz at the force it reached.

    Attributes
    ----------
    scene, source : str
    model : {"plane-strain", "axisymmetric"}
    force : float
        [N/m] (plane strain, whole contact per unit length) or [N] (axisymmetric, full
        circle).
    metrics : dict
        Every metric of :data:`METRICS` [model] (NaN where not available).
    checks : tuple of Check
    passed : bool
    hertz, fem : dict
        Hertz's and the result's width (b or a) [m], p0 [Pa], and the fit's details.
    profile : dict
        ``{"x": (n,) [m], "fem": (n,) [Pa], "hertz": (n,) [Pa]}``.
    stress : dict
        Per body given: the von Mises maxima and depths (result and Hertz) and errors.
    axis_stress : dict
        Per body: ``{"depth", "von_mises"}`` arrays [m], [Pa] and Hertz's at those depths.
    details : dict
    hint : str
        Always "" (kept for the reports shared with the 3-D grade).
    notes : tuple of str
        Hertz's range (b/R or a/R) and its validity warning where the contact is large.
    """

    scene: str
    source: str
    model: str
    force: float
    metrics: dict
    checks: tuple
    passed: bool
    hertz: dict = field(default_factory=dict)
    fem: dict = field(default_factory=dict)
    profile: dict = field(default_factory=dict, repr=False)
    stress: dict = field(default_factory=dict)
    axis_stress: dict = field(default_factory=dict, repr=False)
    details: dict = field(default_factory=dict)
    hint: str = ""
    notes: tuple = ()

    @property
    def width_key(self) -> str:
        """``half_width_rel_err`` (plane strain) or ``a_rel_err`` (axisymmetric)."""
        return "half_width_rel_err" if self.model == "plane-strain" else "a_rel_err"

    def to_dict(self) -> dict:
        """grade.json: force, the metrics at the top level, passed, checks, details."""
        checks = []
        for c in self.checks:
            row = c.to_dict()
            row["meaning"] = METRICS[self.model].get(c.name, ("", ""))[1]
            checks.append(row)
        return nan_to_none({
            "scene": self.scene, "source": self.source, "model": self.model,
            "force": self.force, "force_unit": "N/m" if self.model == "plane-strain" else "N",
            **self.metrics, "passed": self.passed, "hint": self.hint, "checks": checks,
            "hertz": self.hertz, "fem": self.fem, "stress": self.stress,
            "details": self.details, "notes": list(self.notes)})


def fit_semi_ellipse(x, p, weights=None) -> dict:
    """Least-squares fit of p**2 = c0 - q x**2 on the nodes above FIT_THRESHOLD max(p),
    then again without the outliers of the first fit.

    Parameters
    ----------
    x : array_like, shape (n,)
        Positions [m] (|x| is used).
    p : array_like, shape (n,)
        Nodal pressures [Pa], >= 0.
    weights : array_like, shape (n,), optional
        The measure of each node (1: plane strain; the radius: axisymmetric).

    Returns
    -------
    dict
        p0 [Pa], width [m] (NaN where the fit is not a semi-ellipse), fit_nodes (the
        nodes of the second fit), dropped (the outliers left out).

    Examples
    --------
    >>> import numpy as np
    >>> x = np.linspace(0, 1.5e-3, 61)
    >>> p = 2e9 * np.sqrt(np.clip(1 - (x / 1e-3) ** 2, 0, None))
    >>> f = fit_semi_ellipse(x, p)
    >>> round(f["width"] * 1e3, 9), round(f["p0"] / 1e9, 9)
    (1.0, 2.0)
    """
    x = np.abs(np.asarray(x, dtype=float))
    p = np.asarray(p, dtype=float)
    w = np.ones_like(x) if weights is None else np.asarray(weights, dtype=float)
    sel = p > FIT_THRESHOLD * p.max()
    fit = _fit(x, p, w, sel)
    dropped = 0
    if math.isfinite(fit["width"]):
        model = fit["p0"] * np.sqrt(np.clip(1 - (x / fit["width"]) ** 2, 0, None))
        res = np.abs(p - model)
        mad = 1.4826 * float(np.median(res[sel]))
        out = sel & (res > max(OUTLIER_MADS * mad, 0.01 * fit["p0"])) & (
            x < INNER * fit["width"])
        if out.any() and (sel & ~out).sum() >= 3:
            dropped = int(out.sum())
            fit = _fit(x, p, w, sel & ~out)
    return {**fit, "dropped": dropped}


def _fit(x, p, w, sel) -> dict:
    if sel.sum() < 2:
        return {"p0": math.nan, "width": math.nan, "fit_nodes": int(sel.sum())}
    scale = float(x[sel].max()) or 1.0
    unit = float(p[sel].max())
    sw = np.sqrt(w[sel])
    design = np.column_stack([np.ones(sel.sum()), -(x[sel] / scale) ** 2]) * sw[:, None]
    (c0, q), *_ = np.linalg.lstsq(design, (p[sel] / unit) ** 2 * sw, rcond=None)
    ok = c0 > 0 and q > 0
    return {"p0": unit * math.sqrt(c0) if c0 > 0 else math.nan,
            "width": scale * math.sqrt(c0 / q) if ok else math.nan,
            "fit_nodes": int(sel.sum())}


def moments_width(model: str, x, p) -> float:
    """The half-width (plane strain) or contact radius (axisymmetric) [m] from the second
    moment of the nodal pressure (trapezoidal rule): b = 2 sqrt(<x**2>) over p dx,
    a = sqrt(5/2 <r**2>) over p r dr."""
    x = np.asarray(x, dtype=float)
    p = np.asarray(p, dtype=float)
    w = p * (np.abs(x) if model == "axisymmetric" else 1.0)
    m0 = np.trapezoid(w, x)
    m2 = np.trapezoid(w * x * x, x)
    if not m0 > 0:
        return math.nan
    return 2 * math.sqrt(m2 / m0) if model == "plane-strain" else math.sqrt(2.5 * m2 / m0)


def _edge(x, p, active) -> float:
    """Between the last node in contact and the next, on the side of x >= 0 (|x|)."""
    ax = np.abs(x)
    on = active if active is not None else p > 0
    if not on.any():
        return math.nan
    last = float(ax[on].max())
    beyond = ax[(ax > last) & ~on]
    return 0.5 * (last + float(beyond.min())) if beyond.size else math.nan


def _tolerances(model: str, tolerances: Mapping[str, float] | None) -> dict:
    tol = dict(DEFAULT_TOLERANCES[model] if tolerances is None else tolerances)
    for name, value in tol.items():
        if name not in METRICS[model]:
            raise ValueError(f"tolerances: unknown metric {name!r} for a {model} grade; "
                             f"known: {', '.join(sorted(METRICS[model]))}")
        if isinstance(value, bool) or not isinstance(value, int | float) or not (
                math.isfinite(value) and value > 0):
            raise ValueError(f"tolerances: {name} must be a finite number > 0, got {value!r}")
    return tol


def grade_plane(result: PlaneResult, scene: PlaneScene,
                tolerances: Mapping[str, float] | None = None) -> PlaneGrade:
    """Grade a plane-strain or axisymmetric result against Hertz at the force it reached.

    Parameters
    ----------
    result : PlaneResult
    scene : PlaneScene
        Of the same model.
    tolerances : mapping, optional
        ``{metric: largest |value|}``; default :data:`DEFAULT_TOLERANCES` [model].  A
        metric left out is reported for information.

    Returns
    -------
    PlaneGrade

    Raises
    ------
    ValueError
        A scene of the other model, an unknown tolerance, or a result that is not a model of
        the scene (its fitted width more than 1.5 times off Hertz's: wrong scene or units).

    Examples
    --------
    A synthetic plane-strain result, Hertz's own pressure at 200 nodes:

    >>> import numpy as np, hertz
    >>> from fem_validation.results.plane import PlaneResult, PlaneScene
    >>> scene = PlaneScene("roller", "plane-strain", hertz.Body.cylinder(5e-3, 210e9, 0.3),
    ...                    hertz.Body.plane(210e9, 0.3))
    >>> lc = scene.hertz(1e5)
    >>> x = np.linspace(0, 2 * lc.half_width, 200)
    >>> g = grade_plane(PlaneResult("plane-strain", x, lc.pressure(x), 1e5,
    ...                             half_model=True), scene)
    >>> g.passed, abs(g.half_width_rel_err) < 1e-3, abs(g.p0_rel_err) < 1e-3
    (True, True, True)
    """
    if not isinstance(result, PlaneResult):
        raise TypeError(f"result must be a PlaneResult, got {type(result).__name__}")
    if result.model != scene.model:
        raise ValueError(f"{result.source or 'the result'} is a {result.model} model and the "
                         f"scene {scene.name!r} a {scene.model} one")
    model = result.model
    tol = _tolerances(model, tolerances)
    plane_stress = bool(result.details.get("plane stress"))
    if plane_stress:  # thin discs: 1/E* = 1/E1 + 1/E2, out-of-plane stress 0: nu = 0
        import hertz

        scene = PlaneScene(scene.name, model,
                           *(hertz.Body(b.Rx, b.Ry, b.E, 0.0) for b in (scene.body1,
                                                                         scene.body2)),
                           scene.load)
    key = "half_width" if model == "plane-strain" else "a"
    c, notes = hertz_quietly(scene.hertz, result.force)
    width_h = float(c.half_width if model == "plane-strain" else c.a)
    p0_h = float(c.p0)
    x, p = result.x, result.pressure
    fit = fit_semi_ellipse(x, p, x if model == "axisymmetric" else None)
    if not (math.isfinite(fit["width"]) and 1 / 1.5 < fit["width"] / width_h < 1.5):
        raise ResultError(f"{result.source or 'the result'}: its contact ({key} "
                          f"{fit['width']:.4g} m by the p^2 fit) is not Hertz's for the scene "
                          f"{scene.name!r} at the force {result.force:.6g} "
                          f"{result.force_unit} ({width_h:.4g} m): a different scene, force "
                          f"or units?")
    moments = moments_width(model, x, p)
    edge = _edge(x, p, result.active)
    # the profile: Hertz's line, one-sided where the model is
    lo = 0.0 if result.symmetric else -PROFILE_EXTENT * width_h
    s = np.linspace(lo, PROFILE_EXTENT * width_h, PROFILE_POINTS)
    inside = (s >= x.min()) & (s <= x.max())
    fem = np.where(inside, np.interp(s, x, p), np.nan)
    hz = np.asarray(c.pressure(s) if model == "plane-strain" else c.pressure(s, 0.0),
                    dtype=float)
    if not inside.any():
        rms = math.nan
    else:  # over the area: weights |x| in an axisymmetric model (the ring of each point)
        weight = np.abs(s[inside]) if model == "axisymmetric" else np.ones(inside.sum())
        rms = float(np.sqrt(np.sum(weight * (fem[inside] - hz[inside]) ** 2) / weight.sum())
                    / p0_h)
    metrics = {
        f"{key}_rel_err": fit["width"] / width_h - 1,
        f"{key}_moments_rel_err": moments / width_h - 1,
        f"{key}_edge_rel_err": edge / width_h - 1,
        "p0_rel_err": fit["p0"] / p0_h - 1,
        "peak_nodal_rel_err": float(p.max()) / p0_h - 1,
        "rms_profile": rms,
        "pressure_integral_rel_err": result.pressure_integral() / result.force - 1,
        "reaction_rel_err": result.force / result.reaction - 1,
        "approach_rel_err": math.nan,
        "von_mises_rel_err": math.nan, "z_von_mises_rel_err": math.nan,
    }
    if model == "axisymmetric" and math.isfinite(result.approach):
        metrics["approach_rel_err"] = result.approach / float(c.delta) - 1
    stress, axis = {}, {}
    for body, line in sorted(result.axis.items()):
        deep = line.depth >= SURFACE_SKIP * width_h
        if deep.sum() < PEAK_POINTS:
            continue
        top = peak(line.depth[deep], line.von_mises[deep])
        ref = c.subsurface(body)
        vm_h, z_h = float(ref.von_mises), float(ref.z_von_mises)
        stress[f"body{body}"] = {"von_mises": top["value"], "z_von_mises": top["depth"],
                                 "hertz_von_mises": vm_h, "hertz_z_von_mises": z_h,
                                 "von_mises_rel_err": top["value"] / vm_h - 1,
                                 "z_von_mises_rel_err": top["depth"] / z_h - 1,
                                 "fitted": top["fitted"]}
        axis[f"body{body}"] = {"depth": line.depth, "von_mises": line.von_mises,
                               "hertz": _hertz_axis_vm(c, body, line.depth, model)}
    if stress:
        worst = max(stress.values(), key=lambda r: abs(r["von_mises_rel_err"]))
        metrics["von_mises_rel_err"] = worst["von_mises_rel_err"]
        metrics["z_von_mises_rel_err"] = max(
            (r["z_von_mises_rel_err"] for r in stress.values()), key=abs)
    checks = []
    by_construction = ("pressure_integral_rel_err",) if "force_from" in result.details else ()
    for name in METRICS[model]:
        value = float(metrics[name])
        if name in by_construction:
            status, limit = "by construction", None
        elif name not in tol:
            status, limit = "information", None
        elif math.isnan(value):
            status, limit = "not available", tol[name]
        else:
            limit = tol[name]
            status = "pass" if abs(value) <= limit else "fail"
        checks.append(Check(name, value, limit, status))
    passed = all(ch.status != "fail" for ch in checks)
    ratio = width_h / scene.smallest_radius
    if plane_stress:
        notes.insert(0, "plane stress (CPS elements): graded as plane strain with nu = 0 "
                        "(1/E* = 1/E1 + 1/E2, no out-of-plane stress)")
    quadratic = {8, 10} & set(result.details.get("elements") or ())
    if quadratic and -0.6 < metrics["pressure_integral_rel_err"] < -0.4:
        notes.insert(0, "the nodal pressure integrates to about half the force: CalculiX "
                        "2.20's CPRESS on quadratic 2-D elements (tr6, qu8) in node-to-surface "
                        "contact is halved and alternates between corner and mid-side nodes "
                        "(measured on a CPE8 run; its contact forces are right); grade a run "
                        "of linear elements (CPE4, CAX4)")
    notes = [f"Hertz's range: {'b' if key == 'half_width' else 'a'}/R = {ratio:.3g} (R the "
             f"smallest radius in the plane, {scene.smallest_radius:.6g} m)", *notes]
    return PlaneGrade(
        scene=scene.name, source=result.source, model=model, force=result.force,
        metrics=metrics, checks=tuple(checks), passed=passed,
        hertz={key: width_h, "p0": p0_h, "e_star": float(c.e_star)},
        fem={key: fit["width"], "p0": fit["p0"], f"{key}_moments": moments,
             f"{key}_edge": edge, "peak_nodal": float(p.max()),
             "fit_nodes": fit["fit_nodes"], "fit_dropped": fit["dropped"],
             "pressure_integral": result.pressure_integral(), "reaction": result.reaction,
             "approach": result.approach},
        profile={"x": s, "fem": fem, "hertz": hz}, stress=stress, axis_stress=axis,
        details=dict(result.details), notes=tuple(notes))


def _hertz_axis_vm(c, body: int, depth: np.ndarray, model: str) -> np.ndarray:
    """Hertz's von Mises stress on the axis at ``depth`` [Pa]."""
    z = np.maximum(depth, 1e-12 * float(depth.max() or 1.0))
    s = np.asarray(c.stress(0.0, z, body=body) if model == "plane-strain"
                   else c.stress(0.0, 0.0, z, body=body), dtype=float)
    sxx, syy, szz = s[..., 0, 0], s[..., 1, 1], s[..., 2, 2]
    sxy, syz, szx = s[..., 0, 1], s[..., 1, 2], s[..., 2, 0]
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2)
                   + 3 * (sxy ** 2 + syz ** 2 + szx ** 2))
