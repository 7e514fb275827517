"""The tangential grading path: a :class:`~fem_validation.results.tangential.TangentialResult`
against Cattaneo-Mindlin and Mindlin-Deresiewicz.

Every source of a frictional result (our solver, readers of other codes' files)
fills a TangentialResult; :func:`grade_tangential` turns it into a
:class:`TangentialGrade`: metrics against ``hertz`` at the normal force the
result held, one :class:`~fem_validation.grading.contact.Check` per metric, pass/fail.
It never imports a solver.

Method (stated in every report).  Hertz's contact ``c`` at the result's P; the
ellipse frame (X along the major axis a) is the contact frame turned by
``c.major_axis_angle``, and the load's angle there is ``direction -
c.major_axis_angle``.  q is the shear component along the load, mu p0 the
scale of the tractions.

* **Stick zone** (at the snapshot, on the monotonic ramp): Cattaneo-Mindlin's
  mu p - q = mu p0 s sqrt(1 - X^2/c^2 - Y^2/d^2) in the stick ellipse (c, d) =
  s (a, b), s = (1 - Q/(mu P))^(1/3), and 0 in the slip annulus, so a least-
  squares fit of (mu p - q)^2 = A0 + A1 X^2 + A2 Y^2 (+ A12 X Y for a whole
  model) on the nodes with p > 0 and mu p - q > FIT_THRESHOLD max(mu p - q)
  gives the stick semi-axes sqrt(-A0/A1), sqrt(-A0/A2), exactly on exact data.
  Reference: ``c.tangential(Q, mu, direction).stick_a, stick_b`` at the
  result's own Q at the snapshot (matched force).
* **Force against displacement** on the ramp (path points 1 to the first
  reversal): the reference Q_ref(delta) is the inverse of Mindlin's virgin curve
  ``hertz.tangential_history(c, [Q])`` (= ``Tangential.displacement``) at the
  result's displacement, by bisection (:func:`masing_force`); the largest
  |Q - Q_ref| / Q_ref.
* **Unloading and reloading branches**: the reference follows the result's
  displacement path by Masing's rule with memory, ``hertz.tangential_history``
  with the reference's own reversal forces (Q_ref at the first reversal, then
  at the second) inverted at each displacement; for a symmetric loop these are
  ``c.fretting(Q*).unloading`` and ``reloading`` (tested).  The largest
  |Q - Q_ref| / Q*, Q* the mean |Q| of the result at the two reversals.  A
  reloading that passes the first reversal's displacement continues on the
  virgin curve (memory), and is graded so.
* **Loop energy**: the trapezoid rule over the closed loop, first reversal ->
  second reversal -> back to the first reversal's displacement (the last
  segment cut there by linear interpolation), against
  ``c.fretting(Q*).energy``.  The trapezoid rule itself errs on exact Masing
  data by about -1.0 / m^2 relative, m equal displacement steps per branch
  (measured at Q* = 0.5, 0.8, 0.95 mu P: -1.00, -1.01, -1.04 / m^2; m = 8:
  -1.6%, m = 16: -0.40%, m = 32: -0.10%), so from 10 steps per branch it
  stays well inside the 3% tolerance.
* **Traction profiles**: q interpolated linearly on the surface triangles along
  Hertz's major and minor axes to PROFILE_EXTENT semi-axes (as
  :func:`fem_validation.grading.contact.pressure_profiles`) against
  ``Tangential.traction``; the RMS of the difference over mu p0.
* **Information, not checks**: the largest transverse shear |q_perp| / (mu p0)
  (Mindlin's solution has none; a Coulomb contact shows some, its slip being
  misaligned by up to ~9 degrees in the annulus), the area fraction the code
  flags as stuck against s^2, and the integrals of p and q over the surface
  against P and Q.  That slipping nodes carry |q| = mu p is NOT reported: any
  Coulomb solver holds it by construction.

Errors are (result - reference) / reference unless said otherwise.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import SimpleNamespace

import numpy as np

from ..fe.surface import lumped_area, surface_triangles
from ..results.contact import ResultError
from ..results.tangential import TangentialResult
from .contact import (
    FIT_THRESHOLD,
    MISMATCH,
    PROFILE_EXTENT,
    GradeMethods,
    _checks,
    _mirror_axes,
    _tolerances,
    _worst,
    check_symmetry_sides,
    fit_ellipse,
    hertz_quietly,
    nan_to_none,
    pressure_profiles,
    unit_hint,
)

#: Halvings of [-mu P, mu P] in :func:`masing_force` (the last ones change nothing).
BISECTION_STEPS = 64
#: A path force beyond (1 + FORCE_SLACK) mu P is not a model of this contact (units,
#: symmetry or mu contradict each other): bad input.
FORCE_SLACK = 0.05
#: A path whose largest |force| stays below MIN_FORCE_FRACTION mu P holds no measurable
#: partial slip (the loop's area is about Q / (mu P) of Q delta, lost in the rounding of the
#: columns it is computed from; far below, Mindlin's loop energy underflows to 0): the force
#: unit, mu or the normal force is wrong, bad input.
MIN_FORCE_FRACTION = 1e-6

#: Default tolerances of :func:`grade_tangential` (|value| at most this): issue 17's
#: targets for the stick zone (2%), the force against displacement (1%) and the loop
#: energy (3%); 3% of mu p0 for the traction profiles until FEM runs retune it.
DEFAULT_TOLERANCES = {
    "stick_a_rel_err": 0.02, "stick_b_rel_err": 0.02,
    "force_rel_err_max": 0.01, "branch_err_max": 0.01,
    "loop_energy_rel_err": 0.03,
    "traction_rms_major": 0.03, "traction_rms_minor": 0.03,
}

#: Every metric: (short header, meaning).  Relative errors are fractions; RMS and
#: shear values are fractions of mu p0.
METRICS = {
    "stick_a_rel_err": ("stick a", "stick-zone semi-axis along the major axis (fit of "
                                   "(mu p - q)^2) against Cattaneo-Mindlin at the snapshot's Q"),
    "stick_b_rel_err": ("stick b", "stick-zone semi-axis along the minor axis, likewise"),
    "force_rel_err_max": ("force (ramp)", "largest |Q - Q_ref(delta)| / Q_ref(delta) on the "
                                          "monotonic ramp, Mindlin's virgin curve"),
    "branch_err_max": ("force (branches)", "largest |Q - Q_ref(delta)| / Q* on the unloading "
                                           "and reloading branches (Masing's rule)"),
    "loop_energy_rel_err": ("loop energy", "trapezoid area of the closed loop against "
                                           "Mindlin-Deresiewicz's energy at Q*"),
    "traction_rms_major": ("traction RMS major", "RMS of (q - q_CM) along the major axis to "
                                                 f"{PROFILE_EXTENT} a, over mu p0"),
    "traction_rms_minor": ("traction RMS minor", "as traction RMS major, along the minor axis "
                                                 f"to {PROFILE_EXTENT} b"),
    "transverse_shear_max": ("transverse shear", "largest |shear across the load| / (mu p0) "
                                                 "(information: Mindlin's is 0)"),
    "stick_area_rel_err": ("stick area (flags)", "area the code flags as stuck over the "
                                                 "pressed area, against s^2 (information)"),
    "pressure_integral_rel_err": ("p integral", "integral of p over the surface against P "
                                                "(information)"),
    "shear_integral_rel_err": ("q integral", "integral of q over the surface against the "
                                             "snapshot's Q (information)"),
}


@dataclass(frozen=True)
class TangentialGrade(GradeMethods):
    """A frictional result graded against Cattaneo-Mindlin and Mindlin-Deresiewicz.

    Attributes
    ----------
    scene, source : what was graded
    normal_force : float
        P of the whole contact [N] (Hertz is evaluated there).
    mu : float
    direction : float
        The load's angle from the frame's x axis [rad].
    symmetry : str
    metrics : dict
        Every metric of :data:`METRICS` (NaN where not available).
    checks : tuple of Check
    passed : bool
        Every checked metric within its tolerance.
    reference : dict
        Hertz's a, b, p0 [m, Pa], the stick semi-axes [m], Q*, the energy [J], ...
    fem : dict
        The result's fitted stick semi-axes, Q at the snapshot and reversals, its
        loop energy, ...
    profiles : dict
        ``{"major"|"minor": {"s", "fem", "hertz", "rms"}}``: q of the result and of
        Cattaneo-Mindlin along the axes ([m], [Pa]; "hertz" holds the reference).
    path : dict
        ``displacement``, ``force``, ``reference_force`` (NaN where not graded),
        ``branch`` (per point: "start", "ramp", "unloading", "reloading", "beyond")
        and the dense ``reference_curve`` (displacement, force).
    notes : tuple of str
        What could not be graded and why.
    details : dict
        The result's details.
    hint : str
        Where the result looks off by a power of 1000 (a unit mistake): what is off, by
        how much, and the likely cause (:func:`fem_validation.grading.contact.unit_hint`); ""
        otherwise.
    """

    scene: str
    source: str
    normal_force: float
    mu: float
    direction: float
    symmetry: str
    metrics: dict
    checks: tuple
    passed: bool
    reference: dict = field(default_factory=dict)
    fem: dict = field(default_factory=dict)
    profiles: dict = field(default_factory=dict, repr=False)
    path: dict = field(default_factory=dict, repr=False)
    notes: tuple = ()
    details: dict = field(default_factory=dict)
    hint: str = ""

    def to_dict(self) -> dict:
        """grade.json: the metrics at the top level, passed, the unit hint, checks,
        reference, fem, path."""
        checks = [{**c.to_dict(), "meaning": METRICS[c.name][1]} for c in self.checks]
        return nan_to_none({
            "kind": "tangential", "scene": self.scene, "source": self.source,
            "normal_force": self.normal_force, "mu": self.mu, "direction": self.direction,
            "symmetry": self.symmetry, **self.metrics, "passed": self.passed,
            "hint": self.hint, "checks": checks, "reference": self.reference, "fem": self.fem,
            "path": {k: v for k, v in self.path.items() if k != "reference_curve"},
            "notes": list(self.notes), "details": self.details})


# --- the reference ----------------------------------------------------------------------

def masing_force(c, mu: float, direction: float, displacement, reversal_forces=()) -> np.ndarray:
    """The tangential force [N] at a displacement on a Mindlin-Deresiewicz branch.

    The Q with ``hertz.tangential_history(c, [*reversal_forces, Q], mu,
    direction)[-1] == displacement``: after the force reversals given (none:
    the virgin curve), Masing's rule with memory, inverted by bisection over
    [-mu P, mu P] (the displacement rises with Q there).  A displacement
    beyond the onset of sliding gives +-mu P.

    Parameters
    ----------
    c : hertz.Contact
    mu : float
        Coefficient of friction [-].
    direction : float
        The load's angle from the major axis [rad].
    displacement : array_like, shape (m,)
        Displacements along the load [m].
    reversal_forces : sequence of float
        The forces [N] at the reversals before this branch, in order.

    Returns
    -------
    ndarray, shape (m,)

    Examples
    --------
    >>> import hertz
    >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
    >>> c = hertz.contact(ball, hertz.Body.plane(E=210e9, nu=0.3), load=100.0)
    >>> d = c.tangential(20.0, mu=0.3).displacement
    >>> print(f"{masing_force(c, 0.3, 0.0, [d])[0]:.12f}")
    20.000000000000
    """
    import hertz

    delta = np.atleast_1d(np.asarray(displacement, dtype=float))
    limit = mu * c.load
    lo, hi = np.full(delta.shape, -limit), np.full(delta.shape, limit)
    prefix = np.repeat(np.asarray(reversal_forces, dtype=float).reshape(-1, 1), delta.size,
                       axis=1)
    for _ in range(BISECTION_STEPS):
        mid = 0.5 * (lo + hi)
        d = hertz.tangential_history(c, np.vstack([prefix, mid[None]]), mu, direction)[-1]
        above = d > delta
        hi, lo = np.where(above, mid, hi), np.where(above, lo, mid)
    return 0.5 * (lo + hi)


def stick_ellipse(ellipse_xy: np.ndarray, pressure: np.ndarray, shear: np.ndarray, mu: float,
                  cross_term: bool) -> dict:
    """Stick-zone semi-axes from a fit of (mu p - q)^2 = A0 + A1 X^2 + A2 Y^2 (+ A12 X Y).

    Parameters
    ----------
    ellipse_xy : ndarray, shape (n, 2)
        Node positions (X, Y) in the ellipse frame [m].
    pressure, shear : ndarray, shape (n,)
        p and the shear along the load q [Pa].
    mu : float
    cross_term : bool
        Fit A12 (a whole model; a symmetric one has none by symmetry).

    Returns
    -------
    dict
        ``stick_a`` (the semi-axis nearer X), ``stick_b`` [m], ``angle_deg`` of the
        stick_a axis from X, ``fit_nodes``; NaN semi-axes where the fit is not an
        ellipse.
    """
    g = mu * pressure - shear
    sel = (pressure > 0) & (g > FIT_THRESHOLD * g.max())
    # in units of the largest |coordinate| and of g.max(), as fit_ellipse
    scale = float(np.abs(ellipse_xy[sel]).max()) if sel.any() else 1.0
    x, y = ellipse_xy[sel, 0] / scale, ellipse_xy[sel, 1] / scale
    cols = [np.ones(sel.sum()), -x * x, -y * y] + ([-x * y] if cross_term else [])
    nan = {"stick_a": math.nan, "stick_b": math.nan, "angle_deg": math.nan,
           "fit_nodes": int(sel.sum())}
    if sel.sum() < len(cols):
        return nan
    coef, *_ = np.linalg.lstsq(np.column_stack(cols), (g[sel] / g.max()) ** 2, rcond=None)
    a0, qxx, qyy = coef[:3]
    qxy = coef[3] if cross_term else 0.0
    w, v = np.linalg.eigh(np.array([[qxx, qxy / 2], [qxy / 2, qyy]]))
    if not (a0 > 0 and w[0] > 0):
        return nan
    semi = scale * np.sqrt(a0 / w)
    k = int(np.argmax(np.abs(v[0])))  # the eigenvector nearer X
    angle = math.degrees(math.atan2(v[1, k], v[0, k]))
    angle = (angle + 90) % 180 - 90
    return {"stick_a": float(semi[k]), "stick_b": float(semi[1 - k]), "angle_deg": angle,
            "fit_nodes": int(sel.sum())}


def _face_triangles(result: TangentialResult, xy: np.ndarray) -> np.ndarray:
    """The surface's triangles (given, else Delaunay), without faces seen edge-on."""
    tri = result.triangles if result.triangles is not None else surface_triangles(xy)
    d1, d2 = xy[tri[:, 1]] - xy[tri[:, 0]], xy[tri[:, 2]] - xy[tri[:, 0]]
    projected = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    if len(tri) and (projected <= 1e-12 * projected.max()).any():
        tri = tri[projected > 1e-12 * projected.max()]
    return tri


def _unit_ratios(result: TangentialResult, c, fit: dict, area, along: float) -> list:
    """A frictional result's ratios to the reference for
    :func:`fem_validation.grading.contact.unit_hint`: the semi-axes and p0 of the fit of p^2, the
    pressure integral over P, and the displacement at the end of the ramp against
    Mindlin's at the force there (where it lies below 0.95 mu P)."""
    out = [("semi_axes", fit["a"] / c.a), ("semi_axes", fit["b"] / c.b),
           ("peak_pressure", fit["p0"] / c.p0),
           ("pressure_integral",
            result.multiplicity * float(result.pressure @ area) / result.normal_force)]
    rev = result.reversals
    i1 = rev[0] if rev else len(result.force) - 1
    q1 = float(result.force[i1])
    if 0 < q1 < 0.95 * result.mu * c.load:
        ref = float(c.tangential(q1, result.mu, along).displacement)
        out.append(("tangential_displacement", float(result.displacement[i1]) / ref))
    return out


def _sanity(result: TangentialResult, c, xy, area, where: str, fit: dict,
            hint: str = "") -> None:
    """Refuse results that cannot be graded against this scene (bad input, not a fail);
    the messages end with the unit hint, where there is one."""
    hint = f"; {hint}" if hint else ""
    mult = result.multiplicity
    check_symmetry_sides(result.symmetry, xy, where)
    integral = mult * float(result.pressure @ area)
    ratio = integral / result.normal_force
    if not 1 / 1.8 < ratio < 1.8:
        raise ResultError(f"{where}the pressure integral ({integral:.6g} N with symmetry "
                          f"{result.symmetry!r}) and the normal force "
                          f"({result.normal_force:.6g} N) disagree by a factor {ratio:.3g}: "
                          f"units, symmetry or the normal force contradict each other{hint}")
    for name, value, hz in (("semi-major axis", fit["a"], c.a), ("semi-minor axis", fit["b"],
                                                                 c.b)):
        if math.isfinite(value) and not 1 / MISMATCH < value / hz < MISMATCH:
            raise ResultError(f"{where}the scene does not match the result: the contact's "
                              f"{name} from a fit of p^2 is {value:.4g} m, Hertz's at "
                              f"{result.normal_force:.6g} N is {hz:.4g} m (a factor "
                              f"{value / hz:.3g}); check the scene, the units and the frame"
                              f"{hint}")
    limit = result.mu * result.normal_force
    worst = int(np.argmax(np.abs(result.force)))
    path = result.details.get("history") or result.source or "the path"
    if not 0 < limit < math.inf:
        raise ResultError(f"{where}mu = {result.mu:.6g} times the normal force "
                          f"{result.normal_force:.6g} N is out of range (mu P "
                          f"{'overflows' if limit else 'underflows to 0'}): check mu and the "
                          f"normal force{hint}")
    largest = abs(float(result.force[worst]))
    if not largest >= MIN_FORCE_FRACTION * limit:
        raise ResultError(f"{path}: the tangential force never exceeds {largest:.6g} N, "
                          f"{largest / limit:.3g} of mu P = {limit:.6g} N (mu = "
                          f"{result.mu:.6g}, P = {result.normal_force:.6g} N; below "
                          f"{MIN_FORCE_FRACTION:g}): too small "
                          f"to grade against Mindlin; check the force column and its unit, "
                          f"mu and the normal force{hint}")
    if abs(result.force[worst]) > (1 + FORCE_SLACK) * limit:
        raise ResultError(f"{where}the tangential force {result.force[worst]:.6g} N at path "
                          f"index {worst} exceeds mu P = {limit:.6g} N by more than "
                          f"{FORCE_SLACK:.0%}: units, symmetry (a quarter model's force x4), "
                          f"mu or the normal force contradict each other{hint}")


def _closing_loop(d, q, i1, i2, end):
    """The closed loop's points (first reversal -> second -> back to d[i1]) or None."""
    d1 = d[i1]
    reload = np.arange(i2 + 1, end + 1)
    past = reload[d[reload] >= d1]
    if not past.size:
        return None
    j = int(past[0])
    t = (d1 - d[j - 1]) / (d[j] - d[j - 1])
    loop_d = np.concatenate([d[i1:j], [d1]])
    loop_q = np.concatenate([q[i1:j], [q[j - 1] + t * (q[j] - q[j - 1])]])
    return loop_d, loop_q


def loop_energy(displacement, force) -> float:
    """Area [J] of a loop in the (displacement, force) plane, the trapezoid rule of the
    integral of force d(displacement) around it: positive for a dissipative loop, which
    unloads below the force it reloads along (counter-clockwise); the closing segment at
    equal displacement adds nothing."""
    d, q = np.asarray(displacement, dtype=float), np.asarray(force, dtype=float)
    return float(np.sum(0.5 * (q[1:] + q[:-1]) * np.diff(d)))


# --- the grader -------------------------------------------------------------------------

def grade_tangential(result: TangentialResult, scene,
                     tolerances: Mapping[str, float] | None = None, *,
                     hertz_at: Callable | None = None) -> TangentialGrade:
    """Grade a frictional contact result against Cattaneo-Mindlin and Mindlin-Deresiewicz.

    Parameters
    ----------
    result : TangentialResult
        Any source's result (see :mod:`fem_validation.results.tangential`).
    scene : object with ``name`` and ``hertz(load) -> hertz.Contact``
        The two bodies (:class:`fem_validation.scenes.Scene`); body 1 lies on the
        side the frame's normal points to.
    tolerances : dict, optional
        Metric name -> largest allowed |value| (default :data:`DEFAULT_TOLERANCES`;
        metrics not named are reported as information).
    hertz_at : callable, optional
        P [N] -> the Hertz contact to compare with; default ``scene.hertz``.

    Returns
    -------
    TangentialGrade

    Raises
    ------
    ResultError
        If the result contradicts itself or the scene (units, symmetry, a force
        beyond mu P, a scene that does not match): bad input, not a failed grade.
    ValueError
        If a tolerance is not allowed.

    Examples
    --------
    See docs/howto/grade-friction.md (a result built from Cattaneo-Mindlin itself,
    graded, then one with mu 2% off).
    """
    tol = _tolerances(tolerances, DEFAULT_TOLERANCES, METRICS)
    where = f"{result.source}: " if result.source else ""
    c, validity = hertz_quietly(scene.hertz if hertz_at is None else hertz_at,
                                result.normal_force)
    mu, P = result.mu, float(c.load)
    limit = mu * P
    theta = float(c.major_axis_angle)
    along = result.direction - theta  # the load's angle in the ellipse frame
    xy = result.xy
    ct, st = math.cos(theta), math.sin(theta)
    ellipse_xy = np.column_stack([xy[:, 0] * ct + xy[:, 1] * st, -xy[:, 0] * st + xy[:, 1] * ct])
    tri = _face_triangles(result, xy)
    area = lumped_area(xy, tri)
    pressure_fit = fit_ellipse(xy, result.pressure)
    hint = unit_hint(_unit_ratios(result, c, pressure_fit, area, along))
    _sanity(result, c, xy, area, where, pressure_fit, hint)
    p, q, q_perp = result.pressure, result.shear_along, result.shear_across
    scale = mu * c.p0
    notes = list(validity)

    # --- the path: ramp, unloading, reloading -------------------------------------------
    d, path_q = result.displacement, result.force
    k = len(d)
    rev = result.reversals
    i1 = rev[0] if rev else k - 1
    i2 = rev[1] if len(rev) > 1 else (k - 1 if rev else None)
    end = rev[2] if len(rev) > 2 else k - 1
    branch = np.array(["start"] + ["ramp"] * i1 + ["beyond"] * (k - 1 - i1), dtype=object)
    q_ref = np.full(k, np.nan)
    ramp = np.arange(1, i1 + 1)
    ramp = ramp[d[ramp] > 0]
    q_ref[ramp] = masing_force(c, mu, along, d[ramp])
    ramp_err = (path_q[ramp] - q_ref[ramp]) / q_ref[ramp]
    force_err = float(_worst(list(ramp_err))) if ramp.size else math.nan
    curve_d, curve_q = [np.linspace(0.0, d[i1], 60)], []
    curve_q.append(masing_force(c, mu, along, curve_d[0]))
    q1 = float(masing_force(c, mu, along, [d[i1]])[0])
    branch_err, energy_err, q_star, w_fem, w_ref = math.nan, math.nan, math.nan, math.nan, math.nan
    if not rev:
        notes.append("the path never turns back: no unloading or reloading branch, no loop "
                     "energy")
    else:
        unload = np.arange(i1 + 1, i2 + 1)
        branch[unload] = "unloading"
        q_ref[unload] = masing_force(c, mu, along, d[unload], [q1])
        q2 = float(masing_force(c, mu, along, [d[i2]], [q1])[0])
        curve_d.append(np.linspace(d[i1], d[i2], 60))
        curve_q.append(masing_force(c, mu, along, curve_d[-1], [q1]))
        graded = list(unload)
        if len(rev) > 1:
            reload = np.arange(i2 + 1, end + 1)
            branch[reload] = "reloading"
            q_ref[reload] = masing_force(c, mu, along, d[reload], [q1, q2])
            curve_d.append(np.linspace(d[i2], d[end], 60))
            curve_q.append(masing_force(c, mu, along, curve_d[-1], [q1, q2]))
            graded += list(reload)
            q_star = 0.5 * float(abs(path_q[i1]) + abs(path_q[i2]))
            if end < k - 1:
                notes.append(f"the path turns back a third time (index {end}): the "
                             f"{k - 1 - end} points after it are not graded")
        else:
            q_star = float(abs(path_q[i1]))
            notes.append("the path has one reversal: the unloading branch is graded, there "
                         "is no reloading branch and no closed loop (no loop energy)")
        branch_err = (float(np.abs(path_q[graded] - q_ref[graded]).max() / q_star)
                      if graded and q_star > 0 else math.nan)
        if len(rev) > 1:
            loop = _closing_loop(d, path_q, i1, i2, end)
            if loop is None:
                notes.append(f"the reloading branch stops at displacement {d[end]:.6g} m, "
                             f"before the first reversal's {d[i1]:.6g} m: the loop is not "
                             f"closed, no loop energy")
            else:
                w_fem = loop_energy(*loop)
                w_ref = float(c.fretting(min(q_star, limit), mu, along).energy)
                if w_ref > 0:
                    energy_err = w_fem / w_ref - 1
                else:
                    notes.append(f"Mindlin-Deresiewicz's loop energy at Q* = {q_star:.6g} N "
                                 f"underflows to 0 J: no loop energy")
                asym = abs(d[i2]) / d[i1] - 1
                if abs(asym) > 0.01:
                    notes.append(f"the loop is not symmetric (second reversal at "
                                 f"{d[i2]:.6g} m, first at {d[i1]:.6g} m): its energy is "
                                 f"compared with the symmetric loop at the mean amplitude Q*")

    # --- the snapshot: stick zone, traction profiles ------------------------------------
    snap = result.snapshot
    q_snap = float(path_q[snap])
    nan_t = {"stick_a": math.nan, "stick_b": math.nan, "angle_deg": math.nan, "fit_nodes": 0}
    fit, t, prof = nan_t, None, {}
    mirrored = _mirror_axes(result.symmetry, xy)
    if snap > i1:
        notes.append(f"the snapshot (index {snap}) lies after the first reversal: the "
                     f"stick zone and the traction profiles are graded on the monotonic ramp "
                     f"only (Cattaneo-Mindlin); not graded")
    elif not 0 < q_snap < limit:
        notes.append(f"the snapshot's tangential force {q_snap:.6g} N is not between 0 and "
                     f"mu P = {limit:.6g} N (partial slip): no stick zone to grade")
    else:
        t = c.tangential(q_snap, mu, along)
        fit = stick_ellipse(ellipse_xy, p, q, mu, cross_term=result.symmetry == "whole")
        if not math.isfinite(fit["stick_a"]):
            notes.append(f"the fit of (mu p - q)^2 on the {fit['fit_nodes']} nodes above "
                         f"{FIT_THRESHOLD:g} of its largest value is not an ellipse: no stick "
                         f"semi-axes")
        ref = SimpleNamespace(a=c.a, b=c.b, p0=scale, major_axis_angle=theta,
                              pressure=t.traction)
        prof = pressure_profiles(ref, xy, tri, q, mirrored)
    s2 = (t.stick_a / c.a) ** 2 if t is not None else math.nan
    pressed = p > 0
    stick_area, flagged = math.nan, math.nan
    if result.stick is not None:
        flagged = float(area[pressed & result.stick].sum() / area[pressed].sum())
        if t is not None:
            stick_area = flagged / s2 - 1
    shear_integral = result.multiplicity * float(q @ area)
    metrics = {
        "stick_a_rel_err": fit["stick_a"] / t.stick_a - 1 if t is not None else math.nan,
        "stick_b_rel_err": fit["stick_b"] / t.stick_b - 1 if t is not None else math.nan,
        "force_rel_err_max": force_err, "branch_err_max": branch_err,
        "loop_energy_rel_err": energy_err,
        "traction_rms_major": prof["major"]["rms"] if prof else math.nan,
        "traction_rms_minor": prof["minor"]["rms"] if prof else math.nan,
        "transverse_shear_max": float(np.abs(q_perp).max()) / scale,
        "stick_area_rel_err": stick_area,
        "pressure_integral_rel_err": result.multiplicity * float(p @ area) / P - 1,
        "shear_integral_rel_err": (shear_integral / q_snap - 1 if q_snap > 0 else math.nan),
    }
    checks = _checks(metrics, tol, METRICS)
    passed = all(ch.status != "fail" for ch in checks)
    curve_d = np.concatenate(curve_d)
    curve_q = np.concatenate(curve_q)
    return TangentialGrade(
        scene=getattr(scene, "name", ""), source=result.source, normal_force=P, mu=mu,
        direction=result.direction, symmetry=result.symmetry, metrics=metrics,
        checks=tuple(checks), passed=passed,
        reference={"a": c.a, "b": c.b, "p0": c.p0, "alpha": float(c.alpha),
                   "major_axis_angle_deg": math.degrees(theta),
                   "direction_in_ellipse_frame_deg": math.degrees(along),
                   "stick_a": t.stick_a if t is not None else math.nan,
                   "stick_b": t.stick_b if t is not None else math.nan,
                   "stick_area_fraction": s2,
                   "no_slip_stiffness": float(c.tangential_stiffness(along)),
                   "force_at_first_reversal": q1, "loop_energy": w_ref, "mu_P": limit},
        fem={"stick_fit": fit, "snapshot": snap, "snapshot_force": q_snap,
             "snapshot_force_ratio": q_snap / limit, "reversals": list(rev),
             "amplitude": q_star, "loop_energy": w_fem, "shear_integral": shear_integral,
             "stick_area_fraction": flagged},
        profiles=prof,
        path={"displacement": d, "force": path_q, "reference_force": q_ref,
              "branch": [str(b) for b in branch], "reference_curve": (curve_d, curve_q)},
        notes=tuple(notes), details=dict(result.details), hint=hint)


# --- the report: grade.json, grade.md, grade.png ----------------------------------------


