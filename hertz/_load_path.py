"""Mindlin-Deresiewicz beyond constant normal load: a Hertz contact driven along any
sequence of (normal force, tangential force) pairs, the force along a principal axis.

The model (Mindlin's problem class)
-----------------------------------
Mindlin's uncoupled solution, as in :mod:`hertz._tangential`: the pressure is Hertz's
whatever the tangential traction (Goodman's coupling of dissimilar materials neglected,
see :func:`hertz.dundurs_beta`), the slip is taken parallel to the force, Coulomb's
law with one coefficient mu.  Frame: x along the major semi-axis a, y along the
minor semi-axis b; the force along x (``direction = 0``) or along y (``pi/2``).

Why a one-dimensional memory is exact (Jaeger's superposition principle)
------------------------------------------------------------------------
A "Cattaneo distribution" of size c is the traction t(x, y) = t0 sqrt(1 - x^2/c^2 -
y^2/(c b/a)^2) along a principal axis on the ellipse of semi-axes (c, c b/a), similar to
the contact ellipse.  It displaces every point of its own ellipse by the same amount
along the force with no transverse part (Mindlin 1949 for the circle, Deresiewicz 1957
for the ellipse; checked by a quadrature of Cerruti's solution in
tests/test_tangential.py and tests/test_load_path.py).  Its force is (2 pi/3) t0 c^2 b/a,
and a distribution of size a with t0 = mu p0 is the sliding traction mu p, which displaces
the ellipse by 3 mu P / (2 k), k the no-slip stiffness along the force
(:func:`hertz.tangential_compliance`); since k grows as a and P as a^3, the
displacement of size c is t0 c (pi b / a) / (k / a).

Every traction met along a (P, Q) path is a superposition of such distributions of
sizes c in [0, a] (Jaeger's superposition principle, "A new principle in contact
mechanics", J. Tribol. 120 (1998) 677, and Ciavarella, Int. J. Solids Struct. 35 (1998),
for the circle and plane contacts; the same argument holds on the family of similar
ellipses because each distribution displaces its own ellipse rigidly).  Written with a
line load q(c) over the size c in [-a, a], the distribution of size c0 is
q = beta (c0^2 - c^2)_+ (force (4/3) beta c0^3, uniform displacement beta c0^2 / k1 with
k1 = k / (2 a)), so the
traction history is carried by a one-dimensional bed of independent springs of
stiffness k1 per unit length (for the circle this is Popov and Hess's method of
dimensionality reduction, MDR, "Method of Dimensionality Reduction in Contact
Mechanics and Friction", Springer 2015; Aleshin and Van Den Abeele's "method of memory
diagrams", J. Mech. Phys. Solids 2007, solves arbitrary (P, Q) paths of spheres the
same way):

* the normal line load is n(c) = (3 P / (4 a^3)) (a^2 - c^2) (its integral is P and
  it maps to the Hertz pressure);
* each spring in contact (|c| < a) carries u(c) k1; it sticks (u moves with the rigid
  tangential displacement delta of the contact) while |u k1| < mu n(c) and slides at
  u k1 = +-mu n(c) otherwise;
* springs leaving the contact (a shrinks) lose their force; springs entering (a grows)
  start at zero force;
* Q = integral of k1 u over the contact; delta = u of the springs that stick.

Why the bed's state is a solution of the three-dimensional problem, step by step: every
piece of u has |B| <= 1 (a piece that slid has B = -+1, an entering one B = -d_delta /
(a1^2 - a0^2) with |.| <= 1 or it slides), so L -+ u never grows with x and the springs
that slide in a step are always an outer interval [c, a].  The traction increment is then
a sum of Cattaneo distributions of sizes >= c, which move the ellipse of size c rigidly:
that is the stick zone, exactly; in [c, a] the traction is +-mu p (the springs are at
their limit), with the slip of one sign.  tests/test_load_path.py checks on random paths
that the traction (the Abel transform of the line load) never exceeds mu p.

At constant P this is Cattaneo-Mindlin and Masing with memory (tangential_history),
with Q and P rising in proportion it is Mindlin-Deresiewicz's oblique loading
(proportional_loading); the stick zone is the similar ellipse through the innermost
spring that slides.

Exact solution of the spring bed, and what a step is
----------------------------------------------------
Scaled by a_ref, the contact at the largest normal force P_ref of the path, and by
U = 3 mu P_ref / (2 k_ref) (k_ref the no-slip stiffness at P_ref), the spring limit is
L(x) = alpha^2 - x^2 with alpha = a / a_ref = (P / P_ref)^(1/3), and Q / (mu P_ref) =
(3/2) int_0^alpha u dx.  Every state met is piecewise of the form u = A + B x^2 (the
limit is, and so are the states below), so it is held exactly as breakpoints and
coefficients; nothing is discretised in c.

Between two points of the path the relative displacement delta is taken to change
monotonically and in proportion to a^2 (that is to P^(2/3)) wherever P changes.  The
limit L(x) is linear in a^2 too, so the stick/slip of every spring over the step is
decided exactly by its state at the end of the step: a spring in contact becomes
clip(u + d_delta, -L, L) (u -+ L is linear along the step, its extreme is at an end), a
spring entering at size x (when a^2 = x^2) clip(d_delta (a1^2 - x^2) / (a1^2 - a0^2),
-L, L).  d_delta is the root of the (continuous, nondecreasing) force: Newton's method
on the exact slope, inside a bracket that bisection shrinks when Newton would leave it.

So a step is exact, whatever its length, at constant P (any change of Q: Masing's rule
with memory), for P rising at constant Q from any state (d_delta = 0: nothing moves),
for P falling at constant Q from a state whose spring forces all have the sign of Q
(then delta only grows and no spring meets the opposite limit; Mindlin-Deresiewicz's
case), for Q/P fixed from zero (proportional loading), and for any path on which delta
is linear in P^(2/3) between the points.  For another path (Q and P rising together
along curves, say) insert points: the error falls as the square of the step
(tests/test_load_path.py measures the order).

Accuracy and cost: the state is held in units of the path's largest normal force, so
the displacement is right to a few ulp of 3 mu P_ref / (2 k_ref) (a point whose forces
are many orders below P_ref carries that absolute error); near sliding the state is
ill-conditioned in the force (the stick size varies as (1 - Q/(mu P))^(1/3), so a
relative change eps of Q moves it by eps / (3 (1 - Q/(mu P)))).  Each step in which P
rises without slipping adds a piece (its entering springs have their own profile), so
a long rising path costs O(n) per step in :func:`load_path` (_SpringBed, which adds the
increment to every piece); :class:`LoadPathSpring` keeps the same pieces as a stack
(_SpringStacks) and moves them all at once by one number, at a cost per step that does
not grow with the path.

Closed forms (Mindlin & Deresiewicz 1953; derived here from the spring bed, checked
against mpmath at 50 digits in tests/reference_load_path.py)
------------------------------------------------------------
delta_C(P, Q) = 3 mu P / (2 k(P)) [1 - (1 - Q/(mu P))^(2/3)] is Cattaneo-Mindlin.

* From (P0, Q) reached by Q at constant P0, P raised to P1 at constant Q: nothing
  changes (delta stays delta_C(P0, Q)); the new ring carries no traction, no slip.
  Then Q raised by dQ at P1: while dQ <= mu (P1 - P0), delta = delta_C(P0, Q) +
  delta_C(P1, dQ) (a slip annulus grows from the edge into the new ring); beyond,
  delta = delta_C(P1, Q + dQ), the virgin state at P1 (all memory lost).
* From (P0, Q) reached by Q at constant P0, P lowered to P1 at constant Q (Q < mu P1):
  the state is the virgin Cattaneo-Mindlin state of (P1, Q): delta = delta_C(P1, Q),
  stick ellipse a1 (1 - Q/(mu P1))^(1/3); the slip annulus grows at the edge.
* Q/P = r < mu fixed from zero: delta = 3 Q / (2 k(P)), nothing slips.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import _interop, _ufuncs
from ._contact import contact as _contact
from ._tangential import _batch_shape, _mu, _selection, dundurs_beta, tangential_stiffness
from ._validate import as_float_array, error_at, first_failure, index_text

__all__ = ["LoadPath", "LoadPathSpring", "load_path"]


@dataclass(frozen=True, slots=True)
class LoadPath:
    """A Hertz contact driven along a path of normal and tangential forces.

    One entry per point of the path (shape (n,)).  The force acts along a principal
    axis of the contact ellipse (``direction`` 0: the major axis a, pi/2: the minor
    axis b).  Mindlin's uncoupled solution (see :func:`load_path`).

    Attributes
    ----------
    normal_force : ndarray
        P [N].
    tangential_force : ndarray
        Q [N] along the axis (negative: the opposite way), |Q| <= mu P.
    displacement : ndarray
        Relative tangential displacement of distant points of the two bodies along the
        axis [m] (body 1 relative to body 2), 0 at the unloaded start.  At |Q| = mu P
        it is the displacement at which the contact starts to slide as a whole.
    a, b : ndarray
        Semi-axes of the contact ellipse at P [m] (0 where P = 0).
    stick_a, stick_b : ndarray
        Semi-axes [m] of the stick ellipse: the largest ellipse similar to the contact
        ellipse inside which nothing slipped during the step to this point.  (a, b)
        when nothing slipped (for example P raised at fixed Q), 0 when the whole
        contact slides or P = 0.  At a switch-over, where a ring that slipped before
        meets its limit again along its whole length (Q raised by exactly mu (P1 - P0)
        after P was raised from P0 to P1), the ring has not slipped yet: the stick
        ellipse is the larger one, as in Mindlin and Deresiewicz's closed form at that
        point; just beyond, it jumps to the virgin stick zone.  A force within 64 eps of
        the switch-over's is taken to be at it, so every build decides it alike.
    sliding : ndarray of bool
        Whether |Q| = mu P: the whole contact slides.
    mu : float
        Coefficient of friction [-].
    direction : float
        Angle of the force from the major axis [rad], 0 or pi/2.
    dundurs_beta : float
        The size of the normal-tangential coupling that Mindlin's solution neglects
        (:func:`hertz.dundurs_beta`; 0 for elastically similar bodies).
    """

    normal_force: np.ndarray
    tangential_force: np.ndarray
    displacement: np.ndarray
    a: np.ndarray
    b: np.ndarray
    stick_a: np.ndarray
    stick_b: np.ndarray
    sliding: np.ndarray
    mu: float
    direction: float
    dundurs_beta: float


class _SpringBed:
    """The scaled spring bed of the module docstring: u = A + B x^2 on the pieces
    [edges[j], edges[j + 1]] of [0, alpha]; the limit is alpha^2 - x^2."""

    def __init__(self):
        self.edges = np.zeros(1)
        self.A = np.zeros(0)
        self.B = np.zeros(0)
        self.alpha = 0.0

    # A step: d_delta moves the trial state u + d_delta * (wa + wb x^2) of each piece
    def _prepare(self, alpha1):
        edges, A, B = self.edges, self.A, self.B
        alpha0 = self.alpha
        if alpha1 < alpha0:  # springs beyond alpha1 leave the contact
            keep = edges[:-1] < alpha1
            A, B = A[keep], B[keep]
            edges = np.append(edges[:-1][keep], alpha1)
        wa = np.ones(A.size)
        wb = np.zeros(A.size)
        if alpha1 > alpha0:  # springs entering: d_delta (a1^2 - x^2) / (a1^2 - a0^2)
            d = (alpha1 - alpha0) * (alpha1 + alpha0)
            edges = np.append(edges, alpha1)
            A, B = np.append(A, 0.0), np.append(B, 0.0)
            wa, wb = np.append(wa, alpha1 * alpha1 / d), np.append(wb, -1.0 / d)
        return edges, A, B, wa, wb

    @staticmethod
    def _split(edges, ta, tb, a2, wb, delta, pinned=None):
        """Sub-intervals of each piece where the trial u = ta + tb x^2 is above the limit
        a2 - x^2 (regime +1), below its negative (-1) or between (0): x (n, 4) and the
        regime of the 3 sub-intervals (n, 3).  The entering piece (wb != 0) slides as a
        whole or not at all: its trial is delta / (a1^2 - a0^2) = -delta wb times the
        limit, decided here by that ratio rather than by rounding at its ends.  A
        ``pinned`` piece is parallel to a limit and ends the step exactly on it (see
        :meth:`_switch_over`): regime 0, it has not slipped."""
        lo, hi = edges[:-1], edges[1:]
        with np.errstate(divide="ignore", invalid="ignore"):
            s_up = (a2 - ta) / (tb + 1.0)  # ta + tb s = a2 - s
            s_lo = -(a2 + ta) / (tb - 1.0)  # ta + tb s = -(a2 - s)
            x_up = np.sqrt(s_up)
            x_lo = np.sqrt(s_lo)
        x_up = np.where(np.isfinite(x_up), np.clip(x_up, lo, hi), lo)
        x_lo = np.where(np.isfinite(x_lo), np.clip(x_lo, lo, hi), lo)
        x = np.sort(np.stack([lo, x_up, x_lo, hi], axis=1), axis=1)
        mid = 0.5 * (x[:, 1:] + x[:, :-1])
        s = mid * mid
        trial = ta[:, None] + tb[:, None] * s
        limit = a2 - s
        regime = np.where(trial > limit, 1, np.where(trial < -limit, -1, 0))
        entering = wb != 0.0
        if entering.any():
            ratio = -delta * wb[entering]
            regime[entering] = np.where(ratio > 1.0, 1, np.where(ratio < -1.0, -1, 0))[:, None]
        if pinned is not None:
            regime[pinned] = 0
        return x, regime

    @staticmethod
    def _integral(x0, x1, c0, c2):
        """int_x0^x1 (c0 + c2 x^2) dx."""
        w = x1 - x0
        return w * (c0 + c2 * (x1 * x1 + x1 * x0 + x0 * x0) / 3.0)

    def _force(self, prepared, alpha1, delta):
        """(Q / (mu P_ref), d/d(delta) of it) for the increment ``delta``."""
        edges, A, B, wa, wb = prepared
        a2 = alpha1 * alpha1
        ta, tb = A + delta * wa, B + delta * wb
        x, regime = self._split(edges, ta, tb, a2, wb, delta)
        c0 = np.where(regime == 0, ta[:, None], regime * a2)
        c2 = np.where(regime == 0, tb[:, None], -regime * 1.0)
        total = self._integral(x[:, :-1], x[:, 1:], c0, c2).sum()
        stuck = regime == 0
        slope = np.where(stuck, self._integral(x[:, :-1], x[:, 1:], wa[:, None], wb[:, None]),
                         0.0).sum()
        return 1.5 * total, 1.5 * slope

    def _bracket(self, prepared, alpha1):
        """The increments beyond which every spring slides forwards (backwards)."""
        edges, A, B, wa, wb = prepared
        a2 = alpha1 * alpha1
        old = wb == 0.0
        ends = np.concatenate([edges[:-1][old], edges[1:][old]])
        ae = np.concatenate([A[old], A[old]])
        be = np.concatenate([B[old], B[old]])
        s = ends * ends
        up = a2 - s - (ae + be * s)  # what each old spring needs to reach +L
        down = -(a2 - s) - (ae + be * s)
        d = (alpha1 - self.alpha) * (alpha1 + self.alpha) if alpha1 > self.alpha else 0.0
        hi = max(up.max(initial=0.0), d)
        lo = min(down.min(initial=0.0), -d)
        return lo, hi

    def step(self, alpha1, target, sense):
        """Move to contact size alpha1 and force ``target`` = Q / (mu P_ref); ``sense``
        = +1 / -1 if |Q| = mu P (the whole contact slides that way), else 0.  Returns the
        displacement increment and the innermost x that slid (alpha1 if none)."""
        if alpha1 == 0.0:  # no contact: nothing carries or remembers a tangential force
            self.edges, self.A, self.B, self.alpha = np.zeros(1), np.zeros(0), np.zeros(0), 0.0
            return 0.0, 0.0
        prepared = self._prepare(alpha1)
        lo, hi = self._bracket(prepared, alpha1)
        if sense > 0:
            delta = hi
        elif sense < 0:
            delta = lo
        else:
            top = alpha1 * alpha1 * alpha1  # |force| with every spring at its limit
            if target >= top:  # rounding of Q / (mu P_ref) against alpha^3
                delta = hi
            elif target <= -top:
                delta = lo
            else:
                delta = self._solve(prepared, alpha1, target, lo, hi)
                delta, pinned = self._switch_over(prepared, alpha1, target, delta, lo, hi)
                self._commit(prepared, alpha1, delta, pinned)
                return delta, self._front
        self._commit(prepared, alpha1, delta)
        return delta, self._front

    def _switch_over(self, prepared, alpha1, target, delta, lo, hi):
        """Snap a step that ends at a switch-over to the switch-over itself.

        A piece parallel to a limit (one that slid before: u = A -+ x^2, or the entering
        piece, whose trial is proportional to the limit) meets that limit along its whole
        length at one increment d_c.  Ending below d_c the piece sticks, above it the whole
        piece slips, so the stick zone jumps there (the Mindlin-Deresiewicz switch-over
        from "the virgin curve of P1 added" to "the virgin state of (P1, Q)" at dQ = mu
        (P1 - P0)).  Which side a force within rounding of the switch-over's falls on
        would be decided by the last bit of the computed state, which differs between
        builds (numpy's AVX-512 and AVX2 code).  So a target whose force is within
        ``64 eps`` of the largest force alpha1^3 of the force at d_c ends the step at d_c
        exactly, the piece on its limit and not slipped (the stick zone is the larger,
        left-continuous one, as the closed forms give at dQ = mu (P1 - P0)).  Returns
        the increment and the pinned pieces (None if none)."""
        edges, A, B, wa, wb = prepared
        a2 = alpha1 * alpha1
        old = wb == 0.0
        candidates = []
        for sign in (1.0, -1.0):
            parallel = old & (B == -sign)  # u = A - sign x^2, parallel to sign (a2 - x^2)
            candidates += [(sign * a2 - A[j], j) for j in np.flatnonzero(parallel)]
        if not old.all():
            d = (alpha1 - self.alpha) * (alpha1 + self.alpha)
            j = int(np.flatnonzero(~old)[0])
            candidates += [(d, j), (-d, j)]
        tol = 64.0 * np.finfo(float).eps * alpha1 * a2
        # the force is nondecreasing in the increment: only the nearest switch-over on
        # either side of the root can be within tol of the target
        below = [dc for dc, _ in candidates if lo <= dc <= delta]
        above = [dc for dc, _ in candidates if delta < dc <= hi]
        for dc in ([max(below)] if below else []) + ([min(above)] if above else []):
            if abs(self._force(prepared, alpha1, dc)[0] - target) <= tol:
                delta = dc
                break
        else:
            return delta, None
        pinned = np.zeros(A.size, dtype=bool)
        for dc, j in candidates:
            if dc == delta:
                pinned[j] = True
        return delta, pinned

    def move(self, alpha1, delta):
        """Move to contact size alpha1 with the displacement increment ``delta`` (scaled);
        returns Q / (mu P_ref) and the innermost x that slid (alpha1 if none)."""
        if alpha1 == 0.0:
            self.edges, self.A, self.B, self.alpha = np.zeros(1), np.zeros(0), np.zeros(0), 0.0
            return 0.0, 0.0
        self._commit(self._prepare(alpha1), alpha1, delta)
        e = self.edges
        return 1.5 * float(self._integral(e[:-1], e[1:], self.A, self.B).sum()), self._front

    def _solve(self, prepared, alpha1, target, lo, hi):
        """The increment whose force is ``target`` (strictly between the forces at ``lo``
        and ``hi``): Newton's method on the exact slope, kept in a bracket that a
        bisection step shrinks whenever Newton would leave it."""
        x = min(max(0.0, lo), hi)
        best, best_miss = x, math.inf
        for _ in range(200):
            value, slope = self._force(prepared, alpha1, x)
            miss = value - target
            if abs(miss) < best_miss:
                best, best_miss = x, abs(miss)
            if miss == 0.0:
                break
            if miss > 0.0:
                hi = x
            else:
                lo = x
            step = x - miss / slope if slope > 0.0 else math.nan
            if not lo < step < hi:
                step = 0.5 * (lo + hi)
            if abs(step - x) <= 4e-16 * max(abs(step), abs(x)) or not lo < step < hi:
                value = self._force(prepared, alpha1, step)[0] if lo <= step <= hi else value
                if abs(value - target) < best_miss:
                    best = step
                break
            x = step
        return best

    def _commit(self, prepared, alpha1, delta, pinned=None):
        edges, A, B, wa, wb = prepared
        a2 = alpha1 * alpha1
        ta, tb = A + delta * wa, B + delta * wb
        if pinned is not None:  # exactly on the limit (+-(a2 - x^2)), not rounded next to it
            on = np.where(tb[pinned] < 0.0, 1.0, -1.0)
            ta, tb = ta.copy(), tb.copy()
            ta[pinned], tb[pinned] = on * a2, -on
        x, regime = self._split(edges, ta, tb, a2, wb, delta, pinned)
        c0 = np.where(regime == 0, ta[:, None], regime * a2).reshape(-1)
        c2 = np.where(regime == 0, tb[:, None], -regime * 1.0).reshape(-1)
        left, right = x[:, :-1].reshape(-1), x[:, 1:].reshape(-1)
        slid = regime.reshape(-1) != 0
        width = right > left
        self._front = float(left[slid & width].min()) if np.any(slid & width) else alpha1
        # drop slivers of a few ulp (a root that rounds next to an edge), which would
        # keep a trial profile whose regime rounding decided; the neighbour covers them
        keep = (right - left) > 4.0 * np.finfo(float).eps * alpha1
        if not keep.any():
            keep = width
        left, c0, c2 = left[keep], c0[keep], c2[keep]
        left[0] = 0.0
        # merge neighbours with the same coefficients (the stretches that slid)
        new = np.ones(left.size, dtype=bool)
        new[1:] = (c0[1:] != c0[:-1]) | (c2[1:] != c2[:-1])
        self.edges = np.append(left[new], alpha1)
        self.A, self.B = c0[new], c2[new]
        self.alpha = alpha1


def _forces(normal_forces, tangential_forces, mu):
    P = as_float_array(normal_forces, "normal_forces")
    shear = as_float_array(tangential_forces, "tangential_forces")
    for name, arr in (("normal_forces", P), ("tangential_forces", shear)):
        if arr.ndim != 1 or arr.size == 0:
            raise ValueError(f"{name} must be a one-dimensional array of at least one force "
                             f"in N (one per point of the path), got shape {arr.shape}")
    if P.shape != shear.shape:
        raise ValueError("normal_forces and tangential_forces must have the same length (one "
                         f"pair per point of the path), got {P.size} and {shear.size}")
    ok = (P >= 0) & (P < math.inf)
    if not ok.all():
        raise error_at("normal_forces", P, first_failure(ok), "a non-negative, finite force in N")
    ok = np.isfinite(shear)
    if not ok.all():
        raise error_at("tangential_forces", shear, first_failure(ok), "a finite force in N")
    ok = np.abs(shear) <= mu * P
    if not ok.all():
        i = first_failure(ok)
        raise ValueError(
            "tangential_forces must satisfy |Q| <= mu * P at every point, got "
            f"{float(shear[i])!r} N against mu * normal_forces = {float(mu * P[i])!r} N at "
            f"index {i}: beyond the limit of friction the contact slides as a whole and the "
            "force cannot be held (at "
            "|Q| = mu P the result reports sliding)")
    return P, shear


def _direction(direction):
    d = as_float_array(direction, "direction")
    if d.ndim != 0 or not (float(d) == 0.0 or float(d) == math.pi / 2):
        raise ValueError(
            f"direction must be 0.0 (the major axis) or math.pi / 2 (the minor axis), got "
            f"{direction!r}: Mindlin's construction (stick zones similar to the contact "
            "ellipse, slip parallel to the force) is exact only along a principal axis; in "
            "another direction the displacement turns towards the major axis and the stick "
            "zone is not similar to the contact ellipse")
    return float(d)


def load_path(body1, body2, normal_forces, tangential_forces, mu, angle=0.0, direction=0.0):
    """Tangential displacement and stick zone of a Hertz contact along a path of normal
    and tangential forces (Mindlin & Deresiewicz, any order of changes).

    The contact starts unloaded (P = Q = 0, displacement 0) and passes through the
    points (P_k, Q_k) in order.  Between two points the displacement is taken to change
    monotonically and in proportion to P^(2/3) where P changes; this makes every step
    exact at constant P (Masing's rule with memory, as :func:`hertz.tangential_history`),
    at constant Q with P rising (nothing changes) or falling from Mindlin and
    Deresiewicz's state (the slip annulus grows from the edge), and for Q/P fixed from
    zero (as :func:`hertz.proportional_loading`).  For other paths between the given
    points (Q and P rising together along curves, for example), give more points: the
    result converges to the path's own as the square of the step.

    Mindlin's uncoupled solution: Hertz's pressure whatever the tangential traction
    (Goodman's coupling of dissimilar materials neglected; :func:`hertz.dundurs_beta`
    gives its size), slip taken parallel to the force (Mindlin's approximation in the
    slip annulus).  The traction is kept as a superposition of Cattaneo distributions
    on ellipses similar to the contact ellipse, each of which moves its ellipse
    rigidly: along a principal axis this is exact for any path, with a one-dimensional
    memory of the traction over the size of the ellipse (module docstring of
    ``hertz._load_path``, with the derivation and the sources).

    Parameters
    ----------
    body1, body2 : Body
        The bodies, as :func:`hertz.contact` takes them.
    normal_forces : array_like, shape (n,)
        P_k [N], >= 0.  P = 0 separates the bodies: the tangential memory is lost.
    tangential_forces : array_like, shape (n,)
        Q_k [N] along ``direction`` (negative: the opposite way); |Q_k| <= mu P_k.
        |Q_k| = mu P_k is sliding of the whole contact.
    mu : float
        Coefficient of friction [-], > 0.
    angle : float
        Angle between the bodies' principal planes [rad], as :func:`hertz.contact`.
    direction : {0.0, math.pi / 2}
        The force's line: the major axis a (0) or the minor axis b (pi/2) [rad].

    Returns
    -------
    LoadPath
        Per point: displacement [m] along the force, contact and stick semi-axes [m],
        sliding.

    Raises
    ------
    TypeError
        A force that is not a number (or a quantity of another kind, such as a length).
    ValueError
        mu not positive and finite; a force not finite; P < 0; |Q| > mu P (index
        given); arrays not one-dimensional or of different lengths; ``direction`` not
        0 or pi/2.

    Notes
    -----
    The first point is reached from the unloaded state like any other step, so a first
    point with Q != 0 is reached by proportional loading; to apply Q at constant P,
    start the path with (P, 0).  The displacement after P = 0 keeps its last value (the
    bodies part; a new contact starts from that position).

    pint Quantities are taken in any unit of their kind (kN, lbf) and converted to SI;
    pandas Series and numpy arrays alike give their values.  The result holds SI floats.
    One contact per call (a loop over contacts is the caller's).

    Examples
    --------
    Mindlin & Deresiewicz's two cases: the normal force raised, then lowered, under a
    fixed tangential force.

    >>> import hertz
    >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
    >>> plane = hertz.Body.plane(E=210e9, nu=0.3)
    >>> path = hertz.load_path(ball, plane, [100.0, 100.0, 150.0, 60.0],
    ...                        [0.0, 15.0, 15.0, 15.0], mu=0.3)
    >>> bool(path.displacement[2] == path.displacement[1])  # P up: nothing moves
    True
    >>> t = hertz.contact(ball, plane, load=60.0).tangential(15.0, mu=0.3)
    >>> print(f"{path.displacement[3] / t.displacement:.12f}")  # P down: Cattaneo at 60 N
    1.000000000000
    >>> print(f"{path.stick_a[3] / t.stick_a:.12f}")
    1.000000000000
    """
    # pint quantities in any unit of their kind, as SI numbers (never a bare magnitude)
    given = []
    for name, value, unit in (("normal_forces", normal_forces, _interop.N),
                              ("tangential_forces", tangential_forces, _interop.N),
                              ("mu", mu, _interop.ONE), ("angle", angle, _interop.RAD),
                              ("direction", direction, _interop.RAD)):
        if _interop.library(value) == "pint":
            value = _interop._to_si(value, name, unit)
        given.append(value)
    normal_forces, tangential_forces, mu, angle, direction = given
    mu = float(_mu(mu)) if np.ndim(mu) == 0 else None
    if mu is None:
        raise ValueError("mu must be a single positive, finite coefficient of friction for "
                         "the whole path")
    direction = _direction(direction)
    P, shear = _forces(normal_forces, tangential_forces, mu)
    n = P.size
    p_ref = float(P.max())
    zeros = np.zeros(n)
    ref = _contact(body1, body2, load=p_ref if p_ref > 0.0 else 1.0, angle=angle)
    beta = float(dundurs_beta(ref))
    if p_ref == 0.0:  # never in contact (Q = 0 throughout by |Q| <= mu P)
        return _result(P, shear, zeros, zeros, zeros, zeros, zeros, np.zeros(n, dtype=bool),
                       mu, direction, beta)
    a_ref, b_ref = float(ref.a), float(ref.b)
    reach = 1.5 * mu * p_ref / float(tangential_stiffness(ref, direction))  # U
    alpha = np.cbrt(P / p_ref)
    target = shear / (mu * p_ref)
    sense = np.where(np.abs(shear) == mu * P, np.sign(shear), 0.0)
    sense[P == 0.0] = 0.0
    bed = _SpringBed()
    delta = 0.0
    disp = np.empty(n)
    front = np.empty(n)
    for k in range(n):
        step, front[k] = bed.step(float(alpha[k]), float(target[k]), float(sense[k]))
        delta += step
        disp[k] = delta
    sliding = sense != 0.0
    front[sliding] = 0.0
    a = alpha * a_ref
    b = alpha * b_ref
    return _result(P, shear, reach * disp, a, b, front * a_ref, front * b_ref, sliding, mu,
                   direction, beta)


def _result(*fields):
    """The LoadPath, its arrays copied and read-only (the result does not share memory
    with the caller's force arrays)."""
    arrays = []
    for value in fields[:8]:
        value = np.array(value, copy=True)
        value.setflags(write=False)
        arrays.append(value)
    return LoadPath(*arrays, *fields[8:])


class _SpringStacks:
    """The spring bed of the module docstring for N contacts, each a stack of pieces
    ordered by x, advanced by displacement at a cost per step that does not grow with
    the history; the step is compiled (hertz/_load_path_kernel.c, through
    ``_ufuncs.load_path_step``).

    Contact i holds count[i] pieces, each (E, D, B, F): the top one (the last) is
    ``top[i]``, the ones below it ``pieces[i, j]``, j < count[i] - 1 (most steps change
    the top piece alone: it is kept in a dense array).  Piece j covers [E, the next
    piece's E] (the last one up to the contact's size alpha[i]) and carries
    u = (delta[i] - D) + B x^2, delta[i] the scaled displacement since the contact last
    slid as a whole (or since it was re-based).  A step moves every spring in contact by
    d_delta at once by moving delta alone; what changes piece by piece is at the top of
    the stack only, because the springs that slide in a step are always an outer
    interval [c, a] (module docstring) and the springs that enter or leave are at the
    edge:

    * leaving (a falls): pieces that start at or beyond the new a are popped;
    * sliding: pieces whose inner edge slides are popped, the piece holding c is cut
      at c, and one piece on the limit, u = +-(a^2 - x^2), is pushed from c;
    * entering (a rises): one piece is pushed from the old a (the springs that enter
      during the step, u = d_delta (a1^2 - x^2) / (a1^2 - a0^2), or on the limit when
      |d_delta| > a1^2 - a0^2);
    * a piece equal to the top one is merged with it.

    F is the integral of (-D + B x^2) over the pieces below, so that the force
    Q / (mu P_ref) = (3/2) int_0^a u dx is read from the top piece alone.  When a
    contact slides as a whole its stack is one piece and delta starts again at 0;
    delta is also re-based whenever it exceeds 4 a^2 (the pieces' D and F shifted, a
    pass over that contact's pieces), so that delta - D never loses digits to a large
    delta.

    Memory: the pieces of distinct profile that no later slip has wiped out: the
    pieces of springs that entered while P rose with the edge sticking (one per such
    step with its own ratio d_delta / d(a^2); none while the tangential displacement
    stands still) and at most one cut piece per reversal remembered; ``pieces`` is as
    wide as the largest count over the contacts since the last growth plus 2 (a step
    pushes 2 pieces at most), doubled when a step may need more.  Cost per step: one
    pass over the contacts, each piece popped once after it was pushed (amortised
    constant).
    """

    PIECE = 4  # E, D, B, F

    def __init__(self, n):
        self.count = np.zeros(n, dtype=np.intp)
        self.alpha = np.zeros(n)
        self.spare = np.zeros(n)  # the next step's sizes are written here, then swapped
        self.delta = np.zeros(n)
        self.top = np.zeros((n, self.PIECE))
        self.pieces = np.zeros((n, 2, self.PIECE))
        self.most = 0  # the largest count after the last step (at least)

    def reset(self, rows):
        self.count[rows] = 0
        self.alpha[rows] = 0.0
        self.delta[rows] = 0.0

    def room(self):
        """Make room for a step: count + 2 pieces for every contact."""
        width = self.pieces.shape[1]
        need = self.most + 2
        if need > width:
            grow = max(need, 2 * width) - width
            self.pieces = np.pad(self.pieces, ((0, 0), (0, grow), (0, 0)))

    def live(self, i):
        """The pieces of contact i, (count[i], 4): E, D, B, F of each, inner first."""
        n = int(self.count[i])
        return np.concatenate([self.pieces[i, :max(n - 1, 0)], self.top[i, None][:n > 0]])


def _shape_of(*arrays, size=None):
    """The batch's shape: the arrays' broadcast with (size,) if size is given."""
    return _batch_shape(np.broadcast_shapes(*(np.shape(a) for a in arrays)), size)


class LoadPathSpring:
    """Mindlin-Deresiewicz with a changing normal force, in the shape a DEM code uses:
    the normal force and a tangential displacement increment in, the tangential force
    out; for one contact or N at a time.

    The same exact one-dimensional memory as :func:`hertz.load_path` (module docstring
    of ``hertz._load_path``), driven by displacement instead of force, along a
    principal axis: within a step the displacement changes in proportion to P^(2/3)
    where P changes.  At constant P it is :class:`hertz.TangentialSpring`; unlike it,
    the normal force may change at every step (springs leave the contact with their
    force, enter it with none), which is what a DEM contact does.  Where the whole
    contact slides the force is +-mu P and ``sliding`` is true.  A normal force of 0
    separates the bodies: the contact forgets its tangential state, and a later contact
    starts afresh; :meth:`reset` does the same for the slots of contacts that leave.

    Parameters
    ----------
    body1, body2 : Body
        The bodies, as :func:`hertz.contact` takes them (arrays of radii or moduli give
        one contact per element).
    mu : float or array_like
        Coefficient of friction [-], > 0.
    angle : float or array_like
        Angle between the bodies' principal planes [rad].
    direction : {0.0, math.pi / 2}
        The line of the tangential motion: the major (0) or minor (pi/2) axis [rad].
    size : int, optional
        Number of contacts, when the bodies and mu are the same for all (the batch's
        shape is theirs broadcast with (size,)).

    Attributes
    ----------
    normal_force, force, displacement : float or ndarray
        P [N], the tangential force Q [N] and the accumulated relative displacement
        along the line [m] (slip included) after the last step.
    stick_a, stick_b : float or ndarray
        Semi-axes of the stick ellipse of the last step [m] (as :class:`LoadPath`).
    sliding : bool or ndarray of bool
        Whether the whole contact slid in the last step (|Q| = mu P).
    memory : int or ndarray of int
        Pieces of the spring bed each contact holds.

    Notes
    -----
    Memory per contact: 4 doubles per piece of the spring bed (its inner edge, two
    coefficients and the force below it; the arrays are as wide as the largest count
    in the batch plus 2), plus 13 numbers.  The pieces are those of
    distinct profile that no later slip has wiped out: one per step in which P rose
    while the edge of the contact stuck and the displacement moved (the springs that
    entered in that step remember it), and at most one cut piece per remembered
    reversal; springs that slide, and springs that leave the contact, drop theirs.  So
    a contact sliding at its edge, or whose P stands or falls, keeps a few pieces,
    while a long rise of P at a small, varying tangential rate adds one a step (that
    memory is the physics: the springs that entered at each step carry different
    forces).  Cost per step: one compiled pass over the contacts
    (hertz/_load_path_kernel.c: the numpy algorithm it replaced, bit for bit, one
    contact at a time), after numpy's cbrt of the normal forces; each piece is popped
    at most once after it was pushed, so the cost per step does not grow with the
    history.  benchmarks/dem_laws.py measures it at N = 1e6: about 1.8x one scipy
    ellipk + ellipe pass per contact (it was 18x in numpy), near
    :class:`hertz.TangentialSpring`; one contact alone, about 0.011 ms a step (the
    Python call and its input checks).

    Examples
    --------
    >>> import hertz
    >>> ball = hertz.Body.sphere(0.01, E=210e9, nu=0.3)
    >>> plane = hertz.Body.plane(E=210e9, nu=0.3)
    >>> spring = hertz.LoadPathSpring(ball, plane, mu=0.3)
    >>> q = spring.step(100.0, 0.0)  # pressed, no tangential motion yet
    >>> q = spring.step(100.0, 4e-7)  # pushed sideways at 100 N
    >>> t = hertz.contact(ball, plane, load=100.0).tangential(q, mu=0.3)
    >>> print(f"{t.displacement / 4e-7:.12f}")  # the Cattaneo-Mindlin displacement
    1.000000000000
    >>> q = spring.step(150.0, 0.0)  # pressed harder: the force stays
    >>> print(f"{spring.force / q:.12f}")
    1.000000000000
    >>> float(spring.step(10.0, 0.0)), spring.sliding  # unloaded to 10 N: slides at mu P
    (3.0, True)

    Two contacts at once, each its own normal force; the first one leaves:

    >>> springs = hertz.LoadPathSpring(ball, plane, mu=0.3, size=2)
    >>> q = springs.step([100.0, 50.0], [1e-3, -1e-3])
    >>> [float(v) for v in q]
    [30.0, -15.0]
    >>> springs.reset([0])
    >>> [float(v) for v in springs.force]
    [0.0, -15.0]
    """

    def __init__(self, body1, body2, mu, angle=0.0, direction=0.0, size=None):
        if _interop.library(mu) == "pint":
            mu = _interop._to_si(mu, "mu", _interop.ONE)
        mu = _mu(mu)
        self._direction = _direction(direction)
        ref = _contact(body1, body2, load=1.0, angle=angle)  # P_ref = 1 N
        stiffness = np.asarray(tangential_stiffness(ref, self._direction), dtype=float)
        a_ref, b_ref = np.asarray(ref.a, dtype=float), np.asarray(ref.b, dtype=float)
        self._shape = _shape_of(mu, a_ref, b_ref, stiffness, size=size)

        def flat(v):
            return np.broadcast_to(v, self._shape).reshape(-1).copy()

        self._mu = flat(mu)
        self._a_ref, self._b_ref = flat(a_ref), flat(b_ref)
        self._reach = 1.5 * self._mu / flat(stiffness)

        def compact(full, *given):  # one value where the batch shares it (the kernel's stride 0)
            return full[:1].copy() if all(np.size(v) == 1 for v in given) else full

        self._constants = (compact(self._mu, mu), compact(1.0 / self._reach, mu, stiffness))
        n = self._mu.size
        self._bed = _SpringStacks(n)
        self._state = {name: np.zeros(n) for name in ("force", "normal_force",
                                                       "displacement", "front")}
        self._state["sliding"] = np.zeros(n, dtype=bool)

    def _view(self, name):
        return self._shaped(self._state[name].copy())

    def _shaped(self, x):
        return x.reshape(self._shape) if self._shape else x.item()

    shape = property(lambda self: self._shape, doc="The batch's shape (() for one contact).")
    normal_force = property(lambda self: self._view("normal_force"))
    force = property(lambda self: self._view("force"))
    displacement = property(lambda self: self._view("displacement"))
    stick_a = property(lambda self: self._shaped(self._state["front"] * self._a_ref))
    stick_b = property(lambda self: self._shaped(self._state["front"] * self._b_ref))
    sliding = property(lambda self: self._view("sliding"))

    @property
    def memory(self):
        n = self._bed.count
        return n.reshape(self._shape).copy() if self._shape else int(n[0])

    def reset(self, where=None):
        """Return contacts to the unloaded state (no forces, no displacement, no
        memory): a contact that leaves, its slot ready for the next one.

        Parameters
        ----------
        where : array_like of bool or int, optional
            A boolean mask of the batch's shape, or integer indices into the flattened
            batch; all contacts if omitted.
        """
        n = self._mu.size
        rows = np.arange(n) if where is None else _selection(where, self._shape, n)
        self._bed.reset(rows)
        for value in self._state.values():
            value[rows] = 0

    def step(self, normal_force, increment):
        """Move to the normal force ``normal_force`` [N] (>= 0) with the relative
        tangential displacement ``increment`` [m] along the line (both broadcast to the
        contacts); return the tangential force [N], never beyond +-mu P (any increment
        beyond twice the sliding displacement slides the contact as a whole, the same
        state whatever its size).

        Raises
        ------
        ValueError
            A normal force or an increment not finite, a negative normal force, or an
            increment that takes the accumulated displacement beyond the range of a
            double (magnitude 1.8e308 m); the state is unchanged.
        """
        load = np.ascontiguousarray(self._checked(normal_force, "normal_force", _interop.N))
        inc = np.ascontiguousarray(self._checked(increment, "increment", _interop.M))
        bed, state = self._bed, self._state
        bed.room()
        alpha = np.cbrt(load, out=bed.spare)  # the new sizes (numpy's cbrt)
        # the checks, then the step (hertz/_load_path_kernel.c): nothing is written where
        # a check fails
        status, value = _ufuncs.load_path_step(
            bed.count, bed.alpha, bed.delta, bed.top, bed.pieces, alpha, load, inc,
            *self._constants, state["force"], state["normal_force"], state["displacement"],
            state["sliding"], state["front"])
        if status == 1:
            raise error_at("normal_force", load.reshape(self._shape), value,
                           "a non-negative, finite force in N")
        if status == 2:
            raise error_at("increment", inc.reshape(self._shape), value,
                           "a finite displacement in m")
        if status == 3:
            raise ValueError(
                f"increment must keep the accumulated displacement within the range of a "
                f"double (magnitude at most 1.7976931348623157e308 m), got "
                f"{float(inc[value])!r} m on {float(state['displacement'][value])!r} m"
                f"{index_text(self._shape, value)}")
        bed.most = value
        bed.alpha, bed.spare = alpha, bed.alpha
        return self.force

    def _checked(self, value, name, unit):
        if _interop.library(value) == "pint":
            value = _interop._to_si(value, name, unit)
        arr = as_float_array(value, name)
        if not self._shape and arr.ndim != 0:
            raise ValueError(f"{name} must be a single number (one contact, one step), got "
                             f"an array of shape {arr.shape}")
        try:
            return np.broadcast_to(arr, self._shape).reshape(-1)
        except ValueError:
            raise ValueError(f"{name} must broadcast to the contacts' shape {self._shape}, "
                             f"got the shape {arr.shape}") from None

