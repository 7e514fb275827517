"""History-only tangential grading: a DEM code's force-displacement history of one contact
(:class:`~fem_validation.results.tangential_history.TangentialHistory`) against
Mindlin-Deresiewicz, and against the simplified law the code claims.

No contact surface is needed: everything is measured on the path.  Method (stated in
every report); Hertz's contact ``c`` at the history's normal force P, the tangential line
along Hertz's major axis (any line for spheres), k the no-slip stiffness
(1 / ``hertz.tangential_compliance(c)[0, 0]``: 8 G* a for a circle).

* **The driving quantity** (``driven``): a DEM code moves the bodies (displacement-driven,
  ``fix move``) or applies forces (force-driven).  Taken from ``--driven`` or detected: the
  quantity whose steps are equal (a constant velocity) more often.  Every reference is
  taken at the driving quantity: displacement-driven, the reference force at the
  history's own displacements (the same displacement amplitude); force-driven, the
  reference displacement at its forces (the same force amplitude).  The checks, the
  report and the plot use that one reference.
* **Reference at constant P**: Mindlin-Deresiewicz (Masing's rule with memory, sliding at
  mu P): ``hertz.TangentialSpring`` stepped by the history's displacement increments,
  or ``hertz.tangential_history`` at its forces.  **Where P varies**:
  ``hertz.LoadPathSpring`` (``step(P, increment)``: displacement in, force out) or
  ``hertz.load_path`` (forces in, displacement out).
* ``initial_stiffness_rel_err``: the compliance delta / Q of the ramp points with
  |Q| <= STIFFNESS_WINDOW mu P, fitted by a line in Q and taken at Q = 0 (exact for a
  linear law; for Mindlin's curve delta / Q = (1 + q / 6 + ...) / k, q = Q / (mu P), the
  line leaves ~(2/27) q^2, 2e-4 at q = 0.05), against 1 / k.
  ``reversal_stiffness_rel_err``: the same after each reversal on the increments from it
  (Masing's branch doubles the skeleton: the window is 2 STIFFNESS_WINDOW mu P), the worst.
* ``force_rel_err_max``: on the ramp (to the first reversal), the largest
  (Q - Q_ref) / Q_ref (force-driven: (delta - delta_ref) / delta_ref).
  ``branch_err_max``: after the first reversal, the largest |Q - Q_ref| / Q*, Q* the
  reference's amplitude (force-driven: |delta - delta_ref| / delta*).
* ``loop_energy_rel_err``: the trapezoid area of the first closed loop (first reversal ->
  second -> back to the first's driving value) against Mindlin-Deresiewicz's
  closed form ``c.fretting(Q*).energy`` at the reference amplitude: displacement-driven
  Q* = the virgin force at half the displacement range, force-driven half the force
  range (where the reference slides or the loop is not a Masing loop, the trapezoid of
  the reference along the same points, said in the notes).
* ``path_force_err_max`` (P varying; information at constant P): the largest
  |Q - Q_ref| / (mu P_max) over the whole path; the states where the laws part (end of
  each phase: press, push, lift, press back ...) are listed.
* ``law_force_err_max``: with ``law`` one of the simplified laws (:data:`LAWS`), the
  largest |Q - Q_law| / (mu P_max) against that law stepped along the same path; the
  verdict is then on the law claimed (and the stiffness), and the Mindlin-Deresiewicz
  metrics are the measured distance to the physics (information).

Errors are (result - reference) / reference unless said otherwise.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field

import numpy as np

from ..results.contact import ResultError
from ..results.tangential import path_reversals
from ..results.tangential_history import VARYING, TangentialHistory
from .contact import GradeMethods, _checks, _tolerances, hertz_quietly, nan_to_none
from .tangential import _closing_loop, loop_energy

__all__ = ["DEFAULT_TOLERANCES", "LAWS", "METRICS", "HistoryGrade", "grade_history",
           "lammps_law"]

#: The laws a code may claim: the physics, and the linear spring capped at mu P with
#: k = 8 G* a (at constant P all the same), LAMMPS's variants where P changes
#: (pair_style granular, tangential ...): ``mindlin`` (F = k(a) xi, xi the displacement
#: history), ``mindlin_rescale`` (xi scaled by a / a_prev where a falls),
#: ``mindlin/force`` (dF = k(a) d xi), ``mindlin_rescale/force`` (F scaled by a / a_prev
#: where a falls); at the cap the history is set back to +-mu P.
LAWS = ("mindlin-deresiewicz", "linear-capped", "mindlin", "mindlin_rescale", "mindlin/force",
        "mindlin_rescale/force")
LAMMPS_LAWS = LAWS[2:]
#: The stiffness fits take the points with |Q| up to this fraction of mu P.
STIFFNESS_WINDOW = 0.05
#: ... and need at least this many of them.
MIN_WINDOW_POINTS = 2
#: Fewest points on the ramp (after the start) to grade a history.
MIN_RAMP_POINTS = 3
#: The driving quantity's steps are "equal" within this relative difference.
EQUAL_STEPS = 1e-6

DEFAULT_TOLERANCES = {
    "initial_stiffness_rel_err": 0.005, "reversal_stiffness_rel_err": 0.005,
    "force_rel_err_max": 0.01, "branch_err_max": 0.01, "loop_energy_rel_err": 0.03,
    "path_force_err_max": 0.01, "law_force_err_max": 0.01,
}
#: The metrics of Mindlin-Deresiewicz's law (information where another law is claimed).
PHYSICS = ("force_rel_err_max", "branch_err_max", "loop_energy_rel_err", "path_force_err_max")

METRICS = {
    "initial_stiffness_rel_err": (
        "initial stiffness", "secant stiffness at the start of the ramp (compliance fit to "
                             "Q = 0 over |Q| <= 5% mu P) against Mindlin's no-slip k"),
    "reversal_stiffness_rel_err": (
        "stiffness after reversals", "the same from each reversal (Masing: k again), the "
                                     "worst"),
    "force_rel_err_max": (
        "ramp", "largest (Q - Q_ref) / Q_ref on the ramp, Mindlin's virgin curve at the "
                "history's displacement (force-driven: the displacement error at its force)"),
    "branch_err_max": (
        "branches", "largest |Q - Q_ref| / Q* after the first reversal, Masing's rule with "
                    "memory (force-driven: |delta - delta_ref| / delta*)"),
    "loop_energy_rel_err": (
        "loop energy", "trapezoid area of the first closed loop against "
                       "Mindlin-Deresiewicz's energy at the same driving amplitude"),
    "path_force_err_max": (
        "whole path", "largest |Q - Q_ref| / (mu P_max) over the path against "
                      "Mindlin-Deresiewicz (hertz.LoadPathSpring where P varies)"),
    "law_force_err_max": (
        "law claimed", "largest |Q - Q_law| / (mu P_max) against the simplified law the code "
                       "claims, stepped along the same path (force-driven: |delta - "
                       "delta_law| / max |delta|)"),
}


@dataclass(frozen=True)
class HistoryGrade(GradeMethods):
    """A DEM history graded against Mindlin-Deresiewicz and the law the code claims.

    Attributes
    ----------
    scene, source : str
    law : str
        The law claimed (:data:`LAWS`).
    driven : {"displacement", "force"}
    driven_how : str
        Why (given, or the detection's figures).
    mu : float
    normal_force : float
        The largest P [N].
    varying : bool
        Whether P varies (the reference is then ``hertz.LoadPathSpring``/``load_path``).
    metrics : dict
        Every metric of :data:`METRICS` (NaN where not available).
    checks : tuple of Check
    passed : bool
    diagnosis : tuple of str
        The story in words, from the measured numbers.
    reference : dict
        k [N/m], a [m], mu P [N], Q* [N], the reference's loop energy [J], ...
    measured : dict
        The history's stiffnesses [N/m], loop energy [J], reversals, ...
    states : list of dict
        Where P varies: the end of each phase (name, row, P, displacement, Q, the
        reference's Q, LAMMPS's variants' Q, error, whether the laws part there).
    path : dict
        ``displacement``, ``force``, ``normal_force``, ``reference`` (the reference
        at the driving quantity: forces if displacement-driven, displacements if
        force-driven), ``law`` (the claimed law's forces or None).
    notes : tuple of str
    details : dict
    hint : str
    """

    scene: str
    source: str
    law: str
    driven: str
    driven_how: str
    mu: float
    normal_force: float
    varying: bool
    metrics: dict
    checks: tuple
    passed: bool
    diagnosis: tuple = ()
    reference: dict = field(default_factory=dict)
    measured: dict = field(default_factory=dict)
    states: list = field(default_factory=list)
    path: dict = field(default_factory=dict, repr=False)
    notes: tuple = ()
    details: dict = field(default_factory=dict)
    hint: str = ""

    def to_dict(self) -> dict:
        """grade.json: the metrics at the top level, passed, the diagnosis, checks,
        reference, measured, states, notes."""
        checks = [{**c.to_dict(), "meaning": METRICS[c.name][1]} for c in self.checks]
        return nan_to_none({
            "kind": "tangential history", "scene": self.scene, "source": self.source,
            "law": self.law, "driven": self.driven, "driven_how": self.driven_how,
            "mu": self.mu, "normal_force": self.normal_force, "varying": self.varying,
            **self.metrics, "passed": self.passed, "diagnosis": list(self.diagnosis),
            "hint": self.hint, "checks": checks, "reference": self.reference,
            "measured": self.measured, "states": self.states, "notes": list(self.notes),
            "details": self.details})


# --- the laws -----------------------------------------------------------------------------

def lammps_law(variant: str, displacement, normal_force, stiffness, contact_radius,
               mu: float) -> np.ndarray:
    """The tangential force [N] of a linear spring capped at mu P along a path, as LAMMPS's
    ``pair_style granular`` computes it (no damping), one contact along one line.

    Parameters
    ----------
    variant : {"mindlin", "mindlin_rescale", "mindlin/force", "mindlin_rescale/force"}
        ``mindlin``: F = k xi, xi the accumulated displacement; ``mindlin/force``:
        dF = k d(xi); ``_rescale``: the history (xi, or F) times a / a_prev where the
        contact radius a falls.  Where |F| > mu P: F = +-mu P and the history set to it.
    displacement, normal_force, stiffness, contact_radius : array_like, shape (k,)
        Per row: the displacement [m], P [N], the tangential stiffness k = 8 G* a [N/m]
        and a [m] (0 where the bodies do not touch: the history is erased).
    mu : float

    Returns
    -------
    ndarray, shape (k,)

    Examples
    --------
    >>> f = lammps_law("mindlin", [0.0, 1e-6, 2e-6, 1e-6], [1.0] * 4, [1e5] * 4, [1e-5] * 4,
    ...                0.15)
    >>> [round(float(x), 6) for x in f]
    [0.0, 0.1, 0.15, 0.05]
    """
    if variant not in LAMMPS_LAWS:
        raise ValueError(f"variant must be one of {', '.join(LAMMPS_LAWS)}, got {variant!r}")
    force_form = variant.endswith("/force")
    rescale = "rescale" in variant
    d = np.asarray(displacement, dtype=float)
    p, kt, a = (np.broadcast_to(np.asarray(x, dtype=float), d.shape)
                for x in (normal_force, stiffness, contact_radius))
    out = np.zeros(d.shape)
    hist, a_prev, prev_d = 0.0, 0.0, d[0] if d.size else 0.0
    for i in range(d.size):
        inc = d[i] - prev_d
        prev_d = d[i]
        ai, ki, crit = float(a[i]), float(kt[i]), mu * float(p[i])
        if not ai > 0:
            hist, a_prev = 0.0, 0.0
            continue
        if rescale and ai < a_prev:
            hist *= ai / a_prev
        if force_form:
            hist += ki * inc
            fs = hist
        else:
            hist += inc
            fs = ki * hist
        if abs(fs) > crit:
            fs = math.copysign(crit, fs)
            hist = fs if force_form else fs / ki
        a_prev = ai
        out[i] = fs
    return out


def _virgin_force(delta, reach, limit):
    """Mindlin's virgin curve Q(delta) = mu P (1 - (1 - delta / delta_s)^(3/2)) [N],
    delta_s = ``reach``; mu P beyond."""
    x = np.minimum(np.asarray(delta, dtype=float) / reach, 1.0)
    return limit * -np.expm1(1.5 * np.log1p(-x))


# --- measures on the path -----------------------------------------------------------------

def _compliance_fit(dx, dq, window, scale=1.0):
    """Stiffness [N/m] at the start of a branch: delta / Q fitted by a line in Q over the
    points with 0 < |Q| <= window (Q relative to the branch's start), taken at Q = 0;
    None with fewer than MIN_WINDOW_POINTS points; ``scale`` the factor of Q in the
    fit's variable (Masing's branch: 1/2), which does not change the intercept."""
    sel = (np.abs(dq) > 0) & (np.abs(dq) <= window)
    if np.count_nonzero(sel) < MIN_WINDOW_POINTS:
        return None, int(np.count_nonzero(sel))
    x, y = dq[sel] * scale, dx[sel] / dq[sel]
    if np.ptp(x) == 0:
        return 1.0 / float(np.mean(y)), int(sel.sum())
    slope, intercept = np.polyfit(x / np.abs(x).max(), y, 1)
    return 1.0 / float(intercept), int(sel.sum())


def _equal_share(steps) -> float:
    """The share of the nonzero steps equal to their median magnitude."""
    s = np.abs(steps[steps != 0])
    if not s.size:
        return 0.0
    m = np.median(s)
    return float(np.mean(np.abs(s - m) <= EQUAL_STEPS * m))


def detect_driving(h: TangentialHistory) -> tuple[str, str]:
    """("displacement" | "force", why): the quantity whose steps are equal more often
    (displacement where they tie: a DEM code moves bodies)."""
    sd, sq = _equal_share(np.diff(h.displacement)), _equal_share(np.diff(h.force))
    driven = "force" if sq > sd else "displacement"
    tie = "; a tie goes to the displacement: a DEM code moves the bodies" if sq == sd else ""
    return driven, (f"detected: {sd:.0%} of the displacement steps and {sq:.0%} of the "
                    f"force steps are equal{tie}; --driven to say")


def _phases(d, p):
    """[(name, last row)] of the path's phases: press / lift (P changes, the bodies held),
    push / pull back (the displacement changes), hold."""
    labels = []
    for i in range(1, len(d)):
        dd, dp = d[i] - d[i - 1], p[i] - p[i - 1]
        labels.append("push" if dd > 0 else "pull back" if dd < 0 else
                      "press" if dp > 0 else "lift" if dp < 0 else "hold")
    out, seen = [], {}
    for i, lab in enumerate(labels, start=1):
        if out and out[-1][0] == lab:
            out[-1][1] = i
        else:
            out.append([lab, i])
    named = []
    for lab, end in out:
        if lab == "hold":
            continue
        n = seen.get(lab, 0)
        seen[lab] = n + 1
        again = {"press": "press back", "push": "push again", "lift": "lift again",
                 "pull back": "pull back again"}[lab]
        named.append((lab if n == 0 else again if n == 1 else f"{again} ({n})", end))
    return named


def _stiffness_candidates(scene) -> list[tuple[str, float]]:
    """Known wrong constants of a linear law, as multiples of 8 G* a (both bodies of one
    material only: else none)."""
    b1, b2 = scene.body1, scene.body2
    try:
        e1, n1, e2, n2 = (float(x) for x in (b1.E, b1.nu, b2.E, b2.nu))
    except (TypeError, ValueError, AttributeError):
        return []
    if (e1, n1) != (e2, n2):
        return []
    g = e1 / (2 * (1 + n1))
    g_star = 1 / (2 * (2 - n1) / g)
    e_star = 1 / (2 * (1 - n1 * n1) / e1)
    return [("k_t = 4 G a, G of one body", 4 * g / (8 * g_star)),
            ("k_t = 8 G a, G of one body", 8 * g / (8 * g_star)),
            ("k_t = 2 E* a, the normal stiffness", 2 * e_star / (8 * g_star)),
            ("k_t = 4 G* a, a factor 2 lost", 0.5)]


# --- the grader ---------------------------------------------------------------------------

def grade_history(history: TangentialHistory, scene, tolerances: Mapping[str, float] | None = None,
                  *, law: str = "mindlin-deresiewicz", driven: str | None = None,
                  hertz_at: Callable | None = None) -> HistoryGrade:
    """Grade a DEM code's tangential history against Mindlin-Deresiewicz and a claimed law.

    Parameters
    ----------
    history : TangentialHistory
    scene : fem_validation.scenes.Scene
        The two bodies (``body1``, ``body2``, ``angle``, ``hertz(load)``).
    tolerances : dict, optional
        Metric -> largest allowed |value| (default :data:`DEFAULT_TOLERANCES`).
    law : str
        One of :data:`LAWS`: the law the code claims; the verdict is on it (and the
        stiffness); with another than ``"mindlin-deresiewicz"`` the Mindlin-Deresiewicz
        metrics are information (the distance to the physics).  ``"linear-capped"`` is
        defined at constant P only (where P varies, name a LAMMPS variant).
    driven : {"displacement", "force"}, optional
        The driving quantity; default detected (:func:`detect_driving`).
    hertz_at : callable, optional
        P [N] -> hertz.Contact; default ``scene.hertz``.

    Returns
    -------
    HistoryGrade

    Raises
    ------
    ResultError
        A history that cannot be graded (no ramp, too few points for the checks, a
        force beyond mu P, a law not defined for it): bad input, not a failed grade.

    Examples
    --------
    See docs/howto/dem-tangential-law.md.
    """
    if law not in LAWS:
        raise ValueError(f"law must be one of {', '.join(LAWS)}, got {law!r}")
    if driven not in (None, "displacement", "force"):
        raise ValueError(f"driven must be 'displacement' or 'force', got {driven!r}")
    tol = _tolerances(tolerances, DEFAULT_TOLERANCES, METRICS)
    src = history.source or "the history"
    hertz_at = scene.hertz if hertz_at is None else hertz_at
    d, q, p, mu = history.displacement, history.force, history.normal_force, history.mu
    notes = []
    # P constant from the row before the first tangential motion on (a DEM run presses,
    # then pushes): the rows before it (the normal loading) are left out
    start = max(int(np.argmax(d != 0)) - 1, 0)
    offset = 0
    tail = p[start:]
    if (history.varying and start > 0 and tail.min() > 0
            and tail.max() - tail.min() <= VARYING * tail.max()):
        offset = start
        d, q, p = d[start:], q[start:], p[start:]
        notes.append(f"P is constant ({p[0]:.6g} N) from {history.at(start)} on, the row "
                     f"before the first tangential motion: the {start} rows before it (the "
                     f"normal loading) are not graded")
    varying = bool(p.max() - p.min() > VARYING * p.max())
    k_rows = len(d)

    def at(i: int) -> str:
        return history.at(offset + int(i))

    if law == "linear-capped" and varying:
        raise ResultError(f"{src}: --law linear-capped is defined at constant normal force; "
                          f"the normal force varies here ({p.min():.6g} to {p.max():.6g} N): "
                          f"name how the law follows it: {', '.join(LAMMPS_LAWS)}")
    driven_how = "given"
    if driven is None:
        driven, driven_how = detect_driving(history)
    p_max = float(p.max())
    limit_max = mu * p_max
    # Hertz at every distinct P (vectorised), the stiffness along the major axis
    import hertz

    touching = p > 0
    a_rows = np.zeros(k_rows)
    k_rows_t = np.zeros(k_rows)
    uniq, inverse = np.unique(p[touching], return_inverse=True)
    cs, validity = hertz_quietly(hertz_at, uniq)
    notes += list(validity)
    a_rows[touching] = np.atleast_1d(np.asarray(cs.a, dtype=float))[inverse]
    k_rows_t[touching] = 1.0 / np.atleast_1d(
        np.asarray(hertz.tangential_compliance(cs), dtype=float)[..., 0, 0])[inverse]
    radii = [abs(float(r)) for b in (getattr(scene, "body1", None), getattr(scene, "body2", None))
             if b is not None for r in (b.Rx, b.Ry) if math.isfinite(float(r)) and float(r) != 0]
    too_big = np.flatnonzero(a_rows >= min(radii, default=math.inf))
    if too_big.size:  # not a Hertz contact: a unit mistake or a corrupt row
        i = int(too_big[0])
        raise ResultError(f"{src}, {at(i)}: the normal force {p[i]:.6g} N gives a contact "
                          f"radius a = {a_rows[i]:.4g} m, beyond the bodies' radius "
                          f"{min(radii):.4g} m: not a Hertz contact (the force's unit?)")
    c_max, _ = hertz_quietly(hertz_at, p_max)
    k_max = 1.0 / float(hertz.tangential_compliance(c_max)[0, 0])

    over = np.flatnonzero(np.abs(q) > 1.05 * mu * p)
    if over.size:
        i = int(over[0])
        raise ResultError(f"{src}, {at(i)}: the tangential force {q[i]:.6g} N exceeds "
                          f"mu P = {mu * p[i]:.6g} N (mu = {mu:.6g}, P = {p[i]:.6g} N) by "
                          f"more than 5%: mu, the normal force or the force's unit is wrong")
    # the ramp: the first motion, to the first reversal of the driving quantity
    drive = d if driven == "displacement" else q
    rev = path_reversals(drive)
    first = int(np.argmax(d != 0))
    i1 = rev[0] if rev else k_rows - 1
    ramp = np.arange(first, i1 + 1)
    ramp = ramp[(d[ramp] > 0) & touching[ramp]]
    if ramp.size < MIN_RAMP_POINTS:
        raise ResultError(f"{src}: the ramp (the first motion, to the first reversal at "
                          f"{at(i1)}) holds {ramp.size} point(s) with a displacement "
                          f"> 0 in contact; grading needs {MIN_RAMP_POINTS} or more: record "
                          f"more steps")

    # --- the reference at the driving quantity ---------------------------------------------
    md_force = md_disp = None
    sliding = np.zeros(k_rows, dtype=bool)
    if driven == "displacement":
        md_force = np.zeros(k_rows)
        if not varying:
            spring = hertz.TangentialSpring(c_max, mu=mu)
            prev = 0.0
            for i in range(k_rows):
                md_force[i] = spring.step(d[i] - prev)
                sliding[i] = bool(spring.sliding)
                prev = d[i]
        else:
            spring = hertz.LoadPathSpring(scene.body1, scene.body2, mu,
                                          angle=getattr(scene, "angle", 0.0))
            prev = 0.0
            for i in range(k_rows):
                md_force[i] = spring.step(float(p[i]), d[i] - prev)
                sliding[i] = bool(spring.sliding)
                prev = d[i]
        reference = md_force
    else:
        at_cap = (np.abs(q) >= mu * p * (1 - 1e-12)) & touching
        qc = np.clip(q, -mu * p, mu * p)
        if not varying:
            md_disp = hertz.tangential_history(c_max, qc, mu)
        else:
            md_disp = np.asarray(hertz.load_path(scene.body1, scene.body2, p, qc, mu,
                                                 angle=getattr(scene, "angle", 0.0))
                                 .displacement, dtype=float)
        sliding = at_cap
        if at_cap.any():
            notes.append(f"{int(at_cap.sum())} row(s) of this force-driven history are at mu P "
                         f"(sliding: the displacement is not determined by the force): not "
                         f"graded")
        reference = md_disp

    # --- the stiffness at the start and after each reversal --------------------------------
    k0 = float(k_rows_t[ramp[0]])
    win = STIFFNESS_WINDOW * mu * p[ramp[0]]
    base = first - 1 if first > 0 else 0
    seg = ramp[np.abs(p[ramp] - p[ramp[0]]) <= 1e-9 * p[ramp[0]]]
    k_meas, n_win = _compliance_fit(d[seg] - d[base], q[seg] - q[base], win)
    if k_meas is None:
        raise ResultError(f"{src}: the stiffness check needs {MIN_WINDOW_POINTS} or more "
                          f"points with |Q| <= {STIFFNESS_WINDOW:.0%} of mu P = "
                          f"{mu * p[ramp[0]]:.6g} N at the start of the ramp; {n_win} there "
                          f"(first ramp point Q = {q[ramp[0]]:.6g} N, {at(int(ramp[0]))}):"
                          f" record smaller steps at the start")
    e_k0 = k_meas / k0 - 1
    rev_errs, rev_k = [], []
    bounds = list(rev) + [k_rows - 1]
    for j, r in enumerate(rev):
        stop = bounds[j + 1]
        idx = np.arange(r + 1, stop + 1)
        idx = idx[touching[idx] & (np.abs(p[idx] - p[r]) <= 1e-9 * p[r])] if p[r] > 0 else idx[:0]
        if not idx.size or k_rows_t[r] == 0:
            continue
        km, n = _compliance_fit(d[r] - d[idx], q[r] - q[idx], 2 * STIFFNESS_WINDOW * mu * p[r],
                                scale=0.5)
        if km is None:
            notes.append(f"the stiffness after the reversal at {at(r)}: {n} point(s) "
                         f"within {2 * STIFFNESS_WINDOW:.0%} mu P of it, "
                         f"{MIN_WINDOW_POINTS} needed: not measured")
            continue
        rev_k.append(km)
        rev_errs.append(km / float(k_rows_t[r]) - 1)
    e_krev = max(rev_errs, key=abs) if rev_errs else math.nan
    if not rev:
        notes.append("the path never turns back: no stiffness after a reversal, no branches, "
                     "no loop energy")

    # --- ramp, branches, loop energy (constant P) ------------------------------------------
    force_err = branch_err = energy_err = math.nan
    w_meas = w_ref = q_star = math.nan
    energy_how = ""
    path_err = math.nan
    graded = ~sliding if driven == "force" else np.ones(k_rows, dtype=bool)
    if driven == "displacement":
        path_err = float(np.abs(q - md_force).max() / limit_max)
    else:
        ok = graded & touching
        scale = float(np.abs(md_disp[ok]).max()) if ok.any() else math.nan
        path_err = (float(np.abs(d[ok] - md_disp[ok]).max() / scale)
                    if ok.any() and scale > 0 else math.nan)
    c = c_max
    limit = mu * float(c.load)
    reach = 1.5 * limit / k_max  # 3 mu P / (2 k)
    if varying:
        notes.append("the normal force varies: the ramp, branch and loop-energy checks (at "
                     "constant P) are replaced by the whole path against "
                     + ("hertz.LoadPathSpring and the states where the laws part"
                        if driven == "displacement" else "hertz.load_path"))
    else:
        rr = ramp[graded[ramp]]
        if driven == "displacement":
            rr = rr[md_force[rr] > 0]
            errs = (q[rr] - md_force[rr]) / md_force[rr]
        else:
            rr = rr[md_disp[rr] > 0]
            errs = (d[rr] - md_disp[rr]) / md_disp[rr]
        force_err = float(errs[np.argmax(np.abs(errs))]) if errs.size else math.nan
        if rev:
            after = np.arange(rev[0] + 1, k_rows)
            after = after[graded[after]]
            r2 = rev[1] if len(rev) > 1 else k_rows - 1
            if driven == "displacement":
                q_star = 0.5 * (abs(md_force[rev[0]]) + abs(md_force[r2]))
                if after.size and q_star > 0:
                    branch_err = float(np.abs(q[after] - md_force[after]).max() / q_star)
            else:
                d_star = 0.5 * (abs(md_disp[rev[0]]) + abs(md_disp[r2]))
                q_star = 0.5 * (abs(q[rev[0]]) + abs(q[r2]))
                if after.size and d_star > 0:
                    branch_err = float(np.abs(d[after] - md_disp[after]).max() / d_star)
        if len(rev) > 1:
            r1, r2 = rev[0], rev[1]
            end = rev[2] if len(rev) > 2 else k_rows - 1
            if driven == "displacement":
                loop = _closing_loop(d, q, r1, r2, end)
                loop_ref = _closing_loop(d, md_force, r1, r2, end)
            else:
                loop = _closing_loop(q, d, r1, r2, end)
                loop_ref = _closing_loop(q, md_disp, r1, r2, end)
                loop = loop and (loop[1], loop[0])
                loop_ref = loop_ref and (loop_ref[1], loop_ref[0])
            if loop is None:
                notes.append(f"the path does not come back to the first reversal after the "
                             f"second ({at(r2)}): the loop is not closed, no loop "
                             f"energy")
            else:
                w_meas = loop_energy(*loop)
                m = r2 - r1
                if driven == "displacement":
                    half = 0.5 * (d[r1] - d[r2])
                    amp = float(_virgin_force(half, reach, limit))
                    masing = (abs(d[r2]) <= d[r1] * (1 + 1e-12)
                              and not sliding[r1:end + 1].any() and amp < limit)
                else:
                    amp = 0.5 * (q[r1] - q[r2])
                    masing = abs(q[r2]) <= q[r1] * (1 + 1e-12) and amp < limit
                if masing:
                    w_ref = float(c.fretting(amp, mu).energy)
                    energy_how = (f"closed form c.fretting(Q*).energy at Q* = {amp:.6g} N "
                                  f"({amp / limit:.4g} mu P), the reference's amplitude at the "
                                  f"same {driven} range")
                else:
                    w_ref = loop_energy(*loop_ref) if loop_ref is not None else math.nan
                    energy_how = ("the reference's own trapezoid along the same points (it "
                                  "slides, or the loop is not a Masing loop: no closed form)")
                    notes.append(f"loop energy: {energy_how}")
                q_star = amp
                if w_ref > 0:
                    energy_err = w_meas / w_ref - 1
                notes.append(f"the loop's trapezoid rule errs by about -1/m^2 on a smooth "
                             f"loop (m = {m} steps per branch: {-1 / m ** 2:+.1e})")

    # --- the law claimed --------------------------------------------------------------------
    law_force = None
    law_err = math.nan
    variants = {}
    if driven == "displacement":
        for v in LAMMPS_LAWS:
            variants[v] = lammps_law(v, d, p, k_rows_t, a_rows, mu)
        claimed = "mindlin" if law == "linear-capped" else law
        if claimed in variants:
            law_force = variants[claimed]
            law_err = float(np.abs(q - law_force).max() / limit_max)
    elif law != "mindlin-deresiewicz" and not varying:
        # force-driven at constant P: the linear law's displacement, delta += dQ / k, taken
        # up again from the history's where it slides (|Q| = mu P: not determined)
        law_disp = np.empty(k_rows)
        law_disp[0] = d[0]
        for i in range(1, k_rows):
            law_disp[i] = (d[i] if sliding[i] else
                           (d[i - 1] if sliding[i - 1] else law_disp[i - 1])
                           + (q[i] - q[i - 1]) / k_max)
        ok = ~sliding
        scale = float(np.abs(d).max())
        law_err = float(np.abs(d[ok] - law_disp[ok]).max() / scale)
        law_force = None
        notes.append(f"law_force_err_max of this force-driven history: the largest |delta - "
                     f"delta_law| / max |delta|, delta_law = delta + dQ / k ({law})")
    elif law != "mindlin-deresiewicz":
        notes.append(f"the law claimed ({law}) is stepped along force-driven histories at "
                     f"constant P only: not compared (the stiffness checks apply)")

    # --- the states where the laws part (P varying) -----------------------------------------
    states = []
    part_tol = tol.get("path_force_err_max", DEFAULT_TOLERANCES["path_force_err_max"])
    if varying and driven == "displacement":
        for name, row in _phases(d, p):
            ref = float(md_force[row])
            err = (q[row] - ref) / ref if ref != 0 else math.nan
            states.append({
                "state": f"end of {name}", "row": int(row), "line": at(row),
                "normal_force": float(p[row]), "displacement": float(d[row]),
                "force": float(q[row]), "reference_force": ref, "rel_err": err,
                "parts": bool(abs(q[row] - ref) > 1e-6 * limit_max
                              and abs(q[row] - ref) > part_tol * abs(ref)),
                **{v: float(f[row]) for v, f in variants.items()}})

    metrics = {
        "initial_stiffness_rel_err": e_k0, "reversal_stiffness_rel_err": e_krev,
        "force_rel_err_max": force_err, "branch_err_max": branch_err,
        "loop_energy_rel_err": energy_err, "path_force_err_max": path_err,
        "law_force_err_max": law_err,
    }
    checked = dict(tol)
    if law == "mindlin-deresiewicz":
        checked.pop("law_force_err_max", None)
        if not varying:
            checked.pop("path_force_err_max", None)
    else:
        for name in PHYSICS:
            checked.pop(name, None)
    checks = _checks(metrics, checked, METRICS)
    passed = all(ch.status != "fail" for ch in checks)
    scaled = None  # a linear spring capped at mu P with the stiffness measured
    if driven == "displacement" and not varying and k0 > 0:
        scaled = lammps_law("mindlin", d, p, k_rows_t * (k_meas / k0), a_rows, mu)
    diagnosis = _diagnose(metrics, tol, law, varying, driven, k_meas, k0, scene, variants,
                          q, limit_max, w_meas, w_ref, states, scaled)
    return HistoryGrade(
        scene=getattr(scene, "name", ""), source=history.source, law=law, driven=driven,
        driven_how=driven_how, mu=mu, normal_force=p_max, varying=varying, metrics=metrics,
        checks=checks, passed=passed, diagnosis=tuple(diagnosis),
        reference={"a": float(c_max.a), "no_slip_stiffness": k_max,
                   "initial_no_slip_stiffness": k0, "mu_P": limit_max,
                   "sliding_displacement": reach, "amplitude": q_star, "loop_energy": w_ref,
                   "loop_energy_from": energy_how, "model": (
                       ("hertz.LoadPathSpring" if driven == "displacement" else
                        "hertz.load_path") if varying else
                       ("hertz.TangentialSpring" if driven == "displacement" else
                        "hertz.tangential_history"))},
        measured={"initial_stiffness": k_meas, "stiffness_window_points": n_win,
                  "reversal_stiffness": rev_k, "reversals": list(rev),
                  "loop_energy": w_meas, "ramp_points": int(ramp.size), "rows": k_rows},
        states=states,
        path={"displacement": d, "force": q, "normal_force": p, "reference": reference,
              "law": law_force},
        notes=tuple(notes), details=dict(history.details))


def _pct(x: float) -> str:
    if not math.isfinite(x):
        return "-"
    return f"{x:+.1e}" if abs(x) < 1e-4 else f"{x:+.2%}" if abs(x) < 0.1 else f"{x:+.0%}"


def _diagnose(metrics, tol, law, varying, driven, k_meas, k0, scene, variants, q, limit_max,
              w_meas, w_ref, states, scaled=None) -> list[str]:
    """The grade in words, from the measured numbers."""
    out = []
    e = metrics["initial_stiffness_rel_err"]
    if abs(e) <= 1e-6:
        out.append(f"no-slip stiffness exact ({_pct(e)} against Mindlin's k = "
                   f"{k0:.6g} N/m)")
    elif abs(e) <= tol["initial_stiffness_rel_err"]:
        out.append(f"no-slip stiffness right ({_pct(e)} against Mindlin's k)")
    else:
        ratio = k_meas / k0
        guess = next((name for name, r in _stiffness_candidates(scene)
                      if abs(ratio / r - 1) <= 0.02), None)
        out.append(f"stiffness {_pct(e)}: the initial stiffness is {ratio:.4g} x Mindlin's "
                   f"8 G* a" + (f" ({guess}?)" if guess else ""))
    er = metrics["reversal_stiffness_rel_err"]
    if math.isfinite(er) and abs(er) > tol["reversal_stiffness_rel_err"] and abs(e) <= tol[
            "initial_stiffness_rel_err"]:
        out.append(f"the stiffness after a reversal is {_pct(er)} off Mindlin's k (Masing: "
                   f"k again after every reversal)")
    if driven == "displacement" and "mindlin" in variants:
        lin = float(np.abs(q - variants["mindlin"]).max() / limit_max)
        md = metrics["path_force_err_max"]
        if varying:
            best = min(variants, key=lambda v: np.abs(q - variants[v]).max())
            bd = float(np.abs(q - variants[best]).max() / limit_max)
            if bd <= tol["law_force_err_max"]:
                out.append(f"the law is LAMMPS's {best} (within {bd:.1e} mu P)")
            parts = [s for s in states if s["parts"]]
            if parts:
                out.append("it parts from Mindlin-Deresiewicz at: " + ", ".join(
                    f"{s['state']} ({_pct(s['rel_err'])})" for s in parts))
            elif md <= tol["path_force_err_max"]:
                out.append(f"Mindlin-Deresiewicz along the whole path (within {md:.1e} mu P)")
        elif lin <= tol["law_force_err_max"] and md > tol["path_force_err_max"]:
            out.append(f"no micro-slip: a linear spring capped at mu P (within {lin:.1e} mu P "
                       f"of it; Mindlin-Deresiewicz bends from the start: ramp "
                       f"{_pct(metrics['force_rel_err_max'])})")
        elif (scaled is not None and md > tol["path_force_err_max"]
              and float(np.abs(q - scaled).max() / limit_max) <= tol["law_force_err_max"]):
            out.append(f"no micro-slip: a linear spring capped at mu P with the stiffness "
                       f"above (within {float(np.abs(q - scaled).max() / limit_max):.1e} "
                       f"mu P of it)")
        elif md <= tol["path_force_err_max"]:
            out.append(f"Mindlin-Deresiewicz's micro-slip (within {md:.1e} mu P along the "
                       f"path)")
        else:
            out.append(f"neither Mindlin-Deresiewicz ({md:.2g} mu P off) nor a linear spring "
                       f"capped at mu P ({lin:.2g} mu P off)")
    if math.isfinite(w_meas) and math.isfinite(w_ref) and w_ref > 0:
        ee = w_meas / w_ref - 1
        out.append(f"loop energy {w_meas:.4g} J against Mindlin-Deresiewicz's {w_ref:.4g} J "
                   f"({_pct(ee)})" + ("; no hysteresis below sliding" if ee < -0.99 else ""))
    if law != "mindlin-deresiewicz":
        le = metrics["law_force_err_max"]
        if math.isfinite(le):
            verdict = "follows" if le <= tol["law_force_err_max"] else "does NOT follow"
            out.append(f"the history {verdict} the law claimed, {law} ({le:.2g} mu P); "
                       f"its distance to the physics is reported as information")
    return out
